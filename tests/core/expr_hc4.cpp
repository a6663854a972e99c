// Expressions, HC4Revise, HC4, ACID, compositions and the inner/outer box tests with the Boost
// backend (tests/cgal/contractors_cgal_backend.cpp runs the same bodies with cgal_interval).
// Bodies are in tests/contractor_suite.hpp.
#include "contractor_suite.hpp"

#include <certipose/interval/boost_interval.hpp>

#include <doctest/doctest.h>

namespace {

using namespace contractor_suite;

#define CERTIPOSE_CORE_BACKENDS certipose::boost_interval

TEST_CASE_TEMPLATE("paper §5.2.1 example: (x − y)² − z = 0 contracts x to [0, 8]", I, CERTIPOSE_CORE_BACKENDS) {
    check_paper_example<I>();
}

TEST_CASE_TEMPLATE("forward evaluation encloses and is certified", I, CERTIPOSE_CORE_BACKENDS) {
    check_forward_evaluation<I>();
}

TEST_CASE_TEMPLATE("backward projections of every operator", I, CERTIPOSE_CORE_BACKENDS) {
    check_backward_projections<I>();
}

TEST_CASE_TEMPLATE("contractors never remove a solution: spherical shell", I, CERTIPOSE_CORE_BACKENDS) {
    check_all_contractors_keep_solutions<I, shell>();
}
TEST_CASE_TEMPLATE("contractors never remove a solution: expanded shell", I, CERTIPOSE_CORE_BACKENDS) {
    check_all_contractors_keep_solutions<I, expanded_shell>();
}
TEST_CASE_TEMPLATE("contractors never remove a solution: product/quotient", I, CERTIPOSE_CORE_BACKENDS) {
    check_all_contractors_keep_solutions<I, product_quotient>();
}
TEST_CASE_TEMPLATE("contractors never remove a solution: sin/cos", I, CERTIPOSE_CORE_BACKENDS) {
    check_all_contractors_keep_solutions<I, trigonometric>();
}
TEST_CASE_TEMPLATE("contractors never remove a solution: sqrt/pow/abs system", I, CERTIPOSE_CORE_BACKENDS) {
    check_all_contractors_keep_solutions<I, mixed_system>();
}
TEST_CASE_TEMPLATE("contractors never remove a solution: dot/cross with a parameter", I, CERTIPOSE_CORE_BACKENDS) {
    check_all_contractors_keep_solutions<I, vector_param>();
}
TEST_CASE_TEMPLATE("equality constraints keep their exact solutions", I, CERTIPOSE_CORE_BACKENDS) {
    check_equality_solutions_kept<I>();
}

TEST_CASE_TEMPLATE("box tests: satisfied boxes hold only solutions, violated boxes none", I,
                   CERTIPOSE_CORE_BACKENDS) {
    check_box_tests<I, shell>();
    check_box_tests<I, expanded_shell>();
    check_box_tests<I, product_quotient>();
    check_box_tests<I, trigonometric>();
    check_box_tests<I, mixed_system>();
    check_box_tests<I, vector_param>();
}

TEST_CASE_TEMPLATE("not_in keeps every violating point", I, CERTIPOSE_CORE_BACKENDS) {
    check_not_in_keeps_violations<I, shell>();
    check_not_in_keeps_violations<I, expanded_shell>();
    check_not_in_keeps_violations<I, trigonometric>();
    check_not_in_keeps_violations<I, vector_param>();
}

TEST_CASE_TEMPLATE("interval parameters are settable", I, CERTIPOSE_CORE_BACKENDS) { check_parameters<I>(); }
TEST_CASE_TEMPLATE("union, sequence, fixpoint, empty boxes", I, CERTIPOSE_CORE_BACKENDS) { check_compositions<I>(); }
TEST_CASE_TEMPLATE("acid's learned state belongs to the object", I, CERTIPOSE_CORE_BACKENDS) {
    check_acid_state_is_per_object<I>();
}
TEST_CASE_TEMPLATE("contractors and tests model the concepts", I, CERTIPOSE_CORE_BACKENDS) { check_concepts<I>(); }
TEST_CASE_TEMPLATE("the caller's rounding mode is restored", I, CERTIPOSE_CORE_BACKENDS) {
    check_rounding_restored<I>();
}

TEST_CASE("bad parameters throw invalid_argument naming the field") {
    using certipose::invalid_argument;
    CHECK_THROWS_AS(certipose::in(x, 2.0, 1.0), invalid_argument);
    CHECK_THROWS_AS(certipose::in(x, std::nan(""), 1.0), invalid_argument);
    CHECK_THROWS_AS((void)(x + std::nan("")), invalid_argument);
    CHECK_THROWS_AS(certipose::param<0>(1.0, 0.0), invalid_argument);
    auto h = certipose::hc4(x <= 1.0);
    CHECK_THROWS_AS(h.set_ratio(1.0), invalid_argument);
    CHECK_THROWS_AS(h.set_ratio(-0.1), invalid_argument);
    CHECK_THROWS_AS(certipose::fixpoint(h, 2.0), invalid_argument);
    certipose::acid_options o;
    o.s3b = 1;
    CHECK_THROWS_AS(certipose::acid(h, o), invalid_argument);
    o = {};
    o.tuning_period = 10;
    o.tuning_length = 20;
    try {
        certipose::acid a(h, o);
        FAIL("no throw");
    } catch (const invalid_argument& e) {
        CHECK(e.field() == "tuning_period");
    }
    try {
        certipose::in(x, 3.0, 1.0);
        FAIL("no throw");
    } catch (const invalid_argument& e) {
        CHECK(e.field() == "in");
        CHECK(std::string(e.what()).find("got [3, 1]") != std::string::npos);  // both bounds, shortest form
    }
}

}  // namespace

// The expression functions are reachable as certipose::..., not only through ADL.
TEST_CASE("qualified expression functions: certipose::sqr, certipose::dot, ...") {
    using I = certipose::boost_interval;
    constexpr certipose::var<0> x;
    constexpr certipose::var<1> y;
    const auto p = certipose::vec(x, y, 0.0);
    // (x − 1)² + y² ≤ 1 and p·(1, 0, 0) ≥ 1.5 (x ≥ 1.5): x ∈ [1.5, 2].
    auto c = certipose::hc4(certipose::sqr(x - 1.0) + certipose::sqr(y) <= 1.0,
                            certipose::dot(p, certipose::vec(1.0, 0.0, 0.0)) >= 1.5,
                            certipose::norm(certipose::cross(p, certipose::vec(0.0, 0.0, 1.0))) <= 2.0,
                            certipose::sqrt(certipose::abs(x)) + certipose::pow(y, 2) + certipose::sin(y) +
                                    certipose::cos(y) <= 10.0);
    auto b = certipose::interval_box<I, 2>::from_bounds({{{-10, 10}, {-10, 10}}});
    c.contract(b);
    REQUIRE_FALSE(certipose::is_empty(b));
    CHECK(certipose::lower(b[0]) >= 1.5 - 1e-12);
    CHECK(certipose::upper(b[0]) <= 2.0 + 1e-12);
    CHECK(certipose::upper(b[1]) <= 1.0 + 1e-12);
    // The interval functions of the same names still resolve for intervals.
    const certipose::rounding_guard<I> rounding;
    const I four = certipose::sqr(I(2.0));
    CHECK(certipose::lower(certipose::sqrt(four)) <= 2.0);
    CHECK(certipose::upper(certipose::sqrt(four)) >= 2.0);
}
