// certipose/occlusion/no_occlusion.hpp — the OcclusionPolicy that ignores occlusion.
//
// For scenes where nothing can hide the facet (a convex part seen from its front side is
// handled by the backface constraint alone) and for benchmarks that time the rest of the
// pipeline. Every box is VISIBLE; the facet index is still checked so that a bad index fails
// the same way with every policy. No CGAL, no state beyond the face count: thread-safe.
#pragma once

#include "certipose/error.hpp"
#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/occlusion/concept.hpp"
#include "certipose/pose/pose_box.hpp"

#include <cstddef>
#include <span>

namespace certipose {

/// Always VISIBLE. Throws certipose::out_of_range("facet", f, n) for a facet index >= n.
class no_occlusion {
public:
    /// Constraint 6 is never checked (solve_stats::occlusion_checked, "occlusion": "unchecked").
    static constexpr bool checks_occlusion = false;

    explicit no_occlusion(const triangle_mesh& part) noexcept : num_faces_(part.num_faces()) {}
    no_occlusion(const triangle_mesh& part, std::span<const triangle_mesh> /*occluders*/) noexcept
        : num_faces_(part.num_faces()) {}

    template <Interval I>
    visibility classify(const position_box<I>& /*box*/, std::size_t facet) const {
        if (facet >= num_faces_) throw out_of_range("facet", facet, num_faces_);
        return visibility::visible;
    }

    /// No triangle may block (ShadowingOcclusionPolicy): the carving's occlusion cuts find every
    /// box VISIBLE, as `classify` does, so they need not be turned off for this policy.
    template <Interval I>
    bool blockers(const position_box<I>& /*box*/, std::size_t facet, blocker_visitor /*visit*/) const {
        if (facet >= num_faces_) throw out_of_range("facet", facet, num_faces_);
        return true;
    }
    /// Never asked: `blockers` names no triangle.
    occlusion_shadow shadow(std::size_t facet, std::size_t /*triangle*/) const {
        if (facet >= num_faces_) throw out_of_range("facet", facet, num_faces_);
        return {};
    }

private:
    std::size_t num_faces_;
};

}  // namespace certipose
