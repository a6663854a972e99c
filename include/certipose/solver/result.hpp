// certipose/solver/result.hpp — what the solver returns: classified 6D pose boxes and
// statistics (docs/solver.md; as a file: the result JSON of docs/io.md).
//
// VALID boxes are certified: every pose in them satisfies every constraint of docs/conventions.md for
// every point of the facet. BOUNDARY boxes were left undecided at the resolution ε_p / ε_o.
// Everything not returned was certified invalid, or not reached when a budget stopped the run
// (`stats.termination` says which).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <vector>

#include "certipose/constraints/concept.hpp"
#include "certipose/paver/paver.hpp"
#include "certipose/pose/pose_box.hpp"
#include "certipose/solver/paving.hpp"
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
    /// The paving steps the run took, every switch decided for its policies (the paper's
    /// paving: all off; pose_solver::paving_steps).
    carving paving{};
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
    /// Camera regions (solver/camera_regions.hpp, applied after the solve): VALID 6D boxes or
    /// pieces dropped as wholly outside the allowed space, and bisections made deciding pieces.
    std::size_t region_dropped = 0, region_bisections = 0;
    /// Placement tolerance (solver/placement_stage.hpp): VALID boxes that needed splitting to be
    /// proven for every placement, and the bisections made doing so.
    std::size_t placement_split = 0, placement_bisections = 0;
    double seconds_position = 0, seconds_orientation = 0, seconds = 0;
    termination reason = termination::completed;
};

/// One member of solve_stats as the result JSON's "stats" object names it (docs/io.md).
template <class T>
struct stats_field {
    static constexpr bool may_be_required = std::is_same_v<T, std::size_t> || std::is_same_v<T, double>;
    std::string_view name;
    T solve_stats::*member;
    bool required = false;  ///< a result document without it is rejected; else it reads as the default
};
template <class T>
stats_field(std::string_view, T solve_stats::*) -> stats_field<T>;
template <class T>
stats_field(std::string_view, T solve_stats::*, bool) -> stats_field<T>;

/// The members of solve_stats in the result JSON, in the order they are written: io/json.hpp
/// writes and reads the "stats" object from this table alone, so a new field is one line here
/// (and, for a member of a new type, a case in the writer and the reader). valid, boundary and
/// seconds are the contract; the others are extra fields. refinement_passes is not written.
inline constexpr auto solve_stats_fields = std::make_tuple(
    stats_field{"valid", &solve_stats::valid, true},
    stats_field{"boundary", &solve_stats::boundary, true},
    stats_field{"seconds", &solve_stats::seconds, true},
    stats_field{"position_valid", &solve_stats::position_valid},
    stats_field{"position_boundary", &solve_stats::position_boundary},
    stats_field{"contractions", &solve_stats::contractions},
    stats_field{"bisections", &solve_stats::bisections},
    stats_field{"occlusion_tests", &solve_stats::occlusion_tests},
    stats_field{"shadow_walks", &solve_stats::shadow_walks},
    stats_field{"inner_pieces", &solve_stats::inner_pieces},
    stats_field{"occlusion_pieces", &solve_stats::occlusion_pieces},
    stats_field{"corner_boxes", &solve_stats::corner_boxes},
    stats_field{"position_merges", &solve_stats::position_merges},
    stats_field{"valid_volume", &solve_stats::valid_volume},
    stats_field{"boundary_volume", &solve_stats::boundary_volume},
    stats_field{"refinement_stopped", &solve_stats::refinement_stopped},
    stats_field{"merges", &solve_stats::merges},
    stats_field{"grown", &solve_stats::grown},
    stats_field{"seconds_growth", &solve_stats::seconds_growth},
    stats_field{"orientation_certifications", &solve_stats::orientation_certifications},
    stats_field{"orientation_groups", &solve_stats::orientation_groups},
    stats_field{"orientation_borrowed", &solve_stats::orientation_borrowed},
    stats_field{"region_dropped", &solve_stats::region_dropped},
    stats_field{"region_bisections", &solve_stats::region_bisections},
    stats_field{"placement_split", &solve_stats::placement_split},
    stats_field{"placement_bisections", &solve_stats::placement_bisections},
    stats_field{"seconds_position", &solve_stats::seconds_position},
    stats_field{"seconds_orientation", &solve_stats::seconds_orientation},
    stats_field{"termination", &solve_stats::reason},
    stats_field{"boundary_reasons", &solve_stats::boundary_reasons},
    stats_field{"occlusion_checked", &solve_stats::occlusion_checked});

static_assert(std::apply([](const auto&... field) { return ((!field.required || field.may_be_required) && ...); },
                         solve_stats_fields),
              "certipose: only counts and numbers can be required stats fields (io/json.hpp reads them so)");

/// Calls f(field) for each stats_field of solve_stats_fields, in order.
template <class F>
constexpr void for_each_stats_field(F&& f) {
    std::apply([&](const auto&... field) { (f(field), ...); }, solve_stats_fields);
}

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
