// certipose/interval/boost_interval.hpp — the default interval backend: a thin wrapper over
// boost::numeric::interval<double> with sound policies.
//
// Why a wrapper and not the Boost type itself: Boost's unconstrained converting constructor
// makes `Eigen::Matrix3<I> * Eigen::Vector3<I>` ambiguous (STYLE.md); ours converts only from
// arithmetic types. Why these policies (each measured on this toolchain, STYLE.md):
//  * arithmetic: `rounded_arith_opp` only. The `_std` and `_exact` policies gave zero-width
//    results at -O2, so the class is not a template over the policy: it cannot be misconfigured.
//  * rounding mode: `save_state_nothing`, i.e. held upward by `rounding_guard<boost_interval>`
//    (Boost's own `save_state`) once per hot block instead of switched per operation (~4x).
//  * transcendental functions: glibc ignores the rounding mode, so `rounded_transc_widened`
//    evaluates in round-to-nearest and widens by `detail::transcendental_ulps` ulps; Boost's own
//    range reduction (interval π, monotone pieces) does the rest.
//  * checking: `checking_base`, so the empty interval is representable ([NaN, NaN]) and a
//    contractor proving infeasibility returns it instead of throwing.
//  * speed: +, − and × (the bulk of every contractor) are computed branch-free from Boost's
//    rounding primitives (`add_up`, `mul_up`, ...) instead of Boost's operators, which test
//    emptiness and, for ×, dispatch nine ways on signs first; and Boost's volatile
//    `force_rounding` becomes a register barrier on SSE2 (`detail::rounding_control`). With the
//    mode held, a 3x3 matrix–vector product went from ~4x to ~2x the time of raw
//    CGAL::Interval_nt (bench/intervals.cpp).
//  * every operand is read through `detail::pin` (a volatile asm, like CGAL's IA_opacify), so
//    g++ cannot reuse a value computed in round-to-nearest before the guard (GCC PR 34678).
#pragma once

#include <cassert>
#include <cmath>
#include <concepts>
#include <limits>
#include <type_traits>

#include <boost/numeric/interval.hpp>

#include "certipose/detail/config.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/interval/detail/fenv.hpp"
#include "certipose/interval/operations.hpp"

namespace certipose {

namespace detail {

/// Boost rounding policy for transcendental functions: round-to-nearest evaluation widened
/// outward, which is sound for glibc whatever mode the caller holds.
template <class T, class Rounding>
struct rounded_transc_widened : Rounding {
private:
    template <class F>
    static T down(F f, const T& x) {
        const round_to_nearest_scope nearest{};
        return ulps_down(f(x));
    }
    template <class F>
    static T up(F f, const T& x) {
        const round_to_nearest_scope nearest{};
        return ulps_up(f(x));
    }

public:
    T cos_down(const T& x) { return down([](T v) { return std::cos(v); }, x); }
    T cos_up(const T& x) { return up([](T v) { return std::cos(v); }, x); }
    T sin_down(const T& x) { return down([](T v) { return std::sin(v); }, x); }
    T sin_up(const T& x) { return up([](T v) { return std::sin(v); }, x); }
    T acos_down(const T& x) { return down([](T v) { return std::acos(v); }, x); }
    T acos_up(const T& x) { return up([](T v) { return std::acos(v); }, x); }
    T asin_down(const T& x) { return down([](T v) { return std::asin(v); }, x); }
    T asin_up(const T& x) { return up([](T v) { return std::asin(v); }, x); }
    T atan_down(const T& x) { return down([](T v) { return std::atan(v); }, x); }
    T atan_up(const T& x) { return up([](T v) { return std::atan(v); }, x); }

    // Boost's own sqrt_down switches to downward and back; g++ -O2 then evaluated the root
    // once for both bounds (CSE across fesetround, GCC PR 34678): sqrt([2,2]) came out with
    // zero width and an upper bound below √2. With the mode held upward, r = sqrt_up(x) is the
    // root rounded up; r is a lower bound iff r·r ≤ x (tested rounded up), else its predecessor
    // is (the root lies strictly between them). No mode switch, so nothing to CSE.
    T sqrt_down(const T& x) {
        const T r = this->sqrt_up(x);
        return this->mul_up(r, r) <= x ? r : std::nextafter(r, -std::numeric_limits<T>::infinity());
    }
};

#if (defined(__GNUC__) || defined(__clang__)) && defined(__SSE2_MATH__) && __FLT_EVAL_METHOD__ == 0
/// Boost's rounding control for double, with its `force_rounding` (a volatile store and load,
/// there to strip x87 excess precision) replaced by a register-only optimisation barrier: with
/// SSE2 arithmetic there is no excess precision, and the barrier still pins each result where
/// Boost's volatile did. Worth ~20% of a 3x3 matrix–vector product (bench/intervals.cpp).
// The mode itself is read and set through detail/fenv.hpp's inline register access instead of
// Boost's fegetround/fesetround (C99 rounding control), which cost ~100 ns a call here: a
// guard went from ~200 ns to a few.
struct rounding_control : boost::numeric::interval_lib::rounding_control<double> {
    using rounding_mode = fp_modes;
    static void get_rounding_mode(rounding_mode& m) noexcept { m = get_fp_modes(); }
    static void set_rounding_mode(const rounding_mode& m) noexcept { set_fp_modes(m); }
    static void downward() noexcept { set_rounding(FE_DOWNWARD); }
    static void upward() noexcept { set_rounding(FE_UPWARD); }
    static void to_nearest() noexcept { set_rounding(FE_TONEAREST); }
    static void toward_zero() noexcept { set_rounding(FE_TOWARDZERO); }
    static double force_rounding(double r) {
        asm volatile("" : "+x"(r));
        return r;
    }
};
#else
using rounding_control = boost::numeric::interval_lib::rounding_control<double>;
#endif

/// Returns `x` through an empty volatile asm, as CGAL's IA_opacify does. g++ does not know that
/// the rounding mode changes at a guard (GCC PR 34678): a quotient 1.0/3.0 computed in
/// round-to-nearest before the guard was reused, at -O2, as the upper bound of [1]/[3] inside it
/// (zero width, below 1/3). Operands read through this barrier are values the compiler cannot
/// match with earlier ones, and a volatile asm stays after the guard's fesetround.
CERTIPOSE_DETAIL_INLINE double pin(double x) noexcept {
#if (defined(__GNUC__) || defined(__clang__)) && defined(__SSE2_MATH__)
    asm volatile("" : "+x"(x));
    return x;
#elif defined(__GNUC__) || defined(__clang__)
    asm volatile("" : "+m"(x));
    return x;
#else
    volatile double v = x;
    return v;
#endif
}
template <class B>
CERTIPOSE_DETAIL_INLINE B pin_bounds(const B& b) noexcept {
    return B(pin(b.lower()), pin(b.upper()), true);
}

}  // namespace detail

/// The default interval type of certipose (see the header comment). A class of its own, not an
/// alias of a Boost template, so that compiler messages say `certipose::boost_interval`.
class boost_interval {
    // The "opposite trick", the only Boost arithmetic policy that stayed sound at -O2 with the
    // mode held upward (see the header comment).
    using Arith = boost::numeric::interval_lib::rounded_arith_opp<double, detail::rounding_control>;

public:
    using rounding = detail::rounded_transc_widened<double, Arith>;
    using base_type = boost::numeric::interval<
        double, boost::numeric::interval_lib::policies<
                    boost::numeric::interval_lib::save_state_nothing<rounding>,
                    boost::numeric::interval_lib::checking_base<double>>>;
    /// Holds the rounding mode upward, then restores the caller's mode: Boost's own RAII
    /// (`save_state`), which with detail::rounding_control saves and restores both the x87 and
    /// the SSE control word (a CGAL guard may have set the SSE mode alone).
    class guard {
    public:
        guard() noexcept {}  // NOLINT: user-provided so that `const guard g;` is valid
        guard(const guard&) = delete;
        guard& operator=(const guard&) = delete;

    private:
        boost::numeric::interval_lib::save_state<rounding> state_;
    };

    constexpr boost_interval() = default;
    /// A point interval. Only arithmetic types convert implicitly (see the header comment).
    template <class U>
        requires std::is_arithmetic_v<U>
    boost_interval(U v) : b_(static_cast<double>(v)) {}  // NOLINT(implicit)
    /// [lo, hi]; lo > hi or a NaN bound yields the empty interval.
    boost_interval(double lo, double hi) : b_(make(lo, hi)) {}
    explicit boost_interval(const base_type& b) : b_(b) {}

    const base_type& base() const noexcept { return b_; }

    /// Set equality (both empty, or same bounds). Not an order: use certainly_/possibly_.
    friend bool operator==(const boost_interval& a, const boost_interval& b) noexcept {
        const bool ea = boost::numeric::empty(a.b_), eb = boost::numeric::empty(b.b_);
        return ea || eb ? ea == eb : (a.b_.lower() == b.b_.lower() && a.b_.upper() == b.b_.upper());
    }

    CERTIPOSE_DETAIL_INLINE friend boost_interval operator-(const boost_interval& a) { return boost_interval(-a.b_); }
    // +, − and × are the hot path of every contractor, and Boost's versions branch on emptiness
    // (and × nine ways on signs) before computing. Ours compute first with Boost's own rounding
    // primitives and let the empty set's NaN bounds propagate; see mul() for ×.
    CERTIPOSE_DETAIL_INLINE friend boost_interval operator+(const boost_interval& a, const boost_interval& b) {
        detail::assert_rounding_held();
        rounding rnd;
        const base_type x = detail::pin_bounds(a.b_), y = detail::pin_bounds(b.b_);
        return raw(rnd.add_down(x.lower(), y.lower()), rnd.add_up(x.upper(), y.upper()));
    }
    CERTIPOSE_DETAIL_INLINE friend boost_interval operator-(const boost_interval& a, const boost_interval& b) {
        detail::assert_rounding_held();
        rounding rnd;
        const base_type x = detail::pin_bounds(a.b_), y = detail::pin_bounds(b.b_);
        return raw(rnd.sub_down(x.lower(), y.upper()), rnd.sub_up(x.upper(), y.lower()));
    }
    CERTIPOSE_DETAIL_INLINE friend boost_interval operator*(const boost_interval& a, const boost_interval& b) {
        detail::assert_rounding_held();
        const base_type x = detail::pin_bounds(a.b_), y = detail::pin_bounds(b.b_);
        const boost_interval r = mul(x.lower(), x.upper(), y.lower(), y.upper());
        if (!is_empty_fast(r)) [[likely]] return r;
        return boost_interval(x * y);
    }
    friend boost_interval operator/(const boost_interval& a, const boost_interval& b) {
        detail::assert_rounding_held();
        return boost_interval(detail::pin_bounds(a.b_) / detail::pin_bounds(b.b_));
    }
    // Mixed with double: `a + 1.0`, `2.0 * a` (a NaN double yields the empty set).
    CERTIPOSE_DETAIL_INLINE friend boost_interval operator+(const boost_interval& a, double d) { return a + boost_interval(d); }
    CERTIPOSE_DETAIL_INLINE friend boost_interval operator+(double d, const boost_interval& a) { return boost_interval(d) + a; }
    CERTIPOSE_DETAIL_INLINE friend boost_interval operator-(const boost_interval& a, double d) { return a - boost_interval(d); }
    CERTIPOSE_DETAIL_INLINE friend boost_interval operator-(double d, const boost_interval& a) { return boost_interval(d) - a; }
    CERTIPOSE_DETAIL_INLINE friend boost_interval operator*(const boost_interval& a, double d) {
        detail::assert_rounding_held();
        const base_type x = detail::pin_bounds(a.b_);
        const double y = detail::pin(d);
        const boost_interval r = mul(x.lower(), x.upper(), y, y);
        if (!is_empty_fast(r)) [[likely]] return r;
        return boost_interval(x * y);
    }
    CERTIPOSE_DETAIL_INLINE friend boost_interval operator*(double d, const boost_interval& a) { return a * d; }
    friend boost_interval operator/(const boost_interval& a, double d) { detail::assert_rounding_held(); return boost_interval(detail::pin_bounds(a.b_) / detail::pin(d)); }
    friend boost_interval operator/(double d, const boost_interval& a) { detail::assert_rounding_held(); return boost_interval(detail::pin(d) / detail::pin_bounds(a.b_)); }

    boost_interval& operator+=(const boost_interval& o) { return *this = *this + o; }
    boost_interval& operator-=(const boost_interval& o) { return *this = *this - o; }
    boost_interval& operator*=(const boost_interval& o) { return *this = *this * o; }
    boost_interval& operator/=(const boost_interval& o) { return *this = *this / o; }

private:
    // Bounds computed with the mode held upward; NaN bounds mean empty (checking_base).
    CERTIPOSE_DETAIL_INLINE static boost_interval raw(double lo, double hi) { return boost_interval(base_type(lo, hi, true)); }
    static bool is_empty_fast(const boost_interval& r) { return !(r.b_.lower() <= r.b_.upper()); }

    // [al, au] × [bl, bu] without Boost's sign dispatch: all four corner products rounded up,
    // the lower bound through the opposite trick as −max(x · −y). A corner 0 · ∞ is NaN and
    // `x > y ? x : y` keeps the running maximum y when x is NaN, so such a corner is skipped —
    // exactly right, since its true contribution (0 · finite = 0) is bracketed by the corners
    // next to it. Only a NaN in the first corner survives (as do an empty operand's NaN
    // bounds): the caller then falls back to Boost's exact case analysis.
    CERTIPOSE_DETAIL_INLINE static boost_interval mul(double al, double au, double bl, double bu) {
        rounding rnd;
        const auto max = [](double x, double y) { return x > y ? x : y; };
        double l = rnd.mul_up(al, -bl);
        l = max(rnd.mul_up(al, -bu), l);
        l = max(rnd.mul_up(au, -bl), l);
        l = max(rnd.mul_up(au, -bu), l);
        double u = rnd.mul_up(al, bl);
        u = max(rnd.mul_up(al, bu), u);
        u = max(rnd.mul_up(au, bl), u);
        u = max(rnd.mul_up(au, bu), u);
        return raw(-l, u);
    }

    static base_type make(double lo, double hi) {
        if (!(lo <= hi)) return base_type::empty();
        return base_type(lo, hi, true);
    }
    base_type b_{};
};

// Namespace-scope (not hidden friends) so that both `lower(x)` and `certipose::lower(x)` work.
// Templates constrained to boost_interval rather than plain functions: a double argument must
// not convert to an interval silently (`sqrt(2.0)` inside namespace certipose stays an error).
template <std::same_as<boost_interval> A>
CERTIPOSE_DETAIL_INLINE double lower(const A& a) noexcept { return a.base().lower(); }
template <std::same_as<boost_interval> A>
CERTIPOSE_DETAIL_INLINE double upper(const A& a) noexcept { return a.base().upper(); }
template <std::same_as<boost_interval> A>
CERTIPOSE_DETAIL_INLINE bool is_empty(const A& a) noexcept { return boost::numeric::empty(a.base()); }

template <std::same_as<boost_interval> A>
CERTIPOSE_DETAIL_INLINE A sqr(const A& a) {
    detail::assert_rounding_held();
    return A(boost::numeric::square(detail::pin_bounds(a.base())));
}
template <std::same_as<boost_interval> A>
A sqrt(const A& a) {
    detail::assert_rounding_held();
    return A(boost::numeric::sqrt(detail::pin_bounds(a.base())));
}
template <std::same_as<boost_interval> A>
A abs(const A& a) {
    return A(boost::numeric::abs(a.base()));
}
template <std::same_as<boost_interval> A>
A pow(const A& a, int n) {
    detail::assert_rounding_held();
    // Boost returns the empty set for [0,0]^0, but x^0 = 1 everywhere (as std::pow says);
    // and it negates n, which overflows for INT_MIN.
    if (n == 0) return is_empty(a) ? a : A(1.0);
    if (n == std::numeric_limits<int>::min()) return sqr(pow(a, n / 2));
    return A(boost::numeric::pow(detail::pin_bounds(a.base()), n));
}

namespace detail {
// Outward widening may step past ±1; the true range of sin/cos never does.
template <std::same_as<boost_interval> A>
A clamp_unit(const A& a) {
    if (is_empty(a)) return a;
    return A(std::max(-1.0, lower(a)), std::min(1.0, upper(a)));
}
}  // namespace detail

template <std::same_as<boost_interval> A>
A sin(const A& a) {
    detail::assert_rounding_held();
    return detail::clamp_unit(A(boost::numeric::sin(detail::pin_bounds(a.base()))));
}
template <std::same_as<boost_interval> A>
A cos(const A& a) {
    detail::assert_rounding_held();
    return detail::clamp_unit(A(boost::numeric::cos(detail::pin_bounds(a.base()))));
}
template <std::same_as<boost_interval> A>
A acos(const A& a) {
    detail::assert_rounding_held();
    return A(boost::numeric::acos(detail::pin_bounds(a.base())));
}
template <std::same_as<boost_interval> A>
A atan(const A& a) {
    detail::assert_rounding_held();
    return A(boost::numeric::atan(detail::pin_bounds(a.base())));
}

template <>
struct interval_traits<boost_interval> {
    using I = boost_interval;
    using rounding_guard = typename I::guard;
    static I empty() { return I(I::base_type::empty()); }
    static I whole() { return I(I::base_type::whole()); }
    static constexpr const char* name = "boost_interval";
};

static_assert(Interval<boost_interval>);

}  // namespace certipose
