// certipose/solver/detail/growth.hpp — widening certified 6D boxes: the installation tolerance
// (pose_solver::grow, pose_solver::largest_box_around, solve_options::grow).
//
// Everything here is driven by one yes/no question, "is every pose of this 6D box valid?"
// (pose_solver::certify), so every box it returns is a union of certified boxes: soundness
// does not depend on how the search moves, only on that question. The search is greedy: a face
// moves out by a step that doubles while the slab it adds is certified and then halves down to
// the finest step, face after face (the box before the move is a union of certified boxes, so
// box ∪ slab is too); a box around a pose first grows all its half-widths together, in the
// proportions of a reference box, then each on its own. Boxes that share a whole position face
// merge without a new proof: the hull of the two position boxes is their union, and every pose
// of it with an orientation in both orientation boxes lies in one of the two certified boxes.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory_resource>
#include <numbers>
#include <optional>
#include <tuple>
#include <unordered_map>
#include <vector>

#include "certipose/interval/operations.hpp"
#include "certipose/pose/pose_box.hpp"
#include "certipose/solver/task.hpp"

namespace certipose {

namespace detail::growth {

/// The component k of a 6D pose box (x, y, z, φ, γ, β).
template <Interval I>
I& component(pose_box<I>& b, std::size_t k) {
    return k < 3 ? b.position[k] : b.orientation[k - 3];
}
template <Interval I>
const I& component(const pose_box<I>& b, std::size_t k) {
    return k < 3 ? b.position[k] : b.orientation[k - 3];
}

/// Bounds no box may pass: γ ∈ [0, π]; φ and β span at most one turn.
inline constexpr double pi_up = 3.1415926535897936;  // π rounded up

/// Moves face `side` (0: lower, 1: upper) of component k out by `step`, within the limits.
/// False when it cannot move.
template <Interval I>
bool moved(const pose_box<I>& b, std::size_t k, int side, double step, pose_box<I>& out) {
    out = b;
    const I& c = component(b, k);
    double lo = lower(c), hi = upper(c);
    if (side == 0) lo -= step;
    else hi += step;
    if (k == 4) lo = std::max(lo, 0.0), hi = std::min(hi, pi_up);
    if ((k == 3 || k == 5) && hi - lo > 2 * pi_up) {
        if (side == 0) lo = hi - 2 * pi_up;
        else hi = lo + 2 * pi_up;
    }
    // Only outward: the clamps above, rounded, could move a face in.
    if (side == 0 ? !(lo < lower(c)) : !(hi > upper(c))) return false;
    lo = std::min(lo, lower(c)), hi = std::max(hi, upper(c));
    component(out, k) = I(lo, hi);
    return true;
}

/// What moving face `side` of component k turns `b` into `cand` adds: the slab between the old
/// and the new face, as wide as `b` in every other component. `b` ∪ slab = `cand`, so when `b`
/// is certified, certifying the slab certifies `cand`. The slab is the cheaper question (a
/// thinner position box walks fewer occluders) and the easier one (interval bounds over a
/// thinner box are tighter, so the field of view passes where the whole box's bounds may not).
template <Interval I>
pose_box<I> added_slab(const pose_box<I>& b, const pose_box<I>& cand, std::size_t k, int side) {
    pose_box<I> slab = b;
    const I& old_k = component(b, k);
    const I& new_k = component(cand, k);
    component(slab, k) = side == 0 ? I(lower(new_k), lower(old_k)) : I(upper(old_k), upper(new_k));
    return slab;
}

/// Grows the certified box `b` face by face (see the header comment); `ok(box)` certifies.
template <Interval I, class Certify>
pose_box<I> grow(pose_box<I> b, Certify&& ok, const std::array<double, 6>& finest, std::size_t budget) {
    std::size_t spent = 0;
    for (int round = 0; round < 2; ++round) {
        bool grew = false;
        for (std::size_t k = 0; k < 6; ++k)
            for (int side = 0; side < 2; ++side) {
                const I& c = component(b, k);
                double step = std::max(finest[k], (upper(c) - lower(c)) / 2);
                bool expanding = true;
                while (step >= finest[k] && spent < budget) {
                    pose_box<I> cand;
                    if (!moved(b, k, side, step, cand)) break;
                    ++spent;
                    if (ok(added_slab(b, cand, k, side))) {
                        b = cand, grew = true;
                        if (expanding) step *= 2;
                    } else {
                        expanding = false;
                        step /= 2;
                    }
                }
            }
        if (!grew || spent >= budget) break;
    }
    return b;
}

/// The box with centre `c` and half-widths `h` (γ kept within [0, π]).
template <Interval I>
pose_box<I> around(const std::array<double, 6>& c, const std::array<double, 6>& h) {
    pose_box<I> b;
    for (std::size_t k = 0; k < 6; ++k) {
        double lo = c[k] - h[k], hi = c[k] + h[k];
        if (k == 4) lo = std::max(lo, 0.0), hi = std::min(hi, pi_up);
        component(b, k) = I(lo, hi);
    }
    return b;
}

/// The largest box found around pose `c` (x, y, z, φ, γ, β): half-widths t·reference for the
/// largest t certified, then each half-width grown on its own. Nothing when `c` itself fails.
template <Interval I, class Certify>
std::optional<pose_box<I>> largest_around(const std::array<double, 6>& c, Certify&& ok,
                                          const std::array<double, 6>& reference,
                                          const std::array<double, 6>& finest, std::size_t budget) {
    std::array<double, 6> h{};
    if (!ok(around<I>(c, h))) return std::nullopt;
    std::size_t spent = 1;
    // 1. All half-widths together: double t while certified, then bisect.
    double t_ok = 0.0, t = 1.0 / 64;
    const auto scaled = [&](double s) {
        std::array<double, 6> r{};
        for (std::size_t k = 0; k < 6; ++k) r[k] = s * reference[k];
        return r;
    };
    double t_bad = -1.0;
    while (spent < budget && t < 64) {
        ++spent;
        if (ok(around<I>(c, scaled(t)))) t_ok = t, t *= 2;
        else { t_bad = t; break; }
    }
    if (t_bad > 0)
        for (int i = 0; i < 12 && spent < budget; ++i, ++spent) {
            const double m = (t_ok + t_bad) / 2;
            (ok(around<I>(c, scaled(m))) ? t_ok : t_bad) = m;
        }
    h = scaled(t_ok);
    // 2. Each half-width on its own, in turn.
    for (int round = 0; round < 2; ++round)
        for (std::size_t k = 0; k < 6; ++k) {
            double step = std::max(finest[k], h[k]);
            bool expanding = true;
            while (step >= finest[k] && spent < budget) {
                std::array<double, 6> cand = h;
                cand[k] += step;
                if ((k == 3 || k == 5) && cand[k] > pi_up) break;
                ++spent;
                if (ok(around<I>(c, cand))) {
                    h = cand;
                    if (expanding) step *= 2;
                } else {
                    expanding = false;
                    step /= 2;
                }
            }
        }
    return around<I>(c, h);
}

/// A position face as the merges look it up: the dimension it is normal to, its coordinate and
/// the two intervals of the other dimensions. Hashed, not ordered: the merges look up three keys
/// per box and round, and six-way comparisons in an ordered map cost more than the hash.
using face_key = std::tuple<std::size_t, double, double, double, double, double>;

struct face_key_hash {
    std::size_t operator()(const face_key& k) const noexcept {
        // The bits of each double (0.0 for −0.0: equal keys hash alike), mixed by multiplication
        // and a final xor-shift; std::hash<double> hashes the bytes (murmur), which is slower.
        std::uint64_t h = std::get<0>(k);
        const auto mix = [&](double x) {
            h = (h ^ std::bit_cast<std::uint64_t>(x == 0.0 ? 0.0 : x)) * 0x9e3779b97f4a7c15ull;
            h ^= h >> 29;
        };
        mix(std::get<1>(k)), mix(std::get<2>(k)), mix(std::get<3>(k)), mix(std::get<4>(k)), mix(std::get<5>(k));
        return static_cast<std::size_t>(h);
    }
};

template <Interval I>
face_key make_face_key(const position_box<I>& p, std::size_t d, double at) {
    const std::size_t a = (d + 1) % 3, b = (d + 2) % 3;
    return face_key{d, at, lower(p[a]), upper(p[a]), lower(p[b]), upper(p[b])};
}

/// The boxes of one round of a merge by their lower faces (the first box listed for a face
/// keeps it). Built, searched and dropped once per round, so its nodes come from one buffer
/// released at once instead of a heap allocation and a free per face.
class lower_face_index {
public:
    /// `position_of(box)` is the position box of an element of `boxes`.
    template <class Boxes, class PositionOf>
    lower_face_index(const Boxes& boxes, PositionOf&& position_of) : faces_(&buffer_) {
        faces_.reserve(3 * boxes.size());
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            const auto& p = position_of(boxes[i]);
            for (std::size_t d = 0; d < 3; ++d) faces_.emplace(make_face_key(p, d, lower(p[d])), i);
        }
    }
    lower_face_index(const lower_face_index&) = delete;  // the map points into the buffer
    lower_face_index& operator=(const lower_face_index&) = delete;

    /// The box whose lower face in dimension d is the upper face of `p` there, if any.
    template <Interval I>
    std::optional<std::size_t> above(const position_box<I>& p, std::size_t d) const {
        const auto it = faces_.find(make_face_key(p, d, upper(p[d])));
        if (it == faces_.end()) return std::nullopt;
        return it->second;
    }

private:
    std::pmr::monotonic_buffer_resource buffer_;
    std::pmr::unordered_map<face_key, std::size_t, face_key_hash> faces_;
};

/// Merges VALID boxes that share a whole position face (see the header comment): the merged box
/// takes the hull of the orientations when `fov_ok(position, orientation)` certifies it, else
/// their intersection (certified without a proof), and is skipped when that is empty. Repeats
/// until nothing merges or `stop()` says so (a deadline: each merge costs a field-of-view
/// certification, and a refined run hands over tens of thousands of boxes). Returns the number
/// of merges.
template <Interval I, class FovOk>
std::size_t merge_touching(std::vector<pose_box<I>>& boxes, FovOk&& fov_ok, const std::function<bool()>& stop = {}) {
    std::size_t merges = 0;
    for (bool again = true; again && !(stop && stop());) {
        again = false;
        const lower_face_index lower_face(boxes, [](const pose_box<I>& b) -> const position_box<I>& { return b.position; });
        std::vector<bool> gone(boxes.size(), false);
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            if (gone[i]) continue;
            if (i % 256 == 0 && stop && stop()) break;
            for (std::size_t d = 0; d < 3 && !gone[i]; ++d) {
                const auto j = lower_face.above(boxes[i].position, d);
                if (!j || *j == i || gone[*j]) continue;
                const pose_box<I>& a = boxes[i];
                const pose_box<I>& b = boxes[*j];
                // Still the same faces? (an earlier merge may have changed box i)
                const std::size_t u = (d + 1) % 3, v = (d + 2) % 3;
                if (!(upper(a.position[d]) == lower(b.position[d]) && lower(a.position[u]) == lower(b.position[u]) &&
                      upper(a.position[u]) == upper(b.position[u]) && lower(a.position[v]) == lower(b.position[v]) &&
                      upper(a.position[v]) == upper(b.position[v])))
                    continue;
                pose_box<I> m{hull(a.position, b.position), hull(a.orientation, b.orientation)};
                if (!fov_ok(m.position, m.orientation)) {
                    m.orientation = intersect(a.orientation, b.orientation);
                    if (is_empty(m.orientation)) continue;
                }
                boxes[i] = m;
                gone[*j] = true;
                ++merges;
                again = true;
            }
        }
        std::size_t w = 0;
        for (std::size_t i = 0; i < boxes.size(); ++i)
            if (!gone[i]) boxes[w++] = boxes[i];
        boxes.resize(w);
    }
    return merges;
}

/// Merges position boxes that share a whole face, as long as the merged box is at most
/// `max_width` wide in every dimension; repeats until nothing merges. The union of two boxes that
/// share a whole face is their hull, so a property that holds at every point of both holds on
/// the merged box (position-stage VALID boxes: constraints 1–4 and 6). Returns the merges.
template <Interval I>
std::size_t merge_touching_positions(std::vector<position_box<I>>& boxes, double max_width) {
    std::size_t merges = 0;
    // A few rounds: each can double a box, and more rounds cost more than they merge.
    for (int round = 0; round < 4; ++round) {
        bool again = false;
        const lower_face_index lower_face(boxes, [](const position_box<I>& b) -> const position_box<I>& { return b; });
        std::vector<bool> gone(boxes.size(), false), changed(boxes.size(), false);
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            if (gone[i] || changed[i]) continue;
            for (std::size_t d = 0; d < 3; ++d) {
                const auto above = lower_face.above(boxes[i], d);
                if (!above) continue;
                const std::size_t j = *above;
                if (j == i || gone[j] || changed[j]) continue;
                if (upper(boxes[j][d]) - lower(boxes[i][d]) > max_width) continue;
                boxes[i] = hull(boxes[i], boxes[j]);
                gone[j] = true, changed[i] = true;
                ++merges, again = true;
                break;
            }
        }
        std::size_t w = 0;
        for (std::size_t i = 0; i < boxes.size(); ++i)
            if (!gone[i]) boxes[w++] = boxes[i];
        boxes.resize(w);
        if (!again) break;
    }
    return merges;
}

/// The index of the cell of a grid of width `cell` that holds coordinate x, clamped to ±1e15
/// before the cast so that no coordinate overflows it (the clamp keeps the order of indices).
inline long long cell_index(double x, double cell) {
    return static_cast<long long>(std::clamp(std::floor(x / cell), -1e15, 1e15));
}

/// Drops boxes contained in another box of the list (keeps one of equal boxes).
///
/// Largest first, each box against the boxes already kept that could contain it: a box that
/// contains b contains b's centre, so the kept boxes are registered in the cells of a grid they
/// overlap and only those of the cell holding b's centre are compared (all pairs took 1.5 s on
/// the 35 000 boxes of a refined run). Exact: the grid only chooses which pairs to compare.
template <Interval I>
void drop_contained(std::vector<pose_box<I>>& boxes) {
    const auto inside = [](const pose_box<I>& a, const pose_box<I>& b) {
        for (std::size_t k = 0; k < 6; ++k) {
            const I& x = component(a, k);
            const I& y = component(b, k);
            if (!(lower(y) <= lower(x) && upper(x) <= upper(y))) return false;
        }
        return true;
    };
    if (boxes.size() < 2) return;
    // Largest first: a box can only be inside one at least as large.
    std::sort(boxes.begin(), boxes.end(), [](const pose_box<I>& a, const pose_box<I>& b) { return volume(a) > volume(b); });
    // Cells as wide as most boxes (the 90th percentile of their widest side): a box overlaps a
    // few cells and a cell holds a few boxes. A box spanning more than 512 cells (a grown one
    // among refined leaves) is compared with every box instead of being registered everywhere.
    std::vector<double> widest;
    widest.reserve(boxes.size());
    for (const auto& b : boxes) {
        double w = 0;
        for (std::size_t k = 0; k < 3; ++k) w = std::max(w, upper(b.position[k]) - lower(b.position[k]));
        widest.push_back(w);
    }
    const auto p90 = widest.begin() + static_cast<std::ptrdiff_t>(widest.size() * 9 / 10);
    std::nth_element(widest.begin(), p90, widest.end());
    const double cell = *p90 > 0 && std::isfinite(*p90) ? *p90 : 1.0;
    using cell_key = std::array<long long, 3>;
    // cell_index is monotone, so a box that contains b still spans the index of b's centre.
    const auto index = [cell](double x) { return cell_index(x, cell); };
    std::map<cell_key, std::vector<std::size_t>> grid;  // cell -> kept boxes overlapping it
    std::vector<std::size_t> spanning;                  // kept boxes over too many cells
    std::vector<pose_box<I>> kept;
    for (auto& b : boxes) {
        const cell_key at{index(mid(b.position[0])), index(mid(b.position[1])), index(mid(b.position[2]))};
        bool contained = false;
        if (const auto it = grid.find(at); it != grid.end())
            for (std::size_t i : it->second)
                if (inside(b, kept[i])) { contained = true; break; }
        if (!contained)
            for (std::size_t i : spanning)
                if (inside(b, kept[i])) { contained = true; break; }
        if (contained) continue;
        const std::size_t id = kept.size();
        cell_key lo{}, hi{};
        double cells = 1;
        for (std::size_t k = 0; k < 3; ++k) {
            lo[k] = index(lower(b.position[k])), hi[k] = index(upper(b.position[k]));
            cells *= static_cast<double>(hi[k] - lo[k] + 1);
        }
        if (cells > 512) spanning.push_back(id);
        else
            for (long long x = lo[0]; x <= hi[0]; ++x)
                for (long long y = lo[1]; y <= hi[1]; ++y)
                    for (long long z = lo[2]; z <= hi[2]; ++z) grid[cell_key{x, y, z}].push_back(id);
        kept.push_back(std::move(b));
    }
    boxes = std::move(kept);
}

}  // namespace detail::growth

}  // namespace certipose
