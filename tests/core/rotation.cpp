// Tests for pose/rotation.hpp: R(φ, γ, β) = Rz(φ)·Rx(γ)·Rz(β) is a rotation and equals the
// product of the elementary rotations; R·ẑ is the closed-form optical axis; the interval
// rotation, optical axis, world→camera transform and projection enclose their point versions
// at random samples of random boxes; zxz_angles_from_axis inverts the optical axis; a point
// in front projects where the intrinsics say.
#include <certipose/interval/boost_interval.hpp>
#include <certipose/pose/rotation.hpp>

#include <doctest/doctest.h>

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>

// tests/cgal/rotation_cgal.cpp re-includes this file with the CGAL backend; it then runs the
// typed tests only (the others do not depend on the backend).
#ifndef CERTIPOSE_ROTATION_TEST_BACKENDS
#define CERTIPOSE_ROTATION_TEST_BACKENDS certipose::boost_interval
#define CERTIPOSE_ROTATION_TEST_UNTYPED 1
#endif

namespace {

using certipose::optical_axis;
using certipose::zxz_angles_from_axis;
using certipose::zxz_rotation;

constexpr double pi = std::numbers::pi;

struct rng {
    std::mt19937_64 e;
    explicit rng(std::uint64_t seed) : e(seed) {}
    double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(e); }
    int integer(int a, int b) { return std::uniform_int_distribution<int>(a, b)(e); }
};

// K of the case-study camera: f_px = 0.012 / 3.45e-6, centred principal point, no skew.
Eigen::Matrix3d design_k() {
    const double f = 0.012 / 3.45e-6;
    Eigen::Matrix3d k;
    k << f, 0.0, 1224.0, 0.0, f, 1024.0, 0.0, 0.0, 1.0;
    return k;
}

// An angle interval: a point, a sliver, or up to 0.8 rad wide; around 0, kπ/2 or far out.
std::pair<double, double> angle_box(rng& r) {
    double c = r.uniform(-2 * pi, 2 * pi);
    switch (r.integer(0, 5)) {
        case 0: c = r.integer(-4, 4) * (pi / 2); break;
        case 1: c = r.uniform(-1e3, 1e3); break;
        default: break;
    }
    switch (r.integer(0, 3)) {
        case 0: return {c, c};
        case 1: return {c - 1e-9, c + 1e-9};
        default: { const double w = r.uniform(0.0, 0.4); return {c - w, c + w}; }
    }
}

double sample(rng& r, std::pair<double, double> b) {
    switch (r.integer(0, 3)) {
        case 0: return b.first;
        case 1: return b.second;
        default: return std::clamp(b.first + r.uniform(0.0, 1.0) * (b.second - b.first), b.first, b.second);
    }
}

}  // namespace

#ifdef CERTIPOSE_ROTATION_TEST_UNTYPED

TEST_CASE("zxz_rotation is a rotation equal to Rz(φ)·Rx(γ)·Rz(β), with R·ẑ the closed-form axis") {
    rng r(1);
    double worst_orth = 0, worst_det = 0, worst_product = 0;
    int axis_mismatches = 0;
    for (int i = 0; i < 10000; ++i) {
        const double phi = r.uniform(-2 * pi, 2 * pi), gamma = r.uniform(-2 * pi, 2 * pi), beta = r.uniform(-2 * pi, 2 * pi);
        const Eigen::Matrix3d R = zxz_rotation(phi, gamma, beta);
        worst_orth = std::max(worst_orth, (R * R.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff());
        worst_det = std::max(worst_det, std::abs(R.determinant() - 1.0));
        const Eigen::Matrix3d elementary = (Eigen::AngleAxisd(phi, Eigen::Vector3d::UnitZ()) *
                                            Eigen::AngleAxisd(gamma, Eigen::Vector3d::UnitX()) *
                                            Eigen::AngleAxisd(beta, Eigen::Vector3d::UnitZ()))
                                               .toRotationMatrix();
        worst_product = std::max(worst_product, (R - elementary).cwiseAbs().maxCoeff());
        const Eigen::Vector3d closed(std::sin(phi) * std::sin(gamma), -std::cos(phi) * std::sin(gamma), std::cos(gamma));
        // docs/conventions.md: R·ẑ = (sin φ sin γ, −cos φ sin γ, cos γ), exactly as optical_axis computes it.
        if (!(optical_axis(phi, gamma) == closed) || (R * Eigen::Vector3d::UnitZ() - closed).cwiseAbs().maxCoeff() > 1e-15)
            ++axis_mismatches;
    }
    CHECK(worst_orth < 1e-14);
    CHECK(worst_det < 1e-14);
    CHECK(worst_product < 1e-14);
    CHECK(axis_mismatches == 0);

    // Known orientations: identity; φ turns about z; γ = π/2 tips the axis to −y; γ = π looks down.
    CHECK(zxz_rotation(0.0, 0.0, 0.0) == Eigen::Matrix3d::Identity());
    CHECK((zxz_rotation(pi / 2, 0.0, 0.0) * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm() < 1e-15);
    CHECK((optical_axis(0.0, pi / 2) - Eigen::Vector3d(0, -1, 0)).norm() < 1e-15);
    CHECK((optical_axis(pi / 2, pi / 2) - Eigen::Vector3d(1, 0, 0)).norm() < 1e-15);
    CHECK((optical_axis(0.3, pi) - Eigen::Vector3d(0, 0, -1)).norm() < 1e-15);
    // β spins the image about the optical axis and leaves the axis alone.
    CHECK((zxz_rotation(0.4, 1.1, 0.0).col(2) - zxz_rotation(0.4, 1.1, 2.0).col(2)).norm() < 1e-15);
    CHECK((zxz_rotation(0.4, 1.1, 0.0).col(0) - zxz_rotation(0.4, 1.1, 2.0).col(0)).norm() > 0.5);
}

TEST_CASE("zxz_angles_from_axis inverts the optical axis (β = 0) and rejects degenerate directions") {
    rng r(2);
    double worst_axis = 0, worst_angles = 0;
    bool ranges_ok = true;
    for (int i = 0; i < 10000; ++i) {
        // Any direction, any length (the result only depends on the direction).
        Eigen::Vector3d d(r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1));
        if (i % 10 == 0) d.x() = d.y() = 0.0;    // along ±z
        if (i % 10 == 1) d.z() = 0.0;            // horizontal
        if (i % 10 == 2) d.y() = 0.0;
        if (d.squaredNorm() == 0.0) continue;
        d *= std::pow(10.0, r.uniform(-6, 6));
        const auto a = zxz_angles_from_axis(d);
        ranges_ok = ranges_ok && a.beta == 0.0 && a.gamma >= 0.0 && a.gamma <= pi && a.phi >= -pi && a.phi <= pi;
        worst_axis = std::max(worst_axis, (optical_axis(a.phi, a.gamma) - d.normalized()).cwiseAbs().maxCoeff());

        // And from angles back to angles, away from the poles where φ is ill-conditioned.
        const double phi = r.uniform(-pi, pi), gamma = r.uniform(0.01, pi - 0.01);
        const auto b = zxz_angles_from_axis(optical_axis(phi, gamma));
        worst_angles = std::max({worst_angles, std::abs(b.phi - phi), std::abs(b.gamma - gamma)});
    }
    CHECK(ranges_ok);
    CHECK(worst_axis < 1e-15 * 4);
    CHECK(worst_angles < 1e-12);

    const auto up = zxz_angles_from_axis(Eigen::Vector3d(0, 0, 2));
    CHECK(up.gamma == 0.0);
    CHECK(up.phi == 0.0);
    const auto down = zxz_angles_from_axis(Eigen::Vector3d(0, 0, -1e-3));
    CHECK(down.gamma == pi);
    const auto minus_y = zxz_angles_from_axis(Eigen::Vector3d(0, -5, 0));
    CHECK(minus_y.phi == 0.0);
    CHECK(minus_y.gamma == pi / 2);

    for (const Eigen::Vector3d& bad : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(std::nan(""), 0, 1),
                                       Eigen::Vector3d(0, std::numeric_limits<double>::infinity(), 1)}) {
        try {
            (void)zxz_angles_from_axis(bad);
            FAIL("no exception");
        } catch (const certipose::invalid_argument& e) {
            CHECK(e.field() == "direction");
        }
    }
}

TEST_CASE("a point in front of the camera projects where the intrinsics say") {
    const Eigen::Matrix3d K = design_k();
    const double f = K(0, 0);
    // Camera 1 m above the origin looking straight down: γ = π, φ = 0 (axis (0, 0, −1)).
    const Eigen::Vector3d p(0.0, 0.0, 1.0);
    const auto aim = zxz_angles_from_axis(Eigen::Vector3d(0, 0, -1));
    const Eigen::Matrix3d R = zxz_rotation(aim.phi, aim.gamma, 0.0);
    const Eigen::Vector3d x_axis = R.col(0), y_axis = R.col(1);

    const Eigen::Vector3d centre = certipose::world_to_camera(R, p, Eigen::Vector3d(0, 0, 0.5));
    CHECK(certipose::in_front(centre));
    CHECK(centre.z() == doctest::Approx(0.5).epsilon(1e-15));
    const Eigen::Vector2d c = certipose::project(K, centre);
    CHECK(c.x() == doctest::Approx(1224.0).epsilon(1e-12));
    CHECK(c.y() == doctest::Approx(1024.0).epsilon(1e-12));

    // 1 cm along the image x axis at 0.5 m depth: u grows by f · 0.01 / 0.5; along image y,
    // v grows (y points down the image).
    const Eigen::Vector2d right = certipose::project(K, certipose::world_to_camera(R, p, Eigen::Vector3d(0, 0, 0.5) + 0.01 * x_axis));
    const Eigen::Vector2d below = certipose::project(K, certipose::world_to_camera(R, p, Eigen::Vector3d(0, 0, 0.5) + 0.01 * y_axis));
    CHECK(right.x() == doctest::Approx(1224.0 + f * 0.02).epsilon(1e-12));
    CHECK(right.y() == doctest::Approx(1024.0).epsilon(1e-12));
    CHECK(below.y() == doctest::Approx(1024.0 + f * 0.02).epsilon(1e-12));
    CHECK(below.x() == doctest::Approx(1224.0).epsilon(1e-12));

    // Behind the camera.
    CHECK_FALSE(certipose::in_front(certipose::world_to_camera(R, p, Eigen::Vector3d(0, 0, 1.5))));

    // K must have the pinhole form of docs/conventions.md.
    Eigen::Matrix3d bad = K;
    bad(2, 2) = 2.0;
    try {
        (void)certipose::project(bad, centre);
        FAIL("no exception");
    } catch (const certipose::invalid_argument& e) {
        CHECK(e.field() == "K");
    }
}

#endif  // CERTIPOSE_ROTATION_TEST_UNTYPED

TEST_CASE_TEMPLATE("the interval rotation, axis, transform and projection enclose every sampled pose", I,
                   CERTIPOSE_ROTATION_TEST_BACKENDS) {
    using certipose::contains;
    using certipose::matrix3;
    using certipose::vector2;
    using certipose::vector3;
    const Eigen::Matrix3d K = design_k();
    rng r(3);
    int failures = 0, projected = 0;
    std::string first;
    for (int t = 0; t < 2000; ++t) {
        const std::array<std::pair<double, double>, 3> e{angle_box(r), angle_box(r), angle_box(r)};
        // A position box within 1 m of the origin, and a world point ~1 m in front along the
        // box's nominal optical axis (so that projections are often defined).
        std::array<std::pair<double, double>, 3> pb;
        for (auto& b : pb) {
            const double c = r.uniform(-1, 1), w = r.integer(0, 2) == 0 ? 0.0 : r.uniform(0.0, 0.02);
            b = {c - w, c + w};
        }
        const double mid_phi = 0.5 * (e[0].first + e[0].second), mid_gamma = 0.5 * (e[1].first + e[1].second);
        const Eigen::Vector3d q = Eigen::Vector3d(0.5 * (pb[0].first + pb[0].second), 0.5 * (pb[1].first + pb[1].second),
                                                  0.5 * (pb[2].first + pb[2].second)) +
                                  optical_axis(mid_phi, mid_gamma) * r.uniform(0.5, 1.5);

        matrix3<I> R;
        vector3<I> axis, qc;
        vector2<I> px;
        bool front = false;
        const certipose::orientation_box<I> ebox = certipose::orientation_box<I>::from_bounds(e);
        const certipose::position_box<I> pbox = certipose::position_box<I>::from_bounds(pb);
        {
            const certipose::rounding_guard<I> guard;
            R = zxz_rotation(ebox);
            axis = optical_axis(ebox[0], ebox[1]);
            const vector3<I> p(pbox[0], pbox[1], pbox[2]);
            qc = certipose::world_to_camera(R, p, q);
            front = certipose::in_front(qc);
            if (front) px = certipose::project(K, qc);
        }
        projected += front ? 1 : 0;
        for (int k = 0; k < 20; ++k) {
            const double phi = sample(r, e[0]), gamma = sample(r, e[1]), beta = sample(r, e[2]);
            const Eigen::Vector3d p(sample(r, pb[0]), sample(r, pb[1]), sample(r, pb[2]));
            const Eigen::Matrix3d Rd = zxz_rotation(phi, gamma, beta);
            const Eigen::Vector3d ad = optical_axis(phi, gamma), qcd = certipose::world_to_camera(Rd, p, q);
            bool ok = true;
            for (int i = 0; i < 3; ++i) {
                ok = ok && contains(axis(i), ad(i)) && contains(qc(i), qcd(i));
                for (int j = 0; j < 3; ++j) ok = ok && contains(R(i, j), Rd(i, j));
            }
            if (front) {
                ok = ok && certipose::in_front(qcd);
                const Eigen::Vector2d pxd = certipose::project(K, qcd);
                ok = ok && contains(px(0), pxd(0)) && contains(px(1), pxd(1));
            }
            if (!ok && failures++ == 0)
                first = "box " + std::to_string(t) + " sample " + std::to_string(k) + ": phi=" + std::to_string(phi) +
                        " gamma=" + std::to_string(gamma) + " beta=" + std::to_string(beta);
        }
    }
    CHECK_MESSAGE(failures == 0, first);
    CHECK(projected > 100);  // the projection was exercised

    // A thin box encloses a rotation, which stays (nearly) orthonormal: every entry within [−1, 1].
    matrix3<I> thin;
    {
        const certipose::rounding_guard<I> guard;
        thin = zxz_rotation(I(0.3, 0.3 + 1e-9), I(1.0), I(-2.0, -2.0 + 1e-9));
    }
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            CHECK(certipose::subset(thin(i, j), I(-1.0, 1.0)));
            CHECK(certipose::width(thin(i, j)) < 1e-8);
        }
}
