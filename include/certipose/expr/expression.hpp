// certipose/expr/expression.hpp — compile-time expression trees over the variables of a box,
// with forward evaluation and HC4Revise backward projection (paper §5.2.1).
//
// `var<0> x; var<1> y;` name box components; `x * y - sqr(x - 1.0)` builds a tree whose type
// records its shape, so evaluation is inlined straight-line code: no heap, no virtual call.
// Leaves are box variables, double constants and interval parameters (`param<Id>`, values
// known only as intervals at run time, e.g. a facet vertex coordinate; held by value and
// settable with `set_param<Id>`). Operators: + − × ÷, unary −, sqr, sqrt, pow(e, int), abs,
// sin, cos (vectors: expr/vector.hpp).
//
// Evaluation protocol (what constraints and contractors use): each operator node owns one slot
// of a `std::array<I, E::slots>` whose size is computed at compile time; leaves own none (a
// variable reads the box, a constant is a double). `fwd<O>` fills the node's slot (offset O,
// children after it) bottom-up; `bwd<O>(t, ...)` narrows the node to `t` and projects onto the
// children (HC4Revise). A variable occurring several times is intersected at each occurrence,
// which is sound: every projection is a superset of the solutions, so any order of
// intersections is. Projections never remove a point where the expression is defined and
// takes a value in the target (division by an interval containing 0 and the periodic inverse
// of sin/cos included); points outside the domain of sqrt, ÷ or negative powers are removed,
// as in IBEX (a constraint implies its expression is defined).
//
// The node steps are CERTIPOSE_DETAIL_INLINE (detail/config.hpp): a constraint's revise or
// evaluate compiles to one straight-line function over its whole tree.
//
// All of it requires the rounding mode held upward (`rounding_guard<I>`): entry points
// (`evaluate`, contractors, tests) hold it, nodes never do.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>

#include "certipose/detail/config.hpp"
#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"
#include "certipose/expr/detail/projection.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/interval/operations.hpp"

namespace certipose::expr {

/// Base of every expression node (what makes a type an `Expression`).
struct node_tag {};

template <class T>
concept Expression = std::is_base_of_v<node_tag, std::remove_cvref_t<T>>;

/// What the operators accept: an expression or a number (converted to a `constant`).
template <class T>
concept Operand = Expression<T> || std::is_arithmetic_v<std::remove_cvref_t<T>>;

namespace detail {

template <class V>
using interval_of = typename V::value_type;

template <class Box>
inline constexpr std::size_t dimension_of = std::remove_cvref_t<Box>::dimension;

template <class I, class T>
I as_interval(const T& x) {
    if constexpr (std::is_arithmetic_v<std::remove_cvref_t<T>>)
        return I(static_cast<double>(x));
    else
        return x;
}

/// v ∩= t; false when the result is empty.
template <class I>
CERTIPOSE_DETAIL_INLINE bool narrow(I& v, const I& t) {
    v = intersect(v, t);
    return !is_empty(v);
}

template <class I, std::size_t N>
std::array<I, N> zero_gradient() {
    std::array<I, N> g;
    g.fill(I(0.0));
    return g;
}

}  // namespace detail

// ---- leaves -------------------------------------------------------------------------------

namespace detail {

/// What the leaves (var, constant, param) share: no slot of their own (a leaf is read by
/// `value`, so `fwd` computes nothing), never repeated, defined everywhere, and the static facts
/// a node reports. The defaults below are those of a leaf without variables: a zero gradient and
/// no parameter to set. Each leaf adds `value` and `bwd`, and declares its own `grad` or
/// `set_param` where it differs (hiding these).
template <std::uint64_t VarMask, std::size_t VarBound, bool IsConstant>
struct leaf : node_tag {
    static constexpr std::size_t slots = 0;
    static constexpr std::uint64_t var_mask = VarMask;
    static constexpr std::size_t var_bound = VarBound;
    static constexpr bool repeated = false;
    static constexpr bool is_constant = IsConstant;

    template <std::size_t O, class Box, class V>
    CERTIPOSE_DETAIL_INLINE void fwd(const Box&, V&) const noexcept {}
    template <std::size_t O, class Box, class V>
    CERTIPOSE_DETAIL_INLINE bool defined(const Box&, const V&) const noexcept {
        return true;
    }
    template <std::size_t O, class Box, class V>
    auto grad(const Box&, const V&) const {
        return zero_gradient<interval_of<V>, dimension_of<Box>>();
    }
    template <std::size_t Id>
    void set_param(double, double) noexcept {}
};

/// A leaf without variables whose value is known (up to an interval) before evaluation.
using value_leaf = leaf<0, 0, true>;

}  // namespace detail

/// The K-th component of the box.
template <std::size_t K>
struct var : detail::leaf<(K < 64 ? std::uint64_t{1} << K : 0), K + 1, false> {
    static_assert(K < 64, "certipose: expressions address at most 64 box variables");
    static constexpr std::size_t index = K;

    template <std::size_t O, class Box, class V>
    CERTIPOSE_DETAIL_INLINE const auto& value(const Box& box, const V&) const noexcept {
        return box[K];
    }
    template <std::size_t O, class Box, class V>
    CERTIPOSE_DETAIL_INLINE bool bwd(const detail::interval_of<V>& t, Box& box, V&) const {
        return detail::narrow(box[K], t);
    }
    template <std::size_t O, class Box, class V>
    auto grad(const Box&, const V&) const {
        using I = detail::interval_of<V>;
        auto g = detail::zero_gradient<I, detail::dimension_of<Box>>();
        g[K] = I(1.0);
        return g;
    }
};

/// A double constant. NaN is rejected (it would silently make every constraint infeasible).
struct constant : detail::value_leaf {
    double c;

    explicit constant(double v) : c(v) {
        if (std::isnan(v)) throw invalid_argument("constant", "expression constant is NaN");
    }

    template <std::size_t O, class Box, class V>
    double value(const Box&, const V&) const noexcept {
        return c;
    }
    template <std::size_t O, class Box, class V>
    CERTIPOSE_DETAIL_INLINE bool bwd(const detail::interval_of<V>& t, Box&, V&) const {
        return contains(t, c);
    }
};

/// An interval parameter: a value known only to lie in [lo, hi] (e.g. a facet vertex
/// coordinate, or a position-box component when solving for orientation). Held by value in
/// the tree; `set_param<Id>(tree_or_contractor, lo, hi)` updates every parameter with this Id.
template <std::size_t Id = 0>
struct param : detail::value_leaf {
    static constexpr std::size_t id = Id;

    double lo = 0.0, hi = 0.0;

    param() = default;
    explicit param(double v) { set(v, v); }
    param(double l, double h) { set(l, h); }
    // Not for param itself: checking Interval<param> asks whether param is copyable, which asks
    // this constructor again (clang 14 recurses without end; the first conjunct stops it).
    template <class I>
        requires(!std::is_same_v<I, param>) && Interval<I>
    explicit param(const I& v) {
        set(v);
    }

    void set(double l, double h) {
        if (!(l <= h))
            throw invalid_argument("param", "interval parameter " + std::to_string(Id) + " needs lo <= hi, got [" +
                                                certipose::detail::format_double(l) + ", " + certipose::detail::format_double(h) + "]");
        lo = l;
        hi = h;
    }
    template <Interval I>
    void set(const I& v) {
        set(lower(v), upper(v));
    }

    template <std::size_t O, class Box, class V>
    detail::interval_of<V> value(const Box&, const V&) const {
        return detail::interval_of<V>(lo, hi);
    }
    template <std::size_t O, class Box, class V>
    CERTIPOSE_DETAIL_INLINE bool bwd(const detail::interval_of<V>& t, Box&, V&) const {
        return !is_empty(intersect(t, detail::interval_of<V>(lo, hi)));
    }
    template <std::size_t J>
    void set_param(double l, double h) {
        if constexpr (J == Id) set(l, h);
    }
};

// ---- operator nodes -------------------------------------------------------------------------

/// A unary operator node: one slot for its value, then its operand's slots. `Op` supplies the
/// interval rules: fwd(a), bwd(a, y) = a ∩ {t : op(t) ∈ y} (a superset of it), the derivative
/// and the domain test.
template <class Op, class A>
struct unary : node_tag {
    static constexpr std::size_t slots = 1 + A::slots;
    static constexpr std::uint64_t var_mask = A::var_mask;
    static constexpr std::size_t var_bound = A::var_bound;
    static constexpr bool repeated = A::repeated;
    static constexpr bool is_constant = false;

    A a;
    Op op;

    unary(A arg, Op o = {}) : a(std::move(arg)), op(o) {}

    template <std::size_t O, class Box, class V>
    CERTIPOSE_DETAIL_INLINE void fwd(const Box& box, V& v) const {
        using I = detail::interval_of<V>;
        a.template fwd<O + 1>(box, v);
        v[O] = op.fwd(detail::as_interval<I>(a.template value<O + 1>(box, v)));
    }
    template <std::size_t O, class Box, class V>
    CERTIPOSE_DETAIL_INLINE const auto& value(const Box&, const V& v) const noexcept {
        return v[O];
    }
    template <std::size_t O, class Box, class V>
    CERTIPOSE_DETAIL_INLINE bool bwd(const detail::interval_of<V>& t, Box& box, V& v) const {
        using I = detail::interval_of<V>;
        if (!detail::narrow(v[O], t)) return false;
        if constexpr (A::is_constant) {
            return true;
        } else {
            const I target = op.bwd(detail::as_interval<I>(a.template value<O + 1>(box, v)), v[O]);
            return !is_empty(target) && a.template bwd<O + 1>(target, box, v);
        }
    }
    template <std::size_t O, class Box, class V>
    CERTIPOSE_DETAIL_INLINE bool defined(const Box& box, const V& v) const {
        using I = detail::interval_of<V>;
        return a.template defined<O + 1>(box, v) && op.defined(detail::as_interval<I>(a.template value<O + 1>(box, v)));
    }
    template <std::size_t O, class Box, class V>
    auto grad(const Box& box, const V& v) const {
        using I = detail::interval_of<V>;
        auto g = a.template grad<O + 1>(box, v);
        if constexpr (!A::is_constant) {
            const I d = op.deriv(detail::as_interval<I>(a.template value<O + 1>(box, v)), v[O]);
            for (auto& gi : g)
                if (!(lower(gi) == 0.0 && upper(gi) == 0.0)) gi = d * gi;
        }
        return g;
    }
    template <std::size_t Id>
    void set_param(double l, double h) {
        a.template set_param<Id>(l, h);
    }
};

/// A binary operator node: its slot, then the left operand's slots, then the right's. Operands
/// that are double constants are passed to `Op` as doubles (the backends' mixed operations are
/// cheaper, and a constant needs no projection).
template <class Op, class L, class R>
struct binary : node_tag {
    static constexpr std::size_t slots = 1 + L::slots + R::slots;
    static constexpr std::uint64_t var_mask = L::var_mask | R::var_mask;
    static constexpr std::size_t var_bound = std::max(L::var_bound, R::var_bound);
    static constexpr bool repeated = L::repeated || R::repeated || (L::var_mask & R::var_mask) != 0;
    static constexpr bool is_constant = false;

    L l;
    R r;

    binary(L left, R right) : l(std::move(left)), r(std::move(right)) {}

    template <std::size_t O, class Box, class V>
    CERTIPOSE_DETAIL_INLINE void fwd(const Box& box, V& v) const {
        l.template fwd<O + 1>(box, v);
        r.template fwd<O + 1 + L::slots>(box, v);
        v[O] = Op::template fwd<detail::interval_of<V>>(l.template value<O + 1>(box, v),
                                                         r.template value<O + 1 + L::slots>(box, v));
    }
    template <std::size_t O, class Box, class V>
    CERTIPOSE_DETAIL_INLINE const auto& value(const Box&, const V& v) const noexcept {
        return v[O];
    }
    template <std::size_t O, class Box, class V>
    CERTIPOSE_DETAIL_INLINE bool bwd(const detail::interval_of<V>& t, Box& box, V& v) const {
        using I = detail::interval_of<V>;
        constexpr std::size_t lo = O + 1, ro = O + 1 + L::slots;
        if (!detail::narrow(v[O], t)) return false;
        if constexpr (!L::is_constant) {
            const I target = Op::bwd_left(v[O], detail::as_interval<I>(l.template value<lo>(box, v)),
                                          r.template value<ro>(box, v));
            if (is_empty(target) || !l.template bwd<lo>(target, box, v)) return false;
        }
        if constexpr (!R::is_constant) {
            const I target = Op::bwd_right(v[O], l.template value<lo>(box, v),
                                           detail::as_interval<I>(r.template value<ro>(box, v)));
            if (is_empty(target) || !r.template bwd<ro>(target, box, v)) return false;
        }
        return true;
    }
    template <std::size_t O, class Box, class V>
    CERTIPOSE_DETAIL_INLINE bool defined(const Box& box, const V& v) const {
        return l.template defined<O + 1>(box, v) && r.template defined<O + 1 + L::slots>(box, v) &&
               Op::defined(r.template value<O + 1 + L::slots>(box, v));
    }
    template <std::size_t O, class Box, class V>
    auto grad(const Box& box, const V& v) const {
        using I = detail::interval_of<V>;
        constexpr std::size_t lo = O + 1, ro = O + 1 + L::slots;
        auto gl = l.template grad<lo>(box, v);
        const auto gr = r.template grad<ro>(box, v);
        const I a = detail::as_interval<I>(l.template value<lo>(box, v));
        const I b = detail::as_interval<I>(r.template value<ro>(box, v));
        for (std::size_t k = 0; k < gl.size(); ++k) gl[k] = Op::deriv(a, b, v[O], gl[k], gr[k]);
        return gl;
    }
    template <std::size_t Id>
    void set_param(double lo, double hi) {
        l.template set_param<Id>(lo, hi);
        r.template set_param<Id>(lo, hi);
    }
};

// ---- operator rules -----------------------------------------------------------------------
// bwd_left(y, a, b) / bwd_right(y, a, b): a superset of the projection of {x = a op b, x ∈ y}
// onto a / b. The operand being projected is an interval; the other may be a double.

namespace ops {

template <class I>
bool is_zero(const I& g) {
    return lower(g) == 0.0 && upper(g) == 0.0;
}

struct add {
    template <class I, class A, class B>
    CERTIPOSE_DETAIL_INLINE static I fwd(const A& a, const B& b) {
        if constexpr (std::is_arithmetic_v<A> && std::is_arithmetic_v<B>) return I(a) + b;
        else return a + b;
    }
    template <class I, class B>
    CERTIPOSE_DETAIL_INLINE static I bwd_left(const I& y, const I&, const B& b) { return y - b; }
    template <class I, class A>
    CERTIPOSE_DETAIL_INLINE static I bwd_right(const I& y, const A& a, const I&) { return y - a; }
    template <class B>
    static bool defined(const B&) { return true; }
    template <class I>
    static I deriv(const I&, const I&, const I&, const I& ga, const I& gb) {
        return is_zero(gb) ? ga : is_zero(ga) ? gb : ga + gb;
    }
};

struct sub {
    template <class I, class A, class B>
    CERTIPOSE_DETAIL_INLINE static I fwd(const A& a, const B& b) {
        if constexpr (std::is_arithmetic_v<A> && std::is_arithmetic_v<B>) return I(a) - b;
        else return a - b;
    }
    template <class I, class B>
    CERTIPOSE_DETAIL_INLINE static I bwd_left(const I& y, const I&, const B& b) { return y + b; }
    template <class I, class A>
    CERTIPOSE_DETAIL_INLINE static I bwd_right(const I& y, const A& a, const I&) { return a - y; }
    template <class B>
    static bool defined(const B&) { return true; }
    template <class I>
    static I deriv(const I&, const I&, const I&, const I& ga, const I& gb) {
        return is_zero(gb) ? ga : is_zero(ga) ? -gb : ga - gb;
    }
};

struct mul {
    template <class I, class A, class B>
    CERTIPOSE_DETAIL_INLINE static I fwd(const A& a, const B& b) {
        if constexpr (std::is_arithmetic_v<A> && std::is_arithmetic_v<B>) return I(a) * b;
        else return a * b;
    }
    template <class I, class B>
    CERTIPOSE_DETAIL_INLINE static I bwd_left(const I& y, const I& a, const B& b) {
        return expr::detail::div_projection(a, y, b);
    }
    template <class I, class A>
    CERTIPOSE_DETAIL_INLINE static I bwd_right(const I& y, const A& a, const I& b) {
        return expr::detail::div_projection(b, y, a);
    }
    template <class B>
    static bool defined(const B&) { return true; }
    template <class I>
    static I deriv(const I& a, const I& b, const I&, const I& ga, const I& gb) {
        if (is_zero(gb)) return is_zero(ga) ? ga : b * ga;
        if (is_zero(ga)) return a * gb;
        return b * ga + a * gb;
    }
};

struct div {
    template <class I, class A, class B>
    CERTIPOSE_DETAIL_INLINE static I fwd(const A& a, const B& b) {
        if constexpr (std::is_arithmetic_v<B>) {
            if (b == 0.0) return interval_traits<I>::empty();  // x / 0 is defined nowhere
            if constexpr (std::is_arithmetic_v<A>) return I(a) / b;
            else return a / b;
        } else {
            return a / b;
        }
    }
    // x = a / b  ⇒  a = x·b (wherever x is defined).
    template <class I, class B>
    CERTIPOSE_DETAIL_INLINE static I bwd_left(const I& y, const I&, const B& b) { return y * b; }
    // x = a / b  ⇒  b = a / x when x ≠ 0, any b when x = 0 = a.
    template <class I, class A>
    CERTIPOSE_DETAIL_INLINE static I bwd_right(const I& y, const A& a, const I& b) {
        return expr::detail::div_projection(b, expr::detail::as_interval<I>(a), y);
    }
    template <class B>
    static bool defined(const B& b) {
        if constexpr (std::is_arithmetic_v<B>) return b != 0.0;
        else return !contains(b, 0.0);
    }
    template <class I>
    static I deriv(const I&, const I& b, const I& x, const I& ga, const I& gb) {
        // d(a/b) = (da − x·db) / b
        if (is_zero(gb)) return is_zero(ga) ? ga : ga / b;
        return (ga - x * gb) / b;
    }
};

struct neg {
    template <class I>
    CERTIPOSE_DETAIL_INLINE I fwd(const I& a) const { return -a; }
    template <class I>
    CERTIPOSE_DETAIL_INLINE I bwd(const I&, const I& y) const { return -y; }
    template <class I>
    CERTIPOSE_DETAIL_INLINE bool defined(const I&) const { return true; }
    template <class I>
    I deriv(const I&, const I&) const { return I(-1.0); }
};

struct sqr_op {
    template <class I>
    CERTIPOSE_DETAIL_INLINE I fwd(const I& a) const { return sqr(a); }
    template <class I>
    CERTIPOSE_DETAIL_INLINE I bwd(const I& a, const I& y) const { return expr::detail::two_branches(a, expr::detail::sqrt_enclosure(y)); }
    template <class I>
    CERTIPOSE_DETAIL_INLINE bool defined(const I&) const { return true; }
    template <class I>
    I deriv(const I& a, const I&) const { return 2.0 * a; }
};

struct sqrt_op {
    template <class I>
    CERTIPOSE_DETAIL_INLINE I fwd(const I& a) const { return sqrt(a); }
    template <class I>
    CERTIPOSE_DETAIL_INLINE I bwd(const I& a, const I& y) const {
        const I yp = expr::detail::non_negative(y);
        if (is_empty(yp)) return yp;
        return intersect(expr::detail::non_negative(a), sqr(yp));
    }
    template <class I>
    CERTIPOSE_DETAIL_INLINE bool defined(const I& a) const { return !is_empty(a) && lower(a) >= 0.0; }
    template <class I>
    I deriv(const I&, const I& x) const { return 0.5 / x; }
};

struct abs_op {
    template <class I>
    CERTIPOSE_DETAIL_INLINE I fwd(const I& a) const { return abs(a); }
    template <class I>
    CERTIPOSE_DETAIL_INLINE I bwd(const I& a, const I& y) const {
        return expr::detail::two_branches(a, expr::detail::non_negative(y));
    }
    template <class I>
    CERTIPOSE_DETAIL_INLINE bool defined(const I&) const { return true; }
    template <class I>
    I deriv(const I& a, const I&) const {
        if (lower(a) > 0.0) return I(1.0);
        if (upper(a) < 0.0) return I(-1.0);
        return I(-1.0, 1.0);
    }
};

struct pow_op {
    int n = 2;
    template <class I>
    CERTIPOSE_DETAIL_INLINE I fwd(const I& a) const { return pow(a, n); }
    template <class I>
    CERTIPOSE_DETAIL_INLINE I bwd(const I& a, const I& y) const {
        if (n == 0) return a;  // y ∋ 1 was checked by the node; no information on a
        if (n == 1) return y;
        if (n == 2) return expr::detail::two_branches(a, expr::detail::sqrt_enclosure(y));
        if (n > 0) return expr::detail::pow_projection(a, y, n);
        // y = 1 / a^|n|  ⇒  a^|n| ∈ 1 / y
        const I z = expr::detail::div_projection(interval_traits<I>::whole(), I(1.0), y);
        return expr::detail::pow_projection(a, z, -n);
    }
    template <class I>
    CERTIPOSE_DETAIL_INLINE bool defined(const I& a) const { return n >= 0 || !contains(a, 0.0); }
    template <class I>
    I deriv(const I& a, const I&) const {
        if (n == 0) return I(0.0);
        return static_cast<double>(n) * pow(a, n - 1);
    }
};

struct sin_op {
    template <class I>
    CERTIPOSE_DETAIL_INLINE I fwd(const I& a) const { return sin(a); }
    template <class I>
    CERTIPOSE_DETAIL_INLINE I bwd(const I& a, const I& y) const { return expr::detail::periodic_projection(a, y, true); }
    template <class I>
    CERTIPOSE_DETAIL_INLINE bool defined(const I&) const { return true; }
    template <class I>
    I deriv(const I& a, const I&) const { return cos(a); }
};

struct cos_op {
    template <class I>
    CERTIPOSE_DETAIL_INLINE I fwd(const I& a) const { return cos(a); }
    template <class I>
    CERTIPOSE_DETAIL_INLINE I bwd(const I& a, const I& y) const { return expr::detail::periodic_projection(a, y, false); }
    template <class I>
    CERTIPOSE_DETAIL_INLINE bool defined(const I&) const { return true; }
    template <class I>
    I deriv(const I& a, const I&) const { return -sin(a); }
};

}  // namespace ops

// ---- building trees -----------------------------------------------------------------------

/// An operand as an expression node (numbers become `constant`).
template <Operand T>
auto as_expr(const T& x) {
    if constexpr (Expression<T>) return x;
    else return constant(static_cast<double>(x));
}

template <class T>
using expr_t = decltype(as_expr(std::declval<const T&>()));

template <Operand A, Operand B>
    requires(Expression<A> || Expression<B>)
auto operator+(const A& a, const B& b) {
    return binary<ops::add, expr_t<A>, expr_t<B>>(as_expr(a), as_expr(b));
}
template <Operand A, Operand B>
    requires(Expression<A> || Expression<B>)
auto operator-(const A& a, const B& b) {
    return binary<ops::sub, expr_t<A>, expr_t<B>>(as_expr(a), as_expr(b));
}
template <Operand A, Operand B>
    requires(Expression<A> || Expression<B>)
auto operator*(const A& a, const B& b) {
    return binary<ops::mul, expr_t<A>, expr_t<B>>(as_expr(a), as_expr(b));
}
template <Operand A, Operand B>
    requires(Expression<A> || Expression<B>)
auto operator/(const A& a, const B& b) {
    return binary<ops::div, expr_t<A>, expr_t<B>>(as_expr(a), as_expr(b));
}
template <Expression A>
auto operator-(const A& a) {
    return unary<ops::neg, A>(a);
}
template <Expression A>
auto sqr(const A& a) {
    return unary<ops::sqr_op, A>(a);
}
template <Expression A>
auto sqrt(const A& a) {
    return unary<ops::sqrt_op, A>(a);
}
template <Expression A>
auto abs(const A& a) {
    return unary<ops::abs_op, A>(a);
}
/// a^n for an integer n (negative n means 1 / a^|n|).
template <Expression A>
auto pow(const A& a, int n) {
    return unary<ops::pow_op, A>(a, ops::pow_op{n});
}
template <Expression A>
auto sin(const A& a) {
    return unary<ops::sin_op, A>(a);
}
template <Expression A>
auto cos(const A& a) {
    return unary<ops::cos_op, A>(a);
}

/// Sets every `param<Id>` in `e` (an expression, a constraint or a contractor holding them).
template <std::size_t Id, class T>
void set_param(T& e, double lo, double hi) {
    e.template set_param<Id>(lo, hi);
}
template <std::size_t Id, class T, Interval I>
void set_param(T& e, const I& value) {
    e.template set_param<Id>(lower(value), upper(value));
}

}  // namespace certipose::expr

namespace certipose {
using expr::Expression;
using expr::param;
using expr::set_param;
using expr::var;
// The functions too, so that `certipose::sqr(x - 1.0)` works as well as unqualified `sqr(x - 1.0)`
// (found by ADL). They are constrained to expressions, so they overload the interval backends'
// functions of the same name without ambiguity.
using expr::abs;
using expr::cos;
using expr::pow;
using expr::sin;
using expr::sqr;
using expr::sqrt;
}  // namespace certipose
