// certipose/part/patches.hpp — patches: connected sets of facets that a part run certifies at
// once (part_options::patches; docs/part.md#patches).
//
// Every constraint is a statement about every point of the facet, so a pose box proven for each
// facet of a set is VALID for each of them: a patch is paved once, from its *seed* (its first
// selected member), and each VALID box of the seed is then proven for the other members with the
// solver's own proofs (pose_solver::certifier: constraints 1–6, placements included), a box that
// fails split and its halves proven, a few levels down. The pieces proven for every member are
// the patch's, and every member receives them. (Measured, docs/part.md#patches: these proofs cost
// more than paving each member, so patches are off by default; paving the conjunction itself is
// what would make them pay.)
//
// A member must not pay for its patch with much of its own space. The rule, in member order: a
// member joins when the seed's VALID boxes proven for it and for every member that joined before
// still hold at least (1 − max_loss) of the seed's VALID 6D volume; otherwise it is solved on
// its own, as without patches. A seed without a VALID box shares nothing: its members are all
// solved on their own.
//
// Patches come from the mesh: facets are grown into regions over shared edges from the lowest
// unlabelled index, a neighbour joining when its normal lies within `max_cone` of the region
// seed's, its vertices within `max_extent` / 2 of the seed's centroid, and (for a part read from
// CAD) it lies on the same CAD face. The regions depend on the mesh alone; a run's work items
// are the selected facets grouped by region, in the order of each region's first selected
// facet, so a run's output does not depend on threads, MPI ranks or where --resume continues.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"
#include "certipose/geometry/triangle_mesh.hpp"

namespace certipose {

/// How a part run groups facets into patches (part_options::patches).
struct patch_options {
    /// Certify patches of facets at once. Off: every facet is its own work item.
    bool enabled = false;
    /// Largest angle (radians) between a member's normal and its region seed's.
    double max_cone = 0.17;
    /// Largest diameter (metres) of a patch: its members lie within max_extent / 2 of the
    /// region seed's centroid. 0: a quarter of the narrower side of the image at d_min
    /// (part_solver resolves it), so that a patch fits easily in every image that holds one
    /// of its facets.
    double max_extent = 0.0;
    /// Most facets in a patch.
    std::size_t max_members = 64;
    /// The share of the seed's VALID 6D volume a member may cost its patch (see the header).
    double max_loss = 0.25;
    /// How many times a seed box not proven for a member is split, its halves proven again.
    std::size_t split_depth = 3;
    /// The CAD face of each facet (geometry/cad_faces.hpp), when known: a patch never spans
    /// two faces. Empty: regions come from the mesh alone.
    std::vector<std::uint32_t> faces{};

    void validate(std::size_t facets) const {
        const auto bad = [](const char* field, const std::string& what) {
            return invalid_argument(std::string("patches.") + field, "patch_options: patches." + std::string(field) + " " + what);
        };
        if (!(max_cone >= 0.0 && max_cone <= 3.15))
            throw bad("max_cone", "must be in [0, π] radians, got " + detail::format_double(max_cone));
        if (!(max_extent >= 0.0 && std::isfinite(max_extent)))
            throw bad("max_extent", "must be a finite length ≥ 0 (0: automatic), got " +
                                        detail::format_double(max_extent));
        if (max_members == 0) throw bad("max_members", "must be at least 1");
        if (split_depth > 8) throw bad("split_depth", "must be at most 8 (each level doubles the proofs), got " + std::to_string(split_depth));
        if (!(max_loss >= 0.0 && max_loss <= 1.0))
            throw bad("max_loss", "must be in [0, 1], got " + detail::format_double(max_loss));
        if (!faces.empty() && faces.size() != facets)
            throw bad("faces", "names the CAD face of " + std::to_string(faces.size()) +
                                   " facets, but the part has " + std::to_string(facets));
    }
};

/// The part's facets grown into regions (see the header comment): `region_of[f]` is facet f's.
struct patch_regions {
    std::vector<std::uint32_t> region_of;
    std::size_t count = 0;

    /// Regions of `mesh` under `options`, with `extent` the resolved max_extent (metres).
    static patch_regions grow(const triangle_mesh& mesh, const patch_options& options, double extent) {
        constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
        const std::size_t n = mesh.num_faces();
        patch_regions out;
        out.region_of.assign(n, none);
        // Edge adjacency: (edge key, facet) sorted by key; facets sharing a key are neighbours.
        std::vector<std::pair<std::uint64_t, std::uint32_t>> edges;
        edges.reserve(3 * n);
        const auto& faces = mesh.faces();
        for (std::size_t f = 0; f < n; ++f)
            for (int k = 0; k < 3; ++k) {
                std::uint64_t a = faces[f][static_cast<std::size_t>(k)], b = faces[f][static_cast<std::size_t>((k + 1) % 3)];
                if (a > b) std::swap(a, b);
                edges.emplace_back((a << 32) | b, static_cast<std::uint32_t>(f));
            }
        std::sort(edges.begin(), edges.end());
        const auto edge_range = [&](std::uint64_t key) {
            return std::equal_range(edges.begin(), edges.end(), std::pair<std::uint64_t, std::uint32_t>{key, 0},
                                    [](const auto& x, const auto& y) { return x.first < y.first; });
        };
        const double cos_cone = std::cos(options.max_cone), radius = extent / 2;
        std::vector<std::uint32_t> queue;
        for (std::size_t s = 0; s < n; ++s) {
            if (out.region_of[s] != none) continue;
            const auto region = static_cast<std::uint32_t>(out.count++);
            const facet& seed = mesh.facet(s);
            out.region_of[s] = region;
            std::size_t members = 1;
            queue.assign(1, static_cast<std::uint32_t>(s));
            const auto joins = [&](std::size_t g) {
                if (!options.faces.empty() && options.faces[g] != options.faces[s]) return false;
                const facet& x = mesh.facet(g);
                if (!(x.normal.dot(seed.normal) >= cos_cone)) return false;  // NaN normals: never
                for (const auto& v : x.v)
                    if (!((v - seed.centroid).norm() <= radius)) return false;
                return true;
            };
            for (std::size_t q = 0; q < queue.size() && members < options.max_members; ++q) {
                const auto& t = faces[queue[q]];
                for (int k = 0; k < 3 && members < options.max_members; ++k) {
                    std::uint64_t a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
                    if (a > b) std::swap(a, b);
                    const auto [lo, hi] = edge_range((a << 32) | b);
                    for (auto it = lo; it != hi && members < options.max_members; ++it) {
                        const std::uint32_t g = it->second;
                        if (out.region_of[g] != none || !joins(g)) continue;
                        out.region_of[g] = region;
                        ++members;
                        queue.push_back(g);
                    }
                }
            }
        }
        return out;
    }
};

/// A run's work items: the facets in the order the sink receives them, and where each item
/// ends in that order (an item is [end of the previous, end)).
struct work_plan {
    std::vector<std::size_t> order;
    std::vector<std::size_t> ends;

    /// Every facet of `selection` its own item, in order.
    static work_plan per_facet(std::vector<std::size_t> selection) {
        work_plan p;
        p.order = std::move(selection);
        p.ends.resize(p.order.size());
        for (std::size_t i = 0; i < p.ends.size(); ++i) p.ends[i] = i + 1;
        return p;
    }

    /// The facets of `selection` grouped by region, each group in selection order, the groups
    /// in the order of their first facet. Grouping its own order again gives the same plan (a
    /// resumed run, an MPI chunk of whole items).
    static work_plan grouped(const std::vector<std::size_t>& selection, const patch_regions& regions) {
        std::vector<std::size_t> rank(regions.count, std::numeric_limits<std::size_t>::max());
        std::vector<std::size_t> position(selection.size());
        std::size_t groups = 0;
        for (std::size_t i = 0; i < selection.size(); ++i) {
            std::size_t& r = rank[regions.region_of[selection[i]]];
            if (r == std::numeric_limits<std::size_t>::max()) r = groups++;
            position[i] = r;
        }
        std::vector<std::size_t> index(selection.size());
        for (std::size_t i = 0; i < index.size(); ++i) index[i] = i;
        std::stable_sort(index.begin(), index.end(), [&](std::size_t a, std::size_t b) { return position[a] < position[b]; });
        work_plan p;
        p.order.reserve(selection.size());
        for (std::size_t k = 0; k < index.size(); ++k) {
            p.order.push_back(selection[index[k]]);
            if (k + 1 == index.size() || position[index[k + 1]] != position[index[k]]) p.ends.push_back(k + 1);
        }
        return p;
    }

    std::size_t items() const noexcept { return ends.size(); }
    std::size_t begin_of(std::size_t item) const noexcept { return item == 0 ? 0 : ends[item - 1]; }
    std::span<const std::size_t> members(std::size_t item) const noexcept {
        return std::span<const std::size_t>(order).subspan(begin_of(item), ends[item] - begin_of(item));
    }
};

}  // namespace certipose
