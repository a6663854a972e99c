// certipose/orientation/detail/spherical.hpp — small private helpers of the orientation module:
// outward-rounded angle constants and batched libm enclosures (one rounding-mode switch for
// many calls). Not for users.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <utility>

#include "certipose/interval/concept.hpp"
#include "certipose/interval/detail/fenv.hpp"
#include "certipose/interval/detail/transcendental.hpp"
#include "certipose/interval/operations.hpp"

namespace certipose::detail::orientation {

// The double nearest π is below π; its successor is above.
inline constexpr double pi_lo = std::numbers::pi;
inline const double pi_hi = std::nextafter(std::numbers::pi, 4.0);
inline constexpr double half_pi_lo = std::numbers::pi / 2;  // exact halving: still below π/2
inline const double half_pi_hi = std::nextafter(std::numbers::pi / 2, 4.0);

/// Bounds of a real function over an interval, as doubles.
using bounds = certipose::detail::double_bounds;

// Outward widening of a libm result by more than `transcendental_ulps` (2) ulps, cheaper than
// nextafter (interval/detail/transcendental.hpp); call inside a nearest scope. Results here are
// at most a few units in magnitude.
inline double widen_down(double x) noexcept { return scaled_widening::down(x); }
inline double widen_up(double x) noexcept { return scaled_widening::up(x); }

/// Enclosure of { f(x) : x ∈ [l, u] } for f = sin (phase π/2) or cos (phase 0) from the values
/// fl = f(l), fu = f(u) (libm, round-to-nearest): the enclosure of interval/detail/
/// transcendental.hpp in its batched form, which opens no rounding scope (the caller holds one
/// `round_to_nearest_scope` for a whole batch of evaluations), widens cheaply and answers a point
/// by its widened value (most calls of certify_fov are points, box centres, and the search for
/// extrema is most of their cost).
inline bounds periodic_bounds_from(double l, double u, double fl, double fu, double phase) {
    return periodic_bounds_nearest<periodic_batched>(l, u, fl, fu, phase);
}
inline bounds cos_bounds_nearest(double l, double u) {
    return periodic_bounds_from(l, u, std::cos(l), l == u ? std::cos(l) : std::cos(u), 0.0);
}
/// sin x and cos x (call inside a nearest scope): one libm sincos where there is one (glibc
/// computes both with the same code as sin and cos, to the same values), else both.
inline void sincos_nearest(double x, double& s, double& c) {
#if defined(__GLIBC__)
    ::sincos(x, &s, &c);
#else
    s = std::sin(x), c = std::cos(x);
#endif
}

/// Both enclosures of [l, u] from sin and cos at its bounds (call inside a nearest scope).
inline void sincos_bounds_from(double l, double u, double sl, double cl, double su, double cu, bounds& sine,
                               bounds& cosine) {
    sine = periodic_bounds_from(l, u, sl, su, std::numbers::pi / 2);
    cosine = periodic_bounds_from(l, u, cl, cu, 0.0);
}

/// sin and cos at the lower bound, upper bound and a midpoint of each of three angles, kept
/// with the abscissa they were computed at. A tiled proof asks fov_refuted and certify_fov about
/// one box, and each tile shares all but two of these abscissae with the box it was split from;
/// each asks `at` for what it needs, and only an abscissa not held already costs a libm call.
/// The values are the ones each evaluation would compute for itself (the same libm call on the
/// same double), so sharing them changes no verdict.
struct angle_trig {
    static constexpr double none = std::numeric_limits<double>::quiet_NaN();  // equals no abscissa
    std::array<std::array<double, 3>, 3> x{{{none, none, none}, {none, none, none}, {none, none, none}}}, s{}, c{};

    /// sin and cos of `value` for angle j, slot k (0: lower bound, 1: upper bound, 2: midpoint);
    /// inside a nearest scope.
    void at(std::size_t j, std::size_t k, double value, double& sine, double& cosine) {
        if (!(x[j][k] == value)) {
            sincos_nearest(value, s[j][k], c[j][k]);
            x[j][k] = value;
        }
        sine = s[j][k], cosine = c[j][k];
    }
};
/// acos is decreasing on [−1, 1]; arguments are clamped to it (call inside a nearest scope).
inline bounds acos_bounds_nearest(double l, double u) {
    const double lo = widen_down(std::acos(std::clamp(u, -1.0, 1.0)));
    const double hi = widen_up(std::acos(std::clamp(l, -1.0, 1.0)));
    return {std::max(lo, 0.0), std::min(hi, pi_hi)};
}
/// atan is increasing (call inside a nearest scope).
inline bounds atan_bounds_nearest(double l, double u) {
    return {widen_down(std::atan(l)), widen_up(std::atan(u))};
}

template <Interval I>
I to_interval(bounds b) {
    return I(b.lo, b.hi);
}

}  // namespace certipose::detail::orientation
