// docs/step.md: a STEP file read in metres and tessellated, its CAD faces listed, and one facet
// of the largest face solved. Usage: doc_step_faces PART.step
#include <certipose/cgal.hpp>
#include <certipose/io/read_step.hpp>

#include <algorithm>
#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: doc_step_faces PART.step\n");
        return 2;
    }
    try {
        // Metres, whatever unit the file uses; unset deflection: 1/1000 of the part's diagonal.
        const certipose::step_part part = certipose::read_step(argv[1], {.angular_deflection = 0.5});
        const certipose::cad_model& cad = part.cad;
        std::printf("%zu facets from %zu faces (file unit %s), chordal deflection %.3g mm\n", part.mesh.num_faces(),
                    cad.faces.faces.size(), cad.unit.c_str(), cad.deflection * 1e3);
        for (std::size_t i = 0; i < cad.faces.faces.size(); ++i) {
            const certipose::cad_face& face = cad.faces.faces[i];
            // area: of the designed surface; deviation: how far its triangles may lie from it
            std::printf("face %zu %s%s: %.2f cm², %zu facets, deviation %.3g mm\n", i, face.surface.c_str(),
                        face.name.empty() ? "" : (" '" + face.name + "'").c_str(), face.area * 1e4, face.facets.size(),
                        face.deviation * 1e3);
        }

        // The mesh is a triangle_mesh like any other: a facet of the largest face, solved.
        const auto largest = std::max_element(cad.faces.faces.begin(), cad.faces.faces.end(),
                                              [](const auto& a, const auto& b) { return a.area < b.area; });
        const std::size_t facet = largest->facets.front();
        const certipose::thin_lens_camera camera(certipose::thin_lens_parameters{
            .focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6, .max_blur_circle = 6.9e-6,
            .pixel_pitch = 3.45e-6, .width_px = 2448, .height_px = 2048});
        // A tessellation need not be a clean closed solid (an assembly is several bodies):
        // mesh_semantics::automatic reads it as a triangle soup when it is not.
        const certipose::pose_solver<> solver(part.mesh, camera, {.min_view_angle = 0.35},
                                              {.semantics = certipose::mesh_semantics::automatic});
        const auto r = solver.solve(facet, {.position_eps = 0.1, .orientation_eps = 0.38});
        std::printf("facet %zu of face %u: %zu VALID boxes\n", facet, cad.faces.face_of[facet], r.stats.valid);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "doc_step_faces: %s\n", e.what());
        return 1;
    }
}
