// certipose/io/part_files.hpp — the output folder of a whole-part run (docs/part.md, "The
// output folder"): summary.json and boxes.jsonl, written and read. Needs nlohmann-json.
//
// boxes.jsonl has one box per line, in facet order then box order:
//   {"facet": 17, "class": "valid", "position": [[xl,xu],[yl,yu],[zl,zu]], "orientation": [[φl,φu],[γl,γu],[βl,βu]]}
// with bounds in shortest round-trip form (they read back to the same doubles); BOUNDARY lines
// (only on request) also carry "undecided": "<reason>", and VALID lines of a run whose occlusion
// was not checked carry "occlusion": "unchecked". `jsonl_sink` streams lines as facets finish,
// so memory holds one facet's boxes at a time.
//
// summary.json: {"format": "certipose-part-summary", "version": 1, "mesh": {"path", "faces", "scale",
// "digest", "pose" (a row-major 4×4, only when --part-pose moved the part)}, "camera": {as in the single-facet result},
// "task", "settings" (every option that changes the answer: ε_p, ε_o, budgets, occlusion,
// "mesh_semantics", "paving" and carving's steps, "refine_seconds", "grow", "max_boxes",
// "facets", "keep_largest", "box_store", "reuse", "patches": false or {"max_cone", "max_extent",
// "max_members", "max_loss"}), "survey" (a triangle soup's, occlusion/mesh_survey.hpp),
// "occluders", "keep_in", "keep_out" (io/scene_record.hpp; absent: none), "cad" (a part read
// from a CAD file: {"unit", "deflection", "angular_deflection", "dropped_triangles", "faces":
// [{"id", "name", "surface", "area", "deviation", "facets"}]}, geometry/cad_faces.hpp; absent: a mesh),
// "facets": [{"index", "valid", "boundary", "seconds", "termination",
// "reason" (when skipped), "dropped", "reused_from" (part_options::reuse), "patch" (the seed of its patch,
// part_options::patches), "boundary_reasons"}], "totals": {"seconds", "threads", "ranks",
// "facets", "valid", "boundary", "skipped", "termination", "interrupted"}}.
#pragma once

#include "certipose/geometry/cad_faces.hpp"
#include "certipose/io/json.hpp"
#include "certipose/io/result_document.hpp"
#include "certipose/pose/part_pose.hpp"
#include "certipose/part/part_solver.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <istream>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace certipose {

namespace detail::part_io {

inline void append_bounds(std::string& out, const bounds_3d& b) {
    out += '[';
    for (std::size_t i = 0; i < 3; ++i) {
        if (i) out += ',';
        out += '[';
        certipose::detail::append_double(out, b[i][0]);
        out += ',';
        certipose::detail::append_double(out, b[i][1]);
        out += ']';
    }
    out += ']';
}

}  // namespace detail::part_io

/// Appends one boxes.jsonl line (with its newline). Throws invalid_argument for a box with a
/// non-finite or empty bound (the JSON could not hold it).
template <Interval I>
void append_box_line(std::string& out, std::size_t facet, const classified_box<I>& b, bool occlusion_checked) {
    const box_record r = to_record(b);
    for (const auto* bounds : {&r.position, &r.orientation})
        for (const auto& c : *bounds)
            if (!std::isfinite(c[0]) || !std::isfinite(c[1]) || !(c[0] <= c[1]))
                throw invalid_argument("box", "boxes.jsonl: facet " + std::to_string(facet) +
                                                  " has a box with a non-finite or empty interval");
    out += "{\"facet\":";
    out += std::to_string(facet);
    out += ",\"class\":\"";
    out += to_string(r.cls);
    out += "\",\"position\":";
    detail::part_io::append_bounds(out, r.position);
    out += ",\"orientation\":";
    detail::part_io::append_bounds(out, r.orientation);
    if (r.reason) {
        out += ",\"undecided\":\"";
        out += to_string(*r.reason);
        out += '"';
    }
    if (r.cls == box_class::valid && !occlusion_checked) out += ",\"occlusion\":\"unchecked\"";
    out += "}\n";
}

/// A PartSink writing boxes.jsonl lines to a stream, one facet at a time.
template <Interval I>
class jsonl_sink {
public:
    jsonl_sink(std::ostream& out, bool occlusion_checked) : out_(&out), occlusion_checked_(occlusion_checked) {}

    void facet(const facet_outcome<I>& o) {
        const certipose::detail::round_to_nearest_scope nearest;  // shortest digits need it
        line_.clear();
        for (const auto& b : o.boxes) append_box_line(line_, o.record.index, b, occlusion_checked_);
        out_->write(line_.data(), static_cast<std::streamsize>(line_.size()));
        lines_ += o.boxes.size();
        if (!*out_) throw io_error("boxes.jsonl", "boxes.jsonl: write failed (disk full?)");
    }
    std::size_t lines() const noexcept { return lines_; }

private:
    std::ostream* out_;
    bool occlusion_checked_;
    std::string line_;
    std::size_t lines_ = 0;
};

/// summary.json, field by field (see the header comment).
struct part_summary {
    struct mesh_record {
        std::string path;
        std::size_t faces = 0;
        double scale = 1.0;
        std::string digest{};  ///< mesh_digest of the mesh the run solved; empty: not recorded
        /// The part's placement (pose/part_pose.hpp) as a row-major 4×4; none: as read.
        std::optional<std::array<double, 16>> pose{};
        friend bool operator==(const mesh_record&, const mesh_record&) = default;
    };
    struct settings_record {
        double position_eps = 0, orientation_eps = 0;
        std::size_t max_boxes_per_facet = 0;
        std::optional<double> time_limit_per_facet{};
        std::optional<double> time_limit{};
        bool boundary = false;
        std::string occlusion;  ///< "aabb", "boolean", "none", or the policy's name
        bool occlusion_checked = true;
        // Everything else that changes the answer. Written; of these, mesh_semantics, paving,
        // keep_largest and box_store are read back (what certipose-plan needs).
        std::string mesh_semantics = "solid";  ///< how occlusion read the meshes: "solid", "soup" ("none": unchecked)
        std::string box_store = "jsonl";       ///< the box files written: "jsonl", "binary" or "both"
        std::string paving = "default";        ///< "default" (carving) or "paper"
        /// carving's steps and tuning (all off for the paper's paving)
        bool inner_contraction = true, occlusion_cuts = true, leaf_corner_boxes = true;
        std::size_t corner_depth = 0;
        double corner_rest_min_pieces = 0;
        std::optional<double> refine_seconds{};  ///< --refine
        bool grow = false;                       ///< --grow
        std::optional<std::size_t> max_boxes{};  ///< the run's box budget
        std::string facets{};                    ///< the --facets selection as given; empty: all
        std::optional<std::size_t> keep_largest{};  ///< only the K largest VALID boxes per facet kept
        bool reuse = true;  ///< open facets took a translate's boxes, proven again (part_options::reuse)
        /// Patches certified at once (part_options::patches), with max_extent resolved to
        /// metres; nothing: facet by facet.
        std::optional<patch_options> patches{};
    };
    /// What the survey of a triangle soup found (occlusion/mesh_survey.hpp; written when the
    /// scene was read as one).
    struct survey_record {
        std::size_t bodies = 0, closed_bodies = 0, inward_bodies = 0, open_edges = 0, nonmanifold_edges = 0,
                    duplicate_faces = 0, intersecting_pairs = 0, buried = 0, covered = 0;
        std::vector<std::string> examples{};
    };
    struct totals_record {
        double seconds = 0;
        std::size_t threads = 0, ranks = 1;
        std::size_t facets_selected = 0, facets = 0, valid = 0, boundary = 0, skipped = 0;
        termination reason = termination::completed;
        bool interrupted = false;  ///< a signal ended the run
    };
    mesh_record mesh;
    result_document::camera_record camera;
    result_document::task_record task;
    settings_record settings;
    std::optional<survey_record> survey{};
    /// The run's external occluders and camera regions ("occluders", "keep_in", "keep_out").
    scene_record scene{};
    /// The CAD model the mesh is the tessellation of (absent: a mesh file). Part of what the run
    /// was for: a resumed run must have the same tessellation.
    std::optional<cad_model> cad{};
    std::vector<facet_record> facets;
    totals_record totals;
};

inline std::optional<facet_termination> facet_termination_from_string(std::string_view s) {
    for (auto t : {facet_termination::completed, facet_termination::box_budget, facet_termination::deadline,
                   facet_termination::cancelled, facet_termination::skipped})
        if (s == to_string(t)) return t;
    return std::nullopt;
}

// mesh_digest, the fingerprint of "mesh.digest": io/scene_record.hpp.

/// The camera and task records of a document, from the camera the run used.
template <CameraModel C>
void describe_camera(part_summary& s, const C& camera, const inspection_task& task) {
    s.camera = describe_camera_record(camera, task);
    s.task = {task.min_view_angle, task.max_metres_per_pixel, task.placement};
}

/// One element of summary.json's "facets" (keys in the documented order).
inline nlohmann::ordered_json facet_record_to_json(const facet_record& f) {
    using namespace detail::json_io;
    ordered_json r;
    r["index"] = f.index;
    r["valid"] = f.valid;
    r["boundary"] = f.boundary;
    r["seconds"] = finite(f.seconds, "facets.seconds");
    r["termination"] = to_string(f.termination);
    if (f.termination == facet_termination::skipped) r["reason"] = f.reason;
    if (f.dropped > 0) r["dropped"] = f.dropped;
    if (f.reused_from) r["reused_from"] = *f.reused_from;
    if (f.patch) r["patch"] = *f.patch;
    if (f.boundary > 0) {
        ordered_json reasons;
        for (std::size_t k = 0; k < boundary_reason_count; ++k)
            if (f.boundary_reasons[k]) reasons[std::string(to_string(static_cast<boundary_reason>(k)))] = f.boundary_reasons[k];
        r["boundary_reasons"] = std::move(reasons);
    }
    return r;
}

/// Reads one element of summary.json's "facets"; `path` names it in errors ("facets[3]").
inline facet_record facet_record_from_json(const nlohmann::json& element, const std::string& path) {
    using namespace detail::json_io;
    const json& f = require_object(element, path);
    facet_record r;
    r.index = as_count(require(f, path, "index", "an integer"), child(path, "index"));
    r.valid = as_count(require(f, path, "valid", "an integer"), child(path, "valid"));
    r.boundary = as_count(require(f, path, "boundary", "an integer"), child(path, "boundary"));
    r.seconds = required_number(f, path, "seconds");
    const std::string t = as_string(require(f, path, "termination", "a string"), child(path, "termination"), "a string");
    const auto term = facet_termination_from_string(t);
    if (!term) fail(child(path, "termination"), "unknown termination \"" + t + "\"");
    r.termination = *term;
    if (const json* reason = find(f, "reason")) r.reason = as_string(*reason, child(path, "reason"), "a string");
    if (const json* dropped = find(f, "dropped")) r.dropped = as_count(*dropped, child(path, "dropped"));
    if (const json* from = find(f, "reused_from")) r.reused_from = as_count(*from, child(path, "reused_from"));
    if (const json* seed = find(f, "patch")) r.patch = as_count(*seed, child(path, "patch"));
    if (const json* reasons = find(f, "boundary_reasons")) {
        require_object(*reasons, child(path, "boundary_reasons"));
        for (std::size_t k = 0; k < boundary_reason_count; ++k)
            if (const json* v = find(*reasons, to_string(static_cast<boundary_reason>(k))))
                r.boundary_reasons[k] = as_count(*v, child(child(path, "boundary_reasons"), to_string(static_cast<boundary_reason>(k))));
    }
    return r;
}

/// The "mesh" object of summary.json and PLAN.json.
inline nlohmann::ordered_json mesh_record_json(const part_summary::mesh_record& m) {
    using namespace detail::json_io;
    ordered_json j = {{"path", m.path}, {"faces", m.faces}, {"scale", finite(m.scale, "mesh.scale")}};
    if (!m.digest.empty()) j["digest"] = m.digest;
    if (m.pose) {
        ordered_json rows = ordered_json::array();
        for (std::size_t r = 0; r < 4; ++r)
            rows.push_back(numbers(std::array<double, 4>{(*m.pose)[4 * r], (*m.pose)[4 * r + 1], (*m.pose)[4 * r + 2],
                                                         (*m.pose)[4 * r + 3]},
                                   element("mesh.pose", r)));
        j["pose"] = std::move(rows);
    }
    return j;
}

/// summary.json as JSON (keys in the documented order).
inline nlohmann::ordered_json part_summary_to_json(const part_summary& s) {
    using namespace detail::json_io;
    ordered_json j;
    j["format"] = part_summary_format;
    j["version"] = format_version;
    j["mesh"] = mesh_record_json(s.mesh);
    j["camera"] = camera_record_json(s.camera);
    j["task"] = task_record_json(s.task);
    const auto optional = [](const std::optional<double>& v, const std::string& path) {
        return v ? finite(*v, path) : ordered_json(nullptr);
    };
    j["settings"] = {{"position_eps", finite(s.settings.position_eps, "settings.position_eps")},
                     {"orientation_eps", finite(s.settings.orientation_eps, "settings.orientation_eps")},
                     {"max_boxes_per_facet", s.settings.max_boxes_per_facet},
                     {"time_limit_per_facet", optional(s.settings.time_limit_per_facet, "settings.time_limit_per_facet")},
                     {"time_limit", optional(s.settings.time_limit, "settings.time_limit")},
                     {"boundary", s.settings.boundary},
                     {"occlusion", s.settings.occlusion},
                     {"occlusion_checked", s.settings.occlusion_checked},
                     {"mesh_semantics", s.settings.mesh_semantics},
                     {"paving", s.settings.paving},
                     {"inner_contraction", s.settings.inner_contraction},
                     {"occlusion_cuts", s.settings.occlusion_cuts},
                     {"leaf_corner_boxes", s.settings.leaf_corner_boxes},
                     {"corner_depth", s.settings.corner_depth},
                     {"corner_rest_min_pieces", finite(s.settings.corner_rest_min_pieces, "settings.corner_rest_min_pieces")},
                     {"refine_seconds", optional(s.settings.refine_seconds, "settings.refine_seconds")},
                     {"grow", s.settings.grow},
                     {"max_boxes", s.settings.max_boxes ? ordered_json(*s.settings.max_boxes) : ordered_json(nullptr)},
                     {"facets", s.settings.facets.empty() ? ordered_json("all") : ordered_json(s.settings.facets)},
                     {"keep_largest", s.settings.keep_largest ? ordered_json(*s.settings.keep_largest) : ordered_json(nullptr)},
                     {"box_store", s.settings.box_store},
                     {"reuse", s.settings.reuse}};
    if (const auto& p = s.settings.patches)
        j["settings"]["patches"] = {{"max_cone", finite(p->max_cone, "settings.patches.max_cone")},
                                    {"max_extent", finite(p->max_extent, "settings.patches.max_extent")},
                                    {"max_members", p->max_members},
                                    {"max_loss", finite(p->max_loss, "settings.patches.max_loss")}};
    else
        j["settings"]["patches"] = false;
    if (s.survey) {
        const auto& v = *s.survey;
        j["survey"] = {{"bodies", v.bodies},
                       {"closed_bodies", v.closed_bodies},
                       {"inward_bodies", v.inward_bodies},
                       {"open_edges", v.open_edges},
                       {"nonmanifold_edges", v.nonmanifold_edges},
                       {"duplicate_faces", v.duplicate_faces},
                       {"intersecting_pairs", v.intersecting_pairs},
                       {"buried", v.buried},
                       {"covered", v.covered},
                       {"examples", v.examples}};
    }
    put_scene(j, s.scene);
    if (s.cad) {
        const auto& c = *s.cad;
        ordered_json faces = ordered_json::array();
        for (std::size_t i = 0; i < c.faces.faces.size(); ++i) {
            const cad_face& f = c.faces.faces[i];
            const std::string at = "cad.faces[" + std::to_string(i) + "]";
            faces.push_back({{"id", i},
                             {"name", f.name},
                             {"surface", f.surface},
                             {"area", finite(f.area, at + ".area")},
                             {"deviation", finite(f.deviation, at + ".deviation")},
                             {"facets", f.facets}});
        }
        j["cad"] = {{"unit", c.unit},
                    {"deflection", finite(c.deflection, "cad.deflection")},
                    {"angular_deflection", finite(c.angular_deflection, "cad.angular_deflection")},
                    {"dropped_triangles", c.dropped_triangles},
                    {"faces", std::move(faces)}};
    }
    ordered_json facets = ordered_json::array();
    for (const facet_record& f : s.facets) facets.push_back(facet_record_to_json(f));
    j["facets"] = std::move(facets);
    const auto& t = s.totals;
    j["totals"] = {{"seconds", finite(t.seconds, "totals.seconds")},
                   {"threads", t.threads},
                   {"ranks", t.ranks},
                   {"facets_selected", t.facets_selected},
                   {"facets", t.facets},
                   {"valid", t.valid},
                   {"boundary", t.boundary},
                   {"skipped", t.skipped},
                   {"termination", to_string(t.reason)},
                   {"interrupted", t.interrupted}};
    return j;
}

/// Reads the "mesh" object of summary.json and PLAN.json: path, faces, scale and, when given,
/// digest and pose.
inline part_summary::mesh_record mesh_record_from_json(const nlohmann::json& j) {
    using namespace detail::json_io;
    part_summary::mesh_record m;
    const json& mesh = require_object(j, "mesh");
    m.path = as_string(require(mesh, "mesh", "path", "a string"), "mesh.path", "a string");
    m.faces = as_count(require(mesh, "mesh", "faces", "an integer"), "mesh.faces");
    m.scale = required_number(mesh, "mesh", "scale");
    if (const json* d = find(mesh, "digest")) m.digest = as_string(*d, "mesh.digest", "a string");
    if (const json* p = find(mesh, "pose")) {
        const auto rows = as_matrix<4, 4>(*p, "mesh.pose");
        std::array<double, 16> flat{};
        for (std::size_t r = 0; r < 4; ++r)
            for (std::size_t c = 0; c < 4; ++c) flat[4 * r + c] = rows[r][c];
        part_pose_from_matrix(std::vector<double>(flat.begin(), flat.end()), "mesh.pose");  // a rigid motion, or say so
        m.pose = flat;
    }
    return m;
}

/// Reads summary.json's "cad" of a mesh of `facet_count` facets; face ids must be 0, 1, ... in
/// order, and the faces' facet lists a partition of the facets (invalid_argument naming the field).
inline cad_model cad_model_from_json(const nlohmann::json& c, std::size_t facet_count) {
    using namespace detail::json_io;
    cad_model r;
    require_object(c, "cad");
    r.unit = as_string(require(c, "cad", "unit", "a string"), "cad.unit", "a string");
    r.deflection = required_number(c, "cad", "deflection");
    r.angular_deflection = required_number(c, "cad", "angular_deflection");
    if (const json* v = find(c, "dropped_triangles")) r.dropped_triangles = as_count(*v, "cad.dropped_triangles");
    const json& faces = require(c, "cad", "faces", "an array");
    if (!faces.is_array()) fail("cad.faces", "expected an array, got " + describe(faces));
    r.faces.face_of.assign(facet_count, 0);
    for (std::size_t i = 0; i < faces.size(); ++i) {
        const std::string at = element("cad.faces", i);
        const json& f = require_object(faces[i], at);
        if (as_count(require(f, at, "id", "an integer"), child(at, "id")) != i)
            fail(child(at, "id"), "expected " + std::to_string(i) + " (faces in id order)");
        cad_face face;
        face.name = as_string(require(f, at, "name", "a string"), child(at, "name"), "a string");
        face.surface = as_string(require(f, at, "surface", "a string"), child(at, "surface"), "a string");
        face.area = required_number(f, at, "area");
        face.deviation = required_number(f, at, "deviation");
        const json& list = require(f, at, "facets", "an array");
        if (!list.is_array()) fail(child(at, "facets"), "expected an array, got " + describe(list));
        for (std::size_t k = 0; k < list.size(); ++k) {
            const std::size_t facet = as_count(list[k], element(child(at, "facets"), k));
            if (facet >= facet_count)
                fail(element(child(at, "facets"), k),
                     "facet " + std::to_string(facet) + " is out of range (mesh.faces = " + std::to_string(facet_count) + ")");
            face.facets.push_back(static_cast<std::uint32_t>(facet));
            r.faces.face_of[facet] = static_cast<std::uint32_t>(i);
        }
        r.faces.faces.push_back(std::move(face));
    }
    try {
        r.faces.validate(facet_count);
    } catch (const mesh_error& e) {
        fail("cad.faces", e.what());
    }
    return r;
}

/// Reads summary.json back (what part_summary_to_json writes; extra fields are ignored).
/// Throws invalid_argument naming the JSON path of a missing or wrong field.
inline part_summary part_summary_from_json(const nlohmann::json& j) {
    using namespace detail::json_io;
    const certipose::detail::round_to_nearest_scope nearest;
    part_summary s;
    require_object(j, "");
    check_format(j, part_summary_format);
    s.mesh = mesh_record_from_json(require(j, "", "mesh", "an object"));
    s.camera = camera_record_from_json(require(j, "", "camera", "an object"));
    s.task = task_record_from_json(require(j, "", "task", "an object"));
    const json& settings = require_object(require(j, "", "settings", "an object"), "settings");
    s.settings.position_eps = required_number(settings, "settings", "position_eps");
    s.settings.orientation_eps = required_number(settings, "settings", "orientation_eps");
    if (const json* v = find(settings, "max_boxes_per_facet")) s.settings.max_boxes_per_facet = as_count(*v, "settings.max_boxes_per_facet");
    s.settings.time_limit_per_facet = optional_number(settings, "settings", "time_limit_per_facet");
    s.settings.time_limit = optional_number(settings, "settings", "time_limit");
    if (const json* v = find(settings, "boundary"); v && v->is_boolean()) s.settings.boundary = v->get<bool>();
    if (const json* v = find(settings, "occlusion"); v && v->is_string()) s.settings.occlusion = v->get<std::string>();
    if (const json* v = find(settings, "occlusion_checked"); v && v->is_boolean()) s.settings.occlusion_checked = v->get<bool>();
    if (const json* v = find(settings, "mesh_semantics"); v && v->is_string()) s.settings.mesh_semantics = v->get<std::string>();
    if (const json* v = find(settings, "paving"); v && v->is_string()) s.settings.paving = v->get<std::string>();
    if (const json* v = find(settings, "keep_largest"); v && !v->is_null())
        s.settings.keep_largest = as_count(*v, "settings.keep_largest");
    if (const json* v = find(settings, "box_store")) {
        s.settings.box_store = as_string(*v, "settings.box_store", "\"jsonl\", \"binary\" or \"both\"");
        if (s.settings.box_store != "jsonl" && s.settings.box_store != "binary" && s.settings.box_store != "both")
            fail("settings.box_store", "expected \"jsonl\", \"binary\" or \"both\", got \"" + s.settings.box_store + "\"");
    }
    s.scene = scene_from_json(j);
    if (const json* c = find(j, "cad")) s.cad = cad_model_from_json(*c, s.mesh.faces);
    const json& facets = require(j, "", "facets", "an array");
    if (!facets.is_array()) fail("facets", "expected an array, got " + describe(facets));
    for (std::size_t i = 0; i < facets.size(); ++i) s.facets.push_back(facet_record_from_json(facets[i], element("facets", i)));
    const json& totals = require_object(require(j, "", "totals", "an object"), "totals");
    auto& t = s.totals;
    t.seconds = required_number(totals, "totals", "seconds");
    const auto count = [&](std::string_view key, std::size_t& out) {
        if (const json* v = find(totals, key)) out = as_count(*v, child("totals", key));
    };
    count("threads", t.threads);
    count("ranks", t.ranks);
    count("facets_selected", t.facets_selected);
    count("facets", t.facets);
    count("valid", t.valid);
    count("boundary", t.boundary);
    count("skipped", t.skipped);
    if (const json* v = find(totals, "termination")) {
        const auto reason = termination_from_string(as_string(*v, "totals.termination", "a string"));
        if (!reason) fail("totals.termination", "unknown termination");
        t.reason = *reason;
    }
    if (const json* v = find(totals, "interrupted"); v && v->is_boolean()) t.interrupted = v->get<bool>();
    return s;
}

/// Reads <dir>/summary.json. Throws io_error if it is missing or not JSON.
inline part_summary read_part_summary(const std::filesystem::path& dir) {
    const std::filesystem::path file = dir / "summary.json";
    return detail::json_io::with_source(file.string(), [&] {
        return part_summary_from_json(
            detail::json_io::parse(detail::json_io::read_text_file(file, "read_part_summary"), file.string()));
    });
}

/// One line of boxes.jsonl.
struct part_box {
    std::size_t facet = 0;
    box_record box;
    bool occlusion_checked = true;
};

/// Calls `visit(part_box)` for every line of `path` (a boxes.jsonl), in order, without holding
/// the file in memory. Throws io_error(path) if it cannot be read and invalid_argument naming
/// the line (e.g. "boxes.jsonl:12.position") for a malformed one.
inline void read_boxes_jsonl(const std::filesystem::path& path, const std::function<void(const part_box&)>& visit) {
    using namespace detail::json_io;
    std::ifstream in(path, std::ios::binary);
    if (!in) throw io_error(path.string(), "read_boxes_jsonl: cannot open " + path.string());
    const certipose::detail::round_to_nearest_scope nearest;
    std::string line;
    for (std::size_t n = 1; std::getline(in, line); ++n) {
        if (line.empty()) continue;
        const std::string where = path.filename().string() + ":" + std::to_string(n);
        const json j = parse(line, where);
        require_object(j, where);
        part_box b;
        b.facet = as_count(require(j, where, "facet", "an integer"), child(where, "facet"));
        const std::string cls = as_string(require(j, where, "class", "\"valid\" or \"boundary\""), child(where, "class"),
                                          "\"valid\" or \"boundary\"");
        if (cls == "valid") b.box.cls = box_class::valid;
        else if (cls == "boundary") b.box.cls = box_class::boundary;
        else fail(child(where, "class"), "unknown class \"" + cls + "\"");
        b.box.position = as_matrix<3, 2>(require(j, where, "position", "3 intervals"), child(where, "position"));
        b.box.orientation = as_matrix<3, 2>(require(j, where, "orientation", "3 intervals"), child(where, "orientation"));
        check_bounds(b.box.position, child(where, "position"));
        check_bounds(b.box.orientation, child(where, "orientation"));
        if (const json* u = find(j, "undecided")) {
            const std::string name = as_string(*u, child(where, "undecided"), "a string");
            b.box.reason = boundary_reason_from_string(name);
            if (!b.box.reason) fail(child(where, "undecided"), "unknown reason \"" + name + "\"");
        }
        if (const json* o = find(j, "occlusion")) b.occlusion_checked = !(o->is_string() && o->get<std::string>() == "unchecked");
        visit(b);
    }
    if (in.bad()) throw io_error(path.string(), "read_boxes_jsonl: read error in " + path.string());
}

}  // namespace certipose
