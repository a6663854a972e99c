// Tests for the orientation module (include/certipose/orientation/): certify_fov is sound and
// decisive on obvious cases, both policies model OrientationPolicy, and every pose sampled
// inside every certified 6D box satisfies constraint 5 of docs/conventions.md by plain double
// evaluation (R built from elementary rotations, K projection, all three vertices in front and
// inside the image) — over many random facets and position boxes, including aims straight down
// and straight up the z axis (the ZXZ singularity). tests/cgal/orientation_cgal.cpp runs the
// typed tests with cgal_interval.
#include <certipose/camera/pinhole_camera.hpp>
#include <certipose/camera/thin_lens_camera.hpp>
#include <certipose/interval/boost_interval.hpp>
#include <certipose/orientation/certify.hpp>
#include <certipose/orientation/concept.hpp>
#include <certipose/orientation/paper_orientation.hpp>
#include <certipose/orientation/paving_orientation.hpp>

#include <doctest/doctest.h>

#include <Eigen/Dense>

#include <array>
#include <span>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#ifndef CERTIPOSE_ORIENTATION_TEST_BACKENDS
#define CERTIPOSE_ORIENTATION_TEST_BACKENDS certipose::boost_interval
#endif

namespace orientation_test {

using namespace certipose;
constexpr double pi = std::numbers::pi;

// The case-study camera (examples/data/camera.json).
inline thin_lens_camera design_camera() {
    return thin_lens_camera({.focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6, .max_blur_circle = 6.9e-6,
                             .pixel_pitch = 3.45e-6, .width_px = 2448, .height_px = 2048});
}

inline facet make_facet(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    facet f;
    f.v = {a, b, c};
    const Eigen::Vector3d n = (b - a).cross(c - a);
    f.area = n.norm() / 2;
    f.normal = n.normalized();
    f.centroid = (a + b + c) / 3.0;
    f.bbox.setEmpty();
    for (const auto& p : f.v) f.bbox.extend(p);
    return f;
}

// ---- the independent oracle: plain double, written from docs/conventions.md -----------------------
inline Eigen::Matrix3d rot_z(double a) {
    Eigen::Matrix3d m;
    m << std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1;
    return m;
}
inline Eigen::Matrix3d rot_x(double a) {
    Eigen::Matrix3d m;
    m << 1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a);
    return m;
}
/// Constraint 5 at one pose: every vertex in front (q_c.z > 0) and at a pixel inside [0, w]×[0, h].
inline bool fov_holds(const Eigen::Vector3d& p, double phi, double gamma, double beta, const facet& f,
                      const Eigen::Matrix3d& k, double w, double h) {
    const Eigen::Matrix3d r = rot_z(phi) * rot_x(gamma) * rot_z(beta);
    for (const auto& v : f.v) {
        const Eigen::Vector3d qc = r.transpose() * (v - p);
        if (!(qc.z() > 0.0)) return false;
        const Eigen::Vector3d uvw = k * qc;
        const double u = uvw.x() / uvw.z(), vv = uvw.y() / uvw.z();
        if (!(u >= 0.0 && u <= w && vv >= 0.0 && vv <= h)) return false;
    }
    return true;
}

/// A coordinate drawn from [lo, hi]: a third of the draws at an end (extremes matter most).
inline double draw(std::mt19937_64& rng, double lo, double hi) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double t = u(rng);
    if (t < 1.0 / 6) return lo;
    if (t < 2.0 / 6) return hi;
    return lo + u(rng) * (hi - lo);
}

struct sample_counts {
    std::size_t samples = 0, failures = 0;
};

/// Samples `n` poses of position × orientation and counts the ones violating constraint 5.
template <class I, class Camera>
sample_counts sample(const position_box<I>& p, const orientation_box<I>& e, const facet& f, const Camera& cam,
                     std::size_t n, std::mt19937_64& rng) {
    sample_counts c;
    const Eigen::Matrix3d k = cam.intrinsics();
    for (std::size_t i = 0; i < n; ++i) {
        const Eigen::Vector3d x(draw(rng, lower(p[0]), upper(p[0])), draw(rng, lower(p[1]), upper(p[1])),
                                draw(rng, lower(p[2]), upper(p[2])));
        const double phi = draw(rng, lower(e[0]), upper(e[0])), gamma = draw(rng, lower(e[1]), upper(e[1])),
                     beta = draw(rng, lower(e[2]), upper(e[2]));
        ++c.samples;
        if (!fov_holds(x, phi, gamma, beta, f, k, cam.width_px(), cam.height_px())) ++c.failures;
    }
    return c;
}

// ---- random scenarios -----------------------------------------------------------------------
enum class aim_kind { general, straight_down, straight_up };

template <class I>
struct scenario {
    facet f;
    position_box<I> position;
};

/// A random facet (5 mm – 12 cm) and a position box (half-sizes 0 – 5 cm per axis) 0.45 –
/// 0.85 m from it. straight_down puts the box above the facet (optical axis ≈ −z, γ ≈ π),
/// straight_up below it (axis ≈ +z, γ ≈ 0): the ZXZ singularity.
template <class I>
scenario<I> random_scenario(std::mt19937_64& rng, aim_kind kind, double max_size = 0.12) {
    std::uniform_real_distribution<double> u(-1.0, 1.0), u01(0.0, 1.0);
    scenario<I> s;
    const Eigen::Vector3d c(0.2 * u(rng), 0.2 * u(rng), 0.2 * u(rng));
    const double size = 0.005 + (max_size - 0.005) * u01(rng);
    for (;;) {
        const Eigen::Vector3d a = c + size * Eigen::Vector3d(u(rng), u(rng), u(rng));
        const Eigen::Vector3d b = c + size * Eigen::Vector3d(u(rng), u(rng), u(rng));
        const Eigen::Vector3d d = c + size * Eigen::Vector3d(u(rng), u(rng), u(rng));
        if ((b - a).cross(d - a).norm() > 0.05 * size * size) {
            s.f = make_facet(a, b, d);
            break;
        }
    }
    Eigen::Vector3d dir = Eigen::Vector3d::UnitX();
    switch (kind) {
        case aim_kind::general: dir = Eigen::Vector3d(u(rng), u(rng), u(rng)); break;
        case aim_kind::straight_down: dir = Eigen::Vector3d(0.01 * u(rng), 0.01 * u(rng), 1.0); break;
        case aim_kind::straight_up: dir = Eigen::Vector3d(0.01 * u(rng), 0.01 * u(rng), -1.0); break;
    }
    dir.normalize();
    const Eigen::Vector3d centre = s.f.centroid + (0.45 + 0.4 * u01(rng)) * dir;
    for (int j = 0; j < 3; ++j) {
        const double r = 0.05 * u01(rng);
        s.position[static_cast<std::size_t>(j)] = I(centre[j] - r, centre[j] + r);
    }
    return s;
}

inline aim_kind kind_of(std::size_t i) {
    return i % 4 == 1 ? aim_kind::straight_down : i % 4 == 3 ? aim_kind::straight_up : aim_kind::general;
}

/// An orientation box of half-widths w (φ, γ) and wb (β, about 0) whose φ, γ centre is moved
/// off the aim by (+off, −off).
template <class I>
certipose::orientation_box<I> box_near_aim(const certipose::zxz_angles& aim, double off, double w, double wb) {
    certipose::orientation_box<I> e;
    e[0] = I(aim.phi + off - w, aim.phi + off + w), e[1] = I(aim.gamma - off - w, aim.gamma - off + w), e[2] = I(-wb, wb);
    return e;
}

// A camera model written by a user: only what the concept asks for.
struct user_camera {
    Eigen::Matrix3d intrinsics() const {
        Eigen::Matrix3d k;
        k << 1000, 0, 320, 0, 1000, 240, 0, 0, 1;
        return k;
    }
    double width_px() const { return 640; }
    double height_px() const { return 480; }
    certipose::fov_half_angles fov_half_angles() const { return {std::atan(0.32), std::atan(0.24)}; }
    certipose::distance_range distance_range() const { return {0.2, 2.0}; }
};

}  // namespace orientation_test

namespace {

using namespace orientation_test;

TEST_CASE_TEMPLATE("orientation: both policies model OrientationPolicy for every camera model", I,
                   CERTIPOSE_ORIENTATION_TEST_BACKENDS) {
    static_assert(OrientationPolicy<paper_orientation, I, thin_lens_camera>);
    static_assert(OrientationPolicy<paper_orientation, I, pinhole_camera>);
    static_assert(OrientationPolicy<paper_orientation, I, user_camera>);
    static_assert(OrientationPolicy<paving_orientation, I, thin_lens_camera>);
    static_assert(OrientationPolicy<paving_orientation, I, user_camera>);
    static_assert(!OrientationPolicy<int, I, thin_lens_camera>);
    static_assert(BoxTest<fov_orientation_test<I>, orientation_box<I>>);

    // The user camera works end to end: a small facet 1 m in front is certified.
    const facet f = make_facet({0, 0, 0}, {0.02, 0, 0}, {0, 0.02, 0});
    position_box<I> p;
    p[0] = I(0.0, 0.01), p[1] = I(0.0, 0.01), p[2] = I(1.0, 1.01);
    const auto r = paper_orientation{}.orient(p, f, user_camera{}, 0.38);
    REQUIRE(r.boxes.size() == 1);
    CHECK(r.certifications >= 1);
    std::mt19937_64 rng(11);
    CHECK(sample(p, r.boxes[0], f, user_camera{}, 2000, rng).failures == 0);
}

TEST_CASE_TEMPLATE("certify_fov: satisfied for the nominal aim of a tiny box far enough away", I,
                   CERTIPOSE_ORIENTATION_TEST_BACKENDS) {
    const auto cam = design_camera();
    const fov_frustum<I> frustum(cam);
    const facet f = make_facet({0.1, 0.2, 0.0}, {0.13, 0.2, 0.0}, {0.1, 0.23, 0.01});
    const std::array<Eigen::Vector3d, 5> dirs{Eigen::Vector3d(0.3, -0.2, 1.0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 0, 1),
                                              Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(-0.5, 0.7, -0.2)};
    for (const Eigen::Vector3d& dir : dirs) {
        const Eigen::Vector3d c = f.centroid + 0.6 * dir.normalized();
        position_box<I> p;
        for (std::size_t j = 0; j < 3; ++j) p[j] = I(c[static_cast<int>(j)] - 1e-4, c[static_cast<int>(j)] + 1e-4);
        const auto aim = nominal_aim(p, f);
        REQUIRE(aim);
        orientation_box<I> e;
        e[0] = I(aim->phi - 1e-3, aim->phi + 1e-3), e[1] = I(aim->gamma - 1e-3, aim->gamma + 1e-3), e[2] = I(-1e-3, 1e-3);
        CHECK(certify_fov(p, e, f, frustum) == verdict::satisfied);
        CHECK(certify_fov(p, e, f, cam.intrinsics(), cam.width_px(), cam.height_px()) == verdict::satisfied);
        // Any roll: the facet (~3 cm at 0.6 m) stays inside the inscribed circle of the image.
        e[2] = I(-pi, pi);
        CHECK(certify_fov(p, e, f, frustum) == verdict::satisfied);
        // Obviously wrong aims: looking away, 90° off, just outside the circumscribed cone.
        orientation_box<I> away = e, side = e, off = e;
        away[1] = I(pi - aim->gamma - 1e-3, pi - aim->gamma + 1e-3);
        away[0] = I(aim->phi + pi - 1e-3, aim->phi + pi + 1e-3);
        side[1] = I(aim->gamma + pi / 2 - 1e-3, aim->gamma + pi / 2 + 1e-3);
        off[1] = I(aim->gamma + 0.6 - 1e-3, aim->gamma + 0.6 + 1e-3);
        CHECK(certify_fov(p, away, f, frustum) == verdict::violated);
        CHECK(certify_fov(p, side, f, frustum) == verdict::violated);
        CHECK(certify_fov(p, off, f, frustum) == verdict::violated);
        // A half-circle of φ away from the pole includes aims that miss: not certified.
        if (aim->gamma > 0.5 && aim->gamma < pi - 0.5) {
            orientation_box<I> wide = e;
            wide[0] = I(aim->phi - 1.5, aim->phi + 1.5);
            CHECK(certify_fov(p, wide, f, frustum) != verdict::satisfied);
        }
    }
}

TEST_CASE_TEMPLATE("certify_fov: sound on random 6D boxes (sampled poses agree with every verdict)", I,
                   CERTIPOSE_ORIENTATION_TEST_BACKENDS) {
    const auto cam = design_camera();
    const fov_frustum<I> frustum(cam);
    std::mt19937_64 rng(2024);
    std::uniform_real_distribution<double> u(-1.0, 1.0), u01(0.0, 1.0);
    std::size_t satisfied = 0, violated = 0, undecided = 0, samples = 0, singular_satisfied = 0;
    for (std::size_t i = 0; i < 1500; ++i) {
        const auto s = random_scenario<I>(rng, kind_of(i));
        const auto aim = nominal_aim(s.position, s.f);
        REQUIRE(aim);
        // Around the nominal aim, sometimes far off; widths from tiny to large; β from a point
        // to the whole circle; near the pole φ may span the whole circle too.
        const double off = u01(rng) < 0.2 ? 0.8 : 0.15;
        const double cphi = aim->phi + off * u(rng), cgam = aim->gamma + off * u(rng), cbet = 0.3 * u(rng);
        const double wg = 0.4 * u01(rng) * u01(rng);
        const double wp = (kind_of(i) != aim_kind::general && u01(rng) < 0.5) ? pi : wg / std::max(0.2, std::sin(aim->gamma));
        const double t = u01(rng);
        const double wb = t < 0.3 ? pi : t < 0.6 ? 0.5 * u01(rng) : 0.05 * u01(rng);
        orientation_box<I> e;
        e[0] = I(cphi - wp, cphi + wp), e[1] = I(cgam - wg, cgam + wg), e[2] = I(cbet - wb, cbet + wb);
        const verdict v = certify_fov(s.position, e, s.f, frustum);
        const auto c = sample(s.position, e, s.f, cam, 20, rng);
        samples += c.samples;
        if (v == verdict::satisfied) {
            ++satisfied;
            if (kind_of(i) != aim_kind::general) ++singular_satisfied;
            CHECK_MESSAGE(c.failures == 0, "box " << i << " certified but " << c.failures << " poses fail");
        } else if (v == verdict::violated) {
            ++violated;
            CHECK_MESSAGE(c.failures == c.samples, "box " << i << " refuted but a sampled pose passes");
        } else {
            ++undecided;
        }
    }
    MESSAGE("certify_fov verdicts: " << satisfied << " satisfied, " << violated << " violated, " << undecided
                                     << " undecided; " << samples << " sampled poses");
    CHECK(satisfied >= 300);  // the test is not vacuous
    CHECK(violated >= 50);
    CHECK(singular_satisfied >= 50);
    CHECK(samples >= 10000);
}

TEST_CASE_TEMPLATE("fov_refuted: only boxes holding a corner pose that fails, never one certify_fov proves", I,
                   CERTIPOSE_ORIENTATION_TEST_BACKENDS) {
    // paper_orientation gives up on a box fov_refuted names without trying to prove it: that is
    // only right when the box truly holds a pose that does not see the facet. Its witness is a
    // corner of the position box at a corner (or the centre) of the orientation box.
    const auto cam = design_camera();
    const fov_frustum<I> frustum(cam);
    const Eigen::Matrix3d k = cam.intrinsics();
    std::mt19937_64 rng(77);
    std::uniform_real_distribution<double> u(-1.0, 1.0), u01(0.0, 1.0);
    std::size_t refuted = 0, certified = 0, failing_not_refuted = 0;
    for (std::size_t i = 0; i < 1500; ++i) {
        const auto s = random_scenario<I>(rng, kind_of(i));
        const auto aim = nominal_aim(s.position, s.f);
        REQUIRE(aim);
        const double w = 0.3 * u01(rng) * u01(rng), off = 0.1 * u(rng);
        const double wb = u01(rng) < 0.3 ? pi : 0.3 * u01(rng);
        orientation_box<I> e = box_near_aim<I>(*aim, off, w, wb);
        const bool r = fov_refuted(fov_position<I>(s.position, s.f), e, frustum);
        // Does a corner pose fail constraint 5 (plain evaluation)?
        bool corner_fails = false;
        for (std::size_t t = 0; t < 9 && !corner_fails; ++t)
            for (std::size_t c = 0; c < 8 && !corner_fails; ++c) {
                const auto at = [&](const I& x, std::size_t bit, std::size_t of) {
                    return of < 8 ? ((of >> bit) & 1u ? upper(x) : lower(x)) : mid(x);
                };
                const Eigen::Vector3d x(at(s.position[0], 0, c), at(s.position[1], 1, c), at(s.position[2], 2, c));
                corner_fails = !fov_holds(x, at(e[0], 0, t), at(e[1], 1, t), at(e[2], 2, t), s.f, k, cam.width_px(),
                                          cam.height_px());
            }
        if (r) {
            ++refuted;
            CHECK_MESSAGE(corner_fails, "box " << i << " refuted but every corner pose sees the facet");
            CHECK_MESSAGE(certify_fov(s.position, e, s.f, frustum) != verdict::satisfied, "box " << i << " refuted and certified");
        } else if (corner_fails) {
            ++failing_not_refuted;  // within the margin, or only at a corner the check does not try
        }
        if (certify_fov(s.position, e, s.f, frustum) == verdict::satisfied) {
            ++certified;
            CHECK(!r);
        }
    }
    MESSAGE("fov_refuted: " << refuted << " refuted, " << certified << " certified, " << failing_not_refuted
                            << " with a failing corner pose not refuted, of 1500 boxes");
    CHECK(refuted >= 200);    // not vacuous
    CHECK(certified >= 200);
    CHECK(failing_not_refuted <= refuted / 10);  // the worst position is found, not sampled
}

TEST_CASE_TEMPLATE("certify_fov and fov_refuted: sines and cosines carried from a box to its tiles change no verdict", I,
                   CERTIPOSE_ORIENTATION_TEST_BACKENDS) {
    // certify_tiled hands each tile the values its parent computed (angle_trig): every verdict
    // must be the one the tile gets with values of its own, down through several splits, and a
    // value held for another abscissa must never be used.
    const auto cam = design_camera();
    const fov_frustum<I> frustum(cam);
    std::mt19937_64 rng(2026);
    std::uniform_real_distribution<double> u(-1.0, 1.0), u01(0.0, 1.0);
    std::size_t tiles = 0, satisfied = 0, undecided = 0, refuted = 0;
    for (std::size_t i = 0; i < 600; ++i) {
        const auto s = random_scenario<I>(rng, kind_of(i));
        const auto aim = nominal_aim(s.position, s.f);
        REQUIRE(aim);
        const fov_position<I> prepared(s.position, s.f);
        const double w = 0.3 * u01(rng) * u01(rng), off = 0.1 * u(rng), wb = 0.3 * u01(rng);
        orientation_box<I> e = box_near_aim<I>(*aim, off, w, wb);
        detail::orientation::angle_trig carried;
        const bool r = fov_refuted(prepared, e, frustum, carried);
        CHECK(r == fov_refuted(prepared, e, frustum));
        refuted += r;
        // Split at random dimensions and points, always carrying the parent's values along.
        for (int depth = 0; depth < 6; ++depth, ++tiles) {
            detail::orientation::angle_trig own;
            const verdict shared = certify_fov(prepared, e, frustum, carried);
            REQUIRE(shared == certify_fov(prepared, e, frustum, own));
            CHECK(fov_refuted(prepared, e, frustum, carried) == fov_refuted(prepared, e, frustum));
            satisfied += shared == verdict::satisfied;
            undecided += shared == verdict::undecided;
            const std::size_t k = static_cast<std::size_t>(u01(rng) * 3) % 3;
            const double at = lower(e[k]) + (0.2 + 0.6 * u01(rng)) * (upper(e[k]) - lower(e[k]));
            const auto [lo, hi] = bisect_at(e, k, at);
            e = u01(rng) < 0.5 ? lo : hi;
        }
        // Values held for other abscissae: those of an unrelated box.
        orientation_box<I> other = e;
        for (std::size_t j = 0; j < 3; ++j) other[j] = I(lower(e[j]) - 0.05, upper(e[j]) + 0.07);
        detail::orientation::angle_trig stale;
        (void)certify_fov(prepared, other, frustum, stale);
        CHECK(certify_fov(prepared, e, frustum, stale) == certify_fov(prepared, e, frustum));
    }
    MESSAGE("carried trig: " << tiles << " tiles (" << satisfied << " satisfied, " << undecided << " undecided), "
                             << refuted << " of 600 boxes refuted");
    CHECK(satisfied >= 300);  // not vacuous: both verdicts that matter occur
    CHECK(undecided >= 100);
}

TEST_CASE_TEMPLATE("paper_orientation: every sampled pose of every certified box satisfies constraint 5", I,
                   CERTIPOSE_ORIENTATION_TEST_BACKENDS) {
    const auto cam = design_camera();
    const fov_frustum<I> frustum(cam);
    const paper_orientation policy;
    std::mt19937_64 rng(77);
    std::size_t with_box = 0, nominal_in = 0, candidate_has_nominal = 0, samples = 0, failures = 0, singular = 0;
    std::size_t certifications = 0;
    constexpr std::size_t scenarios = 240;
    for (std::size_t i = 0; i < scenarios; ++i) {
        const auto s = random_scenario<I>(rng, kind_of(i));
        const auto r = policy.orient(s.position, s.f, cam, 0.38);
        certifications += r.certifications;
        CHECK(r.boxes.size() <= 1);
        if (r.boxes.empty()) continue;
        ++with_box;
        CHECK(r.certifications >= 1);
        const auto& e = r.boxes[0];
        // Certified indeed, and the nominal aim is inside whenever the paper's box holds it.
        CHECK(certify_fov(s.position, e, s.f, frustum) != verdict::violated);
        const auto aim = nominal_aim(s.position, s.f);
        const std::array<double, 3> nominal{aim->phi, aim->gamma, aim->beta};
        const auto cand = paper_candidate(s.position, s.f, cam);
        REQUIRE(cand);
        if (contains(*cand, nominal)) {
            ++candidate_has_nominal;
            CHECK(contains(e, nominal));
        }
        if (contains(e, nominal)) ++nominal_in;
        if (kind_of(i) != aim_kind::general) ++singular;
        const auto c = sample(s.position, e, s.f, cam, 60, rng);
        samples += c.samples;
        failures += c.failures;
        CHECK_MESSAGE(c.failures == 0, "scenario " << i << ": " << c.failures << " sampled poses fail");
    }
    MESSAGE("paper_orientation: " << with_box << "/" << scenarios << " position boxes certified, nominal aim inside "
                                  << nominal_in << ", " << samples << " sampled poses, " << failures << " failures, "
                                  << double(certifications) / scenarios << " certifications per box");
    CHECK(failures == 0);
    CHECK(samples >= 10000);
    CHECK(with_box >= scenarios * 8 / 10);  // most random boxes get a certified aim
    CHECK(nominal_in >= with_box * 9 / 10);
    CHECK(singular >= 60);                  // straight down / up boxes are certified too
}

TEST_CASE_TEMPLATE("paper_orientation: the returned box contains the nominal aim and is wider than ε_o allows to stop",
                   I, CERTIPOSE_ORIENTATION_TEST_BACKENDS) {
    const auto cam = design_camera();
    const facet f = make_facet({0, 0, 0}, {0.03, 0, 0}, {0, 0.03, 0});
    position_box<I> p;
    p[0] = I(0.20, 0.25), p[1] = I(0.10, 0.15), p[2] = I(0.50, 0.55);
    const auto r = paper_orientation{}.orient(p, f, cam, 0.38);
    REQUIRE(r.boxes.size() == 1);
    const auto aim = nominal_aim(p, f);
    CHECK(contains(r.boxes[0], std::array<double, 3>{aim->phi, aim->gamma, 0.0}));
    // A 3 cm facet 0.6 m away: any roll, and aim tolerance of a few degrees at least.
    CHECK(width(r.boxes[0][2]) > 6.0);
    CHECK(width(r.boxes[0][1]) > 0.1);
    CHECK(width(r.boxes[0][0]) > 0.1);
    std::mt19937_64 rng(5);
    CHECK(sample(p, r.boxes[0], f, cam, 5000, rng).failures == 0);
    // A facet far too large for the field of view from there: nothing is certified.
    const facet big = make_facet({-0.5, -0.5, 0}, {0.5, -0.5, 0}, {0, 0.5, 0});
    CHECK(paper_orientation{}.orient(p, big, cam, 0.38).boxes.empty());
}

TEST_CASE_TEMPLATE("roll_arc: the whole circle only where every roll keeps the facet in the image", I,
                   CERTIPOSE_ORIENTATION_TEST_BACKENDS) {
    // roll_arc answers "every roll" from a cone bound, without walking the circle: checked here
    // by plain evaluation, every sampled position of the box at the nominal aim and any roll.
    const auto cam = design_camera();
    const fov_frustum<I> frustum(cam);
    std::mt19937_64 rng(31);
    std::size_t whole = 0, partial = 0, samples = 0, failures = 0;
    for (std::size_t i = 0; i < 300; ++i) {
        const auto s = random_scenario<I>(rng, kind_of(i), i % 2 ? 0.12 : 0.3);
        const auto aim = nominal_aim(s.position, s.f);
        REQUIRE(aim);
        const auto arc = detail::orientation::roll_arc(s.position, s.f, *aim, frustum);
        if (!arc) continue;
        const bool all = arc->first <= -3.14159 && arc->second >= 3.14159;
        (all ? whole : partial) += 1;
        orientation_box<I> rolls;
        rolls[0] = I(aim->phi), rolls[1] = I(aim->gamma), rolls[2] = I(arc->first, arc->second);
        const auto c = sample(s.position, rolls, s.f, cam, 200, rng);
        samples += c.samples;
        if (all) failures += c.failures;
        CHECK_MESSAGE((!all || c.failures == 0), "scenario " << i << ": " << c.failures << " rolls fail");
    }
    MESSAGE("roll_arc: " << whole << " whole circles, " << partial << " arcs, " << samples << " samples");
    CHECK(failures == 0);
    CHECK(whole >= 50);   // the shortcut is taken ...
    CHECK(partial >= 5);  // ... and the walk still runs where it must
}

TEST_CASE_TEMPLATE("paper_orientation: HC4 on [beta] never narrows the candidate past the roll arc", I,
                   CERTIPOSE_ORIENTATION_TEST_BACKENDS) {
    // Why `orient` leaves the paper's HC4 (and ACID) on [beta] out: on the candidate boxes of
    // random scenarios the contraction never changes what the roll arc alone gives, and the
    // orientation boxes are searched and certified from the candidate, so they would not change.
    const auto cam = design_camera();
    const fov_frustum<I> frustum(cam);
    std::mt19937_64 rng(78);
    std::size_t same = 0, both = 0;
    for (std::size_t i = 0; i < 120; ++i) {
        const auto s = random_scenario<I>(rng, kind_of(i));
        const auto a = paper_candidate(s.position, s.f, cam.fov_half_angles(), frustum, beta_contraction::none);
        const auto b = paper_candidate(s.position, s.f, cam.fov_half_angles(), frustum, beta_contraction::hc4);
        if (!a || !b) continue;
        ++both;
        same += *a == *b;
    }
    MESSAGE("HC4 on [beta]: " << same << " of " << both << " candidates identical with and without it");
    CHECK(both >= 80);
    CHECK(same == both);
}

TEST_CASE_TEMPLATE("paper_orientation: near the ZXZ singularity the boxes stay sound", I,
                   CERTIPOSE_ORIENTATION_TEST_BACKENDS) {
    const auto cam = design_camera();
    const facet f = make_facet({0, 0, 0}, {0.03, 0, 0}, {0, 0.03, 0});
    std::mt19937_64 rng(9);
    for (const double z : {0.6, -0.6}) {  // above (γ ≈ π) and below (γ ≈ 0) the facet
        for (const double dx : {0.0, 0.002, 0.02}) {
            position_box<I> p;
            p[0] = I(0.01 + dx - 0.01, 0.01 + dx + 0.01), p[1] = I(0.0, 0.02), p[2] = I(z - 0.01, z + 0.01);
            const auto r = paper_orientation{}.orient(p, f, cam, 0.38);
            REQUIRE(r.boxes.size() == 1);
            const auto& e = r.boxes[0];
            const auto aim = nominal_aim(p, f);
            CHECK(contains(e, std::array<double, 3>{aim->phi, aim->gamma, 0.0}));
            CHECK(sample(p, e, f, cam, 4000, rng).failures == 0);
            // At the pole φ hardly moves the axis: the certified φ range is wide.
            if (dx == 0.0) CHECK(width(e[0]) > 1.0);
        }
    }
}

TEST_CASE_TEMPLATE("paving_orientation: every VALID box passes the same sampling check", I,
                   CERTIPOSE_ORIENTATION_TEST_BACKENDS) {
    const auto cam = design_camera();
    const paving_orientation policy;
    std::mt19937_64 rng(31);
    std::size_t boxes = 0, samples = 0, failures = 0, with_box = 0;
    for (std::size_t i = 0; i < 3; ++i) {  // each paving certifies thousands of boxes
        const auto s = random_scenario<I>(rng, kind_of(i), 0.04);
        const auto r = policy.orient(s.position, s.f, cam, 0.25);
        CHECK(r.certifications >= r.boxes.size());
        if (!r.boxes.empty()) ++with_box;
        for (const auto& e : r.boxes) {
            ++boxes;
            const auto c = sample(s.position, e, s.f, cam, 20, rng);
            samples += c.samples;
            failures += c.failures;
        }
    }
    MESSAGE("paving_orientation: " << boxes << " VALID boxes, " << samples << " sampled poses, " << failures << " failures");
    CHECK(failures == 0);
    CHECK(with_box >= 2);
    CHECK(samples >= 2000);
}

/// Octant k of a position box (bit d of k: the upper half along dimension d).
template <class I>
position_box<I> octant(const position_box<I>& p, std::size_t k) {
    position_box<I> q;
    for (std::size_t d = 0; d < 3; ++d) {
        const double m = mid(p[d]);
        q[d] = (k >> d) & 1 ? I(m, upper(p[d])) : I(lower(p[d]), m);
    }
    return q;
}

TEST_CASE_TEMPLATE("paper_orientation: a hint changes how a box is found, never its proof", I,
                   CERTIPOSE_ORIENTATION_TEST_BACKENDS) {
    static_assert(HintedOrientationPolicy<paper_orientation, I, thin_lens_camera>);
    static_assert(!HintedOrientationPolicy<paving_orientation, I, thin_lens_camera>);
    static_assert(BorrowingOrientationPolicy<paper_orientation, I, thin_lens_camera>);
    static_assert(!BorrowingOrientationPolicy<paving_orientation, I, thin_lens_camera>);
    const auto cam = design_camera();
    const fov_frustum<I> frustum(cam);
    const paper_orientation policy;
    std::mt19937_64 rng(2026);
    std::size_t boxes = 0, hinted_found = 0, plain_found = 0, failures = 0, samples = 0;
    std::size_t hinted_certs = 0, plain_certs = 0;
    for (std::size_t i = 0; i < 60; ++i) {
        // A position box and its eight octants, in a row: the octants search from what the
        // searches before them found, as the small boxes of one cell of ε_p do in the solver.
        const auto s = random_scenario<I>(rng, kind_of(i));
        std::vector<position_box<I>> row{s.position};
        for (std::size_t k = 0; k < 8; ++k) row.push_back(octant(s.position, k));
        // Carried along the row, and hints that name nothing sensible (too wide, too narrow,
        // out of range, β narrower than φ and γ).
        paper_orientation::hint carried;
        const paper_orientation::hint odd[] = {{0.5, 1.0}, {1e-4, 1e-4}, {0.9, 2.0}, {0.3, 0.1}, {-1.0, 0.5}};
        for (std::size_t j = 0; j < row.size(); ++j) {
            paper_orientation::hint other = odd[(i + j) % std::size(odd)];
            const auto with_row = policy.orient(row[j], s.f, cam, 0.38, carried);
            const auto with_odd = policy.orient(row[j], s.f, cam, 0.38, other);
            const auto plain = policy.orient(row[j], s.f, cam, 0.38);
            ++boxes;
            hinted_certs += with_row.certifications, plain_certs += plain.certifications;
            hinted_found += !with_row.boxes.empty(), plain_found += !plain.boxes.empty();
            CHECK(carried.scale >= 0.0);
            CHECK(carried.scale <= 1.0);
            for (const auto* r : {&with_row, &with_odd}) {
                CHECK(r->boxes.size() <= 1);
                for (const auto& e : r->boxes) {
                    // Proven as the policy proves it (certify_fov, by tiles when one is not enough).
                    std::size_t n = 0;
                    CHECK(policy.certify_tiled(fov_position<I>(row[j], s.f), e, frustum, n));
                    const auto c = sample(row[j], e, s.f, cam, 40, rng);
                    samples += c.samples, failures += c.failures;
                }
            }
        }
    }
    MESSAGE("hinted rows: " << hinted_found << " / " << boxes << " boxes certified in " << hinted_certs
                            << " certifications; without hints " << plain_found << " in " << plain_certs);
    CHECK(failures == 0);
    CHECK(samples >= 20000);
    // What the hints are for: as many certified boxes (not the same ones: a hint's box is the
    // neighbour's scales around this box's aim) for fewer certifications (counts, not times).
    CHECK(hinted_found * 10 >= plain_found * 9);
    CHECK(hinted_certs < plain_certs);
}

TEST_CASE_TEMPLATE("paper_orientation: a borrowed hint is tried alone, and what it gives is proven", I,
                   CERTIPOSE_ORIENTATION_TEST_BACKENDS) {
    const paper_orientation policy, untiled(paper_orientation_options{.tiling_budget = 1});
    const std::size_t budget = policy.options().tiling_budget;
    const auto cam = design_camera();
    std::mt19937_64 rng(2027);
    const fov_frustum<I> frustum(cam);
    std::size_t tried = 0, found = 0, own_failed_borrowed_found = 0, failures = 0, samples = 0;
    std::size_t whole_found = 0, own_found = 0;
    for (std::size_t i = 0; i < 60; ++i) {
        // The hints two searches found for a box, lent to its octants (the solver lends the hints
        // of the cells around a box whose own search failed).
        const auto s = random_scenario<I>(rng, kind_of(i));
        paper_orientation::hint a, b;
        (void)policy.orient(s.position, s.f, cam, 0.38, a);
        position_box<I> half = s.position;
        half[0] = I(lower(s.position[0]), mid(s.position[0]));
        (void)policy.orient(half, s.f, cam, 0.38, b);
        const paper_orientation::hint empty{}, odd{0.3, 0.1};  // knows nothing; β narrower than φ, γ
        for (std::size_t k = 0; k < 8; ++k) {
            const position_box<I> q = octant(s.position, k);
            // Nothing usable to borrow: nothing, at no cost.
            const std::array<const paper_orientation::hint*, 3> useless{nullptr, &empty, &odd};
            const auto none = policy.orient_borrowed(q, s.f, cam, 0.38, std::span<const paper_orientation::hint* const>(useless));
            CHECK(none.boxes.empty());
            CHECK(none.certifications == 0);
            // A hint naming the paper's box itself (scale 1), which seldom certifies: that box
            // or nothing, never the narrower box a search would go on to find.
            const paper_orientation::hint whole{1.0, 1.0};
            const paper_orientation::hint* const w = &whole;
            const auto at_whole = policy.orient_borrowed(q, s.f, cam, 0.38, std::span<const paper_orientation::hint* const>(&w, 1));
            const auto cand = paper_candidate(q, s.f, cam, beta_contraction::none);
            for (const auto& e : at_whole.boxes) {
                REQUIRE(cand);
                for (std::size_t j = 0; j < 3; ++j) {
                    CHECK(std::abs(lower(e[j]) - lower((*cand)[j])) <= 1e-9);
                    CHECK(std::abs(upper(e[j]) - upper((*cand)[j])) <= 1e-9);
                }
            }
            whole_found += !at_whole.boxes.empty(), own_found += !policy.orient(q, s.f, cam, 0.38).boxes.empty();
            if (!(a.scale > 0.0) && !(b.scale > 0.0)) continue;
            const std::array<const paper_orientation::hint*, 4> lent{&a, nullptr, &b, &empty};
            const auto r = policy.orient_borrowed(q, s.f, cam, 0.38, std::span<const paper_orientation::hint* const>(lent));
            ++tried;
            // The widest usable hint alone gives the same answer: the others are not searched.
            const paper_orientation::hint* widest = a.scale >= b.scale ? &a : &b;
            const auto alone = policy.orient_borrowed(q, s.f, cam, 0.38, std::span<const paper_orientation::hint* const>(&widest, 1));
            CHECK(r.boxes == alone.boxes);
            CHECK(r.certifications == alone.certifications);
            // Its box (then one step wider), with β whole and then scaled: four tiled proofs at
            // most, so four evaluations when a proof may not tile; a search would spend more.
            CHECK(r.certifications <= 4 * budget);
            CHECK(untiled.orient_borrowed(q, s.f, cam, 0.38, std::span<const paper_orientation::hint* const>(lent))
                      .certifications <= 4);
            CHECK(r.boxes.size() <= 1);
            for (const auto& e : r.boxes) {
                ++found;
                std::size_t n = 0;
                CHECK(policy.certify_tiled(fov_position<I>(q, s.f), e, frustum, n));
                const auto c = sample(q, e, s.f, cam, 40, rng);
                samples += c.samples, failures += c.failures;
            }
            if (!r.boxes.empty() && policy.orient(q, s.f, cam, 0.38).boxes.empty()) ++own_failed_borrowed_found;
        }
    }
    MESSAGE("borrowed: " << found << " of " << tried << " boxes certified, " << own_failed_borrowed_found
                         << " of them where the box's own search found nothing; " << samples << " sampled poses");
    MESSAGE("the paper's box certified for " << whole_found << " octants, a search of their own for " << own_found);
    CHECK(failures == 0);
    CHECK(found > 0);
    CHECK(samples >= 40 * found);
    CHECK(whole_found < own_found);  // the check above saw searches it would have caught
}

TEST_CASE_TEMPLATE("paving_orientation finds what paper_orientation certifies (same facet, same position box)", I,
                   CERTIPOSE_ORIENTATION_TEST_BACKENDS) {
    const auto cam = design_camera();
    const facet f = make_facet({0, 0, 0}, {0.03, 0, 0}, {0, 0.03, 0});
    position_box<I> p;
    p[0] = I(0.20, 0.22), p[1] = I(0.10, 0.12), p[2] = I(0.50, 0.52);
    const auto paper = paper_orientation{}.orient(p, f, cam, 0.38);
    const auto paved = paving_orientation{}.orient(p, f, cam, 0.38);
    REQUIRE(paper.boxes.size() == 1);
    REQUIRE(!paved.boxes.empty());
    CHECK(paved.certifications > paper.certifications);
    // The paving's VALID boxes are certified on their own; the nominal aim's direction is
    // covered at the paving's resolution: some VALID box has an axis within 0.4 rad of it.
    const auto aim = nominal_aim(p, f);
    bool near = false;
    for (const auto& e : paved.boxes) {
        const double dg = std::abs(mid(e[1]) - aim->gamma);
        if (dg < 0.4) near = true;
    }
    CHECK(near);
}

#ifndef CERTIPOSE_ORIENTATION_TYPED_ONLY

TEST_CASE("orientation: bad input throws naming the field, degenerate input is harmless") {
    using I = boost_interval;
    const auto cam = design_camera();
    const facet f = make_facet({0, 0, 0}, {0.03, 0, 0}, {0, 0.03, 0});
    position_box<I> p;
    p[0] = I(0.2, 0.25), p[1] = I(0.1, 0.15), p[2] = I(0.5, 0.55);
    const auto field_of = [](auto&& call) {
        try {
            call();
        } catch (const certipose::invalid_argument& e) {
            return e.field();
        }
        return std::string("<nothing thrown>");
    };
    for (const double eps : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
        CHECK(field_of([&] { (void)paper_orientation{}.orient(p, f, cam, eps); }) == "orientation_eps");
        CHECK(field_of([&] { (void)paving_orientation{}.orient(p, f, cam, eps); }) == "orientation_eps");
    }
    position_box<I> unbounded = p;
    unbounded[0] = I(0.2, std::numeric_limits<double>::infinity());
    CHECK(field_of([&] { (void)paper_orientation{}.orient(unbounded, f, cam, 0.38); }) == "position_box");
    facet nan_facet = f;
    nan_facet.v[1].x() = std::numeric_limits<double>::quiet_NaN();
    CHECK(field_of([&] { (void)paper_orientation{}.orient(p, nan_facet, cam, 0.38); }) == "facet");
    Eigen::Matrix3d bad_k = cam.intrinsics();
    bad_k(2, 2) = 2.0;
    CHECK(field_of([&] { fov_frustum<I>(bad_k, 2448, 2048); }) == "K");
    CHECK(field_of([&] { fov_frustum<I>(cam.intrinsics(), 0.0, 2048); }) == "width_px");
    CHECK(field_of([&] { fov_frustum<I>(cam.intrinsics(), 2448, -1.0); }) == "height_px");
    Eigen::Matrix3d singular_k = Eigen::Matrix3d::Zero();
    singular_k(2, 2) = 1.0;
    CHECK(field_of([&] { fov_frustum<I>(singular_k, 2448, 2048); }) == "K");
    CHECK(field_of([] { paper_orientation(paper_orientation_options{.tiling_budget = 0}); }) == "tiling_budget");
    for (const double v : {-1e-9, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
        CHECK(field_of([&] { paper_orientation(paper_orientation_options{.refine_min_fraction = v}); }) == "refine_min_fraction");
    CHECK(field_of([] { paving_orientation(paving_orientation_options{.max_boxes = 0}); }) == "max_boxes");

    // Empty boxes: nothing to certify, no exception.
    const auto empty_box = position_box<I>::empty();
    CHECK(paper_orientation{}.orient(empty_box, f, cam, 0.38).boxes.empty());
    CHECK(paving_orientation{}.orient(empty_box, f, cam, 0.38).boxes.empty());
    const fov_frustum<I> frustum(cam);
    orientation_box<I> e;
    e[0] = I(0.0, 0.1), e[1] = I(2.0, 2.1), e[2] = I(-0.1, 0.1);
    CHECK(certify_fov(empty_box, e, f, frustum) == verdict::violated);
    orientation_box<I> unbounded_e = e;
    unbounded_e[2] = I(-std::numeric_limits<double>::infinity(), 0.0);
    CHECK(certify_fov(p, unbounded_e, f, frustum) == verdict::undecided);
    // A position box containing a vertex: never certified, never a crash.
    position_box<I> on_vertex;
    on_vertex[0] = I(-0.01, 0.01), on_vertex[1] = I(-0.01, 0.01), on_vertex[2] = I(-0.01, 0.01);
    CHECK(certify_fov(on_vertex, e, f, frustum) != verdict::satisfied);
    CHECK(paper_orientation{}.orient(on_vertex, f, cam, 0.38).boxes.empty());
    // A position box whose centre is the centroid has no nominal aim.
    position_box<I> at_centroid;
    for (std::size_t j = 0; j < 3; ++j) at_centroid[j] = I(f.centroid[static_cast<int>(j)]);
    CHECK(!nominal_aim(at_centroid, f));
    CHECK(paper_orientation{}.orient(at_centroid, f, cam, 0.38).boxes.empty());
}

TEST_CASE("fov_frustum: cones of the case-study camera") {
    using I = boost_interval;
    const auto cam = design_camera();
    const fov_frustum<I> frustum(cam);
    // Inscribed cone: half the image height over f_px; circumscribed: half the diagonal.
    const double f_px = 0.012 / 3.45e-6;
    CHECK(frustum.inner_half_angle() <= std::atan(1024 / f_px));
    CHECK(frustum.inner_half_angle() > std::atan(1024 / f_px) - 1e-9);
    CHECK(frustum.outer_half_angle() >= std::atan(std::hypot(1224.0, 1024.0) / f_px));
    CHECK(frustum.outer_half_angle() < std::atan(std::hypot(1224.0, 1024.0) / f_px) + 1e-9);
    // Every side encloses the exact vector for the given K, w, h.
    const Eigen::Matrix3d k = cam.intrinsics();
    CHECK(contains(frustum.sides()[1].l[2], 2448 - k(0, 2)));
    CHECK(contains(frustum.sides()[3].l[1], -k(1, 1)));
}

TEST_CASE("frustum_of: one frustum per camera in a row, rebuilt when the camera changes") {
    using I = boost_interval;
    const auto a = design_camera();
    const user_camera b;
    const auto same = [](const fov_frustum<I>& x, const fov_frustum<I>& y) {
        for (std::size_t s = 0; s < 4; ++s)
            for (std::size_t j = 0; j < 3; ++j)
                if (!(lower(x.sides()[s].l[j]) == lower(y.sides()[s].l[j]) && upper(x.sides()[s].l[j]) == upper(y.sides()[s].l[j])))
                    return false;
        return x.inner_half_angle() == y.inner_half_angle() && x.outer_half_angle() == y.outer_half_angle();
    };
    for (int round = 0; round < 3; ++round) {
        CHECK(same(frustum_of<I>(a), fov_frustum<I>(a)));
        CHECK(same(frustum_of<I>(a), fov_frustum<I>(a)));
        CHECK(same(frustum_of<I>(b), fov_frustum<I>(b)));
        CHECK(!same(frustum_of<I>(a), fov_frustum<I>(b)));
    }
    // A bad camera throws every time, and the good one after it is still right.
    struct nan_camera : user_camera {
        Eigen::Matrix3d intrinsics() const {
            Eigen::Matrix3d k = user_camera::intrinsics();
            k(0, 2) = std::numeric_limits<double>::quiet_NaN();
            return k;
        }
    };
    CHECK_THROWS_AS(frustum_of<I>(nan_camera{}), certipose::invalid_argument);
    CHECK_THROWS_AS(frustum_of<I>(nan_camera{}), certipose::invalid_argument);
    CHECK(same(frustum_of<I>(b), fov_frustum<I>(b)));
}

#endif  // CERTIPOSE_ORIENTATION_TYPED_ONLY

}  // namespace
