// certipose/solver/position_stage.hpp — the position half of the paper's Algorithm 3
// (lines 1–27): pave the position space of one facet with the position constraint set and an
// occlusion policy.
//
// A position box is VALID when the constraint set certifies it *and* the occlusion policy says
// VISIBLE; it is discarded when the set proves it violated or occlusion says OCCLUDED;
// otherwise it is bisected (largest-first by default) down to ε_p and then kept as BOUNDARY.
// Occlusion is only asked about boxes the constraints already certify: elsewhere the box is
// bisected anyway, and the exact occlusion test is the expensive part. Two savings follow
// from that order, neither of which changes a VALID box:
//  * A box inside one the set has certified is certified too (every point of it satisfies
//    every constraint), so the boxes below an occlusion-PARTIAL box skip the contractor, which
//    could not remove a point, and the set's test, and go straight to occlusion.
//  * A box the bisector will not split is asked with occlusion_effort::visible_only (when the
//    policy takes it): OCCLUDED would discard it and PARTIAL makes it BOUNDARY, so the costly
//    search for an OCCLUDED certificate only decides which of the two non-VALID labels it gets.
//    Such boxes are BOUNDARY with reason `occlusion`.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "certipose/bisection/largest_first.hpp"
#include "certipose/constraints/concept.hpp"
#include "certipose/occlusion/concept.hpp"
#include "certipose/paver/paver.hpp"
#include "certipose/solver/contraction.hpp"
#include "certipose/solver/task.hpp"

namespace certipose {

namespace detail {

/// The boxes the constraint set has certified whose parts are still being paved: the chain of
/// ancestors of the current box (the paver pops children right after their parent when the
/// buffer is depth-first; with another buffer the chain is cut more often, which only costs
/// the saving). Shared by the stage's contractor and test.
template <class Box>
class certified_ancestors {
public:
    /// Is `b` inside a box the set certified? Drops the ancestors that do not contain it.
    bool covers(const Box& b) {
        while (!chain_.empty()) {
            if (inside(b, chain_.back())) return true;
            chain_.pop_back();
        }
        return false;
    }
    void push(const Box& b) { chain_.push_back(b); }

private:
    static bool inside(const Box& b, const Box& a) {
        for (std::size_t i = 0; i < b.size(); ++i)
            if (!(lower(b[i]) >= lower(a[i]) && upper(b[i]) <= upper(a[i]))) return false;
        return true;
    }
    std::vector<Box> chain_;
};

/// A Contractor that forwards to a constraint set owned elsewhere (the stage's local set), so
/// contractor policies can wrap it without copying the set. A box inside a certified one holds
/// no point to remove: left as it is.
template <class Set, class Box>
struct set_contractor {
    Set* set = nullptr;
    certified_ancestors<Box>* certified = nullptr;
    void contract(Box& box) {
        if (!certified->covers(box)) set->contract(box);
    }
};

/// The paver's inner test: constraint set first (unless an ancestor is certified), then
/// occlusion for certified boxes, with the least effort that decides the box's fate.
template <class Set, class Occlusion, class Bisector, class Box>
struct position_test {
    Set* set;
    const Occlusion* occlusion;
    std::size_t facet;
    std::size_t* occlusion_tests;
    certified_ancestors<Box>* certified;
    Bisector bisector;  // a copy of the paver's: asked only whether it would split the box

    verdict test(const Box& box) {
        if (!certified->covers(box)) {
            const verdict v = set->test(box);
            if (v != verdict::satisfied) return v;
            certified->push(box);
        }
        ++*occlusion_tests;
        visibility seen;
        if constexpr (EffortAwareOcclusionPolicy<Occlusion, typename Box::interval_type>)
            seen = occlusion->classify(box, facet, bisector.choose(box) ? occlusion_effort::full
                                                                        : occlusion_effort::visible_only);
        else
            seen = occlusion->classify(box, facet);
        switch (seen) {
            case visibility::visible: return verdict::satisfied;
            case visibility::occluded: return verdict::violated;
            case visibility::partial: break;
        }
        return verdict::undecided;
    }
};

}  // namespace detail

/// Result of the position stage for one facet.
template <Interval I>
struct position_stage_result {
    certipose::paving<position_box<I>> boxes;  ///< VALID, BOUNDARY (and pending) position boxes
    /// Why each BOUNDARY box of `boxes.boundary` (same order) was left undecided.
    std::vector<boundary_reason> boundary_reasons;
    position_box<I> initial_box;
    std::size_t occlusion_tests = 0;
};

/// Paves the positions of one facet. `Set` models PositionConstraintSet over I and is built from
/// `problem` and `parameters`; `Contraction` is a contraction policy (solver/contraction.hpp);
/// `Bisector` is constructible from ε_p.
template <Interval I, class Set, class Contraction = contraction::hc4, class Bisector = largest_first,
          class Buffer = depth_first, class Occlusion>
    requires SearchableConstraintSet<Set, I> && OcclusionPolicy<Occlusion, I>
position_stage_result<I> pave_positions(const position_problem& problem, std::size_t facet_index,
                                        const Occlusion& occlusion, const paver_options& options,
                                        double position_eps, std::stop_token stop = {},
                                        const constraint_parameters_t<Set>& parameters = {}) {
    Set set = make_constraint_set<Set>(problem, parameters);
    position_stage_result<I> out;
    out.initial_box = set.initial_box();
    detail::certified_ancestors<position_box<I>> certified;
    auto contractor = Contraction::wrap(detail::set_contractor<Set, position_box<I>>{&set, &certified});
    detail::position_test<Set, Occlusion, Bisector, position_box<I>> test{
        &set, &occlusion, facet_index, &out.occlusion_tests, &certified, Bisector(position_eps)};
    paver<position_box<I>, decltype(contractor), decltype(test), Bisector, Buffer> p(
        std::move(contractor), test, Bisector(position_eps), options);
    if (is_empty(out.initial_box)) {
        out.boxes.stats.reason = termination::completed;
        return out;
    }
    out.boxes = p.run(out.initial_box, stop);
    // A BOUNDARY box was contracted and tested just before the bisector declined it, so testing
    // it again gives the same answer: undecided by the set (which constraint, if it says), or
    // certified by the set and PARTIAL for occlusion. Costs one test per BOUNDARY box.
    out.boundary_reasons.reserve(out.boxes.boundary.size());
    for (const auto& b : out.boxes.boundary)
        out.boundary_reasons.push_back(undecided_constraint<I>(set, b).value_or(boundary_reason::occlusion));
    return out;
}

}  // namespace certipose
