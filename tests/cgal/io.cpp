// The files of DESIGN.md §6 with CGAL in the loop: the result JSON round trip over both
// interval backends (the CGAL one holds only the SSE rounding mode, which the readers must
// still neutralise), and the PLY picture parsed back by CGAL's own PLY reader (read_mesh) —
// an independent reader, like MeshLab's and ParaView's.
#include <certipose/interval/boost_interval.hpp>
#include <certipose/interval/cgal_interval.hpp>
#include <certipose/io/json.hpp>
#include <certipose/io/ply.hpp>
#include <certipose/coverage/deployment.hpp>
#include <certipose/io/output_files.hpp>
#include <certipose/io/plan_files.hpp>
#include <certipose/io/read_mesh.hpp>
#include <certipose/io/write_file.hpp>
#include <certipose/occlusion/cgal_aabb_occlusion.hpp>
#include <certipose/solver/task.hpp>

#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <typeinfo>
#include <utility>
#include <vector>

namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::path(CERTIPOSE_BINARY_DIR) / "test_io_cgal";
    fs::create_directories(dir);
    return dir / name;
}

certipose::triangle_mesh tetrahedron() {
    return certipose::triangle_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
                                    {{{0, 2, 1}}, {{0, 1, 3}}, {{0, 3, 2}}, {{1, 2, 3}}});
}

const char* const camera_json = R"({"camera": {"model": "thin_lens", "focal_length": 0.012,
    "f_stop": 8, "focus_distance": 0.6, "max_blur_circle": 6.9e-6, "pixel_pitch": 3.45e-6,
    "width_px": 2448, "height_px": 2048}, "task": {"min_view_angle": 0.35}})";

}  // namespace

TEST_CASE_TEMPLATE("result JSON and PLY under a held rounding mode, read back exactly", I,
                   certipose::boost_interval, certipose::cgal_interval) {
    const auto mesh = tetrahedron();
    const auto input = certipose::parse_camera_task(camera_json);
    const fs::path json_file = scratch("result.json");
    const fs::path ply_file = scratch("boxes.ply");
    certipose::solve_result<I> result;
    certipose::result_document doc, back;
    {
        const certipose::rounding_guard<I> guard;  // as inside the solver: mode held upward
        const double third = 1.0 / 3.0;            // computed upward: not the nearest double
        result.facet_index = 3;
        result.boxes.push_back(
            {certipose::box_class::valid,
             {certipose::position_box<I>::from_bounds({{{0.1, 0.2}, {third, 0.5}, {0.3, 0.30000000000000004}}}),
              certipose::orientation_box<I>::from_bounds({{{-0.7, 0.7}, {0.1, 0.123456789}, {-third, third}}})}});
        result.boxes.push_back(
            {certipose::box_class::boundary,
             {certipose::position_box<I>::from_bounds({{{-2, -1.5}, {1e-9, 2e-9}, {0.5, 0.75}}}),
              certipose::orientation_box<I>::from_bounds({{{0, 1}, {0, 1}, {0, 1}}})}});
        result.stats.valid = 1;
        result.stats.boundary = 1;
        result.stats.seconds = 0.123456789;

        doc = certipose::make_result_document(result, mesh, input.camera, input.task, {});
        certipose::write_result_json(json_file, doc);
        back = certipose::read_result_json(json_file);
        certipose::write_ply(ply_file, mesh, result);
    }
    REQUIRE(back.boxes.size() == 2);
    for (std::size_t b = 0; b < 2; ++b)
        for (int d = 0; d < 3; ++d) {
            CHECK(std::bit_cast<std::uint64_t>(back.boxes[b].position[d][0]) ==
                  std::bit_cast<std::uint64_t>(certipose::lower(result.boxes[b].box.position[d])));
            CHECK(std::bit_cast<std::uint64_t>(back.boxes[b].orientation[d][1]) ==
                  std::bit_cast<std::uint64_t>(certipose::upper(result.boxes[b].box.orientation[d])));
        }
    CHECK(back.stats.seconds == 0.123456789);
    CHECK(back.camera == doc.camera);

    // CGAL's PLY reader takes the picture: 4 part vertices + 3 facet copies + 8 per box; the
    // part's 3 other faces + the facet + 12 per box, in that order. (Read in round-to-nearest:
    // CGAL's text readers, like strtod, honour the rounding mode.)
    const certipose::triangle_mesh read = certipose::read_mesh(ply_file);
    CHECK(read.num_vertices() == 4 + 3 + 16);
    CHECK(read.num_faces() == 3 + 1 + 24);
    for (int k = 0; k < 3; ++k) CHECK(read.facet(3).v[k] == mesh.facet(3).v[k]);
    CHECK(read.facet(3).normal.isApprox(mesh.facet(3).normal));
    for (std::size_t b = 0; b < 2; ++b) {
        Eigen::AlignedBox3d box;
        for (std::size_t f = 4 + 12 * b; f < 4 + 12 * (b + 1); ++f) box.extend(read.facet(f).bbox);
        for (int d = 0; d < 3; ++d) {
            CHECK(box.min()[d] == certipose::lower(result.boxes[b].box.position[d]));
            CHECK(box.max()[d] == certipose::upper(result.boxes[b].box.position[d]));
        }
    }
}

// ==== docs/errors.md: the error catalogue cannot drift ===========================================
//
// Each case below provokes one error the library or certipose-solve reports, and docs/errors.md
// must hold a row with its type and its exact message (scratch paths written as DIR/). A new
// message, or a changed one, fails here with the row to put in the page.

namespace {

struct error_case {
    const char* name;
    std::function<void()> provoke;
};

/// The type name and message of what `provoke` throws, "none" if nothing.
std::pair<std::string, std::string> caught(const std::function<void()>& provoke) {
    try {
        provoke();
    } catch (const certipose::out_of_range& e) {
        return {"out_of_range", e.what()};
    } catch (const certipose::invalid_argument& e) {
        return {"invalid_argument", e.what()};
    } catch (const certipose::mesh_error& e) {
        return {"mesh_error", e.what()};
    } catch (const certipose::io_error& e) {
        return {"io_error", e.what()};
    } catch (const certipose::geometry_error& e) {
        return {"geometry_error", e.what()};
    } catch (const certipose::error& e) {
        return {"error", e.what()};
    } catch (const std::exception& e) {
        return {std::string("NOT A certipose::error: ") + typeid(e).name(), e.what()};
    }
    return {"none", ""};
}

std::string replaced_all(std::string s, const std::string& from, const std::string& to) {
    for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) s.replace(at, from.size(), to);
    return s;
}

}  // namespace

TEST_CASE("docs/errors.md lists every error with its type and exact message") {
    const fs::path dir = scratch("errors").parent_path();
    const auto file = [&](const std::string& name, const std::string& text) {
        const fs::path p = dir / name;
        std::ofstream(p, std::ios::binary) << text;
        return p;
    };
    const std::string tetra_off = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
    const auto thin_lens = [](double focal_length) {
        return certipose::thin_lens_camera(certipose::thin_lens_parameters{
            .focal_length = focal_length, .f_stop = 8, .focus_distance = 0.6, .max_blur_circle = 6.9e-6,
            .pixel_pitch = 3.45e-6, .width_px = 2448, .height_px = 2048});
    };
    const std::vector<error_case> cases{
        {"mesh file missing", [&] { certipose::read_mesh(dir / "missing.off"); }},
        {"unknown mesh format", [&] { certipose::read_mesh(file("part.xyz", "OFF\n")); }},
        {"mesh file not a mesh (PLY)", [&] { certipose::read_mesh(file("garbage.ply", "garbage\n")); }},
        {"mesh file empty", [&] { certipose::read_mesh(file("empty.off", "")); }},
        {"mesh file truncated", [&] { certipose::read_mesh(file("truncated.off", "OFF\n3 1 0\n0 0 0\n")); }},
        {"PLY list longer than the file", [&] {
             certipose::read_mesh(file("longlist.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                                       "property float y\nproperty float z\nelement face 1\n"
                                                       "property list uchar int vertex_indices\nend_header\n"
                                                       "0 0 0\n1 0 0\n0 1 0\n2000000000 0 1 2\n"));
         }},
        {"NaN coordinate (OFF)", [&] { certipose::read_mesh(file("nan.off", "OFF\n3 1 0\n0 0 0\n1 0 0\nnan 1 0\n3 0 1 2\n")); }},
        {"infinite coordinate (OBJ)", [&] { certipose::read_mesh(file("inf.obj", "v 0 0 0\nv 1 0 0\nv 0 inf 0\nf 1 2 3\n")); }},
        {"face index out of range (OFF)", [&] { certipose::read_mesh(file("badidx.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n")); }},
        {"face index out of range (OBJ)", [&] { certipose::read_mesh(file("badidx.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")); }},
        {"non-triangle face", [&] { certipose::read_mesh(file("quad.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n")); }},
        {"degenerate face", [&] { certipose::read_mesh(file("flat.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n2 0 0\n3 0 1 2\n")); }},
        {"bad scale", [&] { certipose::read_mesh(file("tetra.off", tetra_off), {.scale = -1.0}); }},
        {"open mesh given to the occlusion test", [&] {
             certipose::aabb_occlusion occ(certipose::triangle_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{{0, 1, 2}}}));
         }},
        {"facet out of range", [&] { (void)tetrahedron().facet(9); }},
        {"camera field out of range", [&] { (void)thin_lens(-0.012); }},
        {"camera file missing", [&] { certipose::read_camera_task(dir / "missing.json"); }},
        {"camera JSON syntax", [&] { certipose::parse_camera_task("{\"camera\": {", "camera.json"); }},
        {"camera JSON field missing", [&] { certipose::parse_camera_task(R"({"camera": {"model": "thin_lens"}, "task": {}})", "camera.json"); }},
        {"camera JSON unknown field", [&] {
             certipose::parse_camera_task(R"({"camera": {"model": "thin_lens", "focal_lenght": 0.012}, "task": {}})", "camera.json");
         }},
        {"bad position threshold", [&] { certipose::solve_options{.position_eps = 0.0}.validate(); }},
        {"bad orientation threshold", [&] { certipose::solve_options{.orientation_eps = std::nan("")}.validate(); }},
        {"bad corner depth", [&] {
             certipose::solve_options o;
             o.paving = certipose::carving{.corner_depth = 0};
             o.validate();
         }},
        {"bad corner rest", [&] {
             certipose::solve_options o;
             o.paving = certipose::carving{.rest_min_pieces = -1};
             o.validate();
         }},
        {"output directory missing", [&] { certipose::write_file_atomically(dir / "no" / "result.json", "{}"); }},
        {"deployment coverage out of range", [&] {
             certipose::deployment_options o;
             o.coverage = 1.5;
             certipose::plan_greedy({}, {}, o);
         }},
        {"poses file with no pose", [&] { certipose::read_poses(file("poses.json", R"({"poses": []})")); }},
        {"pose box upside down", [&] {
             certipose::read_poses(file("box.json", R"({"poses": [{"position": [[0, 1], [2, 1], [0, 1]], "orientation": [[0, 1], [0, 1], [0, 1]]}]})"));
         }},
        {"output is an input", [&] {
             certipose::refuse_overwriting_inputs({{"--mesh", file("part.off", tetra_off)}}, {{"--out", dir / "." / "part.off"}});
         }},
    };
    std::ifstream in(fs::path(CERTIPOSE_SOURCE_DIR) / "docs" / "errors.md");
    REQUIRE(in);
    const std::string page{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    for (const auto& c : cases) {
        const std::string name = c.name;
        CAPTURE(name);
        auto [type, message] = caught(c.provoke);
        message = replaced_all(message, dir.string() + "/./", "DIR/./");
        message = replaced_all(message, dir.string() + "/", "DIR/");
        REQUIRE_MESSAGE(type.rfind("NOT", 0) != 0, type);
        CHECK(type != "none");
        const std::string row = "| " + std::string(c.name) + " | `" + type + "` | `" + message + "` |";
        CHECK_MESSAGE(page.find(row) != std::string::npos, "docs/errors.md lacks the row (add a last column):\n" << row);
    }
}
