// certipose/occlusion/cgal_aabb_occlusion.hpp — `aabb_occlusion`, a fast certified occlusion
// test (past the paper, docs/occlusion.md).
//
// The union of all sight lines from a position box B to the facet f is the convex hull
// H = conv(B ∪ f). With B strictly in front of f's plane, H meets that plane exactly in f, so
// the facet is VISIBLE from every point of B iff no other scene triangle meets H off the facet
// plane (a triangle may touch H only inside f: the part's faces around f do). The test walks a
// CGAL AABB tree over all scene triangles, pruning nodes outside one of H's planes or behind
// f's plane, and decides each remaining triangle exactly: cheap double tests with rigorous error
// bounds settle nearly every case (separating planes and axes prove a miss; a triangle vertex
// strictly inside H or a corner–facet-vertex sight line crossing the triangle proves a hit);
// triangles sharing an edge or a vertex with f get exact orientation and cone tests; what is
// left is deferred to an exact rational clip of the triangle by H, run only if nothing else
// blocks. OCCLUDED comes only from exact certificates: every corner strictly behind f's plane
// (with a closed outward part, every sight line to f's interior then runs inside the part); no
// corner in front and the box apart from f (in-plane positions see f's interior only across a
// neighbour triangle); one scene triangle holding all 24 corner–vertex sight-line crossings;
// or a planar wall — all scene triangles in one plane that separates the box from f cover
// every crossing (see planar_wall_blocks). So the policy may say PARTIAL where the boolean test
// says OCCLUDED, and never VISIBLE where a sight line is blocked nor OCCLUDED where one is free.
// Read as a triangle soup (mesh_semantics::soup, occlusion/mesh_survey.hpp) there is no inside:
// the certificates that need a closed part (boxes behind or in the facet plane) and the planar
// wall (whose rim is found by edges used once) are not used, and facets the survey finds buried
// or covered are OCCLUDED from everywhere.
// A box touching or crossing f's plane is never VISIBLE (some points see f edge-on or from
// behind). docs/occlusion.md has the details and the measured speed.
//
// The class is declared in occlusion/aabb_occlusion.hpp (no CGAL); this header defines it,
// unless CERTIPOSE_PRECOMPILED says the certipose::precompiled library does (detail/config.hpp).
// Built once per scene: validates every mesh as a closed solid (detail/cgal_scene.hpp), or
// surveys the triangle soup, copies the triangles and builds the tree. `classify` is const and thread-safe: one object may be
// shared by many threads (copies share the immutable scene). It holds round-to-nearest for its
// duration, so callers may hold an interval rounding guard.
#pragma once

#include "certipose/occlusion/aabb_occlusion.hpp"

#if CERTIPOSE_DETAIL_WITH_DEFINITIONS

#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"
#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/interval/detail/fenv.hpp"
#include "certipose/occlusion/concept.hpp"
#include "certipose/occlusion/detail/box_bounds.hpp"
#include "certipose/occlusion/detail/cgal_scene.hpp"
#include "certipose/occlusion/detail/exact_geometry.hpp"
#include "certipose/occlusion/cgal_mesh_survey.hpp"
#include "certipose/pose/pose_box.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Intersections_3/Iso_cuboid_3_Triangle_3.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <utility>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

namespace certipose {

namespace detail::occ {

struct scene_triangle {
    std::array<pt, 3> v;
    std::array<std::uint32_t, 3> id;  ///< vertex ids; part ids are the part's vertex indices
    pt lo, hi;                        ///< bounding box
    /// Its flat patch (assign_flat_patches): triangles with the same one lie in one plane, exactly.
    std::uint32_t patch = 0;
};

/// Appends the faces of `m` with vertex ids offset by `offset` (so that ids of different
/// meshes never collide).
inline void append_triangles(std::vector<scene_triangle>& out, const triangle_mesh& m,
                             std::uint32_t offset) {
    for (const auto& f : m.faces()) {
        scene_triangle t;
        for (int k = 0; k < 3; ++k) {
            const Eigen::Vector3d& p = m.vertices()[f[k]];
            t.v[k] = {p.x(), p.y(), p.z()};
            t.id[k] = f[k] + offset;
        }
        for (int c = 0; c < 3; ++c) {
            t.lo[c] = std::min({t.v[0][c], t.v[1][c], t.v[2][c]});
            t.hi[c] = std::max({t.v[0][c], t.v[1][c], t.v[2][c]});
        }
        out.push_back(t);
    }
}

/// Gives the part faces (the first `part_faces` of `tris`) that are edge-adjacent and exactly
/// coplanar one patch number, and every other triangle one of its own. A triangle of the facet's
/// patch lies in the facet's plane, where the walks pass it over (it blocks no sight line, as
/// the closed half-space behind the plane holds it): the patch says so at once, where the sides
/// of its vertices, each 0, would each take an exact orientation (the filter cannot decide a
/// point on the plane). On a CAD export the facets of a flat face are mostly such neighbours.
/// Exact: two faces are joined only when both are non-degenerate and the far vertex of one
/// lies on the other's plane (orient3 is exact), so by induction a patch is one plane.
/// Faces whose vertices are not shared by index (an unwelded soup) stay apart: slower, not wrong.
inline void assign_flat_patches(std::vector<scene_triangle>& tris, std::size_t part_faces) {
    const certipose::detail::round_to_nearest_scope nearest;  // the orientations' filters assume it
    std::vector<std::uint32_t> parent(tris.size());
    for (std::size_t i = 0; i < tris.size(); ++i) parent[i] = static_cast<std::uint32_t>(i);
    const auto root = [&](std::uint32_t i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    std::vector<char> flat(part_faces);  // non-degenerate: a plane of its own
    for (std::size_t i = 0; i < part_faces; ++i) flat[i] = coplanar_orient(tris[i].v[0], tris[i].v[1], tris[i].v[2]) != 0;
    std::unordered_map<std::uint64_t, std::uint32_t> first_on_edge;  // an edge's first non-degenerate face
    first_on_edge.reserve(part_faces * 2);
    for (std::size_t i = 0; i < part_faces; ++i) {
        if (!flat[i]) continue;
        const scene_triangle& t = tris[i];
        for (int e = 0; e < 3; ++e) {
            const std::uint32_t a = t.id[e], b = t.id[(e + 1) % 3];
            if (a == b) continue;
            const std::uint64_t key = std::uint64_t{std::min(a, b)} << 32 | std::max(a, b);
            const auto [it, fresh] = first_on_edge.emplace(key, static_cast<std::uint32_t>(i));
            if (fresh) continue;
            const scene_triangle& u = tris[it->second];
            if (orient3(u.v[0], u.v[1], u.v[2], t.v[(e + 2) % 3]) != 0) continue;  // t's far vertex off u's plane
            const std::uint32_t ra = root(static_cast<std::uint32_t>(i)), rb = root(it->second);
            if (ra != rb) parent[ra] = rb;
        }
    }
    for (std::size_t i = 0; i < tris.size(); ++i) tris[i].patch = root(static_cast<std::uint32_t>(i));
}

/// The immutable scene of an aabb_occlusion: triangles (part faces first, in face order, then
/// each occluder's) and the AABB tree over them.
struct aabb_scene {
    using triangle_3 = epick::Triangle_3;
    using primitive = CGAL::AABB_triangle_primitive<epick, std::vector<triangle_3>::const_iterator>;
    using tree_type = CGAL::AABB_tree<CGAL::AABB_traits<epick, primitive>>;

    std::vector<scene_triangle> tris;
    std::vector<triangle_3> cgal_tris;
    tree_type tree;
    std::size_t part_faces = 0;
    /// Read as a triangle soup: no inside, so no OCCLUDED from "behind the facet".
    bool soup = false;
    std::optional<mesh_survey> survey;
    std::string why_not_solid;
    mutable std::atomic<std::uint64_t> exact_clips{0};
};


/// Signs of the line a → b against the three directed edges of triangle w (orient3 of a, b
/// and each edge). The line passes through the closed triangle iff the signs do not differ
/// strictly; through its interior iff they are all equal and non-zero.
inline std::array<int, 3> line_edge_signs(const pt& a, const pt& b, const std::array<pt, 3>& w) {
    return {orient3(a, b, w[0], w[1]), orient3(a, b, w[1], w[2]), orient3(a, b, w[2], w[0])};
}
inline bool line_meets_closed_triangle(const pt& a, const pt& b, const std::array<pt, 3>& w) {
    const auto o = line_edge_signs(a, b, w);
    return !((o[0] > 0 || o[1] > 0 || o[2] > 0) && (o[0] < 0 || o[1] < 0 || o[2] < 0));
}

/// Tree-node pruning shared by the traversals: the node's box misses H's bounding box or lies
/// strictly outside one of H's planes from `first_plane` on.
inline bool node_outside_hull_bounds(const sight_hull& H, const pt& lo, const pt& hi) {
    for (int k = 0; k < 3; ++k)
        if (hi[k] < H.lo[k] || lo[k] > H.hi[k]) return true;
    return false;
}
inline bool node_outside_hull(const sight_hull& H, const pt& lo, const pt& hi, std::size_t first_plane) {
    if (node_outside_hull_bounds(H, lo, hi)) return true;
    for (std::size_t p = first_plane; p < H.num_planes; ++p)
        if (box_strictly_outside(H.planes[p], lo, hi)) return true;
    return false;
}

/// The fast decision whether triangle T blocks some sight line, i.e. meets H off the facet
/// plane: `yes` and `no` are exact; `unsure` leaves it to the rational clip. Without `proofs`
/// the search for a proof of `yes` and the costliest separating axes are skipped: `unsure`
/// then also stands for `yes` (what a caller listing the triangles that *may* block needs:
/// most of the time of a blocker walk went into proving hits it treated as maybes anyway).
enum class hit { no, yes, unsure };

inline hit decide(const sight_hull& H, const std::array<std::uint32_t, 3>& fid, bool is_part,
                  const scene_triangle& T, aabb_trace& trace, bool proofs = true) {
    for (int k = 0; k < 3; ++k)
        if (T.hi[k] < H.lo[k] || T.lo[k] > H.hi[k]) return hit::no;
    ++trace.triangles_tested;
    const hplane& fp = H.facet_plane();
    // Adjacency with the facet (shared part vertices).
    int shared = 0;
    std::array<int, 3> where{-1, -1, -1};  // facet slot of each T vertex
    if (is_part)
        for (int m = 0; m < 3; ++m)
            for (int s = 0; s < 3; ++s)
                if (T.id[m] == fid[s]) where[m] = s, ++shared;
    // A shared vertex is one the facet plane is made of: its side is 0, which the filter cannot
    // tell and an exact orientation would (every neighbour of the facet has one or two).
    std::array<int, 3> behind{};
    for (int m = 0; m < 3; ++m) behind[m] = where[m] >= 0 ? 0 : side(fp, T.v[m]);
    // Entirely in the closed half-space behind the facet plane: T ∩ H lies in f.
    if (behind[0] >= 0 && behind[1] >= 0 && behind[2] >= 0) return hit::no;

    // T's own plane: sides of the 11 hull points (computed lazily, used by several tests).
    std::array<int, 11> tside{};
    bool have_tside = false;
    const auto t_sides = [&] {
        if (!have_tside)
            for (int p = 0; p < 11; ++p) tside[p] = orient3(T.v[0], T.v[1], T.v[2], H.pts[p]);
        have_tside = true;
    };
    // Witnesses of a hit: a vertex strictly inside H (then strictly in front), or a
    // corner–facet-vertex segment crossing T at an interior point of the segment.
    const auto witnessed = [&] {
        for (int m = 0; m < 3; ++m) {
            bool inside = true;
            for (std::size_t p = 0; p < H.num_planes && inside; ++p)
                inside = side(H.planes[p], T.v[m]) < 0;
            if (inside) return true;
        }
        t_sides();
        for (int c = 0; c < 8; ++c)
            for (int q = 8; q < 11; ++q) {
                if (tside[c] == 0 || tside[q] == 0 || tside[c] == tside[q]) continue;
                const auto o = line_edge_signs(H.pts[c], H.pts[q], T.v);
                if (o[0] != 0 && o[0] == o[1] && o[1] == o[2]) return true;
            }
        return false;
    };

    // A face with f's three vertices is f as a point set (a duplicate, or the face of another
    // body touching f, in a triangle soup): T ∩ H = f, in the facet plane. Unreachable (such a
    // face lies in the closed half-space behind the plane, handled above); kept so that no
    // edit above makes it block.
    if (shared == 3) return hit::no;
    if (shared == 2) {
        // Edge-adjacent: T = conv(e, w) with e a facet edge. H's face through e is planes[1+m]
        // for edge (f[m], f[m+1]); T meets H only in e iff w is strictly beyond that face, or
        // w is not in front at all (handled above).
        int w = 0;
        while (where[w] >= 0) ++w;
        const int a = where[(w + 1) % 3], b = where[(w + 2) % 3];
        // e is traversed (a → b) by T; the facet traverses it b → a. Edge slot m has
        // f[m] → f[m+1].
        const int m = (b + 1) % 3 == a ? b : a;
        return side(H.planes[1 + static_cast<std::size_t>(m)], T.v[w]) <= 0 ? hit::yes : hit::no;
    }
    if (shared == 1) {
        // Vertex-adjacent: T ∩ H must be {v}. A plane of H through v with the other two
        // vertices strictly outside proves it; so does T's plane with every other hull point
        // strictly on one side.
        int vi = 0;
        while (where[vi] < 0) ++vi;
        const pt& v = T.v[vi];
        const pt& w1 = T.v[(vi + 1) % 3];
        const pt& w2 = T.v[(vi + 2) % 3];
        for (std::size_t p = 0; p < H.num_planes; ++p) {
            const hplane& h = H.planes[p];
            if (side(h, v) == 0 && side(h, w1) > 0 && side(h, w2) > 0) return hit::no;
        }
        t_sides();
        int pos = 0, neg = 0;
        std::array<int, 11> zeros{};
        int nz = 0;
        for (int p = 0; p < 11; ++p) {
            if (p == 8 + where[vi]) continue;
            pos += tside[p] > 0, neg += tside[p] < 0;
            if (tside[p] == 0) zeros[nz++] = p;
        }
        if (pos == 0 || neg == 0) {
            // T's plane supports H, so T ∩ H = T ∩ G with G = conv(v, zeros), a face of H in
            // that plane: decide whether the 2D cones of T and G at v meet beyond v. Two
            // pointed plane cones meet iff one holds a boundary ray of the other.
            for (int a = 0; a < nz; ++a)
                if (in_cone2(v, w1, w2, H.pts[zeros[a]])) return hit::yes;
            for (const pt* d : {&w1, &w2})
                for (int a = 0; a < nz; ++a)
                    for (int b = a; b < nz; ++b)
                        if (in_cone2(v, H.pts[zeros[a]], H.pts[zeros[b]], *d)) return hit::yes;
            return hit::no;
        }
        if (proofs && witnessed()) return hit::yes;
        return hit::unsure;
    }

    // Not adjacent. Separating planes of H (exact for axis planes, rigorous for the rest).
    for (std::size_t p = 1; p < H.num_planes; ++p) {
        const hplane& h = H.planes[p];
        if (h.k != hplane::kind::axis) continue;
        if (side(h, T.v[0]) > 0 && side(h, T.v[1]) > 0 && side(h, T.v[2]) > 0) return hit::no;
    }
    const auto separated = [&](const pt& d, double hmin, double hmax) {
        double tmin = std::numeric_limits<double>::infinity(), tmax = -tmin;
        for (int m = 0; m < 3; ++m) {
            double err = 0;
            const double val = dot_from(d, T.v[m], H.ref, err);
            tmin = std::min(tmin, val - err);
            tmax = std::max(tmax, val + err);
        }
        return tmin > hmax || tmax < hmin;
    };
    for (std::size_t a = 0; a < H.num_face_axes; ++a)
        if (separated(H.face_axes[a].d, H.face_axes[a].hmin, H.face_axes[a].hmax)) return hit::no;
    const auto hull_range = [&](const pt& d, double& hmin, double& hmax) {
        hmin = std::numeric_limits<double>::infinity(), hmax = -hmin;
        for (const pt& x : H.pts) {
            double err = 0;
            const double val = dot_from(d, x, H.ref, err);
            hmin = std::min(hmin, val - err);
            hmax = std::max(hmax, val + err);
        }
    };
    const pt e1{T.v[1][0] - T.v[0][0], T.v[1][1] - T.v[0][1], T.v[1][2] - T.v[0][2]};
    const pt e2{T.v[2][0] - T.v[0][0], T.v[2][1] - T.v[0][1], T.v[2][2] - T.v[0][2]};
    const pt e3{T.v[2][0] - T.v[1][0], T.v[2][1] - T.v[1][1], T.v[2][2] - T.v[1][2]};
    const auto cross = [](const pt& x, const pt& y) {
        return pt{x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
    };
    {
        double hmin = 0, hmax = 0;
        const pt nt = cross(e1, e2);
        hull_range(nt, hmin, hmax);
        if (separated(nt, hmin, hmax)) return hit::no;
    }
    if (!proofs) return hit::unsure;
    if (witnessed()) return hit::yes;
    for (const pt* et : {&e1, &e2, &e3})
        for (std::size_t d = 0; d < H.num_edge_dirs; ++d) {
            const pt ax = cross(*et, H.edge_dirs[d]);
            if (ax[0] == 0 && ax[1] == 0 && ax[2] == 0) continue;
            double hmin = 0, hmax = 0;
            hull_range(ax, hmin, hmax);
            if (separated(ax, hmin, hmax)) return hit::no;
        }
    return hit::unsure;
}

/// Does triangle T block some sight line? Exact: the fast decision, else the rational clip.
inline bool blocks(const sight_hull& H, const std::array<std::uint32_t, 3>& fid, bool is_part,
                   const scene_triangle& T, aabb_trace& trace) {
    const hit d = decide(H, fid, is_part, T, trace);
    if (d != hit::unsure) return d == hit::yes;
    ++trace.exact_clips;
    return triangle_meets_hull_front_exact(H, T.v);
}

/// Certificate of full occlusion by one triangle: its plane strictly separates the box corners
/// from the facet vertices and each of the 24 corner–vertex segments meets it. By convexity
/// (the crossing point of any sight line lies in the hull of those 24 crossings) it then
/// blocks every sight line.
inline bool blocks_every_sight_line(const sight_hull& H, const scene_triangle& T) {
    std::array<int, 11> s{};
    for (int p = 0; p < 11; ++p) s[p] = orient3(T.v[0], T.v[1], T.v[2], H.pts[p]);
    const int box_side = s[0];
    if (box_side == 0) return false;
    for (int p = 1; p < 8; ++p)
        if (s[p] != box_side) return false;
    for (int p = 8; p < 11; ++p)
        if (s[p] != -box_side) return false;
    for (int c = 0; c < 8; ++c)
        for (int q = 8; q < 11; ++q) {
            if (!line_meets_closed_triangle(H.pts[c], H.pts[q], T.v)) return false;
        }
    return true;
}

/// Does the segment (p0, p1) meet H off the facet plane? Exact. `v0` is true when p0 is a
/// facet vertex (then the segment meets H beyond p0 iff p1 − p0 lies in H's tangent cone at p0,
/// i.e. no plane of H through p0 has p1 strictly outside).
inline bool segment_meets_hull_front(const sight_hull& H, const pt& p0, const pt& p1, bool v0) {
    const hplane& fp = H.facet_plane();
    if (side(fp, p0) >= 0 && side(fp, p1) >= 0) return false;  // in the closed back half-space
    if (v0) {
        for (std::size_t p = 0; p < H.num_planes; ++p)
            if (side(H.planes[p], p0) == 0 && side(H.planes[p], p1) > 0) return false;
        return true;  // p1 is strictly in front (above) and p1 − p0 points into H
    }
    const auto strictly_inside = [&](const pt& x) {
        for (std::size_t p = 0; p < H.num_planes; ++p)
            if (side(H.planes[p], x) >= 0) return false;
        return true;
    };
    if (strictly_inside(p0) || strictly_inside(p1)) return true;  // then strictly in front too
    for (std::size_t p = 1; p < H.num_planes; ++p)
        if (side(H.planes[p], p0) > 0 && side(H.planes[p], p1) > 0) return false;
    // Separating axes: H's face normals and segment × hull-edge directions (rigorous bounds).
    const auto separated = [&](const pt& d, double hmin, double hmax) {
        double e0 = 0, e1 = 0;
        const double a = dot_from(d, p0, H.ref, e0), b = dot_from(d, p1, H.ref, e1);
        return std::min(a - e0, b - e1) > hmax || std::max(a + e0, b + e1) < hmin;
    };
    for (std::size_t a = 0; a < H.num_face_axes; ++a)
        if (separated(H.face_axes[a].d, H.face_axes[a].hmin, H.face_axes[a].hmax)) return false;
    const pt e{p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
    for (std::size_t d = 0; d < H.num_edge_dirs; ++d) {
        const pt& g = H.edge_dirs[d];
        const pt ax{e[1] * g[2] - e[2] * g[1], e[2] * g[0] - e[0] * g[2], e[0] * g[1] - e[1] * g[0]};
        if (ax[0] == 0 && ax[1] == 0 && ax[2] == 0) continue;
        double hmin = std::numeric_limits<double>::infinity(), hmax = -hmin;
        for (const pt& x : H.pts) {
            double err = 0;
            const double val = dot_from(ax, x, H.ref, err);
            hmin = std::min(hmin, val - err), hmax = std::max(hmax, val + err);
        }
        if (separated(ax, hmin, hmax)) return false;
    }
    return triangle_meets_hull_front_exact(H, {p0, p1, p1});
}

/// Collects the scene triangles lying exactly in plane P near H (nodes strictly on one side of
/// P or outside H's bounding box are pruned; what they hold can neither contain a sight-line
/// crossing nor have an edge meeting H). Nodes are not tested against H's planes: for walls
/// that test cost more than the few far triangles it saves, whose edges are then just checked.
struct coplanar_collector {
    const sight_hull& H;
    const aabb_scene& scene;
    hplane P, P_flipped;
    std::vector<std::size_t>& out;
    bool overflow = false;
    static constexpr std::size_t max_triangles = 512;

    bool go_further() const { return !overflow; }

    template <class Primitive>
    void intersection(const sight_hull&, const Primitive& prim) {
        const auto idx = static_cast<std::size_t>(prim.id() - scene.cgal_tris.begin());
        const scene_triangle& t = scene.tris[idx];
        for (int k = 0; k < 3; ++k)
            if (t.hi[k] < H.lo[k] || t.lo[k] > H.hi[k]) return;
        if (side(P, t.v[0]) != 0 || side(P, t.v[1]) != 0 || side(P, t.v[2]) != 0) return;
        if (out.size() >= max_triangles) overflow = true;
        else out.push_back(idx);
    }

    template <class Node>
    bool do_intersect(const sight_hull&, const Node& node) const {
        const auto& b = node.bbox();
        const pt lo{b.xmin(), b.ymin(), b.zmin()}, hi{b.xmax(), b.ymax(), b.zmax()};
        if (node_outside_hull(H, lo, hi, H.num_planes)) return false;  // H's bounding box only
        return !box_strictly_outside(P, lo, hi) && !box_strictly_outside(P_flipped, lo, hi);
    }
};

/// Certificate of full occlusion by a planar wall: the plane P of triangle T has every box
/// corner strictly on one side and the facet's vertices on the other side or on P (one
/// strictly). Every sight line to the facet's interior then crosses P at a point of
/// C' = (H ∩ P) minus the facet, a convex set. If no boundary edge of R — the union of the scene
/// triangles lying in P — meets C', and one sight line crosses P inside R, then C' ⊆ R: every
/// sight line to the facet's interior meets a scene triangle. (The box is strictly in front of
/// the facet plane here.)
/// The first part of planar_wall_blocks: the facet vertex strictly across T's plane from every
/// box corner (with no facet vertex on the box side), or -1.
inline int wall_plane_qualifies(const sight_hull& H, const scene_triangle& T) {
    const int box_side = orient3(T.v[0], T.v[1], T.v[2], H.pts[0]);
    if (box_side == 0) return -1;
    for (int p = 1; p < 8; ++p)
        if (orient3(T.v[0], T.v[1], T.v[2], H.pts[p]) != box_side) return -1;
    int across = -1;
    for (int p = 8; p < 11; ++p) {
        const int sp = orient3(T.v[0], T.v[1], T.v[2], H.pts[p]);
        if (sp == box_side) return -1;
        if (sp == -box_side) across = p;
    }
    return across;
}

inline bool planar_wall_blocks(const sight_hull& H, const aabb_scene& scene, std::size_t facet,
                               const scene_triangle& T) {
    const int across = wall_plane_qualifies(H, T);
    if (across < 0) return false;

    std::vector<std::size_t> wall;
    coplanar_collector col{H, scene, make_triple_plane(T.v[0], T.v[1], T.v[2], 1),
                           make_triple_plane(T.v[0], T.v[1], T.v[2], -1), wall};
    scene.tree.traversal(H, col);
    if (col.overflow || wall.empty()) return false;

    // One sight line (corner 0 → a facet vertex across P) crosses P inside R.
    bool witness = false;
    for (std::size_t i = 0; i < wall.size() && !witness; ++i)
        witness = line_meets_closed_triangle(H.pts[0], H.pts[across], scene.tris[wall[i]].v);
    if (!witness) return false;

    // Boundary edges of R: edges used by exactly one triangle of R (vertex ids are unique
    // across scene meshes).
    std::vector<std::pair<std::uint64_t, std::array<std::size_t, 2>>> edges;  // key, (tri, slot)
    edges.reserve(3 * wall.size());
    for (std::size_t i = 0; i < wall.size(); ++i) {
        const auto& id = scene.tris[wall[i]].id;
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = id[k], b = id[(k + 1) % 3];
            const std::uint64_t key = (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
            edges.push_back({key, {wall[i], static_cast<std::size_t>(k)}});
        }
    }
    std::sort(edges.begin(), edges.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    const auto& fid = scene.tris[facet].id;
    const auto is_facet_vertex = [&](std::uint32_t id) { return id == fid[0] || id == fid[1] || id == fid[2]; };
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i + 1;
        while (j < edges.size() && edges[j].first == edges[i].first) ++j;
        if (j - i == 1) {
            const auto& t = scene.tris[edges[i].second[0]];
            const int k = static_cast<int>(edges[i].second[1]);
            const bool part = edges[i].second[0] < scene.part_faces;
            const bool f0 = part && is_facet_vertex(t.id[k]);
            const bool f1 = part && is_facet_vertex(t.id[(k + 1) % 3]);
            if (f0 && f1) {  // a facet edge: inside the facet
            } else if (f1) {
                if (segment_meets_hull_front(H, t.v[(k + 1) % 3], t.v[k], true)) return false;
            } else if (segment_meets_hull_front(H, t.v[k], t.v[(k + 1) % 3], f0)) {
                return false;
            }
        }
        i = j;
    }
    return true;
}

/// May the segment [a, b] share a point with the closed triangle w? Exact when it says no;
/// a segment lying in w's plane is answered yes without looking further.
inline bool segment_may_meet_triangle(const pt& a, const pt& b, const std::array<pt, 3>& w) {
    const int sa = orient3(w[0], w[1], w[2], a), sb = orient3(w[0], w[1], w[2], b);
    if (sa == sb) return sa == 0;  // both strictly on one side: no; both in the plane: maybe
    return line_meets_closed_triangle(a, b, w);  // the segment meets the plane in one point
}

/// Tree pruning for a segment: may the segment from a to b meet `box`? A slab test in plain
/// doubles against the box grown by a margin (a billionth of the coordinates' magnitude) that
/// dwarfs the rounding of the arithmetic, so a node the segment meets is never pruned; one it
/// misses by less is only visited, and its triangles are decided exactly. (CGAL's exact
/// segment–box predicate prunes a little more, but its filter fails whenever an endpoint lies on
/// a box face, which the centroid of an axis-aligned CAD face does, and exact arithmetic follows.)
/// The segment's direction and magnitudes are prepared once for the many nodes of one walk:
/// dividing by the direction is multiplying by its rounded reciprocal, whose few ulps of
/// relative error in t are a coordinate error over a million times smaller than the margin.
struct segment_slabs {
    pt a{}, inv{}, mag{};  ///< start, 1 / (b − a) (0 where `flat`), |a| + |b|
    std::array<bool, 3> flat{};  ///< b − a is 0 in that coordinate

    segment_slabs() = default;
    segment_slabs(const pt& from, const pt& to) : a(from) {
        for (int k = 0; k < 3; ++k) {
            const double d = to[k] - from[k];
            flat[k] = d == 0.0;
            inv[k] = flat[k] ? 0.0 : 1.0 / d;
            mag[k] = std::abs(from[k]) + std::abs(to[k]);
        }
    }

    bool may_meet(const CGAL::Bbox_3& box) const {
        double t0 = 0.0, t1 = 1.0;
        for (int k = 0; k < 3; ++k) {
            const double lo = box.min(k), hi = box.max(k);
            const double margin = 1e-9 * (std::abs(lo) + std::abs(hi) + mag[k]) + 1e-300;
            if (flat[k]) {
                if (a[k] < lo - margin || a[k] > hi + margin) return false;
                continue;
            }
            double ta = (lo - margin - a[k]) * inv[k], tb = (hi + margin - a[k]) * inv[k];
            if (ta > tb) std::swap(ta, tb);
            t0 = std::max(t0, ta), t1 = std::min(t1, tb);
            if (t0 > t1) return false;
        }
        return true;
    }
};

inline bool segment_may_meet_box(const pt& a, const pt& b, const CGAL::Bbox_3& box) {
    return segment_slabs(a, b).may_meet(box);
}

/// Does the sight segment from a (in front of the facet) to b (on it) possibly meet a scene
/// triangle other than `facet`? (CGAL traversal traits over the scene tree.) A triangle in the
/// closed half-space behind the facet plane is passed over, as `decide` does: it can meet the
/// segment at its end on the facet only, which blocks nothing (a sight line is its open
/// segment) — and a soup's duplicate of the facet, or a coplanar neighbour, lies there.
struct segment_hits_other {
    const aabb_scene& scene;
    std::size_t facet;
    pt a, b;
    hplane fp;  ///< the facet's plane
    bool hit = false;
    std::size_t blocker = 0;  ///< the triangle that made `hit`
    segment_slabs slabs{a, b};

    bool go_further() const { return !hit; }

    /// Is scene triangle idx one the walk passes over: the facet, or wholly on or behind its plane?
    bool passed_over(std::size_t idx) const {
        if (idx == facet || scene.tris[idx].patch == scene.tris[facet].patch) return true;  // in the facet plane
        const auto& t = scene.tris[idx].v;
        // A vertex shared with the facet lies on its plane (side 0, see decide).
        const auto& fid = scene.tris[facet].id;
        const auto on_or_behind = [&](std::size_t m) {
            const std::uint32_t id = scene.tris[idx].id[m];
            return id == fid[0] || id == fid[1] || id == fid[2] || side(fp, t[m]) >= 0;
        };
        return on_or_behind(0) && on_or_behind(1) && on_or_behind(2);
    }

    template <class Primitive>
    void intersection(const epick::Segment_3&, const Primitive& prim) {
        const auto idx = static_cast<std::size_t>(prim.id() - scene.cgal_tris.begin());
        if (passed_over(idx)) return;
        if (segment_may_meet_triangle(a, b, scene.tris[idx].v)) hit = true, blocker = idx;
    }

    /// Does triangle idx settle the walk's answer alone? Only when the segment crosses its plane
    /// and meets it (exact orientations): then the segment meets its bounding box, so the walk
    /// reaches it and says `hit` too. (A segment in its plane is a "maybe" the walk may never
    /// reach: not taken from a hint.)
    bool surely_hit_by(std::size_t idx) const {
        if (idx >= scene.tris.size() || passed_over(idx)) return false;
        const auto& w = scene.tris[idx].v;
        const int sa = orient3(w[0], w[1], w[2], a), sb = orient3(w[0], w[1], w[2], b);
        if (sa == sb) return false;  // strictly on one side (no), or in the plane (not sure)
        return line_meets_closed_triangle(a, b, w);
    }

    template <class Node>
    bool do_intersect(const epick::Segment_3&, const Node& node) const {
        return slabs.may_meet(node.bbox());
    }
};

/// Does the segment from `c` to f's centroid rounded to doubles meet no scene triangle but f?
/// (Rounding the centroid may sway a grazing segment either way: callers use the answer only
/// as a filter, see below.)
/// With `hint` (a triangle index, or null): the hinted triangle is tried first and settles the
/// answer when it surely blocks (segment_hits_other::surely_hit_by), the same answer the walk
/// gives; `*hint` receives the triangle that blocked.
inline bool sight_line_free(const aabb_scene& scene, std::size_t facet, const epick::Point_3& c,
                            std::size_t* hint = nullptr) {
    using P = epick::Point_3;
    const auto& f = scene.tris[facet].v;
    const P q((f[0][0] + f[1][0] + f[2][0]) / 3, (f[0][1] + f[1][1] + f[2][1]) / 3, (f[0][2] + f[1][2] + f[2][2]) / 3);
    segment_hits_other t{scene, facet, {c.x(), c.y(), c.z()}, {q.x(), q.y(), q.z()}, facet_plane(f)};
    if (hint && t.surely_hit_by(*hint)) return false;
    const epick::Segment_3 seg(c, q);
    scene.tree.traversal(seg, t);
    if (hint && t.hit) *hint = t.blocker;
    return !t.hit;
}

/// Is a sight line from the box to the facet free? Tries the box centre and two opposite corners
/// against f's centroid. Only a filter: `true` lets `classify` answer PARTIAL (we already know
/// some sight line is blocked) without searching for an OCCLUDED certificate, which needs every
/// sight line blocked and so cannot exist when one is free. Neither way of a grazing segment
/// costs soundness: `true` only yields PARTIAL, which is never a wrong answer, and `false` only
/// costs the search.
inline bool some_sight_line_free(const aabb_scene& scene, std::size_t facet, const pt& lo, const pt& hi) {
    using P = epick::Point_3;
    if (sight_line_free(scene, facet, P(lo[0] + (hi[0] - lo[0]) / 2, lo[1] + (hi[1] - lo[1]) / 2, lo[2] + (hi[2] - lo[2]) / 2)))
        return true;
    for (int k : {0, 7})
        if (sight_line_free(scene, facet, P(k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]))) return true;
    return false;
}

/// CGAL traversal traits: prune nodes H cannot reach, stop at the first blocking triangle.
struct hull_traversal {
    const sight_hull& H;
    const aabb_scene& scene;
    std::size_t facet;
    std::array<std::uint32_t, 3> fid;
    aabb_trace& trace;
    bool blocked = false;

    /// Triangles the fast tests left undecided; decided exactly only if nothing else blocks
    /// (a partial box usually has another blocking triangle with a cheap certificate).
    std::vector<std::size_t> deferred{};
    /// When set, walk everything and collect here every triangle that blocks or may block
    /// (candidate walls for the occlusion certificate; no exact work), up to `max_collected`.
    std::vector<std::size_t>* collect = nullptr;
    static constexpr std::size_t max_collected = 256;

    bool go_further() const { return collect ? collect->size() < max_collected : !blocked; }

    template <class Primitive>
    void intersection(const sight_hull&, const Primitive& prim) {
        const auto idx = static_cast<std::size_t>(prim.id() - scene.cgal_tris.begin());
        // In the facet plane (its flat patch): decide would say no.
        if (idx == facet || scene.tris[idx].patch == scene.tris[facet].patch) return;
        const hit d = decide(H, fid, idx < scene.part_faces, scene.tris[idx], trace);
        if (d == hit::no) return;
        if (collect) {
            collect->push_back(idx);
        } else if (d == hit::yes) {
            blocked = true;
            trace.blocker = idx;
        } else {
            deferred.push_back(idx);
        }
    }

    /// After the walk: settle the deferred triangles exactly until one blocks.
    void settle() {
        for (std::size_t idx : deferred) {
            if (blocked) return;
            ++trace.exact_clips;
            if (triangle_meets_hull_front_exact(H, scene.tris[idx].v)) blocked = true, trace.blocker = idx;
        }
    }

    template <class Node>
    bool do_intersect(const sight_hull&, const Node& node) const {
        const auto& b = node.bbox();
        const pt lo{b.xmin(), b.ymin(), b.zmin()}, hi{b.xmax(), b.ymax(), b.zmax()};
        // Outside H's bounding box (six comparisons: most pruned nodes are), or entirely in the
        // closed half-space behind the facet plane, where nothing blocks, or outside H.
        if (node_outside_hull_bounds(H, lo, hi) || box_outside_closed(H.facet_plane(), lo, hi)) return false;
        return !node_outside_hull(H, lo, hi, 1);
    }
};

/// Adds to `s` the planes through three of the six vertices of facet f and triangle t — t's own
/// plane, each edge of one with each vertex of the other — that have f's vertices on one closed
/// side and t's on the other (exact orientations), as the closed half-space away from f
/// (occlusion_shadow). A plane holding all six vertices separates nothing and is skipped.
inline void add_separating_planes(const std::array<pt, 3>& f, const std::array<pt, 3>& t, occlusion_shadow& s) {
    // The six vertices are f's (0–2) and t's (3–5); a plane is given by three of them, which lie
    // on it: their orientations are 0 without asking (the exact fallback of orient3 is what
    // costs on a point of the plane).
    const auto vertex = [&](int i) -> const pt& { return i < 3 ? f[static_cast<std::size_t>(i)] : t[static_cast<std::size_t>(i - 3)]; };
    const auto consider = [&](int ia, int ib, int ic) {
        const pt &a = vertex(ia), &b = vertex(ib), &c = vertex(ic);
        std::array<int, 3> fs{}, ts{};
        for (int k = 0; k < 3; ++k) {
            fs[k] = (k == ia || k == ib || k == ic) ? 0 : orient3(a, b, c, f[k]);
            ts[k] = (k + 3 == ia || k + 3 == ib || k + 3 == ic) ? 0 : orient3(a, b, c, t[k]);
        }
        const bool flat = fs == std::array<int, 3>{} && ts == std::array<int, 3>{};
        if (flat || s.count == occlusion_shadow::max_planes) return;
        for (const int sigma : {1, -1}) {
            bool ok = true;
            for (int k = 0; k < 3 && ok; ++k) ok = sigma * fs[k] >= 0 && sigma * ts[k] <= 0;
            if (!ok) continue;
            auto& h = s.planes[s.count++];
            for (int k = 0; k < 3; ++k) {
                const pt& x = k == 0 ? a : k == 1 ? b : c;
                h.points[static_cast<std::size_t>(k)] = Eigen::Vector3d(x[0], x[1], x[2]);
            }
            h.sign = sigma;
            return;
        }
    };
    consider(3, 4, 5);
    for (int e = 0; e < 3; ++e)
        for (int v = 0; v < 3; ++v) {
            consider(e, (e + 1) % 3, 3 + v);
            consider(3 + e, 3 + (e + 1) % 3, v);
        }
}

/// CGAL traversal traits: every triangle that may block a sight line (the fast decision says yes
/// or unsure) to the visitor, until it stops the walk or max_blockers is passed.
struct blocker_walk {
    const sight_hull& H;
    const aabb_scene& scene;
    std::size_t facet;
    std::array<std::uint32_t, 3> fid;
    blocker_visitor visit;
    bool stopped = false;
    std::size_t seen = 0;
    aabb_trace trace{};

    bool go_further() const { return !stopped; }

    template <class Primitive>
    void intersection(const sight_hull&, const Primitive& prim) {
        const auto idx = static_cast<std::size_t>(prim.id() - scene.cgal_tris.begin());
        if (idx == facet || stopped || scene.tris[idx].patch == scene.tris[facet].patch) return;  // in the facet plane
        if (decide(H, fid, idx < scene.part_faces, scene.tris[idx], trace, false) == hit::no) return;
        if (++seen > aabb_occlusion::max_blockers || !visit(idx)) stopped = true;
    }

    template <class Node>
    bool do_intersect(const sight_hull&, const Node& node) const {
        const auto& b = node.bbox();
        const pt lo{b.xmin(), b.ymin(), b.zmin()}, hi{b.xmax(), b.ymax(), b.zmax()};
        if (node_outside_hull_bounds(H, lo, hi) || box_outside_closed(H.facet_plane(), lo, hi)) return false;
        return !node_outside_hull(H, lo, hi, 1);
    }
};

/// aabb_occlusion::front_clear's walk: stops at the first triangle but the facet that has a
/// vertex strictly in front of the facet's plane and a bounding box meeting the region.
struct front_walk {
    const aabb_scene& scene;
    std::size_t facet;
    const hplane& plane;  ///< the facet's: side < 0 in front
    pt lo, hi;            ///< the region
    bool blocked = false;

    bool go_further() const { return !blocked; }

    template <class Primitive>
    void intersection(const CGAL::Bbox_3&, const Primitive& prim) {
        const auto idx = static_cast<std::size_t>(prim.id() - scene.cgal_tris.begin());
        if (idx == facet || blocked) return;
        const scene_triangle& t = scene.tris[idx];
        for (int k = 0; k < 3; ++k)
            if (t.hi[k] < lo[k] || t.lo[k] > hi[k]) return;
        for (const pt& v : t.v)
            if (side(plane, v) < 0) {
                blocked = true;
                return;
            }
    }

    template <class Node>
    bool do_intersect(const CGAL::Bbox_3&, const Node& node) const {
        const auto& b = node.bbox();
        const pt nlo{b.xmin(), b.ymin(), b.zmin()}, nhi{b.xmax(), b.ymax(), b.zmax()};
        for (int k = 0; k < 3; ++k)
            if (nhi[k] < lo[k] || nlo[k] > hi[k]) return false;
        return !box_outside_closed(plane, nlo, nhi);  // wholly on or behind the plane: nothing in front
    }
};

/// The part, then each occluder.
inline std::vector<const triangle_mesh*> scene_meshes(const triangle_mesh& part,
                                                     std::span<const triangle_mesh> occluders) {
    std::vector<const triangle_mesh*> all{&part};
    for (const auto& o : occluders) all.push_back(&o);
    return all;
}

}  // namespace detail::occ



CERTIPOSE_DECL aabb_occlusion::aabb_occlusion(const triangle_mesh& part) : aabb_occlusion(part, {}) {}

CERTIPOSE_DECL aabb_occlusion::aabb_occlusion(const triangle_mesh& part, std::span<const triangle_mesh> occluders)
    : aabb_occlusion(part, occluders, mesh_semantics::solid) {}

CERTIPOSE_DECL aabb_occlusion::aabb_occlusion(const triangle_mesh& part, std::span<const triangle_mesh> occluders,
                                              mesh_semantics semantics) {
    auto s = std::make_shared<detail::occ::aabb_scene>();
    const auto validate = [&] {
        detail::occ::validate_solid(part, "aabb_occlusion: part");
        for (std::size_t i = 0; i < occluders.size(); ++i)
            detail::occ::validate_solid(occluders[i], "aabb_occlusion: occluder " + std::to_string(i));
    };
    if (semantics == mesh_semantics::solid) {
        try {
            validate();
        } catch (const mesh_error& e) {
            throw mesh_error(std::string(e.what()) +
                             "; a mesh that is not a clean closed solid (CAD exports) is accepted as a triangle "
                             "soup with mesh_semantics::soup (--mesh-semantics soup)");
        }
    } else if (semantics == mesh_semantics::automatic) {
        try {
            validate();
        } catch (const mesh_error& e) {
            s->soup = true;
            s->why_not_solid = e.what();
        }
    } else {
        s->soup = true;
    }
    s->part_faces = part.num_faces();
    std::uint32_t offset = 0;
    for (const triangle_mesh* m : detail::occ::scene_meshes(part, occluders)) {
        detail::occ::append_triangles(s->tris, *m, offset);
        offset += static_cast<std::uint32_t>(m->num_vertices());
    }
    detail::occ::assign_flat_patches(s->tris, s->part_faces);
    if (s->soup) {
        if (occluders.empty()) {
            s->survey = survey_mesh(part);
        } else {  // one mesh of every scene triangle, part faces first: bodies may overlap across meshes
            std::vector<Eigen::Vector3d> v;
            std::vector<face_indices> f;
            std::uint32_t base = 0;
            for (const triangle_mesh* m : detail::occ::scene_meshes(part, occluders)) {
                v.insert(v.end(), m->vertices().begin(), m->vertices().end());
                for (const auto& t : m->faces()) f.push_back({t[0] + base, t[1] + base, t[2] + base});
                base += static_cast<std::uint32_t>(m->num_vertices());
            }
            s->survey = survey_mesh(triangle_mesh(std::move(v), std::move(f)));
        }
    }
    using P = detail::occ::epick::Point_3;
    for (const auto& t : s->tris)
        s->cgal_tris.emplace_back(P(t.v[0][0], t.v[0][1], t.v[0][2]),
                                  P(t.v[1][0], t.v[1][1], t.v[1][2]),
                                  P(t.v[2][0], t.v[2][1], t.v[2][2]));
    s->tree.rebuild(s->cgal_tris.cbegin(), s->cgal_tris.cend());  // built now: const queries
    scene_ = std::move(s);
}

CERTIPOSE_DECL mesh_semantics aabb_occlusion::semantics() const noexcept {
    return scene_->soup ? mesh_semantics::soup : mesh_semantics::solid;
}

CERTIPOSE_DECL const mesh_survey* aabb_occlusion::survey() const noexcept {
    return scene_->survey ? &*scene_->survey : nullptr;
}

CERTIPOSE_DECL const std::string& aabb_occlusion::why_not_solid() const noexcept { return scene_->why_not_solid; }

CERTIPOSE_DECL std::optional<std::string> aabb_occlusion::hidden(std::size_t facet) const {
    if (facet >= scene_->part_faces) throw out_of_range("facet", facet, scene_->part_faces);
    if (!scene_->survey) return std::nullopt;
    return scene_->survey->why_hidden(facet);
}

CERTIPOSE_DECL visibility aabb_occlusion::classify(const Eigen::AlignedBox3d& box, std::size_t facet,
                                                   occlusion_effort effort) const {
    trace t;
    return explain(box, facet, t, effort);
}

CERTIPOSE_DECL visibility aabb_occlusion::explain(const Eigen::AlignedBox3d& box, std::size_t facet, trace& info,
                                                  occlusion_effort effort) const {
    using namespace detail::occ;
    info = trace{};
    const Eigen::AlignedBox3d b = checked_bounds(box, "aabb_occlusion");
    if (facet >= scene_->part_faces) throw out_of_range("facet", facet, scene_->part_faces);
    // Buried in or covered by another body of a soup: every free sight line starts inside
    // material (occlusion/mesh_survey.hpp), so no camera sees it.
    if (scene_->survey && material_in_front(scene_->survey->hidden[facet])) return visibility::occluded;
    const detail::round_to_nearest_scope nearest;  // the error bounds assume it
    const scene_triangle& F = scene_->tris[facet];
    const pt lo{b.min().x(), b.min().y(), b.min().z()};
    const pt hi{b.max().x(), b.max().y(), b.max().z()};

    // Which side of the facet plane is each corner on (exact)?
    const hplane fp = facet_plane(F.v);
    int behind = 0, front = 0;
    for (int k = 0; k < 8; ++k) {
        const pt c{k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]};
        const int s = side(fp, c);
        behind += s > 0, front += s < 0;
    }
    // In a triangle soup nothing is inside: a position behind the facet may see its back
    // through nothing. The constraints refuse such positions anyway (the backface test).
    if (scene_->soup && front < 8) return visibility::partial;
    if (behind == 8) return visibility::occluded;  // facing away: inside the part
    if (front == 0) {
        // Behind or in the facet plane. An in-plane position outside the facet sees its
        // interior only across its boundary, i.e. across a neighbour triangle (closed part).
        const epick::Iso_cuboid_3 cub(lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
        return CGAL::do_intersect(scene_->cgal_tris[facet], cub) ? visibility::partial : visibility::occluded;
    }
    if (front < 8) return visibility::partial;  // edge-on or behind for some positions

    // ~10 KB whose member defaults cost a memset per call (2 % of a whole-part run): one per
    // thread instead, which build_sight_hull resets; nothing here calls back into explain.
    thread_local sight_hull H;
    build_sight_hull(lo, hi, F.v, H);
    hull_traversal tr{H, *scene_, facet, F.id, info};
    scene_->tree.traversal(H, tr);
    tr.settle();
    if (info.exact_clips) scene_->exact_clips.fetch_add(info.exact_clips, std::memory_order_relaxed);
    if (!tr.blocked) return visibility::visible;
    // The searches for an OCCLUDED certificate below cost ~15× the walk above on the boxes
    // where they fail, which are most of the blocked ones; skip them when PARTIAL will do.
    if (effort == occlusion_effort::visible_only) return visibility::partial;
    const scene_triangle& first = scene_->tris[info.blocker];
    if (blocks_every_sight_line(H, first)) return visibility::occluded;
    // The wall certificates below walk the tree again; most boxes with a blocker still
    // have a free sight line, which rules every certificate out at the cost of a few
    // segment queries.
    if (some_sight_line_free(*scene_, facet, lo, hi)) return visibility::partial;
    // The wall certificate finds the rim of a wall by edges used once; in a soup a duplicated
    // or folded triangle uses a rim edge twice and would hide it, so it is for solids only.
    if (scene_->soup) return visibility::partial;
    if (planar_wall_blocks(H, *scene_, facet, first)) return visibility::occluded;
    // Try the planes of the other blocking triangles (each distinct plane once).
    std::vector<std::size_t> blockers;
    hull_traversal all{H, *scene_, facet, F.id, info};
    all.collect = &blockers;
    scene_->tree.traversal(H, all);
    const auto coplanar = [&](const scene_triangle& u, const scene_triangle& t) {
        return orient3(u.v[0], u.v[1], u.v[2], t.v[0]) == 0 && orient3(u.v[0], u.v[1], u.v[2], t.v[1]) == 0 &&
               orient3(u.v[0], u.v[1], u.v[2], t.v[2]) == 0;
    };
    std::vector<std::size_t> tried{info.blocker}, in_plane;
    for (std::size_t b : blockers) {
        const scene_triangle& T = scene_->tris[b];
        if (tried.size() > max_wall_planes) break;
        const int across = wall_plane_qualifies(H, T);
        if (across < 0) continue;
        bool seen = false;
        for (std::size_t t : tried) seen = seen || coplanar(scene_->tris[t], T);
        if (seen) continue;
        tried.push_back(b);
        // Cheap necessary condition first: each corner's sight line to the facet vertex
        // across the plane crosses a collected triangle of that plane (the only triangles
        // of the plane that can meet H, unless the collection was cut short).
        in_plane.clear();
        for (std::size_t o : blockers)
            if (coplanar(T, scene_->tris[o])) in_plane.push_back(o);
        bool all_cross = true;
        for (int c = 0; c < 8 && all_cross; ++c) {
            bool crosses = false;
            for (std::size_t o : in_plane)
                if (line_meets_closed_triangle(H.pts[c], H.pts[across], scene_->tris[o].v)) {
                    crosses = true;
                    break;
                }
            all_cross = crosses;
        }
        if (all_cross && planar_wall_blocks(H, *scene_, facet, T)) return visibility::occluded;
    }
    return visibility::partial;
}

CERTIPOSE_DECL bool aabb_occlusion::blockers(const Eigen::AlignedBox3d& box, std::size_t facet,
                                              blocker_visitor visit) const {
    using namespace detail::occ;
    const Eigen::AlignedBox3d b = checked_bounds(box, "aabb_occlusion");
    if (facet >= scene_->part_faces) throw out_of_range("facet", facet, scene_->part_faces);
    if (scene_->survey && material_in_front(scene_->survey->hidden[facet])) return false;
    const detail::round_to_nearest_scope nearest;
    const scene_triangle& F = scene_->tris[facet];
    const pt lo{b.min().x(), b.min().y(), b.min().z()};
    const pt hi{b.max().x(), b.max().y(), b.max().z()};
    // The same premise as classify's VISIBLE: every position strictly in front of the facet
    // (then a sight line meeting no other triangle runs outside every solid).
    const hplane fp = facet_plane(F.v);
    for (int k = 0; k < 8; ++k) {
        const pt c{k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]};
        if (side(fp, c) >= 0) return false;
    }
    thread_local sight_hull H;
    build_sight_hull(lo, hi, F.v, H);
    blocker_walk walk{H, *scene_, facet, F.id, visit};
    scene_->tree.traversal(H, walk);
    return !walk.stopped;
}

CERTIPOSE_DECL bool aabb_occlusion::front_clear(const Eigen::AlignedBox3d& box, std::size_t facet) const {
    using namespace detail::occ;
    const Eigen::AlignedBox3d b = checked_bounds(box, "aabb_occlusion");
    if (facet >= scene_->part_faces) throw out_of_range("facet", facet, scene_->part_faces);
    if (scene_->survey && material_in_front(scene_->survey->hidden[facet])) return false;
    const detail::round_to_nearest_scope nearest;
    const scene_triangle& F = scene_->tris[facet];
    const hplane fp = facet_plane(F.v);
    // The region every such sight line lies in: the bounding box of the box and the facet.
    pt lo{b.min().x(), b.min().y(), b.min().z()}, hi{b.max().x(), b.max().y(), b.max().z()};
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], F.lo[k]), hi[k] = std::max(hi[k], F.hi[k]);
    front_walk walk{*scene_, facet, fp, lo, hi};
    scene_->tree.traversal(CGAL::Bbox_3(lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]), walk);
    return !walk.blocked;
}

CERTIPOSE_DECL bool aabb_occlusion::sight_line_blocked(const Eigen::Vector3d& from, std::size_t facet) const {
    std::size_t no_hint = std::numeric_limits<std::size_t>::max();
    return sight_line_blocked(from, facet, no_hint);
}

CERTIPOSE_DECL bool aabb_occlusion::sight_line_blocked(const Eigen::Vector3d& from, std::size_t facet,
                                                        std::size_t& hint) const {
    using namespace detail::occ;
    if (facet >= scene_->part_faces) throw out_of_range("facet", facet, scene_->part_faces);
    if (!from.allFinite())
        throw invalid_argument("point", "aabb_occlusion: the sight line's start must be finite, got (" +
                                            detail::format_double(from.x()) + ", " + detail::format_double(from.y()) +
                                            ", " + detail::format_double(from.z()) + ")");
    if (scene_->survey && material_in_front(scene_->survey->hidden[facet])) return true;
    const detail::round_to_nearest_scope nearest;
    return !sight_line_free(*scene_, facet, epick::Point_3(from.x(), from.y(), from.z()), &hint);
}

CERTIPOSE_DECL occlusion_shadow aabb_occlusion::shadow(std::size_t facet, std::size_t triangle) const {
    using namespace detail::occ;
    if (facet >= scene_->part_faces) throw out_of_range("facet", facet, scene_->part_faces);
    if (triangle >= scene_->tris.size()) throw out_of_range("triangle", triangle, scene_->tris.size());
    const detail::round_to_nearest_scope nearest;
    occlusion_shadow s;
    s.triangle = triangle;
    add_separating_planes(scene_->tris[facet].v, scene_->tris[triangle].v, s);
    return s;
}

CERTIPOSE_DECL std::uint64_t aabb_occlusion::exact_fallbacks() const noexcept {
    return scene_->exact_clips.load(std::memory_order_relaxed);
}

}  // namespace certipose

#endif  // CERTIPOSE_DETAIL_WITH_DEFINITIONS
