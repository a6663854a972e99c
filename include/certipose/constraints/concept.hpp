// certipose/constraints/concept.hpp — the constraint-set policy of the position stage.
//
// A position constraint set is both a Contractor (narrow a position box without losing any
// position that satisfies it) and a BoxTest (certify that every position of a box satisfies
// it, or that none does) on `position_box<I>`. The solver builds one per facet from a
// `position_problem`; a user-written set is a class template over the interval type with that
// constructor, and `all_of` combines sets (e.g. the paper's set plus "stay above the conveyor").
#pragma once

#include "certipose/camera/camera_model.hpp"
#include "certipose/contractor/concept.hpp"
#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/pose/pose_box.hpp"
#include "certipose/solver/task.hpp"

namespace certipose {

/// Everything a position constraint set may depend on, for one facet.
struct position_problem {
    certipose::facet facet;  ///< the facet of interest (vertices, normal, centroid)
    distance_range range;    ///< usable distances [d_min, d_max] (camera + resolution cap)
    inspection_task task;    ///< θ_v and the resolution requirement
};

template <class C, class I>
concept PositionConstraintSet = Interval<I> && Contractor<C, position_box<I>> && BoxTest<C, position_box<I>> &&
                                std::constructible_from<C, const position_problem&>;

}  // namespace certipose
