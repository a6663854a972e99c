// Tests for the bisectors (largest_first, round_robin) and the paver (paper Algorithm 1):
// the spherical shell (centre (1, 2, 0.5), radii 0.3 and 0.5) paved inside [−5, 5]³ brackets
// the exact volume 4/3 π (0.5³ − 0.3³) and the bracket tightens with ε; VALID boxes contain
// only solutions and no solution is lost (random sampling); budgets, deadlines and cancellation
// stop runs with the right reason and return the unclassified rest; depth- and breadth-first
// build the same paving; the bisection tree is consistent; two pavers run on two threads.
#include <certipose/bisection/largest_first.hpp>
#include <certipose/contractor/acid.hpp>
#include <certipose/bisection/round_robin.hpp>
#include <certipose/contractor/eval_test.hpp>
#include <certipose/contractor/hc4.hpp>
#include <certipose/contractor/identity.hpp>
#include <certipose/contractor/not_in.hpp>
#include <certipose/interval/boost_interval.hpp>
#include <certipose/paver/paver.hpp>
#include <certipose/pose/interval_box.hpp>
#include <certipose/solver/task.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cfenv>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <stop_token>
#include <thread>
#include <tuple>
#include <vector>

// tests/cgal/paver.cpp re-includes this file with the CGAL backend; it then runs the typed
// tests only (the others do not depend on the backend).
#ifndef CERTIPOSE_PAVER_TEST_BACKENDS
#define CERTIPOSE_PAVER_TEST_BACKENDS certipose::boost_interval
#define CERTIPOSE_PAVER_TEST_UNTYPED 1
#endif

namespace {

using certipose::bisection_context;
using certipose::box_class;
using certipose::interval_box;
using certipose::largest_first;
using certipose::paver_options;
using certipose::round_robin;
using certipose::split;
using certipose::termination;
using certipose::verdict;

constexpr double inf_v = std::numeric_limits<double>::infinity();

// ---- the shell: (x−1)² + (y−2)² + (z−0.5)² ∈ [0.3², 0.5²] ------------------------------------
// The library's HC4 and tests (contractor/), and a hand-written HC4Revise below that plays a
// user-defined contractor and cross-checks them.
constexpr std::array<double, 3> centre{1.0, 2.0, 0.5};
constexpr double r_in = 0.3, r_out = 0.5;
constexpr double f_lo = 0.09, f_hi = 0.25;
const double exact_volume = 4.0 / 3.0 * std::numbers::pi * (r_out * r_out * r_out - r_in * r_in * r_in);

double shell_f(const std::array<double, 3>& p) {
    double s = 0;
    for (int i = 0; i < 3; ++i) s += (p[i] - centre[i]) * (p[i] - centre[i]);
    return s;
}
bool in_shell(const std::array<double, 3>& p) {
    const double f = shell_f(p);
    return f >= f_lo && f <= f_hi;
}

inline auto shell_constraint() {
    constexpr certipose::var<0> x;
    constexpr certipose::var<1> y;
    constexpr certipose::var<2> z;
    return certipose::in(sqr(x - centre[0]) + sqr(y - centre[1]) + sqr(z - centre[2]), f_lo, f_hi);
}

// A small sound contractor for the shell: HC4Revise written out by hand (forward sum of squares,
// intersect with [f_lo, f_hi], project back through +, sqr and − c).
template <class I>
struct shell_contractor {
    double lo = f_lo, hi = f_hi;
    void contract(interval_box<I, 3>& b) const {
        const certipose::rounding_guard<I> guard{};
        std::array<I, 3> d, s;
        for (int i = 0; i < 3; ++i) d[i] = b[i] - centre[i], s[i] = sqr(d[i]);
        const I f = intersect(s[0] + s[1] + s[2], I(lo, hi));
        if (is_empty(f)) return certipose::set_empty(b);
        for (int i = 0; i < 3; ++i) {
            const I si = intersect(s[i], f - s[(i + 1) % 3] - s[(i + 2) % 3]);
            if (is_empty(si)) return certipose::set_empty(b);
            const I r = sqrt(si);
            const I di = hull(intersect(d[i], r), intersect(d[i], -r));
            b[i] = intersect(b[i], di + centre[i]);
            if (is_empty(b[i])) return certipose::set_empty(b);
        }
    }
};

// A contractor of the complement, f ≤ 0.09 or f ≥ 0.25 (the hull of both contractions), for
// the paver's inner-contractor mode.
template <class I>
struct shell_complement {
    void contract(interval_box<I, 3>& b) const {
        auto below = b, above = b;
        shell_contractor<I>{0.0, f_lo}.contract(below);
        shell_contractor<I>{f_hi, inf_v}.contract(above);
        b = certipose::hull(below, above);
    }
};

// Inner test by interval evaluation: exact here since each variable occurs once.
template <class I>
struct shell_test {
    verdict test(const interval_box<I, 3>& b) const {
        const certipose::rounding_guard<I> guard{};
        I f = sqr(b[0] - centre[0]) + sqr(b[1] - centre[1]) + sqr(b[2] - centre[2]);
        if (subset(f, I(f_lo, f_hi))) return verdict::satisfied;
        if (is_empty(intersect(f, I(f_lo, f_hi)))) return verdict::violated;
        return verdict::undecided;
    }
};

template <class I>
interval_box<I, 3> search_box() {
    return interval_box<I, 3>::from_bounds({{{-5, 5}, {-5, 5}, {-5, 5}}});
}

// The paper's Algorithm 1: HC4 outer contractor, evaluation inner test.
template <class I, class Bisector = largest_first, class Buffer = certipose::depth_first>
auto shell_paving(Bisector bis, paver_options opt = {}, std::stop_token stop = {}) {
    return certipose::pave<Buffer>(search_box<I>(), certipose::hc4(shell_constraint()),
                                   certipose::eval_test(shell_constraint()), std::move(bis), std::move(opt),
                                   std::move(stop));
}

// HC4 outer contractor and an inner contractor (the negation, IBEX's CtcNotIn).
template <class I, class Buffer = certipose::depth_first>
auto shell_paving_inner(double eps, paver_options opt = {}) {
    return certipose::pave<Buffer>(search_box<I>(), certipose::hc4(shell_constraint()),
                                   certipose::inner_contractor{certipose::not_in(shell_constraint())},
                                   largest_first(eps), std::move(opt));
}

template <class Box>
double box_volume(const Box& b) {
    double v = 1;
    for (const auto& c : b) v *= upper(c) - lower(c);
    return v;
}

template <class I>
std::array<double, 3> random_point(const interval_box<I, 3>& b, std::mt19937_64& rng) {
    std::array<double, 3> p{};
    for (int i = 0; i < 3; ++i)
        p[i] = std::uniform_real_distribution<double>(lower(b[i]), upper(b[i]))(rng);
    return p;
}

template <class Box>
bool covered(const std::vector<Box>& boxes, const std::array<double, 3>& p) {
    return std::any_of(boxes.begin(), boxes.end(), [&](const Box& b) { return certipose::contains(b, p); });
}

// Solutions sampled in the shell (rejection sampling in its bounding cube).
std::vector<std::array<double, 3>> shell_samples(std::size_t n, unsigned seed) {
    std::mt19937_64 rng(seed);
    std::vector<std::array<double, 3>> pts;
    while (pts.size() < n) {
        std::array<double, 3> p{};
        for (int i = 0; i < 3; ++i) p[i] = std::uniform_real_distribution<double>(centre[i] - r_out, centre[i] + r_out)(rng);
        if (in_shell(p)) pts.push_back(p);
    }
    return pts;
}

template <class Box>
std::vector<std::array<double, 6>> sorted_bounds(const std::vector<Box>& boxes) {
    std::vector<std::array<double, 6>> v;
    for (const auto& b : boxes) v.push_back({lower(b[0]), upper(b[0]), lower(b[1]), upper(b[1]), lower(b[2]), upper(b[2])});
    std::sort(v.begin(), v.end());
    return v;
}

bool rounding_is_nearest() { return std::fegetround() == FE_TONEAREST; }
using rounding_guard_for_tests = certipose::rounding_guard<certipose::boost_interval>;

}  // namespace

// ---- bisectors -----------------------------------------------------------------------------

static_assert(certipose::Bisector<largest_first, interval_box<certipose::boost_interval, 3>>);
static_assert(certipose::Bisector<round_robin, interval_box<certipose::boost_interval, 3>>);
static_assert(certipose::ContextualBisector<round_robin, interval_box<certipose::boost_interval, 3>>);
static_assert(!certipose::ContextualBisector<largest_first, interval_box<certipose::boost_interval, 3>>);

TEST_CASE_TEMPLATE("largest_first splits the widest dimension at the ratio, down to the precision", I,
                   CERTIPOSE_PAVER_TEST_BACKENDS) {
    using box = interval_box<I, 3>;
    const auto b = box::from_bounds({{{0, 1}, {0, 4}, {-1, 1}}});

    SUBCASE("midpoint by default, the paper's choice") {
        const auto s = largest_first(0.1).choose(b);
        REQUIRE(s);
        CHECK(s->dimension == 1);
        CHECK(s->point == 2.0);
        CHECK(largest_first(0.1).ratio() == 0.5);
    }
    SUBCASE("ratio 0.45 as IBEX") {
        const auto s = largest_first(0.1, 0.45).choose(b);
        REQUIRE(s);
        CHECK(s->dimension == 1);
        CHECK(s->point == doctest::Approx(1.8));
    }
    SUBCASE("a dimension narrower than its precision never competes") {
        const auto s = largest_first(std::vector<double>{0.1, 5.0, 0.1}).choose(b);
        REQUIRE(s);
        CHECK(s->dimension == 2);  // width 2 beats width 1; dimension 1 (width 4) is below 5
        CHECK(s->point == 0.0);
    }
    SUBCASE("every dimension narrower than its precision: no split (BOUNDARY)") {
        CHECK_FALSE(largest_first(4.5).choose(b));
        CHECK(largest_first(4.0).choose(b));  // a width equal to ε is still split ("narrower than ε" stops)
        CHECK_FALSE(largest_first(std::vector<double>{1.5, 4.5, 2.5}).choose(b));
    }
    SUBCASE("ties go to the lowest index") {
        const auto s = largest_first(0.1).choose(box::from_bounds({{{0, 2}, {5, 7}, {1, 2}}}));
        REQUIRE(s);
        CHECK(s->dimension == 0);
    }
    SUBCASE("a component without a float inside is not splittable") {
        const double a = 1.0, a1 = std::nextafter(1.0, 2.0);
        const auto tight = box::from_bounds({{{a, a1}, {0, 0}, {3, 3}}});
        CHECK_FALSE(largest_first(std::numeric_limits<double>::denorm_min()).choose(tight));
    }
    SUBCASE("unbounded components split at a finite point") {
        const auto s = largest_first(1.0).choose(box::from_bounds({{{-inf_v, inf_v}, {0, 1}, {0, 1}}}));
        REQUIRE(s);
        CHECK(s->dimension == 0);
        CHECK(std::isfinite(s->point));
        const auto half = largest_first(1.0).choose(box::from_bounds({{{0, inf_v}, {0, 1}, {0, 1}}}));
        REQUIRE(half);
        CHECK(half->dimension == 0);
        CHECK(half->point > 0);
        CHECK(std::isfinite(half->point));
    }
    SUBCASE("an empty box is not split") { CHECK_FALSE(largest_first(0.1).choose(box::empty())); }
}

#ifdef CERTIPOSE_PAVER_TEST_UNTYPED
TEST_CASE("bisector parameters are validated") {
    using box = interval_box<certipose::boost_interval, 3>;
    for (double bad : {0.0, 1.0, -0.5, 1.5, std::nan("")}) {
        CHECK_THROWS_AS(largest_first(0.1, bad), certipose::invalid_argument);
        CHECK_THROWS_AS(round_robin(0.1, bad), certipose::invalid_argument);
    }
    for (double bad : {0.0, -1.0, std::nan("")}) {
        CHECK_THROWS_AS((void)largest_first(bad), certipose::invalid_argument);
        CHECK_THROWS_AS(round_robin(std::vector<double>{0.1, bad}), certipose::invalid_argument);
    }
    CHECK_THROWS_AS((void)largest_first(std::vector<double>{}), certipose::invalid_argument);
    try {
        (void)largest_first(0.1, 1.0);
        FAIL("no throw");
    } catch (const certipose::invalid_argument& e) {
        CHECK(e.field() == "ratio");
    }
    CHECK_NOTHROW((void)largest_first(inf_v));  // +∞: never split
    // Per-dimension precision must match the box.
    const auto b = box::from_bounds({{{0, 1}, {0, 1}, {0, 1}}});
    CHECK_THROWS_AS(largest_first(std::vector<double>{0.1, 0.1}).choose(b), certipose::invalid_argument);
    CHECK_THROWS_AS(round_robin(std::vector<double>{0.1, 0.1}).choose(b), certipose::invalid_argument);
}

// Error messages name the offending value in its shortest round-trip form (detail/format.hpp):
// std::to_string would print 1e-09 as "0.000000" and hide it.
TEST_CASE("error messages name tiny and non-finite values exactly") {
    using certipose::detail::format_double;
    CHECK(format_double(0.1) == "0.1");
    CHECK(format_double(-1e-9) == "-1e-09");
    CHECK(format_double(0.30000000000000004) == "0.30000000000000004");
    CHECK(format_double(std::numeric_limits<double>::denorm_min()) == "5e-324");
    CHECK(format_double(-std::numeric_limits<double>::infinity()) == "-inf");
    CHECK(format_double(std::nan("")) == "nan");

    const auto message = [](auto&& f) -> std::string {
        try {
            f();
        } catch (const certipose::invalid_argument& e) {
            return e.what();
        }
        return "<no exception>";
    };
    const auto names = [](const std::string& msg, const char* value) {
        INFO(msg);
        CHECK(msg.find(value) != std::string::npos);
    };
    names(message([] { certipose::solve_options{.position_eps = -1e-9}.validate(); }), "-1e-09");
    names(message([] { certipose::solve_options{.orientation_eps = -2.5e-12}.validate(); }), "-2.5e-12");
    names(message([] { certipose::solve_options{.paving = certipose::carving{.rest_min_pieces = -0.5}}.validate(); }), "-0.5");
    names(message([] { certipose::inspection_task{.min_view_angle = -1e-300}.validate(); }), "-1e-300");
    names(message([] { (void)largest_first(0.1, 1.0000000000000002); }), "1.0000000000000002");
    names(message([] { (void)round_robin(-1e-20); }), "-1e-20");
    names(message([] { (void)certipose::param<0>(1e-9, -1e-9); }), "-1e-09");
    constexpr certipose::var<0> x;
    names(message([&] { (void)certipose::in(x, 3e-8, 1e-8); }), "3e-08");
    names(message([] { (void)certipose::acid(certipose::hc4(shell_constraint()), {.var_min_width = -1e-12}); }),
          "-1e-12");
}

#endif  // CERTIPOSE_PAVER_TEST_UNTYPED

TEST_CASE_TEMPLATE("round_robin takes the dimensions in turn and skips the narrow ones", I,
                   CERTIPOSE_PAVER_TEST_BACKENDS) {
    using box = interval_box<I, 3>;
    const auto b = box::from_bounds({{{0, 1}, {0, 0.05}, {0, 8}}});
    round_robin rr(0.1);
    SUBCASE("from the tree context") {
        auto s = rr.choose(b, bisection_context{});
        REQUIRE(s);
        CHECK(s->dimension == 0);
        s = rr.choose(b, bisection_context{1, 0});
        REQUIRE(s);
        CHECK(s->dimension == 2);  // dimension 1 is narrower than 0.1
        s = rr.choose(b, bisection_context{2, 2});
        REQUIRE(s);
        CHECK(s->dimension == 0);
        CHECK(s->point == 0.5);
    }
    SUBCASE("stand-alone, from its own history") {
        std::vector<std::size_t> dims;
        for (int k = 0; k < 4; ++k) dims.push_back(rr.choose(b)->dimension);
        CHECK(dims == std::vector<std::size_t>{0, 2, 0, 2});
    }
    SUBCASE("nothing to split") {
        CHECK_FALSE(round_robin(10.0).choose(b));
        CHECK_FALSE(round_robin(10.0).choose(b, bisection_context{3, 1}));
    }
    SUBCASE("ratio") {
        const auto s = round_robin(0.1, 0.25).choose(b, bisection_context{1, 1});
        REQUIRE(s);
        CHECK(s->dimension == 2);
        CHECK(s->point == 2.0);
    }
}

// ---- the paver on the shell ----------------------------------------------------------------

TEST_CASE_TEMPLATE("paving the spherical shell brackets its exact volume, tighter as eps shrinks", I,
                   CERTIPOSE_PAVER_TEST_BACKENDS) {
    REQUIRE(exact_volume == doctest::Approx(0.41050144).epsilon(1e-7));
    double previous_gap = inf_v;
    for (double eps : {0.1, 0.05, 0.025}) {
        CAPTURE(eps);
        const auto r = shell_paving<I>(largest_first(eps));
        const auto& st = r.stats;
        CHECK(st.reason == termination::completed);
        CHECK(r.pending.empty());
        CHECK(st.valid == r.valid.size());
        CHECK(st.boundary == r.boundary.size());
        CHECK(st.valid > 0);
        CHECK(st.valid_volume <= exact_volume);
        CHECK(exact_volume <= st.valid_volume + st.boundary_volume);
        const double gap = st.boundary_volume;
        CHECK(gap < previous_gap);
        previous_gap = gap;
        // Accounting: each processed box is contracted once; bisections make two boxes each.
        CHECK(st.contractions == st.boxes);
        CHECK(st.boxes == 1 + 2 * st.bisections);
        CHECK(st.boxes == st.valid + st.boundary + st.discarded + st.bisections);
        CHECK(st.valid_volume + st.boundary_volume + st.discarded_volume == doctest::Approx(1000.0));
        // BOUNDARY boxes are narrower than ε in every dimension.
        for (const auto& b : r.boundary) CHECK(certipose::max_width(b) < eps);
        CHECK(rounding_is_nearest());
    }
    CHECK(previous_gap < 0.1);
}

TEST_CASE_TEMPLATE("without contraction the inner test alone discards and certifies (pure Algorithm 1)", I,
                   CERTIPOSE_PAVER_TEST_BACKENDS) {
    const auto r = certipose::pave(search_box<I>(), certipose::identity{}, certipose::eval_test(shell_constraint()),
                                   largest_first(0.1));
    const auto& st = r.stats;
    CHECK(st.discarded > 0);  // boxes the test proved violated
    CHECK(st.boxes == st.valid + st.boundary + st.discarded + st.bisections);
    CHECK(st.valid_volume <= exact_volume);
    CHECK(exact_volume <= st.valid_volume + st.boundary_volume);
    CHECK(st.valid_volume + st.boundary_volume + st.discarded_volume == doctest::Approx(1000.0));
    std::mt19937_64 rng(23);
    for (const auto& b : r.valid) CHECK(in_shell(random_point(b, rng)));
    for (const auto& b : r.boundary) CHECK(certipose::max_width(b) < 0.1);
    for (const auto& p : shell_samples(500, 29)) CHECK((covered(r.valid, p) || covered(r.boundary, p)));
    // Contraction only saves work: the same ε with HC4 processes fewer boxes.
    CHECK(shell_paving<I>(largest_first(0.1)).stats.boxes < st.boxes);
}

TEST_CASE_TEMPLATE("VALID boxes contain only solutions and no solution is lost", I, CERTIPOSE_PAVER_TEST_BACKENDS) {
    const auto r = shell_paving<I>(largest_first(0.05));
    std::mt19937_64 rng(42);
    std::size_t checked = 0;
    for (const auto& b : r.valid)
        for (int k = 0; k < 3; ++k, ++checked) {
            const auto p = random_point(b, rng);
            CHECK(in_shell(p));
            // Corners too: VALID is closed.
        }
    for (const auto& b : r.valid)
        for (const auto& c : certipose::corners(b)) {
            const double f = shell_f(c);
            CHECK(f >= f_lo - 1e-12);
            CHECK(f <= f_hi + 1e-12);
        }
    CHECK(checked >= 3000);
    for (const auto& p : shell_samples(2000, 7)) CHECK((covered(r.valid, p) || covered(r.boundary, p)));
}

TEST_CASE_TEMPLATE("depth-first and breadth-first build the same paving", I, CERTIPOSE_PAVER_TEST_BACKENDS) {
    const auto d = shell_paving<I, largest_first, certipose::depth_first>(largest_first(0.05));
    const auto b = shell_paving<I, largest_first, certipose::breadth_first>(largest_first(0.05));
    CHECK(d.stats.valid == b.stats.valid);
    CHECK(d.stats.boundary == b.stats.boundary);
    CHECK(d.stats.bisections == b.stats.bisections);
    CHECK(d.stats.valid_volume == doctest::Approx(b.stats.valid_volume).epsilon(1e-12));
    CHECK(d.stats.boundary_volume == doctest::Approx(b.stats.boundary_volume).epsilon(1e-12));
    CHECK(sorted_bounds(d.valid) == sorted_bounds(b.valid));
    CHECK(sorted_bounds(d.boundary) == sorted_bounds(b.boundary));
    // Breadth-first keeps the whole frontier: its list grows far larger.
    CHECK(b.stats.peak_pending > d.stats.peak_pending);
}

TEST_CASE_TEMPLATE("round_robin paves the shell too, the same whatever the buffer", I, CERTIPOSE_PAVER_TEST_BACKENDS) {
    const auto d = shell_paving<I, round_robin, certipose::depth_first>(round_robin(0.05));
    const auto b = shell_paving<I, round_robin, certipose::breadth_first>(round_robin(0.05));
    CHECK(d.stats.reason == termination::completed);
    CHECK(d.stats.valid_volume <= exact_volume);
    CHECK(exact_volume <= d.stats.valid_volume + d.stats.boundary_volume);
    CHECK(d.stats.boundary_volume < 0.35);
    CHECK(sorted_bounds(d.valid) == sorted_bounds(b.valid));
    CHECK(sorted_bounds(d.boundary) == sorted_bounds(b.boundary));
    for (const auto& box : d.boundary) CHECK(certipose::max_width(box) < 0.05);
    std::mt19937_64 rng(3);
    for (const auto& box : d.valid) CHECK(in_shell(random_point(box, rng)));
}

TEST_CASE_TEMPLATE("the bisection tree is consistent with the paving", I, CERTIPOSE_PAVER_TEST_BACKENDS) {
    for (const bool inner : {false, true}) {
        CAPTURE(inner);
        paver_options opt;
        opt.record_tree = true;
        const auto r = inner ? shell_paving_inner<I>(0.1, opt) : shell_paving<I>(largest_first(0.1), opt);
        const auto& t = r.tree;
        if (inner) CHECK(t.size() > r.stats.boxes);  // VALID pieces and rests are nodes too
        if (!inner) CHECK(t.size() == r.stats.boxes);
        CHECK(t[0].parent == certipose::paving_node<interval_box<I, 3>>::no_parent);
        CHECK(t[0].box == search_box<I>());
        std::vector<std::vector<std::size_t>> children(t.size());
        std::size_t valid = 0, boundary = 0, discarded = 0;
        for (std::size_t k = 1; k < t.size(); ++k) {
            REQUIRE(t[k].parent < k);
            children[t[k].parent].push_back(k);
        }
        std::vector<interval_box<I, 3>> valid_boxes, boundary_boxes;
        for (std::size_t k = 0; k < t.size(); ++k) {
            CAPTURE(k);
            CHECK(certipose::subset(t[k].contracted, t[k].box));
            switch (t[k].classification) {
                case box_class::bisected: {
                    // Children tile the contracted box: two halves, or VALID pieces and the rest.
                    REQUIRE(children[k].size() >= 2);
                    double v = 0;
                    for (std::size_t c : children[k]) {
                        CHECK(certipose::subset(t[c].box, t[k].contracted));
                        v += box_volume(t[c].box);
                    }
                    CHECK(v == doctest::Approx(box_volume(t[k].contracted)).epsilon(1e-9));
                    break;
                }
                case box_class::valid: ++valid, valid_boxes.push_back(t[k].contracted); break;
                case box_class::boundary: ++boundary, boundary_boxes.push_back(t[k].contracted); break;
                case box_class::discarded: ++discarded; break;
                case box_class::pending: FAIL("pending node after a completed run"); break;
            }
            if (t[k].classification != box_class::bisected) CHECK(children[k].empty());
        }
        CHECK(valid == r.stats.valid);
        CHECK(boundary == r.stats.boundary);
        CHECK(discarded == r.stats.discarded);
        CHECK(sorted_bounds(valid_boxes) == sorted_bounds(r.valid));
        CHECK(sorted_bounds(boundary_boxes) == sorted_bounds(r.boundary));
    }
    // Without the option no tree is kept.
    CHECK(shell_paving<I>(largest_first(0.1)).tree.empty());
    CHECK(shell_paving_inner<I>(0.1).tree.empty());
}

// ---- inner contractor (IBEX's CtcNotIn as the inner half of a separator) --------------------

TEST_CASE_TEMPLATE("an inner contractor certifies more of the shell than the inner test", I,
                   CERTIPOSE_PAVER_TEST_BACKENDS) {
    double previous_gap = inf_v;
    for (double eps : {0.2, 0.1, 0.05}) {
        CAPTURE(eps);
        const auto r = shell_paving_inner<I>(eps);
        const auto t = shell_paving<I>(largest_first(eps));
        const auto& st = r.stats;
        CHECK(st.reason == termination::completed);
        CHECK(st.valid_volume <= exact_volume);
        CHECK(exact_volume <= st.valid_volume + st.boundary_volume);
        CHECK(st.valid_volume > t.stats.valid_volume);
        CHECK(st.boundary_volume < t.stats.boundary_volume);
        CHECK(st.boundary_volume < previous_gap);
        previous_gap = st.boundary_volume;
        CHECK(st.valid_volume + st.boundary_volume + st.discarded_volume == doctest::Approx(1000.0));
        CHECK(st.inner_tests + st.discarded == st.boxes);
        for (const auto& b : r.boundary) CHECK(certipose::max_width(b) < eps);
    }
    // At ε = 0.05 this reproduces IBEX's HC4 + CtcNotIn paving (boundary 0.091, inner 0.365).
    const auto r = shell_paving_inner<I>(0.05);
    CHECK(r.stats.boundary_volume < 0.095);
    CHECK(r.stats.valid_volume > 0.36);
    std::mt19937_64 rng(17);
    for (const auto& b : r.valid) {
        for (int k = 0; k < 3; ++k) CHECK(in_shell(random_point(b, rng)));
        for (const auto& c : certipose::corners(b)) {
            CHECK(shell_f(c) >= f_lo - 1e-12);
            CHECK(shell_f(c) <= f_hi + 1e-12);
        }
    }
    for (const auto& p : shell_samples(500, 19)) CHECK((covered(r.valid, p) || covered(r.boundary, p)));
    const auto bfs = shell_paving_inner<I, certipose::breadth_first>(0.05);
    CHECK(sorted_bounds(bfs.valid) == sorted_bounds(r.valid));
    CHECK(sorted_bounds(bfs.boundary) == sorted_bounds(r.boundary));
}

TEST_CASE_TEMPLATE("user-written policies plug in and agree with the library's HC4", I, CERTIPOSE_PAVER_TEST_BACKENDS) {
    // The hand-written HC4Revise does what hc4 does on this constraint, so the pavings match.
    const auto mine = certipose::pave(search_box<I>(), shell_contractor<I>{}, shell_test<I>{}, largest_first(0.1));
    const auto lib = shell_paving<I>(largest_first(0.1));
    CHECK(mine.stats.valid == lib.stats.valid);
    CHECK(mine.stats.boundary == lib.stats.boundary);
    CHECK(mine.stats.valid_volume == doctest::Approx(lib.stats.valid_volume).epsilon(1e-9));
    const auto mine_inner = certipose::pave(search_box<I>(), shell_contractor<I>{},
                                            certipose::inner_contractor{shell_complement<I>{}}, largest_first(0.1));
    const auto lib_inner = shell_paving_inner<I>(0.1);
    CHECK(mine_inner.stats.boundary == lib_inner.stats.boundary);
    CHECK(mine_inner.stats.valid_volume == doctest::Approx(lib_inner.stats.valid_volume).epsilon(1e-6));
    // The proof-of-inclusion test (not_in_test) certifies at least what evaluation does.
    const auto proof = certipose::pave(search_box<I>(), certipose::hc4(shell_constraint()),
                                       certipose::not_in_test(shell_constraint()), largest_first(0.1));
    CHECK(proof.stats.valid_volume >= lib.stats.valid_volume);
    CHECK(proof.stats.valid_volume <= exact_volume);
    CHECK(exact_volume <= proof.stats.valid_volume + proof.stats.boundary_volume);
}

#ifdef CERTIPOSE_PAVER_TEST_UNTYPED
TEST_CASE("box_difference tiles outer minus inner with at most 2N boxes") {
    using I = certipose::boost_interval;
    using box = interval_box<I, 3>;
    const rounding_guard_for_tests guard{};
    const auto outer = box::from_bounds({{{0, 4}, {0, 4}, {0, 4}}});
    for (const auto& inner : {box::from_bounds({{{1, 2}, {1, 3}, {2, 3}}}), box::from_bounds({{{0, 2}, {0, 4}, {3, 4}}}),
                              box::from_bounds({{{0, 4}, {0, 4}, {0, 1}}})}) {
        std::vector<box> pieces;
        certipose::detail::box_difference(outer, inner, [&](box&& b) { pieces.push_back(b); });
        CHECK(pieces.size() <= 6);
        double v = box_volume(inner);
        for (const auto& p : pieces) {
            v += box_volume(p);
            CHECK(certipose::subset(p, outer));
            // Interiors are disjoint from the inner box.
            const auto x = certipose::intersect(p, inner);
            CHECK((certipose::is_empty(x) || box_volume(x) == 0.0));
        }
        CHECK(v == doctest::Approx(64.0));
    }
}

#endif  // CERTIPOSE_PAVER_TEST_UNTYPED

// ---- budgets, deadlines, progress, cancellation ---------------------------------------------

TEST_CASE_TEMPLATE("a box budget stops the run and returns the unclassified rest", I, CERTIPOSE_PAVER_TEST_BACKENDS) {
    const auto full = shell_paving<I>(largest_first(0.05));
    for (auto buffer_is_bfs : {false, true}) {
        paver_options opt;
        opt.max_boxes = 500;
        opt.record_tree = true;
        const auto r = buffer_is_bfs ? shell_paving<I, largest_first, certipose::breadth_first>(largest_first(0.05), opt)
                                     : shell_paving<I>(largest_first(0.05), opt);
        CHECK(r.stats.reason == termination::box_budget);
        CHECK(r.stats.boxes == 500);
        CHECK(r.stats.pending == r.pending.size());
        CHECK(!r.pending.empty());
        CHECK(r.stats.pending_volume > 0);
        CHECK(r.stats.valid <= full.stats.valid);
        const auto pending_nodes = std::count_if(r.tree.begin(), r.tree.end(),
                                                 [](const auto& n) { return n.classification == box_class::pending; });
        CHECK(static_cast<std::size_t>(pending_nodes) == r.pending.size());
        // No solution lost: VALID ∪ BOUNDARY ∪ pending still covers the shell.
        for (const auto& p : shell_samples(300, 11))
            CHECK((covered(r.valid, p) || covered(r.boundary, p) || covered(r.pending, p)));
        std::mt19937_64 rng(5);
        for (const auto& b : r.valid) CHECK(in_shell(random_point(b, rng)));
    }
    paver_options zero;
    zero.max_boxes = 0;
    const auto z = shell_paving<I>(largest_first(0.05), zero);
    CHECK(z.stats.reason == termination::box_budget);
    CHECK(z.stats.boxes == 0);
    REQUIRE(z.pending.size() == 1);
    CHECK(z.pending[0] == search_box<I>());
    // A budget that is not reached changes nothing.
    paver_options big;
    big.max_boxes = full.stats.boxes;
    const auto exact_budget = shell_paving<I>(largest_first(0.05), big);
    CHECK(exact_budget.stats.reason == termination::completed);
    CHECK(exact_budget.stats.valid == full.stats.valid);
}

TEST_CASE_TEMPLATE("a deadline stops the run", I, CERTIPOSE_PAVER_TEST_BACKENDS) {
    SUBCASE("time limit of zero") {
        paver_options opt;
        opt.time_limit = std::chrono::nanoseconds(0);
        const auto r = shell_paving<I>(largest_first(0.05), opt);
        CHECK(r.stats.reason == termination::deadline);
        CHECK(r.stats.boxes == 0);
        CHECK(r.pending.size() == 1);
    }
    SUBCASE("deadline in the past") {
        paver_options opt;
        opt.deadline = std::chrono::steady_clock::now() - std::chrono::seconds(1);
        opt.time_limit = std::chrono::hours(1);  // the earlier of the two wins
        CHECK(shell_paving<I>(largest_first(0.05), opt).stats.reason == termination::deadline);
    }
    SUBCASE("a deadline hit in the middle of the run") {
        // The progress callback sleeps past the time limit, so the deadline must fire there.
        paver_options opt;
        opt.time_limit = std::chrono::milliseconds(100);
        opt.progress_every = 64;
        opt.progress = [](const certipose::paver_stats& s) {
            if (s.boxes == 128) std::this_thread::sleep_for(std::chrono::milliseconds(150));
            return true;
        };
        const auto r = shell_paving<I>(largest_first(0.05), opt);
        CHECK(r.stats.reason == termination::deadline);
        CHECK(r.stats.boxes >= 128);
        CHECK(r.stats.boxes <= 128 + 16);
        CHECK(!r.pending.empty());
    }
    SUBCASE("a generous limit is not hit") {
        paver_options opt;
        opt.time_limit = std::chrono::hours(1);
        CHECK(shell_paving<I>(largest_first(0.1), opt).stats.reason == termination::completed);
        opt.time_limit = std::chrono::nanoseconds::max();  // must not overflow the clock
        CHECK(shell_paving<I>(largest_first(0.1), opt).stats.reason == termination::completed);
    }
}

TEST_CASE_TEMPLATE("progress callback and stop_token cancel the run", I, CERTIPOSE_PAVER_TEST_BACKENDS) {
    SUBCASE("the callback sees growing statistics, and false cancels") {
        std::vector<std::size_t> seen;
        bool nearest_in_callback = true;
        paver_options opt;
        opt.progress_every = 100;
        opt.progress = [&](const certipose::paver_stats& s) {
            seen.push_back(s.boxes);
            nearest_in_callback = nearest_in_callback && rounding_is_nearest();
            CHECK(s.contractions == s.boxes);
            return seen.size() < 3;
        };
        const auto r = shell_paving<I>(largest_first(0.05), opt);
        CHECK(r.stats.reason == termination::cancelled);
        CHECK(seen == std::vector<std::size_t>{100, 200, 300});
        CHECK(r.stats.boxes == 300);
        CHECK(nearest_in_callback);
        CHECK(!r.pending.empty());
        CHECK(rounding_is_nearest());
    }
    SUBCASE("a callback that always continues does not change the result") {
        std::size_t calls = 0;
        paver_options opt;
        opt.progress_every = 50;
        opt.progress = [&](const certipose::paver_stats&) { return ++calls, true; };
        const auto r = shell_paving<I>(largest_first(0.05), opt);
        CHECK(r.stats.reason == termination::completed);
        CHECK(calls == r.stats.boxes / 50);
        CHECK(r.stats.valid == shell_paving<I>(largest_first(0.05)).stats.valid);
    }
    SUBCASE("a stop requested before the run") {
        std::stop_source src;
        src.request_stop();
        const auto r = shell_paving<I>(largest_first(0.05), {}, src.get_token());
        CHECK(r.stats.reason == termination::cancelled);
        CHECK(r.stats.boxes == 0);
        CHECK(r.pending.size() == 1);
    }
    SUBCASE("a stop requested during the run (from the callback, as another thread would)") {
        std::stop_source src;
        paver_options opt;
        opt.progress_every = 250;
        opt.progress = [&](const certipose::paver_stats&) {
            src.request_stop();
            return true;
        };
        const auto r = shell_paving<I>(largest_first(0.05), opt, src.get_token());
        CHECK(r.stats.reason == termination::cancelled);
        CHECK(r.stats.boxes == 250);
    }
    SUBCASE("a stop from another thread") {
        // ε = 0.001 would take minutes: only the stop ends this run.
        std::atomic<bool> started{false};
        paver_options opt;
        opt.progress_every = 64;
        opt.progress = [&](const certipose::paver_stats&) { return started = true, true; };
        certipose::paving<interval_box<I, 3>> r;
        std::jthread runner([&](std::stop_token token) { r = shell_paving<I>(largest_first(0.001), opt, token); });
        while (!started) std::this_thread::yield();
        runner.request_stop();
        runner.join();
        CHECK(r.stats.reason == termination::cancelled);
        CHECK(r.stats.boxes >= 64);
        CHECK(!r.pending.empty());
    }
    SUBCASE("progress_every = 0 with a callback is rejected") {
        paver_options opt;
        opt.progress_every = 0;
        opt.progress = [](const certipose::paver_stats&) { return true; };
        CHECK_THROWS_AS(shell_paving<I>(largest_first(0.05), opt), certipose::invalid_argument);
        // Also when set after construction, through options().
        paver_options ok;
        ok.progress = opt.progress;
        certipose::paver<interval_box<I, 3>, shell_contractor<I>, shell_test<I>, largest_first> p{{}, {}, largest_first(0.05), ok};
        p.options().progress_every = 0;
        CHECK_THROWS_AS(p.run(search_box<I>()), certipose::invalid_argument);
        CHECK(rounding_is_nearest());
    }
}

// ---- robustness ----------------------------------------------------------------------------

#ifdef CERTIPOSE_PAVER_TEST_UNTYPED
namespace {
struct bad_bisector {
    std::optional<split> choose(const interval_box<certipose::boost_interval, 3>& b) const {
        return split{0, upper(b[0]) + 1.0};  // outside the box: would loop forever if accepted
    }
};
struct out_of_range_bisector {
    std::optional<split> choose(const interval_box<certipose::boost_interval, 3>&) const { return split{3, 0.0}; }
};
struct everything_undecided {
    verdict test(const interval_box<certipose::boost_interval, 3>&) const { return verdict::undecided; }
};
struct no_contraction {
    void contract(interval_box<certipose::boost_interval, 3>&) const {}
};
}  // namespace

TEST_CASE("a bisector returning a split outside the box is an error, not a hang") {
    using I = certipose::boost_interval;
    CHECK_THROWS_AS(certipose::pave(search_box<I>(), no_contraction{}, everything_undecided{}, bad_bisector{}),
                    certipose::invalid_argument);
    CHECK_THROWS_AS(certipose::pave(search_box<I>(), no_contraction{}, everything_undecided{}, out_of_range_bisector{}),
                    certipose::out_of_range);
    CHECK(rounding_is_nearest());  // the guard restored the mode on the way out
}

TEST_CASE("degenerate inputs") {
    using I = certipose::boost_interval;
    using box = interval_box<I, 3>;
    // An empty initial box is discarded at once.
    const auto e = certipose::pave(box::empty(), no_contraction{}, everything_undecided{}, largest_first(0.1));
    CHECK(e.stats.discarded == 1);
    CHECK(e.valid.empty());
    CHECK(e.boundary.empty());
    // A point box is BOUNDARY immediately when undecided.
    const auto p = certipose::pave(box::from_bounds({{{1, 1}, {2, 2}, {3, 3}}}), no_contraction{},
                                   everything_undecided{}, largest_first(0.1));
    CHECK(p.stats.boundary == 1);
    // Unbounded initial box: contraction makes it finite.
    const auto u = certipose::pave(box::from_bounds({{{-inf_v, inf_v}, {-inf_v, inf_v}, {-inf_v, inf_v}}}),
                                   shell_contractor<I>{}, shell_test<I>{}, largest_first(0.1));
    CHECK(u.stats.reason == termination::completed);
    CHECK(u.stats.valid_volume <= exact_volume);
    CHECK(exact_volume <= u.stats.valid_volume + u.stats.boundary_volume);
    // 1-D: x ∈ [0, 10], undecided everywhere → 2^k boundary pieces narrower than 1.
    using box1 = interval_box<I, 1>;
    struct ident1 { void contract(box1&) const {} };
    struct undec1 { verdict test(const box1&) const { return verdict::undecided; } };
    const auto one = certipose::pave(box1::from_bounds({{{0, 10}}}), ident1{}, undec1{}, largest_first(1.0));
    CHECK(one.stats.boundary == 16);
    CHECK(one.stats.boundary_volume == doctest::Approx(10.0));
}

#endif  // CERTIPOSE_PAVER_TEST_UNTYPED

// ---- threads -------------------------------------------------------------------------------

TEST_CASE_TEMPLATE("two pavers on two threads share no state", I, CERTIPOSE_PAVER_TEST_BACKENDS) {
    const auto reference = shell_paving<I>(largest_first(0.05));
    const auto reference_rr = shell_paving<I, round_robin>(round_robin(0.05));
    using box = interval_box<I, 3>;
    using hc4_t = decltype(certipose::hc4(shell_constraint()));
    using test_t = decltype(certipose::eval_test(shell_constraint()));
    certipose::paver<box, hc4_t, test_t, largest_first> p1{certipose::hc4(shell_constraint()),
                                                           certipose::eval_test(shell_constraint()), largest_first(0.05)};
    certipose::paver<box, hc4_t, test_t, round_robin, certipose::breadth_first> p2{
        certipose::hc4(shell_constraint()), certipose::eval_test(shell_constraint()), round_robin(0.05)};
    certipose::paving<box> r1, r2;
    {
        std::jthread t1([&] {
            for (int k = 0; k < 2; ++k) r1 = p1.run(search_box<I>());
        });
        std::jthread t2([&] {
            for (int k = 0; k < 2; ++k) r2 = p2.run(search_box<I>());
        });
    }
    CHECK(r1.stats.valid == reference.stats.valid);
    CHECK(r1.stats.boundary == reference.stats.boundary);
    CHECK(sorted_bounds(r1.valid) == sorted_bounds(reference.valid));
    CHECK(r2.stats.valid == reference_rr.stats.valid);
    CHECK(sorted_bounds(r2.boundary) == sorted_bounds(reference_rr.boundary));
    CHECK(rounding_is_nearest());
}

#ifdef CERTIPOSE_PAVER_TEST_UNTYPED
#include <certipose/solver/detail/carving.hpp>

namespace {
// An inner separator for the shell: contracts (HC4), then carves off what the complement
// contraction proves inside the shell, as VALID pieces; its state counts the carvings above a
// box (so the test can see the state travel to the halves and to pending pieces).
struct shell_separator {
    struct state {
        int carvings = 0;
        friend bool operator==(const state&, const state&) = default;
    };
    int deepest = 0;
    verdict separate(interval_box<certipose::boost_interval, 3>& b, state& s,
                     certipose::piece_sink<interval_box<certipose::boost_interval, 3>, state>& sink) {
        using I = certipose::boost_interval;
        shell_contractor<I>{}.contract(b);
        if (is_empty(b)) return verdict::violated;
        auto failing = b;
        shell_complement<I>{}.contract(failing);
        if (is_empty(failing)) return verdict::satisfied;
        certipose::detail::carve(b, failing, 0.0, [&](interval_box<I, 3>&& piece) { sink.valid(std::move(piece)); });
        ++s.carvings;
        deepest = std::max(deepest, s.carvings);
        return verdict::undecided;
    }
};
}  // namespace

TEST_CASE("an inner separator carves VALID pieces, carries its state, and loses no solution") {
    using I = certipose::boost_interval;
    static_assert(certipose::InnerSeparator<shell_separator, interval_box<I, 3>>);
    certipose::paver<interval_box<I, 3>, certipose::identity, shell_separator, largest_first> p(
        certipose::identity{}, shell_separator{}, largest_first(0.05));
    const auto r = p.run(search_box<I>());
    REQUIRE(r.stats.reason == certipose::termination::completed);
    CHECK(p.inner_test().deepest > 1);  // states reached the halves
    REQUIRE(p.boundary_states().size() == r.boundary.size());
    for (const auto& b : r.valid)
        for (const auto& c : certipose::corners(b)) {
            const double f = shell_f(c);
            CHECK(f >= f_lo - 1e-12);
            CHECK(f <= f_hi + 1e-12);
        }
    for (const auto& p2 : shell_samples(2000, 11)) CHECK((covered(r.valid, p2) || covered(r.boundary, p2)));
    // It certifies at least what the inner contractor does (the same carving, one ulp apart).
    const auto inner = shell_paving_inner<I>(0.05);
    CHECK(r.stats.valid_volume >= 0.99 * inner.stats.valid_volume);
}

TEST_CASE("run_from paves several boxes with their states as one run") {
    using I = certipose::boost_interval;
    using box = interval_box<I, 3>;
    const std::vector<box> halves{box::from_bounds({{{-5, 1}, {-5, 5}, {-5, 5}}}), box::from_bounds({{{1, 5}, {-5, 5}, {-5, 5}}})};
    certipose::paver<box, certipose::identity, shell_separator, largest_first> p(certipose::identity{}, shell_separator{},
                                                                               largest_first(0.05));
    const auto both = p.run_from(halves, {});
    double separate_volume = 0;
    for (const auto& h : halves) separate_volume += p.run(h).stats.valid_volume;
    CHECK(both.stats.valid_volume == doctest::Approx(separate_volume).epsilon(1e-12));
    const std::vector<shell_separator::state> one{shell_separator::state{}};
    CHECK_THROWS_AS(p.run_from(halves, one), certipose::invalid_argument);
}

namespace {
// An inner separator whose state owns heap memory: a tag given to the root box and inherited.
struct tagging_separator {
    struct state {
        std::shared_ptr<const std::vector<int>> tag;
        friend bool operator==(const state&, const state&) = default;
    };
    verdict separate(interval_box<certipose::boost_interval, 3>&, state& s,
                     certipose::piece_sink<interval_box<certipose::boost_interval, 3>, state>&) {
        if (!s.tag) s.tag = std::make_shared<const std::vector<int>>(std::vector<int>{42, 43});
        return verdict::undecided;
    }
};
}  // namespace

TEST_CASE("run_from may be given the paver's own boundary_states(): they are copied before the run") {
    // The refinement idiom: re-pave a run's BOUNDARY boxes with their states on the same paver.
    // The paver once cleared its states before reading them (ASan: heap-use-after-free).
    using I = certipose::boost_interval;
    using box = interval_box<I, 3>;
    certipose::paver<box, certipose::identity, tagging_separator, largest_first> p(certipose::identity{},
                                                                                 tagging_separator{}, largest_first(2.0));
    const auto first = p.run(box::from_bounds({{{0, 4}, {0, 4}, {0, 4}}}));
    REQUIRE(first.boundary.size() == 64);  // each side halved twice: 4 → 2 → 1
    p.bisector() = largest_first(0.5);
    const auto again = p.run_from(first.boundary, p.boundary_states());
    REQUIRE(p.boundary_states().size() == again.boundary.size());
    CHECK(again.boundary.size() > first.boundary.size());
    for (const auto& st : p.boundary_states()) {
        REQUIRE(st.tag);
        CHECK(*st.tag == std::vector<int>{42, 43});
    }
}

TEST_CASE("largest_volume_first decides the largest boxes first: a budget leaves only small ones") {
    using I = certipose::boost_interval;
    paver_options opt;
    opt.max_boxes = 300;
    const auto dfs = shell_paving<I, largest_first, certipose::depth_first>(largest_first(0.01), opt);
    const auto big = shell_paving<I, largest_first, certipose::largest_volume_first>(largest_first(0.01), opt);
    REQUIRE(dfs.stats.reason == certipose::termination::box_budget);
    REQUIRE(big.stats.reason == certipose::termination::box_budget);
    const auto largest = [](const auto& boxes) {
        double v = 0;
        for (const auto& b : boxes) v = std::max(v, certipose::volume(b));
        return v;
    };
    // Depth first leaves a half of the search box pending; largest first never lets one wait.
    CHECK(largest(big.pending) < largest(dfs.pending) / 8);
}
#endif
