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
// `carving` holds the stage's tuning, in units of ε_p, each with a default. Two of its steps
// need a capability of a policy: inner contraction a ComplementContractingSet, occlusion cuts a
// ShadowingOcclusionPolicy. Each is a `step_switch`, by default on exactly when the run's
// policies have the capability (as CGAL's named parameters take a default from the traits), so
// `carving{}` serves every pipeline and no caller works out what its policies can do. `true`
// asks for the step: for policies without the capability that is an error (invalid_argument
// naming the step and the concept, when the position stage is built), never a silent change of
// algorithm; `false` turns it off. The steps a run took are `pose_solver::paving_steps` and
// `solve_stats::paving`, with every switch decided.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <variant>

#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"

namespace certipose {

/// The paper's paving: partly valid boxes are bisected, nothing else.
struct paper_paving {
    void validate() const {}
};

/// A carving step that needs a capability of a policy: on, off, or (the default) on exactly when
/// the run's policies have it (see the header comment). `true` and `false` convert to it, so
/// `carving{.occlusion_cuts = false}` reads as before.
class step_switch {
public:
    constexpr step_switch() noexcept = default;
    constexpr step_switch(bool on) noexcept : state_(on ? state::on : state::off) {}  // NOLINT: a switch is set with a bool
    /// The default: on when the policies can serve the step.
    static constexpr step_switch when_available() noexcept { return {}; }

    /// Left to the policies (the default).
    constexpr bool follows_policies() const noexcept { return state_ == state::automatic; }
    /// Asked for with `true`: policies without the capability are an error.
    constexpr bool required() const noexcept { return state_ == state::on; }
    /// Whether the step runs for policies that have (`available`) or lack its capability.
    constexpr bool decide(bool available) const noexcept { return state_ == state::automatic ? available : state_ == state::on; }
    /// On, once decided (pose_solver::paving_steps, solve_stats::paving): a switch still left to
    /// the policies is not on.
    constexpr bool is_on() const noexcept { return state_ == state::on; }

    friend constexpr bool operator==(step_switch, step_switch) noexcept = default;

private:
    enum class state : std::uint8_t { automatic, on, off };
    state state_ = state::automatic;
};

/// Carving past the paper (solver/position_stage.hpp, solver/detail/carving.hpp).
struct carving {
    /// Carve the part of a partly valid box that certainly satisfies the constraint set off it
    /// (needs a ComplementContractingSet; by default on when the set is one).
    step_switch inner_contraction{};
    /// Carve the certainly visible part off a box that occlusion leaves PARTIAL (needs a
    /// ShadowingOcclusionPolicy; by default on when the occlusion policy is one).
    step_switch occlusion_cuts{};
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

/// The steps a choice takes for policies that have (or lack) each step's capability, as a
/// carving with every switch decided: the paper's paving is carving with every step off (its
/// tuning at the defaults, which no step reads then). Throws invalid_argument naming the step
/// and the concept when a step is asked for (`true`) and the policies lack its capability.
/// pose_solver::paving_steps calls it with its own policies' capabilities.
inline carving carving_steps(const paving_choice& p, bool complement_contracting_set, bool shadowing_occlusion) {
    const carving* c = carving_of(p);
    if (!c) return carving{.inner_contraction = false, .occlusion_cuts = false, .corner_boxes = false};
    if (c->inner_contraction.required() && !complement_contracting_set)
        throw invalid_argument("paving.inner_contraction",
                               "carving: inner contraction needs a constraint set modelling "
                               "certipose::ComplementContractingSet (contract_complement); this one does not: leave "
                               "carving::inner_contraction to the policies or set it to false");
    if (c->occlusion_cuts.required() && !shadowing_occlusion)
        throw invalid_argument("paving.occlusion_cuts",
                               "carving: occlusion cuts need an occlusion policy modelling "
                               "certipose::ShadowingOcclusionPolicy (blockers, shadow), e.g. aabb_occlusion; this "
                               "one does not: leave carving::occlusion_cuts to the policies or set it to false");
    carving out = *c;
    out.inner_contraction = c->inner_contraction.decide(complement_contracting_set);
    out.occlusion_cuts = c->occlusion_cuts.decide(shadowing_occlusion);
    return out;
}

}  // namespace certipose
