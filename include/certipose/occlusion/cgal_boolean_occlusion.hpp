// certipose/occlusion/cgal_boolean_occlusion.hpp — `boolean_occlusion`, the paper's
// occlusion test (§6.3, Algorithm 2) with exact CGAL booleans.
//
// The camera mesh H is the convex hull of the 8 box corners and the 3 facet vertices, built
// with the exact kernel (EPECK; STYLE.md: inexact hulls are wrong on nearly coplanar input).
// The scene is subtracted with CGAL's corefinement (each solid in turn, on copies: corefinement
// modifies its operands), and the result R is classified:
//   VISIBLE  — R is H unchanged: the same exact volume and no vertex that is not a vertex of H
//              (corefinement imprints every contact, even a surface merely touching ∂H, as new
//              vertices, so this also rejects sight lines grazing the scene along ∂H), and the
//              box lies strictly in front of the facet plane (a position in or behind that plane
//              sees the facet edge-on or from behind).
//   OCCLUDED — R is empty; or (Algorithm 2 line 17) H minus the part has lost a facet vertex,
//              which happens only when no box point is in front of the facet; or no connected
//              volume of R touches both the box and the facet. The last is the paper's
//              "box and facet vertices disconnected" made exact: a free sight line lies in R and
//              joins a box point to a facet point, so it would make one volume touch both
//              (touching is tested exactly on R's triangles against the closed box and facet).
//   PARTIAL  — otherwise; also when H is flat (the box lies in the facet plane) or CGAL reports
//              that the difference is not a 2-manifold (the scene meets H in an edge or vertex
//              contact), both undecidable here but harmless: the paver bisects.
// This is deliberately the slow reference (milliseconds per box); aabb_occlusion is the fast
// certified test. Blind spot of any regularized boolean, documented in docs/occlusion.md: a
// scene face lying exactly in a face of H with all its contact corners at vertices of H.
//
// The class is declared in occlusion/boolean_occlusion.hpp (no CGAL); this header defines it,
// unless CERTIPOSE_PRECOMPILED says the certipose::precompiled library does (detail/config.hpp).
// Built once per scene: validates every mesh (detail/cgal_scene.hpp) and keeps an exact copy.
// `classify` is const and thread-safe (CGAL 5.5's lazy exact kernel is thread-safe with
// CGAL_HAS_THREADS, the default; each call works on its own copies).
#pragma once

#include "certipose/occlusion/boolean_occlusion.hpp"

#if CERTIPOSE_DETAIL_WITH_DEFINITIONS

#include "certipose/error.hpp"
#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/interval/detail/fenv.hpp"
#include "certipose/occlusion/concept.hpp"
#include "certipose/occlusion/detail/box_bounds.hpp"
#include "certipose/occlusion/detail/cgal_scene.hpp"
#include "certipose/occlusion/detail/exact_geometry.hpp"
#include "certipose/pose/pose_box.hpp"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <Eigen/Geometry>

#include <array>
#include <cstddef>
#include <exception>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace certipose {

namespace detail::occ {

struct boolean_scene {
    using kernel = CGAL::Exact_predicates_exact_constructions_kernel;
    using mesh = CGAL::Surface_mesh<kernel::Point_3>;
    std::vector<mesh> solids;                  ///< part first, then occluders (exact copies)
    std::vector<Eigen::AlignedBox3d> bboxes;   ///< double bounding boxes, for quick rejection
    std::vector<std::array<pt, 3>> facets;     ///< part facets
};
using exact_kernel = boolean_scene::kernel;
using exact_mesh = boolean_scene::mesh;

template <class Mesh, class Point>
bool has_vertex(const Mesh& m, const Point& p) {
    for (auto v : m.vertices())
        if (m.point(v) == p) return true;
    return false;
}

/// Same exact volume and every vertex of `r` a vertex of `hull`.
template <class Mesh>
bool unchanged(const Mesh& r, const Mesh& hull) {
    namespace PMP = CGAL::Polygon_mesh_processing;
    for (auto v : r.vertices())
        if (!has_vertex(hull, r.point(v))) return false;
    return PMP::volume(r) == PMP::volume(hull);
}

template <class Mesh>
bool box_and_facet_connected(Mesh& r, const Eigen::AlignedBox3d& b, const std::array<pt, 3>& f) {
    namespace PMP = CGAL::Polygon_mesh_processing;
    using fd = typename Mesh::Face_index;
    using K = typename CGAL::Kernel_traits<typename Mesh::Point>::Kernel;
    using point = typename K::Point_3;
    using triangle = typename K::Triangle_3;
    auto [vol, created] = r.template add_property_map<fd, std::size_t>("f:certipose_volume", 0);
    const std::size_t nv = PMP::volume_connected_components(r, vol);
    const typename K::Iso_cuboid_3 cuboid(b.min().x(), b.min().y(), b.min().z(), b.max().x(), b.max().y(),
                                          b.max().z());
    const triangle facet(point(f[0][0], f[0][1], f[0][2]), point(f[1][0], f[1][1], f[1][2]),
                         point(f[2][0], f[2][1], f[2][2]));
    std::vector<char> meets_box(nv, 0), meets_facet(nv, 0);
    for (fd face : r.faces()) {
        const std::size_t id = vol[face];
        if (id >= nv || (meets_box[id] && meets_facet[id])) continue;
        auto h = r.halfedge(face);
        const triangle t(r.point(r.target(h)), r.point(r.target(r.next(h))), r.point(r.source(h)));
        if (!meets_box[id] && CGAL::do_intersect(t, cuboid)) meets_box[id] = 1;
        if (!meets_facet[id] && CGAL::do_intersect(t, facet)) meets_facet[id] = 1;
        if (meets_box[id] && meets_facet[id]) return true;
    }
    return false;
}

}  // namespace detail::occ

template <class Lazy>
basic_boolean_occlusion<Lazy>::basic_boolean_occlusion(const triangle_mesh& part) : basic_boolean_occlusion(part, {}) {}

template <class Lazy>
basic_boolean_occlusion<Lazy>::basic_boolean_occlusion(const triangle_mesh& part,
                                                  std::span<const triangle_mesh> occluders) {
    auto s = std::make_shared<scene>();
    try {
        detail::occ::validate_solid(part, "boolean_occlusion: part");
        for (std::size_t i = 0; i < occluders.size(); ++i)
            detail::occ::validate_solid(occluders[i], "boolean_occlusion: occluder " + std::to_string(i));
    } catch (const mesh_error& e) {
        throw mesh_error(std::string(e.what()) + "; the boolean test subtracts solids, so it needs closed, "
                                                 "edge-manifold, self-intersection-free, outward-facing meshes; "
                                                 "aabb_occlusion (--occlusion aabb) also reads a triangle soup");
    }
    s->solids.push_back(detail::occ::to_surface_mesh<detail::occ::exact_kernel::Point_3>(part, "boolean_occlusion: part"));
    s->bboxes.push_back(part.bbox());
    for (std::size_t i = 0; i < occluders.size(); ++i) {
        s->solids.push_back(detail::occ::to_surface_mesh<detail::occ::exact_kernel::Point_3>(
            occluders[i], "boolean_occlusion: occluder " + std::to_string(i)));
        s->bboxes.push_back(occluders[i].bbox());
    }
    for (const auto& f : part.facets())
        s->facets.push_back({detail::occ::pt{f.v[0].x(), f.v[0].y(), f.v[0].z()},
                             detail::occ::pt{f.v[1].x(), f.v[1].y(), f.v[1].z()},
                             detail::occ::pt{f.v[2].x(), f.v[2].y(), f.v[2].z()}});
    scene_ = std::move(s);
}

template <class Lazy>
visibility basic_boolean_occlusion<Lazy>::classify(const Eigen::AlignedBox3d& box, std::size_t facet) const {
    namespace PMP = CGAL::Polygon_mesh_processing;
    using detail::occ::pt;
    using point = detail::occ::exact_kernel::Point_3;
    using mesh = detail::occ::exact_mesh;
    using detail::occ::box_and_facet_connected;
    using detail::occ::has_vertex;
    using detail::occ::unchanged;
    const Eigen::AlignedBox3d b = detail::occ::checked_bounds(box, "boolean_occlusion");
    const auto& sc = *scene_;
    if (facet >= sc.facets.size()) throw out_of_range("facet", facet, sc.facets.size());
    const detail::round_to_nearest_scope nearest;
    const std::array<pt, 3>& f = sc.facets[facet];

    std::array<pt, 8> corners{};
    int front = 0, on_plane = 0;
    for (int k = 0; k < 8; ++k) {
        corners[k] = {k & 1 ? b.max().x() : b.min().x(), k & 2 ? b.max().y() : b.min().y(),
                      k & 4 ? b.max().z() : b.min().z()};
        const int s = detail::occ::orient3(f[0], f[1], f[2], corners[k]);
        front += s > 0, on_plane += s == 0;
    }
    if (on_plane == 8) return visibility::partial;  // H is flat: no volume to subtract from

    try {
        // Algorithm 2 line 1: the camera mesh.
        std::vector<point> pts;
        for (const pt& c : corners) pts.emplace_back(c[0], c[1], c[2]);
        for (const pt& v : f) pts.emplace_back(v[0], v[1], v[2]);
        mesh hull;
        CGAL::convex_hull_3(pts.begin(), pts.end(), hull);
        Eigen::AlignedBox3d hb = b;
        for (const pt& v : f) hb.extend(Eigen::Vector3d(v[0], v[1], v[2]));

        // Line 3: subtract the scene, one solid at a time.
        mesh result = hull;
        for (std::size_t k = 0; k < sc.solids.size(); ++k) {
            if (!sc.bboxes[k].intersects(hb)) continue;
            mesh solid = sc.solids[k];  // corefinement refines both operands
            mesh out;
            // No throw_on_self_intersection: every operand is free of self-intersections
            // (the scene was checked once, H is convex, results of corefinement are valid),
            // and the per-call check doubles the cost.
            if (!PMP::corefine_and_compute_difference(result, solid, out))
                return visibility::partial;  // the difference is not a 2-manifold
            result = std::move(out);
            if (result.number_of_faces() == 0) return visibility::occluded;
            // Line 17: a facet vertex gone from H minus the part.
            if (k == 0)
                for (const pt& v : f)
                    if (!has_vertex(result, point(v[0], v[1], v[2]))) return visibility::occluded;
        }
        if (result.number_of_faces() == 0) return visibility::occluded;

        // Lines 4–6: unchanged → visible.
        if (front == 8 && unchanged(result, hull)) return visibility::visible;

        // Lines 10–25: does one connected volume touch both the box and the facet?
        return box_and_facet_connected(result, b, f) ? visibility::partial
                                                     : visibility::occluded;
    } catch (const certipose::error&) {
        throw;
    } catch (const std::exception& e) {
        throw geometry_error(std::string("boolean_occlusion: CGAL failed on facet ") +
                             std::to_string(facet) + ": " + e.what());
    }
}

}  // namespace certipose

#endif  // CERTIPOSE_DETAIL_WITH_DEFINITIONS
