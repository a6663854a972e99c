// certipose/occlusion/fixed_occluders.hpp — occluders that stay put while the part moves.
//
// Under a placement tolerance (pose/placement_tolerance.hpp) the part may sit a little off its
// nominal placement, but a fixture plate or a guard rail (the scene's extra occluders) does not
// move with it. The occlusion policy proves the part's own occlusion in the part frame, where
// the part is still; for a fixed occluder the part frame is the wrong one (the occluder moves
// there). In the world frame the camera stays in [p] and every sight line ends on the moved
// facet, which lies inside the facet grown by its reach r (facet_reach). So every sight line lies
// in the convex hull H of [p] and (facet ⊕ box(r)), and a fixed triangle that is separated from
// H cannot block any of them.
//
// `sight_region_clear` proves that separation for every fixed triangle, by a separating axis
// from a small candidate set: the three coordinate axes, the triangle's normal and the facet's
// normal. Supports along an axis n are enclosed with outward-rounded intervals (the axis itself
// needs no exactness: separation along ANY vector is a proof), so "clear" is a proof and a
// rounding doubt or a triangle close to H answers "not proven". Conservative: a triangle beside
// the hull but not separable along these axes is counted as a possible blocker.
//
// Touching is allowed on one condition. Constraint 6 is about the OPEN segment from the camera c
// to a point q of the facet. If along n the triangle lies at or below t_hi, every target q at or
// above it (n·q ≥ t_hi) and the camera box strictly above (n·c > t_hi), every point of the open
// segment has n·x > t_hi: the triangle cannot meet it even where it touches the facet's region.
// That is a facet resting on a fixture plate that the tolerance does not move into it (a turn
// about the plate's normal): its sight lines end on the plate's top face, but never cross it.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/interval/operations.hpp"
#include "certipose/pose/pose_box.hpp"

namespace certipose {

/// Triangles of occluders fixed in the world frame, with their bounding boxes and normals.
struct fixed_occluders {
    struct triangle {
        std::array<Eigen::Vector3d, 3> v;
        Eigen::Vector3d normal;  ///< any vector: a candidate separating axis
        Eigen::AlignedBox3d bbox;
    };
    std::vector<triangle> triangles;

    /// Every face of every mesh.
    template <class Meshes>
    static fixed_occluders of(const Meshes& meshes) {
        fixed_occluders o;
        for (const triangle_mesh& m : meshes)
            for (std::size_t i = 0; i < m.num_faces(); ++i) {
                const facet& f = m.facet(i);
                o.triangles.push_back({f.v, f.normal, f.bbox});
            }
        return o;
    }
    bool empty() const noexcept { return triangles.empty(); }
};

namespace detail::fixed {

/// [min, max] of n·x over the box b, enclosed.
template <Interval I>
std::array<double, 2> box_support(const position_box<I>& b, const Eigen::Vector3d& n) {
    I lo(0.0), hi(0.0);
    for (std::size_t i = 0; i < 3; ++i) {
        const I a(n[static_cast<Eigen::Index>(i)]);
        const I x = a * b[i];  // the product's range over the interval: its ends are the extremes
        lo = lo + I(lower(x));
        hi = hi + I(upper(x));
    }
    return {lower(lo), upper(hi)};
}

/// [min, max] of n·x over the triangle v grown by the box [−r, r], enclosed.
template <Interval I>
std::array<double, 2> grown_triangle_support(const std::array<Eigen::Vector3d, 3>& v, const std::array<double, 3>& r,
                                             const Eigen::Vector3d& n) {
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& x : v) {
        I s(0.0);
        for (Eigen::Index i = 0; i < 3; ++i) s = s + I(n[i]) * (I(x[i]) + I(-r[static_cast<std::size_t>(i)], r[static_cast<std::size_t>(i)]));
        lo = std::min(lo, lower(s));
        hi = std::max(hi, upper(s));
    }
    return {lo, hi};
}

}  // namespace detail::fixed

/// True when no triangle of `fixed` can meet a sight line from a point of [p] to a point of the
/// facet `v` moved by at most r per axis (see the header comment). False means "not proven".
template <Interval I>
bool sight_region_clear(const position_box<I>& p, const std::array<Eigen::Vector3d, 3>& v, const Eigen::Vector3d& facet_normal,
                        const std::array<double, 3>& r, const fixed_occluders& fixed) {
    if (fixed.empty() || is_empty(p)) return true;
    const rounding_guard<I> guard{};
    // The hull's bounding box (plain comparisons of doubles rounded outward).
    Eigen::AlignedBox3d hull_box;
    for (Eigen::Index i = 0; i < 3; ++i) {
        const auto k = static_cast<std::size_t>(i);
        double lo = lower(p[k]), hi = upper(p[k]);
        for (const auto& x : v) {
            lo = std::min(lo, lower(I(x[i]) - I(r[k])));
            hi = std::max(hi, upper(I(x[i]) + I(r[k])));
        }
        hull_box.min()[i] = lo, hull_box.max()[i] = hi;
    }
    for (const auto& t : fixed.triangles) {
        // The coordinate axes: disjoint bounding boxes, or touching only where the targets are
        // with the camera box strictly beyond (see the header comment).
        bool apart = false;
        for (Eigen::Index i = 0; i < 3 && !apart; ++i) {
            const auto k = static_cast<std::size_t>(i);
            apart = t.bbox.max()[i] < hull_box.min()[i] || hull_box.max()[i] < t.bbox.min()[i] ||
                    (t.bbox.max()[i] <= hull_box.min()[i] && t.bbox.max()[i] < lower(p[k])) ||
                    (hull_box.max()[i] <= t.bbox.min()[i] && upper(p[k]) < t.bbox.min()[i]);
        }
        if (apart) continue;
        for (const Eigen::Vector3d& n : {t.normal, facet_normal}) {
            const auto a = detail::fixed::box_support(p, n);
            const auto b = detail::fixed::grown_triangle_support<I>(v, r, n);
            const double h_lo = std::min(a[0], b[0]), h_hi = std::max(a[1], b[1]);
            double t_lo = INFINITY, t_hi = -INFINITY;
            for (const auto& x : t.v) {
                const I s = I(n.x()) * I(x.x()) + I(n.y()) * I(x.y()) + I(n.z()) * I(x.z());
                t_lo = std::min(t_lo, lower(s));
                t_hi = std::max(t_hi, upper(s));
            }
            if (t_hi < h_lo || h_hi < t_lo || (t_hi <= h_lo && t_hi < a[0]) || (h_hi <= t_lo && a[1] < t_lo)) {
                apart = true;
                break;
            }
        }
        if (!apart) return false;
    }
    return true;
}

}  // namespace certipose
