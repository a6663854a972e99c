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
#include "certipose/inspection_task.hpp"
#include "certipose/outcome.hpp"
#include "certipose/solver/paving.hpp"

namespace certipose {

/// Progress report passed to the callback.
struct solve_progress {
    const char* stage;          ///< "position" or "orientation"
    std::size_t boxes_done;     ///< boxes processed so far in the run (the orientation stage goes on counting)
    std::size_t boxes_pending;  ///< boxes still waiting in this stage
    std::size_t valid;          ///< VALID boxes so far
    std::size_t boundary;       ///< BOUNDARY boxes so far
    double seconds;             ///< since the run started
};

/// Anytime refinement below ε_p (solve_options::refine): the position stage paves with the
/// largest undecided box first and keeps splitting boxes down to `min_width` instead of ε_p,
/// until a budget ends it. Stopping early leaves the boxes not yet decided BOUNDARY (reason
/// `budget`): the answer is sound whenever it stops, and more complete the longer it runs.
struct refinement {
    /// Boxes narrower than this (metres) are not split; 0: ε_p / 16.
    double min_width = 0.0;
    /// Budget of the position stage's refinement; the orientation stage then orients what it
    /// certified, and growth (solve_options::grow) widens it. Unset: a quarter of
    /// solve_options::time_limit when that is set, else no time limit (the box budget and
    /// min_width still end it). Not half: refined position boxes are many and small, and
    /// orienting them is what a deadline cuts short (docs/completeness.md).
    std::optional<std::chrono::steady_clock::duration> time_limit{};
    /// The orientation stage bisects a position box no orientation fits down to
    /// ε_p / orientation_split (the paper: down to ε_p, i.e. 1). Such boxes are where the facet
    /// barely fits the image, and refined runs certify most of them two halvings further.
    double orientation_split = 4;

    void validate(double position_eps) const {
        if (!(min_width >= 0.0) || !std::isfinite(min_width))
            throw invalid_argument("refine.min_width", "solve_options: refine.min_width must be >= 0 and finite, got " +
                                                           detail::format_double(min_width));
        if (min_width > position_eps)
            throw invalid_argument("refine.min_width", "solve_options: refine.min_width " + detail::format_double(min_width) +
                                                           " is wider than position_eps " + detail::format_double(position_eps) +
                                                           ": nothing would be refined");
        if (time_limit && time_limit->count() <= 0)
            throw invalid_argument("refine.time_limit", "solve_options: refine.time_limit must be positive");
        if (!(orientation_split >= 1.0) || !std::isfinite(orientation_split))
            throw invalid_argument("refine.orientation_split",
                                   "solve_options: refine.orientation_split must be >= 1 and finite, got " +
                                       detail::format_double(orientation_split));
    }
    /// The width below which boxes are not split.
    double width(double position_eps) const noexcept { return min_width > 0.0 ? min_width : position_eps / 16; }
};

/// How boxes are widened (solve_options::grow, pose_solver::grow / largest_box_around).
struct growth_options {
    /// The finest step of a position face or half-width, metres; 0: ε_p / 64 of the run (or 1 mm
    /// outside a run).
    double position_step = 0.0;
    /// The finest step of an Euler-angle face or half-width, radians; 0: ε_o / 64 (or 0.005).
    double orientation_step = 0.0;
    /// Certifications spent on one box at most (each costs an occlusion test when a position
    /// face moves, and an interval evaluation of the field of view).
    std::size_t max_certifications = 256;

    void validate() const {
        if (!(position_step >= 0.0) || !std::isfinite(position_step))
            throw invalid_argument("grow.position_step", "growth_options: position_step must be >= 0 and finite, got " +
                                                             detail::format_double(position_step));
        if (!(orientation_step >= 0.0) || !std::isfinite(orientation_step))
            throw invalid_argument("grow.orientation_step",
                                   "growth_options: orientation_step must be >= 0 and finite, got " +
                                       detail::format_double(orientation_step));
    }
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
    /// How the position stage treats partly valid boxes: `carving` (the default, with its
    /// tuning) or `paper_paving` (solver/paving.hpp).
    paving_choice paving{};
    /// Anytime refinement below ε_p (see `refinement`); unset: the paper's ε_p stopping rule.
    std::optional<refinement> refine{};
    /// Widen the VALID boxes into fewer, larger ones (merge neighbours, then move every face
    /// out while the box stays certified: solver/detail/growth.hpp); unset: boxes as paved.
    std::optional<growth_options> grow{};

    void validate() const {
        if (!(position_eps > 0.0) || !std::isfinite(position_eps))
            throw invalid_argument("position_eps", "solve_options: position_eps must be positive and finite, got " +
                                                       detail::format_double(position_eps));
        if (!(orientation_eps > 0.0) || !std::isfinite(orientation_eps))
            throw invalid_argument("orientation_eps",
                                   "solve_options: orientation_eps must be positive and finite, got " +
                                       detail::format_double(orientation_eps));
        if (max_boxes == 0) throw invalid_argument("max_boxes", "solve_options: max_boxes must be at least 1");
        std::visit([](const auto& p) { p.validate(); }, paving);
        if (refine) refine->validate(position_eps);
        if (grow) grow->validate();
    }
};

}  // namespace certipose
