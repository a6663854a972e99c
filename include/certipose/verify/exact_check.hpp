// certipose/verify/exact_check.hpp — exact decisions for the sampling check (verify/point_check.hpp).
//
// The sampling check must neither forgive a violation of a few ulps nor invent one where a sight
// line grazes an edge, so "which side of the boundary" is decided exactly. Every input (pose,
// angles, mesh vertices, K, d_min, d_max, θ_v) is a double, i.e. an exact rational, and every
// constraint without a sine in it is decided by signs of polynomials in them. Each sign is
// first evaluated in double with a bound on its rounding error (`bounded`, `orient_filter`);
// only when the value is within that bound of zero is it recomputed in GMP rationals
// (`mpq_class`), which settles it. The transcendental quantities — sin θ_v, and cos/sin of
// φ, γ, β in the rotation — are enclosed by
// MPFR with directed rounding at `enclosure_bits` and carried as rational intervals (`qi`); a
// sign their enclosure cannot settle belongs to a pose on the boundary to within 2^-250 or so,
// and is decided as the constraint is written (a non-strict inequality holds on its boundary,
// a strict one does not) and counted in `exact_stats::undecidable`.
//
// Needs GMP with its C++ interface and MPFR (Debian libgmp-dev, libmpfr-dev; link gmpxx, gmp,
// mpfr — CGAL::CGAL already links them).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <limits>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <gmpxx.h>
#include <mpfr.h>

namespace certipose::verify {

/// How many decisions of the sampling check needed more than doubles. Pass one to the checks
/// of point_check.hpp; a pose needed the exact decision when `exact` grew while it was checked.
struct exact_stats {
    std::size_t exact = 0;        ///< signs the double filter left open, settled in exact arithmetic
    std::size_t undecidable = 0;  ///< of those, signs even the high-precision enclosure left open
};

namespace exact {

// ---- doubles with a rounding-error bound -------------------------------------------------------

/// A double `v` computed from exact inputs, and `e` with |exact value − v| ≤ e.
///
/// Why the bounds below are upper bounds, in any rounding mode: a rounded +, −, ×, √ result z
/// is off by at most one ulp of z, and ulp(z) ≤ 2^-52·|z| (`rel`) when z is normal; an
/// underflowed product is off by at most 2^-1074 (`tiny`), sums never underflow inexactly.
/// The propagation rules are the triangle inequality ((x+dx)(y+dy) − xy = x·dy + y·dx + dx·dy,
/// |√s − √t| ≤ min(√|s−t|, |s−t|/√t)). The bound itself is computed in double from at most
/// eight nonnegative terms, so it may come out low by a factor (1 − 2^-52)^8 and a few
/// underflows; `inflate` multiplies by 1 + 2^-40 and adds 16·2^-1074, which covers that many
/// times over. An overflow makes v or e infinite or NaN, and every comparison below then
/// answers "open", which sends the sign to exact arithmetic.
struct bounded {
    double v = 0.0, e = 0.0;
    bounded() = default;
    bounded(double x) : v(x) {}  // NOLINT(google-explicit-constructor): an input double is exact
    bounded(double x, double err) : v(x), e(err) {}
};

inline constexpr double rel = 0x1p-52;
inline constexpr double tiny = 0x1p-1074;
inline double inflate(double e) { return e * (1.0 + 0x1p-40) + 0x1p-1070; }

inline bounded operator+(const bounded& a, const bounded& b) {
    const double z = a.v + b.v;
    return {z, inflate(a.e + b.e + rel * std::abs(z))};
}
inline bounded operator-(const bounded& a, const bounded& b) {
    const double z = a.v - b.v;
    return {z, inflate(a.e + b.e + rel * std::abs(z))};
}
inline bounded operator-(const bounded& a) { return {-a.v, a.e}; }
inline bounded operator*(const bounded& a, const bounded& b) {
    const double z = a.v * b.v;
    return {z, inflate(std::abs(a.v) * b.e + std::abs(b.v) * a.e + a.e * b.e + rel * std::abs(z) + tiny)};
}
/// √ of a value whose exact counterpart is ≥ 0 (a squared norm).
inline bounded sqrt(const bounded& a) {
    const double y = std::sqrt(std::max(a.v, 0.0));
    const double carried = y > 0.0 ? std::min(std::sqrt(a.e), a.e / y) : std::sqrt(a.e);
    return {y, inflate(carried + rel * y)};
}
/// glibc documents sin and cos of a double to within 1 ulp on x86-64; 4 ulps are allowed.
inline bounded sin_of(double a) {
    const double s = std::sin(a);
    return {s, inflate(4 * rel * std::abs(s) + tiny)};
}
inline bounded cos_of(double a) {
    const double c = std::cos(a);
    return {c, inflate(4 * rel * std::abs(c) + tiny)};
}

/// The sign of the exact value when the bound settles it.
inline std::optional<int> filter_sign(const bounded& b) {
    if (b.v > b.e) return 1;
    if (b.v < -b.e) return -1;
    if (b.e == 0.0 && b.v == 0.0) return 0;  // an input, not computed: exactly zero
    return std::nullopt;
}

// ---- rational intervals from MPFR enclosures ---------------------------------------------------

/// Wide enough that an enclosure fails to settle a sign only within ~2^-250 of a boundary.
inline constexpr mpfr_prec_t enclosure_bits = 256;

/// A closed rational interval [lo, hi]: exact arithmetic on enclosures of transcendental values.
/// Point intervals (the double inputs) stay points through + − ×, so a sign that is exactly zero
/// by the polynomial is still seen as zero.
struct qi {
    mpq_class lo, hi;
    qi() = default;
    qi(double x) : lo(x), hi(x) {}  // NOLINT(google-explicit-constructor): exact
    qi(mpq_class l, mpq_class h) : lo(std::move(l)), hi(std::move(h)) {}
    bool point() const { return lo == hi; }
};
inline qi operator+(const qi& a, const qi& b) { return {a.lo + b.lo, a.hi + b.hi}; }
inline qi operator-(const qi& a, const qi& b) { return {a.lo - b.hi, a.hi - b.lo}; }
inline qi operator-(const qi& a) { return {-a.hi, -a.lo}; }
inline qi operator*(const qi& a, const qi& b) {
    if (a.point() && b.point()) {
        mpq_class p = a.lo * b.lo;
        return {p, p};
    }
    const std::array<mpq_class, 4> p{a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
    return {*std::min_element(p.begin(), p.end()), *std::max_element(p.begin(), p.end())};
}
/// The sign of every number in the interval, or nothing when it holds both signs.
inline std::optional<int> interval_sign(const qi& a) {
    if (a.lo > 0) return 1;
    if (a.hi < 0) return -1;
    if (a.lo == 0 && a.hi == 0) return 0;
    return std::nullopt;
}

/// [lower, upper] enclosing sin(a) or cos(a): MPFR rounds down and up at `enclosure_bits`
/// (correctly, unlike libm), and the results are exact binary fractions.
inline qi trig_enclosure(double a, bool sine) {
    mpfr_t x, r;
    mpfr_init2(x, 53);  // holds a double exactly
    mpfr_init2(r, enclosure_bits);
    mpfr_set_d(x, a, MPFR_RNDN);
    qi out;
    (sine ? mpfr_sin : mpfr_cos)(r, x, MPFR_RNDD);
    mpfr_get_q(out.lo.get_mpq_t(), r);
    (sine ? mpfr_sin : mpfr_cos)(r, x, MPFR_RNDU);
    mpfr_get_q(out.hi.get_mpq_t(), r);
    mpfr_clear(x);
    mpfr_clear(r);
    return out;
}

// ---- generic vectors ---------------------------------------------------------------------------

/// Selects the number type a generic expression is evaluated in (bounded or mpq_class).
template <class T>
struct as_t {
    using type = T;
};
template <class T>
inline constexpr as_t<T> as{};

template <class T>
struct vec3 {
    T x, y, z;
};
template <class T>
vec3<T> lift(const Eigen::Vector3d& p) {
    return {T(p.x()), T(p.y()), T(p.z())};
}
template <class T>
vec3<T> operator-(const vec3<T>& a, const vec3<T>& b) {
    return {T(a.x - b.x), T(a.y - b.y), T(a.z - b.z)};
}
template <class T>
vec3<T> operator+(const vec3<T>& a, const vec3<T>& b) {
    return {T(a.x + b.x), T(a.y + b.y), T(a.z + b.z)};
}
template <class T>
vec3<T> scaled(const T& k, const vec3<T>& a) {
    return {T(k * a.x), T(k * a.y), T(k * a.z)};
}
template <class T>
T dot(const vec3<T>& a, const vec3<T>& b) {
    return T(a.x * b.x + a.y * b.y + a.z * b.z);
}
template <class T>
vec3<T> cross(const vec3<T>& a, const vec3<T>& b) {
    return {T(a.y * b.z - a.z * b.y), T(a.z * b.x - a.x * b.z), T(a.x * b.y - a.y * b.x)};
}
/// det[b − a, c − a, d − a]: positive when d is on the side of plane (a, b, c) that
/// (b − a) × (c − a) points to.
template <class T>
T orient(const vec3<T>& a, const vec3<T>& b, const vec3<T>& c, const vec3<T>& d) {
    return dot(cross(b - a, c - a), d - a);
}

using triangle = std::array<Eigen::Vector3d, 3>;

// ---- lazily settled conditions -----------------------------------------------------------------

/// "value ⋈ 0" for a polynomial atom.
enum class relation { positive, nonnegative, negative, nonpositive, nonzero };

inline bool holds(relation r, int sign) {
    switch (r) {
        case relation::positive: return sign > 0;
        case relation::nonnegative: return sign >= 0;
        case relation::negative: return sign < 0;
        case relation::nonpositive: return sign <= 0;
        case relation::nonzero: return sign != 0;
    }
    return false;
}

/// A condition node: called with `exact_allowed` false it answers from doubles alone (nothing
/// when they cannot tell), with true it always answers, exactly. Nodes are combined by all_of /
/// any_of, which settle members exactly only when the others leave the answer open — so a pose
/// far inside one alternative never pays for a close call in another.
template <class Expr>
auto atom(Expr expr, relation r, exact_stats* stats) {
    return [expr, r, stats](bool exact_allowed) -> std::optional<bool> {
        if (const auto s = filter_sign(expr(as<bounded>))) return holds(r, *s);
        if (!exact_allowed) return std::nullopt;
        if (stats) ++stats->exact;
        return holds(r, sgn(expr(as<mpq_class>)));
    };
}

/// all_of (`decisive` false) and any_of (`decisive` true): one member answering `decisive` gives
/// the answer; only when every member answers the other way is the answer the other one.
template <bool decisive, class... Node>
std::optional<bool> combine(bool exact_allowed, const Node&... node) {
    bool decided = false, open = false;
    const auto first = [&](const auto& n) {
        if (decided) return;
        const auto r = n(false);
        if (!r) open = true;
        else if (*r == decisive) decided = true;
    };
    (first(node), ...);
    if (decided) return decisive;
    if (!open) return !decisive;
    if (!exact_allowed) return std::nullopt;
    bool found = false;
    const auto settle = [&](const auto& n) {
        if (!found && !n(false)) found = *n(true) == decisive;
    };
    (settle(node), ...);
    return found ? decisive : !decisive;
}

template <class... Node>
std::optional<bool> all_of(bool exact_allowed, const Node&... node) {
    return combine<false>(exact_allowed, node...);
}

template <class... Node>
std::optional<bool> any_of(bool exact_allowed, const Node&... node) {
    return combine<true>(exact_allowed, node...);
}

// ---- constraints 1–4 ---------------------------------------------------------------------------
// Over the exact normal direction N = (v2 − v1) × (v3 − v1) and centroid (v1 + v2 + v3)/3, as the
// solver states them (facet::normal and facet::centroid are rounded).

template <class T>
vec3<T> normal_of(const triangle& v) {
    const vec3<T> a = lift<T>(v[0]);
    return cross(lift<T>(v[1]) - a, lift<T>(v[2]) - a);
}
/// N·(p − v1): the signed distance to the facet's plane, times ‖N‖.
template <class T>
T plane_side(as_t<T>, const triangle& v, const Eigen::Vector3d& p) {
    return dot(normal_of<T>(v), lift<T>(p) - lift<T>(v[0]));
}
/// N·(e_i × (p − v_i)), e_i = v_{i+1} − v_i: ≥ 0 for the three edges iff p projects into the facet.
template <class T>
T inner_side(as_t<T>, const triangle& v, const Eigen::Vector3d& p, int i) {
    const vec3<T> a = lift<T>(v[i]);
    return dot(normal_of<T>(v), cross(lift<T>(v[(i + 1) % 3]) - a, lift<T>(p) - a));
}
/// ‖p − v_i‖² − d².
template <class T>
T vertex_gap(as_t<T>, const triangle& v, const Eigen::Vector3d& p, int i, double d) {
    const vec3<T> w = lift<T>(p) - lift<T>(v[i]);
    return T(dot(w, w) - T(d) * T(d));
}
/// e_i·(p − v_i) − k·‖e_i‖², k ∈ {0, 1}: where p's foot falls on edge i's line (before v_i for
/// k = 0 and ≤ 0, past v_{i+1} for k = 1 and ≥ 0).
template <class T>
T edge_foot(as_t<T>, const triangle& v, const Eigen::Vector3d& p, int i, int k) {
    const vec3<T> a = lift<T>(v[i]), e = lift<T>(v[(i + 1) % 3]) - a;
    const T t = dot(e, lift<T>(p) - a);
    return k == 0 ? t : T(t - dot(e, e));
}
/// ‖(p − v_i) × e_i‖² − d²‖e_i‖²: the distance to edge i's line against d, times ‖e_i‖².
template <class T>
T edge_line_gap(as_t<T>, const triangle& v, const Eigen::Vector3d& p, int i, double d) {
    const vec3<T> a = lift<T>(v[i]), e = lift<T>(v[(i + 1) % 3]) - a;
    const vec3<T> c = cross(lift<T>(p) - a, e);
    return T(dot(c, c) - T(d) * T(d) * dot(e, e));
}
/// (N·(p − v1))² − d²‖N‖²: the distance to the plane against d, times ‖N‖².
template <class T>
T plane_gap(as_t<T>, const triangle& v, const Eigen::Vector3d& p, double d) {
    const vec3<T> n = normal_of<T>(v);
    const T h = dot(n, lift<T>(p) - lift<T>(v[0]));
    return T(h * h - T(d) * T(d) * dot(n, n));
}

/// The view-angle terms scaled by 3 to stay polynomial in doubles: with s = 3p − (v1 + v2 + v3)
/// = 3(p − c), (p − c)·N ≥ sin θ_v ‖N‖ ‖p − c‖ ⇔ s·N ≥ sin θ_v √(‖N‖² ‖s‖²).
template <class T>
struct view_terms {
    T along, nn, ss;  // s·N, ‖N‖², ‖s‖²
};
template <class T>
view_terms<T> view_of(const triangle& v, const Eigen::Vector3d& p) {
    const vec3<T> n = normal_of<T>(v);
    const vec3<T> s = scaled(T(3), lift<T>(p)) - (lift<T>(v[0]) + lift<T>(v[1]) + lift<T>(v[2]));
    return {dot(s, n), dot(n, n), dot(s, s)};
}

/// The sign of a − t·√r, r ≥ 0, exactly.
inline int sign_minus_root(const mpq_class& a, const mpq_class& t, const mpq_class& r) {
    const int sa = sgn(a), st = sgn(t);
    if (sgn(r) == 0 || st == 0) return sa;
    if (sa <= 0 && st > 0) return -1;
    if (sa >= 0 && st < 0) return 1;
    const int squares = sgn(mpq_class(a * a - t * t * r));  // both sides of one sign
    return sa > 0 ? squares : -squares;
}

/// Which of constraints 1–4 a position violates (true: violated).
struct position_decision {
    bool on_facet = false, focus = false, backface = false, view_angle = false;
};

/// Constraints 1–4 at p for the facet with vertices v, decided exactly:
///   on the facet     p ∈ facet (violates C_f: distance > 0 is required),
///   focus            distance(p, facet) ≥ d_min and ‖p − v_i‖ ≤ d_max for every i,
///   backface         (p − v1)·N > 0,
///   view angle       (p − c)·N ≥ sin θ_v ‖N‖ ‖p − c‖.
/// The distance to the triangle is not polynomial, but "≥ d" is a combination of polynomial
/// signs: the vertices and each edge segment are at least d away, and so is the plane unless p
/// projects outside the facet (where the nearest point is on an edge).
inline position_decision decide_position(const Eigen::Vector3d& p, const triangle& v, double d_min, double d_max,
                                         double min_view_angle, exact_stats* stats) {
    using R = relation;
    position_decision out;
    const auto side = atom([&](auto t) { return plane_side(t, v, p); }, R::nonzero, stats);
    const auto outside = [&](int i) { return atom([&, i](auto t) { return inner_side(t, v, p, i); }, R::negative, stats); };
    out.on_facet = !*any_of(true, side, outside(0), outside(1), outside(2));

    const auto near_vertex = [&](int i) {
        return atom([&, i](auto t) { return vertex_gap(t, v, p, i, d_min); }, R::nonnegative, stats);
    };
    const auto near_edge = [&](int i) {
        return [&, i, before = atom([&, i](auto t) { return edge_foot(t, v, p, i, 0); }, R::nonpositive, stats),
                past = atom([&, i](auto t) { return edge_foot(t, v, p, i, 1); }, R::nonnegative, stats),
                line = atom([&, i](auto t) { return edge_line_gap(t, v, p, i, d_min); }, R::nonnegative, stats)](
                   bool ex) { return any_of(ex, before, past, line); };
    };
    const auto near_plane = [&, o0 = outside(0), o1 = outside(1), o2 = outside(2),
                             gap = atom([&](auto t) { return plane_gap(t, v, p, d_min); }, R::nonnegative, stats)](
                                bool ex) { return any_of(ex, o0, o1, o2, gap); };
    const auto near_ok = [&](bool ex) -> std::optional<bool> {
        if (!(d_min > 0.0)) return true;  // every distance is ≥ 0
        return all_of(ex, near_vertex(0), near_vertex(1), near_vertex(2), near_edge(0), near_edge(1), near_edge(2),
                      near_plane);
    };
    const auto far_vertex = [&](int i) {
        return atom([&, i](auto t) { return vertex_gap(t, v, p, i, d_max); }, R::nonpositive, stats);
    };
    const auto far_ok = [&](bool ex) -> std::optional<bool> {
        if (d_max == std::numeric_limits<double>::infinity()) return true;
        return all_of(ex, far_vertex(0), far_vertex(1), far_vertex(2));
    };
    out.focus = !*all_of(true, near_ok, far_ok);

    const auto front = atom([&](auto t) { return plane_side(t, v, p); }, R::positive, stats);
    out.backface = !*front(true);

    const auto view = [&](bool ex) -> std::optional<bool> {
        const view_terms<bounded> f = view_of<bounded>(v, p);
        if (const auto s = filter_sign(f.along - sin_of(min_view_angle) * sqrt(f.nn) * sqrt(f.ss))) return *s >= 0;
        if (!ex) return std::nullopt;
        if (stats) ++stats->exact;
        const view_terms<mpq_class> x = view_of<mpq_class>(v, p);
        const mpq_class r = x.nn * x.ss;
        const qi s = trig_enclosure(min_view_angle, true);
        if (sign_minus_root(x.along, s.hi, r) >= 0) return true;  // ≥ 0 for the largest sine, so for the true one
        if (sign_minus_root(x.along, s.lo, r) < 0) return false;
        if (stats) ++stats->undecidable;
        return true;  // on the boundary of a "≥": it holds
    };
    out.view_angle = !*view(true);
    return out;
}

// ---- constraint 5 ------------------------------------------------------------------------------

template <class T>
struct rotation_trig {
    T cp, sp, cg, sg, cb, sb;  // cos and sin of φ, γ, β
};

/// A vertex's camera-frame depth q_c.z and the image-side signs: with (U, V, W) = K q_c, the
/// vertex is in the image iff W ≠ 0 and, σ = sign W, σU ≥ 0, σ(w·W − U) ≥ 0, σV ≥ 0,
/// σ(h·W − V) ≥ 0 — 0 ≤ u ≤ w and 0 ≤ v ≤ h without dividing.
template <class T>
struct image_terms {
    T depth, w;
    std::array<T, 4> sides;
};

/// q_c = Rᵀ (q − x) with R = Rz(φ)·Rx(γ)·Rz(β), applied as Rz(β)ᵀ·Rx(γ)ᵀ·Rz(φ)ᵀ (so each
/// rotation is applied once, and an interval enclosure widens least).
template <class T>
image_terms<T> image_of(const rotation_trig<T>& r, const Eigen::Vector3d& x, const Eigen::Vector3d& q,
                        const Eigen::Matrix3d& K, double width, double height) {
    const vec3<T> d = lift<T>(q) - lift<T>(x);
    const T x1 = r.cp * d.x + r.sp * d.y, y1 = r.cp * d.y - r.sp * d.x;
    const T y2 = r.cg * y1 + r.sg * d.z, z2 = r.cg * d.z - r.sg * y1;
    const T x3 = r.cb * x1 + r.sb * y2, y3 = r.cb * y2 - r.sb * x1;
    const auto row = [&](int i) { return T(T(K(i, 0)) * x3 + T(K(i, 1)) * y3 + T(K(i, 2)) * z2); };
    const T U = row(0), V = row(1), W = row(2);
    return {z2, W, {U, T(T(width) * W - U), V, T(T(height) * W - V)}};
}

/// Constraint 5 (every vertex in front of the camera, q_c.z > 0, and 0 ≤ u ≤ w, 0 ≤ v ≤ h),
/// decided exactly up to the MPFR enclosure of the rotation.
inline bool decide_fov(const Eigen::Vector3d& x, double phi, double gamma, double beta, const triangle& v,
                       const Eigen::Matrix3d& K, double width, double height, exact_stats* stats) {
    const rotation_trig<bounded> fast{cos_of(phi), sin_of(phi), cos_of(gamma), sin_of(gamma), cos_of(beta), sin_of(beta)};
    std::optional<rotation_trig<qi>> enclosed;
    for (const auto& q : v) {
        const image_terms<bounded> f = image_of(fast, x, q, K, width, height);
        std::optional<image_terms<qi>> e;
        // The sign of one term: doubles, else the enclosure; nothing when even that cannot tell.
        const auto sign = [&](const bounded& b, auto member) -> std::optional<int> {
            if (const auto s = filter_sign(b)) return s;
            if (stats) ++stats->exact;
            if (!e) {
                if (!enclosed)
                    enclosed = rotation_trig<qi>{trig_enclosure(phi, false),   trig_enclosure(phi, true),
                                                 trig_enclosure(gamma, false), trig_enclosure(gamma, true),
                                                 trig_enclosure(beta, false),  trig_enclosure(beta, true)};
                e = image_of(*enclosed, x, q, K, width, height);
            }
            const auto s = interval_sign(member(*e));
            if (!s && stats) ++stats->undecidable;
            return s;
        };
        const auto depth = sign(f.depth, [](const image_terms<qi>& t) { return t.depth; });
        if (!depth || *depth <= 0) return false;  // "> 0": its boundary is outside
        const auto w = sign(f.w, [](const image_terms<qi>& t) { return t.w; });
        if (!w || *w == 0) return false;  // no finite image point
        for (std::size_t k = 0; k < 4; ++k) {
            const auto s = sign(f.sides[k], [k](const image_terms<qi>& t) { return t.sides[k]; });
            if (s && *s * *w < 0) return false;  // undecided: on the image edge, which is inside
        }
    }
    return true;
}

// ---- constraint 6 ------------------------------------------------------------------------------

/// An end point of a sight line: the double `q` a caller gave, and the exact point `at` it stands
/// for, within `slack` (per coordinate, rounded up). Points built from a facet's vertices in
/// double (edge midpoints, barycentric samples) are off the facet by a rounding error, and a
/// sight line to such a point could pierce a neighbour of the facet next to its end; the check
/// is about the facet's own points, so it snaps them (`snapped`). `carriers` are the facet
/// vertices with positive weight in `at`: a triangle having all of them as vertices contains
/// `at` in its plane, which the segment then meets only at `at` (decided without arithmetic).
struct sight_end {
    Eigen::Vector3d q;
    std::array<double, 3> slack{};
    Eigen::Vector3d lo, hi;  ///< a box around q holding `at`
    std::array<mpq_class, 3> at;
    std::array<Eigen::Vector3d, 3> carriers;
    int carrier_count = 0;
};

/// q taken as the exact point it is.
inline sight_end literal_end(const Eigen::Vector3d& q) {
    sight_end s;
    s.q = s.lo = s.hi = q;
    for (int k = 0; k < 3; ++k) s.at[k] = q[k];
    return s;
}

/// The point of the facet v that q stands for: a vertex or the midpoint of an edge when q is that
/// point as computed in double ((v_i + v_j) / 2, as facet_targets builds it), otherwise the
/// facet's nearest point to q, in exact arithmetic.
inline sight_end snapped(const triangle& v, const Eigen::Vector3d& q) {
    sight_end s;
    s.q = q;
    vec3<mpq_class> at;
    const auto carry = [&](std::initializer_list<int> idx) {
        for (int i : idx) s.carriers[s.carrier_count++] = v[i];
    };
    const std::array<vec3<mpq_class>, 3> V{lift<mpq_class>(v[0]), lift<mpq_class>(v[1]), lift<mpq_class>(v[2])};
    bool found = false;
    for (int i = 0; i < 3 && !found; ++i)
        if (q == v[i]) at = V[i], carry({i}), found = true;
    for (int i = 0; i < 3 && !found; ++i) {
        const int j = (i + 1) % 3;
        if (q == Eigen::Vector3d((v[i] + v[j]) / 2))
            at = scaled(mpq_class(1, 2), V[i] + V[j]), carry({i, j}), found = true;
    }
    const vec3<mpq_class> n = normal_of<mpq_class>(v);
    const mpq_class nn = dot(n, n);
    if (!found && sgn(nn) == 0) return literal_end(q);  // a degenerate facet has no plane to snap to
    if (!found) {
        const vec3<mpq_class> Q = lift<mpq_class>(q);
        std::array<mpq_class, 3> w;  // barycentric weights of q's projection, times ‖N‖²
        for (int i = 0; i < 3; ++i) {
            const vec3<mpq_class>& a = V[(i + 1) % 3];
            w[i] = dot(n, cross(V[(i + 2) % 3] - a, Q - a));
        }
        if (sgn(w[0]) >= 0 && sgn(w[1]) >= 0 && sgn(w[2]) >= 0) {
            at = scaled(mpq_class(1 / nn), scaled(w[0], V[0]) + scaled(w[1], V[1]) + scaled(w[2], V[2]));
            for (int i = 0; i < 3; ++i)
                if (sgn(w[i]) > 0) carry({i});
        } else {  // outside: the nearest point is on an edge
            std::optional<mpq_class> best;
            for (int i = 0; i < 3; ++i) {
                const int j = (i + 1) % 3;
                const vec3<mpq_class> e = V[j] - V[i];
                mpq_class t = dot(e, Q - V[i]) / dot(e, e);
                if (t < 0) t = 0;
                if (t > 1) t = 1;
                const vec3<mpq_class> y = V[i] + scaled(t, e), r = Q - y;
                const mpq_class d2 = dot(r, r);
                if (best && !(d2 < *best)) continue;
                best = d2, at = y, s.carrier_count = 0;
                if (t == 0) carry({i});
                else if (t == 1) carry({j});
                else carry({i, j});
            }
        }
    }
    s.at = {at.x, at.y, at.z};
    for (int k = 0; k < 3; ++k) {
        const mpq_class off = abs(mpq_class(q[k] - s.at[k]));
        s.slack[k] = sgn(off) == 0 ? 0.0 : std::nextafter(off.get_d(), std::numeric_limits<double>::infinity());
        constexpr double inf = std::numeric_limits<double>::infinity();
        s.lo[k] = s.slack[k] > 0.0 ? std::nextafter(q[k] - s.slack[k], -inf) : q[k];
        s.hi[k] = s.slack[k] > 0.0 ? std::nextafter(q[k] + s.slack[k], inf) : q[k];
    }
    return s;
}

/// p and q in t's plane: does the open segment (p, q) meet the closed triangle? Dropping the
/// axis of N's largest component keeps the plane's geometry up to an affine map, and the
/// segment is clipped to t's three half-planes in its parameter, exactly.
inline bool coplanar_meets(const vec3<mpq_class>& p, const vec3<mpq_class>& q, const triangle& t) {
    if (p.x == q.x && p.y == q.y && p.z == q.z) return false;  // an empty open segment
    const std::array<vec3<mpq_class>, 3> T{lift<mpq_class>(t[0]), lift<mpq_class>(t[1]), lift<mpq_class>(t[2])};
    const vec3<mpq_class> n = normal_of<mpq_class>(t);
    const std::array<mpq_class, 3> an{abs(n.x), abs(n.y), abs(n.z)};
    const int k = static_cast<int>(std::max_element(an.begin(), an.end()) - an.begin());
    if (sgn(an[k]) == 0) return false;  // a degenerate triangle has no interior to meet
    const int flip = sgn(k == 0 ? n.x : k == 1 ? n.y : n.z);
    const auto coord = [](const vec3<mpq_class>& a, int c) -> const mpq_class& { return c == 0 ? a.x : c == 1 ? a.y : a.z; };
    const int i = (k + 1) % 3, j = (k + 2) % 3;  // (i, j, k) right-handed: N_k > 0 means counter-clockwise
    const auto inside = [&](const vec3<mpq_class>& a, const vec3<mpq_class>& b, const vec3<mpq_class>& x) {
        return mpq_class(flip * ((coord(b, i) - coord(a, i)) * (coord(x, j) - coord(a, j)) -
                                 (coord(b, j) - coord(a, j)) * (coord(x, i) - coord(a, i))));
    };
    mpq_class lo = 0, hi = 1;
    for (int e = 0; e < 3; ++e) {
        const mpq_class f0 = inside(T[e], T[(e + 1) % 3], p), f1 = inside(T[e], T[(e + 1) % 3], q);
        if (f0 < 0 && f1 < 0) return false;
        if (f0 < 0) lo = std::max(lo, mpq_class(f0 / (f0 - f1)));
        else if (f1 < 0) hi = std::min(hi, mpq_class(f0 / (f0 - f1)));
    }
    return lo <= hi && lo < 1 && hi > 0;
}

/// The sign of det[b − a, c − a, d* − a] when doubles settle it, for double points a, b, c and
/// a point d* within `slack` of d (per coordinate); the ray cast's hot path, so a static bound
/// rather than `bounded`. With X, Y, Z the differences, the double determinant is within
/// (7ε + O(ε²))·perm of the exact one (Shewchuk's orient3d bound; ε = 2^-52 covers any rounding
/// mode), perm = Σ|Z_k|(|X_i Y_j| + |X_j Y_i|); 16ε·perm leaves room for perm's own rounding.
/// The determinant is affine in d, so moving d to d* changes it by (X × Y)·(d* − d), at most
/// Σ(|X_i Y_j| + |X_j Y_i|)·slack_k, taken twice. The bound ignores underflow, so differences
/// above 2^300 or a perm below 2^-600 are left open (no underflow there can reach ε·perm).
inline std::optional<int> orient_filter(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                        const Eigen::Vector3d& d, const std::array<double, 3>& slack) {
    const Eigen::Vector3d x = b - a, y = c - a, z = d - a;
    const double det = x.cross(y).dot(z);
    double perm = 0.0, reach = 0.0;
    for (int k = 0; k < 3; ++k) {
        const int i = (k + 1) % 3, j = (k + 2) % 3;
        const double m = std::abs(x[i] * y[j]) + std::abs(x[j] * y[i]);
        perm += m * std::abs(z[k]);
        reach += m * slack[k];
    }
    const double largest = std::max({x.cwiseAbs().maxCoeff(), y.cwiseAbs().maxCoeff(), z.cwiseAbs().maxCoeff()});
    if (!(largest <= 0x1p300) || !(perm >= 0x1p-600)) return std::nullopt;
    const double bound = 16 * rel * perm + 2 * reach;
    if (det > bound) return 1;
    if (det < -bound) return -1;
    return std::nullopt;
}

/// Constraint 6 for one triangle: does the open segment from p to `end.at` meet the closed
/// triangle t? Touching t (an edge, a vertex) counts; the segment's own end points do not.
/// Crossing t's plane needs p and the end strictly on opposite sides; the crossing point is in t
/// iff the three signed volumes det[t_i − p, t_{i+1} − p, q − p] are not of both strict signs.
inline bool segment_meets(const Eigen::Vector3d& p, const sight_end& end, const triangle& t, exact_stats* stats) {
    // Bounding boxes first (comparisons of doubles are exact): most triangles are far away.
    for (int k = 0; k < 3; ++k) {
        const double lo = std::min(end.lo[k], p[k]), hi = std::max(end.hi[k], p[k]);
        if (hi < std::min({t[0][k], t[1][k], t[2][k]}) || lo > std::max({t[0][k], t[1][k], t[2][k]})) return false;
    }
    constexpr std::array<double, 3> none{};
    // Rationals only on demand: most calls end in doubles.
    const auto P = [&] { return lift<mpq_class>(p); };
    const auto Q = [&] { return vec3<mpq_class>{end.at[0], end.at[1], end.at[2]}; };
    const auto corner = [&](int i) { return lift<mpq_class>(t[i]); };
    const auto exactly = [&](const mpq_class& v) {
        if (stats) ++stats->exact;
        return sgn(v);
    };
    const auto p_side = [&] { return exactly(orient(corner(0), corner(1), corner(2), P())); };
    const auto q_side = [&] { return exactly(orient(corner(0), corner(1), corner(2), Q())); };
    const auto around = [&](int i) { return exactly(orient(P(), corner(i), corner((i + 1) % 3), Q())); };

    bool end_in_t = end.carrier_count > 0;
    for (int c = 0; c < end.carrier_count; ++c)
        end_in_t = end_in_t && (end.carriers[c] == t[0] || end.carriers[c] == t[1] || end.carriers[c] == t[2]);
    if (end_in_t) {  // the end lies in t's plane (and in t)
        const auto fp = orient_filter(t[0], t[1], t[2], p, none);
        if ((fp ? *fp : p_side()) != 0) return false;
        return coplanar_meets(P(), Q(), t);
    }

    const auto fp = orient_filter(t[0], t[1], t[2], p, none), fq = orient_filter(t[0], t[1], t[2], end.q, end.slack);
    if (fp && fq && *fp == *fq) return false;
    // Volumes of both strict signs mean the line misses t whatever the plane sides are (their sum
    // is (q − p)·N, so a line parallel to t has mixed or zero volumes): this settles the common
    // close call of an end lying in t's plane — coplanar triangles of a flat region — in doubles.
    const std::array<std::optional<int>, 3> f{orient_filter(p, t[0], t[1], end.q, end.slack),
                                              orient_filter(p, t[1], t[2], end.q, end.slack),
                                              orient_filter(p, t[2], t[0], end.q, end.slack)};
    bool pos = false, neg = false;
    for (const auto& s : f) pos = pos || (s && *s > 0), neg = neg || (s && *s < 0);
    if (pos && neg) return false;
    const int sp = fp ? *fp : p_side(), sq = fq ? *fq : q_side();
    if (sp == 0 && sq == 0) return coplanar_meets(P(), Q(), t);
    if (sp == 0 || sq == 0 || sp == sq) return false;  // touches the plane at an end, or stays on one side
    for (int i = 0; i < 3 && !(pos && neg); ++i) {
        if (f[i]) continue;
        const int s = around(i);
        pos = pos || s > 0, neg = neg || s < 0;
    }
    return !(pos && neg);
}

}  // namespace exact
}  // namespace certipose::verify
