// certipose/camera.hpp — the camera module: the CameraModel concept and its built-in models.
//
// Include this for everything camera-related: `CameraModel` with `fov_half_angles`,
// `distance_range` and `capped_distance_range` (camera/camera_model.hpp), the paper's thin-lens
// camera with depth of field (camera/thin_lens_camera.hpp, the default) and an ideal pinhole
// camera with user distance bounds (camera/pinhole_camera.hpp), and `calibrated_camera`, any of
// them reduced to the values the solver reads (camera/calibrated_camera.hpp), and lens distortion:
// `brown_conrady` with its certified image region (camera/distortion.hpp) and
// `distorted_camera<Base>` (camera/distorted_camera.hpp). No CGAL.
#pragma once

#include "certipose/camera/calibrated_camera.hpp"  // IWYU pragma: export
#include "certipose/camera/camera_model.hpp"  // IWYU pragma: export
#include "certipose/camera/distorted_camera.hpp"  // IWYU pragma: export
#include "certipose/camera/distortion.hpp"  // IWYU pragma: export
#include "certipose/camera/pinhole_camera.hpp"  // IWYU pragma: export
#include "certipose/camera/thin_lens_camera.hpp"  // IWYU pragma: export
