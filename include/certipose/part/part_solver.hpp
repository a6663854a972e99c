// certipose/part/part_solver.hpp — every facet of a part (or a selection), solved in parallel
// with oneTBB over one shared pose_solver, and streamed to a sink in facet order.
//
//   certipose::part_solver<> part(mesh, camera, {.min_view_angle = 0.35});
//   my_sink sink;                                     // sink.facet(const facet_outcome<I>&)
//   const certipose::part_result r = part.solve({.facet = {.position_eps = 0.1}}, sink);
//
// One pose_solver (and so one occlusion scene) serves every facet: its `solve` is const and
// thread-safe. Facets run as the stages of a tbb::parallel_pipeline: facet indices are issued in
// order, solved in parallel, and handed to the sink by a serial in-order stage, so the sink sees
// the same facets, boxes and order whatever the thread count (runs bounded by boxes, not time,
// are deterministic), and at most `in_flight` facets' boxes exist at once: memory is bounded by
// the threads, not by the part.
//
// `solve` is three named parts that a reader checks against docs/part.md ("The steps of a part
// run"): a part_schedule (the selection, the run's budgets, stop and progress, and the order
// results reach the sink: part/scheduler.hpp, shared with solve_part_mpi), the facet steps of one
// work item (screen, reuse, solve, regions, keep largest: part/facet_steps.hpp), and
// run_in_order, the oneTBB pipeline between them.
//
// Before paving, a facet that provably no pose can inspect is skipped with the reason
// (`uninspectable`): the facet cannot fit in the image from any distance ≤ d_max, no position
// satisfies the distance, backface and viewing-angle constraints, or the occlusion policy proves
// the whole search box occluded, or (a triangle soup, occlusion/mesh_survey.hpp) the facet is
// buried in another body, covered by one, or repeats an earlier facet. These are certificates,
// like OCCLUDED: a skipped facet would have had no VALID box (a duplicate has its original's).
//
// Reuse between translates (`part_options::reuse`, part/translates.hpp): a facet nothing can
// occlude that is a translate of another such facet takes the boxes of its group's first one (by
// index in the whole part), each VALID box proven again for it, instead of being paved. The
// first one is solved once, by whichever worker needs it first, and its boxes are kept until the
// group's last selected facet is done; the choice does not depend on the selection or the
// threads, so neither do a facet's boxes.
//
// Camera regions (`part_options::regions`, solver/camera_regions.hpp): each facet's result is
// restricted to the allowed camera positions in its worker, right after its solve, so the
// record's counts, the sink's boxes and the run's totals are all of the restricted result.
//
// Budgets: per facet, `facet.max_boxes` and `facet.time_limit` (a facet that hits them keeps its
// VALID boxes, pose_solver.hpp); for the run, `max_boxes` (checked in facet order, so the set of
// facets finished is deterministic), `time_limit`, `stop` and the progress callback (return
// false to cancel). A run that ends early returns the facets finished before the end, in order:
// a facet still in flight is dropped, never reported half done.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <span>
#include <stop_token>
#include <string>
#include <tuple>
#include <utility>
#include <vector>


#include "certipose/error.hpp"
#include "certipose/part/facet_steps.hpp"
#include "certipose/part/part_run.hpp"
#include "certipose/part/scheduler.hpp"
#include "certipose/part/translates.hpp"
#include "certipose/solver/pose_solver.hpp"

namespace certipose {


/// Every facet of a part (see the header comment). The mesh must outlive the solver.
template <class Policies = default_policies>
class part_solver {
public:
    using solver_type = pose_solver<Policies>;
    using interval_type = typename solver_type::interval_type;
    using camera_type = typename solver_type::camera_type;
    using setup = typename solver_type::setup;

    part_solver(const triangle_mesh& part, camera_type camera, inspection_task task, setup s = {})
        : solver_(part, std::move(camera), task, std::move(s)) {}
    part_solver(const triangle_mesh&& part, camera_type camera, inspection_task task, setup s = {}) = delete;

    const solver_type& solver() const noexcept { return solver_; }

    /// Why no pose can inspect facet `f`, when that is provable cheaply; nothing otherwise.
    std::optional<std::string> uninspectable(std::size_t f) const;

    /// A cheap measure of how much paving facet `f` needs, for progress estimates only: the
    /// volume (m³) of its search box contracted by constraints 1–4, which bounds where its boxes
    /// can be (a few µs). 0 when that box is empty or the occlusion hides the facet.
    double work_estimate(std::size_t f) const;

    /// Solves the selected facets and hands each to `sink`, in order (see the header comment).
    /// Throws invalid_argument for bad options and out_of_range for a facet index not in the part.
    // Constrained on Policies::interval, spelled the same here and at the definition: clang 14
    // does not match `PartSink<interval_type>` with its out-of-line spelling.
    template <PartSink<typename Policies::interval> Sink>
    part_result solve(const part_options& options, Sink& sink) const;

    /// The largest diameter of a patch under `options` (metres): its max_extent, or when 0 a
    /// quarter of the narrower side of the image at d_min.
    double patch_extent(const patch_options& options) const {
        if (options.max_extent > 0) return options.max_extent;
        const fov_half_angles fov = solver_.camera().fov_half_angles();
        return 0.25 * 2.0 * solver_.range().min * std::tan(std::min(fov.horizontal, fov.vertical));
    }

    /// The patch regions of the whole part a run with `options` groups its facets by (null: it
    /// solves facet by facet: patches off, or a run that keeps BOUNDARY boxes, part_run.hpp).
    /// Regions of the whole part, so that a facet's boxes do not depend on the selection; kept
    /// for the next run with the same patch options (an MPI rank solves many chunks).
    std::shared_ptr<const patch_regions> patches(const part_options& options) const {
        if (!options.patches.enabled || options.keep_boundary) return nullptr;
        const patch_options& p = options.patches;
        const std::lock_guard lock(regions_->mutex);
        auto& c = regions_->last;
        if (!(c.regions && c.options.max_cone == p.max_cone && c.options.max_extent == p.max_extent &&
              c.options.max_members == p.max_members && c.options.faces == p.faces)) {
            c.options = p;
            c.regions = std::make_shared<const patch_regions>(patch_regions::grow(solver_.part(), p, patch_extent(p)));
        }
        return c.regions;
    }

    /// Facet `f` is open (part/translates.hpp): inspectable, and every sight line to it from a
    /// position of its search box in front of it is free — the occlusion policy's `front_clear`
    /// when it has one, else its VISIBLE over the box. The box is returned (nothing otherwise):
    /// what the reuse step (part/facet_steps.hpp) may move a translate's boxes into.
    std::optional<position_box<interval_type>> open_box(std::size_t f) const;

    /// The part's translate groups (part/translates.hpp), built by the first run that reuses
    /// (copies of this solver share them).
    const translate_groups& translates() const {
        std::call_once(groups_->once, [&] { groups_->groups = translate_groups::of(solver_.part()); });
        return groups_->groups;
    }

private:
    /// Facet `f`'s search box contracted by constraints 1–4 (empty: no position satisfies them):
    /// what `uninspectable` proves on and `work_estimate` measures.
    position_box<interval_type> search_box(std::size_t f) const {
        auto set = make_constraint_set<typename solver_type::constraint_set_type>(
            position_problem{solver_.part().facet(f), solver_.range(), solver_.task()}, solver_.constraints());
        return set.initial_box();
    }

    solver_type solver_;
    struct lazy_groups {
        std::once_flag once;
        translate_groups groups;
    };
    std::shared_ptr<lazy_groups> groups_ = std::make_shared<lazy_groups>();
    struct cached_regions {
        std::mutex mutex;
        struct {
            patch_options options;
            std::shared_ptr<const patch_regions> regions;
        } last;
    };
    std::shared_ptr<cached_regions> regions_ = std::make_shared<cached_regions>();
};

template <class Policies>
auto part_solver<Policies>::open_box(std::size_t f) const -> std::optional<position_box<interval_type>> {
    using I = interval_type;
    // The search box and front_clear first: a template's group is scanned in index order until
    // a member is open, and most members of most groups are not, while uninspectable searches a
    // full-effort OCCLUDED proof over the whole search box; it is asked only of open facets.
    position_box<I> box = search_box(f);
    if (is_empty(box)) return std::nullopt;
    using O = typename solver_type::occlusion_type;
    if constexpr (requires(const O& o) {
                      { o.front_clear(box, f) } -> std::same_as<bool>;
                  }) {
        if (!solver_.occlusion().front_clear(box, f)) return std::nullopt;
    } else if constexpr (checks_occlusion<O>) {
        visibility seen;
        if constexpr (EffortAwareOcclusionPolicy<O, I>)
            seen = solver_.occlusion().classify(box, f, occlusion_effort::visible_only);
        else
            seen = solver_.occlusion().classify(box, f);
        if (seen != visibility::visible) return std::nullopt;
    }
    if (uninspectable(f)) return std::nullopt;
    return box;
}

template <class Policies>
std::optional<std::string> part_solver<Policies>::uninspectable(std::size_t index) const {
    using I = interval_type;
    // 0. The occlusion policy's survey of a triangle soup: buried, covered, a duplicate.
    if constexpr (requires(const typename solver_type::occlusion_type& o) {
                      { o.hidden(index) } -> std::same_as<std::optional<std::string>>;
                  })
        if (auto why = solver_.occlusion().hidden(index)) return why;
    const facet& f = solver_.part().facet(index);
    const distance_range range = solver_.range();
    // 1. Too large for the image: two points seen from p within the circumscribed cone of
    //    half-angle α (every ray through the image) are at most max(1, 2 sin α)·d_max apart
    //    when both are within d_max of p (law of cosines, maximised at the ends).
    {
        const fov_frustum<I> frustum(solver_.camera());
        const rounding_guard<I> rounding;
        const double alpha = frustum.outer_half_angle();
        const I reach = I(range.max) * (alpha >= std::numbers::pi / 2 ? I(2.0) : hull(I(1.0), I(2.0) * sin(I(alpha))));
        for (int a = 0; a < 3; ++a) {
            const int b = (a + 1) % 3;
            const I d2 = sqr(I(f.v[a].x()) - I(f.v[b].x())) + sqr(I(f.v[a].y()) - I(f.v[b].y())) +
                         sqr(I(f.v[a].z()) - I(f.v[b].z()));
            if (lower(d2) > upper(sqr(reach)))
                return "larger than the image can hold from any distance up to d_max (edge " +
                       detail::format_double(std::sqrt(lower(d2))) + " m, at most " +
                       detail::format_double(upper(reach)) + " m fits)";
        }
    }
    // 2. No position satisfies constraints 1–4: the set contracts its search box to nothing.
    const position_box<I> box = search_box(index);
    if (is_empty(box)) return "no position satisfies the distance, backface and viewing-angle constraints";
    // 3. The occlusion policy proves every sight line from the whole search box blocked.
    if (checks_occlusion<typename solver_type::occlusion_type> &&
        solver_.occlusion().classify(box, index) == visibility::occluded)
        return "occluded from every position within d_max";
    return std::nullopt;
}

template <class Policies>
double part_solver<Policies>::work_estimate(std::size_t index) const {
    if constexpr (requires(const typename solver_type::occlusion_type& o) {
                      { o.hidden(index) } -> std::same_as<std::optional<std::string>>;
                  })
        if (solver_.occlusion().hidden(index)) return 0.0;
    const position_box<interval_type> box = search_box(index);
    if (is_empty(box)) return 0.0;
    double v = 1.0;
    for (std::size_t d = 0; d < 3; ++d) v *= upper(box[d]) - lower(box[d]);
    return std::isfinite(v) ? v : 0.0;
}

template <class Policies>
template <PartSink<typename Policies::interval> Sink>
part_result part_solver<Policies>::solve(const part_options& options, Sink& sink) const {
    options.facet.validate();
    options.regions.validate();
    options.reuse.validate();
    options.patches.validate(solver_.part().num_faces());
    const std::shared_ptr<const patch_regions> regions = patches(options);
    part_schedule schedule(options, solver_.part().num_faces(), [&](std::size_t f) { return work_estimate(f); }, regions.get());
    facet_steps<part_solver> steps(*this, options, schedule);  // screen, reuse, solve, regions, keep largest
    return run_in_order<interval_type>(schedule, options, steps, sink);
}

}  // namespace certipose
