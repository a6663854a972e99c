// certipose/io/result_document.hpp — a solver result as plain doubles: exactly the content of
// the result JSON of docs/io.md (no JSON library, no CGAL).
//
// `result_document` is the bridge between the solver and the files that leave the library: it
// is what the JSON writer (io/json.hpp) writes, what the JSON reader returns, and what the PLY
// writer (io/ply.hpp) draws. Intervals become their [lower, upper] bounds — already rounded
// outward by the interval backend, and written back with round-trip precision, so a tool that
// reads the file checks exactly the boxes the library certified. The camera block records
// what the solver certified against: K, the image size and [d_min, d_max] AFTER the optional
// resolution cap (capped_distance_range), so a checker needs no camera model of its own.
#pragma once

#include "certipose/camera/camera_model.hpp"
#include "certipose/camera/distortion.hpp"
#include "certipose/geometry/triangle_mesh.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/io/scene_record.hpp"
#include "certipose/solver/result.hpp"
#include "certipose/solver/task.hpp"

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

namespace certipose {

/// [[l0, u0], [l1, u1], [l2, u2]]: a 3D box as interval bounds.
using bounds_3d = std::array<std::array<double, 2>, 3>;

/// One classified 6D pose box as plain doubles (docs/io.md, "boxes").
struct box_record {
    box_class cls = box_class::valid;
    bounds_3d position{};     ///< [x], [y], [z], metres
    bounds_3d orientation{};  ///< [φ], [γ], [β], radians (ZXZ, docs/conventions.md)
    /// BOUNDARY boxes: which constraint (or budget) left it undecided (JSON "undecided").
    std::optional<boundary_reason> reason{};
    friend bool operator==(const box_record&, const box_record&) = default;
};

/// The result JSON of docs/io.md, field by field.
struct result_document {
    struct facet_record {
        std::size_t index = 0;
        std::array<std::array<double, 3>, 3> vertices{};  ///< v1, v2, v3 (face order)
        std::array<double, 3> normal{};                   ///< outward unit normal
        friend bool operator==(const facet_record&, const facet_record&) = default;
    };
    struct camera_record {
        double width_px = 0, height_px = 0;
        std::array<std::array<double, 3>, 3> K{};  ///< rows of the intrinsic matrix
        double d_min = 0, d_max = 0;               ///< certified distances; d_max may be +inf
        /// The projection centre in the mount frame (axes: the camera's optical frame; origin: the
        /// mount point), metres: the camera JSON's "mount_offset"; zero when it gives none.
        std::array<double, 3> mount_offset{};
        /// The lens distortion the field of view was certified with ("distortion_coefficients"),
        /// and the image margin in pixels ("image_margin_px"); absent / 0 without.
        std::optional<brown_conrady> distortion{};
        double image_margin_px = 0;
        friend bool operator==(const camera_record&, const camera_record&) = default;
    };
    struct task_record {
        double min_view_angle = 0;
        std::optional<double> max_metres_per_pixel{};
        /// The part placement tolerance the boxes are certified for, its datum resolved
        /// ("placement_tolerance"; absent: the nominal placement).
        std::optional<placement_tolerance> placement{};
        friend bool operator==(const task_record&, const task_record&) = default;
    };
    struct settings_record {
        double position_eps = 0, orientation_eps = 0;
        /// carving's steps (false for the paper's paving): inner_contraction, occlusion_cuts, corner_boxes
        bool inner_contraction = true, occlusion_cuts = true, leaf_corner_boxes = true;
        std::size_t corner_depth = 1;  ///< carving::corner_depth (1 in files that do not give it)
        double corner_rest_min_pieces = 2;  ///< carving::rest_min_pieces (2 in files that do not give it)
        std::optional<double> refine_min_width{};               ///< set when the run refined below ε_p
        bool grow = false;                                      ///< the VALID boxes were widened
        friend bool operator==(const settings_record&, const settings_record&) = default;
    };

    facet_record facet;
    camera_record camera;
    task_record task;
    settings_record settings;
    std::vector<box_record> boxes;
    /// valid, boundary and seconds are the contract; the rest are the extra "stats" fields.
    solve_stats stats;
    /// The external occluders and camera regions of the run ("occluders", "keep_in",
    /// "keep_out"; io/scene_record.hpp): set by the program, empty from make_result_document.
    scene_record scene{};
};

/// Bounds of an interval box; an empty component gives NaN bounds (the writers reject them).
template <Interval I>
bounds_3d to_bounds(const interval_box<I, 3>& b) {
    bounds_3d r{};
    for (std::size_t i = 0; i < 3; ++i) r[i] = {lower(b[i]), upper(b[i])};
    return r;
}

template <Interval I>
box_record to_record(const classified_box<I>& b) {
    return {b.cls, to_bounds(b.box.position), to_bounds(b.box.orientation),
            b.cls == box_class::boundary ? std::optional<boundary_reason>(b.reason) : std::nullopt};
}

/// The camera record of a document (result JSON, summary.json, PLAN.json) from the camera a run
/// used: size, K, the certified distances for `task`, and the lens it was certified through (a
/// plan must not read boxes certified through another). The mount offset is the caller's.
template <CameraModel C>
result_document::camera_record describe_camera_record(const C& camera, const inspection_task& task) {
    result_document::camera_record rec;
    rec.width_px = camera.width_px();
    rec.height_px = camera.height_px();
    const Eigen::Matrix3d k = camera.intrinsics();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) rec.K[r][c] = k(r, c);
    const certipose::distance_range range = capped_distance_range(camera, task.max_metres_per_pixel);
    rec.d_min = range.min;
    rec.d_max = range.max;
    if constexpr (requires { camera.distortion(); }) {
        const std::optional<brown_conrady> dist(camera.distortion());
        if (dist && !dist->is_zero()) rec.distortion = dist;
    }
    if constexpr (requires { camera.margin_px(); }) rec.image_margin_px = camera.margin_px();
    return rec;
}

/// The document of one solver run. `mesh` must be the mesh that was solved (the facet is
/// mesh.facet(result.facet_index); throws certipose::out_of_range if that index is not in it),
/// `camera`, `task` and `options` the ones passed to the solver.
template <Interval I, CameraModel C>
result_document make_result_document(const solve_result<I>& result, const triangle_mesh& mesh,
                                     const C& camera, const inspection_task& task,
                                     const solve_options& options) {
    result_document d;
    const certipose::facet& f = mesh.facet(result.facet_index);
    d.facet.index = result.facet_index;
    for (int i = 0; i < 3; ++i) {
        for (int k = 0; k < 3; ++k) d.facet.vertices[i][k] = f.v[i][k];
        d.facet.normal[i] = f.normal[i];
    }
    d.camera = describe_camera_record(camera, task);
    d.task = {task.min_view_angle, task.max_metres_per_pixel, task.placement};
    // The steps the solve took, decided for its policies (the paper's paving: all off).
    const carving& c = result.stats.paving;
    d.settings = {options.position_eps, options.orientation_eps, c.inner_contraction.is_on(), c.occlusion_cuts.is_on(),
                  c.corner_boxes, c.corner_depth, c.rest_min_pieces,
                  options.refine ? std::optional<double>(options.refine->width(options.position_eps)) : std::nullopt,
                  options.grow.has_value()};
    d.boxes.reserve(result.boxes.size());
    for (const auto& b : result.boxes) d.boxes.push_back(to_record(b));
    d.stats = result.stats;
    return d;
}

}  // namespace certipose
