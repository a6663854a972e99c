// certipose/inspection_task.hpp — what is asked of a view of one facet, besides the camera: the
// viewing-angle threshold, an optional resolution requirement (paper §2) and an optional
// tolerance on where the part sits.
//
// Below the constraint sets and the solver: both read it, and neither may include the other.
#pragma once

#include <cmath>
#include <numbers>
#include <optional>

#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"
#include "certipose/pose/placement_tolerance.hpp"

namespace certipose {

/// The inspection task for one facet (constraints 2 and 4 of docs/conventions.md#what-a-valid-box-certifies).
struct inspection_task {
    /// θ_v: the sight line to the facet centre must make at least this angle with the facet's
    /// plane, i.e. the angle to the normal is at most π/2 − θ_v (constraint 4). Radians, [0, π/2).
    double min_view_angle = 0.35;
    /// Optional resolution requirement r (metres on the part per pixel): caps d_max at r·f_px.
    std::optional<double> max_metres_per_pixel{};
    /// Optional placement tolerance of the part (pose/placement_tolerance.hpp): a VALID box then
    /// holds for every placement of the part it admits. Unset or none(): the nominal placement.
    std::optional<placement_tolerance> placement{};

    void validate() const {
        if (!(min_view_angle >= 0.0) || !(min_view_angle < std::numbers::pi / 2))
            throw invalid_argument("min_view_angle", "inspection_task: min_view_angle must be in [0, pi/2), got " +
                                                         detail::format_double(min_view_angle));
        if (max_metres_per_pixel && !(*max_metres_per_pixel > 0.0 && std::isfinite(*max_metres_per_pixel)))
            throw invalid_argument("max_metres_per_pixel",
                                   "inspection_task: max_metres_per_pixel must be positive and finite, got " +
                                       detail::format_double(*max_metres_per_pixel));
        if (placement) placement->validate();
    }
};

}  // namespace certipose
