// certipose/solver/contraction.hpp — the contraction policy of the pipeline: which contractor the
// position stage narrows boxes with, built on the constraint set's own contractor.
//
// The policies are named after the contractors they add (contractor/), in namespace
// `certipose::contraction`, so the pipeline and the contractors speak one vocabulary:
//   contraction::hc4            the set's contractor as it is (HC4 for the paper's set; default)
//   contraction::acid           ACID shaving around it (certipose::acid)
//   contraction::fixpoint       it, repeated until boxes narrow by less than 1 % (certipose::fixpoint)
//   contraction::compose<A, B>  A's contractor, then B's, on the same box (certipose::compose)
// Choose one with `pose_solver<with_contraction<contraction::acid>>` (solver/policies.hpp).
// A policy is a type with `static auto wrap(C c)` returning a Contractor built on top of the
// set's contractor `c` (the `ContractionPolicy` concept); a user policy is any such type.
#pragma once

#include <concepts>
#include <utility>

#include "certipose/contractor/acid.hpp"
#include "certipose/contractor/compose.hpp"
#include "certipose/contractor/concept.hpp"
#include "certipose/contractor/fixpoint.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/pose/pose_box.hpp"

namespace certipose {

namespace contraction {

/// The constraint set's contractor as it is (HC4 for paper_position_constraints; the paper).
struct hc4 {
    template <class C>
    static C wrap(C c) { return c; }
};

/// ACID (3BCID shaving with a learned number of shaved variables) around the set's contractor.
struct acid {
    template <class C>
    static auto wrap(C c) { return certipose::acid(std::move(c)); }
};

/// The set's contractor repeated until boxes narrow by less than 1 % (IBEX's fixpoint ratio).
struct fixpoint {
    template <class C>
    static auto wrap(C c) { return certipose::fixpoint(std::move(c), 0.01); }
};

/// A's contractor, then B's, on the same box (e.g. `compose<contraction::hc4, contraction::acid>`).
template <class A, class B>
struct compose {
    template <class C>
    static auto wrap(C c) { return certipose::compose(A::wrap(c), B::wrap(c)); }
};

}  // namespace contraction

namespace detail {
/// A stand-in for the set's contractor when checking a policy.
template <Interval I>
struct archetype_contractor {
    void contract(position_box<I>&) {}
};
}  // namespace detail

/// A contraction policy for boxes over I: `P::wrap(c)` turns a Contractor into a Contractor.
template <class P, class I>
concept ContractionPolicy = Interval<I> && requires(detail::archetype_contractor<I> c) {
    { P::wrap(c) } -> Contractor<position_box<I>>;
};

// The names before contraction:: existed (certipose 0.1).
using hc4_contraction [[deprecated("use certipose::contraction::hc4")]] = contraction::hc4;
using acid_contraction [[deprecated("use certipose::contraction::acid")]] = contraction::acid;
using fixpoint_contraction [[deprecated("use certipose::contraction::fixpoint")]] = contraction::fixpoint;
template <class A, class B>
using then [[deprecated("use certipose::contraction::compose<A, B>")]] = contraction::compose<A, B>;

}  // namespace certipose
