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

template <class Policies>
inspection_run inspect_boxes(const pose_solver<Policies>& solver,
                             const std::vector<pose_box<typename pose_solver<Policies>::interval_type>>& boxes,
                             const inspection_options& options = {}) {
    inspection_run out;
    out.coverage.resize(boxes.size());
    oneapi::tbb::enumerable_thread_specific<facet_inspector<Policies>> inspectors(
        [&] { return facet_inspector<Policies>(solver); });
    std::atomic<std::size_t> done{0};
    std::atomic<bool> halted{false};
    std::mutex reporting;
    const std::size_t threads =
        options.threads ? options.threads : static_cast<std::size_t>(oneapi::tbb::info::default_concurrency());
    oneapi::tbb::task_arena arena(static_cast<int>(threads));
    arena.execute([&] {
        oneapi::tbb::parallel_for(oneapi::tbb::blocked_range<std::size_t>(0, boxes.size(), 16), [&](const auto& range) {
            auto& inspector = inspectors.local();
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
                if (halted.load(std::memory_order_relaxed) || options.stop.stop_requested()) {
                    halted = true;
                    return;
                }
                out.coverage[i] = inspector.inspect(boxes[i], options.possible_sets);
            }
            const std::size_t n = done.fetch_add(range.size()) + range.size();
            // One caller at a time is enough for a progress line; the others skip it.
            if (options.progress) {
                const std::unique_lock lock(reporting, std::try_to_lock);
                if (lock.owns_lock() && !options.progress(n, boxes.size())) halted = true;
            }
        });
    });
    out.completed = !halted;
    for (const auto& inspector : inspectors) {
        const auto& s = inspector.stats();
        out.stats.boxes += s.boxes, out.stats.culled += s.culled, out.stats.by_constraints += s.by_constraints;
        out.stats.by_field_of_view += s.by_field_of_view, out.stats.occlusion_tests += s.occlusion_tests;
        out.stats.refuted_by_sight_line += s.refuted_by_sight_line;
    }
    return out;
}

}  // namespace certipose
