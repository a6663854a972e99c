// certipose/contractor/not_in.hpp — the negation of a constraint set, as a contractor
// (`not_in`, IBEX's CtcNotIn) and as the strong inner test of the paver (`not_in_test`).
//
// A box lies entirely inside the solution set when no point of it violates any constraint. The
// negation of `e ∈ [a, b]` is `e < a or e > b`; HC4Revise on its closure `e ≤ a` and on
// `e ≥ b` (two copies, then the hull) removes points that satisfy the constraint. If that
// empties the box for every constraint (and every expression is defined on the whole box,
// checked first: undefined points violate a constraint too) the box is certified VALID.
// This proves boxes the evaluation-only test cannot, e.g. where a variable occurs several times
// or near the boundary of a thin shell. `not_in` as a contractor keeps the hull of the points
// that violate at least one constraint (the paver's "inner contractor" in IBEX's sense):
// every point it removes satisfies every constraint, so a paver may classify the removed part
// of a box VALID.
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>
#include <tuple>
#include <utility>

#include "certipose/contractor/concept.hpp"
#include "certipose/contractor/detail/forward_param.hpp"
#include "certipose/contractor/detail/narrowing.hpp"
#include "certipose/contractor/eval_test.hpp"
#include "certipose/expr/constraint.hpp"
#include "certipose/expr/detail/rounding_scope.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/pose/interval_box.hpp"

namespace certipose {

template <Constraint... Cs>
class not_in {
    static_assert(sizeof...(Cs) >= 1, "certipose::not_in needs at least one constraint");

public:
    using certipose_contractor = void;
    static constexpr std::size_t var_bound = std::max({std::size_t{0}, Cs::var_bound...});

    explicit not_in(Cs... cs) : cs_(std::move(cs)...) {}

    /// Narrows the box to the hull of its points violating at least one constraint; leaves it
    /// unchanged when some expression is not certainly defined on it.
    template <Interval I, std::size_t N>
    void contract(interval_box<I, N>& box) const {
        static_assert(var_bound <= N, "certipose::not_in: a constraint uses a variable beyond the box");
        const expr::detail::upward_scope<I> rounding;
        if (is_empty(box)) return;
        bool defined = true;
        std::apply([&](const auto&... c) { defined = (c.defined_on(box) && ...); }, cs_);
        if (!defined) return;
        auto result = interval_box<I, N>::empty();
        std::apply([&](const auto&... c) { (negate(c, box, result), ...); }, cs_);
        box = result;
    }

    const std::tuple<Cs...>& constraints() const noexcept { return cs_; }

    template <std::size_t Id>
    void set_param(double lo, double hi) {
        contractor_detail::forward_set_param<Id>(cs_, lo, hi);
    }

private:
    // Repeated variables make one HC4Revise pass weak; a few more passes are cheap here.
    static constexpr int max_passes = 20;
    static constexpr double pass_ratio = 0.01;

    template <class C, Interval I, std::size_t N>
    static void negate(const C& c, const interval_box<I, N>& box, interval_box<I, N>& result) {
        constexpr double inf = std::numeric_limits<double>::infinity();
        if (c.lo > -inf) result = hull(result, side(c, box, I(-inf, c.lo)));
        if (c.hi < inf) result = hull(result, side(c, box, I(c.hi, inf)));
    }

    template <class C, Interval I, std::size_t N>
    static interval_box<I, N> side(const C& c, interval_box<I, N> b, const I& target) {
        for (int pass = 0; pass < max_passes; ++pass) {
            const auto before = b;
            if (!c.revise(b, target)) return interval_box<I, N>::empty();
            if (!C::repeated || contractor_detail::max_narrowing(before, b) < pass_ratio) break;
        }
        return b;
    }

    std::tuple<Cs...> cs_;
};

template <Constraint... Cs>
not_in(Cs...) -> not_in<Cs...>;

/// BoxTest: `satisfied` when the negation of the constraint set has no point in the box (a
/// proof of inclusion, IBEX's CtcNotIn used as an inner test), `violated` when forward
/// evaluation shows a constraint fails everywhere, else `undecided`.
template <Constraint... Cs>
class not_in_test {
public:
    explicit not_in_test(Cs... cs) : neg_(cs...) {}

    template <Interval I, std::size_t N>
    verdict test(const interval_box<I, N>& box) const {
        const expr::detail::upward_scope<I> rounding;
        if (is_empty(box)) return verdict::violated;
        if (const verdict v = detail::forward_verdict(neg_.constraints(), box); v != verdict::undecided) return v;
        auto b = box;
        neg_.contract(b);
        return is_empty(b) ? verdict::satisfied : verdict::undecided;
    }

    const std::tuple<Cs...>& constraints() const noexcept { return neg_.constraints(); }

    template <std::size_t Id>
    void set_param(double lo, double hi) {
        contractor_detail::forward_set_param<Id>(neg_, lo, hi);
    }

private:
    not_in<Cs...> neg_;
};

template <Constraint... Cs>
not_in_test(Cs...) -> not_in_test<Cs...>;

}  // namespace certipose
