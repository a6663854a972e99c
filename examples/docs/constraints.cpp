// docs/constraints.md: the position problem of one facet, the paper's constraint set on its own,
// and a set with run-time parameters (keep_in_sphere) combined with it and paved for the
// sample part's facet of interest — the position stage alone, no CGAL.
#include <certipose/certipose.hpp>

#include <cstdio>
#include <string>
#include <type_traits>

// The paper's set plus "the camera stays within a robot's reach" (a ball given at run time).
template <class I>
using reachable = certipose::all_of<certipose::paper_position_constraints<I>, certipose::keep_in_sphere<I>>;

int main() {
    using I = certipose::boost_interval;
    const auto part = certipose::make_sample_part();
    const certipose::thin_lens_camera camera(certipose::thin_lens_parameters{
        .focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6, .max_blur_circle = 6.9e-6,
        .pixel_pitch = 3.45e-6, .width_px = 2448, .height_px = 2048});

    // What a set is built from, for one facet (the solver makes one per facet it solves).
    const certipose::position_problem problem{.facet = part.mesh.facet(part.facet_of_interest),
                                              .range = camera.distance_range(),  // [d_min, d_max]
                                              .task = {.min_view_angle = 0.35}};
    std::printf("facet centroid (%.4f, %.4f, %.4f), area %.3g m^2; d in [%.4f, %.4f] m; theta_v %.2f rad\n",
                problem.facet.centroid.x(), problem.facet.centroid.y(), problem.facet.centroid.z(),
                problem.facet.area, problem.range.min, problem.range.max, problem.task.min_view_angle);

    // The paper's set on its own: the initial search box, then a verdict on one box and, when
    // it cannot decide, which constraint it could not certify.
    certipose::paper_position_constraints<I> paper(problem);
    const certipose::position_box<I> start = paper.initial_box();
    std::printf("initial box x [%.3f, %.3f] y [%.3f, %.3f] z [%.3f, %.3f]\n", certipose::lower(start[0]),
                certipose::upper(start[0]), certipose::lower(start[1]), certipose::upper(start[1]),
                certipose::lower(start[2]), certipose::upper(start[2]));
    const auto above = certipose::position_box<I>::from_bounds({{{-0.05, 0.05}, {-0.05, 0.05}, {0.5, 0.6}}});
    const auto why = paper.undecided(above);
    std::printf("box above the facet: %s\n", why ? std::string(certipose::to_string(*why)).c_str() : "certified");

    // A set with parameters: all_of's hold each member's, in order (no_parameters for the paper's).
    static_assert(std::is_same_v<certipose::constraint_parameters_t<certipose::paper_position_constraints<I>>,
                                 certipose::no_parameters>);
    const certipose::keep_in_sphere<I>::parameters sphere{.centre = Eigen::Vector3d(0.0, 0.0, 0.65), .radius = 0.2};
    const reachable<I>::parameters parameters{{}, sphere};

    // The position stage alone (Algorithm 3 lines 1–27), here without occlusion.
    const certipose::no_occlusion occlusion(part.mesh);
    const auto anywhere = certipose::pave_positions<I, certipose::paper_position_constraints<I>>(
        problem, part.facet_of_interest, occlusion, {}, /*ε_p=*/0.1);
    const auto within = certipose::pave_positions<I, reachable<I>>(problem, part.facet_of_interest, occlusion, {},
                                                                   /*ε_p=*/0.1, {}, parameters);
    std::size_t by_sphere = 0;  // keep_in_sphere does not say which of its constraints: `constraint`
    for (const auto r : within.boundary_reasons) by_sphere += r == certipose::boundary_reason::constraint;
    std::printf("VALID position boxes: %zu anywhere, %zu within %.1f m of the base (%zu BOUNDARY on the sphere)\n",
                anywhere.boxes.valid.size(), within.boxes.valid.size(), sphere.radius, by_sphere);
    return within.boxes.valid.size() > 0 && within.boxes.valid.size() < anywhere.boxes.valid.size() ? 0 : 1;
}
