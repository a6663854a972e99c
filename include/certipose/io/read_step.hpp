// certipose/io/read_step.hpp — read a STEP file (AP203, AP214, AP242) into the triangle_mesh that
// is certified and the B-rep face of each of its facets (OpenCASCADE; target certipose::step).
//
// Reading and tessellating are OpenCASCADE's (Debian libocct-*; LGPL-2.1 with the OCCT exception):
// STEPControl_Reader converts the file's unit to metres, BRepMesh_IncrementalMesh tessellates
// every face with a chordal (linear) and an angular deflection. This header only walks the faces,
// keeps their orientation (a REVERSED face's triangles are flipped, so normals point out of a
// solid as the file defines it), welds the vertices that are exactly equal, drops the triangles
// the mesher made degenerate (they have no area to inspect; counted), and measures per face what
// the certificates need to be read correctly: the tessellation is what is certified, and
// `cad_face::deviation` says how far it can be from the designed surface.
//
// Every solid, shell and loose face of every root of the file is read into one mesh: an assembly
// or several bodies are a triangle soup, as a dirty mesh is (occlusion: mesh semantics "soup").
//
// OpenCASCADE's unit setting (`xstep.cascade.unit`) and its default messenger are process-wide:
// read_step sets the unit to metres and silences the messenger (which prints the parser's and the
// transfer's chatter on standard output, where a program's own output goes) while it reads, and
// restores both after; do not read or write STEP files on two threads at once. What goes wrong
// comes back as an exception instead.
#pragma once

#include "certipose/error.hpp"
#include "certipose/geometry/cad_faces.hpp"
#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/io/step_path.hpp"

#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepGProp.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <Interface_InterfaceModel.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Poly_Triangulation.hxx>
#include <STEPControl_Reader.hxx>
#include <StepShape_AdvancedFace.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_ShapeMapHasher.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <TransferBRep.hxx>
#include <Transfer_TransientProcess.hxx>
#include <XSControl_TransferReader.hxx>
#include <XSControl_WorkSession.hxx>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/squared_distance_3.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

namespace certipose {

/// How a STEP file is tessellated.
struct step_options {
    /// Chordal deflection, metres: the largest distance the mesher allows between a triangle and
    /// its surface. Unset: 1/1000 of the diagonal of the part's bounding box. Throws
    /// invalid_argument("deflection") unless finite and > 0.
    std::optional<double> deflection{};
    /// Angular deflection, radians: the largest angle between the normals of neighbouring
    /// triangles on a curved face. Throws invalid_argument("angular_deflection") unless in (0, pi).
    double angular_deflection = 0.5;
    /// Surface samples per face and direction for `cad_face::deviation` (n × n on the face's
    /// parameter rectangle; samples outside a trimmed face are skipped). 0 measures nothing.
    int deviation_samples = 12;
};

/// What read_step read.
struct step_part {
    triangle_mesh mesh;  ///< the tessellation, metres; what the certificates are for
    cad_model cad;       ///< its faces, the file's unit (upper case) and the deflections used
};

namespace detail::step {

inline const char* surface_name(GeomAbs_SurfaceType t) {
    switch (t) {
        case GeomAbs_Plane: return "plane";
        case GeomAbs_Cylinder: return "cylinder";
        case GeomAbs_Cone: return "cone";
        case GeomAbs_Sphere: return "sphere";
        case GeomAbs_Torus: return "torus";
        case GeomAbs_BezierSurface: return "bezier";
        case GeomAbs_BSplineSurface: return "bspline";
        case GeomAbs_SurfaceOfRevolution: return "revolution";
        case GeomAbs_SurfaceOfExtrusion: return "extrusion";
        case GeomAbs_OffsetSurface: return "offset";
        default: return "other";
    }
}

/// The names the file gives its faces (ADVANCED_FACE('name', ...)), by the shape each became;
/// "NONE" and empty names are no names (CAD systems write them for unnamed faces).
inline NCollection_DataMap<TopoDS_Shape, std::string, TopTools_ShapeMapHasher> face_names(STEPControl_Reader& reader) {
    NCollection_DataMap<TopoDS_Shape, std::string, TopTools_ShapeMapHasher> names;
    const Handle(Interface_InterfaceModel) model = reader.Model();
    const Handle(XSControl_TransferReader) tr = reader.WS()->TransferReader();
    if (model.IsNull() || tr.IsNull()) return names;
    const Handle(Transfer_TransientProcess) tp = tr->TransientProcess();
    if (tp.IsNull()) return names;
    for (Standard_Integer i = 1; i <= model->NbEntities(); ++i) {
        const auto face = Handle(StepShape_AdvancedFace)::DownCast(model->Value(i));
        if (face.IsNull() || face->Name().IsNull()) continue;
        std::string name = face->Name()->ToCString();
        if (name.empty() || name == "NONE") continue;
        const TopoDS_Shape shape = TransferBRep::ShapeResult(tp, face);
        if (!shape.IsNull()) names.Bind(shape.Located(TopLoc_Location()), std::move(name));
    }
    return names;
}

}  // namespace detail::step

/// Reads the STEP file `path` into metres and tessellates it (see the header comment).
/// Throws io_error(path) when the file is missing, is not STEP, holds no surface or cannot be
/// tessellated; invalid_argument for bad options. Facets come face by face, in the order
/// OpenCASCADE explores the faces; faces keep that order too.
inline step_part read_step(const std::filesystem::path& path, const step_options& opt = {}) {
    const std::string file = path.string();
    if (opt.deflection && !(std::isfinite(*opt.deflection) && *opt.deflection > 0))
        throw invalid_argument("deflection", "read_step: the deflection must be a finite length > 0 (metres), got " +
                                                 detail::mesh::format(*opt.deflection));
    if (!(opt.angular_deflection > 0 && opt.angular_deflection < std::numbers::pi))
        throw invalid_argument("angular_deflection", "read_step: the angular deflection must be in (0, pi) radians, got " +
                                                         detail::mesh::format(opt.angular_deflection));
    if (opt.deviation_samples < 0)
        throw invalid_argument("deviation_samples", "read_step: deviation_samples must be >= 0, got " +
                                                        std::to_string(opt.deviation_samples));
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) throw io_error(file, file + ": no such file");

    try {
        struct messenger_silenced {
            Handle(Message_Messenger) messenger = Message::DefaultMessenger();
            Message_SequenceOfPrinters printers = messenger->Printers();
            messenger_silenced() { messenger->ChangePrinters().Clear(); }
            ~messenger_silenced() { messenger->ChangePrinters() = printers; }
            messenger_silenced(const messenger_silenced&) = delete;
            messenger_silenced& operator=(const messenger_silenced&) = delete;
        } quiet;
        STEPControl_Reader reader;  // its constructor registers the STEP parameters; then set the unit
        // Metres while this reader transfers; the caller's setting (OpenCASCADE's default is
        // millimetres) is restored afterwards, for its own readers and writers.
        struct unit_in_metres {
            const char* given = Interface_Static::CVal("xstep.cascade.unit");
            std::string previous = given ? given : "MM";
            unit_in_metres() { Interface_Static::SetCVal("xstep.cascade.unit", "M"); }
            ~unit_in_metres() { Interface_Static::SetCVal("xstep.cascade.unit", previous.c_str()); }
            unit_in_metres(const unit_in_metres&) = delete;
            unit_in_metres& operator=(const unit_in_metres&) = delete;
        } metres;
        if (reader.ReadFile(file.c_str()) != IFSelect_RetDone)
            throw io_error(file, file + ": not a STEP file OpenCASCADE can read (ISO 10303-21: AP203, AP214, AP242)");
        std::string unit;
        {
            TColStd_SequenceOfAsciiString lengths, angles, solid_angles;
            reader.FileUnits(lengths, angles, solid_angles);
            for (Standard_Integer i = 1; i <= lengths.Length(); ++i) {
                std::string u = lengths(i).ToCString();  // OpenCASCADE's own writer says "millimetre"
                std::transform(u.begin(), u.end(), u.begin(), [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
                if (unit.empty()) unit = u;
                else if (unit != u) unit += ", " + u;
            }
        }
        reader.TransferRoots();
        const TopoDS_Shape shape = reader.OneShape();
        if (shape.IsNull() || !TopExp_Explorer(shape, TopAbs_FACE).More())
            throw io_error(file, file + ": holds no surface (no B-rep face to tessellate)");

        Bnd_Box bounds;
        BRepBndLib::Add(shape, bounds);
        const double diagonal = bounds.IsVoid() ? 0.0 : std::sqrt(bounds.SquareExtent());
        const double deflection = opt.deflection.value_or(diagonal / 1000);
        if (!(deflection > 0)) throw io_error(file, file + ": the part has no extent to tessellate");
        BRepMesh_IncrementalMesh mesher(shape, deflection, /*isRelative=*/false, opt.angular_deflection, /*isInParallel=*/false);
        const auto names = detail::step::face_names(reader);

        std::vector<Eigen::Vector3d> points;
        std::map<std::array<double, 3>, std::uint32_t> index_of;  // exact welding
        std::vector<face_indices> triangles;
        cad_faces faces;
        std::size_t dropped = 0, untessellated = 0;
        const auto vertex = [&](const gp_Pnt& p) {
            const std::array<double, 3> key{p.X(), p.Y(), p.Z()};
            const auto [it, added] = index_of.emplace(key, static_cast<std::uint32_t>(points.size()));
            if (added) points.emplace_back(p.X(), p.Y(), p.Z());
            return it->second;
        };
        for (TopExp_Explorer e(shape, TopAbs_FACE); e.More(); e.Next()) {
            const TopoDS_Face face = TopoDS::Face(e.Current());
            TopLoc_Location loc;
            const Handle(Poly_Triangulation) tri = BRep_Tool::Triangulation(face, loc);
            if (tri.IsNull() || tri->NbTriangles() == 0) {
                ++untessellated;
                continue;
            }
            const gp_Trsf to_part = loc.Transformation();
            const bool reversed = face.Orientation() == TopAbs_REVERSED;
            cad_face record;
            const auto id = static_cast<std::uint32_t>(faces.faces.size());
            // A face whose triangles are all degenerate (a sliver) keeps its record, with no facet.
            using kernel = CGAL::Simple_cartesian<double>;
            const auto cgal_point = [](const Eigen::Vector3d& p) { return kernel::Point_3(p.x(), p.y(), p.z()); };
            std::vector<kernel::Triangle_3> own;  // this face's triangles, for the deviation
            for (Standard_Integer t = 1; t <= tri->NbTriangles(); ++t) {
                Standard_Integer n1, n2, n3;
                tri->Triangle(t).Get(n1, n2, n3);
                if (reversed) std::swap(n2, n3);
                const face_indices f{vertex(tri->Node(n1).Transformed(to_part)), vertex(tri->Node(n2).Transformed(to_part)),
                                     vertex(tri->Node(n3).Transformed(to_part))};
                const Eigen::Vector3d &a = points[f[0]], &b = points[f[1]], &c = points[f[2]];
                if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2] || detail::mesh::exactly_collinear(a, b, c) ||
                    !((b - a).cross(c - a).norm() > 0)) {
                    ++dropped;
                    continue;
                }
                record.facets.push_back(static_cast<std::uint32_t>(triangles.size()));
                faces.face_of.push_back(id);
                triangles.push_back(f);
                own.emplace_back(cgal_point(a), cgal_point(b), cgal_point(c));
            }
            const BRepAdaptor_Surface surface(face);  // with the face's location
            record.surface = detail::step::surface_name(surface.GetType());
            GProp_GProps props;
            BRepGProp::SurfaceProperties(face, props);
            record.area = props.Mass();
            // Names are keyed by the face without its location (TopTools_ShapeMapHasher ignores
            // the orientation), as face_names binds them.
            if (const std::string* name = names.Seek(face.Located(TopLoc_Location()))) record.name = *name;
            // The deviation: surface points on an n × n grid of the face's parameter rectangle,
            // those inside the (trimmed) face, against the nearest of the face's triangles.
            if (opt.deviation_samples > 0 && !own.empty()) {
                double u0, u1, v0, v1;
                BRepTools::UVBounds(face, u0, u1, v0, v1);
                BRepTopAdaptor_FClass2d inside(face, 1e-9);
                const int n = opt.deviation_samples;
                for (int i = 0; i < n; ++i)
                    for (int j = 0; j < n; ++j) {
                        const double u = u0 + (u1 - u0) * (i + 0.5) / n, v = v0 + (v1 - v0) * (j + 0.5) / n;
                        if (inside.Perform(gp_Pnt2d(u, v)) != TopAbs_IN) continue;
                        const gp_Pnt q = surface.Value(u, v);
                        const kernel::Point_3 p(q.X(), q.Y(), q.Z());
                        double best = std::numeric_limits<double>::infinity();
                        for (const auto& t : own) best = std::min(best, CGAL::squared_distance(p, t));
                        record.deviation = std::max(record.deviation, std::sqrt(best));
                    }
            }
            faces.faces.push_back(std::move(record));
        }
        if (triangles.empty())
            throw io_error(file, file + ": OpenCASCADE made no triangle of its " + std::to_string(untessellated) +
                                     " face(s) (deflection " + detail::mesh::format(deflection) + " m)");
        if (untessellated)
            throw io_error(file, file + ": " + std::to_string(untessellated) +
                                     " face(s) could not be tessellated; a certificate for the rest would not be one "
                                     "for the part (try another --deflection)");
        step_part out{triangle_mesh(std::move(points), std::move(triangles)),
                      {unit, deflection, opt.angular_deflection, dropped, std::move(faces)}};
        out.cad.faces.validate(out.mesh.num_faces());
        return out;
    } catch (const Standard_Failure& e) {
        throw io_error(file, file + ": OpenCASCADE failed: " + std::string(e.GetMessageString() ? e.GetMessageString() : "") +
                                 " (" + e.DynamicType()->Name() + ")");
    }
}

}  // namespace certipose
