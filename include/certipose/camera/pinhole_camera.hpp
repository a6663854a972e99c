// certipose/camera/pinhole_camera.hpp — an ideal pinhole camera with user distance bounds.
//
// `pinhole_camera` has the same intrinsics and field of view as `thin_lens_camera` (K from focal
// length, pixel pitch, principal point, skew and aspect; docs/camera.md) but no depth of field:
// the usable object distances [d_min, d_max] are whatever the user states (working distance of a
// fixture, a telecentric stand-off, a focus range measured on the real lens). Those bounds are
// returned exactly as given, so they are the user's responsibility. d_max may be +infinity.
// Every impossible parameter throws certipose::invalid_argument naming the field.
#pragma once

#include "certipose/detail/format.hpp"
#include "certipose/camera/camera_model.hpp"
#include "certipose/error.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <optional>

namespace certipose {

/// Parameters of a pinhole camera. Lengths in metres, image size and principal point in pixels.
/// Fields left out of a designated initialiser are 0 and are rejected, except the principal
/// point (default: image centre), skew (0), aspect (1), d_min (0) and d_max (+inf).
struct pinhole_parameters {
    double focal_length = 0.0;  ///< f, metres (f_px = focal_length / pixel_pitch)
    double pixel_pitch = 0.0;   ///< metres per pixel on the sensor (width of a pixel)
    double width_px = 0.0;      ///< image width w, pixels
    double height_px = 0.0;     ///< image height h, pixels
    std::optional<Eigen::Vector2d> principal_point_px{};  ///< (c_x, c_y); default (w/2, h/2)
    double skew = 0.0;          ///< s in K
    double aspect = 1.0;        ///< δ = pixel height / pixel width
    double d_min = 0.0;         ///< nearest usable object distance, metres (>= 0)
    double d_max = std::numeric_limits<double>::infinity();  ///< farthest, metres (> d_min)
};

class pinhole_camera : public detail::camera::sensor<pinhole_camera> {
    using sensor = detail::camera::sensor<pinhole_camera>;

public:
    explicit pinhole_camera(const pinhole_parameters& p)
        : sensor("pinhole_camera", p),
          range_{p.d_min, p.d_max} {
        if (!(p.d_min >= 0.0) || !std::isfinite(p.d_min))
            detail::camera::fail("pinhole_camera", "d_min", "finite and >= 0", p.d_min);
        if (!(p.d_max > p.d_min))  // also rejects NaN; +inf is allowed
            detail::camera::fail("pinhole_camera", "d_max",
                                 "greater than d_min (" + detail::format_double(p.d_min) + ")",
                                 p.d_max);
    }

    // intrinsics(), width_px(), height_px(), fov_half_angles(), focal_length() and the other
    // sensor accessors are inherited from detail::camera::sensor.

    /// [d_min, d_max] exactly as given.
    certipose::distance_range distance_range() const noexcept { return range_; }
    using sensor::distance_range;  // (r): capped for a resolution requirement

private:
    certipose::distance_range range_;
};

}  // namespace certipose
