// certipose/solver/task.hpp — what is asked of the solver: the inspection task (paper §2) and
// the run settings (thresholds ε_p, ε_o, budgets, progress, cancellation).
//
// Thresholds are validated where they enter (`validate()`): zero, negative or NaN values throw
// certipose::invalid_argument naming the field, instead of making the paver loop forever.
#pragma once

#include <chrono>
#include <cmath>
#include <cstddef>
#include <functional>
#include <numbers>
#include <optional>
#include <stop_token>
#include <string>

#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"
#include "certipose/paver/paver.hpp"  // termination, box_class

namespace certipose {

/// The inspection task for one facet (DESIGN.md §1, §3).
struct inspection_task {
    /// θ_v: the sight line to the facet centre must make at least this angle with the facet's
    /// plane, i.e. the angle to the normal is at most π/2 − θ_v (constraint 4). Radians, [0, π/2).
    double min_view_angle = 0.35;
    /// Optional resolution requirement r (metres on the part per pixel): caps d_max at r·f_px.
    std::optional<double> max_metres_per_pixel{};

    void validate() const {
        if (!(min_view_angle >= 0.0) || !(min_view_angle < std::numbers::pi / 2))
            throw invalid_argument("min_view_angle", "inspection_task: min_view_angle must be in [0, pi/2), got " +
                                                         detail::format_double(min_view_angle));
        if (max_metres_per_pixel && !(*max_metres_per_pixel > 0.0 && std::isfinite(*max_metres_per_pixel)))
            throw invalid_argument("max_metres_per_pixel",
                                   "inspection_task: max_metres_per_pixel must be positive and finite, got " +
                                       detail::format_double(*max_metres_per_pixel));
    }
};

/// Progress report passed to the callback.
struct solve_progress {
    const char* stage;          ///< "position" or "orientation"
    std::size_t boxes_done;     ///< boxes processed so far in the run (the orientation stage goes on counting)
    std::size_t boxes_pending;  ///< boxes still waiting in this stage
    std::size_t valid;          ///< VALID boxes so far
    std::size_t boundary;       ///< BOUNDARY boxes so far
    double seconds;             ///< since the run started
};

/// Settings of one run (paper §8: ε_p = 0.1 m, ε_o = 0.38 rad).
struct solve_options {
    double position_eps = 0.1;      ///< ε_p, metres: position boxes narrower than this are not split
    double orientation_eps = 0.38;  ///< ε_o, radians: orientation boxes narrower than this are not split
    std::size_t max_boxes = 1'000'000;  ///< budget: boxes processed (all stages)
    std::optional<std::chrono::steady_clock::duration> time_limit{};  ///< budget: wall time
    /// Called from the solving thread every few boxes; return false to cancel.
    std::function<bool(const solve_progress&)> progress{};
    std::stop_token stop{};  ///< cancellation from another thread
    bool keep_tree = false;  ///< also return the bisection tree of the position stage

    void validate() const {
        if (!(position_eps > 0.0) || !std::isfinite(position_eps))
            throw invalid_argument("position_eps", "solve_options: position_eps must be positive and finite, got " +
                                                       detail::format_double(position_eps));
        if (!(orientation_eps > 0.0) || !std::isfinite(orientation_eps))
            throw invalid_argument("orientation_eps",
                                   "solve_options: orientation_eps must be positive and finite, got " +
                                       detail::format_double(orientation_eps));
        if (max_boxes == 0) throw invalid_argument("max_boxes", "solve_options: max_boxes must be at least 1");
    }
};

}  // namespace certipose
