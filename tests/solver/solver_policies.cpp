// Every policy of the pipeline swapped once; each pipeline still passes the sampling check.
#include "solver_support.hpp"

using namespace solver_test;

namespace {
template <class J>
struct above_guard {
    explicit above_guard(const position_problem&) {}
    void contract(position_box<J>& b) {
        const rounding_guard<J> rounding;
        b[2] = intersect(b[2], J(0.3, std::numeric_limits<double>::infinity()));
    }
    verdict test(const position_box<J>& b) const {
        return lower(b[2]) >= 0.3 ? verdict::satisfied : upper(b[2]) < 0.3 ? verdict::violated : verdict::undecided;
    }
};
template <class J>
using guarded_constraints = all_of<paper_position_constraints<J>, above_guard<J>>;

template <class Solver, class Camera>
void swap_check(const char* what, const Camera& camera, std::uint32_t seed) {
    CAPTURE(what);
    const inspection_task task{.min_view_angle = 0.35};
    const Solver solver(part().mesh, camera, task);
    const auto r = solver.solve(part().facet_of_interest, {.position_eps = 0.1, .orientation_eps = 0.38});
    REQUIRE(r.stats.reason == termination::completed);
    CHECK(r.stats.valid > 0);
    const auto rep = check_valid_boxes(r, part().mesh, camera, solver.range(), task.min_view_angle, 20, seed);
    MESSAGE(std::string(what) << ": " << r.stats.valid << " VALID, " << r.stats.boundary << " BOUNDARY, " << rep.samples
                 << " samples, " << rep.violations << " violations");
    CHECK(rep.violations == 0);
}
}  // namespace

TEST_CASE("every policy swapped once still passes the sampling check") {
    const thin_lens_camera thin(design_camera_parameters());
    const pinhole_camera pin(pinhole_parameters{.focal_length = 0.012, .pixel_pitch = 3.45e-6, .width_px = 2448,
                                                .height_px = 2048, .d_min = 0.45, .d_max = 0.7});
    swap_check<pose_solver<cgal_interval, thin_lens_camera, paper_position_constraints, hc4_contraction, largest_first, aabb_occlusion>>(
        "interval type: cgal_interval", thin, 11);
    swap_check<pose_solver<boost_interval, pinhole_camera, paper_position_constraints, hc4_contraction, largest_first, aabb_occlusion>>(
        "camera: pinhole", pin, 12);
    swap_check<pose_solver<boost_interval, thin_lens_camera, guarded_constraints, hc4_contraction, largest_first, aabb_occlusion>>(
        "constraint set: paper + user guard plane", thin, 13);
    swap_check<pose_solver<boost_interval, thin_lens_camera, paper_position_constraints, acid_contraction, largest_first, aabb_occlusion>>(
        "contractor: ACID", thin, 14);
    swap_check<pose_solver<boost_interval, thin_lens_camera, paper_position_constraints, hc4_contraction, round_robin, aabb_occlusion>>(
        "bisector: round robin", thin, 15);
    swap_check<pose_solver<boost_interval, thin_lens_camera, paper_position_constraints, hc4_contraction, largest_first, aabb_occlusion,
                           paper_orientation, breadth_first>>("buffer: breadth first", thin, 16);
}

