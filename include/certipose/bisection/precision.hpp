// certipose/bisection/precision.hpp — the per-dimension precision and the split ratio shared by
// the bisectors (largest_first, round_robin).
//
// A dimension is split only while its width is at least its precision (the paper's ε,
// Algorithm 1 line 16); a box whose every dimension is narrower is left whole and the paver
// classifies it BOUNDARY. The precision is one value for every dimension or one per dimension
// (position in metres next to orientation in radians needs two). The split ratio says where a
// chosen component is cut: at lower + ratio · width.
//
// Default ratio 0.5, the midpoint — the paper's choice (§5.2.2). IBEX defaults to 0.45 so
// that split points avoid symmetric singular points: a system solver certifies an isolated
// solution by proving it lies in a box's interior, and a solution at the centre of a symmetric
// domain (x = 0 in [−10, 10]) would sit on a split face at every level. A paver proves
// inclusion of whole boxes, not isolated solutions, so that reason does not arise; midpoint
// splitting instead keeps every bound a dyadic fraction of the initial box — exact in binary,
// identical whatever the traversal order, and aligned across pavings of the same initial box,
// so boxes from two pavings (e.g. two facets) are nested or disjoint and intersect exactly.
// A user whose constraints do have a singularity on a symmetric split face passes 0.45.
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/interval/operations.hpp"

namespace certipose {

/// The paper's midpoint (see the header comment for why not IBEX's 0.45).
inline constexpr double default_split_ratio = 0.5;

namespace detail {

/// Throws unless 0 < ratio < 1 (a ratio of 0 or 1 would produce an empty half and loop).
inline double checked_split_ratio(double ratio) {
    if (!(ratio > 0.0 && ratio < 1.0))
        throw invalid_argument("ratio", "bisector: split ratio must lie strictly between 0 and 1, got " +
                                            format_double(ratio));
    return ratio;
}

}  // namespace detail

/// One precision for every dimension, or one per dimension. Each must be positive (+∞ means
/// "never split this dimension"); NaN, zero and negative values are rejected.
class bisection_precision {
public:
    /// The same precision for every dimension.
    explicit bisection_precision(double uniform) : eps_{check(uniform, 0)} {}
    /// One precision per dimension; the box given to the bisector must have as many.
    explicit bisection_precision(std::vector<double> per_dimension) : eps_(std::move(per_dimension)) {
        if (eps_.empty()) throw invalid_argument("precision", "bisector: the precision vector is empty");
        for (std::size_t i = 0; i < eps_.size(); ++i) check(eps_[i], i);
    }

    /// Precision of dimension `dim` (the uniform value when only one was given).
    double operator()(std::size_t dim) const noexcept { return eps_.size() == 1 ? eps_[0] : eps_[dim]; }
    bool uniform() const noexcept { return eps_.size() == 1; }
    const std::vector<double>& values() const noexcept { return eps_; }

    /// Throws when per-dimension precisions do not match a box of `n` dimensions.
    void check_dimension(std::size_t n) const {
        if (eps_.size() != 1 && eps_.size() != n)
            throw invalid_argument("precision", "bisector: " + std::to_string(eps_.size()) +
                                                    " precisions given for a box of " + std::to_string(n) +
                                                    " dimensions");
    }

private:
    static double check(double e, std::size_t i) {
        if (!(e > 0.0))
            throw invalid_argument("precision", "bisector: precision of dimension " + std::to_string(i) +
                                                    " must be positive, got " + detail::format_double(e));
        return e;
    }
    std::vector<double> eps_;
};

namespace detail {

/// Width as bisectors compare it: u − l in the current rounding mode. The precision and the
/// largest-first choice are heuristics, so a half-ulp error is harmless, and this avoids
/// `width`'s nextafter on the paver's hot path. NaN (never ≥ ε) for an empty interval.
template <Interval I>
double bisection_width(const I& c) {
    return upper(c) - lower(c);
}

/// The split point of component `c` when it may be split: non-empty, at least `precision`
/// wide, and with a representable point strictly inside (otherwise a half would equal the
/// whole and the paver would never finish). Nothing otherwise.
template <Interval I>
std::optional<double> eligible_split_point(const I& c, double precision, double ratio) {
    if (is_empty(c) || !(bisection_width(c) >= precision)) return std::nullopt;
    const double p = split_point(c, ratio);
    if (!(lower(c) < p && p < upper(c))) return std::nullopt;
    return p;
}

/// What the built-in bisectors share: their precision and split ratio, validated once. A
/// bisector derives from it and inherits the constructors (`using bisector_base::bisector_base;`).
class bisector_base {
public:
    /// Same precision ε for every dimension; split at `ratio` (default: the midpoint).
    explicit bisector_base(double precision, double ratio = default_split_ratio)
        : eps_(precision), ratio_(checked_split_ratio(ratio)) {}
    /// One precision per dimension.
    explicit bisector_base(std::vector<double> precision, double ratio = default_split_ratio)
        : eps_(std::move(precision)), ratio_(checked_split_ratio(ratio)) {}

    const bisection_precision& precision() const noexcept { return eps_; }
    double ratio() const noexcept { return ratio_; }

protected:
    /// Where component `c` (dimension `dim`) would be split, if it may be.
    template <Interval I>
    std::optional<double> split_point_of(const I& c, std::size_t dim) const {
        return eligible_split_point(c, eps_(dim), ratio_);
    }

    bisection_precision eps_;
    double ratio_;
};

}  // namespace detail

}  // namespace certipose
