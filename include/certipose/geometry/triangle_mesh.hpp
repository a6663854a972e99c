// certipose/geometry/triangle_mesh.hpp — the validated triangle mesh every algorithm reads.
//
// `triangle_mesh` is an immutable indexed triangle set (vertices + faces) that is checked once,
// when it is built, so nothing downstream has to re-check it: at least one face, finite
// coordinates, face indices in range, three distinct indices per face and no degenerate face
// (the rule is in `triangle_mesh`'s comment). Each face's derived data — vertices, outward unit
// normal (right-hand rule v1 → v2 → v3, paper §2), centroid, bounding box, area — is computed
// once into a `certipose::facet`, which is what the constraints (docs/conventions.md) consume.
// Topology is NOT required by the constructor (a soup is a valid mesh); `validate_closed_manifold`
// is the check the occlusion policies call, and `welded` merges the duplicated vertices of STL
// soups. `scaled`, `translated` and `rescaled_to_diagonal` bring CAD units (the shared meshes
// are in inches-ish units) to metres. No CGAL here: the exact collinearity test uses
// Boost.Multiprecision integers.
#pragma once

#include "certipose/detail/config.hpp"
#include "certipose/detail/format.hpp"
#include "certipose/error.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <string>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

namespace certipose {

/// A face's vertex indices, counter-clockwise seen from outside (right-hand rule).
using face_indices = std::array<std::uint32_t, 3>;

/// Derived data of one triangular face (paper §2: vertices, outward normal; §6.2: centroid).
struct facet {
    std::array<Eigen::Vector3d, 3> v;  ///< v1, v2, v3 in face order
    Eigen::Vector3d normal;            ///< unit, (v2 − v1) × (v3 − v1) normalised
    Eigen::Vector3d centroid;          ///< (v1 + v2 + v3) / 3 — the paper's f_c
    Eigen::AlignedBox3d bbox;          ///< axis-aligned bounding box of the three vertices
    double area;                       ///< ‖(v2 − v1) × (v3 − v1)‖ / 2
};

/// Unvalidated vertices + faces, e.g. an STL triangle soup before welding.
struct triangle_soup {
    std::vector<Eigen::Vector3d> vertices;
    std::vector<face_indices> faces;
};

namespace detail::mesh {

/// Text of a double (certipose::detail::format_double) or a point, for error messages.
inline std::string format(double v) { return certipose::detail::format_double(v); }

inline std::string format(const Eigen::Vector3d& p) {
    return "(" + format(p.x()) + ", " + format(p.y()) + ", " + format(p.z()) + ")";
}

/// Exact test of (b − a) × (c − a) = 0 for double coordinates (Boost.Multiprecision integers;
/// defined at the end of this header, or in certipose::precompiled: detail/config.hpp).
bool exactly_collinear_exact(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// Filtered exact collinearity: one component of the double cross product whose magnitude
/// exceeds a bound on its rounding error proves non-collinearity; otherwise decide exactly.
/// The bound 8u·(|p| + |q|) is generous against the classical (3u + 16u²) of a 2×2
/// determinant of rounded differences (Shewchuk's orient2d); it assumes no underflow, so
/// tiny or non-finite terms also go to the exact path.
inline bool exactly_collinear(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const Eigen::Vector3d& c) {
    constexpr double u = std::numeric_limits<double>::epsilon() / 2;
    const Eigen::Vector3d d1 = b - a, d2 = c - a;
    for (int k = 0; k < 3; ++k) {
        const int i = (k + 1) % 3, j = (k + 2) % 3;
        const double p = d1[i] * d2[j], q = d1[j] * d2[i];
        const double sum = std::abs(p) + std::abs(q);
        if (!std::isfinite(sum) || sum < 1e-280) continue;
        if (std::abs(p - q) > 8.0 * u * sum) return false;
    }
    return exactly_collinear_exact(a, b, c);
}

/// Undirected-edge key (min, max) and directed key (from, to) as one 64-bit integer.
inline std::uint64_t edge_key(std::uint32_t from, std::uint32_t to) noexcept {
    return (std::uint64_t{from} << 32) | to;
}

}  // namespace detail::mesh

/// A validated triangle mesh with per-face data precomputed.
///
/// Validation (each failure throws certipose::mesh_error whose message names the offending
/// vertex/face index and value): at least one vertex and one face; at most 2³²−1 vertices;
/// every coordinate finite; every face index < num_vertices(); the three indices of a face
/// distinct; no degenerate face. The degeneracy rule: a face is degenerate when its three
/// vertices are EXACTLY collinear (decided exactly from the double coordinates, so coincident
/// positions under different indices count too), or when its normal cannot be computed in
/// double (the cross product under/overflows to 0 or inf). Slivers that are not exactly
/// collinear are kept: their plane is well defined, and the constraints use the normal as
/// computed. Unreferenced vertices are allowed (they occur in OFF files); they count in
/// num_vertices() and bbox().
class triangle_mesh {
public:
    /// Validates and precomputes; throws certipose::mesh_error (see the class comment).
    triangle_mesh(std::vector<Eigen::Vector3d> vertices, std::vector<face_indices> faces)
        : vertices_(std::move(vertices)), faces_(std::move(faces)) {
        using detail::mesh::format;
        if (vertices_.empty() || faces_.empty())
            throw mesh_error("triangle_mesh: empty mesh (" + std::to_string(vertices_.size()) +
                             " vertices, " + std::to_string(faces_.size()) + " faces)");
        if (vertices_.size() > std::numeric_limits<std::uint32_t>::max())
            throw mesh_error("triangle_mesh: " + std::to_string(vertices_.size()) +
                             " vertices do not fit 32-bit face indices");
        for (std::size_t i = 0; i < vertices_.size(); ++i) {
            const Eigen::Vector3d& p = vertices_[i];
            for (int k = 0; k < 3; ++k)
                if (!std::isfinite(p[k]))
                    throw mesh_error("triangle_mesh: vertex " + std::to_string(i) +
                                     " has a non-finite coordinate " + "xyz"[k] + " = " +
                                     format(p[k]));
            bbox_.extend(p);
        }
        facets_.reserve(faces_.size());
        for (std::size_t f = 0; f < faces_.size(); ++f) {
            const face_indices& t = faces_[f];
            const std::string who = "triangle_mesh: face " + std::to_string(f);
            for (int k = 0; k < 3; ++k)
                if (t[k] >= vertices_.size())
                    throw mesh_error(who + " refers to vertex " + std::to_string(t[k]) +
                                     ", out of range (the mesh has " +
                                     std::to_string(vertices_.size()) + " vertices)");
            if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
                throw mesh_error(who + " repeats a vertex (" + std::to_string(t[0]) + ", " +
                                 std::to_string(t[1]) + ", " + std::to_string(t[2]) + ")");
            certipose::facet fc;
            fc.v = {vertices_[t[0]], vertices_[t[1]], vertices_[t[2]]};
            if (detail::mesh::exactly_collinear(fc.v[0], fc.v[1], fc.v[2]))
                throw mesh_error(who + " is degenerate: its vertices " + format(fc.v[0]) + ", " +
                                 format(fc.v[1]) + ", " + format(fc.v[2]) +
                                 " are collinear (zero area)");
            const Eigen::Vector3d cross = (fc.v[1] - fc.v[0]).cross(fc.v[2] - fc.v[0]);
            const double norm = cross.norm();
            if (!(norm > 0.0) || !std::isfinite(norm))
                throw mesh_error(who +
                                 " is degenerate: its normal is not representable in "
                                 "double (area " +
                                 format(norm / 2) + ")");
            fc.normal = cross / norm;
            fc.centroid = (fc.v[0] + fc.v[1] + fc.v[2]) / 3.0;
            fc.bbox.setEmpty();
            for (const auto& p : fc.v) fc.bbox.extend(p);
            fc.area = norm / 2;
            facets_.push_back(fc);
        }
    }

    /// Builds from a soup (same validation; nothing is welded — see `welded`).
    explicit triangle_mesh(triangle_soup soup)
        : triangle_mesh(std::move(soup.vertices), std::move(soup.faces)) {}

    const std::vector<Eigen::Vector3d>& vertices() const noexcept { return vertices_; }
    const std::vector<face_indices>& faces() const noexcept { return faces_; }
    const std::vector<certipose::facet>& facets() const noexcept { return facets_; }
    std::size_t num_vertices() const noexcept { return vertices_.size(); }
    std::size_t num_faces() const noexcept { return faces_.size(); }
    /// Bounding box of all vertices.
    const Eigen::AlignedBox3d& bbox() const noexcept { return bbox_; }

    /// Face i's data; throws certipose::out_of_range("facet", i, num_faces()) when i >= n.
    const certipose::facet& facet(std::size_t i) const {
        if (i >= facets_.size()) throw out_of_range("facet", i, facets_.size());
        return facets_[i];
    }

private:
    std::vector<Eigen::Vector3d> vertices_;
    std::vector<face_indices> faces_;
    std::vector<certipose::facet> facets_;
    Eigen::AlignedBox3d bbox_{};  // default-constructed AlignedBox is empty
};

// ---- topology ---------------------------------------------------------------------------------

namespace detail::mesh {

/// Empty string when every undirected edge is used by exactly two faces with opposite
/// orientations, i.e. every directed edge (a → b) occurs once and its twin (b → a) once;
/// otherwise a message naming the first offending edge (faces in order, edges v1v2, v2v3, v3v1).
inline std::string closed_manifold_violation(const triangle_mesh& m) {
    const auto& faces = m.faces();
    std::vector<std::uint64_t> directed;
    directed.reserve(3 * faces.size());
    for (const auto& t : faces)
        for (int k = 0; k < 3; ++k) directed.push_back(edge_key(t[k], t[(k + 1) % 3]));
    std::sort(directed.begin(), directed.end());
    const auto count = [&](std::uint64_t key) {
        const auto [lo, hi] = std::equal_range(directed.begin(), directed.end(), key);
        return static_cast<std::size_t>(hi - lo);
    };
    for (std::size_t f = 0; f < faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = faces[f][k], b = faces[f][(k + 1) % 3];
            const std::string edge = "edge (" + std::to_string(a) + ", " + std::to_string(b) +
                                     ") of face " + std::to_string(f);
            if (count(edge_key(a, b)) > 1)
                return edge +
                       " is traversed a → b by more than one face (non-manifold edge, "
                       "duplicate face or inconsistent orientation)";
            const std::size_t twins = count(edge_key(b, a));
            if (twins == 0)
                return edge +
                       " has no opposite face (open boundary, or the neighbour is "
                       "inconsistently oriented)";
            if (twins > 1)
                return edge + " has " + std::to_string(twins) +
                       " opposite faces (non-manifold edge)";
        }
    return {};
}

}  // namespace detail::mesh

/// True when every undirected edge is used by exactly two faces with opposite orientation
/// (closed, edge-manifold, consistently oriented). Vertex-manifoldness is not checked.
inline bool is_closed_manifold(const triangle_mesh& m) {
    return detail::mesh::closed_manifold_violation(m).empty();
}

/// Throws certipose::mesh_error naming the first offending edge unless is_closed_manifold(m).
/// Occlusion policies call it: the exact boolean and side-of tests need a closed volume.
inline void validate_closed_manifold(const triangle_mesh& m) {
    if (auto why = detail::mesh::closed_manifold_violation(m); !why.empty())
        throw mesh_error("mesh is not a closed manifold: " + why);
}

/// Number of distinct undirected edges.
inline std::size_t num_edges(const triangle_mesh& m) {
    std::vector<std::uint64_t> keys;
    keys.reserve(3 * m.num_faces());
    for (const auto& t : m.faces())
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = t[k], b = t[(k + 1) % 3];
            keys.push_back(detail::mesh::edge_key(std::min(a, b), std::max(a, b)));
        }
    std::sort(keys.begin(), keys.end());
    return static_cast<std::size_t>(std::unique(keys.begin(), keys.end()) - keys.begin());
}

/// V − E + F, counting only vertices some face uses. For a closed connected orientable
/// surface it is 2 − 2·genus.
inline long euler_characteristic(const triangle_mesh& m) {
    std::vector<bool> used(m.num_vertices(), false);
    for (const auto& t : m.faces())
        for (auto i : t) used[i] = true;
    const long v = static_cast<long>(std::count(used.begin(), used.end(), true));
    return v - static_cast<long>(num_edges(m)) + static_cast<long>(m.num_faces());
}

/// Signed enclosed volume Σ (v1 − o)·((v2 − o) × (v3 − o)) / 6 with o the bbox centre (less
/// cancellation than o = 0). Positive for a closed outward-oriented mesh; meaningless when
/// the mesh is not closed.
inline double signed_volume(const triangle_mesh& m) {
    const Eigen::Vector3d o = m.bbox().center();
    double sum = 0.0;
    for (const auto& f : m.facets()) sum += (f.v[0] - o).dot((f.v[1] - o).cross(f.v[2] - o));
    return sum / 6.0;
}

// ---- welding -----------------------------------------------------------------------------------

/// Merges vertices closer than `tolerance` (distance <= tolerance, up to rounding) and builds
/// the mesh. Clusters are the connected components of the "closer than tolerance" relation
/// (so a chain of near points merges even if its ends are farther apart); each cluster keeps
/// the coordinates of its lowest-index vertex, and output vertices keep the input order of
/// those representatives — with nothing to merge, indices are unchanged. Face order is
/// preserved, so facet ids still match the file. tolerance = 0 merges exactly coincident
/// vertices only (the usual STL soup). A face that welding collapses (two of its vertices
/// merge) is never dropped silently: certipose::mesh_error names the first one and the number
/// of such faces. A face that becomes collinear without collapsing also throws (triangle_mesh's
/// validation). Throws certipose::invalid_argument("tolerance") for a negative or non-finite
/// tolerance, or one below the double resolution of the coordinates (|x| / tolerance >= 2^50;
/// use 0 then), and mesh_error for non-finite coordinates.
inline triangle_mesh welded(const triangle_soup& soup, double tolerance) {
    using detail::mesh::format;
    if (!(tolerance >= 0.0) || !std::isfinite(tolerance))
        throw invalid_argument(
            "tolerance", "welded: tolerance must be finite and >= 0, got " + format(tolerance));
    const auto& pts = soup.vertices;
    const std::size_t n = pts.size();
    for (std::size_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k)
            if (!std::isfinite(pts[i][k]))
                throw mesh_error("welded: vertex " + std::to_string(i) +
                                 " has a non-finite coordinate " + "xyz"[k] + " = " +
                                 format(pts[i][k]));

    std::vector<std::size_t> parent(n);
    std::iota(parent.begin(), parent.end(), std::size_t{0});
    const auto find = [&](std::size_t i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    const auto unite = [&](std::size_t i, std::size_t j) {
        i = find(i), j = find(j);
        if (i != j) parent[std::max(i, j)] = std::min(i, j);  // root = lowest index
    };

    if (tolerance == 0.0) {
        // Exact duplicates: sort indices lexicographically by coordinates (-0 == +0).
        std::vector<std::size_t> order(n);
        std::iota(order.begin(), order.end(), std::size_t{0});
        const auto less = [&](std::size_t i, std::size_t j) {
            const auto &p = pts[i], &q = pts[j];
            return std::tie(p.x(), p.y(), p.z(), i) < std::tie(q.x(), q.y(), q.z(), j);
        };
        std::sort(order.begin(), order.end(), less);
        for (std::size_t k = 1; k < n; ++k)
            if (pts[order[k]] == pts[order[k - 1]]) unite(order[k], order[k - 1]);
    } else {
        // Hash grid with cells of 2·tolerance: two points within tolerance lie in the same or
        // adjacent cells even after rounding the quotient.
        const double cell = 2.0 * tolerance;
        double max_abs = 0.0;
        for (const auto& p : pts) max_abs = std::max(max_abs, p.cwiseAbs().maxCoeff());
        if (max_abs / cell >= 0x1p50)
            throw invalid_argument("tolerance",
                                   "welded: tolerance " + format(tolerance) +
                                       " is below the double resolution of coordinates up to " +
                                       format(max_abs) + "; use 0 to merge exact duplicates");
        struct key_hash {
            std::size_t operator()(const std::array<std::int64_t, 3>& k) const noexcept {
                std::uint64_t h = 1469598103934665603ull;
                for (auto c : k) h = (h ^ static_cast<std::uint64_t>(c)) * 1099511628211ull;
                return static_cast<std::size_t>(h);
            }
        };
        std::unordered_map<std::array<std::int64_t, 3>, std::vector<std::size_t>, key_hash> grid;
        const auto key_of = [&](const Eigen::Vector3d& p) {
            return std::array<std::int64_t, 3>{static_cast<std::int64_t>(std::floor(p.x() / cell)),
                                               static_cast<std::int64_t>(std::floor(p.y() / cell)),
                                               static_cast<std::int64_t>(std::floor(p.z() / cell))};
        };
        const double tol2 = tolerance * tolerance;
        for (std::size_t i = 0; i < n; ++i) {
            const auto k = key_of(pts[i]);
            for (std::int64_t dx = -1; dx <= 1; ++dx)
                for (std::int64_t dy = -1; dy <= 1; ++dy)
                    for (std::int64_t dz = -1; dz <= 1; ++dz) {
                        const auto it = grid.find({k[0] + dx, k[1] + dy, k[2] + dz});
                        if (it == grid.end()) continue;
                        for (std::size_t j : it->second)
                            if ((pts[i] - pts[j]).squaredNorm() <= tol2) unite(i, j);
                    }
            grid[k].push_back(i);
        }
    }

    // Representatives in input order get consecutive new indices.
    std::vector<std::uint32_t> new_index(n);
    std::vector<Eigen::Vector3d> out_vertices;
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t r = find(i);
        if (r == i) {
            new_index[i] = static_cast<std::uint32_t>(out_vertices.size());
            out_vertices.push_back(pts[i]);
        } else {
            new_index[i] = new_index[r];  // r < i: already numbered
        }
    }
    std::vector<face_indices> out_faces;
    out_faces.reserve(soup.faces.size());
    std::size_t collapsed = 0, first_collapsed = 0;
    for (std::size_t f = 0; f < soup.faces.size(); ++f) {
        face_indices t = soup.faces[f];
        const bool was_distinct = t[0] != t[1] && t[1] != t[2] && t[0] != t[2];
        for (auto& i : t) {
            if (i >= n)
                throw mesh_error("welded: face " + std::to_string(f) + " refers to vertex " +
                                 std::to_string(i) + ", out of range (the soup has " +
                                 std::to_string(n) + " vertices)");
            i = new_index[i];
        }
        if (was_distinct && (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]))
            if (collapsed++ == 0) first_collapsed = f;
        out_faces.push_back(t);
    }
    if (collapsed > 0)
        throw mesh_error("welded: welding at tolerance " + format(tolerance) + " collapses " +
                         std::to_string(collapsed) + " face(s), the first is face " +
                         std::to_string(first_collapsed) +
                         " (two of its vertices merge); use a smaller tolerance");
    return triangle_mesh(std::move(out_vertices), std::move(out_faces));
}

/// `welded` on an already valid mesh (e.g. an STL soup loaded without welding).
inline triangle_mesh welded(const triangle_mesh& m, double tolerance) {
    return welded(triangle_soup{m.vertices(), m.faces()}, tolerance);
}

// ---- transforms (tests, unit conversion) ------------------------------------------------------

/// Every coordinate multiplied by s (about the origin). Throws invalid_argument("scale") unless
/// s is finite and > 0 (a negative s would flip the orientation).
inline triangle_mesh scaled(const triangle_mesh& m, double s) {
    if (!(s > 0.0) || !std::isfinite(s))
        throw invalid_argument(
            "scale", "scaled: scale must be finite and > 0, got " + detail::mesh::format(s));
    std::vector<Eigen::Vector3d> v = m.vertices();
    for (auto& p : v) p *= s;
    return triangle_mesh(std::move(v), m.faces());
}

/// Every vertex moved by `offset`. Throws invalid_argument("offset") for a non-finite offset.
inline triangle_mesh translated(const triangle_mesh& m, const Eigen::Vector3d& offset) {
    if (!offset.allFinite())
        throw invalid_argument(
            "offset", "translated: offset must be finite, got " + detail::mesh::format(offset));
    std::vector<Eigen::Vector3d> v = m.vertices();
    for (auto& p : v) p += offset;
    return triangle_mesh(std::move(v), m.faces());
}

/// Scaled about the origin so that the bounding-box diagonal is `diagonal` (e.g. 0.3 m for the
/// shared CAD meshes). Throws invalid_argument("diagonal") unless it is finite and > 0.
inline triangle_mesh rescaled_to_diagonal(const triangle_mesh& m, double diagonal) {
    if (!(diagonal > 0.0) || !std::isfinite(diagonal))
        throw invalid_argument("diagonal",
                               "rescaled_to_diagonal: diagonal must be finite and > 0, got " +
                                   detail::mesh::format(diagonal));
    return scaled(m, diagonal / m.bbox().diagonal().norm());
}

}  // namespace certipose

// The exact fallback of the collinearity test, with Boost.Multiprecision (a few seconds of
// parsing per translation unit, which certipose::precompiled spares its users).
#if CERTIPOSE_DETAIL_WITH_DEFINITIONS
#include <boost/multiprecision/cpp_int.hpp>

namespace certipose::detail::mesh {

/// Exact test of (b − a) × (c − a) = 0 for double coordinates. Each double is m·2^e with an
/// integer m of at most 53 bits, so after scaling all nine coordinates by a common power of two
/// they are integers and the three 2×2 minors are evaluated exactly in cpp_int.
CERTIPOSE_DECL bool exactly_collinear_exact(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    const Eigen::Vector3d& c) {
    using boost::multiprecision::cpp_int;
    const std::array<const Eigen::Vector3d*, 3> pts{&a, &b, &c};
    std::array<std::int64_t, 9> mant{};
    std::array<int, 9> expo{};
    int emin = std::numeric_limits<int>::max();
    for (int i = 0; i < 9; ++i) {
        const double x = (*pts[i / 3])[i % 3];
        int e = 0;
        const double m = std::frexp(x, &e);  // x = m·2^e, 0.5 <= |m| < 1 (or m = 0)
        mant[i] = static_cast<std::int64_t>(std::ldexp(m, 53));  // exact: 53-bit integer
        expo[i] = e - 53;
        if (m != 0.0) emin = std::min(emin, expo[i]);
    }
    if (emin == std::numeric_limits<int>::max()) return true;  // all three points at 0
    std::array<cpp_int, 9> q;
    for (int i = 0; i < 9; ++i) {
        q[i] = mant[i];
        if (mant[i] != 0) q[i] <<= static_cast<unsigned>(expo[i] - emin);
    }
    const auto minor = [&](int i, int j) {  // component (i, j) minor of (b − a) × (c − a)
        const cpp_int bi = q[3 + i] - q[i], bj = q[3 + j] - q[j];
        const cpp_int ci = q[6 + i] - q[i], cj = q[6 + j] - q[j];
        return cpp_int(bi * cj - bj * ci);
    };
    return minor(0, 1) == 0 && minor(1, 2) == 0 && minor(2, 0) == 0;
}

}  // namespace certipose::detail::mesh
#endif  // CERTIPOSE_DETAIL_WITH_DEFINITIONS
