// certipose/camera/calibrated_camera.hpp — any camera model reduced to what the solver reads.
//
// The solver (and every policy certipose ships) uses a camera only through the CameraModel
// concept: K, the image size, the field-of-view half-angles and [d_min, d_max]. A program that
// accepts several models — certipose-solve reads "thin_lens" or "pinhole" from JSON — would
// instantiate the whole pipeline once per model; converting to `calibrated_camera` first needs
// one instantiation for all of them (`pose_solver<with_camera<calibrated_camera>>`), with the
// same answers: the values are copied from the model, not recomputed. No CGAL.
#pragma once

#include <string>
#include <string_view>

#include <Eigen/Core>

#include "certipose/camera/camera_model.hpp"

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
          model_(model) {}

    const Eigen::Matrix3d& intrinsics() const noexcept { return k_; }
    double width_px() const noexcept { return width_px_; }
    double height_px() const noexcept { return height_px_; }
    certipose::fov_half_angles fov_half_angles() const noexcept { return fov_; }
    certipose::distance_range distance_range() const noexcept { return range_; }
    /// The model it was made from, as named at construction.
    const std::string& model() const noexcept { return model_; }

private:
    Eigen::Matrix3d k_;
    double width_px_, height_px_;
    certipose::fov_half_angles fov_;
    certipose::distance_range range_;
    std::string model_;
};

static_assert(CameraModel<calibrated_camera>);

}  // namespace certipose
