// Shared by the solver test files: the sampling check of VALID boxes against every constraint
// with the independent evaluator and ray caster (verify/point_check.hpp), which decides close
// calls exactly. The solver tests are split over three translation units because
// each pipeline instantiation costs a lot to optimise at -O2 and two cores build them in parallel.
#pragma once
#include <doctest/doctest.h>

#include <algorithm>
#include <random>
#include <set>
#include <tuple>
#include <type_traits>

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
    const verify::camera_view view{camera.intrinsics(), camera.width_px(), camera.height_px(), range.min, range.max};
    std::mt19937 rng(seed);
    const auto draw = [&](const I& x) { return std::uniform_real_distribution<double>(lower(x), upper(x))(rng); };
    std::vector<Eigen::Vector3d> bary;
    for (int k = 0; k < 8; ++k) {
        double a = std::uniform_real_distribution<double>(0, 1)(rng), b = std::uniform_real_distribution<double>(0, 1)(rng);
        if (a + b > 1) a = 1 - a, b = 1 - b;
        bary.emplace_back(1 - a - b, a, b);
    }
    const auto targets = verify::facet_targets(f, bary);
    std::vector<const classified_box<I>*> chosen;
    for (const auto& cb : r.boxes)
        if (cb.cls == box_class::valid) chosen.push_back(&cb);
    if (chosen.size() > max_boxes) {
        std::shuffle(chosen.begin(), chosen.end(), rng);
        chosen.resize(max_boxes);
    }
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

