// Tests for pose/quaternion.hpp: quaternion_from_zxz gives the quaternion of zxz_rotation (the
// rotation matrices agree), zxz_from_matrix / zxz_from_quaternion invert zxz_rotation /
// quaternion_from_zxz on random angles away from the gimbal lock to well below the 1e-9 rad the
// POSES.json reader relies on (io/plan_files.hpp), q and −q give the same angles, and at the
// gimbal lock the returned angles still give the same rotation.
#include <certipose/pose/quaternion.hpp>

#include <doctest/doctest.h>

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <numbers>
#include <random>

namespace {

constexpr double pi = std::numbers::pi;

/// The same angle up to a multiple of 2π.
double angle_gap(double a, double b) { return std::abs(std::remainder(a - b, 2 * pi)); }

double matrix_gap(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) { return (a - b).cwiseAbs().maxCoeff(); }

}  // namespace

TEST_CASE("quaternion_from_zxz is the quaternion of zxz_rotation (Hamilton, camera to world, {qx, qy, qz, qw})") {
    std::mt19937_64 e(7);
    std::uniform_real_distribution<double> any(-pi, pi), tilt(0.0, pi);
    for (int n = 0; n < 2000; ++n) {
        const double phi = any(e), gamma = tilt(e), beta = any(e);
        const auto q = certipose::quaternion_from_zxz(phi, gamma, beta);
        CHECK(std::abs(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3] - 1) < 1e-15);
        const Eigen::Matrix3d r = certipose::zxz_rotation(phi, gamma, beta);
        CHECK(matrix_gap(certipose::matrix_from_quaternion(q), r) < 1e-15);
        // Eigen's quaternion (coefficients x, y, z, w) agrees up to sign.
        const Eigen::Quaterniond eq(r);
        const double sign = eq.w() * q[3] + eq.x() * q[0] + eq.y() * q[1] + eq.z() * q[2] < 0 ? -1.0 : 1.0;
        CHECK(std::abs(sign * eq.x() - q[0]) < 1e-14);
        CHECK(std::abs(sign * eq.w() - q[3]) < 1e-14);
    }
    // The named rotations: identity, and γ = π/2 about x (optical axis along world −y).
    const auto id = certipose::quaternion_from_zxz(0, 0, 0);
    CHECK(id == std::array<double, 4>{0, 0, 0, 1});
    const auto tilted = certipose::quaternion_from_zxz(certipose::zxz_angles{0, pi / 2, 0});
    CHECK(std::abs(tilted[0] - std::sqrt(0.5)) < 1e-15);
    CHECK(std::abs(tilted[3] - std::sqrt(0.5)) < 1e-15);
}

TEST_CASE("zxz_from_matrix and zxz_from_quaternion invert the ZXZ rotation on random angles") {
    std::mt19937_64 e(11);
    std::uniform_real_distribution<double> any(-pi, pi), tilt(1e-5, pi - 1e-5);
    double worst = 0;
    for (int n = 0; n < 20000; ++n) {
        const double phi = any(e), gamma = tilt(e), beta = any(e);
        const certipose::zxz_angles m = certipose::zxz_from_matrix(certipose::zxz_rotation(phi, gamma, beta));
        const auto q = certipose::quaternion_from_zxz(phi, gamma, beta);
        const certipose::zxz_angles a = certipose::zxz_from_quaternion(q);
        const certipose::zxz_angles b = certipose::zxz_from_quaternion({-q[0], -q[1], -q[2], -q[3]});  // same rotation
        for (const auto& x : {m, a, b}) {
            CHECK(x.gamma >= 0.0);
            CHECK(x.gamma <= pi);
            CHECK(std::abs(x.phi) <= pi);
            CHECK(std::abs(x.beta) <= pi);
            // Within the bound the reader's ±1e-8 box is built on (error ~ ulp / sin γ).
            const double gap = std::max({angle_gap(x.phi, phi), std::abs(x.gamma - gamma), angle_gap(x.beta, beta)});
            worst = std::max(worst, gap * std::sin(gamma));
            CHECK(gap < 1e-9);
        }
    }
    MESSAGE("largest angle error x sin(gamma): " << worst);
    CHECK(worst < 1e-15);
    // A non-unit quaternion is normalised first.
    const auto q = certipose::quaternion_from_zxz(0.3, 1.1, -2.0);
    const auto a = certipose::zxz_from_quaternion({2 * q[0], 2 * q[1], 2 * q[2], 2 * q[3]});
    CHECK(std::abs(a.phi - 0.3) < 1e-14);
    CHECK(std::abs(a.gamma - 1.1) < 1e-14);
    CHECK(std::abs(a.beta + 2.0) < 1e-14);
}

TEST_CASE("at the gimbal lock zxz_from_matrix returns angles of the same rotation (beta = 0)") {
    for (const double phi : {-2.5, 0.0, 0.4, 3.0}) {
        const double c = std::cos(phi), s = std::sin(phi);
        Eigen::Matrix3d up, down;  // Rz(φ) (γ = 0) and Rz(φ)·Rx(π) (γ = π), exact zeros
        up << c, -s, 0, s, c, 0, 0, 0, 1;
        down << c, s, 0, s, -c, 0, 0, 0, -1;
        for (const Eigen::Matrix3d& r : {up, down}) {
            CHECK(certipose::zxz_sin_gamma(r) == 0.0);
            const certipose::zxz_angles a = certipose::zxz_from_matrix(r);
            CHECK(a.beta == 0.0);
            CHECK(matrix_gap(certipose::zxz_rotation(a.phi, a.gamma, a.beta), r) < 1e-15);
        }
    }
    // Next to it the angles are ill-conditioned but the rotation is still right.
    const Eigen::Matrix3d r = certipose::zxz_rotation(0.4, 1e-12, 0.7);
    const certipose::zxz_angles a = certipose::zxz_from_matrix(r);
    CHECK(matrix_gap(certipose::zxz_rotation(a.phi, a.gamma, a.beta), r) < 1e-12);
}
