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

#include <oneapi/tbb/info.h>
#include <oneapi/tbb/parallel_pipeline.h>
#include <oneapi/tbb/task_arena.h>

#include "certipose/error.hpp"
#include "certipose/orientation/certify.hpp"
#include "certipose/part/translates.hpp"
#include "certipose/solver/camera_regions.hpp"
#include "certipose/solver/keep_largest.hpp"
#include "certipose/solver/pose_solver.hpp"

namespace certipose {

/// How a facet's run ended in a part run (summary.json "termination").
enum class facet_termination : std::uint8_t { completed, box_budget, deadline, cancelled, skipped };

constexpr const char* to_string(facet_termination t) noexcept {
    switch (t) {
        case facet_termination::completed: return "completed";
        case facet_termination::box_budget: return "box_budget";
        case facet_termination::deadline: return "deadline";
        case facet_termination::cancelled: return "cancelled";
        case facet_termination::skipped: return "skipped";
    }
    return "?";
}

/// What the summary keeps of one facet (boxes go to the sink, not here).
struct facet_record {
    std::size_t index = 0;
    std::size_t valid = 0, boundary = 0;
    double seconds = 0.0;
    facet_termination termination = facet_termination::completed;
    std::string reason;  ///< why it was skipped (empty otherwise)
    std::size_t dropped = 0;  ///< VALID boxes found but not kept (part_options::keep_largest)
    /// The translate whose boxes this facet's are, proven again (part_options::reuse); nothing
    /// when the facet was paved on its own.
    std::optional<std::size_t> reused_from{};
    std::array<std::size_t, boundary_reason_count> boundary_reasons{};
};

/// One finished facet as the sink receives it: its record and its boxes (VALID, and BOUNDARY
/// when part_options::keep_boundary).
template <Interval I>
struct facet_outcome {
    facet_record record;
    std::vector<classified_box<I>> boxes;
};

/// A sink: `sink.facet(outcome)`, called in facet order from one thread at a time.
template <class S, class I>
concept PartSink = requires(S& s, const facet_outcome<I>& o) { s.facet(o); };

/// Progress of a part run, reported after each facet.
struct part_progress {
    std::size_t facets_done = 0, facets_total = 0;
    std::size_t valid = 0, boundary = 0;  ///< boxes so far
    double seconds = 0.0;                 ///< elapsed
    /// Estimate: elapsed × (work left / work done), each facet's work estimated by
    /// `part_solver::work_estimate` (a run's facets come in file order, and CAD exports list
    /// cheap and costly surfaces in runs, so counting facets alone misleads; docs/part.md has
    /// the figures).
    double seconds_left = 0.0;
};

/// Settings of a part run.
struct part_options {
    /// Per facet: ε_p, ε_o, the per-facet box budget and time limit (its progress and stop are
    /// ignored: the run has its own).
    solve_options facet{};
    /// Facets to solve, in this order; empty: all of the part.
    std::vector<std::size_t> facets{};
    /// Worker threads; 0: every core (oneTBB's default).
    std::size_t threads = 0;
    /// Also hand BOUNDARY boxes to the sink.
    bool keep_boundary = false;
    /// Where the camera may stand: each facet's VALID boxes are restricted to these regions
    /// (solver/camera_regions.hpp) before the record is made and the sink sees them.
    camera_regions regions{};
    /// Keep only the K largest VALID boxes of each facet (solver/keep_largest.hpp), after the
    /// regions; the record counts the kept ones and the dropped ones apart.
    std::optional<std::size_t> keep_largest{};
    /// Skip facets provably uninspectable before paving them (see the header comment).
    bool skip_uninspectable = true;
    /// The reuse stage: an open facet takes a translate's boxes, each proven again for it
    /// (part/translates.hpp), instead of being paved (see the header comment).
    reuse_options reuse{};
    /// Whole run: boxes processed (sum over facets, in facet order), wall time.
    std::optional<std::size_t> max_boxes{};
    std::optional<std::chrono::steady_clock::duration> time_limit{};
    /// Called after each facet, from the sink's thread; return false to cancel.
    std::function<bool(const part_progress&)> progress{};
    std::stop_token stop{};
    /// Facets solved or waiting for the sink at once (0: 4 per thread): bounds memory.
    std::size_t in_flight = 0;
};

/// What a part run returns: one record per finished facet, in order, and the totals.
struct part_result {
    std::vector<facet_record> facets;
    std::size_t facets_selected = 0;
    std::size_t valid = 0, boundary = 0, skipped = 0;
    std::size_t reused = 0;  ///< facets whose boxes are a translate's, proven again (part_options::reuse)
    double seconds = 0.0;
    std::size_t threads = 0;
    /// The most facets whose boxes existed at once (solving, or waiting for the sink): what
    /// bounds the run's memory, at most part_options::in_flight.
    std::size_t peak_in_flight = 0;
    termination reason = termination::completed;  ///< why the run ended
};

/// A sink that keeps everything (small parts, tests): the outcomes in facet order.
template <Interval I>
struct collecting_sink {
    std::vector<facet_outcome<I>> outcomes;
    void facet(const facet_outcome<I>& o) { outcomes.push_back(o); }
};

/// A sink that hands each finished facet to every sink it points to, in turn (a null pointer is
/// skipped): e.g. boxes.jsonl and boxes.cpbx written from one run.
template <class... Sinks>
struct tee_sink {
    std::tuple<Sinks*...> sinks;
    template <class Outcome>
    void facet(const Outcome& o) {
        std::apply([&](auto*... s) { ((s ? s->facet(o) : void()), ...); }, sinks);
    }
};

namespace detail {

/// The progress estimate of a run (part_progress::seconds_left): each selected facet's share
/// of the work from part_solver::work_estimate, floored at a twentieth of the mean so that
/// facets skipped or hidden still count as a little work.
struct work_meter {
    std::vector<double> cumulative;  ///< work of the first i + 1 facets of the selection

    work_meter() = default;
    template <class Part>
    work_meter(const Part& part, const std::vector<std::size_t>& selection) : cumulative(selection.size()) {
        double mean = 0.0;
        for (std::size_t i = 0; i < selection.size(); ++i) mean += cumulative[i] = part.work_estimate(selection[i]);
        mean /= static_cast<double>(std::max<std::size_t>(selection.size(), 1));
        double sum = 0.0;
        for (double& w : cumulative) w = sum += std::max(w, 0.05 * mean + 1e-300);
    }
    /// Seconds left after the first `done` facets took `elapsed` seconds.
    double seconds_left(std::size_t done, double elapsed) const {
        if (done == 0 || done >= cumulative.size()) return 0.0;
        const double finished = cumulative[done - 1];
        return finished > 0.0 ? elapsed * (cumulative.back() - finished) / finished : 0.0;
    }
};

}  // namespace detail

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

private:
    /// Facet `f`'s search box contracted by constraints 1–4 (empty: no position satisfies them):
    /// what `uninspectable` proves on and `work_estimate` measures.
    position_box<interval_type> search_box(std::size_t f) const {
        auto set = make_constraint_set<typename solver_type::constraint_set_type>(
            position_problem{solver_.part().facet(f), solver_.range(), solver_.task()}, solver_.constraints());
        return set.initial_box();
    }

    /// Facet `f` is open (part/translates.hpp): inspectable, and every sight line to it from a
    /// position of `search_box(f)` in front of it is free — the occlusion policy's `front_clear`
    /// when it has one, else its VISIBLE over the box. The box is returned (nothing otherwise).
    std::optional<position_box<interval_type>> open_box(std::size_t f) const;

    /// The part's translate groups, built by the first run that reuses (copies share them).
    const translate_groups& groups() const {
        std::call_once(groups_->once, [&] { groups_->groups = translate_groups::of(solver_.part()); });
        return groups_->groups;
    }

    solver_type solver_;
    struct lazy_groups {
        std::once_flag once;
        translate_groups groups;
    };
    std::shared_ptr<lazy_groups> groups_ = std::make_shared<lazy_groups>();
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
    using I = interval_type;
    using clock = std::chrono::steady_clock;
    options.facet.validate();
    options.regions.validate();
    options.reuse.validate();
    const std::size_t n = solver_.part().num_faces();
    std::vector<std::size_t> selection = options.facets;
    if (selection.empty()) {
        selection.resize(n);
        for (std::size_t i = 0; i < n; ++i) selection[i] = i;
    }
    for (std::size_t f : selection)
        if (f >= n) throw out_of_range("facet", f, n);
    if (options.max_boxes && *options.max_boxes == 0)
        throw invalid_argument("max_boxes", "part_solver: the run's max_boxes must be at least 1");

    const std::size_t threads =
        options.threads ? options.threads : static_cast<std::size_t>(oneapi::tbb::info::default_concurrency());
    detail::work_meter meter;
    if (options.progress) meter = detail::work_meter(*this, selection);
    const std::size_t tokens = options.in_flight ? options.in_flight : 4 * threads;
    const auto start = clock::now();
    std::optional<clock::time_point> deadline;
    if (options.time_limit) deadline = start + *options.time_limit;
    const auto elapsed = [&] { return std::chrono::duration<double>(clock::now() - start).count(); };

    // Stopping: the user's token, the progress callback, the run's budgets. Facets already in
    // flight see the stop through their own token and are dropped, not reported.
    std::stop_source halt;
    std::stop_callback forward(options.stop, [&] { halt.request_stop(); });
    std::atomic<int> why{static_cast<int>(termination::completed)};
    const auto stop_run = [&](termination t) {
        int expected = static_cast<int>(termination::completed);
        why.compare_exchange_strong(expected, static_cast<int>(t));
        halt.request_stop();
    };

    struct item {
        std::size_t index = 0;
        bool dropped = false;
        facet_outcome<I> outcome;
    };

    std::atomic<std::size_t> live{0}, peak{0};
    const auto enter = [&] {
        const std::size_t now = ++live;
        for (std::size_t p = peak.load(); now > p && !peak.compare_exchange_weak(p, now);) {}
    };

    part_result out;
    out.facets_selected = selection.size();
    out.threads = threads;
    out.facets.reserve(selection.size());
    std::size_t next = 0, boxes_total = 0;
    // The serial stages never run at once and TBB orders every hand-over between stages, but
    // with synchronisation ThreadSanitizer cannot see (libtbb is not instrumented), so it would
    // flag the sink, the totals and each item as races. Every stage passes through this mutex
    // when it starts and when it ends (held for nothing, never while the sink or the solver
    // runs; ~20 ns per facet): that makes the order TBB already guarantees visible, and a TSan
    // run reports only races of our own.
    std::mutex handoff;
    const auto sync = [&] { const std::lock_guard visible{handoff}; };
    struct sync_on_exit {
        const decltype(sync)& f;
        ~sync_on_exit() { f(); }
    };

    // The reuse stage (part/translates.hpp). Per group of translates: its template, the first
    // open member by index in the whole part (found once, by whichever worker asks first), and
    // the template's result, solved once and kept until every selected member of the group is
    // done. Without a translate group, or with a placement tolerance (whose proofs are per
    // placement, placement_stage.hpp), every facet is paved on its own.
    struct template_slot {
        std::once_flag found, solved;
        std::optional<std::size_t> facet;  ///< the template (nothing: no member is open)
        std::optional<solve_result<I>> result;
        std::atomic<std::size_t> users{0};  ///< selected members not done yet
    };
    const bool reusing = options.reuse.translates && solver_.placement_proofs() == nullptr;
    const translate_groups* groups_of = reusing ? &groups() : nullptr;
    std::vector<std::unique_ptr<template_slot>> slots;
    if (groups_of) {
        slots.resize(groups_of->members.size());
        for (std::size_t f : selection)
            if (const auto g = groups_of->shared_group(f)) {
                if (!slots[*g]) slots[*g] = std::make_unique<template_slot>();
                ++slots[*g]->users;
            }
    }
    // What one proof of constraint 5 may take: the orientation policy's own budget when it has
    // one (so that what it proved can be proven again), else paper_orientation's default.
    const std::size_t tiling_budget = [&]() -> std::size_t {
        if constexpr (requires { solver_.orientation().options().tiling_budget; })
            return solver_.orientation().options().tiling_budget;
        else
            return paper_orientation_options{}.tiling_budget;
    }();
    // Facet f's boxes as a translate's, proven again; nothing when it has no open translate, or
    // the template's boxes not proven for f hold more than reuse.max_loss of its VALID volume.
    // `fo` solves the template when f asks first.
    const auto reuse_for = [&](std::size_t f, const solve_options& fo,
                               std::optional<std::size_t>& from_facet) -> std::optional<solve_result<I>> {
        const auto g = groups_of ? groups_of->shared_group(f) : std::nullopt;
        if (!g) return std::nullopt;
        template_slot& slot = *slots[*g];
        std::call_once(slot.found, [&] {
            for (std::size_t m : groups_of->members[*g])
                if (open_box(m)) {
                    slot.facet = m;
                    return;
                }
        });
        if (!slot.facet) return std::nullopt;
        const std::size_t t = *slot.facet;
        std::optional<position_box<I>> search;
        if (t != f && !(search = open_box(f))) return std::nullopt;
        std::call_once(slot.solved, [&] {
            slot.result = solver_.solve(t, fo);
            if (!options.keep_boundary)  // BOUNDARY boxes are only counted: the stats keep them
                std::erase_if(slot.result->boxes, [](const classified_box<I>& b) { return b.cls != box_class::valid; });
        });
        const solve_result<I>& from = *slot.result;
        if (t == f) return from;
        if (from.stats.reason != termination::completed) return std::nullopt;
        const auto t0 = clock::now();
        const facet& target = solver_.part().facet(f);
        auto set = make_constraint_set<typename solver_type::constraint_set_type>(
            position_problem{target, solver_.range(), solver_.task()}, solver_.constraints());
        auto moved = certify_translated<decltype(set), I>(set, *search, target, fov_frustum<I>(solver_.camera()), from.boxes,
                                                         target.centroid - solver_.part().facet(t).centroid,
                                                         options.keep_boundary, tiling_budget, options.reuse.max_loss);
        if (!moved) return std::nullopt;
        solve_result<I> r;
        r.facet_index = f;
        r.stats = from.stats;
        r.stats.valid = moved->valid;
        r.stats.boundary += moved->unproven;
        for (std::size_t k = 0; k < boundary_reason_count; ++k) r.stats.boundary_reasons[k] += moved->unproven_reasons[k];
        r.boxes = std::move(moved->boxes);
        if (moved->unproven > 0) {  // the positions the unproven boxes held alone are no longer certified
            std::set<std::array<double, 6>> seen;
            r.stats.valid_volume = 0;
            for (const auto& b : r.boxes) {
                const auto& p = b.box.position;
                if (b.cls == box_class::valid &&
                    seen.insert({lower(p[0]), upper(p[0]), lower(p[1]), upper(p[1]), lower(p[2]), upper(p[2])}).second)
                    r.stats.valid_volume += volume(p);
            }
        }
        r.stats.seconds = std::chrono::duration<double>(clock::now() - t0).count();
        from_facet = t;
        return r;
    };
    const auto done_with_group = [&](std::size_t f) {
        const auto g = groups_of ? groups_of->shared_group(f) : std::nullopt;
        if (!g) return;
        template_slot& slot = *slots[*g];
        if (--slot.users == 0) slot.result.reset();  // the group's last selected member is done
    };

    // One facet, in a worker: skipped, solved, or dropped when the run ends while it is in flight.
    const auto solve_one = [&](std::size_t f) {
        enter();
        item it;
        it.index = f;
        facet_record& rec = it.outcome.record;
        rec.index = f;
        const auto t0 = clock::now();
        struct group_done_t {
            const decltype(done_with_group)& done;
            std::size_t f;
            ~group_done_t() { done(f); }
        } group_done{done_with_group, f};
        if (halt.stop_requested()) {
            it.dropped = true;
            return it;
        }
        if (options.skip_uninspectable) {
            if (auto reason = uninspectable(f)) {
                rec.termination = facet_termination::skipped;
                rec.reason = std::move(*reason);
                rec.seconds = std::chrono::duration<double>(clock::now() - t0).count();
                return it;
            }
        }
        solve_options fo = options.facet;
        fo.progress = {};
        fo.stop = halt.get_token();
        if (deadline) {
            const auto left = *deadline - clock::now();
            if (!fo.time_limit || left < *fo.time_limit) fo.time_limit = std::max(left, clock::duration(1));
        }
        std::optional<std::size_t> from;  // the translate f's boxes came from
        std::optional<solve_result<I>> reused = reuse_for(f, fo, from);
        auto r = reused ? std::move(*reused) : solver_.solve(f, fo);
        rec.reused_from = from;
        // Cut short by the run (its stop, or its deadline rather than the facet's
        // own): dropped, never reported half done.
        if (r.stats.reason == termination::cancelled ||
            (r.stats.reason == termination::deadline && deadline && clock::now() >= *deadline)) {
            it.dropped = true;
            return it;
        }
        restrict_to_regions(r, options.regions, fo.position_eps);  // nothing without regions
        if (options.keep_largest) rec.dropped = keep_largest_valid(r, *options.keep_largest);
        rec.seconds = r.stats.seconds;
        rec.valid = r.stats.valid;
        rec.boundary = r.stats.boundary;
        rec.boundary_reasons = r.stats.boundary_reasons;
        rec.termination = r.stats.reason == termination::box_budget ? facet_termination::box_budget
                          : r.stats.reason == termination::deadline ? facet_termination::deadline
                                                                    : facet_termination::completed;
        it.outcome.boxes.reserve(options.keep_boundary ? r.boxes.size() : r.stats.valid);
        for (auto& b : r.boxes)
            if (b.cls == box_class::valid || options.keep_boundary) it.outcome.boxes.push_back(std::move(b));
        return it;
    };

    oneapi::tbb::task_arena arena(static_cast<int>(threads));
    arena.execute([&] {
        oneapi::tbb::parallel_pipeline(
            tokens,
            oneapi::tbb::make_filter<void, std::size_t>(
                oneapi::tbb::filter_mode::serial_in_order,
                [&](oneapi::tbb::flow_control& fc) -> std::size_t {
                    sync();
                    const sync_on_exit done{sync};
                    if (next >= selection.size() || halt.stop_requested()) {
                        fc.stop();
                        return 0;
                    }
                    if (deadline && clock::now() >= *deadline) {
                        stop_run(termination::deadline);
                        fc.stop();
                        return 0;
                    }
                    return selection[next++];
                }) &
                oneapi::tbb::make_filter<std::size_t, item>(
                    oneapi::tbb::filter_mode::parallel,
                    [&](std::size_t f) {
                        sync();
                        item it = solve_one(f);
                        sync();
                        return it;
                    }) &
                oneapi::tbb::make_filter<item, void>(oneapi::tbb::filter_mode::serial_in_order, [&](item it) {
                    sync();
                    const sync_on_exit done{sync};
                    struct leave_t {
                        std::atomic<std::size_t>& n;
                        ~leave_t() { --n; }
                    } leave{live};
                    if (it.dropped || halt.stop_requested()) return;  // in order: nothing after a dropped facet
                    const facet_record& rec = it.outcome.record;
                    sink.facet(std::as_const(it.outcome));
                    out.valid += rec.valid;
                    out.boundary += rec.boundary;
                    out.skipped += rec.termination == facet_termination::skipped;
                    out.reused += rec.reused_from.has_value();
                    out.facets.push_back(rec);
                    boxes_total += rec.valid + rec.boundary;
                    if (options.max_boxes && boxes_total >= *options.max_boxes &&
                        out.facets.size() < selection.size())
                        stop_run(termination::box_budget);
                    if (options.progress) {
                        const double s = elapsed();
                        const std::size_t done = out.facets.size();
                        const part_progress p{done, selection.size(), out.valid, out.boundary, s,
                                              meter.seconds_left(done, s)};
                        if (!options.progress(p)) stop_run(termination::cancelled);
                    }
                }));
    });
    sync();  // what the last serial stage wrote, seen in this thread
    if (halt.stop_requested() && why.load() == static_cast<int>(termination::completed))
        why.store(static_cast<int>(termination::cancelled));  // the user's stop token
    out.reason = out.facets.size() == selection.size() ? termination::completed : static_cast<termination>(why.load());
    out.seconds = elapsed();
    out.peak_in_flight = peak.load();
    return out;
}

}  // namespace certipose
