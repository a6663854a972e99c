// certipose/interval/detail/transcendental.hpp — sound sin/cos/acos/atan/pow for a backend
// that only has the four operations and sqrt (e.g. CGAL::Interval_nt).
//
// Method: evaluate at the endpoints in round-to-nearest, widen outward by ulps (glibc is
// accurate to < 1 ulp there but ignores the rounding mode), and add every extremum the
// interval *possibly* contains. Whether k·π (or π/2 + k·π) lies in [l, u] is decided against
// the double approximation of k·π with a tolerance larger than its error, so an extremum is
// never missed; including one that is not there only widens the result.
//
// The templates are unconstrained on purpose: a backend calls them from its own friend
// functions, where the backend type is still incomplete and cannot satisfy `Interval` yet.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "certipose/interval/concept.hpp"
#include "certipose/interval/detail/fenv.hpp"

namespace certipose::detail {

// Shared by sin and cos: f has its extrema at phase + k·π with value sign·(−1)^k.
template <class I, class F>
I periodic_enclosure(const I& x, F f, double phase, double sign_at_k0) {
    if (is_empty(x)) return interval_traits<I>::empty();
    const double l = lower(x), u = upper(x);
    constexpr double pi = std::numbers::pi;
    // Beyond 2^50 the loop counter k below would stop being exact (|x|/π near 2^53 made
    // `k += 1` a no-op and the loop never ended); there the whole range is the answer.
    constexpr double huge = 0x1p50;
    if (!(std::abs(l) < huge) || !(std::abs(u) < huge) || u - l >= 2.0 * pi - 1e-6) return I(-1.0, 1.0);
    double lo, hi;
    {
        const round_to_nearest_scope nearest{};
        const double fl = f(l), fu = f(u);
        lo = ulps_down(std::min(fl, fu));
        hi = ulps_up(std::max(fl, fu));
        const double k0 = std::floor((l - phase) / pi) - 1.0;
        const double k1 = std::ceil((u - phase) / pi) + 1.0;
        for (double k = k0; k <= k1; k += 1.0) {
            const double t = phase + k * pi;
            const double tol = 8.0 * std::numeric_limits<double>::epsilon() * (std::abs(t) + pi);
            if (t + tol < l || t - tol > u) continue;
            const bool even = std::fmod(std::abs(k), 2.0) == 0.0;
            const double value = even ? sign_at_k0 : -sign_at_k0;
            lo = std::min(lo, value);
            hi = std::max(hi, value);
        }
    }
    return I(std::max(lo, -1.0), std::min(hi, 1.0));
}

template <class I>
I generic_cos(const I& x) {
    return periodic_enclosure(x, [](double v) { return std::cos(v); }, 0.0, 1.0);
}

template <class I>
I generic_sin(const I& x) {
    return periodic_enclosure(x, [](double v) { return std::sin(v); }, std::numbers::pi / 2, 1.0);
}

template <class I>
I generic_acos(const I& x) {
    if (is_empty(x) || upper(x) < -1.0 || lower(x) > 1.0) return interval_traits<I>::empty();
    const double pi_hi = std::nextafter(std::numbers::pi, 4.0);
    const round_to_nearest_scope nearest{};
    const double lo = ulps_down(std::acos(std::min(upper(x), 1.0)));
    const double hi = ulps_up(std::acos(std::max(lower(x), -1.0)));
    return I(std::max(lo, 0.0), std::min(hi, pi_hi));
}

template <class I>
I generic_atan(const I& x) {
    if (is_empty(x)) return interval_traits<I>::empty();
    const double half_pi_hi = std::nextafter(std::numbers::pi / 2, 4.0);
    const round_to_nearest_scope nearest{};
    const double lo = ulps_down(std::atan(lower(x)));
    const double hi = ulps_up(std::atan(upper(x)));
    return I(std::max(lo, -half_pi_hi), std::min(hi, half_pi_hi));
}

// x^n for a point interval by squaring; every product is outward rounded by the backend.
template <class I>
I point_pow(double v, unsigned n) {
    I result(1.0), base(v);
    while (n) {
        if (n & 1u) result = result * base;
        n >>= 1u;
        if (n) base = base * base;
    }
    return result;
}

/// Integer power: odd powers are increasing, even powers increasing in |x|, so the bounds
/// come from enclosures of the endpoint powers.
template <class I>
I generic_pow(const I& x, int n) {
    if (is_empty(x)) return x;
    if (n == 0) return I(1.0);
    if (n == std::numeric_limits<int>::min()) return sqr(generic_pow(x, n / 2));  // -n overflows
    if (n < 0) return I(1.0) / generic_pow(x, -n);
    const auto un = static_cast<unsigned>(n);
    if (un % 2u == 1u) return I(lower(point_pow<I>(lower(x), un)), upper(point_pow<I>(upper(x), un)));
    const double l = lower(x), u = upper(x);
    const double amin = (l <= 0.0 && u >= 0.0) ? 0.0 : std::min(std::abs(l), std::abs(u));
    const double amax = std::max(std::abs(l), std::abs(u));
    return I(lower(point_pow<I>(amin, un)), upper(point_pow<I>(amax, un)));
}

}  // namespace certipose::detail
