// certipose/solver/pose_solver.hpp — the paper's Algorithm 3, assembled at compile time from
// policies: certified 6D camera pose boxes for one facet of a part.
//
//   #include <certipose/cgal.hpp>
//   certipose::pose_solver<> solver(mesh, camera, {.min_view_angle = 0.35});   // every default
//   auto result = solver.solve(facet_id, {.position_eps = 0.1, .orientation_eps = 0.38});
//   // the defaults, except one: certipose::pose_solver<certipose::with_contraction<certipose::contraction::acid>>
//
// The policies (interval type, camera model, constraint set, contraction, bisector, occlusion,
// orientation, buffer) come as one bundle, `default_policies` unless a `with_X<...>` replaces
// one of them (solver/policies.hpp); the bundle is checked here, each policy against its concept.
//
// Stage 1 (lines 1–27) paves positions (solver/position_stage.hpp). Stage 2 (lines 28–36) asks
// the orientation policy for certified orientation boxes of each VALID position box; when it
// certifies none the position box is bisected (largest first) down to ε_p — halves of a
// certified position box stay certified for constraints 1–4 and 6, so only orientation is
// asked again — and a box that still fails at ε_p is reported BOUNDARY. BOUNDARY 6D boxes carry
// the whole orientation range (nothing was decided about aiming there) and the reason they were
// left undecided (`classified_box::reason`, counted in `solve_stats::boundary_reasons`).
// An orientation policy modelling HintedOrientationPolicy (paper_orientation does) gets one hint
// per cell of ε_p: the boxes of a cell search from what their neighbours found; one modelling
// BorrowingOrientationPolicy is also asked, for a box whose own search failed in a cell where
// none certified yet, to try the hints of the cells around it.
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
#include "certipose/orientation/concept.hpp"
#include "certipose/solver/contraction.hpp"
#include "certipose/solver/detail/box_certifier.hpp"
#include "certipose/solver/detail/growth.hpp"
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
/// The hint type of an orientation policy (HintedOrientationPolicy), an empty one otherwise.
template <class O, class I, class C>
struct orientation_hint_of {
    struct type {};
};
template <class O, class I, class C>
    requires HintedOrientationPolicy<O, I, C>
struct orientation_hint_of<O, I, C> {
    using type = typename O::hint;
};

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
                  "(static wrap(contractor) -> Contractor; e.g. certipose::contraction::hc4)");
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

public:
    /// Everything besides the part, the camera and the task, all optional.
    struct setup {
        /// External occluders (closed solids) added to the part's own occlusion; read while the
        /// solver is built, not kept. Ignored when `occlusion` is given.
        std::span<const triangle_mesh> occluders{};
        /// A ready occlusion policy (e.g. one shared by several solvers); built from the part
        /// and `occluders` when absent.
        std::optional<occlusion_type> occlusion{};
        /// The orientation policy (with its options).
        orientation_type orientation{};
        /// The constraint set's run-time parameters (solver/policies.hpp, constraints/concept.hpp).
        constraint_parameters constraints{};
    };

    /// Builds the occlusion policy for the scene (the part plus optional external occluders)
    /// once; validates the task and the camera's distance range. The mesh must outlive the solver.
    pose_solver(const triangle_mesh& part, camera_type camera, inspection_task task, setup s = {})
        : part_(&part),
          camera_(std::move(camera)),
          task_(task),
          occlusion_(s.occlusion ? std::move(*s.occlusion) : occlusion_type(part, s.occluders)),
          orientation_(std::move(s.orientation)),
          constraint_parameters_(std::move(s.constraints)) {
        task_.validate();
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

    /// A temporary mesh would be destroyed before `solve` reads it: refused at compile time.
    pose_solver(const triangle_mesh&& part, camera_type camera, inspection_task task, setup s = {}) = delete;

    const camera_type& camera() const noexcept { return camera_; }
    const inspection_task& task() const noexcept { return task_; }
    distance_range range() const noexcept { return range_; }
    const triangle_mesh& part() const noexcept { return *part_; }
    const occlusion_type& occlusion() const noexcept { return occlusion_; }
    const orientation_type& orientation() const noexcept { return orientation_; }
    const constraint_parameters& constraints() const noexcept { return constraint_parameters_; }

    /// Certified pose boxes for facet `facet_index` (Algorithm 3). Throws out_of_range for a bad
    /// index and invalid_argument for bad options; budgets and cancellation end the run early
    /// with `stats.reason` saying why (see the header comment: boxes not decided are BOUNDARY,
    /// never VALID).
    result_type solve(std::size_t facet_index, const solve_options& options = {}) const;

    /// Whether every pose of `box` is valid for facet `facet_index`: each constraint of
    /// DESIGN.md §3 proven over the whole box with the proofs `solve` uses (the constraint set,
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
    using certifier_type = detail::box_certifier<constraint_set_type, occlusion_type, I>;
    certifier_type certifier(std::size_t facet_index) const;

    /// An undecided box: the position box with every orientation (nothing decided about aim).
    static void push_boundary(result_type& out, const position_box<I>& p, boundary_reason why);

    const triangle_mesh* part_;
    camera_type camera_;
    inspection_task task_;
    occlusion_type occlusion_;
    orientation_type orientation_;
    constraint_parameters constraint_parameters_;
    distance_range range_{};
};

// Out of the class body, so that they are not inline: an explicit instantiation declaration
// (certipose::precompiled, detail/precompiled.hpp) then keeps a user's translation unit from
// compiling them again.

template <class Policies>
auto pose_solver<Policies>::solve(std::size_t facet_index, const solve_options& options) const -> result_type {
    options.validate();
    using clock = std::chrono::steady_clock;
    const auto start = clock::now();
    const facet& f = part_->facet(facet_index);  // throws out_of_range("facet", ...)
    const position_problem problem{f, range_, task_};

    result_type out;
    out.facet_index = facet_index;
    solve_stats& st = out.stats;
    st.occlusion_checked = checks_occlusion<occlusion_type>;
    std::optional<clock::time_point> deadline;
    if (options.time_limit) deadline = start + *options.time_limit;
    const auto seconds = [&] { return std::chrono::duration<double>(clock::now() - start).count(); };
    // Cancelled or past the deadline: the orientation groups and growth stop on it (the
    // orientation loop below tells the two apart for solve_stats::reason).
    const auto out_of_time = [&] { return options.stop.stop_requested() || (deadline && clock::now() >= *deadline); };

    // ---- stage 1: positions -----------------------------------------------------------------
    // With refinement the stage paves at ε_p, then refines its BOUNDARY boxes down to the
    // refinement's width, largest first, until its own deadline; that deadline is not the
    // run's: the orientation stage still follows.
    const double split_width = options.refine ? options.refine->width(options.position_eps) : options.position_eps;
    std::optional<clock::time_point> refine_deadline;
    if (options.refine) {
        if (options.refine->time_limit)
            refine_deadline = start + *options.refine->time_limit;
        else if (options.time_limit)
            refine_deadline = start + *options.time_limit / 4;  // see refinement::time_limit
    }
    paver_options popt;
    popt.max_boxes = options.max_boxes;
    popt.deadline = deadline;
    popt.record_tree = options.keep_tree;
    if (options.progress) {
        popt.progress_every = 256;
        popt.progress = [&](const paver_stats& s) {
            return options.progress(solve_progress{"position", s.boxes, s.pending, 0, 0, seconds()});
        };
    }
    const position_stage_options stage_options{.inner_contraction = options.inner_contraction,
                                               .occlusion_cuts = options.occlusion_cuts,
                                               .leaf_corner_boxes = options.leaf_corner_boxes,
                                               .corner_depth = options.corner_depth,
                                               .corner_rest_min_pieces = options.corner_rest_min_pieces};
    std::optional<position_refinement> refinement;
    if (options.refine) refinement = position_refinement{split_width, refine_deadline};
    auto stage1 = pave_positions<I, constraint_set_type, contraction_type, bisector_type, buffer_type>(
        problem, facet_index, occlusion_, popt, options.position_eps, options.stop, constraint_parameters_, stage_options,
        refinement);
    const auto& ps = stage1.boxes.stats;
    st.contractions = stage1.counters.contractions;
    st.bisections = ps.bisections;
    st.occlusion_tests = stage1.counters.occlusion_tests;
    st.shadow_walks = stage1.counters.shadow_walks;
    st.inner_pieces = stage1.counters.inner_pieces;
    st.occlusion_pieces = stage1.counters.occlusion_pieces;
    st.corner_boxes = stage1.counters.corner_boxes;
    st.position_valid = stage1.boxes.valid.size();
    st.position_boundary = stage1.boxes.boundary.size() + stage1.boxes.pending.size();
    st.reason = ps.reason;
    st.refinement_stopped = stage1.refinement_stopped;
    st.refinement_passes = stage1.counters.refinement_passes;
    st.seconds_position = seconds();
    if (options.keep_tree) out.tree = std::move(stage1.boxes.tree);

    // At least one box per position box (VALID or BOUNDARY; bisections add more): growing the
    // vector as it filled copied it and touched twice its pages (7 % of a plate_holes run).
    out.boxes.reserve(stage1.boxes.boundary.size() + stage1.boxes.pending.size() + stage1.boxes.valid.size());
    for (std::size_t i = 0; i < stage1.boxes.boundary.size(); ++i)
        push_boundary(out, stage1.boxes.boundary[i], stage1.boundary_reasons[i]);
    for (const auto& b : stage1.boxes.pending) push_boundary(out, b, boundary_reason::budget);

    // ---- stage 2: orientations (Algorithm 3 lines 28–36) --------------------------------------
    // After a box budget the certified position boxes are still oriented, each once (no more
    // bisection); a deadline or cancellation (`halted`) leaves the rest undecided.
    // Not below ε_p in the paper's paving. When refining, down to ε_p / 4: a position box that no
    // orientation fits at ε_p is one where the facet barely fits the image, and on angle_block
    // (1 s) such boxes held 8 % of the true valid positions, nearly all certified by two more
    // halvings (ε_p / 2 and ε_p / 8 measured the same within this machine's timing noise).
    bisector_type bisector(options.refine ? options.position_eps / 4 : options.position_eps);  // may be stateful (round_robin)
    // Pieces carved off one box and halves of a refined leaf often tile a larger box: merged
    // back, they need fewer orientation searches and give a wider installation tolerance.
    const bool past_paper = options.inner_contraction || options.occlusion_cuts || options.leaf_corner_boxes;
    if (past_paper) st.position_merges = detail::growth::merge_touching_positions(stage1.boxes.valid, options.position_eps);
    std::size_t done = ps.boxes;
    bool halted = st.reason == termination::deadline || st.reason == termination::cancelled;
    std::vector<position_box<I>> todo;
    todo.reserve(stage1.boxes.valid.size());
    using cell_key = std::array<long long, 3>;
    const auto cell_of = [&](const position_box<I>& p) {
        cell_key key{};
        for (std::size_t k = 0; k < 3; ++k) key[k] = detail::growth::cell_index(mid(p[k]), options.position_eps);
        return key;
    };
    // The orientation search of a box, starting from what the searches in its cell of ε_p found
    // (HintedOrientationPolicy; the hint changes how fast a box is found, not its proof).
    using hint_type = typename detail::orientation_hint_of<orientation_type, I, camera_type>::type;
    std::map<cell_key, hint_type> hints;
    // Cells where a search of their own certified (their hints are worth lending), and a box
    // whose own search failed in a cell where none did yet borrows its neighbours' hints
    // (BorrowingOrientationPolicy). Not in the paper's paving, nor for a group's hull: a hull
    // oriented with a borrowed scale would give its members that scale instead of their own
    // searches' (wider on idler_riser and featuretype). What is borrowed is not kept: the next
    // box of the cell searches for itself.
    std::set<cell_key> oriented;
    const auto orient = [&](const position_box<I>& p, bool single) {
        if constexpr (HintedOrientationPolicy<orientation_type, I, camera_type>) {
            const cell_key key = cell_of(p);
            orientation_result<I> o = orientation_.orient(p, f, camera_, options.orientation_eps, hints[key]);
            if (!o.boxes.empty()) {
                oriented.insert(key);
                return o;
            }
            if constexpr (BorrowingOrientationPolicy<orientation_type, I, camera_type>) {
                if (single && past_paper && !oriented.contains(key)) {
                    std::array<const hint_type*, 26> lent{};
                    std::size_t n = 0;
                    for (long long dx = -1; dx <= 1; ++dx)
                        for (long long dy = -1; dy <= 1; ++dy)
                            for (long long dz = -1; dz <= 1; ++dz) {
                                const cell_key k{key[0] + dx, key[1] + dy, key[2] + dz};
                                if (k != key && oriented.contains(k)) lent[n++] = &hints.at(k);
                            }
                    if (n > 0) {
                        orientation_result<I> b = orientation_.orient_borrowed(
                            p, f, camera_, options.orientation_eps, std::span<const hint_type* const>(lent.data(), n));
                        b.certifications += o.certifications;
                        if (!b.boxes.empty()) ++st.orientation_borrowed;
                        return b;
                    }
                }
            }
            return o;
        } else {
            return orientation_.orient(p, f, camera_, options.orientation_eps);
        }
    };
    {
        // Small position boxes in one cell of ε_p (pieces, corner boxes, refined leaves) are
        // oriented together first: an orientation certified over their hull holds for each
        // (constraint 5 over a position box holds over every box inside it). Cells whose hull
        // cannot be oriented are split (below) before falling back to one search per box.
        std::map<cell_key, std::vector<std::size_t>> cells;
        const auto& valid = stage1.boxes.valid;
        for (std::size_t i = 0; i < valid.size(); ++i) cells[cell_of(valid[i])].push_back(i);
        // Largest position volume first, in groups and one by one: a run that a deadline stops
        // in this stage (refinement hands it many small boxes) has certified the most it could.
        std::vector<std::pair<double, const std::vector<std::size_t>*>> by_volume;
        for (const auto& [key, members] : cells) {
            double v = 0;
            for (std::size_t i : members) v += volume(valid[i]);
            by_volume.emplace_back(v, &members);
        }
        std::stable_sort(by_volume.begin(), by_volume.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
        // A cell whose hull no orientation fits is split in two across the hull's widest side
        // (at the median member) and each half tried as a group, down to groups of
        // `min_group`; what is left goes one box at a time. Refined leaves and corner
        // staircases fill a cell with many boxes, most of which share an orientation with
        // their neighbours even when the whole cell does not.
        constexpr std::size_t min_group = 4;
        const auto orient_group = [&](auto& self, std::span<std::size_t> members) -> void {
            if (members.size() < 2 || !past_paper || halted || out_of_time()) {
                for (std::size_t i : members) todo.push_back(valid[i]);
                return;
            }
            position_box<I> h = valid[members[0]];
            for (std::size_t i : members) h = hull(h, valid[i]);
            ++done;
            const orientation_result<I> o = orient(h, false);
            st.orientation_certifications += o.certifications;
            if (!o.boxes.empty()) {
                ++st.orientation_groups;
                for (std::size_t i : members) {
                    for (const auto& e : o.boxes) {
                        out.boxes.push_back(classified_box<I>{box_class::valid, pose_box<I>{valid[i], e}});
                        ++st.valid;
                    }
                    st.valid_volume += volume(valid[i]);
                }
                return;
            }
            if (members.size() < 2 * min_group) {
                for (std::size_t i : members) todo.push_back(valid[i]);
                return;
            }
            const std::size_t k = widest_dimension(h);
            const auto half = members.begin() + static_cast<std::ptrdiff_t>(members.size() / 2);
            std::nth_element(members.begin(), half, members.end(),
                             [&](std::size_t a, std::size_t b) { return mid(valid[a][k]) < mid(valid[b][k]); });
            self(self, members.first(members.size() / 2));
            self(self, members.subspan(members.size() / 2));
        };
        for (auto& [cell_volume, members_ptr] : by_volume) {
            std::vector<std::size_t> members = *members_ptr;
            orient_group(orient_group, members);
        }
        // Popped from the back: largest first (ties in cell order).
        std::reverse(todo.begin(), todo.end());
        std::stable_sort(todo.begin(), todo.end(), [](const auto& a, const auto& b) { return volume(a) < volume(b); });
    }
    while (!todo.empty()) {
        if (!halted) {
            if (options.stop.stop_requested()) {
                st.reason = termination::cancelled, halted = true;
            } else if (deadline && clock::now() >= *deadline) {
                st.reason = termination::deadline, halted = true;
            } else if (options.progress && done % 64 == 0 &&
                       !options.progress(solve_progress{"orientation", done, todo.size(), st.valid, st.boundary,
                                                        seconds()})) {
                st.reason = termination::cancelled, halted = true;
            } else if (st.reason == termination::completed && done >= options.max_boxes) {
                st.reason = termination::box_budget;
            }
        }
        position_box<I> p = std::move(todo.back());
        todo.pop_back();
        if (halted) {
            push_boundary(out, p, boundary_reason::budget);
            continue;
        }
        ++done;
        const orientation_result<I> o = orient(p, true);
        st.orientation_certifications += o.certifications;
        if (!o.boxes.empty()) {
            for (const auto& e : o.boxes) {
                out.boxes.push_back(classified_box<I>{box_class::valid, pose_box<I>{p, e}});
                ++st.valid;
            }
            st.valid_volume += volume(p);
            continue;
        }
        if (st.reason != termination::completed) {  // a budget forbids bisecting further
            push_boundary(out, p, boundary_reason::budget);
            continue;
        }
        const std::optional<split> s = bisector.choose(p);
        if (!s) {
            push_boundary(out, p, boundary_reason::field_of_view);
            continue;
        }
        ++st.bisections;
        auto [left, right] = bisect_at(p, s->dimension, s->point);
        todo.push_back(std::move(right));
        todo.push_back(std::move(left));
    }
    st.seconds_orientation = seconds() - st.seconds_position;

    // ---- past the paper: wider boxes (the installation tolerance) ------------------------------
    if (options.grow && st.valid > 0) {
        auto ok = certifier(facet_index);
        std::vector<pose_box<I>> valid;
        std::vector<classified_box<I>> rest;
        for (auto& b : out.boxes) {
            if (b.cls == box_class::valid) valid.push_back(b.box);
            else rest.push_back(std::move(b));
        }
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
        st.seconds_growth = seconds() - st.seconds_position - st.seconds_orientation;
    }
    st.seconds = seconds();
    return out;
}

template <class Policies>
auto pose_solver<Policies>::certifier(std::size_t facet_index) const -> certifier_type {
    const facet& f = part_->facet(facet_index);  // throws out_of_range("facet", ...)
    return certifier_type(make_constraint_set<constraint_set_type>(position_problem{f, range_, task_}, constraint_parameters_),
                          occlusion_, facet_index, f, fov_frustum<I>(camera_));
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

template <class Policies>
void pose_solver<Policies>::push_boundary(result_type& out, const position_box<I>& p, boundary_reason why) {
    const rounding_guard<I> rounding;
    const double pi_hi = std::nextafter(std::numbers::pi, 4.0);
    const orientation_box<I> all = orientation_box<I>::from_bounds({{{-pi_hi, pi_hi}, {0.0, pi_hi}, {-pi_hi, pi_hi}}});
    out.boxes.push_back(classified_box<I>{box_class::boundary, pose_box<I>{p, all}, why});
    ++out.stats.boundary;
    out.stats.boundary_volume += volume(p);
    ++out.stats.boundary_reasons[static_cast<std::size_t>(why)];
}

}  // namespace certipose
