// libFuzzer harness of read_mesh for one format: CERTIPOSE_FUZZ_EXTENSION (".off", ".obj",
// ".ply" or ".stl") is the extension of the scratch file, which chooses CGAL's reader. A mesh
// that comes back must be what triangle_mesh promises: faces, finite vertices, indices in range.
#include "harness.hpp"

#include <certipose/io/read_mesh.hpp>

#include <cmath>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const certipose_fuzz::scratch_file file(std::string("input") + CERTIPOSE_FUZZ_EXTENSION);
    const auto& path = file.write(data, size);
    certipose_fuzz::accept_certipose_errors([&] {
        const certipose::triangle_mesh m = certipose::read_mesh(path);
        certipose_fuzz::require(m.num_faces() > 0 && m.num_vertices() > 0);
        for (const auto& v : m.vertices()) certipose_fuzz::require(v.allFinite());
        for (const auto& f : m.faces())
            for (auto i : f) certipose_fuzz::require(i < m.num_vertices());
    });
    return 0;
}
