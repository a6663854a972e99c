// certipose/expr/constraint.hpp — constraints `e ∈ [a, b]`, `e1 <= e2`, `e1 >= e2`,
// `e1 == e2` over expression trees, with HC4Revise (forward–backward, paper §5.2.1) and a
// tri-state box test.
//
// Every relation is stored as `in_constraint{e, lo, hi}`: `e1 <= e2` is `e1 − e2 ∈ (−∞, 0]`,
// `e <= 3.0` is `e ∈ (−∞, 3]`, `e1 == e2` is `e1 − e2 ∈ [0, 0]`. The bounds are doubles taken
// exactly (write `param` when a bound is only known as an interval). Each member holds the
// rounding mode for itself (a register read when a caller already holds it).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>

#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"
#include "certipose/expr/detail/rounding_scope.hpp"
#include "certipose/expr/expression.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/interval/operations.hpp"
#include "certipose/outcome.hpp"  // verdict

namespace certipose::expr {

struct constraint_tag {};

/// `e ∈ [lo, hi]`; lo may be −∞ and hi +∞.
template <Expression E>
struct in_constraint : constraint_tag {
    using expression_type = E;
    static constexpr std::size_t var_bound = E::var_bound;
    static constexpr std::uint64_t var_mask = E::var_mask;
    /// A variable occurs more than once: HC4Revise is then not idempotent, so propagation must
    /// revisit the constraint after it narrowed a variable (otherwise it need not: with single
    /// occurrences HC4Revise reaches hull consistency in one pass, Benhamou et al. 1999).
    static constexpr bool repeated = E::repeated;

    E e;
    double lo, hi;

    in_constraint(E expr, double l, double h) : e(std::move(expr)), lo(l), hi(h) {
        if (std::isnan(l) || std::isnan(h) || !(l <= h))
            throw invalid_argument("in", "constraint bounds need lo <= hi (no NaN), got [" + certipose::detail::format_double(l) +
                                             ", " + certipose::detail::format_double(h) + "]");
    }

    template <class Box>
    using values_t = std::array<typename Box::interval_type, E::slots>;

    /// Forward evaluation: fills `v` and returns the enclosure of e over `box`. The building
    /// block of the members below; the caller must hold the rounding mode (they do).
    template <class Box>
    typename Box::interval_type forward(const Box& box, values_t<Box>& v) const {
        using I = typename Box::interval_type;
        static_assert(E::var_bound <= Box::dimension, "certipose: the expression uses a variable beyond the box");
        e.template fwd<0>(box, v);
        return detail::as_interval<I>(e.template value<0>(box, v));
    }

    /// HC4Revise of `e ∈ target`: narrows `box`; false when it proves there is no solution.
    // One straight-line function per constraint: the nodes are forced inline (detail/config.hpp).
    template <class Box>
    bool revise(Box& box, const typename Box::interval_type& target) const {
        const detail::upward_scope<typename Box::interval_type> rounding;
        values_t<Box> v;
        const auto value = forward(box, v);
        if (is_empty(value) || is_empty(intersect(value, target))) return false;
        // Already inside the target: every point of the box where e is defined satisfies the
        // constraint, so the backward pass could not remove anything a solution needs (IBEX
        // calls such a constraint inactive).
        if (subset(value, target)) return true;
        return e.template bwd<0>(target, box, v);
    }
    template <class Box>
    bool revise(Box& box) const {
        using I = typename Box::interval_type;
        return revise(box, I(lo, hi));
    }

    /// Enclosure of e over the box.
    template <class Box>
    typename Box::interval_type evaluate(const Box& box) const {
        const detail::upward_scope<typename Box::interval_type> rounding;
        values_t<Box> v;
        return forward(box, v);
    }

    /// satisfied: e is defined on the whole box and its range lies in [lo, hi];
    /// violated: no point of the box has e defined and inside [lo, hi]; else undecided.
    template <class Box>
    verdict test(const Box& box) const {
        const detail::upward_scope<typename Box::interval_type> rounding;
        using I = typename Box::interval_type;
        values_t<Box> v;
        const I value = forward(box, v);
        const I bounds(lo, hi);
        if (is_empty(value) || is_empty(intersect(value, bounds))) return verdict::violated;
        if (subset(value, bounds) && e.template defined<0>(box, v)) return verdict::satisfied;
        return verdict::undecided;
    }

    /// True when e is certainly defined at every point of the box.
    template <class Box>
    bool defined_on(const Box& box) const {
        const detail::upward_scope<typename Box::interval_type> rounding;
        values_t<Box> v;
        const auto value = forward(box, v);
        return !is_empty(value) && e.template defined<0>(box, v);
    }

    /// Interval gradient of e over the box (for ACID's smear heuristic).
    template <class Box>
    std::array<typename Box::interval_type, Box::dimension> gradient(const Box& box) const {
        const detail::upward_scope<typename Box::interval_type> rounding;
        values_t<Box> v;
        forward(box, v);
        return e.template grad<0>(box, v);
    }

    template <std::size_t Id>
    void set_param(double l, double h) {
        e.template set_param<Id>(l, h);
    }
};

template <class T>
concept Constraint = std::is_base_of_v<constraint_tag, std::remove_cvref_t<T>>;

/// e ∈ [lo, hi].
template <Operand E>
auto in(const E& e, double lo, double hi) {
    return in_constraint<expr_t<E>>(as_expr(e), lo, hi);
}

template <Operand A, Operand B>
    requires(Expression<A> || Expression<B>)
auto operator<=(const A& a, const B& b) {
    if constexpr (std::is_arithmetic_v<B>) return in(a, -detail::inf, static_cast<double>(b));
    else if constexpr (std::is_arithmetic_v<A>) return in(b, static_cast<double>(a), detail::inf);
    else return in(a - b, -detail::inf, 0.0);
}
template <Operand A, Operand B>
    requires(Expression<A> || Expression<B>)
auto operator>=(const A& a, const B& b) {
    if constexpr (std::is_arithmetic_v<B>) return in(a, static_cast<double>(b), detail::inf);
    else if constexpr (std::is_arithmetic_v<A>) return in(b, -detail::inf, static_cast<double>(a));
    else return in(a - b, 0.0, detail::inf);
}
template <Operand A, Operand B>
    requires(Expression<A> || Expression<B>)
auto operator==(const A& a, const B& b) {
    if constexpr (std::is_arithmetic_v<B>) return in(a, static_cast<double>(b), static_cast<double>(b));
    else if constexpr (std::is_arithmetic_v<A>) return in(b, static_cast<double>(a), static_cast<double>(a));
    else return in(a - b, 0.0, 0.0);
}

}  // namespace certipose::expr

namespace certipose {
using expr::Constraint;
using expr::in;
using expr::in_constraint;
}  // namespace certipose
