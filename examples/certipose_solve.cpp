// certipose-solve — certified camera pose boxes for one facet of a part (docs/io.md).
//
//   certipose-solve --mesh PART --facet N --camera CAMERA --position-eps 0.1
//                   --orientation-eps 0.38 --out RESULT.json [--ply BOXES.ply]
//                   [--occlusion aabb|boolean|none] [--scale S] [--part-pose POSE] [--max-boxes N]
//                   [--time-limit SECONDS] [--occluder MESH[:SCALE]]... [--keep-in REGION]...
//                   [--keep-out REGION]... [--part-tolerance TX,TY,TZ,ROT [--datum X,Y,Z]]
//                   [--working-distance DMIN,DMAX --min-view-angle RAD] [--quiet]
//
// Reads the mesh, the --occluder meshes (added to the occlusion scene) and the camera/task JSON,
// solves, restricts the VALID boxes to the --keep-in / --keep-out camera regions
// (solver/camera_regions.hpp), writes the result JSON (and the PLY): both committed together or
// neither (io/output_files.hpp), never over an input. SIGINT/SIGTERM stop the solve through its
// cancellation; nothing is written and the exit code is 130/143. Every
// error prints one line "certipose-solve: ..." on stderr; exit codes: 0 success, 1 bad input
// file / solver / write error, 2 bad command line (docs/errors.md).
//
// The pipeline is `certipose::pose_solver` with the defaults (Boost intervals, the paper's
// constraints with HC4, largest-first, the paper's orientation) and the occlusion policy chosen
// on the command line. The camera, whichever model the JSON names, is a `calibrated_camera`, so
// each occlusion policy instantiates the pipeline once (the aabb one is precompiled).
// Progress goes to stderr when it is a terminal; when a facet gets no VALID box one hint line
// says what stayed undecided and what to try.
#include "certipose_solve_cli.hpp"
#include "program_scene.hpp"

#include <certipose/cgal.hpp>
#include <certipose/io/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <iostream>
#include <numbers>
#include <string>
#include <type_traits>

#include <unistd.h>

namespace {

using I = certipose::boost_interval;
using certipose_program::interruption;

/// Progress on one stderr line, rewritten in place (only when stderr is a terminal).
std::function<bool(const certipose::solve_progress&)> progress_printer(bool quiet) {
    if (quiet || !::isatty(STDERR_FILENO)) return {};
    return [](const certipose::solve_progress& p) {
        std::fprintf(stderr, "\r\033[K%-11s %8zu boxes  %8zu pending  %6zu valid  %6.2f s", p.stage, p.boxes_done,
                     p.boxes_pending, p.valid, p.seconds);
        return true;
    };
}

/// Solves the facet with the pipeline of occlusion policy `Occlusion` (with aabb exactly the
/// pipeline certipose::precompiled instantiates), after the warnings about the scene.
template <class Occlusion>
certipose::solve_result<I> solve_with(const certipose_solve::arguments& args, const certipose_program::program_inputs& in,
                                      const certipose::solve_options& options) {
    // Building the solver builds the occlusion scene (checks the part is a closed solid, or
    // surveys a triangle soup): seconds for a large mesh, so say so on a terminal.
    certipose_program::stage_line stage("certipose-solve", args.quiet || !certipose::checks_occlusion<Occlusion>);
    const auto s =
        certipose_program::build_solver<certipose::pose_solver<certipose::calibrated_pipeline<Occlusion>>>(args.inputs, in, stage);
    stage.done();
    certipose_program::warn_about_scene("certipose-solve", s.occlusion(), args.quiet);
    certipose_program::warn_about_units("certipose-solve", args.inputs, in.mesh, s.camera(), s.range(), args.quiet);
    if constexpr (std::is_same_v<Occlusion, certipose::aabb_occlusion>)
        if (const auto* survey = s.occlusion().survey(); survey && !args.quiet && args.facet < survey->hidden.size() &&
                                                         certipose::material_in_front(survey->hidden[args.facet]))
            if (const auto why = survey->why_hidden(args.facet))
                std::cerr << "certipose-solve: warning: facet " << args.facet << " is " << *why
                          << ": no camera can inspect it\n";
    return s.solve(args.facet, options);
}

/// What to try when most BOUNDARY boxes are undecided for `why`.
std::string advice(certipose::boundary_reason why, const certipose_solve::arguments& args) {
    using certipose::boundary_reason;
    const std::string smaller_eps = "try a smaller --position-eps (e.g. " + certipose::detail::format_double(args.solve.position_eps / 2) + ")";
    switch (why) {
        case boundary_reason::facet_contact:
        case boundary_reason::backface: return "boxes reaching the facet's plane stay undecided; " + smaller_eps;
        case boundary_reason::distance:
            return "the in-focus distance range cuts through every box of this size; " + smaller_eps +
                   ", or a camera with a deeper depth of field";
        case boundary_reason::view_angle:
            return "the viewing-angle cone cuts through every box of this size; " + smaller_eps +
                   " or a smaller task.min_view_angle";
        case boundary_reason::constraint: return "a constraint of the set stayed undecided; " + smaller_eps;
        case boundary_reason::occlusion:
            return "the facet is partly hidden from every box of this size (occlusion partial); " + smaller_eps;
        case boundary_reason::field_of_view:
            return "no orientation keeps the facet in the image from any certified position box; " + smaller_eps +
                   " or --orientation-eps, or a wider lens";
        case boundary_reason::budget: return "the budget ended the run first; raise --max-boxes or --time-limit";
        case boundary_reason::camera_region:
            return "every VALID box left straddles a --keep-in or --keep-out surface; " + smaller_eps +
                   " for finer pieces, or check the regions";
        case boundary_reason::placement:
            return "every VALID box left fails under the part's placement tolerance; " + smaller_eps +
                   " for finer pieces, or a smaller --part-tolerance";
    }
    return smaller_eps;
}

/// A warning before a run that can only end on its budget: the two boundary spheres of the
/// in-focus shell (radii d_min and d_max about the facet) alone leave about (their area) / ε²
/// undecided boxes of width ε.
void warn_if_tiny(const certipose_solve::arguments& args, const certipose::calibrated_camera& camera,
                  const certipose::triangle_mesh& mesh, const certipose::solve_options& options) {
    const certipose::distance_range range = camera.distance_range();
    const double area = 4.0 * std::numbers::pi * (range.min * range.min + range.max * range.max);
    const double boxes = area / (args.solve.position_eps * args.solve.position_eps);
    if (std::isfinite(boxes) && boxes > 10.0 * static_cast<double>(options.max_boxes))
        std::fprintf(stderr,
                     "certipose-solve: warning: --position-eps %s is small for this camera (in focus from %.3g to %.3g m, "
                     "part %.3g m across): about %.1e boundary boxes, over the %zu-box budget; the run will end on "
                     "the budget (raise --position-eps or --max-boxes, or set --time-limit)\n",
                     certipose::detail::format_double(args.solve.position_eps).c_str(), range.min, range.max,
                     mesh.bbox().diagonal().norm(), boxes, options.max_boxes);
}

}  // namespace

int certipose_solve::program::run(const arguments& args, const interruption& signals) {
    certipose_program::stage_line stage("certipose-solve", args.quiet);
    const certipose_program::program_inputs in = certipose_program::read_inputs(args.inputs, stage);
    const certipose::triangle_mesh& mesh = in.mesh;
    const certipose::camera_task& input = in.camera;
    (void)mesh.facet(args.facet);  // out_of_range: "facet 9999 is out of range (valid: 0..N)"
    certipose::solve_options options = certipose::to_solve_options(args.solve);
    if (!args.quiet) warn_if_tiny(args, input.calibrated(), mesh, options);

    options.stop = signals.token();
    options.progress = progress_printer(args.quiet);
    auto result = certipose::visit_occlusion(
        args.occlusion, [&]<class O>(std::type_identity<O>) { return solve_with<O>(args, in, options); });
    if (options.progress) std::fputc('\n', stderr);
    // Camera regions: the VALID boxes restricted to where a camera may stand, before writing.
    certipose::restrict_to_regions(result, args.inputs.scene.regions, options.position_eps);
    const auto interrupted = [&] { return certipose_program::report_interrupted("certipose-solve", signals); };
    if (signals.interrupted()) return interrupted();

    certipose::result_document document = certipose::make_result_document(result, mesh, input, options);
    document.scene = in.extra.record;  // "occluders", "keep_in", "keep_out"
    nlohmann::ordered_json json = certipose::result_to_json(document);
    json["settings"]["occlusion"] = std::string(certipose::to_string(args.occlusion));  // extra field
    // Both files or neither: each is staged complete before either is renamed into place,
    // and a signal that arrives while they are staged discards them (output_files.hpp).
    certipose::output_files files;
    files.add(args.out, certipose::json_text(json));
    if (args.ply) files.add(*args.ply, certipose::ply_text(mesh, document.facet.index, document.boxes));
    if (signals.interrupted()) return interrupted();
    files.commit();

    if (!args.quiet) {
        const auto& st = document.stats;
        std::printf("facet %zu of %s (%zu faces): %zu valid, %zu boundary boxes in %.3f s\n", args.facet,
                    args.inputs.mesh.string().c_str(), mesh.num_faces(), st.valid, st.boundary, st.seconds);
        std::printf("  position stage    %8.3f s  (%zu valid / %zu boundary position boxes, %zu occlusion tests, "
                    "%zu shadow walks)\n",
                    st.seconds_position, st.position_valid, st.position_boundary, st.occlusion_tests, st.shadow_walks);
        std::printf("  orientation stage %8.3f s  (%zu interval certifications)\n", st.seconds_orientation,
                    st.orientation_certifications);
        if (st.inner_pieces + st.occlusion_pieces > 0)
            std::printf("  carved off          %zu pieces by inner contraction, %zu VALID pieces by occlusion cuts\n",
                        st.inner_pieces, st.occlusion_pieces);
        if (st.refinement_stopped)
            std::printf("  refinement          stopped by its time budget (boxes not refined yet are boundary)\n");
        if (args.solve.grow)
            std::printf("  growth            %8.3f s  (%zu merges, %zu boxes widened)\n", st.seconds_growth, st.merges,
                        st.grown);
        std::printf("  certified volume    %.4g m^3 of positions (boundary %.4g m^3)\n", st.valid_volume,
                    st.boundary_volume);
        if (st.boundary > 0)
            std::printf("  boundary boxes undecided on: %s\n", certipose::boundary_summary(st).c_str());
        if (st.reason != certipose::termination::completed)
            std::printf("  stopped early: %s ended the run (unfinished boxes are reported as boundary)\n",
                        certipose::to_string(st.reason));
        if (!st.occlusion_checked)
            std::printf("  occlusion NOT checked (--occlusion none): VALID boxes hold for every constraint "
                        "but occlusion\n");
        if (const std::string extra = certipose_program::scene_text(args.inputs.scene); !extra.empty())
            std::printf("  scene               %s; camera regions dropped %zu VALID pieces, left %zu undecided "
                        "(boundary camera_region)\n",
                        extra.c_str(), st.region_dropped, result.boundary_because(certipose::boundary_reason::camera_region));
        std::printf("wrote %s%s%s\n", args.out.string().c_str(), args.ply ? " and " : "",
                    args.ply ? args.ply->string().c_str() : "");
        if (st.valid == 0) {
            const auto why = certipose::main_boundary_reason(st);
            std::fprintf(stderr, "certipose-solve: hint: no VALID box for facet %zu (boundary boxes undecided on: %s); %s\n",
                         args.facet, certipose::boundary_summary(st).c_str(),
                         why ? advice(*why, args).c_str() : "the facet cannot be inspected with this camera and task");
        }
    }
    return certipose_solve::exit_ok;
}

int main(int argc, char** argv) { return certipose_program::program_main<certipose_solve::program>(argc, argv); }
