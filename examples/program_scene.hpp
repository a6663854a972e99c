// examples/program_scene.hpp — the inputs of the certipose programs, the part that needs the mesh
// reader (not a library header; their flags are declared and checked in program_skeleton.hpp and
// program_support.hpp): `read_inputs`
// reads the part (a mesh, or a STEP file when the programs are built with certipose::step:
// CERTIPOSE_PROGRAMS_READ_STEP), the --occluder meshes (same reader, same errors), the camera and the placement
// tolerance, always in that order; the scene's records for the outputs (io/scene_record.hpp);
// and naming an occluder's file in the occlusion policy's errors (the policies check that every
// scene mesh is a closed solid and call the extra meshes "occluder 0", "occluder 1", ... in the
// order given).
#pragma once

#include "program_skeleton.hpp"

#include <certipose/cgal.hpp>
#include <certipose/io/json.hpp>
#include <certipose/io/output_files.hpp>
#include <certipose/io/scene_record.hpp>
#include <certipose/io/step_path.hpp>
#if defined(CERTIPOSE_PROGRAMS_READ_STEP)
#include <certipose/io/read_step.hpp>
#endif

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace certipose_program {

/// The occluders of a run, read, and what the outputs record of the scene.
struct scene {
    std::vector<certipose::triangle_mesh> occluders;
    certipose::scene_record record;
};

/// Reads every --occluder with its scale (io_error / mesh_error naming the file, as for --mesh).
inline scene read_scene(const scene_arguments& args, stage_line* stage = nullptr) {
    scene s;
    s.occluders.reserve(args.occluders.size());
    for (const auto& o : args.occluders) {
        if (stage) stage->show("reading " + o.path.string());
        if (certipose::is_step_path(o.path))
            throw certipose::io_error(o.path.string(), "--occluder " + o.path.string() +
                                                           ": occluders are read as meshes (OFF, OBJ, PLY, STL), not STEP; "
                                                           "export the fixture as a mesh in metres");
        s.occluders.push_back(certipose::read_mesh(o.path, {.scale = o.scale}));
        s.record.occluders.push_back(certipose::describe_occluder(o.path.string(), o.scale, s.occluders.back()));
    }
    s.record.regions = args.regions;
    return s;
}

/// The --camera file as a camera_task: our camera/task JSON as read_camera_task reads it, or a
/// calibration file (chosen by content, certipose::read_camera_input) with --working-distance and
/// --min-view-angle (parse_scene_options made sure they are given exactly for a calibration file).
/// io_error / invalid_argument name the file.
inline certipose::camera_task read_camera(const std::filesystem::path& camera, const scene_arguments& args) {
    auto input = certipose::read_camera_input(camera);
    if (auto* task = std::get_if<certipose::camera_task>(&input)) return std::move(*task);
    if (!args.working_distance || !args.min_view_angle)  // parse_scene_options checked this
        throw certipose::invalid_argument("--working-distance", camera.string() +
                                                                    ": a calibration file needs --working-distance and --min-view-angle");
    certipose::inspection_task task;
    task.min_view_angle = *args.min_view_angle;
    try {
        return certipose::camera_task_from_calibration(std::get<certipose::calibration>(input), *args.working_distance, task);
    } catch (const certipose::invalid_argument& e) {
        throw certipose::invalid_argument(e.field(), camera.string() + ": " + e.what());
    }
}

/// The task with the run's placement tolerance: --part-tolerance / --datum when given (they
/// replace the camera JSON's task.placement_tolerance), the datum resolved to the part's centroid
/// when neither gives one, so that every output records the datum the boxes were certified about.
inline void apply_placement(certipose::inspection_task& task, const scene_arguments& args, const certipose::triangle_mesh& mesh) {
    if (args.placement) task.placement = *args.placement;
    if (task.placement && !task.placement->datum) task.placement->datum = certipose::surface_centroid(mesh);
}

/// What a program reads before it solves.
struct program_inputs {
    certipose::triangle_mesh mesh;            ///< --mesh × --scale, or a STEP file's tessellation (metres)
    std::optional<certipose::cad_model> cad;  ///< a STEP file's faces and tessellation; none for a mesh
    certipose::camera_task camera;            ///< --camera, its task with the run's placement tolerance
    scene extra;                              ///< the --occluder meshes and the scene's record
};

/// The part as read, before --part-pose: a mesh file read by read_mesh (× --scale), or a STEP
/// file read by read_step with --deflection; io_error names the file, also when this build of the
/// programs reads no STEP.
inline std::pair<certipose::triangle_mesh, std::optional<certipose::cad_model>> read_part_file(const input_arguments& args) {
    if (!certipose::is_step_path(args.mesh)) return {certipose::read_mesh(args.mesh, {.scale = args.scale}), std::nullopt};
#if defined(CERTIPOSE_PROGRAMS_READ_STEP)
    certipose::step_options opt;
    opt.deflection = args.deflection;
    if (args.angular_deflection) opt.angular_deflection = *args.angular_deflection;
    certipose::step_part p = certipose::read_step(args.mesh, opt);
    return {std::move(p.mesh), std::move(p.cad)};
#else
    throw certipose::io_error(args.mesh.string(), args.mesh.string() +
                                                      ": a STEP file, and these programs were built without a STEP reader "
                                                      "(OpenCASCADE was not found: Debian libocct-data-exchange-dev); "
                                                      "give a mesh (OFF, OBJ, PLY, STL) or rebuild");
#endif
}

/// The part in the cell: read_part_file, moved by --part-pose (the same faces, so a STEP part's
/// CAD faces still name its triangles). A pose that makes a sliver exactly degenerate is a
/// mesh_error naming the face and --part-pose.
inline std::pair<certipose::triangle_mesh, std::optional<certipose::cad_model>> read_part(const input_arguments& args) {
    auto part = read_part_file(args);
    if (!args.part_pose) return part;
    try {
        part.first = certipose::posed(part.first, *args.part_pose);
    } catch (const certipose::mesh_error& e) {
        throw certipose::mesh_error(args.mesh.string() + " after --part-pose: " + e.what());
    }
    return part;
}

/// What the outputs record of --part-pose (the mesh record's "pose"): its row-major 4×4, or none.
inline std::optional<std::array<double, 16>> pose_record(const input_arguments& args) {
    if (!args.part_pose) return std::nullopt;
    return args.part_pose->matrix();
}

/// Reads the inputs in one order (the part, the occluders, the camera), then resolves the
/// placement tolerance against the mesh; io_error / mesh_error / invalid_argument name the file.
/// `stage` says what is being read on a terminal.
inline program_inputs read_inputs(const input_arguments& args, stage_line& stage) {
    stage.show((certipose::is_step_path(args.mesh) ? "reading and tessellating " : "reading ") + args.mesh.string());
    auto [mesh, cad] = read_part(args);
    scene extra = read_scene(args.scene, &stage);
    stage.show("reading " + args.camera.string());
    certipose::camera_task camera = read_camera(args.camera, args.scene);
    apply_placement(camera.task, args.scene, mesh);
    stage.done();
    return {std::move(mesh), std::move(cad), std::move(camera), std::move(extra)};
}

/// Returns `build()` (a solver being built); a mesh_error of the occlusion policy about
/// "occluder i" is re-thrown as "--occluder FILE: <the policy's message>".
template <class Build>
decltype(auto) naming_occluders(const scene_arguments& args, Build&& build) {
    try {
        return build();
    } catch (const certipose::mesh_error& e) {
        const std::string what = e.what();
        static const std::string tag = "occluder ";
        for (std::size_t at = what.find(tag); at != std::string::npos; at = what.find(tag, at + 1)) {
            std::size_t end = at + tag.size(), i = 0;
            if (end >= what.size() || !std::isdigit(static_cast<unsigned char>(what[end]))) continue;
            for (; end < what.size() && std::isdigit(static_cast<unsigned char>(what[end])); ++end)
                i = 10 * i + static_cast<std::size_t>(what[end] - '0');
            if (i < args.occluders.size())
                throw certipose::mesh_error("--occluder " + args.occluders[i].path.string() + ": " + what +
                                            " (with --mesh-semantics solid every occluder must be a closed solid)");
        }
        throw;
    }
}

/// `Solver` (a pose_solver or a part_solver of the programs' pipeline,
/// certipose::calibrated_pipeline) for the inputs: says on a terminal that the occlusion scene is
/// being built (seconds for a large mesh), and names an occluder's file in the policy's errors.
/// The caller clears `stage` once it has the solver.
template <class Solver>
Solver build_solver(const input_arguments& args, const program_inputs& in, stage_line& stage) {
    stage.show("building the occlusion scene of the " + std::to_string(in.mesh.num_faces()) + " faces");
    return naming_occluders(args.scene, [&] {
        return Solver(in.mesh, in.camera.calibrated(), in.camera.task,
                      {.occluders = in.extra.occluders, .semantics = args.scene.semantics});
    });
}

/// What a triangle-soup survey found, in one line: "6 bodies (6 closed), 2272 intersecting
/// face pairs, 836 buried facets" (the bodies always; each kind of defect when there is one).
inline std::string survey_text(const certipose::mesh_survey& s) {
    std::string out = std::to_string(s.bodies) + (s.bodies == 1 ? " body" : " bodies") + " (" +
                      std::to_string(s.closed_bodies) + " closed)";
    const auto add = [&](std::size_t n, const char* what) {
        if (n) out += ", " + std::to_string(n) + " " + what;
    };
    add(s.intersecting_pairs, "intersecting face pairs");
    add(s.duplicate_faces, "duplicate faces");
    add(s.open_edges, "open edges");
    add(s.nonmanifold_edges, "non-manifold edges");
    add(s.inward_bodies, "inward-facing bodies");
    add(s.buried, "buried facets");
    add(s.covered, "covered facets");
    return out;
}

/// When the occlusion reads the scene as a triangle soup, says so on stderr with what the
/// survey found and an example of each kind (unless quiet): the run goes on, but the user
/// should know their mesh is not a clean solid and which facets are skipped for it.
template <class Occlusion>
void warn_about_scene(const char* program, const Occlusion& occlusion, bool quiet) {
    if constexpr (requires { occlusion.survey(); }) {
        const certipose::mesh_survey* s = occlusion.survey();
        if (!s || quiet) return;
        std::cerr << program << ": warning: occlusion reads the scene as a triangle soup (a sight line is blocked by "
                  << "any triangle; docs/occlusion.md#dirty-meshes)";
        if (!occlusion.why_not_solid().empty())
            std::cerr << " because it is not a set of clean closed solids: " << occlusion.why_not_solid();
        std::cerr << "\n" << program << ": warning: " << survey_text(*s) << "\n";
        for (const auto& e : s->examples) std::cerr << program << ": warning:   " << e << "\n";
    }
}

/// Says on stderr (unless quiet) when the part's size makes the task impossible for the camera
/// because of a unit, naming the likely one: a part over 100 times the camera's farthest
/// distance d_max across (a millimetre mesh read as metres: 200 m seen from 0.8 m), or one that
/// would span fewer than 4 pixels from the nearest distance d_min (a metre mesh scaled as if it
/// were millimetres). A real part can be large (cameras then see it face by face) or small, but
/// not by factors like these. A STEP file carries its unit: not checked.
template <class Camera>
void warn_about_units(const char* program, const input_arguments& args, const certipose::triangle_mesh& mesh,
                      const Camera& camera, certipose::distance_range range, bool quiet) {
    if (quiet || certipose::is_step_path(args.mesh) || mesh.num_faces() == 0) return;
    const auto brief = [](double x) {  // 3 significant digits: for a person, not a file
        std::ostringstream s;
        s << std::setprecision(3) << x;
        return s.str();
    };
    const double size = mesh.bbox().diagonal().norm();
    const std::string across = brief(size) + " m across";
    const std::string scaled = args.scale == 1.0 ? "" : " after --scale " + certipose::detail::format_double(args.scale);
    if (std::isfinite(range.max) && size > 100 * range.max) {
        std::cerr << program << ": warning: the part is " << across << scaled << ", and the camera sees from at most "
                  << brief(range.max) << " m: is the mesh in millimetres? Its coordinates are read "
                  << "as metres: give --scale 0.001 (inches: --scale 0.0254)\n";
    } else if (range.min > 0 && size * camera.intrinsics()(0, 0) / range.min < 4) {
        std::cerr << program << ": warning: the part is " << across << scaled << ", fewer than 4 pixels from the nearest "
                  << "distance the camera sees it from (" << brief(range.min)
                  << " m): are its coordinates metres already? " << (args.scale == 1.0 ? "Check the mesh's unit"
                                                                                        : "Drop --scale")
                  << " (docs/conventions.md#units)\n";
    }
    // A placement tolerance the size of the part (millimetres typed as metres: 2,2,2) leaves no
    // box that holds for every placement; say which unit it is read in.
    if (args.scene.placement) {
        const auto& t = args.scene.placement->translation;
        const double most = std::max({t[0], t[1], t[2]});
        if (most > 0.25 * size)
            std::cerr << program << ": warning: --part-tolerance lets the part slide by " << brief(most) << " m, more than a "
                      << "quarter of the part (" << across << "): is it in millimetres? It is read as metres: " << brief(most / 1000)
                      << " for " << brief(most) << " mm\n";
        if (std::isfinite(range.max) && args.scene.placement->rotation * range.max > 0.25 * size)
            std::cerr << program << ": warning: --part-tolerance turns the part by " << brief(args.scene.placement->rotation)
                      << " rad (" << brief(args.scene.placement->rotation * 180 / std::numbers::pi) << " degrees), which at the "
                      << "camera's distance moves it by more than a quarter of its size: is that what the fixture allows?\n";
    }
}

/// "1 occluder, 1 keep-out region" (empty without any): for the programs' summary lines.
inline std::string scene_text(const scene_arguments& args) {
    std::string s;
    const auto add = [&](std::size_t n, const char* what) {
        if (n == 0) return;
        if (!s.empty()) s += ", ";
        s += std::to_string(n) + " " + what + (n == 1 ? "" : "s");
    };
    add(args.occluders.size(), "occluder");
    add(args.regions.keep_in.size(), "keep-in region");
    add(args.regions.keep_out.size(), "keep-out region");
    if (args.placement) {
        if (!s.empty()) s += ", ";
        const auto& t = *args.placement;
        s += "part tolerance " + certipose::detail::format_double(t.translation[0]) + "," +
             certipose::detail::format_double(t.translation[1]) + "," + certipose::detail::format_double(t.translation[2]) +
             " m, " + certipose::detail::format_double(t.rotation) + " rad";
    }
    return s;
}

}  // namespace certipose_program
