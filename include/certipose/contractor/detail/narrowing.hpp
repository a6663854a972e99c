// certipose/contractor/detail/narrowing.hpp — how much a contraction narrowed an interval,
// the quantity HC4's propagation and fixpoint loops compare with their ratio.
//
// Not for users. Relative narrowing (IBEX's ratiodelta): (w_before − w_after) / w_before; an
// unbounded interval that gained a finite bound counts as fully narrowed (1), a degenerate one
// cannot narrow (0), an emptied one narrowed fully (1).
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>

#include "certipose/interval/concept.hpp"
#include "certipose/interval/operations.hpp"
#include "certipose/pose/interval_box.hpp"

namespace certipose::contractor_detail {

template <class I>
double narrowing(const I& before, const I& after) {
    if (is_empty(after)) return is_empty(before) ? 0.0 : 1.0;
    if (is_empty(before)) return 0.0;
    const double lb = lower(before), ub = upper(before), la = lower(after), ua = upper(after);
    if (lb == la && ub == ua) return 0.0;
    const double w0 = ub - lb, w1 = ua - la;
    if (!std::isfinite(w0)) {
        const bool gained = (std::isinf(lb) && !std::isinf(la)) || (std::isinf(ub) && !std::isinf(ua));
        return gained ? 1.0 : 0.0;
    }
    if (w0 <= 0.0) return 0.0;
    const double r = (w0 - w1) / w0;
    return r > 0.0 ? r : 0.0;
}

/// Largest relative narrowing over the components.
template <class I, std::size_t N>
double max_narrowing(const interval_box<I, N>& before, const interval_box<I, N>& after) {
    double m = 0.0;
    for (std::size_t i = 0; i < N; ++i) {
        const double r = narrowing(before[i], after[i]);
        if (r > m) m = r;
    }
    return m;
}

}  // namespace certipose::contractor_detail
