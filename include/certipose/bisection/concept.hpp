// certipose/bisection/concept.hpp — the Bisector concept: which dimension to split, and where.
//
// `b.choose(box)` returns the split (dimension and point strictly inside that component), or
// nothing when every dimension is already narrower than its precision — the paper's
// "widest interval narrower than ε" test (Algorithm 1 line 16) that makes a box BOUNDARY.
// A bisector whose choice depends on history (round-robin) may also offer
// `b.choose(box, context)`; the paver then passes the box's place in the bisection tree, so the
// choice depends on the tree and not on the order the buffer visits boxes (depth-first and
// breadth-first then build the same tree).
#pragma once

#include <concepts>
#include <cstddef>
#include <optional>

namespace certipose {

struct split {
    std::size_t dimension;
    double point;
};

template <class B, class Box>
concept Bisector = requires(B& b, const Box& box) {
    { b.choose(box) } -> std::same_as<std::optional<split>>;
};

/// Where a box sits in the bisection tree, as the paver knows it.
struct bisection_context {
    std::size_t depth = 0;                         ///< splits between the root box and this one
    std::optional<std::size_t> parent_dimension;   ///< dimension split to create it (none at the root)
};

/// A bisector that can use the box's history; the paver prefers this overload when present.
template <class B, class Box>
concept ContextualBisector = Bisector<B, Box> && requires(B& b, const Box& box, const bisection_context& c) {
    { b.choose(box, c) } -> std::same_as<std::optional<split>>;
};

}  // namespace certipose
