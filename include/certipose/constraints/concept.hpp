// certipose/constraints/concept.hpp — the constraint-set policy of the position stage.
//
// A position constraint set is both a Contractor (narrow a position box without losing any
// position that satisfies it) and a BoxTest (certify that every position of a box satisfies
// it, or that none does) on `position_box<I>`. The solver builds one per facet from a
// `position_problem` and, when the set declares `using parameters = ...;`, from a value of that
// type too — the run-time configuration of a user's set (a keep-in sphere's centre and radius),
// given once to the solver (`pose_solver<P>::setup::constraints`). A user-written set is a class
// template over the interval type; `all_of` combines sets (e.g. the paper's set plus "stay above
// the conveyor"). A set may also say which of its constraints stayed undecided on a box
// (`undecided(box)`), so that BOUNDARY boxes explain themselves.
#pragma once

#include <concepts>
#include <optional>

#include "certipose/camera/camera_model.hpp"
#include "certipose/contractor/concept.hpp"
#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/pose/pose_box.hpp"
#include "certipose/inspection_task.hpp"
#include "certipose/outcome.hpp"  // boundary_reason, verdict

namespace certipose {

/// Everything a position constraint set may depend on, for one facet.
struct position_problem {
    certipose::facet facet;  ///< the facet of interest (vertices, normal, centroid)
    distance_range range;    ///< usable distances [d_min, d_max] (camera + resolution cap)
    inspection_task task;    ///< θ_v and the resolution requirement
};

/// The parameters a set takes besides the problem: `typename S::parameters`, or `no_parameters`.
struct no_parameters {
    friend bool operator==(no_parameters, no_parameters) = default;
};

namespace detail {
template <class S>
struct parameters_of {
    using type = no_parameters;
};
template <class S>
    requires requires { typename S::parameters; }
struct parameters_of<S> {
    using type = typename S::parameters;
};
}  // namespace detail

template <class S>
using constraint_parameters_t = typename detail::parameters_of<S>::type;

/// A set built from the problem and the parameters it declares.
template <class S>
concept ParameterizedConstraintSet =
    requires { typename S::parameters; } &&
    std::constructible_from<S, const position_problem&, const typename S::parameters&>;

/// A set that can be built for one facet: from the problem alone, or from the problem and its
/// declared parameters.
template <class S>
concept ConstructibleConstraintSet = ParameterizedConstraintSet<S> || std::constructible_from<S, const position_problem&>;

/// Builds `S` for `problem` with `parameters` (ignored by a set that declares none).
template <ConstructibleConstraintSet S>
S make_constraint_set(const position_problem& problem, const constraint_parameters_t<S>& parameters) {
    if constexpr (ParameterizedConstraintSet<S>)
        return S(problem, parameters);
    else
        return S(problem);
}

template <class C, class I>
concept PositionConstraintSet = Interval<I> && Contractor<C, position_box<I>> && BoxTest<C, position_box<I>> &&
                                ConstructibleConstraintSet<C>;

/// The set the solver paves with: a PositionConstraintSet that also gives the initial search
/// box (Algorithm 3 line 4). Members of an all_of after the first need not.
template <class C, class I>
concept SearchableConstraintSet = PositionConstraintSet<C, I> && requires(C& c) {
    { c.initial_box() } -> std::convertible_to<position_box<I>>;
};

/// A set that can also contract the *complement* of itself (IBEX's CtcNotIn; the inner
/// contraction of the position stage): `contract_complement(box)` narrows `box` to a box that
/// still holds every position of it violating at least one of the set's constraints, so every
/// position it removes satisfies all of them. Only the closure of each strict constraint need be
/// kept: the removed part may touch positions where a strict inequality is an equality, and the
/// caller leaves a gap there (solver/position_stage.hpp carves one ulp apart).
template <class C, class I>
concept ComplementContractingSet = PositionConstraintSet<C, I> && requires(C& c, position_box<I>& box) {
    { c.contract_complement(box) } -> std::same_as<void>;
};

/// A set that names the first of its constraints it cannot certify on a box: `undecided(box)`
/// is that constraint, or nothing when the set certifies the whole box (test: satisfied).
template <class C, class I>
concept ExplainingConstraintSet = PositionConstraintSet<C, I> && requires(C& c, const position_box<I>& box) {
    { c.undecided(box) } -> std::same_as<std::optional<boundary_reason>>;
};

/// Which constraint of `set` is not certified on `box` (boundary_reason::constraint when the
/// set does not say which), or nothing when the set certifies all of `box`. One evaluation.
template <class I, class C>
std::optional<boundary_reason> undecided_constraint(C& set, const position_box<I>& box) {
    if constexpr (ExplainingConstraintSet<C, I>)
        return set.undecided(box);
    else if (set.test(box) == verdict::satisfied)
        return std::nullopt;
    else
        return boundary_reason::constraint;
}

}  // namespace certipose
