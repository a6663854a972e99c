// certipose/solver/detail/shadow_walk.hpp — the position stage's walks for shadows (occlusion
// cuts): which triangles may block a sight line from a box, their shadows, and what of a box the
// shadows may reach. What a walk finds is kept in the box's `sight` and inherited by the boxes
// inside it, so one walk serves a whole subtree of the paving.
#pragma once

#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

#include "certipose/interval/concept.hpp"
#include "certipose/pose/pose_box.hpp"
#include "certipose/solver/detail/carving.hpp"

namespace certipose::detail {

/// What is known of the sight lines from a position box.
template <Interval I>
struct sight {
    bool visible = false;  ///< occlusion: VISIBLE from the whole box
    /// The shadows of every triangle that may block a sight line from the box (found for an
    /// ancestor: one tree walk serves all the boxes below it); null until needed. The set owns
    /// the cache it points into: it may outlive the walker that found it (refinement).
    std::shared_ptr<const shadow_set<I>> shadows{};
    /// After a walk for shadows gave up (too many possible blockers, or not strictly in front of
    /// the facet): the largest width of the box it walked, or 1.25 times that for the whole box
    /// of a carving, whose pieces are often much thinner; 0: none did. The walk is asked again
    /// only for boxes at most half this wide: one just a little smaller would almost surely
    /// give up too, and each failed walk costs as much as a successful one.
    double walk_failed_width = 0;
    friend bool operator==(const sight&, const sight&) = default;
};

/// Walks the occlusion policy's tree for one facet (a ShadowingOcclusionPolicy: `walk` is only
/// instantiated for one) and reasons about the shadows found.
template <class Occlusion, Interval I>
class shadow_walker {
public:
    using box = position_box<I>;

    /// `cache`: prepared shadows (by facet and triangle), shared by the walkers of one facet's passes (a copy
    /// of a walker shares it too: one facet's paving runs on one thread); `walks` counts walks.
    shadow_walker(const Occlusion* occlusion, std::size_t facet, std::shared_ptr<shadow_cache<I>> cache,
                  std::size_t* walks)
        : occlusion_(occlusion), facet_(facet), cache_(std::move(cache)), walks_(walks) {}

    /// Is a walk for b's shadows worth it? Not within a box whose walk gave up unless b is at
    /// most half of sight::walk_failed_width wide.
    static bool may_walk(const box& b, const sight<I>& s) {
        return !s.visible && !s.shadows && (s.walk_failed_width == 0 || max_width(b) <= s.walk_failed_width / 2);
    }

    /// One walk of the tree for b: the shadows of the triangles that may block a sight line from
    /// b go to s.shadows (those that may reach b; s.visible when none does), `reach` receives
    /// the hull of what they reach of b and `covered` whether one covers all of b (asked only
    /// with `need_covered`). False when the walk gave up (s.walk_failed_width records it).
    bool walk(const box& b, sight<I>& s, bool need_covered, box& reach, bool& covered) {
        // The walk only names the triangles; their shadows are contracted after it, so a walk
        // that gives up costs no contraction.
        found_.clear();
        auto note = [&](std::size_t triangle) {
            found_.push_back(triangle);
            return true;
        };
        ++*walks_;
        if (!occlusion_->blockers(b, facet_, note)) {
            s.walk_failed_width = max_width(b);
            return false;
        }
        named_.clear();
        for (const std::size_t triangle : found_)
            named_.push_back(&cache_->get(facet_, triangle, [&] { return occlusion_->shadow(facet_, triangle); }));
        auto found = std::make_shared<shadow_set<I>>();
        found->storage = cache_;
        reach = reach_in(b, named_, found->list, covered, need_covered);
        if (found->list.empty()) s.visible = true;
        else s.shadows = std::move(found);
        return true;
    }

    /// Calls visit(shadow, part) for each shadow of `list` that reaches b, with `part` what it
    /// reaches of b (b contracted to the shadow), until visit returns false.
    template <class Visit>
    static void for_each_reaching(const box& b, const shadow_list<I>& list, Visit&& visit) {
        const rounding_guard<I> rounding;
        for (const auto* sh : list) {
            box part = b;
            contract_shadow(part, *sh);
            if (!is_empty(part) && !visit(sh, part)) return;
        }
    }

    /// The hull of the parts of b that the shadows of `list` may reach (empty: none does); the
    /// shadows that may reach b are appended to `kept`, and `covered` says whether one reaches
    /// all of b (asked only with `need_covered`: without, it may stay false once the hull is b).
    static box reach_in(const box& b, const shadow_list<I>& list, shadow_list<I>& kept, bool& covered,
                        bool need_covered) {
        box reach = box::empty();
        const rounding_guard<I> rounding;
        for (const auto* sh : list) {
            if (!(need_covered && !covered) && reach == b) {
                // The hull is all of b already: what is left to ask of a shadow is whether it
                // may reach b (the boxes inside b contract against it again). A box with many
                // possible blockers reaches this after a few, and contracting every other
                // shadow would cost as much as a fresh walk.
                if (shadow_may_reach(b, *sh)) kept.push_back(sh);
                continue;
            }
            box part = b;
            contract_shadow(part, *sh);
            if (is_empty(part)) continue;
            kept.push_back(sh);
            reach = hull(reach, part);
            covered = covered || part == b;
        }
        return reach;
    }

    /// The hull of the parts of b that the shadows of `s` may reach (empty: b sees the facet);
    /// `covered`: one of them reaches all of b. Drops the shadows that miss b when that leaves
    /// at most half of them: the boxes inside b then contract against fewer (the list is
    /// shared with other boxes, so it is copied).
    static box shadow_hull(const box& b, sight<I>& s, bool& covered, bool need_covered) {
        shadow_list<I> kept;
        const box reach = reach_in(b, s.shadows->list, kept, covered, need_covered);
        if (!kept.empty() && 2 * kept.size() <= s.shadows->list.size())
            s.shadows = std::make_shared<const shadow_set<I>>(shadow_set<I>{s.shadows->storage, std::move(kept)});
        return reach;
    }

    /// No point of q lies in a shadow of the list.
    static bool outside(const shadow_list<I>& list, const box& q) {
        bool none = true;
        for_each_reaching(q, list, [&](const prepared_shadow<I>*, const box&) { return none = false; });
        return none;
    }

private:
    const Occlusion* occlusion_;
    std::size_t facet_;
    std::shared_ptr<shadow_cache<I>> cache_;
    std::size_t* walks_;
    std::vector<std::size_t> found_{};  // the triangles one walk names, and their shadows
    shadow_list<I> named_{};            // (kept: no allocation per walk)
};

}  // namespace certipose::detail
