// certipose/solver/contraction.hpp — the contraction policy of the pipeline: which contractor the
// position stage narrows boxes with, built on top of the constraint set's own contractor.
//
// A contraction policy is not a contractor: it is told the set's contractor `c` and returns the
// contractor the stage runs, `policy.wrap(c)`. Its names say what it does to `c`, so that they
// never read as one of the contractors of contractor/ (`certipose::hc4`, `certipose::acid`, ...):
//   contraction::set_only         c as it is (HC4 for the paper's set; the default)
//   contraction::acid_shaving     ACID shaving after c (certipose::acid), with its acid_options
//   contraction::to_fixpoint      c repeated until boxes narrow by less than `ratio`
//   contraction::sequence<A, B>   A's contractor, then B's, on the same box
// Like every policy slot, a contraction policy is a type (chosen with `with_contraction<C>`,
// solver/policies.hpp) plus an optional object given in `pose_solver::setup::contraction`, so it
// can carry run-time options:
//   certipose::pose_solver<certipose::with_contraction<certipose::contraction::acid_shaving>> s(
//       part, camera, task, {.contraction = {.options = {.s3b = 20}}});
// A user policy is any copyable, default-constructible type with a const `wrap(c)` returning a
// Contractor (the ContractionPolicy concept). `pose_solver::position_contractor(facet)` returns
// the contractor a policy builds for a facet, to test or micro-benchmark it.
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
struct set_only {
    template <class C>
    C wrap(C c) const { return c; }
};

/// ACID (3BCID shaving with a learned number of shaved variables) after the set's contractor.
struct acid_shaving {
    acid_options options{};
    template <class C>
    auto wrap(C c) const { return certipose::acid(std::move(c), options); }
};

/// The set's contractor repeated until no component narrows by more than `ratio` (IBEX's
/// fixpoint ratio by default).
struct to_fixpoint {
    double ratio = 0.01;
    template <class C>
    auto wrap(C c) const { return certipose::fixpoint(std::move(c), ratio); }
};

/// A's contractor, then B's, on the same box (e.g. `sequence<set_only, acid_shaving>`).
template <class A, class B>
struct sequence {
    A first{};
    B second{};
    template <class C>
    auto wrap(C c) const { return certipose::compose(first.wrap(c), second.wrap(c)); }
};

}  // namespace contraction

namespace detail {
/// A stand-in for the set's contractor when checking a policy.
template <Interval I>
struct archetype_contractor {
    void contract(position_box<I>&) {}
};
}  // namespace detail

/// A contraction policy for boxes over I: `p.wrap(c)` (p const) turns a Contractor into one.
template <class P, class I>
concept ContractionPolicy = Interval<I> && std::default_initializable<P> && std::copy_constructible<P> &&
                            requires(const P& p, detail::archetype_contractor<I> c) {
                                { p.wrap(c) } -> Contractor<position_box<I>>;
                            };

}  // namespace certipose
