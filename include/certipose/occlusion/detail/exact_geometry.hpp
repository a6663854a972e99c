// certipose/occlusion/detail/exact_geometry.hpp — filtered exact predicates and the sight hull
// H = conv(box ∪ facet) shared by the occlusion policies (not for users; needs CGAL).
//
// Every sign here is exact. The fast path evaluates a determinant in double together with a
// bound on its rounding error (Shewchuk's static bound for the same evaluation tree, with a
// margin); when |value| is not above the bound, the sign comes from CGAL's EPICK predicates
// (themselves interval-filtered, then exact). The bounds assume round-to-nearest: callers hold
// a `round_to_nearest_scope` (interval code elsewhere in certipose may have left the mode
// upward). An absolute slack of 1e-300 covers underflow.
//
// The hull is built by enumerating supporting planes, not by CGAL's indexed convex_hull_3
// (STYLE.md: with EPICK it returns wrong hulls on nearly coplanar input). For an axis-aligned
// box strictly in front of the facet plane, every face of H lies in one of: the facet plane,
// a plane through a facet edge and the box corner "farthest round" that edge, a box face
// plane, or a plane containing a box edge and a facet vertex. Each candidate is kept when all
// eleven points are on one side — decided exactly — so the planes kept are all supporting and
// include every facet plane: their half-spaces intersect to exactly H.
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Exact_rational.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace certipose::detail::occ {

using pt = std::array<double, 3>;
using epick = CGAL::Exact_predicates_inexact_constructions_kernel;

/// Relative error bound factor: Shewchuk's orient3d bound is (7 + 56ε)ε ≈ 7.8e-16, orient2d
/// (3 + 16ε)ε; a dot product of a double direction with a rounded difference is below 4ε.
inline constexpr double rel_err = 1e-15;
/// Absolute slack against gradual underflow in products of tiny differences.
inline constexpr double abs_err = 1e-300;

inline int sign_of(double v) noexcept { return (v > 0) - (v < 0); }

inline int orient3_exact(const pt& p, const pt& q, const pt& r, const pt& s) {
    return static_cast<int>(CGAL::orientation(epick::Point_3(p[0], p[1], p[2]),
                                              epick::Point_3(q[0], q[1], q[2]),
                                              epick::Point_3(r[0], r[1], r[2]),
                                              epick::Point_3(s[0], s[1], s[2])));
}

/// 2D orientation of (p, q, r) in the coordinate plane (i, j): sign of
/// (q − p)_i (r − p)_j − (q − p)_j (r − p)_i.
inline int orient2(const pt& p, const pt& q, const pt& r, int i, int j) {
    const double ux = q[i] - p[i], uy = q[j] - p[j], vx = r[i] - p[i], vy = r[j] - p[j];
    const double a = ux * vy, b = uy * vx;
    const double det = a - b;
    const double err = rel_err * (std::abs(a) + std::abs(b)) + abs_err;
    if (det > err) return 1;
    if (-det > err) return -1;
    // One zero difference leaves a single product, whose sign is exact.
    if (ux == 0 || vy == 0) return -sign_of(uy) * sign_of(vx);
    if (uy == 0 || vx == 0) return sign_of(ux) * sign_of(vy);
    return static_cast<int>(CGAL::orientation(epick::Point_2(p[i], p[j]), epick::Point_2(q[i], q[j]),
                                              epick::Point_2(r[i], r[j])));
}

/// sign of ((q − p) × (r − p)) · (s − p): +1 when s is on the side the normal of the
/// counter-clockwise triangle (p, q, r) points to (CGAL::orientation's convention).
inline int orient3(const pt& p, const pt& q, const pt& r, const pt& s) {
    const double ux = q[0] - p[0], uy = q[1] - p[1], uz = q[2] - p[2];
    const double vx = r[0] - p[0], vy = r[1] - p[1], vz = r[2] - p[2];
    const double wx = s[0] - p[0], wy = s[1] - p[1], wz = s[2] - p[2];
    const double a = uy * vz, b = uz * vy, c = uz * vx, d = ux * vz, e = ux * vy, f = uy * vx;
    const double det = wx * (a - b) + wy * (c - d) + wz * (e - f);
    const double perm = std::abs(wx) * (std::abs(a) + std::abs(b)) +
                        std::abs(wy) * (std::abs(c) + std::abs(d)) +
                        std::abs(wz) * (std::abs(e) + std::abs(f));
    const double err = rel_err * perm + abs_err;
    if (det > err) return 1;
    if (-det > err) return -1;
    // Cases the filter cannot settle but exact double facts can (a difference of doubles is
    // exact when it is 0, and its sign is always right): a coordinate constant over the four
    // points, or an axis-parallel difference vector, which reduces the determinant to ±(that
    // component) × a 2D orientation. Common on CAD parts and axis-aligned boxes.
    if ((ux == 0 && vx == 0 && wx == 0) || (uy == 0 && vy == 0 && wy == 0) ||
        (uz == 0 && vz == 0 && wz == 0))
        return 0;
    const auto axis_of = [](double x, double y, double z) {
        return (y == 0 && z == 0) ? 0 : (x == 0 && z == 0) ? 1 : (x == 0 && y == 0) ? 2 : -1;
    };
    if (const int k = axis_of(ux, uy, uz); k >= 0)  // det = u_k · [v, w]_(k+1, k+2)
        return sign_of(q[k] - p[k]) * orient2(p, r, s, (k + 1) % 3, (k + 2) % 3);
    if (const int k = axis_of(vx, vy, vz); k >= 0)  // det = −v_k · [u, w]
        return -sign_of(r[k] - p[k]) * orient2(p, q, s, (k + 1) % 3, (k + 2) % 3);
    if (const int k = axis_of(wx, wy, wz); k >= 0)  // det = w_k · [u, v]
        return sign_of(s[k] - p[k]) * orient2(p, q, r, (k + 1) % 3, (k + 2) % 3);
    return orient3_exact(p, q, r, s);
}

/// Coherent 2D orientation of three points of one plane: 0 when collinear, otherwise ±1,
/// consistent over all triples of points of that plane. Same rule as CGAL's 3-argument
/// coplanar_orientation: the first projection (xy, yz, xz) in which they are not collinear —
/// for a given plane that projection is the same for every non-collinear triple.
inline int coplanar_orient(const pt& p, const pt& q, const pt& r) {
    if (const int o = orient2(p, q, r, 0, 1); o != 0) return o;
    if (const int o = orient2(p, q, r, 1, 2); o != 0) return o;
    return orient2(p, q, r, 0, 2);
}

/// Is the angle at v between a − v and d − v strictly acute ((a − v)·(d − v) > 0)?
inline bool acute(const pt& a, const pt& v, const pt& d) {
    double dot = 0, mag = 0;
    for (int k = 0; k < 3; ++k) {
        const double t = (a[k] - v[k]) * (d[k] - v[k]);
        dot += t;
        mag += std::abs(t);
    }
    const double err = rel_err * mag + abs_err;
    if (dot > err) return true;
    if (-dot > err) return false;
    return CGAL::angle(epick::Point_3(a[0], a[1], a[2]), epick::Point_3(v[0], v[1], v[2]),
                       epick::Point_3(d[0], d[1], d[2])) == CGAL::ACUTE;
}

/// For points a, b, d coplanar with the apex v (exactly), is d − v in the closed cone spanned
/// by a − v and b − v? The cone must be pointed (a − v, b − v not opposite).
inline bool in_cone2(const pt& v, const pt& a, const pt& b, const pt& d) {
    const int s = coplanar_orient(v, a, b);
    if (s != 0) return coplanar_orient(v, a, d) * s >= 0 && coplanar_orient(v, d, b) * s >= 0;
    // a − v and b − v point the same way: the cone is one ray.
    return coplanar_orient(v, a, d) == 0 && acute(a, v, d);
}

/// An oriented plane; side(x) > 0 means "outside". Axis planes (s·(x_k − c)) are evaluated
/// exactly in double; general planes carry a double normal for filtering and their defining
/// data for exact fallbacks and rational clipping.
struct hplane {
    enum class kind : std::uint8_t { axis, triple, lifted } k = kind::axis;
    int axis = 0;        // axis: coordinate k; lifted: the coordinate the plane is parallel to
    double s = 1.0;      // axis: outward sign; lifted/triple: sign applied to the predicate
    double c = 0.0;      // axis: the plane is x_axis = c
    pt p{}, q{}, r{};    // triple: orient3(p, q, r, x); lifted: orient2(p, q, x) in (i, j)
    pt o{}, n{}, perm{}; // filter: value ≈ n·(x − o), |error| <= rel_err·Σ perm_k |x_k − o_k|
};

inline int lifted_i(int axis) { return (axis + 1) % 3; }
inline int lifted_j(int axis) { return (axis + 2) % 3; }

/// Exact side of x.
inline int side(const hplane& h, const pt& x) {
    switch (h.k) {
        case hplane::kind::axis: return sign_of(h.s * (x[h.axis] - h.c));
        case hplane::kind::triple: {
            // Filter with the cached normal first.
            double val = 0, perm = 0;
            for (int k = 0; k < 3; ++k) {
                const double d = x[k] - h.o[k];
                val += h.n[k] * d;
                perm += h.perm[k] * std::abs(d);
            }
            const double err = rel_err * perm + abs_err;
            if (val > err) return 1;
            if (-val > err) return -1;
            return static_cast<int>(h.s) * orient3(h.p, h.q, h.r, x);
        }
        case hplane::kind::lifted:
            return static_cast<int>(h.s) * orient2(h.p, h.q, x, lifted_i(h.axis), lifted_j(h.axis));
    }
    return 0;
}

/// Plane through p, q, r (not collinear), outside = orient3(p, q, r, ·) · outward > 0.
/// Becomes an exact axis plane when the three points share a coordinate.
inline hplane make_triple_plane(const pt& p, const pt& q, const pt& r, int outward) {
    hplane h;
    for (int k = 0; k < 3; ++k)
        if (p[k] == q[k] && q[k] == r[k]) {
            // orient3(p, q, r, x) = n_k (x_k − p_k) with n_k the 2D orientation in (k+1, k+2).
            const int nk = orient2(p, q, r, (k + 1) % 3, (k + 2) % 3);
            h.k = hplane::kind::axis;
            h.axis = k;
            h.c = p[k];
            h.s = static_cast<double>(nk * outward);
            return h;
        }
    h.k = hplane::kind::triple;
    h.p = p, h.q = q, h.r = r;
    h.s = outward;
    const double ux = q[0] - p[0], uy = q[1] - p[1], uz = q[2] - p[2];
    const double vx = r[0] - p[0], vy = r[1] - p[1], vz = r[2] - p[2];
    h.o = p;
    h.n = {outward * (uy * vz - uz * vy), outward * (uz * vx - ux * vz), outward * (ux * vy - uy * vx)};
    h.perm = {std::abs(uy * vz) + std::abs(uz * vy), std::abs(uz * vx) + std::abs(ux * vz),
              std::abs(ux * vy) + std::abs(uy * vx)};
    return h;
}

/// Plane parallel to axis `axis` through the 2D line p → q (coordinates (i, j) = (axis+1,
/// axis+2)); outside = orient2(p, q, ·) · outward > 0. p and q must differ in (i, j).
inline hplane make_lifted_plane(const pt& p, const pt& q, int axis, int outward) {
    const int i = lifted_i(axis), j = lifted_j(axis);
    hplane h;
    const double dx = q[i] - p[i], dy = q[j] - p[j];
    // orient2(p, q, x) = dx (x_j − p_j) − dy (x_i − p_i)
    if (dx == 0.0 || dy == 0.0) {  // an axis plane: x_i = p_i or x_j = p_j
        h.k = hplane::kind::axis;
        if (dx == 0.0) {
            h.axis = i, h.c = p[i], h.s = static_cast<double>(-sign_of(dy) * outward);
        } else {
            h.axis = j, h.c = p[j], h.s = static_cast<double>(sign_of(dx) * outward);
        }
        return h;
    }
    h.k = hplane::kind::lifted;
    h.axis = axis;
    h.p = p, h.q = q;
    h.s = outward;
    h.o = p;
    h.n = {0, 0, 0};
    h.n[i] = -dy * outward;
    h.n[j] = dx * outward;
    h.perm = {0, 0, 0};
    h.perm[i] = std::abs(dy);
    h.perm[j] = std::abs(dx);
    return h;
}

/// True when the whole axis-aligned box [lo, hi] is certainly strictly outside h.
inline bool box_strictly_outside(const hplane& h, const pt& lo, const pt& hi) {
    if (h.k == hplane::kind::axis) return h.s > 0 ? lo[h.axis] > h.c : hi[h.axis] < h.c;
    // The corner minimising the double normal; a sign mismatch between the double and the
    // exact normal component (only where that component is within its rounding error) is
    // covered by adding perm_k · width_k to the bound.
    double val = 0, perm = 0;
    for (int k = 0; k < 3; ++k) {
        const double x = h.n[k] > 0 ? lo[k] : hi[k];
        const double d = x - h.o[k];
        val += h.n[k] * d;
        perm += h.perm[k] * (std::abs(d) + (hi[k] - lo[k]));
    }
    return val > 2 * rel_err * perm + abs_err;
}

/// True when the whole box is certainly in the closed outside of h (side >= 0 everywhere).
inline bool box_outside_closed(const hplane& h, const pt& lo, const pt& hi) {
    if (h.k == hplane::kind::axis) return h.s > 0 ? lo[h.axis] >= h.c : hi[h.axis] <= h.c;
    return box_strictly_outside(h, lo, hi);
}

/// A separating-axis direction with the hull's projection range precomputed (rigorous bounds:
/// hmin <= d·(h − ref) <= hmax for every hull point h, d taken as the exact double vector).
struct axis_range {
    pt d{};
    double hmin = 0, hmax = 0;
};

/// d·(x − ref) and a bound on its rounding error (d is taken as exact).
inline double dot_from(const pt& d, const pt& x, const pt& ref, double& err) {
    double val = 0, mag = 0;
    for (int k = 0; k < 3; ++k) {
        const double t = x[k] - ref[k];
        val += d[k] * t;
        mag += std::abs(d[k] * t);
    }
    err = rel_err * mag + abs_err;
    return val;
}

/// The sight hull H = conv(box ∪ facet) of a box strictly in front of the facet plane.
struct sight_hull {
    std::array<pt, 11> pts{};  ///< 0..7 box corners (bit 0: x upper, 1: y, 2: z), 8..10 facet
    pt lo{}, hi{};             ///< axis-aligned bounding box of H
    pt ref{};                  ///< reference point for projections (facet vertex 0)
    std::array<hplane, 40> planes{};  ///< planes[0] is the facet plane (outside = behind)
    std::size_t num_planes = 0;
    std::array<axis_range, 40> face_axes{};  ///< double normals of non-axis planes, as SAT axes
    std::size_t num_face_axes = 0;
    /// Directions of hull edges (a superset): the three axes, facet edges, and corner–facet
    /// vertex connectors lying on a hull face.
    std::array<pt, 64> edge_dirs{};
    std::size_t num_edge_dirs = 0;

    const hplane& facet_plane() const noexcept { return planes[0]; }
    void add_plane(const hplane& h) {
        if (num_planes < planes.size()) planes[num_planes++] = h;
    }
    void add_edge_dir(const pt& a, const pt& b) {
        if (num_edge_dirs < edge_dirs.size())
            edge_dirs[num_edge_dirs++] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    }
};

/// The facet plane: outside = behind (orient3(a, c, b, x) > 0).
inline hplane facet_plane(const std::array<pt, 3>& f) { return make_triple_plane(f[0], f[2], f[1], 1); }

/// Builds H. Precondition: every box corner strictly in front of the facet plane (so H is
/// three-dimensional and H ∩ aff(facet) = facet).
inline void build_sight_hull(const pt& lo, const pt& hi, const std::array<pt, 3>& f, sight_hull& H) {
    H.num_planes = H.num_face_axes = H.num_edge_dirs = 0;
    for (int k = 0; k < 8; ++k)
        H.pts[k] = {k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]};
    for (int m = 0; m < 3; ++m) H.pts[8 + m] = f[m];
    for (int k = 0; k < 3; ++k) {
        H.lo[k] = std::min({lo[k], f[0][k], f[1][k], f[2][k]});
        H.hi[k] = std::max({hi[k], f[0][k], f[1][k], f[2][k]});
    }
    H.ref = f[0];
    H.add_plane(facet_plane(f));
    for (int k = 0; k < 3; ++k) {
        pt e{0, 0, 0};
        e[k] = 1;
        H.edge_dirs[H.num_edge_dirs++] = e;
    }
    for (int m = 0; m < 3; ++m) H.add_edge_dir(f[m], f[(m + 1) % 3]);

    // Facet-edge planes: for edge (u, v) in face order, the corner c* with every corner on the
    // inner side of plane (u, v, c*). Corners lie strictly in front, i.e. at angles in (0, π)
    // round the edge, where orient3 orders them: one pass finds the maximum.
    for (int m = 0; m < 3; ++m) {
        const pt& u = f[m];
        const pt& v = f[(m + 1) % 3];
        int best = 0;
        for (int k = 1; k < 8; ++k)
            if (orient3(u, v, H.pts[best], H.pts[k]) > 0) best = k;
        H.add_plane(make_triple_plane(u, v, H.pts[best], 1));
        for (int k = 0; k < 8; ++k)
            if (k == best || orient3(u, v, H.pts[best], H.pts[k]) == 0) {
                H.add_edge_dir(H.pts[k], u);
                H.add_edge_dir(H.pts[k], v);
            }
    }
    // Box face planes that support H (exact comparisons).
    for (int k = 0; k < 3; ++k) {
        const double fmin = std::min({f[0][k], f[1][k], f[2][k]});
        const double fmax = std::max({f[0][k], f[1][k], f[2][k]});
        for (int upper = 0; upper < 2; ++upper) {
            const double c = upper ? hi[k] : lo[k];
            if (upper ? fmax > c : fmin < c) continue;
            hplane h;
            h.k = hplane::kind::axis;
            h.axis = k;
            h.c = c;
            h.s = upper ? 1.0 : -1.0;
            H.add_plane(h);
            for (int m = 0; m < 3; ++m)
                if (f[m][k] == c)  // facet vertex on the box face: connectors to its corners
                    for (int b = 0; b < 8; ++b)
                        if (H.pts[b][k] == c) H.add_edge_dir(H.pts[b], f[m]);
        }
    }
    // Planes containing a box edge parallel to axis `a` and a facet vertex: supporting lines of
    // the projection of H along `a` through a projected box corner and a projected facet vertex.
    for (int a = 0; a < 3; ++a) {
        const int i = lifted_i(a), j = lifted_j(a);
        // The four projected corners (duplicates when the box is flat are harmless).
        std::array<int, 4> cidx{};
        int nc = 0;
        for (int b = 0; b < 8; ++b)
            if (((b >> a) & 1) == 0) cidx[nc++] = b;  // corners with the lower bound along a
        for (int qi = 0; qi < 4; ++qi) {
            const pt& q = H.pts[cidx[qi]];
            for (int m = 0; m < 3; ++m) {
                const pt& v = f[m];
                if (v[i] == q[i] && v[j] == q[j]) continue;
                int pos = 0, neg = 0;
                for (int o = 0; o < 4 && !(pos && neg); ++o) {
                    if (o == qi) continue;
                    const int sgn = orient2(q, v, H.pts[cidx[o]], i, j);
                    pos += sgn > 0, neg += sgn < 0;
                }
                for (int o = 0; o < 3 && !(pos && neg); ++o) {
                    if (o == m) continue;
                    const int sgn = orient2(q, v, f[o], i, j);
                    pos += sgn > 0, neg += sgn < 0;
                }
                if (pos && neg) continue;
                if (!pos && !neg) continue;  // all collinear: impossible for a 3D hull
                H.add_plane(make_lifted_plane(q, v, a, pos ? -1 : 1));
                const int b_up = cidx[qi] | (1 << a);
                H.add_edge_dir(q, v);
                H.add_edge_dir(H.pts[b_up], v);
                for (int o = 0; o < 3; ++o)
                    if (o != m && orient2(q, v, f[o], i, j) == 0) {
                        H.add_edge_dir(q, f[o]);
                        H.add_edge_dir(H.pts[b_up], f[o]);
                    }
            }
        }
    }
    // Double normals of the non-axis planes as SAT directions, with rigorous hull ranges.
    for (std::size_t p = 0; p < H.num_planes; ++p) {
        const hplane& h = H.planes[p];
        if (h.k == hplane::kind::axis) continue;
        axis_range ar;
        ar.d = h.n;
        ar.hmin = std::numeric_limits<double>::infinity();
        ar.hmax = -ar.hmin;
        for (const pt& x : H.pts) {
            double err = 0;
            const double val = dot_from(ar.d, x, H.ref, err);
            ar.hmin = std::min(ar.hmin, val - err);
            ar.hmax = std::max(ar.hmax, val + err);
        }
        H.face_axes[H.num_face_axes++] = ar;
    }
}

/// Exact: is x inside or on H (side <= 0 for every plane)?
inline bool hull_contains(const sight_hull& H, const pt& x) {
    for (std::size_t p = 0; p < H.num_planes; ++p)
        if (side(H.planes[p], x) > 0) return false;
    return true;
}

// ---- exact rational clipping (the fallback that decides every hard case) -------------------

using rational = CGAL::Exact_rational;
using rpt = std::array<rational, 3>;

struct rplane {
    rational a, b, c, d;  // outside: a x + b y + c z + d > 0
};

inline rplane to_rational(const hplane& h) {
    rplane r{0, 0, 0, 0};
    switch (h.k) {
        case hplane::kind::axis: {
            std::array<rational, 3> n{0, 0, 0};
            n[h.axis] = h.s;
            r = {n[0], n[1], n[2], rational(-h.s) * rational(h.c)};
            break;
        }
        case hplane::kind::triple: {
            const rpt p{h.p[0], h.p[1], h.p[2]};
            const rpt u{rational(h.q[0]) - p[0], rational(h.q[1]) - p[1], rational(h.q[2]) - p[2]};
            const rpt v{rational(h.r[0]) - p[0], rational(h.r[1]) - p[1], rational(h.r[2]) - p[2]};
            const rational s(h.s);
            r.a = s * (u[1] * v[2] - u[2] * v[1]);
            r.b = s * (u[2] * v[0] - u[0] * v[2]);
            r.c = s * (u[0] * v[1] - u[1] * v[0]);
            r.d = -(r.a * p[0] + r.b * p[1] + r.c * p[2]);
            break;
        }
        case hplane::kind::lifted: {
            const int i = lifted_i(h.axis), j = lifted_j(h.axis);
            const rational dx = rational(h.q[i]) - rational(h.p[i]);
            const rational dy = rational(h.q[j]) - rational(h.p[j]);
            const rational s(h.s);
            std::array<rational, 3> n{0, 0, 0};
            n[i] = -s * dy;
            n[j] = s * dx;
            r.a = n[0], r.b = n[1], r.c = n[2];
            r.d = -(n[i] * rational(h.p[i]) + n[j] * rational(h.p[j]));
            break;
        }
    }
    return r;
}

inline rational eval(const rplane& h, const rpt& x) { return h.a * x[0] + h.b * x[1] + h.c * x[2] + h.d; }

/// Exact: does the closed triangle t meet H at a point strictly in front of the facet plane
/// (H \ aff(facet))? Clips t by every half-space of H in rational arithmetic (the result is
/// exactly the convex polygon t ∩ H) and looks for a vertex strictly in front; a linear
/// function on a convex polygon peaks at a vertex, so this is an exact decision.
inline bool triangle_meets_hull_front_exact(const sight_hull& H, const std::array<pt, 3>& t) {
    std::vector<rpt> poly, next;
    poly.reserve(16), next.reserve(16);
    for (const pt& v : t) poly.push_back({v[0], v[1], v[2]});
    std::vector<rational> val;
    for (std::size_t p = 0; p < H.num_planes && !poly.empty(); ++p) {
        const rplane h = to_rational(H.planes[p]);
        val.clear();
        for (const rpt& x : poly) val.push_back(eval(h, x));
        next.clear();
        const std::size_t n = poly.size();
        for (std::size_t a = 0; a < n; ++a) {
            const std::size_t b = (a + 1) % n;
            const int sa = CGAL::sign(val[a]), sb = CGAL::sign(val[b]);
            if (sa <= 0) next.push_back(poly[a]);
            if ((sa < 0 && sb > 0) || (sa > 0 && sb < 0)) {
                const rational t0 = val[a] / (val[a] - val[b]);
                next.push_back({poly[a][0] + t0 * (poly[b][0] - poly[a][0]),
                                poly[a][1] + t0 * (poly[b][1] - poly[a][1]),
                                poly[a][2] + t0 * (poly[b][2] - poly[a][2])});
            }
        }
        poly.swap(next);
    }
    if (poly.empty()) return false;
    const rplane front = to_rational(H.facet_plane());  // outside = behind
    for (const rpt& x : poly)
        if (CGAL::sign(eval(front, x)) < 0) return true;
    return false;
}

}  // namespace certipose::detail::occ
