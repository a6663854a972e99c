// certipose/contractor/fixpoint.hpp — repeat a contractor until it stops paying.
//
// `fixpoint(c, ratio)` calls c again while the last call narrowed some component by more than
// `ratio` of its width (IBEX's CtcFixPoint, whose default ratio is 1e-3), or until the box is
// empty. A cap on the number of calls keeps a ratio of 0 from running for long.
#pragma once

#include <cstddef>
#include <string>
#include <utility>

#include "certipose/detail/format.hpp"
#include "certipose/contractor/concept.hpp"
#include "certipose/contractor/detail/forward_param.hpp"
#include "certipose/contractor/detail/narrowing.hpp"
#include "certipose/error.hpp"
#include "certipose/expr/detail/rounding_scope.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/pose/interval_box.hpp"

namespace certipose {

template <class C>
class fixpoint {
public:
    using certipose_contractor = void;
    static constexpr double default_ratio = 1e-3;
    static constexpr int max_calls = 1000;

    explicit fixpoint(C c, double ratio = default_ratio) : c_(std::move(c)), ratio_(ratio) {
        if (!(ratio >= 0.0 && ratio < 1.0))
            throw invalid_argument("ratio", "fixpoint ratio must be in [0, 1), got " + detail::format_double(ratio));
    }

    template <Interval I, std::size_t N>
    void contract(interval_box<I, N>& box) {
        static_assert(Contractor<C, interval_box<I, N>>, "certipose::fixpoint: the part must model Contractor");
        const expr::detail::upward_scope<I> rounding;
        for (int call = 0; call < max_calls && !is_empty(box); ++call) {
            const auto before = box;
            c_.contract(box);
            if (is_empty(box) || contractor_detail::max_narrowing(before, box) <= ratio_) return;
        }
    }

    double ratio() const noexcept { return ratio_; }
    C& inner() noexcept { return c_; }
    const C& inner() const noexcept { return c_; }

    template <std::size_t Id>
    void set_param(double lo, double hi) {
        contractor_detail::forward_set_param<Id, contractor_detail::param_targets::those_having_one>(c_, lo, hi);
    }

private:
    C c_;
    double ratio_;
};

template <class C>
fixpoint(C) -> fixpoint<C>;
template <class C>
fixpoint(C, double) -> fixpoint<C>;

}  // namespace certipose
