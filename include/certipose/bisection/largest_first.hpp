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

class largest_first : public detail::bisector_base {
public:
    using bisector_base::bisector_base;  // (precision or one per dimension, ratio = midpoint)

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
            if (const auto p = split_point_of(box[i], i)) {
                best = split{i, *p};
                best_width = w;
            }
        }
        return best;
    }
};

}  // namespace certipose
