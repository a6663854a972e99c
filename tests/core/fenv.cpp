// The floating-point environment behind the rounding contract (interval/detail/fenv.hpp): guards
// and scopes keep subnormals even when the host flushes them, and hand the host its settings
// back. A program linked with -ffast-math sets MXCSR's FTZ and DAZ bits at start-up; under FTZ
// the upper bound of [1e-200]·[1e-200] came out 0, below the true product.
// (The encodings the register code relies on are static_asserts in fenv.hpp, checked by
// compiling it; -ffast-math and -ffinite-math-only are refused by tests/compile_fail.)
#include <limits>

#include <certipose/expr/detail/rounding_scope.hpp>
#include <certipose/interval/boost_interval.hpp>

#include <doctest/doctest.h>

#if defined(__x86_64__) || defined(_M_X64)
#include <xmmintrin.h>
#endif

namespace {

using certipose::boost_interval;
constexpr double tiny = std::numeric_limits<double>::denorm_min();  // 4.9e-324

}  // namespace

TEST_CASE("rounding guard: a tiny product keeps a positive upper bound") {
    boost_interval p;
    {
        const certipose::rounding_guard<boost_interval> guard;
        p = boost_interval(1e-200) * boost_interval(1e-200);
    }
    CHECK(lower(p) >= 0.0);
    CHECK(upper(p) > 0.0);
}

#if defined(__x86_64__) || defined(_M_X64)  // the header clears FTZ/DAZ on x86-64 only

namespace {

constexpr unsigned ftz = 0x8000u, daz = 0x0040u;

// Restores the test's MXCSR however the test case ends (a failed REQUIRE throws), so that the
// other tests of the program do not inherit FTZ, DAZ or a rounding mode.
class mxcsr_restorer {
public:
    mxcsr_restorer() noexcept : saved_(_mm_getcsr()) {}
    ~mxcsr_restorer() { _mm_setcsr(saved_); }
    mxcsr_restorer(const mxcsr_restorer&) = delete;
    mxcsr_restorer& operator=(const mxcsr_restorer&) = delete;

private:
    unsigned saved_;
};

// The host's setting: FTZ and DAZ on, with `rounding` (an _MM_ROUND_* value).
void set_host(unsigned rounding) { _mm_setcsr((_mm_getcsr() & ~0x6000u) | rounding | ftz | daz); }

// 2 × the smallest subnormal, through volatiles so that the compiler cannot fold it: 0 when the
// environment flushes subnormals (FTZ: the result; DAZ: the operand).
double doubled_tiny() {
    volatile double a = tiny, two = 2.0;
    return a * two;
}

}  // namespace

// Every comparison below runs after MXCSR is restored: under DAZ a comparison reads a subnormal
// operand as 0 as well.
TEST_CASE("rounding guard: FTZ and DAZ are cleared while held and restored after") {
    double flushed = -1.0;
    unsigned inside = 0, after = 0;
    boost_interval product, scaled, sum;
    {
        const mxcsr_restorer restore;
        set_host(_MM_ROUND_NEAREST);
        flushed = doubled_tiny();
        {
            const certipose::rounding_guard<boost_interval> guard;
            inside = _mm_getcsr();
            product = boost_interval(1e-200) * boost_interval(1e-200);
            scaled = boost_interval(tiny) * boost_interval(2.0);    // a subnormal operand
            sum = boost_interval(tiny) + boost_interval(tiny);
        }
        after = _mm_getcsr();
    }
    CHECK(flushed == 0.0);  // the host setting does flush here, so the checks below mean something
    CHECK((inside & (ftz | daz)) == 0u);
    CHECK((inside & 0x6000u) == _MM_ROUND_UP);
    CHECK((after & (ftz | daz)) == (ftz | daz));
    CHECK((after & 0x6000u) == _MM_ROUND_NEAREST);
    CHECK(lower(product) >= 0.0);
    CHECK(upper(product) > 0.0);
    CHECK(upper(product) == tiny);  // 1e-400 rounded up
    CHECK(lower(scaled) == 2 * tiny);
    CHECK(upper(scaled) == 2 * tiny);
    CHECK(lower(sum) == 2 * tiny);
    CHECK(upper(sum) == 2 * tiny);
}

TEST_CASE("rounding guard: nested in a held upward mode with FTZ and DAZ set") {
    // A host (or CGAL's guard, which writes only the rounding field) may hold the mode upward with
    // subnormals flushed. The contract is not held then, so an expression scope takes a guard
    // instead of trusting the mode, and the guard's restore brings the host's bits back.
    bool held_before = true, held_inside = false;
    unsigned inside = 0, after = 0;
    boost_interval sum;
    {
        const mxcsr_restorer restore;
        set_host(_MM_ROUND_UP);
        held_before = certipose::detail::rounding_is_upward();
        {
            const certipose::expr::detail::upward_scope<boost_interval> scope;
            held_inside = certipose::detail::rounding_is_upward();
            inside = _mm_getcsr();
            sum = boost_interval(tiny) + boost_interval(tiny);
        }
        after = _mm_getcsr();
    }
    CHECK_FALSE(held_before);
    CHECK(held_inside);
    CHECK((inside & (ftz | daz)) == 0u);
    CHECK((after & (ftz | daz | 0x6000u)) == (ftz | daz | _MM_ROUND_UP));
    CHECK(lower(sum) == 2 * tiny);
}

TEST_CASE("round_to_nearest_scope keeps subnormals and restores the host's bits") {
    double result = 0.0;
    unsigned inside = 0, after = 0;
    {
        const mxcsr_restorer restore;
        set_host(_MM_ROUND_UP);
        {
            const certipose::detail::round_to_nearest_scope nearest;
            inside = _mm_getcsr();
            result = doubled_tiny();
        }
        after = _mm_getcsr();
    }
    CHECK((inside & (ftz | daz | 0x6000u)) == _MM_ROUND_NEAREST);
    CHECK(result == 2 * tiny);
    CHECK((after & (ftz | daz | 0x6000u)) == (ftz | daz | _MM_ROUND_UP));
}

TEST_CASE("subnormals_scope clears FTZ and DAZ only, and restores them") {
    double result = 0.0;
    unsigned inside = 0, after = 0;
    {
        const mxcsr_restorer restore;
        set_host(_MM_ROUND_UP);
        {
            const certipose::detail::subnormals_scope subnormals;
            inside = _mm_getcsr();
            result = doubled_tiny();
        }
        after = _mm_getcsr();
    }
    CHECK((inside & (ftz | daz | 0x6000u)) == _MM_ROUND_UP);  // the rounding mode left alone
    CHECK(result == 2 * tiny);
    CHECK((after & (ftz | daz | 0x6000u)) == (ftz | daz | _MM_ROUND_UP));
}
#endif
