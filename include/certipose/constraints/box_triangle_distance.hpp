// certipose/constraints/box_triangle_distance.hpp — certified bounds on the distance between an
// axis-aligned box and a triangle, for the focus constraint d_min ≤ ‖p − q‖ (constraint 2, docs/conventions.md).
//
// The minimum over the facet of ‖p − q‖ is the point–triangle distance, not a polynomial, so it
// is bounded rather than contracted. Lower bound: for ANY direction u, the box and the triangle
// are at least (min_{p∈box} u·p − max_i u·v_i) / ‖u‖ apart (they are separated by the slab
// between the two supporting planes). The bound is rigorous whatever u is, so u is chosen in
// plain double (the direction between approximate closest points, plus the facet normal) and only
// the bound itself is evaluated with outward-rounded intervals. Upper bound on the *maximum*
// distance is at a vertex of both (convexity), also evaluated with intervals.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "certipose/interval/concept.hpp"
#include "certipose/interval/operations.hpp"
#include "certipose/pose/pose_box.hpp"

namespace certipose {

namespace detail {

/// Closest point of triangle (a, b, c) to p, plain double (Ericson, Real-Time Collision
/// Detection §5.1.5). Only used to pick a direction; soundness does not depend on it.
inline Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                                 const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const Eigen::Vector3d bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
    const Eigen::Vector3d cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
    const double denom = 1.0 / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

/// Closest point of an axis-aligned box to q (clamping), plain double.
template <Interval I>
Eigen::Vector3d clamp_to_box(const Eigen::Vector3d& q, const position_box<I>& b) {
    return {std::clamp(q.x(), lower(b[0]), upper(b[0])), std::clamp(q.y(), lower(b[1]), upper(b[1])),
            std::clamp(q.z(), lower(b[2]), upper(b[2]))};
}

/// Rigorous lower bounds of the box–triangle distance from directions u and −u (0 where one
/// separates nothing), from one evaluation: the extremes of u·p over the box and over the
/// triangle give both (the bounds for −u are those of u negated, exactly so under outward
/// rounding). Must be called with the rounding mode held (rounding_guard<I>).
template <Interval I>
std::array<double, 2> separation_along(const position_box<I>& b, const std::array<Eigen::Vector3d, 3>& v,
                                       const Eigen::Vector3d& u) {
    // min and max over the box of u·p are attained componentwise; the interval dot product
    // encloses them.
    const I box_side = I(u.x()) * b[0] + I(u.y()) * b[1] + I(u.z()) * b[2];
    double tri_max = -std::numeric_limits<double>::infinity(), tri_min = std::numeric_limits<double>::infinity();
    for (const auto& vi : v) {
        const I s = I(u.x()) * I(vi.x()) + I(u.y()) * I(vi.y()) + I(u.z()) * I(vi.z());
        tri_max = std::max(tri_max, upper(s));
        tri_min = std::min(tri_min, lower(s));
    }
    const double gap_u = lower(I(lower(box_side)) - I(tri_max));      // ≤ min box − max triangle along u
    const double gap_minus = lower(I(tri_min) - I(upper(box_side)));  // the same along −u
    if (!(gap_u > 0.0) && !(gap_minus > 0.0)) return {0.0, 0.0};
    const I norm = sqrt(sqr(I(u.x())) + sqr(I(u.y())) + sqr(I(u.z())));
    const auto along = [&](double gap) { return gap > 0.0 ? lower(I(gap) / I(upper(norm))) : 0.0; };
    return {along(gap_u), along(gap_minus)};
}

}  // namespace detail

/// A lower bound, certified, of min { ‖p − q‖ : p ∈ box, q ∈ triangle }; 0 when the two may meet.
/// It may stop at the first bound reaching `enough` (a caller that only compares the bound
/// with a threshold needs no better one). Needs the rounding mode held (the caller's
/// rounding_guard<I>).
template <Interval I>
double box_triangle_distance_lower(const position_box<I>& b, const std::array<Eigen::Vector3d, 3>& v,
                                   const Eigen::Vector3d& normal,
                                   double enough = std::numeric_limits<double>::infinity()) {
    double best = 0.0;
    const auto try_direction = [&](const Eigen::Vector3d& u) {
        if (u.squaredNorm() > 0.0 && std::isfinite(u.squaredNorm())) {
            const auto both = detail::separation_along(b, v, u);
            best = std::max({best, both[0], both[1]});
        }
    };
    try_direction(normal);  // and −normal
    if (best >= enough && best > 0.0) return best;
    // A few rounds of alternating projection approximate the closest pair (box and triangle
    // are convex); the final difference is the separating direction to test.
    const auto m = midpoint(b);
    Eigen::Vector3d p(m[0], m[1], m[2]), q = v[0];
    for (int it = 0; it < 4; ++it) {
        q = detail::closest_point_on_triangle(p, v[0], v[1], v[2]);
        p = detail::clamp_to_box(q, b);
    }
    try_direction(p - q);
    return best;
}

/// A certified upper bound of max { ‖p − q‖ : p ∈ box, q ∈ triangle } (attained at a box corner
/// and a triangle vertex). Needs the rounding mode held.
template <Interval I>
double box_triangle_distance_upper(const position_box<I>& b, const std::array<Eigen::Vector3d, 3>& v) {
    double best = 0.0;
    for (const auto& vi : v) {
        const I d2 = sqr(b[0] - vi.x()) + sqr(b[1] - vi.y()) + sqr(b[2] - vi.z());
        best = std::max(best, upper(sqrt(d2)));
    }
    return best;
}

}  // namespace certipose
