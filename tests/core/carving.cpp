// The pieces of the position stage's inner contraction and occlusion cuts, and of box growing
// (solver/detail/carving.hpp, solver/detail/growth.hpp), tested on their own: half-space and
// shadow contractions keep every point of the half-space (random points, random planes);
// carved pieces lie strictly outside what they are carved from and, with the rest, cover the
// box; corner boxes pass the predicate that found them; merges and growth keep what a
// certifier accepts and nothing else.
#include <certipose/interval/boost_interval.hpp>
#include <certipose/solver/detail/carving.hpp>
#include <certipose/solver/detail/growth.hpp>

#include <doctest/doctest.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <random>
#include <type_traits>
#include <vector>

using I = certipose::boost_interval;
using box3 = certipose::position_box<I>;
using certipose::lower;
using certipose::upper;

namespace {

box3 random_box(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1, 1), w(0.01, 1);
    box3 b;
    for (int k = 0; k < 3; ++k) {
        const double lo = u(rng);
        b[k] = I(lo, lo + w(rng));
    }
    return b;
}

Eigen::Vector3d random_point(const box3& b, std::mt19937& rng) {
    Eigen::Vector3d p;
    for (int k = 0; k < 3; ++k) p[k] = std::uniform_real_distribution<double>(lower(b[k]), upper(b[k]))(rng);
    return p;
}

bool contains(const box3& b, const Eigen::Vector3d& p) {
    for (int k = 0; k < 3; ++k)
        if (!(lower(b[k]) <= p[k] && p[k] <= upper(b[k]))) return false;
    return true;
}

certipose::occlusion_half_space random_half_space(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1, 1);
    certipose::occlusion_half_space h;
    for (auto& p : h.points) p = Eigen::Vector3d(u(rng), u(rng), u(rng));
    h.sign = u(rng) < 0 ? -1 : 1;
    return h;
}

// sign·((b − a) × (c − a))·(p − a) ≤ 0, in long double (the points are far from the plane or
// not; a point within 1e-12 of it is skipped: the test is about real points).
int side(const certipose::occlusion_half_space& h, const Eigen::Vector3d& p) {
    const auto& [a, b, c] = h.points;
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const long double v = h.sign * ((long double)n.x() * (p.x() - a.x()) + (long double)n.y() * (p.y() - a.y()) +
                                    (long double)n.z() * (p.z() - a.z()));
    if (std::abs((double)v) < 1e-12) return 0;
    return v > 0 ? 1 : -1;
}

}  // namespace

TEST_CASE("half-space and shadow contractions keep every point of the half-space") {
    std::mt19937 rng(3);
    std::size_t kept = 0, emptied = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const box3 b = random_box(rng);
        certipose::occlusion_shadow raw;
        raw.count = 1 + trial % 4;
        for (std::size_t i = 0; i < raw.count; ++i) raw.planes[i] = random_half_space(rng);
        const certipose::rounding_guard<I> rounding;
        const auto prepared = certipose::detail::prepare<I>(raw);
        box3 one = b, shadow = b;
        certipose::detail::contract_half_space(one, prepared.planes[0]);
        certipose::detail::contract_shadow(shadow, prepared);
        box3 unprepared = b;
        certipose::detail::contract_shadow(unprepared, raw);
        emptied += is_empty(shadow);
        for (int k = 0; k < 60; ++k) {
            const Eigen::Vector3d p = random_point(b, rng);
            if (side(raw.planes[0], p) < 0) {
                ++kept;
                CHECK(contains(one, p));
            }
            bool inside = true;
            for (std::size_t i = 0; i < raw.count; ++i) inside = inside && side(raw.planes[i], p) < 0;
            if (inside) {
                CHECK(contains(shadow, p));
                CHECK(contains(unprepared, p));
            }
        }
    }
    CHECK(kept > 1000);
    CHECK(emptied > 10);  // some contractions do prove a box outside (otherwise nothing was tested)
}

TEST_CASE("carved pieces lie strictly outside the contracted part, and with the rest cover the box") {
    std::mt19937 rng(4);
    std::size_t pieces_seen = 0;
    for (int trial = 0; trial < 300; ++trial) {
        box3 b = random_box(rng);
        box3 inner;
        for (int k = 0; k < 3; ++k) {
            const double lo = lower(b[k]), w = upper(b[k]) - lo;
            const double a = lo + w * std::uniform_real_distribution<double>(0, 0.6)(rng);
            inner[k] = I(a, a + w * std::uniform_real_distribution<double>(0, 0.4)(rng));
        }
        const box3 before = b;
        const double min_width = trial % 3 == 0 ? 0.0 : 0.05;
        std::vector<box3> pieces;
        const std::size_t n = certipose::detail::carve(b, inner, min_width, [&](box3&& p) { pieces.push_back(p); });
        CHECK(n == pieces.size());
        pieces_seen += n;
        for (const auto& p : pieces) {
            // every point of a piece is outside the closed inner box
            bool apart = false;
            for (int k = 0; k < 3; ++k)
                apart = apart || upper(p[k]) < lower(inner[k]) || lower(p[k]) > upper(inner[k]);
            CHECK(apart);
        }
        for (int k = 0; k < 3; ++k) CHECK(certipose::subset(inner[k], b[k]));  // the rest holds inner
        for (int s = 0; s < 50; ++s) {
            const Eigen::Vector3d p = random_point(before, rng);
            bool covered = contains(b, p);
            for (const auto& q : pieces) covered = covered || contains(q, p);
            CHECK(covered);
        }
    }
    CHECK(pieces_seen > 300);
}

TEST_CASE("corner boxes pass the predicate that found them") {
    // The valid part: x + y + z ≤ 1 (a half-space through the unit box).
    const auto ok = [](const box3& q) { return upper(q[0]) + upper(q[1]) + upper(q[2]) <= 1.0; };
    const box3 b = box3::from_bounds({{{0, 1}, {0, 1}, {0, 1}}});
    const auto c = certipose::detail::corner_box(b, ok, 8);
    REQUIRE(c);
    CHECK(ok(*c));
    CHECK(lower((*c)[0]) == 0.0);  // anchored at the corner deepest inside
    CHECK(certipose::volume(*c) > 0.03);  // the best box is 1/27; bisection gets close
    // Nothing certified at any corner: nothing returned.
    CHECK_FALSE(certipose::detail::corner_box(b, [](const box3&) { return false; }, 8));
}

TEST_CASE("merges and growth keep to what the certifier accepts") {
    using pose = certipose::pose_box<I>;
    // "Certified": the position inside the ball |p| ≤ 1 and φ inside [−0.5, 0.5].
    const auto inside = [](const pose& b) {
        double far = 0;
        for (int k = 0; k < 3; ++k) far += std::max(lower(b.position[k]) * lower(b.position[k]), upper(b.position[k]) * upper(b.position[k]));
        return far <= 1.0 && lower(b.orientation[0]) >= -0.5 && upper(b.orientation[0]) <= 0.5;
    };
    pose seed{box3::from_bounds({{{0, 0.1}, {0, 0.1}, {0, 0.1}}}), box3::from_bounds({{{-0.1, 0.1}, {0.5, 0.6}, {0, 0.1}}})};
    REQUIRE(inside(seed));
    const std::array<double, 6> finest{1e-3, 1e-3, 1e-3, 1e-3, 1e-3, 1e-3};
    const pose g = certipose::detail::growth::grow(seed, inside, finest, 400);
    CHECK(inside(g));
    CHECK(certipose::volume(g.position) > 10 * certipose::volume(seed.position));
    CHECK(upper(g.orientation[0]) - lower(g.orientation[0]) > 0.9);
    // Every box it returns contains the seed (faces only move out, also where a turn caps φ, β).
    for (std::size_t k = 0; k < 6; ++k)
        CHECK(certipose::subset(certipose::detail::growth::component(seed, k), certipose::detail::growth::component(g, k)));
    // Around a pose: a box with the pose inside, certified.
    const auto around = certipose::detail::growth::largest_around<I>({0.2, 0.1, 0.0, 0.0, 0.5, 0.0}, inside,
                                                                     {0.1, 0.1, 0.1, 0.1, 0.1, 0.1}, finest, 400);
    REQUIRE(around);
    CHECK(inside(*around));
    CHECK(certipose::contains(around->position, std::array<double, 3>{0.2, 0.1, 0.0}));
    CHECK_FALSE(certipose::detail::growth::largest_around<I>({2, 0, 0, 0, 0.5, 0}, inside, {0.1, 0.1, 0.1, 0.1, 0.1, 0.1},
                                                             finest, 400));
    // Two halves of a box merge into it; a third box beside them does not share a whole face.
    std::vector<box3> halves{box3::from_bounds({{{0, 1}, {0, 1}, {0, 1}}}), box3::from_bounds({{{1, 2}, {0, 1}, {0, 1}}}),
                             box3::from_bounds({{{0, 1}, {1, 1.5}, {0, 1}}})};
    CHECK(certipose::detail::growth::merge_touching_positions(halves, 5.0) == 1);
    REQUIRE(halves.size() == 2);
    CHECK(std::count(halves.begin(), halves.end(), box3::from_bounds({{{0, 2}, {0, 1}, {0, 1}}})) == 1);
    // ... unless the merged box would be too wide.
    std::vector<box3> wide{box3::from_bounds({{{0, 1}, {0, 1}, {0, 1}}}), box3::from_bounds({{{1, 2}, {0, 1}, {0, 1}}})};
    CHECK(certipose::detail::growth::merge_touching_positions(wide, 1.5) == 0);
    // 6D boxes: hull of the orientations when the field of view holds, else their intersection.
    std::vector<pose> six{{halves[0], box3::from_bounds({{{0, 0.2}, {0, 1}, {0, 1}}})},
                          {box3::from_bounds({{{2, 3}, {0, 1}, {0, 1}}}), box3::from_bounds({{{0.1, 0.3}, {0, 1}, {0, 1}}})}};
    CHECK(certipose::detail::growth::merge_touching(six, [](const box3&, const box3&) { return false; }) == 1);
    REQUIRE(six.size() == 1);
    CHECK(six[0].orientation[0] == I(0.1, 0.2));
    // Contained boxes go.
    std::vector<pose> nested{seed, g};
    certipose::detail::growth::drop_contained(nested);
    CHECK(nested.size() == 1);
}

TEST_CASE("growth certifies the slab a face adds, and the slab and the box before make the box after") {
    using pose = certipose::pose_box<I>;
    const pose b{box3::from_bounds({{{0, 1}, {2, 3}, {4, 5}}}), box3::from_bounds({{{-0.1, 0.1}, {0.5, 0.6}, {0, 0.1}}})};
    for (std::size_t k = 0; k < 6; ++k)
        for (int side = 0; side < 2; ++side) {
            pose cand;
            REQUIRE(certipose::detail::growth::moved(b, k, side, 0.25, cand));
            const pose slab = certipose::detail::growth::added_slab(b, cand, k, side);
            for (std::size_t j = 0; j < 6; ++j) {
                const I& s = certipose::detail::growth::component(slab, j);
                const I& o = certipose::detail::growth::component(b, j);
                const I& c = certipose::detail::growth::component(cand, j);
                if (j != k) {
                    CHECK(s == o);
                    continue;
                }
                // Touching the old face and reaching the new one: old ∪ slab = cand, no gap.
                CHECK(certipose::hull(s, o) == c);
                CHECK((side == 0 ? upper(s) == lower(o) : lower(s) == upper(o)));
            }
        }
    // Where only thin boxes are certified (every position width ≤ 0.3), the box still grows:
    // each certified slab is thin, the box they add up to is not.
    const auto thin = [](const pose& p) {
        for (int k = 0; k < 3; ++k)
            if (upper(p.position[k]) - lower(p.position[k]) > 0.3) return false;
        return true;
    };
    const pose seed{box3::from_bounds({{{0, 0.1}, {0, 0.1}, {0, 0.1}}}), box3::from_bounds({{{0, 0.1}, {0, 0.1}, {0, 0.1}}})};
    const pose g = certipose::detail::growth::grow(seed, thin, {0.05, 0.05, 0.05, 0.05, 0.05, 0.05}, 400);
    CHECK(upper(g.position[0]) - lower(g.position[0]) > 0.5);
}

TEST_CASE("dropping contained boxes keeps what comparing every pair keeps") {
    using pose = certipose::pose_box<I>;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<pose> boxes;
    const auto random_box = [&](double size) {
        std::array<std::pair<double, double>, 3> p{}, o{};
        for (int k = 0; k < 3; ++k) {
            const double lo = u(rng) * 2, w = size * (0.2 + u(rng));
            p[k] = {lo, lo + w};
            const double a = u(rng);
            o[k] = {a, a + 0.5 * u(rng)};
        }
        return pose{box3::from_bounds(p), box3::from_bounds(o)};
    };
    // Small boxes, a few large ones (some spanning many cells of the grid), and boxes inside
    // others: shrunk copies, exact duplicates.
    for (int i = 0; i < 400; ++i) boxes.push_back(random_box(0.05));
    for (int i = 0; i < 12; ++i) boxes.push_back(random_box(1.5));
    for (int i = 0; i < 200; ++i) {
        pose b = boxes[static_cast<std::size_t>(u(rng) * 412)];
        if (i % 3 != 0)
            for (std::size_t k = 0; k < 6; ++k) {
                I& c = certipose::detail::growth::component(b, k);
                const double w = upper(c) - lower(c);
                c = I(lower(c) + 0.25 * w * u(rng), upper(c) - 0.25 * w * u(rng));
            }
        boxes.push_back(b);
    }
    // The reference: every box against every box kept before it, largest first.
    std::vector<pose> sorted = boxes;
    std::stable_sort(sorted.begin(), sorted.end(), [](const pose& a, const pose& b) { return certipose::volume(a) > certipose::volume(b); });
    std::vector<pose> expected;
    for (const auto& b : sorted) {
        bool in = false;
        for (const auto& k : expected) {
            bool all = true;
            for (std::size_t j = 0; j < 6 && all; ++j)
                all = certipose::subset(certipose::detail::growth::component(b, j), certipose::detail::growth::component(k, j));
            if (all) { in = true; break; }
        }
        if (!in) expected.push_back(b);
    }
    certipose::detail::growth::drop_contained(boxes);
    CHECK(boxes.size() < 612);  // something was dropped
    REQUIRE(boxes.size() == expected.size());
    const auto key = [](const pose& p) {
        std::array<double, 12> k{};
        for (std::size_t j = 0; j < 6; ++j) {
            k[2 * j] = lower(certipose::detail::growth::component(p, j));
            k[2 * j + 1] = upper(certipose::detail::growth::component(p, j));
        }
        return k;
    };
    std::vector<std::array<double, 12>> got, want;
    for (const auto& b : boxes) got.push_back(key(b));
    for (const auto& b : expected) want.push_back(key(b));
    std::sort(got.begin(), got.end());
    std::sort(want.begin(), want.end());
    CHECK(got == want);
}

template <class C>
concept clearable = requires(C& c) { c.clear(); };

TEST_CASE("shadow cache: keyed by facet and triangle, append-only, its references stable") {
    using cache = certipose::detail::shadow_cache<I>;
    static_assert(!std::is_copy_constructible_v<cache> && !std::is_copy_assignable_v<cache>);
    static_assert(!std::is_move_constructible_v<cache> && !std::is_move_assignable_v<cache>);
    static_assert(!clearable<cache>);  // states point into it: nothing may forget a shadow
    // One plane each, its point a the facet's index: the same triangle's shadow for two facets
    // must be two shadows.
    const auto shadow_of = [](std::size_t facet) {
        certipose::occlusion_shadow s;
        s.count = 1;
        const double a = static_cast<double>(facet);
        s.planes[0].points = {Eigen::Vector3d(a, 0, 0), Eigen::Vector3d(a, 1, 0), Eigen::Vector3d(a, 0, 1)};
        s.planes[0].sign = 1;
        return s;
    };
    cache c;
    int made = 0;
    const auto get = [&](std::size_t facet, std::size_t triangle) -> const certipose::detail::prepared_shadow<I>& {
        return c.get(facet, triangle, [&] { return ++made, shadow_of(facet); });
    };
    const auto* first = &get(3, 7);
    CHECK(&get(4, 7) != first);  // the same triangle for another facet: its own shadow
    CHECK(made == 2);
    CHECK(&get(3, 7) == first);  // built once
    CHECK(made == 2);
    // A facet index past 2^32 is not folded onto a small one (the old key packed both in 64 bits).
    CHECK(&get((std::size_t{1} << 32) + 3, 7) != first);
    for (std::size_t t = 0; t < 5000; ++t) (void)get(3, 100 + t);  // rehashes: the first reference stays valid
    CHECK(&get(3, 7) == first);
    CHECK(c.size() == 5003);
    // The planes' right-hand sides tell the facets apart: n·a with n = (1, 0, 0)... up to sign.
    CHECK(std::abs(upper(first->planes[0].rhs)) == doctest::Approx(3.0));
    CHECK(std::abs(upper(get(4, 7).planes[0].rhs)) == doctest::Approx(4.0));
}
