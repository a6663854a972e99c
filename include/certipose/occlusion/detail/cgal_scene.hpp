// certipose/occlusion/detail/cgal_scene.hpp — scene meshes as CGAL surface meshes, validated
// once per policy (not for users; needs CGAL).
//
// Both occlusion policies reason about closed solids: "behind the facet" means "inside the
// part", and the boolean difference needs closed, self-intersection-free operands. So every
// scene mesh (the part and each occluder) must be closed, edge-manifold, consistently oriented,
// free of self-intersections and bound a volume with outward normals. The checks run in the
// order their preconditions require (STYLE.md: with NDEBUG, does_bound_a_volume says true for
// an open mesh, so closedness is checked first) and throw certipose::mesh_error naming the
// mesh ("part", "occluder 2") and the offending edge or faces.
#pragma once

#include "certipose/error.hpp"
#include "certipose/geometry/triangle_mesh.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace certipose::detail::occ {

/// The mesh as a CGAL Surface_mesh (referenced vertices only; face i of the result is face i
/// of `m`). Throws mesh_error when CGAL refuses a face (a non-manifold vertex or edge).
template <class Point>
CGAL::Surface_mesh<Point> to_surface_mesh(const triangle_mesh& m, const std::string& who) {
    using mesh = CGAL::Surface_mesh<Point>;
    using vd = typename mesh::Vertex_index;
    mesh sm;
    std::vector<vd> map(m.num_vertices(), mesh::null_vertex());
    for (const auto& f : m.faces())
        for (auto i : f)
            if (map[i] == mesh::null_vertex()) {
                const auto& p = m.vertices()[i];
                map[i] = sm.add_vertex(Point(p.x(), p.y(), p.z()));
            }
    for (std::size_t i = 0; i < m.num_faces(); ++i) {
        const auto& f = m.faces()[i];
        if (sm.add_face(map[f[0]], map[f[1]], map[f[2]]) == mesh::null_face())
            throw mesh_error(who + ": face " + std::to_string(i) +
                             " makes the mesh non-manifold (CGAL cannot add it)");
    }
    return sm;
}

/// Throws certipose::mesh_error unless `m` is a closed, self-intersection-free, outward
/// oriented solid (see the header comment). `who` names the mesh in messages.
inline void validate_solid(const triangle_mesh& m, const std::string& who) {
    namespace PMP = CGAL::Polygon_mesh_processing;
    using K = CGAL::Exact_predicates_inexact_constructions_kernel;  // exact predicates
    if (auto why = detail::mesh::closed_manifold_violation(m); !why.empty())
        throw mesh_error(who + ": mesh is not a closed manifold: " + why);
    const auto sm = to_surface_mesh<K::Point_3>(m, who);
    if (!CGAL::is_closed(sm)) throw mesh_error(who + ": mesh is not closed");
    if (PMP::does_self_intersect(sm)) {
        using fd = CGAL::Surface_mesh<K::Point_3>::Face_index;
        std::vector<std::pair<fd, fd>> pairs;
        PMP::self_intersections(sm, std::back_inserter(pairs));
        std::string which;
        if (!pairs.empty())
            which = " (e.g. faces " + std::to_string(static_cast<std::size_t>(pairs.front().first)) +
                    " and " + std::to_string(static_cast<std::size_t>(pairs.front().second)) + ", " +
                    std::to_string(pairs.size()) + " intersecting pairs)";
        throw mesh_error(who + ": mesh self-intersects" + which);
    }
    // does_bound_a_volume accepts a consistently inward-facing mesh (it bounds the
    // complement); the outermost shell must face outward.
    if (!PMP::does_bound_a_volume(sm) || !PMP::is_outward_oriented(sm))
        throw mesh_error(who + ": mesh does not bound a volume (inward-facing normals, or "
                               "nested shells with inconsistent orientation)");
}

}  // namespace certipose::detail::occ
