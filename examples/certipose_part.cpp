// certipose-part — certified camera pose boxes for every facet of a part (docs/part.md),
// in parallel.
//
//   certipose-part --mesh PART --camera CAMERA --position-eps E --orientation-eps O --out DIR
//                  [--threads N] [--facets 0,5,17-30] [--boundary] [--scale S]
//                  [--occlusion aabb|boolean|none] [--max-boxes-per-facet K]
//                  [--facet-time-limit SECONDS] [--time-limit SECONDS] [--max-boxes N]
//                  [--occluder MESH[:SCALE]]... [--keep-in REGION]... [--keep-out REGION]...
//                  [--part-tolerance TX,TY,TZ,ROT [--datum X,Y,Z]]
//                  [--working-distance DMIN,DMAX --min-view-angle RAD] [--mesh-semantics auto|solid|soup]
//                  [--keep-largest K] [--box-store binary|jsonl|both] [--no-reuse] [--resume] [--quiet]
//
// --occluder meshes join the part in the occlusion scene; each facet's VALID boxes are
// restricted to the --keep-in / --keep-out camera regions before they are written
// (part_options::regions); summary.json records both ("occluders", "keep_in", "keep_out").
//
// Built as certipose-part-mpi (CERTIPOSE_WITH_MPI), the same program runs under mpirun: facets
// are balanced over the ranks (part/mpi.hpp), each rank uses --threads threads, and rank 0 writes
// the one folder, identical to a single-process run's.
//
// Writes DIR/summary.json and the boxes (VALID; BOUNDARY ones too with --boundary) in
// DIR/boxes.cpbx, the binary store (io/box_store.hpp); --box-store jsonl|both writes
// DIR/boxes.jsonl, one JSON line per box, instead or as well (about three times the bytes).
// While it runs, the stores grow in DIR/run-in-progress/ with a journal of the facets finished,
// made durable every second (io/run_journal.hpp); at the end they move onto DIR/ with the
// summary. A run that a kill, a power loss or a full disk ends leaves DIR's earlier files as
// they were and the unfinished run beside them: --resume (same command) continues it, and a
// different input or setting is refused, naming it. A mesh that is not a clean closed solid is
// read as a triangle soup (--mesh-semantics auto), with a warning naming what was found
// (docs/occlusion.md). SIGINT/SIGTERM stop the run through its cancellation; the facets
// finished are written, the summary marked "interrupted", and the exit code is 130/143
// (--resume continues it too). Every error is one line "certipose-part: ..." on stderr: exit 1
// for bad input files, solver or write errors, 2 for a bad command line. A progress line
// (facets, rate, ETA, memory) goes to stderr when it is a terminal.
#include "program_support.hpp"
#include "program_scene.hpp"

#include <certipose/cgal.hpp>
#include <certipose/io/json.hpp>
#include <certipose/io/output_files.hpp>  // refuse_overwriting_inputs
#include <certipose/io/box_store.hpp>
#include <certipose/io/part_files.hpp>
#include <certipose/io/run_journal.hpp>
#include <certipose/part/part_solver.hpp>
#include <certipose/part/selection.hpp>
#if defined(CERTIPOSE_PART_MPI)
#include <certipose/part/mpi.hpp>
#endif

#include <CLI/CLI.hpp>

#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include <nlohmann/json.hpp>

namespace {

namespace fs = std::filesystem;
using namespace certipose_program;

/// The MPI rank (0 without MPI): only rank 0 prints errors, so a failure is one line, not one per rank.
int this_rank = 0;

struct arguments {
    fs::path mesh, camera, out;
    double position_eps = 0.1, orientation_eps = 0.38, scale = 1.0;
    std::size_t threads = 0;
    std::string facets;
    bool boundary = false, quiet = false, paper_paving = false, grow = false, reuse = true, resume = false;
    std::optional<double> refine;
    std::string occlusion = "aabb";
    std::optional<std::size_t> max_boxes_per_facet, max_boxes, corner_depth;
    std::optional<double> facet_time_limit, time_limit, corner_rest;
    std::optional<std::size_t> keep_largest;
    bool write_jsonl = false, write_binary = true;  ///< --box-store
    scene_arguments scene;  ///< --occluder, --keep-in, --keep-out
};

/// The parsed command line, or the exit code (0 after --help, 2 after a usage error).
std::optional<arguments> parse(int argc, char** argv, int& code) {
    CLI::App app{"certipose-part: certified camera pose boxes for every facet of a part, in parallel. Writes "
                 "DIR/summary.json and DIR/boxes.cpbx (docs/part.md).",
                 "certipose-part"};
    std::string mesh, camera, out, position_eps, orientation_eps, scale, threads, facets, per_facet_boxes,
        facet_time, time_limit, max_boxes, refine, corner_depth, corner_rest, occlusion = "aabb", keep_largest,
        box_store = "binary";
    bool boundary = false, quiet = false, paper_paving = false, grow = false, no_reuse = false, resume = false;
    app.add_option("--mesh", mesh, "part mesh: OFF, OBJ, PLY or STL (triangles only)")->type_name("PART")->required()->check(CLI::ExistingFile);
    app.add_option("--camera", camera, "camera/task JSON, or an OpenCV/ROS calibration file with --working-distance and --min-view-angle (docs/io.md)")->type_name("CAMERA")->required()->check(CLI::ExistingFile);
    app.add_option("--position-eps", position_eps, "position threshold, metres (paper: 0.1)")->type_name("METRES")->required();
    app.add_option("--orientation-eps", orientation_eps, "orientation threshold, radians (paper: 0.38)")->type_name("RADIANS")->required();
    app.add_option("--out", out, "output folder (created if missing)")->type_name("DIR")->required();
    app.add_option("--threads", threads, "worker threads (default: every core)")->type_name("N");
    app.add_option("--facets", facets, "facets to solve, e.g. 0,5,17-30 (default: all)")->type_name("LIST");
    app.add_flag("--boundary", boundary, "also write BOUNDARY boxes");
    app.add_option("--scale", scale, "multiply mesh coordinates by S (e.g. 0.001 for mm)")->type_name("S");
    app.add_option("--occlusion", occlusion, "occlusion test: aabb (default), boolean or none")->type_name("MODE")->check(CLI::IsMember({"aabb", "boolean", "none"}));
    app.add_option("--max-boxes-per-facet", per_facet_boxes, "box budget of each facet")->type_name("K");
    app.add_option("--facet-time-limit", facet_time, "time budget of each facet")->type_name("SECONDS");
    app.add_option("--time-limit", time_limit, "time budget of the whole run")->type_name("SECONDS");
    app.add_option("--max-boxes", max_boxes, "box budget of the whole run (facets in order)")->type_name("N");
    app.add_flag("--paper-paving", paper_paving,
                 "pave as the paper does: bisect partly valid boxes, no inner contraction, occlusion cuts or corner boxes");
    app.add_option("--corner-depth", corner_depth,
                   "corner boxes one undecided leaf may give in a row, 1-8 (default 2; 1 writes fewer boxes)")->type_name("N");
    app.add_option("--corner-rest", corner_rest,
                   "a rest box gives a corner box only when each side is at least PIECES minimal pieces "
                   "(eps/10; default 3, 2 certifies more, slower)")->type_name("PIECES");
    app.add_option("--refine", refine, "per facet, keep refining below position-eps for SECONDS")->type_name("SECONDS");
    app.add_flag("--grow", grow, "widen the VALID boxes: merge neighbours, move faces out while certified");
    app.add_flag("--no-reuse", no_reuse,
                 "pave every facet on its own (default: a facet nothing can occlude takes the boxes of a translate of it, "
                 "each proven again)");
    app.add_option("--keep-largest", keep_largest, "keep only the K largest VALID boxes of each facet (6D volume)")->type_name("K");
    app.add_option("--box-store", box_store,
                   "which box files to write: binary (boxes.cpbx, the default; docs/part.md), jsonl (boxes.jsonl, one JSON line per box) or both")
        ->type_name("FORMAT")
        ->check(CLI::IsMember({"jsonl", "binary", "both"}));
    app.add_flag("--resume", resume,
                 "continue the run in DIR that a kill, a signal, a full disk, --time-limit or --max-boxes ended, "
                 "with the same inputs and settings (docs/part.md)");
    scene_options_text scene;
    add_scene_options(app, scene);
    app.add_flag("--quiet,-q", quiet, "print nothing but errors");
    if (!parse_command_line(app, argc, argv, "certipose-part", code, this_rank == 0)) return std::nullopt;
    try {
        arguments a;
        a.mesh = mesh;
        a.camera = camera;
        a.out = out;
        a.position_eps = parse_double("--position-eps", position_eps, "a positive finite number of metres");
        a.orientation_eps = parse_double("--orientation-eps", orientation_eps, "a positive finite number of radians");
        if (!scale.empty()) a.scale = parse_double("--scale", scale, "a positive finite factor");
        if (!threads.empty()) a.threads = parse_count("--threads", threads, 1);
        a.facets = facets;
        a.boundary = boundary;
        a.quiet = quiet;
        a.occlusion = occlusion;
        if (!per_facet_boxes.empty()) a.max_boxes_per_facet = parse_count("--max-boxes-per-facet", per_facet_boxes, 1);
        if (!max_boxes.empty()) a.max_boxes = parse_count("--max-boxes", max_boxes, 1);
        if (!facet_time.empty()) a.facet_time_limit = parse_double("--facet-time-limit", facet_time, "a positive finite number of seconds");
        if (!refine.empty()) a.refine = parse_double("--refine", refine, "a positive finite number of seconds");
        a.paper_paving = paper_paving;
        if (!corner_depth.empty()) a.corner_depth = parse_corner_depth(corner_depth);
        if (!corner_rest.empty()) a.corner_rest = parse_corner_rest(corner_rest);
        a.grow = grow;
        a.reuse = !no_reuse;
        a.resume = resume;
        if (!keep_largest.empty()) a.keep_largest = parse_count("--keep-largest", keep_largest, 1);
        a.write_jsonl = box_store != "binary";
        a.write_binary = box_store != "jsonl";
        a.scene = parse_scene_options(scene, a.camera);
        if (!time_limit.empty()) a.time_limit = parse_double("--time-limit", time_limit, "a positive finite number of seconds");
        std::error_code ec;
        if (fs::exists(a.out, ec) && !fs::is_directory(a.out, ec))
            throw usage_error("--out: " + a.out.string() + " exists and is not a directory");
        const fs::path parent = fs::absolute(a.out).parent_path();
        if (!fs::is_directory(parent, ec)) throw usage_error("--out: directory does not exist: " + parent.string());
        return a;
    } catch (const usage_error& e) {
        usage_failure("certipose-part", e.what(), code, this_rank == 0);
        return std::nullopt;
    }
}

std::chrono::steady_clock::duration seconds(double s) {
    return std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(s));
}

/// The default pipeline with a calibrated camera and the chosen occlusion policy (with aabb it is
/// exactly the pipeline certipose::precompiled instantiates).
template <class Occlusion>
using part_solver_for = certipose::part_solver<std::conditional_t<
    std::is_same_v<Occlusion, certipose::aabb_occlusion>, certipose::with_camera<certipose::calibrated_camera>,
    certipose::with_occlusion<Occlusion, certipose::with_camera<certipose::calibrated_camera>>>>;

/// summary.json's record of everything else that changes the answer, and of the survey when
/// the occlusion read the scene as a triangle soup.
template <class Part, class Occlusion>
void describe_run_settings(certipose::part_summary& s, const arguments& args, const certipose::solve_options& facet,
                           const Occlusion& occlusion) {
    auto& st = s.settings;
    st.paving = args.paper_paving ? "paper" : "default";
    const certipose::carving c = Part::solver_type::paving_steps(facet.paving);
    st.inner_contraction = c.inner_contraction.is_on();
    st.occlusion_cuts = c.occlusion_cuts.is_on();
    st.leaf_corner_boxes = c.corner_boxes;
    st.corner_depth = c.corner_depth;
    st.corner_rest_min_pieces = c.rest_min_pieces;
    st.refine_seconds = args.refine;
    st.grow = args.grow;
    st.max_boxes = args.max_boxes;
    st.facets = args.facets;
    st.keep_largest = args.keep_largest;
    st.reuse = args.reuse;
    st.box_store = args.write_jsonl && args.write_binary ? "both" : args.write_binary ? "binary" : "jsonl";
    st.mesh_semantics = certipose::checks_occlusion<Occlusion> ? "solid" : "none";  // the boolean test reads solids
    if constexpr (requires { occlusion.survey(); }) {
        st.mesh_semantics = std::string(certipose::to_string(occlusion.semantics()));
        if (const certipose::mesh_survey* v = occlusion.survey())
            s.survey = certipose::part_summary::survey_record{v->bodies,           v->closed_bodies,     v->inward_bodies,
                                                              v->open_edges,       v->nonmanifold_edges, v->duplicate_faces,
                                                              v->intersecting_pairs, v->buried,          v->covered,
                                                              v->examples};
    }
}

/// This process's place in an MPI run (rank 0 of 1 without MPI).
struct process {
    int rank = 0, ranks = 1;
};

/// An error on one rank during an MPI run, while the other ranks wait for it (see `solve`).
struct rank_failure : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// A failure during the run whose message is complete (it says what is kept for --resume).
struct run_failure : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// Discards what it is given (the sink of MPI ranks other than 0, which write nothing).
struct null_sink {
    void facet(const certipose::facet_outcome<certipose::boost_interval>&) {}
};

/// Rank 0's values of `v` on every rank (nothing to do without MPI).
void broadcast(std::array<std::int64_t, 2>& v, process proc) {
#if defined(CERTIPOSE_PART_MPI)
    if (proc.ranks > 1) MPI_Bcast(v.data(), 2, MPI_INT64_T, 0, MPI_COMM_WORLD);
#else
    (void)v, (void)proc;
#endif
}

/// The run's journal (io/run_journal.hpp): the unfinished run continued with --resume, else a
/// new one. Returns how many facets of `selection` are done (their boxes in `boxes_done`), or
/// -2 when --resume finds the run complete.
std::int64_t prepare_journal(const arguments& args, const certipose::part_summary& s, const std::vector<std::size_t>& selection,
                             std::optional<certipose::part_run_journal>& journal, std::size_t& boxes_done) {
    using certipose::part_run_journal;
    const nlohmann::json key =
        certipose::resume_key(nlohmann::json::parse(certipose::json_text(certipose::part_summary_to_json(s))));
    std::vector<std::string> stores;
    if (args.write_binary) stores.emplace_back("boxes.cpbx");
    if (args.write_jsonl) stores.emplace_back("boxes.jsonl");
    const fs::path unfinished = args.out / std::string(part_run_journal::folder_name);
    std::error_code ec;
    if (args.resume) {
        switch (part_run_journal::resume(args.out, key, stores, journal)) {
            case part_run_journal::found::complete:
                if (!args.quiet) std::printf("%s: the run there is complete; nothing to resume\n", args.out.string().c_str());
                return -2;
            case part_run_journal::found::nothing:
                if (!args.quiet)
                    std::fprintf(stderr, "certipose-part: nothing to resume in %s: starting the run\n", args.out.string().c_str());
                break;
            case part_run_journal::found::unfinished: break;
        }
    } else if (fs::exists(unfinished, ec) && !args.quiet) {
        std::fprintf(stderr, "certipose-part: note: starting over; the unfinished run in %s is discarded (--resume continues it)\n",
                     unfinished.string().c_str());
    }
    if (!journal) journal.emplace(part_run_journal::start(args.out, key, stores));
    const auto& done = journal->done().facets;
    for (std::size_t i = 0; i < done.size(); ++i)
        if (i >= selection.size() || done[i].index != selection[i])
            throw certipose::invalid_argument(
                "--resume", "--resume: the run in " + args.out.string() + " finished facet " + std::to_string(done[i].index) +
                                (i < selection.size() ? " where this selection has facet " + std::to_string(selection[i])
                                                      : " beyond this selection") +
                                "; run without --resume to start over");
    for (const auto& f : done) boxes_done += f.valid + f.boundary;
    return static_cast<std::int64_t>(done.size());
}

/// Runs the part and writes the folder; returns the exit code.
template <class Occlusion>
int run(const arguments& args, const certipose::triangle_mesh& mesh, const certipose::camera_task& input,
        const scene& extra, const interruption& signals, process proc) {
    using I = certipose::boost_interval;
    stage_line stage("certipose-part", args.quiet || proc.rank != 0);
    if constexpr (!std::is_same_v<Occlusion, certipose::no_occlusion>)
        stage.show("building the occlusion scene of the " + std::to_string(mesh.num_faces()) + " faces");
    const auto part = naming_occluders(args.scene, [&] {
        return part_solver_for<Occlusion>(mesh, input.calibrated(), input.task, {.occluders = extra.occluders, .semantics = args.scene.semantics});
    });
    stage.done();
    if (proc.rank == 0) warn_about_scene("certipose-part", part.solver().occlusion(), args.quiet);

    certipose::part_options opt;
    opt.facet.position_eps = args.position_eps;
    opt.facet.orientation_eps = args.orientation_eps;
    if (args.max_boxes_per_facet) opt.facet.max_boxes = *args.max_boxes_per_facet;
    if (args.facet_time_limit) opt.facet.time_limit = seconds(*args.facet_time_limit);
    opt.facet.paving = paving_for(args.paper_paving, args.corner_depth, args.corner_rest);
    if (args.refine) opt.facet.refine = certipose::refinement{.time_limit = seconds(*args.refine)};
    if (args.grow) opt.facet.grow = certipose::growth_options{};
    if (args.time_limit) opt.time_limit = seconds(*args.time_limit);
    opt.max_boxes = args.max_boxes;
    opt.threads = args.threads;
    opt.keep_boundary = args.boundary;
    opt.keep_largest = args.keep_largest;
    opt.reuse.translates = args.reuse;
    opt.regions = args.scene.regions;  // each facet's VALID boxes, before they are written
    if (!args.facets.empty()) opt.facets = certipose::parse_facet_selection(args.facets, mesh.num_faces());
    opt.stop = signals.token();
    // The summary's record of the run, all but its results: what a resumed run must share with
    // the run it continues (io/run_journal.hpp).
    certipose::part_summary s;
    s.mesh = {args.mesh.string(), mesh.num_faces(), args.scale, certipose::mesh_digest(mesh)};
    certipose::describe_camera(s, part.solver().camera(), input.task);
    s.camera.mount_offset = input.mount_offset;
    s.settings.position_eps = args.position_eps;
    s.settings.orientation_eps = args.orientation_eps;
    s.settings.max_boxes_per_facet = opt.facet.max_boxes;
    s.settings.time_limit_per_facet = args.facet_time_limit;
    s.settings.time_limit = args.time_limit;
    s.settings.boundary = args.boundary;
    s.settings.occlusion = args.occlusion;
    s.settings.occlusion_checked = certipose::checks_occlusion<Occlusion>;
    describe_run_settings<std::decay_t<decltype(part)>>(s, args, opt.facet, part.solver().occlusion());
    s.scene = extra.record;

    const std::vector<std::size_t> selection = certipose::selected_facets(opt, mesh.num_faces());
    // Rank 0 keeps the journal and tells the other ranks where the selection resumes (-1 after
    // an error there, which it reports; -2 when the run is already complete) and how many boxes
    // the facets before hold (the run's box budget: every rank must agree on what is left).
    std::optional<certipose::part_run_journal> journal;
    std::array<std::int64_t, 2> resume{0, 0};
    if (proc.rank == 0) {
        try {
            std::size_t boxes = 0;
            resume[0] = prepare_journal(args, s, selection, journal, boxes);
            resume[1] = static_cast<std::int64_t>(boxes);
        } catch (...) {
            resume[0] = -1;
            broadcast(resume, proc);
            throw;
        }
    }
    broadcast(resume, proc);
    if (resume[0] == -1) return exit_failure;  // another rank: rank 0 says why
    if (resume[0] == -2) return exit_ok;
    const auto first = static_cast<std::size_t>(resume[0]);
    const auto boxes_done = static_cast<std::size_t>(resume[1]);
    opt.facets.assign(selection.begin() + static_cast<std::ptrdiff_t>(first), selection.end());
    // Nothing left: every facet selected is done, or the box budget is spent.
    const bool budget_spent = args.max_boxes && boxes_done >= *args.max_boxes;
    const bool nothing_left = opt.facets.empty() || budget_spent;
    if (args.max_boxes && !budget_spent) opt.max_boxes = *args.max_boxes - boxes_done;

    const bool progress = proc.rank == 0 && show_progress(args.quiet);
    std::size_t valid_done = 0;  // by the runs this one continues
    if (journal)
        for (const auto& f : journal->done().facets) valid_done += f.valid;
    if (progress)
        opt.progress = [first, valid_done, total = selection.size()](const certipose::part_progress& p) {
            const std::size_t valid = valid_done + p.valid;
            const double rate = p.seconds > 0 ? static_cast<double>(p.facets_done) / p.seconds : 0.0;
            std::fprintf(stderr, "\r\033[K%7zu / %zu facets  %9zu valid  %7.1f facets/s  ETA %-8s  %6.0f MB",
                         first + p.facets_done, total, valid, rate, duration_text(p.seconds_left).c_str(),
                         static_cast<double>(resident_bytes()) / 1e6);
            return true;
        };

    const auto solve = [&](auto& sink) -> certipose::part_result {
        if (nothing_left) return {};  // (an empty opt.facets would mean every facet)
        try {
#if defined(CERTIPOSE_PART_MPI)
            return certipose::solve_part_mpi(part, opt, sink, MPI_COMM_WORLD);
#else
            return part.solve(opt, sink);
#endif
        } catch (const std::exception& e) {
            std::string message = e.what();
            if (journal)
                message += "; the facets finished so far are kept in " + journal->folder().string() +
                           ": run the same command with --resume to continue";
#if defined(CERTIPOSE_PART_MPI)
            // Every rank reads the same inputs, so errors before this point happen on all of them
            // and each returns. An error during the run is one rank's alone (rank 0's disk full, a
            // worker's failure) while the others wait for its messages: it must name the rank and
            // end the job, not return into MPI_Finalize and leave the others hanging. main() does
            // that on rank_failure, once this rank's own files are closed.
            throw rank_failure(message);
#else
            throw run_failure(message);
#endif
        }
    };
    if (proc.rank != 0) {  // a worker rank: solves what rank 0 hands out, writes nothing
        null_sink nothing;
        (void)solve(nothing);
        return signals.interrupted() ? signals.exit_code() : exit_ok;
    }
    std::optional<certipose::jsonl_sink<I>> jsonl;
    std::optional<certipose::box_store_sink<I>> binary;
    if (args.write_jsonl) jsonl.emplace(journal->store("boxes.jsonl"), certipose::checks_occlusion<Occlusion>);
    if (args.write_binary)  // a resumed store keeps its header and the records of the facets done
        binary.emplace(certipose::box_store_sink<I>::append_to(journal->store("boxes.cpbx"), certipose::checks_occlusion<Occlusion>));
    journal->checkpoint();  // the stores' headers, durable before the first facet
    certipose::tee_sink<certipose::jsonl_sink<I>, certipose::box_store_sink<I>> stores{
        {jsonl ? &*jsonl : nullptr, binary ? &*binary : nullptr}};
    certipose::journal_sink<decltype(stores)> sink{&stores, &*journal};
    const certipose::part_result r = solve(sink);
    if (progress) std::fputc('\n', stderr);

    s.facets = journal->done().facets;
    s.facets.insert(s.facets.end(), r.facets.begin(), r.facets.end());
    std::size_t valid = 0, boundary = 0, skipped = 0;
    for (const auto& f : s.facets) {
        valid += f.valid;
        boundary += f.boundary;
        skipped += f.termination == certipose::facet_termination::skipped;
    }
    const certipose::termination reason = s.facets.size() == selection.size() ? certipose::termination::completed
                                          : budget_spent                       ? certipose::termination::box_budget
                                                                               : r.reason;
    const std::size_t threads = r.threads ? r.threads : (args.threads ? args.threads : std::thread::hardware_concurrency());
    s.totals = {journal->seconds(), threads, static_cast<std::size_t>(proc.ranks), selection.size(), s.facets.size(), valid,
                boundary, skipped, reason, signals.interrupted()};
    try {
        if (binary) binary->finish();
        journal->commit(certipose::json_text(certipose::part_summary_to_json(s)));
    } catch (const certipose::error& e) {
        throw run_failure(std::string(e.what()) + "; the facets finished are kept in " + journal->folder().string() +
                          ": run the same command with --resume to finish");
    }
    // A box file of an earlier run in this folder that this run did not write would contradict
    // the new summary (which names the stores it wrote, settings.box_store): remove it.
    std::error_code gone;
    if (!args.write_jsonl) fs::remove(args.out / "boxes.jsonl", gone);
    if (!args.write_binary) fs::remove(args.out / "boxes.cpbx", gone);

    if (!args.quiet) {
        std::printf("%s (%zu faces): %zu of %zu facets in %.2f s on %d rank(s) x %zu threads: %zu valid, %zu boundary "
                    "boxes, %zu facets skipped\n",
                    args.mesh.string().c_str(), mesh.num_faces(), s.facets.size(), selection.size(), s.totals.seconds, proc.ranks,
                    threads, valid, boundary, skipped);
        if (first > 0)
            std::printf("  resumed: %zu facet(s) were finished by the run it continues\n", journal->done().facets.size());
        if (reason != certipose::termination::completed)
            std::printf("  stopped early: %s ended the run; the facets finished are written (--resume continues it)\n",
                        signals.interrupted() ? interruption::name(signals.signal()) : certipose::to_string(reason));
        if (!certipose::checks_occlusion<Occlusion>)
            std::printf("  occlusion NOT checked (--occlusion none): VALID boxes hold for every constraint but occlusion\n");
        if (const std::string text = scene_text(args.scene); !text.empty()) std::printf("  scene: %s\n", text.c_str());
        std::printf("wrote %s", (args.out / "summary.json").string().c_str());
        if (args.write_jsonl) std::printf(", %s", (args.out / "boxes.jsonl").string().c_str());
        if (args.write_binary) std::printf(", %s", (args.out / "boxes.cpbx").string().c_str());
        std::printf("\n");
    }
    return signals.interrupted() ? signals.exit_code() : exit_ok;
}

int report(const std::string& message) {
    if (this_rank == 0) std::cerr << "certipose-part: " << one_line(message) << "\n";
    return exit_failure;
}

}  // namespace

#if defined(CERTIPOSE_PART_MPI)
/// MPI for the program's lifetime; only the main thread calls MPI (part/mpi.hpp).
struct mpi_session {
    process proc;
    mpi_session(int& argc, char**& argv) {
        int provided = 0;
        MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
        MPI_Comm_rank(MPI_COMM_WORLD, &proc.rank);
        MPI_Comm_size(MPI_COMM_WORLD, &proc.ranks);
    }
    ~mpi_session() { MPI_Finalize(); }
};
#endif

int main(int argc, char** argv) {
#if defined(CERTIPOSE_PART_MPI)
    const mpi_session mpi(argc, argv);
    const process proc = mpi.proc;
#else
    const process proc{};
#endif
    this_rank = proc.rank;
    int code = exit_ok;
    const auto args = parse(argc, argv, code);
    if (!args) return code;
    try {
        std::vector<certipose::named_path> inputs{{"--mesh", args->mesh}, {"--camera", args->camera}};
        add_occluder_inputs(inputs, args->scene);
        certipose::refuse_overwriting_inputs(
            inputs, {{"--out", args->out},
                     {"--out", args->out / "summary.json"},
                     {"--out", args->out / "boxes.jsonl"},
                     {"--out", args->out / "boxes.cpbx"}});
        const interruption signals;
        stage_line stage("certipose-part", args->quiet || proc.rank != 0);
        stage.show("reading " + args->mesh.string());
        const certipose::triangle_mesh mesh = certipose::read_mesh(args->mesh, {.scale = args->scale});
        const scene extra = read_scene(args->scene, &stage);
        stage.done();
        certipose::camera_task input = certipose_program::read_camera(args->camera, args->scene);
        certipose_program::apply_placement(input.task, args->scene, mesh);
        if (args->occlusion == "boolean") return run<certipose::boolean_occlusion>(*args, mesh, input, extra, signals, proc);
        if (args->occlusion == "none") return run<certipose::no_occlusion>(*args, mesh, input, extra, signals, proc);
        return run<certipose::aabb_occlusion>(*args, mesh, input, extra, signals, proc);
    } catch (const rank_failure& e) {
        std::cerr << "certipose-part: rank " << proc.rank << " of " << proc.ranks << ": " << one_line(e.what())
                  << "; ending the MPI job" << std::endl;
#if defined(CERTIPOSE_PART_MPI)
        if (proc.ranks > 1) MPI_Abort(MPI_COMM_WORLD, exit_failure);
#endif
        return exit_failure;
    } catch (const run_failure& e) {
        return report(e.what());
    } catch (const certipose::error& e) {
        return report(e.what());
    } catch (const std::exception& e) {
        return report(std::string("unexpected error: ") + e.what());
    }
}
