// The expression / contractor suite (tests/contractor_suite.hpp) with the CGAL interval
// backend: the same bodies tests/core/expr_hc4.cpp runs with boost_interval.
#include "contractor_suite.hpp"

#include <certipose/interval/cgal_interval.hpp>

#include <doctest/doctest.h>

namespace {

using namespace contractor_suite;
using I = certipose::cgal_interval;

TEST_CASE("cgal_interval: paper §5.2.1 example") { check_paper_example<I>(); }
TEST_CASE("cgal_interval: forward evaluation") { check_forward_evaluation<I>(); }
TEST_CASE("cgal_interval: backward projections") { check_backward_projections<I>(); }
TEST_CASE("cgal_interval: contractors never remove a solution") {
    check_all_contractors_keep_solutions<I, shell>();
    check_all_contractors_keep_solutions<I, expanded_shell>();
    check_all_contractors_keep_solutions<I, product_quotient>();
    check_all_contractors_keep_solutions<I, trigonometric>();
    check_all_contractors_keep_solutions<I, mixed_system>();
    check_all_contractors_keep_solutions<I, vector_param>();
    check_equality_solutions_kept<I>();
}
TEST_CASE("cgal_interval: box tests") {
    check_box_tests<I, shell>();
    check_box_tests<I, expanded_shell>();
    check_box_tests<I, product_quotient>();
    check_box_tests<I, trigonometric>();
    check_box_tests<I, mixed_system>();
    check_box_tests<I, vector_param>();
    check_not_in_keeps_violations<I, shell>();
    check_not_in_keeps_violations<I, trigonometric>();
}
TEST_CASE("cgal_interval: parameters, compositions, acid state, concepts, rounding") {
    check_parameters<I>();
    check_compositions<I>();
    check_acid_state_is_per_object<I>();
    check_concepts<I>();
    check_rounding_restored<I>();
}

}  // namespace
