// One whole solve in the CGAL suite: the debug preset runs this suite under ASan + UBSan with
// assertions on (the solver suite runs in Release only, where compiling the pipelines once more
// would not fit CI's time), so the default pipeline — its paving, inner contraction, occlusion
// cuts, corner boxes and orientation stage, header-only here — is exercised sanitized too.
#include "solver_support.hpp"

#include <certipose/io/json.hpp>

#include <chrono>
#include <string>
#include <variant>

using namespace solver_test;

TEST_CASE("one solve: the case study's VALID boxes pass the sampling check, corners included") {
    const thin_lens_camera camera(design_camera_parameters());
    const inspection_task task{.min_view_angle = 0.35};
    const pose_solver<> solver(part().mesh, camera, task);
    const auto r = solver.solve(part().facet_of_interest, {.position_eps = 0.1, .orientation_eps = 0.38});
    REQUIRE(r.stats.reason == termination::completed);
    REQUIRE(r.stats.valid > 50);
    CHECK(r.stats.inner_pieces + r.stats.occlusion_pieces + r.stats.corner_boxes > 0);
    const auto rep = check_valid_boxes(r, part().mesh, camera, solver.range(), task.min_view_angle, 4, 5, true, 60);
    MESSAGE("case study: " << r.stats.valid << " VALID; " << rep.samples << " poses checked, " << rep.violations
                           << " violations");
    CHECK(rep.violations == 0);
}

TEST_CASE("a refinement that completes both passes, sanitized: the issue's angle_block command") {
    // certipose-solve --mesh angle_block.off --scale 0.186104 --facet 520 --camera camera_wide.json
    //   --position-eps 0.4 --orientation-eps 0.38 --refine 400 --max-boxes 4000000
    // Its second pass starts from the first pass's states; they once held shadows from a cache
    // the first pass's paver had freed (ASan: heap-use-after-free), and certified occluded poses.
    const std::string shared = CERTIPOSE_SHARED_MESHES;
    const auto in = read_camera_task(shared + "/../cases/camera_wide.json");
    const auto camera = std::get<thin_lens_camera>(in.camera);
    const auto mesh = read_mesh(shared + "/angle_block.off", {.scale = 0.186104});
    const pose_solver<> solver(mesh, camera, in.task);
    solve_options o{.position_eps = 0.4, .orientation_eps = 0.38, .max_boxes = 4'000'000};
    o.refine = refinement{.time_limit = std::chrono::seconds(400)};
    const auto r = solver.solve(520, o);
    REQUIRE(r.stats.reason == termination::completed);
    CHECK(r.stats.refinement_passes == 2);
    REQUIRE(r.stats.valid > 1000);
    const auto rep = check_valid_boxes(r, mesh, camera, solver.range(), in.task.min_view_angle, 4, 7, true, 400);
    MESSAGE("refined angle_block: " << r.stats.valid << " VALID; " << rep.samples << " poses checked, "
                                    << rep.violations << " violations");
    CHECK(rep.violations == 0);
}
