// certipose/io/plan_files.hpp — the files of deployment planning (DESIGN.md §6, "Deployment
// plan"): PLAN.json written by certipose-plan, and the poses certipose-verify reads. Needs
// nlohmann-json.
//
// PLAN.json: {"mesh": {"path", "faces", "scale"}, "camera": {as in the single-facet result},
// "task", "settings": {"candidates", "tolerance", "target_coverage", "max_cameras"}, "cameras": [{"position",
// "orientation", "nominal": [x,y,z,φ,γ,β], "facets": [certified facet indices],
// "certified_area", "from_facet"}], "coverage": {"certified_area", "coverable_area",
// "total_area", "lower_bound_cameras", "lower_bound_method", "curve"}, "uncovered": [{"facet",
// "reason"}]}. A facet listed under a camera is inspected from every pose of its 6D box.
//
// POSES.json (certipose-verify): {"poses": [P, ...]} where each P is an exact pose
// [x, y, z, φ, γ, β] (or {"pose": [...]}) or a 6D box {"position": [[xl,xu],...],
// "orientation": [[φl,φu],...]}; a PLAN.json is accepted too (its "cameras" are the boxes).
#pragma once

#include "certipose/io/json.hpp"
#include "certipose/io/part_files.hpp"
#include "certipose/io/ply.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace certipose {

/// Why a facet is in no camera's certified set.
enum class uncovered_reason {
    never_visible,  ///< the run proved that no pose inspects it (no VALID or BOUNDARY box)
    boundary_only,  ///< only BOUNDARY boxes at this ε: finer thresholds may certify it
    not_selected,   ///< certified by some candidate, but the plan stopped before taking one
    not_solved,     ///< not in the run's facet selection, or skipped by it
    not_finished,   ///< a budget, deadline or cancellation stopped its solve before any box
};

inline constexpr const char* to_string(uncovered_reason r) noexcept {
    switch (r) {
        case uncovered_reason::never_visible: return "never visible";
        case uncovered_reason::boundary_only: return "only in BOUNDARY boxes at this eps";
        case uncovered_reason::not_selected: return "not selected";
        case uncovered_reason::not_solved: return "not solved";
        case uncovered_reason::not_finished: return "solve stopped early";
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
    };
    struct coverage_record {
        double certified_area = 0, coverable_area = 0, total_area = 0;
        std::size_t lower_bound_cameras = 0;
        std::string lower_bound_method;  ///< "area" or "lp"
        std::vector<double> curve;       ///< certified area after 1, 2, ... cameras
    };
    struct uncovered_record {
        std::size_t facet = 0;
        uncovered_reason reason = uncovered_reason::never_visible;
    };
    part_summary::mesh_record mesh;
    result_document::camera_record camera;
    result_document::task_record task;
    std::size_t candidates = 0;
    /// Half-widths (metres, radians) the candidates were cut to around their centres; none: whole boxes.
    std::optional<std::array<double, 2>> tolerance{};
    std::optional<double> target_coverage{};
    std::optional<std::size_t> max_cameras{};
    std::vector<camera_box> cameras;
    coverage_record coverage;
    std::vector<uncovered_record> uncovered;
};

/// PLAN.json as JSON (keys in the documented order).
inline nlohmann::ordered_json plan_to_json(const plan_document& p) {
    using namespace detail::json_io;
    ordered_json j;
    j["mesh"] = {{"path", p.mesh.path}, {"faces", p.mesh.faces}, {"scale", finite(p.mesh.scale, "mesh.scale")}};
    j["camera"] = camera_record_json(p.camera);
    j["task"] = task_record_json(p.task);
    j["settings"] = {{"candidates", p.candidates},
                     {"tolerance", p.tolerance ? ordered_json{finite((*p.tolerance)[0], "settings.tolerance"),
                                                              finite((*p.tolerance)[1], "settings.tolerance")}
                                               : ordered_json(nullptr)},
                     {"target_coverage", p.target_coverage ? finite(*p.target_coverage, "settings.target_coverage")
                                                           : ordered_json(nullptr)},
                     {"max_cameras", p.max_cameras ? ordered_json(*p.max_cameras) : ordered_json(nullptr)}};
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

/// A PLY of the plan: each facet in the colour of the first camera that certifies it (grey when
/// none does), and each camera's position box in its colour. Throws out_of_range for a facet
/// index beyond `mesh`.
inline std::string plan_ply_text(const triangle_mesh& mesh, const plan_document& plan) {
    const certipose::detail::round_to_nearest_scope nearest;  // plain geometry for the picture
    // Well-separated hues (golden-angle steps), bright enough to tell from the grey.
    const auto colour = [](std::size_t k) {
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
    };
    std::vector<std::size_t> by(mesh.num_faces(), plan.cameras.size());
    for (std::size_t k = plan.cameras.size(); k-- > 0;)
        for (std::size_t f : plan.cameras[k].facets) {
            if (f >= by.size()) throw out_of_range("facet", f, by.size());
            by[f] = k;
        }
    detail::ply::builder out;
    for (std::size_t f = 0; f < mesh.num_faces(); ++f) {  // unshared vertices: one colour per facet
        const rgb c = by[f] < plan.cameras.size() ? colour(by[f]) : rgb{150, 150, 150};
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

/// One pose of POSES.json: an exact pose, or a 6D box.
struct pose_input {
    std::optional<std::array<double, 6>> pose{};
    bounds_3d position{}, orientation{};  ///< the box (for an exact pose: the point itself)
};

/// Reads POSES.json (or a PLAN.json; see the header comment). Throws invalid_argument naming the
/// JSON path of a malformed pose ("poses[3].position") and for a file with no pose.
inline std::vector<pose_input> poses_from_json(const nlohmann::json& j) {
    using namespace detail::json_io;
    const certipose::detail::round_to_nearest_scope nearest;
    require_object(j, "");
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
        const json* exact = e.is_array() ? &e : (e.is_object() ? find(e, "pose") : nullptr);
        if (exact) {
            const std::string where = e.is_array() ? path : child(path, "pose");
            p.pose = as_numbers<6>(*exact, where);
            for (double v : *p.pose)
                if (!std::isfinite(v)) fail(where, "a pose must be finite");
            for (std::size_t k = 0; k < 3; ++k) {
                p.position[k] = {(*p.pose)[k], (*p.pose)[k]};
                p.orientation[k] = {(*p.pose)[k + 3], (*p.pose)[k + 3]};
            }
        } else {
            require_object(e, path);
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
