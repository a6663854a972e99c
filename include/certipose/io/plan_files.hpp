// certipose/io/plan_files.hpp — the files of deployment planning (docs/coverage.md, and
// docs/conventions.md#files): PLAN.json written by certipose-plan, and the poses certipose-verify reads. Needs
// nlohmann-json.
//
// PLAN.json: {"format": "certipose-plan", "version": 1, "mesh": {"path", "faces", "scale", "digest", "pose"},
// "camera": {as in the single-facet result},
// "task", "settings": {"candidates", "tolerance", "target_coverage", "max_cameras"}, "occluders",
// "keep_in", "keep_out" (io/scene_record.hpp; absent: none), "cameras": [{"position",
// "orientation", "nominal": [x,y,z,φ,γ,β], "facets": [certified facet indices],
// "certified_area", "from_facet", "aim": [x,y,z]}], "coverage": {"certified_area", "coverable_area",
// "total_area", "lower_bound_cameras", "lower_bound_method", "curve"}, "uncovered": [{"facet",
// "reason"}]}. A facet listed under a camera is inspected from every pose of its 6D box.
// plan_to_json writes it, plan_from_json / read_plan read it back (the same document).
//
// POSES.json (certipose-verify): {"poses": [P, ...]} where each P is an exact pose
// [x, y, z, φ, γ, β] (or {"pose": [...]}), a 6D box {"position": [[xl,xu],...],
// "orientation": [[φl,φu],...]}, a position and unit quaternion {"position": [x, y, z],
// "quaternion": [qx, qy, qz, qw]} or a row-major 4×4 camera-to-world transform {"matrix":
// [[...], [...], [...], [0, 0, 0, 1]]}; a PLAN.json is accepted too (its "cameras" are the boxes).
// A quaternion or a matrix is converted to ZXZ angles in double (pose/quaternion.hpp), which is
// not exact: the pose becomes the box of ±converted_pose_half_width radians around the converted
// angles (the conversion's error is below 1e-9 rad away from the gimbal lock, which is refused:
// see poses_from_json), its position a point; a matrix orthonormal only approximately gets a
// box widened by that ambiguity (detail::json_io::converted_pose).
#pragma once

#include "certipose/io/json.hpp"
#include "certipose/io/part_files.hpp"
#include "certipose/io/ply.hpp"
#include "certipose/pose/quaternion.hpp"

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstddef>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

namespace certipose {

/// Why a facet is in no camera's certified set.
enum class uncovered_reason {
    never_visible,  ///< the run proved that no pose inspects it (no VALID or BOUNDARY box, or its screen skipped it)
    boundary_only,  ///< only BOUNDARY boxes at this ε: finer thresholds may certify it
    not_selected,   ///< certified by some candidate, but the plan stopped before taking one
    not_solved,     ///< not in the run's facet selection
    not_finished,   ///< a budget, deadline or cancellation stopped its solve before any box
    /// no VALID box, and it lies face to face on an occluder (a part resting on its fixture):
    /// a finer ε will not help (occlusion/resting_contact.hpp)
    rests_on_occluder,
    /// no VALID box, and the space in front of it is inside material: the survey of a triangle
    /// soup found it buried in, or covered by, another body (occlusion/mesh_survey.hpp)
    buried,
};

inline constexpr const char* to_string(uncovered_reason r) noexcept {
    switch (r) {
        case uncovered_reason::never_visible: return "never visible";
        case uncovered_reason::boundary_only: return "only in BOUNDARY boxes at this eps";
        case uncovered_reason::not_selected: return "not selected";
        case uncovered_reason::not_solved: return "not solved";
        case uncovered_reason::not_finished: return "solve stopped early";
        case uncovered_reason::rests_on_occluder: return "rests on an occluder";
        case uncovered_reason::buried: return "buried in another body";
    }
    return "?";
}

/// PLAN.json, field by field (see the header comment).
struct plan_document {
    struct camera_box {
        bounds_3d position{}, orientation{};
        std::array<double, 6> nominal{};
        std::vector<std::size_t> facets;
        double certified_area = 0;
        std::size_t from_facet = 0;  ///< the facet whose VALID box this is
        /// Where the nominal optical axis meets the part (make_plan.hpp's plan_aim); plans written
        /// before it was recorded have none.
        std::optional<std::array<double, 3>> aim;
        friend bool operator==(const camera_box&, const camera_box&) = default;
    };
    struct coverage_record {
        double certified_area = 0, coverable_area = 0, total_area = 0;
        std::size_t lower_bound_cameras = 0;
        std::string lower_bound_method;  ///< "area", "greedy", "lp" or "exact"
        std::vector<double> curve;       ///< certified area after 1, 2, ... cameras
        friend bool operator==(const coverage_record&, const coverage_record&) = default;
    };
    struct uncovered_record {
        std::size_t facet = 0;
        uncovered_reason reason = uncovered_reason::never_visible;
        friend bool operator==(const uncovered_record&, const uncovered_record&) = default;
    };
    part_summary::mesh_record mesh;
    result_document::camera_record camera;
    result_document::task_record task;
    std::size_t candidates = 0;
    /// Of the candidates, those whose C(B) was computed (coverage/thinning.hpp skips the others);
    /// a PLAN.json without the field inspected them all.
    std::size_t inspected = 0;
    /// Half-widths (metres, radians) the candidates were cut to around their centres; none: whole boxes.
    std::optional<std::array<double, 2>> tolerance{};
    std::optional<double> target_coverage{};
    std::optional<std::size_t> max_cameras{};
    std::vector<camera_box> cameras;
    coverage_record coverage;
    std::vector<uncovered_record> uncovered;
    /// The external occluders and camera regions the plan was made with.
    scene_record scene{};
    friend bool operator==(const plan_document&, const plan_document&) = default;
};

/// PLAN.json as JSON (keys in the documented order).
inline nlohmann::ordered_json plan_to_json(const plan_document& p) {
    using namespace detail::json_io;
    ordered_json j;
    j["format"] = plan_format;
    j["version"] = format_version;
    j["mesh"] = mesh_record_json(p.mesh);  // as in summary.json
    j["camera"] = camera_record_json(p.camera);
    j["task"] = task_record_json(p.task);
    if (p.inspected > p.candidates)
        throw invalid_argument("settings.inspected", "plan_to_json: settings.inspected " + std::to_string(p.inspected) +
                                                         " is above settings.candidates " + std::to_string(p.candidates));
    j["settings"] = {{"candidates", p.candidates},
                     {"inspected", p.inspected},
                     {"tolerance", p.tolerance ? ordered_json{finite((*p.tolerance)[0], "settings.tolerance"),
                                                              finite((*p.tolerance)[1], "settings.tolerance")}
                                               : ordered_json(nullptr)},
                     {"target_coverage", p.target_coverage ? finite(*p.target_coverage, "settings.target_coverage")
                                                           : ordered_json(nullptr)},
                     {"max_cameras", p.max_cameras ? ordered_json(*p.max_cameras) : ordered_json(nullptr)}};
    put_scene(j, p.scene);
    ordered_json cameras = ordered_json::array();
    for (std::size_t i = 0; i < p.cameras.size(); ++i) {
        const auto& c = p.cameras[i];
        const std::string path = element("cameras", i);
        ordered_json cam;
        cam["position"] = bounds(c.position, child(path, "position"));
        cam["orientation"] = bounds(c.orientation, child(path, "orientation"));
        cam["nominal"] = numbers(c.nominal, child(path, "nominal"));
        cam["facets"] = c.facets;
        cam["certified_area"] = finite(c.certified_area, child(path, "certified_area"));
        cam["from_facet"] = c.from_facet;
        if (c.aim) cam["aim"] = numbers(*c.aim, child(path, "aim"));
        cameras.push_back(std::move(cam));
    }
    j["cameras"] = std::move(cameras);
    ordered_json curve = ordered_json::array();
    for (double a : p.coverage.curve) curve.push_back(finite(a, "coverage.curve"));
    j["coverage"] = {{"certified_area", finite(p.coverage.certified_area, "coverage.certified_area")},
                     {"coverable_area", finite(p.coverage.coverable_area, "coverage.coverable_area")},
                     {"total_area", finite(p.coverage.total_area, "coverage.total_area")},
                     {"lower_bound_cameras", p.coverage.lower_bound_cameras},
                     {"lower_bound_method", p.coverage.lower_bound_method},
                     {"curve", std::move(curve)}};
    ordered_json uncovered = ordered_json::array();
    for (const auto& u : p.uncovered) uncovered.push_back({{"facet", u.facet}, {"reason", to_string(u.reason)}});
    j["uncovered"] = std::move(uncovered);
    return j;
}

inline std::optional<uncovered_reason> uncovered_reason_from_string(std::string_view s) {
    for (auto r : {uncovered_reason::never_visible, uncovered_reason::boundary_only, uncovered_reason::not_selected,
                   uncovered_reason::not_solved, uncovered_reason::not_finished, uncovered_reason::rests_on_occluder,
                   uncovered_reason::buried})
        if (s == to_string(r)) return r;
    return std::nullopt;
}

/// Reads PLAN.json back: the inverse of plan_to_json (plan_from_json(plan_to_json(p)) == p, every
/// double bit for bit). Fields it does not know are ignored; a missing or wrong field, a box
/// with lower > upper, an unknown uncovered reason, or another "format" / "version" (absent: 1)
/// is an invalid_argument naming the JSON path ("cameras[2].facets[0]"). `source` (a file
/// name) prefixes the messages; empty for none.
inline plan_document plan_from_json(const nlohmann::json& j, const std::string& source = {}) {
    return detail::json_io::with_source(source, [&] {
        using namespace detail::json_io;
        const certipose::detail::round_to_nearest_scope nearest;
        plan_document p;
        require_object(j, "");
        check_format(j, plan_format);
        p.mesh = mesh_record_from_json(require(j, "", "mesh", "an object"));
        p.camera = camera_record_from_json(require(j, "", "camera", "an object"));
        p.task = task_record_from_json(require(j, "", "task", "an object"));

        const json& settings = require_object(require(j, "", "settings", "an object"), "settings");
        p.candidates = as_count(require(settings, "settings", "candidates", "an integer"), "settings.candidates");
        p.inspected = p.candidates;
        if (const json* n = find(settings, "inspected"); n && !n->is_null()) {
            p.inspected = as_count(*n, "settings.inspected");
            if (p.inspected > p.candidates)
                fail("settings.inspected", "expected at most settings.candidates (" + std::to_string(p.candidates) + "), got " +
                                               std::to_string(p.inspected));
        }
        if (const json* t = find(settings, "tolerance"); t && !t->is_null())
            p.tolerance = as_numbers<2>(*t, "settings.tolerance");
        p.target_coverage = optional_number(settings, "settings", "target_coverage");
        if (const json* m = find(settings, "max_cameras"); m && !m->is_null())
            p.max_cameras = as_count(*m, "settings.max_cameras");
        p.scene = scene_from_json(j);

        const auto array = [](const json& obj, const std::string& path, std::string_view key) -> const json& {
            const json& a = require(obj, path, key, "an array");
            if (!a.is_array()) fail(child(path, key), "expected an array, got " + describe(a));
            return a;
        };
        const json& cameras = array(j, "", "cameras");
        for (std::size_t i = 0; i < cameras.size(); ++i) {
            const std::string path = element("cameras", i);
            const json& c = require_object(cameras[i], path);
            plan_document::camera_box cam;
            cam.position = as_matrix<3, 2>(require(c, path, "position", "3 intervals"), child(path, "position"));
            cam.orientation = as_matrix<3, 2>(require(c, path, "orientation", "3 intervals"), child(path, "orientation"));
            check_bounds(cam.position, child(path, "position"));
            check_bounds(cam.orientation, child(path, "orientation"));
            cam.nominal = as_numbers<6>(require(c, path, "nominal", "6 numbers"), child(path, "nominal"));
            const json& facets = array(c, path, "facets");
            for (std::size_t k = 0; k < facets.size(); ++k)
                cam.facets.push_back(as_count(facets[k], element(child(path, "facets"), k)));
            cam.certified_area = required_number(c, path, "certified_area");
            cam.from_facet = as_count(require(c, path, "from_facet", "an integer"), child(path, "from_facet"));
            if (const auto aim = c.find("aim"); aim != c.end()) cam.aim = as_numbers<3>(*aim, child(path, "aim"));
            p.cameras.push_back(std::move(cam));
        }

        const json& coverage = require_object(require(j, "", "coverage", "an object"), "coverage");
        p.coverage.certified_area = required_number(coverage, "coverage", "certified_area");
        p.coverage.coverable_area = required_number(coverage, "coverage", "coverable_area");
        p.coverage.total_area = required_number(coverage, "coverage", "total_area");
        p.coverage.lower_bound_cameras =
            as_count(require(coverage, "coverage", "lower_bound_cameras", "an integer"), "coverage.lower_bound_cameras");
        p.coverage.lower_bound_method = as_string(require(coverage, "coverage", "lower_bound_method", "a string"),
                                                  "coverage.lower_bound_method", "a string");
        const json& curve = array(coverage, "coverage", "curve");
        for (std::size_t k = 0; k < curve.size(); ++k) p.coverage.curve.push_back(as_number(curve[k], element("coverage.curve", k)));

        const json& uncovered = array(j, "", "uncovered");
        for (std::size_t i = 0; i < uncovered.size(); ++i) {
            const std::string path = element("uncovered", i);
            const json& u = require_object(uncovered[i], path);
            plan_document::uncovered_record r;
            r.facet = as_count(require(u, path, "facet", "an integer"), child(path, "facet"));
            const std::string name = as_string(require(u, path, "reason", "a string"), child(path, "reason"), "a string");
            const auto reason = uncovered_reason_from_string(name);
            if (!reason)
                fail(child(path, "reason"), "unknown reason \"" + name +
                                                "\" (expected never visible, only in BOUNDARY boxes at this eps, not "
                                                "selected, not solved, solve stopped early or rests on an occluder)");
            r.reason = *reason;
            p.uncovered.push_back(r);
        }
        return p;
    });
}

/// Reads a PLAN.json file. Throws io_error if it cannot be read or is not JSON, and
/// invalid_argument (message prefixed by the file name) as plan_from_json.
inline plan_document read_plan(const std::filesystem::path& path) {
    return detail::json_io::with_source(path.string(), [&] {
        return plan_from_json(detail::json_io::parse(detail::json_io::read_text_file(path, "read_plan"), path.string()));
    });
}

/// Camera k's colour in the plan's pictures (PLY, glTF, HTML): well-separated hues (golden-angle
/// steps), bright enough to tell from the grey of uncovered facets.
inline rgb plan_camera_colour(std::size_t k) {
    const double h = std::fmod(0.618033988749895 * static_cast<double>(k), 1.0) * 6.0;
    const double x = 1.0 - std::abs(std::fmod(h, 2.0) - 1.0);
    std::array<double, 3> c{};
    switch (static_cast<int>(h)) {
        case 0: c = {1, x, 0}; break;
        case 1: c = {x, 1, 0}; break;
        case 2: c = {0, 1, x}; break;
        case 3: c = {0, x, 1}; break;
        case 4: c = {x, 0, 1}; break;
        default: c = {1, 0, x}; break;
    }
    const auto byte = [](double v) { return static_cast<std::uint8_t>(40 + 200 * v); };
    return rgb{byte(c[0]), byte(c[1]), byte(c[2])};
}

/// For each facet of a part of `num_faces` faces, the first camera of `plan` that certifies it,
/// or plan.cameras.size() when none does. Throws out_of_range for a facet index beyond the part.
inline std::vector<std::size_t> plan_first_cameras(std::size_t num_faces, const plan_document& plan) {
    std::vector<std::size_t> by(num_faces, plan.cameras.size());
    for (std::size_t k = plan.cameras.size(); k-- > 0;)
        for (std::size_t f : plan.cameras[k].facets) {
            if (f >= by.size()) throw out_of_range("facet", f, by.size());
            by[f] = k;
        }
    return by;
}

/// The grey of facets no camera certifies in the plan's pictures, and the darker grey of those no
/// pose can see (plan_unseen_facets).
inline constexpr rgb plan_uncovered_colour{150, 150, 150}, plan_unseen_colour{88, 92, 104};

/// For each facet of a part of `num_faces` faces, whether `plan` says that no pose can see it
/// (uncovered as "never visible" or "rests on an occluder").
inline std::vector<char> plan_unseen_facets(std::size_t num_faces, const plan_document& plan) {
    std::vector<char> unseen(num_faces, 0);
    for (const auto& u : plan.uncovered)
        if (u.facet < num_faces)
            unseen[u.facet] = u.reason == uncovered_reason::never_visible || u.reason == uncovered_reason::rests_on_occluder ||
                              u.reason == uncovered_reason::buried;
    return unseen;
}

/// A PLY of the plan: each facet in the colour of the first camera that certifies it (grey when
/// none does), and each camera's position box in its colour. Throws out_of_range for a facet
/// index beyond `mesh`.
inline std::string plan_ply_text(const triangle_mesh& mesh, const plan_document& plan) {
    const certipose::detail::round_to_nearest_scope nearest;  // plain geometry for the picture
    const std::vector<std::size_t> by = plan_first_cameras(mesh.num_faces(), plan);
    const auto colour = plan_camera_colour;
    detail::ply::builder out;
    for (std::size_t f = 0; f < mesh.num_faces(); ++f) {  // unshared vertices: one colour per facet
        const rgb c = by[f] < plan.cameras.size() ? colour(by[f]) : plan_uncovered_colour;
        const std::size_t first = out.num_vertices;
        for (const auto& v : mesh.facet(f).v) out.vertex(v, c);
        out.face(first, first + 1, first + 2, c);
    }
    for (std::size_t k = 0; k < plan.cameras.size(); ++k) {
        detail::ply::require_finite_bounds(plan.cameras[k].position, "cameras[" + std::to_string(k) + "].position");
        out.solid(plan.cameras[k].position, colour(k));
    }
    return out.text("certipose deployment plan: " + std::to_string(plan.cameras.size()) +
                    " camera boxes, each facet in the colour of the camera that certifies it, grey when none does");
}

/// How POSES.json gave a pose (see the header comment).
enum class pose_form {
    exact,       ///< [x, y, z, φ, γ, β] or {"pose": [...]}
    box,         ///< {"position": [[xl, xu], ...], "orientation": [[φl, φu], ...]}
    quaternion,  ///< {"position": [x, y, z], "quaternion": [qx, qy, qz, qw]}
    matrix,      ///< {"matrix": 4×4 row-major camera-to-world}
};

inline constexpr const char* to_string(pose_form f) noexcept {
    switch (f) {
        case pose_form::exact: return "pose";
        case pose_form::box: return "box";
        case pose_form::quaternion: return "quaternion";
        case pose_form::matrix: return "matrix";
    }
    return "?";
}

/// Half-width (radians) of the orientation box a quaternion or matrix pose becomes around its
/// converted ZXZ angles. The double conversion (pose/quaternion.hpp) errs by a few ulp of the
/// matrix entries divided by sin γ; with sin γ ≥ zxz_gimbal_limit that is below 1e-9 rad, so
/// ±1e-8 holds the exact angles with a tenfold margin.
inline constexpr double converted_pose_half_width = 1e-8;
/// Quaternion and matrix poses with sin γ below this (optical axis within about 1e-6 rad of
/// world ±Z: the ZXZ gimbal lock, where φ and β are ill-conditioned) are refused.
inline constexpr double zxz_gimbal_limit = 1e-6;
/// How far a quaternion's norm may be from 1, and a matrix's rotation part from orthonormal
/// (largest entry of |RᵀR − I|), before the pose is refused.
inline constexpr double pose_unit_tolerance = 1e-6;

/// One pose of POSES.json: an exact pose, a 6D box, or a converted quaternion or matrix pose.
struct pose_input {
    std::optional<std::array<double, 6>> pose{};  ///< exact poses only: [x, y, z, φ, γ, β]
    bounds_3d position{}, orientation{};          ///< the box (for an exact pose: the point itself)
    pose_form form = pose_form::box;
    /// Quaternion and matrix poses: the converted [x, y, z, φ, γ, β], the centre of the box
    /// (whose orientation is ±converted_half_widths around it, its position the point).
    std::optional<std::array<double, 6>> converted{};
    /// Quaternion and matrix poses: the half-widths (radians) of the box's φ, γ, β about the
    /// converted angles: converted_pose_half_width, and for a matrix not quite orthonormal its
    /// widening for that (detail::json_io::converted_pose). Zero for other forms.
    std::array<double, 3> converted_half_widths{};
};

namespace detail::json_io {

/// The ZXZ pose of a rotation matrix `r` and position `x` as a pose_input (see pose_form).
/// Refuses the gimbal lock, naming `where`. `slack` (≥ 0) widens the box for an input that names
/// its rotation only to within that much (a matrix not quite orthonormal): by 4·slack in γ and
/// 4·slack / sin γ in φ and β, the ZXZ angles' sensitivity to a rotation of the axes.
inline pose_input converted_pose(const Eigen::Matrix3d& r, const std::array<double, 3>& x, pose_form form,
                                 const std::string& where, double slack = 0.0) {
    // β reads the third row and φ the third column: both need a horizontal part (for an exact
    // rotation they are the same, sin γ).
    const double sin_gamma = std::min(zxz_sin_gamma(r), std::hypot(r(2, 0), r(2, 1)));
    if (!(sin_gamma >= zxz_gimbal_limit))
        fail(where, "the orientation is at the ZXZ gimbal lock (sin gamma = " + certipose::detail::format_double(sin_gamma) +
                        " < " + certipose::detail::format_double(zxz_gimbal_limit) +
                        ": the optical axis is along world +Z or -Z), where it has no accurate ZXZ angles; give this "
                        "pose as ZXZ angles [x, y, z, phi, gamma, beta] instead");
    const zxz_angles a = zxz_from_matrix(r);
    pose_input p;
    p.form = form;
    p.converted = std::array<double, 6>{x[0], x[1], x[2], a.phi, a.gamma, a.beta};
    const double angles[3] = {a.phi, a.gamma, a.beta};
    for (std::size_t k = 0; k < 3; ++k) {
        p.position[k] = {x[k], x[k]};
        const double h = converted_pose_half_width + (k == 1 ? 4 * slack : 4 * slack / sin_gamma);
        p.orientation[k] = {angles[k] - h, angles[k] + h};
        p.converted_half_widths[k] = h;
    }
    return p;
}

inline void require_finite(std::initializer_list<double> values, const std::string& where) {
    for (double v : values)
        if (!std::isfinite(v)) fail(where, "a pose must be finite");
}

}  // namespace detail::json_io

/// Reads POSES.json (or a PLAN.json; see the header comment). Throws invalid_argument naming the
/// JSON path of a malformed pose ("poses[3].position"), for a file with no pose, a "format"
/// other than "certipose-plan" or a "version" other than 1 (both optional), a quaternion whose
/// norm is not 1 within pose_unit_tolerance, a matrix whose last row is not (0, 0, 0, 1) or
/// whose rotation part is not a rotation within pose_unit_tolerance, and a quaternion or matrix
/// at the ZXZ gimbal lock (sin γ < zxz_gimbal_limit), which must be given as ZXZ angles.
inline std::vector<pose_input> poses_from_json(const nlohmann::json& j) {
    using namespace detail::json_io;
    const certipose::detail::round_to_nearest_scope nearest;
    require_object(j, "");
    check_format(j, plan_format);
    std::string key = "poses";
    const json* list = find(j, "poses");
    if (!list) {
        list = find(j, "cameras");
        key = "cameras";
    }
    if (!list) fail("poses", "expected an array of poses (or a PLAN.json with \"cameras\")");
    if (!list->is_array()) fail(key, "expected an array, got " + describe(*list));
    if (list->empty()) fail(key, "no pose given");
    std::vector<pose_input> out;
    for (std::size_t i = 0; i < list->size(); ++i) {
        const std::string path = element(key, i);
        const json& e = (*list)[i];
        pose_input p;
        if (e.is_object()) {
            int given = 0;
            for (const char* k : {"pose", "orientation", "quaternion", "matrix"}) given += find(e, k) != nullptr;
            if (given > 1)
                fail(path, "give the orientation once: one of \"pose\", \"orientation\", \"quaternion\" or \"matrix\"");
        }
        const json* exact = e.is_array() ? &e : (e.is_object() ? find(e, "pose") : nullptr);
        if (exact) {
            const std::string where = e.is_array() ? path : child(path, "pose");
            p.pose = as_numbers<6>(*exact, where);
            p.form = pose_form::exact;
            for (double v : *p.pose)
                if (!std::isfinite(v)) fail(where, "a pose must be finite");
            for (std::size_t k = 0; k < 3; ++k) {
                p.position[k] = {(*p.pose)[k], (*p.pose)[k]};
                p.orientation[k] = {(*p.pose)[k + 3], (*p.pose)[k + 3]};
            }
        } else if (const json* q = e.is_object() ? find(e, "quaternion") : nullptr) {
            const std::string where = child(path, "quaternion");
            const auto x = as_numbers<3>(require(e, path, "position", "3 numbers [x, y, z]"), child(path, "position"));
            const auto c = as_numbers<4>(*q, where);
            require_finite({x[0], x[1], x[2]}, child(path, "position"));
            require_finite({c[0], c[1], c[2], c[3]}, where);
            const double norm = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2] + c[3] * c[3]);
            if (!(std::abs(norm - 1.0) <= pose_unit_tolerance))
                fail(where, "not a unit quaternion [qx, qy, qz, qw]: its norm is " + certipose::detail::format_double(norm) +
                                " (must be 1 within " + certipose::detail::format_double(pose_unit_tolerance) + ")");
            p = converted_pose(matrix_from_quaternion(c), x, pose_form::quaternion, where);
        } else if (const json* m = e.is_object() ? find(e, "matrix") : nullptr) {
            const std::string where = child(path, "matrix");
            if (find(e, "position"))
                fail(child(path, "position"), "a pose given by \"matrix\" takes its position from the matrix's last column");
            const auto rows = as_matrix<4, 4>(*m, where);
            for (const auto& row : rows) require_finite({row[0], row[1], row[2], row[3]}, where);
            if (!(rows[3][0] == 0 && rows[3][1] == 0 && rows[3][2] == 0 && rows[3][3] == 1))
                fail(element(where, 3), "the last row of a camera-to-world transform must be [0, 0, 0, 1], got [" +
                                            certipose::detail::format_double(rows[3][0]) + ", " +
                                            certipose::detail::format_double(rows[3][1]) + ", " +
                                            certipose::detail::format_double(rows[3][2]) + ", " +
                                            certipose::detail::format_double(rows[3][3]) + "]");
            Eigen::Matrix3d r;
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b) r(a, b) = rows[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)];
            const double off = (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
            if (!(off <= pose_unit_tolerance))
                fail(where, "the rotation part (upper-left 3x3) is not orthonormal within " +
                                certipose::detail::format_double(pose_unit_tolerance) +
                                ": R^T R differs from the identity by up to " + certipose::detail::format_double(off));
            if (!(r.determinant() > 0))
                fail(where, "the rotation part (upper-left 3x3) has determinant " + certipose::detail::format_double(r.determinant()) +
                                ": a reflection, not a rotation");
            // A matrix orthonormal only within `off` does not name one rotation: every rotation
            // within about `off` of it is as much "the" pose. Take the rotation of its quaternion
            // and widen the box by the ambiguity (converted_pose's slack), so that it holds them.
            Eigen::Quaterniond q(r);
            q.normalize();
            p = converted_pose(q.toRotationMatrix(), {rows[0][3], rows[1][3], rows[2][3]}, pose_form::matrix, where, off);
        } else {
            require_object(e, path);
            p.form = pose_form::box;
            p.position = as_matrix<3, 2>(require(e, path, "position", "3 intervals"), child(path, "position"));
            p.orientation = as_matrix<3, 2>(require(e, path, "orientation", "3 intervals"), child(path, "orientation"));
            check_bounds(p.position, child(path, "position"));
            check_bounds(p.orientation, child(path, "orientation"));
        }
        out.push_back(p);
    }
    return out;
}

/// Reads a POSES.json file. Throws io_error if it cannot be read or is not JSON.
inline std::vector<pose_input> read_poses(const std::filesystem::path& path) {
    return detail::json_io::with_source(path.string(), [&] {
        return poses_from_json(detail::json_io::parse(detail::json_io::read_text_file(path, "read_poses"), path.string()));
    });
}

}  // namespace certipose
