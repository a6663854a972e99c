// certipose-part — certified camera pose boxes for every facet of a part (docs/part.md),
// in parallel.
//
//   certipose-part --mesh PART --camera CAMERA --position-eps E --orientation-eps O --out DIR
//                  [--threads N] [--facets 0,5,17-30] [--boundary] [--scale S] [--part-pose POSE]
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
#include "program_skeleton.hpp"
#include "program_scene.hpp"

#include <certipose/cgal.hpp>
#include <certipose/io/json.hpp>
#include <certipose/io/output_files.hpp>
#include <certipose/io/box_store.hpp>
#include <certipose/io/part_files.hpp>
#include <certipose/io/run_journal.hpp>
#include <certipose/part/part_solver.hpp>
#include <certipose/part/selection.hpp>
#include <certipose/solver/occlusion_choice.hpp>
#include <certipose/solver/solve_settings.hpp>
#if defined(CERTIPOSE_PART_MPI)
#include <certipose/part/mpi.hpp>
#endif

#include <CLI/CLI.hpp>

#include <array>
#include <chrono>
#include <csignal>
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
using I = certipose::boost_interval;

/// This process's place in an MPI run (rank 0 of 1 without MPI).
struct process {
    int rank = 0, ranks = 1;
};
process this_process;

/// certipose-part as the programs' skeleton sees it (program_skeleton.hpp).
struct part_program {
    static constexpr const char* name = "certipose-part";
    static constexpr const char* description =
        "certipose-part: certified camera pose boxes for every facet of a part, in parallel. Writes DIR/summary.json "
        "and DIR/boxes.cpbx (docs/part.md).";

    struct options {
        input_options_text inputs;
        solver_options_text solver;
        std::string out, threads, facets, occlusion, time_limit, max_boxes, keep_largest, box_store = "binary";
        bool boundary = false, quiet = false, no_reuse = false, patches = false, resume = false;
    };

    struct arguments {
        input_arguments inputs;          ///< --mesh, --camera, --scale and the scene options
        certipose::solve_settings solve;  ///< each facet's thresholds, budgets and paving
        certipose::occlusion_choice occlusion = certipose::occlusion_choice::aabb;
        fs::path out;
        std::size_t threads = 0;
        std::string facets;
        bool boundary = false, quiet = false, reuse = true, patches = false, resume = false;
        std::optional<std::size_t> max_boxes, keep_largest;
        std::optional<double> time_limit;
        bool write_jsonl = false, write_binary = true;  ///< --box-store

        std::vector<certipose::named_path> files_read() const { return inputs.paths(); }
        std::vector<certipose::named_path> files_written() const {
            return {{"--out", out},
                    {"--out", out / "summary.json"},
                    {"--out", out / "boxes.jsonl"},
                    {"--out", out / "boxes.cpbx"},
                    {"--out", out / "mesh.off"}};
        }
    };

    static void declare(CLI::App& app, options& text) {
        add_input_options(app, text.inputs);
        add_solver_options(app, text.solver, per_facet_budgets);
        add_occlusion_option(app, text.occlusion);
        app.add_option("--out", text.out, "output folder (created if missing)")->type_name("DIR")->required();
        app.add_option("--threads", text.threads, "worker threads (default: every core)")->type_name("N");
        app.add_option("--facets", text.facets, "facets to solve, e.g. 0,5,17-30 (default: all)")->type_name("LIST");
        app.add_flag("--boundary", text.boundary, "also write BOUNDARY boxes");
        app.add_option("--time-limit", text.time_limit, "time budget of the whole run")->type_name("SECONDS");
        app.add_option("--max-boxes", text.max_boxes, "box budget of the whole run (facets in order)")->type_name("N");
        app.add_flag("--no-reuse", text.no_reuse,
                     "pave every facet on its own (default: a facet nothing can occlude takes the boxes of a translate of "
                     "it, each proven again)");
        app.add_flag("--patches", text.patches,
                     "certify patches of neighbouring facets (of one CAD face for a STEP part) at once: the seed's boxes "
                     "proven for every member (docs/part.md; not yet faster than facet by facet)");
        app.add_option("--keep-largest", text.keep_largest, "keep only the K largest VALID boxes of each facet (6D volume)")
            ->type_name("K");
        app.add_option("--box-store", text.box_store,
                       "which box files to write: binary (boxes.cpbx, the default; docs/part.md), jsonl (boxes.jsonl, one "
                       "JSON line per box) or both")
            ->type_name("FORMAT")
            ->check(CLI::IsMember({"jsonl", "binary", "both"}));
        app.add_flag("--resume", text.resume,
                     "continue the run in DIR that a kill, a signal, a full disk, --time-limit or --max-boxes ended, "
                     "with the same inputs and settings (docs/part.md)");
        app.add_flag("--quiet,-q", text.quiet, "print nothing but errors");
    }

    static arguments check(const options& text) {
        arguments a;
        a.inputs = parse_input_options(text.inputs);
        a.solve = parse_solver_options(text.solver, per_facet_budgets);
        a.occlusion = parse_occlusion_option(text.occlusion);
        a.out = text.out;
        if (!text.threads.empty()) a.threads = parse_count("--threads", text.threads, 1);
        a.facets = text.facets;
        a.boundary = text.boundary;
        a.quiet = text.quiet;
        a.reuse = !text.no_reuse;
        a.patches = text.patches;
        a.resume = text.resume;
        if (!text.max_boxes.empty()) a.max_boxes = parse_count("--max-boxes", text.max_boxes, 1);
        if (!text.time_limit.empty())
            a.time_limit = parse_double("--time-limit", text.time_limit, "a positive finite number of seconds");
        if (!text.keep_largest.empty()) a.keep_largest = parse_count("--keep-largest", text.keep_largest, 1);
        a.write_jsonl = text.box_store != "binary";
        a.write_binary = text.box_store != "jsonl";
        std::error_code ec;
        if (fs::exists(a.out, ec) && !fs::is_directory(a.out, ec))
            throw usage_error("--out: " + a.out.string() + " exists and is not a directory");
        const fs::path parent = fs::absolute(a.out).parent_path();
        if (!fs::is_directory(parent, ec)) throw usage_error("--out: directory does not exist: " + parent.string());
        return a;
    }

    static int run(const arguments& args, const interruption& signals);
};

using arguments = part_program::arguments;

/// The part solver of the programs' pipeline under occlusion policy `Occlusion`.
template <class Occlusion>
using part_solver_for = certipose::part_solver<certipose::calibrated_pipeline<Occlusion>>;

/// The whole-part options the command line says (all but the progress callback).
certipose::part_options part_options_for(const arguments& args, std::size_t faces, std::stop_token stop) {
    certipose::part_options opt;
    opt.facet = certipose::to_solve_options(args.solve);
    if (args.time_limit) opt.time_limit = certipose::seconds_setting(*args.time_limit, "--time-limit");
    opt.max_boxes = args.max_boxes;
    opt.threads = args.threads;
    opt.keep_boundary = args.boundary;
    opt.keep_largest = args.keep_largest;
    opt.reuse.translates = args.reuse;
    opt.patches.enabled = args.patches;
    opt.regions = args.inputs.scene.regions;  // each facet's VALID boxes, before they are written
    if (!args.facets.empty()) opt.facets = certipose::parse_facet_selection(args.facets, faces);
    opt.stop = stop;
    return opt;
}

/// The summary's record of the run, all but its results: what a resumed run must share with the
/// run it continues (io/run_journal.hpp). Records the survey when the occlusion read the scene as
/// a triangle soup.
template <class Part>
certipose::part_summary describe_run(const arguments& args, const program_inputs& in, const Part& part,
                                     const certipose::part_options& opt) {
    using Occlusion = typename Part::solver_type::occlusion_type;
    certipose::part_summary s;
    s.mesh = {args.inputs.mesh.string(), in.mesh.num_faces(), args.inputs.scale, certipose::mesh_digest(in.mesh),
              pose_record(args.inputs)};
    certipose::describe_camera(s, part.solver().camera(), in.camera.task);
    s.camera.mount_offset = in.camera.mount_offset;
    auto& st = s.settings;
    st.position_eps = args.solve.position_eps;
    st.orientation_eps = args.solve.orientation_eps;
    st.max_boxes_per_facet = opt.facet.max_boxes;
    st.time_limit_per_facet = args.solve.time_limit;
    st.time_limit = args.time_limit;
    st.boundary = args.boundary;
    st.occlusion = std::string(certipose::to_string(args.occlusion));
    st.occlusion_checked = certipose::checks_occlusion<Occlusion>;
    st.paving = args.solve.paper_paving ? "paper" : "default";
    const certipose::carving c = Part::solver_type::paving_steps(opt.facet.paving);
    st.inner_contraction = c.inner_contraction.is_on();
    st.occlusion_cuts = c.occlusion_cuts.is_on();
    st.leaf_corner_boxes = c.corner_boxes;
    st.corner_depth = c.corner_depth;
    st.corner_rest_min_pieces = c.rest_min_pieces;
    st.refine_seconds = args.solve.refine;
    st.grow = args.solve.grow;
    st.max_boxes = args.max_boxes;
    st.facets = args.facets;
    st.keep_largest = args.keep_largest;
    st.reuse = args.reuse;
    if (part.patches(opt)) {  // on, and not turned off by --boundary
        st.patches = opt.patches;
        st.patches->max_extent = part.patch_extent(opt.patches);
        st.patches->faces.clear();
    }
    st.box_store = args.write_jsonl && args.write_binary ? "both" : args.write_binary ? "binary" : "jsonl";
    st.mesh_semantics = certipose::checks_occlusion<Occlusion> ? "solid" : "none";  // the boolean test reads solids
    const auto& occlusion = part.solver().occlusion();
    if constexpr (requires { occlusion.survey(); }) {
        st.mesh_semantics = std::string(certipose::to_string(occlusion.semantics()));
        if (const certipose::mesh_survey* v = occlusion.survey())
            s.survey = certipose::part_summary::survey_record{v->bodies,           v->closed_bodies,     v->inward_bodies,
                                                              v->open_edges,       v->nonmanifold_edges, v->duplicate_faces,
                                                              v->intersecting_pairs, v->buried,          v->covered,
                                                              v->examples};
    }
    s.scene = in.extra.record;
    s.cad = in.cad;
    return s;
}

/// An error on one rank during an MPI run, while the other ranks wait for it (see `solve_on`).
struct rank_failure : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// A failure during the run whose message is complete: it says what is kept for --resume.
struct run_failure : certipose::error {
    using certipose::error::error;
};

/// Discards what it is given (the sink of MPI ranks other than 0, which write nothing).
struct null_sink {
    void facet(const certipose::facet_outcome<I>&) {}
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

/// Where this run starts: after the facets a resumed run finished (rank 0 decides, every rank learns).
struct resume_point {
    enum { go, complete, failed_elsewhere } status = go;
    std::size_t first = 0;       ///< facets of the selection already done
    std::size_t boxes_done = 0;  ///< their boxes (the run's box budget counts them)
};

/// Rank 0 keeps the journal and tells the other ranks where the selection resumes (-1 after an
/// error there, which it reports; -2 when the run is already complete) and how many boxes the
/// facets before hold: every rank must agree on what is left of the box budget.
resume_point agree_on_resume(const arguments& args, const certipose::part_summary& s, const std::vector<std::size_t>& selection,
                             std::optional<certipose::part_run_journal>& journal, process proc) {
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
    if (resume[0] == -1) return {resume_point::failed_elsewhere};  // another rank: rank 0 says why
    if (resume[0] == -2) return {resume_point::complete};
    return {resume_point::go, static_cast<std::size_t>(resume[0]), static_cast<std::size_t>(resume[1])};
}

/// The progress line on a terminal (rank 0): facets, rate, ETA and memory, counting what the runs
/// this one continues finished.
std::function<bool(const certipose::part_progress&)> progress_line(const std::optional<certipose::part_run_journal>& journal,
                                                                   std::size_t first, std::size_t total) {
    std::size_t valid_done = 0;
    if (journal)
        for (const auto& f : journal->done().facets) valid_done += f.valid;
    return [first, valid_done, total](const certipose::part_progress& p) {
        const double rate = p.seconds > 0 ? static_cast<double>(p.facets_done) / p.seconds : 0.0;
        std::fprintf(stderr, "\r\033[K%7zu / %zu facets  %9zu valid  %7.1f facets/s  ETA %-8s  %6.0f MB", first + p.facets_done,
                     total, valid_done + p.valid, rate, duration_text(p.seconds_left).c_str(),
                     static_cast<double>(resident_bytes()) / 1e6);
        return true;
    };
}

/// Solves `opt.facets` into `sink` (over MPI in certipose-part-mpi). An error says what is kept
/// for --resume; during an MPI run it is a rank_failure (see below).
template <class Part, class Sink>
certipose::part_result solve_on(const Part& part, const certipose::part_options& opt, Sink& sink,
                                const std::optional<certipose::part_run_journal>& journal) {
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
        // Every rank reads the same inputs, so errors before this point happen on all of them and
        // each returns. An error during the run is one rank's alone (rank 0's disk full, a worker's
        // failure) while the others wait for its messages: it must name the rank and end the job,
        // not return into MPI_Finalize and leave the others hanging. part_program::run does that on
        // rank_failure, once this rank's own files are closed.
        throw rank_failure(message);
#else
        throw run_failure(message);
#endif
    }
}

/// The two box stores of rank 0, growing in the journal's folder, and the journal after them.
struct run_stores {
    std::optional<certipose::jsonl_sink<I>> jsonl;
    std::optional<certipose::box_store_sink<I>> binary;

    /// Opens the stores --box-store asks for; `checked`: the run's occlusion policy checks occlusion.
    void open(const arguments& args, certipose::part_run_journal& journal, bool checked) {
        if (args.write_jsonl) jsonl.emplace(journal.store("boxes.jsonl"), checked);
        if (args.write_binary)  // a resumed store keeps its header and the records of the facets done
            binary.emplace(certipose::box_store_sink<I>::append_to(journal.store("boxes.cpbx"), checked));
        journal.checkpoint();  // the stores' headers, durable before the first facet
    }
};

/// The summary's totals and termination, from the facets of the runs before and of this one.
void add_results(certipose::part_summary& s, const certipose::part_result& r, const std::vector<certipose::facet_record>& before,
                 const arguments& args, std::size_t selected, bool budget_spent, double seconds, const interruption& signals) {
    s.facets = before;
    s.facets.insert(s.facets.end(), r.facets.begin(), r.facets.end());
    std::size_t valid = 0, boundary = 0, skipped = 0;
    for (const auto& f : s.facets) {
        valid += f.valid;
        boundary += f.boundary;
        skipped += f.termination == certipose::facet_termination::skipped;
    }
    const certipose::termination reason = s.facets.size() == selected ? certipose::termination::completed
                                          : budget_spent               ? certipose::termination::box_budget
                                                                       : r.reason;
    const std::size_t threads = r.threads ? r.threads : (args.threads ? args.threads : std::thread::hardware_concurrency());
    s.totals = {seconds, threads, static_cast<std::size_t>(this_process.ranks), selected, s.facets.size(), valid, boundary,
                skipped, reason, signals.interrupted()};
}

/// What the run did, on stdout.
void print_report(const arguments& args, const certipose::part_summary& s, std::size_t resumed, bool occlusion_checked,
                  const interruption& signals) {
    const auto& t = s.totals;
    std::printf("%s (%zu %s): %zu of %zu facets in %.2f s on %zu rank(s) x %zu threads: %zu valid, %zu boundary "
                "boxes, %zu facets skipped\n",
                args.inputs.mesh.string().c_str(), s.mesh.faces, s.cad ? "triangles" : "faces", t.facets, t.facets_selected, t.seconds, t.ranks, t.threads,
                t.valid, t.boundary, t.skipped);
    if (resumed > 0) std::printf("  resumed: %zu facet(s) were finished by the run it continues\n", resumed);
    if (t.reason != certipose::termination::completed)
        std::printf("  stopped early: %s ended the run; the facets finished are written (--resume continues it)\n",
                    signals.interrupted() ? interruption::name(signals.signal()) : certipose::to_string(t.reason));
    if (!occlusion_checked)
        std::printf("  occlusion NOT checked (--occlusion none): VALID boxes hold for every constraint but occlusion\n");
    if (const std::string text = scene_text(args.inputs.scene); !text.empty()) std::printf("  scene: %s\n", text.c_str());
    if (s.cad) {
        double deviation = 0;
        for (const auto& f : s.cad->faces.faces) deviation = std::max(deviation, f.deviation);
        std::printf("  CAD: %zu faces (file unit %s), tessellated at %.3g mm and %.3g rad; the triangles are what is "
                    "certified, at most %.3g mm from the surfaces (sampled)%s\n",
                    s.cad->faces.faces.size(), s.cad->unit.empty() ? "not given" : s.cad->unit.c_str(), s.cad->deflection * 1e3,
                    s.cad->angular_deflection, deviation * 1e3,
                    s.cad->dropped_triangles ? (", " + std::to_string(s.cad->dropped_triangles) + " degenerate triangles left out").c_str() : "");
    }
    std::printf("wrote %s", (args.out / "summary.json").string().c_str());
    if (s.cad) std::printf(", %s", (args.out / "mesh.off").string().c_str());
    if (args.write_jsonl) std::printf(", %s", (args.out / "boxes.jsonl").string().c_str());
    if (args.write_binary) std::printf(", %s", (args.out / "boxes.cpbx").string().c_str());
    std::printf("\n");
}

/// Runs the part with occlusion policy `Occlusion` and writes the folder; returns the exit code.
template <class Occlusion>
int run_with(const arguments& args, const program_inputs& in, const interruption& signals) {
    const process proc = this_process;
    stage_line stage("certipose-part", args.quiet || proc.rank != 0 || !certipose::checks_occlusion<Occlusion>);
    const auto part = build_solver<part_solver_for<Occlusion>>(args.inputs, in, stage);
    stage.done();
    if (proc.rank == 0) {
        warn_about_scene("certipose-part", part.solver().occlusion(), args.quiet);
        warn_about_units("certipose-part", args.inputs, in.mesh, part.solver().camera(), part.solver().range(), args.quiet);
    }

    certipose::part_options opt = part_options_for(args, in.mesh.num_faces(), signals.token());
    if (in.cad) opt.patches.faces = in.cad->faces.face_of;  // a patch never spans two faces
    certipose::part_summary s = describe_run(args, in, part, opt);
    // The run's work items, and the facets in the order the run hands them to the sink (patches
    // grouped): what the journal records, checkpointing between items, and --resume continues.
    const auto regions = part.patches(opt);
    const std::vector<std::size_t> chosen = certipose::selected_facets(opt, in.mesh.num_faces());
    const certipose::work_plan plan = regions ? certipose::work_plan::grouped(chosen, *regions) : certipose::work_plan::per_facet(chosen);
    const std::vector<std::size_t>& selection = plan.order;
    std::optional<certipose::part_run_journal> journal;
    const resume_point from = agree_on_resume(args, s, selection, journal, proc);
    if (from.status == resume_point::failed_elsewhere) return exit_failure;
    if (from.status == resume_point::complete) return exit_ok;
    opt.facets.assign(selection.begin() + static_cast<std::ptrdiff_t>(from.first), selection.end());
    // Nothing left: every facet selected is done, or the box budget is spent (an empty
    // opt.facets would mean every facet).
    const bool budget_spent = args.max_boxes && from.boxes_done >= *args.max_boxes;
    const bool nothing_left = opt.facets.empty() || budget_spent;
    if (args.max_boxes && !budget_spent) opt.max_boxes = *args.max_boxes - from.boxes_done;
    const bool progress = proc.rank == 0 && show_progress(args.quiet);
    if (progress) opt.progress = progress_line(journal, from.first, selection.size());

    if (proc.rank != 0) {  // a worker rank: solves what rank 0 hands out, writes nothing
        null_sink nothing;
        if (!nothing_left) (void)solve_on(part, opt, nothing, journal);
        return signals.interrupted() ? signals.exit_code() : exit_ok;
    }
    run_stores stores;
    stores.open(args, *journal, certipose::checks_occlusion<Occlusion>);
    certipose::tee_sink<certipose::jsonl_sink<I>, certipose::box_store_sink<I>> both{
        {stores.jsonl ? &*stores.jsonl : nullptr, stores.binary ? &*stores.binary : nullptr}};
    certipose::journal_sink<decltype(both)> sink{&both, &*journal, &plan.ends, from.first};
    const certipose::part_result r = nothing_left ? certipose::part_result{} : solve_on(part, opt, sink, journal);
    if (progress) std::fputc('\n', stderr);

    add_results(s, r, journal->done().facets, args, selection.size(), budget_spent, journal->seconds(), signals);
    try {
        // A STEP part: the triangles the certificates are for, in metres, beside them (read by
        // the other programs as --mesh; the same digest). Written before the summary that
        // names them; a mesh file is not copied (it is the input).
        if (in.cad) certipose::write_mesh_off(args.out / "mesh.off", in.mesh);
        if (stores.binary) stores.binary->finish();
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
    if (!in.cad) fs::remove(args.out / "mesh.off", gone);  // never the input: files_written names it
    if (!args.quiet) print_report(args, s, from.first > 0 ? journal->done().facets.size() : 0, certipose::checks_occlusion<Occlusion>, signals);
    return signals.interrupted() ? signals.exit_code() : exit_ok;
}

int part_program::run(const arguments& args, const interruption& signals) {
    try {
        stage_line stage("certipose-part", args.quiet || this_process.rank != 0);
        const program_inputs in = read_inputs(args.inputs, stage);
        stage.done();
        return certipose::visit_occlusion(args.occlusion,
                                          [&]<class O>(std::type_identity<O>) { return run_with<O>(args, in, signals); });
    } catch (const rank_failure& e) {
        std::cerr << "certipose-part: rank " << this_process.rank << " of " << this_process.ranks << ": " << one_line(e.what())
                  << "; ending the MPI job" << std::endl;
#if defined(CERTIPOSE_PART_MPI)
        // The launcher ends the job with signals: let them act, not be recorded as stop requests.
        std::signal(SIGINT, SIG_DFL);
        std::signal(SIGTERM, SIG_DFL);
        if (this_process.ranks > 1) MPI_Abort(MPI_COMM_WORLD, exit_failure);
#endif
        return exit_failure;
    }
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
    this_process = mpi.proc;
#endif
    // Only rank 0 prints errors, so a failure is one line, not one per rank.
    return program_main<part_program>(argc, argv, this_process.rank == 0);
}
