// docs/geometry.md — build the sample part, check it, and look at its facet of interest.
#include <certipose/certipose.hpp>

#include <cstdio>

int main() {
    const certipose::sample_part part = certipose::make_sample_part();  // metres
    const certipose::triangle_mesh& mesh = part.mesh;
    certipose::validate_closed_manifold(mesh);  // throws certipose::mesh_error naming an edge

    std::printf("%zu vertices, %zu faces, genus %d (Euler characteristic %ld)\n",
                mesh.num_vertices(), mesh.num_faces(), part.genus,
                certipose::euler_characteristic(mesh));
    std::printf("volume %.9f m^3 (layout: %.9f m^3)\n", certipose::signed_volume(mesh),
                part.volume);

    const certipose::facet& foi = mesh.facet(part.facet_of_interest);  // out_of_range if bad
    std::printf(
        "facet of interest %zu: centroid (%.4f, %.4f, %.4f), normal (%g, %g, %g), "
        "area %.3g m^2\n",
        part.facet_of_interest, foi.centroid.x(), foi.centroid.y(), foi.centroid.z(),
        foi.normal.x(), foi.normal.y(), foi.normal.z(), foi.area);

    // Meshes in other units: rescale (here to a 0.3 m bounding-box diagonal).
    const auto small = certipose::rescaled_to_diagonal(mesh, 0.3);
    std::printf("rescaled bbox diagonal: %.3f m\n", small.bbox().diagonal().norm());
}
