// certipose/orientation/paving_orientation.hpp — an OrientationPolicy that paves the whole
// orientation space: every certified orientation box of a position box, not just one around
// the nominal aim.
//
// The paper's Algorithm 1 paver runs over [φ]×[γ]×[β] = [−π, π]×[0, π]×[−π, π] (every
// rotation) with `certify_fov` as its inner test: a box it satisfies is VALID, a box it
// violates is discarded (no pose of it sees the whole facet), and an undecided box is bisected
// largest-first down to ε_o and then dropped (BOUNDARY is not certified). The answer is the
// union of all VALID boxes at resolution ε_o — the whole certified aiming freedom, where the
// default `paper_orientation` returns one box. It exists to show that the orientation policy
// really swaps, and for users who want every aim; it costs far more certifications (hundreds
// to thousands per position box), so `max_boxes` bounds it (reached: the VALID boxes found so
// far are returned, all still certified). Near γ = 0 or π the paving is sound like everywhere,
// and the pole bound of `certify_fov` lets whole-φ slabs certify there.
#pragma once

#include <cmath>
#include <cstddef>
#include <numbers>
#include <string>
#include <utility>

#include "certipose/bisection/largest_first.hpp"
#include "certipose/camera/camera_model.hpp"
#include "certipose/contractor/identity.hpp"
#include "certipose/error.hpp"
#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/orientation/certify.hpp"
#include "certipose/orientation/concept.hpp"
#include "certipose/paver/paver.hpp"
#include "certipose/pose/pose_box.hpp"

namespace certipose {

struct paving_orientation_options {
    /// Paver budget per position box (boxes processed, i.e. `certify_fov` evaluations).
    std::size_t max_boxes = 200'000;
};

class paving_orientation {
public:
    paving_orientation() = default;
    explicit paving_orientation(paving_orientation_options options) : options_(options) {
        if (options_.max_boxes == 0)
            throw invalid_argument("max_boxes", "paving_orientation: max_boxes must be at least 1");
    }

    const paving_orientation_options& options() const noexcept { return options_; }

    /// Every VALID box of a paving of the orientation space at resolution ε_o (see the header
    /// comment). Throws invalid_argument("orientation_eps") unless ε_o is positive and finite,
    /// and invalid_argument("position_box") for a non-finite box.
    template <Interval I, CameraModel C>
    orientation_result<I> orient(const position_box<I>& position, const facet& f, const C& camera,
                                 double orientation_eps) const {
        orientation_result<I> out;
        if (!detail::orientation::checked_orient_arguments("paving_orientation", position, f, orientation_eps)) return out;
        constexpr double pi = std::numbers::pi;
        const orientation_box<I> all = orientation_box<I>::from_bounds({{{-pi, pi}, {0.0, pi}, {-pi, pi}}});
        paver_options po;
        po.max_boxes = options_.max_boxes;
        auto paving = pave(all, identity{}, fov_orientation_test<I>{position, f, fov_frustum<I>(camera)},
                           largest_first(orientation_eps), po);
        out.boxes = std::move(paving.valid);
        out.certifications = paving.stats.inner_tests;
        return out;
    }

private:
    paving_orientation_options options_{};
};

}  // namespace certipose
