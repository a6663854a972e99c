// certipose/camera/calibrated_camera.hpp — any camera model reduced to what the solver reads.
//
// The solver (and every policy certipose ships) uses a camera only through the CameraModel
// concept: K, the image size, the field-of-view half-angles and [d_min, d_max]. A program that
// accepts several models — certipose-solve reads "thin_lens" or "pinhole" from JSON — would
// instantiate the whole pipeline once per model; converting to `calibrated_camera` first needs
// one instantiation for all of them (`pose_solver<with_camera<calibrated_camera>>`), with the
// same answers: the values are copied from the model, not recomputed — the certified image of a
// distorted camera (camera/distorted_camera.hpp) included, with its coefficients and margin, so
// the one instantiation serves distorted cameras too. No CGAL.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include <Eigen/Core>

#include "certipose/camera/camera_model.hpp"
#include "certipose/camera/distortion.hpp"

namespace certipose {

/// The values of a CameraModel, itself a CameraModel (see the header comment).
class calibrated_camera {
public:
    /// From any camera model; `model` names it in documents ("thin_lens", "pinhole", ...).
    template <CameraModel C>
        requires(!std::same_as<C, calibrated_camera>)
    explicit calibrated_camera(const C& camera, std::string_view model = "camera")
        : k_(camera.intrinsics()),
          width_px_(camera.width_px()),
          height_px_(camera.height_px()),
          fov_(camera.fov_half_angles()),
          range_(camera.distance_range()),
          image_(certified_image(camera)),
          model_(model) {
        if constexpr (requires { camera.distortion(); }) {
            const std::optional<brown_conrady> d(camera.distortion());
            if (d && !d->is_zero()) distortion_ = d;
        }
        if constexpr (requires { camera.margin_px(); }) margin_px_ = camera.margin_px();
    }

    const Eigen::Matrix3d& intrinsics() const noexcept { return k_; }
    double width_px() const noexcept { return width_px_; }
    double height_px() const noexcept { return height_px_; }
    certipose::fov_half_angles fov_half_angles() const noexcept { return fov_; }
    certipose::distance_range distance_range() const noexcept { return range_; }
    /// The image the field of view is certified against (camera_model.hpp's certified_image of
    /// the model): K, width and height unless the model has lens distortion.
    const pinhole_image& image_region() const noexcept { return image_; }
    /// The model's lens distortion, if it has one that is not zero.
    const std::optional<brown_conrady>& distortion() const noexcept { return distortion_; }
    /// The model's image margin in pixels (0 for a model without one).
    double margin_px() const noexcept { return margin_px_; }
    /// The model it was made from, as named at construction.
    const std::string& model() const noexcept { return model_; }

private:
    Eigen::Matrix3d k_;
    double width_px_, height_px_;
    certipose::fov_half_angles fov_;
    certipose::distance_range range_;
    pinhole_image image_;
    std::optional<brown_conrady> distortion_{};
    double margin_px_ = 0.0;
    std::string model_;
};

static_assert(CameraModel<calibrated_camera>);

}  // namespace certipose
