// certipose-export — a plan (PLAN.json of certipose-plan) in the formats a fitter, a robot cell,
// a CAD tool and a person open: a fitter's CSV of nominal poses and certified tolerances (mm,
// degrees), ROS/MoveIt constraints, a URDF (a whole <robot>, or with --snippet the cameras' links
// to paste into one), a glTF 2.0 scene with a camera object per camera, a self-contained HTML
// viewer and a printable installation sheet (HTML, one page per camera).
//
//   certipose-export PLAN.json --format csv|moveit|urdf|glb|html|sheet --out FILE
//                    [--mesh PART [--scale S] [--part-pose POSE]] [--parent-frame NAME] [--link optical|mount]
//                    [--link-prefix PREFIX] [--robot-name NAME] [--snippet] [--title TEXT] [--quiet]
//
// glb, html and sheet draw the part, so they need --mesh (the plan's part; --scale and --part-pose
// default to what the plan recorded, and the face count and digest must match); they draw the
// plan's occluders too, read from the paths it records (one that cannot be read or has changed
// is left out with a warning: a picture is not a certificate). The output is written atomically and
// never over an input. Formats: docs/conventions.md#exports. Errors: one line
// "certipose-export: ..." on stderr, exit 1 (bad input, write error) or 2 (bad command line);
// SIGINT/SIGTERM exit 130/143 and write nothing.
#include "program_skeleton.hpp"

#include <certipose/io/read_mesh.hpp>
#include <certipose/io/json.hpp>
#include <certipose/io/moveit_yaml.hpp>
#include <certipose/io/output_files.hpp>
#include <certipose/io/plan_export.hpp>
#include <certipose/io/plan_files.hpp>
#include <certipose/io/plan_gltf.hpp>
#include <certipose/io/plan_html.hpp>
#include <certipose/io/plan_occluders.hpp>
#include <certipose/io/plan_sheet.hpp>
#include <certipose/io/scene_record.hpp>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

// The viewer's HTML template and bundled script, embedded at build time (web/build.mjs →
// certipose_viewer.cpp); empty when the build had no Node.js or no `npm ci` in web/.
extern const std::string_view certipose_viewer_template;
extern const std::string_view certipose_viewer_script;

namespace {

namespace fs = std::filesystem;
using namespace certipose_program;

/// certipose-export as the programs' skeleton sees it (program_skeleton.hpp).
struct export_program {
    static constexpr const char* name = "certipose-export";
    static constexpr const char* description =
        "certipose-export: a plan's cameras as a fitter's CSV (mm, degrees), ROS/MoveIt constraints, a URDF, glTF "
        "(.glb, with camera objects), a self-contained HTML viewer or a printable installation sheet "
        "(docs/conventions.md#exports).";

    struct options {
        std::string plan, format, out, mesh, scale, part_pose;
        std::optional<std::string> parent_frame, link, link_prefix, robot_name, title;  ///< unset: not given (given empty is a mistake too)
        bool snippet = false, quiet = false;
    };

    struct arguments {
        fs::path plan, mesh, out;
        std::string format, parent_frame = "world", link = "optical", link_prefix = "camera_",
                    robot_name = "certipose_cameras", title;
        std::optional<double> scale;
        std::optional<certipose::part_pose> part_pose;
        bool snippet = false, quiet = false;

        std::vector<certipose::named_path> files_read() const {
            std::vector<certipose::named_path> in{{"PLAN.json", plan}};
            if (!mesh.empty()) in.push_back({"--mesh", mesh});
            return in;
        }
        std::vector<certipose::named_path> files_written() const { return {{"--out", out}}; }
    };

    static void declare(CLI::App& app, options& text) {
        app.add_option("plan", text.plan, "the plan written by certipose-plan")->type_name("PLAN.json")->required()->check(CLI::ExistingFile);
        app.add_option("--format", text.format, "csv, moveit, urdf, glb, html or sheet")->type_name("FORMAT")->required();
        app.add_option("--out", text.out, "the file to write")->type_name("FILE")->required();
        app.add_option("--mesh", text.mesh, "the plan's part (needed by glb, html and sheet): OFF, OBJ, PLY or STL")
            ->type_name("PART")
            ->check(CLI::ExistingFile);
        app.add_option("--scale", text.scale, "multiply mesh coordinates by S (default: the plan's scale)")->type_name("S");
        app.add_option("--part-pose", text.part_pose,
                       "place the part as the plan's run did: X,Y,Z,ROLL,PITCH,YAW or a 3x4/4x4 matrix (default: the "
                       "plan's mesh.pose)")
            ->type_name("POSE");
        app.add_option("--parent-frame", text.parent_frame,
                       "urdf: the link the cameras are fixed to (default world); moveit: the planning frame of the part")
            ->type_name("NAME");
        app.add_option("--link", text.link,
                       "moveit: constrain each camera's optical frame (default) or its mount (with the camera's "
                       "mount_offset)")
            ->type_name("optical|mount");
        app.add_option("--link-prefix", text.link_prefix,
                       "urdf and moveit: camera k's links are PREFIXk_mount and PREFIXk_optical_frame (default camera_)")
            ->type_name("PREFIX");
        app.add_option("--robot-name", text.robot_name, "urdf: the <robot> name (default certipose_cameras)")
            ->type_name("NAME");
        app.add_flag("--snippet", text.snippet,
                     "urdf: only the cameras' links and joints, to paste inside a <robot> that has --parent-frame");
        app.add_option("--title", text.title, "html and sheet: the page title (default: the plan's file name)")->type_name("TEXT");
        app.add_flag("--quiet,-q", text.quiet, "print nothing but errors");
    }

    static arguments check(const options& text) {
        arguments a;
        a.plan = text.plan, a.mesh = text.mesh, a.out = text.out, a.format = text.format, a.quiet = text.quiet;
        if (a.format != "csv" && a.format != "moveit" && a.format != "urdf" && a.format != "glb" && a.format != "html" &&
            a.format != "sheet")
            throw usage_error("--format: expected csv, moveit, urdf, glb, html or sheet, got '" + a.format + "'");
        const bool picture = a.format == "glb" || a.format == "html" || a.format == "sheet";
        // An option the format does not use is a mistake worth naming, not something to ignore.
        const auto only_for = [&](const std::string& option, bool given, bool used, const char* formats) {
            if (given && !used) throw usage_error(option + " applies to " + formats + ", not --format " + a.format);
        };
        only_for("--parent-frame", text.parent_frame.has_value(), a.format == "urdf" || a.format == "moveit",
                 "--format urdf and moveit");
        only_for("--link", text.link.has_value(), a.format == "moveit", "--format moveit");
        only_for("--link-prefix", text.link_prefix.has_value(), a.format == "urdf" || a.format == "moveit",
                 "--format urdf and moveit");
        only_for("--robot-name", text.robot_name.has_value(), a.format == "urdf", "--format urdf");
        only_for("--snippet", text.snippet, a.format == "urdf", "--format urdf");
        only_for("--title", text.title.has_value(), a.format == "html" || a.format == "sheet", "--format html and sheet");
        only_for("--mesh", !text.mesh.empty(), picture, "--format glb, html and sheet");
        only_for("--scale", !text.scale.empty(), picture, "--format glb, html and sheet");
        only_for("--part-pose", !text.part_pose.empty(), picture, "--format glb, html and sheet");
        if (text.parent_frame) a.parent_frame = *text.parent_frame;
        if (text.link) a.link = *text.link;
        if (text.link_prefix) a.link_prefix = *text.link_prefix;
        if (text.robot_name) a.robot_name = *text.robot_name;
        a.snippet = text.snippet;
        if (text.title) a.title = *text.title;
        if (a.link != "optical" && a.link != "mount")
            throw usage_error("--link: expected optical or mount, got '" + a.link + "'");
        if (picture && a.mesh.empty()) throw usage_error("--format " + a.format + " draws the part: give --mesh PART");
        // A plan is about the triangles its run certified; for a STEP part those are the run
        // folder's mesh.off (tessellating again here could differ and would not be checked).
        if (certipose::is_step_path(a.mesh))
            throw usage_error("--mesh: " + a.mesh.string() +
                              " is a STEP file; give the tessellation the plan is for, mesh.off in the certipose-part "
                              "run's folder");
        if (!text.scale.empty()) a.scale = parse_double("--scale", text.scale, "a positive finite factor");
        if (!text.part_pose.empty()) a.part_pose = parse_part_pose(text.part_pose);
        if (a.title.empty()) a.title = "certipose plan: " + a.plan.filename().string();
        check_output("--out", a.out);
        return a;
    }

    static int run(const arguments& args, const interruption& signals);
};

using arguments = export_program::arguments;

std::string content(const arguments& args, const certipose::plan_document& plan) {
    // The plan's occluders are inputs too (the pictures read them): never write over one.
    for (const auto& o : plan.scene.occluders) {
        std::error_code ec;
        if (fs::equivalent(o.path, args.out, ec))
            throw certipose::invalid_argument("--out", "--out " + args.out.string() + " is the plan's occluder " + o.path +
                                                           ": choose another file");
    }
    if (args.format == "csv") return certipose::plan_csv(plan);
    if (args.format == "urdf")
        return certipose::plan_urdf(plan, {.parent_frame = args.parent_frame,
                                           .link_prefix = args.link_prefix,
                                           .robot_name = args.robot_name,
                                           .snippet = args.snippet});
    if (args.format == "moveit")
        return certipose::plan_moveit_yaml(
            plan, {.frame_id = args.parent_frame,
                   .link = args.link == "mount" ? certipose::constrained_link::mount : certipose::constrained_link::optical_frame,
                   .link_prefix = args.link_prefix});
    const double scale = args.scale.value_or(plan.mesh.scale);
    certipose::triangle_mesh mesh = certipose::read_mesh(args.mesh, {.scale = scale});
    if (args.part_pose) {
        mesh = certipose::posed(mesh, *args.part_pose);
    } else if (plan.mesh.pose) {  // where the plan's run placed the part
        mesh = certipose::posed(mesh, certipose::part_pose_from_matrix(
                                          std::vector<double>(plan.mesh.pose->begin(), plan.mesh.pose->end()), "mesh.pose"));
    }
    // The plan's facet indices mean something only on its own part.
    const auto mismatch = [&](const char* what, const std::string& theirs, const std::string& ours) {
        throw certipose::invalid_argument(what, args.plan.string() + ": the plan's " + what + " (" + theirs +
                                                    ") is not this mesh's (" + ours +
                                                    "): give the mesh, and --scale, the plan was made for");
    };
    if (mesh.num_faces() != plan.mesh.faces)
        mismatch("mesh.faces", std::to_string(plan.mesh.faces), std::to_string(mesh.num_faces()));
    if (!plan.mesh.digest.empty() && plan.mesh.digest != certipose::mesh_digest(mesh))
        mismatch("mesh.digest", plan.mesh.digest, certipose::mesh_digest(mesh));
    const certipose::plan_occluders occluders = certipose::read_plan_occluders(plan);
    if (!args.quiet)
        for (const auto& why : occluders.left_out) std::fprintf(stderr, "certipose-export: warning: %s\n", why.c_str());
    if (args.format == "sheet") return certipose::plan_sheet(mesh, plan, {.title = args.title, .occluders = occluders.meshes});
    const std::string glb = certipose::plan_glb(mesh, plan, occluders.meshes);
    if (args.format == "glb") return glb;
    if (certipose_viewer_script.empty())
        throw certipose::invalid_argument("format", "--format html: this build has no web viewer (it needs Node.js and "
                                                    "`npm ci` in web/ when configuring; scripts/install-deps.sh does both)");
    return certipose::plan_html(plan, glb, mesh.num_faces(), {certipose_viewer_template, certipose_viewer_script}, args.title);
}

int export_program::run(const arguments& args, const interruption& signals) {
    const certipose::plan_document plan = certipose::read_plan(args.plan);
    certipose::output_files files;
    files.add(args.out, content(args, plan));
    if (signals.interrupted()) return report_interrupted(name, signals);  // staged, never committed
    files.commit();
    if (!args.quiet)
        std::printf("wrote %s (%s, %zu cameras)\n", args.out.string().c_str(), args.format.c_str(), plan.cameras.size());
    return exit_ok;
}

}  // namespace

int main(int argc, char** argv) { return program_main<export_program>(argc, argv); }
