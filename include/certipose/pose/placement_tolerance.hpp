// certipose/pose/placement_tolerance.hpp — the part is not where the mesh says: how far it may
// sit from its nominal placement, and the position boxes that motion induces.
//
// A `placement_tolerance` admits every rigid motion M(x) = R_p (x − c) + c + t of the part with
// |t_i| ≤ T_i (metres, per axis of the part frame) and R_p a rotation by at most ROT radians
// about any axis through the datum c. A certificate under the tolerance holds for every such M.
//
// Why position boxes suffice. Moving the part by M and keeping the camera at (p, R) images what
// the nominal part shows to the camera at (M⁻¹p, R_pᵀR), so:
//  * the position constraints (distance, backface, viewing angle) and the part's own occlusion
//    depend on the camera position in the part frame only, p' = M⁻¹p. With
//    p' − p = (R_pᵀ − I)(p − c − t) − t and ‖(R_pᵀ − I) x‖ = 2 sin(θ/2)‖x‖ ≤ ROT·‖x‖,
//        |p'_i − p_i| ≤ T_i + ROT·(‖p − c‖ + ‖T‖),
//    so proving them over the box [p] grown by that reach (`camera_reach`) proves them for every
//    placement;
//  * the field of view sees a facet vertex v at Rᵀ(M(v) − p) in camera coordinates: the camera
//    is where it was and the vertex moved, by |M(v)_i − v_i| ≤ T_i + ROT·‖v − c‖. The image test
//    is linear in v − p, so moving v within that box is moving p within it: proving the field
//    of view over [p] grown by the facet's reach (`facet_reach`) with the SAME orientation box
//    proves it for every placement. No Euler-angle enclosure of R_pᵀR is needed.
//  * occluders that do not move with the part (a fixture, the scene's --occluder meshes) are
//    handled by occlusion/fixed_occluders.hpp: in the world frame the sight lines run from [p]
//    to the moved facet, inside the hull of [p] and the facet grown by its reach.
// The reaches are computed with outward rounding, so a box they grow contains every p' (every
// M(v)) exactly. Only poses are removed by this: a box certified under a tolerance is certified
// for the nominal placement too.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"
#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/interval/operations.hpp"
#include "certipose/pose/pose_box.hpp"

namespace certipose {

/// How far the part may sit from its nominal placement (see the header comment).
struct placement_tolerance {
    /// T: the largest translation along x, y, z of the part frame, metres (each >= 0).
    std::array<double, 3> translation{};
    /// ROT: the largest rotation, radians, about any axis through the datum (in [0, π/2]).
    double rotation = 0.0;
    /// c: the point the part rotates about, in the part frame (metres, after any scale). Unset:
    /// the part's centroid (`surface_centroid`, resolved by the solver).
    std::optional<Eigen::Vector3d> datum{};

    /// True when no motion is allowed (then nothing changes anywhere).
    bool none() const noexcept {
        return translation[0] == 0.0 && translation[1] == 0.0 && translation[2] == 0.0 && rotation == 0.0;
    }

    /// Throws invalid_argument("placement_tolerance.<field>") for a negative, NaN or infinite
    /// value, a rotation above π/2 (past it, 2 sin(θ/2) ≤ θ is still true but no camera view
    /// survives; a typo for degrees is likelier), or a non-finite datum.
    void validate() const {
        static constexpr const char* axis[] = {"x", "y", "z"};
        for (std::size_t i = 0; i < 3; ++i)
            if (!(translation[i] >= 0.0) || !std::isfinite(translation[i]))
                throw invalid_argument("placement_tolerance.translation",
                                       std::string("placement_tolerance: the translation along ") + axis[i] +
                                           " must be >= 0 and finite (metres), got " +
                                           detail::format_double(translation[i]));
        if (!(rotation >= 0.0) || !(rotation <= 1.5707963267948966))
            throw invalid_argument("placement_tolerance.rotation",
                                   "placement_tolerance: the rotation must be in [0, pi/2] radians, got " +
                                       detail::format_double(rotation) +
                                       (rotation > 1.5707963267948966 && rotation <= 90.0 ? " (degrees? give radians)" : ""));
        if (datum)
            for (int i = 0; i < 3; ++i)
                if (!std::isfinite((*datum)[i]))
                    throw invalid_argument("placement_tolerance.datum",
                                           std::string("placement_tolerance: the datum's ") + axis[i] +
                                               " must be finite, got " + detail::format_double((*datum)[i]));
    }

    friend bool operator==(const placement_tolerance&, const placement_tolerance&) = default;
};

/// The default datum: the centroid of the part's surface (facet centroids weighted by area; the
/// mean vertex for a part of zero area).
inline Eigen::Vector3d surface_centroid(const triangle_mesh& part) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    double area = 0.0;
    for (const facet& f : part.facets()) {
        sum += f.area * f.centroid;
        area += f.area;
    }
    if (area > 0.0) return sum / area;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& v : part.vertices()) mean += v;
    return mean / static_cast<double>(part.num_vertices());
}

/// A tolerance with its datum resolved (the solver's view of it).
struct resolved_placement {
    std::array<double, 3> translation{};
    double rotation = 0.0;
    Eigen::Vector3d datum = Eigen::Vector3d::Zero();
    /// ‖T‖, rounded up.
    double translation_norm = 0.0;
};

namespace detail::placement {

inline double up(double v) { return std::nextafter(v, INFINITY); }

}  // namespace detail::placement

/// `t` with its datum: `t.datum`, or `centroid` when unset.
inline resolved_placement resolve(const placement_tolerance& t, const Eigen::Vector3d& centroid) {
    t.validate();
    resolved_placement r;
    r.translation = t.translation;
    r.rotation = t.rotation;
    r.datum = t.datum.value_or(centroid);
    using detail::placement::up;
    // ‖T‖ ≤ up(sqrt(up(Σ up(T_i²)))) in any rounding mode (one float step per operation).
    double s = 0.0;
    for (double x : t.translation) s = up(s + up(x * x));
    r.translation_norm = up(std::sqrt(s));
    return r;
}

/// Per axis, how far a point at distance at most `radius` from the datum may move: T_i + ROT·radius,
/// rounded up.
inline std::array<double, 3> reach_at(const resolved_placement& t, double radius) {
    using detail::placement::up;
    const double turn = t.rotation == 0.0 ? 0.0 : up(t.rotation * radius);  // no 0·∞ = NaN
    return {up(t.translation[0] + turn), up(t.translation[1] + turn), up(t.translation[2] + turn)};
}

/// [p] grown by r on each axis, outward-rounded.
template <Interval I>
position_box<I> grown(const position_box<I>& p, const std::array<double, 3>& r) {
    if (is_empty(p)) return p;
    const rounding_guard<I> guard{};
    position_box<I> out = p;
    for (std::size_t i = 0; i < 3; ++i) out[i] = p[i] + I(-r[i], r[i]);
    return out;
}

/// How far, per axis, a camera position of [p] may be from itself in the part frame under the
/// tolerance: T_i + ROT·(max ‖p − c‖ + ‖T‖) (see the header comment), rounded up.
template <Interval I>
std::array<double, 3> camera_reach_radii(const position_box<I>& p, const resolved_placement& t) {
    double far = 0.0;
    {
        const rounding_guard<I> guard{};
        I s(0.0);
        for (std::size_t i = 0; i < 3; ++i) {
            const I d = p[i] - I(t.datum[static_cast<Eigen::Index>(i)]);
            s = s + sqr(d);
        }
        far = upper(sqrt(s) + I(t.translation_norm));
    }
    return reach_at(t, far);
}

/// Every camera position in the part frame, M⁻¹p, for p in [p] and every admitted motion M: [p]
/// grown by camera_reach_radii.
template <Interval I>
position_box<I> camera_reach(const position_box<I>& p, const resolved_placement& t) {
    if (is_empty(p)) return p;
    return grown(p, camera_reach_radii(p, t));
}

/// How far each vertex of the facet (v0, v1, v2) may move under the tolerance: T_i + ROT·max_v ‖v − c‖.
template <Interval I>
std::array<double, 3> facet_reach(const std::array<Eigen::Vector3d, 3>& v, const resolved_placement& t) {
    double far = 0.0;
    {
        const rounding_guard<I> guard{};
        for (const auto& x : v) {
            I s(0.0);
            for (Eigen::Index i = 0; i < 3; ++i) s = s + sqr(I(x[i]) - I(t.datum[i]));
            far = std::max(far, upper(sqrt(s)));
        }
    }
    return reach_at(t, far);
}

}  // namespace certipose
