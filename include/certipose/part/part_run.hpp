// certipose/part/part_run.hpp — what a whole-part run takes and gives: part_options, the
// per-facet record and outcome the sink receives, progress, the run's result, and the PartSink
// concept (docs/part.md). The run itself: part/part_solver.hpp (threads), part/mpi.hpp (MPI),
// both through part/scheduler.hpp.
#pragma once

#include <array>
#include <chrono>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <stop_token>
#include <string>
#include <tuple>
#include <vector>

#include "certipose/part/patches.hpp"     // patch_options
#include "certipose/part/translates.hpp"  // reuse_options
#include "certipose/solver/camera_regions.hpp"
#include "certipose/solver/result.hpp"
#include "certipose/solver/task.hpp"

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
    /// The seed of the patch whose boxes this facet's are (part_options::patches): every box
    /// is proven for each member of the patch. Nothing when the facet was solved on its own.
    std::optional<std::size_t> patch{};
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
    /// Patches: facets certified at once, a box VALID for every member (part/patches.hpp).
    /// Not with keep_boundary: a patch's BOUNDARY boxes are its seed's, which do not enclose
    /// what its other members may see.
    patch_options patches{};
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
    std::size_t patched = 0;  ///< facets whose boxes are their patch's (part_options::patches)
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

}  // namespace certipose
