// certipose/solver/position_stage.hpp — the position half of the paper's Algorithm 3
// (lines 1–27): pave the position space of one facet with the position constraint set and an
// occlusion policy.
//
// A position box is VALID when the constraint set certifies it *and* the occlusion policy says
// VISIBLE; it is discarded when the set proves it violated or occlusion says OCCLUDED;
// otherwise it is bisected (largest-first by default) down to ε_p and then kept as BOUNDARY.
// Occlusion is only asked about boxes the constraints already certify: elsewhere the box is
// bisected anyway, and the exact occlusion test is the expensive part.
// Past the paper, a partly valid box is not only bisected (position_stage_options):
//  * Inner contraction: when the set can contract its complement (ComplementContractingSet),
//    the part of an undecided box that certainly satisfies every constraint is carved off
//    (solver/detail/carving.hpp) and goes straight to occlusion; only the rest is bisected. The
//    paper gives up a layer about ε_p thick along every constraint boundary; this keeps it.
//  * Occlusion cuts: when the occlusion policy can name the shadows of the triangles that may
//    block (ShadowingOcclusionPolicy), the part of an occlusion-PARTIAL box outside all of them
//    is carved off as VALID. The triangles that may block are named by one walk of the occlusion
//    policy's tree per box, and the boxes inside it inherit their shadows: the pieces a carving
//    cuts off a box and its rest share one walk of the whole box.
// The stage is one InnerSeparator of the paver, whose state says whether the set already holds
// on the whole box (an ancestor or a carving proved it): such boxes skip the contractor and the
// set's test, which could not remove or decide anything, and go straight to occlusion. A box
// the bisector will not split is asked with occlusion_effort::visible_only (when the policy
// takes it): OCCLUDED would discard it and PARTIAL makes it BOUNDARY, so the costly search for
// an OCCLUDED certificate only decides which of the two non-VALID labels it gets. Such boxes
// are BOUNDARY with reason `occlusion`. With occlusion cuts, no box is asked for an OCCLUDED
// proof unless position_stage_options::occluded_proofs_with_cuts says so (then only boxes whose
// halves would be split again; position_separator::prove_occluded).
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
#include "certipose/solver/task.hpp"

namespace certipose {

/// The position stage's options beyond the paper (solve_options carries them).
struct position_stage_options {
    /// Carve the part of an undecided box that certainly satisfies the constraint set off it
    /// (sets modelling ComplementContractingSet; the paper's set does).
    bool inner_contraction = true;
    /// Carve the certainly visible part off an occlusion-PARTIAL box (occlusion policies
    /// modelling ShadowingOcclusionPolicy; aabb_occlusion does).
    bool occlusion_cuts = true;
    /// Pieces thinner than this (metres, in the dimension they are cut in) stay with the rest;
    /// 0: a tenth of the bisector's precision.
    double min_piece = 0.0;
    /// Leaf corner boxes: of a box the bisector declines and that stays undecided, the largest
    /// box certified from one of its corners (solver/detail/carving.hpp, corner_box) is VALID
    /// and only the rest BOUNDARY. Its visibility costs one occlusion test (or the shadows).
    bool leaf_corner_boxes = true;
    /// Corner boxes split off one leaf in a row: the rest of a leaf's corner box may give one
    /// of its own, and so on, this many times (a staircase along the boundary; at most 255).
    std::size_t corner_depth = 2;
    /// A rest box gives a corner box only when no side of it is thinner than this many
    /// `min_piece` (solve_options::corner_rest_min_pieces).
    double corner_rest_min_pieces = 3.0;
    /// Look for OCCLUDED proofs (which prune a box and its subtree) on the boxes the bisector
    /// splits (position_separator::prove_occluded): without occlusion cuts (the paper's paving)
    /// on every such box, with them only as `occluded_proofs_with_cuts` says.
    bool occluded_proofs = true;
    /// With occlusion cuts, look for OCCLUDED proofs on the boxes whose halves would be split
    /// again. Off by default: on every 20th facet of the four reference parts they pruned 1.7 %
    /// of the BOUNDARY boxes (fewer, larger ones instead) for 22 % of the run's time, and no
    /// VALID box changed; the cuts' shadows decide most of what a proof would.
    bool occluded_proofs_with_cuts = false;
};

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
        bool visible = false;    ///< occlusion: VISIBLE from the whole box
        /// How many corner boxes were split off the leaf this box is left of (0: none). A rest
        /// box is not split; below options.corner_depth it may give a corner box of its own.
        std::uint8_t rest = 0;
        /// For a box left undecided by the set where the bisector stops: the constraint that
        /// stayed undecided (the BOUNDARY box's reason), found by the same evaluation as the test.
        std::optional<boundary_reason> why{};
        /// The shadows of every triangle that may block a sight line from the box (found for
        /// an ancestor: one tree walk serves all the boxes below it); null until needed. The
        /// set owns the cache it points into: the state may outlive this separator (refinement).
        std::shared_ptr<const shadow_set<I>> shadows{};
        /// After a walk for shadows gave up (too many possible blockers, or not strictly in
        /// front of the facet): the largest width of the box it walked, or 1.25 times that for
        /// the whole box of a carving, whose pieces are often much thinner (see separate); 0:
        /// none did. The walk is asked again only for boxes at most half this wide: one just a
        /// little smaller would almost surely give up too, and each failed walk costs as much
        /// as a successful one.
        double walk_failed_width = 0;
        friend bool operator==(const state&, const state&) = default;
    };

    Set* set;
    Contractor contractor;
    const Occlusion* occlusion;
    std::size_t facet;
    Bisector bisector;  // a copy of the paver's: asked only whether it would split the box
    position_stage_options options;
    double min_piece;
    position_stage_counters* count;
    /// Prepared shadows by triangle, shared by the separators of one facet's passes (a copy of
    /// a separator shares it too: one facet's paving runs on one thread).
    std::shared_ptr<shadow_cache<I>> cache = std::make_shared<shadow_cache<I>>();
    std::vector<std::size_t> found_{};  // the triangles one walk names, and their shadows
    shadow_list<I> named_{};            // (kept: no allocation per walk)

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
                    if (options.inner_contraction && s.rest == 0) {
                        box failing = b;
                        set->contract_complement(failing);
                        if (is_empty(failing)) {
                            certified = true;  // no position of b violates the set: on to occlusion
                        } else {
                            const box whole = b;
                            std::vector<box> pieces;
                            count->inner_pieces += carve(b, failing, min_piece, [&](box&& piece) { pieces.push_back(std::move(piece)); });
                            // The pieces (certified: each asks occlusion) and, for a leaf, the rest
                            // (its corner staircase) would each walk the tree: one walk for the
                            // whole box serves them all. When it gives up, boxes inside walk
                            // again only once they are at most 5/8 as wide (not 1/2 as below a
                            // box of their own: a piece is often much thinner than the whole).
                            // Of the pieces' own walks after a failed one, 84 % gave up too
                            // (featuretype, facet 3262); on every 20th facet of the four
                            // reference parts this rule was 2-7 % faster than always walking
                            // again, with slightly more VALID boxes and volume on each part.
                            if constexpr (ShadowingOcclusionPolicy<Occlusion, I>) {
                                if (!pieces.empty() && options.occlusion_cuts && may_walk(whole, s)) {
                                    bool covered = false;
                                    box reach = box::empty();
                                    if (!walk(whole, s, false, reach, covered)) s.walk_failed_width = 1.25 * max_width(whole);
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
                    if (leaf && options.leaf_corner_boxes && s.rest < options.corner_depth &&
                        see(b, s, false) != visibility::occluded && (s.visible || s.shadows))
                        return staircase(b, s, sink, [&](const box& q) {
                            return set->test(q) == verdict::satisfied && (s.visible || outside(s.shadows->list, q));
                        }, [&] { s.why = undecided_constraint<I>(*set, b); });
                    return verdict::undecided;
                }
            }
            s.certified = true;
        }
        box blocked = b;  // what the shadows may reach of b (see)
        const visibility seen = see(b, s, prove_occluded(b, leaf), &blocked);
        if (seen == visibility::visible) return verdict::satisfied;
        if (seen == visibility::occluded) return verdict::violated;
        if (!s.shadows) return verdict::undecided;
        // Occlusion cut: whatever lies outside the hull of the shadows in b sees the facet.
        if (s.rest >= options.corner_depth) return verdict::undecided;
        if (!(blocked == b))
            count->occlusion_pieces += carve(b, blocked, min_piece, [&](box&& piece) { sink.valid(std::move(piece)); });
        if (leaf && options.leaf_corner_boxes)
            return staircase(b, s, sink, [&](const box& q) { return outside(s.shadows->list, q); }, [] {});
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
        if (s.visible) return visibility::visible;
        if (s.shadows) {
            bool covered = false;
            const box reach = shadow_hull(b, s, covered, full_effort);
            if (is_empty(reach)) {
                s.visible = true;
                return visibility::visible;
            }
            if (blocked) *blocked = reach;
            if (!(covered && full_effort)) return visibility::partial;
        } else if constexpr (ShadowingOcclusionPolicy<Occlusion, I>) {
            // One walk of the tree decides VISIBLE (no triangle may block) and finds the
            // shadows for the cuts; the classification's own walk is then needed only to look
            // for an OCCLUDED proof, on a box that one shadow covers whole.
            if (options.occlusion_cuts && may_walk(b, s)) {
                bool covered = false;
                box reach = box::empty();
                if (walk(b, s, full_effort, reach, covered)) {
                    if (s.visible) return visibility::visible;
                    if (blocked) *blocked = reach;
                    if (!(covered && full_effort)) return visibility::partial;
                } else {
                    // More triangles may block than the walk lists: a test that only looks
                    // for VISIBLE would find one that blocks and say PARTIAL (on every 20th
                    // facet of the four reference parts, asking it changed no VALID box).
                    if (!full_effort) return visibility::partial;
                }
            }
        }
        ++count->occlusion_tests;
        const visibility seen = classify(b, full_effort);
        if (seen == visibility::visible) s.visible = true;
        return seen;
    }

    /// Is a walk for b's shadows worth it? Not within a box whose walk gave up unless b is at
    /// most half of state::walk_failed_width wide.
    static bool may_walk(const box& b, const state& s) {
        return !s.visible && !s.shadows && (s.walk_failed_width == 0 || max_width(b) <= s.walk_failed_width / 2);
    }

    /// One walk of the tree for b: the shadows of the triangles that may block a sight line from
    /// b go to s.shadows (those that may reach b; s.visible when none does), `reach` receives
    /// the hull of what they reach of b and `covered` whether one covers all of b (asked only
    /// with `need_covered`). False when the walk gave up (s.walk_failed_width records it).
    bool walk(const box& b, state& s, bool need_covered, box& reach, bool& covered) {
        // The walk only names the triangles; their shadows are contracted after it, so a walk
        // that gives up costs no contraction.
        found_.clear();
        auto note = [&](std::size_t triangle) {
            found_.push_back(triangle);
            return true;
        };
        ++count->shadow_walks;
        if (!occlusion->blockers(b, facet, note)) {
            s.walk_failed_width = max_width(b);
            return false;
        }
        named_.clear();
        for (const std::size_t triangle : found_)
            named_.push_back(&cache->get(triangle, [&] { return occlusion->shadow(facet, triangle); }));
        auto found = std::make_shared<shadow_set<I>>();
        found->storage = cache;
        reach = reach_in(b, named_, found->list, covered, need_covered);
        if (found->list.empty()) s.visible = true;
        else s.shadows = std::move(found);
        return true;
    }

    /// Calls visit(shadow, part) for each shadow of `list` that reaches b, with `part` what it
    /// reaches of b (b contracted to the shadow), until visit returns false.
    template <class Visit>
    static void for_each_reaching(const box& b, const shadow_list<I>& list, Visit&& visit) {
        const rounding_guard<I> rounding;
        for (const auto* sh : list) {
            box part = b;
            contract_shadow(part, *sh);
            if (!is_empty(part) && !visit(sh, part)) return;
        }
    }

    /// The hull of the parts of b that the shadows of `list` may reach (empty: none does); the
    /// shadows that may reach b are appended to `kept`, and `covered` says whether one reaches
    /// all of b (asked only with `need_covered`: without, it may stay false once the hull is b).
    static box reach_in(const box& b, const shadow_list<I>& list, shadow_list<I>& kept, bool& covered,
                        bool need_covered) {
        box reach = box::empty();
        const rounding_guard<I> rounding;
        for (const auto* sh : list) {
            if (!(need_covered && !covered) && reach == b) {
                // The hull is all of b already: what is left to ask of a shadow is whether it
                // may reach b (the boxes inside b contract against it again). A box with many
                // possible blockers reaches this after a few; contracting the other shadows took
                // half the time of a fresh walk's list (idler_riser, facet 102).
                if (shadow_may_reach(b, *sh)) kept.push_back(sh);
                continue;
            }
            box part = b;
            contract_shadow(part, *sh);
            if (is_empty(part)) continue;
            kept.push_back(sh);
            reach = hull(reach, part);
            covered = covered || part == b;
        }
        return reach;
    }

    /// The hull of the parts of b that the state's shadows may reach (empty: b sees the facet);
    /// `covered`: one of them reaches all of b. Drops the shadows that miss b when that leaves
    /// at most half of them: the boxes inside b then contract against fewer (the list is
    /// shared with other boxes, so it is copied).
    static box shadow_hull(const box& b, state& s, bool& covered, bool need_covered) {
        shadow_list<I> kept;
        const box reach = reach_in(b, s.shadows->list, kept, covered, need_covered);
        if (!kept.empty() && 2 * kept.size() <= s.shadows->list.size())
            s.shadows = std::make_shared<const shadow_set<I>>(shadow_set<I>{s.shadows->storage, std::move(kept)});
        return reach;
    }

    /// Is b worth a corner box of its own? A leaf's first always; a rest box (a slab of a leaf
    /// around its corner box) only when no side of it is thinner than
    /// `corner_rest_min_pieces` minimal pieces: thin slabs gave many boxes for little volume
    /// (the four reference cases at corner_depth 2, 2 pieces against none: 25 % fewer VALID
    /// boxes, a median share 62 % instead of 64 %; 3 against 2: docs/completeness.md).
    bool stair_worth(const box& b, const state& s) const {
        if (s.rest == 0) return true;
        for (std::size_t k = 0; k < 3; ++k)
            if (upper(b[k]) - lower(b[k]) < options.corner_rest_min_pieces * min_piece) return false;
        return true;
    }

    /// Is an OCCLUDED proof worth looking for on b (occlusion_effort::full)? It discards b and
    /// its subtree, but where it fails it costs ~15 tree walks. The paper (no occlusion cuts)
    /// asks for every box the bisector splits. With the cuts, most such boxes are a little
    /// wider than ε_p, with halves that are leaves: pruning them saves two cheap tests, and
    /// on every 20th facet of the four reference parts the proof succeeded for 2.5–13 % of them.
    /// Asking only boxes whose halves would be split again took 8–24 % off the run for
    /// 0.2–2.2 % more BOUNDARY boxes and the same VALID ones; since the pieces of a carving
    /// share one walk, asking none (the default, occluded_proofs_with_cuts) takes 22 % more
    /// for 1.7 % more BOUNDARY boxes, again with the same VALID ones.
    bool prove_occluded(const box& b, bool leaf) {  // not const: a bisector may count its choices (round_robin)
        if (leaf || !options.occluded_proofs) return false;
        if (!options.occlusion_cuts) return true;
        if (!options.occluded_proofs_with_cuts) return false;
        const auto cut = bisector.choose(b);
        if (!cut) return false;
        box lo = b, hi = b;
        lo[cut->dimension] = I(lower(b[cut->dimension]), cut->point);
        hi[cut->dimension] = I(cut->point, upper(b[cut->dimension]));
        return bisector.choose(lo).has_value() || bisector.choose(hi).has_value();
    }

    /// No point of q lies in a shadow of the list.
    static bool outside(const shadow_list<I>& list, const box& q) {
        bool none = true;
        for_each_reaching(q, list, [&](const prepared_shadow<I>*, const box&) { return none = false; });
        return none;
    }

    /// A leaf's corner staircase: while another step is worth it, the largest box `certified`
    /// from a corner of b (solver/detail/carving.hpp, corner_box) is VALID and b becomes one of
    /// the rest (split_off), decided here as the others will be: by `certified` whole, else
    /// undecided (`undecided` updates the state's reason).
    template <class Certified, class Undecided>
    verdict staircase(box& b, state& s, piece_sink<box, state>& sink, Certified&& certified, Undecided&& undecided) {
        while (s.rest < options.corner_depth && stair_worth(b, s)) {
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

/// Paves the positions of one facet. `Set` models PositionConstraintSet over I and is built from
/// `problem` and `parameters`; `Contraction` is a contraction policy (solver/contraction.hpp);
/// `Bisector` is constructible from ε_p (`position_eps`, the width below which boxes are not
/// split); `Buffer` orders the unclassified boxes.
template <Interval I, class Set, class Contraction = contraction::hc4, class Bisector = largest_first,
          class Buffer = depth_first, class Occlusion>
    requires SearchableConstraintSet<Set, I> && OcclusionPolicy<Occlusion, I>
position_stage_result<I> pave_positions(const position_problem& problem, std::size_t facet_index,
                                        const Occlusion& occlusion, const paver_options& options,
                                        double position_eps, std::stop_token stop = {},
                                        const constraint_parameters_t<Set>& parameters = {},
                                        const position_stage_options& stage = {},
                                        const std::optional<position_refinement>& refine = {}) {
    Set set = make_constraint_set<Set>(problem, parameters);
    position_stage_result<I> out;
    out.initial_box = set.initial_box();
    if (is_empty(out.initial_box)) {
        out.boxes.stats.reason = termination::completed;
        return out;
    }
    auto contractor = Contraction::wrap(detail::set_contractor<Set, position_box<I>>{&set});
    using separator = detail::position_separator<Set, decltype(contractor), Occlusion, Bisector, I>;
    // One shadow cache for every pass: the states a pass hands the next hold shadows from it.
    const auto shadows = std::make_shared<detail::shadow_cache<I>>();
    separator sep{&set, std::move(contractor), &occlusion, facet_index, Bisector(position_eps), stage,
                  stage.min_piece > 0.0 ? stage.min_piece : position_eps / 10, &out.counters, shadows};
    paver<position_box<I>, identity, separator, Bisector, Buffer> p(identity{}, std::move(sep), Bisector(position_eps),
                                                                    options);
    out.boxes = p.run(out.initial_box, stop);
    std::vector<typename separator::state> states = p.boundary_states();
    if (refine && out.boxes.stats.reason == termination::completed && !out.boxes.boundary.empty()) {
        // Refinement: the BOUNDARY boxes again, with what was learnt about each (the set holds,
        // it sees the facet, its shadows), largest first, under the refinement's deadline.
        for (auto& st : states) st.rest = 0;
        paver_options again = options;
        if (refine->deadline && (!again.deadline || *refine->deadline < *again.deadline)) again.deadline = refine->deadline;
        again.record_tree = false;
        // Refined leaves give one corner box each: the refinement itself is the staircase, and
        // deeper ones multiply the small boxes the orientation stage must still get through
        // before the run's deadline (plate_holes, 1 s: 38 % of the true positions certified
        // with one, 24 % with two).
        position_stage_options fine_stage = stage;
        fine_stage.corner_depth = 1;
        // No OCCLUDED proofs: down to ε_p / 16 nearly every box has halves that would be split
        // again, so prove_occluded's rule asks one of nearly every box a shadow covers; they
        // rarely succeed and took half of angle_block's refinement time. Without them the
        // refinement gets through 2.5-4x the boxes in the same time (truly occluded ones are
        // bisected and left BOUNDARY instead of pruned): at 1 s with growth, 89.2 / 74.2 /
        // 81.6 / 88.6 % of the true positions certified became 90.2 / 75.7 / 87.5 / 88.9 %.
        fine_stage.occluded_proofs = false;
        auto& st = out.boxes.stats;
        // Two passes: first the boxes the constraint set left undecided, then those it certified
        // and occlusion left PARTIAL. By volume alone, most of a 1 s budget went to the second
        // kind (more boxes, of which an OCCLUDED proof rarely prunes any), where much of the
        // volume is truly occluded; first pass first raised the certified share on
        // idler_riser / featuretype / angle_block from 81.1 / 68.4 / 63.9 % to 82.2 / 69.5 /
        // 68.4 % (3 000 sampled true positions; bench_completeness measures the same).
        // BOUNDARY boxes with their separator states, side by side (run_from takes both).
        struct boundary_list {
            std::vector<position_box<I>> boxes;
            std::vector<typename separator::state> states;
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
            separator fine{&set, Contraction::wrap(detail::set_contractor<Set, position_box<I>>{&set}), &occlusion,
                           facet_index, Bisector(refine->min_width), fine_stage,
                           stage.min_piece > 0.0 ? stage.min_piece : position_eps / 10, &out.counters, shadows};
            paver<position_box<I>, identity, separator, Bisector, largest_volume_first> q(
                identity{}, std::move(fine), Bisector(refine->min_width), again);
            auto more = q.run_from(out.boxes.boundary, states, stop);
            ++out.counters.refinement_passes;
            const auto now = std::chrono::steady_clock::now();
            out.refinement_stopped = more.stats.reason == termination::deadline && refine->deadline &&
                                     now >= *refine->deadline && !(options.deadline && now >= *options.deadline);
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
    // A BOUNDARY box was separated just before the bisector declined it: undecided by the set
    // (which constraint, if it says: one more test), or certified by it and PARTIAL for occlusion.
    out.boundary_reasons.reserve(out.boxes.boundary.size());
    for (std::size_t i = 0; i < out.boxes.boundary.size(); ++i)
        out.boundary_reasons.push_back(
            states[i].certified ? boundary_reason::occlusion
            : states[i].why     ? *states[i].why
                                : undecided_constraint<I>(set, out.boxes.boundary[i]).value_or(boundary_reason::occlusion));
    return out;
}

}  // namespace certipose
