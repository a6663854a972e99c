// certipose/interval/detail/fenv.hpp — small helpers around the hardware rounding mode.
//
// Not for users. glibc's sin/cos/acos/atan return the same value in every rounding mode
// (STYLE.md), so no rounding policy makes them sound: we evaluate them in round-to-nearest,
// where glibc is accurate to within one ulp, and widen the result outward by
// `transcendental_ulps` ulps.
//
// The floating-point environment interval arithmetic relies on, which every guard and scope
// below establishes for its lifetime and then restores:
//  * the rounding mode it asks for (upward for interval operations, nearest for libm calls);
//  * on x86-64, subnormals kept: MXCSR's flush-to-zero (FTZ) and denormals-are-zero (DAZ) bits
//    clear. Either one turns a tiny positive bound into 0 — with FTZ, the upper bound of
//    [1e-200]·[1e-200] came out 0, below the true product. Code linked with -ffast-math sets
//    both at program start, so a host application may hand us either.
// Elsewhere the mode is switched with fesetround, which leaves flush-to-zero as it finds it
// (FPCR.FZ on aarch64): there the contract assumes the default, subnormals kept.
#pragma once

// Options that give up IEEE semantics cannot be undone at run time, so they are refused at
// compile time. GCC and Clang define __FAST_MATH__ for -ffast-math and -Ofast, and
// __FINITE_MATH_ONLY__ as 1 (0 otherwise) for those and -ffinite-math-only; GCC also defines
// __ASSOCIATIVE_MATH__ and __RECIPROCAL_MATH__ for -funsafe-math-optimizations. Clang drops
// __FAST_MATH__ when -frounding-math follows -ffast-math (as certipose's CMake targets add it)
// but keeps __FINITE_MATH_ONLY__, so the second message names -ffast-math too.
#if defined(__FAST_MATH__)
#error certipose needs IEEE semantics, and -ffast-math (or -Ofast) drops them: the compiler may reassociate operations, divide by reciprocals and ignore infinities, NaNs and the rounding mode, so interval bounds would no longer enclose the exact results. Compile code that includes certipose without it.
#elif defined(__FINITE_MATH_ONLY__) && __FINITE_MATH_ONLY__
#error certipose needs infinities and NaNs, and -ffinite-math-only (implied by -ffast-math and -Ofast) lets the compiler assume there are none: unbounded intervals have infinite bounds and the empty interval has NaN bounds, so tests on them would be optimised away. Compile code that includes certipose without it.
#elif defined(__ASSOCIATIVE_MATH__) || defined(__RECIPROCAL_MATH__)
#error certipose needs IEEE semantics, and -funsafe-math-optimizations (-fassociative-math, -freciprocal-math) drops them: reassociated operations and products by reciprocals are not rounded outward, so interval bounds would no longer enclose the exact results. Compile code that includes certipose without it.
#endif

#include <cassert>
#include <cfenv>
#include <cmath>
#include <limits>

#if defined(__x86_64__) || defined(_M_X64)
#include <xmmintrin.h>
#endif

namespace certipose::detail {

/// Outward widening applied to libm results. glibc documents <= 1 ulp for sin, cos, acos,
/// atan on x86_64 in round-to-nearest; two ulps leave a margin for other libms.
inline constexpr int transcendental_ulps = 2;

// On x86-64 double arithmetic obeys the SSE control register (MXCSR), which CGAL's
// Protect_FPU_rounding sets alone, while glibc's fegetround reads only the x87 control word.
// So the mode that matters is read and restored through MXCSR there.
#if defined(__x86_64__) || defined(_M_X64)
/// The MXCSR fields of the contract: rounding control (bits 13–14), flush-to-zero (bit 15) and
/// denormals-are-zero (bit 6). DAZ is reserved on the few early SSE2 processors without it;
/// clearing it, all we ever do to it, is valid on every processor.
inline constexpr unsigned mxcsr_rounding_bits = 0x6000u;
inline constexpr unsigned mxcsr_flush_to_zero = 0x8000u;
inline constexpr unsigned mxcsr_denormals_are_zero = 0x0040u;
inline constexpr unsigned mxcsr_contract_bits =
    mxcsr_rounding_bits | mxcsr_flush_to_zero | mxcsr_denormals_are_zero;
static_assert(mxcsr_rounding_bits == _MM_ROUND_MASK && mxcsr_flush_to_zero == _MM_FLUSH_ZERO_MASK,
              "certipose: the MXCSR rounding and flush-to-zero fields are not where fenv.hpp writes them");

/// Whether interval arithmetic may run: rounding upward with subnormals kept. One register
/// read, so that expression scopes can ask it before every entry point; a host that set FTZ or
/// DAZ under a held upward mode therefore gets a guard, which clears them.
inline bool rounding_is_upward() noexcept { return (_mm_getcsr() & mxcsr_contract_bits) == _MM_ROUND_UP; }
#else
inline bool rounding_is_upward() noexcept { return std::fegetround() == FE_UPWARD; }
#endif

// Reading and setting the mode. On x86-64 with GCC or Clang the two control registers are
// read and written directly (fnstcw/fldcw for x87, stmxcsr/ldmxcsr for SSE), as glibc's
// fesetround does, but inline: glibc's fesetround took ~100 ns per call on these machines
// (the instructions themselves ~1 ns), and every guard and nearest-scope made two or three.
// The "memory" clobber keeps the compiler from moving memory accesses across a switch, as a
// call would; interval operands and results are also pinned (boost_interval.hpp).
#if defined(__x86_64__) || defined(_M_X64)
/// Writes MXCSR alone (the SSE rounding mode, FTZ and DAZ).
inline void write_mxcsr(unsigned mxcsr) noexcept {
#if defined(__GNUC__) || defined(__clang__)
    __asm__ __volatile__("" : : : "memory");
    _mm_setcsr(mxcsr);
    __asm__ __volatile__("" : : : "memory");
#else
    _mm_setcsr(mxcsr);
#endif
}
#endif
#if (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(_M_X64))
/// Both control words: what a guard saves and restores.
struct fp_modes {
    unsigned short x87;
    unsigned int mxcsr;
};
inline fp_modes get_fp_modes() noexcept {
    fp_modes m;
    __asm__ __volatile__("fnstcw %0" : "=m"(m.x87) : : "memory");
    m.mxcsr = _mm_getcsr();
    return m;
}
inline void set_fp_modes(const fp_modes& m) noexcept {
    __asm__ __volatile__("fldcw %0" : : "m"(m.x87) : "memory");
    _mm_setcsr(m.mxcsr);
    __asm__ __volatile__("" : : : "memory");
}
// set_rounding stores an FE_* value into both rounding fields as is: glibc's x86 encoding is
// the x87 rounding-control field (bits 10–11), and the MXCSR field is the same two bits three
// places higher.
static_assert(FE_TONEAREST == 0x000 && FE_DOWNWARD == 0x400 && FE_UPWARD == 0x800 && FE_TOWARDZERO == 0xC00,
              "certipose: set_rounding assumes the FE_* macros are the x87 rounding-control bits");
static_assert((FE_TONEAREST << 3) == _MM_ROUND_NEAREST && (FE_DOWNWARD << 3) == _MM_ROUND_DOWN &&
                  (FE_UPWARD << 3) == _MM_ROUND_UP && (FE_TOWARDZERO << 3) == _MM_ROUND_TOWARD_ZERO,
              "certipose: set_rounding assumes the MXCSR rounding field is the x87 one shifted by 3");
/// Sets both registers to `mode` (FE_TONEAREST, FE_UPWARD, ...) and, in the same MXCSR write,
/// clears FTZ and DAZ: every guard and scope goes through here, so none pays a second write.
inline void set_rounding(int mode) noexcept {
    fp_modes m = get_fp_modes();
    m.x87 = static_cast<unsigned short>((m.x87 & ~0x0C00u) | (static_cast<unsigned>(mode) & 0x0C00u));
    m.mxcsr = (m.mxcsr & ~mxcsr_contract_bits) | ((static_cast<unsigned>(mode) & 0x0C00u) << 3);
    set_fp_modes(m);
}
#else
// The documented fallback (see the top): the rounding mode only, subnormals assumed kept.
using fp_modes = int;
inline fp_modes get_fp_modes() noexcept { return std::fegetround(); }
inline void set_fp_modes(const fp_modes& m) noexcept { std::fesetround(m); }
inline void set_rounding(int mode) noexcept { std::fesetround(mode); }
#endif

/// Debug builds check the rounding protocol on every interval operation: arithmetic computed
/// without a `rounding_guard`, or with subnormals flushed, is silently unsound, so it must fail
/// loudly in the test suite.
inline void assert_rounding_held() noexcept {
    assert(rounding_is_upward() &&
           "certipose: interval arithmetic needs a rounding_guard in scope (rounding upward, FTZ and DAZ clear)");
}

/// Switches to round-to-nearest, with subnormals kept, for its lifetime, restoring the previous
/// modes after. Restores both the x87 and (on x86-64) the SSE mode, which may differ (see above).
class round_to_nearest_scope {
public:
    round_to_nearest_scope() noexcept : saved_(get_fp_modes()) { set_rounding(FE_TONEAREST); }
    ~round_to_nearest_scope() { set_fp_modes(saved_); }
    round_to_nearest_scope(const round_to_nearest_scope&) = delete;
    round_to_nearest_scope& operator=(const round_to_nearest_scope&) = delete;

private:
    fp_modes saved_;
};

/// Saves the SSE control register (MXCSR: rounding mode, FTZ, DAZ) on x86-64 and restores it on
/// destruction; a no-op elsewhere. Needed by guards built on fegetround/fesetround: glibc's
/// fegetround reads only the x87 word, so a caller that had set only the SSE mode (CGAL's
/// Protect_FPU_rounding does) would get the x87 mode back — a guard nested in a CGAL guard used
/// to leave CGAL's arithmetic running in round-to-nearest afterwards.
class sse_mode_saver {
public:
#if defined(__x86_64__) || defined(_M_X64)
    sse_mode_saver() noexcept : saved_(_mm_getcsr()) {}
    ~sse_mode_saver() { write_mxcsr(saved_); }
#else
    sse_mode_saver() noexcept = default;
#endif
    sse_mode_saver(const sse_mode_saver&) = delete;
    sse_mode_saver& operator=(const sse_mode_saver&) = delete;

#if defined(__x86_64__) || defined(_M_X64)
private:
    unsigned saved_;
#endif
};

/// Keeps subnormals (clears FTZ and DAZ) for its lifetime and restores MXCSR after; a no-op off
/// x86-64. For guards that switch the rounding mode by other means than set_rounding: CGAL's
/// Protect_FPU_rounding writes only MXCSR's rounding field, so on a host that set FTZ it would
/// hold the mode upward with subnormals still flushed. Construct it before such a guard.
class subnormals_scope {
public:
    subnormals_scope() noexcept {
#if defined(__x86_64__) || defined(_M_X64)
        write_mxcsr(_mm_getcsr() & ~(mxcsr_flush_to_zero | mxcsr_denormals_are_zero));
#endif
    }
    subnormals_scope(const subnormals_scope&) = delete;
    subnormals_scope& operator=(const subnormals_scope&) = delete;

private:
    sse_mode_saver saved_;  // made before the body clears the bits; puts the caller's back at the end
};

inline double ulps_down(double x, int n = transcendental_ulps) noexcept {
    for (int i = 0; i < n; ++i) x = std::nextafter(x, -std::numeric_limits<double>::infinity());
    return x;
}
inline double ulps_up(double x, int n = transcendental_ulps) noexcept {
    for (int i = 0; i < n; ++i) x = std::nextafter(x, std::numeric_limits<double>::infinity());
    return x;
}

}  // namespace certipose::detail
