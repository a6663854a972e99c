// The whole pipeline (paper Algorithm 3): random poses inside every VALID 6D box of the case
// study and of two real meshes satisfy every constraint of DESIGN.md §3; inputs, budgets and
// cancellation.
#include "solver_support.hpp"

using namespace solver_test;

TEST_CASE("case study: every sampled pose in a VALID box satisfies every constraint (aabb occlusion)") {
    const thin_lens_camera camera(design_camera_parameters());
    const inspection_task task{.min_view_angle = 0.35};
    const default_solver<aabb_occlusion> solver(part().mesh, camera, task);
    const auto r = solver.solve(part().facet_of_interest, {.position_eps = 0.1, .orientation_eps = 0.38});
    REQUIRE(r.stats.reason == termination::completed);
    REQUIRE(r.stats.valid > 50);
    const std::size_t per_box = 10000 / r.stats.valid + 1;
    const auto rep = check_valid_boxes(r, part().mesh, camera, solver.range(), task.min_view_angle, per_box, 1);
    MESSAGE("case study: " << r.stats.valid << " VALID, " << r.stats.boundary << " BOUNDARY; " << rep.samples
                           << " sampled poses, " << rep.violations << " violations");
    CHECK(rep.samples >= 10000);
    CHECK(rep.violations == 0);
}

TEST_CASE("real meshes: sampled poses in VALID boxes satisfy every constraint") {
    const thin_lens_camera camera(design_camera_parameters());
    const inspection_task task{.min_view_angle = 0.35};
    for (const char* name : {"idler_riser.off", "featuretype.off"}) {
        CAPTURE(name);
        const triangle_mesh mesh =
            rescaled_to_diagonal(read_mesh(std::string(CERTIPOSE_SHARED_MESHES) + "/" + name), 0.3);
        const default_solver<aabb_occlusion> solver(mesh, camera, task);
        const std::size_t id = upward_facet(mesh);
        const auto r = solver.solve(id, {.position_eps = 0.1, .orientation_eps = 0.38});
        REQUIRE(r.stats.reason == termination::completed);
        REQUIRE(r.stats.valid > 0);
        const std::size_t per_box = 10000 / r.stats.valid + 1;
        const auto rep = check_valid_boxes(r, mesh, camera, solver.range(), task.min_view_angle, per_box, 2);
        MESSAGE(std::string(name) << " facet " << id << ": " << r.stats.valid << " VALID, " << r.stats.boundary << " BOUNDARY; "
                     << rep.samples << " samples, " << rep.violations << " violations");
        CHECK(rep.samples >= 10000);
        CHECK(rep.violations == 0);
    }
}

TEST_CASE("solver inputs are validated with certipose errors") {
    const thin_lens_camera camera(design_camera_parameters());
    const default_solver<no_occlusion> solver(part().mesh, camera, inspection_task{});
    CHECK_THROWS_AS(solver.solve(part().mesh.num_faces()), certipose::out_of_range);
    CHECK_THROWS_AS(solver.solve(0, {.position_eps = 0.0}), certipose::invalid_argument);
    CHECK_THROWS_AS(solver.solve(0, {.orientation_eps = std::nan("")}), certipose::invalid_argument);
    CHECK_THROWS_AS(solver.solve(0, {.max_boxes = 0}), certipose::invalid_argument);
    CHECK_THROWS_AS(default_solver<no_occlusion>(part().mesh, camera, inspection_task{.min_view_angle = 1.6}),
                    certipose::invalid_argument);
    // A resolution cap below d_min leaves nothing.
    CHECK_THROWS_AS(default_solver<no_occlusion>(part().mesh, camera, inspection_task{.max_metres_per_pixel = 1e-6}),
                    certipose::invalid_argument);
    // A pinhole with unbounded distance cannot be paved.
    const pinhole_camera unbounded(pinhole_parameters{.focal_length = 0.012, .pixel_pitch = 3.45e-6, .width_px = 2448,
                                                      .height_px = 2048});
    using pin_solver = pose_solver<boost_interval, pinhole_camera, paper_position_constraints, hc4_contraction, largest_first, no_occlusion>;
    CHECK_THROWS_AS(pin_solver(part().mesh, unbounded, inspection_task{}), certipose::invalid_argument);
}

TEST_CASE("budgets, progress and cancellation end a run early without a false VALID box") {
    const thin_lens_camera camera(design_camera_parameters());
    const default_solver<aabb_occlusion> solver(part().mesh, camera, inspection_task{});
    const auto full = solver.solve(part().facet_of_interest);
    const auto small = solver.solve(part().facet_of_interest, {.max_boxes = 40});
    CHECK(small.stats.reason == termination::box_budget);
    CHECK(small.stats.valid <= full.stats.valid);
    std::size_t calls = 0;
    solve_options stop_early;
    stop_early.progress = [&](const solve_progress&) { return ++calls < 2; };
    const auto cancelled = solver.solve(part().facet_of_interest, stop_early);
    CHECK(calls >= 1);
    CHECK(cancelled.stats.reason == termination::cancelled);
    std::stop_source source;
    source.request_stop();
    solve_options stopped;
    stopped.stop = source.get_token();
    const auto none = solver.solve(part().facet_of_interest, stopped);
    CHECK(none.stats.reason == termination::cancelled);
    CHECK(none.stats.valid == 0);
    // Whatever was returned VALID early is VALID in the full run too (same deterministic paving).
    const auto rep = check_valid_boxes(small, part().mesh, camera, solver.range(), 0.35, 20, 9);
    CHECK(rep.violations == 0);
}
