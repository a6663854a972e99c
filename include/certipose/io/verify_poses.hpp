// certipose/io/verify_poses.hpp — certify anyone's camera pose: what certipose-verify computes
// for each pose of POSES.json, shared by the program and the Python module (docs/coverage.md).
//
// For a pose (exact, or a 6D box for the installation tolerance): where it stands against the
// camera regions; the facets certified inspected from every pose of it, C(B), and those not
// proven impossible, P(B); and, for an exact pose (or the centre of a converted quaternion or
// matrix pose), the largest box around it that keeps every facet of C certified, shrunk until
// the camera regions allow all of its positions. A pose not wholly in the allowed space
// certifies nothing: "forbidden" makes nothing possible either, "undecided" keeps P(B).
#pragma once

#include "certipose/coverage/inspection.hpp"
#include "certipose/io/plan_files.hpp"
#include "certipose/solver/camera_regions.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <optional>

namespace certipose {

/// The tolerance box `t` around `centre`, its positions shrunk about the centre (halved, at most
/// 40 times, then the centre alone) until the camera regions allow every one: a sub-box of `t`,
/// so still certified. Nothing when not even the centre is allowed.
template <Interval I>
std::optional<pose_box<I>> within_regions(pose_box<I> t, const std::array<double, 6>& centre, const camera_regions& regions) {
    if (regions.empty()) return t;
    const rounding_guard<I> rounding;
    for (int n = 0; n < 40 && regions.classify(t.position) != region_verdict::allowed; ++n)
        for (std::size_t k = 0; k < 3; ++k) {
            const double lo = lower(t.position[k]), hi = upper(t.position[k]), c = centre[k];
            t.position.x[k] = I(std::clamp(c - (c - lo) / 2, lo, c), std::clamp(c + (hi - c) / 2, c, hi));
        }
    if (regions.classify(t.position) != region_verdict::allowed)
        for (std::size_t k = 0; k < 3; ++k) t.position.x[k] = I(centre[k]);
    if (regions.classify(t.position) != region_verdict::allowed) return std::nullopt;
    return t;
}

/// What verify_pose finds for one pose.
struct pose_verification {
    region_verdict where = region_verdict::allowed;  ///< against the camera regions
    facet_coverage coverage;                          ///< C(B) (empty unless allowed) and P(B)
    /// Asked for (an exact or converted pose, with C(B) not empty): the largest box around the
    /// pose keeping C(B) certified (nothing when there is none), and its half-widths about the
    /// pose (x, y, z in metres, φ, γ, β in radians; for a converted pose, less its own
    /// half-widths, pose_input::converted_half_widths, so they hold for the true pose).
    bool tolerance_asked = false;
    std::optional<bounds_3d> tolerance_position{}, tolerance_orientation{};
    std::array<double, 6> half_widths{};
};

/// Verifies one pose (see the header comment); `tolerance`: compute the tolerance box.
template <class Policies>
pose_verification verify_pose(facet_inspector<Policies>& inspector, const pose_input& p, const camera_regions& regions,
                              bool tolerance) {
    using I = typename facet_inspector<Policies>::interval_type;
    pose_verification out;
    pose_box<I> box;
    for (std::size_t k = 0; k < 3; ++k) {
        box.position.x[k] = I(p.position[k][0], p.position[k][1]);
        box.orientation.x[k] = I(p.orientation[k][0], p.orientation[k][1]);
    }
    // Camera regions first: a pose or box not wholly in the allowed space certifies no facet.
    out.where = regions.classify(box.position);
    if (out.where != region_verdict::forbidden) out.coverage = inspector.inspect(box);
    if (out.where != region_verdict::allowed) out.coverage.certified.clear(), out.coverage.certified_area = 0;
    // An exact pose, or the centre of a converted one, whose box is ±converted_half_widths
    // about it, each angle its own (a matrix not quite orthonormal widens φ and β by 1/sin γ
    // more than γ): the half-widths are measured from that box, so they hold for the true pose.
    const auto& centre = p.pose ? p.pose : p.converted;
    if (!centre || !tolerance || out.coverage.certified.empty()) return out;
    out.tolerance_asked = true;
    std::optional<pose_box<I>> t = inspector.largest_box_keeping(*centre, out.coverage.certified);
    if (t) t = within_regions(*t, *centre, regions);
    if (!t) return out;
    const auto rec = to_record(classified_box<I>{box_class::valid, *t});
    for (std::size_t k = 0; k < 3; ++k) {
        out.half_widths[k] = std::min((*centre)[k] - rec.position[k][0], rec.position[k][1] - (*centre)[k]);
        out.half_widths[k + 3] = std::min((*centre)[k + 3] - rec.orientation[k][0], rec.orientation[k][1] - (*centre)[k + 3]) -
                                 (p.pose ? 0.0 : p.converted_half_widths[k]);
        if (!(out.half_widths[k + 3] >= 0)) return out;
    }
    out.tolerance_position = rec.position;
    out.tolerance_orientation = rec.orientation;
    return out;
}

}  // namespace certipose
