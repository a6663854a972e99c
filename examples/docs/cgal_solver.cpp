// docs/solver.md and README.md: the paper's case study with the default pipeline; what a result
// says; budgets and progress; the set-up; any camera model through calibrated_camera; changing
// policies. Links certipose::precompiled: the two pipelines it runs are compiled there.
#include <certipose/cgal.hpp>  // everything, the default solver included

#include <cstdio>
#include <string>
#include <type_traits>
#include <vector>

// A contraction policy of one's own: the set's contractor, twice in a row. `wrap` receives the
// constraint set's contractor `c` and returns a Contractor built on it.
struct twice {
    template <class C>
    auto wrap(C c) const { return certipose::compose(c, c); }
};
static_assert(certipose::ContractionPolicy<twice, certipose::boost_interval>);

// The defaults, except one policy; changes chain from the inside out, or come in any order
// through certipose::policies<...>.
using acid_solver = certipose::pose_solver<certipose::with_contraction<certipose::contraction::acid_shaving>>;
using same_as_my_solver = certipose::pose_solver<
    certipose::policies<certipose::with_bisector<certipose::round_robin>, certipose::with_contraction<twice>>>;
using exact_solver = certipose::pose_solver<
    certipose::with_occlusion<certipose::boolean_occlusion, certipose::with_interval<certipose::cgal_interval>>>;
using my_solver = certipose::pose_solver<certipose::with_contraction<twice, certipose::with_bisector<certipose::round_robin>>>;
static_assert(std::is_same_v<my_solver::contraction_type, same_as_my_solver::contraction_type> &&
              std::is_same_v<my_solver::bisector_type, same_as_my_solver::bisector_type>);
static_assert(std::is_same_v<exact_solver::interval_type, certipose::cgal_interval>);
static_assert(std::is_same_v<exact_solver::camera_type, certipose::thin_lens_camera>);  // the rest: defaults

int main() {
    const auto part = certipose::make_sample_part();  // the paper's §8 part (stand-in), metres
    const certipose::thin_lens_camera camera(certipose::thin_lens_parameters{
        .focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6, .max_blur_circle = 6.9e-6,
        .pixel_pitch = 3.45e-6, .width_px = 2448, .height_px = 2048});
    const certipose::pose_solver<> solver(part.mesh, camera, {.min_view_angle = 0.35});  // every default
    const auto result = solver.solve(part.facet_of_interest, {.position_eps = 0.1, .orientation_eps = 0.38});
    for (const auto& b : result.boxes)
        if (b.cls == certipose::box_class::valid) { /* b.box.position, b.box.orientation: certified */ }

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

    // Why the BOUNDARY boxes were left undecided: per box, counted per reason.
    std::printf("undecided on: %s\n", certipose::boundary_summary(result.stats).c_str());
    if (const auto why = certipose::main_boundary_reason(result.stats))
        std::printf("mostly %s; %zu for occlusion (PARTIAL)\n", std::string(certipose::to_string(*why)).c_str(),
                    result.boundary_because(certipose::boundary_reason::occlusion));

    // A budget and a progress callback; returning false cancels the run.
    std::size_t reports = 0;
    certipose::solve_options budget{.position_eps = 0.1, .orientation_eps = 0.38, .max_boxes = 400};
    budget.progress = [&](const certipose::solve_progress& p) {
        ++reports;  // p.stage ("position", "orientation"), p.boxes_done, p.boxes_pending, p.seconds
        return p.seconds < 60.0;
    };
    const auto cut = solver.solve(part.facet_of_interest, budget);
    std::printf("%s: %zu VALID kept, %zu BOUNDARY (%zu for the budget), %zu progress reports\n",
                certipose::to_string(cut.stats.reason), cut.stats.valid, cut.stats.boundary,
                cut.boundary_because(certipose::boundary_reason::budget), reports);

    // The set-up: external occluders (read now, not kept) or a ready occlusion policy shared by
    // several solvers, and the orientation policy with its options (the constraint set's
    // parameters: docs/constraints.md).
    const std::vector<certipose::triangle_mesh> occluders{
        certipose::translated(certipose::scaled(part.mesh, 0.5), Eigen::Vector3d(0.0, 0.0, 0.35))};
    const certipose::pose_solver<> shaded(part.mesh, camera, {.min_view_angle = 0.35},
                                          {.occluders = occluders,
                                           .orientation = certipose::paper_orientation({.tiling_budget = 16})});
    const certipose::aabb_occlusion scene(part.mesh, occluders);
    const certipose::pose_solver<> sharing(part.mesh, camera, {.min_view_angle = 0.35}, {.occlusion = scene});
    std::printf("with an occluder above the part: %zu VALID (shared scene: %zu)\n",
                shaded.solve(part.facet_of_interest).stats.valid, sharing.solve(part.facet_of_interest).stats.valid);

    // Any camera model as one type: one pipeline instantiation serves them all.
    const certipose::pinhole_camera pinhole({.focal_length = 0.012, .pixel_pitch = 3.45e-6, .width_px = 2448,
                                             .height_px = 2048, .d_min = 0.3});  // d_max: +inf
    using any_camera_solver = certipose::pose_solver<certipose::with_camera<certipose::calibrated_camera>>;
    try {
        const any_camera_solver unbounded(part.mesh, certipose::calibrated_camera(pinhole, "pinhole"), {});
    } catch (const certipose::invalid_argument& e) {
        std::printf("refused: %s (field %s)\n", e.what(), e.field().c_str());
    }
    const any_camera_solver capped(part.mesh, certipose::calibrated_camera(pinhole, "pinhole"),
                                   {.min_view_angle = 0.35, .max_metres_per_pixel = 2e-4});  // d_max = 2e-4 f_px
    const any_camera_solver lens(part.mesh, certipose::calibrated_camera(camera, "thin_lens"), {.min_view_angle = 0.35});
    std::printf("pinhole capped at %.3f m: %zu VALID; thin lens as calibrated_camera: %zu VALID\n", capped.range().max,
                capped.solve(part.facet_of_interest).stats.valid, lens.solve(part.facet_of_interest).stats.valid);

    // A contraction policy with its options, and the contractor the position stage runs with it.
    using acid_pipeline = certipose::pose_solver<certipose::with_contraction<certipose::contraction::acid_shaving>>;
    const acid_pipeline shaving(part.mesh, camera, {.min_view_angle = 0.35}, {.contraction = {.options = {.s3b = 20}}});
    auto contractor = shaving.position_contractor(part.facet_of_interest);  // what the pipeline runs
    auto box = contractor.constraint_set().initial_box();
    contractor.contract(box);
    std::printf("ACID (s3b = %d) narrows the search box to %.3f m^3\n", shaving.contraction().options.s3b,
                certipose::volume(box));
    return result.stats.valid > 0 && cut.stats.valid > 0 && !certipose::is_empty(box) ? 0 : 1;
}
