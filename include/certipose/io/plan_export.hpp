// certipose/io/plan_export.hpp — a plan's cameras in the terms a fitter, a robot cell and a CAD
// tool use: a nominal pose (position + quaternion, 4×4 transform, URDF roll-pitch-yaw) and a
// tolerance that the certified box contains (position half-widths, the optical-axis cone and the
// roll about the axis). Writes the fitter's CSV and the URDF of certipose-export; the MoveIt
// YAML, glTF and HTML writers build on `camera_exports` (io/moveit_yaml.hpp, io/plan_gltf.hpp,
// io/plan_html.hpp). Formats: docs/conventions.md#exports.
//
// Every tolerance written here is *inside* the plan's box (inner, not enclosing): a fitter who
// stays within it installs a camera whose every pose the plan certified. Euler half-widths are not
// written because they are not a fitter's numbers (docs/conventions.md#zxz-angles).
#pragma once

#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/io/plan_files.hpp"
#include "certipose/pose/axis_tolerance.hpp"
#include "certipose/pose/rotation.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

namespace certipose {

/// One plan camera, ready to export. Positions are of the projection centre unless named mount.
struct camera_export {
    std::size_t index = 0;
    std::array<double, 3> position{};       ///< nominal projection centre: the position box's centre
    std::array<double, 3> zxz{};            ///< nominal (φ, γ, β): the orientation box's centre
    Eigen::Matrix3d rotation;               ///< R(φ, γ, β): camera (optical) frame → part frame
    std::array<double, 4> quaternion{};     ///< R as (qx, qy, qz, qw), qw ≥ 0
    std::array<double, 3> position_half{};  ///< every position within ± these of `position` is in the box
    axis_tolerance axis;                    ///< optical-axis cone and roll inside the orientation box
    double rotation_angle = 0;              ///< every rotation by at most this (any axis) is inside
    std::array<double, 3> mount_position{}; ///< the mount point: position − R·mount_offset
};

namespace detail::plan_export {
/// The largest half-width around c = (lo+hi)/2 that stays within [lo, hi] despite rounding.
inline double inner_half(double lo, double hi, double c) {
    const double h = std::min(c - lo, hi - c);
    return std::max(0.0, h - 4 * std::numeric_limits<double>::epsilon() * std::max({1.0, std::abs(lo), std::abs(hi)}));
}
inline std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}
}  // namespace detail::plan_export

/// The export view of every camera of `plan`, in plan order. `mount_offset` is the projection
/// centre in the mount frame (the camera JSON's "mount_offset"; zero: the mount is the centre).
inline std::vector<camera_export> camera_exports(const plan_document& plan) {
    const certipose::detail::round_to_nearest_scope nearest;
    std::vector<camera_export> out;
    out.reserve(plan.cameras.size());
    const Eigen::Vector3d offset(plan.camera.mount_offset[0], plan.camera.mount_offset[1], plan.camera.mount_offset[2]);
    for (std::size_t k = 0; k < plan.cameras.size(); ++k) {
        const auto& c = plan.cameras[k];
        camera_export e;
        e.index = k;
        for (std::size_t i = 0; i < 3; ++i) {
            e.position[i] = (c.position[i][0] + c.position[i][1]) / 2;
            e.position_half[i] = detail::plan_export::inner_half(c.position[i][0], c.position[i][1], e.position[i]);
        }
        e.zxz = zxz_centre(c.orientation);
        e.rotation = zxz_rotation(e.zxz[0], e.zxz[1], e.zxz[2]);
        Eigen::Quaterniond q(e.rotation);
        q.normalize();
        if (q.w() < 0) q.coeffs() = -q.coeffs();
        e.quaternion = {q.x(), q.y(), q.z(), q.w()};
        e.axis = certified_axis_tolerance(c.orientation);
        e.rotation_angle = certified_rotation_angle(c.orientation);
        const Eigen::Vector3d mount = Eigen::Vector3d(e.position[0], e.position[1], e.position[2]) - e.rotation * offset;
        e.mount_position = {mount[0], mount[1], mount[2]};
        out.push_back(e);
    }
    return out;
}

/// The point a fitter aims camera `cam` at: where its nominal optical axis (from the position
/// box's centre along R(φ, γ, β)·z of the orientation box's centre) first meets the part; when the
/// axis misses every facet (it passes through a hole or beside an edge), the point of the axis
/// nearest the area-weighted centroid of the camera's facets. It is a number to install by, not a
/// certificate: plain double arithmetic, and only the part's facets (not the scene's occluders).
inline std::array<double, 3> plan_aim(const triangle_mesh& mesh, const plan_document::camera_box& cam) {
    const certipose::detail::round_to_nearest_scope nearest;
    const Eigen::Vector3d p(cam.nominal[0], cam.nominal[1], cam.nominal[2]);
    const Eigen::Vector3d axis = zxz_rotation(cam.nominal[3], cam.nominal[4], cam.nominal[5]) * Eigen::Vector3d::UnitZ();
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t f = 0; f < mesh.num_faces(); ++f) {  // Möller–Trumbore, front and back faces
        const auto& v = mesh.facet(f).v;
        const Eigen::Vector3d e1 = v[1] - v[0], e2 = v[2] - v[0], q = axis.cross(e2);
        const double det = e1.dot(q);
        if (std::abs(det) < 1e-300) continue;
        const Eigen::Vector3d s = p - v[0];
        const double u = s.dot(q) / det;
        if (u < 0 || u > 1) continue;
        const Eigen::Vector3d r = s.cross(e1);
        const double w = axis.dot(r) / det;
        if (w < 0 || u + w > 1) continue;
        if (const double t = e2.dot(r) / det; t > 0 && t < best) best = t;
    }
    if (!std::isfinite(best)) {
        Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
        double area = 0;
        for (std::size_t f : cam.facets) {
            const auto& v = mesh.facet(f).v;
            const double a = (v[1] - v[0]).cross(v[2] - v[0]).norm() / 2;
            centroid += a * (v[0] + v[1] + v[2]) / 3, area += a;
        }
        best = area > 0 ? std::max(0.0, (centroid / area - p).dot(axis)) : 0.0;
    }
    const Eigen::Vector3d aim = p + best * axis;
    return {aim[0], aim[1], aim[2]};
}

/// URDF's fixed-axis roll-pitch-yaw of a rotation: R = Rz(yaw)·Ry(pitch)·Rx(roll).
inline std::array<double, 3> urdf_rpy(const Eigen::Matrix3d& r) {
    // Pitch and yaw from the first column (its horizontal part gives cos(pitch) accurately up to
    // the lock, where asin(−R₂₀) would lose half the digits); then roll from what is left,
    // Ry(pitch)ᵀ·Rz(yaw)ᵀ·R = Rx(roll), so that near the lock, where yaw alone is ill-conditioned,
    // roll absorbs its error and the three angles still rebuild R to rounding.
    const double cp = std::hypot(r(0, 0), r(1, 0));
    const double pitch = std::atan2(-r(2, 0), cp);
    const double yaw = cp > 0 ? std::atan2(r(1, 0), r(0, 0)) : 0.0;  // at the lock: all of it in roll
    const Eigen::Matrix3d rest = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                                  Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY())).toRotationMatrix().transpose() * r;
    return {std::atan2(rest(2, 1), rest(1, 1)), pitch, yaw};
}

/// A camera in a fitter's units: millimetres to 0.1 mm, degrees to 0.01°. The nominal position is
/// rounded to the nearest step; each tolerance is rounded *down* after giving up what that rounding
/// moved the nominal (0.05 mm; the quaternion's 9 decimals move the orientation by ~1e-9 rad,
/// well inside the 1e-5° given up on each angle), so that a fitter who keeps within the printed
/// tolerance of the printed nominal stays inside the certified box.
struct fitter_camera {
    std::array<double, 3> position_mm{}, half_mm{}, mount_mm{};
    double axis_cone_deg = 0, roll_deg = 0;
    std::optional<std::array<double, 3>> aim_mm;  ///< the plan's aim point, when it has one
    double aim_distance_mm = 0;                   ///< from the projection centre to the aim point
};

namespace detail::plan_export {
inline double to_step(double v, double step) {
    const double r = std::round(v / step) * step;
    return r == 0 ? 0.0 : r;  // never "-0.0"
}
inline double inward(double v, double step, double margin) { return std::max(0.0, std::floor((v - margin) / step) * step); }
inline std::string fixed(double v, int decimals) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v == 0 ? 0.0 : v);
    return buf;
}
}  // namespace detail::plan_export

inline fitter_camera fitter_units(const camera_export& e, const plan_document::camera_box& box) {
    using namespace detail::plan_export;
    const certipose::detail::round_to_nearest_scope nearest;
    constexpr double deg = 180 / std::numbers::pi;
    fitter_camera f;
    for (std::size_t i = 0; i < 3; ++i) {
        f.position_mm[i] = to_step(1000 * e.position[i], 0.1);
        f.half_mm[i] = inward(1000 * e.position_half[i], 0.1, 0.05 + 1e-6);
        f.mount_mm[i] = to_step(1000 * e.mount_position[i], 0.1);
    }
    f.axis_cone_deg = inward(deg * e.axis.cone, 0.01, 1e-5);
    f.roll_deg = inward(deg * e.axis.roll, 0.01, 1e-5);
    if (box.aim) {
        std::array<double, 3> aim{};
        double d2 = 0;
        for (std::size_t i = 0; i < 3; ++i) {
            aim[i] = to_step(1000 * (*box.aim)[i], 0.1);
            d2 += std::pow(1000 * ((*box.aim)[i] - e.position[i]), 2);
        }
        f.aim_mm = aim;
        f.aim_distance_mm = to_step(std::sqrt(d2), 0.1);
    }
    return f;
}

/// The fitter's CSV of certipose-export: a header row whose every column names its unit, then one
/// row per camera (docs/conventions.md#csv). The robot cell's full-precision numbers, in metres
/// and radians, are in the URDF and MoveIt exports.
inline std::string plan_csv(const plan_document& plan) {
    using detail::plan_export::fixed;
    std::string s = "camera,x_mm,y_mm,z_mm,qx,qy,qz,qw";
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) s += ",r" + std::to_string(r) + std::to_string(c);
    s += ",half_x_mm,half_y_mm,half_z_mm,axis_cone_half_angle_deg,roll_half_range_deg,mount_x_mm,mount_y_mm,mount_z_mm"
         ",aim_x_mm,aim_y_mm,aim_z_mm,aim_distance_mm,facets,certified_area_mm2\n";
    const auto exports = camera_exports(plan);
    const certipose::detail::round_to_nearest_scope nearest;
    for (const auto& e : exports) {
        const auto& box = plan.cameras[e.index];
        const fitter_camera f = fitter_units(e, box);
        s += std::to_string(e.index);
        for (double v : f.position_mm) s += "," + fixed(v, 1);
        for (double v : e.quaternion) s += "," + fixed(v, 9);
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) s += "," + fixed(e.rotation(r, c), 9);
        for (double v : f.half_mm) s += "," + fixed(v, 1);
        s += "," + fixed(f.axis_cone_deg, 2) + "," + fixed(f.roll_deg, 2);
        for (double v : f.mount_mm) s += "," + fixed(v, 1);
        if (f.aim_mm) {
            for (double v : *f.aim_mm) s += "," + fixed(v, 1);
            s += "," + fixed(f.aim_distance_mm, 1);
        } else {
            s += ",,,,";  // a plan written before aim points were recorded
        }
        s += "," + std::to_string(box.facets.size()) + "," + fixed(1e6 * box.certified_area, 1) + "\n";
    }
    return s;
}

/// Checks a ROS/URDF name (frame, link): non-empty, letters, digits, '_', '/', '-', '.'.
inline void check_frame_name(const std::string& option, const std::string& name) {
    const bool ok = !name.empty() && std::all_of(name.begin(), name.end(), [](char ch) {
        return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '/' || ch == '-' || ch == '.';
    });
    if (!ok) throw invalid_argument(option, "expected a frame name of letters, digits, '_', '/', '-' or '.', got '" + name + "'");
}

/// What `plan_urdf` writes.
struct urdf_options {
    std::string parent_frame = "world";  ///< the link the cameras are fixed to
    /// Camera k's links are `link_prefix + k + "_mount"` and `+ "_optical_frame"`; the MoveIt
    /// export takes the same prefix, so that its link names are this URDF's.
    std::string link_prefix = "camera_";
    std::string robot_name = "certipose_cameras";
    /// Only the links and joints of the cameras, to paste inside another <robot> that has
    /// `parent_frame`; otherwise a complete <robot> that declares `parent_frame` as its root link.
    bool snippet = false;
};

/// A URDF (docs/conventions.md#urdf): per camera, a `<prefix>k_mount` link on a fixed joint to
/// `parent_frame` at the nominal mount pose, and a `<prefix>k_optical_frame` link on a fixed joint
/// to the mount at the mount offset (the optical frame's axes are the mount's).
inline std::string plan_urdf(const plan_document& plan, const urdf_options& o = {}) {
    check_frame_name("parent_frame", o.parent_frame);
    check_frame_name("link_prefix", o.link_prefix + "0");
    check_frame_name("robot_name", o.robot_name);
    using detail::plan_export::number;
    const auto exports = camera_exports(plan);
    const certipose::detail::round_to_nearest_scope nearest;
    const auto xyz = [&](const std::array<double, 3>& v) { return number(v[0]) + " " + number(v[1]) + " " + number(v[2]); };
    const std::string in = o.snippet ? "" : "  ";
    std::string s;
    if (o.snippet) {
        s = "<!-- certipose deployment plan: " + std::to_string(exports.size()) +
            " cameras, nominal poses (docs/conventions.md#urdf). Paste inside a <robot> that has the link \"" +
            o.parent_frame + "\". -->\n";
    } else {
        s = "<?xml version=\"1.0\"?>\n<!-- certipose deployment plan: " + std::to_string(exports.size()) +
            " cameras, nominal poses (docs/conventions.md#urdf). -->\n<robot name=\"" + o.robot_name + "\">\n" +
            in + "<link name=\"" + o.parent_frame + "\"/>\n";
    }
    for (const auto& e : exports) {
        const std::string k = o.link_prefix + std::to_string(e.index);
        const auto rpy = urdf_rpy(e.rotation);
        s += in + "<link name=\"" + k + "_mount\"/>\n";
        s += in + "<joint name=\"" + k + "_mount_joint\" type=\"fixed\">\n";
        s += in + "  <parent link=\"" + o.parent_frame + "\"/>\n" + in + "  <child link=\"" + k + "_mount\"/>\n";
        s += in + "  <origin xyz=\"" + xyz(e.mount_position) + "\" rpy=\"" + xyz(rpy) + "\"/>\n" + in + "</joint>\n";
        s += in + "<link name=\"" + k + "_optical_frame\"/>\n";
        s += in + "<joint name=\"" + k + "_optical_joint\" type=\"fixed\">\n";
        s += in + "  <parent link=\"" + k + "_mount\"/>\n" + in + "  <child link=\"" + k + "_optical_frame\"/>\n";
        s += in + "  <origin xyz=\"" + xyz(plan.camera.mount_offset) + "\" rpy=\"0 0 0\"/>\n" + in + "</joint>\n";
    }
    if (!o.snippet) s += "</robot>\n";
    return s;
}

}  // namespace certipose
