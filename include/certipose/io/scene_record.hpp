// certipose/io/scene_record.hpp — what the output files record of a run's scene beyond the part
// and the camera: the external occluders added to the occlusion scene, and the camera regions
// (solver/camera_regions.hpp); and `mesh_digest`, the fingerprint they and the part are recorded
// with. No JSON library, no CGAL (io/json.hpp writes and reads the records).
//
// In the result JSON, summary.json and PLAN.json:
//   "occluders": [{"path", "scale", "faces", "digest"}, ...],
//   "keep_in": [{"box": [xmin, ymin, zmin, xmax, ymax, zmax]} | {"sphere": [x, y, z, r]}, ...],
//   "keep_out": [...]
// each an empty list when there are none; a file without them reads as none.
#pragma once

#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/solver/camera_regions.hpp"

#include <bit>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace certipose {

/// A fingerprint of a mesh (its vertex coordinates as given — scaled, if it was read with a scale
/// — bit for bit, and its faces; FNV-1a, 64 bits, as 16 hex digits): a tool reading a run's
/// boxes later checks it is given the same mesh, not merely one with as many faces.
inline std::string mesh_digest(const triangle_mesh& m) {
    std::uint64_t h = 14695981039346656037ULL;
    const auto mix = [&](std::uint64_t word) {
        for (int b = 0; b < 8; ++b) h = (h ^ ((word >> (8 * b)) & 0xffU)) * 1099511628211ULL;
    };
    mix(m.num_vertices()), mix(m.num_faces());
    for (const auto& v : m.vertices())
        for (int k = 0; k < 3; ++k) mix(std::bit_cast<std::uint64_t>(v[k]));
    for (const auto& f : m.faces())
        for (auto i : f) mix(static_cast<std::uint64_t>(i));
    static constexpr char hex[] = "0123456789abcdef";
    std::string out(16, '0');
    for (int i = 15; i >= 0; --i, h >>= 4) out[static_cast<std::size_t>(i)] = hex[h & 0xfU];
    return out;
}

/// One external occluder as the files record it.
struct occluder_record {
    std::string path;
    double scale = 1.0;
    std::size_t faces = 0;
    std::string digest{};  ///< mesh_digest of the occluder as used (after its scale)
    friend bool operator==(const occluder_record&, const occluder_record&) = default;
};

/// The record of an occluder read from `path` with `scale` (`mesh` as read, scaled).
inline occluder_record describe_occluder(std::string path, double scale, const triangle_mesh& mesh) {
    return {std::move(path), scale, mesh.num_faces(), mesh_digest(mesh)};
}

/// The scene of a run beyond the part and the camera (see the header comment).
struct scene_record {
    std::vector<occluder_record> occluders{};
    camera_regions regions{};
    bool empty() const noexcept { return occluders.empty() && regions.empty(); }
    friend bool operator==(const scene_record&, const scene_record&) = default;
};

}  // namespace certipose
