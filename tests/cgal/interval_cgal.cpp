// The interval suite (tests/interval_suite.hpp) over the second backend, cgal_interval: the
// same bodies that tests/core/interval.cpp runs for boost_interval.
#include <certipose/interval/cgal_interval.hpp>
#include <certipose/interval/cgal_eigen.hpp>

#include "interval_suite.hpp"

TEST_CASE_TEMPLATE_INVOKE(interval_constant_width, certipose::cgal_interval);
TEST_CASE_TEMPLATE_INVOKE(interval_inclusion_arith, certipose::cgal_interval);
TEST_CASE_TEMPLATE_INVOKE(interval_inclusion_mixed, certipose::cgal_interval);
TEST_CASE_TEMPLATE_INVOKE(interval_inclusion_algebraic, certipose::cgal_interval);
TEST_CASE_TEMPLATE_INVOKE(interval_inclusion_trig, certipose::cgal_interval);
TEST_CASE_TEMPLATE_INVOKE(interval_inclusion_inverse_trig, certipose::cgal_interval);
TEST_CASE_TEMPLATE_INVOKE(interval_inclusion_atan2, certipose::cgal_interval);
TEST_CASE_TEMPLATE_INVOKE(interval_empty, certipose::cgal_interval);
TEST_CASE_TEMPLATE_INVOKE(interval_set_ops, certipose::cgal_interval);
TEST_CASE_TEMPLATE_INVOKE(interval_comparisons, certipose::cgal_interval);
TEST_CASE_TEMPLATE_INVOKE(interval_guard, certipose::cgal_interval);
TEST_CASE_TEMPLATE_INVOKE(interval_box_ops, certipose::cgal_interval);
TEST_CASE_TEMPLATE_INVOKE(interval_eigen, certipose::cgal_interval);

TEST_CASE("cgal_interval: infinite doubles are accepted as points, as Boost does") {
    constexpr double inf = std::numeric_limits<double>::infinity();
    certipose::cgal_interval r;
    {
        const certipose::rounding_guard<certipose::cgal_interval> guard;
        r = certipose::cgal_interval(1.0, 2.0) + inf;  // Interval_nt(double) asserted finiteness
    }
    CHECK(lower(r) == inf);
    CHECK(upper(r) == inf);
    CHECK(certipose::cgal_interval(-inf) == certipose::cgal_interval(-inf, -inf));
}
