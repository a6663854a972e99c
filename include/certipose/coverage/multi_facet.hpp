// certipose/coverage/multi_facet.hpp — multi-facet inspection spaces (the paper's future work):
// for a set S of facets, pose boxes from every pose of which all of S are inspected.
//
// A pose that lies in a VALID box of facet a and in a VALID box of facet b inspects both, so the
// intersections of the facets' VALID boxes, taken pairwise and then against the next facet's,
// are certified for all of S without a new proof. The Euler angles φ and β are 2π-periodic: a box
// near φ = π meets another near φ = −π in the poses they share modulo 2π, so each box is also
// met shifted by ±2π in φ and β; the shifted bounds are rounded inward, never adding a pose the
// original box does not hold.
//
// `intersect_spaces(spaces)` does this for any per-facet box lists (e.g. read from a whole-part
// run's boxes.jsonl); `multi_facet_space(solver, facets, options)` solves each facet first.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

#include "certipose/error.hpp"
#include "certipose/pose/pose_box.hpp"
#include "certipose/solver/pose_solver.hpp"

namespace certipose {

/// Limits of an intersection: pieces thinner than `min_width` (metres) in some position component
/// are dropped (they carry no installation tolerance), and at most `max_boxes` are kept (the
/// largest by position volume).
struct intersection_options {
    double min_width = 0.0;
    std::size_t max_boxes = 100000;
};

namespace detail {

/// `box` with φ and β moved by `turns_phi`, `turns_beta` whole turns (−1, 0 or 1), the shifted
/// bounds rounded inward: 2π is not a double, so each bound moves by an enclosure of 2π with the
/// outward-rounded arithmetic of `I`, and the inner ends are kept (lo' ≥ lo + 2π, hi' ≤ hi + 2π).
template <Interval I>
pose_box<I> shifted(const pose_box<I>& box, int turns_phi, int turns_beta) {
    pose_box<I> out = box;
    const rounding_guard<I> rounding;
    const double pi_lo = std::numbers::pi;  // the double below π
    const I two_pi = I(2.0 * pi_lo, std::nextafter(2.0 * pi_lo, 8.0));
    const auto move = [&](const I& x, int turns) {
        if (turns == 0) return x;
        const I by = static_cast<double>(turns) * two_pi;
        const double lo = upper(I(lower(x)) + by), hi = lower(I(upper(x)) + by);
        return lo <= hi ? I(lo, hi) : interval_traits<I>::empty();
    };
    out.orientation.x[0] = move(box.orientation[0], turns_phi);
    out.orientation.x[2] = move(box.orientation[2], turns_beta);
    return out;
}

/// Position widths all at least `min_width` (orientation widths are not limited).
template <Interval I>
bool thick_enough(const pose_box<I>& b, double min_width) {
    if (is_empty(b)) return false;
    for (std::size_t k = 0; k < 3; ++k)
        if (!(width(b.position[k]) >= min_width)) return false;
    return true;
}

}  // namespace detail

/// The poses (as boxes) common to a box of `a` and a box of `b`, φ and β taken modulo 2π.
template <Interval I>
std::vector<pose_box<I>> intersect_spaces(const std::vector<pose_box<I>>& a, const std::vector<pose_box<I>>& b,
                                          const intersection_options& options = {}) {
    std::vector<pose_box<I>> out;
    for (const auto& x : a)
        for (const auto& y : b) {
            if (is_empty(intersect(x.position, y.position))) continue;
            for (const int sp : {0, 1, -1})
                for (const int sb : {0, 1, -1}) {
                    const pose_box<I> ys = detail::shifted(y, sp, sb);
                    pose_box<I> r{intersect(x.position, ys.position), intersect(x.orientation, ys.orientation)};
                    if (detail::thick_enough(r, options.min_width)) out.push_back(r);
                }
        }
    if (out.size() > options.max_boxes) {
        std::partial_sort(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(options.max_boxes), out.end(),
                          [](const auto& p, const auto& q) { return volume(p.position) > volume(q.position); });
        out.resize(options.max_boxes);
    }
    return out;
}

/// The poses common to every facet's boxes: `spaces[k]` are the VALID boxes of facet k.
template <Interval I>
std::vector<pose_box<I>> intersect_spaces(const std::vector<std::vector<pose_box<I>>>& spaces,
                                          const intersection_options& options = {}) {
    if (spaces.empty()) throw invalid_argument("facets", "intersect_spaces: give at least one facet's boxes");
    std::vector<pose_box<I>> acc = spaces.front();
    for (std::size_t k = 1; k < spaces.size() && !acc.empty(); ++k) acc = intersect_spaces(acc, spaces[k], options);
    return acc;
}

/// The multi-facet inspection space of `facets`: each facet solved with `options`, then its
/// VALID boxes intersected. Every returned box inspects every facet of `facets` from every pose
/// in it. Throws out_of_range for a facet index beyond the part, invalid_argument for none.
template <class Policies>
std::vector<pose_box<typename pose_solver<Policies>::interval_type>> multi_facet_space(
    const pose_solver<Policies>& solver, const std::vector<std::size_t>& facets, const solve_options& options = {},
    const intersection_options& limits = {}) {
    using I = typename pose_solver<Policies>::interval_type;
    if (facets.empty()) throw invalid_argument("facets", "multi_facet_space: give at least one facet");
    std::vector<std::vector<pose_box<I>>> spaces;
    for (const std::size_t f : facets) {
        const auto r = solver.solve(f, options);
        std::vector<pose_box<I>> valid;
        for (const auto& b : r.boxes)
            if (b.cls == box_class::valid) valid.push_back(b.box);
        if (valid.empty()) return {};
        spaces.push_back(std::move(valid));
    }
    return intersect_spaces(spaces, limits);
}

}  // namespace certipose
