// One whole solve in the CGAL suite: the debug preset runs this suite under ASan + UBSan with
// assertions on (the solver suite runs in Release only, where compiling the pipelines once more
// would not fit CI's time), so the default pipeline — its paving, inner contraction, occlusion
// cuts, corner boxes and orientation stage, header-only here — is exercised sanitized too.
#include "solver_support.hpp"

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
