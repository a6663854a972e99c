// certipose/interval/detail/transcendental.hpp — sound sin/cos/acos/atan/pow for a backend
// that only has the four operations and sqrt (e.g. CGAL::Interval_nt).
//
// Method: evaluate at the endpoints in round-to-nearest (glibc is accurate to < 1 ulp there but
// ignores the rounding mode) and widen outward by ulps. sin and cos also add every extremum the
// interval possibly contains (periodic_bounds_nearest, which orientation/detail/spherical.hpp
// uses too, without a scope of its own).
//
// The templates are unconstrained on purpose: a backend calls them from its own friend
// functions, where the backend type is still incomplete and cannot satisfy `Interval` yet.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "certipose/interval/concept.hpp"
#include "certipose/interval/detail/fenv.hpp"

namespace certipose::detail {

/// Bounds of a real function over an interval, as doubles.
struct double_bounds {
    double lo, hi;
};

// Outward widenings of a libm result computed in round-to-nearest, by more than the error
// `transcendental_ulps` allows for. Either is sound; they differ in cost and tightness.
/// `transcendental_ulps` steps of nextafter: the tightest.
struct ulps_widening {
    static double down(double x) noexcept { return ulps_down(x); }
    static double up(double x) noexcept { return ulps_up(x); }
};
/// Cheaper than nextafter, for hot loops: for finite x, ulp(x) ≤ ε|x|, so subtracting 4ε|x| (an
/// exact power-of-two scaling) plus 16 subnormal ulps moves x down by at least 3.5 ulps after the
/// subtraction's own rounding to nearest (the caller must hold a nearest scope).
struct scaled_widening {
    static_assert(transcendental_ulps <= 3, "scaled_widening widens by 3.5 ulps at least");
    static double down(double x) noexcept { return x - (std::abs(x) * 0x1p-50 + 0x1p-1070); }
    static double up(double x) noexcept { return x + (std::abs(x) * 0x1p-50 + 0x1p-1070); }
};

// How periodic_bounds_nearest treats its argument; the two differ only for bit-for-bit
// compatibility with the two enclosures they replaced, and both are sound.
/// For the interval backends (generic_sin, generic_cos): tightest widening, every argument below
/// 2^50 bounded, a point interval searched for extrema like any other.
struct periodic_generic {
    using widening = ulps_widening;
    // Beyond 2^50 the loop counter k would stop being exact (|x|/π near 2^53 made `k += 1` a
    // no-op and the loop never ended); there the whole range is the answer.
    static constexpr double huge = 0x1p50;
    static constexpr bool points_direct = false;
};
/// For batched evaluation in hot loops (orientation/certify.hpp): cheap widening, the whole
/// range beyond 1e9, and a point interval answered by its widened libm value alone (it encloses
/// the point's image, extremum or not; near ±1 the widening reaches ±1 already).
struct periodic_batched {
    using widening = scaled_widening;
    static constexpr double huge = 1e9;
    static constexpr bool points_direct = true;
};

/// Whether periodic_bounds_nearest answers [l, u] with the whole range [−1, 1]: an argument not
/// below `huge` in magnitude (or NaN), or an interval about a period wide.
inline bool periodic_whole_range(double l, double u, double huge) noexcept {
    return !(std::abs(l) < huge && std::abs(u) < huge) || u - l >= 2.0 * std::numbers::pi - 1e-6;
}

/// THE sin/cos enclosure. Bounds of { f(x) : x ∈ [l, u] } for f = sin (phase π/2) or cos
/// (phase 0), whose extrema are at phase + kπ with value (−1)^k, from fl = f(l) and fu = f(u)
/// computed by libm in round-to-nearest. Call inside a `round_to_nearest_scope`: it opens none,
/// so that a caller can hold one for a whole batch (switching the mode costs more than sin and
/// cos together).
///
/// Method: the endpoint values widened outward (Policy::widening), plus every extremum the
/// interval *possibly* contains. Whether phase + k·π lies in [l, u] is decided against its
/// double approximation with a tolerance larger than its error, so an extremum is never missed;
/// including one that is not there only widens the result.
template <class Policy>
double_bounds periodic_bounds_nearest(double l, double u, double fl, double fu, double phase) {
    if (periodic_whole_range(l, u, Policy::huge)) return {-1.0, 1.0};
    using W = typename Policy::widening;
    double lo = W::down(std::min(fl, fu)), hi = W::up(std::max(fl, fu));
    if constexpr (Policy::points_direct) {
        if (l == u) return {std::max(lo, -1.0), std::min(hi, 1.0)};
    }
    constexpr double pi = std::numbers::pi;
    const double k0 = std::floor((l - phase) / pi) - 1.0;
    const double k1 = std::ceil((u - phase) / pi) + 1.0;
    for (double k = k0; k <= k1; k += 1.0) {
        const double t = phase + k * pi;
        const double tol = 8.0 * std::numeric_limits<double>::epsilon() * (std::abs(t) + pi);
        if (t + tol < l || t - tol > u) continue;
        const double value = std::fmod(std::abs(k), 2.0) == 0.0 ? 1.0 : -1.0;
        lo = std::min(lo, value);
        hi = std::max(hi, value);
    }
    return {std::max(lo, -1.0), std::min(hi, 1.0)};
}

// The interval form for a backend: f evaluated at the bounds in its own nearest scope.
template <class I, class F>
I periodic_enclosure(const I& x, F f, double phase) {
    if (is_empty(x)) return interval_traits<I>::empty();
    const double l = lower(x), u = upper(x);
    // Tested before the scope (in the caller's mode, as periodic_bounds_nearest tests it again
    // under nearest) so that a whole-range argument costs no libm call.
    if (periodic_whole_range(l, u, periodic_generic::huge)) return I(-1.0, 1.0);
    double_bounds b;
    {
        const round_to_nearest_scope nearest{};
        b = periodic_bounds_nearest<periodic_generic>(l, u, f(l), f(u), phase);
    }
    return I(b.lo, b.hi);
}

template <class I>
I generic_cos(const I& x) {
    return periodic_enclosure(x, [](double v) { return std::cos(v); }, 0.0);
}

template <class I>
I generic_sin(const I& x) {
    return periodic_enclosure(x, [](double v) { return std::sin(v); }, std::numbers::pi / 2);
}

template <class I>
I generic_acos(const I& x) {
    if (is_empty(x) || upper(x) < -1.0 || lower(x) > 1.0) return interval_traits<I>::empty();
    const double pi_hi = std::nextafter(std::numbers::pi, 4.0);
    const round_to_nearest_scope nearest{};
    const double lo = ulps_down(std::acos(std::min(upper(x), 1.0)));
    const double hi = ulps_up(std::acos(std::max(lower(x), -1.0)));
    return I(std::max(lo, 0.0), std::min(hi, pi_hi));
}

template <class I>
I generic_atan(const I& x) {
    if (is_empty(x)) return interval_traits<I>::empty();
    const double half_pi_hi = std::nextafter(std::numbers::pi / 2, 4.0);
    const round_to_nearest_scope nearest{};
    const double lo = ulps_down(std::atan(lower(x)));
    const double hi = ulps_up(std::atan(upper(x)));
    return I(std::max(lo, -half_pi_hi), std::min(hi, half_pi_hi));
}

// x^n for a point interval by squaring; every product is outward rounded by the backend.
template <class I>
I point_pow(double v, unsigned n) {
    I result(1.0), base(v);
    while (n) {
        if (n & 1u) result = result * base;
        n >>= 1u;
        if (n) base = base * base;
    }
    return result;
}

/// Integer power: odd powers are increasing, even powers increasing in |x|, so the bounds
/// come from enclosures of the endpoint powers.
template <class I>
I generic_pow(const I& x, int n) {
    if (is_empty(x)) return x;
    if (n == 0) return I(1.0);
    if (n == std::numeric_limits<int>::min()) return sqr(generic_pow(x, n / 2));  // -n overflows
    if (n < 0) return I(1.0) / generic_pow(x, -n);
    const auto un = static_cast<unsigned>(n);
    if (un % 2u == 1u) return I(lower(point_pow<I>(lower(x), un)), upper(point_pow<I>(upper(x), un)));
    const double l = lower(x), u = upper(x);
    const double amin = (l <= 0.0 && u >= 0.0) ? 0.0 : std::min(std::abs(l), std::abs(u));
    const double amax = std::max(std::abs(l), std::abs(u));
    return I(lower(point_pow<I>(amin, un)), upper(point_pow<I>(amax, un)));
}

}  // namespace certipose::detail
