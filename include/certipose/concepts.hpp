// certipose/concepts.hpp — umbrella for every public concept of certipose: what a type must provide
// to stand in for one of the library's parts (an interval backend, a camera, a contractor, a
// bisector, a constraint set, an occlusion or orientation policy, ...). certipose::certipose: no
// CGAL, no oneTBB.
//
//   header / concept                    a model is
//   interval/concept.hpp
//     Interval<I>                       a backend: bounds, rounded arithmetic, a rounding_guard
//   pose/rotation.hpp
//     RotationScalar<T>                 what the rotation functions take: double or an Interval
//   camera/camera_model.hpp
//     CameraModel<C>                    a camera: intrinsics, image size, field of view, distances
//   expr/expression.hpp, expr/constraint.hpp
//     expr::Expression<T>               a node of a compile-time expression tree
//     expr::Operand<T>                  what the operators take: an Expression or a number
//     expr::Constraint<T>               `e ∈ [a, b]`, <=, >=, == over expressions (for hc4)
//   contractor/concept.hpp, contractor/compose.hpp
//     Contractor<C, Box>                `contract(box)` narrows it, losing no solution
//     BoxTest<T, Box>                   `test(box)`: a verdict on every point of the box
//     tagged_contractor<T>              declares `certipose_contractor`: composes with & and |
//   bisection/concept.hpp
//     Bisector<B, Box>                  `choose(box)`: a split, or nothing below the precision
//     ContextualBisector<B, Box>        a Bisector that also reads the bisection_context
//   paver/paver.hpp
//     PavingBox<B>                      a box the paver splits: indexed Interval components
//     PavingBuffer<P, T>                a buffer policy: the order the boxes are taken in
//     InnerContractor<T, Box>           `contract_inner(box)`: what it removes is VALID
//     InnerSeparator<T, Box>            carries a state, carves pieces off a box, then answers
//     InnerTest<T, Box>                 BoxTest, InnerContractor or InnerSeparator
//   constraints/concept.hpp
//     PositionConstraintSet<C, I>       Contractor and BoxTest on position_box<I>, per facet
//     ParameterizedConstraintSet<S>     built from the problem and its declared `parameters`
//     ConstructibleConstraintSet<S>     buildable for one facet, with or without parameters
//     SearchableConstraintSet<C, I>     also `initial_box()`: the search box
//     ComplementContractingSet<C, I>    also `contract_complement(box)`: inner contraction
//     ExplainingConstraintSet<C, I>     also `undecided(box)`: why a box stayed BOUNDARY
//   occlusion/concept.hpp
//     OcclusionPolicy<P, I>             built from the scene; `classify(box, facet)`, certified
//     EffortAwareOcclusionPolicy<P, I>  `classify` also takes an occlusion_effort
//     ShadowingOcclusionPolicy<P, I>    also a box's blockers and their shadows (cuts)
//   solver/contraction.hpp, solver/policies.hpp, solver/orientation_schedule.hpp
//     ContractionPolicy<P, I>           `wrap(c) const`: the stage's contractor from the set's
//     PositionBisector<B, I>            a Bisector of position boxes, built from a width
//     PavingBufferPolicy<B>             the position stage's buffer policy
//     OrientationScheduleFor<S, O, I, C> a schedule type that can drive orientation policy O
//   orientation/concept.hpp
//     OrientationPolicy<P, I, C>        `orient(position, facet, camera, ε_o)`: certified boxes
//     HintedOrientationPolicy<P, I, C>  also searches from a hint per cell of ε_p
//     BorrowingOrientationPolicy<P, I, C> also tries the hints of neighbouring cells
//
// Not included: PartSink<S, I> (part/part_solver.hpp), a sink that receives each finished facet
// of a whole-part run; it needs oneTBB: <certipose/part.hpp>, certipose::part.
#pragma once

#include "certipose/interval/concept.hpp"  // IWYU pragma: export

#include "certipose/camera/camera_model.hpp"  // IWYU pragma: export
#include "certipose/pose/rotation.hpp"  // IWYU pragma: export

#include "certipose/expr/constraint.hpp"  // IWYU pragma: export
#include "certipose/expr/expression.hpp"  // IWYU pragma: export

#include "certipose/bisection/concept.hpp"  // IWYU pragma: export
#include "certipose/contractor/compose.hpp"  // IWYU pragma: export
#include "certipose/contractor/concept.hpp"  // IWYU pragma: export
#include "certipose/paver/paver.hpp"  // IWYU pragma: export

#include "certipose/constraints/concept.hpp"  // IWYU pragma: export
#include "certipose/occlusion/concept.hpp"  // IWYU pragma: export

#include "certipose/orientation/concept.hpp"  // IWYU pragma: export

#include "certipose/solver/contraction.hpp"  // IWYU pragma: export
#include "certipose/solver/orientation_schedule.hpp"  // IWYU pragma: export
#include "certipose/solver/policies.hpp"  // IWYU pragma: export
