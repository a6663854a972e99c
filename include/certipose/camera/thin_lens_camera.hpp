// certipose/camera/thin_lens_camera.hpp — the paper's camera: a thin lens with depth of field.
//
// `thin_lens_camera` is the default CameraModel (paper §4, docs/camera.md). Built from a
// `thin_lens_parameters` aggregate (designated initialisers; metres and pixels), it gives K, the
// FOV half-angles, the thin-lens quantities of paper Eqs. 1–7 (aperture diameter, image distance,
// blur circle, blur angle) and the in-focus distance range [d_min, d_max]: the object distances l
// whose blur circle on the sensor is at most `max_blur_circle`. Those are the classical near/far
// depth-of-field limits with hyperfocal distance H = f²/(N·b_max) + f. Because the solver
// certifies pose boxes against [d_min, d_max], the range is rounded inward: it is a subset of the
// exact range for the given double parameters. Every impossible parameter throws
// certipose::invalid_argument naming the field.
#pragma once

#include "certipose/detail/format.hpp"
#include "certipose/camera/camera_model.hpp"
#include "certipose/error.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

namespace certipose {

/// Parameters of a thin-lens camera. Lengths in metres, image size and principal point in
/// pixels. Fields left out of a designated initialiser are 0 and are rejected, except the
/// principal point (default: image centre), skew (0) and aspect (1, square pixels).
struct thin_lens_parameters {
    double focal_length = 0.0;     ///< f, metres
    double f_stop = 0.0;           ///< N = f / aperture diameter (paper Eq. 3)
    double focus_distance = 0.0;   ///< d_focus = s, object distance in perfect focus, metres (> f)
    double max_blur_circle = 0.0;  ///< b_max, largest acceptable blur circle on the sensor, metres
    double pixel_pitch = 0.0;      ///< metres per pixel on the sensor (width of a pixel)
    double width_px = 0.0;         ///< image width w, pixels
    double height_px = 0.0;        ///< image height h, pixels
    std::optional<Eigen::Vector2d> principal_point_px{};  ///< (c_x, c_y); default (w/2, h/2)
    double skew = 0.0;             ///< s in K
    double aspect = 1.0;           ///< δ = pixel height / pixel width
};

class thin_lens_camera : public detail::camera::sensor<thin_lens_camera> {
    using sensor = detail::camera::sensor<thin_lens_camera>;

public:
    explicit thin_lens_camera(const thin_lens_parameters& p)
        : sensor("thin_lens_camera", p),
          f_stop_(detail::camera::require_positive_finite("thin_lens_camera", "f_stop", p.f_stop)),
          focus_distance_(p.focus_distance),
          max_blur_circle_(detail::camera::require_positive_finite(
              "thin_lens_camera", "max_blur_circle", p.max_blur_circle)) {
        const double f = focal_length();
        // Only objects beyond f form a real image (Eq. 2); focus at infinity is not supported
        // (its near limit would be H - f), so the focus distance must be finite too.
        if (!(focus_distance_ > f) || !std::isfinite(focus_distance_))
            detail::camera::fail("thin_lens_camera", "focus_distance",
                                 "finite and greater than focal_length (" +
                                     detail::format_double(f) + ")",
                                 focus_distance_);
        aperture_diameter_ = f / f_stop_;  // Eq. 3
        hyperfocal_ = f * f / (f_stop_ * max_blur_circle_) + f;
        range_ = in_focus_range();
    }

    // intrinsics(), width_px(), height_px(), fov_half_angles(), focal_length() and the other
    // sensor accessors are inherited from detail::camera::sensor.

    /// In-focus object distances [D_n, D_f], rounded inward (see in_focus_range).
    certipose::distance_range distance_range() const noexcept { return range_; }
    using sensor::distance_range;  // (r): capped for a resolution requirement

    // ---- thin-lens parameters ------------------------------------------------------------
    double f_stop() const noexcept { return f_stop_; }
    double focus_distance() const noexcept { return focus_distance_; }
    double max_blur_circle() const noexcept { return max_blur_circle_; }

    // ---- thin-lens quantities (round-to-nearest point values, not certified) ---------------
    /// a_diam = f / f_stop (paper Eq. 3).
    double aperture_diameter() const noexcept { return aperture_diameter_; }
    /// H = f² / (N · b_max) + f: focused at H, everything from H/2 to infinity is acceptably sharp.
    double hyperfocal_distance() const noexcept { return hyperfocal_; }

    /// l' = f·l / (l − f), where an object at distance l comes to focus behind the lens
    /// (paper Eq. 2). Needs l > f (a real image); l = +inf gives f.
    double image_distance(double object_distance) const {
        const double f = focal_length();
        if (!(object_distance > f))
            detail::camera::fail("thin_lens_camera::image_distance", "object_distance",
                                 "greater than focal_length", object_distance);
        if (std::isinf(object_distance)) return f;
        return f * object_distance / (object_distance - f);
    }
    /// d'_focus = f·d_focus / (d_focus − f): lens-to-sensor distance (paper Eq. 4).
    double focus_image_distance() const { return image_distance(focus_distance_); }

    /// Diameter (metres, on the sensor) of the blur circle of a point at object distance l:
    /// c = a·|l' − s'| / l' (paper Eq. 5). Substituting Eq. 2 for l' and s' gives
    /// (l' − s') / l' = f·(s − l) / (l·(s − f)), so c = a · |l − s| / l · f / (s − f), which also
    /// holds for l <= f (virtual image: the ray cone still meets the sensor in that circle).
    double blur_circle(double object_distance) const {
        check_object_distance("blur_circle", object_distance);
        const double f = focal_length(), s = focus_distance_;
        if (std::isinf(object_distance)) return aperture_diameter_ * f / (s - f);
        return aperture_diameter_ * (std::abs(object_distance - s) / object_distance) *
               (f / (s - f));
    }

    /// θ_blur = a · |1/d_focus − 1/l| (paper Eq. 7, small-angle form of Eq. 6); equals
    /// blur_circle(l) / focus_image_distance().
    double blur_angle(double object_distance) const {
        check_object_distance("blur_angle", object_distance);
        return aperture_diameter_ * std::abs(1.0 / focus_distance_ - 1.0 / object_distance);
    }

private:
    static void check_object_distance(const char* who, double l) {
        if (!(l > 0.0))
            detail::camera::fail(std::string("thin_lens_camera::") + who, "object_distance",
                                 "positive", l);
    }

    // Why these formulas. Write s = focus distance, f = focal length, N = f-stop,
    // b = max_blur_circle, a = f/N, and q = H − f = f²/(N b). The blur circle (see blur_circle)
    // is c(l) = a f |l − s| / (l (s − f)) = (f²/N) |l − s| / (l (s − f)); c(l) <= b  <=>
    // |l − s| / l <= k with k = b N (s − f) / f² = (s − f) / q. c decreases on (0, s] and
    // increases on [s, ∞), so the in-focus set is an interval:
    //   near (l <= s): (s − l)/l = k  =>  l = s / (1 + k) = s (H − f) / (H + s − 2f) = D_n
    //   far  (l >= s): (l − s)/l = k  =>  l = s / (1 − k) = s (H − f) / (H − s)     = D_f,
    // and for k >= 1 (s >= H) c never exceeds b beyond s: D_f = +inf. These are the classical
    // hyperfocal near/far limits (docs/camera.md); tests/core/camera.cpp checks c(D_n) = c(D_f) = b.
    //
    // Why the nudges. The solver certifies ||p − q|| ∈ [d_min, d_max], so d_min must not be
    // below D_n and d_max not above D_f, or a box could be called VALID while a pose in it sees
    // the facet out of focus. Round-to-nearest can land on either side of the exact value, so
    // every operation is followed by one nextafter step in the direction that keeps a bound
    // (detail::camera::up/down): the exact result of an IEEE operation lies within one float of
    // the computed one in any rounding mode. We evaluate s / (1 ± k) with k bounded from the
    // side that moves each limit inward. The cost is a few ulps (~1e-15 relative) of range.
    // The double parameters are taken as exact; 0.012 typed by a user is already rounded.
    certipose::distance_range in_focus_range() const {
        using detail::camera::down;
        using detail::camera::up;
        const double f = focal_length(), s = focus_distance_, n = f_stop_, b = max_blur_circle_;
        const double q_lo = down(down(f * f) / up(n * b));
        const double q_hi = up(up(f * f) / down(n * b));
        if (!(q_lo > 0.0) || !std::isfinite(q_hi))
            detail::camera::fail("thin_lens_camera", "focal_length",
                                 "such that focal_length^2 / (f_stop * max_blur_circle) is a "
                                 "positive finite double",
                                 f);
        // k grows with the tolerated blur, and both limits move inward as k shrinks:
        // D_n = s / (1 + k) grows and D_f = s / (1 − k) shrinks. So one LOWER bound of k
        // serves both. s > f, so s − f > 0 and k_lo >= 0.
        const double k_lo = std::max(0.0, down(down(s - f) / q_hi));

        const double near = up(s / down(1.0 + k_lo));  // >= exact D_n

        // If even an upper bound of 1 − k is <= 0, then k >= 1 exactly: s >= H and D_f = +inf.
        const double one_minus_k_hi = up(1.0 - k_lo);
        const double far = one_minus_k_hi > 0.0 ? down(s / one_minus_k_hi)  // <= exact D_f
                                                : std::numeric_limits<double>::infinity();
        return {near, far};
    }

    double f_stop_, focus_distance_, max_blur_circle_;
    double aperture_diameter_ = 0.0, hyperfocal_ = 0.0;
    certipose::distance_range range_{};
};

}  // namespace certipose
