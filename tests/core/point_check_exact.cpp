// The sampling check (verify/point_check.hpp) decides close calls exactly (verify/exact_check.hpp):
// a sight line grazing an edge by less than rounding is judged by where it really passes; a
// distance a fraction of an ulp below d_min and a vertex a few ulps outside the image are
// violations; a pose exactly on a boundary the 256-bit enclosure cannot resolve is judged as
// the constraint is written and counted; an ordinary pose never needs the exact path. The
// expected answers come from separate rational computations here (a crossing point and its
// barycentric coordinates, a squared distance) or from cos 1 to 60 digits.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <vector>

#include <gmpxx.h>

#include <certipose/camera.hpp>
#include <certipose/geometry/sample_part.hpp>
#include <certipose/verify/point_check.hpp>

using namespace certipose;
using Eigen::Vector3d;

namespace {

using tri = std::array<Vector3d, 3>;

std::array<mpq_class, 3> rational(const Vector3d& p) { return {mpq_class(p.x()), mpq_class(p.y()), mpq_class(p.z())}; }

std::array<mpq_class, 3> minus(const std::array<mpq_class, 3>& a, const std::array<mpq_class, 3>& b) {
    return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
std::array<mpq_class, 3> cross(const std::array<mpq_class, 3>& a, const std::array<mpq_class, 3>& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
mpq_class dot(const std::array<mpq_class, 3>& a, const std::array<mpq_class, 3>& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// The segment's crossing with t's plane, by its parameter, and the smallest barycentric
/// coordinate of the crossing point: an independent answer to "does (p, q) meet t".
struct crossing {
    mpq_class parameter, min_bary;
    bool meets() const { return parameter > 0 && parameter < 1 && min_bary >= 0; }
};
crossing cross_plane(const Vector3d& p, const Vector3d& q, const tri& t) {
    const auto P = rational(p), Q = rational(q), A = rational(t[0]), B = rational(t[1]), C = rational(t[2]);
    const auto n = cross(minus(B, A), minus(C, A));
    const mpq_class dp = dot(n, minus(P, A)), dq = dot(n, minus(Q, A)), nn = dot(n, n);
    const mpq_class s = dp / (dp - dq);
    std::array<mpq_class, 3> X;
    for (int k = 0; k < 3; ++k) X[k] = P[k] + s * (Q[k] - P[k]);
    const mpq_class b0 = dot(n, cross(minus(C, B), minus(X, B))) / nn, b1 = dot(n, cross(minus(A, C), minus(X, C))) / nn;
    const mpq_class b2 = 1 - b0 - b1;
    return {s, std::min({b0, b1, b2})};
}

triangle_mesh one_triangle(const tri& v) { return triangle_mesh({v[0], v[1], v[2]}, {{0, 1, 2}}); }

double ulps_up(double x, int n) {
    for (int i = 0; i < n; ++i) x = std::nextafter(x, INFINITY);
    return x;
}

}  // namespace

TEST_CASE("a sight line grazing a blocker's edge is judged by where it really passes") {
    const tri t{Vector3d(0.1, 0.2, 0.3), Vector3d(1.3, 0.1, 0.2), Vector3d(0.4, 1.1, 0.25)};
    // Aimed at a point of the edge t0–t1 and moved by a few ulps (found by a search against the
    // rational answer): the first misses t, the second meets it, each by less than 1e-15 of
    // the barycentric coordinates.
    const Vector3d miss_p(0x1.e0edcc1206968p-4, 0x1.e60acea8f4698p-1, 0x1.c11f6531eb66ep+0);
    const Vector3d miss_q(0x1.d8d11af3f08b7p+0, -0x1.648577f1cc929p-1, -0x1.4d2986a32448p+0);
    const Vector3d hit_p(0x1.00088c2eb295ap-1, 0x1.48c54361cfe89p-1, 0x1.aabe336043197p+0);
    const Vector3d hit_q(0x1.a50993ef8059ep-3, -0x1.2317044ab8431p-2, -0x1.1bee1f8ed602dp+0);

    const crossing miss = cross_plane(miss_p, miss_q, t), hit = cross_plane(hit_p, hit_q, t);
    REQUIRE(miss.parameter > 0);
    REQUIRE(miss.parameter < 1);
    REQUIRE(miss.min_bary < 0);
    REQUIRE(miss.min_bary > -1e-12);
    REQUIRE(hit.meets());
    REQUIRE(hit.min_bary < 1e-15);

    // Plain doubles get one of them wrong whichever slack is chosen.
    CHECK(verify::segment_hits_triangle(miss_p, miss_q, t, 1e-9, 0.0));     // invents a hit
    CHECK_FALSE(verify::segment_hits_triangle(hit_p, hit_q, t, 1e-9, 1e-9));  // forgives one

    verify::exact_stats stats;
    CHECK_FALSE(verify::segment_meets_triangle(miss_p, miss_q, t, &stats));
    CHECK(stats.exact > 0);
    const std::size_t after_miss = stats.exact;
    CHECK(verify::segment_meets_triangle(hit_p, hit_q, t, &stats));
    CHECK(stats.exact > after_miss);
    CHECK(stats.undecidable == 0);

    // The same through the scene API, which the checks use.
    verify::occluders scene;
    scene.triangles.push_back(t);
    CHECK_FALSE(scene.blocks(miss_p, miss_q));
    CHECK(scene.blocks(hit_p, hit_q));

    // Through an edge or a vertex exactly, the sight line touches the blocker: blocked. Ending on
    // it (a neighbour of the facet, at the sight line's target) is not.
    const tri flat{Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0)};
    CHECK(verify::segment_meets_triangle(Vector3d(0.25, -0.25, 1), Vector3d(0.25, 0.25, -1), flat));
    CHECK(verify::segment_meets_triangle(Vector3d(-0.5, -0.5, 1), Vector3d(0.5, 0.5, -1), flat));
    CHECK_FALSE(verify::segment_meets_triangle(Vector3d(0.25, 0.25, 1), Vector3d(0.25, 0.25, 0), flat));
    CHECK_FALSE(verify::segment_meets_triangle(Vector3d(0.25, 0.25, 1), Vector3d(0.5, 0, 0), flat));
    // In the blocker's plane: the open segment crossing it meets it, one ending at its edge does not.
    CHECK(verify::segment_meets_triangle(Vector3d(-1, 0.25, 0), Vector3d(2, 0.25, 0), flat));
    CHECK_FALSE(verify::segment_meets_triangle(Vector3d(-1, 0.25, 0), Vector3d(0, 0.25, 0), flat));
}

TEST_CASE("a distance to the facet below d_min by less than an ulp is a focus violation") {
    const tri v{Vector3d(0.1, 0.2, 0.3), Vector3d(1.3, 0.1, 0.2), Vector3d(0.4, 1.1, 0.25)};
    const triangle_mesh mesh = one_triangle(v);
    const facet& f = mesh.facet(0);
    // Beside vertex v1, in its region of the triangle (nearest point v1), found by a search.
    const Vector3d p(-0x1.a6b2142f38b5p-6, 0x1.98c242199b344p-4, 0x1.1b4307badeb5cp-1);
    const auto P = rational(p), A = rational(v[0]);
    REQUIRE(dot(minus(P, A), minus(rational(v[1]), A)) <= 0);
    REQUIRE(dot(minus(P, A), minus(rational(v[2]), A)) <= 0);
    const mpq_class dist2 = dot(minus(P, A), minus(P, A));

    // d_min as plain doubles compute the distance: they see no violation, but it is one.
    const double d_min = verify::point_triangle_distance(p, f.v);
    REQUIRE(dist2 < mpq_class(d_min) * mpq_class(d_min));
    REQUIRE_FALSE(verify::point_triangle_distance(p, f.v) < d_min);
    verify::exact_stats stats;
    const auto v0 = verify::check_position(p, f, d_min, 10.0, -1.0, nullptr, {}, {}, &stats);
    CHECK(v0.focus);
    CHECK(stats.exact > 0);

    // Three ulps further: the old tolerance of 1e-9 forgives it, the exact check does not.
    const double d_min3 = ulps_up(d_min, 3);
    CHECK_FALSE(verify::check_position(p, f, d_min3, 10.0, -1.0, nullptr, {}, {1e-9}).focus);
    CHECK(verify::check_position(p, f, d_min3, 10.0, -1.0).focus);

    // Nothing is invented either: the next double below the distance is a d_min it satisfies.
    const double below = std::nextafter(d_min, 0.0);
    REQUIRE(dist2 >= mpq_class(below) * mpq_class(below));
    CHECK_FALSE(verify::check_position(p, f, below, 10.0, -1.0).focus);
}

TEST_CASE("a facet vertex projecting a few ulps outside the image is a field-of-view violation") {
    // Camera at the origin tilted by γ = 1 rad: the vertex (x, 0, 1) has q_c = (x, sin 1, cos 1)
    // and u = 1000 x / cos 1 + 500, so u ≤ w = 1000 iff x ≤ cos(1)/2
    // = 0.270151152934069858700468303721488301866155...; the doubles below are 3 ulps either side.
    const double out3 = 0x1.14a280fb5068ep-2, in3 = 0x1.14a280fb50689p-2;
    verify::camera_view cam{Eigen::Matrix3d::Zero(), 1000, 2000, 0.1, 10.0};
    cam.K << 1000, 0, 500, 0, 1000, 0, 0, 0, 1;
    const verify::pose x{Vector3d::Zero(), 0.0, 1.0, 0.0};
    const auto facet_at = [](double edge_x) {
        return one_triangle({Vector3d(edge_x, 0, 1), Vector3d(0.2, -0.1, 1), Vector3d(0.1, 0.1, 1)});
    };
    const triangle_mesh outside = facet_at(out3), inside = facet_at(in3);

    verify::exact_stats stats;
    CHECK_FALSE(verify::fov_ok(x, outside.facet(0), cam, {}, &stats));
    CHECK(stats.exact > 0);
    CHECK(verify::fov_ok(x, inside.facet(0), cam, {}, &stats));
    CHECK(stats.undecidable == 0);
    CHECK(verify::fov_ok(x, outside.facet(0), cam, {1e-9}));  // what the old tolerance said

    // On the image edge exactly, with φ = −β so that R is the identity but the enclosure of the
    // rotation is not a point: undecidable, and inside, as 0 ≤ u ≤ w is written.
    cam.K << 1000, 0, 500, 0, 1000, 500, 0, 0, 1;
    const verify::pose turned{Vector3d::Zero(), 0.5, 0.0, -0.5};
    const triangle_mesh on_edge = one_triangle({Vector3d(0.5, 0, 1), Vector3d(0.1, 0.1, 1), Vector3d(0, -0.1, 1)});
    verify::exact_stats edge_stats;
    CHECK(verify::fov_ok(turned, on_edge.facet(0), cam, {}, &edge_stats));
    CHECK(edge_stats.undecidable > 0);
}

TEST_CASE("ordinary poses never need the exact decision, the counter counts the close calls") {
    const sample_part part = make_sample_part();
    const thin_lens_camera camera(thin_lens_parameters{.focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6,
                                                       .max_blur_circle = 6.9e-6, .pixel_pitch = 3.45e-6,
                                                       .width_px = 2448, .height_px = 2048});
    const auto range = camera.distance_range();
    const double min_view_angle = 0.35;
    const std::size_t id = part.facet_of_interest;
    const facet& f = part.mesh.facet(id);
    const auto truth = verify::sample_valid_positions(part.mesh, id, range.min, range.max, min_view_angle, 10, 11);
    REQUIRE(truth.valid.size() == 10);
    const auto scene = verify::occluders::of(part.mesh, id);
    const auto targets = verify::facet_targets(f);
    const verify::camera_view view{camera.intrinsics(), camera.width_px(), camera.height_px(), range.min, range.max};
    for (const Vector3d& p : truth.valid) {
        // Aimed at the centroid: R·ẑ = (sin φ sin γ, −cos φ sin γ, cos γ).
        const Vector3d a = (f.centroid - p).normalized();
        const verify::pose x{p, std::atan2(a.x(), -a.y()), std::acos(a.z()), 0.0};
        verify::exact_stats stats;
        const auto v = verify::check_pose(x, f, view, min_view_angle, &scene, targets, {}, &stats);
        CAPTURE(p.transpose());
        CHECK_MESSAGE(!v.any(), v.describe());
        CHECK(stats.exact == 0);
    }
    // A close call through the same API counts: a position d_min − (a fraction of an ulp) from
    // the facet's plane, straight above its centroid along the unit normal is not exact in
    // doubles, so take the distance plain doubles compute for it.
    const Vector3d above = f.centroid + range.min * 1.5 * f.normal;
    const double d = verify::point_triangle_distance(above, f.v);
    verify::exact_stats stats;
    (void)verify::check_position(above, f, d, range.max, 0.0, nullptr, {}, {}, &stats);
    CHECK(stats.exact > 0);
}
