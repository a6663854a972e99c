// certipose/orientation/certify.hpp — proof of the field-of-view constraint over a whole 6D pose
// box by interval arithmetic (constraint 5 of docs/conventions.md; docs/orientation.md).
//
// `certify_fov(position, orientation, facet, K, w, h)` answers, for EVERY camera position p in
// [p] and EVERY rotation R(φ, γ, β) with (φ, γ, β) in [e]: is every facet vertex in front of
// the camera and inside the image? `satisfied` proves that all are, `violated` that no pose of
// the box sees the whole facet, `undecided` is neither. The paper's §6.4 offsets are an
// approximation (an offset about the camera's X/Y axes is not an offset of ZXZ angles), so every
// 6D box certipose returns as VALID has passed this test.
//
// With q = Rᵀ(v − p) a vertex in camera coordinates, the division-free image test
// 0 ≤ (Kq)_x ≤ w·q_z, 0 ≤ (Kq)_y ≤ h·q_z, q_z > 0 is five half-spaces ℓ_k·q > 0: the rows of K,
// w·ẑ and h·ẑ minus them (the side planes of the viewing frustum), and ẑ. Two proofs per vertex:
//  * Centred form (most boxes): g_k(e) = ℓ_k·Rᵀ(e)(v − p0) is enclosed by its mean-value form
//    about the box centre e0, whose derivative is ∂g_k/∂e_j = ℓ_k·(u × a_j) with u = Rᵀ(v − p0)
//    and a_j the rotation axes of φ, γ, β in camera coordinates; factored as ℓ_k·(u0 + U × W),
//    W = Σ a_j (e_j − e0_j), it costs one interval cross product per vertex and stays sharp
//    where the box is narrow. The position enters linearly, ℓ·Rᵀ(v − p) = g(e) + (Rℓ)·(p0 − p),
//    so it is bounded exactly for each rotation: Σ_j |(Rℓ)_j|·radius_j.
//  * Roll-free cone (wide β): if the angle θ between v − p and the optical axis a(φ, γ) is
//    below atan(min_k ℓ_kz / ‖ℓ_k,xy‖) the vertex is in the image for EVERY roll β. θ is
//    bounded by the triangle inequality on the sphere, about the box centre
//    (|θ − θ(v − p0, a0)| ≤ r_pos + r_axis, the angular radii of the position box seen from the
//    vertex and of the patch of axes, the latter from the spherical law of cosines) and about
//    the pole (|A − G| ≤ θ ≤ min(A + G, 2π − A − G), A and G the angles of v − p and a from
//    +z). The pole bound is what stays sharp near the ZXZ singularity γ ≈ 0 or π, where φ and β
//    are coupled (at γ = 0 only φ + β matters) and φ may span the whole circle.
// Violation is proved by one (vertex, side) pair with ℓ_k·q < 0 over the whole box, or by a
// vertex outside the cone circumscribing the image (or behind the camera) for the whole box.
// Each entry point holds a `rounding_guard<I>`; libm is called in a single round-to-nearest
// scope per batch (a mode switch costs ~100 ns, more than the libm calls it brackets).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "certipose/detail/config.hpp"
#include "certipose/detail/format.hpp"
#include "certipose/camera/camera_model.hpp"
#include "certipose/error.hpp"
#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/interval/operations.hpp"
#include "certipose/orientation/detail/spherical.hpp"
#include "certipose/outcome.hpp"  // verdict
#include "certipose/pose/pose_box.hpp"

namespace certipose {

/// The image of a camera as four half-spaces ℓ_k·q ≥ 0 in camera coordinates (u ≥ 0, u ≤ w,
/// v ≥ 0, v ≤ h in the division-free form), with what `certify_fov` needs precomputed once per
/// camera. K must have third row (0, 0, 1) and an invertible upper-left 2×2 block; the principal
/// point may lie anywhere. Throws certipose::invalid_argument("K" / "width_px" / "height_px").
template <Interval I>
class fov_frustum {
public:
    /// ℓ_k·q ≥ 0 ⇔ the pixel of q is on the image side of side k (u ≥ 0, u ≤ w, v ≥ 0, v ≤ h).
    struct side {
        std::array<I, 3> l;  ///< ℓ_k, enclosing the exact vector for the given K, w, h
    };

    fov_frustum(const Eigen::Matrix3d& K, double width_px, double height_px) {
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
                if (!std::isfinite(K(r, c)))
                    throw invalid_argument("K", "fov_frustum: K(" + std::to_string(r) + "," + std::to_string(c) +
                                                    ") must be finite, got " + certipose::detail::format_double(K(r, c)));
        if (!(K(2, 0) == 0.0 && K(2, 1) == 0.0 && K(2, 2) == 1.0))
            throw invalid_argument("K", "fov_frustum: the third row of K must be (0, 0, 1), got (" +
                                            certipose::detail::format_double(K(2, 0)) + ", " + certipose::detail::format_double(K(2, 1)) + ", " +
                                            certipose::detail::format_double(K(2, 2)) + ")");
        if (!(width_px > 0.0) || !std::isfinite(width_px))
            throw invalid_argument("width_px", "fov_frustum: width_px must be positive and finite, got " +
                                                   certipose::detail::format_double(width_px));
        if (!(height_px > 0.0) || !std::isfinite(height_px))
            throw invalid_argument("height_px", "fov_frustum: height_px must be positive and finite, got " +
                                                    certipose::detail::format_double(height_px));
        const rounding_guard<I> guard{};
        const I w(width_px), h(height_px);
        const std::array<std::array<I, 3>, 4> ls{{
            {I(K(0, 0)), I(K(0, 1)), I(K(0, 2))},              // u ≥ 0
            {I(-K(0, 0)), I(-K(0, 1)), w - I(K(0, 2))},        // u ≤ w
            {I(K(1, 0)), I(K(1, 1)), I(K(1, 2))},              // v ≥ 0
            {I(-K(1, 0)), I(-K(1, 1)), h - I(K(1, 2))},        // v ≤ h
        }};
        double inner = detail::orientation::half_pi_lo;
        for (std::size_t k = 0; k < 4; ++k) {
            sides_[k].l = ls[k];
            const I rho = sqrt(sqr(ls[k][0]) + sqr(ls[k][1]));
            if (!(lower(rho) > 0.0))
                throw invalid_argument("K", "fov_frustum: a row of K's upper-left 2x2 block is zero");
            // Roll-free cone: a unit ray q at angle t from the axis has ℓ·q ≥ ℓz cos t − ρ sin t,
            // positive while tan t < ℓz/ρ.
            inner = lower(ls[k][2]) > 0.0 ? std::min(inner, std::max(0.0, lower(atan(ls[k][2] / rho)))) : 0.0;
        }
        inner_ = inner;
        for (std::size_t k = 0; k < 4; ++k)
            for (std::size_t j = 0; j < 3; ++j) side_mids_[k][j] = mid(ls[k][j]);
        // Circumscribed cone: the largest angle from the axis of a ray through the image is at a
        // corner (the normalised image is a parallelogram, the norm is convex).
        const I a = I(K(0, 0)), b = I(K(0, 1)), c = I(K(1, 0)), d = I(K(1, 1));
        const I det = a * d - b * c;
        if (!(lower(det) > 0.0 || upper(det) < 0.0))
            throw invalid_argument("K", "fov_frustum: the upper-left 2x2 block of K must be invertible");
        double tan_outer = 0.0;
        for (const double u : {0.0, width_px})
            for (const double v : {0.0, height_px}) {
                const I du = I(u) - I(K(0, 2)), dv = I(v) - I(K(1, 2));
                const I xn = (d * du - b * dv) / det, yn = (a * dv - c * du) / det;
                tan_outer = std::max(tan_outer, upper(sqrt(sqr(xn) + sqr(yn))));
            }
        outer_ = upper(atan(I(tan_outer)));
    }

    /// From any camera model: its certified image (certified_image: K, width and height for a
    /// camera without distortion, the proven pinhole-equivalent image for one with).
    template <CameraModel C>
    explicit fov_frustum(const C& camera) : fov_frustum(certified_image(camera)) {}
    explicit fov_frustum(const pinhole_image& image) : fov_frustum(image.K, image.width_px, image.height_px) {}

    const std::array<side, 4>& sides() const noexcept { return sides_; }
    /// The midpoints of the sides' ℓ_k (plain doubles, for fov_refuted).
    const std::array<std::array<double, 3>, 4>& side_mids() const noexcept { return side_mids_; }
    /// A lower bound of the half-angle of the largest cone about the optical axis whose rays all
    /// meet the image (0 when the principal point is outside it): inside it any roll is fine.
    double inner_half_angle() const noexcept { return inner_; }
    /// An upper bound of the largest angle between the optical axis and a ray through the image.
    double outer_half_angle() const noexcept { return outer_; }

private:
    std::array<side, 4> sides_{};
    std::array<std::array<double, 3>, 4> side_mids_{};
    double inner_ = 0.0, outer_ = 0.0;
};

/// The frustum of `camera`, built once per thread for each camera in a row (compared by the K
/// and image size of its certified image, camera_model.hpp's certified_image). An orientation search asks for it on every position box, and building it
/// (interval atan, sqrt and divisions) each time would cost more than most searches. A K or size with a NaN never
/// compares equal, so such a camera is rebuilt, and throws, every time.
template <Interval I, CameraModel C>
const fov_frustum<I>& frustum_of(const C& camera) {
    struct entry {
        Eigen::Matrix3d K;
        double width, height;
        fov_frustum<I> frustum;
    };
    thread_local std::optional<entry> last;
    const pinhole_image image = certified_image(camera);
    const Eigen::Matrix3d& K = image.K;
    const double width = image.width_px, height = image.height_px;
    if (!last || !(last->K == K) || !(last->width == width) || !(last->height == height)) {
        fov_frustum<I> built(K, width, height);  // throws before `last` changes
        last.emplace(entry{K, width, height, std::move(built)});
    }
    return last->frustum;
}

namespace detail::orientation {

inline void check_facet(const facet& f) {
    for (const auto& v : f.v)
        for (int k = 0; k < 3; ++k)
            if (!std::isfinite(v[k]))
                throw invalid_argument("facet", "certify_fov: facet vertex coordinate " + certipose::detail::format_double(v[k]) +
                                                    " is not finite");
}

template <Interval I, std::size_t N>
bool finite_box(const interval_box<I, N>& b) {
    for (const I& c : b.x)
        if (!std::isfinite(lower(c)) || !std::isfinite(upper(c))) return false;
    return true;
}

/// The argument checks every orientation policy's `orient` starts with (`who` prefixes the
/// messages): ε_o positive and finite, then — unless the box is empty, when there is nothing to
/// certify and this returns false — a finite box and a finite facet.
template <Interval I>
bool checked_orient_arguments(const std::string& who, const position_box<I>& position, const facet& f,
                              double orientation_eps) {
    if (!(orientation_eps > 0.0) || !std::isfinite(orientation_eps))
        throw invalid_argument("orientation_eps", who + ": orientation_eps must be positive and finite, got " +
                                                      certipose::detail::format_double(orientation_eps));
    if (is_empty(position)) return false;
    if (!finite_box(position)) throw invalid_argument("position_box", who + ": the position box must be finite");
    check_facet(f);
    return true;
}

template <Interval I>
using ivec3 = std::array<I, 3>;

template <Interval I>
CERTIPOSE_DETAIL_INLINE I dot(const ivec3<I>& a, const ivec3<I>& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
template <Interval I>
CERTIPOSE_DETAIL_INLINE ivec3<I> cross(const ivec3<I>& a, const ivec3<I>& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

/// R(φ, γ, β) = Rz(φ)·Rx(γ)·Rz(β) from sines and cosines, row-major (docs/conventions.md#zxz-angles).
template <Interval I>
CERTIPOSE_DETAIL_INLINE std::array<ivec3<I>, 3> zxz_rows(const I& sp, const I& cp, const I& sg, const I& cg, const I& sb, const I& cb) {
    const I cg_sb = cg * sb, cg_cb = cg * cb;
    return {{{cp * cb - sp * cg_sb, -(cp * sb) - sp * cg_cb, sp * sg},
             {sp * cb + cp * cg_sb, cp * cg_cb - sp * sb, -(cp * sg)},
             {sg * sb, sg * cb, cg}}};
}

/// Rᵀ·d for R given by rows.
template <Interval I>
CERTIPOSE_DETAIL_INLINE ivec3<I> transpose_times(const std::array<ivec3<I>, 3>& r, const ivec3<I>& d) {
    return {r[0][0] * d[0] + r[1][0] * d[1] + r[2][0] * d[2], r[0][1] * d[0] + r[1][1] * d[1] + r[2][1] * d[2],
            r[0][2] * d[0] + r[1][2] * d[1] + r[2][2] * d[2]};
}

}  // namespace detail::orientation

/// What certify_fov needs of the position box alone, computed once per box: the orientation
/// search of one position box asks for a couple of dozen 6D certifications of the same [p]
/// (paper_orientation), and these square roots, divisions and libm calls were most of each.
/// The values are exactly those certify_fov computed inline before.
template <Interval I>
struct fov_position {
    position_box<I> box;
    facet target;
    bool empty = true, finite = false;
    std::array<double, 3> p0{}, r_pos{};  ///< centre and radii of the box
    std::array<detail::orientation::ivec3<I>, 3> d0{};  ///< v_i − p0
    I half_diag;                          ///< ‖radii‖
    std::array<I, 3> n0{};                ///< ‖d0_i‖
    std::array<bool, 3> reaches{};        ///< the box may reach vertex i (no roll-free proof then)
    std::array<detail::orientation::bounds, 3> b_pos{}, b_pole{};  ///< angular radius of the box from v_i; angle of d0_i from +z
    /// For fov_refuted (plain doubles, rounded to nearest): v_i − p0, its 1-norm, and that of r_pos.
    std::array<std::array<double, 3>, 3> d_near{};
    std::array<double, 3> d_norm1{};
    double r_norm1 = 0.0;

    /// Throws invalid_argument("facet") for a non-finite vertex.
    fov_position(const position_box<I>& position, const facet& f) : box(position), target(f) {
        using namespace detail::orientation;
        check_facet(f);
        const rounding_guard<I> guard{};
        empty = is_empty(position);
        if (empty) return;
        finite = finite_box(position);
        if (!finite) return;
        r_pos = {radius(position[0]), radius(position[1]), radius(position[2])};
        p0 = midpoint(position);
        for (std::size_t i = 0; i < 3; ++i)
            d0[i] = {I(f.v[i].x()) - I(p0[0]), I(f.v[i].y()) - I(p0[1]), I(f.v[i].z()) - I(p0[2])};
        half_diag = sqrt(sqr(I(r_pos[0])) + sqr(I(r_pos[1])) + sqr(I(r_pos[2])));
        std::array<double, 3> tan_pos{};
        std::array<I, 3> cos_pole{};
        for (std::size_t i = 0; i < 3; ++i) {
            const I n0_sq = dot(d0[i], d0[i]);
            n0[i] = sqrt(n0_sq);
            reaches[i] = !(upper(half_diag) < lower(n0[i]));
            if (reaches[i]) continue;
            // tan of the angular radius of the position box seen from the vertex about d0. The
            // cone {angle(·, d0) ≤ t} is convex for t < π/2, so the largest angle is at a corner
            // p0 − δ: tan = ‖δ⊥‖ / (‖d0‖ + δ∥), with ‖δ‖ = half_diag at every corner.
            const I& n = n0[i];
            const I s0 = I(r_pos[0]) * d0[i][0] / n, s1 = I(r_pos[1]) * d0[i][1] / n, s2 = I(r_pos[2]) * d0[i][2] / n;
            const I hd_sq = sqr(half_diag);
            double worst = 0.0;
            for (const I& t : {s0 + s1 + s2, s0 + s1 - s2, s0 - s1 + s2, s0 - s1 - s2}) {
                for (const I& par : {t, -t}) {
                    const double perp_sq = std::max(0.0, upper(hd_sq - sqr(par)));
                    worst = std::max(worst, upper(sqrt(I(perp_sq)) / (n + par)));
                }
            }
            tan_pos[i] = worst;
            cos_pole[i] = d0[i][2] / n;
        }
        const certipose::detail::round_to_nearest_scope nearest{};
        for (std::size_t i = 0; i < 3; ++i) {
            for (std::size_t j = 0; j < 3; ++j) d_near[i][j] = f.v[i][static_cast<Eigen::Index>(j)] - p0[j];
            d_norm1[i] = std::abs(d_near[i][0]) + std::abs(d_near[i][1]) + std::abs(d_near[i][2]);
        }
        r_norm1 = r_pos[0] + r_pos[1] + r_pos[2];
        for (std::size_t i = 0; i < 3; ++i) {
            if (reaches[i]) continue;
            b_pos[i] = atan_bounds_nearest(tan_pos[i], tan_pos[i]);
            b_pole[i] = acos_bounds_nearest(lower(cos_pole[i]), upper(cos_pole[i]));
        }
    }
};

/// A quick refutation of constraint 5 over [p] × [e]: true when, at a corner or the centre of
/// [e] and the position of [p] worst for it, some vertex lies outside the image by a margin far
/// above rounding. Such a box holds a pose that does not see the facet, so no proof of it can
/// succeed: a search may give up on it without `certify_fov`, whose subdivision (tiling) spends
/// its whole budget before failing. ℓ_k·Rᵀ(v − p) = (Rℓ_k)·(v − p) is linear in p, so its
/// minimum over the box, (Rℓ_k)·(v − p0) − Σ_j |(Rℓ_k)_j|·r_j, is reached at a corner.
/// Plain doubles: `true` is only ever used to give up on a box, never to certify one, so
/// rounding could at worst cost a certification, and the margin (1e-9 of the terms' size,
/// millions of times their rounding error) rules even that out. Most failed tiled proofs hold
/// such a corner pose (docs/orientation.md).
///
/// `trig` holds sines and cosines computed for this box or the box it was split from (a tiled
/// proof passes one along: detail/spherical.hpp, angle_trig); the overload without builds its own.
template <Interval I>
bool fov_refuted(const fov_position<I>& pos, const orientation_box<I>& orientation, const fov_frustum<I>& frustum,
                 detail::orientation::angle_trig& trig) {
    if (pos.empty || !pos.finite || is_empty(orientation) || !detail::orientation::finite_box(orientation)) return false;
    const certipose::detail::round_to_nearest_scope nearest{};
    // sin and cos of the lower bound, upper bound and midpoint of each angle.
    std::array<std::array<double, 3>, 3> sn{}, cs{};
    for (std::size_t j = 0; j < 3; ++j) {
        const std::array<double, 3> at{lower(orientation[j]), upper(orientation[j]), mid(orientation[j])};
        for (std::size_t t = 0; t < 3; ++t) trig.at(j, t, at[t], sn[j][t], cs[j][t]);
    }
    for (std::size_t t = 0; t < 9; ++t) {  // the eight corners of [e], then its centre
        const auto pick = [&](std::size_t j) -> std::size_t { return t < 8 ? (t >> j) & 1u : 2u; };
        const double sp = sn[0][pick(0)], cp = cs[0][pick(0)], sg = sn[1][pick(1)], cg = cs[1][pick(1)];
        const double sb = sn[2][pick(2)], cb = cs[2][pick(2)];
        // R = Rz(φ)·Rx(γ)·Rz(β) (rotation.hpp)
        const double r[3][3] = {{cp * cb - sp * cg * sb, -cp * sb - sp * cg * cb, sp * sg},
                                {sp * cb + cp * cg * sb, cp * cg * cb - sp * sb, -cp * sg},
                                {sg * sb, sg * cb, cg}};
        for (const auto& lk : frustum.side_mids()) {
            double m[3], mn = 0.0, slack = 0.0;
            for (std::size_t i = 0; i < 3; ++i) {
                m[i] = r[i][0] * lk[0] + r[i][1] * lk[1] + r[i][2] * lk[2];
                mn = std::max(mn, std::abs(m[i]));
                slack += std::abs(m[i]) * pos.r_pos[i];
            }
            for (std::size_t v = 0; v < 3; ++v) {
                const auto& d = pos.d_near[v];
                const double worst = m[0] * d[0] + m[1] * d[1] + m[2] * d[2] - slack;
                if (worst < -1e-9 * mn * (pos.d_norm1[v] + pos.r_norm1)) return true;
            }
        }
    }
    return false;
}

template <Interval I>
bool fov_refuted(const fov_position<I>& pos, const orientation_box<I>& orientation, const fov_frustum<I>& frustum) {
    detail::orientation::angle_trig trig;
    return fov_refuted(pos, orientation, frustum, trig);
}

// noclone: GCC's IPA-CP otherwise clones this large function per call site with the CGAL
// backend, and one test translation unit took over 20 min to compile at -O2 (12 s without).
// Clang has no such attribute (nor the problem): silence its unknown-attribute warning.
#if defined(__clang__)
#pragma clang diagnostic push
#pragma clang diagnostic ignored "-Wunknown-attributes"
#endif
/// Proves or refutes constraint 5 over the whole 6D box [p] × [e] (see the header comment), for
/// a position box prepared once (fov_position). An empty box yields `violated` (it holds no pose
/// to certify); a box with an infinite bound yields `undecided`. `trig`: as for fov_refuted.
template <Interval I>
[[gnu::noclone]] verdict certify_fov(const fov_position<I>& pos, const orientation_box<I>& orientation,
                                     const fov_frustum<I>& frustum, detail::orientation::angle_trig& trig) {
    using namespace detail::orientation;
    using certipose::detail::round_to_nearest_scope;
    const rounding_guard<I> guard{};
    if (pos.empty || is_empty(orientation)) return verdict::violated;
    if (!pos.finite || !finite_box(orientation)) return verdict::undecided;

    const I& phi = orientation[0];
    const I& gam = orientation[1];
    const I& bet = orientation[2];
    const double phi0 = mid(phi), gam0 = mid(gam), bet0 = mid(bet);
    const double r_phi = radius(phi), r_gam = radius(gam);
    // The centred form is hopeless when β spans half a turn; the roll-free cone is the tool then.
    const bool centred = width(bet) < pi_lo;
    // The law-of-cosines bound of the axis patch needs sin γ·sin γ0 ≥ 0 and cos Δφ ≥ 0.
    const bool patch = lower(gam) >= 0.0 && upper(gam) <= pi_lo && r_phi <= half_pi_lo;

    // Every sine and cosine the box needs, under ONE switch of the rounding mode (a switch
    // costs more than the libm calls; detail/spherical.hpp).
    bounds b_sp, b_cp, b_sg, b_cg, b_sb, b_cb, b_sp0, b_cp0, b_sg0, b_cg0, b_sb0, b_cb0;
    bounds b_sg_lo{}, b_cg_lo{}, b_sg_hi{}, b_cg_hi{}, b_cr{}, b_g;  // the first five: set and used only for `patch`
    {
        const round_to_nearest_scope nearest{};
        // sin and cos at each bound of [e] (slots 0, 1 of `trig`) and at its centre (slot 2).
        std::array<std::array<double, 3>, 3> sv{}, cv{};
        const std::array<double, 3> centre{phi0, gam0, bet0};
        for (std::size_t j = 0; j < 3; ++j) {
            trig.at(j, 0, lower(orientation[j]), sv[j][0], cv[j][0]);
            trig.at(j, 1, upper(orientation[j]), sv[j][1], cv[j][1]);
            trig.at(j, 2, centre[j], sv[j][2], cv[j][2]);
        }
        const auto over = [&](std::size_t j, bounds& sine, bounds& cosine) {
            sincos_bounds_from(lower(orientation[j]), upper(orientation[j]), sv[j][0], cv[j][0], sv[j][1], cv[j][1], sine,
                               cosine);
        };
        const auto at_point = [&](std::size_t j, std::size_t k, double value, bounds& sine, bounds& cosine) {
            sincos_bounds_from(value, value, sv[j][k], cv[j][k], sv[j][k], cv[j][k], sine, cosine);
        };
        over(0, b_sp, b_cp);
        over(1, b_sg, b_cg);
        b_g = acos_bounds_nearest(b_cg.lo, b_cg.hi);  // angle G between the axis and +z
        over(2, b_sb, b_cb);
        at_point(0, 2, phi0, b_sp0, b_cp0);
        at_point(1, 2, gam0, b_sg0, b_cg0);
        at_point(2, 2, bet0, b_sb0, b_cb0);
        if (patch) {
            at_point(1, 0, lower(gam), b_sg_lo, b_cg_lo);
            at_point(1, 1, upper(gam), b_sg_hi, b_cg_hi);
            b_cr = cos_bounds_nearest(r_phi, r_phi);
        }
    }
    const I sp = to_interval<I>(b_sp), cp = to_interval<I>(b_cp), sg = to_interval<I>(b_sg),
            cg = to_interval<I>(b_cg), sb = to_interval<I>(b_sb), cb = to_interval<I>(b_cb);
    const I sp0 = to_interval<I>(b_sp0), cp0 = to_interval<I>(b_cp0), sg0 = to_interval<I>(b_sg0),
            cg0 = to_interval<I>(b_cg0), sb0 = to_interval<I>(b_sb0), cb0 = to_interval<I>(b_cb0);
    const std::array<double, 3>& r_pos = pos.r_pos;
    const std::array<ivec3<I>, 3>& d0 = pos.d0;

    // ---- centred form in (φ, γ, β), exact in p -----------------------------------------------
    // g_k(e) = ℓ_k·Rᵀ(e)·d0 has ∂g_k/∂e_j = ℓ_k·(u × a_j), u = Rᵀd0, with the rotation axes in
    // camera coordinates a_φ = Rᵀẑ, a_γ = Rz(−β)x̂, a_β = ẑ. So g_k(e) ∈ ℓ_k·(u0 + U × W) with
    // W = Σ_j a_j·(e_j − e0_j): one cross product per vertex, tighter than the sum of partials
    // (sub-distributivity). The position enters linearly: ℓ·Rᵀ(v − p) = g(e) + (Rℓ)·(p0 − p).
    std::array<std::array<bool, 5>, 3> ok{};
    if (centred) {
        const auto rows = zxz_rows(sp, cp, sg, cg, sb, cb);
        const auto rows0 = zxz_rows(sp0, cp0, sg0, cg0, sb0, cb0);
        const I d_phi = phi - I(phi0), d_gam = gam - I(gam0), d_bet = bet - I(bet0);
        const ivec3<I> w{rows[2][0] * d_phi + cb * d_gam, rows[2][1] * d_phi - sb * d_gam, rows[2][2] * d_phi + d_bet};
        std::array<ivec3<I>, 5> ls{};
        for (std::size_t k = 0; k < 4; ++k) ls[k] = frustum.sides()[k].l;
        ls[4] = {I(0.0), I(0.0), I(1.0)};  // in front: q_z > 0
        std::array<I, 5> pos_term{};
        for (std::size_t k = 0; k < 5; ++k) {
            const I t = abs(dot(rows[0], ls[k])) * I(r_pos[0]) + abs(dot(rows[1], ls[k])) * I(r_pos[1]) +
                        abs(dot(rows[2], ls[k])) * I(r_pos[2]);
            pos_term[k] = I(-upper(t), upper(t));
        }
        for (std::size_t i = 0; i < 3; ++i) {
            const ivec3<I> u0 = transpose_times(rows0, d0[i]), u = transpose_times(rows, d0[i]);
            const ivec3<I> du = cross(u, w);
            const ivec3<I> s{u0[0] + du[0], u0[1] + du[1], u0[2] + du[2]};
            for (std::size_t k = 0; k < 5; ++k) {
                const I value = dot(ls[k], s) + pos_term[k];  // ⊇ ℓ_k·q over the box
                if (upper(value) < 0.0) return verdict::violated;  // outside through side k for every pose
                ok[i][k] = lower(value) > 0.0;
            }
        }
    }
    std::array<bool, 3> pending{};
    bool any_pending = false;
    for (std::size_t i = 0; i < 3; ++i) {
        pending[i] = !(ok[i][0] && ok[i][1] && ok[i][2] && ok[i][3] && ok[i][4]);
        any_pending = any_pending || pending[i];
    }
    if (!any_pending) return verdict::satisfied;

    // ---- roll-free cone: the angle θ between v − p and the axis, for the vertices left --------
    // The axis at the box centre and the angular radius of the patch of axes about it. Path via
    // (φ, γ0): moving γ moves the axis by |Δγ|, then moving φ by |Δφ|·|sin γ0|. When `patch`,
    // sharper by the spherical law of cosines:
    //   cos dist = cos γ cos γ0 + sin γ sin γ0 cos Δφ ≥ cos γ cos γ0 + sin γ sin γ0 cos r_φ,
    // a sinusoid in γ whose minimum over Γ ⊂ [0, π] is at an end of Γ (its phase is in [0, π]).
    const ivec3<I> a0{sp0 * sg0, -(cp0 * sg0), cg0};
    const I a0_norm = sqrt(dot(a0, a0));
    double cos_patch = -1.0;
    if (patch) {
        const I b = sg0 * I(b_cr.lo, 1.0);
        cos_patch = std::min(lower(to_interval<I>(b_cg_lo) * cg0 + to_interval<I>(b_sg_lo) * b),
                             lower(to_interval<I>(b_cg_hi) * cg0 + to_interval<I>(b_sg_hi) * b));
    }
    // Angle G = acos(cos γ) between the axis and +z, from the enclosure of cos over [γ].
    const double g_lo = b_g.lo, g_hi = b_g.hi;

    // Per vertex (the position-only parts are in `pos`), then one rounding switch for the acos.
    std::array<I, 3> cos_c{};
    for (std::size_t i = 0; i < 3; ++i) {
        if (!pending[i]) continue;
        if (pos.reaches[i]) return verdict::undecided;  // the box reaches the vertex
        cos_c[i] = dot(d0[i], a0) / (pos.n0[i] * a0_norm);
    }
    std::array<bounds, 3> b_c{};
    bounds b_patch{0.0, pi_hi};
    {
        const round_to_nearest_scope nearest{};
        if (patch) b_patch = acos_bounds_nearest(cos_patch, cos_patch);
        for (std::size_t i = 0; i < 3; ++i) {
            if (!pending[i]) continue;
            b_c[i] = acos_bounds_nearest(lower(cos_c[i]), upper(cos_c[i]));
        }
    }
    const std::array<bounds, 3>& b_pos = pos.b_pos;
    const std::array<bounds, 3>& b_pole = pos.b_pole;
    const double r_axis = std::min({pi_hi, upper(I(r_gam) + I(r_phi) * abs(sg0)), b_patch.hi});
    const I two_pi(2 * pi_lo, 2 * pi_hi);

    bool all_certified = true;
    for (std::size_t i = 0; i < 3; ++i) {
        if (!pending[i]) continue;
        const I r_dir(b_pos[i].hi);
        const I margin = r_dir + I(r_axis);
        const I theta_c = to_interval<I>(b_c[i]), a_pole = to_interval<I>(b_pole[i]);
        // About the box centre: |θ − θ(d0, a0)| ≤ r_dir + r_axis. About the pole:
        // |A − G| ≤ θ ≤ min(A + G, 2π − A − G), A = angle(v − p, ẑ) ∈ a_pole ± r_dir.
        const double a_lo = lower(a_pole - r_dir), a_hi = upper(a_pole + r_dir);
        const double lo = std::max({lower(theta_c - margin), 0.0, lower(I(a_lo) - I(g_hi)), lower(I(g_lo) - I(a_hi))});
        const double hi = std::min({upper(theta_c + margin), pi_hi, upper(I(a_hi) + I(g_hi)),
                                    upper(two_pi - I(a_lo) - I(g_lo))});
        if (!(lo <= hi)) {  // cannot happen with exact bounds; stay undecided rather than guess
            all_certified = false;
            continue;
        }
        if (lo >= half_pi_hi) return verdict::violated;                // behind the camera for every pose
        if (lo > frustum.outer_half_angle()) return verdict::violated;  // outside the image for every pose
        if (!(hi < frustum.inner_half_angle())) all_certified = false;  // else: in the image for any roll
    }
    return all_certified ? verdict::satisfied : verdict::undecided;
}
#if defined(__clang__)
#pragma clang diagnostic pop
#endif

template <Interval I>
verdict certify_fov(const fov_position<I>& pos, const orientation_box<I>& orientation, const fov_frustum<I>& frustum) {
    detail::orientation::angle_trig trig;
    return certify_fov(pos, orientation, frustum, trig);
}

/// Proves constraint 5 over [p] × `box` by `certify_fov`, splitting `box` while undecided: at
/// most `budget` evaluations, counted in `certifications`. β spanning π or more is never split
/// (the roll-free cone test does not improve on halves of it). True when every tile is
/// certified, so the whole box is. How paper_orientation certifies what it finds, and how a box
/// it found is proven again (part/translates.hpp).
template <Interval I>
bool certify_fov_tiled(const fov_position<I>& position, const orientation_box<I>& box, const fov_frustum<I>& frustum,
                       std::size_t budget, std::size_t& certifications) {
    // The sines and cosines of a box's bounds and centre go with it: the refutation and the
    // first evaluation share all their bounds, and a tile all but the two its split made.
    detail::orientation::angle_trig trig;
    if (fov_refuted(position, box, frustum, trig)) return false;
    std::vector<std::pair<orientation_box<I>, detail::orientation::angle_trig>> stack{{box, trig}};
    std::size_t used = 0;
    while (!stack.empty()) {
        auto [b, t] = stack.back();
        stack.pop_back();
        // This tile and every pending one need an evaluation each: when the budget cannot
        // cover them, the answer is already `false` (spending the rest would not change it).
        if (used + 1 + stack.size() > budget) return false;
        ++used, ++certifications;
        const verdict v = certify_fov(position, b, frustum, t);
        if (v == verdict::satisfied) continue;
        if (v == verdict::violated) return false;
        if (width(b[2]) >= detail::orientation::pi_lo) return false;
        const std::size_t k = widest_dimension(b);
        const auto [l, r] = bisect_at(b, k, split_point(b[k]));
        if (!(lower(b[k]) < upper(l[k]) && upper(l[k]) < upper(b[k]))) return false;  // cannot split
        stack.emplace_back(r, t);
        stack.emplace_back(l, t);
    }
    return true;
}

/// Same for a position box given as such. Throws invalid_argument("facet") for a non-finite vertex.
template <Interval I>
verdict certify_fov(const position_box<I>& position, const orientation_box<I>& orientation, const facet& f,
                    const fov_frustum<I>& frustum) {
    return certify_fov(fov_position<I>(position, f), orientation, frustum);
}

/// Same, building the frustum from K and the image size (prefer the frustum overload in loops).
template <Interval I>
verdict certify_fov(const position_box<I>& position, const orientation_box<I>& orientation, const facet& f,
                    const Eigen::Matrix3d& K, double width_px, double height_px) {
    return certify_fov(position, orientation, f, fov_frustum<I>(K, width_px, height_px));
}

/// Same for a 6D pose box.
template <Interval I>
verdict certify_fov(const pose_box<I>& box, const facet& f, const fov_frustum<I>& frustum) {
    return certify_fov(box.position, box.orientation, f, frustum);
}

/// `BoxTest` over orientation boxes for one fixed position box (the inner test of an
/// orientation paver). Counts its evaluations.
template <Interval I>
struct fov_orientation_test {
    position_box<I> position;
    facet target;
    fov_frustum<I> frustum;
    std::size_t certifications = 0;
    std::optional<fov_position<I>> prepared{};  ///< the position-only half, on first use

    verdict test(const orientation_box<I>& orientation) {
        ++certifications;
        if (!prepared) prepared.emplace(position, target);
        return certify_fov(*prepared, orientation, frustum);
    }
};

/// `BoxTest` over 6D boxes (x, y, z, φ, γ, β), e.g. for a 6D paver.
template <Interval I>
struct fov_pose_test {
    facet target;
    fov_frustum<I> frustum;
    std::size_t certifications = 0;

    verdict test(const interval_box<I, 6>& box) {
        ++certifications;
        return certify_fov(pose_box<I>::from_6d(box), target, frustum);
    }
};

}  // namespace certipose
