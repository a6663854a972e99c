// certipose/solver/keep_largest.hpp — a result stage that keeps only the K largest VALID boxes
// of a facet (certipose-part --keep-largest K; part_options::keep_largest).
//
// A whole CAD part gives thousands of VALID boxes per facet, most of them small pieces along
// the constraint boundaries; a user placing cameras wants the roomy ones, and a store of 10^8
// boxes is not one people keep. "Largest" is the 6D volume (position volume × orientation
// volume), ties broken by position volume, then by the boxes' order in the result, so the kept
// set is deterministic. BOUNDARY boxes are left as they are. Dropping VALID boxes never makes a
// claim false: the kept ones are still each certified.
#pragma once

#include "certipose/interval/concept.hpp"
#include "certipose/solver/result.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <set>
#include <utility>
#include <vector>

namespace certipose {

/// Keeps the `k` largest VALID boxes of `r` (see the header comment); returns how many VALID
/// boxes it dropped. `r.stats.valid` and `valid_volume` count the kept ones afterwards. k = 0
/// drops them all.
template <Interval I>
std::size_t keep_largest_valid(solve_result<I>& r, std::size_t k) {
    std::vector<std::size_t> valid;
    for (std::size_t i = 0; i < r.boxes.size(); ++i)
        if (r.boxes[i].cls == box_class::valid) valid.push_back(i);
    if (valid.size() <= k) return 0;
    const auto volumes = [&](std::size_t i) {
        const auto& b = r.boxes[i].box;
        double p = 1, o = 1;
        for (std::size_t d = 0; d < 3; ++d) {
            p *= upper(b.position[d]) - lower(b.position[d]);
            o *= upper(b.orientation[d]) - lower(b.orientation[d]);
        }
        return std::pair<double, double>{p * o, p};
    };
    std::vector<std::pair<double, double>> v(r.boxes.size());
    for (std::size_t i : valid) v[i] = volumes(i);
    std::stable_sort(valid.begin(), valid.end(), [&](std::size_t a, std::size_t b) { return v[a] > v[b]; });
    std::vector<char> keep(r.boxes.size(), 1);
    for (std::size_t j = k; j < valid.size(); ++j) keep[valid[j]] = 0;
    // stats.valid_volume counts each position box with a VALID orientation once: it loses the
    // positions no kept VALID box has any more.
    const auto position_key = [&](std::size_t i) {
        std::array<double, 6> key{};
        for (std::size_t d = 0; d < 3; ++d)
            key[2 * d] = lower(r.boxes[i].box.position[d]), key[2 * d + 1] = upper(r.boxes[i].box.position[d]);
        return key;
    };
    std::set<std::array<double, 6>> kept_positions, dropped_positions;
    for (std::size_t j = 0; j < valid.size(); ++j) (j < k ? kept_positions : dropped_positions).insert(position_key(valid[j]));
    double dropped_volume = 0;
    for (const auto& key : dropped_positions)
        if (!kept_positions.count(key)) dropped_volume += (key[1] - key[0]) * (key[3] - key[2]) * (key[5] - key[4]);
    std::vector<classified_box<I>> out;
    out.reserve(r.boxes.size() - (valid.size() - k));
    for (std::size_t i = 0; i < r.boxes.size(); ++i)
        if (keep[i]) out.push_back(std::move(r.boxes[i]));
    r.boxes = std::move(out);
    const std::size_t dropped = valid.size() - k;
    r.stats.valid = k;
    r.stats.valid_volume = std::max(0.0, r.stats.valid_volume - dropped_volume);
    return dropped;
}

}  // namespace certipose
