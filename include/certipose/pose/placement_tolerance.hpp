// certipose/pose/placement_tolerance.hpp — the part is not where the mesh says: how far it may
// sit from its nominal placement, and the position boxes that motion induces.
//
// A `placement_tolerance` admits every rigid motion M(x) = R_p (x − c) + c + t of the part with
// |t_i| ≤ T_i (metres, per axis of the part frame) and R_p a rotation by at most ROT radians
// about any axis through the datum c. A certificate under the tolerance holds for every such M.
//
// A fixture form: with an `axis` n, R_p = R_t·R_n where R_n turns about n by at most ROT and R_t
// is a tilt by at most TILT about any axis — a part on a plate slides, turns about the plate's
// normal and barely tips. (The order does not matter: R_n·R_t = (R_n R_t R_nᵀ)·R_n and the
// conjugate is a tilt by the same angle.) The turn moves a point only across n and by at most
// ROT·‖x_⊥‖ (x_⊥: its part across n), so along axis i by at most ROT·‖x_⊥‖·√(1 − n̂_i²); the
// tilt moves it by at most TILT·‖x‖ in any direction. Writing R_pᵀ − I = R_nᵀ(R_tᵀ − I) + (R_nᵀ − I)
// for the camera and R_p − I = R_n(R_t' − I) + (R_n − I) for the part's vertices (R_t' the
// conjugate tilt) gives, per axis, ROT·√(1 − n̂_i²)·‖x_⊥‖ + TILT·‖x‖ where the any-axis form
// has ROT·‖x‖; along the plate's normal the turn adds nothing.
//
// Why position boxes suffice. Moving the part by M and keeping the camera at (p, R) images what
// the nominal part shows to the camera at (M⁻¹p, R_pᵀR), so:
//  * the position constraints (distance, backface, viewing angle) and the part's own occlusion
//    depend on the camera position in the part frame only, p' = M⁻¹p. With
//    p' − p = (R_pᵀ − I)(p − c − t) − t and ‖(R_pᵀ − I) x‖ = 2 sin(θ/2)‖x‖ ≤ ROT·‖x‖,
//        |p'_i − p_i| ≤ T_i + ROT·(‖p − c‖ + ‖T‖),
//    (with an axis: T_i + ROT·√(1 − n̂_i²)·(‖(p − c)_⊥‖ + ‖T‖) + TILT·(‖p − c‖ + ‖T‖)),
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

#include <algorithm>
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
    /// ROT: the largest rotation, radians, about any axis through the datum (in [0, π/2]); with
    /// `axis`, about that axis only.
    double rotation = 0.0;
    /// n: the one direction the part turns about (a fixture plate's normal; any length but 0).
    /// Unset: any axis.
    std::optional<Eigen::Vector3d> axis{};
    /// TILT: with `axis`, the largest further rotation about any axis, radians (in [0, π/2]).
    double tilt = 0.0;
    /// c: the point the part rotates about, in the part frame (metres, after any scale). Unset:
    /// the part's centroid (`surface_centroid`, resolved by the solver).
    std::optional<Eigen::Vector3d> datum{};

    /// True when no motion is allowed (then nothing changes anywhere).
    bool none() const noexcept {
        return translation[0] == 0.0 && translation[1] == 0.0 && translation[2] == 0.0 && rotation == 0.0 && tilt == 0.0;
    }

    /// Throws invalid_argument("placement_tolerance.<field>") for a negative, NaN or infinite
    /// value, a rotation above π/2 (past it, 2 sin(θ/2) ≤ θ is still true but no camera view
    /// survives; a typo for degrees is likelier), or a non-finite datum.
    void validate() const {
        static constexpr const char* coordinate[] = {"x", "y", "z"};
        for (std::size_t i = 0; i < 3; ++i)
            if (!(translation[i] >= 0.0) || !std::isfinite(translation[i]))
                throw invalid_argument("placement_tolerance.translation",
                                       std::string("placement_tolerance: the translation along ") + coordinate[i] +
                                           " must be >= 0 and finite (metres), got " +
                                           detail::format_double(translation[i]));
        if (!(rotation >= 0.0) || !(rotation <= 1.5707963267948966))
            throw invalid_argument("placement_tolerance.rotation",
                                   "placement_tolerance: the rotation must be in [0, pi/2] radians, got " +
                                       detail::format_double(rotation) +
                                       (rotation > 1.5707963267948966 && rotation <= 90.0 ? " (degrees? give radians)" : ""));
        if (!(tilt >= 0.0) || !(tilt <= 1.5707963267948966))
            throw invalid_argument("placement_tolerance.tilt",
                                   "placement_tolerance: the tilt must be in [0, pi/2] radians, got " + detail::format_double(tilt) +
                                       (tilt > 1.5707963267948966 && tilt <= 90.0 ? " (degrees? give radians)" : ""));
        if (tilt > 0.0 && !axis)
            throw invalid_argument("placement_tolerance.tilt",
                                   "placement_tolerance: a tilt goes with an axis the part turns about (without one, the "
                                   "rotation is about any axis already)");
        if (axis && (!axis->allFinite() || axis->isZero(0)))
            throw invalid_argument("placement_tolerance.axis", "placement_tolerance: the axis must be a finite non-zero direction, got " +
                                                                   detail::format_double((*axis)[0]) + "," +
                                                                   detail::format_double((*axis)[1]) + "," +
                                                                   detail::format_double((*axis)[2]));
        if (datum)
            for (int i = 0; i < 3; ++i)
                if (!std::isfinite((*datum)[i]))
                    throw invalid_argument("placement_tolerance.datum",
                                           std::string("placement_tolerance: the datum's ") + coordinate[i] +
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
    /// The axis as given (unset: `rotation` is about any axis), and the tilt beyond it.
    std::optional<Eigen::Vector3d> axis{};
    double tilt = 0.0;
    /// √(1 − n̂_i²) per axis i, rounded up: how much of a turn about the axis shows along i.
    std::array<double, 3> across{1.0, 1.0, 1.0};
};

namespace detail::placement {

inline double up(double v) { return std::nextafter(v, INFINITY); }
inline double down(double v) { return std::nextafter(v, -INFINITY); }
// Upper bounds of a + b and a·b for a, b ≥ 0 that stay exact where the operation is (a zero
// operand): along the plate's normal a turn about it must add exactly nothing, or a facet that
// rests on the plate would reach a few ulps into it and lose every box.
inline double add_up(double a, double b) { return a == 0.0 || b == 0.0 ? a + b : up(a + b); }
inline double mul_up(double a, double b) { return a == 0.0 || b == 0.0 ? 0.0 : up(a * b); }

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
    r.axis = t.axis;
    r.tilt = t.tilt;
    if (t.axis) {
        using detail::placement::add_up;
        using detail::placement::down;
        using detail::placement::mul_up;
        const Eigen::Vector3d& n = *t.axis;
        const double nn = down(n.squaredNorm());  // ‖n‖² rounded down (> 0: validate refused a zero axis)
        for (Eigen::Index i = 0; i < 3; ++i) {
            // 1 − n̂_i² = (n_j² + n_k²)/‖n‖², rounded up; exactly 0 along an axis n lies on.
            const double j = n[(i + 1) % 3], k = n[(i + 2) % 3];
            const double rest = add_up(mul_up(j, j), mul_up(k, k));
            r.across[static_cast<std::size_t>(i)] = rest == 0.0 ? 0.0 : std::min(1.0, up(std::sqrt(up(rest / nn))));
        }
    }
    return r;
}

/// Per axis, how far a point at distance at most `radius` from the datum, and at most `across`
/// from the axis line through it (when the tolerance has an axis), may move: T_i + ROT·radius, or
/// T_i + ROT·√(1 − n̂_i²)·across + TILT·radius with an axis; rounded up.
inline std::array<double, 3> reach_at(const resolved_placement& t, double radius, double across) {
    using detail::placement::add_up;
    using detail::placement::mul_up;
    std::array<double, 3> out{};
    for (std::size_t i = 0; i < 3; ++i) {
        // mul_up: no 0·∞ = NaN, and a zero rotation, tilt or share adds exactly nothing.
        const double turn = t.axis ? mul_up(mul_up(t.rotation, t.across[i]), across) : mul_up(t.rotation, radius);
        const double tip = mul_up(t.tilt, radius);
        out[i] = add_up(add_up(t.translation[i], turn), tip);
    }
    return out;
}

namespace detail::placement {

/// Upper bounds of ‖d‖ and of ‖d_⊥‖ (its part across the tolerance's axis; ‖d‖ without one) for
/// the interval vector d, under the caller's rounding guard: ‖d_⊥‖² = ‖d‖² − (d·n)²/‖n‖², whose
/// interval enclosure's upper end is an upper bound.
template <Interval I>
std::array<double, 2> norms(const std::array<I, 3>& d, const resolved_placement& t) {
    I s(0.0);
    for (std::size_t i = 0; i < 3; ++i) s = s + sqr(d[i]);
    const double all = upper(sqrt(s));
    if (!t.axis) return {all, all};
    I q(0.0), nn(0.0);
    for (std::size_t i = 0; i < 3; ++i) {
        const I n((*t.axis)[static_cast<Eigen::Index>(i)]);
        q = q + d[i] * n;
        nn = nn + sqr(n);
    }
    const double perp2 = std::max(0.0, upper(s - sqr(q) / nn));
    return {all, std::min(all, upper(sqrt(I(perp2))))};
}

}  // namespace detail::placement

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
    double far = 0.0, across = 0.0;
    {
        const rounding_guard<I> guard{};
        std::array<I, 3> d;
        for (std::size_t i = 0; i < 3; ++i) d[i] = p[i] - I(t.datum[static_cast<Eigen::Index>(i)]);
        const auto [all, perp] = detail::placement::norms(d, t);
        far = upper(I(all) + I(t.translation_norm));
        across = upper(I(perp) + I(t.translation_norm));
    }
    return reach_at(t, far, across);
}

/// Every camera position in the part frame, M⁻¹p, for p in [p] and every admitted motion M: [p]
/// grown by camera_reach_radii.
template <Interval I>
position_box<I> camera_reach(const position_box<I>& p, const resolved_placement& t) {
    if (is_empty(p)) return p;
    return grown(p, camera_reach_radii(p, t));
}

/// How far each vertex of the facet (v0, v1, v2) may move under the tolerance: T_i + ROT·max_v ‖v − c‖
/// (with an axis: T_i + ROT·√(1 − n̂_i²)·max_v ‖(v − c)_⊥‖ + TILT·max_v ‖v − c‖).
template <Interval I>
std::array<double, 3> facet_reach(const std::array<Eigen::Vector3d, 3>& v, const resolved_placement& t) {
    double far = 0.0, across = 0.0;
    {
        const rounding_guard<I> guard{};
        for (const auto& x : v) {
            std::array<I, 3> d;
            for (std::size_t i = 0; i < 3; ++i)
                d[i] = I(x[static_cast<Eigen::Index>(i)]) - I(t.datum[static_cast<Eigen::Index>(i)]);
            const auto [all, perp] = detail::placement::norms(d, t);
            far = std::max(far, all);
            across = std::max(across, perp);
        }
    }
    return reach_at(t, far, across);
}

}  // namespace certipose
