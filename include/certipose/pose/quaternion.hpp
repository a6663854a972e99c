// certipose/pose/quaternion.hpp — conversions between the ZXZ angles of pose/rotation.hpp
// (R = Rz(φ)·Rx(γ)·Rz(β) maps camera-frame vectors to world vectors) and the other usual
// orientation encodings: a unit quaternion (qx, qy, qz, qw) (Hamilton convention, rotating
// camera-frame vectors to world vectors, the convention of Eigen::Quaterniond and ROS) and a
// 3×3 rotation matrix (camera to world, R·ẑ = optical axis). Plain double, rounded to nearest:
// these are *not* certified enclosures. A caller that turns a converted pose into a claim (the
// readers of io/plan_files.hpp) widens the angles into a small box; see docs/io.md.
//
// ZXZ angles are undefined at the gimbal lock sin γ = 0 (optical axis along world ±Z), where
// only φ + β (γ = 0) or φ − β (γ = π) is determined, and ill-conditioned near it: an error ε in
// R costs about ε / sin γ in φ and β. `zxz_from_matrix` / `zxz_from_quaternion` return angles
// there anyway (β = 0, φ carrying the whole rotation about z); callers that need accuracy test
// `zxz_sin_gamma` first.
#pragma once

#include <array>
#include <cmath>

#include <Eigen/Core>

#include "certipose/pose/rotation.hpp"

namespace certipose {

/// The unit quaternion {qx, qy, qz, qw} of R(φ, γ, β) = Rz(φ)·Rx(γ)·Rz(β):
/// qx = sin(γ/2) cos((φ−β)/2), qy = sin(γ/2) sin((φ−β)/2),
/// qz = cos(γ/2) sin((φ+β)/2), qw = cos(γ/2) cos((φ+β)/2).
inline std::array<double, 4> quaternion_from_zxz(double phi, double gamma, double beta) {
    const double sg = std::sin(gamma / 2), cg = std::cos(gamma / 2);
    const double d = (phi - beta) / 2, s = (phi + beta) / 2;
    return {sg * std::cos(d), sg * std::sin(d), cg * std::sin(s), cg * std::cos(s)};
}
inline std::array<double, 4> quaternion_from_zxz(const zxz_angles& a) {
    return quaternion_from_zxz(a.phi, a.gamma, a.beta);
}

/// The rotation matrix of a quaternion {qx, qy, qz, qw}, normalised first (any non-zero
/// finite quaternion; q and −q give the same matrix).
inline Eigen::Matrix3d matrix_from_quaternion(const std::array<double, 4>& q) {
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    const double x = q[0] / n, y = q[1] / n, z = q[2] / n, w = q[3] / n;
    Eigen::Matrix3d r;
    r << 1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w),
         2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
         2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y);
    return r;
}

/// sin γ of a rotation matrix, √(R₁₃² + R₂₃²) (the horizontal part of the optical axis).
inline double zxz_sin_gamma(const Eigen::Matrix3d& r) { return std::hypot(r(0, 2), r(1, 2)); }

/// The ZXZ angles of a rotation matrix (camera to world), the inverse of zxz_rotation:
/// γ = atan2(√(R₁₃² + R₂₃²), R₃₃) ∈ [0, π], φ = atan2(R₁₃, −R₂₃), β = atan2(R₃₁, R₃₂), both in
/// (−π, π]. Only the third column and third row are read, so for a matrix that is orthonormal
/// only approximately, the optical axis of the result is the direction of the third column.
/// At the exact gimbal lock (R₁₃ = R₂₃ = 0) returns β = 0 and φ = atan2(R₂₁, R₁₁), the whole
/// rotation about z; see the header comment.
inline zxz_angles zxz_from_matrix(const Eigen::Matrix3d& r) {
    zxz_angles a;
    const double sg = zxz_sin_gamma(r);
    a.gamma = std::atan2(sg, r(2, 2));
    if (sg == 0.0) {
        // R = Rz(φ)·Rx(γ) with γ ∈ {0, π}: R₁₁ = cos φ, R₂₁ = sin φ in both cases.
        a.phi = std::atan2(r(1, 0), r(0, 0));
        a.beta = 0.0;
        return a;
    }
    a.phi = std::atan2(r(0, 2), -r(1, 2));
    a.beta = std::atan2(r(2, 0), r(2, 1));
    return a;
}

/// The ZXZ angles of a quaternion {qx, qy, qz, qw} (normalised first), via its matrix.
inline zxz_angles zxz_from_quaternion(const std::array<double, 4>& q) {
    return zxz_from_matrix(matrix_from_quaternion(q));
}

}  // namespace certipose
