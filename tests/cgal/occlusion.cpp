// Tests of the occlusion policies (certipose/occlusion/): the sight hull against CGAL's exact
// hull, the fast per-triangle decisions of aabb_occlusion against its exact rational clip,
// small hand-made scenes with known answers, nearly coplanar configurations, the paper's
// Figure 5 experiment on the sample part and the same on two real meshes. Every VISIBLE and
// OCCLUDED answer of either policy is confirmed by sampling segments between random box points
// and random facet points with plain double ray–triangle tests (VISIBLE ⇒ none blocked,
// OCCLUDED ⇒ all blocked), and the two policies must never contradict each other.
//
// Runtime: the boolean policy costs milliseconds per box (several times more in Debug), so
// Debug builds (no NDEBUG) run it on a deterministic subset of facets (every 47th in Figure 5,
// every 211th on the real meshes, one box of three in the grazing test), use two boxes per real
// mesh instead of four and sample 100 segments per answer (20 on the real meshes) instead of
// 1000. Release runs the
// boolean on every Figure 5 facet and on every 29th facet of the real meshes.

#include <certipose/geometry/sample_part.hpp>
#include <certipose/interval/boost_interval.hpp>
#include <certipose/interval/cgal_interval.hpp>
#include <certipose/io/read_mesh.hpp>
#include <certipose/occlusion/cgal_aabb_occlusion.hpp>
#include <certipose/occlusion/cgal_boolean_occlusion.hpp>
#include <certipose/occlusion/cgal_resting_contact.hpp>  // this program's one definition
#include <certipose/occlusion/concept.hpp>
#include <certipose/occlusion/no_occlusion.hpp>

#include <doctest/doctest.h>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Intersections_3/Iso_cuboid_3_Segment_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

// This TU also holds this program's one copy of the CGAL code behind certipose's non-template
// functions (tests/CMakeLists.txt: CERTIPOSE_PRECOMPILED_DEFINITIONS here, declarations only in
// the others), and so the boolean policy's, which the others see declared only too.
#if !CERTIPOSE_DETAIL_WITH_DEFINITIONS
#error "tests/cgal/occlusion.cpp must be compiled with CERTIPOSE_PRECOMPILED_DEFINITIONS (tests/CMakeLists.txt)"
#endif
template class certipose::basic_boolean_occlusion<void>;

using namespace certipose;
using V = Eigen::Vector3d;
using box3 = Eigen::AlignedBox3d;

template <>
struct doctest::StringMaker<certipose::visibility> {
    static doctest::String convert(certipose::visibility v) {
        return doctest::String(std::string(certipose::to_string(v)).c_str());
    }
};

static_assert(OcclusionPolicy<no_occlusion, boost_interval>);
static_assert(OcclusionPolicy<aabb_occlusion, boost_interval>);
static_assert(RefutingOcclusionPolicy<aabb_occlusion>);
static_assert(!RefutingOcclusionPolicy<no_occlusion>);
static_assert(OcclusionPolicy<aabb_occlusion, cgal_interval>);
static_assert(OcclusionPolicy<boolean_occlusion, boost_interval>);
static_assert(OcclusionPolicy<boolean_occlusion, cgal_interval>);
static_assert(!OcclusionPolicy<int, boost_interval>);

namespace {

#ifdef NDEBUG
constexpr bool debug_build = false;
constexpr int samples_per_answer = 1000;
#else
constexpr bool debug_build = true;
constexpr int samples_per_answer = 100;
#endif

// ---- small scenes --------------------------------------------------------------------------

/// Closed outward box [lo, hi] as 12 triangles.
triangle_mesh cuboid(const V& lo, const V& hi) {
    std::vector<V> v;
    for (int k = 0; k < 8; ++k) v.emplace_back(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z());
    std::vector<face_indices> f{{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6},   // z−, z+
                                {0, 1, 5}, {0, 5, 4}, {2, 6, 7}, {2, 7, 3},   // y−, y+
                                {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};  // x−, x+
    return triangle_mesh(std::move(v), std::move(f));
}

/// Index of the face of `m` whose vertices are exactly a, b, c in some rotation.
std::size_t face_with(const triangle_mesh& m, const V& a, const V& b, const V& c) {
    for (std::size_t i = 0; i < m.num_faces(); ++i) {
        const auto& F = m.facet(i);
        for (int r = 0; r < 3; ++r)
            if (F.v[r] == a && F.v[(r + 1) % 3] == b && F.v[(r + 2) % 3] == c) return i;
    }
    FAIL("no such face");
    return 0;
}

triangle_mesh transformed(const triangle_mesh& m, const Eigen::Matrix3d& R, const V& t) {
    std::vector<V> v;
    for (const V& p : m.vertices()) v.push_back(R * p + t);
    return triangle_mesh(std::move(v), m.faces());
}

// ---- sampled confirmation (plain double) -----------------------------------------------------

/// Segment p → q against a triangle, Möller–Trumbore in double. `margin` > 0 counts only clear
/// hits (barycentrics and the segment parameter at least `margin` inside): a VISIBLE answer must
/// have none. `margin` < 0 counts near misses too: an OCCLUDED answer must have all blocked.
bool segment_hits(const V& pv, const V& qv, const std::array<V, 3>& t, double margin) {
    // Plain arrays: Eigen expressions are slow without optimisation (Debug runs).
    const double p[3] = {pv.x(), pv.y(), pv.z()}, q[3] = {qv.x(), qv.y(), qv.z()};
    const double* a0 = t[0].data();
    const double* a1 = t[1].data();
    const double* a2 = t[2].data();
    const double d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    const double e1[3] = {a1[0] - a0[0], a1[1] - a0[1], a1[2] - a0[2]};
    const double e2[3] = {a2[0] - a0[0], a2[1] - a0[1], a2[2] - a0[2]};
    const auto cross = [](const double* x, const double* y, double* out) {
        out[0] = x[1] * y[2] - x[2] * y[1], out[1] = x[2] * y[0] - x[0] * y[2], out[2] = x[0] * y[1] - x[1] * y[0];
    };
    const auto dot = [](const double* x, const double* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
    double h[3];
    cross(d, e2, h);
    const double a = dot(e1, h);
    if (std::abs(a) < 1e-300) return false;  // parallel: a grazing touch, not a clear hit
    const double f = 1 / a;
    const double s[3] = {p[0] - a0[0], p[1] - a0[1], p[2] - a0[2]};
    const double u = f * dot(s, h);
    if (u < margin || u > 1 - margin) return false;
    double qq[3];
    cross(s, e1, qq);
    const double v = f * dot(d, qq);
    if (v < margin || u + v > 1 - margin) return false;
    const double tt = f * dot(e2, qq);
    const double tm = std::max(margin, 1e-9);  // open segment: the facet point q itself excluded
    return tt > tm && tt < 1 - tm;
}

/// Scene triangles in an AABB tree used only as a broad phase; the narrow phase is
/// segment_hits. Independent of the policies' exact machinery.
class segment_sampler {
public:
    explicit segment_sampler(const std::vector<const triangle_mesh*>& scene) {
        for (const auto* m : scene)
            for (const auto& f : m->facets()) tris_.push_back({f.v[0], f.v[1], f.v[2]});
        using P = K::Point_3;
        for (const auto& t : tris_)
            cg_.emplace_back(P(t[0].x(), t[0].y(), t[0].z()), P(t[1].x(), t[1].y(), t[1].z()),
                             P(t[2].x(), t[2].y(), t[2].z()));
        tree_.rebuild(cg_.cbegin(), cg_.cend());
    }

    /// Number of blocked segments among n random (box point, facet point) pairs.
    int blocked(const box3& box, std::size_t facet, int n, double margin, std::mt19937_64& rng) const {
        std::uniform_real_distribution<double> U(0, 1);
        const auto& F = tris_[facet];
        int count = 0;
        for (int s = 0; s < n; ++s) {
            V p;
            for (int k = 0; k < 3; ++k) p[k] = box.min()[k] + U(rng) * (box.max()[k] - box.min()[k]);
            double a = U(rng), b = U(rng);
            if (a + b > 1) a = 1 - a, b = 1 - b;
            const V q = F[0] + a * (F[1] - F[0]) + b * (F[2] - F[0]);
            traversal tr{*this, p, q, facet, margin};
            tree_.traversal(0, tr);
            count += tr.hit;
        }
        return count;
    }

private:
    using K = CGAL::Exact_predicates_inexact_constructions_kernel;
    using prim = CGAL::AABB_triangle_primitive<K, std::vector<K::Triangle_3>::const_iterator>;
    using tree = CGAL::AABB_tree<CGAL::AABB_traits<K, prim>>;

    struct traversal {
        const segment_sampler& s;
        V p, q;
        std::size_t skip;
        double margin;
        bool hit = false;
        bool go_further() const { return !hit; }
        template <class Prim>
        void intersection(int, const Prim& pr) {
            const auto i = static_cast<std::size_t>(pr.id() - s.cg_.begin());
            if (i != skip && segment_hits(p, q, s.tris_[i], margin)) hit = true;
        }
        template <class Node>
        bool do_intersect(int, const Node& node) const {  // slab test, box grown by 1e-9
            const auto& b = node.bbox();
            const std::array<double, 3> lo{b.xmin() - 1e-9, b.ymin() - 1e-9, b.zmin() - 1e-9};
            const std::array<double, 3> hi{b.xmax() + 1e-9, b.ymax() + 1e-9, b.zmax() + 1e-9};
            double t0 = 0, t1 = 1;
            for (int k = 0; k < 3; ++k) {
                const double d = q[k] - p[k];
                if (d == 0) {
                    if (p[k] < lo[k] || p[k] > hi[k]) return false;
                    continue;
                }
                double a = (lo[k] - p[k]) / d, c = (hi[k] - p[k]) / d;
                if (a > c) std::swap(a, c);
                t0 = std::max(t0, a), t1 = std::min(t1, c);
                if (t0 > t1) return false;
            }
            return true;
        }
    };

    std::vector<std::array<V, 3>> tris_;
    std::vector<K::Triangle_3> cg_;
    tree tree_;
};

/// Checks one answer against sampling; returns false (and reports) on a refutation.
bool confirmed(const segment_sampler& S, const box3& box, std::size_t facet, visibility v,
               std::mt19937_64& rng, const char* who, int n = samples_per_answer) {
    if (v == visibility::partial) return true;
    const int b = S.blocked(box, facet, n, v == visibility::visible ? 1e-9 : -1e-9, rng);
    const bool ok = v == visibility::visible ? b == 0 : b == n;
    if (!ok)
        MESSAGE(who << " said " << to_string(v) << " for facet " << facet << " but " << b << "/" << n
                    << " sampled sight lines are blocked");
    return ok;
}

bool contradict(visibility a, visibility b) {
    return (a == visibility::visible && b == visibility::occluded) ||
           (a == visibility::occluded && b == visibility::visible);
}

/// Runs both policies on every facet (boolean on every `boolean_stride`-th facet), checks
/// sampling and contradictions, returns the table text.
struct experiment_result {
    std::array<std::size_t, 3> fast{}, exact{};
    std::size_t exact_runs = 0, refuted = 0, contradictions = 0;
    std::string table() const {
        std::ostringstream o;
        o << "             visible  partial  occluded\n"
          << "  aabb      " << fast[0] << "  " << fast[1] << "  " << fast[2] << "   (all facets)\n"
          << "  boolean   " << exact[0] << "  " << exact[1] << "  " << exact[2] << "   (" << exact_runs
          << " facets)";
        return o.str();
    }
};

/// The policies and the sampler of one scene, built once.
struct scene_tools {
    aabb_occlusion fast;
    boolean_occlusion exact;
    segment_sampler sampler;
    explicit scene_tools(const triangle_mesh& part) : fast(part), exact(part), sampler({&part}) {}
};

experiment_result run_experiment(const triangle_mesh& part, const scene_tools& tools, const box3& box,
                                 std::size_t boolean_stride, std::mt19937_64& rng,
                                 int samples = samples_per_answer) {
    experiment_result r;
    for (std::size_t f = 0; f < part.num_faces(); ++f) {
        const visibility a = tools.fast.classify(box, f);
        ++r.fast[static_cast<int>(a)];
        r.refuted += !confirmed(tools.sampler, box, f, a, rng, "aabb_occlusion", samples);
        if (f % boolean_stride != 0) continue;
        const visibility b = tools.exact.classify(box, f);
        ++r.exact[static_cast<int>(b)], ++r.exact_runs;
        if (b != a) r.refuted += !confirmed(tools.sampler, box, f, b, rng, "boolean_occlusion", samples);
        if (contradict(a, b)) {
            ++r.contradictions;
            MESSAGE("facet " << f << ": aabb " << to_string(a) << ", boolean " << to_string(b));
        }
    }
    return r;
}

box3 cube_at(const V& centre, double side) {
    return box3(centre - V::Constant(side / 2), centre + V::Constant(side / 2));
}

}  // namespace

// ---- the sight hull --------------------------------------------------------------------------

namespace {

using detail::occ::pt;

pt to_pt(const V& v) { return {v.x(), v.y(), v.z()}; }

/// Our hull planes against CGAL's exact hull: all 11 points inside every plane (so each plane
/// supports H), and each face of CGAL's hull lies in one of our planes (so nothing is missing).
void check_hull(const box3& b, const std::array<V, 3>& f) {
    using EK = CGAL::Exact_predicates_exact_constructions_kernel;
    detail::occ::sight_hull H;
    const std::array<pt, 3> fp{to_pt(f[0]), to_pt(f[1]), to_pt(f[2])};
    detail::occ::build_sight_hull(to_pt(b.min()), to_pt(b.max()), fp, H);
    for (std::size_t p = 0; p < H.num_planes; ++p)
        for (const pt& x : H.pts) REQUIRE(detail::occ::side(H.planes[p], x) <= 0);
    std::vector<EK::Point_3> pts;
    for (const pt& x : H.pts) pts.emplace_back(x[0], x[1], x[2]);
    CGAL::Surface_mesh<EK::Point_3> hull;
    CGAL::convex_hull_3(pts.begin(), pts.end(), hull);
    const auto to_double = [](const EK::Point_3& p) {
        return pt{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
    };
    for (auto face : hull.faces()) {
        std::array<pt, 3> t;
        int k = 0;
        for (auto v : CGAL::vertices_around_face(hull.halfedge(face), hull)) t[k++] = to_double(hull.point(v));
        bool found = false;
        for (std::size_t p = 0; p < H.num_planes && !found; ++p)
            found = detail::occ::side(H.planes[p], t[0]) == 0 && detail::occ::side(H.planes[p], t[1]) == 0 &&
                    detail::occ::side(H.planes[p], t[2]) == 0;
        REQUIRE(found);
    }
}

}  // namespace

TEST_CASE("sight hull planes equal CGAL's exact hull, also on degenerate and nearly coplanar input") {
    const detail::round_to_nearest_scope nearest;
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> U(-1, 1);
    const std::array<V, 3> flat{V(0, 0, 0), V(0.3, 0.05, 0), V(0.1, 0.2, 0)};
    // Random boxes above an axis-aligned facet, including zero-width boxes and boxes whose
    // faces pass through facet vertices.
    for (int i = 0; i < 300; ++i) {
        V lo(U(rng), U(rng), 0.05 + std::abs(U(rng))), hi = lo + V(0.2 * std::abs(U(rng)), 0.2 * std::abs(U(rng)), 0.1 * std::abs(U(rng)));
        if (i % 5 == 1) hi.x() = lo.x();
        if (i % 5 == 2) hi.y() = lo.y(), hi.z() = lo.z();
        if (i % 7 == 3) lo.x() = flat[1].x();
        if (i % 7 == 4) hi.y() = flat[2].y(), lo.x() = flat[0].x();
        // Flat boxes lying in the facet plane's extension, a denormal or a hair above it.
        if (i % 11 == 5) lo.z() = hi.z() = std::numeric_limits<double>::denorm_min();
        if (i % 11 == 6) lo.z() = 1e-300, hi.z() = 1e-13;
        check_hull(box3(lo.cwiseMin(hi), lo.cwiseMax(hi)), flat);
    }
    // A tilted facet and boxes a hair in front of its plane (nearly coplanar: the case where
    // CGAL's indexed convex_hull_3 with EPICK goes wrong).
    const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, V(1, 2, 3).normalized()).toRotationMatrix();
    const std::array<V, 3> tilt{R * flat[0], R * flat[1], R * flat[2]};
    const V n = (tilt[1] - tilt[0]).cross(tilt[2] - tilt[0]).normalized();
    int nearly_coplanar = 0;
    for (int i = 0; i < 200; ++i) {
        // A box whose lowest corner (along n) is 1e-13 or 1e-9 above the facet plane.
        const V size = 1e-3 * V(std::abs(U(rng)), std::abs(U(rng)), std::abs(U(rng)));
        const V low_corner_offset(n.x() < 0 ? size.x() : 0, n.y() < 0 ? size.y() : 0, n.z() < 0 ? size.z() : 0);
        const V on_plane = tilt[0] + 2 * U(rng) * (tilt[1] - tilt[0]) + 2 * U(rng) * (tilt[2] - tilt[0]);
        const V c = on_plane - low_corner_offset + (i % 2 ? 1e-13 : 1e-9) * n;
        const box3 b(c, c + size);
        bool front = true;
        for (int k = 0; k < 8; ++k)
            front = front && detail::occ::orient3(to_pt(tilt[0]), to_pt(tilt[1]), to_pt(tilt[2]),
                                                  to_pt(b.corner(static_cast<box3::CornerType>(k)))) > 0;
        if (front) check_hull(b, tilt), ++nearly_coplanar;
    }
    CHECK(nearly_coplanar > 100);
}

// ---- fast decisions against the exact clip ---------------------------------------------------

namespace {

/// For boxes in front of facet f, every triangle's fast decision equals the exact rational clip.
void check_fast_against_exact(const triangle_mesh& m, std::size_t f, const std::vector<box3>& boxes) {
    const detail::round_to_nearest_scope nearest;
    std::vector<detail::occ::scene_triangle> tris;
    detail::occ::append_triangles(tris, m, 0);
    const auto& F = tris[f];
    std::size_t checked = 0, blocking = 0;
    for (const box3& b : boxes) {
        bool front = true;
        for (int k = 0; k < 8; ++k)
            front = front && detail::occ::orient3(F.v[0], F.v[1], F.v[2], to_pt(b.corner(static_cast<box3::CornerType>(k)))) > 0;
        if (!front) continue;
        detail::occ::sight_hull H;
        detail::occ::build_sight_hull(to_pt(b.min()), to_pt(b.max()), F.v, H);
        for (std::size_t t = 0; t < tris.size(); ++t) {
            if (t == f) continue;
            bool apart = false;  // both answers are "no" when the bounding boxes are apart
            for (int k = 0; k < 3; ++k)
                apart = apart || tris[t].hi[k] < H.lo[k] || tris[t].lo[k] > H.hi[k];
            if (apart) continue;
            detail::occ::aabb_trace trace;
            const bool fast = detail::occ::blocks(H, F.id, true, tris[t], trace);
            const bool exact = detail::occ::triangle_meets_hull_front_exact(H, tris[t].v);
            if (fast != exact)
                FAIL("facet " << f << " triangle " << t << " box " << b.min().transpose() << " / "
                              << b.max().transpose() << ": fast " << fast << " exact " << exact);
            ++checked, blocking += exact;
        }
    }
    CHECK(checked > 0);
    CHECK(blocking > 0);  // the configurations do exercise blocking triangles
}

}  // namespace

TEST_CASE("aabb_occlusion's per-triangle decisions equal an exact rational clip") {
    const auto part = make_sample_part();
    const triangle_mesh& m = part.mesh;
    const std::size_t foi = part.facet_of_interest;
    const V c = m.facet(foi).centroid;
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> U(-1, 1);
    std::vector<box3> boxes;
    // Random boxes above the facet of interest, near and far, some flat.
    for (int i = 0; i < (debug_build ? 40 : 200); ++i) {
        const V lo = c + V(0.4 * U(rng), 0.4 * U(rng), 0.002 + 0.3 * std::abs(U(rng)));
        V hi = lo + V(0.1 * std::abs(U(rng)), 0.1 * std::abs(U(rng)), 0.05 * std::abs(U(rng)));
        if (i % 4 == 0) hi.z() = lo.z();
        boxes.emplace_back(lo, hi);
    }
    // Boxes whose faces lie in the planes of the boss wall and of facet edges (exact contacts),
    // and a box lying a hair above the facet plane, in its extension.
    const auto& F = m.facet(foi);
    boxes.emplace_back(V(F.v[1].x(), -0.05, 0.2), V(F.v[1].x() + 0.1, 0.05, 0.3));
    boxes.emplace_back(V(F.v[1].x() - 0.1, -0.05, 0.2), V(F.v[1].x(), 0.05, 0.3));
    boxes.emplace_back(V(-0.2, F.v[0].y(), 0.1), V(-0.1, F.v[0].y(), 0.15));
    boxes.emplace_back(V(-0.3, -0.1, std::nextafter(F.v[0].z(), 1.0)), V(-0.2, 0.1, std::nextafter(F.v[0].z(), 1.0)));
    boxes.emplace_back(V(-0.3, -0.1, F.v[0].z() + 1e-12), V(-0.2, 0.1, F.v[0].z() + 1e-3));
    check_fast_against_exact(m, foi, boxes);

    // The same on the part rotated off the axes: coplanar neighbours become nearly coplanar.
    const Eigen::Matrix3d R = Eigen::AngleAxisd(0.3, V(1, -2, 0.5).normalized()).toRotationMatrix();
    const triangle_mesh rm = transformed(m, R, V(0.01, 0.02, -0.03));
    std::vector<box3> rboxes;
    const V rc = rm.facet(foi).centroid, rn = rm.facet(foi).normal;
    for (int i = 0; i < (debug_build ? 30 : 150); ++i) {
        const V lo = rc + 0.3 * V(U(rng), U(rng), U(rng)) + (i % 3 == 0 ? 1e-10 : 0.05) * rn;
        rboxes.emplace_back(lo, lo + V(0.05, 0.05, 0.05) * std::abs(U(rng)));
    }
    check_fast_against_exact(rm, foi, rboxes);
}

TEST_CASE("the free-sight-line filter never calls a touching segment free") {
    // segment_may_meet_triangle may only say "no" when CGAL's exact predicate agrees; on a small
    // integer grid many segments touch edges and vertices, lie in the triangle's plane or end
    // on it. Off the plane it must equal CGAL exactly.
    using EK = CGAL::Exact_predicates_exact_constructions_kernel;
    std::mt19937_64 rng(23);
    std::uniform_int_distribution<int> G(-2, 2);
    const auto grid = [&] { return pt{double(G(rng)), double(G(rng)), double(G(rng))}; };
    const auto P = [](const pt& x) { return EK::Point_3(x[0], x[1], x[2]); };
    int meets = 0, coplanar = 0;
    for (int i = 0; i < 20000; ++i) {
        const std::array<pt, 3> w{grid(), grid(), grid()};
        const pt a = grid(), b = grid();
        if (CGAL::collinear(P(w[0]), P(w[1]), P(w[2])) || a == b) continue;
        const bool exact = CGAL::do_intersect(EK::Segment_3(P(a), P(b)), EK::Triangle_3(P(w[0]), P(w[1]), P(w[2])));
        const bool may = detail::occ::segment_may_meet_triangle(a, b, w);
        CAPTURE(i);
        if (exact) CHECK(may);
        const bool in_plane = CGAL::coplanar(P(w[0]), P(w[1]), P(w[2]), P(a)) && CGAL::coplanar(P(w[0]), P(w[1]), P(w[2]), P(b));
        if (!in_plane) CHECK(may == exact);
        meets += exact, coplanar += in_plane;
    }
    CHECK(meets > 1000);
    CHECK(coplanar > 100);
}

TEST_CASE("the segment-box pruning never prunes a box the segment touches") {
    // On a small grid segments often end on a box face, run along one or touch a corner: the
    // plain-double slab test (grown by its margin) must keep every box CGAL's exact predicate
    // says the segment meets, and still prune most of the others.
    using EK = CGAL::Exact_predicates_exact_constructions_kernel;
    std::mt19937_64 rng(29);
    std::uniform_int_distribution<int> G(-3, 3);
    const auto grid = [&] { return pt{G(rng) / 2.0, G(rng) / 2.0, G(rng) / 2.0}; };
    int meets = 0, pruned = 0, misses = 0;
    for (int i = 0; i < 20000; ++i) {
        const pt a = grid(), b = grid(), p = grid(), q = grid();
        if (a == b) continue;
        const CGAL::Bbox_3 box(std::min(p[0], q[0]), std::min(p[1], q[1]), std::min(p[2], q[2]), std::max(p[0], q[0]),
                               std::max(p[1], q[1]), std::max(p[2], q[2]));
        const bool exact = CGAL::do_intersect(EK::Segment_3(EK::Point_3(a[0], a[1], a[2]), EK::Point_3(b[0], b[1], b[2])),
                                              EK::Iso_cuboid_3(box.xmin(), box.ymin(), box.zmin(), box.xmax(), box.ymax(), box.zmax()));
        const bool may = detail::occ::segment_may_meet_box(a, b, box);
        CAPTURE(i);
        if (exact) CHECK(may);
        meets += exact, misses += !exact, pruned += !exact && !may;
    }
    CHECK(meets > 1000);
    CHECK(pruned > 0.9 * misses);
}

// ---- hand-made scenes --------------------------------------------------------------------------

TEST_CASE("a cube: front, behind, edge-on and in-plane boxes") {
    const triangle_mesh cube = cuboid(V(0, 0, 0), V(1, 1, 1));
    const aabb_occlusion fast(cube);
    const boolean_occlusion exact(cube);
    const std::size_t top = face_with(cube, V(0, 0, 1), V(1, 0, 1), V(1, 1, 1));
    const auto both = [&](const box3& b) {
        const visibility a = fast.classify(b, top), e = exact.classify(b, top);
        CHECK(!contradict(a, e));
        return std::pair{a, e};
    };
    // Above the top face: nothing else can block.
    CHECK(both(box3(V(0.2, 0.2, 2), V(0.8, 0.8, 2.5))) == std::pair{visibility::visible, visibility::visible});
    // Far to the side but above the top plane: still visible (the cube is convex).
    CHECK(both(box3(V(5, 5, 1.5), V(6, 6, 2))).first == visibility::visible);
    // Below the cube: the facet faces away.
    CHECK(both(box3(V(0.2, 0.2, -2), V(0.8, 0.8, -1))) == std::pair{visibility::occluded, visibility::occluded});
    // Straddling the facet plane: some positions see it, others are behind it.
    CHECK(both(box3(V(2, 0.2, 0.5), V(3, 0.8, 1.5))) == std::pair{visibility::partial, visibility::partial});
    // A flat box in the plane of the top face, beside it: every sight line to the facet's
    // interior crosses the facet's edge, i.e. a neighbour triangle. The boolean test has no
    // volume to work with (H is flat) and says partial.
    CHECK(both(box3(V(2, 0, 1), V(3, 1, 1))) == std::pair{visibility::occluded, visibility::partial});
    // A flat box in that plane overlapping the facet itself: undecided.
    CHECK(both(box3(V(0.5, 0.1, 1), V(3, 0.2, 1))).first == visibility::partial);
    // One ulp above that plane: every sight line skims the top face but is free.
    const double z = std::nextafter(1.0, 2.0);
    const auto skim = both(box3(V(2, 0, z), V(3, 1, z)));
    CHECK(skim.first == visibility::visible);
    CHECK(skim.second == visibility::visible);
    // A box that cuts into the cube: sight lines from inside run through the solid.
    CHECK(both(box3(V(0.4, 0.4, 0.9), V(0.6, 0.6, 1.5))).first == visibility::partial);
}

TEST_CASE("occluders: a slab that hides the facet, one that hides part of it, one beside it") {
    const triangle_mesh cube = cuboid(V(0, 0, 0), V(1, 1, 1));
    const std::size_t top = face_with(cube, V(0, 0, 1), V(1, 0, 1), V(1, 1, 1));
    const box3 cam(V(0.3, 0.3, 3), V(0.6, 0.6, 3.2));
    const auto run = [&](const triangle_mesh& occ) {
        const std::vector<triangle_mesh> occluders{occ};
        const aabb_occlusion fast(cube, occluders);
        const boolean_occlusion exact(cube, occluders);
        const visibility a = fast.classify(cam, top), e = exact.classify(cam, top);
        CHECK(!contradict(a, e));
        const segment_sampler S({&cube, &occluders[0]});
        std::mt19937_64 rng(3);
        CHECK(confirmed(S, cam, top, a, rng, "aabb_occlusion"));
        CHECK(confirmed(S, cam, top, e, rng, "boolean_occlusion"));
        return std::pair{a, e};
    };
    // A large slab between, placed so that its faces' diagonals pass far from the sight
    // lines: one triangle then holds all 24 corner–vertex crossings (aabb's certificate).
    CHECK(run(cuboid(V(-0.5, -5, 2), V(10, 5, 2.1))) == std::pair{visibility::occluded, visibility::occluded});
    // The same slab centred: the diagonals of its faces now cut through the sight lines, so no
    // single triangle holds every crossing — the planar-wall certificate (all the slab's
    // triangles in one plane) still proves occlusion.
    CHECK(run(cuboid(V(-5, -5, 2), V(5, 5, 2.1))) == std::pair{visibility::occluded, visibility::occluded});
    // A frame of four bars (four occluders) with a small window in the middle of the sight
    // lines: the bars' bottom faces lie in one plane, but their union has a hole there, so no
    // wall certificate may hold.
    {
        const std::vector<triangle_mesh> frame{cuboid(V(-5, -5, 2), V(5, 0.4, 2.1)), cuboid(V(-5, 0.5, 2), V(5, 5, 2.1)),
                                               cuboid(V(-5, 0.4, 2), V(0.4, 0.5, 2.1)), cuboid(V(0.5, 0.4, 2), V(5, 0.5, 2.1))};
        const aabb_occlusion fast(cube, frame);
        const boolean_occlusion exact(cube, frame);
        const visibility a = fast.classify(cam, top), e = exact.classify(cam, top);
        CHECK(a == visibility::partial);
        CHECK(e != visibility::occluded);
        std::vector<const triangle_mesh*> scene{&cube};
        for (const auto& b : frame) scene.push_back(&b);
        const segment_sampler S(scene);
        std::mt19937_64 rng(4);
        const int through = samples_per_answer - S.blocked(cam, top, samples_per_answer, 1e-9, rng);
        CHECK(through > 0);  // some sight lines do pass through the window
        CHECK(confirmed(S, cam, top, e, rng, "boolean_occlusion"));
    }
    // A small plate over half of the facet: partial for both.
    CHECK(run(cuboid(V(-0.5, -0.5, 2), V(0.5, 1.5, 2.1))) == std::pair{visibility::partial, visibility::partial});
    // A block resting against the cube (sharing its x = 1 face) below the facet plane.
    CHECK(run(cuboid(V(1, 0, 0), V(2, 1, 1))) == std::pair{visibility::visible, visibility::visible});
    // A block that touches the top face's plane along the facet's far edge, outside the hull.
    CHECK(run(cuboid(V(1, -1, 1), V(2, 2, 1.5))).first == visibility::visible);
}

TEST_CASE("front_clear: nothing in front of the facet within the region, checked by sampled sight lines") {
    const triangle_mesh cube = cuboid(V(0, 0, 0), V(1, 1, 1));
    const std::size_t top = face_with(cube, V(0, 0, 1), V(1, 0, 1), V(1, 1, 1));
    const std::size_t bottom = face_with(cube, V(0, 0, 0), V(1, 1, 0), V(1, 0, 0));
    const aabb_occlusion alone(cube);
    // A box that touches the facet plane is fine: the answer is about its positions in front.
    const box3 above(V(-2, -2, 1), V(3, 3, 4)), below(V(-2, -2, -4), V(3, 3, 0));
    CHECK(alone.front_clear(above, top));
    CHECK(alone.front_clear(below, bottom));
    // A post standing on the cube, in front of the top face: not clear, and a sight line meets it.
    const std::vector<triangle_mesh> post{cuboid(V(0.3, 0.3, 1.0), V(0.7, 0.7, 1.4))};
    const aabb_occlusion with_post(cube, post);
    CHECK(!with_post.front_clear(above, top));
    CHECK(with_post.front_clear(below, bottom));  // behind the bottom face's plane: harmless
    // Out of the region (the bounding box of the box and the facet): clear again.
    const std::vector<triangle_mesh> far_post{cuboid(V(5, 5, 1.0), V(5.5, 5.5, 1.4))};
    CHECK(aabb_occlusion(cube, far_post).front_clear(above, top));
    CHECK(!aabb_occlusion(cube, far_post).front_clear(box3(V(-2, -2, 1), V(6, 6, 4)), top));
    // Whenever it says clear, no sampled sight line from the box's front part is blocked.
    const segment_sampler S({&cube, &post[0]});
    std::mt19937_64 rng(7);
    const box3 beside(V(0.8, -2, 1.0), V(3, 3, 2));  // the post is inside its region
    CHECK(!with_post.front_clear(beside, top));
    CHECK(S.blocked(box3(V(-2, -2, -4), V(3, 3, -0.01)), bottom, 400, 0.0, rng) == 0);
    CHECK(S.blocked(box3(V(-2, -2, 1.01), V(3, 3, 4)), top, 400, 0.0, rng) > 0);  // not clear, and indeed blocked
    CHECK_THROWS_AS(alone.front_clear(above, 12), out_of_range);
}

TEST_CASE("sight_line_blocked: a slab over the facet blocks, nothing else does, and it never refutes a VISIBLE box") {
    const triangle_mesh cube = cuboid(V(0, 0, 0), V(1, 1, 1));
    const std::size_t top = face_with(cube, V(0, 0, 1), V(1, 0, 1), V(1, 1, 1));
    const std::vector<triangle_mesh> slab{cuboid(V(-5, -5, 2), V(5, 5, 2.1))};
    const aabb_occlusion open_sky(cube), covered(cube, slab);
    const V above(0.5, 0.5, 3);
    CHECK(!open_sky.sight_line_blocked(above, top));
    CHECK(covered.sight_line_blocked(above, top));
    CHECK(!covered.sight_line_blocked(V(0.5, 0.5, 1.5), top));  // under the slab
    // A blocker beside the facet, in front of its plane, across the line from the side.
    const std::vector<triangle_mesh> post{cuboid(V(0.3, 0.3, 1.2), V(0.7, 0.7, 1.4))};
    CHECK(aabb_occlusion(cube, post).sight_line_blocked(V(0.5, 0.5, 3), top));
    CHECK(!aabb_occlusion(cube, post).sight_line_blocked(V(5, 0.5, 1.1), top));
    CHECK_THROWS_AS(open_sky.sight_line_blocked(above, 12), out_of_range);
    try {
        open_sky.sight_line_blocked(V(0, std::numeric_limits<double>::quiet_NaN(), 3), top);
        FAIL("no throw");
    } catch (const invalid_argument& e) {
        CHECK(e.field() == "point");
    }
    // A soup with the top face twice, and the centroid exactly in its plane ((1 + 1 + 1) / 3):
    // the copy touches the line only at its end on the facet, which blocks nothing.
    std::vector<face_indices> doubled = cube.faces();
    doubled.push_back(cube.faces()[top]);
    const aabb_occlusion soup(triangle_mesh(cube.vertices(), doubled), {}, mesh_semantics::soup);
    CHECK(!soup.sight_line_blocked(above, top));
    CHECK(!soup.sight_line_blocked(above, doubled.size() - 1));
    CHECK(soup.classify(box3(above - V(0.1, 0.1, 0.1), above + V(0.1, 0.1, 0.1)), top) == visibility::visible);
    // On the sample part: whenever the centre's line is blocked, no box holding the centre is
    // VISIBLE (the refutation only ever spares a proof that would fail).
    const auto part = make_sample_part();
    const aabb_occlusion fast(part.mesh);
    std::mt19937_64 rng(37);
    std::uniform_real_distribution<double> U(-0.6, 0.6), H(0.005, 0.05);
    std::uniform_int_distribution<std::size_t> F(0, part.mesh.num_faces() - 1);
    int blocked = 0, visible = 0, hint_moved = 0;
    std::size_t chained_hint = std::numeric_limits<std::size_t>::max();
    for (int i = 0; i < (debug_build ? 300 : 3000); ++i) {
        const V c(U(rng), U(rng), std::abs(U(rng)) + 0.05);
        const double h = H(rng);
        const box3 b(c - V(h, h, h), c + V(h, h, h));
        const std::size_t f = F(rng);
        const bool refuted = fast.sight_line_blocked(b.center(), f);
        const visibility v = fast.classify(b, f, occlusion_effort::visible_only);
        CAPTURE(i);
        if (refuted) CHECK(v != visibility::visible);
        blocked += refuted, visible += v == visibility::visible;
        // With a hint, the same answer: the last blocker (as the coverage inspector passes it),
        // a random triangle, and one beyond the scene.
        std::size_t random_hint = F(rng), beyond = part.mesh.num_faces() + 5;
        const std::size_t before = chained_hint;
        CHECK(fast.sight_line_blocked(b.center(), f, chained_hint) == refuted);
        CHECK(fast.sight_line_blocked(b.center(), f, random_hint) == refuted);
        CHECK(fast.sight_line_blocked(b.center(), f, beyond) == refuted);
        if (chained_hint != before) ++hint_moved;
    }
    CHECK(blocked > 0);
    CHECK(visible > 0);
    CHECK(hint_moved > 0);  // a walk that found a blocker hands it on
    // As the inspector asks: every facet in order from one point, each hint the one the last
    // blocked line left.
    for (const V& from : {V(0.05, 0.02, 0.12), V(-0.3, 0.25, 0.2), V(0.4, -0.1, 0.08)}) {
        std::size_t hint = std::numeric_limits<std::size_t>::max();
        for (std::size_t f = 0; f < part.mesh.num_faces(); ++f) {
            const bool refuted = fast.sight_line_blocked(from, f);
            CAPTURE(f);
            CHECK(fast.sight_line_blocked(from, f, hint) == refuted);
        }
    }
}

TEST_CASE("flat patches: edge-adjacent faces exactly in one plane share one, nothing else does") {
    // A cube whose top is split into four triangles around its centre, then the centre lifted by
    // one ulp, then a bottom corner lifted: the patches the walks pass over
    // (cgal_aabb_occlusion.hpp, assign_flat_patches) must be exactly coplanar.
    using detail::occ::scene_triangle;
    std::vector<V> v{V(0, 0, 0), V(1, 0, 0), V(1, 1, 0), V(0, 1, 0), V(0, 0, 1), V(1, 0, 1), V(1, 1, 1), V(0, 1, 1),
                     V(0.5, 0.5, 1)};
    std::vector<face_indices> f{{0, 2, 1}, {0, 3, 2},                          // bottom (z = 0)
                                {4, 5, 8}, {5, 6, 8}, {6, 7, 8}, {7, 4, 8},    // top (z = 1), 4 faces
                                {0, 1, 5}, {0, 5, 4}, {1, 2, 6}, {1, 6, 5},    // sides
                                {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
    const auto patches_of = [](const triangle_mesh& m) {
        std::vector<scene_triangle> tris;
        detail::occ::append_triangles(tris, m, 0);
        detail::occ::assign_flat_patches(tris, tris.size());
        std::vector<std::uint32_t> p;
        for (const auto& t : tris) p.push_back(t.patch);
        return p;
    };
    const auto p = patches_of(triangle_mesh(v, f));
    CHECK(p[0] == p[1]);
    CHECK((p[2] == p[3] && p[3] == p[4] && p[4] == p[5]));
    CHECK(p[0] != p[2]);
    for (std::size_t side = 6; side < 14; side += 2) {
        CHECK(p[side] == p[side + 1]);
        CHECK(p[side] != p[0]);
        CHECK(p[side] != p[2]);
    }
    CHECK(p[6] != p[8]);
    // The top's centre one ulp up: the four top faces are no longer one plane.
    std::vector<V> lifted = v;
    lifted[8].z() = std::nextafter(1.0, 2.0);
    const auto q = patches_of(triangle_mesh(lifted, f));
    CHECK(q[2] != q[3]);
    CHECK(q[2] != q[4]);
    // A collinear sliver (which triangle_mesh refuses, but a scene built otherwise need not)
    // between the top's edge 4–5 and a face of the front plane y = 0: a degenerate face lies in
    // every plane through its line, so it must join no patch, or it would join these two.
    const auto tri = [](std::array<V, 3> p, std::array<std::uint32_t, 3> id) {
        scene_triangle t;
        for (std::size_t k = 0; k < 3; ++k) t.v[k] = {p[k].x(), p[k].y(), p[k].z()}, t.id[k] = id[k];
        return t;
    };
    std::vector<scene_triangle> sliver{tri({v[4], v[5], v[8]}, {4, 5, 8}),              // top
                                       tri({v[5], v[4], V(0.5, 0, 1)}, {5, 4, 9}),      // collinear
                                       tri({V(0.5, 0, 1), v[4], V(0.5, 0, 0)}, {9, 4, 10})};  // y = 0
    detail::occ::assign_flat_patches(sliver, sliver.size());
    CHECK(sliver[1].patch != sliver[0].patch);
    CHECK(sliver[1].patch != sliver[2].patch);
    CHECK(sliver[0].patch != sliver[2].patch);
    // A bottom corner off the plane of the other three: the bottom's two faces part.
    std::vector<V> tilted = v;
    tilted[2].z() = 1e-12;
    CHECK(patches_of(triangle_mesh(tilted, f))[0] != patches_of(triangle_mesh(tilted, f))[1]);
}

TEST_CASE("the sample part's facet of interest behind its boss: a wall touching the facet") {
    // The facet shares an edge with the boss's west wall. A low box east of the boss sees the
    // facet only through the boss: every sight line crosses a wall plane that contains the
    // facet's edge (the facet touches the wall plane instead of lying strictly across it).
    const auto part = make_sample_part();
    const std::size_t foi = part.facet_of_interest;
    const aabb_occlusion fast(part.mesh);
    const boolean_occlusion exact(part.mesh);
    const segment_sampler S({&part.mesh});
    std::mt19937_64 rng(9);
    const double z = part.mesh.facet(foi).v[0].z();
    const box3 hidden(V(0.45, -0.05, std::nextafter(z, 1.0)), V(0.55, 0.05, 0.15));
    const box3 above(V(-0.1, -0.05, 0.4), V(0.0, 0.05, 0.5));  // west of the boss, high
    CHECK(fast.classify(hidden, foi) == visibility::occluded);
    CHECK(exact.classify(hidden, foi) == visibility::occluded);
    CHECK(confirmed(S, hidden, foi, visibility::occluded, rng, "test"));
    CHECK(fast.classify(above, foi) == visibility::visible);
    CHECK(exact.classify(above, foi) == visibility::visible);
    CHECK(confirmed(S, above, foi, visibility::visible, rng, "test"));
}

TEST_CASE("occlusion_effort::visible_only: the same VISIBLE, PARTIAL for what full effort calls OCCLUDED") {
    const auto part = make_sample_part();
    const std::size_t foi = part.facet_of_interest;
    const aabb_occlusion fast(part.mesh);
    const double z = part.mesh.facet(foi).v[0].z();
    const box3 hidden(V(0.45, -0.05, std::nextafter(z, 1.0)), V(0.55, 0.05, 0.15));
    const box3 above(V(-0.1, -0.05, 0.4), V(0.0, 0.05, 0.5));
    CHECK(fast.classify(hidden, foi, occlusion_effort::full) == visibility::occluded);
    CHECK(fast.classify(hidden, foi, occlusion_effort::visible_only) == visibility::partial);
    CHECK(fast.classify(above, foi, occlusion_effort::visible_only) == visibility::visible);
    // Every facet against Figure 5's box and the two above: VISIBLE exactly where full effort
    // says so; OCCLUDED only without a search (e.g. a box behind the facet plane), else PARTIAL.
    const box3 fig5(V(-0.1, -0.1, 0.25), V(0.1, 0.1, 0.3));
    std::size_t visible = 0, occluded = 0, relabelled = 0;
    for (const box3* box : {&fig5, &hidden, &above}) {
        const Eigen::RowVector3d lo = box->min().transpose();
        CAPTURE(lo);
        for (std::size_t f = 0; f < part.mesh.num_faces(); ++f) {
            const visibility full = fast.classify(*box, f);
            const visibility quick = fast.classify(*box, f, occlusion_effort::visible_only);
            CAPTURE(f);
            CHECK((full == visibility::visible) == (quick == visibility::visible));
            if (full == visibility::partial) CHECK(quick == visibility::partial);
            if (quick == visibility::occluded) CHECK(full == visibility::occluded);
            visible += full == visibility::visible;
            occluded += full == visibility::occluded;
            relabelled += full == visibility::occluded && quick == visibility::partial;
        }
    }
    MESSAGE(visible << " visible, " << occluded << " occluded (box, facet) pairs, " << relabelled
                    << " of them partial with visible_only");
    CHECK(visible > 0);
    CHECK(relabelled > 0);
}

TEST_CASE("facets with coplanar neighbours and boxes at grazing angles agree with sampling") {
    // The sample part's top surface is flat: every top facet has coplanar neighbours. Boxes
    // just above the top plane, far away, see the top facets at grazing angles.
    const auto part = make_sample_part();
    const triangle_mesh& m = part.mesh;
    const aabb_occlusion fast(m);
    const boolean_occlusion exact(m);
    const segment_sampler S({&m});
    std::mt19937_64 rng(5);
    const double top = 0.05;
    const std::vector<box3> boxes{box3(V(-0.6, -0.05, std::nextafter(top, 1.0)), V(-0.5, 0.05, top + 1e-3)),
                                  box3(V(-0.6, -0.05, top), V(-0.5, 0.05, top + 1e-3)),
                                  box3(V(0.5, 0.2, top + 0.02), V(0.6, 0.3, top + 0.05))};
    std::size_t visible = 0;
    for (std::size_t f = 0; f < m.num_faces(); f += debug_build ? 37 : 11) {
        if (m.facet(f).normal.z() < 0.5) continue;  // top-facing facets
        for (const box3& b : boxes) {
            const visibility a = fast.classify(b, f);
            CHECK(confirmed(S, b, f, a, rng, "aabb_occlusion"));
            if (!debug_build || &b == &boxes[0]) {
                const visibility e = exact.classify(b, f);
                CHECK(!contradict(a, e));
                CHECK(confirmed(S, b, f, e, rng, "boolean_occlusion"));
            }
            if (b.min().z() == top && m.facet(f).v[0].z() == top)
                CHECK(a == visibility::partial);  // in the facet plane: never visible
            visible += a == visibility::visible;
        }
    }
    CHECK(visible > 0);
}

TEST_CASE("scene validation and bad arguments throw the documented errors") {
    const triangle_mesh cube = cuboid(V(0, 0, 0), V(1, 1, 1));
    // Open: drop the last face.
    std::vector<face_indices> open_faces = cube.faces();
    open_faces.pop_back();
    const triangle_mesh open(cube.vertices(), open_faces);
    CHECK_THROWS_AS(aabb_occlusion{open}, mesh_error);
    CHECK_THROWS_AS(boolean_occlusion{open}, mesh_error);
    // Inside out.
    std::vector<face_indices> flipped = cube.faces();
    for (auto& f : flipped) std::swap(f[1], f[2]);
    const triangle_mesh inverted(cube.vertices(), flipped);
    CHECK_THROWS_WITH_AS(aabb_occlusion{inverted}, doctest::Contains("does not bound a volume"), mesh_error);
    // Two interpenetrating cubes in one mesh: self-intersecting.
    const triangle_mesh other = cuboid(V(0.5, 0.5, 0.5), V(1.5, 1.5, 1.5));
    std::vector<V> v = cube.vertices();
    std::vector<face_indices> f = cube.faces();
    for (const V& p : other.vertices()) v.push_back(p);
    for (auto t : other.faces()) f.push_back({t[0] + 8, t[1] + 8, t[2] + 8});
    const triangle_mesh twin(v, f);
    CHECK_THROWS_WITH_AS(boolean_occlusion{twin}, doctest::Contains("self-intersects"), mesh_error);
    // A bad occluder is named.
    const std::vector<triangle_mesh> bad{cube, open};
    CHECK_THROWS_WITH_AS((aabb_occlusion{cube, bad}), doctest::Contains("occluder 1"), mesh_error);

    const aabb_occlusion fast(cube);
    const boolean_occlusion exact(cube);
    const no_occlusion none(cube);
    const box3 b(V(0, 0, 2), V(1, 1, 3));
    CHECK_THROWS_AS(fast.classify(b, 12), out_of_range);
    CHECK_THROWS_AS(exact.classify(b, 99), out_of_range);
    CHECK_THROWS_AS(none.classify(position_box<boost_interval>::from_bounds({{{0, 1}, {0, 1}, {2, 3}}}), 12), out_of_range);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    try {
        fast.classify(box3(V(0, 0, nan), V(1, 1, 3)), 0);
        FAIL("no throw");
    } catch (const invalid_argument& e) {
        CHECK(e.field() == "box");
    }
    CHECK_THROWS_AS(exact.classify(box3(V(0, 0, std::numeric_limits<double>::infinity()), V(1, 1, 3)), 0), invalid_argument);
    CHECK_THROWS_AS(fast.classify(position_box<boost_interval>::empty(), 0), invalid_argument);
}

TEST_CASE_TEMPLATE("classify takes position boxes over every interval backend, under a held rounding mode", I,
                   boost_interval, cgal_interval) {
    const triangle_mesh cube = cuboid(V(0, 0, 0), V(1, 1, 1));
    const std::size_t top = face_with(cube, V(0, 0, 1), V(1, 0, 1), V(1, 1, 1));
    const aabb_occlusion fast(cube);
    const boolean_occlusion exact(cube);
    const no_occlusion none(cube);
    const rounding_guard<I> guard;  // the solver calls policies with the interval mode held
    const auto above = position_box<I>::from_bounds({{{0.2, 0.8}, {0.2, 0.8}, {2, 2.5}}});
    const auto below = position_box<I>::from_bounds({{{0.2, 0.8}, {0.2, 0.8}, {-2, -1}}});
    CHECK(fast.classify(above, top) == visibility::visible);
    CHECK(exact.classify(above, top) == visibility::visible);
    CHECK(fast.classify(below, top) == visibility::occluded);
    CHECK(exact.classify(below, top) == visibility::occluded);
    CHECK(none.classify(below, top) == visibility::visible);
    CHECK(detail::rounding_is_upward());  // the policies restored the caller's mode
}

TEST_CASE("one aabb_occlusion shared by two threads answers as it does alone") {
    const auto part = make_sample_part();
    const aabb_occlusion fast(part.mesh);
    const box3 b(V(-0.1, -0.1, 0.25), V(0.1, 0.1, 0.3));
    const std::size_t n = part.mesh.num_faces();
    std::vector<visibility> alone(n), t1(n), t2(n);
    for (std::size_t f = 0; f < n; ++f) alone[f] = fast.classify(b, f);
    std::thread a([&] { for (std::size_t f = 0; f < n; ++f) t1[f] = fast.classify(b, f); });
    std::thread c([&] { for (std::size_t f = n; f-- > 0;) t2[f] = fast.classify(b, f); });
    a.join(), c.join();
    CHECK(t1 == alone);
    CHECK(t2 == alone);
}

// ---- the paper's Figure 5 and real meshes ----------------------------------------------------

TEST_CASE("Figure 5: box [-0.1,0.1]x[-0.1,0.1]x[0.25,0.3] against every facet of the sample part") {
    const auto part = make_sample_part();
    std::mt19937_64 rng(2023);
    const box3 box(V(-0.1, -0.1, 0.25), V(0.1, 0.1, 0.3));
    const scene_tools tools(part.mesh);
    const experiment_result r = run_experiment(part.mesh, tools, box, debug_build ? 47 : 1, rng);
    MESSAGE("Figure 5 (" << part.mesh.num_faces() << " facets):\n" << r.table());
    CHECK(r.refuted == 0);
    CHECK(r.contradictions == 0);
    for (int k = 0; k < 3; ++k) CHECK(r.fast[k] > 0);  // all three classes occur, as in the paper
    CHECK(r.exact[0] > 0);
    CHECK(r.exact[2] > 0);
}

TEST_CASE("real meshes, rescaled to a 0.3 m diagonal, with boxes at several distances") {
    for (const char* name : {"idler_riser.off", "featuretype.off"}) {
        const triangle_mesh raw = read_mesh(std::string(CERTIPOSE_SHARED_MESHES) + "/" + name);
        const triangle_mesh scaled_mesh = rescaled_to_diagonal(raw, 0.3);
        const triangle_mesh m = translated(scaled_mesh, -scaled_mesh.bbox().center());
        const scene_tools tools(m);
        std::mt19937_64 rng(17);
        const std::size_t stride = debug_build ? 211 : 29;
        // Three distances along one direction and a second direction at mid distance (Debug:
        // the nearest and the farthest only).
        const V diag = V(1, 1, 1).normalized(), low = V(-1, 0.5, -0.3).normalized();
        std::vector<V> centres{0.3 * diag, 0.8 * diag};
        if (!debug_build) centres.insert(centres.end(), {V(0.5 * diag), V(0.5 * low)});
        for (const V& centre : centres) {
            const box3 box = cube_at(centre, 0.1);
            const experiment_result res = run_experiment(m, tools, box, stride, rng, debug_build ? 20 : 1000);
            MESSAGE(std::string(name) << ", 0.1 m box at " << centre.norm() << " m towards ("
                                      << (centre / centre.norm()).transpose() << "):\n" << res.table());
            CHECK(res.refuted == 0);
            CHECK(res.contradictions == 0);
            CHECK(res.fast[0] > 0);
            CHECK(res.fast[2] > 0);
        }
    }
}
