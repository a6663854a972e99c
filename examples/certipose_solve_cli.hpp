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

#include "program_skeleton.hpp"

#include <certipose/io/output_files.hpp>
#include <certipose/solver/occlusion_choice.hpp>
#include <certipose/solver/solve_settings.hpp>

#include <CLI/CLI.hpp>

#include <cstddef>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace certipose_solve {

using certipose_program::exit_failure;
using certipose_program::exit_ok;
using certipose_program::exit_usage;

/// certipose-solve as the programs' skeleton sees it: its options and its body
/// (program_skeleton.hpp; `run` is in certipose_solve.cpp).
struct program {
    static constexpr const char* name = "certipose-solve";
    static constexpr const char* description =
        "certipose-solve: certified camera pose boxes from which a facet of a part can be inspected (paper: "
        "Parrott, Pickard, Dubay 2023). Writes the result JSON of docs/io.md and optionally a PLY of the boxes.";

    /// The command line as given.
    struct options {
        certipose_program::input_options_text inputs;
        certipose_program::solver_options_text solver;
        std::string facet, out, ply, occlusion;
        bool quiet = false;
    };

    /// The validated command line.
    struct arguments {
        certipose_program::input_arguments inputs;  ///< --mesh, --camera, --scale and the scene options
        std::size_t facet = 0;                      ///< --facet: face index in file order
        certipose::solve_settings solve;            ///< thresholds, budgets, paving (--position-eps, ...)
        std::filesystem::path out;                  ///< --out: result JSON
        std::optional<std::filesystem::path> ply;   ///< --ply: boxes for MeshLab/ParaView
        certipose::occlusion_choice occlusion = certipose::occlusion_choice::aabb;  ///< --occlusion
        bool quiet = false;                         ///< --quiet: no summary, no progress

        std::vector<certipose::named_path> files_read() const { return inputs.paths(); }
        std::vector<certipose::named_path> files_written() const {
            std::vector<certipose::named_path> o{{"--out", out}};
            if (ply) o.push_back({"--ply", *ply});
            return o;
        }
    };

    static void declare(CLI::App& app, options& text) {
        certipose_program::add_input_options(app, text.inputs);
        app.add_option("--facet", text.facet, "index of the facet of interest (file order, from 0)")->type_name("N")->required();
        certipose_program::add_solver_options(app, text.solver);
        certipose_program::add_occlusion_option(app, text.occlusion);
        app.add_option("--out", text.out, "result JSON to write (atomically)")->type_name("RESULT.json")->required();
        app.add_option("--ply", text.ply, "also write the part, facet and boxes as a coloured PLY")->type_name("BOXES.ply");
        app.add_flag("--quiet,-q", text.quiet, "print nothing but errors");
    }

    static arguments check(const options& text) {
        using namespace certipose_program;
        arguments a;
        a.inputs = parse_input_options(text.inputs);
        a.facet = parse_count("--facet", text.facet, 0);
        a.solve = parse_solver_options(text.solver);
        a.occlusion = parse_occlusion_option(text.occlusion);
        a.out = text.out;
        check_output("--out", a.out);
        if (!text.ply.empty()) {
            a.ply = text.ply;
            check_output("--ply", *a.ply);
        }
        a.quiet = text.quiet;
        return a;
    }

    static int run(const arguments& args, const certipose_program::interruption& signals);
};

using arguments = program::arguments;
using parse_outcome = certipose_program::parse_outcome<arguments>;

/// Parses the command line (see the header comment). Writes only the --help text to `out` and
/// only one error line to `err`.
inline parse_outcome parse_arguments(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
    return certipose_program::parse_program<program>(argc, argv, out, err);
}

}  // namespace certipose_solve
