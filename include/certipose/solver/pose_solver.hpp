// certipose/solver/pose_solver.hpp — the paper's Algorithm 3, assembled at compile time from
// policies: certified 6D camera pose boxes for one facet of a part.
//
//   using Solver = certipose::pose_solver<
//       certipose::boost_interval,              // interval type
//       certipose::thin_lens_camera,            // camera model
//       certipose::paper_position_constraints,  // position constraint set (class template over I)
//       certipose::hc4_contraction,             // contractor policy (wraps the set's HC4)
//       certipose::largest_first,               // bisector (constructible from ε_p)
//       certipose::aabb_occlusion,              // occlusion policy (built once per scene)
//       certipose::paper_orientation>;          // orientation policy
//   Solver solver(mesh, camera, task);
//   auto result = solver.solve(facet_id, {.position_eps = 0.1, .orientation_eps = 0.38});
//
// Stage 1 (lines 1–27) paves positions (solver/position_stage.hpp). Stage 2 (lines 28–36) asks
// the orientation policy for certified orientation boxes of each VALID position box; when it
// certifies none the position box is bisected (largest first) down to ε_p — halves of a
// certified position box stay certified for constraints 1–4 and 6, so only orientation is
// asked again — and a box that still fails at ε_p is reported BOUNDARY. BOUNDARY 6D boxes carry
// the whole orientation range (nothing was decided about aiming there).
//
// The default occlusion policy is `aabb_occlusion` (certified, CGAL): it is only declared here,
// so this header compiles without CGAL; include <certipose/occlusion/cgal_aabb_occlusion.hpp>
// (or <certipose/certipose_cgal.hpp>) to use the default, or pass `no_occlusion` /
// `boolean_occlusion` / your own policy. One solver may solve several facets, also from several
// threads at once: `solve` is const and every run owns its state.
#pragma once

#include <chrono>
#include <cstddef>
#include <numbers>
#include <span>
#include <utility>
#include <vector>

#include "certipose/detail/format.hpp"
#include "certipose/bisection/largest_first.hpp"
#include "certipose/camera/camera_model.hpp"
#include "certipose/camera/thin_lens_camera.hpp"
#include "certipose/constraints/paper_position_constraints.hpp"
#include "certipose/interval/boost_interval.hpp"
#include "certipose/occlusion/concept.hpp"
#include "certipose/orientation/concept.hpp"
#include "certipose/orientation/paper_orientation.hpp"
#include "certipose/solver/contraction.hpp"
#include "certipose/solver/position_stage.hpp"
#include "certipose/solver/result.hpp"
#include "certipose/solver/task.hpp"

namespace certipose {

class aabb_occlusion;  // occlusion/cgal_aabb_occlusion.hpp (needs certipose::cgal)

template <Interval I = boost_interval, CameraModel Camera = thin_lens_camera,
          template <class> class ConstraintSet = paper_position_constraints, class Contraction = hc4_contraction,
          class Bisector = largest_first, class Occlusion = aabb_occlusion, class Orientation = paper_orientation,
          class Buffer = depth_first>
class pose_solver {
public:
    using interval_type = I;
    using camera_type = Camera;
    using constraint_set_type = ConstraintSet<I>;
    using occlusion_type = Occlusion;
    using orientation_type = Orientation;

    /// Builds the occlusion policy for the scene (the part plus optional external occluders)
    /// once; validates the task. The mesh must outlive the solver.
    pose_solver(const triangle_mesh& part, Camera camera, inspection_task task,
                std::span<const triangle_mesh> occluders = {}, Orientation orientation = {})
        : pose_solver(part, std::move(camera), task, Occlusion(part, occluders), std::move(orientation)) {}

    /// With a ready occlusion policy (e.g. one shared by several solvers, or configured).
    pose_solver(const triangle_mesh& part, Camera camera, inspection_task task, Occlusion occlusion,
                Orientation orientation)
        : part_(&part), camera_(std::move(camera)), task_(task), occlusion_(std::move(occlusion)),
          orientation_(std::move(orientation)) {
        static_assert(PositionConstraintSet<ConstraintSet<I>, I>,
                      "pose_solver: ConstraintSet<I> must model PositionConstraintSet");
        static_assert(OcclusionPolicy<Occlusion, I>, "pose_solver: Occlusion must model OcclusionPolicy");
        static_assert(OrientationPolicy<Orientation, I, Camera>,
                      "pose_solver: Orientation must model OrientationPolicy");
        task_.validate();
        range_ = capped_distance_range(camera_, task_.max_metres_per_pixel);
        if (range_.empty())
            throw invalid_argument("max_metres_per_pixel",
                                   "pose_solver: the resolution requirement leaves no usable distance (d_max " +
                                       detail::format_double(range_.max) + " < d_min " + detail::format_double(range_.min) + ")");
        if (!std::isfinite(range_.max))
            throw invalid_argument("d_max", "pose_solver: the camera's usable distance is unbounded; set "
                                            "max_metres_per_pixel or use a camera with a finite d_max");
    }

    const Camera& camera() const noexcept { return camera_; }
    const inspection_task& task() const noexcept { return task_; }
    distance_range range() const noexcept { return range_; }
    const triangle_mesh& part() const noexcept { return *part_; }
    const Occlusion& occlusion() const noexcept { return occlusion_; }

    /// Certified pose boxes for facet `facet_index` (Algorithm 3). Throws out_of_range for a bad
    /// index and invalid_argument for bad options; budgets and cancellation end the run early
    /// with `stats.reason` saying why (boxes not reached are reported BOUNDARY, never VALID).
    solve_result<I> solve(std::size_t facet_index, const solve_options& options = {}) const {
        options.validate();
        using clock = std::chrono::steady_clock;
        const auto start = clock::now();
        const facet& f = part_->facet(facet_index);  // throws out_of_range("facet", ...)
        const position_problem problem{f, range_, task_};

        solve_result<I> out;
        out.facet_index = facet_index;
        solve_stats& st = out.stats;
        std::optional<clock::time_point> deadline;
        if (options.time_limit) deadline = start + *options.time_limit;
        const auto seconds = [&] { return std::chrono::duration<double>(clock::now() - start).count(); };

        // ---- stage 1: positions -------------------------------------------------------------
        paver_options popt;
        popt.max_boxes = options.max_boxes;
        popt.deadline = deadline;
        popt.record_tree = options.keep_tree;
        if (options.progress) {
            popt.progress_every = 256;
            popt.progress = [&](const paver_stats& s) {
                return options.progress(solve_progress{"position", s.boxes, s.pending, 0, 0, seconds()});
            };
        }
        auto stage1 = pave_positions<I, ConstraintSet<I>, Contraction, Bisector, Buffer>(
            problem, facet_index, occlusion_, popt, options.position_eps, options.stop);
        const auto& ps = stage1.boxes.stats;
        st.contractions = ps.contractions;
        st.bisections = ps.bisections;
        st.occlusion_tests = stage1.occlusion_tests;
        st.position_valid = stage1.boxes.valid.size();
        st.position_boundary = stage1.boxes.boundary.size() + stage1.boxes.pending.size();
        st.reason = ps.reason;
        st.seconds_position = seconds();
        if (options.keep_tree) out.tree = std::move(stage1.boxes.tree);

        for (const auto& b : stage1.boxes.boundary) push_boundary(out, b);
        for (const auto& b : stage1.boxes.pending) push_boundary(out, b);

        // ---- stage 2: orientations (Algorithm 3 lines 28–36) ----------------------------------
        Bisector bisector(options.position_eps);  // may be stateful (round_robin)
        std::vector<position_box<I>> todo(stage1.boxes.valid.rbegin(), stage1.boxes.valid.rend());
        std::size_t done = ps.boxes;
        while (!todo.empty()) {
            if (st.reason == termination::completed) {
                if (options.stop.stop_requested()) st.reason = termination::cancelled;
                else if (done >= options.max_boxes) st.reason = termination::box_budget;
                else if (deadline && clock::now() >= *deadline) st.reason = termination::deadline;
                else if (options.progress && done % 64 == 0 &&
                         !options.progress(solve_progress{"orientation", done, todo.size(), st.valid, st.boundary,
                                                          seconds()}))
                    st.reason = termination::cancelled;
            }
            position_box<I> p = std::move(todo.back());
            todo.pop_back();
            if (st.reason != termination::completed) {  // stopped: what is left stays undecided
                push_boundary(out, p);
                continue;
            }
            ++done;
            const orientation_result<I> o = orientation_.orient(p, f, camera_, options.orientation_eps);
            st.orientation_certifications += o.certifications;
            if (!o.boxes.empty()) {
                for (const auto& e : o.boxes) {
                    out.boxes.push_back(classified_box<I>{box_class::valid, pose_box<I>{p, e}});
                    ++st.valid;
                }
                continue;
            }
            const std::optional<split> s = bisector.choose(p);
            if (!s) {
                push_boundary(out, p);
                continue;
            }
            ++st.bisections;
            auto [left, right] = bisect_at(p, s->dimension, s->point);
            todo.push_back(std::move(right));
            todo.push_back(std::move(left));
        }
        st.seconds_orientation = seconds() - st.seconds_position;
        st.seconds = seconds();
        return out;
    }

private:
    /// An undecided box: the position box with every orientation (nothing decided about aim).
    static void push_boundary(solve_result<I>& out, const position_box<I>& p) {
        const rounding_guard<I> rounding;
        const double pi_hi = std::nextafter(std::numbers::pi, 4.0);
        const orientation_box<I> all = orientation_box<I>::from_bounds({{{-pi_hi, pi_hi}, {0.0, pi_hi}, {-pi_hi, pi_hi}}});
        out.boxes.push_back(classified_box<I>{box_class::boundary, pose_box<I>{p, all}});
        ++out.stats.boundary;
    }

    const triangle_mesh* part_;
    Camera camera_;
    inspection_task task_;
    Occlusion occlusion_;
    Orientation orientation_;
    distance_range range_{};
};

}  // namespace certipose
