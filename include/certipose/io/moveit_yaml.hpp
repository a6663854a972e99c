// certipose/io/moveit_yaml.hpp — a plan's cameras as ROS moveit_msgs/Constraints in YAML, one per
// camera: a BOX PositionConstraint on the projection centre and an OrientationConstraint with
// rotation-vector tolerances (parameterization 1). Needs yaml-cpp (Debian libyaml-cpp-dev).
//
// Both regions are inside the plan's certified box, so a motion planner that honours them only
// reaches certified poses:
//   * the BOX is centred on the position box's centre with its inner half-widths;
//   * MoveIt measures the orientation error as the rotation vector v of R_des⁻¹·R and accepts
//     |v_i| ≤ tol_i; a rotation with |v_i| ≤ t has angle ≤ √3·t, and every rotation within the
//     angle `camera_export::rotation_angle` of the nominal lies in the ZXZ box
//     (pose/axis_tolerance.hpp). So tol = rotation_angle/√3 on each axis.
// The constrained link is the camera's optical frame, or its mount with the mount offset as
// MoveIt's target_point_offset (the constrained point is then still the projection centre).
#pragma once

#include "certipose/io/plan_export.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <string>

namespace certipose {

/// Which link of the camera the constraints name.
enum class constrained_link { optical_frame, mount };

struct moveit_options {
    std::string frame_id = "world";  ///< the part's frame in the planning scene
    constrained_link link = constrained_link::optical_frame;
    /// The link name of camera k: `link_prefix + k + "_optical_frame"` or `+ "_mount"`.
    std::string link_prefix = "camera_";
};

/// The rotation-vector tolerance (per axis, radians) written for a camera.
inline double moveit_axis_tolerance(const camera_export& e) { return e.rotation_angle / std::sqrt(3.0) * (1 - 1e-12); }

/// The YAML document (docs/conventions.md#moveit): {"cameras": [{"name", "facets", "constraints":
/// moveit_msgs/Constraints}]}.
inline std::string plan_moveit_yaml(const plan_document& plan, const moveit_options& o = {}) {
    check_frame_name("frame_id", o.frame_id);
    check_frame_name("link_prefix", o.link_prefix + "0");
    const auto exports = camera_exports(plan);
    const certipose::detail::round_to_nearest_scope nearest;
    YAML::Emitter y;
    y.SetDoublePrecision(17);
    const auto vec = [&](const char* a, double x, const char* b, double yv, const char* c, double z) {
        y << YAML::Flow << YAML::BeginMap << YAML::Key << a << YAML::Value << x << YAML::Key << b << YAML::Value << yv
          << YAML::Key << c << YAML::Value << z << YAML::EndMap;
    };
    const auto header = [&] {
        y << YAML::Key << "header" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "frame_id"
          << YAML::Value << o.frame_id << YAML::EndMap;
    };
    y << YAML::Comment("certipose deployment plan as moveit_msgs/Constraints (docs/conventions.md#moveit)");
    y << YAML::BeginMap << YAML::Key << "cameras" << YAML::Value << YAML::BeginSeq;
    for (const auto& e : exports) {
        const std::string link = o.link_prefix + std::to_string(e.index) +
                                 (o.link == constrained_link::mount ? "_mount" : "_optical_frame");
        const auto& offset = o.link == constrained_link::mount ? plan.camera.mount_offset : std::array<double, 3>{};
        const double tol = moveit_axis_tolerance(e);
        y << YAML::BeginMap;
        y << YAML::Key << "name" << YAML::Value << "camera " + std::to_string(e.index);
        y << YAML::Key << "facets" << YAML::Value << YAML::Flow << plan.cameras[e.index].facets;
        y << YAML::Key << "constraints" << YAML::Value << YAML::BeginMap;
        y << YAML::Key << "name" << YAML::Value << "certipose camera " + std::to_string(e.index);
        y << YAML::Key << "position_constraints" << YAML::Value << YAML::BeginSeq << YAML::BeginMap;
        header();
        y << YAML::Key << "link_name" << YAML::Value << link;
        y << YAML::Key << "target_point_offset" << YAML::Value;
        vec("x", offset[0], "y", offset[1], "z", offset[2]);
        y << YAML::Key << "constraint_region" << YAML::Value << YAML::BeginMap;
        y << YAML::Key << "primitives" << YAML::Value << YAML::BeginSeq << YAML::BeginMap;
        y << YAML::Key << "type" << YAML::Value << 1;  // shape_msgs/SolidPrimitive BOX
        y << YAML::Key << "dimensions" << YAML::Value << YAML::Flow << YAML::BeginSeq << 2 * e.position_half[0]
          << 2 * e.position_half[1] << 2 * e.position_half[2] << YAML::EndSeq;
        y << YAML::EndMap << YAML::EndSeq;
        y << YAML::Key << "primitive_poses" << YAML::Value << YAML::BeginSeq << YAML::BeginMap;
        y << YAML::Key << "position" << YAML::Value;
        vec("x", e.position[0], "y", e.position[1], "z", e.position[2]);
        y << YAML::Key << "orientation" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "x" << YAML::Value
          << 0.0 << YAML::Key << "y" << YAML::Value << 0.0 << YAML::Key << "z" << YAML::Value << 0.0 << YAML::Key << "w"
          << YAML::Value << 1.0 << YAML::EndMap;
        y << YAML::EndMap << YAML::EndSeq << YAML::EndMap;  // primitive_poses, constraint_region
        y << YAML::Key << "weight" << YAML::Value << 1.0 << YAML::EndMap << YAML::EndSeq;
        y << YAML::Key << "orientation_constraints" << YAML::Value << YAML::BeginSeq << YAML::BeginMap;
        header();
        y << YAML::Key << "link_name" << YAML::Value << link;
        y << YAML::Key << "orientation" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "x" << YAML::Value
          << e.quaternion[0] << YAML::Key << "y" << YAML::Value << e.quaternion[1] << YAML::Key << "z" << YAML::Value
          << e.quaternion[2] << YAML::Key << "w" << YAML::Value << e.quaternion[3] << YAML::EndMap;
        y << YAML::Key << "absolute_x_axis_tolerance" << YAML::Value << tol;
        y << YAML::Key << "absolute_y_axis_tolerance" << YAML::Value << tol;
        y << YAML::Key << "absolute_z_axis_tolerance" << YAML::Value << tol;
        y << YAML::Key << "parameterization" << YAML::Value << 1 << YAML::Comment("ROTATION_VECTOR");
        y << YAML::Key << "weight" << YAML::Value << 1.0 << YAML::EndMap << YAML::EndSeq;
        y << YAML::EndMap;  // constraints
        y << YAML::EndMap;  // camera
    }
    y << YAML::EndSeq << YAML::EndMap;
    if (!y.good()) throw invalid_argument("plan", std::string("plan_moveit_yaml: ") + y.GetLastError());
    return std::string(y.c_str()) + "\n";
}

}  // namespace certipose
