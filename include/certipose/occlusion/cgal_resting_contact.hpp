// certipose/occlusion/cgal_resting_contact.hpp — the definition of `resting_on_occluders`
// (occlusion/resting_contact.hpp), with CGAL's exact predicates. Compiled into
// certipose::precompiled, or inline header-only.
#pragma once

#include "certipose/occlusion/resting_contact.hpp"

#if CERTIPOSE_DETAIL_WITH_DEFINITIONS

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cstddef>
#include <span>
#include <vector>

namespace certipose {

namespace detail::contact {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
inline K::Point_3 point(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

/// `p`, coplanar with the non-degenerate triangle abc, lies in its closed triangle.
inline bool in_closed_triangle(const K::Point_3& a, const K::Point_3& b, const K::Point_3& c, const K::Point_3& p) {
    return CGAL::coplanar_orientation(a, b, c, p) != CGAL::NEGATIVE &&
           CGAL::coplanar_orientation(b, c, a, p) != CGAL::NEGATIVE &&
           CGAL::coplanar_orientation(c, a, b, p) != CGAL::NEGATIVE;
}
}  // namespace detail::contact

CERTIPOSE_DECL std::vector<char> resting_on_occluders(const triangle_mesh& part, std::span<const triangle_mesh> occluders,
                                                      const std::vector<char>& ask) {
    using namespace detail::contact;
    std::vector<char> out(part.num_faces(), 0);
    struct held {
        K::Point_3 a, b, c;
        Eigen::AlignedBox3d bbox;
    };
    std::vector<held> under;
    for (const triangle_mesh& m : occluders)
        for (std::size_t i = 0; i < m.num_faces(); ++i) {
            const facet& t = m.facet(i);
            held h{point(t.v[0]), point(t.v[1]), point(t.v[2]), t.bbox};
            if (!CGAL::collinear(h.a, h.b, h.c)) under.push_back(h);
        }
    if (under.empty()) return out;
    for (std::size_t f = 0; f < part.num_faces(); ++f) {
        if (!ask.empty() && !ask[f]) continue;
        const facet& fa = part.facet(f);
        const K::Point_3 v[3] = {point(fa.v[0]), point(fa.v[1]), point(fa.v[2])};
        if (CGAL::collinear(v[0], v[1], v[2])) continue;
        bool corner_held[3] = {false, false, false};
        for (const held& t : under) {
            if (!t.bbox.intersects(fa.bbox)) continue;
            if (CGAL::orientation(t.a, t.b, t.c, v[0]) != CGAL::COPLANAR ||
                CGAL::orientation(t.a, t.b, t.c, v[1]) != CGAL::COPLANAR ||
                CGAL::orientation(t.a, t.b, t.c, v[2]) != CGAL::COPLANAR)
                continue;
            // Coplanar: the two orientations in the common plane differ exactly when the normals
            // are opposite, i.e. the facet faces into the occluder.
            if (CGAL::coplanar_orientation(t.a, t.b, t.c) == CGAL::coplanar_orientation(v[0], v[1], v[2])) continue;
            for (int k = 0; k < 3; ++k)
                if (!corner_held[k] && in_closed_triangle(t.a, t.b, t.c, v[k])) corner_held[k] = true;
            if (corner_held[0] && corner_held[1] && corner_held[2]) break;
        }
        out[f] = corner_held[0] && corner_held[1] && corner_held[2];
    }
    return out;
}

}  // namespace certipose

#endif
