// docs/coverage.md: which facets a pose box certifies, C(B) and P(B); multi-facet inspection
// spaces; a greedy deployment plan with its lower bound; the tolerance of a given pose keeping its
// facets. Links certipose::precompiled.
#include <certipose/cgal.hpp>
#include <certipose/coverage/candidates.hpp>
#include <certipose/coverage/deployment.hpp>
#include <certipose/coverage/inspect_boxes.hpp>
#include <certipose/coverage/inspection.hpp>
#include <certipose/coverage/multi_facet.hpp>

#include <cstdio>

int main() {
    using I = certipose::boost_interval;
    const auto part = certipose::make_sample_part();
    const certipose::thin_lens_camera camera(certipose::thin_lens_parameters{
        .focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6, .max_blur_circle = 6.9e-6,
        .pixel_pitch = 3.45e-6, .width_px = 2448, .height_px = 2048});
    const certipose::pose_solver<> solver(part.mesh, camera, {.min_view_angle = 0.35});
    const certipose::solve_options eps{.position_eps = 0.1, .orientation_eps = 0.38};

    // C(B) and P(B) of the largest VALID box of the facet of interest, cut to ±5 mm, ±0.02 rad.
    certipose::candidate_pool<I> largest(1);
    for (const auto& b : solver.solve(part.facet_of_interest, eps).boxes)
        if (b.cls == certipose::box_class::valid) largest.add(part.facet_of_interest, b.box);
    if (largest.boxes().empty()) return 1;
    const certipose::pose_box<I> box =
        certipose::around_centre(largest.boxes().front().box, {0.005, 0.005, 0.005, 0.02, 0.02, 0.02});
    certipose::facet_inspector<> inspector(solver);
    const certipose::facet_coverage c = inspector.inspect(box);
    std::printf("the box certifies %zu facets (%.5f m^2); %zu are possible (%.5f m^2)\n", c.certified.size(),
                c.certified_area, c.possible.size(), c.possible_area);

    // The poses from which two facets are both certified.
    if (c.certified.size() >= 2) {
        const std::vector<std::size_t> pair{c.certified.front(), c.certified.back()};
        const auto both = certipose::multi_facet_space(solver, pair, eps);
        std::printf("facets %zu and %zu: %zu boxes in their common inspection space\n", pair[0], pair[1], both.size());
    }

    // A plan: candidates are the largest VALID box of every 50th facet.
    certipose::candidate_pool<I> pool(1);
    for (std::size_t f = 0; f < part.mesh.num_faces(); f += 50)
        for (const auto& b : solver.solve(f, eps).boxes)
            if (b.cls == certipose::box_class::valid) pool.add(f, b.box);
    // Each cut to an installation tolerance of ±5 mm, ±0.02 rad around its centre: still VALID for
    // its facet, and certifying far more facets than the whole box.
    std::vector<certipose::pose_box<I>> boxes;
    for (const auto& cand : pool.boxes())
        boxes.push_back(certipose::around_centre(cand.box, {0.005, 0.005, 0.005, 0.02, 0.02, 0.02}));
    const certipose::inspection_run run = certipose::inspect_boxes(solver, boxes);
    std::vector<certipose::deployment_candidate> sets;
    for (const auto& cov : run.coverage) sets.push_back({cov.certified});
    const certipose::deployment_plan plan = certipose::plan_greedy(sets, inspector.areas(), {.coverage = 0.95});
    std::printf("%zu cameras certify %.1f %% of the coverable area; any plan needs at least %zu\n", plan.chosen.size(),
                100 * plan.certified_area / plan.coverable_area, plan.lower_bound);

    // Someone else's exact pose: what it certifies, and how far it may move and keep all of it.
    const auto m = certipose::midpoint(box.as_6d());
    const std::array<double, 6> pose{m[0], m[1], m[2], m[3], m[4], m[5]};
    certipose::pose_box<I> point;
    for (std::size_t k = 0; k < 3; ++k) point.position.x[k] = I(pose[k]), point.orientation.x[k] = I(pose[k + 3]);
    const auto facets = inspector.inspect(point).certified;
    if (const auto tolerance = inspector.largest_box_keeping(pose, facets))
        std::printf("the pose certifies %zu facets; all stay certified within x +-%.1f mm, gamma +-%.3f rad\n",
                    facets.size(), 500 * certipose::width(tolerance->position[0]), certipose::width(tolerance->orientation[1]) / 2);
}
