// certipose/solver/policies.hpp — the policies of the pipeline (DESIGN.md §5), as one bundle with
// defaults, and the one way to change them: "the defaults, except this one".
//
//   certipose::pose_solver<>                                                  // every default
//   certipose::pose_solver<certipose::with_contraction<certipose::contraction::acid>>
//   certipose::pose_solver<certipose::with_occlusion<certipose::boolean_occlusion,
//                          certipose::with_interval<certipose::cgal_interval>>>  // two changed
//
// `default_policies` names each policy; `with_X<T, Base = default_policies>` derives from Base
// and replaces X by T (in the manner of Boost.Interval's policies and CGAL's traits classes), so
// changes chain from the inside out and a user bundle may also derive from default_policies
// directly. Each `with_X` checks T against its concept where the user names it, so the first
// error line names the concept; pose_solver checks a whole bundle the same way.
//
// | member           | concept                              | default                         |
// | interval         | Interval                             | boost_interval                  |
// | camera           | CameraModel                          | thin_lens_camera                |
// | constraints<I>   | SearchableConstraintSet              | paper_position_constraints<I>   |
// | contraction      | ContractionPolicy                    | contraction::hc4                |
// | bisector         | PositionBisector                     | largest_first                   |
// | occlusion        | OcclusionPolicy                      | aabb_occlusion (needs CGAL)     |
// | orientation      | OrientationPolicy                    | paper_orientation               |
// | buffer           | PavingBufferPolicy                   | depth_first                     |
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
    using contraction = certipose::contraction::hc4;
    using bisector = largest_first;
    using occlusion = aabb_occlusion;
    using orientation = paper_orientation;
    using buffer = depth_first;
};

/// Base's policies with the interval type I (the constraint set follows it).
template <Interval I, class Base = default_policies>
struct with_interval : Base {
    using interval = I;
};

/// Base's policies with camera model C.
template <CameraModel C, class Base = default_policies>
struct with_camera : Base {
    using camera = C;
};

/// Base's policies with the position constraint set S<I> (S a class template over the interval
/// type, e.g. an alias template of an all_of).
template <template <class> class S, class Base = default_policies>
    requires SearchableConstraintSet<S<typename Base::interval>, typename Base::interval>
struct with_constraints : Base {
    template <class I>
    using constraints = S<I>;
};

/// Base's policies with contraction policy C (contraction::hc4, ::acid, ::fixpoint, ::compose).
template <class C, class Base = default_policies>
    requires ContractionPolicy<C, typename Base::interval>
struct with_contraction : Base {
    using contraction = C;
};

/// Base's policies with bisector B (largest_first, round_robin, or a user bisector).
template <class B, class Base = default_policies>
    requires PositionBisector<B, typename Base::interval>
struct with_bisector : Base {
    using bisector = B;
};

/// Base's policies with occlusion policy O (aabb_occlusion, boolean_occlusion, no_occlusion).
template <class O, class Base = default_policies>
    requires OcclusionPolicy<O, typename Base::interval>
struct with_occlusion : Base {
    using occlusion = O;
};

/// Base's policies with orientation policy O (paper_orientation, paving_orientation).
template <class O, class Base = default_policies>
    requires OrientationPolicy<O, typename Base::interval, typename Base::camera>
struct with_orientation : Base {
    using orientation = O;
};

/// Base's policies with the paver's buffer policy B (depth_first, breadth_first).
template <PavingBufferPolicy B, class Base = default_policies>
struct with_buffer : Base {
    using buffer = B;
};

}  // namespace certipose
