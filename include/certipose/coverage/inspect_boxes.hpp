// certipose/coverage/inspect_boxes.hpp — C(B) and P(B) (coverage/inspection.hpp) of many pose
// boxes at once, on worker threads: the candidates of a deployment plan.
//
// Each worker thread builds its own facet_inspector the first time it runs (an inspector owns
// per-facet constraint sets and a shadow cache, so it is not shared); boxes are independent, so
// the results do not depend on the thread count. `stop` ends the run early: boxes not inspected
// by then get empty sets (nothing claimed), and `inspection_run::completed` says so.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <mutex>
#include <stop_token>
#include <vector>

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/enumerable_thread_specific.h>
#include <oneapi/tbb/info.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include "certipose/coverage/inspection.hpp"

namespace certipose {

struct inspection_options {
    std::size_t threads = 0;  ///< worker threads; 0: every core
    std::stop_token stop{};
    /// Called now and then with (boxes done, boxes in all), from whichever worker thread finished
    /// a batch, one call at a time (so it needs no lock of its own); false stops the run.
    std::function<bool(std::size_t, std::size_t)> progress{};
    /// List the facets of P(B) too (facet_inspector::inspect); false keeps only C(B) and the areas.
    bool possible_sets = true;
};

struct inspection_run {
    std::vector<facet_coverage> coverage;  ///< by box, in the order given
    inspection_stats stats;                ///< summed over the threads
    bool completed = true;                 ///< false: stopped early (see the header comment)
};

namespace detail {

/// The worker threads and per-thread inspectors of one inspection, kept across calls of `run`
/// (a plan's thinning inspects its candidates in rounds: the facets' constraint sets and the
/// shadows one round built serve the next).
template <class Policies>
class box_inspection {
public:
    using interval_type = typename pose_solver<Policies>::interval_type;

    box_inspection(const pose_solver<Policies>& solver, const inspection_options& options)
        : options_(options),
          inspectors_([&solver] { return facet_inspector<Policies>(solver); }),
          arena_(static_cast<int>(options.threads ? options.threads
                                                  : static_cast<std::size_t>(oneapi::tbb::info::default_concurrency()))) {}

    /// Inspects boxes[i] for each i of `which` into coverage[i]. `done_before` boxes of `total`
    /// were done before this call (for the progress callback); a task takes at least `grain`
    /// boxes. Returns false when stopped.
    bool run(const std::vector<pose_box<interval_type>>& boxes, const std::vector<std::size_t>& which,
             std::vector<facet_coverage>& coverage, std::size_t done_before, std::size_t total, std::size_t grain = 16) {
        std::atomic<std::size_t> done{done_before};
        arena_.execute([&] {
            oneapi::tbb::parallel_for(oneapi::tbb::blocked_range<std::size_t>(0, which.size(), grain), [&](const auto& range) {
                auto& inspector = inspectors_.local();
                for (std::size_t k = range.begin(); k != range.end(); ++k) {
                    if (halted_.load(std::memory_order_relaxed) || options_.stop.stop_requested()) {
                        halted_ = true;
                        return;
                    }
                    coverage[which[k]] = inspector.inspect(boxes[which[k]], options_.possible_sets);
                }
                const std::size_t n = done.fetch_add(range.size()) + range.size();
                // One caller at a time is enough for a progress line; the others skip it.
                if (options_.progress) {
                    const std::unique_lock lock(reporting_, std::try_to_lock);
                    if (lock.owns_lock() && !options_.progress(n, total)) halted_ = true;
                }
            });
        });
        return !halted_;
    }

    /// facet_inspector::view_estimate of every box over the facets of `sample`.
    std::vector<double> estimate(const std::vector<pose_box<interval_type>>& boxes, const std::vector<std::size_t>& sample) {
        std::vector<double> out(boxes.size());
        arena_.execute([&] {
            oneapi::tbb::parallel_for(oneapi::tbb::blocked_range<std::size_t>(0, boxes.size(), 64), [&](const auto& range) {
                auto& inspector = inspectors_.local();
                for (std::size_t i = range.begin(); i != range.end(); ++i) out[i] = inspector.view_estimate(boxes[i], sample);
            });
        });
        return out;
    }

    /// The inspectors' counters, summed over the threads.
    inspection_stats stats() const {
        inspection_stats out;
        for (const auto& inspector : inspectors_) {
            const auto& s = inspector.stats();
            out.boxes += s.boxes, out.culled += s.culled, out.by_constraints += s.by_constraints;
            out.by_field_of_view += s.by_field_of_view, out.occlusion_tests += s.occlusion_tests;
            out.refuted_by_sight_line += s.refuted_by_sight_line;
        }
        return out;
    }

private:
    inspection_options options_;
    oneapi::tbb::enumerable_thread_specific<facet_inspector<Policies>> inspectors_;
    oneapi::tbb::task_arena arena_;
    std::atomic<bool> halted_{false};
    std::mutex reporting_;
};

}  // namespace detail

template <class Policies>
inspection_run inspect_boxes(const pose_solver<Policies>& solver,
                             const std::vector<pose_box<typename pose_solver<Policies>::interval_type>>& boxes,
                             const inspection_options& options = {}) {
    inspection_run out;
    out.coverage.resize(boxes.size());
    std::vector<std::size_t> all(boxes.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
    detail::box_inspection<Policies> inspection(solver, options);
    out.completed = inspection.run(boxes, all, out.coverage, 0, boxes.size());
    out.stats = inspection.stats();
    return out;
}

}  // namespace certipose
