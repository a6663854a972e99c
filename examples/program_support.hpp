// examples/program_support.hpp — what every certipose program does the same way (not a library
// header): exit codes, strict number parsing, the scene options, interruption by SIGINT/SIGTERM
// through the library's cancellation, and a progress line on stderr when it is a terminal. The
// skeleton that puts these together (one error line, the shared flags) is program_skeleton.hpp.
//
// `interruption` installs handlers for SIGINT and SIGTERM that only record the signal (the one
// thing a handler may safely do); a watcher thread turns it into `std::stop_source::request_stop`,
// which the solvers poll between boxes. The program then stops computing, discards or commits its
// outputs as its contract says (never a half-written file, no temporary left), and exits with
// 128 + the signal (130 for SIGINT, 143 for SIGTERM). A second signal while it winds down ends the
// process the default way.
//
// The scene options every program takes the same way (`add_scene_options`, `parse_scene_options`):
//   --occluder MESH[:SCALE]  (repeatable) an extra closed mesh in the occlusion scene — a fixture,
//                            the conveyor, the cell — read like --mesh, coordinates × SCALE
//                            (default 1). The text is split at its LAST colon only when what
//                            follows is a number, so "C:\parts\jig.off" or "a:b.off" are paths;
//                            a number that is not a positive finite factor is a usage error.
//   --keep-out REGION        (repeatable) no camera position in REGION
//   --keep-in REGION         (repeatable) camera positions only in the union of these REGIONs
//   --part-tolerance TX,TY,TZ,ROT  the part may sit off its nominal placement by any translation
//                            with |t_i| <= T_i (metres) combined with any rotation of at most ROT
//                            radians about any axis through the datum: every VALID box holds for
//                            every such placement (pose/placement_tolerance.hpp)
//   --datum X,Y,Z            the point the part rotates about (default: the part's centroid)
//   --part-axis NX,NY,NZ     the fixture form: ROT turns about this direction only (a plate's
//                            normal), so the part does not tip into the plate, and
//   --part-tilt TILT         a further rotation of at most TILT radians about any axis
//   --working-distance DMIN,DMAX, --min-view-angle RAD  what a calibration file given as --camera
//                            lacks (the camera JSON's d_min, d_max and task.min_view_angle):
//                            required with a calibration file, refused with a camera JSON. The
//                            file's kind is chosen by content (io/calibration.hpp `detect`), here
//                            at parse time, so that either mistake is a usage error (exit 2).
// REGION = box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX or sphere:X,Y,Z,R (metres, the part's frame after
// --scale and --part-pose: the cell's; solver/camera_regions.hpp). Reading the occluders and naming them in the occlusion
// policy's errors needs CGAL: program_scene.hpp.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <stdexcept>
#include <system_error>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <stop_token>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <certipose/camera/camera_model.hpp>
#include <certipose/error.hpp>
#include <certipose/io/calibration.hpp>
#include <certipose/occlusion/mesh_semantics.hpp>
#include <certipose/pose/part_pose.hpp>
#include <certipose/pose/placement_tolerance.hpp>
#include <certipose/solver/camera_regions.hpp>
#include <certipose/solver/paving.hpp>

#include <iostream>

namespace certipose_program {

namespace detail {
inline std::atomic<int> received_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "a signal handler may only touch lock-free atomics");

extern "C" inline void record_signal(int sig) {
    if (received_signal.exchange(sig) != 0) {  // the second one: give up winding down
        std::signal(sig, SIG_DFL);
        std::raise(sig);
    }
}
}  // namespace detail

/// SIGINT/SIGTERM as a stop request (see the header comment). One per program, for its lifetime.
class interruption {
public:
    interruption() {
        detail::received_signal.store(0);
        old_int_ = std::signal(SIGINT, detail::record_signal);
        old_term_ = std::signal(SIGTERM, detail::record_signal);
        watcher_ = std::jthread([this](std::stop_token done) {
            while (!done.stop_requested()) {
                if (detail::received_signal.load() != 0) {
                    source_.request_stop();
                    return;
                }
                std::this_thread::sleep_for(std::chrono::milliseconds(10));
            }
        });
    }
    interruption(const interruption&) = delete;
    interruption& operator=(const interruption&) = delete;
    ~interruption() {
        watcher_.request_stop();
        watcher_.join();
        std::signal(SIGINT, old_int_);
        std::signal(SIGTERM, old_term_);
    }

    std::stop_token token() const { return source_.get_token(); }
    /// The signal received, 0 if none.
    int signal() const noexcept { return detail::received_signal.load(); }
    bool interrupted() const noexcept { return signal() != 0; }
    /// 128 + the signal: the shell's convention for "killed by signal".
    int exit_code() const noexcept { return 128 + signal(); }
    static const char* name(int sig) noexcept { return sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "a signal"; }

private:
    std::stop_source source_;
    using handler = void (*)(int);
    handler old_int_ = SIG_DFL, old_term_ = SIG_DFL;
    std::jthread watcher_;
};

inline constexpr int exit_ok = 0;
inline constexpr int exit_failure = 1;  ///< bad input file, solver or write error
inline constexpr int exit_usage = 2;    ///< bad command line

/// Thrown by the checks below; becomes the one error line.
struct usage_error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// The number `text` spells (all of it), or "OPTION: expected WHAT, got 'TEXT'".
inline double parse_number(const std::string& option, const std::string& text, const char* what) {
    double v = 0.0;
    const char* first = text.data();
    const char* last = text.data() + text.size();
    const auto [end, ec] = std::from_chars(first, last, v);
    if (ec != std::errc{} || end != last || text.empty())
        throw usage_error(option + ": expected " + what + ", got '" + text + "'");
    return v;
}

/// A positive finite number.
inline double parse_double(const std::string& option, const std::string& text, const char* what) {
    const double v = parse_number(option, text, what);
    if (!(v > 0.0) || !std::isfinite(v))
        throw usage_error(option + ": must be " + what + ", got " + text);
    return v;
}

inline std::size_t parse_count(const std::string& option, const std::string& text,
                               std::size_t min) {
    std::size_t v = 0;
    const char* first = text.data();
    const char* last = text.data() + text.size();
    const auto [end, ec] = std::from_chars(first, last, v);  // decimal digits only, no sign
    if (ec == std::errc::result_out_of_range)
        throw usage_error(option + ": " + text + " is too large");
    if (ec != std::errc{} || end != last || text.empty())
        throw usage_error(option + ": expected an integer >= " + std::to_string(min) + ", got '" +
                          text + "'");
    if (v < min)
        throw usage_error(option + ": expected an integer >= " + std::to_string(min) + ", got " +
                          text);
    return v;
}

/// One --occluder: the mesh file and the factor its coordinates are multiplied by.
struct occluder_arg {
    std::filesystem::path path;
    double scale = 1.0;
};

/// The scene options of a program (see the header comment), validated.
struct scene_arguments {
    std::vector<occluder_arg> occluders;
    certipose::camera_regions regions;
    /// --part-tolerance and --datum (the datum unset: the part's centroid, set by apply_placement)
    std::optional<certipose::placement_tolerance> placement;
    /// --working-distance and --min-view-angle: set exactly when --camera is a calibration file
    std::optional<certipose::distance_range> working_distance;
    std::optional<double> min_view_angle;
    /// --mesh-semantics: how the occlusion reads the part and the occluders
    certipose::mesh_semantics semantics = certipose::mesh_semantics::automatic;
};

/// The scene options as given (CLI11 fills them; parse_scene_options checks them).
struct scene_options_text {
    std::vector<std::string> occluders, keep_in, keep_out;
    std::string part_tolerance, datum, part_axis, part_tilt;
    std::string working_distance, min_view_angle;
    std::string mesh_semantics = "auto";
};

/// MESH or MESH:SCALE (see the header comment); the file must exist, as --mesh's must.
inline occluder_arg parse_occluder(const std::string& text) {
    occluder_arg o{text, 1.0};
    if (const auto colon = text.rfind(':'); colon != std::string::npos) {
        const std::string tail = text.substr(colon + 1);
        double v = 0.0;
        const auto [end, ec] = std::from_chars(tail.data(), tail.data() + tail.size(), v);
        if (!tail.empty() && ec == std::errc{} && end == tail.data() + tail.size()) {  // MESH:NUMBER
            if (!(v > 0.0) || !std::isfinite(v))
                throw usage_error("--occluder " + text + ": the scale must be a positive finite factor, got '" + tail + "'");
            o.path = text.substr(0, colon);
            o.scale = v;
        }
    }
    if (o.path.empty()) throw usage_error("--occluder: no mesh file in '" + text + "'");
    std::error_code ec;
    if (!std::filesystem::exists(o.path, ec)) throw usage_error("--occluder: File does not exist: " + o.path.string());
    if (std::filesystem::is_directory(o.path, ec))
        throw usage_error("--occluder: " + o.path.string() + " is a directory, not a mesh file");
    return o;
}

/// A --keep-in / --keep-out REGION, or a usage error naming the text.
inline certipose::camera_region parse_region(const std::string& option, const std::string& text) {
    try {
        return certipose::parse_camera_region(text, option);
    } catch (const certipose::invalid_argument& e) {
        throw usage_error(e.what());
    }
}

/// Adds --occluder, --keep-out and --keep-in (repeatable, one value per occurrence) to `app`.
inline void add_scene_options(CLI::App& app, scene_options_text& text) {
    app.add_option("--occluder", text.occluders,
                   "an extra closed mesh in the occlusion scene (fixture, conveyor, cell), read like --mesh, "
                   "coordinates x SCALE (default 1); repeatable")
        ->type_name("MESH[:SCALE]")
        ->allow_extra_args(false);
    app.add_option("--keep-out", text.keep_out,
                   "no camera position in REGION: box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX or sphere:X,Y,Z,R "
                   "(metres, part frame after --scale and --part-pose); repeatable")
        ->type_name("REGION")
        ->allow_extra_args(false);
    app.add_option("--keep-in", text.keep_in,
                   "camera positions only inside REGION (or another --keep-in; same syntax); repeatable")
        ->type_name("REGION")
        ->allow_extra_args(false);
    app.add_option("--part-tolerance", text.part_tolerance,
                   "the part may be off its nominal placement by |t_i| <= T_i metres and a rotation of at most ROT "
                   "radians about the datum: every VALID box holds for every such placement")
        ->type_name("TX,TY,TZ,ROT");
    app.add_option("--part-axis", text.part_axis,
                   "with --part-tolerance: ROT turns the part about this direction only (a fixture plate's normal, "
                   "e.g. 0,0,1), so it slides and turns on the plate without tipping into it")
        ->type_name("NX,NY,NZ");
    app.add_option("--part-tilt", text.part_tilt,
                   "with --part-axis: the part may also tip by at most TILT radians about any axis (default 0)")
        ->type_name("TILT");
    app.add_option("--datum", text.datum, "the point the part rotates about (metres, part frame after --scale and --part-pose; "
                                          "default: the part's centroid); needs --part-tolerance")
        ->type_name("X,Y,Z");
    app.add_option("--working-distance", text.working_distance,
                   "with a calibration file as --camera: the camera-to-facet distances DMIN,DMAX (metres) "
                   "the image is in focus at (the camera JSON's d_min, d_max)")
        ->type_name("DMIN,DMAX");
    app.add_option("--min-view-angle", text.min_view_angle,
                   "with a calibration file as --camera: the smallest angle (radians, [0, pi/2)) between the "
                   "line of sight and the facet's plane (the camera JSON's task.min_view_angle)")
        ->type_name("RAD");
    app.add_option("--mesh-semantics", text.mesh_semantics,
                   "how occlusion reads the meshes: solid (closed solids only), soup (any triangles: overlapping "
                   "bodies, duplicates, open seams; a sight line is blocked by any triangle), or auto (default: "
                   "solid when every mesh is one, else soup, with a warning)")
        ->type_name("MODE")
        ->check(CLI::IsMember({"auto", "solid", "soup"}));
}

/// N comma-separated finite numbers, or a usage error naming the option and the text.
template <std::size_t N>
std::array<double, N> parse_numbers(const std::string& option, const std::string& text, const char* shape) {
    std::array<double, N> out{};
    std::size_t at = 0;
    for (std::size_t i = 0; i < N; ++i) {
        const std::size_t end = i + 1 < N ? text.find(',', at) : text.size();
        if (end == std::string::npos)
            throw usage_error(option + " " + text + ": expected " + shape + " (" + std::to_string(N) + " numbers)");
        const std::string item = text.substr(at, end - at);
        double v = 0.0;
        const auto [ptr, ec] = std::from_chars(item.data(), item.data() + item.size(), v);
        if (item.empty() || ec != std::errc{} || ptr != item.data() + item.size() || !std::isfinite(v))
            throw usage_error(option + " " + text + ": '" + item + "' is not a finite number (expected " + shape + ")");
        out[i] = v;
        at = end + 1;
    }
    return out;
}

/// --part-pose: "X,Y,Z,ROLL,PITCH,YAW" (metres, radians; R = Rz(yaw)·Ry(pitch)·Rx(roll), as in the
/// URDF export) or a row-major 3×4 / 4×4 matrix (12 or 16 numbers); a usage error names the text.
inline certipose::part_pose parse_part_pose(const std::string& text) {
    const std::size_t n = static_cast<std::size_t>(std::count(text.begin(), text.end(), ',')) + 1;
    constexpr const char* shape = "X,Y,Z,ROLL,PITCH,YAW (metres, radians) or a row-major 3x4 or 4x4 matrix";
    try {
        if (n == 6) {
            const auto v = parse_numbers<6>("--part-pose", text, shape);
            return certipose::part_pose_from_xyz_rpy({v[0], v[1], v[2]}, {v[3], v[4], v[5]}, "--part-pose");
        }
        if (n == 12) {
            const auto v = parse_numbers<12>("--part-pose", text, shape);
            return certipose::part_pose_from_matrix(std::vector<double>(v.begin(), v.end()), "--part-pose");
        }
        if (n == 16) {
            const auto v = parse_numbers<16>("--part-pose", text, shape);
            return certipose::part_pose_from_matrix(std::vector<double>(v.begin(), v.end()), "--part-pose");
        }
    } catch (const certipose::invalid_argument& e) {
        throw usage_error(e.what());
    }
    throw usage_error("--part-pose " + text + ": expected " + shape + ", got " + std::to_string(n) + " numbers");
}

/// True when the --camera file is a calibration file (OpenCV YAML/JSON, ROS camera_info) rather
/// than our camera/task JSON: by content, as certipose::read_camera_input chooses. An unreadable
/// file counts as a camera JSON; reading it later reports the error.
inline bool is_calibration_file(const std::filesystem::path& camera) {
    std::ifstream in(camera, std::ios::binary);
    if (!in) return false;
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    return certipose::detect(text) != certipose::calibration_format::unknown;
}

/// --working-distance and --min-view-angle against the kind of the --camera file (see the header
/// comment): required with a calibration file, refused with a camera JSON.
inline void parse_camera_options(const scene_options_text& text, const std::filesystem::path& camera, scene_arguments& s) {
    const bool given_d = !text.working_distance.empty(), given_a = !text.min_view_angle.empty();
    if (!is_calibration_file(camera)) {
        if (given_d || given_a)
            throw usage_error(std::string(given_d ? "--working-distance" : "--min-view-angle") + ": only with a calibration file as --camera; " +
                              camera.string() + " is a camera/task JSON, which has its own d_min, d_max and task.min_view_angle");
        return;
    }
    if (!given_d || !given_a)
        throw usage_error("--camera " + camera.string() + " is a calibration file (no working distance or task): give " +
                          (!given_d && !given_a ? "--working-distance DMIN,DMAX and --min-view-angle RAD"
                           : !given_d          ? "--working-distance DMIN,DMAX"
                                               : "--min-view-angle RAD"));
    const auto d = parse_numbers<2>("--working-distance", text.working_distance, "DMIN,DMAX");
    if (!(d[0] > 0.0 && d[0] < d[1]))
        throw usage_error("--working-distance " + text.working_distance + ": expected 0 < DMIN < DMAX (metres)");
    s.working_distance = certipose::distance_range{d[0], d[1]};
    const double a = parse_number("--min-view-angle", text.min_view_angle, "a number of radians in [0, pi/2)");
    if (!(a >= 0.0 && a < std::numbers::pi / 2))
        throw usage_error("--min-view-angle " + text.min_view_angle + ": expected radians in [0, pi/2)" +
                          (a >= std::numbers::pi / 2 && a <= 90.0 ? " (degrees?)" : ""));
    s.min_view_angle = a;
}

/// The scene options checked (usage_error naming the offending text); `camera` is the --camera
/// file, which decides whether --working-distance and --min-view-angle belong.
inline scene_arguments parse_scene_options(const scene_options_text& text, const std::filesystem::path& camera) {
    scene_arguments s;
    parse_camera_options(text, camera, s);
    s.semantics = text.mesh_semantics == "solid"  ? certipose::mesh_semantics::solid
                  : text.mesh_semantics == "soup" ? certipose::mesh_semantics::soup
                                                  : certipose::mesh_semantics::automatic;
    for (const auto& o : text.occluders) s.occluders.push_back(parse_occluder(o));
    for (const auto& r : text.keep_in) s.regions.keep_in.push_back(parse_region("--keep-in", r));
    for (const auto& r : text.keep_out) s.regions.keep_out.push_back(parse_region("--keep-out", r));
    if (!text.datum.empty() && text.part_tolerance.empty())
        throw usage_error("--datum " + text.datum + ": needs --part-tolerance (a datum alone moves nothing)");
    if (!text.part_axis.empty() && text.part_tolerance.empty())
        throw usage_error("--part-axis " + text.part_axis + ": needs --part-tolerance (an axis alone moves nothing)");
    if (!text.part_tilt.empty() && text.part_axis.empty())
        throw usage_error("--part-tilt " + text.part_tilt +
                          ": needs --part-axis (without an axis, --part-tolerance's ROT is about any axis already)");
    if (!text.part_tolerance.empty()) {
        const auto v = parse_numbers<4>("--part-tolerance", text.part_tolerance, "TX,TY,TZ,ROT");
        certipose::placement_tolerance t{.translation = {v[0], v[1], v[2]}, .rotation = v[3]};
        if (!text.part_axis.empty()) {
            const auto n = parse_numbers<3>("--part-axis", text.part_axis, "NX,NY,NZ");
            t.axis = Eigen::Vector3d(n[0], n[1], n[2]);
            if (t.axis->isZero(0)) throw usage_error("--part-axis " + text.part_axis + ": the axis must not be 0,0,0");
        }
        if (!text.part_tilt.empty()) {
            t.tilt = parse_number("--part-tilt", text.part_tilt, "TILT (radians)");
            if (!(t.tilt >= 0) || !(t.tilt <= 1.5707963267948966))
                throw usage_error("--part-tilt " + text.part_tilt + ": must be in [0, pi/2] radians" +
                                  (t.tilt > 1.5707963267948966 && t.tilt <= 90 ? " (degrees? give radians)" : ""));
        }
        if (!text.datum.empty()) {
            const auto d = parse_numbers<3>("--datum", text.datum, "X,Y,Z");
            t.datum = Eigen::Vector3d(d[0], d[1], d[2]);
        }
        try {
            t.validate();
        } catch (const certipose::invalid_argument& e) {
            throw usage_error("--part-tolerance " + text.part_tolerance + ": " + e.what());
        }
        s.placement = t;
    }
    return s;
}

/// The file will be written at the end of a possibly long run: fail now if it cannot be.
inline void check_output(const std::string& option, const std::filesystem::path& p) {
    std::error_code ec;
    if (!p.has_filename()) throw usage_error(option + ": not a file name: '" + p.string() + "'");
    if (std::filesystem::is_directory(p, ec))
        throw usage_error(option + ": " + p.string() + " is a directory");
    const std::filesystem::path dir = p.parent_path().empty() ? "." : p.parent_path();
    if (!std::filesystem::is_directory(dir, ec))
        throw usage_error(option + ": directory does not exist: " + dir.string());
}

inline std::string one_line(std::string s) {
    for (char& c : s)
        if (c == '\n' || c == '\r') c = ' ';
    while (!s.empty() && s.back() == ' ') s.pop_back();
    return s;
}


/// The exit code of a run a signal stopped, after one line saying so (for programs that then
/// write nothing).
inline int report_interrupted(const char* program, const interruption& signals) {
    std::cerr << program << ": interrupted by " << interruption::name(signals.signal()) << "; nothing written\n";
    return signals.exit_code();
}

/// True when progress should be drawn: stderr is a terminal and the user did not ask for quiet.
inline bool show_progress(bool quiet) { return !quiet && ::isatty(STDERR_FILENO); }

/// What the program is doing before its progress line starts (reading and checking a large
/// mesh takes seconds: ~15 s for 10^6 faces, most of it CGAL's self-intersection test), on one
/// stderr line rewritten in place; only when stderr is a terminal. `done()` clears it.
class stage_line {
public:
    stage_line(const char* program, bool quiet) : program_(program), on_(show_progress(quiet)) {}
    stage_line(const stage_line&) = delete;
    stage_line& operator=(const stage_line&) = delete;
    ~stage_line() { done(); }
    void show(const std::string& what) {
        if (!on_) return;
        std::fprintf(stderr, "\r\033[K%s: %s...", program_, what.c_str());
        std::fflush(stderr);
        shown_ = true;
    }
    void done() {
        if (shown_) std::fprintf(stderr, "\r\033[K");
        shown_ = false;
    }

private:
    const char* program_;
    bool on_, shown_ = false;
};

/// This process's resident memory in bytes (Linux /proc/self/statm), or 0 where it cannot be read:
/// the progress lines show it, so that a user sees a large run's footprint before it hurts.
inline std::size_t resident_bytes() {
    std::ifstream in("/proc/self/statm");
    std::size_t pages = 0, resident = 0;
    if (!(in >> pages >> resident)) return 0;
    const long page = ::sysconf(_SC_PAGESIZE);
    return resident * static_cast<std::size_t>(page > 0 ? page : 4096);
}

/// "1h02m", "3m07s", "12.3s".
inline std::string duration_text(double s) {
    char buf[32];
    if (!(s >= 0.0) || s > 1e7) return "?";
    if (s >= 3600) std::snprintf(buf, sizeof buf, "%dh%02dm", static_cast<int>(s / 3600), static_cast<int>(s / 60) % 60);
    else if (s >= 60) std::snprintf(buf, sizeof buf, "%dm%02ds", static_cast<int>(s / 60), static_cast<int>(s) % 60);
    else std::snprintf(buf, sizeof buf, "%.1fs", s);
    return buf;
}

}  // namespace certipose_program
