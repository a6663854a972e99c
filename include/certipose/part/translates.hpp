// certipose/part/translates.hpp — facets that are translates of one another, and one facet's
// boxes proven again for a translate of it: the reuse stage of a part run
// (part_options::reuse, part/part_solver.hpp; docs/part.md#reuse-between-translates).
//
// Constraints 1–5 see a pose only through the facet's vertices relative to the camera (the
// distances, the view angle, where each vertex falls in the image), so for a facet g = f + t the
// poses that satisfy them are f's moved by t. Occlusion is not translation-invariant: reuse is
// limited to *open* facets, whose sight lines from anywhere in their search box in front of them
// are all free (nothing of the scene stands in front of the facet's plane within reach:
// aabb_occlusion::front_clear). For two open translates, f's paving moved by t is g's up to
// rounding, so it certifies the same share of g.
//
// Planar faces of CAD exports and gridded meshes are tessellated into many congruent triangles
// (the bundled sample part has a few dozen shapes for 2 300 facets): a paving of one of them
// serves the others for the price of checking its boxes.
//
// Nothing rests on the grouping being right: it compares edge vectors rounded to a grid of
// `translate_groups::quantum` metres, so nearly translated facets group too. Every VALID box a
// facet takes is proven again for that facet — constraints 1–4 by its constraint set, 5 by
// certify_fov_tiled, 6 by the open answer over its search box, which the box must lie in,
// strictly in front of the facet's plane (interval arithmetic on an enclosure of its normal).
// A box whose proof fails is BOUNDARY; when those hold more than `reuse_options::max_loss` of
// the translate's VALID volume, `certify_translated` refuses and the facet is paved on its own.
// BOUNDARY boxes are moved outward-rounded: they claim nothing.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"
#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/orientation/certify.hpp"
#include "certipose/pose/pose_box.hpp"
#include "certipose/solver/detail/box_certifier.hpp"
#include "certipose/solver/result.hpp"

namespace certipose {

/// The reuse stage's options (part_options::reuse).
struct reuse_options {
    /// An open facet with a translate takes the boxes of the first open facet of its group (by
    /// index, in the whole part, so that a facet's boxes do not depend on the selection or on
    /// how MPI cut it), each proven again for it. Off: every facet is paved on its own.
    bool translates = true;
    /// The share of the translate's VALID 6D volume whose proofs may fail for the facet (those
    /// boxes become BOUNDARY): beyond it, the facet is paved on its own. Boxes at the very edge
    /// of what their proofs allow (grown ones, refined ones) do not always survive the move.
    double max_loss = 0.01;

    void validate() const {
        if (!(max_loss >= 0.0 && max_loss <= 1.0))
            throw invalid_argument("reuse.max_loss", "reuse_options: max_loss must be in [0, 1], got " +
                                                         detail::format_double(max_loss));
    }
};

/// The part's facets grouped by shape up to translation: `group_of[f]` is facet f's group (or
/// `none` for a facet too large for the grid), `members[g]` the facets of group g in index
/// order. Only groups of two or more facets matter to reuse.
struct translate_groups {
    static constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
    /// The grid edge vectors are rounded to (metres): far below any tessellation's detail and
    /// far above the rounding of coordinates that were meant to be translates.
    static constexpr double quantum = 1e-9;

    std::vector<std::uint32_t> group_of;
    std::vector<std::vector<std::size_t>> members;

    static translate_groups of(const triangle_mesh& mesh) {
        translate_groups out;
        out.group_of.assign(mesh.num_faces(), none);
        struct key_hash {
            std::size_t operator()(const std::array<std::int64_t, 6>& k) const noexcept {
                std::uint64_t h = 0x9e3779b97f4a7c15ull;
                for (std::int64_t x : k) h = (h ^ static_cast<std::uint64_t>(x)) * 0x100000001b3ull;
                return static_cast<std::size_t>(h ^ (h >> 29));
            }
        };
        std::unordered_map<std::array<std::int64_t, 6>, std::uint32_t, key_hash> index;
        index.reserve(mesh.num_faces());
        for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
            const auto key = shape_key(mesh.facet(f));
            if (!key) continue;
            auto [it, added] = index.try_emplace(*key, static_cast<std::uint32_t>(out.members.size()));
            if (added) out.members.emplace_back();
            out.members[it->second].push_back(f);
            out.group_of[f] = it->second;
        }
        return out;
    }

    /// The group of facet f when it has other members, else nothing.
    std::optional<std::uint32_t> shared_group(std::size_t f) const {
        if (f >= group_of.size() || group_of[f] == none || members[group_of[f]].size() < 2) return std::nullopt;
        return group_of[f];
    }

private:
    // The edge vectors (b − a, c − a) on the grid, for the cyclic order of the vertices whose key
    // is least: the same triangle listed from another vertex has the same key (a mirrored one,
    // with the other normal, does not).
    static std::optional<std::array<std::int64_t, 6>> shape_key(const facet& f) {
        std::optional<std::array<std::int64_t, 6>> best;
        for (int r = 0; r < 3; ++r) {
            const Eigen::Vector3d& a = f.v[static_cast<std::size_t>(r)];
            const Eigen::Vector3d& b = f.v[static_cast<std::size_t>((r + 1) % 3)];
            const Eigen::Vector3d& c = f.v[static_cast<std::size_t>((r + 2) % 3)];
            std::array<std::int64_t, 6> k{};
            for (int d = 0; d < 3; ++d) {
                const double e1 = (b[d] - a[d]) / quantum, e2 = (c[d] - a[d]) / quantum;
                if (!(std::abs(e1) < 4e18) || !(std::abs(e2) < 4e18)) return std::nullopt;
                k[static_cast<std::size_t>(d)] = std::llround(e1);
                k[static_cast<std::size_t>(d) + 3] = std::llround(e2);
            }
            if (!best || k < *best) best = k;
        }
        return best;
    }
};

namespace detail {

/// [x + t] with its ends rounded inward (a subset of the exact translate; empty when the interval
/// is thinner than the rounding) or outward (a superset).
template <Interval I>
I translated(const I& x, double t, bool inward) {
    const I lo = I(lower(x)) + I(t), hi = I(upper(x)) + I(t);
    if (!inward) return I(lower(lo), upper(hi));
    if (!(upper(lo) <= lower(hi))) return interval_traits<I>::empty();
    return I(upper(lo), lower(hi));
}

}  // namespace detail

/// What `certify_translated` makes of a translate's boxes: its boxes moved onto the facet, every
/// VALID one proven for it, and those of its VALID boxes that could not be proven, which are now
/// BOUNDARY (kept among `boxes` only when asked), counted by the constraint whose proof failed.
template <Interval I>
struct translated_boxes {
    std::vector<classified_box<I>> boxes;
    std::size_t valid = 0;     ///< VALID boxes among `boxes`
    std::size_t unproven = 0;  ///< the translate's VALID boxes not proven here
    std::array<std::size_t, boundary_reason_count> unproven_reasons{};
};

/// The boxes of `from` (a facet's result) moved by `shift` onto facet `f`, each VALID one proven
/// for f (see the header comment), or nothing when those that cannot be proven hold more than
/// `max_loss` of `from`'s VALID 6D volume. `set` is f's constraint set, `search` a box from
/// whose positions in front of f every sight line to f is free (every VALID box is cut to it
/// and must be strictly in front), `frustum` the camera's, and `tiling_budget` the certify_fov
/// evaluations one proof of constraint 5 may take (certify_fov_tiled; the orientation
/// policy's, so that what it proved can be proven again). BOUNDARY boxes are moved outward and
/// kept, with the unproven ones, only with `keep_boundary`.
template <class Set, Interval I>
std::optional<translated_boxes<I>> certify_translated(Set& set, const position_box<I>& search, const facet& f,
                                                      const fov_frustum<I>& frustum, std::span<const classified_box<I>> from,
                                                      const Eigen::Vector3d& shift, bool keep_boundary,
                                                      std::size_t tiling_budget, double max_loss) {
    const rounding_guard<I> rounding;
    std::vector<classified_box<I>> out;
    out.reserve(from.size());
    std::vector<std::uint8_t> failed;  // per box of `out`: 0, or 1 + the boundary_reason of its failed proof
    std::vector<const classified_box<I>*> source;  // per box of `out`: the translate's box
    failed.reserve(from.size());
    source.reserve(from.size());
    double total = 0.0;
    const auto six = [](const pose_box<I>& b) { return volume(b.position) * volume(b.orientation); };
    // An enclosure of (v2 − v1) × (v3 − v1): its side of every box is proven, not estimated.
    const auto coord = [&](int k, int d) { return I(f.v[static_cast<std::size_t>(k)][d]); };
    std::array<I, 3> e1{}, e2{}, normal{};
    for (int d = 0; d < 3; ++d) e1[d] = coord(1, d) - coord(0, d), e2[d] = coord(2, d) - coord(0, d);
    normal[0] = e1[1] * e2[2] - e1[2] * e2[1];
    normal[1] = e1[2] * e2[0] - e1[0] * e2[2];
    normal[2] = e1[0] * e2[1] - e1[1] * e2[0];
    const auto fail_code = [](boundary_reason r) { return static_cast<std::uint8_t>(1 + static_cast<int>(r)); };
    // Constraints 1–4 and 6 per position box (a position box with several orientations comes
    // in a row: proven once).
    std::optional<position_box<I>> last_from;
    std::uint8_t last_code = 0;
    for (const classified_box<I>& b : from) {
        const bool valid = b.cls == box_class::valid;
        if (!valid && !keep_boundary) continue;
        classified_box<I> moved = b;
        for (std::size_t d = 0; d < 3; ++d)
            moved.box.position[d] = detail::translated(b.box.position[d], shift[static_cast<Eigen::Index>(d)], valid);
        std::uint8_t code = 0;
        if (valid) {
            total += six(b.box);
            for (std::size_t d = 0; d < 3; ++d) moved.box.position[d] = intersect(moved.box.position[d], search[d]);
            if (!(last_from && *last_from == b.box.position)) {
                last_from = b.box.position;
                const position_box<I>& p = moved.box.position;
                // Strictly in front of f's plane: the premise of the occlusion answer over `search`.
                const bool ahead =
                    !is_empty(p) && lower((p[0] - I(f.v[0].x())) * normal[0] + (p[1] - I(f.v[0].y())) * normal[1] +
                                          (p[2] - I(f.v[0].z())) * normal[2]) > 0.0;
                last_code = !ahead ? fail_code(boundary_reason::occlusion)
                            : detail::prove_position_set(set, p) != verdict::satisfied ? fail_code(boundary_reason::constraint)
                                                                                       : 0;
            }
            code = last_code;
        }
        out.push_back(std::move(moved));
        failed.push_back(code);
        source.push_back(&b);
    }
    // Constraint 5 per orientation box, over the hull of the positions it was found for. The
    // orientation stage certifies the boxes of a cell of ε_p over their hull, split at the
    // median while it fails (solver/orientation_schedule.hpp), and a proof over a position box
    // holds for every box inside it, while a proof over a smaller box may fail where the hull's
    // held (the centred form is not monotone in the box). So here too: the hull of the boxes
    // that share an orientation box, split at the median down to single boxes while it fails.
    std::map<std::array<double, 6>, std::vector<std::size_t>> by_orientation;
    for (std::size_t i = 0; i < out.size(); ++i) {
        if (out[i].cls != box_class::valid || failed[i]) continue;
        const auto& o = out[i].box.orientation;
        by_orientation[{lower(o[0]), upper(o[0]), lower(o[1]), upper(o[1]), lower(o[2]), upper(o[2])}].push_back(i);
    }
    std::size_t certifications = 0;
    const auto prove = [&](auto& self, std::span<std::size_t> members) -> void {
        position_box<I> h = out[members.front()].box.position;
        for (std::size_t i : members) h = hull(h, out[i].box.position);
        if (certify_fov_tiled(fov_position<I>(h, f), out[members.front()].box.orientation, frustum, tiling_budget,
                              certifications))
            return;
        if (members.size() == 1) {
            failed[members.front()] = fail_code(boundary_reason::field_of_view);
            return;
        }
        const std::size_t k = widest_dimension(h);
        const auto half = members.begin() + static_cast<std::ptrdiff_t>(members.size() / 2);
        std::nth_element(members.begin(), half, members.end(), [&](std::size_t a, std::size_t b) {
            return mid(out[a].box.position[k]) < mid(out[b].box.position[k]);
        });
        self(self, members.first(members.size() / 2));
        self(self, members.subspan(members.size() / 2));
    };
    for (auto& [key, members] : by_orientation) prove(prove, members);

    translated_boxes<I> result;
    double lost = 0.0;
    for (std::size_t i = 0; i < out.size(); ++i) {
        if (!failed[i]) {
            result.valid += out[i].cls == box_class::valid;
            continue;
        }
        lost += six(source[i]->box);
        ++result.unproven;
        const auto reason = static_cast<boundary_reason>(failed[i] - 1);
        ++result.unproven_reasons[static_cast<std::size_t>(reason)];
        out[i].cls = box_class::boundary;
        out[i].reason = reason;
        for (std::size_t d = 0; d < 3; ++d)  // the translate's box, moved outward: it claims nothing
            out[i].box.position[d] =
                detail::translated(source[i]->box.position[d], shift[static_cast<Eigen::Index>(d)], false);
    }
    if (!(lost <= max_loss * total)) return std::nullopt;
    if (result.unproven > 0 && !keep_boundary)
        std::erase_if(out, [](const classified_box<I>& b) { return b.cls != box_class::valid; });
    result.boxes = std::move(out);
    return result;
}

}  // namespace certipose
