// certipose/pose/pose_box.hpp — position boxes [x]×[y]×[z], orientation boxes [φ]×[γ]×[β]
// (ZXZ Euler angles, docs/conventions.md) and the 6D pose box the solver returns (paper §6.1).
#pragma once

#include "certipose/pose/interval_box.hpp"

namespace certipose {

/// [x]×[y]×[z] in metres.
template <Interval I>
using position_box = interval_box<I, 3>;

/// [φ]×[γ]×[β] in radians, R = Rz(φ)·Rx(γ)·Rz(β).
template <Interval I>
using orientation_box = interval_box<I, 3>;

/// A 6D pose box: every camera position in `position` combined with every orientation in
/// `orientation` (paper Eq. 26 with Eq. 24).
template <Interval I>
struct pose_box {
    position_box<I> position;
    orientation_box<I> orientation;

    /// The same box as one 6D interval vector (x, y, z, φ, γ, β), e.g. for a 6D paver.
    interval_box<I, 6> as_6d() const {
        interval_box<I, 6> b;
        for (std::size_t i = 0; i < 3; ++i) b[i] = position[i], b[i + 3] = orientation[i];
        return b;
    }
    static pose_box from_6d(const interval_box<I, 6>& b) {
        pose_box p;
        for (std::size_t i = 0; i < 3; ++i) p.position[i] = b[i], p.orientation[i] = b[i + 3];
        return p;
    }
    friend bool operator==(const pose_box&, const pose_box&) = default;
};

template <Interval I>
bool is_empty(const pose_box<I>& p) {
    return is_empty(p.position) || is_empty(p.orientation);
}
template <Interval I>
double volume(const pose_box<I>& p) {
    return volume(p.position) * volume(p.orientation);
}

}  // namespace certipose
