// certipose/expr/evaluate.hpp — forward evaluation of an expression over a box or at a point.
//
// The natural interval extension (paper §5.1): an enclosure of { e(p) : p ∈ box }, or a
// certified enclosure of e at one point. Holds the rounding mode itself.
#pragma once

#include <array>
#include <cstddef>

#include "certipose/expr/detail/rounding_scope.hpp"
#include "certipose/expr/expression.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/pose/interval_box.hpp"

namespace certipose::expr {

/// Enclosure of e over the box (empty when e is defined nowhere on it).
template <Interval I, std::size_t N, Expression E>
I evaluate(const E& e, const interval_box<I, N>& box) {
    static_assert(E::var_bound <= N, "certipose: the expression uses a variable beyond the box");
    const detail::upward_scope<I> rounding;
    std::array<I, E::slots> v;
    e.template fwd<0>(box, v);
    return detail::as_interval<I>(e.template value<0>(box, v));
}

/// Certified enclosure of e at a point: `evaluate<boost_interval>(e, std::array{1.0, 2.0})`.
template <Interval I, std::size_t N, Expression E>
I evaluate(const E& e, const std::array<double, N>& point) {
    interval_box<I, N> box;
    for (std::size_t i = 0; i < N; ++i) box[i] = I(point[i]);
    return evaluate(e, box);
}

}  // namespace certipose::expr

namespace certipose {
using expr::evaluate;
}  // namespace certipose
