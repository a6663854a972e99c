// certipose/solver/detail/box_certifier.hpp — "is every pose of this 6D box valid for this
// facet?", answered with the solver's own proofs (pose_solver::certify and what builds on it).
//
// The position part must be certified by the constraint set (its test, or its complement
// contraction leaving nothing), then by the occlusion policy (VISIBLE, or no shadow of a
// possible blocker reaching the box), and the whole 6D box by certify_fov. `false` means "not
// proven", never "proven invalid". The last position box and its answer are kept, so that
// growing an orientation face costs one field-of-view evaluation.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "certipose/constraints/concept.hpp"
#include "certipose/occlusion/concept.hpp"
#include "certipose/occlusion/fixed_occluders.hpp"
#include "certipose/orientation/certify.hpp"
#include "certipose/pose/placement_tolerance.hpp"
#include "certipose/pose/pose_box.hpp"
#include "certipose/solver/detail/carving.hpp"

namespace certipose {

/// What the solver's proofs need of a placement tolerance (pose/placement_tolerance.hpp): the
/// tolerance with its datum, and the occluders that do not move with the part.
struct placement_scene {
    resolved_placement tolerance;
    fixed_occluders fixed;
};

}  // namespace certipose

namespace certipose::detail {

/// Constraints 1–4 over a position box by `set`: satisfied when its test says so or its
/// complement contraction leaves nothing of the box; violated when its test says so.
template <class Set, Interval I>
verdict prove_position_set(Set& set, const position_box<I>& p) {
    if (is_empty(p)) return verdict::violated;
    const verdict v = set.test(p);
    if (v != verdict::undecided) return v;
    if constexpr (ComplementContractingSet<Set, I>) {
        position_box<I> failing = p;
        set.contract_complement(failing);
        if (is_empty(failing)) return verdict::satisfied;
    }
    return verdict::undecided;
}

/// Constraint 6 over a position box: the occlusion policy says VISIBLE, or (a shadowing policy)
/// no shadow of a triangle that may block reaches the box. `shadows` caches prepared shadows
/// (shadow_cache, keyed by facet and triangle).
template <class Occlusion, Interval I>
bool prove_visible(const Occlusion& occlusion, const position_box<I>& p, std::size_t facet,
                   shadow_cache<I>& shadows) {
    visibility seen;
    if constexpr (EffortAwareOcclusionPolicy<Occlusion, I>)
        seen = occlusion.classify(p, facet, occlusion_effort::visible_only);
    else
        seen = occlusion.classify(p, facet);
    if (seen == visibility::visible) return true;
    if constexpr (ShadowingOcclusionPolicy<Occlusion, I>) {
        if (seen == visibility::partial) {
            auto outside = [&](std::size_t triangle) {
                const auto& s = shadows.get(facet, triangle, [&] { return occlusion.shadow(facet, triangle); });
                const rounding_guard<I> rounding;
                position_box<I> t = p;
                contract_shadow(t, s);
                return is_empty(t);  // stop at the first shadow that may reach the box
            };
            return occlusion.blockers(p, facet, outside);
        }
    }
    return false;
}

/// With a placement tolerance (`placement` not null), every proof is made for every placement
/// it admits: constraints 1–4 and the part's occlusion over camera_reach([p]) (the camera
/// positions in the part frame), the field of view over [p] grown by the facet's reach, and the
/// fixed occluders by sight_region_clear (pose/placement_tolerance.hpp explains why).
template <class Set, class Occlusion, Interval I>
class box_certifier {
public:
    box_certifier(Set set, const Occlusion& occlusion, std::size_t facet_index, const facet& f, fov_frustum<I> frustum,
                  const placement_scene* placement = nullptr)
        : set_(std::move(set)), occlusion_(&occlusion), facet_index_(facet_index), facet_(f), frustum_(std::move(frustum)),
          placement_(placement) {
        if (placement_) facet_reach_ = facet_reach<I>(f.v, placement_->tolerance);
    }

    /// Constraints 1–4 and 6 over the whole position box.
    bool position(const position_box<I>& p) {
        if (last_ && *last_ == p) return last_ok_;
        remember(p, prove_position(p));
        return last_ok_;
    }

    /// Every constraint over the whole 6D box. Cheapest proof first: the constraint set, the
    /// field of view, and only then occlusion (a tree walk, ~20× a field-of-view evaluation),
    /// which most failing boxes of a growth search then never pay for.
    bool operator()(const pose_box<I>& b) {
        if (is_empty(b)) return false;
        const position_box<I>& p = b.position;
        if (last_ && *last_ == p) return last_ok_ && fov(p, b.orientation);
        if (prove_position_set(set_, in_part_frame(p)) != verdict::satisfied) {
            remember(p, false);
            return false;
        }
        if (!fov(p, b.orientation)) return false;  // occlusion over p not known yet: nothing kept
        remember(p, prove_sight(p));
        return last_ok_;
    }

    /// Constraint 5 over position × orientation.
    bool fov(const position_box<I>& p, const orientation_box<I>& o) {
        ++certifications;
        if (!(last_ && *last_ == p)) return certify_fov(fov_box(p), o, facet_, frustum_) == verdict::satisfied;
        if (!prepared_) prepared_.emplace(fov_box(p), facet_);
        return certify_fov(*prepared_, o, frustum_) == verdict::satisfied;
    }

    std::size_t certifications = 0;  ///< field-of-view evaluations

private:
    void remember(const position_box<I>& p, bool ok) {
        last_ = p;
        last_ok_ = ok;
        prepared_.reset();
    }
    // The camera positions the proofs of constraints 1–4 and 6 must cover.
    position_box<I> in_part_frame(const position_box<I>& p) const {
        return placement_ ? camera_reach(p, placement_->tolerance) : p;
    }
    // The positions the field-of-view proof must cover (the facet's motion moved onto the camera).
    position_box<I> fov_box(const position_box<I>& p) const { return placement_ ? grown(p, facet_reach_) : p; }
    bool prove_sight(const position_box<I>& p) {
        if (!prove_visible(*occlusion_, in_part_frame(p), facet_index_, cache_)) return false;
        return !placement_ || sight_region_clear(p, facet_.v, facet_.normal, facet_reach_, placement_->fixed);
    }
    bool prove_position(const position_box<I>& p) {
        return prove_position_set(set_, in_part_frame(p)) == verdict::satisfied && prove_sight(p);
    }

    Set set_;
    const Occlusion* occlusion_;
    std::size_t facet_index_;
    facet facet_;
    fov_frustum<I> frustum_;
    const placement_scene* placement_ = nullptr;
    std::array<double, 3> facet_reach_{};
    std::optional<position_box<I>> last_{};
    bool last_ok_ = false;
    std::optional<fov_position<I>> prepared_{};
    shadow_cache<I> cache_{};
};

}  // namespace certipose::detail

namespace certipose {
/// The certifier of whole 6D boxes with the solver's proofs (pose_solver::certifier).
template <class Set, class Occlusion, Interval I>
using pose_certifier = detail::box_certifier<Set, Occlusion, I>;
}  // namespace certipose
