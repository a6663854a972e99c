// certipose/bisection/round_robin.hpp — split the dimensions in turn, at `ratio` of the width.
//
// Round-robin (IBEX's RoundRobin) splits dimension k+1 of a box made by splitting dimension k,
// skipping dimensions narrower than their precision (bisection/precision.hpp); when none is
// left, `choose` returns nothing and the paver classifies the box BOUNDARY. It is cheaper per
// choice than largest-first and insensitive to a dimension's scale, but splits dimensions
// regardless of how wide they are.
//
// The turn is a property of the box's place in the tree, not of the bisector: the paver calls
// `choose(box, context)` with the dimension that created the box, so depth-first and
// breadth-first pavings are identical and the bisector stays stateless there. Used outside a
// paver, `choose(box)` continues after the dimension this object split last. Models `Bisector`
// and `ContextualBisector`.
#pragma once

#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "certipose/bisection/concept.hpp"
#include "certipose/bisection/precision.hpp"
#include "certipose/interval/operations.hpp"

namespace certipose {

class round_robin : public detail::bisector_base {
public:
    using bisector_base::bisector_base;  // (precision or one per dimension, ratio = midpoint)

    /// The first splittable dimension after the parent's (dimension 0 first at the root).
    template <class Box>
    std::optional<split> choose(const Box& box, const bisection_context& context) const {
        return next_after(box, context.parent_dimension);
    }

    /// Stand-alone use: the first splittable dimension after the one this object chose last.
    template <class Box>
    std::optional<split> choose(const Box& box) {
        auto s = next_after(box, last_);
        if (s) last_ = s->dimension;
        return s;
    }

private:
    template <class Box>
    std::optional<split> next_after(const Box& box, std::optional<std::size_t> previous) const {
        eps_.check_dimension(box.size());
        const std::size_t n = box.size();
        if (n == 0) return std::nullopt;
        const std::size_t start = previous ? (*previous + 1) % n : 0;
        for (std::size_t k = 0; k < n; ++k) {
            const std::size_t i = (start + k) % n;
            if (const auto p = split_point_of(box[i], i)) return split{i, *p};
        }
        return std::nullopt;
    }

    std::optional<std::size_t> last_;
};

}  // namespace certipose
