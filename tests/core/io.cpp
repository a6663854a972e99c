// Tests for the files that leave the library (docs/conventions.md#files): the camera/task input JSON (every
// error path), the result JSON (exact round trip of doubles, the contract's field layout,
// reader errors), atomic writes (nothing half-written, nothing left behind), the PLY picture
// (parsed back by a small reader written here) and the certipose-solve command line.
#include <certipose/interval/boost_interval.hpp>
#include <certipose/io/json.hpp>
#include <certipose/io/output_files.hpp>
#include <certipose/io/ply.hpp>
#include <certipose/io/write_file.hpp>

#include "../../examples/certipose_solve_cli.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#ifndef CERTIPOSE_IO_TEST_BACKENDS
#define CERTIPOSE_IO_TEST_BACKENDS certipose::boost_interval
#endif

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr double inf_v = std::numeric_limits<double>::infinity();

// ---- helpers ------------------------------------------------------------------------------------

/// A fresh empty directory, removed with its content at scope exit.
struct temp_dir {
    fs::path path;
    temp_dir() {
        static int n = 0;
        std::random_device rd;
        path = fs::temp_directory_path() /
               ("certipose-io-test-" + std::to_string(rd()) + "-" + std::to_string(n++));
        fs::create_directories(path);
    }
    ~temp_dir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
    std::size_t entries() const {
        return static_cast<std::size_t>(std::distance(fs::directory_iterator(path), fs::directory_iterator()));
    }
};

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// A closed tetrahedron, outward-oriented; face 3 is the facet of interest (normal (1,1,1)/√3).
certipose::triangle_mesh tetrahedron() {
    return certipose::triangle_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
                                    {{{0, 2, 1}}, {{0, 1, 3}}, {{0, 3, 2}}, {{1, 2, 3}}});
}

const char* const design_input = R"({"camera": {"model": "thin_lens", "focal_length": 0.012, "f_stop": 8, "focus_distance": 0.6,
            "max_blur_circle": 6.9e-6, "pixel_pitch": 3.45e-6, "width_px": 2448, "height_px": 2048,
            "principal_point_px": [1224, 1024], "skew": 0, "aspect": 1},
 "task": {"min_view_angle": 0.35, "max_metres_per_pixel": null}})";

json design_json() { return json::parse(design_input); }

json pinhole_json() {
    return json::parse(R"({"camera": {"model": "pinhole", "focal_length": 0.016, "pixel_pitch": 5e-6,
        "width_px": 1920, "height_px": 1200, "d_min": 0.3, "d_max": 0.9},
        "task": {"min_view_angle": 0.2, "max_metres_per_pixel": 1e-4}})");
}

/// Runs parse_camera_task on `j` and returns the invalid_argument it must throw.
certipose::invalid_argument input_error(const json& j) {
    try {
        (void)certipose::parse_camera_task(j.dump(), "cam.json");
    } catch (const certipose::invalid_argument& e) {
        return e;
    }
    FAIL("no invalid_argument for " << j.dump());
    return certipose::invalid_argument("", "");
}

/// Checks the error names `field` (the JSON path) and its message says `says`.
void expect_input_error(const json& j, const std::string& field, const std::string& says) {
    const auto e = input_error(j);
    CHECK(e.field() == field);
    const std::string what = e.what();
    CHECK_MESSAGE(what.find(says) != std::string::npos, what);
    CHECK_MESSAGE(what.rfind("cam.json: " + field + ": ", 0) == 0, what);
    CHECK(what.find('\n') == std::string::npos);
}

bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

void check_same_document(const certipose::result_document& a, const certipose::result_document& b) {
    CHECK(a.facet == b.facet);
    CHECK(a.camera == b.camera);
    CHECK(a.task == b.task);
    CHECK(a.settings == b.settings);
    REQUIRE(a.boxes.size() == b.boxes.size());
    for (std::size_t i = 0; i < a.boxes.size(); ++i) {
        CHECK(a.boxes[i].cls == b.boxes[i].cls);
        CHECK(a.boxes[i].reason == b.boxes[i].reason);
        for (int d = 0; d < 3; ++d)
            for (int k = 0; k < 2; ++k) {
                CHECK(same_bits(a.boxes[i].position[d][k], b.boxes[i].position[d][k]));
                CHECK(same_bits(a.boxes[i].orientation[d][k], b.boxes[i].orientation[d][k]));
            }
    }
    const auto& s = a.stats;
    const auto& t = b.stats;
    CHECK(s.valid == t.valid);
    CHECK(s.boundary == t.boundary);
    CHECK(s.position_valid == t.position_valid);
    CHECK(s.position_boundary == t.position_boundary);
    CHECK(s.contractions == t.contractions);
    CHECK(s.bisections == t.bisections);
    CHECK(s.occlusion_tests == t.occlusion_tests);
    CHECK(s.shadow_walks == t.shadow_walks);
    CHECK(s.orientation_certifications == t.orientation_certifications);
    CHECK(s.boundary_reasons == t.boundary_reasons);
    CHECK(s.occlusion_checked == t.occlusion_checked);
    CHECK(same_bits(s.seconds, t.seconds));
    CHECK(same_bits(s.seconds_position, t.seconds_position));
    CHECK(same_bits(s.seconds_orientation, t.seconds_orientation));
    CHECK(s.reason == t.reason);
}

/// A solver-like result with awkward doubles (1/3, subnormals, huge, negative zero-width).
template <class I>
certipose::solve_result<I> sample_result() {
    certipose::solve_result<I> r;
    r.facet_index = 3;
    const double third = 1.0 / 3.0;
    auto box = [](std::array<std::pair<double, double>, 3> p, std::array<std::pair<double, double>, 3> o) {
        return certipose::pose_box<I>{certipose::position_box<I>::from_bounds(p),
                                      certipose::orientation_box<I>::from_bounds(o)};
    };
    r.boxes.push_back({certipose::box_class::valid,
                       box({{{0.1, 0.2}, {third, 0.4}, {0.25, 0.30000000000000004}}},
                           {{{-3.141592653589793, -1.5}, {0.1, 0.48}, {-0.19, 0.19}}})});
    r.boxes.push_back({certipose::box_class::boundary,
                       box({{{-1e-300, 5e-324}, {1e10, 1.7976931348623157e308}, {-2.5, -2.5}}},
                           {{{0, 0}, {std::nextafter(1.0, 2.0), 2.0}, {-0.0, 0.0}}}),
                       certipose::boundary_reason::view_angle});
    r.stats.valid = 1;
    r.stats.boundary = 1;
    r.stats.boundary_reasons[static_cast<std::size_t>(certipose::boundary_reason::view_angle)] = 1;
    r.stats.position_valid = 7;
    r.stats.position_boundary = 11;
    r.stats.contractions = 123456789012ULL;
    r.stats.bisections = 42;
    r.stats.occlusion_tests = 99;
    r.stats.shadow_walks = 31;
    r.stats.orientation_certifications = 5;
    r.stats.seconds = 0.123456789;
    r.stats.seconds_position = 0.1;
    r.stats.seconds_orientation = 0.023456789;
    r.stats.reason = certipose::termination::deadline;
    return r;
}

// ---- a small PLY reader (ASCII, the subset write_ply emits) --------------------------------------

struct ply_file {
    std::vector<std::string> header;
    std::size_t header_vertices = 0, header_faces = 0;
    std::vector<std::array<double, 3>> vertices;
    std::vector<std::array<int, 3>> vertex_colours;
    std::vector<std::array<std::size_t, 3>> faces;
    std::vector<std::array<int, 3>> face_colours;
};

ply_file read_ply(const std::string& text) {
    ply_file f;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line) && line != "end_header") {
        f.header.push_back(line);
        std::istringstream ls(line);
        std::string word, element;
        ls >> word;
        if (word == "element") {
            std::size_t n = 0;
            ls >> element >> n;
            (element == "vertex" ? f.header_vertices : f.header_faces) = n;
        }
    }
    REQUIRE(line == "end_header");
    for (std::size_t i = 0; i < f.header_vertices; ++i) {
        REQUIRE(static_cast<bool>(std::getline(in, line)));
        std::istringstream ls(line);
        std::array<double, 3> p{};
        std::array<int, 3> c{};
        std::string x[3];
        ls >> x[0] >> x[1] >> x[2] >> c[0] >> c[1] >> c[2];
        REQUIRE(static_cast<bool>(ls));
        for (int k = 0; k < 3; ++k) p[k] = std::stod(x[k]);  // stod: exact for shortest-round-trip text
        std::string rest;
        CHECK_FALSE(static_cast<bool>(ls >> rest));
        f.vertices.push_back(p);
        f.vertex_colours.push_back(c);
    }
    for (std::size_t i = 0; i < f.header_faces; ++i) {
        REQUIRE(static_cast<bool>(std::getline(in, line)));
        std::istringstream ls(line);
        int n = 0;
        std::array<std::size_t, 3> t{};
        std::array<int, 3> c{};
        ls >> n >> t[0] >> t[1] >> t[2] >> c[0] >> c[1] >> c[2];
        REQUIRE(static_cast<bool>(ls));
        CHECK(n == 3);
        for (auto v : t) CHECK(v < f.header_vertices);
        f.faces.push_back(t);
        f.face_colours.push_back(c);
    }
    CHECK_FALSE(static_cast<bool>(std::getline(in, line)));  // nothing after the faces
    return f;
}

std::array<int, 3> colour(certipose::rgb c) { return {c.r, c.g, c.b}; }

/// 6 × signed volume of the closed triangle set `faces` (positive when oriented outward).
double six_volume(const ply_file& f, std::size_t first_face, std::size_t count) {
    double v = 0;
    for (std::size_t i = first_face; i < first_face + count; ++i) {
        const auto& t = f.faces[i];
        const Eigen::Vector3d a(f.vertices[t[0]].data()), b(f.vertices[t[1]].data()),
            c(f.vertices[t[2]].data());
        v += a.dot(b.cross(c));
    }
    return v;
}

}  // namespace

// ==== camera/task input ==========================================================================

TEST_CASE("the case-study camera/task JSON reads into a thin-lens camera and a task") {
    const certipose::camera_task in = certipose::parse_camera_task(design_input);
    REQUIRE(std::holds_alternative<certipose::thin_lens_camera>(in.camera));
    const auto& c = std::get<certipose::thin_lens_camera>(in.camera);
    CHECK(c.focal_length() == 0.012);
    CHECK(c.f_stop() == 8);
    CHECK(c.focus_distance() == 0.6);
    CHECK(c.max_blur_circle() == 6.9e-6);
    CHECK(c.pixel_pitch() == 3.45e-6);
    CHECK(c.width_px() == 2448);
    CHECK(c.height_px() == 2048);
    CHECK(c.principal_point_px() == Eigen::Vector2d(1224, 1024));
    CHECK(c.skew() == 0);
    CHECK(c.aspect() == 1);
    CHECK(in.task.min_view_angle == 0.35);
    CHECK_FALSE(in.task.max_metres_per_pixel.has_value());

    // The example file shipped for certipose-solve is the same document.
    const fs::path shipped = fs::path(__FILE__).parent_path() / "../../examples/data/camera.json";
    const certipose::camera_task file = certipose::read_camera_task(shipped);
    const auto& f = std::get<certipose::thin_lens_camera>(file.camera);
    CHECK(f.intrinsics() == c.intrinsics());
    CHECK(f.distance_range().min == c.distance_range().min);
    CHECK(f.distance_range().max == c.distance_range().max);
    CHECK(file.task.min_view_angle == in.task.min_view_angle);
}

TEST_CASE("optional camera fields may be left out or null") {
    json j = design_json();
    j["camera"].erase("principal_point_px");
    j["camera"].erase("skew");
    j["camera"]["aspect"] = nullptr;
    j["task"].erase("max_metres_per_pixel");
    const auto in = certipose::parse_camera_task(j.dump());
    const auto& c = std::get<certipose::thin_lens_camera>(in.camera);
    CHECK(c.principal_point_px() == Eigen::Vector2d(1224, 1024));
    CHECK(c.skew() == 0);
    CHECK(c.aspect() == 1);
    CHECK_FALSE(in.task.max_metres_per_pixel);
}

TEST_CASE("a pinhole camera reads with its working distances, d_max null is unbounded") {
    json j = pinhole_json();
    auto in = certipose::parse_camera_task(j.dump());
    REQUIRE(std::holds_alternative<certipose::pinhole_camera>(in.camera));
    const auto& p = std::get<certipose::pinhole_camera>(in.camera);
    CHECK(p.focal_length() == 0.016);
    CHECK(p.distance_range().min == 0.3);
    CHECK(p.distance_range().max == 0.9);
    CHECK(p.principal_point_px() == Eigen::Vector2d(960, 600));
    CHECK(in.task.max_metres_per_pixel == 1e-4);

    j["camera"]["d_max"] = nullptr;
    in = certipose::parse_camera_task(j.dump());
    CHECK(std::get<certipose::pinhole_camera>(in.camera).distance_range().max == inf_v);
}

TEST_CASE("camera_task_to_json writes what parse_camera_task reads back, for both models") {
    for (const json& j : {design_json(), pinhole_json()}) {
        const auto in = certipose::parse_camera_task(j.dump());
        const std::string text = certipose::json_text(certipose::camera_task_to_json(in));
        const auto back = certipose::parse_camera_task(text);
        CHECK(in.camera.index() == back.camera.index());
        std::visit(
            [&](const auto& a) {
                const auto& b = std::get<std::decay_t<decltype(a)>>(back.camera);
                CHECK(a.intrinsics() == b.intrinsics());
                CHECK(a.width_px() == b.width_px());
                CHECK(a.height_px() == b.height_px());
                CHECK(a.distance_range().min == b.distance_range().min);
                CHECK(a.distance_range().max == b.distance_range().max);
            },
            in.camera);
        CHECK(in.task.min_view_angle == back.task.min_view_angle);
        CHECK(in.task.max_metres_per_pixel == back.task.max_metres_per_pixel);
    }
}

TEST_CASE("unknown fields are errors naming the field's JSON path") {
    json j = design_json();
    j["camera"]["focal_lenght"] = 0.012;
    expect_input_error(j, "camera.focal_lenght", "unknown field");

    j = design_json();
    j["task"]["min_viewing_angle"] = 0.3;
    expect_input_error(j, "task.min_viewing_angle", "unknown field");

    j = design_json();
    j["cameras"] = json::object();
    expect_input_error(j, "cameras", "unknown field");

    // A field of the other model is unknown for this one.
    j = design_json();
    j["camera"]["d_max"] = 0.9;
    expect_input_error(j, "camera.d_max", "thin_lens camera fields");
    j = pinhole_json();
    j["camera"]["f_stop"] = 8;
    expect_input_error(j, "camera.f_stop", "pinhole camera fields");
}

TEST_CASE("wrong types are errors naming the field and the type found") {
    json j = design_json();
    j["camera"]["focal_length"] = "0.012";
    expect_input_error(j, "camera.focal_length", "expected a number, got string \"0.012\"");

    j = design_json();
    j["camera"]["width_px"] = true;
    expect_input_error(j, "camera.width_px", "expected a number, got boolean true");

    j = design_json();
    j["camera"]["principal_point_px"] = {1224, 1024, 0};
    expect_input_error(j, "camera.principal_point_px", "expected an array of 2 numbers, got an array of 3");

    j = design_json();
    j["camera"]["principal_point_px"] = {1224, "1024"};
    expect_input_error(j, "camera.principal_point_px[1]", "expected a number");

    j = design_json();
    j["camera"]["model"] = 1;
    expect_input_error(j, "camera.model", "expected a string");

    j = design_json();
    j["camera"]["model"] = "fisheye";
    expect_input_error(j, "camera.model", "unknown camera model \"fisheye\"");

    j = design_json();
    j["camera"] = json::array({1, 2});
    expect_input_error(j, "camera", "expected an object, got an array of 2");

    j = design_json();
    j["task"] = nullptr;
    expect_input_error(j, "task", "expected an object, got null");

    j = design_json();
    j["task"]["max_metres_per_pixel"] = "fine";
    expect_input_error(j, "task.max_metres_per_pixel", "expected a number");

    const auto top = input_error(json::array({design_json()}));
    CHECK(top.field().empty());
    CHECK(std::string(top.what()).find("(top level): expected an object") != std::string::npos);
}

TEST_CASE("every missing required field is an error naming it") {
    for (const char* field : {"model", "focal_length", "f_stop", "focus_distance", "max_blur_circle",
                              "pixel_pitch", "width_px", "height_px"}) {
        CAPTURE(field);
        json j = design_json();
        j["camera"].erase(field);
        expect_input_error(j, std::string("camera.") + field, "missing required field");
    }
    for (const char* field : {"focal_length", "pixel_pitch", "width_px", "height_px", "d_min", "d_max"}) {
        CAPTURE(field);
        json j = pinhole_json();
        j["camera"].erase(field);
        expect_input_error(j, std::string("camera.") + field, "missing required field");
    }
    for (const char* field : {"camera", "task"}) {
        json j = design_json();
        j.erase(field);
        expect_input_error(j, field, "missing required field");
    }
    json j = design_json();
    j["task"].erase("min_view_angle");
    expect_input_error(j, "task.min_view_angle", "missing required field");
}

TEST_CASE("a duplicate field is an error, not silently the last value") {
    const std::string text = R"({"camera": {"model": "thin_lens", "focal_length": 0.012, "focal_length": 0.016}})";
    try {
        (void)certipose::parse_camera_task(text, "cam.json");
        FAIL("no error");
    } catch (const certipose::invalid_argument& e) {
        CHECK(e.field() == "camera.focal_length");
        CHECK(std::string(e.what()) == "cam.json: camera.focal_length: duplicate field");
    }
    // Paths through arrays name the element.
    try {
        (void)certipose::parse_camera_task(R"({"x": [0, {"a": 1, "a": 2}]})");
        FAIL("no error");
    } catch (const certipose::invalid_argument& e) {
        CHECK(e.field() == "x[1].a");
    }
}

TEST_CASE("bad JSON syntax is an io_error with the source, line and column") {
    const std::string bad = "{\"camera\": {\"model\": \"thin_lens\",\n  \"focal_length\": 0.012,,\n}}";
    try {
        (void)certipose::parse_camera_task(bad, "cam.json");
        FAIL("no error");
    } catch (const certipose::io_error& e) {
        CHECK(e.path() == "cam.json");
        const std::string what = e.what();
        CHECK_MESSAGE(what.rfind("cam.json: invalid JSON: parse error at line 2, column", 0) == 0, what);
        CHECK(what.find("[json.exception") == std::string::npos);
    }
    for (const char* text : {"", "{", "[1, 2", "{\"camera\": 1e999}", "{\"a\": \"\xff\"}", "nul"}) {
        CAPTURE(text);
        CHECK_THROWS_AS((void)certipose::parse_camera_task(text, "x.json"), certipose::io_error);
    }
    // Comments are not JSON.
    CHECK_THROWS_AS((void)certipose::parse_camera_task("// camera\n{}", "x.json"), certipose::io_error);
}

TEST_CASE("impossible camera and task values are the camera's own invalid_argument, with the path") {
    const auto check = [](json j, const std::string& field, const std::string& says) {
        const auto e = input_error(j);
        CHECK(e.field() == field);
        const std::string what = e.what();
        CHECK_MESSAGE(what.find(says) != std::string::npos, what);
    };
    json j = design_json();
    j["camera"]["focal_length"] = -0.012;
    check(j, "camera.focal_length", "thin_lens_camera: focal_length must be positive and finite, got -0.012");

    j = design_json();
    j["camera"]["focus_distance"] = 0.01;
    check(j, "camera.focus_distance", "greater than focal_length");

    j = design_json();
    j["camera"]["principal_point_px"] = {3000, 1024};
    check(j, "camera.principal_point_px", "inside the image");

    j = design_json();
    j["camera"]["width_px"] = 0;
    check(j, "camera.width_px", "width_px must be positive");

    j = pinhole_json();
    j["camera"]["d_max"] = 0.2;
    check(j, "camera.d_max", "pinhole_camera: d_max must be greater than d_min");

    j = design_json();
    j["task"]["min_view_angle"] = 2.0;
    check(j, "task.min_view_angle", "min_view_angle must be in [0, pi/2)");

    j = design_json();
    j["task"]["max_metres_per_pixel"] = -1;
    check(j, "task.max_metres_per_pixel", "must be positive");
}

TEST_CASE("read_camera_task: missing or unreadable files are io_errors, schema errors name the file") {
    temp_dir dir;
    CHECK_THROWS_WITH_AS((void)certipose::read_camera_task(dir.path / "nope.json"),
                         doctest::Contains("no such file"), certipose::io_error);
    CHECK_THROWS_WITH_AS((void)certipose::read_camera_task(dir.path), doctest::Contains("is a directory"),
                         certipose::io_error);
    const fs::path file = dir.path / "cam.json";
    json j = design_json();
    j["camera"]["focal_lenght"] = 1;
    std::ofstream(file) << j.dump();
    try {
        (void)certipose::read_camera_task(file);
        FAIL("no error");
    } catch (const certipose::invalid_argument& e) {
        CHECK(e.field() == "camera.focal_lenght");
        CHECK(std::string(e.what()).rfind(file.string() + ": camera.focal_lenght: unknown field", 0) == 0);
    }
    std::ofstream(file, std::ios::trunc) << "{\"camera\":";
    try {
        (void)certipose::read_camera_task(file);
        FAIL("no error");
    } catch (const certipose::io_error& e) {
        CHECK(e.path() == file.string());
        CHECK(std::string(e.what()).find("line 1, column") != std::string::npos);
    }
}

// ==== result JSON ================================================================================

TEST_CASE_TEMPLATE("the result JSON round-trips every double exactly", I, CERTIPOSE_IO_TEST_BACKENDS) {
    const certipose::rounding_guard<I> guard;
    const auto mesh = tetrahedron();
    const auto in = certipose::parse_camera_task(design_input);
    certipose::solve_options options;
    options.position_eps = 0.1;
    options.orientation_eps = 0.38;
    const auto result = sample_result<I>();
    const certipose::result_document doc =
        certipose::make_result_document(result, mesh, in.camera, in.task, options);

    // The document holds what the solver certified against.
    CHECK(doc.facet.index == 3);
    CHECK(doc.facet.vertices[0] == std::array<double, 3>{1, 0, 0});
    CHECK(doc.facet.normal[0] == mesh.facet(3).normal.x());
    const auto& cam = std::get<certipose::thin_lens_camera>(in.camera);
    CHECK(doc.camera.K[0][0] == cam.intrinsics()(0, 0));
    CHECK(doc.camera.d_min == cam.distance_range().min);
    CHECK(doc.camera.d_max == cam.distance_range().max);
    CHECK(doc.boxes[0].position[1][0] == certipose::lower(result.boxes[0].box.position[1]));

    temp_dir dir;
    const fs::path file = dir.path / "result.json";
    certipose::write_result_json(file, doc);
    CHECK(dir.entries() == 1);
    const certipose::result_document back = certipose::read_result_json(file);
    check_same_document(doc, back);

    // The contract's layout: these keys, this order, K rows, intervals as [lower, upper].
    const auto raw = nlohmann::ordered_json::parse(slurp(file));
    std::vector<std::string> keys;
    for (auto it = raw.begin(); it != raw.end(); ++it) keys.push_back(it.key());
    CHECK(keys == std::vector<std::string>{"format", "version", "facet", "camera", "task", "settings", "occluders", "keep_in",
                                           "keep_out", "boxes", "stats"});
    CHECK(raw["format"] == "certipose-result");
    CHECK(raw["version"].is_number_integer());
    CHECK(raw["version"] == 1);
    CHECK_FALSE(raw["camera"].contains("mount_offset"));  // written only when not zero
    CHECK(raw["camera"]["width_px"].is_number_integer());
    CHECK(raw["camera"]["width_px"] == 2448);
    CHECK(raw["camera"]["K"][2] == json::array({0.0, 0.0, 1.0}));
    CHECK(raw["boxes"][0]["class"] == "valid");
    CHECK(raw["boxes"][1]["class"] == "boundary");
    CHECK(raw["boxes"][1]["position"][0].size() == 2);
    CHECK(raw["stats"]["valid"] == 1);
    CHECK(raw["stats"]["termination"] == "deadline");
    // Extras: why each BOUNDARY box is undecided, counted per reason; occlusion was checked.
    CHECK(raw["boxes"][1]["undecided"] == "view_angle");
    CHECK_FALSE(raw["boxes"][0].contains("undecided"));
    CHECK_FALSE(raw["boxes"][0].contains("occlusion"));
    CHECK(raw["stats"]["boundary_reasons"]["view_angle"] == 1);
    CHECK(raw["stats"]["boundary_reasons"]["occlusion"] == 0);
    CHECK(raw["stats"]["occlusion_checked"] == true);
    CHECK(raw["settings"]["orientation_eps"] == 0.38);
    // One member per line, one box per line: "{", 9 members, "boxes": [, 2 boxes, "],", stats, "}".
    const std::string text = slurp(file);
    CHECK(std::count(text.begin(), text.end(), '\n') == 16);
    CHECK(text.rfind("{\n  \"format\": \"certipose-result\",\n  \"version\": 1,\n  \"facet\": ", 0) == 0);
}

TEST_CASE("a result whose occlusion was not checked says so on every VALID box") {
    using I = certipose::boost_interval;
    const auto mesh = tetrahedron();
    const auto in = certipose::parse_camera_task(design_input);
    auto result = sample_result<I>();
    result.stats.occlusion_checked = false;
    const auto doc = certipose::make_result_document(result, mesh, in.camera, in.task, {});
    const auto raw = certipose::result_to_json(doc);
    CHECK(raw["boxes"][0]["occlusion"] == "unchecked");
    CHECK_FALSE(raw["boxes"][1].contains("occlusion"));  // BOUNDARY boxes certify nothing anyway
    CHECK(raw["stats"]["occlusion_checked"] == false);
    CHECK_FALSE(certipose::result_from_json(nlohmann::json::parse(raw.dump())).stats.occlusion_checked);
}

TEST_CASE("boundary summaries name the reasons, most frequent first") {
    certipose::solve_stats s;
    CHECK(certipose::boundary_summary(s) == "none");
    CHECK_FALSE(certipose::main_boundary_reason(s));
    s.boundary_reasons[static_cast<std::size_t>(certipose::boundary_reason::view_angle)] = 124;
    s.boundary_reasons[static_cast<std::size_t>(certipose::boundary_reason::occlusion)] = 1000;
    CHECK(certipose::boundary_summary(s) == "occlusion 1000, view_angle 124");
    CHECK(certipose::main_boundary_reason(s) == certipose::boundary_reason::occlusion);
    // Reading back: an unknown reason is an error naming the box's path.
    const auto in = certipose::parse_camera_task(design_input);
    const auto doc = certipose::make_result_document(sample_result<certipose::boost_interval>(), tetrahedron(), in.camera,
                                                     in.task, {});
    auto j = nlohmann::json::parse(certipose::result_to_json(doc).dump());
    j["boxes"][1]["undecided"] = "no such reason";
    try {
        (void)certipose::result_from_json(j);
        FAIL("an unknown reason was accepted");
    } catch (const certipose::invalid_argument& e) {
        CHECK(e.field() == "boxes[1].undecided");
    }
}

TEST_CASE("result JSON: random doubles survive the text exactly") {
    std::mt19937_64 rng(20230417);
    certipose::result_document d;
    d.camera.d_max = inf_v;  // written as null, read back as +inf
    std::size_t n = 0;
    const auto random_finite = [&] {
        for (;;) {
            const double v = std::bit_cast<double>(rng());
            if (std::isfinite(v)) return v;
        }
    };
    for (int i = 0; i < 400; ++i) {
        certipose::box_record b;
        b.cls = i % 3 ? certipose::box_class::valid : certipose::box_class::boundary;
        for (int k = 0; k < 3; ++k) {
            const double p0 = random_finite(), p1 = random_finite();
            const double o0 = std::ldexp(random_finite(), -1000);  // tiny and subnormal values
            const double o1 = std::uniform_real_distribution<>(-4, 4)(rng);
            b.position[k] = {std::min(p0, p1), std::max(p0, p1)};
            b.orientation[k] = {std::min(o0, o1), std::max(o0, o1)};
            n += 2;
        }
        d.boxes.push_back(b);
    }
    const auto back = certipose::parse_result_json(certipose::json_text(certipose::result_to_json(d)));
    check_same_document(d, back);
    CHECK(back.camera.d_max == inf_v);
    CHECK(n == 2400);
}

TEST_CASE_TEMPLATE("the result writer refuses what JSON cannot hold, and leaves the old file", I,
                   CERTIPOSE_IO_TEST_BACKENDS) {
    const certipose::rounding_guard<I> guard;
    const auto mesh = tetrahedron();
    const auto in = certipose::parse_camera_task(design_input);
    auto result = sample_result<I>();
    result.boxes[1].box.position[1] = certipose::interval_traits<I>::empty();  // a solver bug
    const auto doc = certipose::make_result_document(result, mesh, in.camera, in.task, {});

    temp_dir dir;
    const fs::path file = dir.path / "result.json";
    std::ofstream(file) << "old";
    CHECK_THROWS_WITH_AS(certipose::write_result_json(file, doc),
                         doctest::Contains("boxes[1].position[1]"), certipose::invalid_argument);
    CHECK(slurp(file) == "old");
    CHECK(dir.entries() == 1);

    auto d = certipose::result_document{};
    d.settings.position_eps = std::numeric_limits<double>::quiet_NaN();
    try {
        (void)certipose::result_to_json(d);
        FAIL("no error");
    } catch (const certipose::invalid_argument& e) {
        CHECK(e.field() == "settings.position_eps");
    }
    d = {};
    d.boxes.push_back({certipose::box_class::valid, {{{1, 0}, {0, 1}, {0, 1}}}, {}});
    CHECK_THROWS_WITH_AS((void)certipose::result_to_json(d), doctest::Contains("lower bound above upper"),
                         certipose::invalid_argument);

    // The facet must be a face of the mesh (here a single triangle, no face 3).
    CHECK_THROWS_AS((void)certipose::make_result_document(sample_result<I>(), certipose::triangle_mesh(
                                                               {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{{0, 1, 2}}}),
                                                           in.camera, in.task, {}),
                    certipose::out_of_range);
}

TEST_CASE("the result reader ignores extra fields and names what is missing or wrong") {
    certipose::result_document d;
    d.boxes.push_back({certipose::box_class::boundary, {{{0, 1}, {0, 1}, {0, 1}}}, {{{0, 1}, {0, 1}, {0, 1}}}});
    const nlohmann::ordered_json good = certipose::result_to_json(d);

    // Extras anywhere are allowed (the contract).
    auto j = good;
    j["program"] = {{"name", "certipose-solve"}};
    j["boxes"][0]["depth"] = 7;
    j["stats"]["orientation_boxes_per_position"] = 3.5;
    CHECK(certipose::parse_result_json(j.dump()).boxes.size() == 1);

    // Extra stats are optional.
    j = good;
    for (const char* k : {"position_valid", "contractions", "seconds_position", "termination"}) j["stats"].erase(k);
    CHECK(certipose::parse_result_json(j.dump()).stats.reason == certipose::termination::completed);

    const auto expect = [](const nlohmann::ordered_json& bad, const std::string& field, const std::string& says) {
        try {
            (void)certipose::parse_result_json(bad.dump(), "r.json");
            FAIL("no error for " << field);
        } catch (const certipose::invalid_argument& e) {
            CHECK(e.field() == field);
            CHECK_MESSAGE(std::string(e.what()).find(says) != std::string::npos, e.what());
        }
    };
    j = good;
    j.erase("boxes");
    expect(j, "boxes", "missing required field");
    j = good;
    j["boxes"][0]["class"] = "maybe";
    expect(j, "boxes[0].class", "unknown class \"maybe\"");
    j = good;
    j["boxes"][0]["position"][2] = {1.0, 0.5};
    expect(j, "boxes[0].position[2]", "above upper bound");
    j = good;
    j["boxes"][0]["orientation"] = {{0, 1}, {0, 1}};
    expect(j, "boxes[0].orientation", "expected an array of 3 arrays of 2 numbers");
    j = good;
    j["camera"]["K"][1][2] = "c_y";
    expect(j, "camera.K[1][2]", "expected a number");
    j = good;
    j["stats"]["valid"] = -1;
    expect(j, "stats.valid", "non-negative integer");
    j = good;
    j["stats"]["termination"] = "bored";
    expect(j, "stats.termination", "unknown termination");
    j = good;
    j["facet"].erase("normal");
    expect(j, "facet.normal", "missing required field");

    CHECK_THROWS_AS((void)certipose::parse_result_json("{\"facet\": }"), certipose::io_error);
}

TEST_CASE("format and version: the result reader accepts none or its own, and names any other") {
    certipose::result_document d;
    d.boxes.push_back({certipose::box_class::valid, {{{0, 1}, {0, 1}, {0, 1}}}, {{{0, 1}, {0, 1}, {0, 1}}}});
    const nlohmann::ordered_json good = certipose::result_to_json(d);
    CHECK(good.begin().key() == "format");
    CHECK(std::next(good.begin()).key() == "version");

    // Files written before the fields existed are version 1; a float 1.0 is 1 too.
    auto j = good;
    j.erase("format");
    j.erase("version");
    CHECK(certipose::parse_result_json(j.dump(), "r.json").boxes.size() == 1);
    j = good;
    j["version"] = 1.0;
    CHECK(certipose::parse_result_json(j.dump(), "r.json").boxes.size() == 1);

    const auto error = [](const nlohmann::ordered_json& bad) -> std::pair<std::string, std::string> {
        try {
            (void)certipose::parse_result_json(bad.dump(), "r.json");
        } catch (const certipose::invalid_argument& e) {
            return {e.field(), e.what()};
        }
        FAIL("no error for " << bad.dump());
        return {};
    };
    j = good;
    j["version"] = 2;
    CHECK(error(j) == std::pair<std::string, std::string>{"version", "r.json: \"version\": 2 is not supported (this build reads version 1)"});
    j["version"] = "1";
    CHECK(error(j).second == "r.json: \"version\": \"1\" is not supported (this build reads version 1)");
    j = good;
    j["format"] = "certipose-plan";
    CHECK(error(j) == std::pair<std::string, std::string>{
                          "format", "r.json: \"format\": \"certipose-plan\" is not supported here (expected \"certipose-result\")"});
    j["format"] = json::array({1, 2});  // the format is checked before the version
    j["version"] = 7;
    CHECK(error(j).second == "r.json: \"format\": an array of 2 is not supported here (expected \"certipose-result\")");

    // The camera/task input takes an optional "version": 1, and no "format".
    json in = design_json();
    in["version"] = 1;
    CHECK_NOTHROW((void)certipose::parse_camera_task(in.dump(), "cam.json"));
    in["version"] = 3;
    const auto e = input_error(in);
    CHECK(e.field() == "version");
    CHECK(std::string(e.what()) == "cam.json: \"version\": 3 is not supported (this build reads version 1)");
    in = design_json();
    in["format"] = "certipose-camera";
    expect_input_error(in, "format", "unknown field (top-level fields: version, camera, task)");
}

TEST_CASE("camera.mount_offset: optional, finite, kept by camera_task and written back in every camera record") {
    using I = certipose::boost_interval;
    json j = design_json();
    CHECK(certipose::parse_camera_task(j.dump()).mount_offset == std::array<double, 3>{});
    j["camera"]["mount_offset"] = nullptr;  // null: the default, as for the other optional fields
    CHECK(certipose::parse_camera_task(j.dump()).mount_offset == std::array<double, 3>{});
    j["camera"]["mount_offset"] = {0.01, -0.02, 0.1 / 3};
    const auto in = certipose::parse_camera_task(j.dump());
    CHECK(in.mount_offset == std::array<double, 3>{0.01, -0.02, 0.1 / 3});
    json p = pinhole_json();
    p["camera"]["mount_offset"] = {0, 0, -0.0};  // −0 reads as +0: the same point
    const auto pin = certipose::parse_camera_task(p.dump());
    CHECK(pin.mount_offset == std::array<double, 3>{});
    CHECK_FALSE(std::signbit(pin.mount_offset[2]));

    // camera_task_to_json writes it back (when not zero).
    const auto back = certipose::parse_camera_task(certipose::json_text(certipose::camera_task_to_json(in)));
    CHECK(back.mount_offset == in.mount_offset);
    CHECK_FALSE(certipose::camera_task_to_json(pin)["camera"].contains("mount_offset"));

    // The result document of the input keeps it; the result JSON writes and reads it exactly.
    certipose::solve_result<I> result;
    result.facet_index = 3;
    const certipose::result_document doc = certipose::make_result_document(result, tetrahedron(), in, {});
    CHECK(doc.camera.mount_offset == in.mount_offset);
    const auto raw = certipose::result_to_json(doc);
    CHECK(raw["camera"]["mount_offset"] == json::array({0.01, -0.02, 0.1 / 3}));
    CHECK(certipose::parse_result_json(certipose::json_text(raw)).camera == doc.camera);
    auto other = doc;
    other.camera.mount_offset[1] = std::nextafter(-0.02, 0.0);
    CHECK_FALSE(other.camera == doc.camera);

    // Bad values name the path.
    j["camera"]["mount_offset"] = {0.01, 0.02};
    expect_input_error(j, "camera.mount_offset", "expected an array of 3 numbers, got an array of 2");
    j["camera"]["mount_offset"] = {0.01, "0.02", 0};
    expect_input_error(j, "camera.mount_offset[1]", "expected a number, got string \"0.02\"");
    p["camera"]["mount_offset"] = "front";
    expect_input_error(p, "camera.mount_offset", "expected an array of 3 numbers");
    auto r = raw;
    r["camera"]["mount_offset"] = {0, 0};
    CHECK_THROWS_WITH_AS((void)certipose::parse_result_json(r.dump()),
                         "camera.mount_offset: expected an array of 3 numbers, got an array of 2", certipose::invalid_argument);
    // Not finite: only from a document built in code (JSON text cannot hold it).
    json nan_offset = design_json();
    nan_offset["camera"]["mount_offset"] = {0.0, std::nan(""), 0.0};
    CHECK_THROWS_WITH_AS((void)certipose::camera_task_from_json(nan_offset),
                         doctest::Contains("camera.mount_offset[1]: must be a finite number of metres"), certipose::invalid_argument);
}

// ==== atomic writes ==============================================================================

TEST_CASE("write_file_atomically replaces the whole content or nothing") {
    temp_dir dir;
    const fs::path file = dir.path / "out.txt";
    certipose::write_file_atomically(file, "first");
    CHECK(slurp(file) == "first");
    const std::string big(1 << 20, 'x');
    certipose::write_file_atomically(file, big);
    CHECK(slurp(file) == big);
    CHECK(dir.entries() == 1);  // no temporary file left behind
    certipose::write_file_atomically(file, "");
    CHECK(fs::file_size(file) == 0);

    // Target directory missing: io_error naming the path, nothing created anywhere.
    const fs::path missing = dir.path / "no" / "such" / "dir" / "out.json";
    try {
        certipose::write_file_atomically(missing, "data");
        FAIL("no error");
    } catch (const certipose::io_error& e) {
        CHECK(e.path() == missing.string());
        CHECK(std::string(e.what()).find("No such file or directory") != std::string::npos);
    }
    CHECK_FALSE(fs::exists(dir.path / "no"));
    CHECK(dir.entries() == 1);

    // A directory in the way is not replaced.
    fs::create_directory(dir.path / "sub");
    CHECK_THROWS_AS(certipose::write_file_atomically(dir.path / "sub", "data"), certipose::io_error);
    CHECK(fs::is_directory(dir.path / "sub"));
    CHECK(dir.entries() == 2);

    CHECK_THROWS_AS(certipose::write_file_atomically("", "data"), certipose::io_error);
    CHECK_THROWS_AS(certipose::write_json_file(dir.path / "none" / "r.json", nlohmann::ordered_json::object()),
                    certipose::io_error);
}

TEST_CASE("output_files: every output of a run is committed together, or none is") {
    temp_dir dir;
    const fs::path a = dir.path / "result.json", b = dir.path / "boxes.ply";
    std::ofstream(a) << "old result";
    {
        // The second file cannot be written: the first target keeps its old content and no
        // temporary file is left (the situation of a JSON written before a failing PLY).
        certipose::output_files files;
        files.add(a, "new result");
        CHECK_THROWS_AS(files.add(dir.path / "missing" / "boxes.ply", "ply"), certipose::io_error);
    }
    CHECK(slurp(a) == "old result");
    CHECK(dir.entries() == 1);
    {
        // Staged but never committed (an exception, or a signal before commit): discarded.
        certipose::output_files files;
        files.add(a, "new result");
        files.stream(b) << "streamed ";
        files.stream(b) << "ply";
        CHECK(dir.entries() == 3);  // the old file and two temporaries
    }
    CHECK(slurp(a) == "old result");
    CHECK_FALSE(fs::exists(b));
    CHECK(dir.entries() == 1);
    certipose::output_files files;
    files.add(a, "new result");
    files.stream(b) << "streamed ply";
    files.commit();
    CHECK(slurp(a) == "new result");
    CHECK(slurp(b) == "streamed ply");
    CHECK(dir.entries() == 2);
}

TEST_CASE("refuse_overwriting_inputs: an input under another name, a link or a second output is refused") {
    temp_dir dir;
    const fs::path mesh = dir.path / "part.off", cam = dir.path / "camera.json";
    std::ofstream(mesh) << "OFF\n";
    std::ofstream(cam) << "{}";
    fs::create_symlink(mesh, dir.path / "link.off");
    fs::create_hard_link(cam, dir.path / "hard.json");
    const std::vector<certipose::named_path> inputs{{"--mesh", mesh}, {"--camera", cam}};
    const auto refused = [&](const fs::path& out, const fs::path& second = {}) -> std::string {
        std::vector<certipose::named_path> outputs{{"--out", out}};
        if (!second.empty()) outputs.push_back({"--ply", second});
        try {
            certipose::refuse_overwriting_inputs(inputs, outputs);
        } catch (const certipose::invalid_argument& e) {
            return e.what();
        }
        return {};
    };
    CHECK(refused(mesh).find("is the input --mesh") != std::string::npos);
    CHECK(refused(dir.path / "." / "part.off").find("is the input --mesh") != std::string::npos);
    CHECK(refused(dir.path / "link.off").find("is the input --mesh") != std::string::npos);
    CHECK(refused(dir.path / "hard.json").find("is the input --camera") != std::string::npos);
    CHECK(refused(dir.path / "r.json", dir.path / "x" / ".." / "r.json").find("same file as --out") != std::string::npos);
    CHECK(refused(dir.path / "r.json", dir.path / "b.ply").empty());
    CHECK(refused(dir.path / "new" / "r.json").empty());  // not existing yet, and not an input
}

// ==== PLY ========================================================================================

TEST_CASE_TEMPLATE("the PLY holds the part, the facet and one outward solid per box, in colour", I,
                   CERTIPOSE_IO_TEST_BACKENDS) {
    const certipose::rounding_guard<I> guard;
    const auto mesh = tetrahedron();
    auto result = sample_result<I>();
    result.boxes[1].box.position = certipose::position_box<I>::from_bounds({{{0.5, 0.75}, {1.0 / 3, 2.0}, {-1, 0.1}}});
    const certipose::ply_options opt;
    temp_dir dir;
    const fs::path file = dir.path / "boxes.ply";
    certipose::write_ply(file, mesh, result, opt);
    const ply_file ply = read_ply(slurp(file));

    CHECK(ply.header[0] == "ply");
    CHECK(ply.header[1] == "format ascii 1.0");
    CHECK(std::find(ply.header.begin(), ply.header.end(), "property list uchar int vertex_indices") != ply.header.end());
    CHECK(ply.header_vertices == 4 + 3 + 8 * 2);
    CHECK(ply.header_faces == 3 + 1 + 12 * 2);
    CHECK(ply.vertices.size() == ply.header_vertices);
    CHECK(ply.faces.size() == ply.header_faces);

    // Part (all faces but the facet), facet, then the boxes in order.
    for (std::size_t f = 0; f < 3; ++f) CHECK(ply.face_colours[f] == colour(opt.part_colour));
    CHECK(ply.face_colours[3] == colour(opt.facet_colour));
    const auto& facet_face = ply.faces[3];
    for (int k = 0; k < 3; ++k) {
        CHECK(ply.vertex_colours[facet_face[k]] == colour(opt.facet_colour));
        for (int d = 0; d < 3; ++d) CHECK(ply.vertices[facet_face[k]][d] == mesh.facet(3).v[k][d]);
    }
    for (std::size_t b = 0; b < 2; ++b) {
        const auto want = colour(b == 0 ? opt.valid_colour : opt.boundary_colour);
        const std::size_t first_face = 4 + 12 * b;
        for (std::size_t f = first_face; f < first_face + 12; ++f) {
            CHECK(ply.face_colours[f] == want);
            for (auto v : ply.faces[f]) CHECK(ply.vertex_colours[v] == want);
        }
        // The corners are exactly the interval bounds, and the solid encloses the box's volume
        // with outward normals.
        double volume = 1;
        for (int d = 0; d < 3; ++d) {
            const double lo = certipose::lower(result.boxes[b].box.position[d]);
            const double hi = certipose::upper(result.boxes[b].box.position[d]);
            volume *= hi - lo;
            for (std::size_t v = 7 + 8 * b; v < 7 + 8 * (b + 1); ++v)
                CHECK((ply.vertices[v][d] == lo || ply.vertices[v][d] == hi));
        }
        CHECK(six_volume(ply, first_face, 12) == doctest::Approx(6 * volume).epsilon(1e-9));
    }
}

TEST_CASE("PLY options: without the part, with aim needles, bad input is refused") {
    const auto mesh = tetrahedron();
    std::vector<certipose::box_record> boxes(3);
    for (auto& b : boxes) {
        b.position = {{{-1, -0.9}, {-1, -0.9}, {-1, -0.9}}};
        b.orientation = {{{0.1, 0.2}, {2.0, 2.1}, {-1, 1}}};
    }
    certipose::ply_options opt;
    opt.part = false;
    opt.aim = true;
    const ply_file ply = read_ply(certipose::ply_text(mesh, 3, boxes, opt));
    CHECK(ply.header_vertices == 3 + 8 * 3 + 8 * 3);
    CHECK(ply.header_faces == 1 + 12 * 3 + 12 * 3);
    // Needles are outward solids too, in the aim colour, starting at the box centre.
    const std::size_t first = 1 + 12 * 3;
    for (std::size_t n = 0; n < 3; ++n) {
        CHECK(ply.face_colours[first + 12 * n] == colour(opt.aim_colour));
        CHECK(six_volume(ply, first + 12 * n, 12) > 0);
    }

    CHECK_THROWS_AS((void)certipose::ply_text(mesh, 4, boxes), certipose::out_of_range);
    boxes[2].position[0][1] = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_WITH_AS((void)certipose::ply_text(mesh, 3, boxes), doctest::Contains("boxes[2].position"),
                         certipose::invalid_argument);
    temp_dir dir;
    CHECK_THROWS_AS(certipose::write_ply(dir.path / "missing" / "b.ply", mesh, 3, {}), certipose::io_error);
    CHECK(dir.entries() == 0);
}

// ==== certipose-solve command line ===============================================================

namespace {

struct cli_run {
    certipose_solve::parse_outcome outcome;
    std::string out, err;
};

cli_run run_cli(std::vector<std::string> args) {
    args.insert(args.begin(), "certipose-solve");
    std::vector<const char*> argv;
    for (const auto& a : args) argv.push_back(a.c_str());
    std::ostringstream out, err;
    cli_run r;
    r.outcome = certipose_solve::parse_arguments(static_cast<int>(argv.size()), argv.data(), out, err);
    r.out = out.str();
    r.err = err.str();
    return r;
}

}  // namespace

TEST_CASE("certipose-solve: a full command line parses into the arguments") {
    temp_dir dir;
    const std::string mesh = (dir.path / "part.off").string(), cam = (dir.path / "cam.json").string();
    std::ofstream(mesh) << "OFF\n";
    std::ofstream(cam) << "{}";
    const std::string out = (dir.path / "r.json").string(), ply = (dir.path / "b.ply").string();

    auto r = run_cli({"--mesh", mesh, "--facet", "17", "--camera", cam, "--position-eps", "0.1",
                      "--orientation-eps", "3.8e-1", "--out", out, "--ply", ply, "--occlusion", "boolean",
                      "--scale", "0.001", "--max-boxes", "5000", "--time-limit", "2.5", "--corner-rest", "2",
                      "--quiet"});
    REQUIRE_MESSAGE(r.outcome.args, r.err);
    const auto& a = *r.outcome.args;
    CHECK(a.inputs.mesh == mesh);
    CHECK(a.facet == 17);
    CHECK(a.inputs.camera == cam);
    CHECK(a.solve.position_eps == 0.1);
    CHECK(a.solve.orientation_eps == 0.38);
    CHECK(a.out == out);
    CHECK(a.ply == fs::path(ply));
    CHECK(a.occlusion == certipose::occlusion_choice::boolean);
    CHECK(a.inputs.scale == 0.001);
    CHECK(a.solve.max_boxes == 5000u);
    CHECK(a.solve.time_limit == 2.5);
    CHECK(a.solve.corner_rest == 2.0);
    CHECK(a.quiet);
    CHECK(r.err.empty());

    // Defaults.
    r = run_cli({"--mesh", mesh, "--facet", "0", "--camera", cam, "--position-eps", "0.1",
                 "--orientation-eps", "0.38", "--out", out});
    REQUIRE(r.outcome.args);
    CHECK(r.outcome.args->occlusion == certipose::occlusion_choice::aabb);
    CHECK(r.outcome.args->inputs.scale == 1.0);
    CHECK_FALSE(r.outcome.args->ply);
    CHECK_FALSE(r.outcome.args->solve.max_boxes);
    CHECK_FALSE(r.outcome.args->quiet);

    r = run_cli({"--help"});
    CHECK_FALSE(r.outcome.args);
    CHECK(r.outcome.exit_code == 0);
    CHECK(r.out.find("--orientation-eps") != std::string::npos);
}

TEST_CASE("certipose-solve: every command-line mistake is one error line and exit code 2") {
    temp_dir dir;
    const std::string mesh = (dir.path / "part.off").string(), cam = (dir.path / "cam.json").string();
    std::ofstream(mesh) << "OFF\n";
    std::ofstream(cam) << "{}";
    const std::string out = (dir.path / "r.json").string();
    const std::vector<std::string> good{"--mesh", mesh, "--facet", "3", "--camera", cam, "--position-eps",
                                        "0.1", "--orientation-eps", "0.38", "--out", out};
    const auto with = [&](const std::string& option, const std::string& value) {
        auto args = good;
        const auto it = std::find(args.begin(), args.end(), option);
        if (it == args.end()) {
            args.push_back(option);
            args.push_back(value);
        } else {
            *(it + 1) = value;
        }
        return args;
    };
    const auto without = [&](const std::string& option) {
        auto args = good;
        const auto it = std::find(args.begin(), args.end(), option);
        args.erase(it, it + 2);
        return args;
    };
    struct bad_case {
        std::vector<std::string> args;
        std::string says;
    };
    const std::vector<bad_case> cases{
        {without("--mesh"), "--mesh is required"},
        {without("--out"), "--out is required"},
        {without("--position-eps"), "--position-eps is required"},
        {with("--mesh", (dir.path / "nope.off").string()), "--mesh"},
        {with("--camera", (dir.path / "nope.json").string()), "--camera"},
        {with("--facet", "-1"), "--facet"},
        {with("--facet", "1.5"), "--facet: expected an integer >= 0, got '1.5'"},
        {with("--corner-rest", "-1"), "--corner-rest: expected a finite number >= 0, got -1"},
        {with("--corner-rest", "three"), "--corner-rest: expected a number >= 0, got 'three'"},
        {with("--facet", "99999999999999999999999"), "--facet: 99999999999999999999999 is too large"},
        {with("--position-eps", "0"), "--position-eps: must be a positive finite number of metres, got 0"},
        {with("--position-eps", "abc"), "--position-eps: expected a positive finite number of metres, got 'abc'"},
        {with("--orientation-eps", "nan"), "--orientation-eps: must be"},
        {with("--orientation-eps", "0.38rad"), "--orientation-eps: expected"},
        {with("--scale", "-2"), "--scale"},
        {with("--max-boxes", "0"), "--max-boxes: expected an integer >= 1, got 0"},
        {with("--time-limit", "inf"), "--time-limit: must be"},
        {with("--occlusion", "raycast"), "--occlusion"},
        {with("--out", (dir.path / "missing" / "r.json").string()), "--out: directory does not exist"},
        {with("--out", dir.path.string()), "is a directory"},
        // An output that is an input or the other output, under any spelling (issue: `--out
        // part.off` used to replace the mesh and exit 0).
        {with("--ply", out), "--ply " + out + " is the same file as --out"},
        {with("--out", mesh), "--out " + mesh + " is the input --mesh"},
        {with("--out", (dir.path / "." / "part.off").string()), "is the input --mesh"},
        {with("--out", (dir.path / "." / "cam.json").string()), "is the input --camera"},
        {with("--ply", mesh), "--ply " + mesh + " is the input --mesh"},
        {with("--frobnicate", "1"), "--frobnicate"},
        // A tuning of carving that --paper-paving would ignore is named, not dropped.
        {[&] { auto a = with("--corner-depth", "3"); a.push_back("--paper-paving"); return a; }(),
         "--corner-depth tunes the default paving; --paper-paving has no corner boxes"},
        {with("--corner-depth", "9"), "--corner-depth: expected an integer from 1 to 8, got 9"},
    };
    for (const auto& c : cases) {
        std::string line;
        for (const auto& a : c.args) line += a + " ";
        CAPTURE(line);
        const auto r = run_cli(c.args);
        CHECK_FALSE(r.outcome.args);
        CHECK(r.outcome.exit_code == certipose_solve::exit_usage);
        CHECK(r.out.empty());
        CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
        CHECK(r.err.rfind("certipose-solve: error: ", 0) == 0);
        CHECK_MESSAGE(r.err.find(c.says) != std::string::npos, r.err);
    }
}
