// make_sample_part — writes the procedural sample part (paper §8 stand-in) as an OFF file.
//
// Usage: make_sample_part [OUTPUT.off [MAX_CELL_SIZE]]   (default: sample_part.off, 0.014 m)
// The build runs it to produce ${CMAKE_BINARY_DIR}/examples/sample_part.off, which the other
// examples read. It prints the counts and the facet of interest on stdout. A smaller cell makes
// a finer part of the same shape: 0.014 / 3 gives about nine times the faces (~20 700), the
// whole-part benchmark's large part.
#include <certipose/geometry/sample_part.hpp>
#include <certipose/io/write_mesh.hpp>

#include <cstdio>
#include <cstdlib>
#include <exception>

int main(int argc, char** argv) {
    // An option (--help, -h) is not a file name to write the part to.
    if (argc > 3 || (argc >= 2 && argv[1][0] == '-')) {
        std::fprintf(stderr, "usage: %s [OUTPUT.off [MAX_CELL_SIZE]]\n", argv[0]);
        return 2;
    }
    const char* out = argc >= 2 ? argv[1] : "sample_part.off";
    certipose::sample_part_options options;
    if (argc == 3) {
        char* end = nullptr;
        options.max_cell_size = std::strtod(argv[2], &end);
        if (end == argv[2] || *end != '\0' || !(options.max_cell_size > 0.0)) {
            std::fprintf(stderr, "make_sample_part: MAX_CELL_SIZE must be a positive number of metres, got '%s'\n", argv[2]);
            return 2;
        }
    }
    try {
        const certipose::sample_part part = certipose::make_sample_part(options);
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
