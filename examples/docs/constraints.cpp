// docs/constraints.md: a user-written position constraint set ("keep the camera above a guard
// plane z >= 0.4 m") combined with the paper's set and paved for the sample part's facet.
#include <certipose/camera.hpp>
#include <certipose/constraints/paper_position_constraints.hpp>
#include <certipose/geometry/sample_part.hpp>
#include <certipose/interval/boost_interval.hpp>
#include <certipose/occlusion/no_occlusion.hpp>
#include <certipose/solver/position_stage.hpp>

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

int main() {
    using I = certipose::boost_interval;
    using constraints = certipose::all_of<certipose::paper_position_constraints<I>, above_guard<I>>;
    static_assert(certipose::PositionConstraintSet<constraints, I>);

    const auto part = certipose::make_sample_part();
    const certipose::thin_lens_camera camera(certipose::thin_lens_parameters{
        .focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6, .max_blur_circle = 6.9e-6,
        .pixel_pitch = 3.45e-6, .width_px = 2448, .height_px = 2048});
    const certipose::position_problem problem{part.mesh.facet(part.facet_of_interest), camera.distance_range(),
                                              certipose::inspection_task{.min_view_angle = 0.35}};
    const certipose::no_occlusion occlusion(part.mesh);
    const auto result = certipose::pave_positions<I, constraints>(problem, part.facet_of_interest, occlusion,
                                                                  certipose::paver_options{}, /*ε_p=*/0.1);
    std::printf("%zu VALID and %zu BOUNDARY position boxes, all above z = %.1f m\n", result.boxes.valid.size(),
                result.boxes.boundary.size(), above_guard<I>::height);
}
