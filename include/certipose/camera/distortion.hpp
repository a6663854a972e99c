// certipose/camera/distortion.hpp — lens distortion (Brown–Conrady, OpenCV's model) and the
// region of the image it lets the solver certify.
//
// A real lens bends rays: a point at normalized coordinates (x, y) = (X/Z, Y/Z) is imaged at
// (x_d, y_d) = distort(x, y) and then at the pixel K·(x_d, y_d, 1). The solver's field-of-view
// proof (orientation/certify.hpp) works with a pinhole frustum — linear half-spaces in q — so a
// distorted camera is reduced to a pinhole one: `certified_image_rectangle` finds a rectangle of
// normalized coordinates around the principal ray and PROVES, by interval arithmetic over a cover
// of tiles, that every point of it is imaged inside the image minus a margin, and that the map
// has no fold there (the radial profile r·radial(r) increases and the Jacobian is positive), so
// that the rectangle is a region where the model describes the lens (strong barrel distortion
// maps far-off rays back into the image: the fold check keeps those out). `pinhole_image_of`
// turns the rectangle into the K, width and height of a pinhole whose frustum lies inside it.
// Only the final certification is rigorous; the search for the rectangle uses plain doubles.
#pragma once

#include "certipose/camera/camera_model.hpp"
#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"
#include "certipose/interval/boost_interval.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/interval/operations.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <span>
#include <string>

namespace certipose {

/// OpenCV's distortion model, coefficients in OpenCV's order (k1, k2, p1, p2, k3, k4, k5, k6):
/// radial polynomial k1..k3, tangential p1, p2, and the rational model's denominator k4..k6
/// (zero unless the calibration used CALIB_RATIONAL_MODEL). All zero is no distortion.
struct brown_conrady {
    double k1 = 0, k2 = 0, p1 = 0, p2 = 0, k3 = 0, k4 = 0, k5 = 0, k6 = 0;

    /// From OpenCV's coefficient vector: 4 (k1, k2, p1, p2), 5 (+ k3) or 8 (+ k4, k5, k6) values,
    /// each finite. Throws invalid_argument("distortion_coefficients") naming the count or the
    /// offending index and value.
    static brown_conrady from_opencv(std::span<const double> c) {
        if (c.size() != 4 && c.size() != 5 && c.size() != 8)
            throw invalid_argument("distortion_coefficients",
                                   "distortion_coefficients: expected 4, 5 or 8 coefficients (OpenCV order k1, k2, "
                                   "p1, p2[, k3[, k4, k5, k6]]), got " +
                                       std::to_string(c.size()));
        for (std::size_t i = 0; i < c.size(); ++i)
            if (!std::isfinite(c[i]))
                throw invalid_argument("distortion_coefficients", "distortion_coefficients[" + std::to_string(i) +
                                                                      "] must be finite, got " +
                                                                      detail::format_double(c[i]));
        std::array<double, 8> a{};
        std::copy(c.begin(), c.end(), a.begin());
        return {a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7]};
    }

    /// The 8 coefficients in OpenCV's order.
    std::array<double, 8> opencv() const noexcept { return {k1, k2, p1, p2, k3, k4, k5, k6}; }
    /// The rational model (a denominator) is in use.
    bool rational() const noexcept { return k4 != 0 || k5 != 0 || k6 != 0; }
    bool is_zero() const noexcept { return !rational() && k1 == 0 && k2 == 0 && p1 == 0 && p2 == 0 && k3 == 0; }
    /// How many coefficients describe it: 8 for the rational model, else 5.
    std::size_t count() const noexcept { return rational() ? 8 : 5; }

    friend bool operator==(const brown_conrady&, const brown_conrady&) = default;

    /// (x_d, y_d) of normalized coordinates (x, y), as OpenCV's projectPoints computes them.
    std::array<double, 2> distort(double x, double y) const noexcept {
        const double r2 = x * x + y * y;
        const double radial = (1 + r2 * (k1 + r2 * (k2 + r2 * k3))) / (1 + r2 * (k4 + r2 * (k5 + r2 * k6)));
        return {x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x),
                y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y};
    }

    /// An enclosure of distort over the box [x] × [y] (the caller holds a rounding_guard<I>).
    /// Where the rational denominator's enclosure is not positive the map may have a pole, so
    /// the answer is the whole plane.
    template <Interval I>
    std::array<I, 2> distort(const I& x, const I& y) const {
        const I x2 = sqr(x), y2 = sqr(y), r2 = x2 + y2, xy = x * y;
        const I den = ((k6 * r2 + k5) * r2 + k4) * r2 + 1.0;
        if (!certainly_greater(den, 0.0)) return {interval_traits<I>::whole(), interval_traits<I>::whole()};
        const I radial = (((k3 * r2 + k2) * r2 + k1) * r2 + 1.0) / den;
        return {x * radial + (2 * p1) * xy + p2 * (r2 + 2.0 * x2), y * radial + p1 * (r2 + 2.0 * y2) + (2 * p2) * xy};
    }
};

/// A rectangle [x_lo, x_hi] × [y_lo, y_hi] of normalized coordinates (x = X/Z, y = Y/Z).
struct normalized_rectangle {
    double x_lo, x_hi, y_lo, y_hi;
};

namespace detail::distortion {

/// The camera's pixel map u = fx·x_d + s·y_d + c_x, v = fy·y_d + c_y and the allowed pixels.
struct pixel_map {
    double fx, s, cx, fy, cy, width, height, margin;
    brown_conrady d;
};

/// Radial numerator N(t) and denominator D(t) of t = r², and their derivatives, in any scalar.
template <class T>
struct radial_terms {
    T n, dn, den, dden;
};
template <class T>
radial_terms<T> radial(const brown_conrady& d, const T& t) {
    // 3·k is not exact in doubles: multiply after the interval product (2·k is exact).
    return {((d.k3 * t + d.k2) * t + d.k1) * t + 1.0, (3.0 * (d.k3 * t) + 2 * d.k2) * t + d.k1,
            ((d.k6 * t + d.k5) * t + d.k4) * t + 1.0, (3.0 * (d.k6 * t) + 2 * d.k5) * t + d.k4};
}

/// The sign of d(r·radial(r))/dr at t = r² is that of N·D + 2t(N'·D − N·D') (D > 0 given).
template <class T>
T fold_margin(const radial_terms<T>& r, const T& t) {
    return r.n * r.den + 2.0 * t * (r.dn * r.den - r.n * r.dden);
}

/// The Jacobian of (x_d, y_d) is symmetric: [[a, b], [b, c]] with R = N/D, R' = dR/dt.
template <class T>
T jacobian(const brown_conrady& d, const T& x, const T& y, const T& x2, const T& y2, const T& xy,
           const T& R, const T& dR) {
    const T a = R + 2.0 * x2 * dR + (2 * d.p1) * y + 6.0 * (d.p2 * x);  // 6·p is not exact in doubles
    const T b = 2.0 * xy * dR + (2 * d.p1) * x + (2 * d.p2) * y;
    const T c = R + 2.0 * y2 * dR + 6.0 * (d.p1 * y) + (2 * d.p2) * x;
    return a * c - b * b;
}

/// Plain-double test of one point for the search (not a proof).
inline bool point_ok(const pixel_map& m, double x, double y) {
    const auto [xd, yd] = m.d.distort(x, y);
    const double u = m.fx * xd + m.s * yd + m.cx, v = m.fy * yd + m.cy;
    return u >= m.margin && u <= m.width - m.margin && v >= m.margin && v <= m.height - m.margin;
}

inline bool no_fold_at(const pixel_map& m, double x, double y) {
    const double t = x * x + y * y;
    const auto r = radial(m.d, t);
    if (!(r.den > 0)) return false;
    const double R = r.n / r.den, dR = (r.dn * r.den - r.n * r.dden) / (r.den * r.den);
    return fold_margin(r, t) > 0 && jacobian(m.d, x, y, x * x, y * y, x * y, R, dR) > 0;
}

/// The search's plain-double judgement of a rectangle: the boundary is imaged inside the image
/// (enough when there is no fold: the image of the rectangle is then bounded by the image of
/// its boundary) and no fold is seen on a grid.
inline bool plausible(const pixel_map& m, const normalized_rectangle& r) {
    constexpr int edge = 256, grid = 16;
    for (int i = 0; i <= edge; ++i) {
        const double a = static_cast<double>(i) / edge;
        const double x = r.x_lo + a * (r.x_hi - r.x_lo), y = r.y_lo + a * (r.y_hi - r.y_lo);
        if (!point_ok(m, x, r.y_lo) || !point_ok(m, x, r.y_hi) || !point_ok(m, r.x_lo, y) || !point_ok(m, r.x_hi, y))
            return false;
    }
    for (int i = 0; i <= grid; ++i)
        for (int j = 0; j <= grid; ++j)
            if (!no_fold_at(m, r.x_lo + (r.x_hi - r.x_lo) * i / grid, r.y_lo + (r.y_hi - r.y_lo) * j / grid))
                return false;
    // The radial profile along the longest ray (the rectangle holds every radius up to it).
    const double t_max = std::max(std::max(r.x_lo * r.x_lo, r.x_hi * r.x_hi) + std::max(r.y_lo * r.y_lo, r.y_hi * r.y_hi), 0.0);
    for (int i = 0; i <= 64; ++i) {
        const double t = t_max * i / 64;
        const auto rt = radial(m.d, t);
        if (!(rt.den > 0) || !(fold_margin(rt, t) > 0)) return false;
    }
    return true;
}

/// Interval proof for one tile: every point images inside [margin, w − margin] × [margin,
/// h − margin], the denominator is positive, and there is no fold (see the header comment).
inline bool tile_certified(const pixel_map& m, double x_lo, double x_hi, double y_lo, double y_hi) {
    using I = boost_interval;
    const I x(x_lo, x_hi), y(y_lo, y_hi);
    const I x2 = sqr(x), y2 = sqr(y), t = x2 + y2, xy = x * y;
    const radial_terms<I> r = radial(m.d, t);
    if (!certainly_greater(r.den, 0.0)) return false;
    const I R = r.n / r.den;
    const I xd = x * R + (2 * m.d.p1) * xy + m.d.p2 * (t + 2.0 * x2);
    const I yd = y * R + m.d.p1 * (t + 2.0 * y2) + (2 * m.d.p2) * xy;
    const I u = m.fx * xd + m.s * yd + m.cx, v = m.fy * yd + m.cy;
    const double u_max = lower(I(m.width) - I(m.margin)), v_max = lower(I(m.height) - I(m.margin));
    if (!certainly_geq(u, m.margin) || !certainly_leq(u, u_max) || !certainly_geq(v, m.margin) ||
        !certainly_leq(v, v_max))
        return false;
    if (!certainly_greater(fold_margin(r, t), 0.0)) return false;
    const I dR = (r.dn * r.den - r.n * r.dden) / sqr(r.den);
    return certainly_greater(jacobian(m.d, x, y, x2, y2, xy, R, dR), 0.0);
}

/// A tile, split into four while undecided (the halves share their split line: a closed cover).
inline bool certify_tile(const pixel_map& m, double x_lo, double x_hi, double y_lo, double y_hi, int depth,
                         long& budget) {
    if (--budget < 0) return false;
    if (tile_certified(m, x_lo, x_hi, y_lo, y_hi)) return true;
    if (depth == 0) return false;
    const double xm = 0.5 * x_lo + 0.5 * x_hi, ym = 0.5 * y_lo + 0.5 * y_hi;
    if (!(x_lo < xm && xm < x_hi && y_lo < ym && ym < y_hi)) return false;
    if (!point_ok(m, xm, ym)) return false;  // a plain counterexample: no proof will come
    return certify_tile(m, x_lo, xm, y_lo, ym, depth - 1, budget) && certify_tile(m, xm, x_hi, y_lo, ym, depth - 1, budget) &&
           certify_tile(m, x_lo, xm, ym, y_hi, depth - 1, budget) && certify_tile(m, xm, x_hi, ym, y_hi, depth - 1, budget);
}

/// The rigorous step: a 32 × 32 grid of tiles covering r exactly (first and last split points
/// are r's bounds), each proven by tile_certified, subdivided up to 10 times where undecided.
inline bool certify(const pixel_map& m, const normalized_rectangle& r) {
    constexpr int n = 32;
    const rounding_guard<boost_interval> guard{};
    std::array<double, n + 1> xs{}, ys{};
    for (int i = 0; i <= n; ++i) {
        xs[static_cast<std::size_t>(i)] = i == n ? r.x_hi : r.x_lo + (r.x_hi - r.x_lo) * i / n;
        ys[static_cast<std::size_t>(i)] = i == n ? r.y_hi : r.y_lo + (r.y_hi - r.y_lo) * i / n;
    }
    for (std::size_t i = 0; i < n; ++i)
        if (!(xs[i] < xs[i + 1]) || !(ys[i] < ys[i + 1])) return false;
    long budget = 400000;
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j)
            if (!certify_tile(m, xs[i], xs[i + 1], ys[j], ys[j + 1], 10, budget)) return false;
    return true;
}

inline normalized_rectangle scaled(const normalized_rectangle& r, double lo_x, double hi_x, double lo_y, double hi_y) {
    return {r.x_lo * lo_x, r.x_hi * hi_x, r.y_lo * lo_y, r.y_hi * hi_y};
}

[[noreturn]] inline void fail_k(const std::string& what) {
    throw invalid_argument("K", "certified_image_rectangle: " + what);
}

}  // namespace detail::distortion

/// The largest rectangle of normalized coordinates found around the principal ray (0, 0) whose
/// every point is PROVEN to be imaged, through the distortion `d` and K (third row (0, 0, 1),
/// K(1, 0) = 0, fx, fy > 0), inside [margin, w − margin] × [margin, h − margin], with no fold of
/// the distortion over it (see the header comment). Without distortion it is the pinhole image
/// minus the margin, up to a relative 1e-13. The search scales the margin-reduced pinhole
/// rectangle by a common factor in (0, 3] (bisection), then grows each side alone; the result is
/// then certified, and shrunk by a growing factor until it is. Throws invalid_argument naming
/// "image_margin_px" (negative, NaN, or no image left around the principal point), "K",
/// "width_px"/"height_px", or "distortion_coefficients" when no rectangle around the principal
/// point can be certified.
inline normalized_rectangle certified_image_rectangle(const Eigen::Matrix3d& K, double width_px, double height_px,
                                                      const brown_conrady& d, double margin_px = 0.0) {
    using namespace detail::distortion;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            if (!std::isfinite(K(r, c))) fail_k("K must be finite");
    if (!(K(2, 0) == 0.0 && K(2, 1) == 0.0 && K(2, 2) == 1.0)) fail_k("the third row of K must be (0, 0, 1)");
    if (K(1, 0) != 0.0) fail_k("K(1,0) must be 0, got " + detail::format_double(K(1, 0)));
    if (!(K(0, 0) > 0.0) || !(K(1, 1) > 0.0)) fail_k("K(0,0) and K(1,1) must be positive");
    if (!(width_px > 0.0) || !std::isfinite(width_px))
        throw invalid_argument("width_px", "certified_image_rectangle: width_px must be positive and finite, got " +
                                               detail::format_double(width_px));
    if (!(height_px > 0.0) || !std::isfinite(height_px))
        throw invalid_argument("height_px", "certified_image_rectangle: height_px must be positive and finite, got " +
                                                detail::format_double(height_px));
    if (!(margin_px >= 0.0) || !std::isfinite(margin_px))
        throw invalid_argument("image_margin_px", "image_margin_px must be finite and >= 0, got " +
                                                      detail::format_double(margin_px));
    const pixel_map m{K(0, 0), K(0, 1), K(0, 2), K(1, 1), K(1, 2), width_px, height_px, margin_px, d};
    // The pinhole rectangle: v = fy·y + cy in [m, h − m]; u = fx·x + s·y + cx in [m, w − m] for
    // every y of that range.
    const double y_lo = (m.margin - m.cy) / m.fy, y_hi = (m.height - m.margin - m.cy) / m.fy;
    const double s_lo = std::min(m.s * y_lo, m.s * y_hi), s_hi = std::max(m.s * y_lo, m.s * y_hi);
    const double x_lo = (m.margin - m.cx - s_lo) / m.fx, x_hi = (m.width - m.margin - m.cx - s_hi) / m.fx;
    if (!(x_lo < 0.0 && 0.0 < x_hi && y_lo < 0.0 && 0.0 < y_hi))
        throw invalid_argument("image_margin_px", "image_margin_px: " + detail::format_double(margin_px) +
                                                      " leaves no image around the principal point");
    const normalized_rectangle base{x_lo, x_hi, y_lo, y_hi};
    normalized_rectangle best = base;
    double eps = 1e-13;
    if (!d.is_zero()) {
        constexpr double s_max = 3.0;
        double lo = 1e-4, hi = s_max;
        if (!plausible(m, scaled(base, lo, lo, lo, lo)))
            throw invalid_argument("distortion_coefficients",
                                   "distortion_coefficients: no image rectangle around the principal point can be "
                                   "certified (the distorted image leaves the sensor, or folds, right next to it)");
        if (plausible(m, scaled(base, hi, hi, hi, hi))) {
            lo = hi;
        } else {
            for (int it = 0; it < 50; ++it) {
                const double mid = 0.5 * (lo + hi);
                (plausible(m, scaled(base, mid, mid, mid, mid)) ? lo : hi) = mid;
            }
        }
        // Grow each side alone (an off-centre principal point, or a distortion stronger on one
        // side, leaves room that the common factor did not use).
        std::array<double, 4> f{lo, lo, lo, lo};
        for (std::size_t side = 0; side < 4; ++side) {
            double a = f[side], b = s_max;
            std::array<double, 4> g = f;
            g[side] = b;
            if (plausible(m, scaled(base, g[0], g[1], g[2], g[3]))) {
                f[side] = b;
                continue;
            }
            for (int it = 0; it < 40; ++it) {
                g[side] = 0.5 * (a + b);
                (plausible(m, scaled(base, g[0], g[1], g[2], g[3])) ? a : b) = g[side];
            }
            f[side] = a;
        }
        best = scaled(base, f[0], f[1], f[2], f[3]);
        eps = 1e-6;
    }
    // The search ends on the image's edge (or a fold), where no enclosure can prove anything;
    // shrinking every side toward the principal point gives the proof room.
    for (; eps < 0.5; eps *= 4) {
        const double k = 1.0 - eps;
        const normalized_rectangle r = scaled(best, k, k, k, k);
        if (certify(m, r)) return r;
    }
    throw invalid_argument("distortion_coefficients",
                           "distortion_coefficients: no image rectangle around the principal point can be certified");
}

/// The pinhole image whose division-free frustum (0 ≤ (Kq)_x ≤ w·q_z, 0 ≤ (Kq)_y ≤ h·q_z) lies
/// inside the cone of `r`: K = [[1, 0, −x_lo], [0, 1, −y_lo], [0, 0, 1]], so (Kq)_x = q_x −
/// x_lo·q_z and the frustum is x_lo ≤ x ≤ x_lo + w (x = q_x/q_z), exactly for these doubles —
/// fov_frustum takes K's entries as exact, and negation is exact. The width must satisfy
/// x_lo + w ≤ x_hi in real arithmetic: the computed difference fl(x_hi − x_lo) is one of the two
/// doubles around the exact one in any rounding mode, so the double below it is ≤ the exact
/// difference. Likewise in y.
inline pinhole_image pinhole_image_of(const normalized_rectangle& r) {
    pinhole_image image;
    image.K << 1.0, 0.0, -r.x_lo, 0.0, 1.0, -r.y_lo, 0.0, 0.0, 1.0;
    image.width_px = detail::camera::down(r.x_hi - r.x_lo);
    image.height_px = detail::camera::down(r.y_hi - r.y_lo);
    return image;
}

/// Half-angles of the largest axis-symmetric pyramid inside the rectangle (for aiming, like a
/// camera's fov_half_angles; not a certificate).
inline certipose::fov_half_angles fov_half_angles_of(const normalized_rectangle& r) {
    return {std::atan(detail::camera::down(std::min(-r.x_lo, r.x_hi))),
            std::atan(detail::camera::down(std::min(-r.y_lo, r.y_hi)))};
}

}  // namespace certipose
