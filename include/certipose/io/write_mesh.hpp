// certipose/io/write_mesh.hpp — write a triangle_mesh as an ASCII OFF file (no CGAL).
//
// `write_mesh_off` is the one writer the library needs: examples store the generated sample
// part, tools hand meshes to MeshLab/ParaView. Coordinates are written in the shortest text
// that reads back as the same double (std::to_chars), so a write + read_mesh round trip is
// exact and facet ids are preserved (faces are written in order). The file is replaced
// atomically (write_file_atomically), like every certipose writer. Reading lives in
// certipose/io/read_mesh.hpp (CGAL). Failure throws certipose::io_error naming the path.
#pragma once

#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"
#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/io/write_file.hpp"

#include <filesystem>
#include <string>

namespace certipose {

/// Writes `m` to `path` as ASCII OFF ("OFF", "V F 0", one vertex per line, "3 a b c" per face),
/// atomically replacing an existing file. Throws certipose::io_error(path) if it cannot be
/// written (missing directory, no permission, disk full).
inline void write_mesh_off(const std::filesystem::path& path, const triangle_mesh& m) {
    std::string text =
        "OFF\n" + std::to_string(m.num_vertices()) + " " + std::to_string(m.num_faces()) + " 0\n";
    for (const auto& p : m.vertices()) {
        for (int k = 0; k < 3; ++k) {
            detail::append_double(text, p[k]);
            text += k < 2 ? ' ' : '\n';
        }
    }
    for (const auto& t : m.faces())
        text += "3 " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " +
                std::to_string(t[2]) + "\n";
    write_file_atomically(path, text);
}

}  // namespace certipose
