// Every policy of the pipeline swapped once; each pipeline still passes the sampling check.
#include "solver_support.hpp"

#include <certipose/constraints/keep_in_sphere.hpp>

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
void swap_check(const char* what, const Camera& camera, std::uint32_t seed, paving_choice paving = {}) {
    CAPTURE(what);
    const inspection_task task{.min_view_angle = 0.35};
    const Solver solver(part().mesh, camera, task);
    const auto r = solver.solve(part().facet_of_interest, {.position_eps = 0.1, .orientation_eps = 0.38, .paving = paving});
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
    swap_check<pose_solver<with_interval<cgal_interval>>>("interval type: cgal_interval", thin, 11);
    swap_check<pose_solver<with_camera<pinhole_camera>>>("camera: pinhole", pin, 12);
    // The guard plane cannot contract its complement: the default carving runs without inner
    // contraction (the step follows the policies), as does carving that turns it off; asked for
    // with `true`, it is refused, naming the concept.
    swap_check<pose_solver<with_constraints<guarded_constraints>>>("constraint set: paper + user guard plane", thin, 13);
    swap_check<pose_solver<with_constraints<guarded_constraints>>>("constraint set: paper + user guard plane, said off", thin,
                                                                   17, carving{.inner_contraction = false});
    {
        using guarded_solver = pose_solver<with_constraints<guarded_constraints>>;
        const guarded_solver guarded(part().mesh, thin, {.min_view_angle = 0.35});
        const carving steps = guarded_solver::paving_steps(carving{});
        CHECK_FALSE(steps.inner_contraction.is_on());
        CHECK(steps.occlusion_cuts.is_on());  // aabb_occlusion gives shadows
        const auto r = guarded.solve(part().facet_of_interest, {.position_eps = 0.1, .orientation_eps = 0.38});
        CHECK_FALSE(r.stats.paving.inner_contraction.is_on());
        CHECK(r.stats.inner_pieces == 0);
        CHECK_THROWS_WITH_AS(guarded.solve(part().facet_of_interest, {.paving = carving{.inner_contraction = true}}),
                             doctest::Contains("certipose::ComplementContractingSet"), certipose::invalid_argument);
        // The paper's own set can: the default takes the step there.
        CHECK(pose_solver<>::paving_steps(carving{}).inner_contraction.is_on());
        CHECK_FALSE(pose_solver<>::paving_steps(paper_paving{}).inner_contraction.is_on());
    }
    swap_check<pose_solver<with_contraction<contraction::acid_shaving>>>("contractor: ACID", thin, 14);
    swap_check<pose_solver<with_bisector<round_robin>>>("bisector: round robin", thin, 15);
    swap_check<pose_solver<with_buffer<breadth_first>>>("buffer: breadth first", thin, 16);
}


namespace {
template <class J>
using reachable = all_of<paper_position_constraints<J>, keep_in_sphere<J>>;
}  // namespace

TEST_CASE("a user constraint set takes run-time parameters: a keep-in sphere") {
    const thin_lens_camera camera(design_camera_parameters());
    const inspection_task task{.min_view_angle = 0.35};
    const facet& f = part().mesh.facet(part().facet_of_interest);
    using solver_type = pose_solver<with_constraints<reachable>>;
    static_assert(std::is_same_v<solver_type::constraint_parameters, reachable<boost_interval>::parameters>);
    // A robot base above the facet: a short reach certifies fewer boxes than a long one — the
    // radius is read at run time, not compiled in.
    const Eigen::Vector3d base = f.centroid + 0.6 * f.normal;
    const auto run = [&](double radius) {
        const solver_type solver(part().mesh, camera, task, {.constraints = {{}, {.centre = base, .radius = radius}}});
        CHECK(solver.constraints().get<1>().radius == radius);
        auto r = solver.solve(part().facet_of_interest, {.position_eps = 0.1, .orientation_eps = 0.38});
        REQUIRE(r.stats.reason == termination::completed);
        REQUIRE(r.stats.valid > 0);
        // Every corner of every VALID box is within reach, and sampled poses satisfy the rest.
        for (const auto& b : r.boxes) {
            if (b.cls != box_class::valid) continue;
            for (const Eigen::Vector3d& corner : position_corners(b.box.position)) CHECK((corner - base).norm() <= radius);
        }
        const auto rep = check_valid_boxes(r, part().mesh, camera, solver.range(), task.min_view_angle, 20, 21);
        CHECK(rep.violations == 0);
        return r.stats.valid;
    };
    CHECK(run(0.15) < run(0.3));
    CHECK_THROWS_AS(solver_type(part().mesh, camera, task, {.constraints = {{}, {.centre = base, .radius = -1.0}}}),
                    certipose::invalid_argument);
}

TEST_CASE("calibrated_camera: one pipeline for every camera model, box for box the same answers") {
    const inspection_task task{.min_view_angle = 0.35};
    const solve_options opt{.position_eps = 0.1, .orientation_eps = 0.38};
    const thin_lens_camera thin(design_camera_parameters());
    const pinhole_camera pin(pinhole_parameters{.focal_length = 0.012, .pixel_pitch = 3.45e-6, .width_px = 2448,
                                                .height_px = 2048, .d_min = 0.45, .d_max = 0.7});
    using calibrated_solver = pose_solver<with_camera<calibrated_camera>>;
    const auto by_model_thin = pose_solver<>(part().mesh, thin, task).solve(part().facet_of_interest, opt);
    const auto by_model_pin = pose_solver<with_camera<pinhole_camera>>(part().mesh, pin, task).solve(part().facet_of_interest, opt);
    const calibrated_camera thin_c(thin, "thin_lens"), pin_c(pin, "pinhole");
    CHECK(thin_c.model() == "thin_lens");
    CHECK(thin_c.intrinsics() == thin.intrinsics());
    CHECK(thin_c.distance_range().max == thin.distance_range().max);
    const auto calibrated_thin = calibrated_solver(part().mesh, thin_c, task).solve(part().facet_of_interest, opt);
    const auto calibrated_pin = calibrated_solver(part().mesh, pin_c, task).solve(part().facet_of_interest, opt);
    REQUIRE(by_model_thin.stats.valid > 0);
    REQUIRE(by_model_pin.stats.valid > 0);
    CHECK(valid_box_set(calibrated_thin) == valid_box_set(by_model_thin));
    CHECK(valid_box_set(calibrated_pin) == valid_box_set(by_model_pin));
    CHECK(calibrated_thin.stats.boundary == by_model_thin.stats.boundary);
    CHECK(calibrated_pin.stats.boundary == by_model_pin.stats.boundary);
}
