// make_sample_part — writes the procedural sample part (paper §8 stand-in) as an OFF file.
//
// Usage: make_sample_part [OUTPUT.off]   (default: sample_part.off)
// The build runs it to produce ${CMAKE_BINARY_DIR}/examples/sample_part.off, which the other
// examples read. It prints the counts and the facet of interest on stdout.
#include <certipose/geometry/sample_part.hpp>
#include <certipose/io/write_mesh.hpp>

#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
    if (argc > 2) {
        std::fprintf(stderr, "usage: %s [OUTPUT.off]\n", argv[0]);
        return 2;
    }
    const char* out = argc == 2 ? argv[1] : "sample_part.off";
    try {
        const certipose::sample_part part = certipose::make_sample_part();
        certipose::write_mesh_off(out, part.mesh);
        const auto& foi = part.mesh.facet(part.facet_of_interest);
        std::printf("%s: %zu vertices, %zu faces, genus %d, volume %.9g m^3\n", out,
                    part.mesh.num_vertices(), part.mesh.num_faces(), part.genus, part.volume);
        std::printf("facet of interest: %zu, centroid (%g, %g, %g)\n", part.facet_of_interest,
                    foi.centroid.x(), foi.centroid.y(), foi.centroid.z());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "make_sample_part: %s\n", e.what());
        return 1;
    }
    return 0;
}
