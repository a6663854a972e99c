// The STEP reader (io/read_step.hpp): parts made here by OpenCASCADE's primitives and written in
// millimetres by its STEP writer, read back in metres with their faces; the real SolidWorks part
// of ../shared/cad against its own STL export; and the refusals.
#include <certipose/io/read_mesh.hpp>
#include <certipose/io/read_step.hpp>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Writer.hxx>
#include <gp_Ax2.hxx>

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <string>

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#endif

namespace {

#if defined(__SANITIZE_ADDRESS__)
using leaks_ignored = __lsan::ScopedDisabler;
#else
struct leaks_ignored {};
#endif

/// OpenCASCADE registers its STEP parameters once per process, on the first reader or writer,
/// and never frees them. That is done here, before any test, with LeakSanitizer looking away, so
/// that what read_step itself allocates is still checked (the debug preset).
const struct step_registered_once {
    step_registered_once() {
        [[maybe_unused]] const leaks_ignored ignored;
        STEPControl_Controller::Init();
    }
} registered;

namespace fs = std::filesystem;
using namespace certipose;

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::path(CERTIPOSE_BINARY_DIR) / "tests" / "step_scratch";
    fs::create_directories(dir);
    return dir / name;
}

/// Writes `shape` (coordinates in millimetres) as an AP214 STEP file in millimetres.
void write_step_mm(const TopoDS_Shape& shape, const fs::path& path) {
    [[maybe_unused]] const leaks_ignored ignored;  // OpenCASCADE 7.6's writer leaks a few bytes a file (GeomToStep_MakeDirection)
    STEPControl_Writer writer;
    Interface_Static::SetCVal("xstep.cascade.unit", "MM");
    Interface_Static::SetCVal("write.step.unit", "MM");
    REQUIRE(writer.Transfer(shape, STEPControl_AsIs) == IFSelect_RetDone);
    REQUIRE(writer.Write(path.string().c_str()) == IFSelect_RetDone);
}

std::map<std::string, int> surfaces(const step_part& p) {
    std::map<std::string, int> n;
    for (const auto& f : p.cad.faces.faces) ++n[f.surface];
    return n;
}

}  // namespace

TEST_CASE("read_step: a box written in millimetres is read in metres, one plane per face, normals out") {
    const fs::path file = scratch("box_mm.step");
    write_step_mm(BRepPrimAPI_MakeBox(20.0, 10.0, 5.0).Shape(), file);
    Interface_Static::SetCVal("xstep.cascade.unit", "MM");
    const int printers = Message::DefaultMessenger()->Printers().Length();
    const step_part p = read_step(file);
    // the process-wide settings it changes while it reads are given back
    CHECK(std::string(Interface_Static::CVal("xstep.cascade.unit")) == "MM");
    CHECK(Message::DefaultMessenger()->Printers().Length() == printers);
    CHECK(p.cad.unit == "MILLIMETRE");
    const auto box = p.mesh.bbox();
    CHECK(box.min().norm() < 1e-15);
    CHECK(std::abs(box.max().x() - 0.020) < 1e-15);
    CHECK(std::abs(box.max().y() - 0.010) < 1e-15);
    CHECK(std::abs(box.max().z() - 0.005) < 1e-15);
    // default deflection: 1/1000 of the diagonal
    CHECK(std::abs(p.cad.deflection - std::sqrt(0.02 * 0.02 + 0.01 * 0.01 + 0.005 * 0.005) / 1000) < 1e-9);
    REQUIRE(p.cad.faces.faces.size() == 6);
    CHECK(surfaces(p) == std::map<std::string, int>{{"plane", 6}});
    double area = 0;
    for (const auto& f : p.cad.faces.faces) {
        CHECK(f.facets.size() >= 2);
        CHECK(f.deviation < 1e-12);  // a plane is its triangles
        area += f.area;
    }
    CHECK(std::abs(area - 2 * (200 + 100 + 50) * 1e-6) < 1e-15);
    CHECK_NOTHROW(p.cad.faces.validate(p.mesh.num_faces()));
    // welded across faces into a closed solid whose normals point out (REVERSED faces flipped)
    CHECK_NOTHROW(validate_closed_manifold(p.mesh));
    CHECK(p.mesh.num_vertices() == 8);
    CHECK(std::abs(signed_volume(p.mesh) - 1e-6) < 1e-18);
    // each facet's normal agrees with its face's (all facets of the face x = 0 point to -x)
    for (std::size_t i = 0; i < p.cad.faces.faces.size(); ++i) {
        const auto& n0 = p.mesh.facet(p.cad.faces.faces[i].facets[0]).normal;
        for (auto f : p.cad.faces.faces[i].facets) CHECK(p.mesh.facet(f).normal.dot(n0) > 1 - 1e-12);
    }
}

TEST_CASE("read_step: curved faces are within the deflection of their triangles, and a finer one is closer") {
    const fs::path file = scratch("bored_block_mm.step");
    // a 40 × 40 × 20 mm block with a 10 mm bore through it: planes and one cylinder (in two
    // halves or one, as OpenCASCADE's cylinder has a seam)
    const TopoDS_Shape block = BRepPrimAPI_MakeBox(40.0, 40.0, 20.0).Shape();
    const TopoDS_Shape bore = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(20, 20, -1), gp_Dir(0, 0, 1)), 5.0, 22.0).Shape();
    write_step_mm(BRepAlgoAPI_Cut(block, bore).Shape(), file);
    const double r = 0.005;
    double coarse_deviation = 0;
    std::size_t coarse_facets = 0;
    for (const double deflection : {1e-4, 1e-5}) {
        CAPTURE(deflection);
        const step_part p = read_step(file, {.deflection = deflection, .angular_deflection = 1.0});
        CHECK(p.cad.deflection == deflection);
        const auto kinds = surfaces(p);
        CHECK(kinds.at("plane") == 6);
        REQUIRE(kinds.count("cylinder") == 1);
        double bore_area = 0, deviation = 0;
        for (const auto& f : p.cad.faces.faces)
            if (f.surface == "cylinder") {
                bore_area += f.area;
                deviation = std::max(deviation, f.deviation);
            }
        CHECK(std::abs(bore_area - 2 * std::numbers::pi * r * 0.020) < 1e-12);
        // the chord of an inscribed polygon: sampled sag is positive and within the deflection
        CHECK(deviation > 0);
        CHECK(deviation <= deflection * (1 + 1e-6));
        CHECK_NOTHROW(validate_closed_manifold(p.mesh));
        const double exact = 0.04 * 0.04 * 0.02 - std::numbers::pi * r * r * 0.02;
        CHECK(signed_volume(p.mesh) > exact);  // the bore's polygon is inscribed: less removed
        CHECK(signed_volume(p.mesh) < exact + 2 * std::numbers::pi * r * 0.02 * deflection);
        if (coarse_facets) {
            CHECK(p.mesh.num_faces() > coarse_facets);
            CHECK(deviation < coarse_deviation);
        }
        coarse_deviation = deviation;
        coarse_facets = p.mesh.num_faces();
    }
}

TEST_CASE("read_step: the real SolidWorks part (inches) matches its own STL export, face by face") {
    const fs::path file = fs::path(CERTIPOSE_SHARED_CAD) / "featuretype.STEP";
    const step_part p = read_step(file);
    CHECK(p.cad.unit == "INCH");
    CHECK(p.cad.faces.faces.size() == 96);
    CHECK(surfaces(p) == std::map<std::string, int>{{"plane", 49}, {"cylinder", 46}, {"bspline", 1}});
    CHECK_NOTHROW(p.cad.faces.validate(p.mesh.num_faces()));
    double area = 0;
    for (const auto& f : p.cad.faces.faces) {
        CAPTURE(f.surface);
        CHECK(!f.facets.empty());
        CHECK(f.deviation <= p.cad.deflection * 1.5);
        area += f.area;
    }
    // the same part as its STL export, in inches: the same bounding box to within the
    // deflection, and the same surface area to a fraction of a percent
    const triangle_mesh stl = read_mesh(fs::path(CERTIPOSE_SHARED_MESHES) / "featuretype.off", {.scale = 0.0254});
    CHECK((p.mesh.bbox().min() - stl.bbox().min()).norm() < 2 * p.cad.deflection);
    CHECK((p.mesh.bbox().max() - stl.bbox().max()).norm() < 2 * p.cad.deflection);
    double stl_area = 0;
    for (const auto& f : stl.facets()) stl_area += f.area;
    CHECK(std::abs(area - stl_area) < 0.005 * stl_area);
    double mesh_area = 0;
    for (const auto& f : p.mesh.facets()) mesh_area += f.area;
    CHECK(std::abs(area - mesh_area) < 0.005 * area);
}

TEST_CASE("read_step: refusals name the file or the option") {
    CHECK(is_step_path("a/b.STEP"));
    CHECK(is_step_path("b.stp"));
    CHECK_FALSE(is_step_path("b.off"));
    CHECK_FALSE(is_step_path("step"));
    try {
        (void)read_step(scratch("missing.step"));
        FAIL("no throw");
    } catch (const io_error& e) {
        CHECK(e.path() == scratch("missing.step").string());
        CHECK(std::string(e.what()).find("no such file") != std::string::npos);
    }
    const fs::path text = scratch("not_step.step");
    std::ofstream(text) << "solid nothing\nendsolid\n";
    try {
        (void)read_step(text);
        FAIL("no throw");
    } catch (const io_error& e) {
        CHECK(e.path() == text.string());
        CHECK(std::string(e.what()).find("not a STEP file") != std::string::npos);
    }
    const fs::path box = scratch("box_for_options.step");
    write_step_mm(BRepPrimAPI_MakeBox(1.0, 1.0, 1.0).Shape(), box);
    for (const double bad : {0.0, -1e-3, std::nan("")}) {
        try {
            (void)read_step(box, {.deflection = bad});
            FAIL("no throw");
        } catch (const invalid_argument& e) {
            CHECK(e.field() == "deflection");
        }
    }
    try {
        (void)read_step(box, {.angular_deflection = 0.0});
        FAIL("no throw");
    } catch (const invalid_argument& e) {
        CHECK(e.field() == "angular_deflection");
    }
    // the caller's unit setting is left as it was
    Interface_Static::SetCVal("xstep.cascade.unit", "MM");
    (void)read_step(box);
    CHECK(std::string(Interface_Static::CVal("xstep.cascade.unit")) == "MM");
}

TEST_CASE("cad_faces::validate refuses a map that is not one") {
    cad_faces f;
    f.face_of = {0, 0, 1};
    f.faces.resize(2);
    f.faces[0].facets = {0, 1};
    f.faces[1].facets = {2};
    CHECK_NOTHROW(f.validate(3));
    CHECK_THROWS_AS(f.validate(4), mesh_error);
    f.faces[1].facets = {1};
    CHECK_THROWS_AS(f.validate(3), mesh_error);
    f.faces[0].facets = {1, 0};
    f.faces[1].facets = {2};
    CHECK_THROWS_AS(f.validate(3), mesh_error);
}
