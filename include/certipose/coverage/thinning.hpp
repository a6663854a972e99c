// certipose/coverage/thinning.hpp — C(B) of a plan's candidates, skipping the candidates whose
// facet another candidate already certifies (docs/coverage.md#thinning).
//
// A plan's candidates come one (or a few) per facet, and on a finely tessellated part the
// candidates of neighbouring facets are nearly the same camera: each C(B) is thousands of facets
// on a CAD export, most of them certified by many other candidates too. Inspecting all of them
// is the plan's cost (C(B) of one candidate proves every facet in view on its own), and a plan
// keeps a handful. Thinning inspects the candidates in rounds and skips a candidate whose facet
// some inspected candidate certifies already: that facet is coverable without it.
//
// The order is the greedy choice's: a plan takes the candidates that certify the most first, so
// those should be inspected before the candidates they make redundant. Each candidate's view is
// estimated on a sample of facets spread over the part (facet_inspector::view_estimate: the
// cull, and the viewing angle from the box's centre; no proof), and the candidates are taken
// largest estimate first, ties in a fixed pseudo-random order.
//
// What it keeps: every candidate's facet is certified by an inspected candidate (its own, or one
// that certifies it), so every facet some candidate is VALID for stays coverable when each
// candidate counts its own facet (a trusted run: make_plan adds it); a facet that only skipped
// candidates' C(B) certified drops out. What it gives up: the skipped candidates are not choices
// of the plan, so it may need a camera more than one chosen from all of them, and its lower
// bound is over the inspected candidates. The C(B) it computes are the inspector's, bit for bit;
// which candidates are inspected depends on the rounds alone, never on the threads.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

#include "certipose/coverage/inspect_boxes.hpp"
#include "certipose/error.hpp"

namespace certipose {

/// Tuning of the thinning (plan_options::thinning).
struct thinning_options {
    /// Candidates inspected together (on the worker threads) before the covered facets are
    /// updated. Smaller rounds skip more, but leave the plan fewer choices among the candidates
    /// that see the most; larger ones keep the threads busier. A fixed number, so that the
    /// candidates inspected do not depend on the thread count.
    std::size_t round = 64;
    /// A candidate is skipped once its facet is certified by this many inspected candidates:
    /// more keeps more choices for the plan (perhaps fewer cameras), at the cost of more C(B).
    std::size_t certified_by = 1;
    /// About how many facets the candidates' view estimates are summed over: every
    /// ⌊faces / sample⌋-th facet index (between `sample` and 2·`sample` − 1 facets; all of them
    /// on a part of fewer faces).
    std::size_t sample = 2048;
    /// A candidate's own facet counts as certified by it once it is inspected (a trusted run, in
    /// which every candidate is VALID for its facet: make_plan's trust_run).
    bool own_facet = true;

    void validate() const {
        if (round < 1) throw invalid_argument("thinning.round", "thinning_options: round must be at least 1");
        if (sample < 1) throw invalid_argument("thinning.sample", "thinning_options: sample must be at least 1");
        if (certified_by < 1)
            throw invalid_argument("thinning.certified_by", "thinning_options: certified_by must be at least 1");
    }
};

/// C(B) of the inspected candidates (empty for the skipped, and for every candidate of a round
/// that was stopped), and which were inspected.
struct thinned_inspection : inspection_run {
    std::vector<char> inspected;  ///< by candidate: 1 when its C(B) was computed
    std::size_t inspected_count = 0;
};

namespace detail {
/// The order thinning visits candidates in: largest `estimate` first, ties in a fixed
/// permutation (splitmix64 of the index), so that consecutive candidates, usually neighbouring
/// facets, land in different rounds.
inline std::vector<std::size_t> thinning_order(const std::vector<double>& estimate) {
    const std::size_t n = estimate.size();
    const auto mix = [](std::uint64_t x) {
        x += 0x9e3779b97f4a7c15ull;
        x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
        x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
        return x ^ (x >> 31);
    };
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::vector<std::uint64_t> key(n);
    for (std::size_t i = 0; i < n; ++i) key[i] = mix(i);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        if (estimate[a] != estimate[b]) return estimate[a] > estimate[b];
        return key[a] != key[b] ? key[a] < key[b] : a < b;
    });
    return order;
}
}  // namespace detail

/// C(B) of `boxes` (the candidates, whose facets are `facets`, same order), skipping each
/// candidate whose facet an inspected candidate already certifies (see the header comment).
/// `options.progress` counts skipped candidates as done, and is called with (all, all) at the
/// end of a completed run. Throws invalid_argument when `facets`
/// is not as long as `boxes`, and out_of_range for a facet beyond the part.
template <class Policies>
thinned_inspection inspect_thinned(const pose_solver<Policies>& solver,
                                   const std::vector<pose_box<typename pose_solver<Policies>::interval_type>>& boxes,
                                   const std::vector<std::size_t>& facets, const thinning_options& thinning,
                                   const inspection_options& options = {}) {
    thinning.validate();
    if (facets.size() != boxes.size())
        throw invalid_argument("facets", "inspect_thinned: one facet per box, got " + std::to_string(facets.size()) +
                                             " facets for " + std::to_string(boxes.size()) + " boxes");
    const std::size_t num_faces = solver.part().num_faces();
    for (std::size_t f : facets)
        if (f >= num_faces) throw out_of_range("facet", f, num_faces);
    thinned_inspection out;
    out.coverage.resize(boxes.size());
    out.inspected.assign(boxes.size(), 0);
    std::vector<std::uint32_t> covered(num_faces, 0);  // inspected candidates certifying each facet
    if (options.stop.stop_requested()) {
        out.completed = false;
        return out;
    }
    detail::box_inspection<Policies> inspection(solver, options);
    const std::vector<std::size_t> order = [&] {
        std::vector<std::size_t> sample;
        const std::size_t stride = std::max<std::size_t>(1, num_faces / thinning.sample);
        for (std::size_t f = 0; f < num_faces; f += stride) sample.push_back(f);
        return detail::thinning_order(inspection.estimate(boxes, sample));
    }();
    std::size_t next = 0, done = 0;
    std::vector<std::size_t> round;
    while (next < order.size()) {
        round.clear();
        for (; next < order.size() && round.size() < thinning.round; ++next) {
            const std::size_t j = order[next];
            if (covered[facets[j]] >= thinning.certified_by) ++done;  // skipped: done, nothing to inspect
            else round.push_back(j);
        }
        if (round.empty()) continue;
        // One box a task: a round is a few dozen boxes, and a C(B) on a large part takes a tenth
        // of a second, so chunks of several would leave a thread idle at the end of each round.
        if (!inspection.run(boxes, round, out.coverage, done, boxes.size(), 1)) {
            for (std::size_t j : round) out.coverage[j] = {};  // not all of the round was inspected
            out.completed = false;
            break;
        }
        done += round.size();
        for (std::size_t j : round) {
            out.inspected[j] = 1;
            ++out.inspected_count;
            bool own = false;
            for (std::size_t f : out.coverage[j].certified) ++covered[f], own = own || f == facets[j];
            if (thinning.own_facet && !own) ++covered[facets[j]];
        }
    }
    // The last candidates in the order are mostly skipped, after the last round reported.
    if (out.completed && options.progress && !boxes.empty()) out.completed = options.progress(boxes.size(), boxes.size());
    out.stats = inspection.stats();
    return out;
}

}  // namespace certipose
