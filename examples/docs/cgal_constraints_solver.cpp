// docs/constraints.md: a user-written position constraint set ("keep the camera above a guard
// plane z >= 0.4 m") and a parameterised one (keep_in_sphere), combined with the paper's set and
// given to the whole pipeline through with_constraints and setup::constraints.
#include <certipose/cgal.hpp>

#include <cstdio>
#include <limits>

// A constraint set is a class template over the interval type, built from the facet's
// position_problem, with a sound contract() and a three-valued test().
template <class I>
struct above_guard {
    static constexpr double height = 0.4;  // metres

    explicit above_guard(const certipose::position_problem&) {}

    // Never removes a position with z >= height.
    void contract(certipose::position_box<I>& box) {
        const certipose::rounding_guard<I> rounding;
        box[2] = certipose::intersect(box[2], I(height, std::numeric_limits<double>::infinity()));
    }
    // satisfied: every position of the box is above; violated: none is.
    certipose::verdict test(const certipose::position_box<I>& box) const {
        if (certipose::lower(box[2]) >= height) return certipose::verdict::satisfied;
        if (certipose::upper(box[2]) < height) return certipose::verdict::violated;
        return certipose::verdict::undecided;
    }
};

// The pipeline takes the set as a class template over the interval type: an alias template.
// The paper's set comes first: it supplies the initial search box.
template <class I>
using cell = certipose::all_of<certipose::paper_position_constraints<I>, above_guard<I>, certipose::keep_in_sphere<I>>;

int main() {
    static_assert(certipose::PositionConstraintSet<cell<certipose::boost_interval>, certipose::boost_interval>);
    const auto part = certipose::make_sample_part();
    const certipose::thin_lens_camera camera(certipose::thin_lens_parameters{
        .focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6, .max_blur_circle = 6.9e-6,
        .pixel_pitch = 3.45e-6, .width_px = 2448, .height_px = 2048});
    const certipose::inspection_task task{.min_view_angle = 0.35};

    // One parameter value per member set, in order; {} for the sets that declare none.
    using solver_type = certipose::pose_solver<certipose::with_constraints<cell>>;
    const solver_type solver(part.mesh, camera, task,
                             {.constraints = {{}, {}, {.centre = Eigen::Vector3d(0.0, 0.0, 0.65), .radius = 0.25}}});
    const auto result = solver.solve(part.facet_of_interest, {.position_eps = 0.1, .orientation_eps = 0.38});
    std::printf("%zu VALID pose boxes above z = %.1f m and within %.2f m of the base; undecided on: %s\n",
                result.stats.valid, above_guard<certipose::boost_interval>::height,
                solver.constraints().get<2>().radius, certipose::boundary_summary(result.stats).c_str());
    for (const auto& b : result.boxes)
        if (b.cls == certipose::box_class::valid && certipose::lower(b.box.position[2]) < above_guard<certipose::boost_interval>::height)
            return 1;
    return result.stats.valid > 0 ? 0 : 1;
}
