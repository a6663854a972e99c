// Tests of the camera-region stage (solver/camera_regions.hpp): the text form and its errors,
// box/sphere classification (closed regions, exact for boxes, sound under rounding for spheres),
// and the restriction of a result's VALID boxes — checked against an exact (GMP rational) point
// test at box corners and random points: no VALID position is in a keep-out or outside every
// keep-in, no allowed position is lost, and what stays undecided is BOUNDARY "camera_region".
// Also the records of io/scene_record.hpp in the result JSON (written, read back, absent).
#include <certipose/interval/boost_interval.hpp>
#include <certipose/io/json.hpp>
#include <certipose/solver/camera_regions.hpp>

#include <doctest/doctest.h>

#include <gmpxx.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace {

using I = certipose::boost_interval;
using certipose::camera_region;
using certipose::camera_regions;
using certipose::region_relation;
using certipose::region_verdict;

using point = std::array<double, 3>;

certipose::position_box<I> pbox(point lo, point hi) {
    const certipose::rounding_guard<I> rounding;
    certipose::position_box<I> b;
    for (std::size_t k = 0; k < 3; ++k) b.x[k] = I(lo[k], hi[k]);
    return b;
}

/// Exactly: is `p` in the closed region `r`? (GMP rationals: no rounding at all.)
bool in_region(const point& p, const camera_region& r) {
    const auto& v = r.values;
    if (r.is_box()) {
        for (std::size_t k = 0; k < 3; ++k)
            if (p[k] < v[k] || p[k] > v[k + 3]) return false;
        return true;
    }
    mpq_class d2 = 0;
    for (std::size_t k = 0; k < 3; ++k) {
        const mpq_class d = mpq_class(p[k]) - mpq_class(v[k]);
        d2 += d * d;
    }
    const mpq_class rr = mpq_class(v[3]) * mpq_class(v[3]);
    return d2 <= rr;
}

/// Exactly: may a camera stand at `p`?
bool allowed(const point& p, const camera_regions& regions) {
    for (const auto& r : regions.keep_out)
        if (in_region(p, r)) return false;
    if (regions.keep_in.empty()) return true;
    for (const auto& r : regions.keep_in)
        if (in_region(p, r)) return true;
    return false;
}

bool contains(const certipose::position_box<I>& b, const point& p) {
    for (std::size_t k = 0; k < 3; ++k)
        if (p[k] < certipose::lower(b[k]) || p[k] > certipose::upper(b[k])) return false;
    return true;
}

std::vector<point> corners_and_samples(const certipose::position_box<I>& b, std::mt19937_64& rng, int samples) {
    std::vector<point> out;
    for (const auto& c : certipose::corners(b)) out.push_back(c);
    for (int s = 0; s < samples; ++s) {
        point p{};
        for (std::size_t k = 0; k < 3; ++k)
            p[k] = std::uniform_real_distribution<double>(certipose::lower(b[k]), certipose::upper(b[k]))(rng);
        out.push_back(p);
    }
    return out;
}

std::string message_of(const std::string& text, const std::string& field) {
    try {
        (void)certipose::parse_camera_region(text, field);
    } catch (const certipose::invalid_argument& e) {
        CHECK(e.field() == field);
        return e.what();
    }
    FAIL("no error for '" << text << "'");
    return {};
}

}  // namespace

TEST_CASE("camera regions: the text form, read back exactly, and every error names the text") {
    const camera_region b = certipose::parse_camera_region("box:-0.2,-0.15,-1,0.2,0.15,-0.01");
    CHECK(b.is_box());
    CHECK(b == camera_region::box({-0.2, -0.15, -1}, {0.2, 0.15, -0.01}));
    CHECK(certipose::to_string(b) == "box:-0.2,-0.15,-1,0.2,0.15,-0.01");
    const camera_region s = certipose::parse_camera_region("sphere:0.1,0,0.6,1e-1");
    CHECK_FALSE(s.is_box());
    CHECK(s == camera_region::sphere({0.1, 0, 0.6}, 0.1));
    CHECK(certipose::parse_camera_region(certipose::to_string(s)) == s);
    const double third = 1.0 / 3.0;
    const camera_region odd = camera_region::sphere({third, -third, 1e-300}, 0.1 + 0.2);
    CHECK(certipose::parse_camera_region(certipose::to_string(odd)) == odd);  // bit for bit

    for (const char* text : {"cube:0,0,0,1,1,1", "box", "box0,0,0,1,1,1", "", "sphere;0,0,0,1"})
        CHECK(message_of(text, "--keep-out").find(std::string("'") + text + "'") != std::string::npos);
    CHECK(message_of("box:0,0,0,1,1", "--keep-out").find("expected 6 numbers") != std::string::npos);
    CHECK(message_of("sphere:0,0,0,1,2", "--keep-in").find("expected 4 numbers") != std::string::npos);
    CHECK(message_of("box:0,0,0,1,1,1x", "--keep-out").find("'1x' is not a number") != std::string::npos);
    CHECK(message_of("box:0,0,,1,1,1", "--keep-out").find("'' is not a number") != std::string::npos);
    CHECK(message_of("box:0,0,0,1,1,1,", "--keep-out").find("'' is not a number") != std::string::npos);
    const std::string order = message_of("box:1,0,0,0,1,1", "--keep-out");
    CHECK(order.find("xmin 1 is not below xmax 0") != std::string::npos);
    CHECK(order.find("'box:1,0,0,0,1,1'") != std::string::npos);
    CHECK(order.rfind("--keep-out: ", 0) == 0);
    CHECK(message_of("box:0,0,2,1,1,2", "--keep-out").find("zmin 2 is not below zmax 2") != std::string::npos);
    CHECK(message_of("sphere:0,0,0,0", "--keep-in").find("radius must be positive") != std::string::npos);
    CHECK(message_of("sphere:0,0,0,-1", "--keep-in").find("radius must be positive, got -1") != std::string::npos);
    CHECK(message_of("box:0,0,0,1,1,nan", "--keep-out").find("finite") != std::string::npos);
    CHECK(message_of("sphere:inf,0,0,1", "--keep-out").find("finite") != std::string::npos);

    camera_regions regions;
    regions.keep_out = {camera_region::box({0, 0, 0}, {1, 1, 1}), camera_region::box({0, 0, 0}, {1, 0, 1})};
    CHECK_THROWS_WITH_AS(regions.validate(), doctest::Contains("keep_out[1]: ymin 0 is not below ymax 0"),
                         certipose::invalid_argument);
    regions.keep_out.pop_back();
    regions.keep_in = {camera_region::sphere({0, 0, 0}, std::numeric_limits<double>::infinity())};
    CHECK_THROWS_WITH_AS(regions.validate(), doctest::Contains("keep_in[0]"), certipose::invalid_argument);
    regions.keep_in.clear();
    regions.min_width = -1;
    CHECK_THROWS_AS(regions.validate(), certipose::invalid_argument);
    regions.min_width = 0;
    CHECK_NOTHROW(regions.validate());
    CHECK(regions.width(0.1) == doctest::Approx(0.01));
    regions.min_width = 0.002;
    CHECK(regions.width(0.1) == 0.002);
}

TEST_CASE("camera regions: boxes against box regions, exactly, boundaries included") {
    const camera_region r = camera_region::box({0, 0, 0}, {1, 1, 1});
    CHECK(certipose::relate(pbox({0.2, 0.2, 0.2}, {0.8, 0.8, 0.8}), r) == region_relation::inside);
    CHECK(certipose::relate(pbox({0, 0, 0}, {1, 1, 1}), r) == region_relation::inside);  // closed
    CHECK(certipose::relate(pbox({1.5, 0, 0}, {2, 1, 1}), r) == region_relation::outside);
    CHECK(certipose::relate(pbox({-1, -1, -1}, {-0.5, 2, 2}), r) == region_relation::outside);
    // Touching a face: the face belongs to the region, so the box is not disjoint from it.
    CHECK(certipose::relate(pbox({1, 0, 0}, {2, 1, 1}), r) == region_relation::straddles);
    const double above = std::nextafter(1.0, 2.0);
    CHECK(certipose::relate(pbox({above, 0, 0}, {2, 1, 1}), r) == region_relation::outside);
    CHECK(certipose::relate(pbox({0.5, 0.5, 0.5}, {1.5, 0.6, 0.6}), r) == region_relation::straddles);
    CHECK(certipose::relate(pbox({0.5, 0.5, 0.5}, {above, 0.6, 0.6}), r) == region_relation::straddles);
    // A box enclosing the region straddles it.
    CHECK(certipose::relate(pbox({-1, -1, -1}, {2, 2, 2}), r) == region_relation::straddles);
}

TEST_CASE("camera regions: boxes against spheres, sound under rounding") {
    const camera_region s = camera_region::sphere({0, 0, 0}, 1);
    CHECK(certipose::relate(pbox({-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}), s) == region_relation::inside);
    CHECK(certipose::relate(pbox({0.9, 0.9, 0.9}, {2, 2, 2}), s) == region_relation::outside);  // corner at √2.43 > 1
    CHECK(certipose::relate(pbox({0.5, 0.5, 0.5}, {2, 2, 2}), s) == region_relation::straddles);
    CHECK(certipose::relate(pbox({-2, -2, -2}, {2, 2, 2}), s) == region_relation::straddles);
    // A box beside the sphere on one axis: its nearest point is (1.5, 0, 0).
    CHECK(certipose::relate(pbox({1.5, -0.1, -0.1}, {2, 0.1, 0.1}), s) == region_relation::outside);
    // The box's nearest point exactly on the sphere: touching, not disjoint.
    CHECK(certipose::relate(pbox({1, -0.1, -0.1}, {2, 0.1, 0.1}), s) != region_relation::outside);
    // 0.1 is not a double: the decisions must hold for the doubles given, whatever the rounding.
    const camera_region t = camera_region::sphere({0.1, 0.2, 0.3}, 0.3);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-0.5, 0.8), w(1e-9, 0.3);
    for (int n = 0; n < 20000; ++n) {
        point lo{u(rng), u(rng), u(rng)};
        point hi{lo[0] + w(rng), lo[1] + w(rng), lo[2] + w(rng)};
        const auto b = pbox(lo, hi);
        const region_relation rel = certipose::relate(b, t);
        for (const point& p : corners_and_samples(b, rng, 4)) {
            if (rel == region_relation::inside) REQUIRE(in_region(p, t));
            if (rel == region_relation::outside) REQUIRE_FALSE(in_region(p, t));
        }
    }
}

TEST_CASE("camera regions: keep-in and keep-out verdicts") {
    camera_regions regions;
    CHECK(regions.empty());
    CHECK(regions.classify(pbox({0, 0, 0}, {1, 1, 1})) == region_verdict::allowed);
    regions.keep_out = {camera_region::box({-1, -1, -1}, {1, 1, 0})};
    CHECK(regions.classify(pbox({0, 0, 0.5}, {1, 1, 1})) == region_verdict::allowed);
    CHECK(regions.classify(pbox({0, 0, -0.5}, {0.5, 0.5, -0.1})) == region_verdict::forbidden);
    CHECK(regions.classify(pbox({0, 0, -0.5}, {0.5, 0.5, 0.5})) == region_verdict::undecided);
    regions.keep_in = {camera_region::sphere({0, 0, 1}, 0.5), camera_region::box({5, 5, 5}, {6, 6, 6})};
    CHECK(regions.classify(pbox({-0.1, -0.1, 0.9}, {0.1, 0.1, 1.1})) == region_verdict::allowed);
    CHECK(regions.classify(pbox({5.1, 5.1, 5.1}, {5.2, 5.2, 5.2})) == region_verdict::allowed);
    CHECK(regions.classify(pbox({3, 3, 3}, {4, 4, 4})) == region_verdict::forbidden);  // outside every keep-in
    CHECK(regions.classify(pbox({0, 0, 0.9}, {1, 1, 1})) == region_verdict::undecided);
    // Inside a keep-in but touching a keep-out: not allowed as a whole.
    regions.keep_out.push_back(camera_region::box({5.5, 5.5, 5.5}, {7, 7, 7}));
    CHECK(regions.classify(pbox({5.1, 5.1, 5.1}, {5.5, 5.2, 5.2})) == region_verdict::allowed);
    CHECK(regions.classify(pbox({5.5, 5.5, 5.5}, {5.6, 5.6, 5.6})) == region_verdict::forbidden);
    CHECK(regions.classify(pbox({5.1, 5.1, 5.1}, {5.6, 5.6, 5.6})) == region_verdict::undecided);
}

TEST_CASE("camera regions: the restriction keeps no VALID position outside the allowed space, and loses none inside") {
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> centre(-0.6, 0.6), size(0.05, 0.5), radius(0.05, 0.6);
    const auto random_region = [&] {
        if (rng() % 2) {
            const point c{centre(rng), centre(rng), centre(rng)};
            const point h{size(rng), size(rng), size(rng)};
            return camera_region::box({c[0] - h[0], c[1] - h[1], c[2] - h[2]}, {c[0] + h[0], c[1] + h[1], c[2] + h[2]});
        }
        return camera_region::sphere({centre(rng), centre(rng), centre(rng)}, radius(rng));
    };
    std::size_t valid_after = 0, undecided_after = 0, dropped = 0;
    for (int trial = 0; trial < 60; ++trial) {
        camera_regions regions;
        for (std::size_t n = rng() % 3; n-- > 0;) regions.keep_in.push_back(random_region());
        for (std::size_t n = 1 + rng() % 3; n-- > 0;) regions.keep_out.push_back(random_region());
        const double eps = 0.2;  // pieces down to eps / 10

        certipose::solve_result<I> r;
        const certipose::orientation_box<I> angles = pbox({0.1, 0.2, 0.3}, {0.2, 0.4, 0.5});
        std::vector<certipose::position_box<I>> originals;
        for (int k = 0; k < 6; ++k) {
            const point lo{centre(rng), centre(rng), centre(rng)};
            const auto p = pbox(lo, {lo[0] + size(rng), lo[1] + size(rng), lo[2] + size(rng)});
            originals.push_back(p);
            r.boxes.push_back({certipose::box_class::valid, {p, angles}});
            if (k == 2) r.boxes.push_back({certipose::box_class::valid, {p, pbox({1, 1, 1}, {1.1, 1.1, 1.1})}});
        }
        const auto untouched = pbox({-3, -3, -3}, {3, 3, 3});
        r.boxes.push_back({certipose::box_class::boundary, {untouched, angles}, certipose::boundary_reason::distance});
        r.stats.valid = 7;
        r.stats.boundary = 1;
        r.stats.boundary_reasons[static_cast<std::size_t>(certipose::boundary_reason::distance)] = 1;

        certipose::restrict_to_regions(r, regions, eps);

        std::size_t valid = 0, by_region = 0, boundary_other = 0;
        for (const auto& b : r.boxes) {
            if (b.cls == certipose::box_class::valid) {
                ++valid;
                // Soundness: every corner and sampled point of a VALID box may hold a camera.
                for (const point& p : corners_and_samples(b.box.position, rng, 20)) REQUIRE(allowed(p, regions));
                CHECK(regions.classify(b.box.position) == region_verdict::allowed);
            } else if (b.reason == certipose::boundary_reason::camera_region) {
                ++by_region;
                CHECK(regions.classify(b.box.position) == region_verdict::undecided);
                CHECK(certipose::max_width(b.box.position) <= regions.width(eps));
            } else {
                ++boundary_other;
                CHECK(b.box.position == untouched);  // the solve's BOUNDARY boxes are left alone
            }
            // Orientations untouched: each piece keeps its VALID box's intervals.
            const bool second = b.box.orientation == pbox({1, 1, 1}, {1.1, 1.1, 1.1});
            CHECK((b.box.orientation == angles || second));
            if (second) CHECK(certipose::subset(b.box.position, originals[2]));
        }
        CHECK(r.stats.valid == valid);
        CHECK(boundary_other == 1);
        CHECK(r.stats.boundary == 1 + by_region);
        CHECK(r.stats.boundary_reasons[static_cast<std::size_t>(certipose::boundary_reason::camera_region)] == by_region);
        valid_after += valid, undecided_after += by_region, dropped += r.stats.region_dropped;

        // Completeness: an allowed position of an original VALID box is in a VALID or an
        // undecided piece of it.
        for (const auto& o : originals)
            for (const point& p : corners_and_samples(o, rng, 40)) {
                if (!allowed(p, regions)) continue;
                bool found = false;
                for (const auto& b : r.boxes)
                    if (b.box.orientation == angles && b.box.position != untouched && contains(b.box.position, p)) found = true;
                REQUIRE(found);
            }
    }
    // The trials cut, dropped and kept boxes (the checks above were not vacuous).
    CHECK(valid_after > 0);
    CHECK(undecided_after > 0);
    CHECK(dropped > 0);
}

TEST_CASE("camera regions: no regions change nothing, a wholly allowed box is kept, a wholly forbidden one dropped") {
    certipose::solve_result<I> r;
    const auto p = pbox({0, 0, 0}, {1, 1, 1});
    r.boxes.push_back({certipose::box_class::valid, {p, p}});
    r.stats.valid = 1;
    r.stats.valid_volume = 1;
    const auto before = r.boxes;
    certipose::restrict_to_regions(r, camera_regions{}, 0.1);
    CHECK(r.boxes.size() == 1);
    CHECK(r.boxes[0].box == before[0].box);
    camera_regions far;
    far.keep_out = {camera_region::sphere({5, 5, 5}, 1)};
    certipose::restrict_to_regions(r, far, 0.1);
    CHECK(r.boxes.size() == 1);
    CHECK(r.boxes[0].box == before[0].box);
    CHECK(r.stats.valid == 1);
    CHECK(r.stats.valid_volume == 1);
    CHECK(r.stats.region_bisections == 0);
    // A keep-out over the whole box drops it.
    camera_regions all;
    all.keep_out = {camera_region::box({-1, -1, -1}, {2, 2, 2})};
    certipose::restrict_to_regions(r, all, 0.1);
    CHECK(r.boxes.empty());
    CHECK(r.stats.valid == 0);
    CHECK(r.stats.region_dropped == 1);
    CHECK(r.stats.valid_volume == 0);
}

TEST_CASE("camera regions: occluders and regions in the result JSON, and files without them") {
    using namespace certipose;
    result_document d;
    d.settings.position_eps = 0.1;
    d.settings.orientation_eps = 0.38;
    d.camera.width_px = 10, d.camera.height_px = 10, d.camera.d_min = 0.1, d.camera.d_max = 1;
    d.scene.occluders = {{"fixture_plate.off", 0.001, 12, "0123456789abcdef"}};
    d.scene.regions.keep_in = {camera_region::sphere({0, 0, 0.3}, 1.0 / 3.0)};
    d.scene.regions.keep_out = {camera_region::box({-1, -1, -1}, {1, 1, -0.01}), camera_region::sphere({0.1, 0, 0.5}, 0.05)};
    const nlohmann::ordered_json j = result_to_json(d);
    CHECK(j["occluders"][0]["path"] == "fixture_plate.off");
    CHECK(j["occluders"][0]["digest"] == "0123456789abcdef");
    CHECK(j["keep_out"][0].contains("box"));
    CHECK(j["keep_out"][1]["sphere"].size() == 4);
    const result_document back = parse_result_json(json_text(j));
    CHECK(back.scene == d.scene);  // bit for bit

    nlohmann::json old = nlohmann::json::parse(json_text(j));
    old.erase("occluders"), old.erase("keep_in"), old.erase("keep_out");
    CHECK(result_from_json(old).scene.empty());

    nlohmann::json bad = nlohmann::json::parse(json_text(j));
    bad["keep_out"][1]["sphere"][3] = -1;
    CHECK_THROWS_WITH_AS(result_from_json(bad), doctest::Contains("keep_out[1]: the radius must be positive"),
                         invalid_argument);
    bad = nlohmann::json::parse(json_text(j));
    bad["keep_in"][0] = {{"cylinder", {0, 0, 0, 1}}};
    CHECK_THROWS_WITH_AS(result_from_json(bad), doctest::Contains("keep_in[0]"), invalid_argument);
    bad = nlohmann::json::parse(json_text(j));
    bad["occluders"][0].erase("digest");
    CHECK_THROWS_WITH_AS(result_from_json(bad), doctest::Contains("occluders[0].digest"), invalid_argument);
}

TEST_CASE("camera regions: box regions are cut exactly on their faces, leaving nothing undecided") {
    // A keep-out slab through the middle of a VALID box and a keep-in that clips one corner: the
    // pieces are decided in a few exact cuts, however small ε_p is (no halving to ε_p / 10).
    certipose::solve_result<I> r;
    const auto p = pbox({0, 0, 0}, {1, 1, 1});
    r.boxes.push_back({certipose::box_class::valid, {p, p}});
    r.stats.valid = 1;
    r.stats.valid_volume = 1;
    camera_regions regions;
    regions.keep_out = {camera_region::box({-1, -1, 0.4}, {2, 2, 0.6})};
    regions.keep_in = {camera_region::box({0.25, -1, -1}, {2, 2, 2})};
    certipose::restrict_to_regions(r, regions, 1e-6);
    std::size_t valid = 0;
    double volume = 0;
    for (const auto& b : r.boxes) {
        CHECK(b.cls == certipose::box_class::valid);  // nothing undecided
        ++valid;
        volume += certipose::volume(b.box.position);
        CHECK(regions.classify(b.box.position) == region_verdict::allowed);
        // The faces are kept to the last double: the pieces touch the regions' planes.
        CHECK((upper(b.box.position[2]) == std::nextafter(0.4, -INFINITY) || lower(b.box.position[2]) == std::nextafter(0.6, INFINITY)));
        CHECK(lower(b.box.position[0]) == 0.25);
    }
    CHECK(valid == 2);
    CHECK(r.stats.region_bisections <= 6);
    CHECK(std::abs(volume - 0.75 * 0.8) < 1e-12);
}
