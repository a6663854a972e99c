// certipose-verify — certify anyone's camera plan: for each given pose (exact, or a 6D box for
// the installation tolerance), the facets certified inspected from every pose of it, C(B), and
// those not proven impossible, P(B), with the coverage interval [area(C), area(P)] / area; for an
// exact pose, also the largest box around it that keeps every facet of C certified.
//
//   certipose-verify --mesh PART --camera CAMERA --poses POSES.json [--scale S] [--part-pose POSE]
//                    [--out REPORT.json] [--no-tolerance] [--occluder MESH[:SCALE]]...
//                    [--keep-in REGION]... [--keep-out REGION]... [--part-tolerance TX,TY,TZ,ROT [--datum X,Y,Z]]
//                    [--working-distance DMIN,DMAX --min-view-angle RAD] [--quiet]
//
// --occluder meshes join the part in the occlusion scene. With --keep-in / --keep-out
// (solver/camera_regions.hpp) every pose is first placed against the camera regions
// ("camera_region" in the report): "forbidden" (no position of it allowed) certifies and makes
// possible nothing; "undecided" (partly outside, or too close to a sphere's surface to tell)
// certifies nothing ("possible" is still given); "allowed" is inspected as usual, and an exact
// pose's tolerance box is shrunk about the pose until its positions are all allowed.
// POSES.json: {"poses": [[x,y,z,φ,γ,β], {"position": [[xl,xu],...], "orientation": [[φl,φu],...]},
// {"position": [x,y,z], "quaternion": [qx,qy,qz,qw]}, {"matrix": 4x4 camera-to-world}, ...]} or a
// PLAN.json (io/plan_files.hpp; a quaternion or matrix becomes a ±1e-8 rad box around its ZXZ angles). One line per pose on stdout; REPORT.json (written
// atomically) holds the sets. Errors: one line "certipose-verify: ..." on stderr, exit 1 (bad
// input, write error) or 2 (bad command line); SIGINT/SIGTERM exit 130/143 and write nothing.
#include "program_skeleton.hpp"
#include "program_scene.hpp"

#include <certipose/cgal.hpp>
#include <certipose/coverage/inspection.hpp>
#include <certipose/io/json.hpp>
#include <certipose/io/output_files.hpp>
#include <certipose/io/plan_files.hpp>
#include <certipose/io/verify_poses.hpp>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using namespace certipose_program;
using I = certipose::boost_interval;
using policies = certipose::with_camera<certipose::calibrated_camera>;

/// certipose-verify as the programs' skeleton sees it (program_skeleton.hpp).
struct verify_program {
    static constexpr const char* name = "certipose-verify";
    static constexpr const char* description =
        "certipose-verify: the facets each given camera pose (or pose box) certifiably inspects.";

    struct options {
        input_options_text inputs;
        std::string poses, out;
        bool no_tolerance = false, quiet = false;
    };

    struct arguments {
        input_arguments inputs;  ///< --mesh, --camera, --scale and the scene options
        fs::path poses, out;
        bool tolerance = true, quiet = false;

        std::vector<certipose::named_path> files_read() const {
            std::vector<certipose::named_path> in = inputs.paths();
            in.push_back({"--poses", poses});
            return in;
        }
        std::vector<certipose::named_path> files_written() const {
            if (out.empty()) return {};
            return {{"--out", out}};
        }
    };

    static void declare(CLI::App& app, options& text) {
        add_input_options(app, text.inputs, "multiply mesh coordinates by S");
        app.add_option("--poses", text.poses, "exact poses or 6D boxes, or a PLAN.json (docs/coverage.md)")
            ->type_name("POSES.json")
            ->required()
            ->check(CLI::ExistingFile);
        app.add_option("--out", text.out, "the report: each pose's certified and possible facets")->type_name("REPORT.json");
        app.add_flag("--no-tolerance", text.no_tolerance, "skip the largest tolerance box around exact poses");
        app.add_flag("--quiet,-q", text.quiet, "print nothing but errors");
    }

    static arguments check(const options& text) {
        arguments a;
        a.inputs = parse_input_options(text.inputs);
        a.poses = text.poses, a.out = text.out;
        a.tolerance = !text.no_tolerance;
        a.quiet = text.quiet;
        if (!a.out.empty()) check_output("--out", a.out);
        return a;
    }

    static int run(const arguments& args, const interruption& signals);
};

using arguments = verify_program::arguments;

int verify_program::run(const arguments& args, const interruption& signals) {
    stage_line stage("certipose-verify", args.quiet);
    const program_inputs in = read_inputs(args.inputs, stage);
    const certipose::triangle_mesh& mesh = in.mesh;
    const certipose::camera_task& input = in.camera;
    stage.show("reading " + args.poses.string());
    const std::vector<certipose::pose_input> poses = certipose::read_poses(args.poses);
    const auto solver = build_solver<certipose::pose_solver<policies>>(args.inputs, in, stage);
    certipose::facet_inspector<policies> inspector(solver);
    stage.done();
    warn_about_scene("certipose-verify", solver.occlusion(), args.quiet);
    warn_about_units("certipose-verify", args.inputs, in.mesh, solver.camera(), solver.range(), args.quiet);

    double total = 0;
    for (double a : inspector.areas()) total += a;
    nlohmann::ordered_json report;
    report["format"] = "certipose-verify-report";
    report["version"] = certipose::detail::json_io::format_version;
    // As summary.json and PLAN.json write it, without a digest (none is compared against).
    report["mesh"] = certipose::mesh_record_json(
        {.path = args.inputs.mesh.string(), .faces = mesh.num_faces(), .scale = args.inputs.scale, .pose = pose_record(args.inputs)});
    certipose::detail::json_io::put_scene(report, in.extra.record);  // "occluders", "keep_in", "keep_out"
    // The placement tolerance every facet of "facets" is certified for (absent: nominal).
    if (input.task.placement) {
        nlohmann::ordered_json task;
        certipose::detail::json_io::put_placement(task, input.task.placement);
        report["placement_tolerance"] = task["placement_tolerance"];
    }
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    std::vector<char> certified_any(mesh.num_faces(), 0);
    double union_area = 0;
    for (std::size_t i = 0; i < poses.size(); ++i) {
        if (signals.interrupted()) return report_interrupted("certipose-verify", signals);
        const certipose::pose_input& p = poses[i];
        const certipose::pose_verification v = certipose::verify_pose(inspector, p, args.inputs.scene.regions, args.tolerance);
        const certipose::region_verdict where = v.where;
        const certipose::facet_coverage& c = v.coverage;
        for (std::size_t f : c.certified)
            if (!certified_any[f]) certified_any[f] = 1, union_area += inspector.areas()[f];
        nlohmann::ordered_json r;
        r["index"] = i;
        r["kind"] = certipose::to_string(p.form);
        r["position"] = p.position;
        r["orientation"] = p.orientation;
        r["facets"] = c.certified;
        r["possible"] = c.possible;
        r["certified_area"] = c.certified_area;
        r["possible_area"] = c.possible_area;
        r["coverage"] = {total > 0 ? c.certified_area / total : 0.0, total > 0 ? c.possible_area / total : 0.0};
        r["camera_region"] = certipose::to_string(where);
        std::string tolerance_text;
        if (v.tolerance_position) {
            const auto& half = v.half_widths;
            r["tolerance"] = {{"position", *v.tolerance_position}, {"orientation", *v.tolerance_orientation}, {"half_widths", half}};
            char buf[160];
            std::snprintf(buf, sizeof buf, "; tolerance +-%.1f/%.1f/%.1f mm, +-%.3f/%.3f/%.3f rad", 1e3 * half[0],
                          1e3 * half[1], 1e3 * half[2], half[3], half[4], half[5]);
            tolerance_text = buf;
        } else if (v.tolerance_asked) {
            r["tolerance"] = nullptr;
        }
        list.push_back(std::move(r));
        if (!args.quiet)
            std::printf("pose %zu (%s): %s%zu facets certified, %zu possible: coverage [%.2f %%, %.2f %%]%s\n", i,
                        p.pose ? "exact" : certipose::to_string(p.form),
                        where == certipose::region_verdict::forbidden   ? "OUTSIDE the allowed camera space (--keep-in/--keep-out): "
                        : where == certipose::region_verdict::undecided ? "PARTLY OUTSIDE the allowed camera space (--keep-in/--keep-out): "
                                                                        : "",
                        c.certified.size(), c.possible.size(),
                        total > 0 ? 100 * c.certified_area / total : 0.0, total > 0 ? 100 * c.possible_area / total : 0.0,
                        tolerance_text.c_str());
    }
    report["poses"] = std::move(list);
    report["union"] = {{"certified_area", union_area}, {"total_area", total}, {"coverage", total > 0 ? union_area / total : 0.0}};
    if (!args.quiet)
        std::printf("all %zu poses together certify %.2f %% of the part's area\n", poses.size(),
                    total > 0 ? 100 * union_area / total : 0.0);
    if (!args.out.empty()) {
        if (signals.interrupted()) return report_interrupted("certipose-verify", signals);
        certipose::output_files files;
        files.add(args.out, certipose::json_text(report));
        files.commit();
        if (!args.quiet) std::printf("wrote %s\n", args.out.string().c_str());
    }
    return exit_ok;
}

}  // namespace

int main(int argc, char** argv) { return program_main<verify_program>(argc, argv); }
