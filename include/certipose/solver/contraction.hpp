// certipose/solver/contraction.hpp — the contractor policy of the pipeline: how the position
// stage narrows boxes with the constraint set's own contractor (HC4 for the paper's set).
//
// A policy is a type with `static auto wrap(C c)` returning a Contractor built on top of the
// constraint set's contractor `c`: `hc4_contraction` uses it as is, `acid_contraction` shaves
// with ACID around it, `fixpoint_contraction` repeats it, `then<A, B>` runs A's then B's.
// A user policy is any type with such a `wrap`.
#pragma once

#include <utility>

#include "certipose/contractor/acid.hpp"
#include "certipose/contractor/compose.hpp"
#include "certipose/contractor/fixpoint.hpp"

namespace certipose {

/// The constraint set's contractor as it is (HC4 for paper_position_constraints; the paper).
struct hc4_contraction {
    template <class C>
    static C wrap(C c) { return c; }
};

/// ACID (3BCID shaving with a learned number of shaved variables) around the set's contractor.
struct acid_contraction {
    template <class C>
    static auto wrap(C c) { return acid(std::move(c)); }
};

/// The set's contractor repeated until boxes narrow by less than 1 % (IBEX's fixpoint ratio).
struct fixpoint_contraction {
    template <class C>
    static auto wrap(C c) { return fixpoint(std::move(c), 0.01); }
};

/// A's contractor, then B's, on the same box (e.g. `then<hc4_contraction, acid_contraction>`).
template <class A, class B>
struct then {
    template <class C>
    static auto wrap(C c) { return compose(A::wrap(c), B::wrap(c)); }
};

}  // namespace certipose
