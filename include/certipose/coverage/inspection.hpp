// certipose/coverage/inspection.hpp — which facets a 6D pose box inspects: C(B), the facets
// certified inspected from every pose of the box, and P(B) ⊇ C(B), the facets not proven
// impossible (docs/coverage.md).
//
// `facet_inspector` holds, for one solver (part, camera, task, occlusion scene), each facet's
// position constraint set, built the first time a box needs it. `inspect(box)` goes through the
// facets:
//  1. a cheap cull proves most of them impossible with plain geometry and wide margins: the ball
//     around the box is farther than d_max from the facet's bounding sphere, or nearer than
//     d_min to all of it, or wholly behind the facet's plane, or the facet's centroid is outside
//     every view the orientation box allows (every optical axis of the box lies within ρ of the
//     axis at its centre orientation; from anywhere in the ball the centroid is within
//     asin(r / distance) of its direction from the centre; a facet whose three vertices are in
//     the image has its centroid in it, at most the image-corner angle off the axis);
//  2. the facet's constraint set (constraints 1–4: its test, then its complement contraction)
//     and certify_fov (constraint 5) over the whole box: either violated → impossible; both
//     certified → step 3; otherwise possible;
//  3. the occlusion policy (constraint 6): VISIBLE, or no shadow of a possible blocker reaching
//     the box → the facet is in C(B); otherwise it stays in P(B) only. A policy that can refute
//     visibility with one sight line (RefutingOcclusionPolicy) is asked first whether the box's
//     centre sees the facet's centroid: on a large part most facets in view of a box are hidden
//     from it, and one segment query settles those at a fraction of the proof's cost.
// A face the occlusion survey found to duplicate an earlier one (a repeated shell of a CAD
// export, occlusion/mesh_survey.hpp) counts no area: it is seen as its original is, so every
// box certifying one certifies both, and the part's area would hold that surface twice.
// Steps 2–3 are the proofs `pose_solver::certify` uses, so a facet in C(B) is one the
// single-facet solver would certify for the box. An inspector owns its constraint sets and a
// cache of occlusion shadows, so it is not shared between threads: build one per thread.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Dense>

#include "certipose/constraints/concept.hpp"
#include "certipose/occlusion/concept.hpp"
#include "certipose/occlusion/mesh_survey.hpp"
#include "certipose/orientation/certify.hpp"
#include "certipose/pose/pose_box.hpp"
#include "certipose/solver/detail/box_certifier.hpp"
#include "certipose/solver/detail/carving.hpp"
#include "certipose/solver/pose_solver.hpp"
#include "certipose/solver/task.hpp"  // growth_options

namespace certipose {

/// What a pose box inspects: facet indices in increasing order, and their areas (m²).
struct facet_coverage {
    std::vector<std::size_t> certified;  ///< C(B): every constraint proven for every pose
    std::vector<std::size_t> possible;   ///< P(B) ⊇ C(B): not proven impossible
    double certified_area = 0, possible_area = 0;
};

/// Counters of an inspector (what each step decided, summed over calls).
struct inspection_stats {
    std::size_t boxes = 0, culled = 0, by_constraints = 0, by_field_of_view = 0, occlusion_tests = 0;
    std::size_t refuted_by_sight_line = 0;  ///< of the occlusion tests, those one sight line settled
};

template <class Policies = default_policies>
class facet_inspector {
public:
    using solver_type = pose_solver<Policies>;
    using interval_type = typename solver_type::interval_type;
    using constraint_set_type = typename solver_type::constraint_set_type;

    /// Prepares the facets' areas (0 for a duplicate face, see the header comment) and bounding
    /// spheres (each facet's constraint set is built when a box first needs it). `solver` must
    /// outlive the inspector.
    explicit facet_inspector(const solver_type& solver) : solver_(&solver), frustum_(solver.camera()) {
        const triangle_mesh& m = solver.part();
        const mesh_survey* survey = nullptr;
        if constexpr (requires { solver.occlusion().survey(); }) survey = solver.occlusion().survey();
        sets_.resize(m.num_faces());
        areas_.reserve(m.num_faces());
        for (std::size_t f = 0; f < m.num_faces(); ++f) {
            const facet& fa = m.facet(f);
            const bool duplicate = survey && f < survey->hidden.size() && survey->hidden[f] == hidden_facet::duplicate;
            areas_.push_back(duplicate ? 0.0 : fa.area);
            double r = 0;
            for (const auto& v : fa.v) r = std::max(r, (v - fa.centroid).norm());
            radius_.push_back(r);
        }
        // The largest angle between the optical axis and a ray through the image (a corner).
        // The certified image (camera_model.hpp): a distorted camera sees only its proven region.
        const pinhole_image image = certified_image(solver.camera());
        const Eigen::Matrix3d Kinv = image.K.inverse();
        for (const double u : {0.0, image.width_px})
            for (const double v : {0.0, image.height_px}) {
                const Eigen::Vector3d ray = Kinv * Eigen::Vector3d(u, v, 1.0);
                corner_angle_ = std::max(corner_angle_, std::atan2(ray.head<2>().norm(), ray.z()));
            }
    }
    /// A temporary solver would be destroyed before `inspect` reads it: refused at compile time.
    explicit facet_inspector(const solver_type&& solver) = delete;

    /// C(B) and P(B) for the 6D box (see the header comment). With `list_possible` false the
    /// facets of P(B) are not listed (its area is still summed): a plan keeps C(B) of every
    /// candidate, and P(B) is many times larger on a big part. Throws invalid_argument("box")
    /// for an empty or unbounded box.
    facet_coverage inspect(const pose_box<interval_type>& box, bool list_possible = true) {
        for (std::size_t k = 0; k < 3; ++k)
            if (is_empty(box.position[k]) || is_empty(box.orientation[k]) || !std::isfinite(lower(box.position[k])) ||
                !std::isfinite(upper(box.position[k])) || !std::isfinite(lower(box.orientation[k])) ||
                !std::isfinite(upper(box.orientation[k])))
                throw invalid_argument("box", "facet_inspector: the pose box must be finite and non-empty");
        ++stats_.boxes;
        facet_coverage out;
        const triangle_mesh& m = solver_->part();
        const view_cull cull = cull_of(box);
        for (std::size_t f = 0; f < m.num_faces(); ++f) {
            // 1. Cull.
            if (cull.out(m.facet(f), radius_[f])) {
                ++stats_.culled;
                continue;
            }
            switch (decide(box, f)) {
                case decision::certified:
                    out.certified.push_back(f);
                    out.certified_area += areas_[f];
                    [[fallthrough]];
                case decision::possible:
                    if (list_possible) out.possible.push_back(f);
                    out.possible_area += areas_[f];
                    break;
                case decision::impossible: break;
            }
        }
        return out;
    }

    /// The area of the facets of `sample` that the cull (step 1) keeps for `box` and that the
    /// box's centre sees at the task's viewing angle or steeper (constraint 4 at the centroid): a
    /// cheap estimate of C(B)'s area over a sample of the part (thinning orders candidates by it).
    /// Proves nothing: occlusion and the field of view are not asked.
    double view_estimate(const pose_box<interval_type>& box, const std::vector<std::size_t>& sample) const {
        const triangle_mesh& m = solver_->part();
        const view_cull cull = cull_of(box);
        const double sin_view = std::sin(solver_->task().min_view_angle);
        double area = 0;
        for (std::size_t f : sample) {
            const facet& fa = m.facet(f);
            const Eigen::Vector3d to_camera = cull.c - fa.centroid;
            if (!cull.out(fa, radius_[f]) && fa.normal.dot(to_camera) >= sin_view * to_camera.norm()) area += areas_[f];
        }
        return area;
    }

    /// Whether facet `f` is certified inspected from every pose of `box` (steps 2–3; no cull,
    /// which only ever rejects). Throws out_of_range for a facet beyond the part.
    bool certifies(const pose_box<interval_type>& box, std::size_t f) {
        if (f >= sets_.size()) throw out_of_range("facet", f, sets_.size());
        return !is_empty(box) && decide(box, f) == decision::certified;
    }

    /// The largest box found around the exact pose (x, y, z, φ, γ, β) from every pose of which
    /// each facet of `facets` stays certified (half-widths grown together in the proportions of
    /// `eps` = (ε_p, ε_o), then each on its own; solver/detail/growth.hpp). Nothing when the pose
    /// itself does not certify them all. Throws invalid_argument for a non-finite pose.
    std::optional<pose_box<interval_type>> largest_box_keeping(const std::array<double, 6>& pose,
                                                               const std::vector<std::size_t>& facets,
                                                               const growth_options& options = {},
                                                               std::array<double, 2> eps = {0.064, 0.32}) {
        options.validate();
        for (double v : pose)
            if (!std::isfinite(v))
                throw invalid_argument("pose", "facet_inspector: the pose must be finite, got " + detail::format_double(v));
        if (!(eps[0] > 0 && eps[1] > 0 && std::isfinite(eps[0]) && std::isfinite(eps[1])))
            throw invalid_argument("eps", "facet_inspector::largest_box_keeping: eps must be positive and finite");
        for (std::size_t f : facets)
            if (f >= sets_.size()) throw out_of_range("facet", f, sets_.size());
        const auto ok = [&](const pose_box<interval_type>& b) {
            for (std::size_t f : facets)
                if (!certifies(b, f)) return false;
            return true;
        };
        const std::array<double, 6> reference{eps[0], eps[0], eps[0], eps[1], eps[1], eps[1]};
        return detail::growth::largest_around<interval_type>(pose, ok, reference, detail::finest_steps(options, eps[0], eps[1]),
                                                             options.max_certifications);
    }

    /// Facet areas (m²), by facet index; 0 for a duplicate face.
    const std::vector<double>& areas() const noexcept { return areas_; }
    const solver_type& solver() const noexcept { return *solver_; }
    const inspection_stats& stats() const noexcept { return stats_; }

private:
    enum class decision { impossible, possible, certified };

    // Step 1 for one box: the box as a ball (centre c, radius r) and its orientations as a cone
    // of optical axes (a0, ρ); `out` proves a facet impossible with plain geometry and margins.
    struct view_cull {
        Eigen::Vector3d c, a0;
        double r = 0, rho = 0, corner_angle = 0;
        distance_range range;
        static constexpr double slack = 1e-6;  // radians and relative: far beyond double rounding

        bool out(const facet& fa, double radius) const {
            const Eigen::Vector3d d = fa.centroid - c;
            const double dist = d.norm();
            if (dist - r - radius > range.max * (1 + slack)) return true;           // too far
            if (dist + r + radius < range.min * (1 - slack)) return true;           // too near
            if (fa.normal.dot(c - fa.v[0]) < -r * (1 + slack)) return true;         // behind
            if (dist > r * (1 + slack)) {                                           // out of view
                const double angle = std::acos(std::clamp(a0.dot(d) / dist, -1.0, 1.0));
                return angle > rho + std::asin(std::min(1.0, r / dist)) + corner_angle + slack;
            }
            return false;
        }
    };

    view_cull cull_of(const pose_box<interval_type>& box) const {
        view_cull v;
        Eigen::Vector3d half;
        for (int k = 0; k < 3; ++k) {
            const auto& x = box.position[static_cast<std::size_t>(k)];
            v.c[k] = lower(x) + (upper(x) - lower(x)) / 2;
            half[k] = (upper(x) - lower(x)) / 2;
        }
        v.r = half.norm() * (1 + 1e-12) + 1e-12;
        const double phi = mid(box.orientation[0]), gamma = mid(box.orientation[1]);
        v.a0 = Eigen::Vector3d(std::sin(phi) * std::sin(gamma), -std::cos(phi) * std::sin(gamma), std::cos(gamma));
        // |d axis| ≤ |dγ| + sin γ |dφ| ≤ the half-widths in γ and φ (ZXZ: β only rolls).
        v.rho = (upper(box.orientation[1]) - lower(box.orientation[1])) / 2 +
                (upper(box.orientation[0]) - lower(box.orientation[0])) / 2;
        v.corner_angle = corner_angle_;
        v.range = solver_->range();
        return v;
    }

    // Steps 2–3 of the header comment for one facet.
    decision decide(const pose_box<interval_type>& box, std::size_t f) {
        // With a placement tolerance, the proofs cover every admitted placement, as the
        // solver's certifier does (solver/detail/box_certifier.hpp).
        const placement_scene* moving = solver_->placement_proofs();
        const facet& target = solver_->part().facet(f);
        const position_box<interval_type> in_part = moving ? camera_reach(box.position, moving->tolerance) : box.position;
        const std::array<double, 3> reach = moving ? facet_reach<interval_type>(target.v, moving->tolerance)
                                                   : std::array<double, 3>{};
        const verdict v = detail::prove_position_set(set(f), in_part);
        if (v == verdict::violated) {
            ++stats_.by_constraints;
            return decision::impossible;
        }
        // The box's sines and cosines (trig_) serve every facet it is asked about.
        const verdict fov = certify_fov(fov_position<interval_type>(moving ? grown(box.position, reach) : box.position, target),
                                        box.orientation, frustum_, trig_);
        if (fov == verdict::violated) {
            ++stats_.by_field_of_view;
            return decision::impossible;
        }
        if (v != verdict::satisfied || fov != verdict::satisfied) return decision::possible;
        ++stats_.occlusion_tests;
        if constexpr (RefutingOcclusionPolicy<typename solver_type::occlusion_type>) {
            if (const auto c = centre(in_part); c && sight_line_blocked(*c, f)) {
                ++stats_.refuted_by_sight_line;
                return decision::possible;
            }
        }
        // Bounded memory over many boxes: a new cache, since the shadow cache is append-only
        // (nothing here points into the old one past a single proof).
        if (cache_->size() > max_cached_shadows) cache_ = std::make_unique<detail::shadow_cache<interval_type>>();
        if (!detail::prove_visible(solver_->occlusion(), in_part, f, *cache_)) return decision::possible;
        if (moving && !sight_region_clear(box.position, target.v, target.normal, reach, moving->fixed))
            return decision::possible;
        return decision::certified;
    }

    // The policy's sight_line_blocked, with the triangle that blocked the last sight line as a
    // hint when the policy takes one (the same answer, often without a walk of its tree).
    bool sight_line_blocked(const Eigen::Vector3d& from, std::size_t f) {
        const auto& occlusion = solver_->occlusion();
        if constexpr (requires { occlusion.sight_line_blocked(from, f, sight_hint_); })
            return occlusion.sight_line_blocked(from, f, sight_hint_);
        else
            return occlusion.sight_line_blocked(from, f);
    }

    // A point of the box (each coordinate between its bounds); nothing for an unbounded box,
    // which the occlusion policy's proof then refuses.
    static std::optional<Eigen::Vector3d> centre(const position_box<interval_type>& p) {
        for (std::size_t k = 0; k < 3; ++k)
            if (!std::isfinite(lower(p[k])) || !std::isfinite(upper(p[k]))) return std::nullopt;
        return Eigen::Vector3d(mid(p[0]), mid(p[1]), mid(p[2]));
    }

    // Facet f's position constraint set, built the first time a box reaches step 2 for it: most
    // facets of a large part are culled by every box (a 10^6-face part would otherwise hold
    // gigabytes of sets it never uses).
    constraint_set_type& set(std::size_t f) {
        if (!sets_[f]) {
            const solver_type& s = *solver_;
            sets_[f] = std::make_unique<constraint_set_type>(make_constraint_set<constraint_set_type>(
                position_problem{s.part().facet(f), s.range(), s.task()}, s.constraints()));
        }
        return *sets_[f];
    }

    const solver_type* solver_;
    fov_frustum<interval_type> frustum_;
    std::vector<std::unique_ptr<constraint_set_type>> sets_;  // a pointer each: most stay empty
    std::vector<double> areas_, radius_;
    double corner_angle_ = 0;
    static constexpr std::size_t max_cached_shadows = std::size_t{1} << 16;
    std::unique_ptr<detail::shadow_cache<interval_type>> cache_ = std::make_unique<detail::shadow_cache<interval_type>>();
    std::size_t sight_hint_ = std::numeric_limits<std::size_t>::max();  // no triangle yet
    detail::orientation::angle_trig trig_;  // sines and cosines of the last box's angles (a cache by value)
    inspection_stats stats_;
};

}  // namespace certipose
