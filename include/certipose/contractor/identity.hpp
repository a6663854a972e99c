// certipose/contractor/identity.hpp — the contractor that does nothing.
//
// The neutral element of composition (IBEX's CtcIdentity): a policy slot that wants no
// contraction (e.g. a paver driven by its inner test and bisection only) plugs this in.
// It computes nothing, so it needs no rounding guard.
#pragma once

#include <cstddef>

#include "certipose/interval/concept.hpp"
#include "certipose/pose/interval_box.hpp"

namespace certipose {

struct identity {
    using certipose_contractor = void;
    template <Interval I, std::size_t N>
    void contract(interval_box<I, N>&) const noexcept {}
};

}  // namespace certipose
