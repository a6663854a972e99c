// certipose/solver/policies.hpp — the policies of the pipeline, as one bundle with defaults, and
// one way to change them: "the defaults, except these".
//
//   certipose::pose_solver<>                                                  // every default
//   certipose::pose_solver<certipose::with_contraction<certipose::contraction::acid_shaving>>
//   certipose::pose_solver<certipose::policies<certipose::with_occlusion<certipose::boolean_occlusion>,
//                                              certipose::with_interval<certipose::cgal_interval>>>
//
// `default_policies` names each policy; `with_X<T, Base = default_policies>` derives from Base
// and replaces X by T (in the manner of Boost.Interval's policies and CGAL's traits classes).
// `policies<Changes...>` applies several changes in any order (each names the one slot it
// replaces). Each `with_X` checks T against its concept where the user names it, so the first
// error line names the concept; pose_solver checks a whole bundle the same way.
//
// Every slot works the same way: a type here, plus an optional object in pose_solver::setup
// for the slots whose objects carry options (contraction, occlusion, orientation, the
// constraint set's parameters); the others are built by the solver (the bisector from the
// width it must stop at, the buffer and schedule have no state).
//
// | member           | concept                  | default                       | setup object        |
// | interval         | Interval                 | boost_interval                | —                   |
// | camera           | CameraModel              | thin_lens_camera              | (the constructor's) |
// | constraints<I>   | SearchableConstraintSet  | paper_position_constraints<I> | constraints (params)|
// | contraction      | ContractionPolicy        | contraction::set_only         | contraction         |
// | bisector         | PositionBisector         | largest_first                 | — (built from ε)    |
// | occlusion        | OcclusionPolicy          | aabb_occlusion (needs CGAL)   | occlusion (or mesh) |
// | orientation      | OrientationPolicy        | paper_orientation             | orientation         |
// | schedule         | OrientationScheduleFor   | hinted_schedule               | schedule (tuning)   |
// | buffer           | PavingBufferPolicy       | depth_first                   | —                   |
//
// `constraints` is a class template over the interval type, so it follows `with_interval`;
// combine sets through an alias template: `template <class I> using reachable =
// all_of<paper_position_constraints<I>, keep_in_sphere<I>>;` then `with_constraints<reachable>`.
#pragma once

#include <concepts>

#include "certipose/bisection/concept.hpp"
#include "certipose/bisection/largest_first.hpp"
#include "certipose/camera/camera_model.hpp"
#include "certipose/camera/thin_lens_camera.hpp"
#include "certipose/constraints/concept.hpp"
#include "certipose/constraints/paper_position_constraints.hpp"
#include "certipose/interval/boost_interval.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/occlusion/concept.hpp"
#include "certipose/orientation/concept.hpp"
#include "certipose/orientation/paper_orientation.hpp"
#include "certipose/paver/paver.hpp"
#include "certipose/pose/pose_box.hpp"
#include "certipose/solver/contraction.hpp"
#include "certipose/solver/orientation_schedule.hpp"

namespace certipose {

class aabb_occlusion;  // occlusion/aabb_occlusion.hpp (its definitions need certipose::cgal)

/// A bisector for position boxes over I that the solver can build from ε_p.
template <class B, class I>
concept PositionBisector = Interval<I> && Bisector<B, position_box<I>> && std::constructible_from<B, double>;

/// A buffer policy of the paver (depth_first, breadth_first, or a type with a nested buffer<T>).
template <class B>
concept PavingBufferPolicy = PavingBuffer<B, position_box<boost_interval>>;

/// Every default of the pipeline (see the header comment).
struct default_policies {
    using interval = boost_interval;
    using camera = thin_lens_camera;
    template <class I>
    using constraints = paper_position_constraints<I>;
    using contraction = certipose::contraction::set_only;
    using bisector = largest_first;
    using occlusion = aabb_occlusion;
    using orientation = paper_orientation;
    using schedule = hinted_schedule;
    using buffer = depth_first;
    /// `policies<...>` re-applies a bundle's changes on another base: none here.
    template <class Base>
    using rebase = Base;
};

/// Base's policies with the interval type I (the constraint set follows it).
template <Interval I, class Base = default_policies>
struct with_interval : Base {
    using interval = I;
    template <class B>
    using rebase = with_interval<I, typename Base::template rebase<B>>;
};

/// Base's policies with camera model C.
template <CameraModel C, class Base = default_policies>
struct with_camera : Base {
    using camera = C;
    template <class B>
    using rebase = with_camera<C, typename Base::template rebase<B>>;
};

/// Base's policies with the position constraint set S<I> (S a class template over the interval
/// type, e.g. an alias template of an all_of).
template <template <class> class S, class Base = default_policies>
    requires SearchableConstraintSet<S<typename Base::interval>, typename Base::interval>
struct with_constraints : Base {
    template <class I>
    using constraints = S<I>;
    template <class B>
    using rebase = with_constraints<S, typename Base::template rebase<B>>;
};

/// Base's policies with contraction policy C (contraction::set_only, acid_shaving, to_fixpoint,
/// sequence<A, B>, or a user policy).
template <class C, class Base = default_policies>
    requires ContractionPolicy<C, typename Base::interval>
struct with_contraction : Base {
    using contraction = C;
    template <class B>
    using rebase = with_contraction<C, typename Base::template rebase<B>>;
};

/// Base's policies with bisector B (largest_first, round_robin, or a user bisector).
template <class B, class Base = default_policies>
    requires PositionBisector<B, typename Base::interval>
struct with_bisector : Base {
    using bisector = B;
    template <class B2>
    using rebase = with_bisector<B, typename Base::template rebase<B2>>;
};

/// Base's policies with occlusion policy O (aabb_occlusion, boolean_occlusion, no_occlusion).
template <class O, class Base = default_policies>
    requires OcclusionPolicy<O, typename Base::interval>
struct with_occlusion : Base {
    using occlusion = O;
    template <class B>
    using rebase = with_occlusion<O, typename Base::template rebase<B>>;
};

/// Base's policies with orientation policy O (paper_orientation, paving_orientation). The
/// bundle's orientation schedule must be able to drive it: the default, hinted_schedule, needs a
/// BorrowingOrientationPolicy; add `with_schedule<per_box_schedule>` for any other (checked
/// when the bundle is complete: pose_solver, `policies`).
template <class O, class Base = default_policies>
    requires OrientationPolicy<O, typename Base::interval, typename Base::camera>
struct with_orientation : Base {
    using orientation = O;
    template <class B>
    using rebase = with_orientation<O, typename Base::template rebase<B>>;
};

/// Base's policies with orientation schedule S (hinted_schedule, per_box_schedule). Checked
/// against the orientation policy when the bundle is complete (pose_solver, `policies`), since
/// either may be named first.
template <class S, class Base = default_policies>
struct with_schedule : Base {
    using schedule = S;
    template <class B>
    using rebase = with_schedule<S, typename Base::template rebase<B>>;
};

/// Base's policies with the paver's buffer policy B (depth_first, breadth_first).
template <PavingBufferPolicy B, class Base = default_policies>
struct with_buffer : Base {
    using buffer = B;
    template <class B2>
    using rebase = with_buffer<B, typename Base::template rebase<B2>>;
};

namespace detail {
template <class Base, class... Changes>
struct apply_changes {
    using type = Base;
};
template <class Base, class First, class... Rest>
struct apply_changes<Base, First, Rest...> {
    using type = typename apply_changes<typename First::template rebase<Base>, Rest...>::type;
};
}  // namespace detail

/// The defaults with several changes, each a `with_X<T>` (or a chain of them), in any order:
/// `policies<with_occlusion<boolean_occlusion>, with_contraction<contraction::acid_shaving>>`.
/// The orientation schedule is checked against the orientation policy once all are applied.
template <class... Changes>
    requires OrientationScheduleFor<typename detail::apply_changes<default_policies, Changes...>::type::schedule,
                                    typename detail::apply_changes<default_policies, Changes...>::type::orientation,
                                    typename detail::apply_changes<default_policies, Changes...>::type::interval,
                                    typename detail::apply_changes<default_policies, Changes...>::type::camera>
struct policies : detail::apply_changes<default_policies, Changes...>::type {};

}  // namespace certipose
