// certipose/solver/result.hpp — what the solver returns: classified 6D pose boxes and
// statistics (DESIGN.md §1, §6).
//
// VALID boxes are certified: every pose in them satisfies every constraint of DESIGN.md §3 for
// every point of the facet. BOUNDARY boxes were left undecided at the resolution ε_p / ε_o.
// Everything not returned was certified invalid, or not reached when a budget stopped the run
// (`stats.termination` says which).
#pragma once

#include <cstddef>
#include <vector>

#include "certipose/pose/pose_box.hpp"
#include "certipose/solver/task.hpp"

namespace certipose {

/// A returned box: `cls` is box_class::valid or box_class::boundary.
template <Interval I>
struct classified_box {
    box_class cls;
    pose_box<I> box;
};

/// Per-stage counts and times.
struct solve_stats {
    std::size_t valid = 0, boundary = 0;       ///< 6D boxes returned per class
    std::size_t position_valid = 0;            ///< certified position boxes (before orientation)
    std::size_t position_boundary = 0;
    std::size_t contractions = 0, bisections = 0;
    std::size_t occlusion_tests = 0;
    std::size_t orientation_certifications = 0;  ///< 6D interval certifications attempted
    double seconds_position = 0, seconds_orientation = 0, seconds = 0;
    termination reason = termination::completed;
};

template <Interval I>
struct solve_result {
    std::size_t facet_index = 0;
    std::vector<classified_box<I>> boxes;
    solve_stats stats;
    /// The position stage's bisection tree, when solve_options::keep_tree.
    std::vector<paving_node<position_box<I>>> tree;
};

}  // namespace certipose
