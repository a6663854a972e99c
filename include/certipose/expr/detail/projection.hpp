// certipose/expr/detail/projection.hpp — the backward (projection) rules HC4Revise needs that
// are more than one interval operation: division by an interval containing 0, inverse of even
// powers and of sqr, certified n-th roots, and the periodic inverse of sin/cos.
//
// Not for users. Every function returns a superset of the exact projection (sound); they are
// called with the rounding mode held upward (the caller's rounding_guard), except where a libm
// call needs round-to-nearest, which the function switches to locally.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

#include "certipose/detail/config.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/interval/detail/fenv.hpp"
#include "certipose/interval/detail/transcendental.hpp"
#include "certipose/interval/operations.hpp"

namespace certipose::expr::detail {

inline constexpr double inf = std::numeric_limits<double>::infinity();

template <class I>
CERTIPOSE_DETAIL_INLINE I non_negative(const I& a) {
    return intersect(a, I(0.0, inf));
}

/// t ∩ { n / d : n ∈ N, d ∈ D, d ≠ 0 }, plus all of t when 0 ∈ N and 0 ∈ D (then n = 0·d holds
/// for any quotient). This is the projection of a product x = a·b onto a (N = x, D = b) and of a
/// quotient x = a/b onto b (N = a, D = x). When 0 is inside D the quotient set is the union of
/// two half-lines; we return the hull of t's intersections with them.
template <class I>
I div_projection(const I& t, const I& n, const I& d) {
    if (is_empty(t) || is_empty(n) || is_empty(d)) return interval_traits<I>::empty();
    const bool zero_in_n = contains(n, 0.0), zero_in_d = contains(d, 0.0);
    if (zero_in_n && zero_in_d) return t;
    if (!zero_in_d) return intersect(t, n / d);
    const double dl = lower(d), du = upper(d);
    if (dl == 0.0 && du == 0.0) return interval_traits<I>::empty();  // n ≠ 0 can't be 0·q
    I part_a = interval_traits<I>::empty(), part_b = interval_traits<I>::empty();
    if (lower(n) > 0.0) {
        const double nl = lower(n);
        if (dl < 0.0) part_a = I(-inf, upper(I(nl) / I(dl)));  // d ∈ [dl, 0): q ≤ nl/dl
        if (du > 0.0) part_b = I(lower(I(nl) / I(du)), inf);   // d ∈ (0, du]: q ≥ nl/du
    } else {
        const double nu = upper(n);
        if (du > 0.0) part_a = I(-inf, upper(I(nu) / I(du)));
        if (dl < 0.0) part_b = I(lower(I(nu) / I(dl)), inf);
    }
    return hull(intersect(t, part_a), intersect(t, part_b));
}

/// Same with a scalar divisor (a product or quotient by a double constant).
template <class I>
I div_projection(const I& t, const I& n, double d) {
    if (d == 0.0) return contains(n, 0.0) ? t : interval_traits<I>::empty();
    return intersect(t, n / d);
}

/// An enclosure of √y for y ≥ 0 that never switches the rounding mode: the backend's
/// upward-rounded sqrt of [0, y] gives the upper bound (a lower bound of 0 needs no downward
/// rounding, e.g. Boost's opposite-trick policy switches the FPU mode twice for one), and the
/// lower bound is one double below the upward-rounded √lower, kept only if the backend's
/// outward-rounded square confirms it. Inverting sqr is HC4's most frequent projection, and the
/// mode switches cost more than the rest of it.
template <class I>
I sqrt_enclosure(const I& y) {
    if (is_empty(y) || upper(y) < 0.0) return interval_traits<I>::empty();
    const double hi = upper(sqrt(I(0.0, upper(y))));
    if (lower(y) <= 0.0) return I(0.0, hi);
    const double up = upper(sqrt(I(0.0, lower(y))));  // > 0: lower(y) > 0
    if (upper(sqr(I(up))) <= lower(y)) return I(up, hi);  // exact root (e.g. √4)
    // The double just below `up` (std::nextafter is a libm call; for a positive finite double
    // the predecessor is the bit pattern minus one).
    const double r = std::isfinite(up) ? std::bit_cast<double>(std::bit_cast<std::uint64_t>(up) - 1) : up;
    if (upper(sqr(I(r))) <= lower(y)) return I(r, hi);
    return I(lower(sqrt(I(lower(y)))), hi);
}

/// a ∩ (r ∪ −r) as a hull: the two branches of an even function's inverse.
template <class I>
CERTIPOSE_DETAIL_INLINE I two_branches(const I& a, const I& r) {
    if (is_empty(r)) return r;
    return hull(intersect(a, r), intersect(a, -r));
}

/// A double r ≤ y^(1/n) for y ≥ 0, n ≥ 1, verified with outward-rounded powers.
template <class I>
double root_down(double y, int n) {
    if (n == 1 || y <= 0.0 || y == inf) return std::max(y, 0.0);
    double r;
    {
        const certipose::detail::round_to_nearest_scope nearest{};
        r = certipose::detail::ulps_down(std::pow(y, 1.0 / n), 2);
    }
    for (int i = 0; i < 10 && r > 0.0; ++i) {
        if (upper(certipose::detail::point_pow<I>(r, static_cast<unsigned>(n))) <= y) return r;
        r = certipose::detail::ulps_down(r, 1 << i);
    }
    return 0.0;  // always a lower bound
}

/// A double r ≥ y^(1/n) for y ≥ 0, n ≥ 1, verified with outward-rounded powers.
template <class I>
double root_up(double y, int n) {
    if (n == 1 || y <= 0.0 || y == inf) return std::max(y, 0.0);
    double r;
    {
        const certipose::detail::round_to_nearest_scope nearest{};
        r = certipose::detail::ulps_up(std::pow(y, 1.0 / n), 2);
    }
    for (int i = 0; i < 10 && r < inf; ++i) {
        if (lower(certipose::detail::point_pow<I>(r, static_cast<unsigned>(n))) >= y) return r;
        r = certipose::detail::ulps_up(r, 1 << i);
    }
    return std::max(1.0, y);  // y^(1/n) ≤ max(1, y) for n ≥ 1
}

/// a ∩ { t : t^n ∈ y } for n ≥ 1 (both branches for even n).
template <class I>
I pow_projection(const I& a, const I& y, int n) {
    if (is_empty(y)) return y;
    if (n % 2 == 0) {
        const I yp = non_negative(y);
        if (is_empty(yp)) return yp;
        return two_branches(a, I(root_down<I>(lower(yp), n), root_up<I>(upper(yp), n)));
    }
    const auto signed_root_down = [n](double v) {
        return v >= 0.0 ? root_down<I>(v, n) : -root_up<I>(-v, n);
    };
    const auto signed_root_up = [n](double v) {
        return v >= 0.0 ? root_up<I>(v, n) : -root_down<I>(-v, n);
    };
    return intersect(a, I(signed_root_down(lower(y)), signed_root_up(upper(y))));
}

/// a ∩ { t : cos(t − shift) ∈ y } as a hull, where shift is 0 (cos) or π/2 (sin, since
/// sin t = cos(t − π/2)). The preimage is ±acos(y) + shift + 2kπ; we intersect a with each
/// piece over the periods a spans. Domains wider than `max_periods` periods (or unbounded) are
/// returned unchanged: sound, only loose.
template <class I>
I periodic_projection(const I& a, const I& y, bool sine) {
    if (is_empty(a) || is_empty(y)) return interval_traits<I>::empty();
    const I yy = intersect(y, I(-1.0, 1.0));
    if (is_empty(yy)) return yy;
    if (lower(yy) <= -1.0 && upper(yy) >= 1.0) return a;
    constexpr double max_periods = 8.0;
    constexpr double pi_lo = std::numbers::pi;  // the double nearest π is below π
    const double pi_hi = std::nextafter(pi_lo, 4.0);
    const double al = lower(a), au = upper(a);
    if (!std::isfinite(al) || !std::isfinite(au) || au - al > max_periods * 2.0 * pi_lo) return a;
    const I two_pi(2.0 * pi_lo, 2.0 * pi_hi);
    const I shift = sine ? I(pi_lo / 2.0, pi_hi / 2.0) : I(0.0);
    const I c = acos(yy);  // ⊂ [0, π]
    const I plus = c + shift, minus = shift - c;
    // k such that a piece [−π, π] + shift + 2kπ may meet a, with a margin of one period.
    const double k0 = std::floor(al / (2.0 * pi_lo)) - 1.0;
    const double k1 = std::ceil(au / (2.0 * pi_lo)) + 1.0;
    I r = interval_traits<I>::empty();
    for (double k = k0; k <= k1; k += 1.0) {
        const I offset = I(k) * two_pi;
        r = hull(r, intersect(a, plus + offset));
        r = hull(r, intersect(a, minus + offset));
    }
    return r;
}

}  // namespace certipose::expr::detail
