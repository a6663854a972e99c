// Tests for lens distortion (camera/distortion.hpp, camera/distorted_camera.hpp): the interval
// enclosure contains sampled plain values, the certified image rectangle holds what it claims on
// 10^5 sampled points for barrel and pincushion distortion, zero coefficients give the pinhole
// image, the pinhole-equivalent image lies inside the rectangle, and bad input names its field.
#include <certipose/camera.hpp>
#include <certipose/interval/boost_interval.hpp>
#include <certipose/orientation/certify.hpp>
#include <certipose/verify/point_check.hpp>

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace {

using certipose::boost_interval;
using certipose::brown_conrady;
using certipose::calibrated_camera;
using certipose::distorted_camera;
using certipose::thin_lens_camera;

certipose::thin_lens_parameters case_study() {
    return {.focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6, .max_blur_circle = 6.9e-6,
            .pixel_pitch = 3.45e-6, .width_px = 2448, .height_px = 2048};
}

brown_conrady coefficients(std::vector<double> c) { return brown_conrady::from_opencv(c); }

/// Samples the rectangle (its edges and corners included): every distorted pixel must lie in
/// the image minus the margin.
std::size_t outside_samples(const certipose::normalized_rectangle& r, const Eigen::Matrix3d& K, double w, double h,
                            const brown_conrady& d, double margin, std::size_t n) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> ux(r.x_lo, r.x_hi), uy(r.y_lo, r.y_hi);
    std::size_t bad = 0;
    for (std::size_t i = 0; i < n; ++i) {
        double x = ux(rng), y = uy(rng);
        if (i % 4 == 0) x = (i / 4) % 2 ? r.x_lo : r.x_hi;
        if (i % 8 == 1) y = (i / 8) % 2 ? r.y_lo : r.y_hi;
        const auto [xd, yd] = d.distort(x, y);
        const double u = K(0, 0) * xd + K(0, 1) * yd + K(0, 2), v = K(1, 1) * yd + K(1, 2);
        if (!(u >= margin && u <= w - margin && v >= margin && v <= h - margin)) ++bad;
    }
    return bad;
}

}  // namespace

TEST_CASE("distortion: from_opencv takes 4, 5 or 8 finite coefficients") {
    const brown_conrady d = coefficients({0.1, -0.2, 0.001, 0.002, 0.05});
    CHECK(d.k1 == 0.1);
    CHECK(d.k3 == 0.05);
    CHECK(d.count() == 5);
    CHECK(!d.is_zero());
    CHECK(coefficients({0, 0, 0, 0}).is_zero());
    CHECK(coefficients({0, 0, 0, 0, 0, 1, 0, 0}).count() == 8);
    for (std::vector<double> bad : {std::vector<double>{1, 2, 3}, std::vector<double>(6, 0.0), std::vector<double>{}}) {
        try {
            (void)coefficients(bad);
            FAIL("accepted " << bad.size() << " coefficients");
        } catch (const certipose::invalid_argument& e) {
            CHECK(e.field() == "distortion_coefficients");
            CHECK(std::string(e.what()).find("got " + std::to_string(bad.size())) != std::string::npos);
        }
    }
    try {
        (void)coefficients({0.1, std::numeric_limits<double>::quiet_NaN(), 0, 0});
        FAIL("accepted NaN");
    } catch (const certipose::invalid_argument& e) {
        CHECK(e.field() == "distortion_coefficients");
        CHECK(std::string(e.what()).find("distortion_coefficients[1]") != std::string::npos);
        CHECK(std::string(e.what()).find("nan") != std::string::npos);
    }
}

TEST_CASE("distortion: the plain formula is OpenCV's") {
    // Hand-computed: x = 0.2, y = -0.1, r² = 0.05.
    const brown_conrady d = coefficients({0.3, 0.1, 0.01, -0.02, 0.05});
    const double r2 = 0.05, radial = 1 + 0.3 * r2 + 0.1 * r2 * r2 + 0.05 * r2 * r2 * r2;
    const auto [xd, yd] = d.distort(0.2, -0.1);
    CHECK(xd == doctest::Approx(0.2 * radial + 2 * 0.01 * 0.2 * -0.1 + -0.02 * (r2 + 2 * 0.04)).epsilon(1e-14));
    CHECK(yd == doctest::Approx(-0.1 * radial + 0.01 * (r2 + 2 * 0.01) + 2 * -0.02 * 0.2 * -0.1).epsilon(1e-14));
}

TEST_CASE("distortion: the interval enclosure contains sampled plain values") {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    const std::array<brown_conrady, 4> models{coefficients({0.3, 0.1, 0.001, -0.002}),
                                              coefficients({-0.5, 0.2, 0, 0, 0.01}),
                                              coefficients({0.2, -0.1, 0.003, 0.001, 0.02, 0.1, 0.02, 0.01}),
                                              coefficients({-1.0, 0.5, 0, 0, -0.1})};
    const certipose::rounding_guard<boost_interval> guard{};
    for (const brown_conrady& d : models)
        for (int i = 0; i < 2000; ++i) {
            const double x0 = u(rng), y0 = u(rng), wx = 0.2 * std::abs(u(rng)), wy = 0.2 * std::abs(u(rng));
            const boost_interval x(x0, x0 + wx), y(y0, y0 + wy);
            const auto e = d.distort(x, y);
            for (int k = 0; k < 8; ++k) {
                const double px = x0 + wx * std::abs(u(rng)), py = y0 + wy * std::abs(u(rng));
                std::array<double, 2> p{};
                {
                    const certipose::detail::round_to_nearest_scope nearest;
                    p = d.distort(px, py);
                }
                CHECK(certipose::contains(e[0], p[0]));
                CHECK(certipose::contains(e[1], p[1]));
            }
        }
    // A rational denominator that may vanish gives the whole plane.
    const brown_conrady pole = coefficients({0, 0, 0, 0, 0, -1, 0, 0});
    const auto e = pole.distort(boost_interval(0.9, 1.1), boost_interval(0.0, 0.1));
    CHECK(certipose::lower(e[0]) == -std::numeric_limits<double>::infinity());
}

TEST_CASE("distortion: the certified rectangle holds on 10^5 samples, barrel and pincushion") {
    const thin_lens_camera base(case_study());
    const Eigen::Matrix3d K = base.intrinsics();
    struct example {
        std::vector<double> c;
        double margin;
    };
    for (const example& ex : {example{{0.3, 0.1, 0, 0}, 0.0}, example{{-0.3, 0, 0, 0}, 0.0},
                              example{{-0.5, 0.2, 0, 0}, 5.0}, example{{0.3, 0.1, 0.002, -0.001, 0.05}, 2.0},
                              example{{-0.3, 0.05, 0, 0, 0, 0.1, 0.01, 0}, 0.0}, example{{1.0, 0, 0, 0}, 0.0},
                              example{{-1.0, 0, 0, 0}, 0.0}}) {
        CAPTURE(ex.c[0]);
        CAPTURE(ex.c[1]);
        const brown_conrady d = coefficients(ex.c);
        const auto r = certipose::certified_image_rectangle(K, base.width_px(), base.height_px(), d, ex.margin);
        CHECK(r.x_lo < 0);
        CHECK(r.x_hi > 0);
        CHECK(r.y_lo < 0);
        CHECK(r.y_hi > 0);
        CHECK(outside_samples(r, K, base.width_px(), base.height_px(), d, ex.margin, 100000) == 0);
        // Not much smaller than the sensor: the search uses the image.
        const double pinhole_half_width = base.width_px() / 2 / K(0, 0);
        CHECK(r.x_hi > 0.4 * pinhole_half_width);
        // The pinhole-equivalent image lies inside the rectangle.
        const certipose::pinhole_image img = certipose::pinhole_image_of(r);
        CHECK(-img.K(0, 2) == r.x_lo);
        CHECK(img.width_px - img.K(0, 2) <= r.x_hi);
        CHECK(img.height_px - img.K(1, 2) <= r.y_hi);
    }
}

TEST_CASE("distortion: pincushion shrinks and barrel grows the usable image") {
    const thin_lens_camera base(case_study());
    const auto rect = [&](std::vector<double> c) {
        return certipose::certified_image_rectangle(base.intrinsics(), base.width_px(), base.height_px(), coefficients(c));
    };
    const double half = base.width_px() / 2 / base.intrinsics()(0, 0);
    CHECK(rect({0.3, 0.1, 0, 0}).x_hi < half);
    CHECK(rect({-0.3, 0, 0, 0}).x_hi > half);
}

TEST_CASE("distortion: zero coefficients give the pinhole rectangle") {
    const thin_lens_camera base(case_study());
    const Eigen::Matrix3d K = base.intrinsics();
    const auto r = certipose::certified_image_rectangle(K, base.width_px(), base.height_px(), brown_conrady{});
    CHECK(r.x_lo == doctest::Approx(-K(0, 2) / K(0, 0)).epsilon(1e-12));
    CHECK(r.x_hi == doctest::Approx((base.width_px() - K(0, 2)) / K(0, 0)).epsilon(1e-12));
    CHECK(r.y_lo == doctest::Approx(-K(1, 2) / K(1, 1)).epsilon(1e-12));
    CHECK(r.y_hi == doctest::Approx((base.height_px() - K(1, 2)) / K(1, 1)).epsilon(1e-12));
    const auto m = certipose::certified_image_rectangle(K, base.width_px(), base.height_px(), brown_conrady{}, 10.0);
    CHECK(m.x_hi == doctest::Approx((base.width_px() - 10 - K(0, 2)) / K(0, 0)).epsilon(1e-12));
}

TEST_CASE("distortion: a fold limits strong barrel distortion") {
    // r·(1 − 0.5 r²) has its maximum at r² = 2/3: beyond it the model maps rays back inward.
    Eigen::Matrix3d K;
    K << 500, 0, 1000, 0, 500, 1000, 0, 0, 1;  // a very wide image: the fold, not the sensor, limits
    const auto r = certipose::certified_image_rectangle(K, 2000, 2000, coefficients({-0.5, 0, 0, 0}));
    CHECK(r.x_hi * r.x_hi + r.y_hi * r.y_hi < 2.0 / 3.0);
    CHECK(r.x_hi > 0.3);
}

TEST_CASE("distortion: bad input names its field") {
    const thin_lens_camera base(case_study());
    const auto field_of = [&](auto&& f) -> std::string {
        try {
            f();
        } catch (const certipose::invalid_argument& e) {
            return e.field();
        }
        return "(accepted)";
    };
    const Eigen::Matrix3d K = base.intrinsics();
    CHECK(field_of([&] { (void)certipose::certified_image_rectangle(K, 2448, 2048, {}, -1.0); }) == "image_margin_px");
    CHECK(field_of([&] { (void)certipose::certified_image_rectangle(K, 2448, 2048, {}, 1100.0); }) == "image_margin_px");
    CHECK(field_of([&] {
              (void)certipose::certified_image_rectangle(K, 2448, 2048, {}, std::numeric_limits<double>::quiet_NaN());
          }) == "image_margin_px");
    // A denominator that vanishes at the principal point's neighbourhood edge... and a hopeless one:
    // k1 = -50 folds almost at once, k4 = -1e6 puts a pole next to the principal point.
    CHECK(field_of([&] { (void)certipose::certified_image_rectangle(K, 2448, 2048, coefficients({0, 0, 0, 0, 0, -1e9, 0, 0})); }) ==
          "distortion_coefficients");
}

TEST_CASE("distortion: distorted_camera and calibrated_camera carry the certified image") {
    const thin_lens_camera base(case_study());
    const distorted_camera<thin_lens_camera> cam(base, coefficients({0.3, 0.1, 0, 0}), 2.0);
    static_assert(certipose::CameraModel<distorted_camera<thin_lens_camera>>);
    static_assert(certipose::HasImageRegion<distorted_camera<thin_lens_camera>>);
    CHECK(cam.intrinsics() == base.intrinsics());
    CHECK(cam.distance_range().min == base.distance_range().min);
    CHECK(cam.fov_half_angles().horizontal < base.fov_half_angles().horizontal);
    const certipose::pinhole_image img = certipose::certified_image(cam);
    CHECK(img.K(0, 0) == 1.0);
    const calibrated_camera c(cam, "thin_lens");
    REQUIRE(c.distortion().has_value());
    CHECK(c.distortion()->k1 == 0.3);
    CHECK(c.margin_px() == 2.0);
    CHECK(c.image_region().K == img.K);
    CHECK(c.image_region().width_px == img.width_px);
    CHECK(c.fov_half_angles().vertical == cam.fov_half_angles().vertical);
    // Without distortion the certified image is the camera's own.
    const calibrated_camera plain(base, "thin_lens");
    CHECK(!plain.distortion().has_value());
    CHECK(plain.image_region().K == base.intrinsics());
    // The frustum reads the certified image.
    const certipose::fov_frustum<boost_interval> f(cam);
    CHECK(f.outer_half_angle() < certipose::fov_frustum<boost_interval>(base).outer_half_angle());
}

TEST_CASE("distortion: the point check judges through the distortion") {
    const thin_lens_camera base(case_study());
    const Eigen::Matrix3d K = base.intrinsics();
    // A small facet 0.5 m ahead, seen near the right edge of the image: inside the pinhole image,
    // outside once pincushion distortion pushes it outward.
    const double z = 0.5, xn = 0.34;
    certipose::facet f;
    f.v = {Eigen::Vector3d(xn * z, 0, z), Eigen::Vector3d(xn * z - 0.001, 0.001, z), Eigen::Vector3d(xn * z - 0.001, -0.001, z)};
    certipose::verify::pose x;
    x.position = Eigen::Vector3d::Zero();
    certipose::verify::camera_view view{K, base.width_px(), base.height_px(), 0.1, 10.0};
    CHECK(certipose::verify::fov_ok(x, f, view));
    view.distortion = coefficients({0.3, 0.1, 0, 0}).opencv();
    CHECK(!certipose::verify::fov_ok(x, f, view));
    view.distortion = coefficients({-0.3, 0, 0, 0}).opencv();
    CHECK(certipose::verify::fov_ok(x, f, view));
    view.margin_px = 400;
    CHECK(!certipose::verify::fov_ok(x, f, view));
}
