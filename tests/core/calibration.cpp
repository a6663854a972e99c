// Tests for calibration files (io/calibration.hpp) and their use in the camera JSON
// (io/json.hpp): OpenCV FileStorage YAML and JSON and ROS camera_info YAML are parsed to K, the
// image size and the distortion; each malformed value names its key path; the format is chosen
// by content; "camera.calibration" is resolved relative to the JSON file; max_blur_px is
// max_blur_circle in pixels.
#include <certipose/io/calibration.hpp>
#include <certipose/io/json.hpp>

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <variant>

namespace fs = std::filesystem;

namespace {

const char* opencv_yaml = R"(%YAML:1.0
---
image_width: 2448
image_height: 2048
camera_matrix: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 3478.26, 0., 1230.5, 0., 3480.1, 1019.25, 0., 0., 1. ]
distortion_coefficients: !!opencv-matrix
   rows: 1
   cols: 5
   dt: d
   data: [ -0.3, 0.1, 0.001, -0.0005, 0. ]
)";

const char* opencv_json = R"({
    "image_width": 2448,
    "image_height": 2048,
    "camera_matrix": {"type_id": "opencv-matrix", "rows": 3, "cols": 3, "dt": "d",
                      "data": [3478.26, 0.0, 1230.5, 0.0, 3480.1, 1019.25, 0.0, 0.0, 1.0]},
    "distortion_coefficients": {"type_id": "opencv-matrix", "rows": 8, "cols": 1, "dt": "d",
                                "data": [0.2, -0.1, 0.0, 0.0, 0.01, 0.05, 0.0, 0.0]}
})";

const char* ros_yaml = R"(image_width: 2448
image_height: 2048
camera_name: inspection_cam
camera_matrix:
  rows: 3
  cols: 3
  data: [3478.26, 0, 1230.5, 0, 3480.1, 1019.25, 0, 0, 1]
distortion_model: plumb_bob
distortion_coefficients:
  rows: 1
  cols: 5
  data: [0.3, 0.1, 0, 0, 0]
rectification_matrix:
  rows: 3
  cols: 3
  data: [1, 0, 0, 0, 1, 0, 0, 0, 1]
projection_matrix:
  rows: 3
  cols: 4
  data: [3478.26, 0, 1230.5, 0, 0, 3480.1, 1019.25, 0, 0, 0, 1, 0]
)";

fs::path scratch_dir() {
    static const fs::path dir = [] {
        std::random_device rd;
        const fs::path d = fs::temp_directory_path() / ("certipose-calibration-" + std::to_string(rd()));
        fs::create_directories(d);
        return d;
    }();
    return dir;
}

fs::path write(const std::string& name, const std::string& text) {
    const fs::path p = scratch_dir() / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
    return p;
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
    const auto at = s.find(from);
    REQUIRE(at != std::string::npos);
    return s.replace(at, from.size(), to);
}

/// field() and what() of the invalid_argument parse_calibration throws.
std::pair<std::string, std::string> error_of(const std::string& text) {
    try {
        (void)certipose::parse_calibration(text, "cal.yaml");
    } catch (const certipose::invalid_argument& e) {
        return {e.field(), e.what()};
    }
    FAIL("no invalid_argument");
    return {};
}

}  // namespace

TEST_CASE("calibration: the three formats are detected by content and parsed") {
    using certipose::calibration_format;
    CHECK(certipose::detect(opencv_yaml) == calibration_format::opencv_yaml);
    CHECK(certipose::detect(opencv_json) == calibration_format::opencv_json);
    CHECK(certipose::detect(ros_yaml) == calibration_format::ros_yaml);
    CHECK(certipose::detect(R"({"camera": {"model": "pinhole"}})") == calibration_format::unknown);

    const auto a = certipose::parse_calibration(opencv_yaml, "a.yaml");
    CHECK(a.format == "opencv_yaml");
    CHECK(a.width_px == 2448);
    CHECK(a.height_px == 2048);
    CHECK(a.K(0, 0) == 3478.26);
    CHECK(a.K(1, 1) == 3480.1);
    CHECK(a.K(0, 2) == 1231.0);  // OpenCV's pixel centres are at whole numbers, certipose's at halves
    CHECK(a.K(1, 2) == 1019.75);
    CHECK(a.K(2, 2) == 1.0);
    CHECK(a.distortion.k1 == -0.3);
    CHECK(a.distortion.p2 == -0.0005);

    const auto b = certipose::parse_calibration(opencv_json, "b.json");
    CHECK(b.format == "opencv_json");
    CHECK(b.K(1, 2) == 1019.75);
    CHECK(b.distortion.count() == 8);
    CHECK(b.distortion.k4 == 0.05);

    const auto c = certipose::parse_calibration(ros_yaml, "c.yaml");
    CHECK(c.format == "ros_yaml");
    CHECK(c.K(0, 0) == 3478.26);
    CHECK(c.distortion.k1 == 0.3);
    CHECK(c.distortion.k2 == 0.1);

    // A file with none of the formats' marks.
    CHECK_THROWS_AS((void)certipose::parse_calibration("hello: world\n", "x.yaml"), certipose::io_error);
    CHECK_THROWS_AS((void)certipose::read_calibration(scratch_dir() / "missing.yaml"), certipose::io_error);
}

TEST_CASE("calibration: each malformed value names its key") {
    const std::string y = opencv_yaml, r = ros_yaml;
    CHECK(error_of(replaced(y, "rows: 3", "rows: 2")).first == "camera_matrix.data");
    CHECK(error_of(replaced(y, "data: [ 3478.26, 0., 1230.5, 0., 3480.1, 1019.25, 0., 0., 1. ]",
                            "data: [ 3478.26, 0., 1230.5, 0., 3480.1, 1019.25 ]"))
              .first == "camera_matrix.data");
    CHECK(error_of(replaced(y, "image_width: 2448\n", "")).first == "image_width");
    CHECK(error_of(replaced(y, "3480.1", ".nan")).first == "camera_matrix.data[4]");
    CHECK(error_of(replaced(y, "3480.1", "-3480.1")).first == "camera_matrix.data[4]");
    CHECK(error_of(replaced(y, "0., 0., 1. ]", "0., 0., 2. ]")).first == "camera_matrix.data[8]");
    CHECK(error_of(replaced(y, "1230.5", "2500")).first == "camera_matrix.data[2]");
    CHECK(error_of(replaced(y, "-0.3, 0.1, 0.001", "-0.3, abc, 0.001")).first == "distortion_coefficients.data[1]");
    CHECK(error_of(replaced(y, "cols: 5", "cols: 3")).first == "distortion_coefficients.data");
    CHECK(error_of(replaced(y, "   dt: d\n   data: [ 3478.26", "   data: [ 3478.26")).first == "camera_matrix.dt");
    const auto fisheye = error_of(replaced(r, "plumb_bob", "equidistant"));
    CHECK(fisheye.first == "distortion_model");
    CHECK(fisheye.second.find("fisheye") != std::string::npos);
    CHECK(fisheye.second.rfind("cal.yaml: ", 0) == 0);
    CHECK(error_of(replaced(r, "plumb_bob", "rational_polynomial")).first == "distortion_coefficients.data");
    CHECK(error_of(replaced(r, "cols: 4", "cols: 3")).first == "projection_matrix.data");
    // Syntax errors are io_errors naming the line.
    try {
        (void)certipose::parse_calibration(replaced(r, "data: [3478.26, 0, 1230.5", "data: [3478.26, 0, [1230.5"), "c.yaml");
        FAIL("accepted");
    } catch (const certipose::io_error& e) {
        CHECK(std::string(e.what()).find("line") != std::string::npos);
    }
    CHECK_THROWS_AS((void)certipose::parse_calibration(std::string(opencv_json) + "}", "b.json"), certipose::io_error);
}

TEST_CASE("calibration: the camera JSON references a calibration file relative to itself") {
    write("cal/opencv.yaml", opencv_yaml);
    const std::string json = R"({"camera": {"model": "thin_lens", "calibration": "cal/opencv.yaml", "focal_length": 0.012,
                                 "f_stop": 8, "focus_distance": 0.6, "max_blur_px": 2, "image_margin_px": 4},
                     "task": {"min_view_angle": 0.35}})";
    const fs::path p = write("inputs/camera.json", json);
    write("inputs/cal/opencv.yaml", opencv_yaml);
    const certipose::camera_task t = certipose::read_camera_task(p);
    const auto& cam = std::get<certipose::thin_lens_camera>(t.camera);
    CHECK(cam.intrinsics()(0, 0) == doctest::Approx(3478.26).epsilon(1e-15));
    CHECK(cam.intrinsics()(1, 1) == doctest::Approx(3480.1).epsilon(1e-15));
    CHECK(cam.principal_point_px().x() == 1231.0);
    CHECK(cam.width_px() == 2448);
    CHECK(cam.pixel_pitch() == doctest::Approx(0.012 / 3478.26));
    CHECK(cam.max_blur_circle() == doctest::Approx(2 * 0.012 / 3478.26));
    REQUIRE(t.distortion.has_value());
    CHECK(t.distortion->k1 == -0.3);
    CHECK(t.image_margin_px == 4);
    const certipose::calibrated_camera c = t.calibrated();
    CHECK(c.distortion().has_value());
    CHECK(c.margin_px() == 4);
    // The sensor fields may not be given twice.
    const auto field = [&](const std::string& text) -> std::string {
        try {
            (void)certipose::parse_camera_task(text, "camera.json", p.parent_path());
        } catch (const certipose::invalid_argument& e) {
            return e.field();
        }
        return "(accepted)";
    };
    CHECK(field(replaced(json, "\"focal_length\": 0.012", "\"focal_length\": 0.012, \"width_px\": 100")) == "camera.width_px");
    CHECK(field(replaced(json, "\"focal_length\": 0.012", "\"focal_length\": 0.012, \"pixel_pitch\": 3e-6")) ==
          "camera.pixel_pitch");
    CHECK(field(replaced(json, "\"focal_length\": 0.012,", "")) == "camera.focal_length");
    CHECK(field(replaced(json, "\"max_blur_px\": 2", "\"max_blur_px\": 2, \"max_blur_circle\": 1e-5")) == "camera.max_blur_px");
    CHECK(field(replaced(json, "\"image_margin_px\": 4", "\"image_margin_px\": -1")) == "camera.image_margin_px");
    CHECK(field(replaced(json, "\"image_margin_px\": 4",
                         "\"image_margin_px\": 4, \"distortion_coefficients\": [0, 0, 0, 0]")) ==
          "camera.distortion_coefficients");
    // read_camera_input chooses by content.
    CHECK(std::holds_alternative<certipose::camera_task>(certipose::read_camera_input(p)));
    const auto direct = certipose::read_camera_input(write("direct.yaml", ros_yaml));
    REQUIRE(std::holds_alternative<certipose::calibration>(direct));
    const certipose::camera_task from = certipose::camera_task_from_calibration(
        std::get<certipose::calibration>(direct), {0.2, 0.8}, certipose::inspection_task{.min_view_angle = 0.35});
    CHECK(std::get<certipose::pinhole_camera>(from.camera).intrinsics()(0, 0) == doctest::Approx(3478.26).epsilon(1e-15));
    CHECK(from.distortion->k1 == 0.3);
}

TEST_CASE("calibration: camera JSON distortion, margin and max_blur_px") {
    const std::string base = R"({"camera": {"model": "thin_lens", "focal_length": 0.012, "f_stop": 8, "focus_distance": 0.6,
        "max_blur_circle": 6.9e-6, "pixel_pitch": 3.45e-6, "width_px": 2448, "height_px": 2048},
        "task": {"min_view_angle": 0.35}})";
    const certipose::camera_task plain = certipose::parse_camera_task(base);
    CHECK(!plain.distortion);
    const certipose::camera_task px =
        certipose::parse_camera_task(replaced(base, "\"max_blur_circle\": 6.9e-6", "\"max_blur_px\": 2"));
    CHECK(std::get<certipose::thin_lens_camera>(px.camera).max_blur_circle() == 2 * 3.45e-6);
    CHECK(std::get<certipose::thin_lens_camera>(px.camera).distance_range().min ==
          std::get<certipose::thin_lens_camera>(plain.camera).distance_range().min);
    const certipose::camera_task d = certipose::parse_camera_task(
        replaced(base, "\"width_px\"", "\"distortion_coefficients\": [0.3, 0.1, 0, 0], \"image_margin_px\": 2, \"width_px\""));
    REQUIRE(d.distortion);
    CHECK(d.distortion->k1 == 0.3);
    CHECK(d.image_margin_px == 2);
    // Written back and read again: the same camera.
    const certipose::camera_task back = certipose::parse_camera_task(certipose::camera_task_to_json(d).dump());
    CHECK(back.distortion == d.distortion);
    CHECK(back.image_margin_px == 2);
    const auto field = [&](const std::string& text) -> std::string {
        try {
            (void)certipose::parse_camera_task(text);
        } catch (const certipose::invalid_argument& e) {
            return e.field();
        }
        return "(accepted)";
    };
    CHECK(field(replaced(base, "\"width_px\"", "\"distortion_coefficients\": [0.3, 0.1, 0], \"width_px\"")) ==
          "camera.distortion_coefficients");
    CHECK(field(replaced(base, "\"width_px\"", "\"distortion_coefficients\": [0.3, 0.1, 0, \"x\"], \"width_px\"")) ==
          "camera.distortion_coefficients[3]");
    CHECK(field(replaced(base, "\"width_px\"", "\"distortion_coefficients\": [0, 0, 0, 0, 0, -1e9, 0, 0], \"width_px\"")) ==
          "camera.distortion_coefficients");
    CHECK(field(replaced(base, "\"max_blur_circle\": 6.9e-6", "\"max_blur_px\": -1")) == "camera.max_blur_px");
    CHECK(field(replaced(base, "\"max_blur_circle\": 6.9e-6,", "")) == "camera.max_blur_circle");
    CHECK(field(replaced(base, "\"width_px\"", "\"calibration\": \"none.yaml\", \"width_px\"")) == "camera.width_px");
}

TEST_CASE("calibration: an OpenCV JSON nested a hundred thousand levels deep is refused, not a stack overflow") {
    const std::string deep = std::string(100000, '[') + std::string(100000, ']');
    const std::string text = R"({"camera_matrix": {"type_id": "opencv-matrix", "rows": 3, "cols": 3, "dt": "d", "data": )" +
                             deep + "}}";
    CHECK_THROWS_WITH_AS(certipose::parse_calibration(text, "deep.json"), doctest::Contains("nested deeper than 32 levels"),
                         certipose::io_error);
}
