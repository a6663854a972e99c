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
    /// min_width still end it). A quarter, not a half: refined position boxes are many and
    /// small, and orienting them is what a deadline cut short on the reference cases (at 1 s,
    /// plate_holes certified 23-31 % of its true positions with half, 88 % with a quarter).
    std::optional<std::chrono::steady_clock::duration> time_limit{};

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
    /// face moves, ~0.1 ms, and an interval evaluation of the field of view, ~10 µs).
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
    /// Past the paper: carve the part of a partly valid position box that certainly satisfies
    /// the position constraints off it instead of bisecting it whole (inner contraction).
    bool inner_contraction = true;
    /// Past the paper: carve the certainly visible part off an occlusion-PARTIAL box.
    bool occlusion_cuts = true;
    /// Past the paper: of a box left undecided at ε_p, certify the largest box from one of its
    /// corners and leave only the rest BOUNDARY. All three off: the paper's paving.
    bool leaf_corner_boxes = true;
    /// How many corner boxes one such box may give in a row (1–8): the rest of a corner box
    /// may give one of its own, and so on, a staircase along the boundary. 1: one per box.
    std::size_t corner_depth = 2;
    /// A rest box (what is left of a box beside its corner box) gives a corner box of its own
    /// only when none of its sides is thinner than this many minimal pieces (ε_p / 10): thin
    /// slabs give many small boxes for little volume, and orienting them is most of a sliver
    /// facet's time. 3 (the default) against 2: ~18 % less time on plate_holes (facet 7), for
    /// 1.6–4.5 points less of the true valid positions certified on the four reference cases
    /// (angle_block 64.5 → 60.0 %; docs/completeness.md). 0: every rest box while
    /// `corner_depth` allows.
    double corner_rest_min_pieces = 3.0;
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
        if (corner_depth < 1 || corner_depth > 8)
            throw invalid_argument("corner_depth",
                                   "solve_options: corner_depth must be between 1 and 8, got " + std::to_string(corner_depth));
        if (!(corner_rest_min_pieces >= 0.0) || !std::isfinite(corner_rest_min_pieces))
            throw invalid_argument("corner_rest_min_pieces",
                                   "solve_options: corner_rest_min_pieces must be >= 0 and finite, got " +
                                       detail::format_double(corner_rest_min_pieces));
        if (refine) refine->validate(position_eps);
        if (grow) grow->validate();
    }
};

}  // namespace certipose
