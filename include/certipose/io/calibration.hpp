// certipose/io/calibration.hpp — camera calibration files: OpenCV FileStorage (YAML or JSON) and
// ROS camera_info YAML, read to K, the image size and the Brown–Conrady distortion.
//
// Needs yaml-cpp (Debian libyaml-cpp-dev, CMake target yaml-cpp) and nlohmann-json. The format is
// chosen by content (`detect`), not by the file name: OpenCV's YAML starts with the "%YAML:1.0"
// directive (which yaml-cpp rejects, so it is turned into a comment before parsing, keeping line
// numbers) and tags its matrices `!!opencv-matrix` {rows, cols, dt, data}; OpenCV's JSON writes
// the same matrices as objects with "type_id": "opencv-matrix"; ROS camera_info YAML has
// camera_name, distortion_model and {rows, cols, data} matrices. Both JSON and YAML go through one
// validation: the JSON is parsed strictly by nlohmann and converted to a YAML node.
// The reader is strict, because a calibration drives a certificate: every value is checked (K's
// third row is (0, 0, 1), fx, fy > 0, K(1,0) = 0, the principal point inside the image, rows·cols
// equal to the data's length, finite numbers, 4/5/8 distortion coefficients). A bad value is an
// invalid_argument whose field() is its key path ("camera_matrix.data[4]") and whose message
// starts with the file name; an unreadable file or a syntax error is an io_error (with the line).
// K is returned in certipose's pixel convention: OpenCV's c_x, c_y plus 0.5 (docs/conventions.md).
// ROS's rectification and projection matrices are checked for shape but not used: the solver
// certifies poses for the raw (distorted, unrectified) image, which K and D describe. Fisheye
// ("equidistant") calibrations are refused: certipose has no certified fisheye model.
#pragma once

#include "certipose/camera/distortion.hpp"
#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"
#include "certipose/interval/detail/fenv.hpp"

#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace certipose {

/// The calibration file formats certipose reads.
enum class calibration_format { opencv_yaml, opencv_json, ros_yaml, unknown };

inline const char* to_string(calibration_format f) noexcept {
    switch (f) {
        case calibration_format::opencv_yaml: return "opencv_yaml";
        case calibration_format::opencv_json: return "opencv_json";
        case calibration_format::ros_yaml: return "ros_yaml";
        case calibration_format::unknown: break;
    }
    return "unknown";
}

/// A camera calibration: K (pixels), the image size and the lens distortion. `format` names the
/// file format it was read from (to_string(calibration_format)).
struct calibration {
    Eigen::Matrix3d K;
    double width_px = 0, height_px = 0;
    brown_conrady distortion;
    std::string format;
};

/// The format of a calibration file's text, by content: a "%YAML" directive or `!!opencv-matrix`
/// tags → OpenCV YAML; a JSON object with an "opencv-matrix" → OpenCV JSON; YAML with
/// "distortion_model:" or "camera_name:" → ROS camera_info. `unknown` otherwise.
inline calibration_format detect(std::string_view text) {
    std::size_t i = 0;
    if (text.substr(0, 3) == "\xEF\xBB\xBF") i = 3;  // UTF-8 byte-order mark
    while (i < text.size() && (text[i] == ' ' || text[i] == '\t' || text[i] == '\r' || text[i] == '\n')) ++i;
    const std::string_view body = text.substr(i);
    const auto has = [&](std::string_view s) { return body.find(s) != std::string_view::npos; };
    if (body.substr(0, 5) == "%YAML") return has("distortion_model") ? calibration_format::ros_yaml : calibration_format::opencv_yaml;
    if (!body.empty() && body.front() == '{') {
        if (has("opencv-matrix")) return calibration_format::opencv_json;
        if (has("\"distortion_model\"")) return calibration_format::ros_yaml;  // camera_info as flow YAML
        return calibration_format::unknown;
    }
    if (has("!!opencv-matrix")) return calibration_format::opencv_yaml;
    if (has("distortion_model:") || has("camera_name:")) return calibration_format::ros_yaml;
    return calibration_format::unknown;
}

namespace detail::calibration_io {

[[noreturn]] inline void fail(const std::string& source, const std::string& field, const std::string& msg) {
    throw invalid_argument(field, (source.empty() ? std::string() : source + ": ") + field + ": " + msg);
}

inline std::string child(const std::string& path, std::string_view key) { return path + "." + std::string(key); }
inline std::string element(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }

/// YAML node from nlohmann JSON: numbers as their round-trip text, so one validation serves both.
/// A calibration is a few levels deep; deeper nesting is refused before the recursion could
/// exhaust the stack (nlohmann parses any depth without recursing).
inline YAML::Node to_yaml(const nlohmann::json& j, const std::string& source, const std::string& prefix, int depth = 0) {
    if (depth > 32) throw io_error(source, prefix + "nested deeper than 32 levels: not a calibration file");
    if (j.is_object()) {
        YAML::Node n(YAML::NodeType::Map);
        for (auto it = j.begin(); it != j.end(); ++it) n[it.key()] = to_yaml(it.value(), source, prefix, depth + 1);
        return n;
    }
    if (j.is_array()) {
        YAML::Node n(YAML::NodeType::Sequence);
        for (const auto& e : j) n.push_back(to_yaml(e, source, prefix, depth + 1));
        return n;
    }
    if (j.is_null()) return YAML::Node(YAML::NodeType::Null);
    if (j.is_string()) return YAML::Node(j.get<std::string>());
    return YAML::Node(j.dump());
}

class reader {
public:
    reader(const YAML::Node& root, std::string source, calibration_format format)
        : root_(root), source_(std::move(source)), format_(format) {
        if (!root_.IsMap()) fail(source_, "(top level)", "expected a mapping of calibration keys");
    }

    calibration read() {
        calibration c;
        c.format = to_string(format_);
        c.width_px = positive_integer("image_width");
        c.height_px = positive_integer("image_height");
        const std::vector<double> k = matrix("camera_matrix", 3, 3);
        c.K << k[0], k[1], k[2], k[3], k[4], k[5], k[6], k[7], k[8];
        check_intrinsics(c);
        // OpenCV (and ROS) put pixel centres at whole numbers, certipose at half-integers (the
        // image spans [0, w] × [0, h], docs/conventions.md): the same principal point is 0.5
        // further in certipose's pixel coordinates.
        c.K(0, 2) += 0.5;
        c.K(1, 2) += 0.5;
        std::size_t expected = 0;  // 0: 4, 5 or 8
        if (format_ == calibration_format::ros_yaml) {
            const YAML::Node m = required("distortion_model", "a string");
            const std::string model = scalar_string(m, "distortion_model");
            if (model == "plumb_bob")
                expected = 5;
            else if (model == "rational_polynomial")
                expected = 8;
            else if (model == "equidistant" || model == "fisheye")
                fail(source_, "distortion_model",
                     "\"" + model + "\" (fisheye) is not supported: certipose certifies the Brown-Conrady (plumb_bob, "
                     "rational_polynomial) model only");
            else
                fail(source_, "distortion_model",
                     "unknown model \"" + model + "\" (expected \"plumb_bob\" or \"rational_polynomial\")");
            if (const YAML::Node r = root_["rectification_matrix"]) (void)matrix("rectification_matrix", 3, 3);
            if (const YAML::Node p = root_["projection_matrix"]) (void)matrix("projection_matrix", 3, 4);
        }
        const std::vector<double> d = vector("distortion_coefficients", expected);
        try {
            c.distortion = brown_conrady::from_opencv(d);
        } catch (const invalid_argument& e) {  // the counts and values were checked: keep the path anyway
            fail(source_, "distortion_coefficients", e.what());
        }
        return c;
    }

private:
    YAML::Node required(std::string_view key, std::string_view expected) const {
        const YAML::Node n = root_[std::string(key)];
        if (!n || n.IsNull()) fail(source_, std::string(key), "missing required key (" + std::string(expected) + ")");
        return n;
    }

    std::string scalar_string(const YAML::Node& n, const std::string& field) const {
        if (!n.IsScalar()) fail(source_, field, "expected a scalar");
        return n.Scalar();
    }

    double number(const YAML::Node& n, const std::string& field) const {
        if (!n || !n.IsScalar()) fail(source_, field, "expected a number");
        double v = 0;
        {
            const certipose::detail::round_to_nearest_scope nearest;  // text → double honours the mode
            if (!YAML::convert<double>::decode(n, v))
                fail(source_, field, "expected a number, got \"" + n.Scalar().substr(0, 40) + "\"");
        }
        if (!std::isfinite(v)) fail(source_, field, "must be finite, got " + certipose::detail::format_double(v));
        return v;
    }

    double positive_integer(std::string_view key) const {
        const std::string field(key);
        const double v = number(required(key, "a positive integer"), field);
        if (!(v > 0) || v != std::trunc(v) || v > 1e9)
            fail(source_, field, "must be a positive integer number of pixels, got " + certipose::detail::format_double(v));
        return v;
    }

    std::size_t count(const YAML::Node& m, const std::string& path, std::string_view key) const {
        const std::string field = child(path, key);
        const YAML::Node n = m[std::string(key)];
        if (!n) fail(source_, field, "missing required key (an integer)");
        const double v = number(n, field);
        if (!(v >= 1) || v != std::trunc(v) || v > 1e6) fail(source_, field, "must be a positive integer, got " + certipose::detail::format_double(v));
        return static_cast<std::size_t>(v);
    }

    /// A {rows, cols, data} matrix (OpenCV: also dt and the opencv-matrix tag or type_id), its
    /// data checked against rows·cols and, when given, the expected shape.
    std::vector<double> matrix_data(const std::string& key, std::size_t& rows, std::size_t& cols) const {
        const YAML::Node m = required(key, "a matrix {rows, cols, data}");
        if (!m.IsMap()) fail(source_, key, "expected a matrix {rows, cols, data}");
        rows = count(m, key, "rows");
        cols = count(m, key, "cols");
        if (format_ == calibration_format::opencv_json) {
            const YAML::Node t = m["type_id"];
            if (!t || !t.IsScalar() || t.Scalar() != "opencv-matrix")
                fail(source_, child(key, "type_id"), "expected \"opencv-matrix\"");
        }
        if (format_ != calibration_format::ros_yaml) {
            const YAML::Node dt = m["dt"];
            if (!dt) fail(source_, child(key, "dt"), "missing required key (\"d\" or \"f\")");
            const std::string t = scalar_string(dt, child(key, "dt"));
            if (t != "d" && t != "f") fail(source_, child(key, "dt"), "expected \"d\" or \"f\" (floating point), got \"" + t.substr(0, 20) + "\"");
        }
        const std::string data_path = child(key, "data");
        const YAML::Node data = m["data"];
        if (!data) fail(source_, data_path, "missing required key (a list of numbers)");
        if (!data.IsSequence()) fail(source_, data_path, "expected a list of numbers");
        if (data.size() != rows * cols)
            fail(source_, data_path,
                 "has " + std::to_string(data.size()) + " numbers, but rows x cols = " + std::to_string(rows) + " x " +
                     std::to_string(cols));
        std::vector<double> out;
        out.reserve(data.size());
        for (std::size_t i = 0; i < data.size(); ++i) out.push_back(number(data[i], element(data_path, i)));
        return out;
    }

    std::vector<double> matrix(const std::string& key, std::size_t rows, std::size_t cols) const {
        std::size_t r = 0, c = 0;
        std::vector<double> out = matrix_data(key, r, c);
        if (r != rows) fail(source_, child(key, "rows"), "must be " + std::to_string(rows) + ", got " + std::to_string(r));
        if (c != cols) fail(source_, child(key, "cols"), "must be " + std::to_string(cols) + ", got " + std::to_string(c));
        return out;
    }

    /// A 1 × n or n × 1 matrix of distortion coefficients, n = `expected` or (0) 4, 5 or 8.
    std::vector<double> vector(const std::string& key, std::size_t expected) const {
        std::size_t r = 0, c = 0;
        std::vector<double> out = matrix_data(key, r, c);
        if (r != 1 && c != 1) fail(source_, key, "must be a 1 x n or n x 1 matrix, got " + std::to_string(r) + " x " + std::to_string(c));
        const std::size_t n = out.size();
        if (expected != 0 && n != expected)
            fail(source_, child(key, "data"),
                 "the distortion model needs " + std::to_string(expected) + " coefficients, got " + std::to_string(n));
        if (n != 4 && n != 5 && n != 8)
            fail(source_, child(key, "data"),
                 "expected 4, 5 or 8 coefficients (k1, k2, p1, p2[, k3[, k4, k5, k6]]), got " + std::to_string(n) +
                     (n > 8 ? " (thin-prism and tilted models are not supported)" : ""));
        return out;
    }

    void check_intrinsics(const calibration& c) const {
        const std::string d = "camera_matrix.data";
        const auto is = [&](int r, int col, double v) {
            if (c.K(r, col) != v)
                fail(source_, element(d, static_cast<std::size_t>(3 * r + col)),
                     "must be " + certipose::detail::format_double(v) + ", got " + certipose::detail::format_double(c.K(r, col)));
        };
        is(2, 0, 0.0), is(2, 1, 0.0), is(2, 2, 1.0), is(1, 0, 0.0);
        if (!(c.K(0, 0) > 0)) fail(source_, element(d, 0), "fx must be positive, got " + certipose::detail::format_double(c.K(0, 0)));
        if (!(c.K(1, 1) > 0)) fail(source_, element(d, 4), "fy must be positive, got " + certipose::detail::format_double(c.K(1, 1)));
        if (!(c.K(0, 2) + 0.5 > 0 && c.K(0, 2) + 0.5 < c.width_px))
            fail(source_, element(d, 2),
                 "the principal point's x must be inside the image (0 < cx + 0.5 < image_width = " +
                     certipose::detail::format_double(c.width_px) + "), got " + certipose::detail::format_double(c.K(0, 2)));
        if (!(c.K(1, 2) + 0.5 > 0 && c.K(1, 2) + 0.5 < c.height_px))
            fail(source_, element(d, 5),
                 "the principal point's y must be inside the image (0 < cy + 0.5 < image_height = " +
                     certipose::detail::format_double(c.height_px) + "), got " + certipose::detail::format_double(c.K(1, 2)));
    }

    YAML::Node root_;
    std::string source_;
    calibration_format format_;
};

/// "%YAML:1.0" (OpenCV's directive, not YAML 1.2 syntax) → a comment on the same line.
inline std::string without_opencv_directive(std::string_view text) {
    std::string s(text);
    const std::size_t at = s.find("%YAML");
    if (at != std::string::npos && s.find_first_not_of(" \t\r\n\xEF\xBB\xBF") == at) s[at] = '#';
    return s;
}

}  // namespace detail::calibration_io

/// Parses a calibration file's text (format by `detect`). `source` (a file name) prefixes every
/// message and is the io_error path. Throws io_error for an unknown format or a syntax error
/// (with the line), invalid_argument (field() = key path) for a bad value.
inline calibration parse_calibration(std::string_view text, const std::string& source = {}) {
    using namespace detail::calibration_io;
    const std::string prefix = source.empty() ? std::string() : source + ": ";
    const calibration_format format = detect(text);
    if (format == calibration_format::unknown)
        throw io_error(source, prefix +
                                   "not a calibration file certipose reads (OpenCV FileStorage YAML or JSON with "
                                   "camera_matrix and distortion_coefficients, or ROS camera_info YAML)");
    YAML::Node root;
    if (format == calibration_format::opencv_json) {
        nlohmann::json j;
        try {
            const certipose::detail::round_to_nearest_scope nearest;
            j = nlohmann::json::parse(text.begin(), text.end());
        } catch (const nlohmann::json::exception& e) {
            std::string what = e.what();
            if (const auto close = what.find("] "); !what.empty() && what.front() == '[' && close != std::string::npos)
                what.erase(0, close + 2);
            throw io_error(source, prefix + "invalid JSON: " + what);
        }
        root = to_yaml(j, source, prefix);
    } else {
        try {
            root = YAML::Load(without_opencv_directive(text));
        } catch (const YAML::Exception& e) {
            throw io_error(source, prefix + "invalid YAML at line " + std::to_string(e.mark.line + 1) + ": " + e.msg);
        }
    }
    try {
        return reader(root, source, format).read();
    } catch (const YAML::Exception& e) {  // a shape the checks above did not foresee
        throw io_error(source, prefix + "unreadable calibration at line " + std::to_string(e.mark.line + 1) + ": " + e.msg);
    }
}

/// Reads a calibration file. Throws io_error(path) if it is missing or unreadable, and what
/// parse_calibration throws.
inline calibration read_calibration(const std::filesystem::path& path) {
    const std::string name = path.string();
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw io_error(name, "read_calibration: " + name + " is a directory, not a file");
    if (!std::filesystem::exists(path, ec)) throw io_error(name, "read_calibration: no such file: " + name);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw io_error(name, "read_calibration: cannot open " + name);
    // A calibration is a few hundred bytes. Reading at most 1 MiB keeps a wrong path (a log, a
    // device such as /dev/zero named in a camera JSON) from filling memory or reading forever
    // (a FIFO with no writer still blocks, as for any reader).
    constexpr std::size_t limit = std::size_t{1} << 20;
    std::string text(limit + 1, '\0');
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    if (in.bad()) throw io_error(name, "read_calibration: cannot read " + name);
    text.resize(static_cast<std::size_t>(in.gcount()));
    if (text.size() > limit) throw io_error(name, "read_calibration: " + name + " is larger than 1 MiB: not a calibration file");
    return parse_calibration(text, name);
}

}  // namespace certipose
