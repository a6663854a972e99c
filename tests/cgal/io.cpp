// The files of docs/conventions.md#files with CGAL in the loop: the result JSON round trip over both
// interval backends (the CGAL one holds only the SSE rounding mode, which the readers must
// still neutralise), and the PLY picture parsed back by CGAL's own PLY reader (read_mesh) —
// an independent reader, like MeshLab's and ParaView's.
#include <certipose/interval/boost_interval.hpp>
#include <certipose/interval/cgal_interval.hpp>
#include <certipose/io/box_store.hpp>
#include <certipose/io/json.hpp>
#include <certipose/io/ply.hpp>
#include <certipose/coverage/deployment.hpp>
#include <certipose/io/output_files.hpp>
#include <certipose/io/plan_files.hpp>
#include <certipose/io/read_mesh.hpp>
#include <certipose/io/write_file.hpp>
#include <certipose/occlusion/cgal_aabb_occlusion.hpp>
#include <certipose/solver/task.hpp>

#include <Eigen/Dense>
#include <doctest/doctest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <numbers>
#include <random>
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
        {"non-finite sight-line start", [&] {
             const certipose::aabb_occlusion occ(tetrahedron());
             (void)occ.sight_line_blocked({std::numeric_limits<double>::quiet_NaN(), 0, 0}, 0);
         }},
        {"camera field out of range", [&] { (void)thin_lens(-0.012); }},
        {"camera file missing", [&] { certipose::read_camera_task(dir / "missing.json"); }},
        {"camera JSON syntax", [&] { certipose::parse_camera_task("{\"camera\": {", "camera.json"); }},
        {"camera JSON field missing", [&] { certipose::parse_camera_task(R"({"camera": {"model": "thin_lens"}, "task": {}})", "camera.json"); }},
        {"camera JSON unknown field", [&] {
             certipose::parse_camera_task(R"({"camera": {"model": "thin_lens", "focal_lenght": 0.012}, "task": {}})", "camera.json");
         }},
        {"distortion coefficient count", [&] {
             certipose::parse_camera_task(R"({"camera": {"model": "pinhole", "focal_length": 0.012, "pixel_pitch": 3.45e-6,
                 "width_px": 2448, "height_px": 2048, "d_min": 0.2, "d_max": 1, "distortion_coefficients": [0.1, 0.2, 0]},
                 "task": {"min_view_angle": 0.35}})", "camera.json");
         }},
        {"distortion beyond certification", [&] {
             certipose::parse_camera_task(R"({"camera": {"model": "pinhole", "focal_length": 0.012, "pixel_pitch": 3.45e-6,
                 "width_px": 2448, "height_px": 2048, "d_min": 0.2, "d_max": 1, "distortion_coefficients": [0, 0, 0, 0, 0, -1e9, 0, 0]},
                 "task": {"min_view_angle": 0.35}})", "camera.json");
         }},
        {"image margin too large", [&] {
             certipose::parse_camera_task(R"({"camera": {"model": "pinhole", "focal_length": 0.012, "pixel_pitch": 3.45e-6,
                 "width_px": 2448, "height_px": 2048, "d_min": 0.2, "d_max": 1, "image_margin_px": 1100},
                 "task": {"min_view_angle": 0.35}})", "camera.json");
         }},
        {"calibration and sensor field both given", [&] {
             certipose::parse_camera_task(R"({"camera": {"model": "pinhole", "calibration": "cal.yaml", "width_px": 2448,
                 "d_min": 0.2, "d_max": 1}, "task": {"min_view_angle": 0.35}})", "camera.json");
         }},
        {"calibration file not a calibration", [&] { certipose::read_calibration(file("notes.yaml", "hello: world\n")); }},
        {"calibration YAML syntax", [&] { certipose::read_calibration(file("broken.yaml", "camera_name: x\ncamera_matrix: [1, [2\n")); }},
        {"calibration fisheye", [&] {
             certipose::read_calibration(file("fisheye.yaml", "image_width: 640\nimage_height: 480\ncamera_name: c\n"
                                                              "camera_matrix: {rows: 3, cols: 3, data: [500, 0, 320, 0, 500, 240, 0, 0, 1]}\n"
                                                              "distortion_model: equidistant\n"
                                                              "distortion_coefficients: {rows: 1, cols: 4, data: [0, 0, 0, 0]}\n"));
         }},
        {"calibration matrix size", [&] {
             certipose::read_calibration(file("rows.yaml", "image_width: 640\nimage_height: 480\ncamera_name: c\n"
                                                           "camera_matrix: {rows: 3, cols: 3, data: [500, 0, 320, 0, 500, 240]}\n"
                                                           "distortion_model: plumb_bob\n"
                                                           "distortion_coefficients: {rows: 1, cols: 5, data: [0, 0, 0, 0, 0]}\n"));
         }},
        {"calibration principal point outside", [&] {
             certipose::read_calibration(file("pp.yaml", "image_width: 640\nimage_height: 480\ncamera_name: c\n"
                                                         "camera_matrix: {rows: 3, cols: 3, data: [500, 0, 700, 0, 500, 240, 0, 0, 1]}\n"
                                                         "distortion_model: plumb_bob\n"
                                                         "distortion_coefficients: {rows: 1, cols: 5, data: [0, 0, 0, 0, 0]}\n"));
         }},
        {"calibration key missing", [&] {
             certipose::read_calibration(file("nokey.yaml", "image_width: 640\nimage_height: 480\ncamera_name: c\n"
                                                            "distortion_model: plumb_bob\n"
                                                            "distortion_coefficients: {rows: 1, cols: 5, data: [0, 0, 0, 0, 0]}\n"));
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
        {"pose quaternion not unit", [&] {
             certipose::read_poses(file("quaternion.json", R"({"poses": [{"position": [0, 0, 1], "quaternion": [0.5, 0, 0, 0.8]}]})"));
         }},
        {"pose at the ZXZ gimbal lock", [&] {
             certipose::read_poses(file("lock.json", R"({"poses": [{"position": [0, 0, 1], "quaternion": [1, 0, 0, 0]}]})"));
         }},
        {"pose matrix not a rotation", [&] {
             certipose::read_poses(file("matrix.json", R"({"poses": [{"matrix": [[1, 0, 0, 0], [0, 0, -1.01, 0], [0, 1, 0, 1], [0, 0, 0, 1]]}]})"));
         }},
        {"document of another version", [&] {
             certipose::read_plan(file("version.json", R"({"format": "certipose-plan", "version": 2})"));
         }},
        {"document of another format", [&] {
             certipose::read_plan(file("format.json", R"({"format": "certipose-result", "version": 1})"));
         }},
        {"placement tolerance negative", [] {
             const certipose::placement_tolerance t{.translation = {0.001, -0.001, 0}};
             t.validate();
         }},
        {"placement tolerance in degrees", [] {
             const certipose::placement_tolerance t{.rotation = 2};
             t.validate();
         }},
        {"camera JSON placement tolerance", [] {
             certipose::parse_camera_task(R"({"camera": {"model": "pinhole", "focal_length": 0.012, "pixel_pitch": 3.45e-6,
                 "width_px": 2448, "height_px": 2048, "d_min": 0.4, "d_max": 0.8},
                 "task": {"min_view_angle": 0.35, "placement_tolerance": {"translation": [0.001, 0.001, 0.001], "rotation": -0.01}}})");
         }},
        {"box store truncated", [&] {
             const fs::path store = dir / "boxes.cpbx";
             {
                 std::ofstream out(store, std::ios::binary);
                 certipose::box_store_sink<certipose::boost_interval> sink(out, true);
                 certipose::facet_outcome<certipose::boost_interval> o;
                 o.record.index = 3;
                 o.boxes.resize(1);
                 for (std::size_t k = 0; k < 3; ++k) {
                     o.boxes[0].box.position[k] = certipose::boost_interval(0.0, 1.0);
                     o.boxes[0].box.orientation[k] = certipose::boost_interval(0.0, 1.0);
                 }
                 sink.facet(o);
             }
             fs::resize_file(store, fs::file_size(store) - 7);
             certipose::read_box_store(store, [](const certipose::part_box&) {});
         }},
        {"not a box store", [&] { certipose::read_box_store(file("boxes.cpbx", tetra_off), [](const certipose::part_box&) {}); }},
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

// ==== PLAN.json, summary.json and POSES.json: format, version, plan reader, pose forms =========

namespace {

/// A plan with awkward doubles (1/3, subnormal, -0, the largest double) and every optional set.
certipose::plan_document sample_plan() {
    certipose::plan_document p;
    p.mesh = {"parts/bracket.off", 2300, 0.001, "0123456789abcdef"};
    p.camera.width_px = 2448;
    p.camera.height_px = 2048;
    p.camera.K = {{{3478.2608695652175, 0, 1224}, {0, 3478.2608695652175, 1024}, {0, 0, 1}}};
    p.camera.d_min = 0.489636037212339;
    p.camera.d_max = std::numeric_limits<double>::infinity();  // written as null
    p.camera.mount_offset = {0.01, -0.0125, 1.0 / 3};
    p.task = {0.35, 1e-4};
    p.candidates = 17;
    p.inspected = 5;
    p.tolerance = std::array<double, 2>{0.005, 0.02};
    p.target_coverage = 0.95;
    p.max_cameras = 4;
    certipose::plan_document::camera_box c;
    c.position = {{{0.1, 0.2}, {1.0 / 3, 0.4}, {-0.0, 5e-324}}};
    c.orientation = {{{-3.141592653589793, -3.0}, {0.1, 0.2}, {-0.19, 1.7976931348623157e308}}};
    c.nominal = {0.15, 0.36666666666666664, 0, -3.0707963267948966, 0.15000000000000002, 0.5};
    c.facets = {1, 2, 900};
    c.certified_area = 0.0012345678901234567;
    c.from_facet = 900;
    p.cameras = {c, c};
    p.cameras[1].facets.clear();
    p.coverage = {0.0024691357802469134, 0.003, 0.16, 2, "lp", {0.0012345678901234567, 0.0024691357802469134}};
    p.uncovered = {{0, certipose::uncovered_reason::never_visible}, {3, certipose::uncovered_reason::boundary_only},
                   {4, certipose::uncovered_reason::not_selected}, {5, certipose::uncovered_reason::not_solved},
                   {6, certipose::uncovered_reason::not_finished}, {7, certipose::uncovered_reason::rests_on_occluder},
                   {8, certipose::uncovered_reason::buried}};
    return p;
}

/// field() and what() of the invalid_argument `read` throws.
std::pair<std::string, std::string> argument_error(const std::function<void()>& read) {
    try {
        read();
    } catch (const certipose::invalid_argument& e) {
        return {e.field(), e.what()};
    }
    FAIL("no invalid_argument");
    return {};
}

}  // namespace

TEST_CASE("PLAN.json: read_plan reads back exactly what plan_to_json wrote") {
    const fs::path file = scratch("plan.json");
    for (const bool optional_set : {true, false}) {
        certipose::plan_document doc = sample_plan();
        if (!optional_set) {
            doc.mesh.digest.clear();
            doc.tolerance.reset();
            doc.target_coverage.reset();
            doc.max_cameras.reset();
            doc.task.max_metres_per_pixel.reset();
            doc.camera.mount_offset = {};
            doc.camera.d_max = 0.7745933384972885;
            doc.cameras.clear();
            doc.uncovered.clear();
            doc.coverage.curve.clear();
        }
        certipose::write_json_file(file, certipose::plan_to_json(doc));
        const certipose::plan_document back = certipose::read_plan(file);
        CHECK(back == doc);
        CHECK(std::signbit(doc.cameras.empty() ? -0.0 : back.cameras[0].position[2][0]));  // -0 kept
        // The same document, bit for bit, written again.
        CHECK(certipose::json_text(certipose::plan_to_json(back)) == certipose::json_text(certipose::plan_to_json(doc)));
    }
    // The leading keys; mount_offset only when not zero.
    const auto j = certipose::plan_to_json(sample_plan());
    std::vector<std::string> keys;
    for (auto it = j.begin(); it != j.end(); ++it) keys.push_back(it.key());
    CHECK(keys == std::vector<std::string>{"format", "version", "mesh", "camera", "task", "settings", "occluders", "keep_in",
                                           "keep_out", "cameras", "coverage", "uncovered"});
    CHECK(j["format"] == "certipose-plan");
    CHECK(j["version"] == 1);
    CHECK(j["camera"]["mount_offset"].size() == 3);
    // A file without format and version (written before they existed) is version 1.
    auto old = j;
    old.erase("format");
    old.erase("version");
    CHECK(certipose::plan_from_json(nlohmann::json::parse(old.dump()), "old.json") == sample_plan());
    // A file written before thinning inspected every candidate.
    old["settings"].erase("inspected");
    CHECK(certipose::plan_from_json(nlohmann::json::parse(old.dump()), "old.json").inspected == 17);
    // More inspected than offered is not written.
    certipose::plan_document wrong = sample_plan();
    wrong.inspected = 18;
    CHECK_THROWS_AS((void)certipose::plan_to_json(wrong), certipose::invalid_argument);
}

TEST_CASE("PLAN.json: bad documents are errors naming the file and the JSON path") {
    const auto good = nlohmann::json::parse(certipose::plan_to_json(sample_plan()).dump());
    const auto expect = [&](const std::function<void(nlohmann::json&)>& edit, const std::string& field,
                            const std::string& message) {
        nlohmann::json j = good;
        edit(j);
        const auto [f, what] = argument_error([&] { (void)certipose::plan_from_json(j, "PLAN.json"); });
        CHECK(f == field);
        CHECK(what == message);
    };
    expect([](auto& j) { j["version"] = 2; }, "version", "PLAN.json: \"version\": 2 is not supported (this build reads version 1)");
    expect([](auto& j) { j["format"] = "certipose-part-summary"; }, "format",
           "PLAN.json: \"format\": \"certipose-part-summary\" is not supported here (expected \"certipose-plan\")");
    expect([](auto& j) { j.erase("cameras"); }, "cameras", "PLAN.json: cameras: missing required field (an array)");
    expect([](auto& j) { j["cameras"] = nlohmann::json::object(); }, "cameras", "PLAN.json: cameras: expected an array, got an object");
    expect([](auto& j) { j["cameras"][1]["position"][0] = {0.3, 0.2}; }, "cameras[1].position[0]",
           "PLAN.json: cameras[1].position[0]: lower bound 0.3 is above upper bound 0.2");
    expect([](auto& j) { j["cameras"][0]["facets"][2] = -1; }, "cameras[0].facets[2]",
           "PLAN.json: cameras[0].facets[2]: expected a non-negative integer, got number -1");
    expect([](auto& j) { j["cameras"][0]["nominal"] = {1, 2, 3}; }, "cameras[0].nominal",
           "PLAN.json: cameras[0].nominal: expected an array of 6 numbers, got an array of 3");
    expect([](auto& j) { j["settings"]["inspected"] = 18; }, "settings.inspected",
           "PLAN.json: settings.inspected: expected at most settings.candidates (17), got 18");
    expect([](auto& j) { j["settings"]["tolerance"] = 0.005; }, "settings.tolerance",
           "PLAN.json: settings.tolerance: expected an array of 2 numbers, got number 0.005");
    expect([](auto& j) { j["camera"]["mount_offset"] = {0, 0}; }, "camera.mount_offset",
           "PLAN.json: camera.mount_offset: expected an array of 3 numbers, got an array of 2");
    expect([](auto& j) { j["uncovered"][1]["reason"] = "shy"; }, "uncovered[1].reason",
           "PLAN.json: uncovered[1].reason: unknown reason \"shy\" (expected never visible, only in BOUNDARY boxes at this "
           "eps, not selected, not solved, solve stopped early or rests on an occluder)");
    expect([](auto& j) { j["coverage"].erase("lower_bound_method"); }, "coverage.lower_bound_method",
           "PLAN.json: coverage.lower_bound_method: missing required field (a string)");
    // Files: missing is an io_error; JSON errors name the file.
    CHECK_THROWS_AS((void)certipose::read_plan(scratch("no-such-plan.json")), certipose::io_error);
    const fs::path bad = scratch("bad-plan.json");
    std::ofstream(bad) << "{\"format\": \"certipose-plan\", \"version\": 9}";
    CHECK(argument_error([&] { (void)certipose::read_plan(bad); }).second ==
          bad.string() + ": \"version\": 9 is not supported (this build reads version 1)");
}

namespace {

/// A summary.json record of a 4-facet part at ε_p 0.1, ε_o 0.38, without facets.
certipose::part_summary small_summary(const std::string& mesh_path) {
    certipose::part_summary s;
    s.mesh = {mesh_path, 4, 1.0, "0123456789abcdef"};
    s.camera = sample_plan().camera;
    s.task = {0.35, std::nullopt};
    s.settings.position_eps = 0.1;
    s.settings.orientation_eps = 0.38;
    return s;
}

}  // namespace

TEST_CASE("summary.json: format and version lead, mount_offset round-trips, other versions are refused") {
    certipose::part_summary s = small_summary("part.off");
    s.totals.seconds = 1.5;
    certipose::facet_record own, reused;
    own.index = 1, own.valid = 3;
    reused.index = 2, reused.valid = 3, reused.reused_from = 1;
    s.facets = {own, reused};
    s.mesh.pose = certipose::part_pose_from_xyz_rpy({0.1, 0.2, 0.3}, {0.4, 0.5, 0.6}).matrix();  // --part-pose
    const fs::path dir = scratch("summary") / "run";
    fs::create_directories(dir);
    const auto j = certipose::part_summary_to_json(s);
    CHECK(j.begin().key() == "format");
    CHECK(j["format"] == "certipose-part-summary");
    CHECK(std::next(j.begin()).key() == "version");
    certipose::write_json_file(dir / "summary.json", j);
    const certipose::part_summary back = certipose::read_part_summary(dir);
    CHECK(back.camera == s.camera);
    CHECK(back.mesh == s.mesh);  // the pose to the last bit
    REQUIRE(j["mesh"]["pose"].size() == 4);
    CHECK(j["mesh"]["pose"][3] == nlohmann::json::array({0.0, 0.0, 0.0, 1.0}));
    {
        auto mirrored = nlohmann::json::parse(j.dump());
        mirrored["mesh"]["pose"][2][2] = -mirrored["mesh"]["pose"][2][2].get<double>();
        mirrored["mesh"]["pose"][2][0] = -mirrored["mesh"]["pose"][2][0].get<double>();
        mirrored["mesh"]["pose"][2][1] = -mirrored["mesh"]["pose"][2][1].get<double>();
        CHECK(argument_error([&] { (void)certipose::part_summary_from_json(mirrored); }).first == "mesh.pose");
    }
    // The reuse stage: on by default, and which facet's boxes a reused facet took.
    CHECK(j["settings"]["reuse"] == true);
    CHECK(!j["facets"][0].contains("reused_from"));
    CHECK(j["facets"][1]["reused_from"] == 1);
    REQUIRE(back.facets.size() == 2);
    CHECK(!back.facets[0].reused_from);
    CHECK(back.facets[1].reused_from == std::optional<std::size_t>(1));

    auto v2 = nlohmann::json::parse(j.dump());
    v2["version"] = 2;
    std::ofstream(dir / "summary.json") << v2.dump();
    const auto [field, what] = argument_error([&] { (void)certipose::read_part_summary(dir); });
    CHECK(field == "version");
    CHECK(what == (dir / "summary.json").string() + ": \"version\": 2 is not supported (this build reads version 1)");
    auto other = nlohmann::json::parse(j.dump());
    other["format"] = "certipose-plan";
    CHECK(argument_error([&] { (void)certipose::part_summary_from_json(other); }).second ==
          "\"format\": \"certipose-plan\" is not supported here (expected \"certipose-part-summary\")");
    other.erase("format");  // older files: no format, no version
    other.erase("version");
    CHECK(certipose::part_summary_from_json(other).camera == s.camera);
}

TEST_CASE("summary.json: a STEP part's cad record round-trips, and a record that is not a partition is refused naming it") {
    certipose::part_summary s = small_summary("part.step");
    certipose::cad_model cad;
    cad.unit = "INCH";
    cad.deflection = 1.5e-4;
    cad.angular_deflection = 0.5;
    cad.dropped_triangles = 2;
    cad.faces.face_of = {1, 0, 1, 1};
    cad.faces.faces = {{"", "plane", 1e-4, 0.0, {1}}, {"the bore", "cylinder", 2.5e-4, 3.75e-5, {0, 2, 3}}};
    s.cad = cad;
    const auto j = certipose::part_summary_to_json(s);
    CHECK(j["cad"]["unit"] == "INCH");
    CHECK(j["cad"]["faces"][1]["id"] == 1);
    CHECK(j["cad"]["faces"][1]["name"] == "the bore");
    CHECK(j["cad"]["faces"][1]["facets"] == nlohmann::json::array({0, 2, 3}));
    const certipose::part_summary back = certipose::part_summary_from_json(nlohmann::json::parse(j.dump()));
    REQUIRE(back.cad);
    CHECK(back.cad->unit == "INCH");
    CHECK(back.cad->deflection == 1.5e-4);
    CHECK(back.cad->angular_deflection == 0.5);
    CHECK(back.cad->dropped_triangles == 2);
    CHECK(back.cad->faces.face_of == cad.faces.face_of);
    REQUIRE(back.cad->faces.faces.size() == 2);
    CHECK(back.cad->faces.faces[1].name == "the bore");
    CHECK(back.cad->faces.faces[1].surface == "cylinder");
    CHECK(back.cad->faces.faces[1].deviation == 3.75e-5);
    CHECK(back.cad->faces.faces[1].facets == cad.faces.faces[1].facets);
    // a mesh file's run has no cad record
    s.cad.reset();
    CHECK(!certipose::part_summary_to_json(s).contains("cad"));

    auto bad = nlohmann::json::parse(j.dump());
    bad["cad"]["faces"][0]["facets"] = nlohmann::json::array({1, 7});
    auto e = argument_error([&] { (void)certipose::part_summary_from_json(bad); });
    CHECK(e.first == "cad.faces[0].facets[1]");
    CHECK(e.second.find("facet 7 is out of range (mesh.faces = 4)") != std::string::npos);
    bad = nlohmann::json::parse(j.dump());
    bad["cad"]["faces"][0]["facets"] = nlohmann::json::array({0});  // facet 0 in both faces, facet 1 in none
    e = argument_error([&] { (void)certipose::part_summary_from_json(bad); });
    CHECK(e.first == "cad.faces");
    bad = nlohmann::json::parse(j.dump());
    bad["cad"]["faces"][1]["id"] = 5;
    CHECK(argument_error([&] { (void)certipose::part_summary_from_json(bad); }).first == "cad.faces[1].id");
}

TEST_CASE("POSES.json: a 4x4 whose rotation is orthonormal only within 1e-6 gets a box holding the rotation it approximates") {
    // R(0.4, γ, 0.2) with one entry of the third row nudged by 5e-7: β read from that row alone is
    // off by about 5e-7 / sin γ, far beyond ±1e-8; the box must still hold the exact angles.
    for (const double gamma : {2e-6, 1e-3, 0.3, 1.5, 3.0}) {
        CAPTURE(gamma);
        Eigen::Matrix3d r = certipose::zxz_rotation(0.4, gamma, 0.2);
        r(2, 0) += 5e-7;
        nlohmann::json matrix = nlohmann::json::array();
        for (int a = 0; a < 3; ++a) matrix.push_back({r(a, 0), r(a, 1), r(a, 2), 0.0});
        matrix.push_back({0, 0, 0, 1});
        nlohmann::json doc;
        doc["poses"] = {{{"matrix", matrix}}};
        const auto poses = certipose::poses_from_json(doc);
        REQUIRE(poses.size() == 1);
        const double angles[3] = {0.4, gamma, 0.2};
        for (std::size_t k = 0; k < 3; ++k) {
            CAPTURE(k);
            CHECK(poses[0].orientation[k][0] <= angles[k]);
            CHECK(poses[0].orientation[k][1] >= angles[k]);
        }
    }
}

TEST_CASE("POSES.json: a 4x4's box holds every rotation within its off-orthonormality (the factor 4, bounded by test)") {
    // A matrix M orthonormal only within off = max|MᵀM − I| names every rotation R with
    // max|R − M| ≤ off as much as any other. The reader widens the box by 4·off in γ and
    // 4·off / sin γ in φ and β. Here: random rotations (sin γ from 1e-3 to 1) perturbed entry by
    // entry, and for each, rotations about 26 axes from M's nearest rotation (polar factor),
    // pushed as far as max|R − M| ≤ off allows; every one must lie in the box, and the box's
    // half-widths must be those the reader records (pose_input::converted_half_widths).
    std::mt19937_64 e(11);
    std::uniform_real_distribution<double> any(-3.1, 3.1), unit(-1, 1), tilt(std::asin(1e-3), std::numbers::pi / 2);
    const auto angle_of = [](double a, double centre) { return std::remainder(a - centre, 2 * std::numbers::pi); };
    double worst = 0;  // the largest |angle − centre| / (half-width − 1e-8) seen
    int checked = 0;
    for (int n = 0; n < 300; ++n) {
        const double gamma = (n % 2 ? tilt(e) : std::numbers::pi - tilt(e)), eta = std::pow(10.0, -9 + 2.5 * (n % 5) / 4.0);
        const Eigen::Matrix3d r0 = certipose::zxz_rotation(any(e), gamma, any(e));
        Eigen::Matrix3d m = r0;
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) m(a, b) += eta * unit(e);
        const double off = (m.transpose() * m - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
        if (!(off <= certipose::pose_unit_tolerance) || !(off > 0)) continue;
        nlohmann::json matrix = nlohmann::json::array();
        for (int a = 0; a < 3; ++a) matrix.push_back({m(a, 0), m(a, 1), m(a, 2), 0.0});
        matrix.push_back({0, 0, 0, 1});
        nlohmann::json doc;
        doc["poses"] = {{{"matrix", matrix}}};
        const auto p = certipose::poses_from_json(doc).at(0);
        REQUIRE(p.converted.has_value());
        const double sin_gamma = std::sin((*p.converted)[4]);
        for (std::size_t k = 0; k < 3; ++k) {
            const double h = p.converted_half_widths[k];
            CHECK(h == doctest::Approx(certipose::converted_pose_half_width + (k == 1 ? 4 * off : 4 * off / sin_gamma)).epsilon(1e-6));
            CHECK(p.orientation[k][0] == (*p.converted)[k + 3] - h);
            CHECK(p.orientation[k][1] == (*p.converted)[k + 3] + h);
        }
        const Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
        const Eigen::Matrix3d polar = svd.matrixU() * svd.matrixV().transpose();
        const auto within = [&](const Eigen::Matrix3d& r) {
            const auto a = certipose::zxz_from_matrix(r);
            const double angles[3] = {a.phi, a.gamma, a.beta};
            for (std::size_t k = 0; k < 3; ++k) {
                const double d = std::abs(angle_of(angles[k], (*p.converted)[k + 3]));
                CAPTURE(k);
                CAPTURE(off);
                CAPTURE(sin_gamma);
                CHECK(d <= p.converted_half_widths[k]);
                worst = std::max(worst, d / (p.converted_half_widths[k] - certipose::converted_pose_half_width));
            }
            ++checked;
        };
        REQUIRE((polar - m).cwiseAbs().maxCoeff() <= off);  // the nearest rotation is one of them
        within(polar);
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    if (!dx && !dy && !dz) continue;
                    const Eigen::Vector3d axis = Eigen::Vector3d(dx, dy, dz).normalized();
                    const auto turned = [&](double s) { return Eigen::Matrix3d(polar * Eigen::AngleAxisd(s, axis)); };
                    double lo = 0, hi = 8 * off;  // the largest turn with max|R − M| ≤ off, by bisection
                    for (int it = 0; it < 60; ++it) {
                        const double s = (lo + hi) / 2;
                        ((turned(s) - m).cwiseAbs().maxCoeff() <= off ? lo : hi) = s;
                    }
                    within(turned(lo));
                }
    }
    CHECK(checked > 5000);
    MESSAGE("largest share of the widening used: " << worst);  // the factor 4's margin
    CHECK(worst < 1.0);
}

TEST_CASE("POSES.json: quaternion and 4x4 poses become 1e-8 rad boxes around their ZXZ angles") {
    std::mt19937_64 e(5);
    std::uniform_real_distribution<double> any(-3.1, 3.1), tilt(1e-3, 3.14), coordinate(-2, 2);
    for (int n = 0; n < 500; ++n) {
        const double phi = any(e), gamma = tilt(e), beta = any(e);
        const std::array<double, 3> x{coordinate(e), coordinate(e), coordinate(e)};
        const auto q = certipose::quaternion_from_zxz(phi, gamma, beta);
        const Eigen::Matrix3d r = certipose::zxz_rotation(phi, gamma, beta);
        nlohmann::json matrix = nlohmann::json::array();
        for (int a = 0; a < 3; ++a) matrix.push_back({r(a, 0), r(a, 1), r(a, 2), x[static_cast<std::size_t>(a)]});
        matrix.push_back({0, 0, 0, 1});
        nlohmann::json doc;
        doc["poses"] = {{{"position", x}, {"quaternion", q}},
                        {{"position", x}, {"quaternion", {-q[0], -q[1], -q[2], -q[3]}}},  // the same rotation
                        {{"matrix", matrix}}};
        const auto poses = certipose::poses_from_json(doc);
        REQUIRE(poses.size() == 3);
        for (std::size_t i = 0; i < 3; ++i) {
            const auto& p = poses[i];
            CHECK(p.form == (i < 2 ? certipose::pose_form::quaternion : certipose::pose_form::matrix));
            CHECK_FALSE(p.pose.has_value());  // not an exact pose
            REQUIRE(p.converted.has_value());
            const double angles[3] = {phi, gamma, beta};
            for (std::size_t k = 0; k < 3; ++k) {
                CHECK(p.position[k][0] == x[k]);  // the position stays exact
                CHECK(p.position[k][1] == x[k]);
                CHECK(std::abs((*p.converted)[k + 3] - angles[k]) < 1e-9);
                // The box holds the true angle with room to spare, and is 2e-8 wide.
                CHECK(p.orientation[k][0] < angles[k] - 5e-9);
                CHECK(p.orientation[k][1] > angles[k] + 5e-9);
                // 2e-8 wide; a matrix's box is widened by its (here rounding-level) distance from
                // orthonormal, over sin γ.
                const double w = p.orientation[k][1] - p.orientation[k][0] - 2 * certipose::converted_pose_half_width;
                CHECK(w > -1e-15);
                CHECK(w < (i < 2 ? 1e-15 : 1e-11));
            }
        }
    }
    // PLAN.json's format and version are accepted; another format is not.
    nlohmann::json plan = nlohmann::json::parse(certipose::plan_to_json(sample_plan()).dump());
    CHECK(certipose::poses_from_json(plan).size() == 2);
    plan["format"] = "certipose-result";
    CHECK(argument_error([&] { (void)certipose::poses_from_json(plan); }).first == "format");
}

TEST_CASE("POSES.json: a non-unit quaternion, a bad matrix and the gimbal lock are errors naming the pose") {
    const fs::path file = scratch("poses-bad.json");
    const auto expect = [&](const std::string& pose, const std::string& field, const std::string& message) {
        std::ofstream(file) << "{\"poses\": [[0, 0, 1, 0, 0.5, 0], " << pose << "]}";
        const auto [f, what] = argument_error([&] { (void)certipose::read_poses(file); });
        CHECK(f == field);
        CHECK(what == file.string() + ": " + message);
    };
    expect(R"({"position": [0, 0, 1], "quaternion": [0, 0, 0, 2]})", "poses[1].quaternion",
           "poses[1].quaternion: not a unit quaternion [qx, qy, qz, qw]: its norm is 2 (must be 1 within 1e-06)");
    expect(R"({"position": [0, 0, 1], "quaternion": [0.5, 0, 0, 0.866]})", "poses[1].quaternion",
           "poses[1].quaternion: not a unit quaternion [qx, qy, qz, qw]: its norm is 0.9999779997579946 (must be 1 within 1e-06)");
    expect(R"({"position": [0, 0, 1], "quaternion": [0, 0, 0.6, 0.8]})", "poses[1].quaternion",
           "poses[1].quaternion: the orientation is at the ZXZ gimbal lock (sin gamma = 0 < 1e-06: the optical axis is "
           "along world +Z or -Z), where it has no accurate ZXZ angles; give this pose as ZXZ angles [x, y, z, phi, "
           "gamma, beta] instead");
    expect(R"({"position": [0, 0, 1], "quaternion": [1, 0, 0, 0]})", "poses[1].quaternion",
           "poses[1].quaternion: the orientation is at the ZXZ gimbal lock (sin gamma = 0 < 1e-06: the optical axis is "
           "along world +Z or -Z), where it has no accurate ZXZ angles; give this pose as ZXZ angles [x, y, z, phi, "
           "gamma, beta] instead");
    expect(R"({"quaternion": [0, 0, 0, 1]})", "poses[1].position", "poses[1].position: missing required field (3 numbers [x, y, z])");
    expect(R"({"position": [[0, 1], [0, 1], [0, 1]], "quaternion": [0, 0, 0, 1]})", "poses[1].position[0]",
           "poses[1].position[0]: expected a number, got an array of 2");
    expect(R"({"matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 1], [0, 0, 0, 1]]})", "poses[1].matrix",
           "poses[1].matrix: the orientation is at the ZXZ gimbal lock (sin gamma = 0 < 1e-06: the optical axis is along "
           "world +Z or -Z), where it has no accurate ZXZ angles; give this pose as ZXZ angles [x, y, z, phi, gamma, "
           "beta] instead");
    expect(R"({"matrix": [[1, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 1], [0, 0, 1, 1]]})", "poses[1].matrix[3]",
           "poses[1].matrix[3]: the last row of a camera-to-world transform must be [0, 0, 0, 1], got [0, 0, 1, 1]");
    expect(R"({"matrix": [[1, 0, 0, 0], [0, 0, -1.01, 0], [0, 1, 0, 1], [0, 0, 0, 1]]})", "poses[1].matrix",
           "poses[1].matrix: the rotation part (upper-left 3x3) is not orthonormal within 1e-06: R^T R differs from the "
           "identity by up to 0.020100000000000007");
    expect(R"({"matrix": [[-1, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 1], [0, 0, 0, 1]]})", "poses[1].matrix",
           "poses[1].matrix: the rotation part (upper-left 3x3) has determinant -1: a reflection, not a rotation");
    expect(R"({"matrix": [[1, 0, 0], [0, 0, -1], [0, 1, 0]]})", "poses[1].matrix",
           "poses[1].matrix: expected an array of 4 arrays of 4 numbers, got an array of 3");
    expect(R"({"matrix": [[1, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 1], [0, 0, 0, 1]], "position": [0, 0, 1]})", "poses[1].position",
           "poses[1].position: a pose given by \"matrix\" takes its position from the matrix's last column");
    expect(R"({"position": [0, 0, 1], "quaternion": [0, 0, 0, 1], "orientation": [[0, 1], [0, 1], [0, 1]]})", "poses[1]",
           "poses[1]: give the orientation once: one of \"pose\", \"orientation\", \"quaternion\" or \"matrix\"");
    // A camera looking sideways (γ = π/2, optical axis along world −y) converts fine.
    std::ofstream(file) << R"({"poses": [{"matrix": [[1, 0, 0, 0.5], [0, 0, -1, 0], [0, 1, 0, 1], [0, 0, 0, 1]]}]})";
    const auto p = certipose::read_poses(file);
    REQUIRE(p.size() == 1);
    CHECK(std::abs((*p[0].converted)[4] - std::numbers::pi / 2) < 1e-15);
    CHECK(p[0].position[0][0] == 0.5);
}
