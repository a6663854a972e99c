// certipose/contractor/concept.hpp — the Contractor and BoxTest concepts shared by every
// contractor, constraint set and paver.
//
// A contractor (paper §5.2.1, IBEX's Ctc) narrows a box in place: afterwards the box is a
// subset of what it was and still contains every solution the old box contained; when it
// proves there is none it leaves the box empty (`is_empty(box)`), it does not throw.
// A box test (IBEX's inner/outer tests) classifies a whole box: every point satisfies the
// constraints, none does, or undecided. The paver (Algorithm 1) needs both: the contractor to
// shrink, the test to certify VALID boxes.
#pragma once

#include <concepts>

#include "certipose/outcome.hpp"  // verdict

namespace certipose {

/// `c.contract(box)` narrows `box` soundly; an empty box afterwards means "no solution".
template <class C, class Box>
concept Contractor = requires(C& c, Box& box) {
    { c.contract(box) } -> std::same_as<void>;
};

/// `t.test(box)` classifies the whole box.
template <class T, class Box>
concept BoxTest = requires(T& t, const Box& box) {
    { t.test(box) } -> std::same_as<verdict>;
};

}  // namespace certipose
