// certipose/interval/cgal_interval.hpp — a second interval backend over CGAL::Interval_nt
// (needs certipose::cgal).
//
// It exists to prove the library generic over the interval type, and because CGAL's interval
// is fast (SSE2, ~23 ns for a 3x3 matrix–vector product with the mode held). Interval_nt<false>
// assumes the caller holds the rounding mode upward, which `rounding_guard<cgal_interval>`
// (CGAL's own Protect_FPU_rounding) does. Interval_nt cannot represent the empty set, so the
// wrapper carries an emptiness flag; it has no sin/cos/acos/atan, which come from
// detail/transcendental.hpp (round-to-nearest evaluation widened outward).
#pragma once

#include <algorithm>
#include <type_traits>

#include <CGAL/Interval_nt.h>

#include "certipose/interval/concept.hpp"
#include "certipose/interval/detail/fenv.hpp"
#include "certipose/interval/detail/transcendental.hpp"
#include "certipose/interval/operations.hpp"

namespace certipose {

class cgal_interval;
inline bool is_empty(const cgal_interval& a) noexcept;

class cgal_interval {
public:
    using base_type = CGAL::Interval_nt<false>;
    /// CGAL's guard writes only the rounding field of MXCSR: the subnormals scope, made first
    /// and ended last, clears flush-to-zero and denormals-are-zero around it (a host linked
    /// with -ffast-math sets them, and a flushed upper bound is below the true value).
    class guard {
    public:
        guard() noexcept {}  // NOLINT: user-provided, so that `const guard g;` is valid
        guard(const guard&) = delete;
        guard& operator=(const guard&) = delete;

    private:
        detail::subnormals_scope subnormals_;
        CGAL::Protect_FPU_rounding<true> rounding_;
    };

    cgal_interval() : v_(0.0) {}
    template <class U>
        requires std::is_arithmetic_v<U>
    cgal_interval(U v) : v_(0.0), empty_(std::isnan(static_cast<double>(v))) {  // NOLINT
        // Interval_nt(double) asserts a finite value; the two-bound form accepts ±inf, which
        // mixed operations meet (`a + inf`), as Boost does.
        if (!empty_) v_ = base_type(static_cast<double>(v), static_cast<double>(v));
    }
    /// [lo, hi]; lo > hi or a NaN bound yields the empty interval.
    cgal_interval(double lo, double hi) : v_(0.0), empty_(!(lo <= hi)) {
        if (!empty_) v_ = base_type(lo, hi);
    }
    explicit cgal_interval(const base_type& v) : v_(v) {}

    static cgal_interval empty() {
        cgal_interval e;
        e.empty_ = true;
        return e;
    }
    const base_type& base() const noexcept { return v_; }
    bool empty_flag() const noexcept { return empty_; }

    friend bool operator==(const cgal_interval& a, const cgal_interval& b) noexcept {
        if (a.empty_ || b.empty_) return a.empty_ == b.empty_;
        return a.v_.inf() == b.v_.inf() && a.v_.sup() == b.v_.sup();
    }

    friend cgal_interval operator-(const cgal_interval& a) { return a.empty_ ? a : cgal_interval(-a.v_); }
    friend cgal_interval operator+(const cgal_interval& a, const cgal_interval& b) { return binary(a, b, [](auto x, auto y) { return x + y; }); }
    friend cgal_interval operator-(const cgal_interval& a, const cgal_interval& b) { return binary(a, b, [](auto x, auto y) { return x - y; }); }
    friend cgal_interval operator*(const cgal_interval& a, const cgal_interval& b) { return binary(a, b, [](auto x, auto y) { return x * y; }); }
    friend cgal_interval operator/(const cgal_interval& a, const cgal_interval& b) { return binary(a, b, [](auto x, auto y) { return x / y; }); }
    friend cgal_interval operator+(const cgal_interval& a, double d) { return a + cgal_interval(d); }
    friend cgal_interval operator+(double d, const cgal_interval& a) { return cgal_interval(d) + a; }
    friend cgal_interval operator-(const cgal_interval& a, double d) { return a - cgal_interval(d); }
    friend cgal_interval operator-(double d, const cgal_interval& a) { return cgal_interval(d) - a; }
    friend cgal_interval operator*(const cgal_interval& a, double d) { return a * cgal_interval(d); }
    friend cgal_interval operator*(double d, const cgal_interval& a) { return cgal_interval(d) * a; }
    friend cgal_interval operator/(const cgal_interval& a, double d) { return a / cgal_interval(d); }
    friend cgal_interval operator/(double d, const cgal_interval& a) { return cgal_interval(d) / a; }
    cgal_interval& operator+=(const cgal_interval& o) { return *this = *this + o; }
    cgal_interval& operator-=(const cgal_interval& o) { return *this = *this - o; }
    cgal_interval& operator*=(const cgal_interval& o) { return *this = *this * o; }
    cgal_interval& operator/=(const cgal_interval& o) { return *this = *this / o; }

private:
    template <class Op>
    static cgal_interval binary(const cgal_interval& a, const cgal_interval& b, Op op) {
        detail::assert_rounding_held();
        if (a.empty_ || b.empty_) return empty();
        return cgal_interval(op(a.v_, b.v_));
    }

    base_type v_;
    bool empty_ = false;
};

inline bool is_empty(const cgal_interval& a) noexcept { return a.empty_flag(); }

// Namespace-scope (not hidden friends) so that both `lower(x)` and `certipose::lower(x)` work.
inline double lower(const cgal_interval& a) noexcept {
    return is_empty(a) ? std::numeric_limits<double>::quiet_NaN() : a.base().inf();
}
inline double upper(const cgal_interval& a) noexcept {
    return is_empty(a) ? std::numeric_limits<double>::quiet_NaN() : a.base().sup();
}
inline cgal_interval sqr(const cgal_interval& a) {
    detail::assert_rounding_held();
    return is_empty(a) ? a : cgal_interval(CGAL::square(a.base()));
}
inline cgal_interval sqrt(const cgal_interval& a) {
    detail::assert_rounding_held();
    if (is_empty(a) || a.base().sup() < 0.0) return cgal_interval::empty();
    // CGAL's sqrt clamps a negative lower bound to 0: the domain restriction we want.
    return cgal_interval(CGAL::sqrt(a.base()));
}
inline cgal_interval abs(const cgal_interval& a) { return is_empty(a) ? a : cgal_interval(CGAL::abs(a.base())); }
inline cgal_interval pow(const cgal_interval& a, int n) { return detail::generic_pow(a, n); }
inline cgal_interval sin(const cgal_interval& a) { return detail::generic_sin(a); }
inline cgal_interval cos(const cgal_interval& a) { return detail::generic_cos(a); }
inline cgal_interval acos(const cgal_interval& a) { return detail::generic_acos(a); }
inline cgal_interval atan(const cgal_interval& a) { return detail::generic_atan(a); }

template <>
struct interval_traits<cgal_interval> {
    using rounding_guard = cgal_interval::guard;
    static cgal_interval empty() { return cgal_interval::empty(); }
    static cgal_interval whole() { return cgal_interval(cgal_interval::base_type::largest()); }
    static constexpr const char* name = "cgal_interval";
};

static_assert(Interval<cgal_interval>);

}  // namespace certipose
