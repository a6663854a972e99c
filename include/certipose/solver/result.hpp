// certipose/solver/result.hpp — what the solver returns: classified 6D pose boxes and
// statistics (DESIGN.md §1, §6).
//
// VALID boxes are certified: every pose in them satisfies every constraint of DESIGN.md §3 for
// every point of the facet. BOUNDARY boxes were left undecided at the resolution ε_p / ε_o.
// Everything not returned was certified invalid, or not reached when a budget stopped the run
// (`stats.termination` says which).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "certipose/constraints/concept.hpp"
#include "certipose/pose/pose_box.hpp"
#include "certipose/solver/task.hpp"

namespace certipose {

/// A returned box: `cls` is box_class::valid or box_class::boundary; for a BOUNDARY box,
/// `reason` says which constraint (or budget) left it undecided.
template <Interval I>
struct classified_box {
    box_class cls;
    pose_box<I> box;
    boundary_reason reason = boundary_reason::constraint;
};

/// Per-stage counts and times.
struct solve_stats {
    std::size_t valid = 0, boundary = 0;       ///< 6D boxes returned per class
    /// BOUNDARY boxes per reason, indexed by boundary_reason (they sum to `boundary`).
    std::array<std::size_t, boundary_reason_count> boundary_reasons{};
    /// False when the occlusion policy does not check constraint 6 (no_occlusion): VALID boxes
    /// then hold for every constraint but occlusion.
    bool occlusion_checked = true;
    std::size_t position_valid = 0;            ///< certified position boxes (before orientation)
    std::size_t position_boundary = 0;
    std::size_t contractions = 0, bisections = 0;
    std::size_t occlusion_tests = 0;  ///< occlusion classifications (the policy's classify)
    std::size_t shadow_walks = 0;     ///< tree walks for the shadows of possible blockers (occlusion cuts)
    std::size_t inner_pieces = 0;      ///< position pieces the complement contraction carved off
    std::size_t occlusion_pieces = 0;  ///< VALID position pieces carved off occlusion-PARTIAL boxes
    std::size_t corner_boxes = 0;      ///< VALID corner boxes split off boxes left undecided at ε_p
    std::size_t position_merges = 0;   ///< VALID position boxes merged with a neighbour before orientation
    /// Volumes (m³) of the position parts of the VALID and BOUNDARY boxes returned: sums of
    /// products of widths, a measure of the answer, not certified bounds.
    double valid_volume = 0, boundary_volume = 0;
    /// The refinement's own time limit ended the position stage (solve_options::refine).
    bool refinement_stopped = false;
    /// Refinement passes that ran (0–2): the BOUNDARY boxes the constraint set left undecided,
    /// then those occlusion left PARTIAL, which start from the first pass's states.
    std::size_t refinement_passes = 0;
    /// solve_options::grow: pairs of VALID boxes merged, boxes widened by growth.
    std::size_t merges = 0, grown = 0;
    double seconds_growth = 0;
    std::size_t orientation_certifications = 0;  ///< 6D interval certifications attempted
    std::size_t orientation_groups = 0;  ///< cells of small position boxes oriented together
    /// position boxes oriented with a neighbouring cell's hint after their own search failed
    std::size_t orientation_borrowed = 0;
    double seconds_position = 0, seconds_orientation = 0, seconds = 0;
    termination reason = termination::completed;
};

/// The reason most BOUNDARY boxes have (ties: the earlier reason); nothing without BOUNDARY boxes.
inline std::optional<boundary_reason> main_boundary_reason(const solve_stats& s) {
    std::optional<boundary_reason> best;
    for (std::size_t r = 0; r < boundary_reason_count; ++r)
        if (s.boundary_reasons[r] > 0 && (!best || s.boundary_reasons[r] > s.boundary_reasons[static_cast<std::size_t>(*best)]))
            best = static_cast<boundary_reason>(r);
    return best;
}

/// "occlusion 1000, view_angle 124": the reasons of the BOUNDARY boxes, most frequent first.
inline std::string boundary_summary(const solve_stats& s) {
    std::array<std::size_t, boundary_reason_count> order{};
    for (std::size_t r = 0; r < boundary_reason_count; ++r) order[r] = r;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return s.boundary_reasons[a] > s.boundary_reasons[b]; });
    std::string out;
    for (std::size_t r : order) {
        if (s.boundary_reasons[r] == 0) break;
        if (!out.empty()) out += ", ";
        out += std::string(to_string(static_cast<boundary_reason>(r))) + " " + std::to_string(s.boundary_reasons[r]);
    }
    return out.empty() ? "none" : out;
}

template <Interval I>
struct solve_result {
    std::size_t facet_index = 0;
    std::vector<classified_box<I>> boxes;
    solve_stats stats;
    /// The position stage's bisection tree, when solve_options::keep_tree.
    std::vector<paving_node<position_box<I>>> tree;

    /// BOUNDARY boxes left undecided for `r`.
    std::size_t boundary_because(boundary_reason r) const noexcept {
        return stats.boundary_reasons[static_cast<std::size_t>(r)];
    }
};

}  // namespace certipose
