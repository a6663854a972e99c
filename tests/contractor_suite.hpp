// Shared bodies of the expression / contractor tests, instantiated for every interval backend:
// tests/core/expr_hc4.cpp (boost_interval, no CGAL) and tests/cgal/contractors_cgal_backend.cpp
// (cgal_interval). Each function is a complete check for one interval type I.
//
// Oracles are written independently of the library: plain double evaluation of each
// constraint with a margin (points within 1e-9 of a bound are neither "satisfying" nor
// "violating"), so rounding in the oracle cannot fake a failure.
#pragma once

#include <certipose/contractors.hpp>

#include <doctest/doctest.h>

#include <array>
#include <cfenv>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace contractor_suite {

using namespace certipose;
using point = std::array<double, 3>;
using bounds3 = std::array<std::pair<double, double>, 3>;

inline constexpr var<0> x{};
inline constexpr var<1> y{};
inline constexpr var<2> z{};
inline constexpr double inf = std::numeric_limits<double>::infinity();

// ---- constraint shapes ---------------------------------------------------------------------
// Each shape: the constraints (a tuple), an oracle `value_ok(p, m)` = every constraint holds with
// margin m (m > 0: strictly inside by m; m < 0: within |m| of holding), the domain boxes are
// drawn from, and a smaller region where satisfying points are found by rejection.

struct shell {
    static constexpr const char* name = "spherical shell";
    static auto constraints() { return std::tuple(in(sqr(x - 1.0) + sqr(y - 2.0) + sqr(z - 0.5), 0.09, 0.25)); }
    static bool holds(const point& p, double m) {
        const double d = (p[0] - 1) * (p[0] - 1) + (p[1] - 2) * (p[1] - 2) + (p[2] - 0.5) * (p[2] - 0.5);
        return d >= 0.09 + m && d <= 0.25 - m;
    }
    static constexpr bounds3 domain{{{-5, 5}, {-5, 5}, {-5, 5}}};
    static constexpr bounds3 region{{{0.45, 1.55}, {1.45, 2.55}, {-0.05, 1.05}}};
};

struct expanded_shell {
    static constexpr const char* name = "expanded shell";
    static auto constraints() {
        return std::tuple(in(sqr(x) + sqr(y) + sqr(z) - 2.0 * x - 4.0 * y - z + 5.25, 0.09, 0.25));
    }
    static bool holds(const point& p, double m) {
        const double d = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] - 2 * p[0] - 4 * p[1] - p[2] + 5.25;
        return d >= 0.09 + m && d <= 0.25 - m;
    }
    static constexpr bounds3 domain = shell::domain;
    static constexpr bounds3 region = shell::region;
};

// Product and quotient; the denominator's domain contains 0.
struct product_quotient {
    static constexpr const char* name = "product/quotient";
    static auto constraints() { return std::tuple(in(x * y / z, 1.0, 2.0)); }
    static bool holds(const point& p, double m) {
        if (std::abs(p[2]) < 1e-6) return false;
        const double q = p[0] * p[1] / p[2];
        return q >= 1.0 + m && q <= 2.0 - m;
    }
    static constexpr bounds3 domain{{{-3, 3}, {-3, 3}, {-3, 3}}};
    static constexpr bounds3 region = domain;
};

// Periodic functions over several periods.
struct trigonometric {
    static constexpr const char* name = "sin/cos";
    static auto constraints() { return std::tuple(in(sin(x) + cos(y) * z, 0.2, 0.8)); }
    static bool holds(const point& p, double m) {
        const double v = std::sin(p[0]) + std::cos(p[1]) * p[2];
        return v >= 0.2 + m && v <= 0.8 - m;
    }
    static constexpr bounds3 domain{{{-10, 10}, {-10, 10}, {-2, 2}}};
    static constexpr bounds3 region = domain;
};

// A system: sqrt, integer powers (odd and negative), abs, an inequality between expressions.
struct mixed_system {
    static constexpr const char* name = "sqrt/pow/abs system";
    static auto constraints() {
        return std::tuple(in(sqrt(sqr(x) + sqr(y)) + pow(z, 3) - abs(x - y), -1.0, 1.0),
                          pow(x, -2) + y <= 4.0, x + 0.5 * z >= y - 1.0);
    }
    static bool holds(const point& p, double m) {
        const double a = std::sqrt(p[0] * p[0] + p[1] * p[1]) + p[2] * p[2] * p[2] - std::abs(p[0] - p[1]);
        if (!(a >= -1.0 + m && a <= 1.0 - m)) return false;
        if (std::abs(p[0]) < 1e-6) return false;
        if (!(1.0 / (p[0] * p[0]) + p[1] <= 4.0 - m)) return false;
        return p[0] + 0.5 * p[2] - (p[1] - 1.0) >= m;
    }
    static constexpr bounds3 domain{{{-3, 3}, {-3, 3}, {-3, 3}}};
    static constexpr bounds3 region = domain;
};

// 3-vectors and an interval parameter: (p × a) · b ∈ [−0.5, 0.5] with a = (1, t, 0.5),
// t ∈ [0.5, 0.7] known only as an interval. Contraction keeps a point when SOME t works; the
// inner tests certify a box only when EVERY t works (the expression is linear in t, so its
// range over t is spanned by t = 0.5 and t = 0.7).
struct vector_param {
    static constexpr const char* name = "dot/cross with a parameter";
    static auto constraints() {
        const auto p = vec(x, y, z);
        const auto a = vec(1.0, param<0>(0.5, 0.7), 0.5);
        const auto b = vec(0.3, 0.2, 1.0);
        return std::tuple(in(dot(cross(p, a), b), -0.5, 0.5));
    }
    static double f(const point& p, double t) {
        const double cx = p[1] * 0.5 - p[2] * t, cy = p[2] * 1.0 - p[0] * 0.5, cz = p[0] * t - p[1] * 1.0;
        return cx * 0.3 + cy * 0.2 + cz * 1.0;
    }
    // "some t" when m > 0 (points that must survive contraction), "every t" when m ≤ 0.
    static bool holds(const point& p, double m) {
        const double f0 = f(p, 0.5), f1 = f(p, 0.7);
        const double lo = std::min(f0, f1), hi = std::max(f0, f1);
        if (m > 0) return hi >= -0.5 + m && lo <= 0.5 - m;
        return lo >= -0.5 + m && hi <= 0.5 - m;
    }
    static constexpr bounds3 domain{{{-3, 3}, {-3, 3}, {-3, 3}}};
    static constexpr bounds3 region = domain;
};

// ---- helpers -----------------------------------------------------------------------------

template <class I>
using box3 = interval_box<I, 3>;

inline point uniform_in(std::mt19937_64& rng, const bounds3& b) {
    point p{};
    for (std::size_t i = 0; i < 3; ++i) p[i] = std::uniform_real_distribution<double>(b[i].first, b[i].second)(rng);
    return p;
}

template <class I>
point uniform_in(std::mt19937_64& rng, const box3<I>& b) {
    point p{};
    for (std::size_t i = 0; i < 3; ++i) {
        const double l = lower(b[i]), u = upper(b[i]);
        p[i] = l == u ? l : std::uniform_real_distribution<double>(l, u)(rng);
        p[i] = std::min(std::max(p[i], l), u);
    }
    return p;
}

inline constexpr double margin = 1e-9;

/// Points strictly satisfying the shape (by `margin`), found by rejection in its region.
template <class Shape>
std::vector<point> satisfying_points(std::size_t n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::vector<point> pts;
    for (std::size_t tries = 0; pts.size() < n && tries < 400 * n; ++tries) {
        const point p = uniform_in(rng, Shape::region);
        if (Shape::holds(p, margin)) pts.push_back(p);
    }
    return pts;
}

/// A random box containing p: each side extends a random distance, from 1e-6 to the domain's
/// width (cubed uniform: many small boxes, some large ones).
template <class I, class Shape>
box3<I> box_around(std::mt19937_64& rng, const point& p) {
    box3<I> b;
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (std::size_t i = 0; i < 3; ++i) {
        const double w = Shape::domain[i].second - Shape::domain[i].first;
        const double a = u(rng), c = u(rng);
        b[i] = I(p[i] - (1e-6 + w * a * a * a), p[i] + (1e-6 + w * c * c * c));
    }
    return b;
}

template <class Shape>
auto make_hc4() {
    return std::apply([](auto... c) { return hc4(c...); }, Shape::constraints());
}
template <class Shape>
auto make_eval_test() {
    return std::apply([](auto... c) { return eval_test(c...); }, Shape::constraints());
}
template <class Shape>
auto make_not_in_test() {
    return std::apply([](auto... c) { return not_in_test(c...); }, Shape::constraints());
}
template <class Shape>
auto make_not_in() {
    return std::apply([](auto... c) { return not_in(c...); }, Shape::constraints());
}

/// Property: no satisfying point is ever removed. Boxes are drawn around pool points; every pool
/// point inside the box is checked after contraction, until at least `min_checks` (point, box)
/// pairs were checked. Also checks that the result is inside the original box and that the
/// contractor narrowed some boxes (the property is not vacuous).
template <class I, class Shape, class C>
void check_keeps_solutions(C contractor, const std::string& what, std::size_t min_checks = 10000) {
    const std::string context = std::string(Shape::name) + " / " + what + " / " + interval_traits<I>::name;
    INFO(context);
    const auto pool = satisfying_points<Shape>(2000, 7);
    REQUIRE(pool.size() == 2000);
    std::mt19937_64 rng(42);
    std::size_t checks = 0, removed = 0, narrowed = 0, grew = 0, boxes = 0;
    while (checks < min_checks && boxes < 20000) {
        const point& c = pool[rng() % pool.size()];
        const box3<I> original = box_around<I, Shape>(rng, c);
        box3<I> b = original;
        contractor.contract(b);
        ++boxes;
        if (!subset(b, original)) ++grew;
        if (!(b == original)) ++narrowed;
        for (const point& p : pool) {
            if (!contains(original, p)) continue;
            ++checks;
            if (!contains(b, p)) ++removed;
        }
    }
    CHECK(checks >= min_checks);
    CHECK(removed == 0);
    CHECK(grew == 0);
    CHECK(narrowed > 0);
    // Contractors must hand the caller's rounding mode back.
    CHECK(std::fegetround() == FE_TONEAREST);
}

/// Every contractor and composition on one shape.
template <class I, class Shape>
void check_all_contractors_keep_solutions() {
    check_keeps_solutions<I, Shape>(make_hc4<Shape>(), "hc4");
    {
        auto c = make_hc4<Shape>();
        c.set_ratio(0.0);
        check_keeps_solutions<I, Shape>(c, "hc4 ratio 0");
    }
    check_keeps_solutions<I, Shape>(acid(make_hc4<Shape>()), "acid");
    check_keeps_solutions<I, Shape>(make_hc4<Shape>() & acid(make_hc4<Shape>()), "hc4 & acid");
    check_keeps_solutions<I, Shape>(compose(make_hc4<Shape>(), identity{}, make_hc4<Shape>()), "compose");
    check_keeps_solutions<I, Shape>(make_hc4<Shape>() | acid(make_hc4<Shape>()), "hc4 | acid");
    check_keeps_solutions<I, Shape>(fixpoint(make_hc4<Shape>() & acid(make_hc4<Shape>()), 0.01), "fixpoint(hc4 & acid)");
    check_keeps_solutions<I, Shape>(fixpoint(make_hc4<Shape>()), "fixpoint(hc4)");
    acid_options o;
    o.s3b = 4;
    o.scid = 3;
    o.tuning_period = 60;
    o.tuning_length = 20;
    check_keeps_solutions<I, Shape>(make_hc4<Shape>() & acid(make_hc4<Shape>(), o), "hc4 & acid(s3b 4, scid 3)");
}

/// Inner/outer tests: a box declared satisfied holds only satisfying points, a box declared
/// violated holds none (uniform sampling plus every pool point); both verdicts occur.
template <class I, class Shape, class T>
void check_box_test(const T& test, const std::string& what, std::size_t& satisfied_out) {
    const std::string context = std::string(Shape::name) + " / " + what + " / " + interval_traits<I>::name;
    INFO(context);
    const auto pool = satisfying_points<Shape>(2000, 11);
    std::mt19937_64 rng(5);
    std::size_t satisfied = 0, violated = 0, bad_satisfied = 0, bad_violated = 0;
    for (int k = 0; k < 3000; ++k) {
        // Half the boxes around satisfying points, half anywhere in the domain.
        const point c = k % 2 ? pool[rng() % pool.size()] : uniform_in(rng, Shape::domain);
        box3<I> b = box_around<I, Shape>(rng, c);
        // and small ones, where inner proofs succeed (the expanded shell needs tiny ones)
        const double small = k % 3 == 0 ? 0.01 : k % 3 == 1 ? 0.001 : 0.0;
        if (small > 0)
            for (std::size_t i = 0; i < 3; ++i) b[i] = I(c[i] - small * (1 + i), c[i] + 0.5 * small * (2 + i));
        const verdict v = test.test(b);
        if (v == verdict::satisfied) {
            ++satisfied;
            for (int s = 0; s < 64; ++s)
                if (!Shape::holds(uniform_in(rng, b), -margin)) ++bad_satisfied;
            for (const auto& corner : corners(b))
                if (!Shape::holds(corner, -margin)) ++bad_satisfied;
        } else if (v == verdict::violated) {
            ++violated;
            for (const point& p : pool)
                if (contains(b, p)) ++bad_violated;
        }
    }
    CHECK(bad_satisfied == 0);
    CHECK(bad_violated == 0);
    CHECK(satisfied > 0);
    CHECK(violated > 0);
    satisfied_out = satisfied;
}

template <class I, class Shape>
void check_box_tests() {
    std::size_t by_eval = 0, by_negation = 0;
    check_box_test<I, Shape>(make_eval_test<Shape>(), "eval_test", by_eval);
    check_box_test<I, Shape>(make_not_in_test<Shape>(), "not_in_test", by_negation);
    // The negation test starts with the evaluation test, so it proves at least as much.
    CHECK(by_negation >= by_eval);
}

/// not_in keeps every point that violates a constraint (by the margin).
template <class I, class Shape>
void check_not_in_keeps_violations() {
    const std::string context = std::string(Shape::name) + " / not_in / " + interval_traits<I>::name;
    INFO(context);
    auto c = make_not_in<Shape>();
    std::mt19937_64 rng(3);
    std::size_t checks = 0, removed = 0;
    for (int k = 0; k < 2000; ++k) {
        const point center = uniform_in(rng, Shape::region);
        const box3<I> original = box_around<I, Shape>(rng, center);
        box3<I> b = original;
        c.contract(b);
        for (int s = 0; s < 8; ++s) {
            const point p = uniform_in(rng, original);
            if (Shape::holds(p, -margin)) continue;  // satisfying (or too close to call)
            ++checks;
            if (!contains(b, p)) ++removed;
        }
    }
    CHECK(checks > 1000);
    CHECK(removed == 0);
}

// ---- deterministic checks ------------------------------------------------------------------

template <class I>
void check_paper_example() {
    // Paper §5.2.1: (x − y)² − z = 0, x ∈ [0, 10], y ∈ [0, 4], z ∈ [9, 16]: the forward pass
    // gives [−16, 91] at the root and the backward pass contracts x to [0, 8].
    auto b = box3<I>::from_bounds({{{0, 10}, {0, 4}, {9, 16}}});
    const auto c = sqr(x - y) - z == 0.0;
    const I root = evaluate(c.e, b);
    CHECK(lower(root) <= -16.0);
    CHECK(upper(root) >= 91.0);
    CHECK(lower(root) >= -16.0 - 1e-12);
    CHECK(upper(root) <= 91.0 + 1e-12);
    hc4 h(c);
    h.contract(b);
    REQUIRE(!is_empty(b));
    CHECK(lower(b[0]) <= 0.0);
    CHECK(upper(b[0]) >= 8.0);
    CHECK(upper(b[0]) <= 8.0 + 1e-12);
    CHECK(lower(b[0]) >= -1e-12);
    CHECK(lower(b[1]) == 0.0);
    CHECK(upper(b[1]) == 4.0);
}

template <class I>
void check_forward_evaluation() {
    const auto b = box3<I>::from_bounds({{{0, 1}, {2, 3}, {-1, 1}}});
    // Dependency: x·x − x over [0, 1] encloses the true range [−1/4, 0].
    const I v = evaluate(sqr(x) - x, b);
    CHECK(lower(v) <= -0.25);
    CHECK(upper(v) >= 0.0);
    // 1/3 is not a double: its enclosure must have positive width (rounding held).
    const I third = evaluate(x / 3.0, box3<I>::from_bounds({{{1, 1}, {0, 0}, {0, 0}}}));
    CHECK(lower(third) < upper(third));
    CHECK(lower(third) <= 1.0 / 3.0);
    CHECK(upper(third) >= 1.0 / 3.0);
    // Point evaluation.
    const I at = evaluate<I>(sqr(x - 1.0) + sqr(y - 2.0) + sqr(z - 0.5), point{1.25, 2.0, 0.75});
    CHECK(lower(at) <= 0.125);
    CHECK(upper(at) >= 0.125);
    CHECK(upper(at) - lower(at) < 1e-15);
    // cos(0.7935) with positive width (widened libm result).
    const I c = evaluate(cos(x), box3<I>::from_bounds({{{0.7935, 0.7935}, {0, 0}, {0, 0}}}));
    CHECK(lower(c) < upper(c));
    // sqrt of a negative interval is empty; 1/0 is empty.
    CHECK(is_empty(evaluate(sqrt(z - 2.0), b)));
    CHECK(is_empty(evaluate(x / 0.0, b)));
    // Division by an interval containing 0 is unbounded, never wrong.
    const I q = evaluate(y / z, b);
    CHECK(lower(q) == -inf);
    CHECK(upper(q) == inf);
    // vec/dot/cross.
    const auto u = vec(x, y, z);
    const I d = evaluate(dot(cross(u, vec(1.0, 0.0, 0.0)), vec(0.0, 1.0, 0.0)), b);  // (u × e_x)_y = u_z
    CHECK(lower(d) <= -1.0);
    CHECK(upper(d) >= 1.0);
    CHECK(upper(d) - lower(d) <= 2.0 + 1e-12);
    CHECK(std::fegetround() == FE_TONEAREST);
}

template <class I, class C>
box3<I> contracted(C c, box3<I> b) {
    hc4 h(std::move(c));
    h.contract(b);
    return b;
}

template <class I>
void check_backward_projections() {
    using B = box3<I>;
    constexpr double pi = std::numbers::pi;
    const auto near = [](double a, double b) { return std::abs(a - b) <= 1e-9 * (1 + std::abs(b)); };
    {  // product with a factor straddling 0, and one away from it
        auto b = contracted<I>(in(x * y, 1.0, 2.0), B::from_bounds({{{0.5, 1}, {-10, 10}, {0, 0}}}));
        CHECK(near(lower(b[1]), 1.0));
        CHECK(near(upper(b[1]), 4.0));
        b = contracted<I>(in(x * y, 1.0, 2.0), B::from_bounds({{{-1, 1}, {-10, 10}, {0, 0}}}));
        CHECK(lower(b[1]) == -10.0);  // y ∈ (−∞, −1] ∪ [1, ∞): hull is everything
        CHECK(upper(b[1]) == 10.0);
        b = contracted<I>(in(x * y, 1.0, 2.0), B::from_bounds({{{-1, 1}, {0, 0.5}, {0, 0}}}));
        CHECK(is_empty(b));  // |x·y| ≤ 0.5
        // x·y = 0 with 0 ∈ x: any y works (x = 0); nothing may be removed from y.
        b = contracted<I>(x * y == 0.0, B::from_bounds({{{-1, 1}, {2, 3}, {0, 0}}}));
        CHECK(lower(b[1]) == 2.0);
        CHECK(upper(b[1]) == 3.0);
        CHECK(lower(b[0]) == 0.0);  // but x must be 0
        CHECK(upper(b[0]) == 0.0);
        b = contracted<I>(x * 0.0 == 0.0, B::from_bounds({{{1, 2}, {0, 0}, {0, 0}}}));
        CHECK(lower(b[0]) == 1.0);
        CHECK(upper(b[0]) == 2.0);
        b = contracted<I>(x * 0.0 == 1.0, B::from_bounds({{{1, 2}, {0, 0}, {0, 0}}}));
        CHECK(is_empty(b));
    }
    {  // quotient with 0 inside the denominator: x / y ∈ [1, 2], x ∈ [1, 2], y ∈ [−1, 1] ⇒ y ∈ [0.5, 1]
        auto b = contracted<I>(in(x / y, 1.0, 2.0), B::from_bounds({{{1, 2}, {-1, 1}, {0, 0}}}));
        CHECK(lower(b[1]) <= 0.5);
        CHECK(near(lower(b[1]), 0.5));
        CHECK(upper(b[1]) == 1.0);
    }
    {  // sin over several periods: sin x ∈ [0.5, 1], x ∈ [0, 10] ⇒ x ∈ [π/6, 2π + 5π/6]
        auto b = contracted<I>(in(sin(x), 0.5, 1.0), B::from_bounds({{{0, 10}, {0, 0}, {0, 0}}}));
        CHECK(lower(b[0]) <= pi / 6);
        CHECK(near(lower(b[0]), pi / 6));
        CHECK(upper(b[0]) >= 2 * pi + 5 * pi / 6);
        CHECK(near(upper(b[0]), 2 * pi + 5 * pi / 6));
    }
    {  // cos x = 1 has no solution in [0.1, 6] (the next one is 2π); cos x ≤ −0.5 on [0, 3]
        auto b = contracted<I>(cos(x) == 1.0, B::from_bounds({{{0.1, 6}, {0, 0}, {0, 0}}}));
        CHECK(is_empty(b));
        b = contracted<I>(cos(x) <= -0.5, B::from_bounds({{{0, 3}, {0, 0}, {0, 0}}}));
        CHECK(near(lower(b[0]), 2 * pi / 3));
        CHECK(lower(b[0]) <= 2 * pi / 3);
        CHECK(upper(b[0]) == 3.0);
    }
    {  // sqrt and its domain
        auto b = contracted<I>(in(sqrt(x), 2.0, 3.0), B::from_bounds({{{-10, 100}, {0, 0}, {0, 0}}}));
        CHECK(lower(b[0]) == 4.0);
        CHECK(upper(b[0]) == 9.0);
        b = contracted<I>(sqrt(x) >= 0.0, B::from_bounds({{{-5, -1}, {0, 0}, {0, 0}}}));
        CHECK(is_empty(b));
    }
    {  // integer powers: odd, even, negative
        auto b = contracted<I>(in(pow(x, 3), 8.0, 27.0), B::from_bounds({{{-10, 10}, {0, 0}, {0, 0}}}));
        CHECK(lower(b[0]) <= 2.0);
        CHECK(near(lower(b[0]), 2.0));
        CHECK(upper(b[0]) >= 3.0);
        CHECK(near(upper(b[0]), 3.0));
        b = contracted<I>(in(pow(x, 4), 16.0, 81.0), B::from_bounds({{{-10, 2.5}, {0, 0}, {0, 0}}}));
        CHECK(near(lower(b[0]), -3.0));
        CHECK(lower(b[0]) <= -3.0);
        CHECK(upper(b[0]) == 2.5);
        b = contracted<I>(in(pow(x, -2), 0.25, 4.0), B::from_bounds({{{0, 10}, {0, 0}, {0, 0}}}));
        CHECK(near(lower(b[0]), 0.5));
        CHECK(lower(b[0]) <= 0.5);
        CHECK(near(upper(b[0]), 2.0));
        CHECK(upper(b[0]) >= 2.0);
        b = contracted<I>(in(pow(x, 3), -27.0, -8.0), B::from_bounds({{{-10, 10}, {0, 0}, {0, 0}}}));
        CHECK(near(lower(b[0]), -3.0));
        CHECK(near(upper(b[0]), -2.0));
        CHECK(upper(b[0]) >= -2.0);
    }
    {  // abs, unary minus, sqr's two branches
        auto b = contracted<I>(in(abs(x), 1.0, 2.0), B::from_bounds({{{0, 5}, {0, 0}, {0, 0}}}));
        CHECK(lower(b[0]) == 1.0);
        CHECK(upper(b[0]) == 2.0);
        b = contracted<I>(in(-x, 1.0, 2.0), B::from_bounds({{{-5, 5}, {0, 0}, {0, 0}}}));
        CHECK(lower(b[0]) == -2.0);
        CHECK(upper(b[0]) == -1.0);
        b = contracted<I>(in(sqr(x), 4.0, 9.0), B::from_bounds({{{-2.5, 10}, {0, 0}, {0, 0}}}));
        CHECK(lower(b[0]) == -2.5);
        CHECK(upper(b[0]) == 3.0);
        b = contracted<I>(in(sqr(x), 4.0, 9.0), B::from_bounds({{{-1.5, 10}, {0, 0}, {0, 0}}}));
        CHECK(lower(b[0]) == 2.0);
    }
    {  // repeated variables: x − x = 0 holds everywhere, nothing may be removed
        auto b = contracted<I>(x - x == 0.0, B::from_bounds({{{0, 1}, {0, 0}, {0, 0}}}));
        CHECK(lower(b[0]) == 0.0);
        CHECK(upper(b[0]) == 1.0);
        // x·x + x ∈ [2, 2] ⇒ x ∈ {1, −2}: both must survive on [−3, 3]
        b = contracted<I>(x * x + x == 2.0, B::from_bounds({{{-3, 3}, {0, 0}, {0, 0}}}));
        CHECK(contains(b[0], 1.0));
        CHECK(contains(b[0], -2.0));
    }
    {  // relations between expressions, and constants on either side
        auto b = contracted<I>(x <= y, B::from_bounds({{{0, 10}, {-5, 3}, {0, 0}}}));
        CHECK(upper(b[0]) == 3.0);
        CHECK(lower(b[1]) == 0.0);
        b = contracted<I>(x >= y + 1.0, B::from_bounds({{{0, 10}, {2, 30}, {0, 0}}}));
        CHECK(lower(b[0]) == 3.0);
        CHECK(upper(b[1]) == 9.0);
        b = contracted<I>(2.0 <= x, B::from_bounds({{{0, 10}, {0, 0}, {0, 0}}}));
        CHECK(lower(b[0]) == 2.0);
        b = contracted<I>(2.0 >= x, B::from_bounds({{{0, 10}, {0, 0}, {0, 0}}}));
        CHECK(upper(b[0]) == 2.0);
        b = contracted<I>(z == x * y, B::from_bounds({{{1, 2}, {3, 4}, {0, 100}}}));
        CHECK(lower(b[2]) == 3.0);
        CHECK(upper(b[2]) == 8.0);
    }
    {  // unbounded domains contract to finite ones
        auto b = contracted<I>(in(sqr(x - 1.0) + sqr(y - 2.0) + sqr(z - 0.5), 0.09, 0.25),
                               B::from_bounds({{{-inf, inf}, {-inf, inf}, {-inf, inf}}}));
        CHECK(near(lower(b[0]), 0.5));
        CHECK(near(upper(b[0]), 1.5));
        CHECK(near(upper(b[2]), 1.0));
    }
    CHECK(std::fegetround() == FE_TONEAREST);
}

template <class I>
void check_equality_solutions_kept() {
    // Points that satisfy z = x·y exactly (dyadic x, y: the product is exact in double).
    std::mt19937_64 rng(9);
    hc4 h(z == x * y, sqr(x) + sqr(y) <= 9.0);
    auto h_acid = hc4(z == x * y, sqr(x) + sqr(y) <= 9.0) & acid(hc4(z == x * y, sqr(x) + sqr(y) <= 9.0));
    std::size_t removed = 0;
    for (int k = 0; k < 2000; ++k) {
        const double px = static_cast<double>(static_cast<int>(rng() % 257) - 128) / 64.0;
        const double py = static_cast<double>(static_cast<int>(rng() % 257) - 128) / 64.0;
        if (px * px + py * py > 9.0) continue;
        const point p{px, py, px * py};
        std::mt19937_64 brng(k);
        auto b = box_around<I, shell>(brng, p);
        auto b2 = b;
        h.contract(b);
        h_acid.contract(b2);
        if (!contains(b, p) || !contains(b2, p)) ++removed;
    }
    CHECK(removed == 0);
}

template <class I>
void check_parameters() {
    // x·t + y ∈ [0, 1] with t a parameter; set_param changes what the contractor removes.
    auto h = hc4(in(x * param<0>(1.0, 2.0) + y, 0.0, 1.0), in(x - z, -0.1, 0.1));
    auto b = box3<I>::from_bounds({{{-5, 5}, {0, 0}, {-5, 5}}});
    h.contract(b);
    CHECK(lower(b[0]) == 0.0);
    CHECK(upper(b[0]) == 1.0);  // x ∈ [0, 1/t] for some t ∈ [1, 2]
    set_param<0>(h, 4.0, 4.0);
    b = box3<I>::from_bounds({{{-5, 5}, {0, 0}, {-5, 5}}});
    h.contract(b);
    CHECK(upper(b[0]) == 0.25);
    CHECK(upper(b[2]) <= 0.35 + 1e-12);
    set_param<0>(h, I(-1.0, -1.0));
    b = box3<I>::from_bounds({{{-5, 5}, {0, 0}, {-5, 5}}});
    h.contract(b);
    CHECK(lower(b[0]) == -1.0);
    CHECK(upper(b[0]) == 0.0);
    // Parameters reach through compositions.
    auto composed = hc4(in(x * param<1>(1.0, 1.0), 0.0, 1.0)) & identity{};
    set_param<1>(composed, 2.0, 2.0);
    b = box3<I>::from_bounds({{{-5, 5}, {0, 0}, {0, 0}}});
    composed.contract(b);
    CHECK(upper(b[0]) == 0.5);
    auto united = hc4(in(x * param<2>(1.0, 1.0), 0.0, 1.0)) | hc4(in(x * param<2>(1.0, 1.0), 2.0, 3.0));
    set_param<2>(united, 4.0, 4.0);
    b = box3<I>::from_bounds({{{-5, 5}, {0, 0}, {0, 0}}});
    united.contract(b);
    CHECK(lower(b[0]) == 0.0);
    CHECK(upper(b[0]) == 0.75);
}

template <class I>
void check_compositions() {
    using B = box3<I>;
    // Union: the hull of two half-line contractions.
    auto left = hc4(x <= -1.0);
    auto right = hc4(x >= 1.0);
    auto either = left | right;
    auto b = B::from_bounds({{{-5, 5}, {0, 0}, {0, 0}}});
    either.contract(b);
    CHECK(lower(b[0]) == -5.0);
    CHECK(upper(b[0]) == 5.0);
    b = B::from_bounds({{{-0.5, 5}, {0, 0}, {0, 0}}});
    either.contract(b);
    CHECK(lower(b[0]) == 1.0);
    b = B::from_bounds({{{-0.5, 0.5}, {0, 0}, {0, 0}}});
    either.contract(b);
    CHECK(is_empty(b));
    // Sequence flattens and stops at the empty box.
    auto seq = hc4(x >= 1.0) & hc4(x <= 2.0) & identity{};
    static_assert(std::tuple_size_v<std::remove_cvref_t<decltype(seq.parts())>> == 3);
    b = B::from_bounds({{{-5, 5}, {0, 0}, {0, 0}}});
    seq.contract(b);
    CHECK(lower(b[0]) == 1.0);
    CHECK(upper(b[0]) == 2.0);
    // Fixpoint does at least what one pass does, and more where variables repeat.
    const auto e = in(sqr(x) + sqr(y) + sqr(z) - 2.0 * x - 4.0 * y - z + 5.25, 0.09, 0.25);
    auto once = B::from_bounds({{{-5, 5}, {-5, 5}, {-5, 5}}});
    auto many = once;
    auto one_pass = hc4(e) & acid(hc4(e));
    one_pass.contract(once);
    auto fp = fixpoint(hc4(e) & acid(hc4(e)), 1e-3);
    fp.contract(many);
    CHECK(subset(many, once));
    CHECK(volume(many) < volume(once));
    CHECK(fp.ratio() == 1e-3);
    // Empty boxes stay empty, for every contractor.
    auto empty = B::empty();
    hc4(e).contract(empty);
    CHECK(is_empty(empty));
    acid(hc4(e)).contract(empty);
    CHECK(is_empty(empty));
    CHECK(eval_test(e).test(empty) == verdict::violated);
    CHECK(not_in_test(e).test(empty) == verdict::violated);
}

template <class I>
void check_acid_state_is_per_object() {
    const auto e = in(sqr(x) + sqr(y) + sqr(z) - 2.0 * x - 4.0 * y - z + 5.25, 0.09, 0.25);
    acid_options o;
    o.tuning_period = 10;
    o.tuning_length = 5;
    auto a = acid(hc4(e), o);
    auto b = acid(hc4(e), o);
    CHECK(a.learned_var_count() == -1);
    const auto start = box3<I>::from_bounds({{{-5, 5}, {-5, 5}, {-5, 5}}});
    for (int k = 0; k < 25; ++k) {
        auto box = start;
        a.contract(box);
    }
    CHECK(a.calls() == 25);
    CHECK(b.calls() == 0);  // no shared (static) state
    CHECK(b.learned_var_count() == -1);
    CHECK(a.learned_var_count() >= 0);
    CHECK(a.learned_var_count() <= 15);
    // Same inputs, same learning: the state is deterministic and copyable.
    auto c = a;
    auto box1 = start, box2 = start;
    a.contract(box1);
    c.contract(box2);
    CHECK(box1 == box2);
    CHECK(a.learned_var_count() == c.learned_var_count());
}

template <class I>
void check_concepts() {
    using B = box3<I>;
    const auto e = in(sqr(x - 1.0) + sqr(y - 2.0) + sqr(z - 0.5), 0.09, 0.25);
    using H = decltype(hc4(e));
    static_assert(Contractor<H, B>);
    static_assert(Contractor<decltype(acid(hc4(e))), B>);
    static_assert(Contractor<decltype(hc4(e) & acid(hc4(e))), B>);
    static_assert(Contractor<decltype(hc4(e) | identity{}), B>);
    static_assert(Contractor<decltype(fixpoint(hc4(e))), B>);
    static_assert(Contractor<identity, B>);
    static_assert(Contractor<decltype(not_in(e)), B>);
    static_assert(BoxTest<decltype(eval_test(e)), B>);
    static_assert(BoxTest<decltype(not_in_test(e)), B>);
    static_assert(!Contractor<decltype(e), B>);
    CHECK(H::constraint_count == 1);
}

/// The rounding mode seen by callers is untouched, whatever mode they hold.
template <class I>
void check_rounding_restored() {
    const auto e = in(sqr(x - 1.0) + sqr(y - 2.0) + sqr(z - 0.5), 0.09, 0.25);
    auto h = hc4(e) & acid(hc4(e));
    const eval_test t(e);
    for (int mode : {FE_TONEAREST, FE_DOWNWARD, FE_TOWARDZERO}) {
        std::fesetround(mode);
        auto b = box3<I>::from_bounds({{{-5, 5}, {-5, 5}, {-5, 5}}});
        h.contract(b);
        (void)t.test(b);
        CHECK(std::fegetround() == mode);
        std::fesetround(FE_TONEAREST);
        CHECK(lower(b[0]) <= 0.5);
        CHECK(upper(b[0]) >= 1.5);
    }
}

}  // namespace contractor_suite
