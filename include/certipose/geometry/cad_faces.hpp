// certipose/geometry/cad_faces.hpp — which B-rep face of a CAD model each facet came from.
//
// A part designed in CAD is a set of B-rep faces (planes, cylinders, fillets); its tessellation is
// the triangle_mesh every certificate is about. `cad_faces` keeps the link between the two, so
// that what is proven per facet can be reported per face, in the words of the engineer who named
// "the bore", and so that the facets of one face can be certified together (a patch). It is data
// only: io/read_step.hpp fills it from a STEP file; a mesh read from OFF, OBJ, PLY or STL has
// none. Facet and face indices are 0-based and follow the mesh's face order.
#pragma once

#include "certipose/error.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace certipose {

/// One B-rep face of a CAD model, as tessellated.
struct cad_face {
    std::string name;     ///< the name the file gives the face; empty when it gives none
    std::string surface;  ///< the kind of surface: "plane", "cylinder", "cone", "sphere", "torus",
                          ///< "bspline", "bezier", "revolution", "extrusion", "offset" or "other"
    double area = 0;      ///< of the B-rep face (not of its triangles), m²
    /// The largest distance from a sampled point of the face to its triangles, m: how far the
    /// tessellation, which is what is certified, can be from the designed surface.
    double deviation = 0;
    std::vector<std::uint32_t> facets;  ///< its facets, in increasing order
};

/// The B-rep faces of a mesh's facets: `face_of[f]` is the face of facet f, and
/// `faces[i].facets` lists the facets of face i (the same map, read the other way).
struct cad_faces {
    std::vector<std::uint32_t> face_of;
    std::vector<cad_face> faces;

    /// Throws certipose::mesh_error unless the map covers exactly `facet_count` facets, every
    /// face index is in range, and each face's facet list is the inverse of `face_of`.
    void validate(std::size_t facet_count) const {
        if (face_of.size() != facet_count)
            throw mesh_error("cad_faces: " + std::to_string(face_of.size()) + " facets mapped, the mesh has " +
                             std::to_string(facet_count));
        std::size_t listed = 0;
        for (std::size_t i = 0; i < faces.size(); ++i) {
            const auto& list = faces[i].facets;
            for (std::size_t k = 0; k < list.size(); ++k) {
                const std::uint32_t f = list[k];
                if (f >= facet_count || face_of[f] != i || (k > 0 && list[k - 1] >= f))
                    throw mesh_error("cad_faces: face " + std::to_string(i) + " lists facet " + std::to_string(f) +
                                     (f >= facet_count ? ", out of range" : ", which is not its own or out of order"));
            }
            listed += list.size();
        }
        if (listed != facet_count)
            throw mesh_error("cad_faces: the faces list " + std::to_string(listed) + " facets, the mesh has " +
                             std::to_string(facet_count));
    }
};

/// A CAD model as the mesh certified for it: its B-rep faces and how it was tessellated.
struct cad_model {
    std::string unit;               ///< the file's length unit, as it names it ("INCH", "MILLIMETRE", ...)
    double deflection = 0;          ///< the chordal deflection it was tessellated with, m
    double angular_deflection = 0;  ///< the angular deflection, rad
    std::size_t dropped_triangles = 0;  ///< degenerate triangles of the mesher, left out
    cad_faces faces;                ///< the B-rep face of each facet
};

}  // namespace certipose
