// certipose-plan — the fewest camera boxes that certify a part (docs/coverage.md).
//
//   certipose-plan --mesh PART --camera CAMERA [--scale S]
//                  (--part-results DIR | --position-eps E --orientation-eps O [--facets LIST])
//                  [--cameras K | --coverage F] [--candidates-per-facet N] [--tolerance P,O | none]
//                  [--exact SECONDS] [--lp-seconds SECONDS]
//                  [--threads N] [--occluder MESH[:SCALE]]... [--keep-in REGION]... [--keep-out REGION]...
//                  [--part-tolerance TX,TY,TZ,ROT [--datum X,Y,Z]] [--working-distance DMIN,DMAX --min-view-angle RAD]
//                  --out PLAN.json [--ply PLAN.ply] [--quiet]
//
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
// write error) or 2 (bad command line).
#include "program_support.hpp"
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
#include <certipose/io/plan_files.hpp>
#include <certipose/part/part_solver.hpp>
#include <certipose/part/selection.hpp>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace {

namespace fs = std::filesystem;
using namespace certipose_program;
using I = certipose::boost_interval;
using policies = certipose::with_camera<certipose::calibrated_camera>;

struct arguments {
    fs::path mesh, camera, part_results, out, ply;
    double scale = 1.0;
    std::optional<double> position_eps, orientation_eps, coverage, exact;
    double lp_seconds = 60;
    std::optional<std::size_t> cameras;
    std::string facets;
    std::size_t per_facet = 1, threads = 0;
    std::optional<std::array<double, 2>> tolerance = std::array<double, 2>{0.005, 0.02};
    bool quiet = false;
    scene_arguments scene;  ///< --occluder, --keep-in, --keep-out
};

std::optional<arguments> parse(int argc, char** argv, int& code) {
    CLI::App app{"certipose-plan: the fewest camera pose boxes that certify a part. Writes PLAN.json (docs/coverage.md).",
                 "certipose-plan"};
    std::string mesh, camera, part_results, out, ply, scale, position_eps, orientation_eps, cameras, coverage, per_facet,
        exact, lp_seconds, threads, facets, tolerance;
    bool quiet = false;
    app.add_option("--mesh", mesh, "part mesh: OFF, OBJ, PLY or STL (triangles only)")->type_name("PART")->required()->check(CLI::ExistingFile);
    app.add_option("--camera", camera, "camera/task JSON, or an OpenCV/ROS calibration file with --working-distance and --min-view-angle (docs/io.md)")->type_name("CAMERA")->required()->check(CLI::ExistingFile);
    app.add_option("--scale", scale, "multiply mesh coordinates by S (as the run did)")->type_name("S");
    app.add_option("--part-results", part_results, "a certipose-part output folder (summary.json, and boxes.cpbx or boxes.jsonl)")->type_name("DIR")->check(CLI::ExistingDirectory);
    app.add_option("--position-eps", position_eps, "one-shot mode: run the whole part first at this threshold (metres)")->type_name("METRES");
    app.add_option("--orientation-eps", orientation_eps, "one-shot mode: orientation threshold (radians)")->type_name("RADIANS");
    app.add_option("--facets", facets, "one-shot mode: facets to solve, e.g. 0,5,17-30 (default: all)")->type_name("LIST");
    app.add_option("--cameras", cameras, "at most K cameras (maximum coverage)")->type_name("K");
    app.add_option("--coverage", coverage, "the fewest cameras certifying this share of the coverable area (default 0.95)")->type_name("F");
    app.add_option("--candidates-per-facet", per_facet, "largest VALID boxes of each facet to consider (default 1)")->type_name("N");
    app.add_option("--tolerance", tolerance,
                   "candidate boxes: half-widths around each VALID box's centre, metres and radians, or 'none' "
                   "for whole boxes (default 0.005,0.02)")
        ->type_name("P,O");
    app.add_option("--exact", exact, "try GLPK's exact answer for up to SECONDS")->type_name("SECONDS");
    app.add_option("--lp-seconds", lp_seconds, "give GLPK's LP lower bound up to SECONDS (default 60; a bound not proven by then is not claimed)")->type_name("SECONDS");
    app.add_option("--threads", threads, "worker threads (default: every core)")->type_name("N");
    app.add_option("--out", out, "the plan")->type_name("PLAN.json")->required();
    app.add_option("--ply", ply, "the part coloured by camera, and the camera boxes")->type_name("PLAN.ply");
    scene_options_text scene;
    add_scene_options(app, scene);
    app.add_flag("--quiet,-q", quiet, "print nothing but errors");
    if (!parse_command_line(app, argc, argv, "certipose-plan", code)) return std::nullopt;
    try {
        arguments a;
        a.mesh = mesh, a.camera = camera, a.part_results = part_results, a.out = out, a.ply = ply, a.quiet = quiet;
        a.facets = facets;
        if (!scale.empty()) a.scale = parse_double("--scale", scale, "a positive finite factor");
        if (!position_eps.empty()) a.position_eps = parse_double("--position-eps", position_eps, "a positive finite number of metres");
        if (!orientation_eps.empty())
            a.orientation_eps = parse_double("--orientation-eps", orientation_eps, "a positive finite number of radians");
        if (part_results.empty() == !(a.position_eps && a.orientation_eps))
            throw usage_error("give either --part-results DIR or both --position-eps and --orientation-eps (one-shot mode)");
        if (!part_results.empty() && (a.position_eps || a.orientation_eps || !facets.empty()))
            throw usage_error("--position-eps, --orientation-eps and --facets belong to the one-shot mode, not --part-results");
        if (!cameras.empty() && !coverage.empty()) throw usage_error("give --cameras or --coverage, not both");
        if (!cameras.empty()) a.cameras = parse_count("--cameras", cameras, 1);
        if (!coverage.empty()) {
            a.coverage = parse_double("--coverage", coverage, "a share in (0, 1]");
            if (*a.coverage > 1.0) throw usage_error("--coverage: expected a share in (0, 1], got '" + coverage + "'");
        }
        if (!per_facet.empty()) a.per_facet = parse_count("--candidates-per-facet", per_facet, 1);
        if (tolerance == "none") a.tolerance.reset();
        else if (!tolerance.empty()) {
            const auto comma = tolerance.find(',');
            if (comma == std::string::npos)
                throw usage_error("--tolerance: expected P,O (metres, radians) or 'none', got '" + tolerance + "'");
            a.tolerance = std::array<double, 2>{
                parse_double("--tolerance", tolerance.substr(0, comma), "a positive finite number of metres"),
                parse_double("--tolerance", tolerance.substr(comma + 1), "a positive finite number of radians")};
        }
        if (!exact.empty()) a.exact = parse_double("--exact", exact, "a positive finite number of seconds");
        if (!lp_seconds.empty()) a.lp_seconds = parse_double("--lp-seconds", lp_seconds, "a positive finite number of seconds");
        if (!threads.empty()) a.threads = parse_count("--threads", threads, 1);
        a.scene = parse_scene_options(scene, a.camera);
        check_output("--out", a.out);
        if (!a.ply.empty()) check_output("--ply", a.ply);
        return a;
    } catch (const usage_error& e) {
        usage_failure("certipose-plan", e.what(), code);
        return std::nullopt;
    }
}

double since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

/// The same double, bit for bit (so both +inf, for an unbounded d_max): a run whose camera differs
/// in the last bit of d_min certified its boxes against other constraints, and the difference is
/// exactly where its box edges sit. summary.json round-trips every double (shortest digits written,
/// read back in round-to-nearest), so a run of this camera always compares equal.
bool same(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

/// The run's occluders and camera regions must be the plan's: a box certified without an occluder
/// may be hidden by it, and one restricted to other regions may stand where the plan forbids.
/// Occluders are compared by digest and scale (bit for bit), regions exactly, each list in any order.
void check_scene(const certipose::scene_record& run, const certipose::scene_record& here, const std::string& where) {
    const auto mismatch = [&](const std::string& what, const std::string& theirs, const std::string& ours) {
        throw certipose::invalid_argument(what, where + ": the run's " + what + " (" + theirs + ") is not this plan's (" + ours +
                                                    "): plan with the --occluder, --keep-in and --keep-out the run used");
    };
    using occluder = certipose::occluder_record;
    const auto occluder_key = [](const occluder& o) { return std::pair(o.digest, std::bit_cast<std::uint64_t>(o.scale)); };
    const auto occluders = [&](std::vector<occluder> list) {
        std::sort(list.begin(), list.end(), [&](const occluder& a, const occluder& b) { return occluder_key(a) < occluder_key(b); });
        return list;
    };
    const auto occluders_text = [](const std::vector<occluder>& list) {
        std::string s;
        for (const auto& o : list)
            s += (s.empty() ? "" : ", ") + o.path + ":" + certipose::detail::format_double(o.scale) + " digest " + o.digest;
        return s.empty() ? std::string("none") : s;
    };
    const auto a = occluders(run.occluders), b = occluders(here.occluders);
    if (!std::equal(a.begin(), a.end(), b.begin(), b.end(),
                    [&](const occluder& x, const occluder& y) { return occluder_key(x) == occluder_key(y); }))
        mismatch("occluders", occluders_text(run.occluders), occluders_text(here.occluders));
    const auto region_key = [](const certipose::camera_region& r) {
        std::array<std::uint64_t, 7> k{static_cast<std::uint64_t>(r.shape)};
        for (std::size_t i = 0; i < 6; ++i) k[i + 1] = std::bit_cast<std::uint64_t>(r.values[i]);
        return k;
    };
    const auto regions = [&](std::vector<certipose::camera_region> list) {
        std::sort(list.begin(), list.end(), [&](const auto& x, const auto& y) { return region_key(x) < region_key(y); });
        return list;
    };
    const auto regions_text = [](const std::vector<certipose::camera_region>& list) {
        std::string s;
        for (const auto& r : list) s += (s.empty() ? "" : " ") + certipose::to_string(r);
        return s.empty() ? std::string("none") : s;
    };
    for (const auto& [key, theirs, ours] : {std::tuple{"keep_in", &run.regions.keep_in, &here.regions.keep_in},
                                            std::tuple{"keep_out", &run.regions.keep_out, &here.regions.keep_out}}) {
        const auto x = regions(*theirs), y = regions(*ours);
        if (!std::equal(x.begin(), x.end(), y.begin(), y.end(),
                        [&](const auto& p, const auto& q) { return region_key(p) == region_key(q); }))
            mismatch(key, regions_text(*theirs), regions_text(*ours));
    }
}

/// The run in DIR must be of this mesh, camera and task, with occlusion checked: otherwise its
/// boxes certify something else.
void check_run(const certipose::part_summary& run, const certipose::part_summary& here, const fs::path& dir) {
    const std::string where = (dir / "summary.json").string();
    const auto mismatch = [&](const std::string& what, const std::string& theirs, const std::string& ours) {
        throw certipose::invalid_argument(what, where + ": the run's " + what + " (" + theirs + ") is not this plan's (" + ours +
                                                    "): plan with the mesh, --scale and camera the run used");
    };
    const auto text = [](double v) { return certipose::detail::format_double(v); };
    if (run.mesh.faces != here.mesh.faces)
        mismatch("mesh.faces", std::to_string(run.mesh.faces), std::to_string(here.mesh.faces));
    if (!same(run.mesh.scale, here.mesh.scale)) mismatch("mesh.scale", text(run.mesh.scale), text(here.mesh.scale));
    if (!run.mesh.digest.empty() && run.mesh.digest != here.mesh.digest)
        mismatch("mesh.digest", run.mesh.digest, here.mesh.digest);
    const auto& a = run.camera;
    const auto& b = here.camera;
    if (!same(a.width_px, b.width_px) || !same(a.height_px, b.height_px))
        mismatch("camera size", text(a.width_px) + "x" + text(a.height_px), text(b.width_px) + "x" + text(b.height_px));
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            if (!same(a.K[r][c], b.K[r][c])) mismatch("camera.K", text(a.K[r][c]), text(b.K[r][c]));
    // The lens: boxes certified through one distortion (or none) do not hold through another.
    const auto lens = [&](const auto& cam) {
        std::string s = "none";
        if (cam.distortion) {
            s.clear();
            for (double k : cam.distortion->opencv()) s += (s.empty() ? "" : ",") + text(k);
        }
        return s + ", margin " + text(cam.image_margin_px) + " px";
    };
    if (!(a.distortion == b.distortion) || !same(a.image_margin_px, b.image_margin_px))
        mismatch("camera.distortion_coefficients", lens(a), lens(b));
    if (!same(a.d_min, b.d_min) || !same(a.d_max, b.d_max))
        mismatch("camera distance range", text(a.d_min) + ".." + text(a.d_max), text(b.d_min) + ".." + text(b.d_max));
    // The mount offset changes no box (they are of the projection centre), but the plan's mount
    // poses are computed with it: a run of another offset is another camera installation.
    if (a.mount_offset != b.mount_offset) {
        const auto point = [&](const std::array<double, 3>& p) { return "[" + text(p[0]) + ", " + text(p[1]) + ", " + text(p[2]) + "]"; };
        mismatch("camera.mount_offset", point(a.mount_offset), point(b.mount_offset));
    }
    if (!same(run.task.min_view_angle, here.task.min_view_angle))
        mismatch("task.min_view_angle", text(run.task.min_view_angle), text(here.task.min_view_angle));
    // Boxes certified for another placement tolerance (or none) are not this plan's: fewer
    // placements than asked would be covered, or cameras lost to a tolerance not asked for.
    if (!(run.task.placement == here.task.placement)) {
        const auto tol = [&](const std::optional<certipose::placement_tolerance>& t) -> std::string {
            if (!t) return "none";
            std::string s = text(t->translation[0]) + "," + text(t->translation[1]) + "," + text(t->translation[2]) + "," +
                            text(t->rotation);
            if (t->datum) s += " about " + text(t->datum->x()) + "," + text(t->datum->y()) + "," + text(t->datum->z());
            return s;
        };
        mismatch("task.placement_tolerance", tol(run.task.placement), tol(here.task.placement));
    }
    if (!run.settings.occlusion_checked)
        throw certipose::invalid_argument("settings.occlusion", where + ": the run did not check occlusion (--occlusion none); "
                                                                        "its boxes certify no facet: run it with occlusion");
    check_scene(run.scene, here.scene, where);
}

int run(const arguments& args, const interruption& signals) {
    stage_line stage("certipose-plan", args.quiet);
    stage.show("reading " + args.mesh.string());
    const certipose::triangle_mesh mesh = certipose::read_mesh(args.mesh, {.scale = args.scale});
    certipose::camera_task input = certipose_program::read_camera(args.camera, args.scene);
    certipose_program::apply_placement(input.task, args.scene, mesh);
    const scene extra = read_scene(args.scene, &stage);
    stage.show("building the occlusion scene of the " + std::to_string(mesh.num_faces()) + " faces");
    const auto part = naming_occluders(args.scene, [&] {
        return certipose::part_solver<policies>(mesh, input.calibrated(), input.task, {.occluders = extra.occluders, .semantics = args.scene.semantics});
    });
    stage.done();
    warn_about_scene("certipose-plan", part.solver().occlusion(), args.quiet);
    const auto& solver = part.solver();
    const bool progress = show_progress(args.quiet);

    certipose::plan_document doc;
    doc.mesh = {args.mesh.string(), mesh.num_faces(), args.scale, certipose::mesh_digest(mesh)};
    certipose::part_summary here;
    here.mesh = doc.mesh;
    certipose::describe_camera(here, solver.camera(), input.task);
    here.camera.mount_offset = input.mount_offset;
    doc.camera = here.camera;
    doc.task = here.task;
    here.scene = extra.record;
    doc.scene = extra.record;

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
        check_run(run, here, args.part_results);
        trust_run = !run.mesh.digest.empty();
        records = run.facets;
        certipose::read_part_boxes(args.part_results, run.settings.box_store, [&](const certipose::part_box& b) {
            if (b.facet >= mesh.num_faces())
                throw certipose::out_of_range("facet", b.facet, mesh.num_faces());
            if (b.box.cls != certipose::box_class::valid || !b.occlusion_checked) return;
            certipose::pose_box<I> box;
            for (std::size_t k = 0; k < 3; ++k) {
                box.position.x[k] = I(b.box.position[k][0], b.box.position[k][1]);
                box.orientation.x[k] = I(b.box.orientation[k][0], b.box.orientation[k][1]);
            }
            if (args.scene.regions.empty()) return pool.add(b.facet, box);
            // The run had these very regions (check_run), so its boxes are already allowed: cut
            // anyway, as the one-shot run does, so that no candidate can leave the allowed space.
            const auto pieces = certipose::split_by_regions(box.position, args.scene.regions,
                                                            args.scene.regions.width(run.settings.position_eps));
            for (const auto& p : pieces.allowed) pool.add(b.facet, certipose::pose_box<I>{p, box.orientation});
        });
        stage.done();
    } else {
        certipose::part_options opt;
        opt.facet.position_eps = *args.position_eps;
        opt.facet.orientation_eps = *args.orientation_eps;
        opt.threads = args.threads;
        opt.stop = signals.token();
        opt.regions = args.scene.regions;  // each facet's VALID boxes, before they become candidates
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
    doc.candidates = candidates.size();
    doc.tolerance = args.tolerance;

    // 2. C(B) of every candidate, plus its own facet when the run is trusted (see above).
    const auto t1 = std::chrono::steady_clock::now();
    std::vector<certipose::pose_box<I>> boxes;
    for (const auto& c : candidates) {
        if (!args.tolerance) {
            boxes.push_back(c.box);
            continue;
        }
        const double p = (*args.tolerance)[0], o = (*args.tolerance)[1];
        boxes.push_back(certipose::around_centre(c.box, {p, p, p, o, o, o}));
    }
    certipose::inspection_options iopt;
    iopt.threads = args.threads;
    iopt.stop = signals.token();
    iopt.possible_sets = false;  // the plan needs C(B) only
    if (progress)
        iopt.progress = [](std::size_t done, std::size_t all) {
            std::fprintf(stderr, "\r\033[Kcertipose-plan: certified facet sets of %zu / %zu candidate boxes", done, all);
            return true;
        };
    const certipose::inspection_run inspected = certipose::inspect_boxes(solver, boxes, iopt);
    if (progress) std::fputs("\r\033[K", stderr);
    if (signals.interrupted() || !inspected.completed) return report_interrupted("certipose-plan", signals);
    const double seconds_inspection = since(t1);
    // The inspector's areas: a duplicated face counts once (coverage/inspection.hpp).
    const std::vector<double> areas = certipose::facet_inspector<policies>(solver).areas();
    std::vector<certipose::deployment_candidate> sets(candidates.size());
    for (std::size_t j = 0; j < candidates.size(); ++j) {
        sets[j].facets = inspected.coverage[j].certified;
        auto& fs = sets[j].facets;
        if (trust_run && !std::binary_search(fs.begin(), fs.end(), candidates[j].facet))
            fs.insert(std::lower_bound(fs.begin(), fs.end(), candidates[j].facet), candidates[j].facet);
    }

    // 3. The choice and its lower bound.
    const auto t2 = std::chrono::steady_clock::now();
    certipose::deployment_options dopt;
    dopt.cameras = args.cameras;
    dopt.coverage = args.coverage;
    doc.max_cameras = args.cameras;
    doc.target_coverage = args.cameras ? args.coverage : std::optional<double>(args.coverage.value_or(0.95));
    certipose::deployment_plan plan = certipose::plan_greedy(sets, areas, dopt);
    std::string method =
        plan.lower_bound > certipose::area_lower_bound(sets, areas, plan.certified_area) ? "greedy" : "area";
    const auto lp_limit = std::chrono::milliseconds(static_cast<long long>(std::min(args.lp_seconds, 1e6) * 1000));
    if (progress)
        std::fprintf(stderr, "\r\033[Kcertipose-plan: %zu cameras chosen; GLPK's LP lower bound (up to %g s)...",
                     plan.chosen.size(), args.lp_seconds);
    const std::size_t lp = certipose::lp_lower_bound(sets, areas, plan.certified_area * (1 - 1e-9), lp_limit);
    if (progress) std::fputs("\r\033[K", stderr);
    if (lp > plan.lower_bound) plan.lower_bound = lp, method = "lp";
    bool exact = false;
    if (args.exact && plan.chosen.size() > plan.lower_bound) {
        const auto limit = std::chrono::milliseconds(static_cast<long long>(*args.exact * 1000));
        if (const auto best = certipose::plan_exact(sets, areas, plan.certified_area * (1 - 1e-9), limit)) {
            exact = true;
            if (best->size() < plan.chosen.size()) {
                const std::size_t bound = plan.lower_bound;
                plan = certipose::plan_of(sets, areas, *best);
                plan.lower_bound = std::max(bound, best->size());
            } else {
                plan.lower_bound = plan.chosen.size();  // proven optimal
            }
            method = "exact";
        }
    }
    const double seconds_choice = since(t2);

    for (std::size_t k = 0; k < plan.chosen.size(); ++k) {
        const std::size_t j = plan.chosen[k];
        const auto record = certipose::to_record(certipose::classified_box<I>{certipose::box_class::valid, boxes[j]});
        certipose::plan_document::camera_box cam;
        cam.position = record.position;
        cam.orientation = record.orientation;
        for (std::size_t i = 0; i < 3; ++i) {
            cam.nominal[i] = 0.5 * (record.position[i][0] + record.position[i][1]);
            cam.nominal[i + 3] = 0.5 * (record.orientation[i][0] + record.orientation[i][1]);
        }
        cam.facets = sets[j].facets;
        for (std::size_t f : cam.facets) cam.certified_area += areas[f];
        cam.from_facet = candidates[j].facet;
        doc.cameras.push_back(std::move(cam));
    }
    doc.coverage = {plan.certified_area, plan.coverable_area, plan.total_area, plan.lower_bound, method, plan.curve};

    // 4. The facets no chosen camera certifies, and why.
    std::vector<char> coverable(mesh.num_faces(), 0);
    for (const auto& s : sets)
        for (std::size_t f : s.facets) coverable[f] = 1;
    std::vector<const certipose::facet_record*> record_of(mesh.num_faces(), nullptr);
    for (const auto& r : records)
        if (r.index < record_of.size()) record_of[r.index] = &r;
    for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
        if (plan.covered_by[f] != certipose::deployment_plan::npos) continue;
        using certipose::uncovered_reason;
        uncovered_reason why = uncovered_reason::not_solved;
        if (coverable[f]) why = uncovered_reason::not_selected;
        else if (const auto* r = record_of[f]; r && r->termination != certipose::facet_termination::skipped) {
            if (r->valid > 0) why = uncovered_reason::not_selected;  // VALID boxes, none a candidate that proves it
            else if (r->boundary > 0) why = uncovered_reason::boundary_only;
            else if (r->termination != certipose::facet_termination::completed) why = uncovered_reason::not_finished;
            else why = uncovered_reason::never_visible;
        }
        doc.uncovered.push_back({f, why});
    }

    certipose::output_files files;
    files.add(args.out, certipose::json_text(certipose::plan_to_json(doc)));
    if (!args.ply.empty()) files.add(args.ply, certipose::plan_ply_text(mesh, doc));
    if (signals.interrupted()) return report_interrupted("certipose-plan", signals);
    files.commit();

    if (!args.quiet) {
        const auto pct = [](double a, double b) { return b > 0 ? 100.0 * a / b : 0.0; };
        std::printf("%s (%zu faces): %zu camera box(es) certify %.1f %% of the coverable area (%.1f %% of the part); "
                    "at least %zu needed (%s bound)\n",
                    args.mesh.string().c_str(), mesh.num_faces(), plan.chosen.size(), pct(plan.certified_area, plan.coverable_area),
                    pct(plan.certified_area, plan.total_area), plan.lower_bound, method.c_str());
        std::printf("  %zu candidates (%s %.2f s), their certified facet sets %.2f s, choice %.2f s%s; %zu facets uncovered\n",
                    candidates.size(), args.part_results.empty() ? "solved in" : "read in", seconds_candidates,
                    seconds_inspection, seconds_choice, exact ? " (GLPK exact)" : "", doc.uncovered.size());
        std::printf("wrote %s%s%s\n", args.out.string().c_str(), args.ply.empty() ? "" : " and ", args.ply.string().c_str());
    }
    return exit_ok;
}

}  // namespace

int main(int argc, char** argv) {
    int code = exit_ok;
    const auto args = parse(argc, argv, code);
    if (!args) return code;
    return report_errors("certipose-plan", [&] {
        std::vector<certipose::named_path> inputs{{"--mesh", args->mesh}, {"--camera", args->camera}};
        add_occluder_inputs(inputs, args->scene);
        if (!args->part_results.empty()) {
            inputs.push_back({"--part-results", args->part_results / "summary.json"});
            inputs.push_back({"--part-results", args->part_results / "boxes.jsonl"});
            inputs.push_back({"--part-results", args->part_results / "boxes.cpbx"});
        }
        std::vector<certipose::named_path> outputs{{"--out", args->out}};
        if (!args->ply.empty()) outputs.push_back({"--ply", args->ply});
        certipose::refuse_overwriting_inputs(inputs, outputs);
        const interruption signals;
        return run(*args, signals);
    });
}
