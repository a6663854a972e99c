// docs/placement.md: certifying camera boxes for a part that does not sit exactly where its mesh
// says. The case study solved for the nominal placement and for every placement within ±3 mm and
// 1° about the part's centroid; then with a fixture plate that stays put while the part moves.
// Links certipose::precompiled (the default pipeline is compiled there).
#include <certipose/cgal.hpp>

#include <array>
#include <cstdio>
#include <numbers>

int main() {
    const auto part = certipose::make_sample_part();
    const certipose::thin_lens_camera camera(certipose::thin_lens_parameters{
        .focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6, .max_blur_circle = 6.9e-6,
        .pixel_pitch = 3.45e-6, .width_px = 2448, .height_px = 2048});
    const certipose::solve_options options{.position_eps = 0.1, .orientation_eps = 0.38};

    // Any translation up to 3 mm along each axis, with any rotation up to 1° about any axis
    // through the datum (unset: the part's centroid).
    certipose::inspection_task task{.min_view_angle = 0.35};
    task.placement = certipose::placement_tolerance{.translation = {0.003, 0.003, 0.003},
                                                    .rotation = std::numbers::pi / 180};
    const certipose::pose_solver<> solver(part.mesh, camera, task);
    const auto result = solver.solve(part.facet_of_interest, options);
    // Every pose of a VALID box inspects the facet for every placement the tolerance admits.
    std::printf("datum (%.4f, %.4f, %.4f) m: %zu VALID boxes, %.4f m^3; %zu pieces left undecided by the tolerance\n",
                solver.placement()->datum.x(), solver.placement()->datum.y(), solver.placement()->datum.z(),
                result.stats.valid, result.stats.valid_volume, result.boundary_because(certipose::boundary_reason::placement));

    // A fixture does not move with the part: pass it as an occluder, and the proofs treat it as
    // fixed in the world while the part moves (occlusion/fixed_occluders.hpp).
    // examples/data/fixture_plate.off: 0.4 × 0.3 × 0.01 m, its top at z = 0 under the part.
    const certipose::triangle_mesh plate(
        {{-0.2, -0.15, -0.01}, {0.2, -0.15, -0.01}, {0.2, 0.15, -0.01}, {-0.2, 0.15, -0.01},
         {-0.2, -0.15, 0}, {0.2, -0.15, 0}, {0.2, 0.15, 0}, {-0.2, 0.15, 0}},
        {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
         {2, 3, 7}, {2, 7, 6}, {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}});
    const std::array<certipose::triangle_mesh, 1> fixture{plate};
    const certipose::pose_solver<> on_plate(part.mesh, camera, task, {.occluders = fixture});
    const auto held = on_plate.solve(part.facet_of_interest, options);
    std::printf("on a fixed plate: %zu VALID boxes\n", held.stats.valid);
    return result.stats.valid > 0 && held.stats.valid > 0 ? 0 : 1;
}
