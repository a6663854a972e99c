// Shared by the solver test files: the sampling check of VALID boxes against every constraint
// with the independent evaluator and ray caster (verify/point_check.hpp), which decides close
// calls exactly. The solver tests are split over three translation units because
// each pipeline instantiation costs a lot to optimise at -O2 and two cores build them in parallel.
#pragma once
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <random>
#include <set>
#include <span>
#include <tuple>
#include <type_traits>

#include <Eigen/Geometry>

#include <certipose/bisection/round_robin.hpp>
#include <certipose/camera.hpp>
#include <certipose/geometry/sample_part.hpp>
#include <certipose/interval/boost_interval.hpp>
#include <certipose/interval/cgal_interval.hpp>
#include <certipose/io/read_mesh.hpp>
#include <certipose/occlusion/cgal_aabb_occlusion.hpp>
#include <certipose/occlusion/no_occlusion.hpp>
#include <certipose/solver/pose_solver.hpp>
#include <certipose/verify/point_check.hpp>

using namespace certipose;

namespace solver_test {

inline thin_lens_parameters design_camera_parameters() {
    return {.focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6, .max_blur_circle = 6.9e-6,
            .pixel_pitch = 3.45e-6, .width_px = 2448, .height_px = 2048};
}

inline const sample_part& part() {
    static const sample_part p = make_sample_part();
    return p;
}

struct sampling_report {
    std::size_t valid_boxes = 0, samples = 0, violations = 0;
    std::size_t corners = 0;      ///< of `samples`, box corners
    std::size_t exact = 0;        ///< of `samples`, poses a constraint of which needed the exact decision
    std::size_t undecidable = 0;  ///< of `samples`, poses on a boundary even the exact decision left open
};

/// The checker's view of a camera: K, image, distances, and the lens distortion of one that has it.
template <CameraModel Camera>
verify::camera_view view_of(const Camera& camera, distance_range range) {
    verify::camera_view v{camera.intrinsics(), camera.width_px(), camera.height_px(), range.min, range.max};
    if constexpr (requires { camera.distortion(); }) {
        const std::optional<brown_conrady> d(camera.distortion());
        if (d) v.distortion = d->opencv();
        v.margin_px = camera.margin_px();
    }
    return v;
}

/// The 8 corners of a position box (bit k of the index picks the upper bound on axis k).
template <class Box>
std::array<Eigen::Vector3d, 8> position_corners(const Box& position) {
    std::array<Eigen::Vector3d, 8> out;
    for (int k = 0; k < 8; ++k)
        out[static_cast<std::size_t>(k)] = {k & 1 ? upper(position[0]) : lower(position[0]),
                                            k & 2 ? upper(position[1]) : lower(position[1]),
                                            k & 4 ? upper(position[2]) : lower(position[2])};
    return out;
}

/// 8 random barycentric points (sight-line targets beside the vertices, edge midpoints, centroid).
inline std::vector<Eigen::Vector3d> random_barycentric(std::mt19937& rng) {
    std::vector<Eigen::Vector3d> bary;
    for (int k = 0; k < 8; ++k) {
        double a = std::uniform_real_distribution<double>(0, 1)(rng), b = std::uniform_real_distribution<double>(0, 1)(rng);
        if (a + b > 1) a = 1 - a, b = 1 - b;
        bary.emplace_back(1 - a - b, a, b);
    }
    return bary;
}

/// The VALID boxes of `r`, or `max_boxes` of them chosen at random (each equally likely).
template <class I>
std::vector<const classified_box<I>*> valid_boxes_of(const solve_result<I>& r, std::size_t max_boxes, std::mt19937& rng) {
    std::vector<const classified_box<I>*> chosen;
    for (const auto& cb : r.boxes)
        if (cb.cls == box_class::valid) chosen.push_back(&cb);
    if (chosen.size() > max_boxes) {
        std::shuffle(chosen.begin(), chosen.end(), rng);
        chosen.resize(max_boxes);
    }
    return chosen;
}

/// A facet of a part run (its index, its boxes and its VALID count) as a solve_result, for
/// check_valid_boxes.
template <class I>
solve_result<I> as_result(std::size_t facet, const std::vector<classified_box<I>>& boxes, std::size_t valid) {
    solve_result<I> r;
    r.facet_index = facet;
    r.boxes = boxes;
    r.stats.valid = valid;
    return r;
}

/// Samples `per_box` random poses in every VALID box, and its 64 corners, and checks them
/// against everything, all exactly: carved boxes touch a constraint boundary, and their corners
/// lie on it or within rounding of it, where only exact arithmetic tells a violation of a few
/// ulps from none (verify::exact_stats counts how many poses needed it).
/// With `max_boxes`, a random subset of that many VALID boxes (each equally likely) is checked.
template <class I, CameraModel Camera>
sampling_report check_valid_boxes(const solve_result<I>& r, const triangle_mesh& mesh, const Camera& camera,
                                  distance_range range, double min_view_angle, std::size_t per_box,
                                  std::uint32_t seed, bool with_corners = true,
                                  std::size_t max_boxes = static_cast<std::size_t>(-1)) {
    sampling_report rep;
    const facet& f = mesh.facet(r.facet_index);
    const auto all = verify::occluders::of(mesh, r.facet_index);
    const verify::camera_view view = view_of(camera, range);
    std::mt19937 rng(seed);
    const auto draw = [&](const I& x) { return std::uniform_real_distribution<double>(lower(x), upper(x))(rng); };
    const std::vector<Eigen::Vector3d> bary = random_barycentric(rng);
    const auto targets = verify::facet_targets(f, bary);
    const std::vector<const classified_box<I>*> chosen = valid_boxes_of(r, max_boxes, rng);
    for (const auto* chosen_box : chosen) {
        const auto& cb = *chosen_box;
        ++rep.valid_boxes;
        Eigen::AlignedBox3d region = f.bbox;
        region.extend(Eigen::Vector3d(lower(cb.box.position[0]), lower(cb.box.position[1]), lower(cb.box.position[2])));
        region.extend(Eigen::Vector3d(upper(cb.box.position[0]), upper(cb.box.position[1]), upper(cb.box.position[2])));
        const auto near = all.within(region);
        const auto count_exact = [&](const verify::exact_stats& st) {
            rep.exact += st.exact > 0;
            rep.undecidable += st.undecidable > 0;
        };
        const auto check = [&](const verify::pose& x) {
            verify::exact_stats st;
            const auto v = verify::check_pose(x, f, view, min_view_angle, &near, targets, {}, &st);
            ++rep.samples;
            count_exact(st);
            if (v.any()) {
                ++rep.violations;
                if (rep.violations <= 3)
                    MESSAGE("violation (" << v.describe() << ") at p = " << x.position.transpose() << ", angles "
                                          << x.phi << " " << x.gamma << " " << x.beta);
            }
        };
        for (std::size_t k = 0; k < per_box; ++k) {
            verify::pose x;
            for (int d = 0; d < 3; ++d) x.position[d] = draw(cb.box.position[d]);
            x.phi = draw(cb.box.orientation[0]);
            x.gamma = draw(cb.box.orientation[1]);
            x.beta = draw(cb.box.orientation[2]);
            check(x);
        }
        if (with_corners) {
            std::array<std::array<double, 2>, 6> bounds{};
            for (std::size_t d = 0; d < 3; ++d) {
                bounds[d] = {lower(cb.box.position[d]), upper(cb.box.position[d])};
                bounds[d + 3] = {lower(cb.box.orientation[d]), upper(cb.box.orientation[d])};
            }
            // The 64 corners: the position constraints (ray casting: the expensive part) once per
            // position corner, the field of view at each of its 8 orientation corners.
            const auto all_corners = verify::corners(bounds);
            for (std::size_t pc = 0; pc < 8; ++pc) {
                verify::exact_stats pos_st;
                const auto pos = verify::check_position(all_corners[pc].position, f, view.d_min, view.d_max,
                                                        min_view_angle, &near, targets, {}, &pos_st);
                for (std::size_t oc = 0; oc < 8; ++oc) {
                    const verify::pose& x = all_corners[pc + 8 * oc];
                    verify::violations v = pos;
                    verify::exact_stats st = pos_st;
                    v.fov = !verify::fov_ok(x, f, view, {}, &st);
                    ++rep.samples, ++rep.corners;
                    count_exact(st);
                    if (v.any()) {
                        ++rep.violations;
                        if (rep.violations <= 3)
                            MESSAGE("violation (" << v.describe() << ") at box corner p = " << x.position.transpose()
                                                  << ", angles " << x.phi << " " << x.gamma << " " << x.beta);
                    }
                }
            }
        }
    }
    return rep;
}

// ---- placement tolerance: the part moved -------------------------------------------------------
/// One rigid motion of the part: x ↦ R (x − c) + c + t.
struct motion {
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    Eigen::Vector3d t = Eigen::Vector3d::Zero(), c = Eigen::Vector3d::Zero();
    Eigen::Vector3d operator()(const Eigen::Vector3d& x) const { return R * (x - c) + c + t; }
};

/// A motion the tolerance admits. `extreme`: every translation at ±T_i and the rotation at ROT
/// (shrunk by 1e-9 so that rounding of the motion itself cannot step outside the tolerance). With
/// an axis: a turn about it by up to ±ROT, then a tilt by up to TILT about a random axis.
inline motion draw_motion(const resolved_placement& tol, std::mt19937& rng, bool extreme) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::normal_distribution<double> g;
    motion m;
    m.c = tol.datum;
    const double shrink = 1.0 - 1e-9;
    for (int i = 0; i < 3; ++i)
        m.t[i] = tol.translation[static_cast<std::size_t>(i)] * shrink * (extreme ? (u(rng) < 0 ? -1.0 : 1.0) : u(rng));
    Eigen::Vector3d axis(g(rng), g(rng), g(rng));
    axis.normalize();
    if (tol.axis) {
        const double turn = tol.rotation * shrink * (extreme ? (u(rng) < 0 ? -1.0 : 1.0) : u(rng));
        const double tip = tol.tilt * shrink * (extreme ? 1.0 : std::abs(u(rng)));
        m.R = Eigen::AngleAxisd(tip, axis).toRotationMatrix() * Eigen::AngleAxisd(turn, tol.axis->normalized()).toRotationMatrix();
        return m;
    }
    const double angle = tol.rotation * shrink * (extreme ? 1.0 : std::abs(u(rng)));
    m.R = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    return m;
}

inline facet moved_facet(const facet& f, const motion& m) {
    facet out;
    for (int i = 0; i < 3; ++i) out.v[static_cast<std::size_t>(i)] = m(f.v[static_cast<std::size_t>(i)]);
    const Eigen::Vector3d n = (out.v[1] - out.v[0]).cross(out.v[2] - out.v[0]);
    out.normal = n.normalized();
    out.area = n.norm() / 2;
    out.centroid = (out.v[0] + out.v[1] + out.v[2]) / 3;
    out.bbox = Eigen::AlignedBox3d(out.v[0]);
    out.bbox.extend(out.v[1]), out.bbox.extend(out.v[2]);
    return out;
}

struct placed_report {
    std::size_t valid_boxes = 0, samples = 0, violations = 0, occluded = 0, fov = 0, position = 0;
};

/// Samples every VALID box of `r` (up to `max_boxes`, chosen at random): `per_box` random poses,
/// each against `motions` random admitted motions, and the 64 corners, each against one extreme
/// motion — the part (and its facet) moved, the `fixed` meshes not.
template <class I, class Camera>
placed_report check_placed(const solve_result<I>& r, const triangle_mesh& mesh, const Camera& camera, distance_range range,
                           double min_view_angle, const resolved_placement& tol, std::span<const triangle_mesh> fixed,
                           std::size_t per_box, std::size_t motions, std::uint32_t seed,
                           std::size_t max_boxes = static_cast<std::size_t>(-1)) {
    placed_report rep;
    const facet& f = mesh.facet(r.facet_index);
    const auto part_rest = verify::occluders::of(mesh, r.facet_index);
    verify::occluders fixed_all;
    for (const triangle_mesh& m : fixed)
        for (std::size_t i = 0; i < m.num_faces(); ++i) fixed_all.triangles.push_back(m.facet(i).v);
    const verify::camera_view view = view_of(camera, range);
    std::mt19937 rng(seed);
    const auto draw = [&](const I& x) { return std::uniform_real_distribution<double>(lower(x), upper(x))(rng); };
    const std::vector<Eigen::Vector3d> bary = random_barycentric(rng);
    const std::vector<const classified_box<I>*> chosen = valid_boxes_of(r, max_boxes, rng);
    for (const auto* cbp : chosen) {
        const auto& box = cbp->box;
        ++rep.valid_boxes;
        Eigen::AlignedBox3d region = f.bbox;
        region.extend(Eigen::Vector3d(lower(box.position[0]), lower(box.position[1]), lower(box.position[2])));
        region.extend(Eigen::Vector3d(upper(box.position[0]), upper(box.position[1]), upper(box.position[2])));
        // Part triangles that may come into the region once moved.
        double far = 0;
        for (int k = 0; k < 8; ++k) far = std::max(far, (region.corner(static_cast<Eigen::AlignedBox3d::CornerType>(k)) - tol.datum).norm());
        Eigen::AlignedBox3d grown_region = region;
        const double reach =
            std::max({tol.translation[0], tol.translation[1], tol.translation[2]}) + (tol.rotation + tol.tilt) * far + 1e-9;
        grown_region.min().array() -= reach, grown_region.max().array() += reach;
        const auto part_near = part_rest.within(grown_region);
        const auto fixed_near = fixed_all.within(grown_region);
        const auto check = [&](const verify::pose& x, const motion& m) {
            verify::occluders scene = fixed_near;
            for (const auto& t : part_near.triangles) scene.triangles.push_back({m(t[0]), m(t[1]), m(t[2])});
            const facet g = moved_facet(f, m);
            const auto targets = verify::facet_targets(g, bary);
            const auto v = verify::check_pose(x, g, view, min_view_angle, &scene, targets);
            ++rep.samples;
            if (v.any()) {
                ++rep.violations;
                rep.occluded += v.occluded, rep.fov += v.fov;
                rep.position += v.on_facet || v.focus || v.backface || v.view_angle;
                if (rep.violations <= 3)
                    MESSAGE("violation (" << v.describe() << ") at p = " << x.position.transpose() << ", angles " << x.phi << " "
                                          << x.gamma << " " << x.beta << ", part moved by t = " << m.t.transpose());
            }
        };
        for (std::size_t k = 0; k < per_box; ++k) {
            verify::pose x;
            for (int d = 0; d < 3; ++d) x.position[d] = draw(box.position[static_cast<std::size_t>(d)]);
            x.phi = draw(box.orientation[0]), x.gamma = draw(box.orientation[1]), x.beta = draw(box.orientation[2]);
            for (std::size_t j = 0; j < motions; ++j) check(x, draw_motion(tol, rng, j % 2 == 1));
        }
        std::array<std::array<double, 2>, 6> bounds{};
        for (std::size_t d = 0; d < 3; ++d) {
            bounds[d] = {lower(box.position[d]), upper(box.position[d])};
            bounds[d + 3] = {lower(box.orientation[d]), upper(box.orientation[d])};
        }
        for (const verify::pose& x : verify::corners(bounds)) check(x, draw_motion(tol, rng, true));
    }
    return rep;
}

/// A deterministic facet a camera above the part can see: among facets facing up (normal z >
/// 0.7), the highest one (centroid z), lowest index on ties. (The largest upward facet is a bad
/// choice: on idler_riser it is a long sliver too long for any certified box at ε_p = 0.1 m.)
inline std::size_t upward_facet(const triangle_mesh& mesh) {
    std::size_t best = mesh.num_faces();
    for (std::size_t i = 0; i < mesh.num_faces(); ++i) {
        const facet& f = mesh.facet(i);
        if (f.normal.z() > 0.7 && (best == mesh.num_faces() || f.centroid.z() > mesh.facet(best).centroid.z() + 1e-9))
            best = i;
    }
    REQUIRE(best < mesh.num_faces());
    return best;
}

/// The default pipeline with another occlusion policy or interval type (pose_solver<> itself,
/// the precompiled instantiation, when both are the defaults).
template <class Occlusion, class I = boost_interval>
using default_solver = std::conditional_t<std::is_same_v<Occlusion, aabb_occlusion> && std::is_same_v<I, boost_interval>,
                                          pose_solver<>, pose_solver<with_occlusion<Occlusion, with_interval<I>>>>;

/// The VALID boxes of a result as exact bound tuples (to compare runs box for box).
template <class I>
std::set<std::array<double, 12>> valid_box_set(const solve_result<I>& r) {
    std::set<std::array<double, 12>> s;
    for (const auto& cb : r.boxes)
        if (cb.cls == box_class::valid) {
            std::array<double, 12> k{};
            for (int d = 0; d < 3; ++d) {
                k[2 * d] = lower(cb.box.position[d]), k[2 * d + 1] = upper(cb.box.position[d]);
                k[6 + 2 * d] = lower(cb.box.orientation[d]), k[7 + 2 * d] = upper(cb.box.orientation[d]);
            }
            s.insert(k);
        }
    return s;
}

}  // namespace solver_test

