// certipose/camera/camera_model.hpp — what the solver needs to know about a camera.
//
// A camera model gives the intrinsic matrix K = [[f_px, s, c_x], [0, δ·f_px, c_y], [0, 0, 1]]
// (docs/conventions.md, paper §4), the image size in pixels, the field-of-view half-angles about the
// optical axis and the range [d_min, d_max] of object distances (metres) at which the part is
// imaged usably (in focus for a thin lens, user bounds for a pinhole). The solver certifies pose
// boxes against [d_min, d_max], so a model must return a range CONTAINED in the true one: erring
// inward only ever turns a VALID box into a BOUNDARY or discarded one, never the reverse.
// `capped_distance_range` adds the optional resolution requirement (metres on the part per
// pixel) for any model. The built-in models are `thin_lens_camera` and `pinhole_camera`.
#pragma once

#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <concepts>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

namespace certipose {

/// Half-angles (radians) of the largest pyramid about the optical axis, symmetric in the
/// camera's x and y directions, whose image lies inside the sensor. With a centred principal
/// point and no skew: horizontal = atan(w / (2 f_px)), vertical = atan(h / (2 δ f_px)).
struct fov_half_angles {
    double horizontal;
    double vertical;
};

/// Usable object distances in metres: every distance in [min, max] is usable. `max` may be
/// +infinity. `min > max` means no distance is usable (e.g. a resolution cap below `min`).
struct distance_range {
    double min;
    double max;

    bool empty() const noexcept { return !(min <= max); }
    bool contains(double l) const noexcept { return min <= l && l <= max; }
};

/// A camera the solver can place (the camera-model policy, docs/camera.md).
template <class C>
concept CameraModel = requires(const C& c) {
    { c.intrinsics() } -> std::convertible_to<Eigen::Matrix3d>;
    { c.width_px() } -> std::convertible_to<double>;
    { c.height_px() } -> std::convertible_to<double>;
    { c.fov_half_angles() } -> std::convertible_to<certipose::fov_half_angles>;
    { c.distance_range() } -> std::convertible_to<certipose::distance_range>;
};

/// The image the solver certifies the field of view against, as an ideal pinhole camera's: a
/// point q (camera coordinates) is in it when q_z > 0 and 0 ≤ (Kq)_x ≤ w·q_z, 0 ≤ (Kq)_y ≤ h·q_z
/// (docs/conventions.md, constraint 5). For a camera without lens distortion it is the camera's
/// own K and image size; a distorted camera gives a smaller pinhole image whose every ray is
/// proven to land inside the real image (camera/distortion.hpp).
struct pinhole_image {
    Eigen::Matrix3d K;
    double width_px;
    double height_px;
};

/// A camera model whose certified image differs from its intrinsics (lens distortion).
template <class C>
concept HasImageRegion = requires(const C& c) {
    { c.image_region() } -> std::convertible_to<pinhole_image>;
};

/// The image the solver certifies against: `c.image_region()` when the model has one, else the
/// model's own K, width and height. Every field-of-view proof (orientation/certify.hpp) and
/// every cull built on the image's angles reads the camera through this function, never through
/// intrinsics() directly, so that a distorted camera is certified against its proven region.
template <CameraModel C>
pinhole_image certified_image(const C& c) {
    if constexpr (HasImageRegion<C>)
        return c.image_region();
    else
        return {c.intrinsics(), c.width_px(), c.height_px()};
}

namespace detail::camera {

[[noreturn]] inline void fail(std::string_view who, std::string_view field, std::string_view rule,
                              double value) {
    throw invalid_argument(std::string(field), std::string(who) + ": " + std::string(field) +
                                                   " must be " + std::string(rule) + ", got " +
                                                   certipose::detail::format_double(value));
}

/// Finite and > 0. `!(v > 0)` also rejects NaN.
inline double require_positive_finite(std::string_view who, std::string_view field, double v) {
    if (!(v > 0.0) || !std::isfinite(v)) fail(who, field, "positive and finite", v);
    return v;
}

inline double require_finite(std::string_view who, std::string_view field, double v) {
    if (!std::isfinite(v)) fail(who, field, "finite", v);
    return v;
}

/// Floating-point neighbours. One step away from a computed value bounds the exact value: an
/// IEEE operation returns one of the two floats around the exact result in ANY rounding mode,
/// so the exact result lies between pred(r) and succ(r). Chaining one step per operation gives
/// rigorous bounds without touching the rounding mode (and without -frounding-math).
inline double up(double v) { return std::nextafter(v, std::numeric_limits<double>::infinity()); }
inline double down(double v) { return std::nextafter(v, -std::numeric_limits<double>::infinity()); }

/// The sensor half shared by every built-in model, as its public base (CRTP): validated
/// intrinsics, K, the FOV half-angles, their accessors, and `distance_range(r)` — the model's
/// own `distance_range()` capped for a resolution requirement. A model declares
/// `using sensor<Model>::distance_range;` next to its `distance_range()`, which would hide it.
/// `who` prefixes error messages ("thin_lens_camera: focal_length must be ...").
template <class Model>
class sensor {
public:
    /// From a parameter aggregate with the sensor fields (focal_length, pixel_pitch, width_px,
    /// height_px, principal_point_px, skew, aspect), e.g. thin_lens_parameters.
    template <class Parameters>
    sensor(std::string_view who, const Parameters& p)
        : sensor(who, p.focal_length, p.pixel_pitch, p.width_px, p.height_px, p.principal_point_px, p.skew,
                 p.aspect) {}

    sensor(std::string_view who, double focal_length, double pixel_pitch, double width_px,
           double height_px, const std::optional<Eigen::Vector2d>& principal_point_px,
           double skew, double aspect)
        : focal_length_(require_positive_finite(who, "focal_length", focal_length)),
          pixel_pitch_(require_positive_finite(who, "pixel_pitch", pixel_pitch)),
          width_px_(require_positive_finite(who, "width_px", width_px)),
          height_px_(require_positive_finite(who, "height_px", height_px)),
          skew_(require_finite(who, "skew", skew)),
          aspect_(require_positive_finite(who, "aspect", aspect)) {
        f_px_ = focal_length_ / pixel_pitch_;
        if (!(f_px_ > 0.0) || !std::isfinite(f_px_) || !std::isfinite(aspect_ * f_px_) ||
            !(aspect_ * f_px_ > 0.0))
            fail(who, "focal_length",
                 "such that focal_length / pixel_pitch (and times aspect) is a positive finite "
                 "double",
                 focal_length_);
        // The ideal principal point is the image centre (paper §4); a calibrated one must at
        // least lie strictly inside the image, or the optical axis never meets the sensor and
        // there is no field of view about it.
        principal_point_ = principal_point_px.value_or(Eigen::Vector2d(width_px_ / 2, height_px_ / 2));
        const double cx = principal_point_.x(), cy = principal_point_.y();
        if (!(cx > 0.0 && cx < width_px_))
            fail(who, "principal_point_px", "inside the image (0 < x < width_px)", cx);
        if (!(cy > 0.0 && cy < height_px_))
            fail(who, "principal_point_px", "inside the image (0 < y < height_px)", cy);

        k_ << f_px_, skew_, cx,
              0.0, aspect_ * f_px_, cy,
              0.0, 0.0, 1.0;

        // Largest pyramid |x/z| <= tan α_h, |y/z| <= tan α_v whose image is inside the sensor:
        // v = δ f_px y/z + c_y needs δ f_px tan α_v <= min(c_y, h - c_y); u = f_px x/z + s y/z +
        // c_x needs f_px tan α_h + |s| tan α_v <= min(c_x, w - c_x). Centred, no skew: DESIGN §2.
        const double tan_v = std::min(cy, height_px_ - cy) / (aspect_ * f_px_);
        const double tan_h = (std::min(cx, width_px_ - cx) - std::abs(skew_) * tan_v) / f_px_;
        if (!(tan_h > 0.0))
            fail(who, "skew", "small enough that the image keeps a horizontal field of view",
                 skew_);
        fov_ = {std::atan(tan_h), std::atan(tan_v)};
    }

    double focal_length() const noexcept { return focal_length_; }
    double pixel_pitch() const noexcept { return pixel_pitch_; }
    double focal_length_px() const noexcept { return f_px_; }
    double width_px() const noexcept { return width_px_; }
    double height_px() const noexcept { return height_px_; }
    const Eigen::Vector2d& principal_point_px() const noexcept { return principal_point_; }
    double skew() const noexcept { return skew_; }
    double aspect() const noexcept { return aspect_; }
    const Eigen::Matrix3d& intrinsics() const noexcept { return k_; }
    certipose::fov_half_angles fov_half_angles() const noexcept { return fov_; }

    /// The model's distance_range() capped at r · f_px for a resolution requirement of r metres
    /// per pixel (capped_distance_range, found by ADL: it is declared below).
    /// Throws invalid_argument("max_metres_per_pixel") for r <= 0 or NaN.
    certipose::distance_range distance_range(double max_metres_per_pixel) const {
        return capped_distance_range(static_cast<const Model&>(*this), max_metres_per_pixel);
    }

private:
    double focal_length_, pixel_pitch_, width_px_, height_px_, skew_, aspect_;
    double f_px_ = 0.0;
    Eigen::Vector2d principal_point_;
    Eigen::Matrix3d k_;
    certipose::fov_half_angles fov_{};
};

}  // namespace detail::camera

/// `c.distance_range()` with the optional resolution requirement applied: when
/// `max_metres_per_pixel` = r is given, a point at distance l seen head-on spans l / f_px metres
/// per pixel, so max is capped at r · f_px (docs/conventions.md; obliquity is the viewing-angle
/// constraint's job). f_px is read from K(0,0) and the product is rounded DOWN so the cap is
/// never above the exact r · f_px, even when K(0,0) itself was rounded from focal_length /
/// pixel_pitch. r = +infinity or std::nullopt means no cap. The result may be empty.
/// Throws invalid_argument("max_metres_per_pixel") if r is NaN or not positive.
template <CameraModel C>
certipose::distance_range capped_distance_range(const C& camera,
                                                std::optional<double> max_metres_per_pixel) {
    certipose::distance_range range = camera.distance_range();
    if (!max_metres_per_pixel) return range;
    const double r = *max_metres_per_pixel;
    if (!(r > 0.0))
        detail::camera::fail("capped_distance_range", "max_metres_per_pixel", "positive", r);
    if (std::isinf(r)) return range;
    const Eigen::Matrix3d k = camera.intrinsics();
    const double f_px_lo = detail::camera::down(k(0, 0));
    const double cap = detail::camera::down(r * f_px_lo);
    if (cap < range.max) range.max = cap;
    return range;
}

}  // namespace certipose
