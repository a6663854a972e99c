// certipose/orientation/paper_orientation.hpp — the default OrientationPolicy: the paper's §6.4
// orientation intervals, certified over the whole 6D box (docs/orientation.md, Algorithm 3 l. 28–36).
//
// For a certified position box [p]:
//  1. Nominal aim: the optical axis from the centre of [p] to the facet centroid gives φ_nom and
//     γ_nom (axis R·ẑ = (sin φ sin γ, −cos φ sin γ, cos γ)); β_nom = 0.
//  2. Allowable φ/γ offsets (§6.4.1): the facet vertices relative to [p] are expressed in the
//     nominal camera frame ([D]_v, interval vectors over the whole box) and bounded by four
//     hyperplanes through the camera centre — two containing the camera Y axis (left/right),
//     two containing its X axis (up/down) — solved with HC4. We parametrise each plane by the
//     tangent of its angle (x = tan a: X − x·Z ≥ 0) rather than by cos a / sin a, so the unknown
//     occurs once per constraint and HC4Revise is exact on it. The pan/tilt that keep the
//     bounded angles within the FOV half-angles are the offsets. A pan about the camera's Y axis
//     is NOT an offset of φ: moving φ drags the axis along a circle of radius sin γ, so the φ
//     offsets are the pan offsets divided by sin γ_nom (the paper adds them unscaled); moving
//     γ tilts the axis by the same angle.
//  3. Allowable β (§6.4.2): the projection constraints ℓ_k·Rz(−β)·[b]_v ≥ 0 (vertex inside
//     each image side, division-free), [b]_v = Rx(−[γ])·Rz(−[φ])·([v] − [p]), contracted from
//     [−π, π] with HC4 (and ACID; the paper uses both). That hull is an outer approximation, in
//     practice the whole circle, and certification decides the box anyway, so `orient` does
//     not compute it (`paper_candidate` does by default). Past the paper, [β] is narrowed to
//     the arc of rolls about β = 0 that keeps every vertex inside the image at the nominal aim.
//  4. Certification: the paper's box is an approximation (it bounds the vertices over some
//     position of the box, and offsets of ZXZ angles are not camera-frame offsets), so the 6D
//     box is proven with `certify_fov`, by internal subdivision when one evaluation is not
//     enough (the hull of a certified tiling is certified). The paper's box itself is not
//     tried: its φ/γ edges are where a vertex reaches the image border from some position of
//     the box, so a proof over the whole box fails (docs/orientation.md). The box shrinks toward the nominal aim
//     (halving from one half, down to a box narrower than ε_o; β stays whole when the roll is
//     free, since the roll-free cone test does not care), the largest certified scale is
//     refined by bisection, and then β alone is widened back toward the paper's [β] as far as
//     certification allows (φ and γ alone are not: at the refined scale they are what fails,
//     and widening either does not certify). So each position box yields
//     one certified box, containing the nominal aim whenever the paper's box does, as wide as the
//     search can certify — the installation tolerance in aim — or nothing, and the solver
//     bisects [p]. With β whole, the smallest box the halving would try is certified first:
//     when that fails, the search gives up at once (one tiled certification instead of ~19).
//  5. Hints (HintedOrientationPolicy, past the paper): the solver passes what the search of a
//     neighbouring box in the same cell of ε_p found (`hint`: the refined scale and β's widened
//     scale). The box at those scales around this box's own aim is tried first, then one step
//     wider; the search above runs only when it fails. Neighbours mostly take the same scale,
//     so most small boxes (carved pieces, corner boxes) cost 1–2 tiled certifications instead of
//     ~24 (the refinement and β widening fail most of the time and cost the most); the box
//     found may be a little narrower than a search of its own would give.
//  6. Refutation: a box that `fov_refuted` shows to hold a pose not seeing the facet is given up
//     without a tiled proof (which spends its whole budget before failing). A search without a
//     hint refutes its narrowest box first: every box its halving would try holds it.
// Near the ZXZ singularity (γ_nom ≈ 0 or π, looking straight down or up the z axis) φ and β are
// coupled (at γ = 0 only φ + β matters) and the φ offsets blow up as 1/sin γ: they are capped at
// ±π. Boxes stay sound (certification bounds the axis by its angle from the pole there) but the
// certified ones are often narrower, or need a smaller position box.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <optional>
#include <span>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "certipose/camera/camera_model.hpp"
#include "certipose/contractor/acid.hpp"
#include "certipose/contractor/concept.hpp"
#include "certipose/contractor/hc4.hpp"
#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"
#include "certipose/expr/constraint.hpp"
#include "certipose/expr/expression.hpp"
#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/interval/operations.hpp"
#include "certipose/orientation/certify.hpp"
#include "certipose/orientation/concept.hpp"
#include "certipose/orientation/detail/spherical.hpp"
#include "certipose/pose/pose_box.hpp"
#include "certipose/pose/rotation.hpp"

namespace certipose {

/// The paper's nominal aim for a position box: the optical axis from the box centre to the
/// facet centroid (γ ∈ [0, π], φ = 0 on the z axis where it is undetermined), β = 0. Nothing
/// when the box centre is the centroid.
template <Interval I>
std::optional<zxz_angles> nominal_aim(const position_box<I>& position, const facet& f) {
    if (is_empty(position)) return std::nullopt;
    const auto m = midpoint(position);
    const Eigen::Vector3d dir = f.centroid - Eigen::Vector3d(m[0], m[1], m[2]);
    if (!(dir.squaredNorm() > 0.0) || !dir.allFinite()) return std::nullopt;
    return zxz_angles_from_axis(dir);
}

/// Search settings of `paper_orientation` (defaults suit ε_o ≈ 0.1–0.4 rad).
struct paper_orientation_options {
    /// `certify_fov` evaluations allowed to prove one box by internal subdivision (1: none).
    std::size_t tiling_budget = 8;
    /// Bisection steps on the scale factor between the largest certified scale and the next.
    int refine_steps = 2;
    /// Afterwards, bisection steps widening [β] alone toward the paper's [β] (0: off).
    int widen_steps = 1;
    /// Hard cap of `certify_fov` evaluations per position box.
    std::size_t max_certifications = 256;
    /// Position boxes smaller than this fraction of their cell of ε_p (ε_p³, known from the
    /// hint: HintedOrientationPolicy) keep the first scale that certifies: no `refine_steps`, no
    /// β widening (0: every box is refined). Small boxes are the many corner boxes and pieces
    /// along the boundary of what is valid, most of which take their neighbour's scale anyway.
    /// A search without a hint refines every box.
    double refine_min_fraction = 0.1;
};

/// How `paper_candidate` contracts [β] from [−π, π] before the roll arc narrows it.
enum class beta_contraction {
    none,     ///< the roll arc alone
    hc4,      ///< HC4 over the twelve projection constraints (the paper)
    hc4_acid  ///< HC4, then ACID (the paper's "HC4 and ACID")
};

namespace detail::orientation {

// ---- §6.4.1: the four hyperplanes, x = tan(angle) of each plane in the nominal camera frame.
// Box: (x_left, x_right, t_up, t_down). Params 3v, 3v+1, 3v+2: [D]_v's x, y, z.
template <std::size_t V>
auto hyperplane_constraints() {
    constexpr var<0> x_left;
    constexpr var<1> x_right;
    constexpr var<2> t_up;
    constexpr var<3> t_down;
    const param<3 * V> dx{};
    const param<3 * V + 1> dy{};
    const param<3 * V + 2> dz{};
    return std::tuple{dx - dz * x_left >= 0.0,   // right of the left plane
                      dx - dz * x_right <= 0.0,  // left of the right plane
                      dy - dz * t_up >= 0.0,     // below the upper plane (image y points down)
                      dy - dz * t_down <= 0.0};  // above the lower plane
}

inline auto make_hyperplane_system() {
    return std::apply([](auto... c) { return hc4(std::move(c)...); },
                      std::tuple_cat(hyperplane_constraints<0>(), hyperplane_constraints<1>(),
                                     hyperplane_constraints<2>()));
}

// ---- §6.4.2: the projection constraint in β for one (vertex, image side): ℓ·Rz(−β)·b ≥ 0.
// Box: (β). Params 0–2: [b]_v, 3–5: ℓ_k. All twelve (vertex, side) pairs share this one
// constraint type with different parameters, so HC4's propagation over them is a loop (below)
// instead of twelve template instantiations of a trigonometric tree (compile time).
inline auto make_beta_constraint() {
    constexpr var<0> b;
    const param<0> bx{};
    const param<1> by{};
    const param<2> bz{};
    const param<3> lx{};
    const param<4> ly{};
    const param<5> lz{};
    // q = Rz(−β)·b; ℓ·q ≥ 0.
    return hc4(lx * (cos(b) * bx + sin(b) * by) + ly * (cos(b) * by - sin(b) * bx) + lz * bz >= 0.0);
}

template <std::size_t Id, class C, Interval I>
void set_interval_param(C& c, const I& v) {
    c.template set_param<Id>(lower(v), upper(v));
}

template <class C, Interval I, std::size_t... Is>
void set_params(C& c, const std::array<I, sizeof...(Is)>& values, std::index_sequence<Is...>) {
    (set_interval_param<Is>(c, values[Is]), ...);
}

/// The twelve projection constraints of §6.4.2 as one `Contractor` of the box (β): HC4's
/// propagation, i.e. each constraint revised in turn until [β] narrows by less than HC4's ratio
/// in a whole round (one variable, so every constraint is requeued after any narrowing).
template <Interval I>
class beta_projection {
public:
    using certipose_contractor = void;

    beta_projection(const std::array<std::array<I, 3>, 3>& b, const std::array<std::array<I, 3>, 4>& sides)
        : b_(b), sides_(sides) {}

    void contract(interval_box<I, 1>& box) const {
        for (int round = 0; round < 32 && !is_empty(box); ++round) {
            const double before = width(box[0]);
            for (std::size_t vk = 0; vk < 12 && !is_empty(box); ++vk) {
                const auto& bv = b_[vk / 4];
                const auto& l = sides_[vk % 4];
                const std::array<I, 6> values{bv[0], bv[1], bv[2], l[0], l[1], l[2]};
                set_params(c_, values, std::make_index_sequence<6>{});
                c_.contract(box);
            }
            if (is_empty(box) || !(width(box[0]) < (1.0 - c_.ratio()) * before)) break;
        }
    }

private:
    using hc4_type = decltype(make_beta_constraint());
    std::array<std::array<I, 3>, 3> b_;
    std::array<std::array<I, 3>, 4> sides_;
    mutable hc4_type c_ = make_beta_constraint();  // parameters are rewritten on every call
};

/// The rolls β ∈ [lo, hi] ∋ 0 such that, at the aim (φ, γ) and for every position of the box,
/// every vertex stays inside the image: with b = (Rz(φ)Rx(γ))ᵀ(v − p) over the position box
/// (a box about its centre c with half-extents e), side k holds for all p iff
/// (Rz(β)ℓ_k)·c − Σ_j |(Rz(β)ℓ_k)_j|·e_j ≥ 0. Walked out from 0 in steps of π/32, then refined
/// by bisection. Plain double: a starting point for the search, which certification decides.
/// Nothing when β = 0 itself fails; [−π, π] when every roll works.
template <Interval I>
std::optional<std::pair<double, double>> roll_arc(const position_box<I>& position, const facet& f, const zxz_angles& aim,
                                                  const fov_frustum<I>& frustum) {
    const certipose::detail::round_to_nearest_scope nearest{};
    const Eigen::Matrix3d r = zxz_rotation(aim.phi, aim.gamma, 0.0);
    const auto p0 = midpoint(position);
    const Eigen::Vector3d rad(radius(position[0]), radius(position[1]), radius(position[2]));
    std::array<Eigen::Vector3d, 3> c, e;
    for (std::size_t v = 0; v < 3; ++v) {
        c[v] = r.transpose() * (f.v[v] - Eigen::Vector3d(p0[0], p0[1], p0[2]));
        e[v] = r.transpose().cwiseAbs() * rad;
    }
    std::array<Eigen::Vector3d, 4> l;
    for (std::size_t k = 0; k < 4; ++k)
        for (int j = 0; j < 3; ++j) l[k][j] = mid(frustum.sides()[k].l[static_cast<std::size_t>(j)]);
    const auto fits_cs = [&](double cb, double sb) {
        for (const auto& lk : l) {
            const Eigen::Vector3d m(cb * lk.x() - sb * lk.y(), sb * lk.x() + cb * lk.y(), lk.z());
            for (std::size_t v = 0; v < 3; ++v)
                if (m.dot(c[v]) - m.cwiseAbs().dot(e[v]) < 0.0) return false;
        }
        return true;
    };
    const auto fits = [&](double beta) { return fits_cs(std::cos(beta), std::sin(beta)); };
    constexpr double step = std::numbers::pi / 32;
    // cos and sin of the walk's steps, once (here, i.e. rounding to nearest, as computed inline
    // before): most arcs walk all 64 steps, and their libm calls were most of this function.
    static const std::array<std::array<double, 2>, 33> steps = [] {
        std::array<std::array<double, 2>, 33> t{};
        for (int i = 0; i <= 32; ++i) t[i] = {std::cos(i * step), std::sin(i * step)};
        return t;
    }();
    // Most arcs are the whole circle (the facet is small in the image), and walking it costs 64
    // tests. Every roll fits when, for each side k and vertex v, lz·c_z − ρ_k(‖c_xy‖ + ‖e_xy‖)
    // − |lz|·e_z > 0 (ρ_k = ‖ℓ_k,xy‖, which Rz(β) keeps): the rotated ℓ_k has m·c ≥ lz·c_z −
    // ρ_k‖c_xy‖ and |m|·e ≤ ρ_k‖e_xy‖ + |lz|·e_z. The margin, far above rounding, makes the walk
    // agree: it would have found the whole circle too.
    const auto every_roll_fits = [&] {
        for (const auto& lk : l) {
            const double rho = std::hypot(lk.x(), lk.y());
            for (std::size_t v = 0; v < 3; ++v) {
                const double cxy = std::hypot(c[v].x(), c[v].y()), exy = std::hypot(e[v].x(), e[v].y());
                const double worst = lk.z() * c[v].z() - rho * (cxy + exy) - std::abs(lk.z()) * e[v].z();
                const double scale = std::abs(lk.z()) * (std::abs(c[v].z()) + e[v].z()) + rho * (cxy + exy);
                if (!(worst > 1e-9 * scale)) return false;
            }
        }
        return true;
    };
    if (every_roll_fits()) return std::pair{-pi_lo, pi_lo};
    if (!fits(0.0)) return std::nullopt;
    const auto reach = [&](double sign) {
        double ok = 0.0;
        for (int i = 1; i <= 32; ++i) {
            const double t = i * step;
            if (!fits_cs(steps[i][0], sign * steps[i][1])) {
                double bad = t;
                for (int j = 0; j < 4; ++j) {
                    const double m = 0.5 * (ok + bad);
                    (fits(sign * m) ? ok : bad) = m;
                }
                return ok;
            }
            ok = t;
        }
        return std::numbers::pi;
    };
    const double up = reach(1.0), down = reach(-1.0);
    if (up + down >= 2 * std::numbers::pi - 1e-9) return std::pair{-pi_lo, pi_lo};
    return std::pair{-down, up};
}

}  // namespace detail::orientation

/// The box of §6.4 before certification: [φ], [γ] from the four-hyperplane system (HC4) and
/// [β] from the projection constraints (as `beta` says; HC4 by default), narrowed to the roll arc
/// about β = 0 that fits at the nominal aim. Nothing when the facet cannot fit the field of
/// view from every position of the box (the hyperplanes are farther apart than the FOV, or a
/// vertex may lie beside or behind the nominal camera). Not certified.
// Not inlined: its plain-double steps (the pan and tilt sums, the roll arc) run between changes
// of the rounding mode, which g++ does not know orders them (GCC PR 34678), so an inlined copy
// may round one of them otherwise and give a box one ulp apart. One copy per interval type
// gives every camera model of a program the same candidate boxes.
template <Interval I>
[[gnu::noinline]] std::optional<orientation_box<I>> paper_candidate(const position_box<I>& position, const facet& f,
                                                  const fov_half_angles& fov, const fov_frustum<I>& frustum,
                                                  beta_contraction beta = beta_contraction::hc4) {
    using namespace detail::orientation;
    const auto aim = nominal_aim(position, f);
    if (!aim || is_empty(position)) return std::nullopt;
    const rounding_guard<I> guard{};
    const Eigen::Matrix3d r0 = zxz_rotation(aim->phi, aim->gamma, 0.0);

    // [D]_v = R_nomᵀ·(v − [p]) over the whole position box.
    std::array<I, 9> dv{};
    for (std::size_t v = 0; v < 3; ++v) {
        const std::array<I, 3> d{I(f.v[v].x()) - position[0], I(f.v[v].y()) - position[1],
                                 I(f.v[v].z()) - position[2]};
        for (std::size_t r = 0; r < 3; ++r)
            dv[3 * v + r] = I(r0(0, r)) * d[0] + I(r0(1, r)) * d[1] + I(r0(2, r)) * d[2];
        if (!(lower(dv[3 * v + 2]) > 0.0)) return std::nullopt;  // beside or behind the nominal camera
    }
    auto planes = make_hyperplane_system();
    set_params(planes, dv, std::make_index_sequence<9>{});
    constexpr double big = 1e6;  // any plane angle in (−π/2, π/2)
    interval_box<I, 4> x = interval_box<I, 4>::from_bounds({{{-big, big}, {-big, big}, {-big, big}, {-big, big}}});
    planes.contract(x);
    if (is_empty(x)) return std::nullopt;

    // Pan Δh keeps every horizontal angle h in [Δh − α_h, Δh + α_h]: Δh ∈ [a_right − α_h,
    // a_left + α_h] (the best planes HC4 allows); the same for tilt.
    bounds left, right, up, down;
    {
        const certipose::detail::round_to_nearest_scope nearest{};
        left = atan_bounds_nearest(upper(x[0]), upper(x[0]));
        right = atan_bounds_nearest(lower(x[1]), lower(x[1]));
        up = atan_bounds_nearest(upper(x[2]), upper(x[2]));
        down = atan_bounds_nearest(lower(x[3]), lower(x[3]));
    }
    const double pan_lo = right.lo - fov.horizontal, pan_hi = left.hi + fov.horizontal;
    const double tilt_lo = down.lo - fov.vertical, tilt_hi = up.hi + fov.vertical;
    if (!(pan_lo <= pan_hi) || !(tilt_lo <= tilt_hi)) return std::nullopt;

    // Pan moves the axis along e₁ by sin γ·Δφ; tilt toward +y (down) is −Δγ.
    const double s = std::sin(aim->gamma);
    const double phi_lo = s > 0 ? std::max(-pi_lo, pan_lo / s) : -pi_lo;
    const double phi_hi = s > 0 ? std::min(pi_lo, pan_hi / s) : pi_lo;
    orientation_box<I> box;
    box[0] = I(aim->phi + phi_lo, aim->phi + phi_hi);
    box[1] = I(aim->gamma - tilt_hi, aim->gamma - tilt_lo);

    interval_box<I, 1> b = interval_box<I, 1>::from_bounds({{{-pi_lo, pi_lo}}});
    if (beta != beta_contraction::none) {
        // [b]_v = Rx(−[γ])·Rz(−[φ])·(v − [p]) and the four image sides ℓ_k.
        const I sp = sin(box[0]), cp = cos(box[0]), sg = sin(box[1]), cg = cos(box[1]);
        std::array<std::array<I, 3>, 3> bv{};
        for (std::size_t v = 0; v < 3; ++v) {
            const std::array<I, 3> d{I(f.v[v].x()) - position[0], I(f.v[v].y()) - position[1],
                                     I(f.v[v].z()) - position[2]};
            const I cx = cp * d[0] + sp * d[1], cy = cp * d[1] - sp * d[0];
            bv[v] = {cx, cg * cy + sg * d[2], cg * d[2] - sg * cy};
        }
        std::array<std::array<I, 3>, 4> sides{};
        for (std::size_t k = 0; k < 4; ++k) sides[k] = frustum.sides()[k].l;
        const beta_projection<I> projection(bv, sides);
        projection.contract(b);
        if (beta == beta_contraction::hc4_acid && !is_empty(b)) acid(projection).contract(b);
        if (is_empty(b)) return std::nullopt;
    }
    // HC4's [β] (when run) is an outer approximation over the whole box of positions and aims,
    // in practice the whole circle. Past the paper: intersect it with the arc of rolls about β = 0
    // that keeps every vertex inside the image from every position at the nominal aim.
    const auto arc = roll_arc(position, f, *aim, frustum);
    if (arc) {
        const I narrowed = intersect(b[0], I(arc->first, arc->second));
        if (!is_empty(narrowed)) b[0] = narrowed;
    }
    box[2] = b[0];
    return box;
}

/// Same, for any camera model.
template <Interval I, CameraModel C>
std::optional<orientation_box<I>> paper_candidate(const position_box<I>& position, const facet& f, const C& camera,
                                                  beta_contraction beta = beta_contraction::hc4) {
    return paper_candidate(position, f, camera.fov_half_angles(), fov_frustum<I>(camera), beta);
}

/// The default orientation policy (see the header comment). Stateless: `orient` is const and
/// one object may serve several threads.
class paper_orientation {
public:
    paper_orientation() = default;
    explicit paper_orientation(paper_orientation_options options) : options_(options) {
        if (options_.tiling_budget == 0)
            throw invalid_argument("tiling_budget", "paper_orientation: tiling_budget must be at least 1");
        if (options_.refine_steps < 0 || options_.widen_steps < 0)
            throw invalid_argument("refine_steps", "paper_orientation: refine_steps and widen_steps must be >= 0");
        if (options_.max_certifications == 0)
            throw invalid_argument("max_certifications", "paper_orientation: max_certifications must be at least 1");
        if (!(options_.refine_min_fraction >= 0.0) || !std::isfinite(options_.refine_min_fraction))
            throw invalid_argument("refine_min_fraction",
                                   "paper_orientation: refine_min_fraction must be >= 0 and finite, got " +
                                       certipose::detail::format_double(options_.refine_min_fraction));
    }

    const paper_orientation_options& options() const noexcept { return options_; }

    /// What a search found, for the search of a nearby position box (HintedOrientationPolicy):
    /// the scales of the paper's box that certified. The next search tries the box at those
    /// scales around its own aim, then one step wider (×1.5), and searches only when the first
    /// fails (halving from below the hint's scale, then the scales above it): at a neighbour's
    /// scales most boxes of a cell certify at once, where a search of their own spends many
    /// evaluations, mostly on failed refinements.
    struct hint {
        double scale = 0.0;       ///< of φ and γ (and β unless widened), in (0, 1]; 0: nothing known
        double beta_scale = 0.0;  ///< of β, after widening toward the paper's [β]
        double cell = 0.0;        ///< width of the cell of ε_p it serves (0: unknown)
    };

    /// A hint for a cell `cell_width` (ε_p) wide, knowing nothing yet.
    hint new_hint(double cell_width) const noexcept { return hint{.cell = cell_width}; }

    /// Certified orientation boxes for `position` (at most one; see the header comment).
    /// Throws invalid_argument("orientation_eps") unless ε_o is positive and finite, and
    /// invalid_argument("position_box") for a non-finite box.
    template <Interval I, CameraModel C>
    orientation_result<I> orient(const position_box<I>& position, const facet& f, const C& camera,
                                 double orientation_eps) const {
        hint none;
        return orient(position, f, camera, orientation_eps, none);
    }

    /// The same, starting from the scale `from` names and updating it (see `hint`).
    template <Interval I, CameraModel C>
    orientation_result<I> orient(const position_box<I>& position, const facet& f, const C& camera,
                                 double orientation_eps, hint& from) const {
        return orient_from(position, f, camera, orientation_eps, from, false);
    }

    /// For a box whose own search found nothing (BorrowingOrientationPolicy): the box that the
    /// widest of `neighbours` names around this box's own aim, then one step wider, as for a
    /// hint, and no search. Null or empty hints are skipped; none left: nothing, at no cost.
    /// The search of a box stops halving at ε_o, while a neighbour's scale (found by halving
    /// and refining the neighbour's own, wider, candidate box) may name a narrower box that
    /// certifies (docs/completeness.md measures what this adds).
    template <Interval I, CameraModel C>
    orientation_result<I> orient_borrowed(const position_box<I>& position, const facet& f, const C& camera,
                                          double orientation_eps, std::span<const hint* const> neighbours) const {
        const hint* widest = nullptr;
        for (const hint* h : neighbours)
            if (h && h->scale > 0.0 && h->scale <= 1.0 && h->beta_scale >= h->scale && h->beta_scale <= 1.0 &&
                (!widest || h->scale > widest->scale))
                widest = h;
        if (!widest) {
            (void)detail::orientation::checked_orient_arguments("paper_orientation", position, f, orientation_eps);
            return {};
        }
        hint from = *widest;
        return orient_from(position, f, camera, orientation_eps, from, true);
    }

private:
    // `borrowed`: try the box `from` names (and one step wider) only (orient_borrowed).
    template <Interval I, CameraModel C>
    orientation_result<I> orient_from(const position_box<I>& position, const facet& f, const C& camera,
                                      double orientation_eps, hint& from, bool borrowed) const {
        orientation_result<I> out;
        if (!detail::orientation::checked_orient_arguments("paper_orientation", position, f, orientation_eps)) return out;
        const rounding_guard<I> guard{};
        // A copy: frustum_of's one-entry cache is replaced by the next camera asked for on this
        // thread, which a user's policy wrapping this one may do while the search runs.
        const fov_frustum<I> frustum = frustum_of<I>(camera);
        const auto aim = nominal_aim(position, f);
        const auto cand = paper_candidate(position, f, camera.fov_half_angles(), frustum, beta_contraction::none);
        if (!aim || !cand) return out;

        std::array<double, 3> centre{aim->phi, aim->gamma, aim->beta};
        if (!contains(*cand, centre)) centre = midpoint(*cand);
        const fov_position<I> prepared(position, f);  // the position-only half of every certification
        // Small boxes keep the scale found (refine_min_fraction of the hint's cell).
        const bool refine = !(volume(position) < options_.refine_min_fraction * (from.cell * from.cell * from.cell));
        const bool whole_roll = width((*cand)[2]) >= 2 * detail::orientation::pi_lo;
        std::optional<orientation_box<I>> best =
            scale_search<I>(*this, *cand, centre, prepared, frustum, orientation_eps, whole_roll, out.certifications)
                .run(from, borrowed, refine);
        if (!best && whole_roll && out.certifications < options_.max_certifications)  // not roll-free after all
            best = scale_search<I>(*this, *cand, centre, prepared, frustum, orientation_eps, false, out.certifications)
                       .run(from, borrowed, refine);
        if (best) out.boxes.push_back(*best);
        return out;
    }

    /// The search of steps 4–5 of the header comment for one position box: the paper's box
    /// shrunk toward `centre` by a scale s, with β kept whole when `roll_free` (the roll-free
    /// cone does not care how wide β is, so shrinking it would be wasted). Its steps, in order:
    /// the hint's box (`hinted_box`), the narrowest box the halving would try (`floor_may_certify`),
    /// the halving (`start_scale`, `halve`), then `refine_scale` and `widen_beta`.
    template <Interval I>
    class scale_search {
    public:
        scale_search(const paper_orientation& policy, const orientation_box<I>& candidate, std::array<double, 3> centre,
                     const fov_position<I>& prepared, const fov_frustum<I>& frustum, double orientation_eps,
                     bool roll_free, std::size_t& certifications)
            : policy_(policy), cand_(candidate), centre_(centre), prepared_(prepared), frustum_(frustum),
              eps_(orientation_eps), roll_free_(roll_free), certifications_(certifications) {}

        /// The certified box found (and `from` updated to its scales), or nothing. `borrowed`:
        /// only the hint's box; `refine`: refine the scale and widen β once one certifies.
        std::optional<orientation_box<I>> run(hint& from, bool borrowed, bool refine) {
            const bool hinted = from.scale > 0.0 && from.scale <= 1.0;  // refined scales reach past 1/2
            const bool first = hinted && from.beta_scale >= from.scale && from.beta_scale <= 1.0;
            if (first)
                if (auto b = hinted_box(from)) return b;
            if (borrowed) return std::nullopt;  // the box's own search has failed already
            // ... else the search, from the hint's scale when there is one.
            const bool tried = first && (roll_free_ || from.beta_scale == from.scale);  // scaled(from.scale) failed
            if ((roll_free_ || !hinted) && !floor_may_certify(from, tried)) return std::nullopt;
            const double start = start_scale(from, hinted, tried);
            halve(start, 1e-6, from, hinted);
            // Below a failed hint nothing certified: the scales above it, which the halving
            // from 1/2 would have tried, may still (the box need not be like its neighbour's).
            if (!best_ && start < 0.5) halve(0.5, start, from, hinted);
            if (!best_) return std::nullopt;
            if (refine) refine_scale();
            const double beta = refine ? widen_beta() : s_ok_;
            from.scale = s_ok_, from.beta_scale = beta;
            return best_;
        }

    private:
        orientation_box<I> scaled(double s) const {
            orientation_box<I> b;
            for (std::size_t j = 0; j < 3; ++j)
                b[j] = roll_free_ && j == 2 ? cand_[2]
                                            : I(centre_[j] + s * (lower(cand_[j]) - centre_[j]),
                                                centre_[j] + s * (upper(cand_[j]) - centre_[j]));
            return b;
        }
        bool narrow(const orientation_box<I>& b) const {  // every shrunk angle below ε_o
            for (std::size_t j = 0; j < 3; ++j)
                if (!(roll_free_ && j == 2) && width(b[j]) >= eps_) return false;
            return true;
        }
        orientation_box<I> with_beta(orientation_box<I> b, double s) const {
            if (!roll_free_) b[2] = scaled(s)[2];
            return b;
        }
        bool certified(const orientation_box<I>& b) { return policy_.certify_tiled(prepared_, b, frustum_, certifications_); }
        bool budget_left() const { return certifications_ < policy_.options_.max_certifications; }

        /// The neighbour's box, as it was found (scale refined, β widened), around this box's own
        /// aim: most boxes of a cell certify it at once, and searching on would mostly spend
        /// failed certifications to find what it holds.
        std::optional<orientation_box<I>> hinted_box(hint& from) {
            const auto b = with_beta(scaled(from.scale), from.beta_scale);
            const std::size_t before = certifications_;
            if (!certified(b)) return std::nullopt;
            // One step wider: a smaller position box, or one nearer the facet's axis, may hold a
            // wider aim than the neighbour's (the hint then moves up with it). Only when the
            // hint's box took one evaluation: one that needed tiling is near the edge of what
            // certifies, and a wider box then rarely certifies.
            hint up = from;
            up.scale = std::min(1.0, 1.5 * from.scale), up.beta_scale = std::min(1.0, 1.5 * from.beta_scale);
            const auto wider = with_beta(scaled(up.scale), up.beta_scale);
            if (up.scale > from.scale && certifications_ == before + 1 && budget_left() && certified(wider)) {
                from = up;
                return wider;
            }
            return b;
        }

        /// The smallest scale the halving would try (the first whose box is narrower than ε_o).
        /// With β whole (roll-free), when even that box fails so does every wider one (they
        /// contain it), and the halving would spend many failed certifications to learn it; most
        /// position boxes no orientation fits are such (wider than ε_p, bisected next). With β
        /// scaled too, a wider box may reach the roll-free cone test, which certifies what the
        /// centred form of a narrow one cannot: there only a refutation of the narrowest box
        /// (held by every box of the halving) ends the search.
        bool floor_may_certify(const hint& from, bool tried) {
            double narrowest = 0.5;
            while (narrowest > 1e-6 && !narrow(scaled(narrowest))) narrowest *= 0.5;
            if (roll_free_) {
                floor_ = narrowest;
                return !(tried && from.scale == floor_) && certified(scaled(floor_));
            }
            return !fov_refuted(prepared_, scaled(narrowest), frustum_);
        }

        /// Where the halving starts: from 1/2 (the paper's box itself does not certify, see the
        /// header comment), or below the hint's scale; from a certified hint, it doubles while
        /// certified (up to 1/2) instead, and the halving has nothing left to do.
        double start_scale(const hint& from, bool hinted, bool tried) {
            if (!hinted) return 0.5;
            const auto b = scaled(from.scale);
            if (!tried && certified(b)) {
                best_ = b, s_ok_ = from.scale, s_fail_ = 2 * from.scale;
                while (2 * s_ok_ <= 0.5 && budget_left()) {
                    const auto wider = scaled(2 * s_ok_);
                    if (!certified(wider)) break;
                    best_ = wider, s_ok_ *= 2, s_fail_ = 2 * s_ok_;
                }
                return 0.5;
            }
            if (!narrow(b)) return from.scale / 2;
            return 0.0;  // the hint's box is narrower than ε_o already: nothing below it
        }

        /// Halves toward the centre from `from_scale` until a box certifies, or the box is
        /// narrower than ε_o, or the scale reaches `down_to`.
        void halve(double from_scale, double down_to, const hint& from, bool hinted) {
            for (double s = from_scale; !best_ && budget_left() && s > down_to; s *= 0.5) {
                if (s <= floor_) {  // the floor's box is certified (floor_may_certify)
                    best_ = scaled(floor_), s_ok_ = floor_, s_fail_ = 2 * s;
                    return;
                }
                const auto b = scaled(s);
                if (hinted && s == from.scale) {  // the hint's own box: it failed already
                    if (narrow(b)) return;
                    continue;
                }
                if (certified(b)) {
                    best_ = b, s_ok_ = s, s_fail_ = 2 * s;
                    return;
                }
                if (narrow(b)) return;
            }
        }

        /// Bisection on the scale between the largest certified one and the next that failed.
        void refine_scale() {
            for (int i = 0; i < policy_.options_.refine_steps && budget_left(); ++i) {
                const double s = 0.5 * (s_ok_ + s_fail_);
                const auto b = scaled(s);
                if (certified(b)) best_ = b, s_ok_ = s;
                else s_fail_ = s;
            }
        }

        /// Widens β alone toward the paper's [β] (the whole of it usually certifies); the scale
        /// of β reached.
        double widen_beta() {
            double lo = s_ok_;
            if (best_->x[2] == cand_[2]) return lo;
            double hi = 1.0;
            for (int i = 0; i <= policy_.options_.widen_steps && budget_left(); ++i) {
                const double s = i == 0 ? hi : 0.5 * (lo + hi);
                const auto b = with_beta(*best_, s);
                if (certified(b)) {
                    best_ = b, lo = s;
                    if (i == 0) break;
                } else {
                    hi = s;
                }
            }
            return lo;
        }

        const paper_orientation& policy_;
        const orientation_box<I>& cand_;
        std::array<double, 3> centre_;
        const fov_position<I>& prepared_;
        const fov_frustum<I>& frustum_;
        double eps_;
        bool roll_free_;
        std::size_t& certifications_;
        std::optional<orientation_box<I>> best_{};
        double s_ok_ = 1.0, s_fail_ = 1.0, floor_ = 0.0;
    };

public:
    /// Proves `box` by `certify_fov`, splitting it while undecided (at most `tiling_budget`
    /// evaluations; β spanning π or more is never split: the roll-free cone test does not
    /// improve on halves of it). True when every tile is certified.
    template <Interval I>
    bool certify_tiled(const fov_position<I>& position, const orientation_box<I>& box,
                       const fov_frustum<I>& frustum, std::size_t& certifications) const {
        return certify_fov_tiled(position, box, frustum, options_.tiling_budget, certifications);
    }

private:
    paper_orientation_options options_{};
};

}  // namespace certipose
