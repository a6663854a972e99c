// docs/solver.md: the paper's case study with the default pipeline.
#include <certipose/geometry/sample_part.hpp>
#include <certipose/occlusion/cgal_aabb_occlusion.hpp>
#include <certipose/solver/pose_solver.hpp>

#include <cstdio>

int main() {
    const auto part = certipose::make_sample_part();
    const certipose::thin_lens_camera camera(certipose::thin_lens_parameters{
        .focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6, .max_blur_circle = 6.9e-6,
        .pixel_pitch = 3.45e-6, .width_px = 2448, .height_px = 2048});
    using Solver = certipose::pose_solver<>;  // every default: Boost intervals, thin lens, HC4, AABB occlusion
    const Solver solver(part.mesh, camera, {.min_view_angle = 0.35});
    const auto result = solver.solve(part.facet_of_interest, {.position_eps = 0.1, .orientation_eps = 0.38});
    std::printf("facet %zu: %zu VALID and %zu BOUNDARY pose boxes in %.3f s\n", result.facet_index,
                result.stats.valid, result.stats.boundary, result.stats.seconds);
    for (const auto& b : result.boxes) {
        if (b.cls != certipose::box_class::valid) continue;
        const auto& p = b.box.position;
        const auto& e = b.box.orientation;
        std::printf("first VALID box: x [%.3f, %.3f] y [%.3f, %.3f] z [%.3f, %.3f], phi [%.3f, %.3f] gamma [%.3f, %.3f] beta [%.3f, %.3f]\n",
                    certipose::lower(p[0]), certipose::upper(p[0]), certipose::lower(p[1]), certipose::upper(p[1]),
                    certipose::lower(p[2]), certipose::upper(p[2]), certipose::lower(e[0]), certipose::upper(e[0]),
                    certipose::lower(e[1]), certipose::upper(e[1]), certipose::lower(e[2]), certipose::upper(e[2]));
        break;
    }
}
