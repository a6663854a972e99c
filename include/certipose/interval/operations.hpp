// certipose/interval/operations.hpp — set operations, bisection and named comparisons for any
// `Interval`, written once on top of lower/upper/is_empty.
//
// Algorithms never compare intervals with raw `<` (Boost.Interval throws on overlap, and the
// meaning is ambiguous): they say `certainly_less(a, b)` (every a below every b) or
// `possibly_less(a, b)` (some a below some b). On an empty interval the `certainly_*`
// predicates are vacuously true and the `possibly_*` ones false, which is what keeps a
// contractor's emptiness proof consistent with the comparisons.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "certipose/detail/config.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/interval/detail/fenv.hpp"

namespace certipose {

// ---- set operations ----------------------------------------------------------------------

/// Smallest interval containing both (the paper's ⊔). Empty is the identity.
template <Interval I>
CERTIPOSE_DETAIL_INLINE I hull(const I& a, const I& b) {
    if (is_empty(a)) return b;
    if (is_empty(b)) return a;
    return I(std::min(lower(a), lower(b)), std::max(upper(a), upper(b)));
}

/// Intersection (the paper's ∩); empty when disjoint.
template <Interval I>
CERTIPOSE_DETAIL_INLINE I intersect(const I& a, const I& b) {
    if (is_empty(a) || is_empty(b)) return interval_traits<I>::empty();
    const double l = std::max(lower(a), lower(b));
    const double u = std::min(upper(a), upper(b));
    return l <= u ? I(l, u) : interval_traits<I>::empty();
}

namespace detail {
/// The next double above w ≥ 0 (w itself when +inf or NaN; the smallest positive double when
/// w is ±0): std::nextafter for this one case without a libm call, which width and radius made
/// millions of times per facet.
inline double next_up_non_negative(double w) noexcept {
    if (!(w < std::numeric_limits<double>::infinity())) return w;
    if (!(w > 0.0)) return std::numeric_limits<double>::denorm_min();
    return std::bit_cast<double>(std::bit_cast<std::uint64_t>(w) + 1);
}
}  // namespace detail

/// Width u − l, never underestimated whatever the current rounding mode (one ulp up covers
/// any rounding of the subtraction); 0 for an empty interval.
template <Interval I>
double width(const I& a) {
    if (is_empty(a)) return 0.0;
    const double w = upper(a) - lower(a);
    return w == 0.0 ? 0.0 : detail::next_up_non_negative(w);
}

/// A point inside `a` near its centre, finite whenever `a` is non-empty (a half-infinite
/// interval yields the finite bound's side, the whole line yields 0). Any rounding keeps it
/// inside [l, u], which is all bisection needs.
template <Interval I>
double mid(const I& a) {
    const double l = lower(a), u = upper(a);
    constexpr double big = std::numeric_limits<double>::max();
    if (l == -std::numeric_limits<double>::infinity())
        return u == std::numeric_limits<double>::infinity() ? 0.0 : std::min(u, -big);
    if (u == std::numeric_limits<double>::infinity()) return std::max(l, big);
    const double m = 0.5 * l + 0.5 * u;  // no overflow, unlike (l + u) / 2
    return std::clamp(m, l, u);
}

/// Radius, rounded up: every point of `a` is within `radius(a)` of `mid(a)`.
template <Interval I>
double radius(const I& a) {
    if (is_empty(a)) return 0.0;
    const double m = mid(a);
    return detail::next_up_non_negative(std::max(m - lower(a), upper(a) - m));
}

template <Interval I>
bool contains(const I& a, double x) {
    return !is_empty(a) && lower(a) <= x && x <= upper(a);
}

/// a ⊆ b. The empty set is a subset of everything.
template <Interval I>
CERTIPOSE_DETAIL_INLINE bool subset(const I& a, const I& b) {
    if (is_empty(a)) return true;
    return !is_empty(b) && lower(b) <= lower(a) && upper(a) <= upper(b);
}

/// a ⊆ interior of b (strict on both finite ends).
template <Interval I>
bool strict_subset(const I& a, const I& b) {
    if (is_empty(a)) return true;
    return !is_empty(b) && lower(b) < lower(a) && upper(a) < upper(b);
}

template <Interval I>
bool is_degenerate(const I& a) {
    return !is_empty(a) && lower(a) == upper(a);
}

/// The split point at `ratio` of the width (0 < ratio < 1), strictly inside when the interval
/// has an interior, so that both halves are strictly smaller than `a`.
template <Interval I>
double split_point(const I& a, double ratio = 0.5) {
    const double l = lower(a), u = upper(a);
    if (!std::isfinite(l) || !std::isfinite(u)) return mid(a);
    double p = l + ratio * (u - l);
    if (!(l < p && p < u)) p = 0.5 * l + 0.5 * u;
    return std::clamp(p, l, u);
}

/// Splits `a` at `split_point(a, ratio)`; the halves share the split point (a closed cover).
template <Interval I>
std::pair<I, I> bisect(const I& a, double ratio = 0.5) {
    const double p = split_point(a, ratio);
    return {I(lower(a), p), I(p, upper(a))};
}

// ---- named comparisons (every/some element of a against every/some element of b) ----------

template <Interval I>
bool certainly_less(const I& a, const I& b) {
    return is_empty(a) || is_empty(b) || upper(a) < lower(b);
}
template <Interval I>
bool certainly_leq(const I& a, const I& b) {
    return is_empty(a) || is_empty(b) || upper(a) <= lower(b);
}
template <Interval I>
bool certainly_greater(const I& a, const I& b) { return certainly_less(b, a); }
template <Interval I>
bool certainly_geq(const I& a, const I& b) { return certainly_leq(b, a); }

template <Interval I>
bool possibly_less(const I& a, const I& b) {
    return !is_empty(a) && !is_empty(b) && lower(a) < upper(b);
}
template <Interval I>
bool possibly_leq(const I& a, const I& b) {
    return !is_empty(a) && !is_empty(b) && lower(a) <= upper(b);
}
template <Interval I>
bool possibly_greater(const I& a, const I& b) { return possibly_less(b, a); }
template <Interval I>
bool possibly_geq(const I& a, const I& b) { return possibly_leq(b, a); }

// Mixed forms against a double, the common case in constraints (`expr ≤ d_max`).
template <Interval I> bool certainly_less(const I& a, double b) { return is_empty(a) || upper(a) < b; }
template <Interval I> bool certainly_leq(const I& a, double b) { return is_empty(a) || upper(a) <= b; }
template <Interval I> bool certainly_greater(const I& a, double b) { return is_empty(a) || lower(a) > b; }
template <Interval I> bool certainly_geq(const I& a, double b) { return is_empty(a) || lower(a) >= b; }
template <Interval I> bool possibly_less(const I& a, double b) { return !is_empty(a) && lower(a) < b; }
template <Interval I> bool possibly_leq(const I& a, double b) { return !is_empty(a) && lower(a) <= b; }
template <Interval I> bool possibly_greater(const I& a, double b) { return !is_empty(a) && upper(a) > b; }
template <Interval I> bool possibly_geq(const I& a, double b) { return !is_empty(a) && upper(a) >= b; }

// ---- atan2 ----------------------------------------------------------------------------------

/// Enclosure of { atan2(y, x) : y ∈ [y], x ∈ [x] } in [−π, π]. A box that does not contain the
/// origin and does not cross the branch cut (the negative x axis) is a convex set seen under
/// an angle < π, so the extreme angles are attained at its corners; otherwise the answer is
/// the whole range. Corners are evaluated in round-to-nearest and widened outward.
template <Interval I>
I atan2(const I& y, const I& x) {
    if (is_empty(y) || is_empty(x)) return interval_traits<I>::empty();
    // Outward bounds of π: the double nearest π is below π.
    constexpr double pi_lo = std::numbers::pi;
    const double pi_hi = std::nextafter(pi_lo, 4.0);
    const I full(-pi_hi, pi_hi);
    const bool origin_inside = lower(x) <= 0 && upper(x) >= 0 && lower(y) <= 0 && upper(y) >= 0;
    const bool crosses_cut = lower(x) < 0 && lower(y) < 0 && upper(y) >= 0;
    if (origin_inside || crosses_cut) return full;
    if (!std::isfinite(lower(x)) || !std::isfinite(upper(x)) || !std::isfinite(lower(y)) ||
        !std::isfinite(upper(y))) {
        // Unbounded boxes: fall back to the whole range rather than reason about limits.
        return full;
    }
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    {
        const detail::round_to_nearest_scope nearest{};
        for (double yy : {lower(y), upper(y)})
            for (double xx : {lower(x), upper(x)}) {
                // +0.0 for y = 0 keeps points on the cut's upper side at +π, where they belong
                // given the tests above (a box touching the cut from below was sent to `full`).
                const double a = std::atan2(yy == 0.0 ? 0.0 : yy, xx);
                lo = std::min(lo, a);
                hi = std::max(hi, a);
            }
    }
    return I(std::max(detail::ulps_down(lo), -pi_hi), std::min(detail::ulps_up(hi), pi_hi));
}

}  // namespace certipose
