// certipose/part/scheduler.hpp — the one scheduler of a whole-part run, for threads and MPI
// alike: the selection, the run's budgets and stop, progress, and the order in which results
// reach the sink (docs/part.md, "The steps of a part run").
//
// A run hands out *work items* (a facet, or a patch of facets: part/patches.hpp) in order, has
// them done in parallel (part_solver's facet steps, part/facet_steps.hpp), and takes the results
// back in the same order: `part_schedule::emit` gives each facet to the sink and counts it; at
// the end of each item it checks the run's box budget (in order, so the set of items finished
// does not depend on the threads) and calls the progress callback. An item reaches the sink
// whole or not at all. `run_in_order` does this with a oneTBB pipeline; solve_part_mpi
// (part/mpi.hpp) hands chunks of whole items to ranks and calls the same `emit` on rank 0.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <mutex>
#include <optional>
#include <utility>
#include <vector>

#include <oneapi/tbb/info.h>
#include <oneapi/tbb/parallel_pipeline.h>
#include <oneapi/tbb/task_arena.h>

#include "certipose/error.hpp"
#include "certipose/part/part_run.hpp"
#include "certipose/part/patches.hpp"
#include "certipose/solver/run_context.hpp"

namespace certipose {

/// One unit of work of a part run: item `item` of the run's work_plan (a facet, or a patch of
/// facets). Trivial (no member initialiser): oneTBB passes small trivial tokens between stages
/// in place.
struct work_item {
    std::size_t item;
};

/// A work item done, as the scheduler carries it back: the outcome of each of its facets, in
/// the plan's order, or dropped when the run ended while it was in flight (never reported half
/// done).
template <Interval I>
struct work_result {
    bool dropped = false;
    std::vector<facet_outcome<I>> outcomes;
};

namespace detail {

/// The progress estimate of a run (part_progress::seconds_left): each selected facet's share
/// of the work from part_solver::work_estimate, floored at a twentieth of the mean so that
/// facets skipped or hidden still count as a little work.
struct work_meter {
    std::vector<double> cumulative;  ///< work of the first i + 1 facets of the selection

    work_meter() = default;
    template <class Estimate>
    work_meter(const std::vector<std::size_t>& selection, Estimate&& estimate) : cumulative(selection.size()) {
        double mean = 0.0;
        for (std::size_t i = 0; i < selection.size(); ++i) mean += cumulative[i] = estimate(selection[i]);
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

/// The facets `options` selects in a part of `faces` facets, in order: `options.facets`, or all
/// of them when it is empty. Throws out_of_range for a facet not in the part.
inline std::vector<std::size_t> selected_facets(const part_options& options, std::size_t faces) {
    std::vector<std::size_t> selection = options.facets;
    if (selection.empty()) {
        selection.resize(faces);
        for (std::size_t i = 0; i < faces; ++i) selection[i] = i;
    }
    for (std::size_t f : selection)
        if (f >= faces) throw out_of_range("facet", f, faces);
    return selection;
}

/// The run-level state of a part run (see the header comment): what to do, in which order, and
/// what has been handed to the sink. `emit` and `next` are called from one thread at a time.
class part_schedule {
public:
    /// The selection of `options` over a part of `faces` facets (empty: all of them, in order),
    /// as work items: grouped by `regions` (part/patches.hpp), or a facet each when it is null.
    /// `estimate(f)` weighs facet f for the progress estimate (called only when there is a
    /// progress callback). Throws out_of_range for a facet not in the part and invalid_argument
    /// for a box budget of 0.
    template <class Estimate>
    part_schedule(const part_options& options, std::size_t faces, Estimate&& estimate, const patch_regions* regions = nullptr)
        : options_(&options), selection_(selected_facets(options, faces)), context_(options.stop, options.time_limit) {
        if (options.max_boxes && *options.max_boxes == 0)
            throw invalid_argument("max_boxes", "part_solver: the run's max_boxes must be at least 1");
        plan_ = regions ? work_plan::grouped(selection_, *regions) : work_plan::per_facet(selection_);
        if (options.progress) meter_ = detail::work_meter(plan_.order, std::forward<Estimate>(estimate));
        result_.facets_selected = selection_.size();
        result_.facets.reserve(selection_.size());
    }
    part_schedule(const part_schedule&) = delete;
    part_schedule& operator=(const part_schedule&) = delete;

    const std::vector<std::size_t>& selection() const noexcept { return selection_; }
    /// The work items, and the order in which the selected facets reach the sink.
    const work_plan& plan() const noexcept { return plan_; }
    /// The run's clock, deadline and stop (the user's token, the budgets, the progress callback).
    run_context& context() noexcept { return context_; }
    const run_context& context() const noexcept { return context_; }

    /// The next work item in order; nothing when every one was handed out or the run is
    /// stopped or past its deadline (which stops it).
    std::optional<work_item> next() {
        if (next_ >= plan_.items() || context_.stop_requested()) return std::nullopt;
        if (context_.past_deadline()) {
            context_.stop(termination::deadline);
            return std::nullopt;
        }
        return work_item{next_++};
    }

    /// `item_options` for one item of this run: the run's stop, its progress off, and its time
    /// limit shortened to what is left of the run's deadline.
    solve_options item_options(const solve_options& item_options) const {
        solve_options o = item_options;
        o.progress = {};
        o.stop = context_.token();
        if (const auto deadline = context_.deadline()) {
            const auto left = *deadline - run_context::clock::now();
            if (!o.time_limit || left < *o.time_limit) o.time_limit = std::max(left, run_context::clock::duration(1));
        }
        return o;
    }

    /// Was a result cut short by the run (its stop, or its deadline rather than the item's own)?
    /// Such a result is dropped, never reported half done.
    bool cut_short(const solve_stats& stats) const {
        return stats.reason == termination::cancelled || (stats.reason == termination::deadline && context_.past_deadline());
    }

    /// Hands a finished facet to the sink, in the plan's order (the caller keeps the order),
    /// and counts it; after an item's last facet, stops the run when the box budget is spent
    /// or the progress callback says so. Nothing more is handed over once the run is stopped,
    /// except the rest of an item already begun (an item is emitted whole).
    template <class Sink, Interval I>
    void emit(Sink& sink, const facet_outcome<I>& o) {
        const std::size_t done = result_.facets.size();
        const bool starts_item = done == 0 || plan_.ends[item_] == done;
        if (starts_item && context_.stop_requested()) return;
        if (starts_item && done > 0) ++item_;
        const facet_record& rec = o.record;
        sink.facet(o);
        result_.valid += rec.valid;
        result_.boundary += rec.boundary;
        result_.skipped += rec.termination == facet_termination::skipped;
        result_.reused += rec.reused_from.has_value();
        result_.patched += rec.patch.has_value();
        result_.facets.push_back(rec);
        boxes_ += rec.valid + rec.boundary;
        if (result_.facets.size() != plan_.ends[item_]) return;  // the item goes on
        if (options_->max_boxes && boxes_ >= *options_->max_boxes && result_.facets.size() < selection_.size())
            context_.stop(termination::box_budget);
        if (options_->progress) {
            const double s = context_.seconds();
            const std::size_t done = result_.facets.size();
            const part_progress p{done, selection_.size(), result_.valid, result_.boundary, s, meter_.seconds_left(done, s)};
            if (!options_->progress(p)) context_.stop(termination::cancelled);
        }
    }

    /// The run's result: the records handed to the sink, in order, the totals and why it ended.
    part_result finish(std::size_t threads, std::size_t peak_in_flight = 0) {
        part_result out = std::move(result_);
        out.reason = out.facets.size() == selection_.size() ? termination::completed : context_.reason();
        out.seconds = context_.seconds();
        out.threads = threads;
        out.peak_in_flight = peak_in_flight;
        return out;
    }

private:
    const part_options* options_;
    std::vector<std::size_t> selection_;
    work_plan plan_;
    run_context context_;
    detail::work_meter meter_{};
    std::size_t next_ = 0, boxes_ = 0, item_ = 0;
    part_result result_{};
};

/// The worker threads of `options` (0: oneTBB's default, every core).
inline std::size_t part_threads(const part_options& options) {
    return options.threads ? options.threads : static_cast<std::size_t>(oneapi::tbb::info::default_concurrency());
}

/// Runs `schedule`'s work items through `work` (work_item -> work_result<I>, called in parallel)
/// on `part_threads(options)` threads, at most `options.in_flight` items at once (0: 4 per
/// thread), and emits the results to `sink` in selection order: a oneTBB pipeline whose first
/// and last stages are serial and in order.
template <Interval I, class Work, class Sink>
part_result run_in_order(part_schedule& schedule, const part_options& options, Work&& work, Sink& sink) {
    const std::size_t threads = part_threads(options);
    const std::size_t tokens = options.in_flight ? options.in_flight : 4 * threads;
    std::atomic<std::size_t> live{0}, peak{0};
    bool gap = false;  // an item was dropped: none after it reaches the sink
    // The serial stages never run at once and TBB orders every hand-over between stages, but
    // with synchronisation ThreadSanitizer cannot see (libtbb is not instrumented), so it would
    // flag the sink, the totals and each item as races. Every stage passes through this mutex
    // when it starts and when it ends (held for nothing, never while the sink or the work
    // runs; ~20 ns per item): that makes the order TBB already guarantees visible, and a TSan
    // run reports only races of our own.
    std::mutex handoff;
    const auto sync = [&] { const std::lock_guard visible{handoff}; };
    struct sync_on_exit {
        const decltype(sync)& f;
        ~sync_on_exit() { f(); }
    };
    oneapi::tbb::task_arena arena(static_cast<int>(threads));
    arena.execute([&] {
        oneapi::tbb::parallel_pipeline(
            tokens,
            oneapi::tbb::make_filter<void, work_item>(oneapi::tbb::filter_mode::serial_in_order,
                                                      [&](oneapi::tbb::flow_control& fc) -> work_item {
                                                          sync();
                                                          const sync_on_exit done{sync};
                                                          const std::optional<work_item> w = schedule.next();
                                                          if (!w) {
                                                              fc.stop();
                                                              return {};
                                                          }
                                                          const std::size_t now = ++live;
                                                          for (std::size_t p = peak.load(); now > p && !peak.compare_exchange_weak(p, now);) {}
                                                          return *w;
                                                      }) &
                oneapi::tbb::make_filter<work_item, work_result<I>>(oneapi::tbb::filter_mode::parallel,
                                                                    [&](work_item w) {
                                                                        sync();
                                                                        work_result<I> r = work(w);
                                                                        sync();
                                                                        return r;
                                                                    }) &
                oneapi::tbb::make_filter<work_result<I>, void>(oneapi::tbb::filter_mode::serial_in_order,
                                                               [&](work_result<I> r) {
                                                                   sync();
                                                                   const sync_on_exit done{sync};
                                                                   --live;
                                                                   // In order: nothing after a dropped item.
                                                                   gap = gap || r.dropped;
                                                                   if (gap) return;
                                                                   for (const auto& o : r.outcomes) schedule.emit(sink, o);
                                                               }));
    });
    sync();  // what the last serial stage wrote, seen in this thread
    return schedule.finish(threads, peak.load());
}

}  // namespace certipose
