// certipose-plan — the fewest camera boxes that certify a part (docs/coverage.md).
//
//   certipose-plan --mesh PART --camera CAMERA [--scale S] [--part-pose POSE]
//                  (--part-results DIR | --position-eps E --orientation-eps O [--facets LIST])
//                  [--cameras K | --coverage F] [--candidates-per-facet N] [--tolerance P,O | none]
//                  [--exact SECONDS] [--lp-seconds SECONDS]
//                  [--threads N] [--occluder MESH[:SCALE]]... [--keep-in REGION]... [--keep-out REGION]...
//                  [--part-tolerance TX,TY,TZ,ROT [--datum X,Y,Z]] [--compare-run DIR]
//                  [--working-distance DMIN,DMAX --min-view-angle RAD] --out PLAN.json [--ply PLAN.ply] [--quiet]
//
// --compare-run DIR: a certipose-part run of the same part, camera and scene made with another
// placement tolerance (typically none) is planned the same way, and the summary gives both plans'
// cameras and shares side by side: what the tolerance costs. Only the summary says it; PLAN.json
// is this plan's alone.
// --occluder meshes join the part in the occlusion scene (of the one-shot run and of every C(B));
// candidates are restricted to the --keep-in / --keep-out camera regions (solver/camera_regions.hpp;
// the one-shot run per facet, a --part-results run's boxes as they are read). A --part-results run
// must have been made with the same occluders (digests, scales) and regions, compared exactly.
// Candidates are the largest VALID boxes of each facet (coverage/candidates.hpp), read from a
// certipose-part folder or from a whole-part run made here first (one-shot mode), cut down to the
// installation tolerance around their centres (--tolerance, default ±5 mm, ±0.02 rad). For each the
// certified facet set C(B) is computed (coverage/inspection.hpp); the plan is greedy maximum
// coverage (coverage/deployment.hpp), optionally replaced by GLPK's exact answer when it proves
// one with fewer cameras within --exact SECONDS, and always comes with a lower bound (the largest
// of the area bound, the greedy bound and the LP relaxation's, if GLPK solves it within
// --lp-seconds, default 60). Facets no chosen camera certifies are listed with
// the reason. PLAN.json and the PLY are committed together; SIGINT/SIGTERM stop the run, leave no
// file and exit 130/143. Errors: one line "certipose-plan: ..." on stderr, exit 1 (bad input,
// write error, or a plan with no camera: written, with each facet's reason) or 2 (bad command
// line).
#include "program_skeleton.hpp"
#include "program_scene.hpp"

#include <certipose/cgal.hpp>
#include <certipose/coverage/candidates.hpp>
#include <certipose/coverage/deployment.hpp>
#include <certipose/coverage/glpk_deployment.hpp>
#include <certipose/coverage/inspect_boxes.hpp>
#include <certipose/io/json.hpp>
#include <certipose/io/output_files.hpp>
#include <certipose/io/box_store.hpp>
#include <certipose/io/part_files.hpp>
#include <certipose/io/make_plan.hpp>
#include <certipose/io/plan_files.hpp>
#include <certipose/part/part_solver.hpp>
#include <certipose/part/selection.hpp>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace {

namespace fs = std::filesystem;
using namespace certipose_program;
using I = certipose::boost_interval;
using policies = certipose::with_camera<certipose::calibrated_camera>;

/// The facet solver's flags of the one-shot mode: the thresholds, optional.
constexpr solver_flags one_shot_flags{
    .max_boxes = nullptr, .time_limit = nullptr, .thresholds_required = false, .paving = false, .thresholds_note = "one-shot mode (the whole part is solved first at this threshold): "};

/// certipose-plan as the programs' skeleton sees it (program_skeleton.hpp).
struct plan_program {
    static constexpr const char* name = "certipose-plan";
    static constexpr const char* description =
        "certipose-plan: the fewest camera pose boxes that certify a part. Writes PLAN.json (docs/coverage.md).";

    struct options {
        input_options_text inputs;
        solver_options_text solver;
        std::string part_results, compare_run, out, ply, cameras, coverage, per_facet, exact, lp_seconds, threads, facets,
            tolerance;
        bool quiet = false, all_candidates = false, lp_whole = false;
    };

    struct arguments {
        input_arguments inputs;  ///< --mesh, --camera, --scale and the scene options
        fs::path part_results, out, ply;
        fs::path compare_run;  ///< --compare-run: a run of another placement tolerance, planned beside this one
        /// The one-shot mode's thresholds (--position-eps, --orientation-eps); unset with --part-results.
        std::optional<certipose::solve_settings> one_shot;
        std::optional<double> coverage, exact;
        double lp_seconds = 60;
        std::optional<std::size_t> cameras;
        std::string facets;
        std::size_t per_facet = 1, threads = 0;
        std::optional<std::array<double, 2>> tolerance = std::array<double, 2>{0.005, 0.02};
        bool quiet = false;
        bool all_candidates = false;  ///< --all-candidates: no thinning
        bool lp_whole = false;        ///< --lp-whole: the LP bound leaves out no facet class

        std::vector<certipose::named_path> files_read() const {
            std::vector<certipose::named_path> in = inputs.paths();
            if (!part_results.empty())
                for (const char* f : {"summary.json", "boxes.jsonl", "boxes.cpbx"}) in.push_back({"--part-results", part_results / f});
            if (!compare_run.empty())
                for (const char* f : {"summary.json", "boxes.jsonl", "boxes.cpbx"}) in.push_back({"--compare-run", compare_run / f});
            return in;
        }
        std::vector<certipose::named_path> files_written() const {
            std::vector<certipose::named_path> out_files{{"--out", out}};
            if (!ply.empty()) out_files.push_back({"--ply", ply});
            return out_files;
        }
    };

    static void declare(CLI::App& app, options& text) {
        add_input_options(app, text.inputs, "multiply mesh coordinates by S (as the run did)");
        app.add_option("--part-results", text.part_results, "a certipose-part output folder (summary.json, and boxes.cpbx or boxes.jsonl)")
            ->type_name("DIR")
            ->check(CLI::ExistingDirectory);
        app.add_option("--compare-run", text.compare_run,
                       "also plan from this certipose-part folder, a run of the same part, camera and scene with another "
                       "--part-tolerance (or none), and print both plans' cameras and shares side by side")
            ->type_name("DIR")
            ->check(CLI::ExistingDirectory);
        add_solver_options(app, text.solver, one_shot_flags);
        app.add_option("--facets", text.facets, "one-shot mode: facets to solve, e.g. 0,5,17-30 (default: all)")->type_name("LIST");
        app.add_option("--cameras", text.cameras, "at most K cameras (maximum coverage)")->type_name("K");
        app.add_option("--coverage", text.coverage, "the fewest cameras certifying this share of the coverable area (default 0.95)")
            ->type_name("F");
        app.add_option("--candidates-per-facet", text.per_facet, "largest VALID boxes of each facet to consider (default 1)")
            ->type_name("N");
        app.add_option("--tolerance", text.tolerance,
                       "candidate boxes: half-widths around each VALID box's centre, metres and radians, or 'none' "
                       "for whole boxes (default 0.005,0.02)")
            ->type_name("P,O");
        app.add_flag("--all-candidates", text.all_candidates,
                     "compute the certified facet set of every candidate (default: skip a candidate whose facet an already "
                     "inspected one certifies, largest estimated view first; docs/coverage.md#thinning)");
        app.add_option("--exact", text.exact, "try GLPK's exact answer for up to SECONDS")->type_name("SECONDS");
        app.add_option("--lp-seconds", text.lp_seconds,
                       "give GLPK's LP lower bound up to SECONDS (default 60; a bound not proven by then is not claimed)")
            ->type_name("SECONDS");
        app.add_flag("--lp-whole", text.lp_whole,
                     "solve the LP bound's whole program (default: on a large part, leave out its smallest facet classes, "
                     "at most 1 % of the area, which keeps it a lower bound and solves it in seconds; docs/coverage.md)");
        app.add_option("--threads", text.threads, "worker threads (default: every core)")->type_name("N");
        app.add_option("--out", text.out, "the plan")->type_name("PLAN.json")->required();
        app.add_option("--ply", text.ply, "the part coloured by camera, and the camera boxes")->type_name("PLAN.ply");
        app.add_flag("--quiet,-q", text.quiet, "print nothing but errors");
    }

    static arguments check(const options& text) {
        arguments a;
        a.inputs = parse_input_options(text.inputs);
        a.part_results = text.part_results, a.out = text.out, a.ply = text.ply, a.quiet = text.quiet;
        a.compare_run = text.compare_run;
        a.facets = text.facets;
        a.all_candidates = text.all_candidates;
        a.lp_whole = text.lp_whole;
        const bool thresholds = !text.solver.position_eps.empty() && !text.solver.orientation_eps.empty();
        const bool any_threshold = !text.solver.position_eps.empty() || !text.solver.orientation_eps.empty();
        const certipose::solve_settings solve = parse_solver_options(text.solver, one_shot_flags);
        if (text.part_results.empty() == !thresholds)
            throw usage_error("give either --part-results DIR or both --position-eps and --orientation-eps (one-shot mode)");
        if (!text.part_results.empty() && (any_threshold || !text.facets.empty()))
            throw usage_error("--position-eps, --orientation-eps and --facets belong to the one-shot mode, not --part-results");
        if (thresholds) a.one_shot = solve;
        const std::string& cameras = text.cameras;
        const std::string& coverage = text.coverage;
        const std::string& tolerance = text.tolerance;
        if (!cameras.empty() && !coverage.empty()) throw usage_error("give --cameras or --coverage, not both");
        if (!cameras.empty()) a.cameras = parse_count("--cameras", cameras, 1);
        if (!coverage.empty()) {
            a.coverage = parse_double("--coverage", coverage, "a share in (0, 1]");
            if (*a.coverage > 1.0) throw usage_error("--coverage: expected a share in (0, 1], got '" + coverage + "'");
        }
        if (!text.per_facet.empty()) a.per_facet = parse_count("--candidates-per-facet", text.per_facet, 1);
        if (tolerance == "none") a.tolerance.reset();
        else if (!tolerance.empty()) {
            const auto comma = tolerance.find(',');
            if (comma == std::string::npos)
                throw usage_error("--tolerance: expected P,O (metres, radians) or 'none', got '" + tolerance + "'");
            a.tolerance = std::array<double, 2>{
                parse_double("--tolerance", tolerance.substr(0, comma), "a positive finite number of metres"),
                parse_double("--tolerance", tolerance.substr(comma + 1), "a positive finite number of radians")};
        }
        if (!text.exact.empty()) a.exact = parse_double("--exact", text.exact, "a positive finite number of seconds");
        if (!text.lp_seconds.empty())
            a.lp_seconds = parse_double("--lp-seconds", text.lp_seconds, "a positive finite number of seconds");
        if (!text.threads.empty()) a.threads = parse_count("--threads", text.threads, 1);
        check_output("--out", a.out);
        if (!a.ply.empty()) check_output("--ply", a.ply);
        return a;
    }

    static int run(const arguments& args, const interruption& signals);
};

using arguments = plan_program::arguments;

double since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

/// A placement tolerance as the summary names it: "±3.0, 3.0, 3.0 mm and 1.00° about any axis".
std::string placement_text(const certipose::placement_tolerance& t) {
    using certipose::detail::plan_export::fixed;
    std::string how = "±" + fixed(1000 * t.translation[0], 1) + ", " + fixed(1000 * t.translation[1], 1) + ", " +
                      fixed(1000 * t.translation[2], 1) + " mm and " + fixed(t.rotation * 180 / std::numbers::pi, 2) + "°";
    if (!t.axis) return how + " about any axis";
    return how + " about (" + fixed(t.axis->x(), 3) + ", " + fixed(t.axis->y(), 3) + ", " + fixed(t.axis->z(), 3) + ")" +
           (t.tilt > 0 ? ", tipped by up to " + fixed(t.tilt * 180 / std::numbers::pi, 2) + "°" : "");
}

/// "N camera box(es) certify X % of the coverable area (Y % of the part)".
std::string shares_text(const certipose::plan_document& doc) {
    const auto pct = [](double a, double b) { return b > 0 ? 100.0 * a / b : 0.0; };
    char line[160];
    std::snprintf(line, sizeof line, "%zu camera box(es) certify %.1f %% of the coverable area (%.1f %% of the part)",
                  doc.cameras.size(), pct(doc.coverage.certified_area, doc.coverage.coverable_area),
                  pct(doc.coverage.certified_area, doc.coverage.total_area));
    return line;
}


int plan_program::run(const arguments& args, const interruption& signals) {
    stage_line stage("certipose-plan", args.quiet);
    const program_inputs in = read_inputs(args.inputs, stage);
    const certipose::triangle_mesh& mesh = in.mesh;
    const certipose::camera_task& input = in.camera;
    const scene& extra = in.extra;
    const auto part = build_solver<certipose::part_solver<policies>>(args.inputs, in, stage);
    stage.done();
    warn_about_scene("certipose-plan", part.solver().occlusion(), args.quiet);
    warn_about_units("certipose-plan", args.inputs, in.mesh, part.solver().camera(), part.solver().range(), args.quiet);
    const auto& solver = part.solver();
    const bool progress = show_progress(args.quiet);

    certipose::plan_document doc;
    doc.mesh = {args.inputs.mesh.string(), mesh.num_faces(), args.inputs.scale, certipose::mesh_digest(mesh),
                pose_record(args.inputs)};
    certipose::part_summary here;
    here.mesh = doc.mesh;
    certipose::describe_camera(here, solver.camera(), input.task);
    here.camera.mount_offset = input.mount_offset;
    doc.camera = here.camera;
    doc.task = here.task;
    here.scene = extra.record;
    doc.scene = extra.record;
    const certipose::plan_document header = doc;  // what a plan of the --compare-run starts from

    // --compare-run: a run of this part, camera and scene with another placement tolerance,
    // checked before any work, so that a wrong folder costs nothing and writes nothing.
    std::optional<certipose::part_summary> other_run;
    if (!args.compare_run.empty()) {
        const std::string where = (args.compare_run / "summary.json").string();
        other_run = certipose::read_part_summary(args.compare_run);
        certipose::part_summary there = here;
        there.task.placement = other_run->task.placement;
        certipose::check_part_run(*other_run, there, where);
        if (other_run->task.placement == here.task.placement)
            throw certipose::invalid_argument("--compare-run", where + ": the run has this plan's placement tolerance; compare "
                                                                       "with a run of another --part-tolerance, or of none");
    }

    // 1. Candidates, and what the run found for each facet (for the reasons of the uncovered).
    const auto t0 = std::chrono::steady_clock::now();
    certipose::candidate_pool<I> pool(args.per_facet);
    std::vector<certipose::facet_record> records;
    // A candidate's own facet is certified for it by the run: trusted when the run is known to be
    // of this very mesh (its digest matches, or it ran here); otherwise only what the inspector
    // proves counts.
    bool trust_run = args.part_results.empty();
    if (!args.part_results.empty()) {
        stage.show("reading " + args.part_results.string());
        const certipose::part_summary run = certipose::read_part_summary(args.part_results);
        certipose::check_part_run(run, here, (args.part_results / "summary.json").string());
        trust_run = !run.mesh.digest.empty();
        records = run.facets;
        certipose::add_run_candidates(pool, args.part_results, run, mesh.num_faces(), args.inputs.scene.regions);
        stage.done();
    } else {
        certipose::part_options opt;
        opt.facet = certipose::to_solve_options(*args.one_shot);
        opt.threads = args.threads;
        opt.stop = signals.token();
        opt.regions = args.inputs.scene.regions;  // each facet's VALID boxes, before they become candidates
        if (!args.facets.empty()) opt.facets = certipose::parse_facet_selection(args.facets, mesh.num_faces());
        if (progress)
            opt.progress = [](const certipose::part_progress& p) {
                std::fprintf(stderr, "\r\033[Kcertipose-plan: solving facets %zu / %zu, ETA %s", p.facets_done, p.facets_total,
                             duration_text(p.seconds_left).c_str());
                return true;
            };
        const certipose::part_result r = part.solve(opt, pool);
        if (progress) std::fputs("\r\033[K", stderr);
        records = r.facets;
    }
    if (signals.interrupted()) return report_interrupted("certipose-plan", signals);
    const double seconds_candidates = since(t0);
    const std::vector<certipose::candidate_box<I>> candidates = pool.boxes();

    // 2.-4. C(B) of every candidate, the choice and its lower bound, the uncovered facets.
    certipose::plan_options popt;
    popt.cameras = args.cameras;
    popt.coverage = args.coverage;
    popt.tolerance = args.tolerance;
    popt.lp_seconds = args.lp_seconds;
    if (args.lp_whole) popt.relaxation.max_left_out = 0;
    popt.exact_seconds = args.exact;
    popt.threads = args.threads;
    if (args.all_candidates) popt.thinning.reset();
    popt.occluders = extra.occluders;
    popt.stop = signals.token();
    if (progress) {
        popt.inspection_progress = [](std::size_t done, std::size_t all) {
            std::fprintf(stderr, "\r\033[Kcertipose-plan: certified facet sets of %zu / %zu candidate boxes", done, all);
            return true;
        };
        popt.before_lp = [&](std::size_t chosen) {
            std::fprintf(stderr, "\r\033[Kcertipose-plan: %zu cameras chosen; GLPK's LP lower bound (up to %g s)...", chosen,
                         args.lp_seconds);
        };
        popt.after_lp = [] { std::fputs("\r\033[K", stderr); };
    }
    const certipose::plan_report made = certipose::make_plan(doc, solver, candidates, records, trust_run, popt);
    if (progress) std::fputs("\r\033[K", stderr);
    if (signals.interrupted() || !made.completed) return report_interrupted("certipose-plan", signals);
    const auto& plan = doc.coverage;

    // The --compare-run planned the same way, with a solver of its placement tolerance (C(B) is
    // proven for the placements that run's boxes hold for).
    std::optional<certipose::plan_document> other;
    if (other_run) {
        certipose::candidate_pool<I> other_pool(args.per_facet);
        stage.show("reading " + args.compare_run.string());
        certipose::add_run_candidates(other_pool, args.compare_run, *other_run, mesh.num_faces(), args.inputs.scene.regions);
        program_inputs other_in = in;
        other_in.camera.task.placement = other_run->task.placement;
        const auto other_part = build_solver<certipose::part_solver<policies>>(args.inputs, other_in, stage);
        stage.done();
        other = header;
        other->task.placement = other_run->task.placement;
        const certipose::plan_report r = certipose::make_plan(*other, other_part.solver(), other_pool.boxes(), other_run->facets,
                                                              !other_run->mesh.digest.empty(), popt);
        if (progress) std::fputs("\r\033[K", stderr);
        if (signals.interrupted() || !r.completed) return report_interrupted("certipose-plan", signals);
    }

    certipose::output_files files;
    files.add(args.out, certipose::json_text(certipose::plan_to_json(doc)));
    if (!args.ply.empty()) files.add(args.ply, certipose::plan_ply_text(mesh, doc));
    if (signals.interrupted()) return report_interrupted("certipose-plan", signals);
    files.commit();

    if (!args.quiet) {
        std::printf("%s (%zu faces): %s; at least %zu needed (%s bound)\n", args.inputs.mesh.string().c_str(),
                    mesh.num_faces(), shares_text(doc).c_str(), plan.lower_bound_cameras, plan.lower_bound_method.c_str());
        // The shares above hold for every placement the tolerance admits: say which, beside them.
        const auto& t = doc.task.placement;
        if (t && !t->none())
            std::printf("  certified for every placement of the part within %s (--part-tolerance%s)\n",
                        placement_text(*t).c_str(), other ? "" : "; without it, more of the part may be coverable");
        if (other) {
            const auto& o = other->task.placement;
            const std::string what = o && !o->none() ? "with the placement tolerance " + placement_text(*o)
                                                     : std::string("without a placement tolerance");
            std::printf("  %s (--compare-run %s): %s\n", what.c_str(), args.compare_run.string().c_str(),
                        shares_text(*other).c_str());
        }
        std::printf("  %zu candidates (%s %.2f s), the certified facet sets of %zu inspected %.2f s, choice %.2f s%s; %zu facets uncovered\n",
                    candidates.size(), args.part_results.empty() ? "solved in" : "read in", seconds_candidates,
                    made.inspected, made.seconds_inspection, made.seconds_choice, made.exact ? " (GLPK exact)" : "", doc.uncovered.size());
        std::printf("wrote %s%s%s\n", args.out.string().c_str(), args.ply.empty() ? "" : " and ", args.ply.string().c_str());
    }
    // A plan with no camera is a task that failed, not a result to pass on in silence: the plan is
    // written (it lists each facet's reason), the exit code says so, and the message says why.
    if (doc.cameras.empty()) {
        std::map<std::string, std::size_t> reasons;
        for (const auto& u : doc.uncovered) ++reasons[certipose::to_string(u.reason)];
        std::string why;
        for (const auto& [reason, n] : reasons) why += (why.empty() ? "" : ", ") + std::to_string(n) + " " + reason;
        // Every facet solved was proven unseen (the rest were not asked for): the camera cannot
        // see this part at all, most often because of its units.
        const auto reason = [&](certipose::uncovered_reason r) { return reasons.count(certipose::to_string(r)); };
        const bool unseen = reason(certipose::uncovered_reason::never_visible) &&
                            reasons.size() == 1 + reason(certipose::uncovered_reason::not_solved);
        std::fprintf(stderr, "certipose-plan: no camera certifies any facet of %s (%s)%s; %s lists each facet's reason\n",
                     args.inputs.mesh.string().c_str(), why.empty() ? "no facets" : why.c_str(),
                     unseen ? ": no pose of the camera sees them; check the mesh's units (--scale) against the camera's "
                              "working distance"
                            : "",
                     args.out.string().c_str());
        return exit_failure;
    }
    return exit_ok;
}

}  // namespace

int main(int argc, char** argv) { return program_main<plan_program>(argc, argv); }
