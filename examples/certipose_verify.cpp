// certipose-verify — certify anyone's camera plan: for each given pose (exact, or a 6D box for
// the installation tolerance), the facets certified inspected from every pose of it, C(B), and
// those not proven impossible, P(B), with the coverage interval [area(C), area(P)] / area; for an
// exact pose, also the largest box around it that keeps every facet of C certified.
//
//   certipose-verify --mesh PART --camera CAMERA.json --poses POSES.json [--scale S]
//                    [--out REPORT.json] [--no-tolerance] [--quiet]
//
// POSES.json: {"poses": [[x,y,z,φ,γ,β], {"position": [[xl,xu],...], "orientation": [[φl,φu],...]},
// ...]} or a PLAN.json (io/plan_files.hpp). One line per pose on stdout; REPORT.json (written
// atomically) holds the sets. Errors: one line "certipose-verify: ..." on stderr, exit 1 (bad
// input, write error) or 2 (bad command line); SIGINT/SIGTERM exit 130/143 and write nothing.
#include "program_support.hpp"

#include <certipose/cgal.hpp>
#include <certipose/coverage/inspection.hpp>
#include <certipose/io/json.hpp>
#include <certipose/io/output_files.hpp>
#include <certipose/io/plan_files.hpp>

#include <CLI/CLI.hpp>

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

struct arguments {
    fs::path mesh, camera, poses, out;
    double scale = 1.0;
    bool tolerance = true, quiet = false;
};

std::optional<arguments> parse(int argc, char** argv, int& code) {
    CLI::App app{"certipose-verify: the facets each given camera pose (or pose box) certifiably inspects.", "certipose-verify"};
    std::string mesh, camera, poses, out, scale;
    bool no_tolerance = false, quiet = false;
    app.add_option("--mesh", mesh, "part mesh: OFF, OBJ, PLY or STL (triangles only)")->type_name("PART")->required()->check(CLI::ExistingFile);
    app.add_option("--camera", camera, "camera/task JSON (docs/io.md)")->type_name("CAMERA.json")->required()->check(CLI::ExistingFile);
    app.add_option("--poses", poses, "exact poses or 6D boxes, or a PLAN.json (docs/coverage.md)")->type_name("POSES.json")->required()->check(CLI::ExistingFile);
    app.add_option("--scale", scale, "multiply mesh coordinates by S")->type_name("S");
    app.add_option("--out", out, "the report: each pose's certified and possible facets")->type_name("REPORT.json");
    app.add_flag("--no-tolerance", no_tolerance, "skip the largest tolerance box around exact poses");
    app.add_flag("--quiet,-q", quiet, "print nothing but errors");
    if (!parse_command_line(app, argc, argv, "certipose-verify", code)) return std::nullopt;
    try {
        arguments a;
        a.mesh = mesh, a.camera = camera, a.poses = poses, a.out = out;
        a.tolerance = !no_tolerance;
        a.quiet = quiet;
        if (!scale.empty()) a.scale = parse_double("--scale", scale, "a positive finite factor");
        if (!a.out.empty()) check_output("--out", a.out);
        return a;
    } catch (const usage_error& e) {
        usage_failure("certipose-verify", e.what(), code);
        return std::nullopt;
    }
}

int run(const arguments& args, const interruption& signals) {
    stage_line stage("certipose-verify", args.quiet);
    stage.show("reading " + args.mesh.string());
    const certipose::triangle_mesh mesh = certipose::read_mesh(args.mesh, {.scale = args.scale});
    const certipose::camera_task input = certipose::read_camera_task(args.camera);
    const std::vector<certipose::pose_input> poses = certipose::read_poses(args.poses);
    stage.show("checking that the " + std::to_string(mesh.num_faces()) + " faces bound a closed solid");
    const certipose::pose_solver<policies> solver(mesh, input.calibrated(), input.task);
    certipose::facet_inspector<policies> inspector(solver);
    stage.done();

    double total = 0;
    for (double a : inspector.areas()) total += a;
    nlohmann::ordered_json report;
    report["mesh"] = {{"path", args.mesh.string()}, {"faces", mesh.num_faces()}, {"scale", args.scale}};
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    std::vector<char> certified_any(mesh.num_faces(), 0);
    double union_area = 0;
    for (std::size_t i = 0; i < poses.size(); ++i) {
        if (signals.interrupted()) return report_interrupted("certipose-verify", signals);
        const certipose::pose_input& p = poses[i];
        certipose::pose_box<I> box;
        for (std::size_t k = 0; k < 3; ++k) {
            box.position.x[k] = I(p.position[k][0], p.position[k][1]);
            box.orientation.x[k] = I(p.orientation[k][0], p.orientation[k][1]);
        }
        const certipose::facet_coverage c = inspector.inspect(box);
        for (std::size_t f : c.certified)
            if (!certified_any[f]) certified_any[f] = 1, union_area += inspector.areas()[f];
        nlohmann::ordered_json r;
        r["index"] = i;
        r["kind"] = p.pose ? "pose" : "box";
        r["position"] = p.position;
        r["orientation"] = p.orientation;
        r["facets"] = c.certified;
        r["possible"] = c.possible;
        r["certified_area"] = c.certified_area;
        r["possible_area"] = c.possible_area;
        r["coverage"] = {total > 0 ? c.certified_area / total : 0.0, total > 0 ? c.possible_area / total : 0.0};
        std::string tolerance_text;
        if (p.pose && args.tolerance && !c.certified.empty()) {
            if (const auto t = inspector.largest_box_keeping(*p.pose, c.certified)) {
                const auto rec = certipose::to_record(certipose::classified_box<I>{certipose::box_class::valid, *t});
                std::array<double, 6> half{};
                for (std::size_t k = 0; k < 3; ++k) {
                    half[k] = std::min((*p.pose)[k] - rec.position[k][0], rec.position[k][1] - (*p.pose)[k]);
                    half[k + 3] = std::min((*p.pose)[k + 3] - rec.orientation[k][0], rec.orientation[k][1] - (*p.pose)[k + 3]);
                }
                r["tolerance"] = {{"position", rec.position}, {"orientation", rec.orientation}, {"half_widths", half}};
                char buf[160];
                std::snprintf(buf, sizeof buf, "; tolerance +-%.1f/%.1f/%.1f mm, +-%.3f/%.3f/%.3f rad", 1e3 * half[0],
                              1e3 * half[1], 1e3 * half[2], half[3], half[4], half[5]);
                tolerance_text = buf;
            } else {
                r["tolerance"] = nullptr;
            }
        }
        list.push_back(std::move(r));
        if (!args.quiet)
            std::printf("pose %zu (%s): %zu facets certified, %zu possible: coverage [%.2f %%, %.2f %%]%s\n", i,
                        p.pose ? "exact" : "box", c.certified.size(), c.possible.size(),
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

int main(int argc, char** argv) {
    int code = exit_ok;
    const auto args = parse(argc, argv, code);
    if (!args) return code;
    return report_errors("certipose-verify", [&] {
        std::vector<certipose::named_path> outputs;
        if (!args->out.empty()) outputs.push_back({"--out", args->out});
        certipose::refuse_overwriting_inputs({{"--mesh", args->mesh}, {"--camera", args->camera}, {"--poses", args->poses}},
                                             outputs);
        const interruption signals;
        return run(*args, signals);
    });
}
