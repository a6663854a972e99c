// A downstream program that includes only the umbrella header and runs the default pipeline (the
// paper's case study), built against the installed package with certipose::precompiled and as an
// add_subdirectory with header-only certipose::cgal (tests/consumer/*/CMakeLists.txt).
#include <certipose/cgal.hpp>

#include <cstdio>

int main() {
    const auto part = certipose::make_sample_part();
    const certipose::thin_lens_camera camera(certipose::thin_lens_parameters{
        .focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6, .max_blur_circle = 6.9e-6,
        .pixel_pitch = 3.45e-6, .width_px = 2448, .height_px = 2048});
    const certipose::pose_solver<> solver(part.mesh, camera, {.min_view_angle = 0.35});
    const auto r = solver.solve(part.facet_of_interest, {.position_eps = 0.1, .orientation_eps = 0.38});
    const bool ok = r.stats.reason == certipose::termination::completed && r.stats.valid > 0 &&
                    r.stats.occlusion_checked && r.stats.valid + r.stats.boundary == r.boxes.size();
    std::printf("consumer (default pipeline): %zu VALID, %zu BOUNDARY: %s\n", r.stats.valid, r.stats.boundary,
                ok ? "ok" : "FAILED");
    return ok ? 0 : 1;
}
