// certipose/io/plan_export.hpp — a plan's cameras in the terms a fitter, a robot cell and a CAD
// tool use: a nominal pose (position + quaternion, 4×4 transform, URDF roll-pitch-yaw) and a
// tolerance that the certified box contains (position half-widths, the optical-axis cone and the
// roll about the axis). Writes the CSV and the URDF snippet of certipose-export; the MoveIt
// YAML, glTF and HTML writers build on `camera_exports` (io/moveit_yaml.hpp, io/plan_gltf.hpp,
// io/plan_html.hpp). Formats: docs/conventions.md#exports.
//
// Every tolerance written here is *inside* the plan's box (inner, not enclosing): a fitter who
// stays within it installs a camera whose every pose the plan certified. Euler half-widths are not
// written because they are not a fitter's numbers (docs/conventions.md#zxz-angles).
#pragma once

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

/// The CSV of certipose-export: a header row, then one row per camera (docs/conventions.md#csv).
inline std::string plan_csv(const plan_document& plan) {
    using detail::plan_export::number;
    std::string s = "camera,x,y,z,qx,qy,qz,qw";
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) s += ",m" + std::to_string(r) + std::to_string(c);
    s += ",half_x,half_y,half_z,axis_cone_half_angle,roll_half_range,mount_x,mount_y,mount_z,facets,certified_area\n";
    const auto exports = camera_exports(plan);
    const certipose::detail::round_to_nearest_scope nearest;
    for (const auto& e : exports) {
        s += std::to_string(e.index);
        for (double v : e.position) s += "," + number(v);
        for (double v : e.quaternion) s += "," + number(v);
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c)
                s += "," + number(r < 3 ? (c < 3 ? e.rotation(r, c) : e.position[static_cast<std::size_t>(r)]) : (c < 3 ? 0.0 : 1.0));
        for (double v : e.position_half) s += "," + number(v);
        s += "," + number(e.axis.cone) + "," + number(e.axis.roll);
        for (double v : e.mount_position) s += "," + number(v);
        s += "," + std::to_string(plan.cameras[e.index].facets.size()) + "," + number(plan.cameras[e.index].certified_area);
        s += "\n";
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

/// A URDF snippet: per camera, a `camera_<k>_mount` link on a fixed joint to `parent_frame` at the
/// nominal mount pose, and a `camera_<k>_optical_frame` link on a fixed joint to the mount at the
/// mount offset (the optical frame's axes are the mount's). Paste it inside a <robot>.
inline std::string plan_urdf(const plan_document& plan, const std::string& parent_frame) {
    check_frame_name("parent_frame", parent_frame);
    using detail::plan_export::number;
    const auto exports = camera_exports(plan);
    const certipose::detail::round_to_nearest_scope nearest;
    const auto xyz = [&](const std::array<double, 3>& v) { return number(v[0]) + " " + number(v[1]) + " " + number(v[2]); };
    std::string s = "<!-- certipose deployment plan: " + std::to_string(exports.size()) +
                    " cameras, nominal poses (docs/conventions.md#urdf). Paste inside <robot>. -->\n";
    for (const auto& e : exports) {
        const std::string k = std::to_string(e.index);
        const auto rpy = urdf_rpy(e.rotation);
        s += "<link name=\"camera_" + k + "_mount\"/>\n";
        s += "<joint name=\"camera_" + k + "_mount_joint\" type=\"fixed\">\n";
        s += "  <parent link=\"" + parent_frame + "\"/>\n  <child link=\"camera_" + k + "_mount\"/>\n";
        s += "  <origin xyz=\"" + xyz(e.mount_position) + "\" rpy=\"" + xyz(rpy) + "\"/>\n</joint>\n";
        s += "<link name=\"camera_" + k + "_optical_frame\"/>\n";
        s += "<joint name=\"camera_" + k + "_optical_joint\" type=\"fixed\">\n";
        s += "  <parent link=\"camera_" + k + "_mount\"/>\n  <child link=\"camera_" + k + "_optical_frame\"/>\n";
        s += "  <origin xyz=\"" + xyz(plan.camera.mount_offset) + "\" rpy=\"0 0 0\"/>\n</joint>\n";
    }
    return s;
}

}  // namespace certipose
