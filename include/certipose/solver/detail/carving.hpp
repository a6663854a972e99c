// certipose/solver/detail/carving.hpp — cutting the certified part off a box (the position
// stage's inner contraction and occlusion cuts).
//
// Both work the same way: a contraction keeps, of a box B, a box R holding every position of B
// that may fail (violate a constraint of the set, or lose sight of the facet); whatever lies
// outside R is certified. `carve` hands out B \ R as at most six pieces and leaves B narrowed to
// the rest. Each piece stays one ulp clear of R's bounds, so its points are strictly outside R:
// a constraint with a strict inequality (backface: (p − v1)·n > 0) may be an equality on R's
// faces, never on the pieces. Slabs thinner than `min_width` are not cut off: they stay with
// the rest, which the paver bisects anyway, instead of becoming boxes no camera can use.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <unordered_map>
#include <vector>

#include "certipose/interval/operations.hpp"
#include "certipose/occlusion/concept.hpp"
#include "certipose/pose/pose_box.hpp"

namespace certipose::detail {

/// Emits the pieces of `box` outside `inner` (inner ⊆ box, not empty) and narrows `box` to the
/// rest (see the header comment). Returns the number of pieces.
template <class Box, class F>
std::size_t carve(Box& box, const Box& inner, double min_width, F&& emit) {
    using I = typename Box::interval_type;
    constexpr double inf = std::numeric_limits<double>::infinity();
    std::size_t pieces = 0;
    for (std::size_t i = 0; i < box.size(); ++i) {
        const double lo = lower(box[i]), hi = upper(box[i]);
        const double cut_lo = std::nextafter(lower(inner[i]), -inf), cut_hi = std::nextafter(upper(inner[i]), inf);
        if (cut_lo > lo && cut_lo - lo >= min_width) {
            Box piece = box;
            piece[i] = I(lo, cut_lo);
            emit(std::move(piece));
            box[i] = I(cut_lo, upper(box[i]));
            ++pieces;
        }
        if (cut_hi < hi && hi - cut_hi >= min_width) {
            Box piece = box;
            piece[i] = I(cut_hi, hi);
            emit(std::move(piece));
            box[i] = I(lower(box[i]), cut_hi);
            ++pieces;
        }
    }
    return pieces;
}

/// A box inside `b` that `ok` certifies, anchored at a corner of `b` (nothing when no corner
/// point is certified): near a smooth boundary the valid part of a small box is close to the
/// side of a plane, and the largest box inside that is anchored at the corner deepest inside.
/// The corner is the certified one with the most certified neighbours; from it the box grows
/// toward the opposite corner, all three widths in proportion (bisection, `steps` times), then
/// each on its own. `ok` is the only proof: every box returned passed it.
template <class Box, class Ok>
std::optional<Box> corner_box(const Box& b, Ok&& ok, int steps) {
    using I = typename Box::interval_type;
    const auto corner = [&](std::size_t k, std::size_t d) { return (k >> d) & 1 ? upper(b[d]) : lower(b[d]); };
    std::array<bool, 8> good{};
    for (std::size_t k = 0; k < 8; ++k) {
        Box p;
        for (std::size_t d = 0; d < 3; ++d) p[d] = I(corner(k, d));
        good[k] = ok(p);
    }
    std::size_t best = 8;
    int best_neighbours = -1;
    for (std::size_t k = 0; k < 8; ++k) {
        if (!good[k]) continue;
        int n = 0;
        for (std::size_t d = 0; d < 3; ++d) n += good[k ^ (std::size_t{1} << d)];
        if (n > best_neighbours) best = k, best_neighbours = n;
    }
    if (best == 8) return std::nullopt;
    // The box from the corner reaching t_d of the way across dimension d.
    const auto reach = [&](const std::array<double, 3>& t) {
        Box q;
        for (std::size_t d = 0; d < 3; ++d) {
            const double from = corner(best, d), to = corner(best ^ 7, d), end = from + t[d] * (to - from);
            q[d] = intersect(from <= end ? I(from, end) : I(end, from), b[d]);  // rounding may overshoot b
        }
        return q;
    };
    double lo = 0.0, hi = 1.0;
    for (int i = 0; i < steps; ++i) {
        const double m = (lo + hi) / 2;
        (ok(reach({m, m, m})) ? lo : hi) = m;
    }
    if (lo == 0.0) return std::nullopt;
    std::array<double, 3> t{lo, lo, lo};
    for (std::size_t d = 0; d < 3; ++d) {
        double up = 1.0;
        for (int i = 0; i < (steps + 1) / 2; ++i) {
            std::array<double, 3> c = t;
            c[d] = (t[d] + up) / 2;
            if (ok(reach(c))) t = c;
            else up = c[d];
        }
    }
    return reach(t);
}

/// A half-space of occlusion_half_space prepared for repeated use over intervals: the points
/// p with n·p ≤ rhs, n = sign·(b − a) × (c − a) and rhs = n·a enclosing the exact values.
template <Interval I>
struct prepared_half_space {
    std::array<I, 3> n;
    I rhs;
    /// Enclosures of 1/n_k where n_k excludes 0 (else unused): contractions multiply by them
    /// instead of dividing (a division was 7 % of a run), one ulp looser at most.
    std::array<I, 3> inv;
};

/// A shadow (occlusion_shadow) prepared for repeated contractions.
template <Interval I>
struct prepared_shadow {
    std::array<prepared_half_space<I>, occlusion_shadow::max_planes> planes{};
    std::size_t count = 0;
};

/// The shadows of the triangles that may block a sight line from some box, shared by the boxes
/// inside it (any triangle that may block from a sub-box may block from the box). They point
/// into a shadow_cache: a list that outlives the call it was made in is a shadow_set.
template <Interval I>
using shadow_list = std::vector<const prepared_shadow<I>*>;

template <Interval I>
class shadow_cache;

/// A shadow_list together with the cache its pointers point into. A box's state carries its
/// shadows beyond the paver that found them (a refinement pass paves the BOUNDARY boxes of the
/// pass before, with their states): the set keeps the storage alive for as long as any state
/// holds it, so no certificate can outlive the shadows it was proved with.
template <Interval I>
struct shadow_set {
    std::shared_ptr<const shadow_cache<I>> storage;
    shadow_list<I> list;
};


/// Call under a rounding_guard<I>.
template <Interval I>
prepared_shadow<I> prepare(const occlusion_shadow& s) {
    prepared_shadow<I> out;
    out.count = s.count;
    for (std::size_t p = 0; p < s.count; ++p) {
        const auto& [a, b, c] = s.planes[p].points;
        std::array<I, 3> u, v;
        for (int k = 0; k < 3; ++k) u[k] = I(b[k]) - I(a[k]), v[k] = I(c[k]) - I(a[k]);
        auto& h = out.planes[p];
        h.n = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        if (s.planes[p].sign < 0)
            for (auto& x : h.n) x = -x;
        h.rhs = h.n[0] * I(a[0]) + h.n[1] * I(a[1]) + h.n[2] * I(a[2]);
        for (std::size_t k = 0; k < 3; ++k)
            h.inv[k] = lower(h.n[k]) > 0.0 || upper(h.n[k]) < 0.0 ? I(1.0) / h.n[k] : I(0.0);
    }
    return out;
}

/// Prepared shadows by facet and scene triangle: a triangle's shadow depends on the facet and the
/// triangle alone, so each is built once. Keyed by both, so that a cache shared between facets
/// can never hand one facet another's shadow. Append-only and node-based: a reference `get`
/// returned stays valid for the cache's lifetime, which is what lets a box's state carry
/// pointers into it (shadow_set holds the cache alive). It cannot be cleared, copied or moved;
/// a user who must bound its memory starts a new one where no state points into the old.
template <Interval I>
class shadow_cache {
public:
    shadow_cache() = default;
    shadow_cache(const shadow_cache&) = delete;
    shadow_cache& operator=(const shadow_cache&) = delete;

    /// The shadow of scene triangle `triangle` for facet `facet`, from `make()` (an
    /// occlusion_shadow) the first time.
    template <class Make>
    const prepared_shadow<I>& get(std::size_t facet, std::size_t triangle, Make&& make) {
        const key k{facet, triangle};
        auto it = map_.find(k);
        if (it == map_.end()) {
            const rounding_guard<I> rounding;
            it = map_.emplace(k, prepare<I>(make())).first;
        }
        return it->second;
    }
    std::size_t size() const noexcept { return map_.size(); }

private:
    struct key {
        std::size_t facet, triangle;
        bool operator==(const key&) const = default;
    };
    struct key_hash {
        std::size_t operator()(const key& k) const noexcept {
            // splitmix64's finaliser over both: facets and triangles are small, dense integers
            std::uint64_t x = static_cast<std::uint64_t>(k.facet) * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint64_t>(k.triangle);
            x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
            x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
            return static_cast<std::size_t>(x ^ (x >> 31));
        }
    };
    std::unordered_map<key, prepared_shadow<I>, key_hash> map_;
};

/// Narrows `box` to a box holding all its points with n·p ≤ rhs (emptying it when there are
/// none); every bound is rounded outward. Call under a rounding_guard<I>.
template <Interval I>
void contract_half_space(position_box<I>& box, const prepared_half_space<I>& h) {
    std::array<I, 3> t{h.n[0] * box[0], h.n[1] * box[1], h.n[2] * box[2]};
    for (int k = 0; k < 3; ++k) {
        const I rest = h.rhs - t[(k + 1) % 3] - t[(k + 2) % 3];  // n_k p_k ≤ rest
        const I top(upper(rest));
        if (lower(h.n[k]) > 0.0) {
            const double bound = upper(top * h.inv[k]);
            box[k] = bound < lower(box[k]) ? interval_traits<I>::empty() : I(lower(box[k]), std::min(upper(box[k]), bound));
        } else if (upper(h.n[k]) < 0.0) {
            const double bound = lower(top * h.inv[k]);
            box[k] = bound > upper(box[k]) ? interval_traits<I>::empty() : I(std::max(lower(box[k]), bound), upper(box[k]));
        } else {
            continue;
        }
        if (is_empty(box[k])) {
            box = position_box<I>::empty();
            return;
        }
        t[k] = h.n[k] * box[k];
    }
}

/// False when `box` lies wholly on the safe side of one plane of the shadow (then no point of
/// it is in the shadow); true says nothing. Call under a rounding_guard<I>.
template <Interval I>
bool shadow_may_reach(const position_box<I>& box, const prepared_shadow<I>& s) {
    for (std::size_t p = 0; p < s.count; ++p) {
        const auto& h = s.planes[p];
        if (lower(h.n[0] * box[0] + h.n[1] * box[1] + h.n[2] * box[2]) > upper(h.rhs)) return false;
    }
    return true;
}

/// Narrows `box` to a box holding every point of it inside the shadow; a box wholly on the safe
/// side of one plane is emptied at once (shadow_may_reach). Call under a rounding_guard<I>.
template <Interval I>
void contract_shadow(position_box<I>& box, const prepared_shadow<I>& s) {
    if (!shadow_may_reach(box, s)) {
        box = position_box<I>::empty();
        return;
    }
    for (std::size_t p = 0; p < s.count; ++p) {
        contract_half_space(box, s.planes[p]);
        if (is_empty(box)) return;
    }
}

/// Narrows `box` to a box holding all its points in the closed half-space h (points p with
/// sign·n·(p − a) ≤ 0, n = (b − a) × (c − a)), emptying it when there are none. The normal is
/// an interval enclosure of the exact one and every bound is rounded outward, so no point of
/// the half-space is lost. Call under a rounding_guard<I>.
template <Interval I>
void contract_half_space(position_box<I>& box, const occlusion_half_space& h) {
    const auto& [a, b, c] = h.points;
    std::array<I, 3> u, v, n, d;
    for (int k = 0; k < 3; ++k) u[k] = I(b[k]) - I(a[k]), v[k] = I(c[k]) - I(a[k]);
    n = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    if (h.sign < 0)
        for (auto& x : n) x = -x;
    for (int k = 0; k < 3; ++k) d[k] = box[k] - I(a[k]);
    // n·d ≤ 0: for each coordinate, n_k d_k ≤ −Σ_{j≠k} n_j d_j.
    for (int k = 0; k < 3; ++k) {
        I rest(0.0);
        for (int j = 0; j < 3; ++j)
            if (j != k) rest = rest - n[j] * d[j];
        const I top(upper(rest));
        if (lower(n[k]) > 0.0) {  // d_k ≤ top / n_k
            const double bound = upper(I(a[k]) + I(upper(top / n[k])));
            box[k] = bound < lower(box[k]) ? interval_traits<I>::empty()
                                           : I(lower(box[k]), std::min(upper(box[k]), bound));
        } else if (upper(n[k]) < 0.0) {  // d_k ≥ top / n_k
            const double bound = lower(I(a[k]) + I(lower(top / n[k])));
            box[k] = bound > upper(box[k]) ? interval_traits<I>::empty()
                                           : I(std::max(lower(box[k]), bound), upper(box[k]));
        }
        if (is_empty(box[k])) {
            box = position_box<I>::empty();
            return;
        }
        d[k] = box[k] - I(a[k]);
    }
}

/// Narrows `box` to a box holding every point of it inside `shadow` (the intersection of its
/// half-spaces; a shadow without planes keeps the whole box). Two sweeps: the planes of one
/// shadow narrow each other once more, after which little changes.
template <Interval I>
void contract_shadow(position_box<I>& box, const occlusion_shadow& shadow) {
    for (int sweep = 0; sweep < 2; ++sweep)
        for (std::size_t p = 0; p < shadow.count; ++p) {
            contract_half_space(box, shadow.planes[p]);
            if (is_empty(box)) return;
        }
}

}  // namespace certipose::detail
