// certipose/pose/axis_tolerance.hpp — an orientation box in a fitter's terms: how far the optical
// axis may tilt (a cone around the nominal axis) and how far the camera may roll about it, such
// that every such orientation lies inside the box.
//
// Why: a ±w interval on φ is not a ±w tilt. The optical axis R·ẑ has polar angle γ and azimuth φ
// about world z, so across φ it moves by only w·sin γ, and β is the azimuth of world z seen from
// the camera (the roll). A fitter needs the reverse statement: "tilt the axis by at most c, roll
// by at most ρ, and every pose is still certified". The bounds below are spherical geometry, not
// a linearisation:
//   * a rotation R = R₀·S·T (T about the optical axis by |τ| ≤ ρ, S a swing: the optical axis of
//     R₀·S is within c of R₀'s) has its optical axis within c of the nominal one, so
//     |γ − γ₀| ≤ c, and its azimuth |φ − φ₀| ≤ asin(sin c / sin γ₀) (tangent from the pole to the
//     small circle of radius c) when c < min(γ₀, π − γ₀);
//   * world z seen from the camera, Rᵀ·ẑ = (sin γ sin β, sin γ cos β, cos γ), is moved by Sᵀ by at
//     most c and turned by Tᵀ about the camera z by exactly τ: |β − β₀| ≤ ρ + asin(sin c / sin γ₀).
// A rotation by angle θ in total (any axis, on either side of R₀) has swing ≤ θ and twist ≤ θ,
// which turns a rotation-vector tolerance (ROS/MoveIt) into (c, ρ) = (θ, θ).
// Everything is plain double; every bound is shrunk (inner) or widened (enclosure) by `margin`,
// far above the few-ulp error of these expressions, so the statements hold despite rounding.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace certipose {

/// Orientation bounds as [lower, upper] per ZXZ angle (φ, γ, β), radians.
using zxz_bounds = std::array<std::array<double, 2>, 3>;

/// A fitter's orientation tolerance around a nominal orientation: the optical axis within a cone
/// of half-angle `cone` around the nominal axis, and the roll about the axis within ±`roll`.
struct axis_tolerance {
    double cone = 0;  ///< radians
    double roll = 0;  ///< radians
};

namespace detail::axis_tol {
/// Absolute slack (radians) absorbing the rounding of the closed forms below.
inline constexpr double margin = 1e-9;

/// Largest azimuth change of a direction at polar angle γ₀ moved by at most c on the sphere;
/// +inf when the cap of radius c reaches a pole (then every azimuth is possible).
inline double azimuth_spread(double c, double gamma0) {
    const double s0 = std::sin(gamma0);
    if (c >= std::min(gamma0, std::numbers::pi - gamma0)) return INFINITY;
    return std::asin(std::min(1.0, std::sin(c) / s0));
}
}  // namespace detail::axis_tol

/// The ZXZ box that encloses every orientation within `t` of the nominal angles `nominal` (φ₀, γ₀,
/// β₀): the set R₀·S·T of the header comment, widened by the margin. Unbounded (±inf) in φ and β
/// when the cone reaches world ±z.
inline zxz_bounds zxz_enclosure(const std::array<double, 3>& nominal, axis_tolerance t) {
    using namespace detail::axis_tol;
    const double dphi = azimuth_spread(t.cone, nominal[1]);
    return {{{nominal[0] - dphi - margin, nominal[0] + dphi + margin},
             {nominal[1] - t.cone - margin, nominal[1] + t.cone + margin},
             {nominal[2] - t.roll - dphi - margin, nominal[2] + t.roll + dphi + margin}}};
}

/// The nominal orientation of a box: its centre.
inline std::array<double, 3> zxz_centre(const zxz_bounds& b) {
    return {(b[0][0] + b[0][1]) / 2, (b[1][0] + b[1][1]) / 2, (b[2][0] + b[2][1]) / 2};
}

/// A fitter's tolerance that `box` certifies around its centre: every orientation with the optical
/// axis within `cone` of the nominal one and the roll within ±`roll` lies in `box`. The cone is
/// chosen first (as wide as γ, φ and half of β's room allow), the roll takes the rest of β's room.
/// Zero when the box is too thin or its centre too close to the ZXZ gimbal lock (γ₀ = 0 or π).
inline axis_tolerance certified_axis_tolerance(const zxz_bounds& box) {
    using namespace detail::axis_tol;
    const auto c0 = zxz_centre(box);
    double half[3];
    for (int i = 0; i < 3; ++i) half[i] = std::min(c0[i] - box[i][0], box[i][1] - c0[i]) - 2 * margin;
    const double s0 = std::sin(c0[1]);
    if (half[0] <= 0 || half[1] <= 0 || half[2] <= 0 || !(s0 > 0)) return {};
    // c ≤ γ's room; azimuth_spread(c) ≤ φ's room and ≤ half of β's room; c below the pole.
    const double room = std::min({half[0], half[2] / 2, std::numbers::pi / 2});
    double cone = std::min({half[1], std::asin(std::min(1.0, s0 * std::sin(room))),
                            std::min(c0[1], std::numbers::pi - c0[1]) / 2});
    cone = std::max(0.0, cone - margin);
    const double spread = azimuth_spread(cone, c0[1]);
    const double roll = std::max(0.0, half[2] - spread - margin);
    return {cone, roll};
}

/// The largest total rotation angle θ (any axis, applied on either side of the nominal
/// orientation) whose every rotation lies in `box`: (cone, roll) = (θ, θ) fits. A rotation-vector
/// tolerance of θ/√3 per axis (MoveIt's ROTATION_VECTOR parameterisation) is then inside.
inline double certified_rotation_angle(const zxz_bounds& box) {
    const auto c0 = zxz_centre(box);
    const auto fits = [&](double theta) {
        const auto e = zxz_enclosure(c0, {theta, theta});
        for (int i = 0; i < 3; ++i)
            if (!(e[i][0] >= box[i][0] && e[i][1] <= box[i][1])) return false;
        return true;
    };
    if (!fits(0)) return 0;
    double lo = 0, hi = std::numbers::pi / 2;
    for (int k = 0; k < 60; ++k) {
        const double mid = (lo + hi) / 2;
        (fits(mid) ? lo : hi) = mid;
    }
    return lo;  // fits(lo) was checked: the enclosure of (lo, lo) lies in the box
}

}  // namespace certipose
