// certipose/io/ply.hpp — a picture of a result for MeshLab and ParaView: the part, the facet of
// interest and the pose boxes as coloured solids in one ASCII PLY file (no CGAL, no JSON).
//
// What is drawn: the part mesh in grey (optional), the facet of interest in red (its own three
// vertices, so its colour does not bleed into the neighbouring faces), each box's POSITION box
// [x]×[y]×[z] as a solid of 12 outward-oriented triangles — VALID green, BOUNDARY yellow — and,
// optionally, a thin blue "needle" from each box centre along the optical axis of the
// orientation box's centre (R·ẑ, docs/conventions.md), i.e. where the camera points.
// Colours are stored twice, as uchar red/green/blue on the vertices AND on the faces, because
// the viewers read different ones: MeshLab shows vertex colours by default and reads face
// colours; ParaView's vtkPLYReader turns face colours into a cell array "RGB" and vertex colours
// into a point array "RGB" (colour by either, untick "Map Scalars" for the true colours). Faces
// are "property list uchar int vertex_indices", the one spelling every reader accepts.
// Coordinates are written with round-trip precision (in round-to-nearest, whatever rounding
// mode the caller holds). Files are written atomically.
#pragma once

#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"
#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/interval/detail/fenv.hpp"
#include "certipose/io/result_document.hpp"
#include "certipose/io/write_file.hpp"
#include "certipose/solver/result.hpp"

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace certipose {

/// An 8-bit colour.
struct rgb {
    std::uint8_t r = 0, g = 0, b = 0;
    friend bool operator==(const rgb&, const rgb&) = default;
};

/// What write_ply draws and in which colours.
struct ply_options {
    bool part = true;  ///< draw the part (all faces but the facet of interest)
    bool aim = false;  ///< draw a needle along each box's nominal optical axis
    /// Needle length in metres; 0 = automatic: 0.3 × the distance from the box centre to the
    /// facet centroid (so the needles of well-aimed boxes point a third of the way at it).
    double aim_length = 0.0;
    rgb part_colour{170, 170, 170};
    rgb facet_colour{220, 40, 40};
    rgb valid_colour{40, 190, 60};
    rgb boundary_colour{245, 205, 40};
    rgb aim_colour{40, 90, 230};
};

namespace detail::ply {

/// Triangles of a box whose corner k is (bit0 → x, bit1 → y, bit2 → z), counter-clockwise seen
/// from outside (normals point out of the box).
inline constexpr std::array<std::array<int, 3>, 12> box_triangles{{
    {0, 4, 6}, {0, 6, 2},  // −x
    {1, 3, 7}, {1, 7, 5},  // +x
    {0, 1, 5}, {0, 5, 4},  // −y
    {2, 6, 7}, {2, 7, 3},  // +y
    {0, 2, 3}, {0, 3, 1},  // −z
    {4, 5, 7}, {4, 7, 6},  // +z
}};

struct builder {
    std::string vertices, faces;
    std::size_t num_vertices = 0, num_faces = 0;

    static void colour(std::string& out, rgb c) {
        out += ' ' + std::to_string(c.r) + ' ' + std::to_string(c.g) + ' ' + std::to_string(c.b) + '\n';
    }
    std::size_t vertex(const Eigen::Vector3d& p, rgb c) {
        for (int k = 0; k < 3; ++k) {
            certipose::detail::append_double(vertices, p[k]);
            if (k < 2) vertices += ' ';
        }
        colour(vertices, c);
        return num_vertices++;
    }
    void face(std::size_t a, std::size_t b, std::size_t c, rgb col) {
        faces += "3 " + std::to_string(a) + ' ' + std::to_string(b) + ' ' + std::to_string(c);
        colour(faces, col);
        ++num_faces;
    }
    /// An axis-aligned box.
    void solid(const bounds_3d& b, rgb c) {
        std::array<Eigen::Vector3d, 8> corners;
        for (std::size_t k = 0; k < 8; ++k)
            for (std::size_t d = 0; d < 3; ++d) corners[k][static_cast<int>(d)] = b[d][(k >> d) & 1];
        solid(corners, c);
    }
    /// The whole file: header (with `comment`), vertices, faces.
    std::string text(const std::string& comment) const {
        std::string t = "ply\nformat ascii 1.0\n";
        t += "comment " + comment + "\n";
        t += "element vertex " + std::to_string(num_vertices) + "\n";
        t += "property double x\nproperty double y\nproperty double z\n";
        t += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
        t += "element face " + std::to_string(num_faces) + "\n";
        t += "property list uchar int vertex_indices\n";
        t += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
        t += "end_header\n";
        return t + vertices + faces;
    }
    /// A hexahedron from 8 corners in box_triangles' order.
    void solid(const std::array<Eigen::Vector3d, 8>& corners, rgb c) {
        const std::size_t first = num_vertices;
        for (const auto& p : corners) vertex(p, c);
        for (const auto& t : box_triangles) face(first + t[0], first + t[1], first + t[2], c);
    }
};

inline void require_finite_bounds(const bounds_3d& b, const std::string& path) {
    for (std::size_t i = 0; i < 3; ++i)
        if (!std::isfinite(b[i][0]) || !std::isfinite(b[i][1]) || !(b[i][0] <= b[i][1]))
            throw invalid_argument(path, "write_ply: " + path + "[" + std::to_string(i) +
                                             "] is not a finite non-empty interval");
}

}  // namespace detail::ply

/// The PLY text (see the header comment). Throws certipose::out_of_range("facet") if
/// `facet_index` is not a face of `mesh`, certipose::invalid_argument("boxes[i].position")
/// for a box with a non-finite or empty interval.
inline std::string ply_text(const triangle_mesh& mesh, std::size_t facet_index,
                            std::span<const box_record> boxes, const ply_options& opt = {}) {
    const certipose::facet& foi = mesh.facet(facet_index);
    const certipose::detail::round_to_nearest_scope nearest;  // plain geometry for the picture
    if (opt.aim && (!(opt.aim_length >= 0.0) || !std::isfinite(opt.aim_length)))
        throw invalid_argument("aim_length", "write_ply: aim_length must be finite and >= 0, got " +
                                                 detail::mesh::format(opt.aim_length));
    detail::ply::builder out;
    std::size_t valid = 0, boundary = 0;

    if (opt.part) {
        for (const auto& p : mesh.vertices()) out.vertex(p, opt.part_colour);
        for (std::size_t f = 0; f < mesh.num_faces(); ++f)
            if (f != facet_index) {
                const auto& t = mesh.faces()[f];
                out.face(t[0], t[1], t[2], opt.part_colour);
            }
    }
    const std::size_t fv = out.num_vertices;
    for (const auto& p : foi.v) out.vertex(p, opt.facet_colour);
    out.face(fv, fv + 1, fv + 2, opt.facet_colour);

    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const box_record& b = boxes[i];
        const std::string path = "boxes[" + std::to_string(i) + "]";
        detail::ply::require_finite_bounds(b.position, path + ".position");
        (b.cls == box_class::valid ? valid : boundary) += 1;
        out.solid(b.position, b.cls == box_class::valid ? opt.valid_colour : opt.boundary_colour);
    }

    if (opt.aim) {
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            const box_record& b = boxes[i];
            detail::ply::require_finite_bounds(b.orientation,
                                               "boxes[" + std::to_string(i) + "].orientation");
            Eigen::Vector3d centre;
            for (int d = 0; d < 3; ++d) centre[d] = 0.5 * b.position[d][0] + 0.5 * b.position[d][1];
            const double phi = 0.5 * b.orientation[0][0] + 0.5 * b.orientation[0][1];
            const double gamma = 0.5 * b.orientation[1][0] + 0.5 * b.orientation[1][1];
            // Optical axis R·ẑ of R = Rz(φ)·Rx(γ)·Rz(β) (docs/conventions.md#zxz-angles); β spins about it.
            const Eigen::Vector3d axis(std::sin(phi) * std::sin(gamma),
                                       -std::cos(phi) * std::sin(gamma), std::cos(gamma));
            double length = opt.aim_length;
            if (length == 0.0) length = 0.3 * (foi.centroid - centre).norm();
            // A thin square prism; (a, b, axis) is right-handed so box_triangles stay outward.
            const Eigen::Vector3d helper =
                std::abs(axis.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
            const Eigen::Vector3d a = helper.cross(axis).normalized();
            const Eigen::Vector3d c = axis.cross(a);
            const double w = 0.02 * length;
            std::array<Eigen::Vector3d, 8> corners;
            for (int k = 0; k < 8; ++k)
                corners[k] = centre + ((k & 1) ? w : -w) * a + ((k & 2) ? w : -w) * c +
                             ((k & 4) ? length : 0.0) * axis;
            out.solid(corners, opt.aim_colour);
        }
    }

    return out.text("certipose pose boxes for facet " + std::to_string(facet_index) + ": " + std::to_string(valid) +
                    " valid (green), " + std::to_string(boundary) + " boundary (yellow); facet red" +
                    (opt.part ? ", part grey" : "") + (opt.aim ? ", optical axes blue" : ""));
}

/// Writes ply_text(...) to `path` atomically. Throws certipose::io_error(path) on failure.
inline void write_ply(const std::filesystem::path& path, const triangle_mesh& mesh,
                      std::size_t facet_index, std::span<const box_record> boxes,
                      const ply_options& opt = {}) {
    write_file_atomically(path, ply_text(mesh, facet_index, boxes, opt));
}

/// The boxes of a result document (e.g. read back with read_result_json).
inline void write_ply(const std::filesystem::path& path, const triangle_mesh& mesh,
                      const result_document& d, const ply_options& opt = {}) {
    write_ply(path, mesh, d.facet.index, d.boxes, opt);
}

/// The boxes of a solver result.
template <Interval I>
void write_ply(const std::filesystem::path& path, const triangle_mesh& mesh,
               const solve_result<I>& r, const ply_options& opt = {}) {
    std::vector<box_record> boxes;
    boxes.reserve(r.boxes.size());
    for (const auto& b : r.boxes) boxes.push_back(to_record(b));
    write_ply(path, mesh, r.facet_index, boxes, opt);
}

}  // namespace certipose
