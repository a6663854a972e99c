// certipose/solver/paving.hpp — the paving choice of a run (solve_options::paving): how the
// position stage treats a box that is partly valid.
//
//   paper_paving   the paper's Algorithm 3: bisect it, down to ε_p, and leave the last halves
//                  BOUNDARY; the orientation stage then searches once per position box.
//   carving        (the default) carve off what is certainly valid, and let the leaves the
//                  bisector declines give corner boxes (solver/position_stage.hpp); the
//                  orientation stage then also runs the steps meant for the many small boxes
//                  this makes (solver/orientation_schedule.hpp: merges, groups, borrowing).
//
// `carving` holds the stage's tuning, in units of ε_p, each with a default. Each of its steps
// needs a capability of a policy: inner contraction a ComplementContractingSet, occlusion cuts a
// ShadowingOcclusionPolicy. A step that is on for a policy without the capability is an error
// (invalid_argument naming the step and the concept), never skipped: turn it off to pave
// without it (the programs do for --occlusion boolean: the paper's test names no shadows).
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <variant>

#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"

namespace certipose {

/// The paper's paving: partly valid boxes are bisected, nothing else.
struct paper_paving {
    void validate() const {}
};

/// Carving past the paper (solver/position_stage.hpp, solver/detail/carving.hpp).
struct carving {
    /// Carve the part of a partly valid box that certainly satisfies the constraint set off it
    /// (the set must model ComplementContractingSet).
    bool inner_contraction = true;
    /// Carve the certainly visible part off a box that occlusion leaves PARTIAL (the occlusion
    /// policy must model ShadowingOcclusionPolicy).
    bool occlusion_cuts = true;
    /// Of a box the bisector declines and that stays undecided, certify the largest box from one
    /// of its corners (VALID) and leave only the rest BOUNDARY.
    bool corner_boxes = true;
    /// Corner boxes one such box may give in a row (1–8): the rest of a corner box may give one
    /// of its own, and so on, a staircase along the boundary of what is valid.
    std::size_t corner_depth = 2;
    /// Pieces thinner than ε_p / pieces_per_eps (in the dimension they are cut in) stay with
    /// the box they would be cut from: the "minimal piece" of the rules below.
    double pieces_per_eps = 10;
    /// A rest box (what is left of a box beside its corner box) gives a corner box of its own
    /// only when none of its sides is thinner than this many minimal pieces: thin slabs give
    /// many small boxes for little volume. 0: whenever `corner_depth` allows.
    double rest_min_pieces = 3;

    /// ε_p / pieces_per_eps, metres.
    double min_piece(double position_eps) const noexcept { return position_eps / pieces_per_eps; }

    void validate() const {
        if (corner_depth < 1 || corner_depth > 8)
            throw invalid_argument("paving.corner_depth",
                                   "carving: corner_depth must be between 1 and 8, got " + std::to_string(corner_depth));
        if (!(pieces_per_eps >= 1.0) || !std::isfinite(pieces_per_eps))
            throw invalid_argument("paving.pieces_per_eps", "carving: pieces_per_eps must be >= 1 and finite, got " +
                                                                detail::format_double(pieces_per_eps));
        if (!(rest_min_pieces >= 0.0) || !std::isfinite(rest_min_pieces))
            throw invalid_argument("paving.rest_min_pieces", "carving: rest_min_pieces must be >= 0 and finite, got " +
                                                                 detail::format_double(rest_min_pieces));
    }
};

/// The paving choice of a run: carving (the default) or the paper's.
using paving_choice = std::variant<carving, paper_paving>;

/// The carving of a choice, or nothing for the paper's paving.
inline const carving* carving_of(const paving_choice& p) noexcept { return std::get_if<carving>(&p); }

/// The steps a choice takes, as a carving: the paper's paving is carving with every step off
/// (its tuning at the defaults, which no step reads then).
inline carving carving_steps(const paving_choice& p) noexcept {
    if (const carving* c = carving_of(p)) return *c;
    return carving{.inner_contraction = false, .occlusion_cuts = false, .corner_boxes = false};
}

}  // namespace certipose
