// certipose/verify/point_check.hpp — an independent check of one camera pose against every
// constraint of the inspection (1 not on the facet, 2 focus, 3 backface, 4 viewing angle, 5 field
// of view, 6 occlusion, by ray casting).
//
// This is deliberately NOT the certified code path: no intervals, no contractors, no CGAL — a
// second implementation written straight from the constraints, so that sampling random poses
// inside the boxes the solver calls VALID can catch a bug in the certified path (docs/testing.md).
// Carved boxes touch constraint boundaries, so their corners and some samples lie within
// rounding of one; the checks therefore decide every constraint exactly (verify/exact_check.hpp):
// plain doubles with an error bound for the ordinary pose, rationals and a 256-bit MPFR
// enclosure only for the close calls, which an `exact_stats` counts. A nonzero `tolerance` still
// selects the old plain-double judgement that forgives small violations (for comparison only).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/verify/exact_check.hpp"

namespace certipose::verify {

/// One camera pose: position (metres) and ZXZ Euler angles (radians).
struct pose {
    Eigen::Vector3d position;
    double phi = 0, gamma = 0, beta = 0;
};

/// The camera as the check needs it. `distortion` holds OpenCV's coefficients (k1, k2, p1, p2,
/// k3, k4, k5, k6; all zero: none) and `margin_px` the pixels kept free along the image's edges.
struct camera_view {
    Eigen::Matrix3d K;
    double width_px, height_px;
    double d_min, d_max;
    std::array<double, 8> distortion{};
    double margin_px = 0;
};

/// Which constraints a pose violates (all false: the pose is valid).
struct violations {
    bool on_facet = false, focus = false, backface = false, view_angle = false, fov = false, occluded = false;
    bool any() const { return on_facet || focus || backface || view_angle || fov || occluded; }
    bool any_position() const { return on_facet || focus || backface || view_angle || occluded; }
    std::string describe() const {
        std::string s;
        const auto add = [&](bool b, const char* n) { if (b) s += (s.empty() ? "" : ", ") + std::string(n); };
        add(on_facet, "on_facet"), add(focus, "focus"), add(backface, "backface");
        add(view_angle, "view_angle"), add(fov, "fov"), add(occluded, "occluded");
        return s.empty() ? "none" : s;
    }
};

/// R(φ, γ, β) = Rz(φ)·Rx(γ)·Rz(β), written out independently of pose/rotation.hpp.
inline Eigen::Matrix3d zxz(double phi, double gamma, double beta) {
    const auto rz = [](double a) {
        Eigen::Matrix3d m;
        m << std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1;
        return m;
    };
    Eigen::Matrix3d rx;
    rx << 1, 0, 0, 0, std::cos(gamma), -std::sin(gamma), 0, std::sin(gamma), std::cos(gamma);
    return rz(phi) * rx * rz(beta);
}

/// Distance from p to triangle (a, b, c) by projection and edge clamping.
inline double point_triangle_distance(const Eigen::Vector3d& p, const std::array<Eigen::Vector3d, 3>& v) {
    const Eigen::Vector3d n = (v[1] - v[0]).cross(v[2] - v[0]).normalized();
    const Eigen::Vector3d proj = p - n * n.dot(p - v[0]);
    bool inside = true;
    for (int i = 0; i < 3; ++i) {
        const Eigen::Vector3d e = v[(i + 1) % 3] - v[i];
        if (n.dot(e.cross(proj - v[i])) < 0) inside = false;
    }
    if (inside) return std::abs(n.dot(p - v[0]));
    double best = INFINITY;
    for (int i = 0; i < 3; ++i) {
        const Eigen::Vector3d a = v[i], e = v[(i + 1) % 3] - v[i];
        const double t = std::clamp(e.dot(p - a) / e.squaredNorm(), 0.0, 1.0);
        best = std::min(best, (p - (a + t * e)).norm());
    }
    return best;
}

/// The plain-double test, kept to compare with (the checks use `segment_meets_triangle`).
/// Möller–Trumbore: does the open segment (p, q) cross triangle t? Hits within `end_slack` of
/// either end (in segment parameter) are ignored: the segment may touch the facet's own edges at
/// q, where neighbours of the facet meet it. With `edge_slack` > 0, hits within
/// that distance (in barycentric coordinates) of t's boundary are ignored too: a pose whose sight
/// line grazes a blocker's edge to within rounding is not called blocked (see `tolerance`).
inline bool segment_hits_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                                  const std::array<Eigen::Vector3d, 3>& t, double end_slack = 1e-9,
                                  double edge_slack = 0.0) {
    const Eigen::Vector3d d = q - p, e1 = t[1] - t[0], e2 = t[2] - t[0];
    if (edge_slack > 0.0) {
        // With a tolerance, division-free: the segment crosses t's plane transversally (both
        // ends off it by more than the slack, on either side) and passes each edge line of t on
        // the same side, each signed volume above the slack relative to its scale. Grazes (a
        // sight line through an edge or vertex of t, or along its plane, to within ~1e-9 of the
        // distances involved) are forgiven: plain doubles cannot tell which side they are on.
        const Eigen::Vector3d n = e1.cross(e2).normalized();
        const double dp = n.dot(p - t[0]), dq = n.dot(q - t[0]), reach = edge_slack * d.norm();
        if (std::abs(dp) <= reach || std::abs(dq) <= reach || (dp > 0) == (dq > 0)) return false;
        int side = 0;
        for (int i = 0; i < 3; ++i) {
            const Eigen::Vector3d a = t[i] - p, b = t[(i + 1) % 3] - p;
            const double vol = a.dot(b.cross(d)), scale = a.norm() * b.norm() * d.norm();
            if (std::abs(vol) <= edge_slack * scale) return false;
            const int s = vol > 0 ? 1 : -1;
            if (side != 0 && s != side) return false;
            side = s;
        }
        // The crossing point is inside t; the end slack keeps the segment's own ends out.
        const double tt = dp / (dp - dq);
        return tt > end_slack && tt < 1.0 - end_slack;
    }
    const Eigen::Vector3d h = d.cross(e2);
    const double a = e1.dot(h);
    if (std::abs(a) < 1e-300) return false;  // parallel (a grazing segment in the plane is ignored)
    const double f = 1.0 / a;
    const Eigen::Vector3d s = p - t[0];
    const double u = f * s.dot(h);
    if (u < edge_slack || u > 1.0 - edge_slack) return false;
    const Eigen::Vector3d qv = s.cross(e1);
    const double v = f * d.dot(qv);
    if (v < edge_slack || u + v > 1.0 - edge_slack) return false;
    const double tt = f * e2.dot(qv);
    return tt > end_slack && tt < 1.0 - end_slack;
}

/// Constraint 6 for one triangle, decided exactly: does the open segment (p, q) meet the closed
/// triangle t (touching an edge or a vertex counts, p and q themselves do not)? p and q are taken
/// as the exact points they are; counts close calls in `stats`.
inline bool segment_meets_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                                   const std::array<Eigen::Vector3d, 3>& t, exact_stats* stats = nullptr) {
    return exact::segment_meets(p, exact::literal_end(q), t, stats);
}

/// Scene triangles other than the facet of interest, for ray casting.
struct occluders {
    std::vector<std::array<Eigen::Vector3d, 3>> triangles;

    /// All faces of `part` except `facet_index`, plus every face of each extra mesh.
    static occluders of(const triangle_mesh& part, std::size_t facet_index,
                        std::span<const triangle_mesh> extra = {}) {
        occluders o;
        for (std::size_t i = 0; i < part.num_faces(); ++i)
            if (i != facet_index) o.triangles.push_back(part.facet(i).v);
        for (const auto& m : extra)
            for (std::size_t i = 0; i < m.num_faces(); ++i) o.triangles.push_back(m.facet(i).v);
        return o;
    }
    /// Only the triangles whose bounding box meets `region` (a cheap pre-filter for a batch of
    /// segments that all lie inside `region`).
    occluders within(const Eigen::AlignedBox3d& region) const {
        occluders o;
        for (const auto& t : triangles) {
            Eigen::AlignedBox3d b(t[0]);
            b.extend(t[1]), b.extend(t[2]);
            if (b.intersects(region)) o.triangles.push_back(t);
        }
        return o;
    }
    /// Does a triangle meet the open segment (p, q)? With `edge_slack` 0, decided exactly
    /// (segment_meets_triangle); with `edge_slack` > 0, the old plain-double test that forgives
    /// grazes of that size (segment_hits_triangle).
    bool blocks(const Eigen::Vector3d& p, const Eigen::Vector3d& q, double edge_slack = 0.0,
                exact_stats* stats = nullptr) const {
        if (edge_slack > 0.0) {
            for (const auto& t : triangles)
                if (segment_hits_triangle(p, q, t, 1e-9, edge_slack)) return true;
            return false;
        }
        return blocks(p, exact::literal_end(q), stats);
    }
    /// The same for a sight line to a point of the facet snapped by exact::snapped.
    bool blocks(const Eigen::Vector3d& p, const exact::sight_end& end, exact_stats* stats = nullptr) const {
        for (const auto& t : triangles)
            if (exact::segment_meets(p, end, t, stats)) return true;
        return false;
    }
};

/// Points of the facet used as sight-line targets: the vertices, edge midpoints, the centroid,
/// and `extra` caller-chosen barycentric samples.
inline std::vector<Eigen::Vector3d> facet_targets(const facet& f, std::span<const Eigen::Vector3d> extra_barycentric = {}) {
    std::vector<Eigen::Vector3d> pts{f.v[0], f.v[1], f.v[2], (f.v[0] + f.v[1]) / 2, (f.v[1] + f.v[2]) / 2,
                                     (f.v[2] + f.v[0]) / 2, f.centroid};
    for (const auto& b : extra_barycentric) pts.push_back(b[0] * f.v[0] + b[1] * f.v[1] + b[2] * f.v[2]);
    return pts;
}

/// How the checks judge a pose near a constraint boundary. 0 (the default): exactly, as the
/// constraint is written — no violation forgiven, none invented (exact_check.hpp). t > 0: the
/// old plain-double judgement, forgiving violations smaller than t relative to the quantities
/// compared (distances, the view-angle sine, pixel coordinates, barycentric coordinates of a
/// grazed blocker). It hides real violations of a few ulps; kept only to compare with.
struct tolerance {
    double relative = 0.0;
};

namespace detail {

/// The sight-line ends of `targets`, snapped to the facet v (exact::snapped). Callers check many
/// poses against one facet and one target list, so the last list is kept per thread.
inline const std::vector<exact::sight_end>& sight_ends(const std::array<Eigen::Vector3d, 3>& v,
                                                       std::span<const Eigen::Vector3d> targets) {
    thread_local std::array<Eigen::Vector3d, 3> facet_of;
    thread_local std::vector<exact::sight_end> ends;
    bool same = ends.size() == targets.size() && facet_of == v;
    for (std::size_t i = 0; same && i < targets.size(); ++i) same = ends[i].q == targets[i];
    if (!same) {
        facet_of = v;
        ends.clear();
        for (const auto& q : targets) ends.push_back(exact::snapped(v, q));
    }
    return ends;
}

/// The old plain-double judgement with a relative tolerance t > 0 (see `tolerance`).
inline violations forgiving_position_check(const Eigen::Vector3d& p, const facet& f, double d_min, double d_max,
                                           double min_view_angle, const occluders* scene,
                                           std::span<const Eigen::Vector3d> targets, double t) {
    violations r;
    const double dist = point_triangle_distance(p, f.v);
    r.on_facet = !(dist > 0.0);
    double far = 0;
    for (const auto& v : f.v) far = std::max(far, (p - v).norm());
    r.focus = dist < d_min * (1 - t) || far > d_max * (1 + t);
    const double scale = (p - f.v[0]).norm();
    r.backface = !((p - f.v[0]).dot(f.normal) > -t * scale);
    r.view_angle = (p - f.centroid).dot(f.normal) < (std::sin(min_view_angle) - t) * (p - f.centroid).norm();
    if (scene)
        for (const auto& q : targets)
            if (scene->blocks(p, q, t)) {
                r.occluded = true;
                break;
            }
    return r;
}

}  // namespace detail

/// Checks the position constraints (1–4 and, if `scene` is given, 6) at p, each
/// decided exactly (with `tol` > 0: the forgiving plain-double judgement). Sight lines go to the
/// points of the facet that `targets` stand for (exact::snapped). Close calls are counted in
/// `stats`.
inline violations check_position(const Eigen::Vector3d& p, const facet& f, double d_min, double d_max,
                                 double min_view_angle, const occluders* scene = nullptr,
                                 std::span<const Eigen::Vector3d> targets = {}, tolerance tol = {},
                                 exact_stats* stats = nullptr) {
    if (tol.relative > 0.0)
        return detail::forgiving_position_check(p, f, d_min, d_max, min_view_angle, scene, targets, tol.relative);
    violations r;
    const exact::position_decision d = exact::decide_position(p, f.v, d_min, d_max, min_view_angle, stats);
    r.on_facet = d.on_facet, r.focus = d.focus, r.backface = d.backface, r.view_angle = d.view_angle;
    if (scene && !targets.empty())
        for (const auto& end : detail::sight_ends(f.v, targets))
            if (scene->blocks(p, end, stats)) {
                r.occluded = true;
                break;
            }
    return r;
}

namespace detail {

/// Constraint 5 with lens distortion, in plain doubles and written from OpenCV's formula, not
/// from camera/distortion.hpp: a facet point q (camera coordinates) is seen when q_z > 0 and its
/// distorted pixel lies in [margin, w − margin] × [margin, h − margin]. A straight edge is not
/// straight in the distorted image, so the vertices are not enough: the check walks 16 points
/// per edge and a few interior points. The certified region keeps its proofs ~1e-6 of the image
/// away from the edge, so the 1e-9 px forgiven here is only round-off of this computation.
inline bool distorted_fov_ok(const pose& x, const facet& f, const camera_view& cam) {
    const Eigen::Matrix3d R = zxz(x.phi, x.gamma, x.beta);
    const auto& c = cam.distortion;
    constexpr double noise = 1e-9;
    const auto seen = [&](const Eigen::Vector3d& point) {
        const Eigen::Vector3d q = R.transpose() * (point - x.position);
        if (!(q.z() > 0.0)) return false;
        const double xn = q.x() / q.z(), yn = q.y() / q.z();
        const double r2 = xn * xn + yn * yn, r4 = r2 * r2, r6 = r4 * r2;
        const double radial = (1 + c[0] * r2 + c[1] * r4 + c[4] * r6) / (1 + c[5] * r2 + c[6] * r4 + c[7] * r6);
        const double xd = xn * radial + 2 * c[2] * xn * yn + c[3] * (r2 + 2 * xn * xn);
        const double yd = yn * radial + c[2] * (r2 + 2 * yn * yn) + 2 * c[3] * xn * yn;
        const double u = cam.K(0, 0) * xd + cam.K(0, 1) * yd + cam.K(0, 2);
        const double v = cam.K(1, 0) * xd + cam.K(1, 1) * yd + cam.K(1, 2);
        const double lo = cam.margin_px - noise;
        return u >= lo && v >= lo && u <= cam.width_px - lo && v <= cam.height_px - lo;
    };
    constexpr int per_edge = 16;
    for (int e = 0; e < 3; ++e)
        for (int k = 0; k < per_edge; ++k) {
            const double t = static_cast<double>(k) / per_edge;
            if (!seen((1 - t) * f.v[e] + t * f.v[(e + 1) % 3])) return false;
        }
    static constexpr std::array<std::array<double, 3>, 7> interior{{{1. / 3, 1. / 3, 1. / 3},
                                                                    {0.6, 0.2, 0.2},
                                                                    {0.2, 0.6, 0.2},
                                                                    {0.2, 0.2, 0.6},
                                                                    {0.45, 0.45, 0.1},
                                                                    {0.1, 0.45, 0.45},
                                                                    {0.45, 0.1, 0.45}}};
    for (const auto& b : interior)
        if (!seen(b[0] * f.v[0] + b[1] * f.v[1] + b[2] * f.v[2])) return false;
    return true;
}

}  // namespace detail

/// Constraint 5 (field of view): every vertex in front of the camera and inside the image,
/// decided exactly (with `tol` > 0: the forgiving plain-double judgement). With lens distortion
/// or an image margin, every point checked (vertices, edges, interior) is judged in plain doubles
/// through the distortion (detail::distorted_fov_ok).
inline bool fov_ok(const pose& x, const facet& f, const camera_view& cam, tolerance tol = {},
                   exact_stats* stats = nullptr) {
    if (cam.margin_px != 0.0 || cam.distortion != std::array<double, 8>{}) return detail::distorted_fov_ok(x, f, cam);
    if (!(tol.relative > 0.0))
        return exact::decide_fov(x.position, x.phi, x.gamma, x.beta, f.v, cam.K, cam.width_px, cam.height_px, stats);
    const Eigen::Matrix3d R = zxz(x.phi, x.gamma, x.beta);
    const double mu = tol.relative * cam.width_px, mv = tol.relative * cam.height_px;
    for (const auto& v : f.v) {
        const Eigen::Vector3d qc = R.transpose() * (v - x.position);
        if (!(qc.z() > 0.0)) return false;
        const Eigen::Vector3d uvw = cam.K * qc;
        const double u = uvw.x() / uvw.z(), w = uvw.y() / uvw.z();
        if (u < -mu || u > cam.width_px + mu || w < -mv || w > cam.height_px + mv) return false;
    }
    return true;
}

/// Every constraint at one pose.
inline violations check_pose(const pose& x, const facet& f, const camera_view& cam, double min_view_angle,
                             const occluders* scene = nullptr, std::span<const Eigen::Vector3d> targets = {},
                             tolerance tol = {}, exact_stats* stats = nullptr) {
    violations r = check_position(x.position, f, cam.d_min, cam.d_max, min_view_angle, scene, targets, tol, stats);
    r.fov = !fov_ok(x, f, cam, tol, stats);
    return r;
}

/// Positions drawn uniformly in the facet's bounding box grown by d_max that satisfy
/// constraints 1–4 and see 15 points of the facet (vertices, edge midpoints, centroid and 8 random
/// points) without a blocked sight line: an independent sample of the true inspection space of
/// the positions (constraint 5 is left out: the question is which positions, not which aims).
/// Stops after `wanted` positions or 400·wanted draws; `drawn` counts the draws.
struct position_sample {
    std::vector<Eigen::Vector3d> valid;
    std::size_t drawn = 0;
};
inline position_sample sample_valid_positions(const triangle_mesh& mesh, std::size_t facet_index, double d_min,
                                              double d_max, double min_view_angle, std::size_t wanted,
                                              std::uint32_t seed) {
    const facet& f = mesh.facet(facet_index);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<Eigen::Vector3d> bary;
    for (int k = 0; k < 8; ++k) {
        double a = u(rng), b = u(rng);
        if (a + b > 1) a = 1 - a, b = 1 - b;
        bary.emplace_back(1 - a - b, a, b);
    }
    const auto targets = facet_targets(f, bary);
    const auto scene = occluders::of(mesh, facet_index);
    const Eigen::Vector3d lo = f.bbox.min().array() - d_max, hi = f.bbox.max().array() + d_max;
    position_sample out;
    while (out.valid.size() < wanted && out.drawn < 400 * wanted) {
        ++out.drawn;
        const Eigen::Vector3d p(lo.x() + u(rng) * (hi.x() - lo.x()), lo.y() + u(rng) * (hi.y() - lo.y()),
                                lo.z() + u(rng) * (hi.z() - lo.z()));
        if (check_position(p, f, d_min, d_max, min_view_angle).any()) continue;  // cheap constraints first
        if (check_position(p, f, d_min, d_max, min_view_angle, &scene, targets).any()) continue;
        out.valid.push_back(p);
    }
    return out;
}

/// The 64 corners of a 6D box given by its bounds (x, y, z, φ, γ, β as [lower, upper]).
inline std::array<pose, 64> corners(const std::array<std::array<double, 2>, 6>& b) {
    std::array<pose, 64> out{};
    for (std::size_t k = 0; k < 64; ++k) {
        const auto at = [&](std::size_t d) { return b[d][(k >> d) & 1]; };
        out[k].position = Eigen::Vector3d(at(0), at(1), at(2));
        out[k].phi = at(3), out[k].gamma = at(4), out[k].beta = at(5);
    }
    return out;
}

}  // namespace certipose::verify
