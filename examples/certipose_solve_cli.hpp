// examples/certipose_solve_cli.hpp — the command line of `certipose-solve` (CLI11).
//
// Usage (docs/io.md):
//   certipose-solve --mesh PART --facet N --camera CAMERA --position-eps 0.1
//                   --orientation-eps 0.38 --out RESULT.json [--ply BOXES.ply]
//                   [--occlusion aabb|boolean|none] [--scale S] [--max-boxes N]
//                   [--time-limit SECONDS] [--occluder MESH[:SCALE]]... [--keep-in REGION]...
//                   [--keep-out REGION]... [--part-tolerance TX,TY,TZ,ROT [--datum X,Y,Z]]
//                   [--working-distance DMIN,DMAX --min-view-angle RAD] [--quiet]
// `parse_arguments` turns argv into `arguments` or into an exit code. Every mistake — unknown
// or missing option, malformed number, non-positive threshold, missing input file, output
// directory that does not exist — prints ONE line "certipose-solve: error: ..." on `err` and
// gives exit code 2 (usage error), before any work is done; --help prints the usage on `out`
// and gives 0. Numbers are parsed with std::from_chars, so "1e-1" works and "0.1abc", "nan",
// "-1" or "0x10" do not slip through. Not a library header: it is shared by the program and
// its tests only.
#pragma once

#include "program_support.hpp"

#include <certipose/io/output_files.hpp>

#include <CLI/CLI.hpp>

#include <charconv>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace certipose_solve {

using certipose_program::exit_failure;
using certipose_program::exit_ok;
using certipose_program::exit_usage;

enum class occlusion_mode { aabb, boolean, none };

inline const char* to_string(occlusion_mode m) noexcept {
    switch (m) {
        case occlusion_mode::aabb: return "aabb";
        case occlusion_mode::boolean: return "boolean";
        case occlusion_mode::none: return "none";
    }
    return "?";
}

/// The validated command line.
struct arguments {
    std::filesystem::path mesh;    ///< --mesh: OFF, OBJ, PLY or STL
    std::size_t facet = 0;         ///< --facet: face index in file order
    std::filesystem::path camera;  ///< --camera: camera/task JSON or calibration file (docs/io.md)
    double position_eps = 0.1;     ///< --position-eps, metres
    double orientation_eps = 0.38; ///< --orientation-eps, radians
    std::filesystem::path out;     ///< --out: result JSON
    std::optional<std::filesystem::path> ply;           ///< --ply: boxes for MeshLab/ParaView
    occlusion_mode occlusion = occlusion_mode::aabb;    ///< --occlusion
    double scale = 1.0;            ///< --scale: mesh coordinates × S (e.g. 0.001 for mm)
    std::optional<std::size_t> max_boxes;               ///< --max-boxes budget
    std::optional<double> time_limit_seconds;           ///< --time-limit budget
    bool paper_paving = false;     ///< --paper-paving: no inner contraction, occlusion cuts or corner boxes
    std::optional<std::size_t> corner_depth;            ///< --corner-depth: corner boxes per leaf in a row
    std::optional<double> corner_rest;                  ///< --corner-rest: a rest box's narrowest side for a corner box, in minimal pieces
    std::optional<double> refine_seconds;               ///< --refine: anytime refinement budget
    bool grow = false;             ///< --grow: widen the VALID boxes
    bool quiet = false;            ///< --quiet: no summary, no progress
    /// --occluder, --keep-in, --keep-out (program_support.hpp)
    certipose_program::scene_arguments scene{};
};

/// `args` set: run with them. Unset: exit with `exit_code` (0 after --help).
struct parse_outcome {
    std::optional<arguments> args;
    int exit_code = exit_ok;
};

namespace detail {
using certipose_program::check_output;
using certipose_program::one_line;
using certipose_program::parse_corner_depth;
using certipose_program::parse_corner_rest;
using certipose_program::parse_count;
using certipose_program::parse_double;
using certipose_program::usage_error;
}  // namespace detail

/// Parses the command line (see the header comment). Writes only the --help text to `out` and
/// only one error line to `err`.
inline parse_outcome parse_arguments(int argc, const char* const* argv, std::ostream& out,
                                     std::ostream& err) {
    CLI::App app{"certipose-solve: certified camera pose boxes from which a facet of a part can "
                 "be inspected (paper: Parrott, Pickard, Dubay 2023). Writes the result JSON of "
                 "docs/io.md and optionally a PLY of the boxes.",
                 "certipose-solve"};
    std::string mesh, camera, output, ply, facet, position_eps, orientation_eps, scale,
        max_boxes, time_limit, refine, corner_depth, corner_rest, occlusion = "aabb";
    bool quiet = false, paper_paving = false, grow = false;
    app.add_option("--mesh", mesh, "part mesh: OFF, OBJ, PLY or STL (triangles only)")
        ->type_name("PART")
        ->required()
        ->check(CLI::ExistingFile);
    app.add_option("--facet", facet, "index of the facet of interest (file order, from 0)")
        ->type_name("N")
        ->required();
    app.add_option("--camera", camera, "camera/task JSON, or an OpenCV/ROS calibration file with --working-distance and --min-view-angle (docs/io.md)")
        ->type_name("CAMERA")
        ->required()
        ->check(CLI::ExistingFile);
    app.add_option("--position-eps", position_eps, "position threshold, metres (paper: 0.1)")
        ->type_name("METRES")
        ->required();
    app.add_option("--orientation-eps", orientation_eps,
                   "orientation threshold, radians (paper: 0.38)")
        ->type_name("RADIANS")
        ->required();
    app.add_option("--out", output, "result JSON to write (atomically)")
        ->type_name("RESULT.json")
        ->required();
    app.add_option("--ply", ply, "also write the part, facet and boxes as a coloured PLY")
        ->type_name("BOXES.ply");
    app.add_option("--occlusion", occlusion, "occlusion test: aabb (default), boolean or none")
        ->type_name("MODE")
        ->check(CLI::IsMember({"aabb", "boolean", "none"}));
    app.add_option("--scale", scale, "multiply mesh coordinates by S (e.g. 0.001 for mm)")
        ->type_name("S");
    app.add_option("--max-boxes", max_boxes, "stop after N boxes (result marked box_budget)")
        ->type_name("N");
    app.add_option("--time-limit", time_limit, "stop after SECONDS (result marked deadline)")
        ->type_name("SECONDS");
    app.add_flag("--paper-paving", paper_paving,
                 "pave as the paper does: bisect partly valid boxes, no inner contraction, occlusion cuts or corner boxes");
    app.add_option("--corner-depth", corner_depth,
                   "corner boxes one undecided leaf may give in a row, 1-8 (default 2; 1 writes fewer boxes)")
        ->type_name("N");
    app.add_option("--corner-rest", corner_rest,
                   "a rest box gives a corner box only when each side is at least PIECES minimal pieces "
                   "(eps/10; default 3, 2 certifies more, slower)")
        ->type_name("PIECES");
    app.add_option("--refine", refine,
                   "keep refining below position-eps, largest undecided box first, for SECONDS")
        ->type_name("SECONDS");
    app.add_flag("--grow", grow, "widen the VALID boxes: merge neighbours, move faces out while certified");
    certipose_program::scene_options_text scene;
    certipose_program::add_scene_options(app, scene);
    app.add_flag("--quiet,-q", quiet, "print nothing but errors");

    const auto fail = [&](const std::string& message) {
        err << "certipose-solve: error: " << detail::one_line(message)
            << " (run with --help for usage)\n";
        return parse_outcome{std::nullopt, exit_usage};
    };
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        out << app.help();
        return {std::nullopt, exit_ok};
    } catch (const CLI::CallForAllHelp&) {
        out << app.help();
        return {std::nullopt, exit_ok};
    } catch (const CLI::ParseError& e) {
        return fail(e.what());
    }

    try {
        arguments a;
        a.mesh = mesh;
        a.camera = camera;
        a.facet = detail::parse_count("--facet", facet, 0);
        a.position_eps = detail::parse_double("--position-eps", position_eps,
                                              "a positive finite number of metres");
        a.orientation_eps = detail::parse_double("--orientation-eps", orientation_eps,
                                                 "a positive finite number of radians");
        a.out = output;
        detail::check_output("--out", a.out);
        std::vector<certipose::named_path> outputs{{"--out", a.out}};
        if (!ply.empty()) {
            a.ply = ply;
            detail::check_output("--ply", *a.ply);
            outputs.push_back({"--ply", *a.ply});
        }
        a.scene = certipose_program::parse_scene_options(scene, a.camera);
        std::vector<certipose::named_path> inputs{{"--mesh", a.mesh}, {"--camera", a.camera}};
        for (const auto& o : a.scene.occluders) inputs.push_back({"--occluder", o.path});
        // `--out part.off`, `--out ./camera.json`, `--ply` onto `--out`: refused, nothing run.
        try {
            certipose::refuse_overwriting_inputs(inputs, outputs);
        } catch (const certipose::invalid_argument& e) {
            throw detail::usage_error(e.what());
        }
        a.occlusion = occlusion == "boolean" ? occlusion_mode::boolean
                      : occlusion == "none"  ? occlusion_mode::none
                                             : occlusion_mode::aabb;
        if (!scale.empty())
            a.scale = detail::parse_double("--scale", scale, "a positive finite factor");
        if (!max_boxes.empty()) a.max_boxes = detail::parse_count("--max-boxes", max_boxes, 1);
        if (!time_limit.empty())
            a.time_limit_seconds =
                detail::parse_double("--time-limit", time_limit, "a positive finite number of seconds");
        if (!refine.empty())
            a.refine_seconds = detail::parse_double("--refine", refine, "a positive finite number of seconds");
        a.paper_paving = paper_paving;
        if (!corner_depth.empty()) a.corner_depth = detail::parse_corner_depth(corner_depth);
        if (!corner_rest.empty()) a.corner_rest = detail::parse_corner_rest(corner_rest);
        a.grow = grow;
        a.quiet = quiet;
        return {std::move(a), exit_ok};
    } catch (const detail::usage_error& e) {
        return fail(e.what());
    }
}

}  // namespace certipose_solve
