// certipose/camera/distorted_camera.hpp — any camera model with lens distortion.
//
// `distorted_camera<Base>` wraps a thin_lens_camera or pinhole_camera (or any CameraModel) and a
// Brown–Conrady distortion (camera/distortion.hpp). Its intrinsics, image size and distance range
// are the base model's — the real K, used for outputs and the resolution cap — while the solver
// certifies the field of view against `image_region()`: the pinhole-equivalent image of the
// rectangle of normalized coordinates proven to be imaged inside the real image minus
// `margin_px` with no fold. That region is computed once, at construction, and its
// fov_half_angles are what an orientation search aims with. Throws what
// certified_image_rectangle throws (invalid_argument naming "distortion_coefficients",
// "image_margin_px", ...).
#pragma once

#include "certipose/camera/camera_model.hpp"
#include "certipose/camera/distortion.hpp"

#include <Eigen/Core>

#include <utility>

namespace certipose {

template <CameraModel Base>
class distorted_camera {
public:
    distorted_camera(Base base, const brown_conrady& distortion, double margin_px = 0.0)
        : base_(std::move(base)), distortion_(distortion), margin_px_(margin_px) {
        const normalized_rectangle r =
            certified_image_rectangle(base_.intrinsics(), base_.width_px(), base_.height_px(), distortion_, margin_px_);
        rectangle_ = r;
        image_ = pinhole_image_of(r);
        fov_ = fov_half_angles_of(r);
    }

    const Base& base() const noexcept { return base_; }
    const brown_conrady& distortion() const noexcept { return distortion_; }
    double margin_px() const noexcept { return margin_px_; }
    /// The certified rectangle of normalized coordinates (camera/distortion.hpp).
    const normalized_rectangle& certified_rectangle() const noexcept { return rectangle_; }

    // ---- CameraModel ------------------------------------------------------------------------
    /// The real K of the base model (not the certified image's).
    Eigen::Matrix3d intrinsics() const { return base_.intrinsics(); }
    double width_px() const { return base_.width_px(); }
    double height_px() const { return base_.height_px(); }
    certipose::distance_range distance_range() const { return base_.distance_range(); }
    /// The half-angles of the certified image (what is usable), not of the bare sensor.
    certipose::fov_half_angles fov_half_angles() const noexcept { return fov_; }
    /// The pinhole image the field of view is certified against (HasImageRegion).
    const pinhole_image& image_region() const noexcept { return image_; }

private:
    Base base_;
    brown_conrady distortion_;
    double margin_px_;
    normalized_rectangle rectangle_{};
    pinhole_image image_{};
    certipose::fov_half_angles fov_{};
};

}  // namespace certipose
