// certipose/occlusion/mesh_survey.hpp — what an occlusion scene is made of, when it is not a
// set of clean closed solids: the declarations (no CGAL; the definitions are in
// certipose/occlusion/cgal_mesh_survey.hpp, or in certipose::precompiled).
//
// CAD exports come with overlapping bodies, duplicate shells and small open seams. A user cannot
// repair them, so the scene may be read as a *triangle soup* (`mesh_semantics::soup`): a sight
// line is blocked when it meets any triangle, and nothing is assumed about inside and outside.
// The survey says what the mesh holds (bodies, open and non-manifold edges, duplicate faces,
// intersecting faces) so that programs can warn, and which facets no camera can inspect
// although a triangle soup would let some sight lines reach them:
//
//   - `buried`: the space just in front of the facet is inside another closed body. Every
//     camera that sees it freely would sit inside material (a VISIBLE box and the space in
//     front of the facet are in one connected piece of the complement of the soup, so a
//     VISIBLE box of a buried facet lies in that body). Decided at the facet's centroid: a point
//     in front of it, closer than any other triangle of the body, tested by CGAL's
//     Side_of_triangle_mesh.
//   - `covered`: a face lies on it turned over — one with the same three vertices (two bodies
//     welded face to face), or a face of a closed body through its centroid in its plane (a body
//     resting on it, with other vertices or from another mesh): material in front. A two-sided
//     sheet (a surface exported with both sides, as twin faces) is taken as covered too: its
//     facets are skipped, which loses them but claims nothing.
//   - `duplicate`: another face, earlier in the mesh, has the same three vertices and the same
//     orientation (a duplicated shell). Solving it again would repeat that facet's answer.
//
// docs/occlusion.md#dirty-meshes says which certificates hold for which semantics.
#pragma once

#include "certipose/detail/config.hpp"
#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/occlusion/mesh_semantics.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace certipose {

/// Why no camera can inspect a facet of a triangle soup (see the header comment).
enum class hidden_facet : std::uint8_t { none, buried, covered, duplicate };

/// Whether a camera that sees the facet would sit inside material (`buried`, `covered`): the
/// occlusion policies then call it OCCLUDED from everywhere. A duplicate is seen as its original is.
constexpr bool material_in_front(hidden_facet h) noexcept {
    return h == hidden_facet::buried || h == hidden_facet::covered;
}

/// What `survey_mesh` found. Facet indices are the mesh's face indices.
struct mesh_survey {
    std::size_t faces = 0;
    std::size_t bodies = 0;             ///< connected components (faces sharing vertices)
    std::size_t closed_bodies = 0;      ///< bodies whose every edge has exactly two faces, opposed
    std::size_t inward_bodies = 0;      ///< closed bodies that enclose a negative volume
    std::size_t open_edges = 0;         ///< undirected edges of one face only
    std::size_t nonmanifold_edges = 0;  ///< undirected edges of more than two faces
    std::size_t duplicate_faces = 0;    ///< faces with the vertices of an earlier face
    std::size_t intersecting_pairs = 0; ///< pairs of faces with no common vertex that meet
    std::size_t buried = 0, covered = 0;
    /// One line per kind of defect found, naming an example ("faces 4044 and 22646 intersect").
    std::vector<std::string> examples;
    /// The intersecting pairs (lower index first), in the order found; at most the first 10^6.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> intersecting;
    /// Per face: why no camera can inspect it (`none` for most).
    std::vector<hidden_facet> hidden;
    /// Per face of a duplicate: the earlier face it repeats (else the face itself).
    std::vector<std::uint32_t> original;

    /// No defect of a triangle soup that a solid may not have (bodies may still overlap
    /// without touching edges; `intersecting_pairs` says whether they do).
    bool clean() const noexcept {
        return open_edges == 0 && nonmanifold_edges == 0 && duplicate_faces == 0 && intersecting_pairs == 0 &&
               inward_bodies == 0 && closed_bodies == bodies;
    }
    /// Why facet `f` cannot be inspected, in words; nothing when it can.
    std::optional<std::string> why_hidden(std::size_t f) const;
};

/// Surveys `m` (see the header comment). Cost: a box intersection of all faces and one
/// Side_of_triangle_mesh query per facet and closed body around it — about a second for
/// 10^5 faces.
CERTIPOSE_DECL mesh_survey survey_mesh(const triangle_mesh& m);

inline std::optional<std::string> mesh_survey::why_hidden(std::size_t f) const {
    if (f >= hidden.size()) return std::nullopt;
    switch (hidden[f]) {
        case hidden_facet::none: return std::nullopt;
        case hidden_facet::buried: return "buried inside another closed body of the mesh";
        case hidden_facet::covered:
            return "covered by a face of another body with the same vertices (material on both sides)";
        case hidden_facet::duplicate:
            return "a duplicate of facet " + std::to_string(original[f]) + " (same vertices, same orientation)";
    }
    return std::nullopt;
}

}  // namespace certipose
