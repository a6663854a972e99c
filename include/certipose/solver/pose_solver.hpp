// certipose/solver/pose_solver.hpp — the paper's Algorithm 3, assembled at compile time from
// policies: certified 6D camera pose boxes for one facet of a part.
//
//   #include <certipose/cgal.hpp>
//   certipose::pose_solver<> solver(mesh, camera, {.min_view_angle = 0.35});   // every default
//   auto result = solver.solve(facet_id, {.position_eps = 0.1, .orientation_eps = 0.38});
//   // the defaults, except one:
//   certipose::pose_solver<certipose::with_contraction<certipose::contraction::acid_shaving>> acid(mesh, camera, task);
//
// The policies (solver/policies.hpp) come as one bundle, `default_policies` unless `with_X<...>`
// or `policies<...>` replaces some; each is checked against its concept where it is named, and
// the bundle again here. A policy whose objects carry options takes them from `setup`.
//
// `solve` runs the stages of Algorithm 3, each a named part with its own options:
//   1. position stage (lines 1–27, solver/position_stage.hpp): pave at ε_p as
//      solve_options::paving says (paper_paving, or carving with its tuning), then refine the
//      BOUNDARY boxes below ε_p when solve_options::refine asks;
//   2. orientation stage (lines 28–36, solver/orientation_schedule.hpp): merge touching position
//      boxes, orient groups, then orient each box, bisecting one no orientation fits;
//   3. placement (past the paper, solver/placement_stage.hpp), when the task has a placement
//      tolerance: the VALID boxes re-proven for every admitted placement of the part, split
//      where they are not;
//   4. growth (past the paper, solver/detail/growth.hpp), when solve_options::grow asks.
// BOUNDARY 6D boxes carry the whole orientation range (nothing was decided about aiming there)
// and the reason they were left undecided (`classified_box::reason`).
//
// Budgets: `max_boxes` counts boxes of both stages. When it ends the position stage, the
// position boxes certified so far are still oriented (each once, without further bisection), so a
// run cut short keeps every VALID box it had earned; a deadline or cancellation ends both stages
// where they are. What is left is BOUNDARY with reason `budget`, never VALID.
//
// The mesh must outlive the solver (it is referenced, not copied): a temporary mesh is refused
// at compile time. The camera's usable distance must be bounded (a pinhole camera's d_max is
// +inf unless given): the solver throws invalid_argument("d_max") otherwise.
//
// The default occlusion policy is `aabb_occlusion` (certified, CGAL): it is only declared here,
// so this header compiles without CGAL; include <certipose/cgal.hpp> to use the default, or pass
// `no_occlusion` / `boolean_occlusion` / your own policy. One solver may solve several facets,
// also from several threads at once: `solve` is const and every run owns its state.
#pragma once

#include <array>
#include <chrono>
#include <algorithm>
#include <cmath>
#include <map>
#include <cstddef>
#include <numbers>
#include <optional>
#include <set>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "certipose/camera/camera_model.hpp"
#include "certipose/constraints/concept.hpp"
#include "certipose/detail/format.hpp"
#include "certipose/occlusion/concept.hpp"
#include "certipose/occlusion/mesh_semantics.hpp"
#include "certipose/orientation/concept.hpp"
#include "certipose/solver/contraction.hpp"
#include "certipose/solver/detail/box_certifier.hpp"
#include "certipose/solver/detail/growth.hpp"
#include "certipose/solver/orientation_schedule.hpp"
#include "certipose/solver/paving.hpp"
#include "certipose/solver/placement_stage.hpp"
#include "certipose/solver/policies.hpp"
#include "certipose/solver/position_stage.hpp"
#include "certipose/solver/result.hpp"
#include "certipose/solver/task.hpp"

namespace certipose {

namespace detail {
template <class T>
concept complete_type = requires { sizeof(T); };
template <class O, class I>
concept complete_occlusion_policy = complete_type<O> && OcclusionPolicy<O, I>;
}  // namespace detail

namespace detail {
/// The finest growth steps of the six components.
inline std::array<double, 6> finest_steps(const growth_options& o, double position_eps, double orientation_eps) {
    const double p = o.position_step > 0 ? o.position_step : position_eps / 64;
    const double e = o.orientation_step > 0 ? o.orientation_step : orientation_eps / 64;
    return {p, p, p, e, e, e};
}
}  // namespace detail

template <class Policies = default_policies>
class pose_solver {
public:
    using policies = Policies;
    using interval_type = typename Policies::interval;
    using camera_type = typename Policies::camera;
    using constraint_set_type = typename Policies::template constraints<interval_type>;
    using contraction_type = typename Policies::contraction;
    using bisector_type = typename Policies::bisector;
    using occlusion_type = typename Policies::occlusion;
    using orientation_type = typename Policies::orientation;
    using buffer_type = typename Policies::buffer;
    using schedule_type = typename Policies::schedule;
    /// What the constraint set takes besides the facet (`no_parameters` for the paper's set).
    using constraint_parameters = constraint_parameters_t<constraint_set_type>;
    using result_type = solve_result<interval_type>;

private:
    using I = interval_type;
    // Each policy against its concept, in the order of the table in solver/policies.hpp, so the
    // first error names the policy and the concept it misses.
    static_assert(Interval<I>, "certipose::pose_solver: Policies::interval must model certipose::Interval");
    static_assert(CameraModel<camera_type>, "certipose::pose_solver: Policies::camera must model certipose::CameraModel");
    static_assert(SearchableConstraintSet<constraint_set_type, I>,
                  "certipose::pose_solver: Policies::constraints<I> must model certipose::SearchableConstraintSet "
                  "(contract(box), test(box) -> verdict, initial_box(), built from a position_problem [and its "
                  "parameters])");
    static_assert(ContractionPolicy<contraction_type, I>,
                  "certipose::pose_solver: Policies::contraction must model certipose::ContractionPolicy "
                  "(wrap(contractor) const -> Contractor; e.g. certipose::contraction::set_only)");
    static_assert(PositionBisector<bisector_type, I>,
                  "certipose::pose_solver: Policies::bisector must model certipose::PositionBisector "
                  "(choose(box) -> std::optional<split>, constructible from position_eps)");
    static_assert(detail::complete_occlusion_policy<occlusion_type, I>,
                  "certipose::pose_solver: Policies::occlusion must model certipose::OcclusionPolicy (the default, "
                  "aabb_occlusion, needs <certipose/cgal.hpp> or <certipose/occlusion/cgal_aabb_occlusion.hpp>)");
    static_assert(OrientationPolicy<orientation_type, I, camera_type>,
                  "certipose::pose_solver: Policies::orientation must model certipose::OrientationPolicy "
                  "(orient(position, facet, camera, orientation_eps) -> orientation_result<I>)");
    static_assert(PavingBufferPolicy<buffer_type>,
                  "certipose::pose_solver: Policies::buffer must model certipose::PavingBufferPolicy");
    static_assert(OrientationScheduleFor<schedule_type, orientation_type, I, camera_type>,
                  "certipose::pose_solver: Policies::schedule cannot drive Policies::orientation: hinted_schedule "
                  "needs a certipose::BorrowingOrientationPolicy (hints and borrowing); use "
                  "with_schedule<per_box_schedule> for any OrientationPolicy");

public:
    /// Everything besides the part, the camera and the task, all optional.
    struct setup {
        /// External occluders (closed solids) added to the part's own occlusion; read while the
        /// solver is built, not kept. Ignored by the occlusion when `occlusion` is given; with a
        /// placement tolerance in the task they are also the occluders that do not move with the
        /// part (occlusion/fixed_occluders.hpp), so pass them then too.
        std::span<const triangle_mesh> occluders{};
        /// A ready occlusion policy (e.g. one shared by several solvers); built from the part
        /// and `occluders` when absent. Refused with a placement tolerance in the task.
        std::optional<occlusion_type> occlusion{};
        /// How the occlusion policy reads the part and the occluders (occlusion/mesh_survey.hpp):
        /// closed solids (the default), a triangle soup, or whichever the meshes are. A policy
        /// without a constructor taking it reads solids only and refuses anything else.
        mesh_semantics semantics = mesh_semantics::solid;
        /// The orientation policy (with its options).
        orientation_type orientation{};
        /// The constraint set's run-time parameters (solver/policies.hpp, constraints/concept.hpp).
        constraint_parameters constraints{};
        /// The contraction policy (with its options, e.g. contraction::acid_shaving's).
        contraction_type contraction{};
        /// Tuning of the orientation schedule's steps for carving (solver/orientation_schedule.hpp).
        schedule_options schedule{};
        /// Options of the placement stage (solver/placement_stage.hpp; used with a placement
        /// tolerance in the task).
        placement_stage_options placement{};
    };

    /// Builds the occlusion policy for the scene (the part plus optional external occluders)
    /// once; validates the task and the camera's distance range. The mesh must outlive the solver.
    pose_solver(const triangle_mesh& part, camera_type camera, inspection_task task, setup s = {})
        : part_(&part),
          camera_(std::move(camera)),
          task_(task),
          occlusion_(s.occlusion ? std::move(*s.occlusion) : make_occlusion(part, s.occluders, s.semantics)),
          orientation_(std::move(s.orientation)),
          constraint_parameters_(std::move(s.constraints)),
          contraction_(std::move(s.contraction)),
          schedule_(s.schedule),
          placement_options_(s.placement) {
        task_.validate();
        schedule_.validate();
        placement_options_.validate();
        if (task_.placement && !task_.placement->none()) {
            // The fixed occluders are the scene's extra meshes, known only from `occluders`: a
            // ready policy may hold some the solver cannot see, which would then be proven in
            // the part frame only, as if they moved with the part.
            if (s.occlusion)
                throw invalid_argument("occlusion", "pose_solver: a placement tolerance needs the occluders themselves "
                                                    "(setup.occluders), not a ready occlusion policy: they stay put while "
                                                    "the part moves");
            placement_ = placement_scene{resolve(*task_.placement, surface_centroid(part)), fixed_occluders::of(s.occluders)};
        }
        range_ = capped_distance_range(camera_, task_.max_metres_per_pixel);
        if (range_.empty())
            throw invalid_argument("max_metres_per_pixel",
                                   "pose_solver: the resolution requirement leaves no usable distance (d_max " +
                                       detail::format_double(range_.max) + " < d_min " +
                                       detail::format_double(range_.min) + ")");
        if (!std::isfinite(range_.max))
            throw invalid_argument("d_max", "pose_solver: the camera's usable distance is unbounded; set "
                                            "max_metres_per_pixel or use a camera with a finite d_max");
        // The set is built per facet in solve(); building one now checks its parameters here,
        // where they were given, instead of at the first solve.
        (void)make_constraint_set<constraint_set_type>(position_problem{part.facet(0), range_, task_},
                                                       constraint_parameters_);
    }

    /// The occlusion policy for the scene, read as `semantics` says (setup::semantics).
    static occlusion_type make_occlusion(const triangle_mesh& part, std::span<const triangle_mesh> occluders,
                                         mesh_semantics semantics) {
        if constexpr (std::constructible_from<occlusion_type, const triangle_mesh&, std::span<const triangle_mesh>,
                                              mesh_semantics>) {
            return occlusion_type(part, occluders, semantics);
        } else {
            if (semantics == mesh_semantics::soup && checks_occlusion<occlusion_type>)
                throw invalid_argument("semantics", "pose_solver: this occlusion policy reads closed solids only; "
                                                    "aabb_occlusion reads a triangle soup");
            return occlusion_type(part, occluders);
        }
    }

    /// A temporary mesh would be destroyed before `solve` reads it: refused at compile time.
    pose_solver(const triangle_mesh&& part, camera_type camera, inspection_task task, setup s = {}) = delete;

    const camera_type& camera() const noexcept { return camera_; }
    const inspection_task& task() const noexcept { return task_; }
    distance_range range() const noexcept { return range_; }
    const triangle_mesh& part() const noexcept { return *part_; }
    const occlusion_type& occlusion() const noexcept { return occlusion_; }
    const orientation_type& orientation() const noexcept { return orientation_; }
    const constraint_parameters& constraints() const noexcept { return constraint_parameters_; }
    const contraction_type& contraction() const noexcept { return contraction_; }
    const schedule_options& schedule() const noexcept { return schedule_; }
    /// The task's placement tolerance with its datum resolved (the part's centroid when the task
    /// gives none); nothing when the task has none.
    std::optional<resolved_placement> placement() const {
        if (!placement_) return std::nullopt;
        return placement_->tolerance;
    }

    /// What the proofs of every admitted placement need (box_certifier, facet_inspector), or null.
    const placement_scene* placement_proofs() const noexcept { return placement_ ? &*placement_ : nullptr; }


    /// The steps `paving` takes with this pipeline's policies: carving's switches left to the
    /// policies decided by what the constraint set and the occlusion policy can do (paving.hpp).
    /// Throws invalid_argument for a step asked for that they cannot serve.
    static carving paving_steps(const paving_choice& paving) {
        return certipose::paving_steps<constraint_set_type, occlusion_type, I>(paving);
    }

    /// The position stage the pipeline runs for a facet (solver/position_stage.hpp), as `solve`
    /// builds it: its `contractor()` is the contraction policy's contractor on the facet's
    /// constraint set, `pave` / `refine` its steps. For tests and benchmarks of a stage alone.
    using position_stage_type = certipose::position_stage<I, constraint_set_type, occlusion_type, contraction_type, bisector_type,
                                               buffer_type>;
    position_stage_type position_stage(std::size_t facet_index, const solve_options& options = {}) const {
        options.validate();
        return position_stage_type(position_problem{part_->facet(facet_index), range_, task_}, facet_index, occlusion_,
                                   options.paving, options.position_eps, constraint_parameters_, contraction_);
    }

    /// The contractor the position stage narrows boxes with for a facet, owning the facet's
    /// constraint set: what the pipeline really runs, to test or micro-benchmark.
    auto position_contractor(std::size_t facet_index) const {
        return owning_contractor<constraint_set_type, contraction_type, I>(
            make_constraint_set<constraint_set_type>(position_problem{part_->facet(facet_index), range_, task_},
                                                     constraint_parameters_),
            contraction_);
    }

    /// The certifier of whole 6D boxes for a facet, with the solver's own proofs (`certify`,
    /// growth): `c(box)` for every constraint, `c.fov(position, orientation)` for constraint 5.
    using certifier_type = pose_certifier<constraint_set_type, occlusion_type, I>;
    certifier_type certifier(std::size_t facet_index) const;

    /// Certified pose boxes for facet `facet_index` (Algorithm 3). Throws out_of_range for a bad
    /// index and invalid_argument for bad options; budgets and cancellation end the run early
    /// with `stats.reason` saying why (see the header comment: boxes not decided are BOUNDARY,
    /// never VALID).
    result_type solve(std::size_t facet_index, const solve_options& options = {}) const;

    /// Whether every pose of `box` is valid for facet `facet_index`: each of the six
    /// constraints proven over the whole box with the proofs `solve` uses (the constraint set,
    /// the occlusion policy, certify_fov). false means "not proven", not "invalid".
    bool certify(std::size_t facet_index, const pose_box<I>& box) const;

    /// `box` — one `certify` accepts, e.g. a VALID box of `solve` — widened face by face while
    /// it stays certified (solver/detail/growth.hpp): the same box or a larger one, certified.
    /// Throws invalid_argument("box") when `certify` does not accept `box`.
    pose_box<I> grow(std::size_t facet_index, const pose_box<I>& box, const growth_options& options = {}) const;

    /// The largest certified box found around the pose (x, y, z, φ, γ, β): all half-widths
    /// grown together in the proportions of (ε_p, ε_p, ε_p, ε_o, ε_o, ε_o) of `eps` (defaults:
    /// 0.1 m, 0.38 rad), then each on its own — the installation tolerance of that pose, per
    /// axis (γ stays within [0, π], so the box is not centred there). Nothing when the pose
    /// itself cannot be certified valid.
    std::optional<pose_box<I>> largest_box_around(std::size_t facet_index, const std::array<double, 6>& pose,
                                                  const growth_options& options = {},
                                                  std::array<double, 2> eps = {0.1, 0.38}) const;

private:
    // The stages of `solve`, in order (see the header comment).
    position_stage_result<I> run_position_stage(std::size_t facet_index, const solve_options& options,
                                                const run_context& clock, result_type& out) const;
    void run_orientation_stage(const facet& f, const solve_options& options, const run_context& clock,
                               position_stage_result<I>& positions, result_type& out) const;
    void run_growth(std::size_t facet_index, const solve_options& options, const run_context& clock,
                    result_type& out) const;
    void run_placement_stage(std::size_t facet_index, const solve_options& options, const run_context& clock,
                             result_type& out) const;

    const triangle_mesh* part_;
    camera_type camera_;
    inspection_task task_;
    occlusion_type occlusion_;
    orientation_type orientation_;
    constraint_parameters constraint_parameters_;
    contraction_type contraction_;
    schedule_options schedule_;
    placement_stage_options placement_options_;
    std::optional<placement_scene> placement_{};
    distance_range range_{};
};

// Out of the class body, so that they are not inline: an explicit instantiation declaration
// (certipose::precompiled, detail/precompiled.hpp) then keeps a user's translation unit from
// compiling them again.

template <class Policies>
auto pose_solver<Policies>::solve(std::size_t facet_index, const solve_options& options) const -> result_type {
    options.validate();
    const run_context clock(options.stop, options.time_limit);
    const facet& f = part_->facet(facet_index);  // throws out_of_range("facet", ...)
    result_type out;
    out.facet_index = facet_index;
    out.stats.occlusion_checked = checks_occlusion<occlusion_type>;
    out.stats.paving = paving_steps(options.paving);

    position_stage_result<I> positions = run_position_stage(facet_index, options, clock, out);  // lines 1–27
    run_orientation_stage(f, options, clock, positions, out);                                   // lines 28–36
    if (placement_ && out.stats.valid > 0) run_placement_stage(facet_index, options, clock, out);  // past the paper
    if (options.grow && out.stats.valid > 0) run_growth(facet_index, options, clock, out);      // past the paper
    out.stats.seconds = clock.seconds();
    return out;
}

template <class Policies>
auto pose_solver<Policies>::run_position_stage(std::size_t facet_index, const solve_options& options,
                                               const run_context& clock, result_type& out) const
    -> position_stage_result<I> {
    paver_options popt;
    popt.max_boxes = options.max_boxes;
    popt.deadline = clock.deadline();
    popt.record_tree = options.keep_tree;
    if (options.progress) {
        popt.progress_every = 256;
        popt.progress = [&](const paver_stats& s) {
            return options.progress(solve_progress{"position", s.boxes, s.pending, 0, 0, clock.seconds()});
        };
    }
    position_stage_type stage = position_stage(facet_index, options);
    position_stage_result<I> r = stage.pave(popt, options.stop);
    if (options.refine) {
        // The refinement's deadline is its own, not the run's: the orientation stage follows.
        position_refinement refine{options.refine->width(options.position_eps), std::nullopt};
        if (options.refine->time_limit) refine.deadline = clock.start() + *options.refine->time_limit;
        else if (options.time_limit) refine.deadline = clock.start() + *options.time_limit / 4;  // refinement::time_limit
        stage.refine(r, refine, popt, options.stop);
    }
    stage.explain(r);

    solve_stats& st = out.stats;
    const auto& ps = r.boxes.stats;
    st.contractions = r.counters.contractions;
    st.bisections = ps.bisections;
    st.occlusion_tests = r.counters.occlusion_tests;
    st.shadow_walks = r.counters.shadow_walks;
    st.inner_pieces = r.counters.inner_pieces;
    st.occlusion_pieces = r.counters.occlusion_pieces;
    st.corner_boxes = r.counters.corner_boxes;
    st.position_valid = r.boxes.valid.size();
    st.position_boundary = r.boxes.boundary.size() + r.boxes.pending.size();
    st.reason = ps.reason;
    st.refinement_stopped = r.refinement_stopped;
    st.refinement_passes = r.counters.refinement_passes;
    st.seconds_position = clock.seconds();
    if (options.keep_tree) out.tree = std::move(r.boxes.tree);
    return r;
}

template <class Policies>
void pose_solver<Policies>::run_orientation_stage(const facet& f, const solve_options& options,
                                                  const run_context& clock, position_stage_result<I>& positions,
                                                  result_type& out) const {
    // At least one 6D box per position box (bisections add more).
    out.boxes.reserve(positions.boxes.boundary.size() + positions.boxes.pending.size() + positions.boxes.valid.size());
    for (std::size_t i = 0; i < positions.boxes.boundary.size(); ++i)
        detail::push_boundary(out, positions.boxes.boundary[i], positions.boundary_reasons[i]);
    for (const auto& b : positions.boxes.pending) detail::push_boundary(out, b, boundary_reason::budget);

    // A position box no orientation fits is bisected down to ε_p (the paper), or further when
    // refining (refinement::orientation_split). The bisector may be stateful (round_robin).
    bisector_type bisector(options.refine ? options.position_eps / options.refine->orientation_split
                                          : options.position_eps);
    orientation_stage<schedule_type, orientation_type, camera_type, I, bisector_type> stage(
        orientation_, f, camera_, options, schedule_, clock, std::move(bisector), out, positions.boxes.stats.boxes);
    stage.merge_positions(positions.boxes.valid);
    stage.orient_groups(positions.boxes.valid);
    stage.orient_each();
    out.stats.seconds_orientation = clock.seconds() - out.stats.seconds_position;
}

template <class Policies>
void pose_solver<Policies>::run_growth(std::size_t facet_index, const solve_options& options,
                                       const run_context& clock, result_type& out) const {
    solve_stats& st = out.stats;
    auto ok = certifier(facet_index);
    std::vector<pose_box<I>> valid;
    std::vector<classified_box<I>> rest;
    for (auto& b : out.boxes) {
        if (b.cls == box_class::valid) valid.push_back(b.box);
        else rest.push_back(std::move(b));
    }
    const auto out_of_time = [&] { return clock.out_of_time(); };
    st.merges = detail::growth::merge_touching(
        valid, [&](const position_box<I>& p, const orientation_box<I>& e) { return ok.fov(p, e); }, out_of_time);
    const auto finest = detail::finest_steps(*options.grow, options.position_eps, options.orientation_eps);
    for (auto& b : valid) {
        if (out_of_time()) break;
        const pose_box<I> g = detail::growth::grow(b, ok, finest, options.grow->max_certifications);
        if (!(g == b)) ++st.grown, b = g;
    }
    detail::growth::drop_contained(valid);
    out.boxes = std::move(rest);
    st.valid = valid.size();
    st.valid_volume = 0;
    for (auto& b : valid) {
        st.valid_volume += volume(b.position);
        out.boxes.push_back(classified_box<I>{box_class::valid, std::move(b)});
    }
    st.orientation_certifications += ok.certifications;
    st.seconds_growth = clock.seconds() - st.seconds_position - st.seconds_orientation;
}

template <class Policies>
void pose_solver<Policies>::run_placement_stage(std::size_t facet_index, const solve_options& options,
                                                const run_context& clock, result_type& out) const {
    auto ok = certifier(facet_index);
    // The margin of the erode-and-restore step: the reach of the box's camera positions, at
    // least the facet's own (solver/placement_stage.hpp).
    const std::array<double, 3> facet_margin = facet_reach<I>(part_->facet(facet_index).v, placement_->tolerance);
    const auto margin = [&](const position_box<I>& p) {
        std::array<double, 3> m = camera_reach_radii(p, placement_->tolerance);
        for (std::size_t k = 0; k < 3; ++k) m[k] = std::max(m[k], facet_margin[k]);
        return m;
    };
    certify_for_every_placement(
        out, [&](const pose_box<I>& b) { return ok(b); }, margin, options.position_eps, options.orientation_eps,
        placement_options_, [&] { return clock.out_of_time(); },
        [&] { return options.stop.stop_requested() ? termination::cancelled : termination::deadline; });
    out.stats.orientation_certifications += ok.certifications;
}

template <class Policies>
auto pose_solver<Policies>::certifier(std::size_t facet_index) const -> certifier_type {
    const facet& f = part_->facet(facet_index);  // throws out_of_range("facet", ...)
    return certifier_type(make_constraint_set<constraint_set_type>(position_problem{f, range_, task_}, constraint_parameters_),
                          occlusion_, facet_index, f, fov_frustum<I>(camera_), placement_ ? &*placement_ : nullptr);
}

template <class Policies>
bool pose_solver<Policies>::certify(std::size_t facet_index, const pose_box<I>& box) const {
    auto ok = certifier(facet_index);
    return ok(box);
}

template <class Policies>
auto pose_solver<Policies>::grow(std::size_t facet_index, const pose_box<I>& box, const growth_options& options) const
    -> pose_box<I> {
    options.validate();
    auto ok = certifier(facet_index);
    if (!ok(box)) throw invalid_argument("box", "pose_solver::grow: the box is not certified for this facet");
    // Outside a run there is no ε: the defaults of growth_options (1 mm, 0.005 rad) are the
    // finest steps a run at ε_p = 0.064 m, ε_o = 0.32 rad would take.
    return detail::growth::grow(box, ok, detail::finest_steps(options, 0.064, 0.32), options.max_certifications);
}

template <class Policies>
auto pose_solver<Policies>::largest_box_around(std::size_t facet_index, const std::array<double, 6>& pose,
                                               const growth_options& options, std::array<double, 2> eps) const
    -> std::optional<pose_box<I>> {
    options.validate();
    for (double v : pose)
        if (!std::isfinite(v))
            throw invalid_argument("pose", "pose_solver::largest_box_around: the pose must be finite, got " +
                                               detail::format_double(v));
    if (!(eps[0] > 0 && eps[1] > 0 && std::isfinite(eps[0]) && std::isfinite(eps[1])))
        throw invalid_argument("eps", "pose_solver::largest_box_around: eps must be positive and finite");
    auto ok = certifier(facet_index);
    const std::array<double, 6> reference{eps[0], eps[0], eps[0], eps[1], eps[1], eps[1]};
    return detail::growth::largest_around<I>(pose, ok, reference, detail::finest_steps(options, eps[0], eps[1]),
                                             options.max_certifications);
}

}  // namespace certipose
