// certipose/pose/interval_box.hpp — an N-dimensional box of intervals, the unit the paver
// bisects and contractors narrow.
//
// Fixed size (std::array), so contracting and bisecting never allocate. A box is empty as soon
// as one component is: contractors prove infeasibility by emptying a component, and
// `is_empty(box)` is what the paver tests.
#pragma once

#include <array>
#include <cstddef>
#include <initializer_list>
#include <limits>
#include <utility>

#include "certipose/interval/concept.hpp"
#include "certipose/interval/operations.hpp"

namespace certipose {

template <Interval I, std::size_t N>
struct interval_box {
    using interval_type = I;
    static constexpr std::size_t dimension = N;

    std::array<I, N> x{};

    I& operator[](std::size_t i) noexcept { return x[i]; }
    const I& operator[](std::size_t i) const noexcept { return x[i]; }
    static constexpr std::size_t size() noexcept { return N; }
    auto begin() noexcept { return x.begin(); }
    auto end() noexcept { return x.end(); }
    auto begin() const noexcept { return x.begin(); }
    auto end() const noexcept { return x.end(); }

    /// Every component set to the empty interval.
    static interval_box empty() {
        interval_box b;
        b.x.fill(interval_traits<I>::empty());
        return b;
    }
    /// Builds a box from {lower, upper} pairs: `interval_box<I,3>::from_bounds({{0,1},{2,3},{4,5}})`.
    static interval_box from_bounds(const std::array<std::pair<double, double>, N>& bounds) {
        interval_box b;
        for (std::size_t i = 0; i < N; ++i) b.x[i] = I(bounds[i].first, bounds[i].second);
        return b;
    }

    friend bool operator==(const interval_box&, const interval_box&) = default;
};

template <Interval I, std::size_t N>
bool is_empty(const interval_box<I, N>& b) {
    for (const I& c : b.x)
        if (is_empty(c)) return true;
    return false;
}

/// Marks the whole box empty (one empty component is enough; all are set for clarity).
template <Interval I, std::size_t N>
void set_empty(interval_box<I, N>& b) {
    b.x.fill(interval_traits<I>::empty());
}

/// Largest component width (the paper's "widest interval", Algorithm 1 line 16).
template <Interval I, std::size_t N>
double max_width(const interval_box<I, N>& b) {
    double w = 0.0;
    for (const I& c : b.x) w = std::max(w, width(c));
    return w;
}

/// Index of the widest component (first one on ties).
template <Interval I, std::size_t N>
std::size_t widest_dimension(const interval_box<I, N>& b) {
    std::size_t k = 0;
    double w = -1.0;
    for (std::size_t i = 0; i < N; ++i)
        if (const double wi = width(b.x[i]); wi > w) w = wi, k = i;
    return k;
}

/// Volume (product of widths, each rounded up), 0 for an empty box.
template <Interval I, std::size_t N>
double volume(const interval_box<I, N>& b) {
    if (is_empty(b)) return 0.0;
    double v = 1.0;
    for (const I& c : b.x) v *= width(c);
    return v;
}

template <Interval I, std::size_t N>
std::array<double, N> midpoint(const interval_box<I, N>& b) {
    std::array<double, N> m{};
    for (std::size_t i = 0; i < N; ++i) m[i] = mid(b.x[i]);
    return m;
}

template <Interval I, std::size_t N>
bool contains(const interval_box<I, N>& b, const std::array<double, N>& p) {
    for (std::size_t i = 0; i < N; ++i)
        if (!contains(b.x[i], p[i])) return false;
    return true;
}

/// a ⊆ b componentwise.
template <Interval I, std::size_t N>
bool subset(const interval_box<I, N>& a, const interval_box<I, N>& b) {
    if (is_empty(a)) return true;
    for (std::size_t i = 0; i < N; ++i)
        if (!subset(a.x[i], b.x[i])) return false;
    return true;
}

template <Interval I, std::size_t N>
interval_box<I, N> hull(const interval_box<I, N>& a, const interval_box<I, N>& b) {
    if (is_empty(a)) return b;
    if (is_empty(b)) return a;
    interval_box<I, N> r;
    for (std::size_t i = 0; i < N; ++i) r.x[i] = hull(a.x[i], b.x[i]);
    return r;
}

template <Interval I, std::size_t N>
interval_box<I, N> intersect(const interval_box<I, N>& a, const interval_box<I, N>& b) {
    interval_box<I, N> r;
    for (std::size_t i = 0; i < N; ++i) r.x[i] = intersect(a.x[i], b.x[i]);
    if (is_empty(r)) set_empty(r);
    return r;
}

/// Splits `b` along dimension `dim` at `point` (which must lie inside that component); the two
/// halves share the split face, so together they cover `b` exactly (paper §5.2.2).
template <Interval I, std::size_t N>
std::pair<interval_box<I, N>, interval_box<I, N>> bisect_at(const interval_box<I, N>& b, std::size_t dim,
                                                            double point) {
    auto left = b, right = b;
    left.x[dim] = I(lower(b.x[dim]), point);
    right.x[dim] = I(point, upper(b.x[dim]));
    return {left, right};
}

/// The 2^N corners, corner k taking the upper bound of component i when bit i of k is set.
template <Interval I, std::size_t N>
std::array<std::array<double, N>, (std::size_t{1} << N)> corners(const interval_box<I, N>& b) {
    std::array<std::array<double, N>, (std::size_t{1} << N)> c{};
    for (std::size_t k = 0; k < c.size(); ++k)
        for (std::size_t i = 0; i < N; ++i) c[k][i] = (k >> i) & 1u ? upper(b.x[i]) : lower(b.x[i]);
    return c;
}

}  // namespace certipose
