// inspect_facet — load a mesh, print one facet's data and the case-study camera's quantities.
//
// Usage: inspect_facet [MESH] [FACET]
//   MESH   .off/.obj/.ply/.stl in metres (default: the sample part generated at build time)
//   FACET  facet index (default: the sample part's facet of interest)
#include <certipose/camera/thin_lens_camera.hpp>
#include <certipose/geometry/sample_part.hpp>
#include <certipose/io/read_mesh.hpp>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <numbers>
#include <string>

#ifndef CERTIPOSE_SAMPLE_PART_OFF
#define CERTIPOSE_SAMPLE_PART_OFF "sample_part.off"
#endif

namespace {

void print_vector(const char* label, const Eigen::Vector3d& v) {
    std::printf("  %-9s (%.9g, %.9g, %.9g)\n", label, v.x(), v.y(), v.z());
}

}  // namespace

int main(int argc, char** argv) {
    if (argc > 3) {
        std::fprintf(stderr, "usage: %s [MESH] [FACET]\n", argv[0]);
        return 2;
    }
    try {
        const std::string path = argc >= 2 ? argv[1] : CERTIPOSE_SAMPLE_PART_OFF;
        std::size_t facet_id = certipose::make_sample_part().facet_of_interest;
        if (argc == 3) {
            char* end = nullptr;
            const unsigned long long id = std::strtoull(argv[2], &end, 10);
            if (end == argv[2] || *end != '\0' || argv[2][0] == '-') {
                std::fprintf(stderr,
                             "inspect_facet: FACET must be a non-negative integer, got '%s'\n",
                             argv[2]);
                return 2;
            }
            facet_id = static_cast<std::size_t>(id);
        }

        const certipose::triangle_mesh mesh = certipose::read_mesh(path);
        std::printf(
            "%s: %zu vertices, %zu faces, %s\n", path.c_str(), mesh.num_vertices(),
            mesh.num_faces(),
            certipose::is_closed_manifold(mesh) ? "closed manifold" : "NOT closed manifold");

        const certipose::facet& f = mesh.facet(facet_id);  // throws out_of_range
        std::printf("facet %zu\n", facet_id);
        print_vector("v1", f.v[0]);
        print_vector("v2", f.v[1]);
        print_vector("v3", f.v[2]);
        print_vector("normal", f.normal);
        print_vector("centroid", f.centroid);
        std::printf("  %-9s %.9g m^2\n", "area", f.area);

        // The paper's case-study camera (examples/data/camera.json).
        const certipose::thin_lens_camera camera({.focal_length = 0.012,
                                                  .f_stop = 8,
                                                  .focus_distance = 0.6,
                                                  .max_blur_circle = 6.9e-6,
                                                  .pixel_pitch = 3.45e-6,
                                                  .width_px = 2448,
                                                  .height_px = 2048});
        const Eigen::Matrix3d k = camera.intrinsics();
        std::printf("camera (thin lens, f = 12 mm, N = 8, focused at 0.6 m)\n  K =\n");
        for (int r = 0; r < 3; ++r)
            std::printf("    [%10.3f %10.3f %10.3f]\n", k(r, 0), k(r, 1), k(r, 2));
        const auto fov = camera.fov_half_angles();
        const double deg = 180 / std::numbers::pi;
        std::printf("  FOV half-angles: %.6f rad (%.2f deg) x %.6f rad (%.2f deg)\n",
                    fov.horizontal, fov.horizontal * deg, fov.vertical, fov.vertical * deg);
        const auto range = camera.distance_range();
        std::printf("  in focus: [d_min, d_max] = [%.6f, %.6f] m\n", range.min, range.max);
        // Where a head-on camera at mid-range would sit (constraints 2-4 hold there).
        print_vector("head-on", f.centroid + f.normal * ((range.min + range.max) / 2));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "inspect_facet: %s\n", e.what());
        return 1;
    }
    return 0;
}
