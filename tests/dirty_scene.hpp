// A synthetic CAD-like dirty mesh for the tests (tests/solver/dirty_mesh.cpp, and sanitized in
// tests/cgal/solve_once.cpp): a slab pierced by a box, a box with a prism standing face to face
// on it (sharing its top triangle's vertices), a duplicated shell and an open sheet between them.
#pragma once

#include <certipose/geometry/triangle_mesh.hpp>

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace dirty_test {

using certipose::face_indices;
using certipose::triangle_mesh;

/// Builds the scene; remembers where each body's faces start.
struct dirty_scene {
    std::vector<Eigen::Vector3d> v;
    std::vector<face_indices> f;
    std::size_t slab = 0, piercer = 0, base = 0, prism = 0, doubled = 0, doubled_copy = 0, sheet = 0;

    std::uint32_t vertex(double x, double y, double z) {
        v.emplace_back(x, y, z);
        return static_cast<std::uint32_t>(v.size() - 1);
    }
    /// An axis-aligned box, outward; returns its first face. Faces 2–3 are its top (4,5,7),(4,7,6).
    std::size_t box(Eigen::Vector3d lo, Eigen::Vector3d hi) {
        std::array<std::uint32_t, 8> id{};
        for (int k = 0; k < 8; ++k)
            id[k] = vertex(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z());
        const std::size_t first = f.size();
        const int faces[12][3] = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                                  {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
        for (const auto& t : faces) f.push_back({id[t[0]], id[t[1]], id[t[2]]});
        return first;
    }
};

inline dirty_scene make_dirty_scene() {
    dirty_scene s;
    s.slab = s.box({0, 0, 0}, {0.3, 0.3, 0.05});              // closed, clean
    s.piercer = s.box({0.1, 0.1, 0.02}, {0.2, 0.2, 0.12});    // overlaps the slab: its bottom is buried
    s.base = s.box({0.4, 0, 0}, {0.5, 0.1, 0.05});
    {  // a prism standing face to face on the base's top triangle (4,5,7), sharing its vertices
        const face_indices t = s.f[s.base + 2];
        std::array<std::uint32_t, 3> up{};
        for (int k = 0; k < 3; ++k) up[k] = s.vertex(s.v[t[k]].x(), s.v[t[k]].y(), 0.08);
        s.prism = s.f.size();
        s.f.push_back({up[0], up[1], up[2]});  // top
        s.f.push_back({t[0], t[2], t[1]});     // bottom: the base's face turned over
        for (int k = 0; k < 3; ++k) {
            const int n = (k + 1) % 3;
            s.f.push_back({t[k], t[n], up[n]});
            s.f.push_back({t[k], up[n], up[k]});
        }
    }
    s.doubled = s.box({0.4, 0.2, 0}, {0.5, 0.3, 0.05});
    s.doubled_copy = s.f.size();
    for (int k = 0; k < 12; ++k) s.f.push_back(s.f[s.doubled + static_cast<std::size_t>(k)]);  // a duplicated shell
    {  // an open sheet standing at x = 0.35
        const auto a = s.vertex(0.35, 0, 0), b = s.vertex(0.35, 0.3, 0), c = s.vertex(0.35, 0.3, 0.08),
                   d = s.vertex(0.35, 0, 0.08);
        s.sheet = s.f.size();
        s.f.push_back({a, b, c});
        s.f.push_back({a, c, d});
    }
    return s;
}

inline const dirty_scene& scene() {
    static const dirty_scene s = make_dirty_scene();
    return s;
}
inline const triangle_mesh& mesh() {
    static const triangle_mesh m(scene().v, scene().f);
    return m;
}

/// Inside a closed axis-aligned box (the checker's own test of "a camera in material").
inline bool inside_closed_body(const Eigen::Vector3d& p) {
    const auto in = [&](Eigen::Vector3d lo, Eigen::Vector3d hi) {
        return (p.array() > lo.array()).all() && (p.array() < hi.array()).all();
    };
    return in({0, 0, 0}, {0.3, 0.3, 0.05}) || in({0.1, 0.1, 0.02}, {0.2, 0.2, 0.12}) ||
           in({0.4, 0, 0}, {0.5, 0.1, 0.08}) || in({0.4, 0.2, 0}, {0.5, 0.3, 0.05});
}

}  // namespace dirty_test
