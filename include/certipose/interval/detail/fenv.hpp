// certipose/interval/detail/fenv.hpp — small helpers around the hardware rounding mode.
//
// Not for users. glibc's sin/cos/acos/atan return the same value in every rounding mode
// (STYLE.md), so no rounding policy makes them sound: we evaluate them in round-to-nearest,
// where glibc is accurate to within one ulp, and widen the result outward by
// `transcendental_ulps` ulps.
#pragma once

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
inline bool rounding_is_upward() noexcept { return _MM_GET_ROUNDING_MODE() == _MM_ROUND_UP; }
#else
inline bool rounding_is_upward() noexcept { return std::fegetround() == FE_UPWARD; }
#endif

// Reading and setting the mode. On x86-64 with GCC or Clang the two control registers are
// read and written directly (fnstcw/fldcw for x87, stmxcsr/ldmxcsr for SSE), as glibc's
// fesetround does, but inline: glibc's fesetround took ~100 ns per call on these machines
// (the instructions themselves ~1 ns), and every guard and nearest-scope made two or three.
// The "memory" clobber keeps the compiler from moving memory accesses across a switch, as a
// call would; interval operands and results are also pinned (boost_interval.hpp).
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
/// Sets both registers to `mode` (FE_TONEAREST, FE_UPWARD, ...: on x86 these are the x87
/// rounding-control bits, and the SSE ones are the same bits three places higher).
inline void set_rounding(int mode) noexcept {
    fp_modes m = get_fp_modes();
    m.x87 = static_cast<unsigned short>((m.x87 & ~0x0C00u) | (static_cast<unsigned>(mode) & 0x0C00u));
    m.mxcsr = (m.mxcsr & ~0x6000u) | ((static_cast<unsigned>(mode) & 0x0C00u) << 3);
    set_fp_modes(m);
}
#else
using fp_modes = int;
inline fp_modes get_fp_modes() noexcept { return std::fegetround(); }
inline void set_fp_modes(const fp_modes& m) noexcept { std::fesetround(m); }
inline void set_rounding(int mode) noexcept { std::fesetround(mode); }
#endif

/// Debug builds check the rounding protocol on every interval operation: arithmetic computed
/// without a `rounding_guard` is silently unsound, so it must fail loudly in the test suite.
inline void assert_rounding_held() noexcept {
    assert(rounding_is_upward() && "certipose: interval arithmetic needs a rounding_guard in scope");
}

/// Switches to round-to-nearest for its lifetime, restoring the previous mode after.
/// Restores both the x87 and (on x86-64) the SSE mode, which may differ (see above).
class round_to_nearest_scope {
public:
    round_to_nearest_scope() noexcept : saved_(get_fp_modes()) { set_rounding(FE_TONEAREST); }
    ~round_to_nearest_scope() { set_fp_modes(saved_); }
    round_to_nearest_scope(const round_to_nearest_scope&) = delete;
    round_to_nearest_scope& operator=(const round_to_nearest_scope&) = delete;

private:
    fp_modes saved_;
};

/// Saves the SSE rounding mode (MXCSR) on x86-64 and restores it on destruction; a no-op
/// elsewhere. Needed by guards built on fegetround/fesetround: glibc's fegetround reads only the
/// x87 word, so a caller that had set only the SSE mode (CGAL's Protect_FPU_rounding does) would
/// get the x87 mode back — a guard nested in a CGAL guard used to leave CGAL's arithmetic
/// running in round-to-nearest afterwards.
class sse_mode_saver {
public:
#if defined(__x86_64__) || defined(_M_X64)
    sse_mode_saver() noexcept : saved_(_mm_getcsr()) {}
    ~sse_mode_saver() { _mm_setcsr(saved_); }
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

inline double ulps_down(double x, int n = transcendental_ulps) noexcept {
    for (int i = 0; i < n; ++i) x = std::nextafter(x, -std::numeric_limits<double>::infinity());
    return x;
}
inline double ulps_up(double x, int n = transcendental_ulps) noexcept {
    for (int i = 0; i < n; ++i) x = std::nextafter(x, std::numeric_limits<double>::infinity());
    return x;
}

}  // namespace certipose::detail
