// The interval test suite, written once over the backend type and instantiated per backend:
// tests/core/interval.cpp (boost_interval, no CGAL) and tests/cgal/interval_cgal.cpp
// (cgal_interval). Each TEST_CASE_TEMPLATE_DEFINE below is invoked there by its id.
//
// What would catch an unsound backend:
//  * constants the compiler can see (1/3, cos(0.7935), sqrt(2), ...) keep a strictly positive
//    width — at -O2 g++ folded 1/3 to a point and evaluated sqrt once for both bounds;
//  * the inclusion property: for every operation, 10⁴ random points of random boxes, evaluated
//    in plain double arithmetic OUTSIDE any rounding guard (round-to-nearest), lie inside the
//    interval result. Boxes include points, zero-touching and zero-straddling ones, huge and
//    tiny magnitudes, sin/cos boxes across kπ and π/2 + kπ, wide and 1e6-large arguments, atan2
//    boxes in every quadrant, across the branch cut and touching the axes. A libm result within
//    one ulp of the truth stays inside any sound enclosure with double bounds, so the reference
//    needs no slack;
//  * the empty set propagates through every operation, and the rounding guard restores the
//    caller's mode;
//  * Eigen expressions over intervals (products with interval and double matrices, dot,
//    cross, squared norm) enclose the same expressions on points. The including file must
//    include the backend's Eigen traits first (interval/eigen.hpp or interval/cgal_eigen.hpp).
#pragma once

#include <certipose/interval/concept.hpp>
#include <certipose/interval/operations.hpp>
#include <certipose/pose/interval_box.hpp>

#include <doctest/doctest.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cfenv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#if defined(__x86_64__) || defined(_M_X64)
#include <xmmintrin.h>
#endif

namespace certipose_test {

using bounds = std::pair<double, double>;

inline constexpr double inf_v = std::numeric_limits<double>::infinity();
inline constexpr double nan_v = std::numeric_limits<double>::quiet_NaN();
inline constexpr double pi_v = std::numbers::pi;

/// Random source for the property tests (fixed seeds: failures reproduce).
struct random_source {
    std::mt19937_64 engine;
    explicit random_source(std::uint64_t seed) : engine(seed) {}
    double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(engine); }
    int integer(int a, int b) { return std::uniform_int_distribution<int>(a, b)(engine); }
    bool chance(double p) { return uniform(0.0, 1.0) < p; }
};

/// A point of [l, u]: often an endpoint (where rounding bites), else uniform inside.
inline double point_in(random_source& r, bounds b) {
    const auto [l, u] = b;
    switch (r.integer(0, 3)) {
        case 0: if (std::isfinite(l)) return l; break;
        case 1: if (std::isfinite(u)) return u; break;
        default: break;
    }
    if (!std::isfinite(l) || !std::isfinite(u)) {  // unbounded: a finite point, often far out
        const double far = r.chance(0.2) ? 0.0 : r.uniform(0.0, 1.0) * std::pow(10.0, r.uniform(-3.0, 8.0));
        if (std::isfinite(l)) return l + far;
        if (std::isfinite(u)) return u - far;
        return r.chance(0.5) ? far : -far;
    }
    return std::clamp(l + r.uniform(0.0, 1.0) * (u - l), l, u);
}

/// Boxes of every shape and magnitude: points, a few ulps wide, wide, touching or straddling 0.
inline bounds general_box(random_source& r, double max_scale = 1e8) {
    const std::array<double, 8> scales{1e-300, 1e-8, 1.0, 1.0, 1.0, 1.0, 1e3, max_scale};
    const double s = scales[static_cast<std::size_t>(r.integer(0, 7))];
    const double c = r.uniform(-1.0, 1.0) * s;
    const double w = r.uniform(0.0, 1.0) * s * (r.chance(0.3) ? 3.0 : 0.5);
    switch (r.integer(0, 9)) {
        case 0: return {c, c};                                  // point
        case 1: return {c, c + std::abs(c) * 4e-16};            // a few ulps
        case 2: return {0.0, std::abs(c) + w};                  // touching 0 from above
        case 3: return {-(std::abs(c) + w), 0.0};               // touching 0 from below
        case 4: return {-w, w};                                 // symmetric about 0
        case 5: return {0.0, 0.0};
        case 6: { const double k = std::round(c); return {k, k}; }  // integers (exact products)
        default: return {c - w, c + w};
    }
}

/// Boxes for sin and cos: across the extrema kπ and π/2 + kπ, wide, large arguments, tiny.
inline bounds trig_box(random_source& r) {
    switch (r.integer(0, 6)) {
        case 0: return general_box(r);
        case 1:
        case 2: {  // across an extremum k·π/2
            const double c = r.integer(-40, 40) * (pi_v / 2) + r.uniform(-1e-3, 1e-3);
            const double w = r.chance(0.5) ? r.uniform(0.0, 1e-3) : r.uniform(0.0, 0.8);
            return {c - w, c + w};
        }
        case 3: {  // wide, up to three periods
            const double c = r.uniform(-20.0, 20.0), w = r.uniform(1.0, 10.0);
            return {c - w, c + w};
        }
        case 4: {  // large arguments
            const std::array<double, 4> s{1e6, 1e6, 1e9, 1e15};
            const double c = s[static_cast<std::size_t>(r.integer(0, 3))] * r.uniform(0.5, 1.0) * (r.chance(0.5) ? 1 : -1);
            const double w = r.chance(0.3) ? 0.0 : r.uniform(0.0, 1e-3) + std::abs(c) * 1e-15;
            return {c - w, c + w};
        }
        case 5: {  // an endpoint exactly on the double nearest k·π/2
            const double t = r.integer(-12, 12) * (pi_v / 2);
            const double w = r.uniform(0.0, 0.5);
            return r.chance(0.5) ? bounds{t, t + w} : bounds{t - w, t};
        }
        default: {  // tiny, near 0
            const double c = r.uniform(-1e-8, 1e-8), w = r.uniform(0.0, 1e-8);
            return {c - w, c + w};
        }
    }
}

/// Boxes around the domain [−1, 1] of acos (some leave it, some touch ±1).
inline bounds unit_box(random_source& r) {
    const double w = r.chance(0.2) ? 0.0 : (r.chance(0.3) ? 1e-10 : r.uniform(0.0, 0.4));
    switch (r.integer(0, 5)) {
        case 0: return {1.0 - w, 1.0};
        case 1: return {-1.0, -1.0 + w};
        case 2: return {-1.0, 1.0};
        default: { const double c = r.uniform(-1.3, 1.3); return {c - w, c + w}; }
    }
}

/// One coordinate of an atan2 box: positive, negative, touching 0 from either side,
/// straddling 0, exactly 0, or a nonzero point; magnitudes from 1e-8 to 1e5.
inline bounds axis_box(random_source& r) {
    const std::array<double, 4> s{1e-8, 1.0, 1.0, 1e5};
    const double m = s[static_cast<std::size_t>(r.integer(0, 3))];
    const double a = r.uniform(0.01, 1.0) * m, b = a + r.uniform(0.0, 2.0) * m;
    switch (r.integer(0, 7)) {
        case 0: return {a, b};
        case 1: return {-b, -a};
        case 2: return {0.0, b};
        case 3: return {-b, 0.0};
        case 4: return {-a, b};
        case 5: return {0.0, 0.0};
        case 6: return {a, a};
        default: return {-a, -a};
    }
}

/// One draw of the inclusion test: boxes a, b, points x ∈ a, y ∈ b, an exponent n.
struct sample {
    bounds a{}, b{};
    double x = 0, y = 0;
    int n = 0;
};

inline std::string format_sample(const char* what, const sample& s, double reference, double lo, double hi) {
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "%s: a=[%.17g, %.17g] b=[%.17g, %.17g] n=%d x=%.17g y=%.17g: reference %.17g "
                  "not in [%.17g, %.17g]",
                  what, s.a.first, s.a.second, s.b.first, s.b.second, s.n, s.x, s.y, reference, lo, hi);
    return buf;
}

inline constexpr int inclusion_samples = 10000;

/// The inclusion property for one operation. `gen` draws a sample, `point` evaluates it in
/// double (here, outside any guard: round-to-nearest), `enclose` in intervals (inside one
/// guard). A NaN reference means the point is outside the domain (x/0, sqrt(−1), ...) and is
/// skipped; at least half the samples must be in the domain.
template <class I, class Gen, class Point, class Enclose>
void check_inclusion(const char* what, std::uint64_t seed, Gen gen, Point point, Enclose enclose) {
    random_source r(seed);
    std::vector<sample> samples(inclusion_samples);
    std::vector<double> reference(inclusion_samples);
    for (int i = 0; i < inclusion_samples; ++i) {
        samples[i] = gen(r);
        reference[i] = point(samples[i]);
    }
    std::vector<I> result;
    result.reserve(samples.size());
    {
        const certipose::rounding_guard<I> guard;
        for (const sample& s : samples) result.push_back(enclose(I(s.a.first, s.a.second), I(s.b.first, s.b.second), s));
    }
    int checked = 0, failures = 0;
    std::string first;
    for (int i = 0; i < inclusion_samples; ++i) {
        if (std::isnan(reference[i])) continue;
        ++checked;
        if (!certipose::contains(result[i], reference[i])) {
            if (failures++ == 0)
                first = format_sample(what, samples[i], reference[i], lower(result[i]), upper(result[i]));
        }
    }
    INFO(std::string(what));
    CHECK_MESSAGE(failures == 0, first);
    CHECK(checked >= inclusion_samples / 2);
}

// Sample generators.
inline sample one_general(random_source& r) {
    sample s;
    s.a = general_box(r);
    s.x = point_in(r, s.a);
    return s;
}
inline sample two_general(random_source& r) {
    sample s;
    s.a = general_box(r);
    s.b = general_box(r);
    s.x = point_in(r, s.a);
    s.y = point_in(r, s.b);
    return s;
}
/// Huge magnitudes too, so products and quotients overflow and underflow.
inline sample two_extreme(random_source& r) {
    sample s;
    s.a = general_box(r, 1e160);
    s.b = general_box(r, 1e160);
    s.x = point_in(r, s.a);
    s.y = point_in(r, s.b);
    return s;
}
/// Unbounded boxes ([c, ∞), (−∞, c], the whole line, [0, ∞), ...) against zero-touching and
/// ordinary ones, where a product meets 0·∞ at a corner. Points stay finite.
inline bounds unbounded_box(random_source& r) {
    const double c = r.chance(0.3) ? 0.0 : r.uniform(-5.0, 5.0);
    switch (r.integer(0, 5)) {
        case 0: return {c, inf_v};
        case 1: return {-inf_v, c};
        case 2: return {-inf_v, inf_v};
        default: return general_box(r, 10.0);
    }
}
inline sample two_unbounded(random_source& r) {
    sample s;
    s.a = unbounded_box(r);
    s.b = unbounded_box(r);
    s.x = point_in(r, s.a);
    s.y = point_in(r, s.b);
    return s;
}
/// Interval with a double: b is the point {y, y}.
inline sample general_and_double(random_source& r) {
    sample s = two_general(r);
    s.b = {s.y, s.y};
    return s;
}

inline double sqr_point(double x) { return x * x; }
inline double atan2_point(double y, double x) { return std::atan2(y == 0.0 ? 0.0 : y, x); }  // −0 is 0

/// The mode the SSE unit (x86-64 double arithmetic) rounds in, as an FE_* value.
inline int sse_rounding() {
#if defined(__x86_64__) || defined(_M_X64)
    switch (_MM_GET_ROUNDING_MODE()) {
        case _MM_ROUND_UP: return FE_UPWARD;
        case _MM_ROUND_DOWN: return FE_DOWNWARD;
        case _MM_ROUND_TOWARD_ZERO: return FE_TOWARDZERO;
        default: return FE_TONEAREST;
    }
#else
    return std::fegetround();
#endif
}

}  // namespace certipose_test

// ---- widths that a constant-folding or CSE-ing compiler would collapse ------------------------

TEST_CASE_TEMPLATE_DEFINE("interval: results on visible constants keep a positive width", I, interval_constant_width) {
    using namespace certipose;
    // The same expressions in double, computed first, in round-to-nearest: a compiler that
    // ignores the rounding mode may reuse them inside the guard (g++ did, for 1/3 and sqrt 2).
    const std::vector<double> nearest{
        1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0, std::cos(0.7935), std::sqrt(2.0), 0.1 + 0.2, 0.1 - 0.7,
        0.1 * 3.0, 3.0 * 0.1, 0.1 * 0.1, 1.1 * 1.1 * 1.1, 1.0 / 3.0, std::sin(1.0), std::acos(0.3),
        std::atan(0.5), std::atan2(1.0, 3.0)};
    std::vector<std::pair<const char*, I>> r;
    {
        const rounding_guard<I> guard;
        r = {{"1/3", I(1.0) / I(3.0)},           {"1/3 (double divisor)", I(1.0) / 3.0},
             {"1/3 (double dividend)", 1.0 / I(3.0)}, {"cos(0.7935)", cos(I(0.7935))},
             {"sqrt(2)", sqrt(I(2.0))},           {"0.1+0.2", I(0.1) + I(0.2)},
             {"0.1-0.7", I(0.1) - 0.7},           {"0.1*3", I(0.1) * I(3.0)},
             {"3*0.1", 3.0 * I(0.1)},             {"sqr(0.1)", sqr(I(0.1))},
             {"pow(1.1,3)", pow(I(1.1), 3)},      {"pow(3,-1)", pow(I(3.0), -1)},
             {"sin(1)", sin(I(1.0))},             {"acos(0.3)", acos(I(0.3))},
             {"atan(0.5)", atan(I(0.5))},         {"atan2(1,3)", atan2(I(1.0), I(3.0))}};
    }
    REQUIRE(r.size() == nearest.size());
    for (std::size_t i = 0; i < r.size(); ++i) {
        const auto& [name, v] = r[i];
        INFO(std::string(name));
        CHECK_FALSE(is_empty(v));
        CHECK(lower(v) < upper(v));  // every one of these results is irrational or inexact
        CHECK(width(v) > 0.0);
        if (i != 10) CHECK(contains(v, nearest[i]));  // (1.1·1.1)·1.1 rounds twice
    }
    const I root2 = r[4].second;
    CHECK(upper(root2) * upper(root2) > 2.0);  // √2 is irrational: strictly inside
    CHECK(lower(root2) * lower(root2) < 2.0);
}

// ---- the inclusion property, one operation at a time -------------------------------------------

TEST_CASE_TEMPLATE_DEFINE("interval: + - * / of two intervals contain every point result", I, interval_inclusion_arith) {
    using namespace certipose_test;
    for (auto gen : {two_general, two_extreme, two_unbounded}) {
        const std::uint64_t salt = gen == two_general ? 0 : (gen == two_extreme ? 100 : 200);
        check_inclusion<I>("a + b", 1 + salt, gen, [](const sample& s) { return s.x + s.y; },
                           [](const I& a, const I& b, const sample&) { return a + b; });
        check_inclusion<I>("a - b", 2 + salt, gen, [](const sample& s) { return s.x - s.y; },
                           [](const I& a, const I& b, const sample&) { return a - b; });
        check_inclusion<I>("a * b", 3 + salt, gen, [](const sample& s) { return s.x * s.y; },
                           [](const I& a, const I& b, const sample&) { return a * b; });
        check_inclusion<I>("a / b", 4 + salt, gen,
                           [](const sample& s) { return s.y == 0.0 ? nan_v : s.x / s.y; },
                           [](const I& a, const I& b, const sample&) { return a / b; });
    }
    // Compound assignment is the same operation.
    check_inclusion<I>("a *= b", 5, two_general, [](const sample& s) { return s.x * s.y; },
                       [](I a, const I& b, const sample&) { return a *= b; });
    check_inclusion<I>("a -= b", 6, two_general, [](const sample& s) { return s.x - s.y; },
                       [](I a, const I& b, const sample&) { return a -= b; });
}

TEST_CASE_TEMPLATE_DEFINE("interval: + - * / with a double contain every point result", I, interval_inclusion_mixed) {
    using namespace certipose_test;
    const auto gen = general_and_double;
    check_inclusion<I>("a + d", 11, gen, [](const sample& s) { return s.x + s.y; },
                       [](const I& a, const I&, const sample& s) { return a + s.y; });
    check_inclusion<I>("d + a", 12, gen, [](const sample& s) { return s.y + s.x; },
                       [](const I& a, const I&, const sample& s) { return s.y + a; });
    check_inclusion<I>("a - d", 13, gen, [](const sample& s) { return s.x - s.y; },
                       [](const I& a, const I&, const sample& s) { return a - s.y; });
    check_inclusion<I>("d - a", 14, gen, [](const sample& s) { return s.y - s.x; },
                       [](const I& a, const I&, const sample& s) { return s.y - a; });
    check_inclusion<I>("a * d", 15, gen, [](const sample& s) { return s.x * s.y; },
                       [](const I& a, const I&, const sample& s) { return a * s.y; });
    check_inclusion<I>("d * a", 16, gen, [](const sample& s) { return s.y * s.x; },
                       [](const I& a, const I&, const sample& s) { return s.y * a; });
    check_inclusion<I>("a / d", 17, gen, [](const sample& s) { return s.y == 0.0 ? nan_v : s.x / s.y; },
                       [](const I& a, const I&, const sample& s) { return a / s.y; });
    check_inclusion<I>("d / a", 18, gen, [](const sample& s) { return s.x == 0.0 ? nan_v : s.y / s.x; },
                       [](const I& a, const I&, const sample& s) { return s.y / a; });
}

TEST_CASE_TEMPLATE_DEFINE("interval: unary -, sqr, sqrt, abs and integer pow contain every point result", I,
                          interval_inclusion_algebraic) {
    using namespace certipose_test;
    check_inclusion<I>("-a", 21, one_general, [](const sample& s) { return -s.x; },
                       [](const I& a, const I&, const sample&) { return -a; });
    check_inclusion<I>("sqr(a)", 22, one_general, [](const sample& s) { return sqr_point(s.x); },
                       [](const I& a, const I&, const sample&) { return sqr(a); });
    check_inclusion<I>("sqrt(a)", 23, one_general, [](const sample& s) { return s.x < 0.0 ? nan_v : std::sqrt(s.x); },
                       [](const I& a, const I&, const sample&) { return sqrt(a); });
    check_inclusion<I>("abs(a)", 24, one_general, [](const sample& s) { return std::abs(s.x); },
                       [](const I& a, const I&, const sample&) { return abs(a); });
    // Exponents -7..12: negative, zero, even and odd. Bases within 1e3 keep x^12 finite.
    const auto pow_gen = [](random_source& r) {
        sample s;
        s.a = r.chance(0.5) ? general_box(r, 1e3) : bounds{r.uniform(-3.0, 1.0), r.uniform(1.0, 3.0)};
        if (s.a.first > s.a.second) std::swap(s.a.first, s.a.second);
        s.x = point_in(r, s.a);
        s.n = r.integer(-7, 12);
        return s;
    };
    check_inclusion<I>("pow(a, n)", 25, pow_gen,
                       [](const sample& s) { return s.n < 0 && s.x == 0.0 ? nan_v : std::pow(s.x, s.n); },
                       [](const I& a, const I&, const sample& s) { return pow(a, s.n); });
}

TEST_CASE_TEMPLATE_DEFINE("interval: sin and cos contain every point result (extrema, wide, large)", I,
                          interval_inclusion_trig) {
    using namespace certipose_test;
    const auto gen = [](random_source& r) {
        sample s;
        s.a = trig_box(r);
        s.x = point_in(r, s.a);
        return s;
    };
    check_inclusion<I>("sin(a)", 31, gen, [](const sample& s) { return std::sin(s.x); },
                       [](const I& a, const I&, const sample&) { return sin(a); });
    check_inclusion<I>("cos(a)", 32, gen, [](const sample& s) { return std::cos(s.x); },
                       [](const I& a, const I&, const sample&) { return cos(a); });

    // The extrema themselves: a box across π/2 + 2kπ reaches sin = 1 exactly, across kπ the
    // cosine reaches ±1, and sin/cos never leave [−1, 1].
    using namespace certipose;
    for (int k = -20; k <= 20; ++k) {
        const double top = pi_v / 2 + 2 * k * pi_v, turn = k * pi_v;
        I s, c, w;
        {
            const rounding_guard<I> guard;
            s = sin(I(top - 1e-3, top + 1e-3));
            c = cos(I(turn - 1e-3, turn + 1e-3));
            w = cos(I(turn, turn + 100.0));
        }
        INFO("k = " << k);
        CHECK(upper(s) == 1.0);
        CHECK(lower(s) < 1.0);
        CHECK(upper(c) >= (k % 2 == 0 ? 1.0 : -1.0 + 1e-7));
        CHECK(lower(c) <= (k % 2 == 0 ? 1.0 - 1e-7 : -1.0));
        CHECK(lower(w) == -1.0);
        CHECK(upper(w) == 1.0);
    }
    {
        I huge_s, huge_c, inf_s;
        {
            const rounding_guard<I> guard;
            huge_s = sin(I(1e300));
            huge_c = cos(I(1e17, 1e17));
            inf_s = sin(I(0.0, inf_v));
        }
        for (const I& v : {huge_s, huge_c, inf_s}) {
            CHECK(subset(v, I(-1.0, 1.0)));
            CHECK_FALSE(is_empty(v));
        }
        CHECK(contains(huge_s, std::sin(1e300)));
        CHECK(contains(huge_c, std::cos(1e17)));
    }
}

TEST_CASE_TEMPLATE_DEFINE("interval: acos and atan contain every point result", I, interval_inclusion_inverse_trig) {
    using namespace certipose_test;
    const auto unit_gen = [](random_source& r) {
        sample s;
        s.a = unit_box(r);
        s.x = point_in(r, s.a);
        return s;
    };
    check_inclusion<I>("acos(a)", 41, unit_gen, [](const sample& s) { return std::abs(s.x) > 1.0 ? nan_v : std::acos(s.x); },
                       [](const I& a, const I&, const sample&) { return acos(a); });
    check_inclusion<I>("atan(a)", 42, one_general, [](const sample& s) { return std::atan(s.x); },
                       [](const I& a, const I&, const sample&) { return atan(a); });
    using namespace certipose;
    I outside, whole_atan;
    {
        const rounding_guard<I> guard;
        outside = acos(I(1.5, 2.0));
        whole_atan = atan(interval_traits<I>::whole());
    }
    CHECK(is_empty(outside));  // no point of [1.5, 2] is in the domain
    CHECK(contains(whole_atan, std::atan(1e308)));
    CHECK(contains(whole_atan, -pi_v / 2));
    CHECK(subset(whole_atan, I(-1.5707963268, 1.5707963268)));
}

TEST_CASE_TEMPLATE_DEFINE("interval: atan2 contains every point result (quadrants, cut, axes)", I,
                          interval_inclusion_atan2) {
    using namespace certipose_test;
    const auto gen = [](random_source& r) {
        sample s;
        s.a = axis_box(r);  // y
        s.b = axis_box(r);  // x
        s.x = point_in(r, s.a);
        s.y = point_in(r, s.b);
        return s;
    };
    check_inclusion<I>("atan2(y, x)", 51, gen, [](const sample& s) { return atan2_point(s.x, s.y); },
                       [](const I& y, const I& x, const sample&) { return atan2(y, x); });

    using namespace certipose;
    I q1, cut_above, across_cut, origin, touching_y_axis;
    {
        const rounding_guard<I> guard;
        q1 = atan2(I(1.0, 2.0), I(1.0, 2.0));
        cut_above = atan2(I(0.0, 1.0), I(-2.0, -1.0));
        across_cut = atan2(I(-1.0, 1.0), I(-2.0, -1.0));
        origin = atan2(I(-1.0, 1.0), I(0.0, 1.0));
        touching_y_axis = atan2(I(1.0, 2.0), I(0.0, 1.0));
    }
    CHECK(subset(q1, I(0.4636, 1.1072)));                // [atan(1/2), atan(2)]
    CHECK(contains(cut_above, pi_v));                     // y = 0 on the upper side of the cut
    CHECK(lower(cut_above) > 2.0);
    CHECK(contains(across_cut, pi_v));
    CHECK(contains(across_cut, -pi_v));
    CHECK(contains(origin, 0.0));
    CHECK(lower(origin) <= -pi_v);
    CHECK(contains(touching_y_axis, pi_v / 2));
    CHECK(upper(touching_y_axis) < 1.5708);
}

// ---- the empty set ---------------------------------------------------------------------------

TEST_CASE_TEMPLATE_DEFINE("interval: the empty set propagates through every operation", I, interval_empty) {
    using namespace certipose;
    const I e = interval_traits<I>::empty();
    const I a(1.0, 2.0);
    CHECK(is_empty(e));
    CHECK(is_empty(I(2.0, 1.0)));
    CHECK(is_empty(I(certipose_test::nan_v, 1.0)));
    CHECK(is_empty(I(certipose_test::nan_v)));
    CHECK_FALSE(is_empty(interval_traits<I>::whole()));
    std::vector<std::pair<const char*, I>> r;
    {
        const rounding_guard<I> guard;
        r = {{"e+a", e + a},   {"a+e", a + e},   {"e-a", e - a},     {"a-e", a - e},
             {"e*a", e * a},   {"a*e", a * e},   {"e/a", e / a},     {"a/e", a / e},
             {"e+1", e + 1.0}, {"1+e", 1.0 + e}, {"e-1", e - 1.0},   {"1-e", 1.0 - e},
             {"e*2", e * 2.0}, {"2*e", 2.0 * e}, {"e/2", e / 2.0},   {"2/e", 2.0 / e},
             {"e*0", e * 0.0}, {"0*e", 0.0 * e}, {"a*nan", a * certipose_test::nan_v},
             {"-e", -e},       {"sqr", sqr(e)},  {"sqrt", sqrt(e)},  {"abs", abs(e)},
             {"pow 3", pow(e, 3)}, {"pow 0", pow(e, 0)}, {"pow -2", pow(e, -2)},
             {"sin", sin(e)},  {"cos", cos(e)},  {"acos", acos(e)},  {"atan", atan(e)},
             {"atan2(e,a)", atan2(e, a)}, {"atan2(a,e)", atan2(a, e)},
             {"sqrt(<0)", sqrt(I(-2.0, -1.0))}};
    }
    for (const auto& [name, v] : r) {
        INFO(std::string(name));
        CHECK(is_empty(v));
    }
    CHECK(width(e) == 0.0);
    CHECK(radius(e) == 0.0);
    CHECK(e == interval_traits<I>::empty());
    CHECK_FALSE(e == a);
    CHECK_FALSE(contains(e, 0.0));
    CHECK(subset(e, a));
    CHECK(subset(e, e));
    CHECK_FALSE(subset(a, e));
    CHECK(hull(e, a) == a);
    CHECK(hull(a, e) == a);
    CHECK(is_empty(intersect(e, a)));
    CHECK(is_empty(intersect(a, e)));
    CHECK_FALSE(is_degenerate(e));
}

// ---- set operations, width, midpoint, bisection ----------------------------------------------

TEST_CASE_TEMPLATE_DEFINE("interval: hull, intersect, subset, contains, width, mid, bisect", I, interval_set_ops) {
    using namespace certipose;
    using namespace certipose_test;
    random_source r(61);
    int failures = 0;
    for (int i = 0; i < inclusion_samples; ++i) {
        const bounds ab = general_box(r), bb = general_box(r);
        const I a(ab.first, ab.second), b(bb.first, bb.second);
        const I h = hull(a, b), n = intersect(a, b);
        bool ok = subset(a, h) && subset(b, h) && subset(n, a) && subset(n, b) &&
                  lower(h) == std::min(ab.first, bb.first) && upper(h) == std::max(ab.second, bb.second);
        // Disjoint exactly when one ends before the other starts.
        ok = ok && (is_empty(n) == (ab.second < bb.first || bb.second < ab.first));
        ok = ok && contains(a, ab.first) && contains(a, ab.second) &&
             !contains(a, std::nextafter(ab.second, inf_v)) && !contains(a, std::nextafter(ab.first, -inf_v));
        // Width is never below the true width; a point has width 0.
        ok = ok && width(a) >= ab.second - ab.first && (ab.first == ab.second) == (width(a) == 0.0);
        ok = ok && contains(a, mid(a)) && radius(a) >= 0.0 &&
             contains(I(mid(a) - radius(a), mid(a) + radius(a)), ab.first);
        // Bisection: a closed cover sharing the split point, both halves inside.
        const auto [lo, hi] = bisect(a);
        ok = ok && lower(lo) == ab.first && upper(hi) == ab.second && upper(lo) == lower(hi) &&
             subset(lo, a) && subset(hi, a);
        if (std::nextafter(ab.first, inf_v) < ab.second)  // a double strictly inside: split there
            ok = ok && lower(hi) > ab.first && upper(lo) < ab.second;
        const auto [l3, h3] = bisect(a, 0.25);
        ok = ok && upper(l3) == lower(h3) && contains(a, upper(l3));
        if (!ok && failures++ == 0) FAIL_CHECK("a=[" << ab.first << ", " << ab.second << "] b=[" << bb.first << ", " << bb.second << "]");
    }
    CHECK(failures == 0);

    // Unbounded intervals still have a finite midpoint inside them, and infinite width.
    const I whole = interval_traits<I>::whole();
    CHECK(mid(whole) == 0.0);
    CHECK(width(whole) == inf_v);
    CHECK(std::isfinite(mid(I(0.0, inf_v))));
    CHECK(contains(I(0.0, inf_v), mid(I(0.0, inf_v))));
    CHECK(contains(I(-inf_v, -5.0), mid(I(-inf_v, -5.0))));
    const auto [wl, wh] = bisect(whole);
    CHECK(upper(wl) == lower(wh));
    CHECK(std::isfinite(upper(wl)));
    // Point intervals and degenerate checks.
    CHECK(is_degenerate(I(3.0)));
    CHECK_FALSE(is_degenerate(I(3.0, 4.0)));
    CHECK(strict_subset(I(1.0, 2.0), I(0.0, 3.0)));
    CHECK_FALSE(strict_subset(I(0.0, 2.0), I(0.0, 3.0)));
    CHECK(split_point(I(0.0, 1.0), 0.25) == 0.25);
    CHECK(I(1.0, 2.0) == I(1.0, 2.0));
    CHECK_FALSE(I(1.0, 2.0) == I(1.0, 3.0));
}

// ---- named comparisons -------------------------------------------------------------------------

TEST_CASE_TEMPLATE_DEFINE("interval: certainly_ and possibly_ comparisons, with empty cases", I, interval_comparisons) {
    using namespace certipose;
    const I e = interval_traits<I>::empty();
    const I a(1.0, 2.0), b(3.0, 4.0), overlap(1.5, 3.5), touch(2.0, 3.0), p2(2.0);

    // Disjoint, a below b.
    CHECK(certainly_less(a, b));     CHECK(certainly_leq(a, b));
    CHECK(possibly_less(a, b));      CHECK(possibly_leq(a, b));
    CHECK_FALSE(certainly_greater(a, b)); CHECK_FALSE(certainly_geq(a, b));
    CHECK_FALSE(possibly_greater(a, b));  CHECK_FALSE(possibly_geq(a, b));
    CHECK(certainly_greater(b, a));  CHECK(possibly_geq(b, a));
    // Overlapping: nothing certain, everything possible.
    CHECK_FALSE(certainly_less(a, overlap)); CHECK_FALSE(certainly_greater(a, overlap));
    CHECK_FALSE(certainly_leq(a, overlap));  CHECK_FALSE(certainly_geq(a, overlap));
    CHECK(possibly_less(a, overlap));   CHECK(possibly_greater(a, overlap));
    CHECK(possibly_leq(a, overlap));    CHECK(possibly_geq(a, overlap));
    // Touching at 2: ≤ is certain, < is not; > is impossible, ≥ possible.
    CHECK_FALSE(certainly_less(a, touch)); CHECK(certainly_leq(a, touch));
    CHECK_FALSE(possibly_greater(a, touch)); CHECK(possibly_geq(a, touch));
    CHECK(certainly_leq(p2, p2));  CHECK_FALSE(certainly_less(p2, p2));
    CHECK(possibly_leq(p2, p2));   CHECK_FALSE(possibly_less(p2, p2));
    // Against doubles.
    CHECK(certainly_less(a, 2.5));    CHECK_FALSE(certainly_less(a, 2.0)); CHECK(certainly_leq(a, 2.0));
    CHECK(certainly_greater(a, 0.5)); CHECK_FALSE(certainly_greater(a, 1.0)); CHECK(certainly_geq(a, 1.0));
    CHECK(possibly_less(a, 1.5));     CHECK_FALSE(possibly_less(a, 1.0)); CHECK(possibly_leq(a, 1.0));
    CHECK(possibly_greater(a, 1.5));  CHECK_FALSE(possibly_greater(a, 2.0)); CHECK(possibly_geq(a, 2.0));
    // Empty: every certainly_ is vacuously true, every possibly_ false.
    for (const I& x : {a, e}) {
        CHECK(certainly_less(e, x));    CHECK(certainly_less(x, e));
        CHECK(certainly_leq(e, x));     CHECK(certainly_geq(x, e));
        CHECK(certainly_greater(e, x)); CHECK(certainly_geq(e, x));
        CHECK_FALSE(possibly_less(e, x));    CHECK_FALSE(possibly_less(x, e));
        CHECK_FALSE(possibly_leq(e, x));     CHECK_FALSE(possibly_geq(x, e));
        CHECK_FALSE(possibly_greater(e, x)); CHECK_FALSE(possibly_geq(e, x));
    }
    CHECK(certainly_less(e, 0.0));   CHECK(certainly_geq(e, 0.0));
    CHECK_FALSE(possibly_less(e, 0.0)); CHECK_FALSE(possibly_geq(e, 0.0));

    // Duality on random boxes: certainly_less(a, b) ⇔ ¬possibly_geq(a, b), and the certain
    // relation implies the possible one, both checked against the endpoints.
    certipose_test::random_source r(71);
    int failures = 0;
    for (int i = 0; i < certipose_test::inclusion_samples; ++i) {
        const auto ab = certipose_test::general_box(r, 10.0), bb = certipose_test::general_box(r, 10.0);
        const I x(ab.first, ab.second), y(bb.first, bb.second);
        const bool ok = certainly_less(x, y) == !possibly_geq(x, y) && certainly_leq(x, y) == !possibly_greater(x, y) &&
                        certainly_greater(x, y) == !possibly_leq(x, y) && certainly_geq(x, y) == !possibly_less(x, y) &&
                        (!certainly_less(x, y) || possibly_less(x, y)) &&
                        certainly_less(x, y) == (ab.second < bb.first) && possibly_less(x, y) == (ab.first < bb.second);
        failures += ok ? 0 : 1;
    }
    CHECK(failures == 0);
}

// ---- the rounding guard ------------------------------------------------------------------------

TEST_CASE_TEMPLATE_DEFINE("interval: the rounding guard holds upward and restores the caller's mode", I, interval_guard) {
    using certipose_test::sse_rounding;
    for (const int mode : {FE_TONEAREST, FE_DOWNWARD, FE_TOWARDZERO, FE_UPWARD}) {
        REQUIRE(std::fesetround(mode) == 0);
        {
            const certipose::rounding_guard<I> guard;
            CHECK(sse_rounding() == FE_UPWARD);
            {
                const certipose::rounding_guard<I> nested;
                CHECK(sse_rounding() == FE_UPWARD);
            }
            CHECK(sse_rounding() == FE_UPWARD);
        }
        CHECK(sse_rounding() == mode);
        CHECK(std::fegetround() == mode);
    }
#if defined(__x86_64__) || defined(_M_X64)
    // Only the SSE mode set (as CGAL's own guard does): restored as it was, not to the x87 mode.
    for (const unsigned sse : {_MM_ROUND_UP, _MM_ROUND_DOWN}) {
        REQUIRE(std::fesetround(FE_TONEAREST) == 0);
        _MM_SET_ROUNDING_MODE(sse);
        { const certipose::rounding_guard<I> guard; }
        CHECK(_MM_GET_ROUNDING_MODE() == sse);
        CHECK(std::fegetround() == FE_TONEAREST);
    }
#endif
    REQUIRE(std::fesetround(FE_TONEAREST) == 0);
    CHECK(sse_rounding() == FE_TONEAREST);
}

// ---- interval_box ----------------------------------------------------------------------------

TEST_CASE_TEMPLATE_DEFINE("interval_box: widest dimension, volume, bisection, corners, subset, hull, intersect", I,
                          interval_box_ops) {
    using namespace certipose;
    using box3 = interval_box<I, 3>;
    const box3 b = box3::from_bounds({{{0.0, 1.0}, {-2.0, 2.0}, {5.0, 5.5}}});
    CHECK(widest_dimension(b) == 1);
    CHECK(max_width(b) >= 4.0);
    CHECK(volume(b) >= 2.0);
    CHECK(volume(b) < 2.0 + 1e-12);
    CHECK(volume(box3::empty()) == 0.0);
    CHECK(volume(box3::from_bounds({{{0.0, 1.0}, {2.0, 2.0}, {0.0, 1.0}}})) == 0.0);
    CHECK(widest_dimension(box3::from_bounds({{{0.0, 1.0}, {0.0, 1.0}, {0.0, 1.0}}})) == 0);  // first on ties
    const auto m = midpoint(b);
    CHECK(contains(b, m));
    CHECK_FALSE(contains(b, std::array<double, 3>{0.5, 0.0, 6.0}));

    // bisect_at covers the box exactly: the halves share the cut face and differ only there.
    const auto [lo, hi] = bisect_at(b, 1, 0.5);
    CHECK(subset(lo, b));
    CHECK(subset(hi, b));
    CHECK(upper(lo[1]) == 0.5);
    CHECK(lower(hi[1]) == 0.5);
    CHECK(lower(lo[1]) == -2.0);
    CHECK(upper(hi[1]) == 2.0);
    CHECK(lo[0] == b[0]);
    CHECK(hi[2] == b[2]);
    CHECK(hull(lo, hi) == b);
    CHECK(is_degenerate(intersect(lo, hi)[1]));
    certipose_test::random_source r(81);
    for (int i = 0; i < 1000; ++i) {  // every point of b lies in one of the halves
        const std::array<double, 3> p{certipose_test::point_in(r, {0.0, 1.0}), certipose_test::point_in(r, {-2.0, 2.0}),
                                      certipose_test::point_in(r, {5.0, 5.5})};
        REQUIRE((contains(lo, p) || contains(hi, p)));
    }

    // Corners: 2^N distinct points of the box; corner k takes the upper bound where bit i is set.
    const auto c = corners(b);
    CHECK(c.size() == 8);
    for (std::size_t k = 0; k < c.size(); ++k) {
        CHECK(contains(b, c[k]));
        for (std::size_t i = 0; i < 3; ++i) CHECK(c[k][i] == (((k >> i) & 1u) ? upper(b[i]) : lower(b[i])));
        for (std::size_t j = 0; j < k; ++j) CHECK(c[j] != c[k]);
    }

    // subset, hull, intersect, with empty boxes.
    const box3 inner = box3::from_bounds({{{0.2, 0.8}, {-1.0, 1.0}, {5.1, 5.2}}});
    const box3 apart = box3::from_bounds({{{2.0, 3.0}, {-1.0, 1.0}, {5.1, 5.2}}});
    CHECK(subset(inner, b));
    CHECK_FALSE(subset(b, inner));
    CHECK(subset(box3::empty(), inner));
    CHECK(hull(inner, b) == b);
    CHECK(hull(box3::empty(), b) == b);
    CHECK(hull(b, box3::empty()) == b);
    const box3 h = hull(b, apart);
    CHECK(subset(b, h));
    CHECK(subset(apart, h));
    CHECK(upper(h[0]) == 3.0);
    CHECK(intersect(inner, b) == inner);
    CHECK(is_empty(intersect(b, apart)));
    CHECK(is_empty(intersect(b, box3::empty())));
    box3 gone = b;
    set_empty(gone);
    CHECK(is_empty(gone));
    CHECK_FALSE(is_empty(b));
}

// ---- Eigen -------------------------------------------------------------------------------------

namespace certipose_test {

/// Sample points lie on the grid 2⁻²⁰ℤ within ±16, so the products and 3-term sums below are
/// exact in double: the reference is the true value whatever order Eigen sums in.
inline double grid(double x) { return std::ldexp(std::round(std::ldexp(x, 20)), -20); }

/// A box around a grid point (sometimes a point box, sometimes with grid endpoints) and a
/// grid point inside it.
struct grid_box {
    bounds b;
    double p;
};
inline grid_box random_grid_box(random_source& r) {
    const double c = grid(r.uniform(-8.0, 8.0));
    switch (r.integer(0, 4)) {
        case 0: return {{c, c}, c};
        case 1: { const double w = grid(r.uniform(0.0, 2.0)); return {{c - w, c + w}, grid(c + r.uniform(-w, w))}; }
        default: {
            const double lo = c - r.uniform(0.0, 2.0) * (r.chance(0.2) ? 1e-9 : 1.0);
            const double hi = c + r.uniform(0.0, 2.0) * (r.chance(0.2) ? 1e-9 : 1.0);
            double p = grid(r.uniform(lo, hi));
            if (p < lo || p > hi) p = c;  // c is a grid point inside
            return {{lo, hi}, p};
        }
    }
}

}  // namespace certipose_test

TEST_CASE_TEMPLATE_DEFINE("interval: Eigen products, dot, cross and squared norm enclose point samples", I,
                          interval_eigen) {
    using namespace certipose;
    using namespace certipose_test;
    using mat3 = Eigen::Matrix<I, 3, 3>;
    using vec3 = Eigen::Matrix<I, 3, 1>;
    static_assert(std::is_same_v<typename Eigen::NumTraits<I>::Literal, double>);
    static_assert(std::is_same_v<typename decltype(std::declval<Eigen::Matrix3d>() * std::declval<vec3>())::Scalar, I>);

    random_source r(91);
    constexpr int boxes = 300, points_per_box = 40;
    int failures = 0;
    std::string first;
    for (int t = 0; t < boxes; ++t) {
        std::array<grid_box, 9> mb;
        std::array<grid_box, 3> ub, vb;
        for (auto& g : mb) g = random_grid_box(r);
        for (auto& g : ub) g = random_grid_box(r);
        for (auto& g : vb) g = random_grid_box(r);
        mat3 m;
        vec3 u, v;
        Eigen::Matrix3d md;  // a double matrix: grid points
        for (int i = 0; i < 3; ++i) {
            u(i) = I(ub[i].b.first, ub[i].b.second);
            v(i) = I(vb[i].b.first, vb[i].b.second);
            for (int j = 0; j < 3; ++j) {
                m(i, j) = I(mb[3 * i + j].b.first, mb[3 * i + j].b.second);
                md(i, j) = mb[3 * i + j].p;
            }
        }
        vec3 mu, mdu, mtu, cross, sum, scaled;
        I dot, n2, n;
        {
            const rounding_guard<I> guard;
            mu = m * u;
            mdu = md * u;
            mtu = m.transpose() * u;
            dot = u.dot(v);
            cross = u.cross(v);
            n2 = u.squaredNorm();
            n = u.norm();
            sum = u + v - vec3::Zero();
            scaled = 2.0 * u;
        }
        for (int k = 0; k < points_per_box; ++k) {
            Eigen::Matrix3d mp;
            Eigen::Vector3d up, vp;
            for (int i = 0; i < 3; ++i) {
                up(i) = k == 0 ? ub[i].p : grid(point_in(r, ub[i].b));
                vp(i) = k == 0 ? vb[i].p : grid(point_in(r, vb[i].b));
                if (!contains(u(i), up(i))) up(i) = ub[i].p;  // rounding to the grid left the box
                if (!contains(v(i), vp(i))) vp(i) = vb[i].p;
                for (int j = 0; j < 3; ++j) {
                    double x = grid(point_in(r, mb[3 * i + j].b));
                    if (!contains(m(i, j), x)) x = mb[3 * i + j].p;
                    mp(i, j) = x;
                }
            }
            const Eigen::Vector3d rmu = mp * up, rmdu = md * up, rmtu = mp.transpose() * up;
            const Eigen::Vector3d rcross = up.cross(vp), rsum = up + vp, rscaled = 2.0 * up;
            bool ok = contains(dot, up.dot(vp)) && contains(n2, up.squaredNorm()) && contains(n, up.norm());
            for (int i = 0; i < 3; ++i)
                ok = ok && contains(mu(i), rmu(i)) && contains(mdu(i), rmdu(i)) && contains(mtu(i), rmtu(i)) &&
                     contains(cross(i), rcross(i)) && contains(sum(i), rsum(i)) && contains(scaled(i), rscaled(i));
            if (!ok && failures++ == 0) {
                char buf[256];
                std::snprintf(buf, sizeof buf, "box %d point %d: u=(%.17g, %.17g, %.17g) v=(%.17g, %.17g, %.17g)", t, k,
                              up(0), up(1), up(2), vp(0), vp(1), vp(2));
                first = buf;
            }
        }
        // The squared norm is sqr-tight: it never dips below 0 (x·x would, for x ∋ 0).
        if (lower(n2) < 0.0 && failures++ == 0) first = "squaredNorm below 0";
    }
    CHECK_MESSAGE(failures == 0, first);

    // Literals and special matrices need NumTraits<I>::Literal = double.
    mat3 id = mat3::Identity();
    vec3 z = vec3::Zero();
    CHECK(id(0, 0) == I(1.0));
    CHECK(id(0, 1) == I(0.0));
    CHECK(z(2) == I(0.0));
    const mat3 cast = Eigen::Matrix3d::Constant(0.5).cast<I>();
    CHECK(cast(1, 2) == I(0.5));

    // Pivot scoring never compares overlapping intervals: a certainly non-zero candidate beats a
    // possibly-zero one, then the largest guaranteed magnitude wins.
    using score_op = Eigen::internal::scalar_score_coeff_op<I>;
    using score = typename score_op::result_type;
    Eigen::Matrix<I, 4, 1> col(I(-0.1, 0.2), I(0.9, 1.1), I(-1.2, -1.0), I(-2.0, 0.0));
    Eigen::Index best = -1;
    const score s = col.unaryExpr(score_op()).maxCoeff(&best);
    CHECK(best == 2);
    CHECK(s != score(0));
    CHECK(score(I(0.0)) == score(0));
    CHECK(score(I(0.0, 2.0)) < score(I(0.5, 0.6)));
    CHECK(score(I(0.0, 1.0)) < score(I(0.0, 2.0)));
    CHECK(score(interval_traits<I>::empty()) < score(I(0.0)));
    Eigen::Matrix<I, 3, 1> zero_col(I(0.0), I(0.0), I(0.0));
    CHECK(zero_col.unaryExpr(score_op()).maxCoeff() == score(0));  // Eigen's exact-zero pivot test
}
