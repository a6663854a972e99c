// certipose/coverage/candidates.hpp — the candidate camera boxes of a deployment plan: the
// largest VALID boxes of each facet of a whole-part run, kept while the run streams them.
//
// A whole part yields millions of VALID boxes and C(B) costs about a millisecond each, so a
// plan does not inspect them all: per facet it keeps the `per_facet` boxes of largest position
// volume (ties: orientation volume), the ones with the most installation tolerance. Every
// candidate is VALID for its own facet (the run certified it), whatever the inspector proves.
// `candidate_pool` is a PartSink (part/part_solver.hpp) for a one-shot run, and takes boxes read
// back from boxes.jsonl through `add`.
//
// A whole VALID box is a poor camera: it must certify a facet for every orientation it holds,
// and its orientation intervals are up to ε_o wide, so it certifies little beyond its own facet.
// `around_centre(box, tolerance)` cuts it down to the installation tolerance the engineer needs
// (say ±5 mm, ±0.02 rad) around its centre: a sub-box, so still VALID for its facet, and one from
// all of which more facets are inspected — on the sample part hundreds are certified instead of one.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <map>
#include <utility>
#include <vector>

#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"
#include "certipose/part/part_solver.hpp"
#include "certipose/pose/pose_box.hpp"

namespace certipose {

template <Interval I>
struct candidate_box {
    std::size_t facet = 0;  ///< the facet the box is VALID for
    pose_box<I> box;
};

/// The part of `box` within `half_widths` (x, y, z in metres; φ, γ, β in radians) of its centre.
/// Always a sub-box of `box` (the bounds are intersected with the box's own), so it is VALID for
/// what `box` is VALID for. Throws invalid_argument for a negative or non-finite half-width.
template <Interval I>
pose_box<I> around_centre(const pose_box<I>& box, const std::array<double, 6>& half_widths) {
    for (double h : half_widths)
        if (!(h >= 0.0) || !std::isfinite(h))
            throw invalid_argument("tolerance", "around_centre: half-widths must be >= 0 and finite, got " +
                                                    detail::format_double(h));
    pose_box<I> out = box;
    for (std::size_t k = 0; k < 6; ++k) {
        const I& x = k < 3 ? box.position[k] : box.orientation[k - 3];
        const double c = std::clamp(lower(x) + (upper(x) - lower(x)) / 2, lower(x), upper(x));
        const I cut = intersect(x, I(std::max(lower(x), c - half_widths[k]), std::min(upper(x), c + half_widths[k])));
        (k < 3 ? out.position.x[k] : out.orientation.x[k - 3]) = cut;
    }
    return out;
}

template <Interval I>
class candidate_pool {
public:
    explicit candidate_pool(std::size_t per_facet = 1) : per_facet_(per_facet) {
        if (per_facet == 0) throw invalid_argument("per_facet", "candidate_pool: keep at least one box per facet");
    }
    // The copies and moves forget the last facet's list (it points into a map).
    candidate_pool(const candidate_pool& o) : per_facet_(o.per_facet_), by_facet_(o.by_facet_) {}
    candidate_pool(candidate_pool&& o) noexcept : per_facet_(o.per_facet_), by_facet_(std::move(o.by_facet_)) { o.last_ = nullptr; }
    candidate_pool& operator=(const candidate_pool& o) {
        if (this != &o) per_facet_ = o.per_facet_, by_facet_ = o.by_facet_, last_ = nullptr;
        return *this;
    }
    candidate_pool& operator=(candidate_pool&& o) noexcept {
        if (this != &o) per_facet_ = o.per_facet_, by_facet_ = std::move(o.by_facet_), last_ = nullptr, o.last_ = nullptr;
        return *this;
    }
    ~candidate_pool() = default;

    /// Offers a VALID box of `facet`; kept if it is among the facet's `per_facet` largest.
    void add(std::size_t facet, const pose_box<I>& box) {
        // A run's boxes come facet by facet: the last facet's list saves a lookup per box.
        if (!last_ || last_facet_ != facet) last_ = &by_facet_[facet], last_facet_ = facet;
        auto& kept = *last_;
        if (kept.size() == per_facet_ && !larger(box, kept.back())) return;  // not among the largest
        kept.push_back(box);
        std::sort(kept.begin(), kept.end(), larger);
        if (kept.size() > per_facet_) kept.pop_back();
    }

    /// PartSink: the VALID boxes of a finished facet.
    void facet(const facet_outcome<I>& o) {
        for (const auto& b : o.boxes)
            if (b.cls == box_class::valid) add(o.record.index, b.box);
    }

    /// The kept boxes, by facet then size.
    std::vector<candidate_box<I>> boxes() const {
        std::vector<candidate_box<I>> out;
        for (const auto& [f, kept] : by_facet_)
            for (const auto& b : kept) out.push_back({f, b});
        return out;
    }

private:
    static bool larger(const pose_box<I>& a, const pose_box<I>& b) {
        const double pa = volume(a.position), pb = volume(b.position);
        return pa != pb ? pa > pb : volume(a.orientation) > volume(b.orientation);
    }
    std::size_t per_facet_;
    std::map<std::size_t, std::vector<pose_box<I>>> by_facet_;  // std::map: its elements stay put
    std::vector<pose_box<I>>* last_ = nullptr;
    std::size_t last_facet_ = 0;
};

}  // namespace certipose
