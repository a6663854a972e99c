// certipose/contractor/eval_test.hpp — the evaluation-only box test of a constraint set.
//
// One forward evaluation per constraint (the natural interval extension, paper §5.1):
// `satisfied` when every constraint's range lies inside its bounds and its expression is
// defined on the whole box (so every pose in the box is valid — the paper's VALID test);
// `violated` as soon as one constraint's range misses its bounds (no point can satisfy it);
// otherwise `undecided`. It models `BoxTest` for `interval_box<I, N>` of any backend; the
// paver uses it as its inner test. Cheap but weak where variables repeat: not_in_test is the
// stronger inner proof.
#pragma once

#include <algorithm>
#include <cstddef>
#include <tuple>
#include <utility>

#include "certipose/contractor/concept.hpp"
#include "certipose/contractor/detail/forward_param.hpp"
#include "certipose/expr/constraint.hpp"
#include "certipose/expr/detail/rounding_scope.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/pose/interval_box.hpp"

namespace certipose {

namespace detail {

/// One forward evaluation per constraint, stopping at the first violated one: `violated` if
/// some constraint fails on the whole box, `satisfied` if all hold on all of it, else
/// `undecided`. The box must be non-empty and the rounding mode held upward.
template <class... Cs, Interval I, std::size_t N>
verdict forward_verdict(const std::tuple<Cs...>& cs, const interval_box<I, N>& box) {
    bool all = true;
    bool violated = false;
    std::apply(
        [&](const auto&... c) {
            (void)((
                       [&] {
                           const verdict v = c.test(box);
                           if (v == verdict::violated) violated = true;
                           if (v != verdict::satisfied) all = false;
                           return violated;
                       }() ||
                       ...));
        },
        cs);
    if (violated) return verdict::violated;
    return all ? verdict::satisfied : verdict::undecided;
}

}  // namespace detail

template <Constraint... Cs>
class eval_test {
    static_assert(sizeof...(Cs) >= 1, "certipose::eval_test needs at least one constraint");

public:
    static constexpr std::size_t var_bound = std::max({std::size_t{0}, Cs::var_bound...});

    explicit eval_test(Cs... cs) : cs_(std::move(cs)...) {}

    /// An empty box is reported violated (it holds no point; the paver discards it).
    template <Interval I, std::size_t N>
    verdict test(const interval_box<I, N>& box) const {
        static_assert(var_bound <= N, "certipose::eval_test: a constraint uses a variable beyond the box");
        const expr::detail::upward_scope<I> rounding;
        if (is_empty(box)) return verdict::violated;
        return detail::forward_verdict(cs_, box);
    }

    const std::tuple<Cs...>& constraints() const noexcept { return cs_; }

    template <std::size_t Id>
    void set_param(double lo, double hi) {
        contractor_detail::forward_set_param<Id>(cs_, lo, hi);
    }

private:
    std::tuple<Cs...> cs_;
};

template <Constraint... Cs>
eval_test(Cs...) -> eval_test<Cs...>;

}  // namespace certipose
