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

#if defined(__x86_64__) || defined(_M_X64)
#include <xmmintrin.h>

#include <limits>

// CGAL's own guard writes only MXCSR's rounding field; cgal_interval's guard clears
// flush-to-zero and denormals-are-zero around it (tests/core/fenv.cpp does the same for
// boost_interval). Every comparison runs after MXCSR is restored: DAZ would read a subnormal
// operand of a comparison as 0 too.
TEST_CASE("cgal_interval's guard: FTZ and DAZ are cleared while held and restored after") {
    constexpr unsigned ftz = 0x8000u, daz = 0x0040u;
    const unsigned saved = _mm_getcsr();
    _mm_setcsr((saved & ~0x6000u) | _MM_ROUND_NEAREST | ftz | daz);
    unsigned inside = 0;
    certipose::cgal_interval product, sum;
    {
        const certipose::rounding_guard<certipose::cgal_interval> guard;
        inside = _mm_getcsr();
        product = certipose::cgal_interval(1e-200) * certipose::cgal_interval(1e-200);
        const double tiny = std::numeric_limits<double>::denorm_min();
        sum = certipose::cgal_interval(tiny) + certipose::cgal_interval(tiny);
    }
    const unsigned after = _mm_getcsr();
    _mm_setcsr(saved);
    const double tiny = std::numeric_limits<double>::denorm_min();
    CHECK((inside & (ftz | daz)) == 0u);
    CHECK((after & (ftz | daz | 0x6000u)) == (ftz | daz | _MM_ROUND_NEAREST));
    CHECK(upper(product) > 0.0);
    CHECK(lower(product) >= 0.0);
    CHECK(lower(sum) == 2 * tiny);
}
#endif
