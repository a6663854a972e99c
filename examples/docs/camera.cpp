// docs/camera.md — the case-study camera (examples/data/camera.json): K, FOV half-angles and the in-focus range.
#include <certipose/certipose.hpp>  // or just <certipose/camera.hpp>

#include <cstdio>
#include <numbers>

int main() {
    const certipose::thin_lens_camera camera({.focal_length = 0.012,  // metres
                                              .f_stop = 8,
                                              .focus_distance = 0.6,
                                              .max_blur_circle = 6.9e-6,  // 2 pixels
                                              .pixel_pitch = 3.45e-6,
                                              .width_px = 2448,
                                              .height_px = 2048});  // principal point: centre
    static_assert(certipose::CameraModel<certipose::thin_lens_camera>);

    const Eigen::Matrix3d k = camera.intrinsics();
    std::printf("K =\n");
    for (int r = 0; r < 3; ++r) std::printf("  [%10.3f %10.3f %10.3f]\n", k(r, 0), k(r, 1), k(r, 2));

    const auto fov = camera.fov_half_angles();
    const double deg = 180 / std::numbers::pi;
    std::printf("FOV half-angles: horizontal %.6f rad (%.2f deg), vertical %.6f rad (%.2f deg)\n",
                fov.horizontal, fov.horizontal * deg, fov.vertical, fov.vertical * deg);

    std::printf("hyperfocal H = %.6f m, aperture = %.4f m\n", camera.hyperfocal_distance(),
                camera.aperture_diameter());
    const auto range = camera.distance_range();  // rounded inward: safe to certify against
    std::printf("[d_min, d_max] = [%.9f, %.9f] m\n", range.min, range.max);

    // A resolution requirement of 0.2 mm per pixel caps d_max at 2e-4 * f_px.
    const auto capped = camera.distance_range(2e-4);
    std::printf("with 0.2 mm/px:  [%.9f, %.9f] m\n", capped.min, capped.max);
}
