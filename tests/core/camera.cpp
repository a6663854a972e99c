// Tests for the camera module: hand-computed values for the case-study camera, the thin-lens
// identities of paper Eqs. 1–7, the inward rounding of [d_min, d_max] (checked exactly with
// rationals), the resolution cap and parameter validation.
#include <certipose/camera.hpp>

#include <doctest/doctest.h>

#include <boost/multiprecision/cpp_int.hpp>

#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <string>

namespace {

using certipose::CameraModel;
using certipose::pinhole_camera;
using certipose::pinhole_parameters;
using certipose::thin_lens_camera;
using certipose::thin_lens_parameters;
using rational = boost::multiprecision::cpp_rational;

constexpr double inf_v = std::numeric_limits<double>::infinity();
constexpr double nan_v = std::numeric_limits<double>::quiet_NaN();

static_assert(CameraModel<thin_lens_camera>);
static_assert(CameraModel<pinhole_camera>);
static_assert(!CameraModel<int>);
static_assert(!CameraModel<thin_lens_parameters>);

// The case-study camera (examples/data/camera.json).
thin_lens_parameters design_parameters() {
    return {.focal_length = 0.012,
            .f_stop = 8,
            .focus_distance = 0.6,
            .max_blur_circle = 6.9e-6,
            .pixel_pitch = 3.45e-6,
            .width_px = 2448,
            .height_px = 2048,
            .principal_point_px = Eigen::Vector2d(1224, 1024),
            .skew = 0,
            .aspect = 1};
}

pinhole_parameters design_pinhole() {
    return {.focal_length = 0.012,
            .pixel_pitch = 3.45e-6,
            .width_px = 2448,
            .height_px = 2048,
            .d_min = 0.49,
            .d_max = 0.78};
}

double rel(double got, double want) { return std::abs(got - want) / std::abs(want); }

// Hand-computed (exact rational arithmetic on the decimal parameters, 18 digits):
// f_px = 0.012 / 3.45e-6 = 80000/23; H = 0.012² / (8 · 6.9e-6) + 0.012;
// D_n = s (H − f) / (H + s − 2f); D_f = s (H − f) / (H − s).
constexpr double f_px_hand = 3478.26086956521739;
constexpr double hyperfocal_hand = 2.62069565217391304;
constexpr double d_near_hand = 0.489636037212338817;
constexpr double d_far_hand = 0.774593338497288877;

// Exact near/far limits (hyperfocal formulas) of the double-valued parameters.
struct exact_limits {
    rational near, far;
    bool far_infinite;
};
exact_limits exact_dof(const thin_lens_parameters& p) {
    const rational f(p.focal_length), n(p.f_stop), s(p.focus_distance), b(p.max_blur_circle);
    const rational h = f * f / (n * b) + f;
    exact_limits r{s * (h - f) / (h + s - 2 * f), 0, s >= h};
    if (!r.far_infinite) r.far = s * (h - f) / (h - s);
    return r;
}

// Exact sensor blur circle a·|l − s|/l · f/(s − f), a = f/N.
rational exact_blur_circle(const thin_lens_parameters& p, double l_double) {
    const rational f(p.focal_length), n(p.f_stop), s(p.focus_distance), l(l_double);
    return (f / n) * abs(l - s) / l * f / (s - f);
}

// The field() of the invalid_argument a call throws, or a marker if it throws nothing else.
template <class F>
std::string thrown_field(F&& make, std::string* message = nullptr) {
    try {
        make();
    } catch (const certipose::invalid_argument& e) {
        if (message) *message = e.what();
        return e.field();
    } catch (...) {
        return "<other exception>";
    }
    return "<no exception>";
}

template <class Params, class T>
std::string field_for(Params p, T Params::*member, T value, std::string* message = nullptr) {
    p.*member = value;
    if constexpr (std::is_same_v<Params, thin_lens_parameters>)
        return thrown_field([&] { thin_lens_camera{p}; }, message);
    else
        return thrown_field([&] { pinhole_camera{p}; }, message);
}

}  // namespace

TEST_CASE("thin_lens_camera: K and FOV of the DESIGN camera") {
    const thin_lens_camera cam(design_parameters());
    const Eigen::Matrix3d k = cam.intrinsics();
    CHECK(rel(k(0, 0), f_px_hand) < 1e-15);
    CHECK(rel(k(1, 1), f_px_hand) < 1e-15);  // δ = 1
    CHECK(k(0, 1) == 0.0);
    CHECK(k(0, 2) == 1224.0);
    CHECK(k(1, 2) == 1024.0);
    CHECK(k(1, 0) == 0.0);
    CHECK(k(2, 0) == 0.0);
    CHECK(k(2, 1) == 0.0);
    CHECK(k(2, 2) == 1.0);
    CHECK(cam.width_px() == 2448.0);
    CHECK(cam.height_px() == 2048.0);

    // α_h = atan(2448 / (2 · 80000/23)) = atan(0.35190), α_v = atan(2048 · 23 / 160000).
    const auto fov = cam.fov_half_angles();
    CHECK(fov.horizontal == doctest::Approx(0.338366465928072).epsilon(1e-13));
    CHECK(fov.vertical == doctest::Approx(0.286311294461578).epsilon(1e-13));
    CHECK(fov.horizontal == doctest::Approx(std::atan(2448.0 * 23.0 / 160000.0)).epsilon(1e-14));
    CHECK(fov.vertical == doctest::Approx(std::atan(2048.0 * 23.0 / 160000.0)).epsilon(1e-14));

    // Without an explicit principal point the image centre is used.
    thin_lens_parameters p = design_parameters();
    p.principal_point_px.reset();
    const thin_lens_camera centred(p);
    CHECK(centred.intrinsics() == cam.intrinsics());
    CHECK(centred.principal_point_px() == Eigen::Vector2d(1224, 1024));
}

TEST_CASE("thin_lens_camera: thin-lens quantities (paper Eqs. 2-7)") {
    const thin_lens_camera cam(design_parameters());
    CHECK(rel(cam.aperture_diameter(), 0.0015) < 1e-15);  // Eq. 3: 0.012 / 8
    CHECK(rel(cam.hyperfocal_distance(), hyperfocal_hand) < 1e-14);
    // Eq. 4: 0.012 · 0.6 / 0.588 = 0.6 / 49
    CHECK(rel(cam.focus_image_distance(), 0.6 / 49.0) < 1e-14);
    // Eq. 1 holds: 1/l + 1/l' = 1/f.
    for (double l : {0.05, 0.3, 0.6, 2.0, 100.0})
        CHECK(rel(1.0 / l + 1.0 / cam.image_distance(l), 1.0 / 0.012) < 1e-13);
    CHECK(cam.image_distance(inf_v) == 0.012);

    // Eq. 7 by hand: θ(1.0) = 0.0015 · |1/0.6 − 1| = 0.001, θ(0.3) = 0.0015 · |1/0.6 − 1/0.3| = 0.0025.
    CHECK(rel(cam.blur_angle(1.0), 0.001) < 1e-13);
    CHECK(rel(cam.blur_angle(0.3), 0.0025) < 1e-13);
    CHECK(cam.blur_angle(0.6) == 0.0);
    CHECK(rel(cam.blur_angle(inf_v), 0.0025) < 1e-13);  // a / s
    // Eq. 6 (small angle): θ_blur = c_diam / d'_focus.
    for (double l : {0.01, 0.2, 0.45, 0.6, 0.9, 5.0, 1e6, inf_v})
        CHECK(cam.blur_angle(l) * cam.focus_image_distance() ==
              doctest::Approx(cam.blur_circle(l)).epsilon(1e-12));
    // Eq. 5 from image distances: c = a · |l' − s'| / l'.
    for (double l : {0.2, 0.45, 0.9, 5.0}) {
        const double li = cam.image_distance(l), si = cam.focus_image_distance();
        CHECK(cam.blur_circle(l) ==
              doctest::Approx(0.0015 * std::abs(li - si) / li).epsilon(1e-10));
    }
    CHECK(cam.blur_circle(0.6) == 0.0);
}

TEST_CASE("thin_lens_camera: [d_min, d_max] are the hyperfocal near/far limits") {
    const thin_lens_parameters p = design_parameters();
    const thin_lens_camera cam(p);
    const auto range = cam.distance_range();

    CHECK(rel(range.min, d_near_hand) < 1e-12);
    CHECK(rel(range.max, d_far_hand) < 1e-12);

    const double f = 0.012, s = 0.6, h = cam.hyperfocal_distance();
    CHECK(rel(range.min, s * (h - f) / (h + s - 2 * f)) < 1e-12);
    CHECK(rel(range.max, s * (h - f) / (h - s)) < 1e-12);

    // The limits are where the sensor blur circle equals b_max ...
    CHECK(rel(cam.blur_circle(range.min), 6.9e-6) < 1e-9);
    CHECK(rel(cam.blur_circle(range.max), 6.9e-6) < 1e-9);
    // ... and the blur is larger just outside, smaller inside.
    CHECK(cam.blur_circle(range.min * (1 - 1e-6)) > 6.9e-6);
    CHECK(cam.blur_circle(range.max * (1 + 1e-6)) > 6.9e-6);
    CHECK(cam.blur_circle(range.min * (1 + 1e-6)) < 6.9e-6);
    CHECK(cam.blur_circle(range.max * (1 - 1e-6)) < 6.9e-6);
    CHECK(range.contains(0.6));
    CHECK_FALSE(range.empty());
}

TEST_CASE("thin_lens_camera: [d_min, d_max] is rounded inward") {
    const thin_lens_parameters p = design_parameters();
    const auto range = thin_lens_camera(p).distance_range();

    // Long double reference (64-bit mantissa) of the same formulas.
    const long double f = p.focal_length, n = p.f_stop, s = p.focus_distance,
                      b = p.max_blur_circle;
    const long double h = f * f / (n * b) + f;
    const long double near_ld = s * (h - f) / (h + s - 2 * f), far_ld = s * (h - f) / (h - s);
    CHECK(static_cast<long double>(range.min) >= near_ld);
    CHECK(static_cast<long double>(range.max) <= far_ld);

    // Exactly, and in exact arithmetic the blur circle at the returned limits is <= b_max.
    const exact_limits exact = exact_dof(p);
    CHECK(rational(range.min) >= exact.near);
    CHECK(rational(range.max) <= exact.far);
    CHECK(exact_blur_circle(p, range.min) <= rational(p.max_blur_circle));
    CHECK(exact_blur_circle(p, range.max) <= rational(p.max_blur_circle));
}

TEST_CASE("thin_lens_camera: inward rounding holds over random parameters (exact check)") {
    std::mt19937_64 rng(20230917);
    auto log_uniform = [&](double lo, double hi) {
        return std::exp(std::uniform_real_distribution<double>(std::log(lo), std::log(hi))(rng));
    };
    int finite_far = 0, infinite_far = 0;
    for (int i = 0; i < 300; ++i) {
        thin_lens_parameters p = design_parameters();
        p.focal_length = log_uniform(0.002, 0.2);
        p.f_stop = log_uniform(1.0, 32.0);
        p.max_blur_circle = log_uniform(1e-6, 5e-5);
        const double h = p.focal_length * p.focal_length / (p.f_stop * p.max_blur_circle);
        // Focus from just beyond f to a few hyperfocal distances, plus cases right at H.
        p.focus_distance = i % 10 == 0 ? h + p.focal_length
                                       : p.focal_length * (1 + log_uniform(1e-6, 4 * h / p.focal_length));
        if (!(p.focus_distance > p.focal_length)) continue;
        const thin_lens_camera cam(p);
        const auto range = cam.distance_range();
        const exact_limits exact = exact_dof(p);
        const rational b(p.max_blur_circle);

        CHECK(rational(range.min) >= exact.near);
        CHECK(exact_blur_circle(p, range.min) <= b);
        // Not needlessly conservative: a few ulps only.
        CHECK(rational(range.min) <= exact.near * rational(1 + 1e-14));
        if (exact.far_infinite) {
            ++infinite_far;
            // Either +inf_v or a (sound) finite lower bound when s is within rounding of H.
            if (std::isfinite(range.max)) CHECK(exact_blur_circle(p, range.max) <= b);
        } else {
            ++finite_far;
            CHECK(std::isfinite(range.max));
            CHECK(rational(range.max) <= exact.far);
            CHECK(exact_blur_circle(p, range.max) <= b);
        }
        CHECK(range.min <= range.max);
    }
    CHECK(finite_far > 100);
    CHECK(infinite_far > 10);
}

TEST_CASE("thin_lens_camera: focused at or beyond the hyperfocal distance, d_max is infinite") {
    thin_lens_parameters p = design_parameters();
    p.focus_distance = 3.0;  // > H = 2.6207
    const thin_lens_camera cam(p);
    CHECK(cam.distance_range().max == inf_v);
    // D_n = s (H − f) / (H + s − 2f) still holds.
    const double h = cam.hyperfocal_distance(), f = 0.012, s = 3.0;
    CHECK(rel(cam.distance_range().min, s * (h - f) / (h + s - 2 * f)) < 1e-12);
    // Focused at H: near limit (H − f) H / (2H − 2f) = H / 2, far limit +inf_v (or, when the
    // double H lies just below the exact one, a huge sound finite bound).
    p.focus_distance = h;
    const auto at_h = thin_lens_camera(p).distance_range();
    CHECK(rel(at_h.min, h / 2) < 1e-12);
    CHECK(at_h.max > 1e10);
    // Below H the far limit is finite.
    p.focus_distance = 2.0;
    CHECK(std::isfinite(thin_lens_camera(p).distance_range().max));
}

TEST_CASE("capped_distance_range: resolution requirement caps d_max at r * f_px") {
    const thin_lens_camera cam(design_parameters());
    const auto base = cam.distance_range();

    // r = 2e-4 m/px: cap = 2e-4 · 80000/23 = 16/23 = 0.69565 < d_max.
    const auto capped = cam.distance_range(2e-4);
    CHECK(capped.min == base.min);
    CHECK(rel(capped.max, 16.0 / 23.0) < 1e-14);
    CHECK(rational(capped.max) <= rational(2e-4) * rational(0.012) / rational(3.45e-6));
    CHECK(certipose::capped_distance_range(cam, 2e-4).max == capped.max);

    // Loose requirement or none: unchanged.
    CHECK(cam.distance_range(1e-3).max == base.max);
    CHECK(certipose::capped_distance_range(cam, std::nullopt).max == base.max);
    CHECK(cam.distance_range(inf_v).max == base.max);

    // Tighter than the near limit: no usable distance.
    const auto none = cam.distance_range(1e-4);  // cap 0.3478 < d_min 0.4896
    CHECK(none.empty());
    CHECK_FALSE(none.contains(0.45));

    // Pinhole with infinite d_max gets a finite cap.
    pinhole_parameters pp = design_pinhole();
    pp.d_max = inf_v;
    CHECK(rel(pinhole_camera(pp).distance_range(2e-4).max, 16.0 / 23.0) < 1e-14);

    for (double bad : {0.0, -1e-4, nan_v, -inf_v}) {
        std::string msg;
        CHECK(thrown_field([&] { (void)cam.distance_range(bad); }, &msg) ==
              "max_metres_per_pixel");
        CHECK(msg.find("max_metres_per_pixel") != std::string::npos);
    }
}

namespace {
// A user-written model: nothing from the library but the concept's return types.
struct fixed_camera {
    Eigen::Matrix3d intrinsics() const {
        Eigen::Matrix3d k;
        k << 1000, 0, 320, 0, 1000, 240, 0, 0, 1;
        return k;
    }
    double width_px() const { return 640; }
    double height_px() const { return 480; }
    certipose::fov_half_angles fov_half_angles() const { return {0.31, 0.235}; }
    certipose::distance_range distance_range() const { return {0.1, 2.0}; }
};
static_assert(CameraModel<fixed_camera>);
}  // namespace

TEST_CASE("capped_distance_range works for a user-written CameraModel") {
    const auto r = certipose::capped_distance_range(fixed_camera{}, 1e-3);  // cap 1.0 m
    CHECK(r.min == 0.1);
    CHECK(r.max <= 1.0);
    CHECK(r.max > 1.0 - 1e-14);
}

TEST_CASE("pinhole_camera: same intrinsics, user distance bounds") {
    const pinhole_camera pin(design_pinhole());
    const thin_lens_camera lens(design_parameters());
    CHECK(pin.intrinsics() == lens.intrinsics());
    CHECK(pin.fov_half_angles().horizontal == lens.fov_half_angles().horizontal);
    CHECK(pin.fov_half_angles().vertical == lens.fov_half_angles().vertical);
    CHECK(pin.distance_range().min == 0.49);
    CHECK(pin.distance_range().max == 0.78);
    CHECK(rel(pin.focal_length_px(), f_px_hand) < 1e-15);

    pinhole_parameters p = design_pinhole();
    p.d_min = 0;
    p.d_max = inf_v;
    const pinhole_camera open(p);
    CHECK(open.distance_range().min == 0.0);
    CHECK(open.distance_range().max == inf_v);
}

TEST_CASE("cameras: off-centre principal point, skew and aspect") {
    pinhole_parameters p = design_pinhole();
    p.principal_point_px = Eigen::Vector2d(1000, 1300);
    p.skew = 40;
    p.aspect = 1.1;
    const pinhole_camera cam(p);
    const Eigen::Matrix3d k = cam.intrinsics();
    CHECK(k(0, 1) == 40.0);
    CHECK(rel(k(1, 1), 1.1 * f_px_hand) < 1e-15);
    CHECK(k(0, 2) == 1000.0);
    CHECK(k(1, 2) == 1300.0);

    // The FOV pyramid's corner rays project inside the image, and it touches the border.
    const auto fov = cam.fov_half_angles();
    const double th = std::tan(fov.horizontal), tv = std::tan(fov.vertical);
    double touch_u = inf_v, touch_v = inf_v;
    for (double sx : {-1.0, 1.0})
        for (double sy : {-1.0, 1.0}) {
            const Eigen::Vector3d q = k * Eigen::Vector3d(sx * th, sy * tv, 1.0);
            const double u = q.x() / q.z(), v = q.y() / q.z();
            CHECK(u >= -1e-9);
            CHECK(u <= 2448 + 1e-9);
            CHECK(v >= -1e-9);
            CHECK(v <= 2048 + 1e-9);
            touch_u = std::min({touch_u, u, 2448 - u});
            touch_v = std::min({touch_v, v, 2048 - v});
        }
    CHECK(std::abs(touch_u) < 1e-9);
    CHECK(std::abs(touch_v) < 1e-9);
    // Vertical: nearest border is 2048 − 1300 = 748 px at δ f_px.
    CHECK(rel(tv, 748.0 / (1.1 * f_px_hand)) < 1e-13);
}

TEST_CASE("thin_lens_camera: every impossible parameter throws invalid_argument naming it") {
    using P = thin_lens_parameters;
    const P good = design_parameters();
    CHECK(thrown_field([&] { thin_lens_camera{good}; }) == "<no exception>");

    for (double bad : {0.0, -0.012, nan_v, inf_v, -inf_v}) {
        CAPTURE(bad);
        CHECK(field_for(good, &P::focal_length, bad) == "focal_length");
        CHECK(field_for(good, &P::f_stop, bad) == "f_stop");
        CHECK(field_for(good, &P::pixel_pitch, bad) == "pixel_pitch");
        CHECK(field_for(good, &P::max_blur_circle, bad) == "max_blur_circle");
        CHECK(field_for(good, &P::focus_distance, bad) == "focus_distance");
        CHECK(field_for(good, &P::width_px, bad) == "width_px");
        CHECK(field_for(good, &P::height_px, bad) == "height_px");
        CHECK(field_for(good, &P::aspect, bad) == "aspect");
    }
    // focus distance must exceed the focal length.
    CHECK(field_for(good, &P::focus_distance, 0.012) == "focus_distance");
    CHECK(field_for(good, &P::focus_distance, 0.011) == "focus_distance");
    CHECK(field_for(good, &P::focus_distance, 0.0120001) == "<no exception>");
    for (double bad : {nan_v, inf_v, -inf_v}) CHECK(field_for(good, &P::skew, bad) == "skew");
    CHECK(field_for(good, &P::skew, -3.0) == "<no exception>");
    // Skew so large that no horizontal field of view remains.
    CHECK(field_for(good, &P::skew, 1e6) == "skew");

    using V = std::optional<Eigen::Vector2d>;
    for (const V& bad : {V(Eigen::Vector2d(nan_v, 1024)), V(Eigen::Vector2d(1224, nan_v)),
                         V(Eigen::Vector2d(inf_v, 1024)), V(Eigen::Vector2d(-1, 1024)),
                         V(Eigen::Vector2d(1224, 2048)), V(Eigen::Vector2d(2448, 1)),
                         V(Eigen::Vector2d(1224, 0))})
        CHECK(field_for(good, &P::principal_point_px, bad) == "principal_point_px");

    // Fields left out of the designated initialiser are rejected, naming the first one.
    CHECK(thrown_field([] { thin_lens_camera{thin_lens_parameters{}}; }) == "focal_length");
    CHECK(thrown_field([] {
              thin_lens_camera{{.focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6,
                                .pixel_pitch = 3.45e-6, .width_px = 2448, .height_px = 2048}};
          }) == "max_blur_circle");

    // Parameters whose derived quantities leave the double range.
    P huge = good;  // f² overflows
    huge.focal_length = 1e160;
    huge.focus_distance = 1e161;
    CHECK(thrown_field([&] { thin_lens_camera{huge}; }) == "focal_length");
    CHECK(field_for(good, &P::focal_length, 1e-170) == "focal_length");  // f² underflows to 0

    // The message names the field and the offending value.
    std::string msg;
    CHECK(field_for(good, &P::focal_length, -0.012, &msg) == "focal_length");
    CHECK(msg.find("focal_length") != std::string::npos);
    CHECK(msg.find("-0.012") != std::string::npos);
    CHECK(field_for(good, &P::focus_distance, 0.005, &msg) == "focus_distance");
    CHECK(msg.find("0.005") != std::string::npos);
    CHECK(field_for(good, &P::f_stop, nan_v, &msg) == "f_stop");
    CHECK(msg.find("nan") != std::string::npos);

    // Object-distance arguments of the thin-lens quantities.
    const thin_lens_camera cam(good);
    for (double bad : {0.0, -1.0, nan_v}) {
        CHECK(thrown_field([&] { (void)cam.blur_circle(bad); }) == "object_distance");
        CHECK(thrown_field([&] { (void)cam.blur_angle(bad); }) == "object_distance");
    }
    for (double bad : {0.012, 0.005, nan_v})
        CHECK(thrown_field([&] { (void)cam.image_distance(bad); }) == "object_distance");
}

TEST_CASE("pinhole_camera: every impossible parameter throws invalid_argument naming it") {
    using P = pinhole_parameters;
    const P good = design_pinhole();
    CHECK(thrown_field([&] { pinhole_camera{good}; }) == "<no exception>");
    for (double bad : {0.0, -0.012, nan_v, inf_v}) {
        CAPTURE(bad);
        CHECK(field_for(good, &P::focal_length, bad) == "focal_length");
        CHECK(field_for(good, &P::pixel_pitch, bad) == "pixel_pitch");
        CHECK(field_for(good, &P::width_px, bad) == "width_px");
        CHECK(field_for(good, &P::height_px, bad) == "height_px");
        CHECK(field_for(good, &P::aspect, bad) == "aspect");
    }
    CHECK(field_for(good, &P::skew, nan_v) == "skew");
    CHECK(field_for(good, &P::principal_point_px,
                    std::optional<Eigen::Vector2d>(Eigen::Vector2d(nan_v, nan_v))) ==
          "principal_point_px");

    for (double bad : {-1e-9, -1.0, nan_v, inf_v, -inf_v}) {
        CAPTURE(bad);
        CHECK(field_for(good, &P::d_min, bad) == "d_min");
    }
    for (double bad : {0.49, 0.3, 0.0, nan_v, -inf_v}) {
        CAPTURE(bad);
        CHECK(field_for(good, &P::d_max, bad) == "d_max");
    }
    CHECK(field_for(good, &P::d_min, 0.0) == "<no exception>");
    CHECK(field_for(good, &P::d_max, inf_v) == "<no exception>");

    std::string msg;
    CHECK(field_for(good, &P::d_max, 0.3, &msg) == "d_max");
    CHECK(msg.find("0.3") != std::string::npos);
    CHECK(msg.find("0.49") != std::string::npos);
}
