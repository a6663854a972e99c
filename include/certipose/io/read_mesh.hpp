// certipose/io/read_mesh.hpp — read OFF, OBJ, PLY or STL into a validated triangle_mesh (CGAL).
//
// `read_mesh` is how parts and occluders enter the library (DESIGN.md §6: certipose-solve
// reads OFF, OBJ, PLY or STL). Parsing is CGAL's (CGAL::IO::read_OFF / read_OBJ / read_PLY /
// read_STL, the readers behind read_polygon_soup); this header only chooses the reader from
// the extension (case-insensitive), turns every failure into a certipose exception naming the
// path, optionally welds and scales, and builds the triangle_mesh, whose validation rejects
// NaN/inf coordinates and degenerate faces. Polygons with more than three vertices are
// REJECTED, not triangulated: the face order of the file is kept exactly, so a facet index
// means the same face in the file, in MeshLab and in certipose's result JSON. STL soups need no
// welding tolerance: CGAL's STL reader already merges exactly coincident points. Needs
// certipose::cgal. The writer, write_mesh_off, is in certipose/io/write_mesh.hpp (no CGAL).
#pragma once

#include <certipose/detail/config.hpp>
#include <certipose/geometry/triangle_mesh.hpp>
#include <certipose/io/write_mesh.hpp>

#include <filesystem>
#include <optional>

namespace certipose {

/// Options of read_mesh.
struct read_options {
    /// Unset: no welding. Set: merge vertices closer than this, in FILE units (before `scale`);
    /// see `welded`. Throws invalid_argument("weld_tolerance") if negative or non-finite.
    std::optional<double> weld_tolerance{};
    /// Multiplies every coordinate after reading (e.g. 0.0254 for inches → metres).
    /// Throws invalid_argument("scale") unless finite and > 0.
    double scale = 1.0;
};

/// Reads a triangle mesh from `path` (.off, .obj, .ply or .stl, any letter case).
/// Throws certipose::io_error(path) when the extension is unknown, the file is missing or
/// unreadable, CGAL cannot parse it, or it holds no face; certipose::mesh_error (message
/// prefixed with the path) when a polygon is not a triangle or the mesh fails triangle_mesh's
/// validation or welding; certipose::invalid_argument for bad options. Faces keep file order.
triangle_mesh read_mesh(const std::filesystem::path& path, const read_options& opt = {});

}  // namespace certipose

// The definition (CGAL's readers), unless the certipose::precompiled library has it
// (detail/config.hpp).
#if CERTIPOSE_DETAIL_WITH_DEFINITIONS

#include "certipose/interval/detail/fenv.hpp"

#include <certipose/error.hpp>
#include <certipose/geometry/triangle_mesh.hpp>
#include <certipose/io/write_mesh.hpp>

#include <CGAL/IO/OBJ.h>
#include <CGAL/IO/OFF.h>
#include <CGAL/IO/PLY.h>
#include <CGAL/IO/STL.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

namespace certipose {

namespace detail::io {

/// Point type for CGAL's STL reader, which merges points through a std::map<Point, int>. With
/// CGAL's points (or std::array) a NaN compares equivalent to anything in that coordinate, so
/// a NaN vertex could silently merge into another vertex; this order is a strict weak order
/// that keeps NaN points apart (NaN after every number, NaNs equal), so triangle_mesh sees them.
struct stl_point {
    double c[3]{};
    double& operator[](std::size_t i) noexcept { return c[i]; }
    const double& operator[](std::size_t i) const noexcept { return c[i]; }
    friend bool operator<(const stl_point& a, const stl_point& b) noexcept {
        for (int i = 0; i < 3; ++i) {
            const bool na = std::isnan(a.c[i]), nb = std::isnan(b.c[i]);
            if (na || nb) {
                if (na != nb) return nb;
                continue;
            }
            if (a.c[i] < b.c[i]) return true;
            if (b.c[i] < a.c[i]) return false;
        }
        return false;
    }
};

inline std::string lowercase_extension(const std::filesystem::path& p) {
    std::string ext = p.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    return ext;
}

}  // namespace detail::io

CERTIPOSE_DECL triangle_mesh read_mesh(const std::filesystem::path& path, const read_options& opt) {
    // Decimal parsing and scaling must round to nearest even when the caller holds an interval
    // rounding_guard (upward, "0.3" would parse to the next double up).
    const detail::round_to_nearest_scope nearest{};
    const std::string name = path.string();
    if (!(opt.scale > 0.0) || !std::isfinite(opt.scale))
        throw invalid_argument("scale", "read_mesh: scale must be finite and > 0, got " +
                                            detail::mesh::format(opt.scale));
    if (opt.weld_tolerance &&
        (!(*opt.weld_tolerance >= 0.0) || !std::isfinite(*opt.weld_tolerance)))
        throw invalid_argument("weld_tolerance",
                               "read_mesh: weld_tolerance must be finite and >= 0, got " +
                                   detail::mesh::format(*opt.weld_tolerance));

    const std::string ext = detail::io::lowercase_extension(path);
    if (ext != ".off" && ext != ".obj" && ext != ".ply" && ext != ".stl")
        throw io_error(name, "read_mesh: unknown mesh format '" + path.extension().string() +
                                 "' of " + name + " (supported: .off, .obj, .ply, .stl)");
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw io_error(name, "read_mesh: no such file: " + name);
    if (!std::ifstream(path, std::ios::binary))
        throw io_error(name, "read_mesh: cannot open " + name);

    triangle_soup soup;
    std::vector<std::vector<std::size_t>> polygons;
    bool ok = false;
    try {
        if (ext == ".stl") {
            std::vector<detail::io::stl_point> points;
            ok = CGAL::IO::read_STL(name, points, polygons);
            soup.vertices.reserve(points.size());
            for (const auto& p : points) soup.vertices.emplace_back(p[0], p[1], p[2]);
        } else {
            std::vector<CGAL::Simple_cartesian<double>::Point_3> points;
            if (ext == ".off")
                ok = CGAL::IO::read_OFF(name, points, polygons);
            else if (ext == ".obj")
                ok = CGAL::IO::read_OBJ(name, points, polygons);
            else
                ok = CGAL::IO::read_PLY(name, points, polygons);
            soup.vertices.reserve(points.size());
            for (const auto& p : points) soup.vertices.emplace_back(p.x(), p.y(), p.z());
        }
    } catch (const std::exception& e) {  // e.g. bad_alloc on an absurd vertex count
        throw io_error(name, "read_mesh: cannot parse " + name + ": " + e.what());
    }
    const std::string format = ext.substr(1);
    if (!ok)
        throw io_error(name, "read_mesh: cannot parse " + name + " as " + format +
                                 " (malformed, truncated or an index out of range)");
    if (polygons.empty())
        throw io_error(name, "read_mesh: " + name + " contains no faces (empty, or not a " +
                                 format + " file)");

    soup.faces.reserve(polygons.size());
    for (std::size_t f = 0; f < polygons.size(); ++f) {
        const auto& poly = polygons[f];
        if (poly.size() != 3)
            throw mesh_error(name + ": face " + std::to_string(f) + " has " +
                             std::to_string(poly.size()) +
                             " vertices; only triangle meshes are supported (triangulate it "
                             "first, e.g. in MeshLab)");
        face_indices t{};
        for (int k = 0; k < 3; ++k) {
            if (poly[k] >= soup.vertices.size() ||
                poly[k] > std::numeric_limits<std::uint32_t>::max())
                throw mesh_error(name + ": face " + std::to_string(f) + " refers to vertex " +
                                 std::to_string(poly[k]) + ", out of range (the file has " +
                                 std::to_string(soup.vertices.size()) + " vertices)");
            t[k] = static_cast<std::uint32_t>(poly[k]);
        }
        soup.faces.push_back(t);
    }
    polygons.clear();

    try {
        triangle_mesh m =
            opt.weld_tolerance ? welded(soup, *opt.weld_tolerance) : triangle_mesh(std::move(soup));
        return opt.scale == 1.0 ? m : scaled(m, opt.scale);
    } catch (const mesh_error& e) {
        throw mesh_error(name + ": " + e.what());
    }
}

}  // namespace certipose

#endif  // CERTIPOSE_DETAIL_WITH_DEFINITIONS
