// certipose/solver/placement_stage.hpp — the stage that keeps only what holds for every placement
// of the part its placement tolerance admits (pose/placement_tolerance.hpp).
//
// The position and orientation stages pave for the nominal placement; their VALID boxes then go
// through this stage, with a certifier whose proofs cover every admitted placement
// (solver/detail/box_certifier.hpp with a placement_scene). For each box B:
//   1. B itself: accepted → VALID as it is;
//   2. erode and restore: the core of B, its position faces moved in by the margin m(B) (the
//      reach of its camera positions, at least the facet's), should pass by inclusion — the
//      proofs over B covered every position the core can reach in the part frame — unless a
//      fixed occluder is in the way; it is certified like any box, then; then each position
//      face is moved back out to where B had it, one at a time, kept there when the certifier
//      still accepts the box. Only the faces where B touched the edge of what holds for every
//      placement stay eroded; the slabs they cut off (disjoint, with the box a partition of B)
//      go on to step 3;
//   3. what is left undecided — those slabs, or B when its core is not certified (a fixed
//      occluder, a box thinner than 2m) — is bisected, on
//      the axis widest relative to (ε_p, ε_p, ε_p, ε_o, ε_o, ε_o), and each half decided the same
//      way, down to ε_p / position_split and ε_o / orientation_split or `max_certifications` per
//      box; what is still unproven then is BOUNDARY `placement` (its intervals are certified for
//      the nominal placement only) — the whole box, once, when no piece of it was proven.
// Every piece returned VALID has passed the certifier, and every piece is a sub-box of a nominal
// VALID box: the stage only removes poses. Growth (solve_options::grow) runs after
// it with the same certifier, so grown boxes hold for every placement too.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"
#include "certipose/interval/operations.hpp"
#include "certipose/pose/pose_box.hpp"
#include "certipose/solver/result.hpp"

namespace certipose {

/// Options of the placement stage (see the header comment).
struct placement_stage_options {
    /// Pieces are not split below ε_p / position_split on a position axis.
    double position_split = 4;
    /// Pieces are not split below ε_o / orientation_split on an angle.
    double orientation_split = 4;
    /// Certifications spent on one VALID box of the nominal solve at most. Every halving that
    /// proves neither half leaves one more BOUNDARY piece, so this also bounds how many pieces a
    /// box straddling the tolerance's margin turns into (at most about half of it).
    std::size_t max_certifications = 24;

    void validate() const {
        if (!(position_split >= 1.0) || !std::isfinite(position_split))
            throw invalid_argument("placement.position_split", "placement_stage_options: position_split must be >= 1 and finite, got " +
                                                                    detail::format_double(position_split));
        if (!(orientation_split >= 1.0) || !std::isfinite(orientation_split))
            throw invalid_argument("placement.orientation_split",
                                   "placement_stage_options: orientation_split must be >= 1 and finite, got " +
                                       detail::format_double(orientation_split));
        if (max_certifications == 0)
            throw invalid_argument("placement.max_certifications", "placement_stage_options: max_certifications must be at least 1");
    }
};

namespace detail::placement {

/// Step 2 of the header comment: a partition of `b` into one certified box and the slabs left
/// undecided, or nothing when its core is not certified. `m`: the margin per position axis.
template <Interval I, class Certify>
std::optional<std::pair<pose_box<I>, std::vector<pose_box<I>>>> erode_and_restore(const pose_box<I>& b,
                                                                                    const std::array<double, 3>& m,
                                                                                    Certify& certified, std::size_t& spent) {
    pose_box<I> core = b;
    for (std::size_t k = 0; k < 3; ++k) {
        const double lo = std::nextafter(lower(b.position[k]) + m[k], INFINITY);
        const double hi = std::nextafter(upper(b.position[k]) - m[k], -INFINITY);
        if (!(lo < hi)) return std::nullopt;  // thinner than 2m: no core
        core.position[k] = I(lo, hi);
    }
    ++spent;
    if (!certified(core)) return std::nullopt;
    // Move each face back out, keeping it where the certifier still accepts the box.
    pose_box<I> kept = core;
    for (std::size_t k = 0; k < 3; ++k)
        for (const bool upper_face : {false, true}) {
            pose_box<I> trial = kept;
            trial.position[k] = upper_face ? I(lower(kept.position[k]), upper(b.position[k]))
                                           : I(lower(b.position[k]), upper(kept.position[k]));
            ++spent;
            if (certified(trial)) kept = trial;
        }
    // The rest of b, as disjoint slabs: peel each eroded face off what is left.
    std::vector<pose_box<I>> slabs;
    pose_box<I> rest = b;
    for (std::size_t k = 0; k < 3; ++k) {
        if (lower(kept.position[k]) > lower(rest.position[k])) {
            pose_box<I> slab = rest;
            slab.position[k] = I(lower(rest.position[k]), lower(kept.position[k]));
            slabs.push_back(slab);
            rest.position[k] = I(lower(kept.position[k]), upper(rest.position[k]));
        }
        if (upper(kept.position[k]) < upper(rest.position[k])) {
            pose_box<I> slab = rest;
            slab.position[k] = I(upper(kept.position[k]), upper(rest.position[k]));
            slabs.push_back(slab);
            rest.position[k] = I(lower(rest.position[k]), upper(kept.position[k]));
        }
    }
    return std::pair{kept, std::move(slabs)};
}

}  // namespace detail::placement

/// The placement stage over `result`'s VALID boxes (see the header comment). `certified(box)`
/// proves a 6D box for every placement; `margin(position)` is the per-axis margin of step 2;
/// `out_of_time()` ends the stage early, leaving the boxes not yet decided BOUNDARY (reason
/// `budget`), and `stop_reason()` then says why (deadline or cancelled) in stats.reason. Updates
/// counts, volumes and reasons of result.stats.
template <Interval I, class Certify, class Margin, class OutOfTime, class StopReason>
void certify_for_every_placement(solve_result<I>& result, Certify&& certified, Margin&& margin, double position_eps,
                                 double orientation_eps, const placement_stage_options& options, OutOfTime&& out_of_time,
                                 StopReason&& stop_reason) {
    options.validate();
    solve_stats& st = result.stats;
    const std::array<double, 6> finest{position_eps / options.position_split, position_eps / options.position_split,
                                       position_eps / options.position_split, orientation_eps / options.orientation_split,
                                       orientation_eps / options.orientation_split, orientation_eps / options.orientation_split};
    const std::array<double, 6> scale{position_eps, position_eps, position_eps, orientation_eps, orientation_eps, orientation_eps};
    std::vector<classified_box<I>> boxes;
    boxes.reserve(result.boxes.size());
    bool stopped = false;
    const auto boundary = [&](const pose_box<I>& b, boundary_reason why = boundary_reason::placement) {
        boxes.push_back(classified_box<I>{box_class::boundary, b, why});
        ++st.boundary;
        ++st.boundary_reasons[static_cast<std::size_t>(why)];
    };
    for (auto& b : result.boxes) {
        if (b.cls != box_class::valid) {
            boxes.push_back(std::move(b));
            continue;
        }
        if (!stopped && out_of_time()) {
            stopped = true;
            // Say why, as the other stages do (a run that was complete until now ends here).
            if (st.reason == termination::completed) st.reason = stop_reason();
        }
        if (stopped) {  // not decided: the run's budget, as for the other stages
            boundary(b.box, boundary_reason::budget);
            continue;
        }
        std::size_t spent = 1;
        if (certified(b.box)) {
            boxes.push_back(std::move(b));
            continue;
        }
        ++st.placement_split;
        std::vector<pose_box<I>> todo, certified_pieces, undecided;
        if (auto parts = detail::placement::erode_and_restore(b.box, margin(b.box.position), certified, spent)) {
            certified_pieces.push_back(std::move(parts->first));
            todo = std::move(parts->second);  // the slabs: split along them below, while the budget lasts
        } else {
            todo.push_back(b.box);
        }
        while (!todo.empty()) {
            pose_box<I> piece = std::move(todo.back());
            todo.pop_back();
            // The axis widest relative to its ε that may still be split.
            interval_box<I, 6> six = piece.as_6d();
            std::size_t axis = 6;
            double best = 0.0;
            for (std::size_t k = 0; k < 6; ++k) {
                const double w = width(six[k]);
                if (w > finest[k] && w / scale[k] > best) best = w / scale[k], axis = k;
            }
            if (axis == 6 || spent + 2 > options.max_certifications) {
                undecided.push_back(std::move(piece));
                continue;
            }
            ++st.placement_bisections;
            const auto [lo, hi] = bisect(six[axis]);
            for (const I& half : {lo, hi}) {
                interval_box<I, 6> h = six;
                h[axis] = half;
                const pose_box<I> q = pose_box<I>::from_6d(h);
                ++spent;
                if (certified(q)) certified_pieces.push_back(q);
                else todo.push_back(q);
            }
        }
        if (certified_pieces.empty()) {  // nothing of b proven: b itself, once
            boundary(b.box);
            continue;
        }
        for (auto& q : certified_pieces) boxes.push_back(classified_box<I>{box_class::valid, std::move(q)});
        for (const auto& q : undecided) boundary(q);
    }
    result.boxes = std::move(boxes);
    // As the orientation stage counts it: each position box once, however many orientation
    // boxes share it.
    st.valid = 0;
    st.valid_volume = 0.0;
    std::set<std::array<double, 6>> seen;
    for (const auto& b : result.boxes) {
        if (b.cls != box_class::valid) continue;
        ++st.valid;
        const auto& p = b.box.position;
        if (seen.insert({lower(p[0]), lower(p[1]), lower(p[2]), upper(p[0]), upper(p[1]), upper(p[2])}).second)
            st.valid_volume += volume(p);
    }
}

}  // namespace certipose
