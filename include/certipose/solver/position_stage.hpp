// certipose/solver/position_stage.hpp — the position half of the paper's Algorithm 3
// (lines 1–27): pave the position space of one facet with the position constraint set and an
// occlusion policy.
//
// A position box is VALID when the constraint set certifies it *and* the occlusion policy says
// VISIBLE; it is discarded when the set proves it violated or occlusion says OCCLUDED;
// otherwise it is bisected (largest-first by default) down to ε_p and then kept as BOUNDARY.
// Occlusion is only asked about boxes the constraints already certify: elsewhere the box is
// bisected anyway, and the exact occlusion test is the expensive part.
// With `carving` (solve_options::paving, solver/paving.hpp), a partly valid box is not only
// bisected:
//  * Inner contraction: the part of an undecided box that certainly satisfies every constraint
//    is carved off (solver/detail/carving.hpp; the set contracts its complement,
//    ComplementContractingSet) and goes straight to occlusion; only the rest is bisected. The
//    paper gives up a layer about ε_p thick along every constraint boundary; this keeps it.
//  * Occlusion cuts: the part of an occlusion-PARTIAL box outside the shadows of every triangle
//    that may block (ShadowingOcclusionPolicy) is carved off as VALID. The triangles are named
//    by one walk of the occlusion policy's tree per box, and the boxes inside it inherit their
//    shadows: the pieces a carving cuts off a box and its rest share one walk of the whole box.
//  * Corner boxes: of a box the bisector declines and that stays undecided, the largest box
//    certified from one of its corners is VALID and only the rest BOUNDARY (a staircase of
//    `corner_depth` steps along the boundary).
// The stage is one InnerSeparator of the paver, whose state says whether the set already holds
// on the whole box (an ancestor or a carving proved it): such boxes skip the contractor and the
// set's test, which could not remove or decide anything, and go straight to occlusion. A box
// the bisector will not split is asked with occlusion_effort::visible_only (when the policy
// takes it): OCCLUDED would discard it and PARTIAL makes it BOUNDARY, so the costly search for
// an OCCLUDED certificate only decides which of the two non-VALID labels it gets. Such boxes
// are BOUNDARY with reason `occlusion`. OCCLUDED proofs (which prune a box and its subtree) are
// looked for on the boxes the bisector splits only in the paper's paving: with occlusion cuts,
// the shadows decide most of what a proof would, for a fraction of its cost.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <memory>
#include <optional>
#include <stop_token>
#include <utility>
#include <vector>

#include "certipose/bisection/largest_first.hpp"
#include "certipose/constraints/concept.hpp"
#include "certipose/contractor/identity.hpp"
#include "certipose/occlusion/concept.hpp"
#include "certipose/paver/paver.hpp"
#include "certipose/solver/contraction.hpp"
#include "certipose/solver/detail/carving.hpp"
#include "certipose/solver/detail/shadow_walk.hpp"
#include "certipose/solver/paving.hpp"
#include "certipose/solver/task.hpp"

namespace certipose {

namespace detail {
/// What the separator does with a partly valid box: the paving choice, made concrete for one
/// run (the minimal piece in metres), plus what refinement changes.
struct separator_rules {
    carving steps{};       ///< which steps run, and their tuning (all off: the paper's paving)
    double min_piece = 0;  ///< metres
    /// Look for OCCLUDED proofs on the boxes the bisector splits (the paper's paving; off with
    /// occlusion cuts, and in refinement, where they rarely succeed).
    bool occluded_proofs = true;

    /// `steps` decided for the stage's policies (paving_steps).
    static separator_rules from(const carving& steps, double position_eps) {
        return separator_rules{steps, steps.min_piece(position_eps), !steps.occlusion_cuts.is_on()};
    }
};
}  // namespace detail

/// The steps `paving` takes with a constraint set `Set` and an occlusion policy `Occlusion`:
/// each step_switch left to the policies is on when they have its capability (paving.hpp).
/// Throws invalid_argument naming the step and the concept when one is asked for (`true`) and
/// they do not.
template <class Set, class Occlusion, Interval I>
carving paving_steps(const paving_choice& paving) {
    return carving_steps(paving, ComplementContractingSet<Set, I>, ShadowingOcclusionPolicy<Occlusion, I>);
}

/// Counters of the position stage.
struct position_stage_counters {
    std::size_t contractions = 0;      ///< calls to the set's contractor
    std::size_t occlusion_tests = 0;   ///< occlusion classifications (a walk that finds the shadows decides most boxes without one)
    std::size_t inner_pieces = 0;      ///< pieces the set's complement contraction carved off
    std::size_t occlusion_pieces = 0;  ///< VALID pieces carved off occlusion-PARTIAL boxes
    std::size_t corner_boxes = 0;      ///< VALID corner boxes split off leaves
    std::size_t shadow_walks = 0;      ///< tree walks collecting the shadows of possible blockers
    std::size_t refinement_passes = 0; ///< refinement passes that ran (position_refinement)
};

namespace detail {

/// A Contractor that forwards to a constraint set owned elsewhere (the stage's local set), so
/// contraction policies can wrap it without copying the set.
template <class Set, class Box>
struct set_contractor {
    Set* set = nullptr;
    void contract(Box& box) { set->contract(box); }
};

/// The paver's inner separator (see the header comment).
template <class Set, class Contractor, class Occlusion, class Bisector, class I>
struct position_separator {
    using box = position_box<I>;
    struct state {
        bool certified = false;  ///< the constraint set holds on the whole box
        /// How many corner boxes were split off the leaf this box is left of (0: none). A rest
        /// box is not split; below options.steps.corner_depth it may give a corner box of its own.
        std::uint8_t rest = 0;
        /// For a box left undecided by the set where the bisector stops: the constraint that
        /// stayed undecided (the BOUNDARY box's reason), found by the same evaluation as the test.
        std::optional<boundary_reason> why{};
        /// What is known of the sight lines from the box (visible, the shadows of what may
        /// block them, a walk that gave up): found for an ancestor, it serves the boxes inside.
        sight<I> seen{};
        friend bool operator==(const state&, const state&) = default;
    };

    Set* set;
    Contractor contractor;
    const Occlusion* occlusion;
    std::size_t facet;
    Bisector bisector;  // a copy of the paver's: asked only whether it would split the box
    separator_rules options;
    position_stage_counters* count;
    /// The walks for shadows (occlusion cuts), with the facet's cache of prepared shadows.
    shadow_walker<Occlusion, I> walker;

    verdict separate(box& b, state& s, piece_sink<box, state>& sink) {
        const bool leaf = !bisector.choose(b).has_value();
        if (!s.certified) {
            contractor.contract(b);  // Algorithm 1 line 5
            ++count->contractions;
            if (is_empty(b)) return verdict::violated;
            const verdict v = set->test(b);  // lines 10–11
            if (v == verdict::violated) return verdict::violated;
            if (v == verdict::undecided) {
                bool certified = false;
                if constexpr (ComplementContractingSet<Set, I>) {
                    if (options.steps.inner_contraction.is_on() && s.rest == 0) {
                        box failing = b;
                        set->contract_complement(failing);
                        if (is_empty(failing)) {
                            certified = true;  // no position of b violates the set: on to occlusion
                        } else {
                            const box whole = b;
                            std::vector<box> pieces;
                            count->inner_pieces += carve(b, failing, options.min_piece, [&](box&& piece) { pieces.push_back(std::move(piece)); });
                            // The pieces (certified: each asks occlusion) and, for a leaf, the rest
                            // (its corner staircase) would each walk the tree: one walk for the
                            // whole box serves them all. When it gives up, boxes inside walk
                            // again only once they are at most 5/8 as wide (not 1/2 as below a
                            // box of their own: a piece is often much thinner than the whole, and
                            // most pieces' own walks after a failed one give up too).
                            if constexpr (ShadowingOcclusionPolicy<Occlusion, I>) {
                                if (!pieces.empty() && options.steps.occlusion_cuts.is_on() && walker.may_walk(whole, s.seen)) {
                                    bool covered = false;
                                    box reach = box::empty();
                                    if (!walker.walk(whole, s.seen, false, reach, covered)) s.seen.walk_failed_width = 1.25 * max_width(whole);
                                }
                            }
                            for (auto& piece : pieces) {
                                state ps = s;
                                ps.certified = true;
                                sink.pending(std::move(piece), std::move(ps));
                            }
                        }
                    }
                }
                if (!certified) {
                    // Where the bisector stops, the constraint still undecided is the BOUNDARY
                    // box's reason (asked now: the state carries it to the end of the run).
                    if (leaf) s.why = undecided_constraint<I>(*set, b);
                    if (leaf && options.steps.corner_boxes && s.rest < options.steps.corner_depth &&
                        see(b, s, false) != visibility::occluded && (s.seen.visible || s.seen.shadows))
                        return staircase(b, s, sink, [&](const box& q) {
                            return set->test(q) == verdict::satisfied && (s.seen.visible || walker.outside(s.seen.shadows->list, q));
                        }, [&] { s.why = undecided_constraint<I>(*set, b); });
                    return verdict::undecided;
                }
            }
            s.certified = true;
        }
        box blocked = b;  // what the shadows may reach of b (see)
        const visibility seen = see(b, s, prove_occluded(leaf), &blocked);
        if (seen == visibility::visible) return verdict::satisfied;
        if (seen == visibility::occluded) return verdict::violated;
        if (!s.seen.shadows) return verdict::undecided;
        // Occlusion cut: whatever lies outside the hull of the shadows in b sees the facet.
        if (s.rest >= options.steps.corner_depth) return verdict::undecided;
        if (!(blocked == b))
            count->occlusion_pieces += carve(b, blocked, options.min_piece, [&](box&& piece) { sink.valid(std::move(piece)); });
        if (leaf && options.steps.corner_boxes)
            return staircase(b, s, sink, [&](const box& q) { return walker.outside(s.seen.shadows->list, q); }, [] {});
        return verdict::undecided;
    }

private:
    /// Occlusion of b, from what the state knows, the shadows of the triangles that may block
    /// (occlusion cuts: one tree walk, whose shadows the boxes inside b inherit), or one
    /// occlusion test (with `full_effort` for the boxes prove_occluded picks: an OCCLUDED proof
    /// prunes them). The test is asked only when there are no shadows or one of them covers b (no cut
    /// is possible then, but an OCCLUDED proof may prune it). For a PARTIAL box with shadows,
    /// `blocked` receives the hull of what they may reach of b.
    visibility see(const box& b, state& s, bool full_effort, box* blocked = nullptr) {
        if (s.seen.visible) return visibility::visible;
        if (s.seen.shadows) {
            bool covered = false;
            const box reach = walker.shadow_hull(b, s.seen, covered, full_effort);
            if (is_empty(reach)) {
                s.seen.visible = true;
                return visibility::visible;
            }
            if (blocked) *blocked = reach;
            if (!(covered && full_effort)) return visibility::partial;
        } else if constexpr (ShadowingOcclusionPolicy<Occlusion, I>) {
            // One walk of the tree decides VISIBLE (no triangle may block) and finds the
            // shadows for the cuts; the classification's own walk is then needed only to look
            // for an OCCLUDED proof, on a box that one shadow covers whole.
            if (options.steps.occlusion_cuts.is_on() && walker.may_walk(b, s.seen)) {
                bool covered = false;
                box reach = box::empty();
                if (walker.walk(b, s.seen, full_effort, reach, covered)) {
                    if (s.seen.visible) return visibility::visible;
                    if (blocked) *blocked = reach;
                    if (!(covered && full_effort)) return visibility::partial;
                } else {
                    // More triangles may block than the walk lists: a test that only looks
                    // for VISIBLE would find one that blocks and say PARTIAL.
                    if (!full_effort) return visibility::partial;
                }
            }
        }
        ++count->occlusion_tests;
        const visibility seen = classify(b, full_effort);
        if (seen == visibility::visible) s.seen.visible = true;
        return seen;
    }

    /// Is b worth a corner box of its own? A leaf's first always; a rest box (a slab of a leaf
    /// around its corner box) only when no side of it is thinner than `rest_min_pieces` minimal
    /// pieces: thin slabs give many boxes for little volume (carving::rest_min_pieces).
    bool stair_worth(const box& b, const state& s) const {
        if (s.rest == 0) return true;
        for (std::size_t k = 0; k < 3; ++k)
            if (upper(b[k]) - lower(b[k]) < options.steps.rest_min_pieces * options.min_piece) return false;
        return true;
    }

    /// Is an OCCLUDED proof worth looking for on b (occlusion_effort::full)? It discards b and
    /// its subtree, but where it fails it costs many tree walks. The paper's paving asks for
    /// every box the bisector splits; with occlusion cuts the shadows decide most of what a
    /// proof would (separator_rules::occluded_proofs).
    bool prove_occluded(bool leaf) const { return !leaf && options.occluded_proofs; }

    /// A leaf's corner staircase: while another step is worth it, the largest box `certified`
    /// from a corner of b (solver/detail/carving.hpp, corner_box) is VALID and b becomes one of
    /// the rest (split_off), decided here as the others will be: by `certified` whole, else
    /// undecided (`undecided` updates the state's reason).
    template <class Certified, class Undecided>
    verdict staircase(box& b, state& s, piece_sink<box, state>& sink, Certified&& certified, Undecided&& undecided) {
        while (s.rest < options.steps.corner_depth && stair_worth(b, s)) {
            auto inner = corner_box(b, certified, 6);
            if (!inner) break;
            split_off(b, std::move(*inner), s, sink);
            if (is_empty(b)) return verdict::violated;  // nothing left
            if (certified(b)) return verdict::satisfied;
            undecided();
        }
        return verdict::undecided;
    }

    /// `inner` (certified) is VALID; the rest of b, at most six boxes, is BOUNDARY: all but one
    /// go to the sink, b becomes the last.
    void split_off(box& b, box&& inner, state& s, piece_sink<box, state>& sink) {
        ++count->corner_boxes;
        ++s.rest;  // b becomes one of the rest: its reason is asked again at the end
        s.why.reset();
        const state& rest = s;
        std::vector<box> pieces;
        box_difference(b, inner, [&](box&& piece) { pieces.push_back(std::move(piece)); });
        sink.valid(std::move(inner));
        if (pieces.empty()) {  // the corner box is all of b: b is done
            b = box::empty();
            return;
        }
        for (std::size_t i = 0; i + 1 < pieces.size(); ++i) sink.pending(std::move(pieces[i]), rest);
        b = std::move(pieces.back());
    }

    visibility classify(const box& b, bool full_effort) const {
        if constexpr (EffortAwareOcclusionPolicy<Occlusion, I>)
            return occlusion->classify(b, facet, full_effort ? occlusion_effort::full : occlusion_effort::visible_only);
        else
            return occlusion->classify(b, facet);
    }
};

}  // namespace detail

/// A refinement pass after the paving at ε_p (solve_options::refine): the BOUNDARY boxes are
/// paved again, largest first, down to `min_width`, until `deadline`.
struct position_refinement {
    double min_width = 0.0;
    std::optional<std::chrono::steady_clock::time_point> deadline{};
};

/// Result of the position stage for one facet.
template <Interval I>
struct position_stage_result {
    certipose::paving<position_box<I>> boxes;  ///< VALID, BOUNDARY (and pending) position boxes
    /// Why each BOUNDARY box of `boxes.boundary` (same order) was left undecided.
    std::vector<boundary_reason> boundary_reasons;
    position_box<I> initial_box;
    position_stage_counters counters;
    bool refinement_stopped = false;  ///< the refinement's deadline ended it (boxes left BOUNDARY)
};

/// A contractor that owns the constraint set it is built on: `Contraction`'s contractor on a
/// set of its own (pose_solver::position_contractor). Movable: the set stays where it is.
template <class Set, class Contraction, Interval I>
class owning_contractor {
    using set_contractor_type = detail::set_contractor<Set, position_box<I>>;

public:
    using contractor_type = decltype(std::declval<const Contraction&>().wrap(std::declval<set_contractor_type>()));

    owning_contractor(Set set, const Contraction& contraction)
        : set_(std::make_unique<Set>(std::move(set))), contractor_(contraction.wrap(set_contractor_type{set_.get()})) {}

    void contract(position_box<I>& box) { contractor_.contract(box); }
    /// The set it is built on (e.g. for its `initial_box()`).
    Set& constraint_set() noexcept { return *set_; }
    const Set& constraint_set() const noexcept { return *set_; }

private:
    std::unique_ptr<Set> set_;
    contractor_type contractor_;
};

/// The position stage for one facet (Algorithm 3 lines 1–27), as two named steps: `pave` at ε_p
/// with the paving choice, then optionally `refine` its BOUNDARY boxes below ε_p. It owns the
/// facet's constraint set, the contractor the contraction policy builds on it (`contractor()`:
/// what the stage runs, for tests and benchmarks) and the shadow cache both steps share.
/// `Bisector` is constructible from the width below which boxes are not split; `Buffer` orders
/// the unclassified boxes of `pave` (refinement takes the largest first).
template <Interval I, class Set, class Occlusion, class Contraction = contraction::set_only,
          class Bisector = largest_first, class Buffer = depth_first>
    requires SearchableConstraintSet<Set, I> && OcclusionPolicy<Occlusion, I> && ContractionPolicy<Contraction, I>
class position_stage {
    using set_contractor_type = detail::set_contractor<Set, position_box<I>>;

public:
    using contractor_type = decltype(std::declval<const Contraction&>().wrap(std::declval<set_contractor_type>()));

    /// Throws invalid_argument when the paving choice asks for a step the policies cannot take
    /// (paving_steps) or the set's parameters are bad.
    position_stage(const position_problem& problem, std::size_t facet_index, const Occlusion& occlusion,
                   const paving_choice& paving, double position_eps, const constraint_parameters_t<Set>& parameters = {},
                   Contraction contraction = {})
        : set_(std::make_unique<Set>(make_constraint_set<Set>(problem, parameters))),
          contraction_(std::move(contraction)),
          occlusion_(&occlusion),
          facet_(facet_index),
          position_eps_(position_eps),
          rules_(detail::separator_rules::from(paving_steps<Set, Occlusion, I>(paving), position_eps)) {}

    /// The contractor the stage narrows boxes with: the contraction policy's, on the set's.
    /// It refers to this stage's set: use it while the stage lives.
    contractor_type contractor() const { return contraction_.wrap(set_contractor_type{set_.get()}); }
    Set& constraint_set() const noexcept { return *set_; }

    /// Paves from the set's initial box down to ε_p.
    position_stage_result<I> pave(const paver_options& options, std::stop_token stop = {}) {
        position_stage_result<I> out;
        out.initial_box = set_->initial_box();
        states_.clear();
        if (is_empty(out.initial_box)) {
            out.boxes.stats.reason = termination::completed;
            return out;
        }
        paver<position_box<I>, identity, separator, Bisector, Buffer> p(
            identity{}, make_separator(rules_, position_eps_, out.counters), Bisector(position_eps_), options);
        out.boxes = p.run(out.initial_box, stop);
        states_ = p.boundary_states();
        return out;
    }

    /// Paves the BOUNDARY boxes of a completed `pave` again, largest first, down to
    /// `refine.min_width`, until its deadline (solve_options::refine). Refined leaves give one
    /// corner box each (the refinement is itself the staircase), and no OCCLUDED proofs are
    /// looked for (nearly every box this deep has halves that would be split again, and the
    /// proofs rarely succeed). Two passes: first the boxes the set left undecided, then those it
    /// certified and occlusion left PARTIAL, much of whose volume is truly occluded.
    void refine(position_stage_result<I>& out, const position_refinement& refine, const paver_options& options,
                std::stop_token stop = {});

    /// Why each BOUNDARY box of `out` was left undecided (position_stage_result::boundary_reasons).
    void explain(position_stage_result<I>& out) const;

private:
    using separator = detail::position_separator<Set, contractor_type, Occlusion, Bisector, I>;
    using state = typename separator::state;

    separator make_separator(const detail::separator_rules& rules, double split_width,
                             position_stage_counters& counters) const {
        return separator{set_.get(), contractor(), occlusion_, facet_, Bisector(split_width), rules, &counters,
                         detail::shadow_walker<Occlusion, I>(occlusion_, facet_, shadows_, &counters.shadow_walks)};
    }

    std::unique_ptr<Set> set_;  // stable address: contractors and separators point at it
    Contraction contraction_;
    const Occlusion* occlusion_;
    std::size_t facet_;
    double position_eps_;
    detail::separator_rules rules_;
    // One shadow cache for both steps: the states `pave` hands `refine` hold shadows from it.
    std::shared_ptr<detail::shadow_cache<I>> shadows_ = std::make_shared<detail::shadow_cache<I>>();
    std::vector<state> states_;  // of the BOUNDARY boxes, in their order
};

template <Interval I, class Set, class Occlusion, class Contraction, class Bisector, class Buffer>
    requires SearchableConstraintSet<Set, I> && OcclusionPolicy<Occlusion, I> && ContractionPolicy<Contraction, I>
void position_stage<I, Set, Occlusion, Contraction, Bisector, Buffer>::refine(position_stage_result<I>& out,
                                                                              const position_refinement& refine,
                                                                              const paver_options& options,
                                                                              std::stop_token stop) {
    if (out.boxes.stats.reason != termination::completed || out.boxes.boundary.empty()) return;
    std::vector<state>& states = states_;
    for (auto& st : states) st.rest = 0;
    paver_options again = options;
    if (refine.deadline && (!again.deadline || *refine.deadline < *again.deadline)) again.deadline = refine.deadline;
    again.record_tree = false;
    detail::separator_rules fine_rules = rules_;
    fine_rules.steps.corner_depth = 1;
    fine_rules.occluded_proofs = false;
    auto& st = out.boxes.stats;
    // BOUNDARY boxes with their separator states, side by side (run_from takes both).
    struct boundary_list {
        std::vector<position_box<I>> boxes;
        std::vector<state> states;
    };
    // Moves out.boxes.boundary / states into `certified` (the set certified them: PARTIAL
    // for occlusion) and `rest`, keeping their order.
    const auto sort_out = [&](boundary_list& certified, boundary_list& rest) {
        for (std::size_t i = 0; i < states.size(); ++i) {
            boundary_list& to = states[i].certified ? certified : rest;
            to.boxes.push_back(std::move(out.boxes.boundary[i]));
            to.states.push_back(std::move(states[i]));
        }
        out.boxes.boundary.clear(), states.clear();
    };
    const auto append = [&](boundary_list& from) {
        for (std::size_t i = 0; i < from.boxes.size(); ++i)
            out.boxes.boundary.push_back(std::move(from.boxes[i])), states.push_back(std::move(from.states[i]));
        from = {};
    };
    boundary_list later, refined;  // refined: BOUNDARY boxes of the passes that ran
    {
        boundary_list first;
        sort_out(later, first);
        append(first);
    }
    for (int pass = 0; pass < 2; ++pass) {
        if (pass == 1) {
            // Reached only when pass 0 completed or had nothing to refine (the end of the
            // loop breaks otherwise). The first pass's occlusion-only boxes join the
            // second; its set-undecided ones are at the refinement's width already.
            sort_out(later, refined);
            append(later);
        }
        if (out.boxes.boundary.empty()) continue;
        again.max_boxes = options.max_boxes > st.boxes ? options.max_boxes - st.boxes : 1;
        paver<position_box<I>, identity, separator, Bisector, largest_volume_first> q(
            identity{}, make_separator(fine_rules, refine.min_width, out.counters), Bisector(refine.min_width), again);
        auto more = q.run_from(out.boxes.boundary, states, stop);
        ++out.counters.refinement_passes;
        const auto now = std::chrono::steady_clock::now();
        out.refinement_stopped = more.stats.reason == termination::deadline && refine.deadline &&
                                 now >= *refine.deadline && !(options.deadline && now >= *options.deadline);
        st.boxes += more.stats.boxes, st.bisections += more.stats.bisections, st.inner_tests += more.stats.inner_tests;
        st.valid += more.stats.valid, st.valid_volume += more.stats.valid_volume;
        st.discarded += more.stats.discarded, st.discarded_volume += more.stats.discarded_volume;
        st.peak_pending = std::max(st.peak_pending, more.stats.peak_pending);
        if (!out.refinement_stopped) st.reason = more.stats.reason;
        for (auto& v : more.valid) out.boxes.valid.push_back(std::move(v));
        out.boxes.boundary = std::move(more.boundary);
        states = q.boundary_states();
        if (out.refinement_stopped) {
            // Not refined yet, but decided as far as the paving at ε_p went: BOUNDARY, for
            // the reason the set gives.
            for (auto& b : more.pending) {
                out.boxes.boundary.push_back(std::move(b));
                states.emplace_back();
            }
        } else {
            out.boxes.pending = std::move(more.pending);
            st.pending = more.stats.pending, st.pending_volume = more.stats.pending_volume;
        }
        if (st.reason != termination::completed || out.refinement_stopped) break;
    }
    // What no pass reached (a stopped first pass leaves the second kind as it was), then
    // what the passes left.
    append(later);
    append(refined);
    st.boundary = out.boxes.boundary.size();
    st.boundary_volume = 0;
    for (const auto& b : out.boxes.boundary) st.boundary_volume += detail::paving_volume(b);
}

template <Interval I, class Set, class Occlusion, class Contraction, class Bisector, class Buffer>
    requires SearchableConstraintSet<Set, I> && OcclusionPolicy<Occlusion, I> && ContractionPolicy<Contraction, I>
void position_stage<I, Set, Occlusion, Contraction, Bisector, Buffer>::explain(position_stage_result<I>& out) const {
    // A BOUNDARY box was separated just before the bisector declined it: undecided by the set
    // (which constraint, if it says: one more test), or certified by it and PARTIAL for occlusion.
    out.boundary_reasons.clear();
    out.boundary_reasons.reserve(out.boxes.boundary.size());
    for (std::size_t i = 0; i < out.boxes.boundary.size(); ++i) {
        const state* s = i < states_.size() ? &states_[i] : nullptr;
        out.boundary_reasons.push_back(
            s && s->certified ? boundary_reason::occlusion
            : s && s->why     ? *s->why
                              : undecided_constraint<I>(*set_, out.boxes.boundary[i]).value_or(boundary_reason::occlusion));
    }
}

/// Paves the positions of one facet with a `position_stage`: `pave`, `refine` when asked, and
/// the BOUNDARY boxes' reasons. `Set` is built from `problem` and `parameters`.
template <Interval I, class Set, class Contraction = contraction::set_only, class Bisector = largest_first,
          class Buffer = depth_first, class Occlusion>
    requires SearchableConstraintSet<Set, I> && OcclusionPolicy<Occlusion, I> && ContractionPolicy<Contraction, I>
position_stage_result<I> pave_positions(const position_problem& problem, std::size_t facet_index,
                                        const Occlusion& occlusion, const paver_options& options,
                                        double position_eps, std::stop_token stop = {},
                                        const constraint_parameters_t<Set>& parameters = {},
                                        const paving_choice& paving = {},
                                        const std::optional<position_refinement>& refine = {},
                                        Contraction contraction = {}) {
    position_stage<I, Set, Occlusion, Contraction, Bisector, Buffer> stage(problem, facet_index, occlusion, paving,
                                                                           position_eps, parameters,
                                                                           std::move(contraction));
    position_stage_result<I> out = stage.pave(options, stop);
    if (refine) stage.refine(out, *refine, options, stop);
    stage.explain(out);
    return out;
}

}  // namespace certipose
