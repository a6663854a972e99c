// certipose/io/json.hpp — the JSON files of docs/io.md: the camera/task input and the result.
//
// Needs nlohmann-json (Debian nlohmann-json3-dev, CMake target nlohmann_json::nlohmann_json);
// no other certipose header includes it, so the core stays free of it. No CGAL.
//
// Input (`read_camera_task`): a strict reader. The document is a contract typed by hand, so
// every mistake is an error that names the field by its JSON path — unknown field (a typo such
// as "camera.focal_lenght"), duplicate field, wrong type, missing required field — thrown as
// certipose::invalid_argument whose field() is that path; a value the camera or the task
// rejects (negative focal length, ...) is the camera's own invalid_argument re-thrown with the
// path ("camera.focal_length"); bad JSON syntax is certipose::io_error with nlohmann's line and
// column. Output (`write_result_json`): the result JSON of docs/io.md, written atomically,
// doubles in round-trip precision (nlohmann's shortest-round-trip formatting), one box per
// line. Its reader (`read_result_json`) returns plain doubles and, since the contract allows
// extra fields, ignores fields it does not know. Field-by-field description: docs/io.md.
// Every entry point switches to round-to-nearest for its duration: glibc's strtod (behind
// nlohmann's parser) honours the FPU rounding mode, so text read while a rounding_guard holds the
// mode upward came back as a different double (measured: 1/3 and 0.123456789 did not survive).
#pragma once

#include "certipose/detail/format.hpp"
#include "certipose/camera.hpp"
#include "certipose/camera/calibrated_camera.hpp"
#include "certipose/error.hpp"
#include "certipose/interval/detail/fenv.hpp"
#include "certipose/io/calibration.hpp"
#include "certipose/io/result_document.hpp"
#include "certipose/io/write_file.hpp"
#include "certipose/solver/result.hpp"
#include "certipose/solver/task.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace certipose {

/// A camera read from JSON: the model is chosen by the file ("model": "thin_lens" | "pinhole").
using any_camera = std::variant<thin_lens_camera, pinhole_camera>;

/// "thin_lens" or "pinhole": the input JSON's name of the model.
inline const char* model_name(const any_camera& camera) noexcept {
    return std::holds_alternative<thin_lens_camera>(camera) ? "thin_lens" : "pinhole";
}

/// The camera as the one type the solver reads (camera/calibrated_camera.hpp), whatever its
/// model: a program that accepts every model instantiates the pipeline once,
/// `pose_solver<with_camera<calibrated_camera>>`.
inline calibrated_camera calibrated(const any_camera& camera) {
    return std::visit([&](const auto& c) { return calibrated_camera(c, model_name(camera)); }, camera);
}

/// The camera/task input JSON (docs/io.md; conventions: docs/conventions.md).
struct camera_task {
    any_camera camera;
    inspection_task task;
    /// "camera.mount_offset": the projection centre in the mount frame (axes: the camera's
    /// optical frame; origin: the mount point), metres; zero when the file gives none.
    std::array<double, 3> mount_offset{};
    /// "camera.distortion_coefficients" (or the calibration file's): the lens distortion, if any.
    std::optional<brown_conrady> distortion{};
    /// "camera.image_margin_px": pixels kept free along the image's edges (default 0).
    double image_margin_px = 0.0;

    /// The camera as the solver reads it: `certipose::calibrated(camera)`, or, with distortion or
    /// a margin, the calibrated_camera of `distorted_camera(camera, distortion, image_margin_px)`
    /// (its certified image computed here, a few milliseconds). Throws invalid_argument naming
    /// "distortion_coefficients" / "image_margin_px" when no image region can be certified.
    calibrated_camera calibrated() const {
        if (!distortion && image_margin_px == 0.0) return certipose::calibrated(camera);
        const brown_conrady d = distortion.value_or(brown_conrady{});
        return std::visit(
            [&](const auto& c) { return calibrated_camera(distorted_camera(c, d, image_margin_px), model_name(camera)); },
            camera);
    }
};

namespace detail::json_io {

using json = nlohmann::json;
using ordered_json = nlohmann::ordered_json;

// ---- paths and messages ---------------------------------------------------------------------

inline std::string child(const std::string& path, std::string_view key) {
    return path.empty() ? std::string(key) : path + "." + std::string(key);
}
inline std::string element(const std::string& path, std::size_t i) {
    return path + "[" + std::to_string(i) + "]";
}

/// Control characters (a key may contain a newline) would break the "one line" error rule.
inline std::string printable(std::string s) {
    for (char& c : s)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    return s;
}

[[noreturn]] inline void fail(const std::string& path, const std::string& msg) {
    throw invalid_argument(path, printable((path.empty() ? std::string("(top level)") : path) +
                                           ": " + msg));
}

/// "string \"0.012\"", "number 5", "null", "array of 3", "object" — for "expected X, got Y".
inline std::string describe(const json& j) {
    if (j.is_object()) return "an object";
    if (j.is_array()) return "an array of " + std::to_string(j.size());
    std::string text = j.dump(-1, ' ', false, json::error_handler_t::replace);
    if (text.size() > 40) text = text.substr(0, 37) + "...";
    if (j.is_null()) return "null";
    return std::string(j.is_string() ? "string " : j.is_boolean() ? "boolean " : "number ") + text;
}

inline std::string join(std::initializer_list<std::string_view> names) {
    std::string s;
    for (auto n : names) s += (s.empty() ? "" : ", ") + std::string(n);
    return s;
}

// ---- typed access ---------------------------------------------------------------------------

inline const json& require_object(const json& j, const std::string& path) {
    if (!j.is_object()) fail(path, "expected an object, got " + describe(j));
    return j;
}

inline void reject_unknown(const json& obj, const std::string& path,
                           std::initializer_list<std::string_view> allowed, std::string_view what) {
    for (auto it = obj.begin(); it != obj.end(); ++it)
        if (std::find(allowed.begin(), allowed.end(), it.key()) == allowed.end())
            fail(child(path, it.key()),
                 "unknown field (" + std::string(what) + " fields: " + join(allowed) + ")");
}

inline const json* find(const json& obj, std::string_view key) {
    const auto it = obj.find(std::string(key));
    return it == obj.end() ? nullptr : &*it;
}

inline const json& require(const json& obj, const std::string& path, std::string_view key,
                           std::string_view expected) {
    const json* v = find(obj, key);
    if (!v) fail(child(path, key), "missing required field (" + std::string(expected) + ")");
    return *v;
}

inline double as_number(const json& j, const std::string& path) {
    if (!j.is_number()) fail(path, "expected a number, got " + describe(j));
    return j.get<double>();
}

inline double required_number(const json& obj, const std::string& path, std::string_view key) {
    return as_number(require(obj, path, key, "a number"), child(path, key));
}

/// Absent or null: std::nullopt.
inline std::optional<double> optional_number(const json& obj, const std::string& path,
                                             std::string_view key) {
    const json* v = find(obj, key);
    if (!v || v->is_null()) return std::nullopt;
    return as_number(*v, child(path, key));
}

inline std::size_t as_count(const json& j, const std::string& path) {
    if (!j.is_number_unsigned()) {
        if (j.is_number_integer() && j.get<std::int64_t>() >= 0) return j.get<std::size_t>();
        fail(path, "expected a non-negative integer, got " + describe(j));
    }
    return j.get<std::size_t>();
}

inline std::string as_string(const json& j, const std::string& path, std::string_view expected) {
    if (!j.is_string()) fail(path, "expected " + std::string(expected) + ", got " + describe(j));
    return j.get<std::string>();
}

/// An array of exactly N numbers.
template <std::size_t N>
std::array<double, N> as_numbers(const json& j, const std::string& path) {
    if (!j.is_array() || j.size() != N)
        fail(path, "expected an array of " + std::to_string(N) + " numbers, got " + describe(j));
    std::array<double, N> a{};
    for (std::size_t i = 0; i < N; ++i) a[i] = as_number(j[i], element(path, i));
    return a;
}

/// An array of exactly R arrays of exactly C numbers.
template <std::size_t R, std::size_t C>
std::array<std::array<double, C>, R> as_matrix(const json& j, const std::string& path) {
    if (!j.is_array() || j.size() != R)
        fail(path, "expected an array of " + std::to_string(R) + " arrays of " +
                       std::to_string(C) + " numbers, got " + describe(j));
    std::array<std::array<double, C>, R> m{};
    for (std::size_t i = 0; i < R; ++i) m[i] = as_numbers<C>(j[i], element(path, i));
    return m;
}

// ---- parsing ----------------------------------------------------------------------------------

inline std::string strip_nlohmann_prefix(std::string what) {
    // "[json.exception.parse_error.101] parse error at line 2, column 7: ..." → "parse error ..."
    if (!what.empty() && what.front() == '[')
        if (const auto close = what.find("] "); close != std::string::npos) what.erase(0, close + 2);
    return what;
}

/// Parses `text` as strict JSON (no comments). Duplicate keys — which nlohmann would silently
/// resolve to the last one — are an invalid_argument naming the path; syntax errors are an
/// io_error(source) with line and column.
inline json parse(std::string_view text, const std::string& source) {
    struct frame {
        bool array;
        std::set<std::string> keys{};
        std::string key{};
        std::size_t index = 0;
    };
    std::vector<frame> frames;
    const auto path_of = [&frames] {
        std::string p;
        for (const frame& f : frames) p = f.array ? element(p, f.index) : child(p, f.key);
        return p;
    };
    const json::parser_callback_t callback = [&](int, json::parse_event_t event, json& parsed) {
        switch (event) {
            case json::parse_event_t::object_start: frames.push_back({false}); break;
            case json::parse_event_t::array_start: frames.push_back({true}); break;
            case json::parse_event_t::key: {
                frame& f = frames.back();
                f.key = parsed.get<std::string>();
                if (!f.keys.insert(f.key).second) fail(path_of(), "duplicate field");
                break;
            }
            case json::parse_event_t::object_end:
            case json::parse_event_t::array_end:
                frames.pop_back();
                [[fallthrough]];
            case json::parse_event_t::value:
                if (!frames.empty() && frames.back().array) ++frames.back().index;
                break;
        }
        return true;
    };
    const std::string prefix = source.empty() ? std::string() : source + ": ";
    const certipose::detail::round_to_nearest_scope nearest;  // strtod honours the mode
    try {
        return json::parse(text.begin(), text.end(), callback, /*allow_exceptions=*/true,
                           /*ignore_comments=*/false);
    } catch (const json::exception& e) {  // parse_error (syntax), out_of_range (1e999)
        throw io_error(source, printable(prefix + "invalid JSON: " + strip_nlohmann_prefix(e.what())));
    }
}

inline std::string read_text_file(const std::filesystem::path& path, std::string_view who) {
    const std::string name = path.string();
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw io_error(name, std::string(who) + ": " + name + " is a directory, not a file");
    if (!std::filesystem::exists(path, ec))
        throw io_error(name, std::string(who) + ": no such file: " + name);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw io_error(name, std::string(who) + ": cannot open " + name);
    std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (in.bad()) throw io_error(name, std::string(who) + ": cannot read " + name);
    return text;
}

/// Runs `f` and prefixes the message of any invalid_argument with the file name, keeping the
/// JSON path in field(): "camera.json: camera.focal_lenght: unknown field (...)".
template <class F>
auto with_source(const std::string& source, F&& f) {
    try {
        return f();
    } catch (const invalid_argument& e) {
        if (source.empty()) throw;
        throw invalid_argument(e.field(), source + ": " + e.what());
    }
}

/// Builds a camera (or validates a task) and re-throws its invalid_argument with the JSON path.
template <class F>
auto checked_by_model(const std::string& path, F&& f) {
    try {
        return f();
    } catch (const invalid_argument& e) {
        const std::string field = child(path, e.field());
        throw invalid_argument(field, field + ": " + e.what());
    }
}

// ---- writing ----------------------------------------------------------------------------------

inline ordered_json finite(double v, const std::string& path) {
    if (!std::isfinite(v))
        throw invalid_argument(path, path + ": cannot be written to JSON, it is not finite (" +
                                         detail::format_double(v) + ")");
    return v;
}

/// An integral double (image sizes) as a JSON integer, as in docs/io.md; others as doubles.
inline ordered_json integral_or_double(double v, const std::string& path) {
    if (std::isfinite(v) && v == std::trunc(v) && std::abs(v) < 9007199254740992.0)
        return static_cast<std::int64_t>(v);
    return finite(v, path);
}

/// +inf (an unbounded range) is written as null; other non-finite values are an error.
inline ordered_json finite_or_unbounded(double v, const std::string& path) {
    if (v == std::numeric_limits<double>::infinity()) return nullptr;
    return finite(v, path);
}

template <std::size_t N>
ordered_json numbers(const std::array<double, N>& a, const std::string& path) {
    ordered_json j = ordered_json::array();
    for (std::size_t i = 0; i < N; ++i) j.push_back(finite(a[i], element(path, i)));
    return j;
}

template <std::size_t R, std::size_t C>
ordered_json matrix(const std::array<std::array<double, C>, R>& m, const std::string& path) {
    ordered_json j = ordered_json::array();
    for (std::size_t i = 0; i < R; ++i) j.push_back(numbers(m[i], element(path, i)));
    return j;
}

inline ordered_json bounds(const bounds_3d& b, const std::string& path) {
    ordered_json j = matrix(b, path);  // rejects NaN (an empty interval) and infinities first
    for (std::size_t i = 0; i < 3; ++i)
        if (b[i][0] > b[i][1])
            throw invalid_argument(element(path, i),
                                   element(path, i) + ": lower bound above upper bound (" +
                                       detail::format_double(b[i][0]) + " > " +
                                       detail::format_double(b[i][1]) + ")");
    return j;
}

inline void check_bounds(const bounds_3d& b, const std::string& path) {
    for (std::size_t i = 0; i < 3; ++i)
        if (!(b[i][0] <= b[i][1]))
            fail(element(path, i), "lower bound " + detail::format_double(b[i][0]) +
                                       " is above upper bound " +
                                       detail::format_double(b[i][1]));
}

inline std::optional<boundary_reason> boundary_reason_from_string(std::string_view s) {
    for (std::size_t r = 0; r < boundary_reason_count; ++r)
        if (s == to_string(static_cast<boundary_reason>(r))) return static_cast<boundary_reason>(r);
    return std::nullopt;
}

inline std::optional<termination> termination_from_string(std::string_view s) {
    for (termination t : {termination::completed, termination::box_budget, termination::deadline,
                          termination::cancelled})
        if (s == to_string(t)) return t;
    return std::nullopt;
}

// ---- format and version ---------------------------------------------------------------------

/// The "format" names of the documents the programs write, and the one "version" this build
/// reads and writes. A document without "format" or "version" is read as this version.
inline constexpr const char* result_format = "certipose-result";
inline constexpr const char* part_summary_format = "certipose-part-summary";
inline constexpr const char* plan_format = "certipose-plan";
inline constexpr int format_version = 1;

/// A JSON value as it appears in the file, shortened: "certipose-result" (quoted), 2, an object.
inline std::string value_text(const json& j) {
    if (!j.is_string() && !j.is_number() && !j.is_boolean()) return describe(j);
    std::string text = j.dump(-1, ' ', false, json::error_handler_t::replace);
    if (text.size() > 40) text = text.substr(0, 37) + "...";
    return text;
}

/// Refuses a "version" other than 1 (absent: version 1). Throws invalid_argument("version").
inline void check_version(const json& j) {
    const json* v = j.is_object() ? find(j, "version") : nullptr;
    if (!v || (v->is_number() && v->get<double>() == double(format_version))) return;
    throw invalid_argument("version", printable("\"version\": " + value_text(*v) + " is not supported (this build reads version " +
                                                std::to_string(format_version) + ")"));
}

/// Refuses a "format" other than `format` (absent: accepted), then checks "version".
/// Throws invalid_argument("format") / ("version").
inline void check_format(const json& j, std::string_view format) {
    if (const json* f = j.is_object() ? find(j, "format") : nullptr;
        f && !(f->is_string() && f->get<std::string>() == format))
        throw invalid_argument("format", printable("\"format\": " + value_text(*f) + " is not supported here (expected \"" +
                                                   std::string(format) + "\")"));
    check_version(j);
}

/// "camera.mount_offset": absent or null is zero; else 3 finite numbers (−0 read as +0).
inline std::array<double, 3> mount_offset_from_json(const json& camera, const std::string& path) {
    const json* v = find(camera, "mount_offset");
    if (!v || v->is_null()) return {};
    const std::string where = child(path, "mount_offset");
    std::array<double, 3> a = as_numbers<3>(*v, where);
    for (std::size_t i = 0; i < 3; ++i) {
        if (!std::isfinite(a[i])) fail(element(where, i), "must be a finite number of metres, got " + detail::format_double(a[i]));
        a[i] += 0.0;  // -0 → +0: the same point, written the same way
    }
    return a;
}

}  // namespace detail::json_io

// ==== camera/task input ========================================================================

namespace detail::json_io {

/// What the "camera" object gives: the model, and the lens distortion and image margin that
/// camera_task keeps beside it.
struct camera_input {
    any_camera camera;
    std::optional<brown_conrady> distortion{};
    double image_margin_px = 0.0;
};

/// Reads the "camera" object; `base_dir` resolves a relative "calibration" path (see docs/io.md).
inline camera_input read_camera(const json& j, const std::string& path, const std::filesystem::path& base_dir) {
    const certipose::detail::round_to_nearest_scope nearest;
    require_object(j, path);
    const std::string model =
        as_string(require(j, path, "model", "\"thin_lens\" or \"pinhole\""), child(path, "model"),
                  "a string (\"thin_lens\" or \"pinhole\")");
    if (model != "thin_lens" && model != "pinhole")
        fail(child(path, "model"), "unknown camera model \"" + model + "\" (expected \"thin_lens\" or \"pinhole\")");
    const bool thin_lens = model == "thin_lens";
    if (thin_lens)
        reject_unknown(j, path,
                       {"model", "focal_length", "f_stop", "focus_distance", "max_blur_circle", "max_blur_px",
                        "pixel_pitch", "width_px", "height_px", "principal_point_px", "skew", "aspect",
                        "distortion_coefficients", "image_margin_px", "calibration", "mount_offset"},
                       "thin_lens camera");
    else
        reject_unknown(j, path,
                       {"model", "focal_length", "pixel_pitch", "width_px", "height_px", "principal_point_px", "skew",
                        "aspect", "d_min", "d_max", "distortion_coefficients", "image_margin_px", "calibration",
                        "mount_offset"},
                       "pinhole camera");
    (void)mount_offset_from_json(j, path);  // not the model's: camera_task keeps it
    std::optional<brown_conrady> distortion;
    // Optional fields mirror the C++ defaults; null means "use the default" too.
    const auto principal_point = [&]() -> std::optional<Eigen::Vector2d> {
        const json* v = find(j, "principal_point_px");
        if (!v || v->is_null()) return std::nullopt;
        const auto a = as_numbers<2>(*v, child(path, "principal_point_px"));
        return Eigen::Vector2d(a[0], a[1]);
    };
    const json* calibration_ref = find(j, "calibration");
    if (calibration_ref && calibration_ref->is_null()) calibration_ref = nullptr;
    // The sensor fields every built-in model has (detail::camera::sensor), from the file or from
    // the calibration: K's fx, skew, cx, fy, cy and the image size; the metres need one of
    // focal_length or pixel_pitch (pixel_pitch = focal_length / fx). The model recomputes its K
    // from them, so K(0,0) = focal_length / pixel_pitch may differ from fx in the last bit.
    const auto read_sensor = [&](auto& p) {
        if (!calibration_ref) {
            p.focal_length = required_number(j, path, "focal_length");
            p.pixel_pitch = required_number(j, path, "pixel_pitch");
            p.width_px = required_number(j, path, "width_px");
            p.height_px = required_number(j, path, "height_px");
            p.principal_point_px = principal_point();
            p.skew = optional_number(j, path, "skew").value_or(0.0);
            p.aspect = optional_number(j, path, "aspect").value_or(1.0);
            return;
        }
        const std::string where = child(path, "calibration");
        const std::string file = as_string(*calibration_ref, where, "a file name (string)");
        for (std::string_view key : {"width_px", "height_px", "principal_point_px", "skew", "aspect",
                                     "distortion_coefficients"})
            if (find(j, key))
                fail(child(path, key), "comes from the calibration file (" + where + "): remove it");
        const std::optional<double> f = optional_number(j, path, "focal_length");
        const std::optional<double> pitch = optional_number(j, path, "pixel_pitch");
        if (f && pitch)
            fail(child(path, "pixel_pitch"),
                 "with a calibration file give focal_length or pixel_pitch, not both (pixel_pitch = focal_length / fx)");
        if (!f && !pitch && thin_lens)
            fail(child(path, "focal_length"),
                 "missing required field: a thin_lens camera with a calibration file needs focal_length or "
                 "pixel_pitch (metres)");
        std::filesystem::path file_path(file);
        if (file_path.is_relative()) file_path = base_dir / file_path;
        const calibration c = read_calibration(file_path);
        const double fx = c.K(0, 0);
        // A pinhole without metres: any pitch gives the same K (focal_length = fx · pitch).
        p.pixel_pitch = pitch ? *pitch : f ? *f / fx : 1e-6;
        p.focal_length = f ? *f : p.pixel_pitch * fx;
        p.width_px = c.width_px;
        p.height_px = c.height_px;
        p.principal_point_px = Eigen::Vector2d(c.K(0, 2), c.K(1, 2));
        p.skew = c.K(0, 1);
        p.aspect = c.K(1, 1) / fx;
        if (!c.distortion.is_zero()) distortion = c.distortion;
    };
    if (!calibration_ref)
        if (const json* v = find(j, "distortion_coefficients"); v && !v->is_null()) {
            const std::string where = child(path, "distortion_coefficients");
            if (!v->is_array() || (v->size() != 4 && v->size() != 5 && v->size() != 8))
                fail(where, "expected an array of 4, 5 or 8 numbers (OpenCV order k1, k2, p1, p2[, k3[, k4, k5, k6]]), got " +
                                describe(*v));
            std::vector<double> c;
            for (std::size_t i = 0; i < v->size(); ++i) c.push_back(as_number((*v)[i], element(where, i)));
            const brown_conrady d = checked_by_model(path, [&] { return brown_conrady::from_opencv(c); });
            if (!d.is_zero()) distortion = d;
        }
    const double margin = optional_number(j, path, "image_margin_px").value_or(0.0);
    if (!(margin >= 0.0) || !std::isfinite(margin))
        fail(child(path, "image_margin_px"),
             "must be a finite number of pixels >= 0, got " + detail::format_double(margin));
    const auto make_camera = [&]() -> any_camera {
        if (thin_lens) {
            thin_lens_parameters p;
            read_sensor(p);
            p.f_stop = required_number(j, path, "f_stop");
            p.focus_distance = required_number(j, path, "focus_distance");
            // The acceptable blur in metres on the sensor, or in pixels (times the pixel pitch).
            const std::optional<double> blur = optional_number(j, path, "max_blur_circle");
            const std::optional<double> blur_px = optional_number(j, path, "max_blur_px");
            if (blur && blur_px) fail(child(path, "max_blur_px"), "give max_blur_circle (metres) or max_blur_px (pixels), not both");
            if (!blur && !blur_px)
                fail(child(path, "max_blur_circle"), "missing required field (a number of metres, or max_blur_px in pixels)");
            if (blur_px && !(*blur_px > 0.0 && std::isfinite(*blur_px)))
                fail(child(path, "max_blur_px"), "must be positive and finite, got " + detail::format_double(*blur_px));
            p.max_blur_circle = blur ? *blur : *blur_px * p.pixel_pitch;
            return checked_by_model(path, [&] { return any_camera(thin_lens_camera(p)); });
        }
        pinhole_parameters p;
        read_sensor(p);
        // A pinhole has no depth of field, so the working distances must be stated; d_max may
        // be null for "unbounded" (JSON has no infinity).
        p.d_min = required_number(j, path, "d_min");
        const json& d_max = require(j, path, "d_max", "a number, or null for unbounded");
        p.d_max = d_max.is_null() ? std::numeric_limits<double>::infinity() : as_number(d_max, child(path, "d_max"));
        return checked_by_model(path, [&] { return any_camera(pinhole_camera(p)); });
    };
    camera_input out{make_camera(), distortion, margin};
    // The certified image is proven here, so that a distortion no image region survives is an
    // error of this field, not of the solver's construction.
    if (distortion || margin != 0.0)
        checked_by_model(path, [&] {
            return std::visit(
                [&](const auto& c) {
                    (void)distorted_camera(c, distortion.value_or(brown_conrady{}), margin);
                    return 0;
                },
                out.camera);
        });
    return out;
}

/// "placement_tolerance": {"translation": [tx, ty, tz], "rotation": r, "axis": [nx, ny, nz]
/// (optional), "tilt": t (optional, with an axis), "datum": [x, y, z] | null} of a task object (pose/placement_tolerance.hpp); absent or null: none. Values are validated
/// and errors name the JSON path ("task.placement_tolerance.rotation").
inline std::optional<placement_tolerance> placement_from_json(const json& task, const std::string& path) {
    const json* v = find(task, "placement_tolerance");
    if (!v || v->is_null()) return std::nullopt;
    const std::string here = child(path, "placement_tolerance");
    require_object(*v, here);
    reject_unknown(*v, here, {"translation", "rotation", "axis", "tilt", "datum"}, "placement_tolerance");
    placement_tolerance t;
    t.translation = as_numbers<3>(require(*v, here, "translation", "3 numbers (metres)"), child(here, "translation"));
    t.rotation = required_number(*v, here, "rotation");
    if (const json* a = find(*v, "axis"); a && !a->is_null()) {
        const auto n = as_numbers<3>(*a, child(here, "axis"));
        t.axis = Eigen::Vector3d(n[0], n[1], n[2]);
    }
    if (const json* tilt = find(*v, "tilt"); tilt && !tilt->is_null()) t.tilt = required_number(*v, here, "tilt");
    if (const json* d = find(*v, "datum"); d && !d->is_null()) {
        const auto a = as_numbers<3>(*d, child(here, "datum"));
        t.datum = Eigen::Vector3d(a[0], a[1], a[2]);
    }
    checked_by_model(path, [&] {  // its fields are named "placement_tolerance.<field>"
        t.validate();
        return 0;
    });
    return t;
}

/// Writes "placement_tolerance" into a task object when there is one.
inline void put_placement(ordered_json& task, const std::optional<placement_tolerance>& t) {
    if (!t) return;
    ordered_json p;
    p["translation"] = numbers(t->translation, "task.placement_tolerance.translation");
    p["rotation"] = finite(t->rotation, "task.placement_tolerance.rotation");
    if (t->axis) {
        p["axis"] = numbers(std::array<double, 3>{t->axis->x(), t->axis->y(), t->axis->z()}, "task.placement_tolerance.axis");
        p["tilt"] = finite(t->tilt, "task.placement_tolerance.tilt");
    }
    p["datum"] = t->datum ? numbers(std::array<double, 3>{t->datum->x(), t->datum->y(), t->datum->z()},
                                    "task.placement_tolerance.datum")
                          : ordered_json(nullptr);
    task["placement_tolerance"] = std::move(p);
}

}  // namespace detail::json_io

/// The "camera" object of the input JSON (all fields in docs/io.md). `path` is
/// the JSON path used in error messages. The lens distortion and image margin are not part of the
/// model: camera_task keeps them (camera_task_from_json). A relative "calibration" path is
/// resolved against `base_dir` (the JSON file's directory; empty: the working directory).
inline any_camera camera_from_json(const nlohmann::json& j, const std::string& path = "camera",
                                   const std::filesystem::path& base_dir = {}) {
    return detail::json_io::read_camera(j, path, base_dir).camera;
}

/// The "task" object of the input JSON.
inline inspection_task task_from_json(const nlohmann::json& j, const std::string& path = "task") {
    using namespace detail::json_io;
    const certipose::detail::round_to_nearest_scope nearest;
    require_object(j, path);
    reject_unknown(j, path, {"min_view_angle", "max_metres_per_pixel", "placement_tolerance"}, "task");
    inspection_task t;
    t.min_view_angle = required_number(j, path, "min_view_angle");
    t.max_metres_per_pixel = optional_number(j, path, "max_metres_per_pixel");
    t.placement = placement_from_json(j, path);
    checked_by_model(path, [&] {
        t.validate();
        return 0;
    });
    return t;
}

/// The whole input document {"version": 1, "camera": {...}, "task": {...}}; camera and task are
/// required, "version" is optional (1 is the only one).
/// A relative "camera.calibration" path is resolved against `base_dir`.
inline camera_task camera_task_from_json(const nlohmann::json& j, const std::filesystem::path& base_dir = {}) {
    using namespace detail::json_io;
    require_object(j, "");
    reject_unknown(j, "", {"version", "camera", "task"}, "top-level");
    check_version(j);
    const json& camera_json = require(j, "", "camera", "an object");
    camera_input camera = read_camera(camera_json, "camera", base_dir);
    inspection_task task = task_from_json(require(j, "", "task", "an object"), "task");
    return {std::move(camera.camera), task, mount_offset_from_json(camera_json, "camera"), camera.distortion,
            camera.image_margin_px};
}

/// Parses the input JSON from text. `source` (a file name) prefixes messages and is the
/// io_error path; empty for none. `base_dir` resolves a relative "camera.calibration" path
/// (read_camera_task passes the file's directory).
inline camera_task parse_camera_task(std::string_view text, const std::string& source = {},
                                     const std::filesystem::path& base_dir = {}) {
    return detail::json_io::with_source(source, [&] {
        return camera_task_from_json(detail::json_io::parse(text, source), base_dir);
    });
}

/// Reads the input JSON file. Throws certipose::io_error(path) if it is missing, unreadable or
/// not JSON; certipose::invalid_argument (field() = JSON path, message prefixed by the file
/// name) for schema errors and impossible values.
inline camera_task read_camera_task(const std::filesystem::path& path) {
    return parse_camera_task(detail::json_io::read_text_file(path, "read_camera_task"),
                             path.string(), path.parent_path());
}

/// A pinhole camera_task from a calibration read directly (no camera JSON): K, the image size
/// and the distortion from the file, `working` as [d_min, d_max] (metres) and `task`. The pinhole
/// model's K is all that matters, so the pixel pitch is an arbitrary 1e-6 m with focal_length =
/// fx · 1e-6 (K(0,0) = focal_length / pixel_pitch may differ from fx in the last bit).
/// Throws invalid_argument naming the camera field ("d_min", ...) for impossible values.
inline camera_task camera_task_from_calibration(const calibration& c, distance_range working, inspection_task task) {
    pinhole_parameters p;
    p.pixel_pitch = 1e-6;
    p.focal_length = c.K(0, 0) * p.pixel_pitch;
    p.width_px = c.width_px;
    p.height_px = c.height_px;
    p.principal_point_px = Eigen::Vector2d(c.K(0, 2), c.K(1, 2));
    p.skew = c.K(0, 1);
    p.aspect = c.K(1, 1) / c.K(0, 0);
    p.d_min = working.min;
    p.d_max = working.max;
    task.validate();
    camera_task out{any_camera(pinhole_camera(p)), task};
    if (!c.distortion.is_zero()) out.distortion = c.distortion;
    (void)out.calibrated();  // proves the certified image now (throws distortion_coefficients)
    return out;
}

/// A camera input file, chosen by content: our camera/task JSON (a top-level "camera" object)
/// or a calibration file (OpenCV YAML/JSON, ROS camera_info). Throws what read_camera_task or
/// parse_calibration throws.
inline std::variant<camera_task, calibration> read_camera_input(const std::filesystem::path& path) {
    const std::string text = detail::json_io::read_text_file(path, "read_camera_input");
    if (detect(text) == calibration_format::unknown)
        return parse_camera_task(text, path.string(), path.parent_path());
    return parse_calibration(text, path.string());
}

/// The input JSON for a camera and task (every field written, defaults included), e.g. to
/// generate configurations; parse_camera_task reads it back to an equal camera.
inline nlohmann::ordered_json camera_task_to_json(const camera_task& in) {
    using namespace detail::json_io;
    ordered_json cam;
    const auto sensor = [&](const auto& c) {
        cam["focal_length"] = finite(c.focal_length(), "camera.focal_length");
        cam["pixel_pitch"] = finite(c.pixel_pitch(), "camera.pixel_pitch");
        cam["width_px"] = integral_or_double(c.width_px(), "camera.width_px");
        cam["height_px"] = integral_or_double(c.height_px(), "camera.height_px");
        cam["principal_point_px"] = ordered_json::array(
            {finite(c.principal_point_px().x(), "camera.principal_point_px[0]"),
             finite(c.principal_point_px().y(), "camera.principal_point_px[1]")});
        cam["skew"] = finite(c.skew(), "camera.skew");
        cam["aspect"] = finite(c.aspect(), "camera.aspect");
    };
    if (const auto* t = std::get_if<thin_lens_camera>(&in.camera)) {
        cam["model"] = "thin_lens";
        cam["focal_length"] = nullptr;  // keep the documented field order
        cam["f_stop"] = finite(t->f_stop(), "camera.f_stop");
        cam["focus_distance"] = finite(t->focus_distance(), "camera.focus_distance");
        cam["max_blur_circle"] = finite(t->max_blur_circle(), "camera.max_blur_circle");
        sensor(*t);
    } else {
        const auto& p = std::get<pinhole_camera>(in.camera);
        cam["model"] = "pinhole";
        sensor(p);
        cam["d_min"] = finite(p.distance_range().min, "camera.d_min");
        cam["d_max"] = finite_or_unbounded(p.distance_range().max, "camera.d_max");
    }
    if (in.distortion) {
        ordered_json d = ordered_json::array();
        const auto c = in.distortion->opencv();
        for (std::size_t i = 0; i < in.distortion->count(); ++i)
            d.push_back(finite(c[i], element("camera.distortion_coefficients", i)));
        cam["distortion_coefficients"] = std::move(d);
    }
    if (in.image_margin_px != 0.0) cam["image_margin_px"] = finite(in.image_margin_px, "camera.image_margin_px");
    if (in.mount_offset != std::array<double, 3>{}) cam["mount_offset"] = numbers(in.mount_offset, "camera.mount_offset");
    ordered_json task;
    task["min_view_angle"] = finite(in.task.min_view_angle, "task.min_view_angle");
    task["max_metres_per_pixel"] =
        in.task.max_metres_per_pixel
            ? finite_or_unbounded(*in.task.max_metres_per_pixel, "task.max_metres_per_pixel")
            : ordered_json(nullptr);
    put_placement(task, in.task.placement);
    return {{"camera", std::move(cam)}, {"task", std::move(task)}};
}

// ==== result ===================================================================================

/// `make_result_document` for a camera read from JSON.
template <Interval I>
result_document make_result_document(const solve_result<I>& result, const triangle_mesh& mesh,
                                     const any_camera& camera, const inspection_task& task,
                                     const solve_options& options) {
    return std::visit(
        [&](const auto& c) { return make_result_document(result, mesh, c, task, options); },
        camera);
}

/// `make_result_document` for the camera/task input read from JSON, its mount_offset included.
template <Interval I>
result_document make_result_document(const solve_result<I>& result, const triangle_mesh& mesh,
                                     const camera_task& input, const solve_options& options) {
    result_document d = make_result_document(result, mesh, input.camera, input.task, options);
    d.camera.mount_offset = input.mount_offset;
    d.camera.distortion = input.distortion;
    d.camera.image_margin_px = input.image_margin_px;
    return d;
}

/// The result JSON of docs/io.md (keys in the documented order). Non-finite numbers are an
/// invalid_argument naming the JSON path, except camera.d_max = +inf, written as null. Extra
/// fields may be added to the returned object before it is written (write_json_file).
namespace detail::json_io {

/// The "camera" object of the result documents (single facet, whole part, plan).
inline ordered_json camera_record_json(const result_document::camera_record& c) {
    ordered_json camera;
    camera["width_px"] = integral_or_double(c.width_px, "camera.width_px");
    camera["height_px"] = integral_or_double(c.height_px, "camera.height_px");
    camera["K"] = matrix(c.K, "camera.K");
    camera["d_min"] = finite(c.d_min, "camera.d_min");
    camera["d_max"] = finite_or_unbounded(c.d_max, "camera.d_max");
    // Written only when not zero, so the documents of a camera without one stay as they were.
    if (c.mount_offset != std::array<double, 3>{}) camera["mount_offset"] = numbers(c.mount_offset, "camera.mount_offset");
    // Likewise the lens distortion (OpenCV order, 5 or 8 numbers) and the image margin.
    if (c.distortion) {
        ordered_json d = ordered_json::array();
        const auto k = c.distortion->opencv();
        for (std::size_t i = 0; i < c.distortion->count(); ++i) d.push_back(finite(k[i], element("camera.distortion_coefficients", i)));
        camera["distortion_coefficients"] = std::move(d);
    }
    if (c.image_margin_px != 0.0) camera["image_margin_px"] = finite(c.image_margin_px, "camera.image_margin_px");
    return camera;
}

/// Reads the "camera" object of the result documents (extra fields ignored).
inline result_document::camera_record camera_record_from_json(const json& j, const std::string& path = "camera") {
    result_document::camera_record c;
    const json& camera = require_object(j, path);
    c.width_px = required_number(camera, path, "width_px");
    c.height_px = required_number(camera, path, "height_px");
    c.K = as_matrix<3, 3>(require(camera, path, "K", "a 3x3 matrix"), child(path, "K"));
    c.d_min = required_number(camera, path, "d_min");
    const json& d_max = require(camera, path, "d_max", "a number, or null for unbounded");
    c.d_max = d_max.is_null() ? std::numeric_limits<double>::infinity() : as_number(d_max, child(path, "d_max"));
    c.mount_offset = mount_offset_from_json(camera, path);
    if (const json* v = find(camera, "distortion_coefficients"); v && !v->is_null()) {
        const std::string where = child(path, "distortion_coefficients");
        if (!v->is_array()) fail(where, "expected an array of 4, 5 or 8 numbers, got " + describe(*v));
        std::vector<double> k;
        for (std::size_t i = 0; i < v->size(); ++i) k.push_back(as_number((*v)[i], element(where, i)));
        c.distortion = checked_by_model(path, [&] { return brown_conrady::from_opencv(k); });
    }
    c.image_margin_px = optional_number(camera, path, "image_margin_px").value_or(0.0);
    return c;
}


/// Reads the "task" object of the result documents (extra fields ignored).
inline result_document::task_record task_record_from_json(const json& j, const std::string& path = "task") {
    result_document::task_record t;
    const json& task = require_object(j, path);
    t.min_view_angle = required_number(task, path, "min_view_angle");
    t.max_metres_per_pixel = optional_number(task, path, "max_metres_per_pixel");
    t.placement = placement_from_json(task, path);
    return t;
}

/// The "task" object of the result documents.
inline ordered_json task_record_json(const result_document::task_record& t) {
    ordered_json task;
    task["min_view_angle"] = finite(t.min_view_angle, "task.min_view_angle");
    task["max_metres_per_pixel"] = t.max_metres_per_pixel
                                       ? finite_or_unbounded(*t.max_metres_per_pixel, "task.max_metres_per_pixel")
                                       : ordered_json(nullptr);
    put_placement(task, t.placement);
    return task;
}

/// Adds "occluders", "keep_in" and "keep_out" (io/scene_record.hpp) to a document, each an
/// array (empty when there are none).
inline void put_scene(ordered_json& j, const scene_record& s) {
    ordered_json occluders = ordered_json::array();
    for (std::size_t i = 0; i < s.occluders.size(); ++i) {
        const occluder_record& o = s.occluders[i];
        ordered_json r;
        r["path"] = o.path;
        r["scale"] = finite(o.scale, child(element("occluders", i), "scale"));
        r["faces"] = o.faces;
        r["digest"] = o.digest;
        occluders.push_back(std::move(r));
    }
    j["occluders"] = std::move(occluders);
    const auto regions = [](const std::vector<camera_region>& list, const std::string& key) {
        ordered_json out = ordered_json::array();
        for (std::size_t i = 0; i < list.size(); ++i) {
            ordered_json numbers = ordered_json::array();
            for (double v : list[i].numbers()) numbers.push_back(finite(v, element(key, i)));
            ordered_json r;
            r[list[i].name()] = std::move(numbers);
            out.push_back(std::move(r));
        }
        return out;
    };
    j["keep_in"] = regions(s.regions.keep_in, "keep_in");
    j["keep_out"] = regions(s.regions.keep_out, "keep_out");
}

/// Reads "occluders", "keep_in" and "keep_out" of a document; absent (or null) ones are empty.
/// Throws invalid_argument naming the JSON path ("keep_out[1].box", "occluders[0].digest") of a
/// malformed entry or an invalid region.
inline scene_record scene_from_json(const json& j) {
    scene_record s;
    const auto array = [&](std::string_view key) -> const json* {
        const json* list = find(j, key);
        if (!list || list->is_null()) return nullptr;
        if (!list->is_array()) fail(std::string(key), "expected an array, got " + describe(*list));
        return list;
    };
    if (const json* list = array("occluders"))
        for (std::size_t i = 0; i < list->size(); ++i) {
            const std::string path = element("occluders", i);
            const json& o = require_object((*list)[i], path);
            occluder_record r;
            r.path = as_string(require(o, path, "path", "a string"), child(path, "path"), "a string");
            r.scale = required_number(o, path, "scale");
            if (!(r.scale > 0.0) || !std::isfinite(r.scale))
                fail(child(path, "scale"), "expected a positive finite factor, got " + detail::format_double(r.scale));
            r.faces = as_count(require(o, path, "faces", "an integer"), child(path, "faces"));
            r.digest = as_string(require(o, path, "digest", "a string"), child(path, "digest"), "a string");
            s.occluders.push_back(std::move(r));
        }
    const auto regions = [&](std::string_view key, std::vector<camera_region>& out) {
        const json* list = array(key);
        if (!list) return;
        for (std::size_t i = 0; i < list->size(); ++i) {
            const std::string path = element(std::string(key), i);
            const json& e = require_object((*list)[i], path);
            const char* expected = "expected {\"box\": [xmin, ymin, zmin, xmax, ymax, zmax]} or {\"sphere\": [x, y, z, r]}";
            if (e.size() != 1) fail(path, expected);
            camera_region r;
            if (const json* b = find(e, "box")) {
                const auto v = as_numbers<6>(*b, child(path, "box"));
                r = camera_region::box({v[0], v[1], v[2]}, {v[3], v[4], v[5]});
            } else if (const json* b = find(e, "sphere")) {
                const auto v = as_numbers<4>(*b, child(path, "sphere"));
                r = camera_region::sphere({v[0], v[1], v[2]}, v[3]);
            } else {
                fail(path, expected);
            }
            r.validate(path);
            out.push_back(r);
        }
    };
    regions("keep_in", s.regions.keep_in);
    regions("keep_out", s.regions.keep_out);
    return s;
}

}  // namespace detail::json_io

inline nlohmann::ordered_json result_to_json(const result_document& d) {
    using namespace detail::json_io;
    ordered_json facet;
    facet["index"] = d.facet.index;
    facet["vertices"] = matrix(d.facet.vertices, "facet.vertices");
    facet["normal"] = numbers(d.facet.normal, "facet.normal");

    ordered_json camera = camera_record_json(d.camera);
    ordered_json task = task_record_json(d.task);

    ordered_json settings;
    settings["position_eps"] = finite(d.settings.position_eps, "settings.position_eps");
    settings["orientation_eps"] = finite(d.settings.orientation_eps, "settings.orientation_eps");
    settings["inner_contraction"] = d.settings.inner_contraction;
    settings["occlusion_cuts"] = d.settings.occlusion_cuts;
    settings["leaf_corner_boxes"] = d.settings.leaf_corner_boxes;
    settings["corner_depth"] = d.settings.corner_depth;
    settings["corner_rest_min_pieces"] = finite(d.settings.corner_rest_min_pieces, "settings.corner_rest_min_pieces");
    if (d.settings.refine_min_width)
        settings["refine_min_width"] = finite(*d.settings.refine_min_width, "settings.refine_min_width");
    settings["grow"] = d.settings.grow;

    ordered_json boxes = ordered_json::array();
    for (std::size_t i = 0; i < d.boxes.size(); ++i) {
        const box_record& b = d.boxes[i];
        const std::string path = element("boxes", i);
        ordered_json box;
        box["class"] = to_string(b.cls);
        box["position"] = bounds(b.position, child(path, "position"));
        box["orientation"] = bounds(b.orientation, child(path, "orientation"));
        // Extra fields: why a BOUNDARY box is undecided; that a VALID box's occlusion was not
        // checked (no_occlusion), so that a tool reading boxes alone cannot miss it.
        if (b.reason) box["undecided"] = std::string(to_string(*b.reason));
        if (b.cls == box_class::valid && !d.stats.occlusion_checked) box["occlusion"] = "unchecked";
        boxes.push_back(std::move(box));
    }

    const solve_stats& s = d.stats;
    ordered_json stats;
    // The fields of solve_stats_fields (solver/result.hpp), in its order. Beyond valid, boundary
    // and seconds they are extra fields (allowed by the contract): per-stage counts and times,
    // why the run ended.
    for_each_stats_field([&](const auto& field) {
        const std::string key(field.name);
        const auto& v = s.*field.member;
        using T = std::remove_cvref_t<decltype(v)>;
        if constexpr (std::is_same_v<T, double>) {
            stats[key] = finite(v, child("stats", key));
        } else if constexpr (std::is_same_v<T, termination>) {
            stats[key] = to_string(v);
        } else if constexpr (std::is_same_v<T, decltype(solve_stats::boundary_reasons)>) {
            ordered_json reasons;
            for (std::size_t r = 0; r < boundary_reason_count; ++r)
                reasons[std::string(to_string(static_cast<boundary_reason>(r)))] = v[r];
            stats[key] = std::move(reasons);
        } else {
            static_assert(std::is_same_v<T, std::size_t> || std::is_same_v<T, bool>, "a stats field of a new type");
            stats[key] = v;
        }
    });

    ordered_json j;
    j["format"] = result_format;
    j["version"] = format_version;
    j["facet"] = std::move(facet);
    j["camera"] = std::move(camera);
    j["task"] = std::move(task);
    j["settings"] = std::move(settings);
    put_scene(j, d.scene);
    j["boxes"] = std::move(boxes);
    j["stats"] = std::move(stats);
    return j;
}

/// Text of a JSON document laid out for people and diffs: one top-level member per line, and
/// one element per line for arrays of objects/arrays (so one box per line), each member dumped
/// compactly with round-trip doubles. Ends with a newline.
inline std::string json_text(const nlohmann::ordered_json& j) {
    using ordered_json = nlohmann::ordered_json;
    const certipose::detail::round_to_nearest_scope nearest;  // shortest round-trip digits
    const auto dump = [](const ordered_json& v) {
        return v.dump(-1, ' ', false, ordered_json::error_handler_t::replace);
    };
    if (!j.is_object() || j.empty()) return dump(j) + "\n";
    std::string out = "{\n";
    std::size_t n = 0;
    for (auto it = j.begin(); it != j.end(); ++it, ++n) {
        out += "  " + dump(ordered_json(it.key())) + ": ";
        const ordered_json& v = it.value();
        const bool nested_lines = v.is_array() && !v.empty() &&
                                  std::all_of(v.begin(), v.end(), [](const ordered_json& e) {
                                      return e.is_object() || e.is_array();
                                  });
        if (nested_lines) {
            out += "[\n";
            for (std::size_t i = 0; i < v.size(); ++i)
                out += "    " + dump(v[i]) + (i + 1 < v.size() ? ",\n" : "\n");
            out += "  ]";
        } else {
            out += dump(v);
        }
        out += n + 1 < j.size() ? ",\n" : "\n";
    }
    return out + "}\n";
}

/// Writes any JSON document (e.g. result_to_json plus extra fields) atomically, laid out by
/// json_text. Throws certipose::io_error(path) on failure; nothing is written half.
inline void write_json_file(const std::filesystem::path& path, const nlohmann::ordered_json& j) {
    write_file_atomically(path, json_text(j));
}

/// Writes the result JSON of docs/io.md atomically.
inline void write_result_json(const std::filesystem::path& path, const result_document& d) {
    write_json_file(path, result_to_json(d));
}

/// Reads a result JSON document (as written by result_to_json or by another tool). Fields it
/// does not know are ignored (the contract allows extras); required fields missing or of the
/// wrong type, an unknown class or termination, or a box with lower > upper are an
/// invalid_argument naming the JSON path. camera.d_max null reads as +inf; absent extra stats
/// read as 0 / "completed".
inline result_document result_from_json(const nlohmann::json& j) {
    using namespace detail::json_io;
    const certipose::detail::round_to_nearest_scope nearest;  // integer → double conversions
    result_document d;
    require_object(j, "");
    check_format(j, result_format);

    const json& facet = require_object(require(j, "", "facet", "an object"), "facet");
    d.facet.index = as_count(require(facet, "facet", "index", "an integer"), "facet.index");
    d.facet.vertices = as_matrix<3, 3>(require(facet, "facet", "vertices", "3 points"),
                                       "facet.vertices");
    d.facet.normal = as_numbers<3>(require(facet, "facet", "normal", "3 numbers"), "facet.normal");

    d.camera = camera_record_from_json(require(j, "", "camera", "an object"));
    d.task = task_record_from_json(require(j, "", "task", "an object"));

    const json& settings = require_object(require(j, "", "settings", "an object"), "settings");
    d.settings.position_eps = required_number(settings, "settings", "position_eps");
    d.settings.orientation_eps = required_number(settings, "settings", "orientation_eps");
    const auto flag = [&](const json& obj, const std::string& path, std::string_view key, bool& out) {
        if (const json* v = find(obj, key)) {
            if (!v->is_boolean()) fail(child(path, key), "expected true or false, got " + describe(*v));
            out = v->get<bool>();
        }
    };
    flag(settings, "settings", "inner_contraction", d.settings.inner_contraction);
    flag(settings, "settings", "occlusion_cuts", d.settings.occlusion_cuts);
    flag(settings, "settings", "leaf_corner_boxes", d.settings.leaf_corner_boxes);
    if (const json* v = find(settings, "corner_depth")) d.settings.corner_depth = as_count(*v, "settings.corner_depth");
    d.settings.corner_rest_min_pieces = optional_number(settings, "settings", "corner_rest_min_pieces").value_or(2.0);
    if (!(d.settings.corner_rest_min_pieces >= 0.0))
        fail("settings.corner_rest_min_pieces", "must be >= 0, got " + certipose::detail::format_double(d.settings.corner_rest_min_pieces));
    d.settings.refine_min_width = optional_number(settings, "settings", "refine_min_width");
    flag(settings, "settings", "grow", d.settings.grow);
    d.scene = scene_from_json(j);

    const json& boxes = require(j, "", "boxes", "an array");
    if (!boxes.is_array()) fail("boxes", "expected an array, got " + describe(boxes));
    d.boxes.reserve(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const std::string path = element("boxes", i);
        const json& b = require_object(boxes[i], path);
        box_record r;
        const std::string cls = as_string(require(b, path, "class", "\"valid\" or \"boundary\""),
                                          child(path, "class"), "\"valid\" or \"boundary\"");
        if (cls == "valid")
            r.cls = box_class::valid;
        else if (cls == "boundary")
            r.cls = box_class::boundary;
        else
            fail(child(path, "class"), "unknown class \"" + cls + "\" (expected \"valid\" or \"boundary\")");
        r.position = as_matrix<3, 2>(require(b, path, "position", "3 intervals"), child(path, "position"));
        r.orientation = as_matrix<3, 2>(require(b, path, "orientation", "3 intervals"),
                                        child(path, "orientation"));
        check_bounds(r.position, child(path, "position"));
        check_bounds(r.orientation, child(path, "orientation"));
        if (const json* u = find(b, "undecided")) {
            const std::string name = as_string(*u, child(path, "undecided"), "a string");
            r.reason = boundary_reason_from_string(name);
            if (!r.reason) fail(child(path, "undecided"), "unknown reason \"" + name + "\"");
        }
        d.boxes.push_back(r);
    }

    const json& stats = require_object(require(j, "", "stats", "an object"), "stats");
    solve_stats& s = d.stats;
    // The fields of solve_stats_fields (solver/result.hpp); an optional one that is absent reads
    // as its default (0, "completed", true), and an optional number that is null as 0.
    for_each_stats_field([&](const auto& field) {
        const std::string path = child("stats", field.name);
        auto& out = s.*field.member;
        using T = std::remove_cvref_t<decltype(out)>;
        if constexpr (std::is_same_v<T, double>) {
            out = field.required ? required_number(stats, "stats", field.name)
                                 : optional_number(stats, "stats", field.name).value_or(0.0);
        } else {
            const json* v = field.required ? &require(stats, "stats", field.name, "an integer") : find(stats, field.name);
            if (!v) return;
            if constexpr (std::is_same_v<T, std::size_t>) {
                out = as_count(*v, path);
            } else if constexpr (std::is_same_v<T, bool>) {
                if (!v->is_boolean()) fail(path, "expected true or false, got " + describe(*v));
                out = v->get<bool>();
            } else if constexpr (std::is_same_v<T, termination>) {
                const std::string name = as_string(*v, path, "a string");
                const auto reason = termination_from_string(name);
                if (!reason)
                    fail(path, "unknown termination \"" + name + "\" (expected completed, box_budget, deadline or cancelled)");
                out = *reason;
            } else {
                static_assert(std::is_same_v<T, decltype(solve_stats::boundary_reasons)>, "a stats field of a new type");
                require_object(*v, path);
                for (std::size_t r = 0; r < boundary_reason_count; ++r) {
                    const std::string_view key = to_string(static_cast<boundary_reason>(r));
                    if (const json* c = find(*v, key)) out[r] = as_count(*c, child(path, key));
                }
            }
        }
    });
    return d;
}

/// Parses a result JSON document from text (`source` as in parse_camera_task).
inline result_document parse_result_json(std::string_view text, const std::string& source = {}) {
    return detail::json_io::with_source(source, [&] {
        return result_from_json(detail::json_io::parse(text, source));
    });
}

/// Reads a result JSON file. Throws certipose::io_error(path) if it is missing, unreadable or
/// not JSON; certipose::invalid_argument (field() = JSON path) if it does not match the format.
inline result_document read_result_json(const std::filesystem::path& path) {
    return parse_result_json(detail::json_io::read_text_file(path, "read_result_json"),
                             path.string());
}

}  // namespace certipose
