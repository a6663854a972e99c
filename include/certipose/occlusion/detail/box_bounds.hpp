// certipose/occlusion/detail/box_bounds.hpp — a position box's bounds as doubles, checked
// (not for users; no CGAL).
//
// Occlusion is decided on the set the intervals denote, [lower, upper] per axis: any outward
// rounding of the interval bounds only makes the box larger, which keeps every answer sound.
#pragma once

#include "certipose/error.hpp"
#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/pose/pose_box.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <string>

namespace certipose::detail::occ {

/// Throws invalid_argument("box") for an empty box or a non-finite bound (an unbounded box has
/// no finite sight hull); otherwise returns [lower, upper] per axis.
inline Eigen::AlignedBox3d checked_bounds(const Eigen::AlignedBox3d& b, const char* who) {
    for (int k = 0; k < 3; ++k) {
        const double lo = b.min()[k], hi = b.max()[k];
        if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo <= hi))
            throw invalid_argument("box", std::string(who) + ": position box component " +
                                              "xyz"[k] + " = [" + detail::mesh::format(lo) +
                                              ", " + detail::mesh::format(hi) +
                                              "] must be finite and non-empty");
    }
    return b;
}

template <Interval I>
Eigen::AlignedBox3d box_bounds(const position_box<I>& box, const char* who) {
    Eigen::AlignedBox3d b;
    for (int k = 0; k < 3; ++k) {
        const I& c = box[static_cast<std::size_t>(k)];
        if (is_empty(c))
            throw invalid_argument("box", std::string(who) + ": position box component " +
                                              "xyz"[k] + " is empty");
        b.min()[k] = lower(c);
        b.max()[k] = upper(c);
    }
    return checked_bounds(b, who);
}

}  // namespace certipose::detail::occ
