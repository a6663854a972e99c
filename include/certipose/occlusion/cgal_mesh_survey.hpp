// certipose/occlusion/cgal_mesh_survey.hpp — the definition of `survey_mesh`
// (occlusion/mesh_survey.hpp), with CGAL's box intersection, AABB tree and
// Side_of_triangle_mesh. Compiled into certipose::precompiled, or inline header-only.
#pragma once

#include "certipose/occlusion/mesh_survey.hpp"

#if CERTIPOSE_DETAIL_WITH_DEFINITIONS

#include "certipose/occlusion/detail/cgal_scene.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <numeric>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace certipose {

namespace detail::survey {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using point = K::Point_3;

inline point to_point(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

/// Union–find over vertex ids: faces sharing a vertex are in one body.
inline std::vector<std::uint32_t> bodies_of(const triangle_mesh& m, std::size_t& count) {
    std::vector<std::uint32_t> parent(m.num_vertices());
    std::iota(parent.begin(), parent.end(), 0u);
    const auto find = [&](std::uint32_t v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    for (const auto& f : m.faces()) {
        const std::uint32_t a = find(f[0]), b = find(f[1]), c = find(f[2]);
        parent[b] = a;
        parent[find(c)] = a;
    }
    std::vector<std::uint32_t> id(m.num_vertices(), UINT32_MAX), body(m.num_faces());
    count = 0;
    for (std::size_t i = 0; i < m.num_faces(); ++i) {
        const std::uint32_t r = find(m.faces()[i][0]);
        if (id[r] == UINT32_MAX) id[r] = static_cast<std::uint32_t>(count++);
        body[i] = id[r];
    }
    return body;
}

/// One closed body: its faces as a CGAL surface mesh and the AABB tree that the closest-point
/// and side-of queries share.
struct closed_body {
    using mesh = CGAL::Surface_mesh<point>;
    using primitive = CGAL::AABB_face_graph_triangle_primitive<mesh>;
    using tree_type = CGAL::AABB_tree<CGAL::AABB_traits<K, primitive>>;
    std::uint32_t id = 0;
    std::unique_ptr<mesh> sm = std::make_unique<mesh>();  // the tree points into it: it must not move
    std::unique_ptr<tree_type> tree;
    CGAL::Bbox_3 box;
};

/// Whether a face of `body` within a hair of point `p` lies in the plane of (a, b, c) and faces
/// the other way (exact coplanarity; the orientation from the normals, which are parallel then).
inline bool resting_on(const closed_body& body, const point& p, double scale, const point& a, const point& b,
                       const point& c, const Eigen::Vector3d& normal) {
    const double h = 1e-9 * scale;
    const CGAL::Bbox_3 near(p.x() - h, p.y() - h, p.z() - h, p.x() + h, p.y() + h, p.z() + h);
    std::vector<closed_body::mesh::Face_index> faces;
    body.tree->all_intersected_primitives(near, std::back_inserter(faces));
    for (const auto fd : faces) {
        std::array<point, 3> g;
        int k = 0;
        for (const auto v : CGAL::vertices_around_face(body.sm->halfedge(fd), *body.sm)) g[k++] = body.sm->point(v);
        bool coplanar = true;
        for (const point& x : g) coplanar = coplanar && CGAL::orientation(a, b, c, x) == CGAL::COPLANAR;
        if (!coplanar) continue;
        const Eigen::Vector3d ga(g[0].x(), g[0].y(), g[0].z()), gb(g[1].x(), g[1].y(), g[1].z()),
            gc(g[2].x(), g[2].y(), g[2].z());
        if ((gb - ga).cross(gc - ga).dot(normal) < 0) return true;
    }
    return false;
}

}  // namespace detail::survey

CERTIPOSE_DECL mesh_survey survey_mesh(const triangle_mesh& m) {
    using namespace detail::survey;
    mesh_survey s;
    const std::size_t n = m.num_faces();
    const auto& F = m.faces();
    const auto& V = m.vertices();
    s.faces = n;
    s.hidden.assign(n, hidden_facet::none);
    s.original.resize(n);
    std::iota(s.original.begin(), s.original.end(), 0u);

    std::vector<std::uint32_t> body = bodies_of(m, s.bodies);
    std::vector<std::size_t> first_face(s.bodies, n);
    for (std::size_t i = n; i-- > 0;) first_face[body[i]] = i;

    // Edges: (undirected key, directed?) sorted, counted.
    std::vector<std::uint64_t> directed, undirected;
    directed.reserve(3 * n);
    undirected.reserve(3 * n);
    for (const auto& f : F)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = f[k], b = f[(k + 1) % 3];
            directed.push_back(detail::mesh::edge_key(a, b));
            undirected.push_back(detail::mesh::edge_key(std::min(a, b), std::max(a, b)));
        }
    std::vector<std::uint64_t> d_sorted = directed, u_sorted = undirected;
    std::sort(d_sorted.begin(), d_sorted.end());
    std::sort(u_sorted.begin(), u_sorted.end());
    const auto count = [](const std::vector<std::uint64_t>& v, std::uint64_t key) {
        const auto [lo, hi] = std::equal_range(v.begin(), v.end(), key);
        return static_cast<std::size_t>(hi - lo);
    };
    std::optional<std::string> open_example, nonmanifold_example;
    for (std::size_t i = 0; i < u_sorted.size();) {
        std::size_t j = i;
        while (j < u_sorted.size() && u_sorted[j] == u_sorted[i]) ++j;
        const auto edge_text = [&] {
            return "edge (" + std::to_string(u_sorted[i] >> 32) + ", " + std::to_string(u_sorted[i] & 0xffffffffu) + ")";
        };
        if (j - i == 1) {
            ++s.open_edges;
            if (!open_example) open_example = edge_text() + " has one face (an open seam)";
        } else if (j - i > 2) {
            ++s.nonmanifold_edges;
            if (!nonmanifold_example) nonmanifold_example = edge_text() + " has " + std::to_string(j - i) + " faces";
        }
        i = j;
    }
    // A body is closed when each of its edges has one face each way.
    std::vector<char> body_closed(s.bodies, 1);
    for (std::size_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = F[i][k], b = F[i][(k + 1) % 3];
            if (count(d_sorted, detail::mesh::edge_key(a, b)) != 1 || count(d_sorted, detail::mesh::edge_key(b, a)) != 1)
                body_closed[body[i]] = 0;
        }

    // Duplicates: faces with the vertex set of an earlier face.
    {
        std::map<std::array<std::uint32_t, 3>, std::uint32_t> first;
        std::optional<std::string> example;
        for (std::size_t i = 0; i < n; ++i) {
            std::array<std::uint32_t, 3> key{F[i][0], F[i][1], F[i][2]};
            std::sort(key.begin(), key.end());
            const auto [it, fresh] = first.emplace(key, static_cast<std::uint32_t>(i));
            if (fresh) continue;
            ++s.duplicate_faces;
            const auto& o = F[it->second];
            // Same orientation: (a, b, c) is a rotation of the original's vertex order.
            bool same = false;
            for (int r = 0; r < 3; ++r)
                same = same || (F[i][0] == o[r] && F[i][1] == o[(r + 1) % 3] && F[i][2] == o[(r + 2) % 3]);
            if (same) {
                s.hidden[i] = hidden_facet::duplicate;
                s.original[i] = it->second;
            } else {
                s.hidden[i] = s.hidden[it->second] = hidden_facet::covered;
            }
            if (!example)
                example = "faces " + std::to_string(it->second) + " and " + std::to_string(i) + " have the same vertices" +
                          (same ? "" : " and face each other");
        }
        if (example) s.examples.push_back(*example);
    }
    if (open_example) s.examples.push_back(*open_example);
    if (nonmanifold_example) s.examples.push_back(*nonmanifold_example);

    // Intersecting faces with no common vertex (box intersection, then CGAL's exact predicate).
    {
        using box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::uint32_t>;
        std::vector<box> boxes;
        boxes.reserve(n);
        std::vector<K::Triangle_3> tris;
        tris.reserve(n);
        for (std::size_t i = 0; i < n; ++i) {
            tris.emplace_back(to_point(V[F[i][0]]), to_point(V[F[i][1]]), to_point(V[F[i][2]]));
            boxes.emplace_back(tris.back().bbox(), static_cast<std::uint32_t>(i));
        }
        std::optional<std::pair<std::uint32_t, std::uint32_t>> example;
        CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const box& a, const box& b) {
            const auto& fa = F[a.info()];
            const auto& fb = F[b.info()];
            for (auto x : fa)
                for (auto y : fb)
                    if (x == y) return;
            if (!CGAL::do_intersect(tris[a.info()], tris[b.info()])) return;
            ++s.intersecting_pairs;
            const std::pair<std::uint32_t, std::uint32_t> p{std::min(a.info(), b.info()), std::max(a.info(), b.info())};
            if (s.intersecting.size() < 1'000'000) s.intersecting.push_back(p);
            if (!example || p < *example) example = p;
        });
        if (example)
            s.examples.push_back("faces " + std::to_string(example->first) + " and " + std::to_string(example->second) +
                                 " intersect (" + std::to_string(s.intersecting_pairs) + " pairs)");
    }

    // Closed bodies: orientation, and the facets buried inside them.
    std::vector<detail::survey::closed_body> closed;
    {
        std::vector<std::vector<std::uint32_t>> faces_of(s.bodies);
        for (std::size_t i = 0; i < n; ++i) faces_of[body[i]].push_back(static_cast<std::uint32_t>(i));
        std::optional<std::string> inward_example;
        for (std::uint32_t b = 0; b < s.bodies; ++b) {
            if (!body_closed[b]) continue;
            ++s.closed_bodies;
            // Signed volume (6×), in doubles: only its sign is used, for a warning and to skip
            // the body as a container.
            double volume = 0;
            for (std::uint32_t f : faces_of[b])
                volume += V[F[f][0]].dot(V[F[f][1]].cross(V[F[f][2]]));
            if (volume < 0) {
                ++s.inward_bodies;
                if (!inward_example)
                    inward_example = "the closed body of face " + std::to_string(faces_of[b].front()) +
                                     " faces inward (negative volume)";
            }
            if (!(volume > 0)) continue;  // inward, or flat (a two-sided sheet): holds no material
            closed_body cb;
            cb.id = b;
            // Sparse: an assembly of 10^4 bodies must not cost 10^4 maps of every vertex.
            std::unordered_map<std::uint32_t, closed_body::mesh::Vertex_index> map;
            bool ok = true;
            for (std::uint32_t f : faces_of[b]) {
                std::array<closed_body::mesh::Vertex_index, 3> h;
                for (int k = 0; k < 3; ++k) {
                    const auto [slot, fresh] = map.try_emplace(F[f][k]);
                    if (fresh) slot->second = cb.sm->add_vertex(to_point(V[F[f][k]]));
                    h[k] = slot->second;
                }
                ok = ok && cb.sm->add_face(h[0], h[1], h[2]) != closed_body::mesh::null_face();
            }
            if (!ok || !CGAL::is_closed(*cb.sm)) continue;  // a non-manifold vertex: no side-of test
            cb.tree = std::make_unique<closed_body::tree_type>(faces(*cb.sm).first, faces(*cb.sm).second, *cb.sm);
            cb.tree->accelerate_distance_queries();
            cb.box = cb.tree->bbox();
            closed.push_back(std::move(cb));
        }
        if (inward_example) s.examples.push_back(*inward_example);
    }
    if (!closed.empty() && s.bodies > 1) {
        std::vector<CGAL::Side_of_triangle_mesh<closed_body::mesh, K>> sides;
        sides.reserve(closed.size());
        for (const auto& cb : closed) sides.emplace_back(*cb.tree);
        std::optional<std::string> example;
        for (std::size_t i = 0; i < n; ++i) {
            if (s.hidden[i] != hidden_facet::none) continue;
            const Eigen::Vector3d a = V[F[i][0]], b = V[F[i][1]], c = V[F[i][2]];
            const Eigen::Vector3d centre = (a + b + c) / 3.0;
            const Eigen::Vector3d normal = (b - a).cross(c - a).normalized();
            for (std::size_t k = 0; k < closed.size(); ++k) {
                const closed_body& cb = closed[k];
                if (cb.id == body[i]) continue;
                const point pc = to_point(centre);
                if (pc.x() < cb.box.xmin() || pc.x() > cb.box.xmax() || pc.y() < cb.box.ymin() ||
                    pc.y() > cb.box.ymax() || pc.z() < cb.box.zmin() || pc.z() > cb.box.zmax())
                    continue;
                // A point in front of the centroid, closer than any face of the body: the
                // segment to it meets none, so it is on the side the facet's front is on.
                const double d = std::sqrt(CGAL::to_double(cb.tree->squared_distance(pc)));
                const double scale = std::max({a.norm(), b.norm(), c.norm(), 1e-300});
                if (!(d > 1e-12 * scale)) {
                    // The centroid is on the body. A face of it lying in the facet's plane,
                    // turned over, means the body rests on the facet: material in front (a
                    // contact with other vertices than the facet's, or across meshes). A face
                    // through it at an angle pierces the facet: left to the soup's sight lines.
                    if (resting_on(cb, pc, scale, to_point(a), to_point(b), to_point(c), normal)) {
                        s.hidden[i] = hidden_facet::covered;
                        break;
                    }
                    continue;
                }
                const point q = to_point(centre + 0.5 * d * normal);
                if (sides[k](q) == CGAL::ON_BOUNDED_SIDE) {
                    s.hidden[i] = hidden_facet::buried;
                    ++s.buried;
                    if (!example)
                        example = "facet " + std::to_string(i) + " is buried inside the body of face " +
                                  std::to_string(first_face[cb.id]);
                    break;
                }
            }
        }
        if (example) s.examples.push_back(*example);
    }
    // A duplicate is seen as its original is: buried or covered with it.
    for (std::size_t i = 0; i < n; ++i)
        if (s.hidden[i] == hidden_facet::duplicate && material_in_front(s.hidden[s.original[i]])) {
            s.hidden[i] = s.hidden[s.original[i]];
            s.buried += s.hidden[i] == hidden_facet::buried;
        }
    for (auto h : s.hidden) s.covered += h == hidden_facet::covered;
    return s;
}

}  // namespace certipose

#endif  // CERTIPOSE_DETAIL_WITH_DEFINITIONS
