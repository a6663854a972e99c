// examples/program_skeleton.hpp — the skeleton every certipose program shares, so that a new
// program is its own options and a body (not a library header).
//
// A program is a type:
//
//   struct my_program {
//       static constexpr const char* name = "certipose-x";
//       static constexpr const char* description = "certipose-x: what it does.";
//       struct options { ... };                      // the command line as text (CLI11 fills it)
//       struct arguments {                           // the command line checked
//           std::vector<certipose::named_path> files_read() const;     // no output may be one
//           std::vector<certipose::named_path> files_written() const;
//           ...
//       };
//       static void declare(CLI::App&, options&);    // its flags (the shared ones by the helpers below)
//       static arguments check(const options&);      // usage_error naming the offending text
//       static int run(const arguments&, const interruption&);  // the body: an exit code
//   };
//   int main(int argc, char** argv) { return certipose_program::program_main<my_program>(argc, argv); }
//
// `program_main` then does what every program does the same way: --help (exit 0); a bad command
// line, or an output that is one of the inputs, as one line "<name>: error: ..." (exit 2) before
// any work; SIGINT/SIGTERM as a stop request for the body (`interruption`); an error the body
// throws as one line "<name>: ..." (exit 1).
//
// The flags several programs share are declared once here, each with its parser:
// - the inputs: --mesh (a mesh, or a STEP file with --deflection), --camera, --scale, --part-pose and the
//   scene options of program_support.hpp
//   (`add_input_options`, `parse_input_options`; program_scene.hpp reads them, `read_inputs`);
// - the facet solver: --position-eps, --orientation-eps, the two per-facet budgets and the
//   paving's flags (`add_solver_options`, `parse_solver_options`), read into
//   certipose::solve_settings, which certipose::to_solve_options turns into solve_options as
//   the Python module does;
// - --occlusion (`add_occlusion_option`), read by certipose::parse_occlusion_choice, whose
//   certipose::visit_occlusion is the one dispatch from the name to a pipeline type.
#pragma once

#include "program_support.hpp"

#include <certipose/io/output_files.hpp>
#include <certipose/io/step_path.hpp>
#include <certipose/solver/occlusion_choice.hpp>
#include <certipose/solver/solve_settings.hpp>

#include <CLI/CLI.hpp>

#include <filesystem>
#include <iostream>
#include <numbers>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace certipose_program {

// ---- the inputs -----------------------------------------------------------------------------

/// --mesh, --camera, --scale, --deflection, --part-pose and the scene options as given.
struct input_options_text {
    std::string mesh, camera, scale, deflection, part_pose;
    scene_options_text scene;
};

/// The inputs of a program that reads a part and a camera, checked.
struct input_arguments {
    std::filesystem::path mesh;    ///< --mesh: OFF, OBJ, PLY, STL, or STEP (.step, .stp)
    std::filesystem::path camera;  ///< --camera: camera/task JSON or a calibration file
    double scale = 1.0;            ///< --scale: mesh coordinates × S (not for STEP: it has its unit)
    std::optional<double> deflection;          ///< --deflection LIN (STEP only; unset: the reader's default)
    std::optional<double> angular_deflection;  ///< --deflection LIN,ANG (STEP only)
    std::optional<certipose::part_pose> part_pose;  ///< --part-pose: the part moved into the cell's frame
    scene_arguments scene;         ///< --occluder, --keep-in, --keep-out, --part-tolerance, ...

    /// The files read: no output may be one of them.
    std::vector<certipose::named_path> paths() const {
        std::vector<certipose::named_path> p{{"--mesh", mesh}, {"--camera", camera}};
        for (const auto& o : scene.occluders) p.push_back({"--occluder", o.path});
        return p;
    }
};

/// Adds --mesh, --camera, --scale, --deflection, --part-pose and the scene options to `app`.
inline void add_input_options(CLI::App& app, input_options_text& text,
                              const char* scale_help = "multiply mesh coordinates by S (e.g. 0.001 for mm; not for STEP)") {
    app.add_option("--mesh", text.mesh,
                   "the part: a mesh (OFF, OBJ, PLY or STL; triangles only) or a STEP file (.step, .stp; read in metres "
                   "and tessellated, see --deflection)")
        ->type_name("PART")
        ->required()
        ->check(CLI::ExistingFile);
    app.add_option("--camera", text.camera,
                   "camera/task JSON, or an OpenCV/ROS calibration file with --working-distance and --min-view-angle "
                   "(docs/io.md)")
        ->type_name("CAMERA")
        ->required()
        ->check(CLI::ExistingFile);
    app.add_option("--scale", text.scale, scale_help)->type_name("S");
    app.add_option("--deflection", text.deflection,
                   "STEP only: the tessellation's chordal deflection, metres (default: 1/1000 of the part's diagonal), "
                   "and its angular deflection, radians (default 0.5); what is certified is the tessellation")
        ->type_name("LIN[,ANG]");
    app.add_option("--part-pose", text.part_pose,
                   "place the part in the cell after --scale: X,Y,Z,ROLL,PITCH,YAW (metres, radians; as a URDF origin) "
                   "or a row-major 3x4/4x4 matrix; occluders, regions and results are in the cell's frame")
        ->type_name("POSE");
    add_scene_options(app, text.scene);
}

/// The inputs checked (usage_error naming the offending text).
inline input_arguments parse_input_options(const input_options_text& text) {
    input_arguments a;
    a.mesh = text.mesh;
    a.camera = text.camera;
    const bool step = certipose::is_step_path(a.mesh);
    if (!text.scale.empty()) {
        if (step)
            throw usage_error("--scale: " + a.mesh.string() +
                              " is a STEP file, which carries its length unit (it is read in metres); --scale is for meshes");
        a.scale = parse_double("--scale", text.scale, "a positive finite factor");
    }
    if (!text.deflection.empty()) {
        if (!step)
            throw usage_error("--deflection: " + a.mesh.string() +
                              " is a mesh, already tessellated; --deflection is for STEP files");
        const auto comma = text.deflection.find(',');
        a.deflection = parse_double("--deflection", text.deflection.substr(0, comma), "a positive finite length in metres");
        if (comma != std::string::npos) {
            const double angle = parse_double("--deflection", text.deflection.substr(comma + 1),
                                              "an angle in radians, in (0, pi)");
            if (!(angle < std::numbers::pi))
                throw usage_error("--deflection: the angular deflection must be in (0, pi) radians, got " +
                                  text.deflection.substr(comma + 1));
            a.angular_deflection = angle;
        }
    }
    if (!text.part_pose.empty()) a.part_pose = parse_part_pose(text.part_pose);
    a.scene = parse_scene_options(text.scene, a.camera);
    return a;
}

// ---- the facet solver's flags ---------------------------------------------------------------

/// The facet solver's flags as given.
struct solver_options_text {
    std::string position_eps, orientation_eps, max_boxes, time_limit, refine, corner_depth, corner_rest;
    bool paper_paving = false, grow = false;
};

/// Which of the facet solver's flags a program offers, and under which names: certipose-solve
/// solves one facet, so its budgets are --max-boxes and --time-limit; certipose-part keeps those
/// names for the whole run and calls the facet's --max-boxes-per-facet and --facet-time-limit.
struct solver_flags {
    const char* max_boxes = "--max-boxes";    ///< nullptr: not offered
    const char* time_limit = "--time-limit";  ///< nullptr: not offered
    bool thresholds_required = true;          ///< --position-eps and --orientation-eps
    bool paving = true;  ///< --paper-paving, --corner-depth, --corner-rest, --refine, --grow
    const char* thresholds_note = "";  ///< a prefix of the thresholds' help, e.g. "one-shot mode: "
};

/// The flags of certipose-part (and of any program that solves many facets).
inline constexpr solver_flags per_facet_budgets{.max_boxes = "--max-boxes-per-facet", .time_limit = "--facet-time-limit"};

/// Adds the facet solver's flags that `flags` offers to `app`.
inline void add_solver_options(CLI::App& app, solver_options_text& text, const solver_flags& flags = {}) {
    const std::string note = flags.thresholds_note;
    auto* p = app.add_option("--position-eps", text.position_eps, note + "position threshold, metres (paper: 0.1)")
                  ->type_name("METRES");
    auto* o = app.add_option("--orientation-eps", text.orientation_eps, note + "orientation threshold, radians (paper: 0.38)")
                  ->type_name("RADIANS");
    if (flags.thresholds_required) p->required(), o->required();
    if (flags.max_boxes)
        app.add_option(flags.max_boxes, text.max_boxes, "stop a facet's solve after N boxes (its result marked box_budget)")
            ->type_name("N");
    if (flags.time_limit)
        app.add_option(flags.time_limit, text.time_limit, "stop a facet's solve after SECONDS (its result marked deadline)")
            ->type_name("SECONDS");
    if (!flags.paving) return;
    app.add_flag("--paper-paving", text.paper_paving,
                 "pave as the paper does: bisect partly valid boxes, no inner contraction, occlusion cuts or corner boxes");
    app.add_option("--corner-depth", text.corner_depth,
                   "corner boxes one undecided leaf may give in a row, 1-8 (default 2; 1 writes fewer boxes)")
        ->type_name("N");
    app.add_option("--corner-rest", text.corner_rest,
                   "a rest box gives a corner box only when each side is at least PIECES minimal pieces "
                   "(eps/10; default 3, 2 certifies more, slower)")
        ->type_name("PIECES");
    app.add_option("--refine", text.refine,
                   "keep refining each facet below position-eps, largest undecided box first, for SECONDS")
        ->type_name("SECONDS");
    app.add_flag("--grow", text.grow, "widen the VALID boxes: merge neighbours, move faces out while certified");
}

/// --corner-depth: carving::corner_depth, 1 to 8.
inline std::size_t parse_corner_depth(const std::string& text) {
    const std::size_t v = parse_count("--corner-depth", text, 1);
    if (v > 8) throw usage_error("--corner-depth: expected an integer from 1 to 8, got " + text);
    return v;
}

/// --corner-rest: carving::rest_min_pieces, a finite number >= 0.
inline double parse_corner_rest(const std::string& text) {
    const double v = parse_number("--corner-rest", text, "a number >= 0");
    if (!(v >= 0.0) || !std::isfinite(v)) throw usage_error("--corner-rest: expected a finite number >= 0, got " + text);
    return v;
}

/// The facet solver's flags checked (usage_error naming the flag); thresholds not given keep
/// solve_settings' defaults (a program whose thresholds are optional looks at the text).
inline certipose::solve_settings parse_solver_options(const solver_options_text& text, const solver_flags& flags = {}) {
    certipose::solve_settings s;
    if (!text.position_eps.empty())
        s.position_eps = parse_double("--position-eps", text.position_eps, "a positive finite number of metres");
    if (!text.orientation_eps.empty())
        s.orientation_eps = parse_double("--orientation-eps", text.orientation_eps, "a positive finite number of radians");
    if (!text.max_boxes.empty()) s.max_boxes = parse_count(flags.max_boxes, text.max_boxes, 1);
    if (!text.time_limit.empty())
        s.time_limit = parse_double(flags.time_limit, text.time_limit, "a positive finite number of seconds");
    if (!text.refine.empty()) s.refine = parse_double("--refine", text.refine, "a positive finite number of seconds");
    s.paper_paving = text.paper_paving;
    if (!text.corner_depth.empty()) s.corner_depth = parse_corner_depth(text.corner_depth);
    if (!text.corner_rest.empty()) s.corner_rest = parse_corner_rest(text.corner_rest);
    if (s.paper_paving && (s.corner_depth || s.corner_rest))
        throw usage_error(std::string(s.corner_depth ? "--corner-depth" : "--corner-rest") +
                          " tunes the default paving; --paper-paving has no corner boxes");
    s.grow = text.grow;
    try {
        (void)certipose::to_solve_options(s);  // anything the flags above could not see alone
    } catch (const certipose::invalid_argument& e) {
        throw usage_error(e.what());
    }
    return s;
}

// ---- --occlusion ----------------------------------------------------------------------------

/// Adds --occlusion (aabb, boolean or none; certipose::parse_occlusion_choice reads it).
inline void add_occlusion_option(CLI::App& app, std::string& text) {
    text = std::string(certipose::to_string(certipose::occlusion_choice::aabb));
    app.add_option("--occlusion", text, "occlusion test: aabb (default), boolean or none")
        ->type_name("MODE")
        ->check(CLI::IsMember(std::vector<std::string>(certipose::occlusion_choice_names.begin(),
                                                       certipose::occlusion_choice_names.end())));
}

/// The --occlusion given (CLI11 checked the name).
inline certipose::occlusion_choice parse_occlusion_option(const std::string& text) {
    try {
        return certipose::parse_occlusion_choice(text, "--occlusion");
    } catch (const certipose::invalid_argument& e) {
        throw usage_error(e.what());
    }
}

// ---- the program --------------------------------------------------------------------------------

/// What a program's command line gave: its arguments to run with, or the exit code to end with
/// now (0 after --help, 2 after a usage error).
template <class Arguments>
struct parse_outcome {
    std::optional<Arguments> args;
    int exit_code = exit_ok;
};

/// Parses `Program`'s command line (see the header comment): only the --help text goes to
/// `out`, only one error line to `err` (and nothing when not `print`: MPI ranks other than 0).
template <class Program>
parse_outcome<typename Program::arguments> parse_program(int argc, const char* const* argv, std::ostream& out,
                                                         std::ostream& err, bool print = true) {
    CLI::App app{Program::description, Program::name};
    typename Program::options text;
    Program::declare(app, text);
    const auto fail = [&](const std::string& message) {
        if (print) err << Program::name << ": error: " << one_line(message) << " (run with --help for usage)\n";
        return parse_outcome<typename Program::arguments>{std::nullopt, exit_usage};
    };
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        if (print) out << app.help();
        return {std::nullopt, exit_ok};
    } catch (const CLI::CallForAllHelp&) {
        if (print) out << app.help();
        return {std::nullopt, exit_ok};
    } catch (const CLI::ParseError& e) {
        return fail(e.what());
    }
    try {
        typename Program::arguments a = Program::check(text);
        // `--out part.off`, `--out ./camera.json`, a second output onto the first: refused, nothing run.
        try {
            certipose::refuse_overwriting_inputs(a.files_read(), a.files_written());
        } catch (const certipose::invalid_argument& e) {
            throw usage_error(e.what());
        }
        return {std::move(a), exit_ok};
    } catch (const usage_error& e) {
        return fail(e.what());
    }
}

/// The whole life of `Program` (see the header comment); `print` false silences its error lines
/// (an MPI rank other than 0, whose rank 0 says the same).
template <class Program>
int program_main(int argc, char** argv, bool print = true) {
    try {  // parsing too: comparing an output with the inputs reads the file system
        const auto parsed = parse_program<Program>(argc, argv, std::cout, std::cerr, print);
        if (!parsed.args) return parsed.exit_code;
        const interruption signals;
        return Program::run(*parsed.args, signals);
    } catch (const std::exception& e) {
        const bool ours = dynamic_cast<const certipose::error*>(&e) != nullptr;
        if (print) std::cerr << Program::name << ": " << (ours ? "" : "unexpected error: ") << one_line(e.what()) << "\n";
        return exit_failure;
    }
}

}  // namespace certipose_program
