// pose/axis_tolerance.hpp: the fitter's cone and roll, and the rotation angle, that an orientation
// box certifies really lie inside it — checked by sampling rotations of the claimed sets, turning
// them into ZXZ angles with pose/quaternion.hpp (plain double) and testing membership, box edges
// included; and the enclosure really encloses.
#include <doctest/doctest.h>

#include <certipose/pose/axis_tolerance.hpp>
#include <certipose/pose/quaternion.hpp>
#include <certipose/pose/rotation.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>
#include <random>

namespace {

using namespace certipose;

/// a − b reduced to (−π, π]: ZXZ angles are read back modulo 2π.
double angle_diff(double a, double b) { return std::remainder(a - b, 2 * std::numbers::pi); }

/// Whether angles `e` (read back from a matrix) lie in `box` up to `slack`, modulo 2π for φ, β.
bool inside(const zxz_bounds& box, const zxz_angles& e, double slack) {
    const auto c = zxz_centre(box);
    const double v[3] = {e.phi, e.gamma, e.beta};
    for (int i = 0; i < 3; ++i) {
        const double d = i == 1 ? v[i] - c[i] : angle_diff(v[i], c[i]);
        if (d < box[i][0] - c[i] - slack || d > box[i][1] - c[i] + slack) return false;
    }
    return true;
}

Eigen::Matrix3d about(const Eigen::Vector3d& axis, double angle) {
    return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

}  // namespace

TEST_CASE("axis_tolerance: every orientation within the certified cone and roll lies in the box") {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    std::size_t checked = 0, nonzero = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const double g0 = 0.2 + 2.7 * u(rng);
        const zxz_bounds box{{{-3 + 6 * u(rng), 0}, {g0 - 0.3 * u(rng), g0 + 0.3 * u(rng)}, {-3 + 6 * u(rng), 0}}};
        zxz_bounds b = box;
        b[0][1] = b[0][0] + 0.4 * u(rng) + 1e-3;
        b[2][1] = b[2][0] + 0.4 * u(rng) + 1e-3;
        const axis_tolerance t = certified_axis_tolerance(b);
        REQUIRE(t.cone >= 0);
        REQUIRE(t.roll >= 0);
        if (t.cone > 0 && t.roll > 0) ++nonzero;
        const auto c = zxz_centre(b);
        const Eigen::Matrix3d r0 = zxz_rotation(c[0], c[1], c[2]);
        for (int k = 0; k < 50; ++k) {
            // The extremes (k < 8) and random points of the set R₀·S·T.
            const double dir = 2 * std::numbers::pi * u(rng);
            const double swing = k < 8 ? t.cone : t.cone * std::sqrt(u(rng));
            const double twist = k < 8 ? (k % 2 ? t.roll : -t.roll) : t.roll * (2 * u(rng) - 1);
            const Eigen::Matrix3d s = about(Eigen::Vector3d(std::cos(dir), std::sin(dir), 0), swing);
            const Eigen::Matrix3d r = r0 * s * about(Eigen::Vector3d::UnitZ(), twist);
            const Eigen::Matrix3d r2 = r0 * about(Eigen::Vector3d::UnitZ(), twist) * s;  // the other order
            // The margin of the header is 1e-9; the conversion back costs ~1e-15 / sin γ.
            CHECK_MESSAGE(inside(b, zxz_from_matrix(r), 1e-12), "trial ", trial, " k ", k);
            CHECK_MESSAGE(inside(b, zxz_from_matrix(r2), 1e-12), "trial ", trial, " k ", k);
            ++checked;
        }
    }
    CHECK(checked == 400 * 50);
    CHECK(nonzero > 300);  // the tolerance is not vacuous on ordinary boxes
}

TEST_CASE("axis_tolerance: a box at the gimbal lock or thinner than the margin certifies nothing") {
    CHECK(certified_axis_tolerance({{{0, 0.1}, {-0.05, 0.05}, {0, 0.1}}}).cone == 0);  // centre γ = 0
    CHECK(certified_axis_tolerance({{{0, 1e-10}, {1, 1.1}, {0, 0.1}}}).cone == 0);
    CHECK(certified_rotation_angle({{{0, 0.1}, {-0.05, 0.05}, {0, 0.1}}}) == 0);
}

TEST_CASE("axis_tolerance: rotations by at most the certified angle, on either side, lie in the box") {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0, 1);
    std::normal_distribution<double> n(0, 1);
    for (int trial = 0; trial < 200; ++trial) {
        const double g0 = 0.3 + 2.5 * u(rng);
        const zxz_bounds b{{{0.1, 0.1 + 0.05 + 0.3 * u(rng)}, {g0 - 0.1, g0 + 0.05 + 0.2 * u(rng)}, {-1, -1 + 0.05 + 0.3 * u(rng)}}};
        const double theta = certified_rotation_angle(b);
        REQUIRE(theta > 0);
        const auto c = zxz_centre(b);
        const Eigen::Matrix3d r0 = zxz_rotation(c[0], c[1], c[2]);
        // The enclosure of the angle's set lies in the box.
        const auto e = zxz_enclosure(c, {theta, theta});
        for (int i = 0; i < 3; ++i) CHECK((e[i][0] >= b[i][0] && e[i][1] <= b[i][1]));
        for (int k = 0; k < 50; ++k) {
            const Eigen::Vector3d axis(n(rng), n(rng), n(rng));
            const double angle = k < 10 ? theta : theta * u(rng);
            CHECK(inside(b, zxz_from_matrix(r0 * about(axis, angle)), 1e-12));
            CHECK(inside(b, zxz_from_matrix(about(axis, angle) * r0), 1e-12));
            // The enclosure encloses (its own statement, checked the same way).
            CHECK(inside(e, zxz_from_matrix(r0 * about(axis, angle)), 1e-12));
        }
    }
}
