// The interval suite (tests/interval_suite.hpp) over the default backend, boost_interval, plus
// what is specific to it: only the opposite-trick arithmetic policy is accepted, and the cases
// where the wrapper departs from Boost's operators (0·∞ corners of its branch-free product,
// [0,0]^0, the INT_MIN exponent, sqrt's lower bound).
#include <string>
#include <type_traits>
#include <certipose/interval/boost_interval.hpp>
#include <certipose/interval/eigen.hpp>

#include "interval_suite.hpp"

#include <boost/numeric/interval.hpp>

#include <climits>

TEST_CASE_TEMPLATE_INVOKE(interval_constant_width, certipose::boost_interval);
TEST_CASE_TEMPLATE_INVOKE(interval_inclusion_arith, certipose::boost_interval);
TEST_CASE_TEMPLATE_INVOKE(interval_inclusion_mixed, certipose::boost_interval);
TEST_CASE_TEMPLATE_INVOKE(interval_inclusion_algebraic, certipose::boost_interval);
TEST_CASE_TEMPLATE_INVOKE(interval_inclusion_trig, certipose::boost_interval);
TEST_CASE_TEMPLATE_INVOKE(interval_inclusion_inverse_trig, certipose::boost_interval);
TEST_CASE_TEMPLATE_INVOKE(interval_inclusion_atan2, certipose::boost_interval);
TEST_CASE_TEMPLATE_INVOKE(interval_empty, certipose::boost_interval);
TEST_CASE_TEMPLATE_INVOKE(interval_set_ops, certipose::boost_interval);
TEST_CASE_TEMPLATE_INVOKE(interval_comparisons, certipose::boost_interval);
TEST_CASE_TEMPLATE_INVOKE(interval_guard, certipose::boost_interval);
TEST_CASE_TEMPLATE_INVOKE(interval_box_ops, certipose::boost_interval);
TEST_CASE_TEMPLATE_INVOKE(interval_eigen, certipose::boost_interval);

namespace {

namespace bil = boost::numeric::interval_lib;
using certipose::boost_interval;

static_assert(certipose::Interval<boost_interval>);

}  // namespace

// boost_interval was basic_boost_interval<Arith> with a check rejecting the policies that gave
// zero-width results at -O2; it is now one class with the opposite trick built in, so there is
// no policy left to get wrong. What the old check guarded stays asserted: the arithmetic is
// rounded_arith_opp, with certipose's rounding control.
TEST_CASE("boost_interval: the opposite-trick arithmetic, in a class of its own") {
    static_assert(std::is_base_of_v<bil::rounded_arith_opp<double, certipose::detail::rounding_control>,
                                    boost_interval::rounding>);
    static_assert(!std::is_base_of_v<bil::rounded_arith_std<double>, boost_interval::rounding>);
    static_assert(std::is_class_v<boost_interval> && !std::is_same_v<boost_interval, boost_interval::base_type>);
    CHECK(std::string(certipose::interval_traits<boost_interval>::name) == "boost_interval");
}

TEST_CASE("boost_interval: exact answers where Boost's operators alone would differ") {
    using certipose::interval_traits;
    constexpr double inf = std::numeric_limits<double>::infinity();
    boost_interval zero_inf, whole_zero, neg_inf, z0, big_neg, root4, root2;
    {
        const certipose::rounding_guard<boost_interval> guard;
        zero_inf = boost_interval(0.0) * boost_interval(1.0, inf);         // 0·∞ corners are 0
        whole_zero = interval_traits<boost_interval>::whole() * boost_interval(0.0);
        neg_inf = boost_interval(-1.0, 0.0) * boost_interval(-inf, -2.0);  // a NaN corner skipped
        z0 = pow(boost_interval(0.0), 0);                                 // Boost says empty
        big_neg = pow(boost_interval(1.0, 2.0), INT_MIN);                 // Boost negates INT_MIN
        root4 = sqrt(boost_interval(4.0));                                // exact roots stay exact
        root2 = sqrt(boost_interval(2.0));
    }
    CHECK(zero_inf == boost_interval(0.0));
    CHECK(whole_zero == boost_interval(0.0));
    CHECK(lower(neg_inf) == 0.0);
    CHECK(upper(neg_inf) == inf);
    CHECK(z0 == boost_interval(1.0));
    CHECK(lower(big_neg) == 0.0);
    CHECK(upper(big_neg) == 1.0);
    CHECK(root4 == boost_interval(2.0));
    CHECK(lower(root2) == 1.4142135623730949);
    CHECK(upper(root2) == 1.4142135623730951);
}
