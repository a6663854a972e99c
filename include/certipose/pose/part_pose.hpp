// certipose/pose/part_pose.hpp — where the part stands in the cell: a rigid motion p ↦ R·p + t
// applied to the mesh as it is read, so that a part can be stood on end or moved onto its fixture
// without editing its file (the programs' --part-pose).
//
// Why a placement and not a frame change of the results: the certificates are for the triangles
// the solver is given. Moving the mesh first (in double, round to nearest) and certifying the
// moved triangles keeps every claim about the very mesh that is recorded (by its digest), while
// the occluders, keep-in/keep-out regions and results stay in the cell's frame, where the fixture
// is. A pose is a rotation within 1e-9 of orthonormal with determinant +1 (a mirror would turn
// the part inside out); the rotation used is the one given, not re-orthonormalised, so that the
// same text always gives the same mesh.
#pragma once

#include "certipose/error.hpp"
#include "certipose/geometry/triangle_mesh.hpp"

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace certipose {

/// A rigid placement of the part: p ↦ rotation·p + translation (metres, the cell's frame).
struct part_pose {
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();

    bool is_identity() const { return rotation == Eigen::Matrix3d::Identity() && translation.isZero(0); }

    /// Row-major 4×4 homogeneous matrix, as recorded in the outputs.
    std::array<double, 16> matrix() const {
        std::array<double, 16> m{};
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) m[static_cast<std::size_t>(4 * r + c)] = rotation(r, c);
            m[static_cast<std::size_t>(4 * r + 3)] = translation[r];
        }
        m[15] = 1;
        return m;
    }
};

/// The pose of a row-major 4×4 (or 3×4, the last row implied) matrix; invalid_argument naming
/// `field` when the rotation is not one (orthonormal within 1e-9, determinant +1), the last row
/// is not 0 0 0 1 or a number is not finite.
inline part_pose part_pose_from_matrix(const std::vector<double>& m, const std::string& field = "part_pose") {
    if (m.size() != 12 && m.size() != 16)
        throw invalid_argument(field, field + ": a matrix is 12 (3×4) or 16 (4×4) numbers, row by row, got " +
                                          std::to_string(m.size()));
    for (double v : m)
        if (!std::isfinite(v)) throw invalid_argument(field, field + ": every number must be finite");
    if (m.size() == 16 && !(m[12] == 0 && m[13] == 0 && m[14] == 0 && m[15] == 1))
        throw invalid_argument(field, field + ": the last row of a rigid 4×4 is 0 0 0 1");
    part_pose p;
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) p.rotation(r, c) = m[static_cast<std::size_t>(4 * r + c)];
        p.translation[r] = m[static_cast<std::size_t>(4 * r + 3)];
    }
    const double off = (p.rotation.transpose() * p.rotation - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    if (!(off <= 1e-9))
        throw invalid_argument(field, field + ": the 3×3 part is not a rotation (RᵀR differs from I by " +
                                          std::to_string(off) + "; give at least 10 significant digits)");
    if (!(p.rotation.determinant() > 0))
        throw invalid_argument(field, field + ": the 3×3 part is a reflection (determinant −1), which would turn the part "
                                              "inside out; give a rotation");
    return p;
}

/// The pose of a translation (metres) and URDF's fixed-axis roll, pitch, yaw (radians):
/// R = Rz(yaw)·Ry(pitch)·Rx(roll), as in the URDF export (docs/conventions.md#urdf).
inline part_pose part_pose_from_xyz_rpy(const std::array<double, 3>& xyz, const std::array<double, 3>& rpy,
                                        const std::string& field = "part_pose") {
    for (double v : xyz)
        if (!std::isfinite(v)) throw invalid_argument(field, field + ": every number must be finite");
    for (double v : rpy)
        if (!std::isfinite(v)) throw invalid_argument(field, field + ": every number must be finite");
    part_pose p;
    p.rotation = (Eigen::AngleAxisd(rpy[2], Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(rpy[1], Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(rpy[0], Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
    p.translation = Eigen::Vector3d(xyz[0], xyz[1], xyz[2]);
    return p;
}

/// `mesh` moved by `pose`: the same faces, each vertex v at rotation·v + translation.
inline triangle_mesh posed(const triangle_mesh& mesh, const part_pose& pose) {
    std::vector<Eigen::Vector3d> vertices;
    vertices.reserve(mesh.num_vertices());
    for (const auto& v : mesh.vertices()) vertices.push_back(pose.rotation * v + pose.translation);
    return triangle_mesh(std::move(vertices), mesh.faces());
}

}  // namespace certipose
