// certipose/bisection/largest_first.hpp — the paper's bisector: split the widest component
// (§5.2.2, "largest-first"), at `ratio` of its width.
//
// Only components at least as wide as their precision compete (bisection/precision.hpp); when
// none does, `choose` returns nothing and the paver classifies the box BOUNDARY (Algorithm 1
// lines 16–17). Widths are compared as they are, not divided by the precision, as in the paper
// and IBEX's LargestFirst. Stateless: the choice depends on the box alone, so the paver builds
// the same tree whatever its buffer order. Models `Bisector`.
#pragma once

#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "certipose/bisection/concept.hpp"
#include "certipose/bisection/precision.hpp"
#include "certipose/interval/operations.hpp"

namespace certipose {

class largest_first {
public:
    /// Same precision ε for every dimension; split at `ratio` (default: the midpoint).
    explicit largest_first(double precision, double ratio = default_split_ratio)
        : eps_(precision), ratio_(detail::checked_split_ratio(ratio)) {}
    /// One precision per dimension.
    explicit largest_first(std::vector<double> precision, double ratio = default_split_ratio)
        : eps_(std::move(precision)), ratio_(detail::checked_split_ratio(ratio)) {}

    /// The widest splittable component (lowest index on ties) and its split point, or nothing
    /// when no component is at least its precision wide.
    template <class Box>
    std::optional<split> choose(const Box& box) const {
        eps_.check_dimension(box.size());
        std::optional<split> best;
        double best_width = -1.0;
        for (std::size_t i = 0; i < box.size(); ++i) {
            const double w = detail::bisection_width(box[i]);
            if (!(w > best_width)) continue;
            if (const auto p = detail::eligible_split_point(box[i], eps_(i), ratio_)) {
                best = split{i, *p};
                best_width = w;
            }
        }
        return best;
    }

    const bisection_precision& precision() const noexcept { return eps_; }
    double ratio() const noexcept { return ratio_; }

private:
    bisection_precision eps_;
    double ratio_;
};

}  // namespace certipose
