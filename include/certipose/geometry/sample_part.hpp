// certipose/geometry/sample_part.hpp — a procedural stand-in for the paper's sample part.
//
// The paper's case study (§6.3.2, §8) uses a machined block of 1145 vertices / 2298 faces with
// protrusions on its top surface, through-holes, and a facet of interest next to a protrusion
// so that occlusion matters. We cannot ship that CAD file, so `make_sample_part` builds a part
// of the same character, deterministically and without booleans: a 2.5D height field on a
// tensor-product grid. The grid lines include every feature boundary, so each cell is a hole
// (no material), plain block (0 .. thickness) or protrusion (0 .. thickness + protrusion
// height); the mesh is the cells' top and bottom squares plus vertical walls between cells of
// different height, every wall split at every z level. Cells share whole edges and walls
// share whole level segments, so the surface is closed, edge-manifold, outward-oriented and
// free of T-junctions and degenerate faces (features never touch, so no two cells of one
// height meet only diagonally). Defaults: a 0.30 × 0.20 × 0.05 m block centred at the origin
// in x, y with its bottom at z = 0 and top surface at z = 0.05; three protrusions 0.03 m tall
// (a central boss, a rib, a corner boss) and three rectangular through-holes (genus 3, like
// the paper's part); 1146 vertices / 2300 faces (the paper's: 1145 / 2298; a quad-split
// height field always has a multiple of 4 faces). The paper's Figure-5 box
// [−0.1, 0.1]² × [0.25, 0.3] m sits above it.
#pragma once

#include "certipose/error.hpp"
#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/interval/detail/fenv.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace certipose {

/// Size of the generated part (metres). Features keep their place relative to the block: their
/// x coordinates scale with length / 0.30 and their y coordinates with width / 0.20.
struct sample_part_options {
    double length = 0.30;             ///< x extent, centred at x = 0
    double width = 0.20;              ///< y extent, centred at y = 0
    double thickness = 0.05;          ///< block from z = 0 to z = thickness (the top surface)
    double protrusion_height = 0.03;  ///< protrusions rise this far above the top surface
    /// Refinement: grid cells are at most this long in x and y. The default gives 1146 vertices /
    /// 2300 faces (the paper's part: 1145 / 2298).
    double max_cell_size = 0.014;
};

/// The generated part and what the case study needs to know about it.
struct sample_part {
    triangle_mesh mesh;
    /// A top-surface facet (normal +z, z = thickness) sharing an edge with the central boss's
    /// west wall: occluded from part of the space above it, visible from the rest.
    std::size_t facet_of_interest;
    double volume;  ///< enclosed volume from the layout (not from the mesh), m³
    int genus;      ///< number of through-holes
};

namespace detail::sample {

/// An axis-aligned rectangle of the layout, metres for the default 0.30 × 0.20 block.
struct rect {
    double x0, x1, y0, y1;
};

// Features never touch each other or the outer boundary (see the header comment).
inline constexpr std::array<rect, 3> protrusions{{
    {0.01, 0.05, -0.03, 0.03},   // central boss; the facet of interest is west of it
    {-0.12, -0.03, 0.05, 0.07},  // rib
    {0.08, 0.12, -0.08, -0.04},  // corner boss
}};
inline constexpr std::array<rect, 3> holes{{
    {-0.11, -0.07, -0.06, -0.02},
    {0.08, 0.10, 0.03, 0.07},
    {0.02, 0.05, 0.05, 0.08},
}};

inline void require_positive(const char* field, double v) {
    if (!(v > 0.0) || !std::isfinite(v))
        throw invalid_argument(field, std::string("make_sample_part: ") + field +
                                          " must be finite and > 0, got " +
                                          detail::mesh::format(v));
}

/// Sorted breakpoints `lines`, each interval split into equal parts no longer than h.
inline std::vector<double> refine(std::vector<double> lines, double h) {
    std::sort(lines.begin(), lines.end());
    lines.erase(std::unique(lines.begin(), lines.end()), lines.end());
    std::vector<double> out{lines.front()};
    for (std::size_t k = 0; k + 1 < lines.size(); ++k) {
        const double a = lines[k], b = lines[k + 1];
        // The small slack keeps an interval of exactly h (up to rounding) in one cell.
        const auto parts = static_cast<std::size_t>(std::max(1.0, std::ceil((b - a) / h - 1e-9)));
        for (std::size_t m = 1; m < parts; ++m)
            out.push_back(a + (b - a) * static_cast<double>(m) / static_cast<double>(parts));
        out.push_back(b);
    }
    return out;
}

}  // namespace detail::sample

/// Builds the sample part (see the header comment). Deterministic: the same options give the
/// same vertices, faces and order. Throws certipose::invalid_argument naming the field for a
/// non-positive or non-finite option, or a max_cell_size so small the grid would exceed 10⁶
/// cells.
inline sample_part make_sample_part(const sample_part_options& opt = {}) {
    // The same part whatever rounding mode the caller holds (e.g. inside a rounding_guard).
    const detail::round_to_nearest_scope nearest{};
    using detail::sample::rect;
    detail::sample::require_positive("length", opt.length);
    detail::sample::require_positive("width", opt.width);
    detail::sample::require_positive("thickness", opt.thickness);
    detail::sample::require_positive("protrusion_height", opt.protrusion_height);
    detail::sample::require_positive("max_cell_size", opt.max_cell_size);
    const double sx = opt.length / 0.30, sy = opt.width / 0.20;
    if ((opt.length / opt.max_cell_size) * (opt.width / opt.max_cell_size) > 1e6)
        throw invalid_argument("max_cell_size", "make_sample_part: max_cell_size " +
                                                    detail::mesh::format(opt.max_cell_size) +
                                                    " would make more than 10^6 grid cells");
    const auto place = [&](const rect& r) {
        return rect{r.x0 * sx, r.x1 * sx, r.y0 * sy, r.y1 * sy};
    };

    // Grid lines: block outline and every feature edge, then refined.
    std::vector<double> xl{-opt.length / 2, opt.length / 2}, yl{-opt.width / 2, opt.width / 2};
    for (const auto* list : {&detail::sample::protrusions, &detail::sample::holes})
        for (const rect& r0 : *list) {
            const rect r = place(r0);
            xl.insert(xl.end(), {r.x0, r.x1});
            yl.insert(yl.end(), {r.y0, r.y1});
        }
    const std::vector<double> xs = detail::sample::refine(xl, opt.max_cell_size);
    const std::vector<double> ys = detail::sample::refine(yl, opt.max_cell_size);
    const std::size_t nx = xs.size() - 1, ny = ys.size() - 1;

    // Cell levels: 0 = no material (hole, or outside the block), 1 = block, 2 = protrusion.
    const std::array<double, 3> z{0.0, opt.thickness, opt.thickness + opt.protrusion_height};
    std::vector<int> level(nx * ny, 1);
    const auto inside = [](const rect& r, double x, double y) {
        return r.x0 < x && x < r.x1 && r.y0 < y && y < r.y1;
    };
    for (std::size_t i = 0; i < nx; ++i)
        for (std::size_t j = 0; j < ny; ++j) {
            const double xc = (xs[i] + xs[i + 1]) / 2, yc = (ys[j] + ys[j + 1]) / 2;
            for (const rect& r : detail::sample::protrusions)
                if (inside(place(r), xc, yc)) level[i * ny + j] = 2;
            for (const rect& r : detail::sample::holes)
                if (inside(place(r), xc, yc)) level[i * ny + j] = 0;
        }
    const auto cell_level = [&](std::ptrdiff_t i, std::ptrdiff_t j) {
        if (i < 0 || j < 0 || i >= static_cast<std::ptrdiff_t>(nx) ||
            j >= static_cast<std::ptrdiff_t>(ny))
            return 0;
        return level[static_cast<std::size_t>(i) * ny + static_cast<std::size_t>(j)];
    };

    // Vertices are created on first use, so the order is that of the face emission below.
    std::vector<Eigen::Vector3d> vertices;
    std::vector<std::int64_t> vertex_id((nx + 1) * (ny + 1) * 3, -1);
    const auto vtx = [&](std::size_t i, std::size_t j, int k) {
        auto& id = vertex_id[(i * (ny + 1) + j) * 3 + static_cast<std::size_t>(k)];
        if (id < 0) {
            id = static_cast<std::int64_t>(vertices.size());
            vertices.emplace_back(xs[i], ys[j], z[static_cast<std::size_t>(k)]);
        }
        return static_cast<std::uint32_t>(id);
    };
    std::vector<face_indices> faces;
    // Quad a b c d, counter-clockwise seen from outside, as triangles (a b c), (a c d).
    const auto quad = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
        faces.push_back({a, b, c});
        faces.push_back({a, c, d});
    };

    // The facet of interest: top face of the cell west of the central boss, at the boss's
    // mid-y; its first triangle (a b c) owns the edge b c on the boss's west wall.
    const rect boss = place(detail::sample::protrusions[0]);
    const std::size_t foi_i =
        static_cast<std::size_t>(std::find(xs.begin(), xs.end(), boss.x0) - xs.begin()) - 1;
    const double boss_mid_y = (boss.y0 + boss.y1) / 2;
    const std::size_t foi_j =
        static_cast<std::size_t>(std::upper_bound(ys.begin(), ys.end(), boss_mid_y) - ys.begin()) -
        1;
    std::size_t foi = 0;

    for (std::size_t i = 0; i < nx; ++i)
        for (std::size_t j = 0; j < ny; ++j) {
            const int l =
                cell_level(static_cast<std::ptrdiff_t>(i), static_cast<std::ptrdiff_t>(j));
            if (l == 0) continue;
            if (i == foi_i && j == foi_j) foi = faces.size();
            quad(vtx(i, j, l), vtx(i + 1, j, l), vtx(i + 1, j + 1, l), vtx(i, j + 1, l));  // top
            quad(vtx(i, j, 0), vtx(i, j + 1, 0), vtx(i + 1, j + 1, 0), vtx(i + 1, j, 0));  // bottom
        }
    // Walls on x = xs[i] between cells (i−1, j) and (i, j); they face the lower cell.
    for (std::size_t i = 0; i <= nx; ++i)
        for (std::size_t j = 0; j < ny; ++j) {
            const auto ii = static_cast<std::ptrdiff_t>(i), jj = static_cast<std::ptrdiff_t>(j);
            const int west = cell_level(ii - 1, jj), east = cell_level(ii, jj);
            for (int k = std::min(west, east); k < std::max(west, east); ++k) {
                if (west > east)  // outward = +x
                    quad(vtx(i, j, k), vtx(i, j + 1, k), vtx(i, j + 1, k + 1), vtx(i, j, k + 1));
                else  // outward = −x
                    quad(vtx(i, j, k), vtx(i, j, k + 1), vtx(i, j + 1, k + 1), vtx(i, j + 1, k));
            }
        }
    // Walls on y = ys[j] between cells (i, j−1) and (i, j).
    for (std::size_t j = 0; j <= ny; ++j)
        for (std::size_t i = 0; i < nx; ++i) {
            const auto ii = static_cast<std::ptrdiff_t>(i), jj = static_cast<std::ptrdiff_t>(j);
            const int south = cell_level(ii, jj - 1), north = cell_level(ii, jj);
            for (int k = std::min(south, north); k < std::max(south, north); ++k) {
                if (south > north)  // outward = +y
                    quad(vtx(i, j, k), vtx(i, j, k + 1), vtx(i + 1, j, k + 1), vtx(i + 1, j, k));
                else  // outward = −y
                    quad(vtx(i, j, k), vtx(i + 1, j, k), vtx(i + 1, j, k + 1), vtx(i, j, k + 1));
            }
        }

    double volume = opt.length * opt.width * opt.thickness;
    for (const rect& r0 : detail::sample::protrusions) {
        const rect r = place(r0);
        volume += (r.x1 - r.x0) * (r.y1 - r.y0) * opt.protrusion_height;
    }
    for (const rect& r0 : detail::sample::holes) {
        const rect r = place(r0);
        volume -= (r.x1 - r.x0) * (r.y1 - r.y0) * opt.thickness;
    }
    sample_part part{triangle_mesh(std::move(vertices), std::move(faces)), foi, volume,
                     static_cast<int>(detail::sample::holes.size())};
    // Guards the construction above: a layout change that broke manifoldness fails loudly here.
    validate_closed_manifold(part.mesh);
    return part;
}

}  // namespace certipose
