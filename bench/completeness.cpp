// How much of the true inspection space the solver certifies, per mode (not a Google Benchmark:
// one table, every mode in the same run): on the case study (the bundled sample part's facet of
// interest, examples/data/camera.json) always, and on the four reference cases of
// docs/completeness.md#the-reference-cases when the build names their folder
// (-DCERTIPOSE_REFERENCE_DATA=DIR, holding meshes/*.off and cases/*.json; those meshes are not
// distributed with certipose). CERTIPOSE_BENCH_CAMERA=FILE replaces the case study's camera JSON.
//
// The truth comes from an independent sampler (verify/point_check.hpp, plain doubles and ray
// casting): positions drawn uniformly in the facet's bounding box grown by d_max that satisfy
// constraints 1–4 and see 15 points of the facet (vertices, edge midpoints, centroid, 8 random
// points) without a blocked sight line. The *certified share* is the fraction of them inside
// the position part of a VALID box; the *position tolerance* of such a sample is the largest,
// over the VALID boxes holding it, of the box's smallest position width (what a fitter may be
// off by in every direction), reported with the Euler-angle widths of that box.
//
//   bench_completeness [samples=6000] [modes=paper,inner,full,refine,grow,refine_grow] [every=0]
//   (also: cuts, leaf, depth1 — one corner box per leaf, rest2 — corner boxes of rest boxes
//   down to two minimal pieces, the default before 3). refine_grow: refinement and growth
//   in one 1 s budget, the most complete answer a second gives.
// A mode may carry a part placement tolerance (pose/placement_tolerance.hpp) after '@':
// "full@0.003/0.0175" solves with ±3 mm on each axis and 0.0175 rad about the part's centroid;
// the truth stays the nominal one, so the share shows what the tolerance costs.
// With `every` = N > 0, no table: each part's every Nth facet is solved once per mode, and the
// totals (seconds, VALID / BOUNDARY boxes, certified volume) are printed — a broader check that
// a change to the solver keeps its VALID boxes and what it costs, beyond the four facets.
#include <certipose/cgal.hpp>
#include <certipose/io/json.hpp>
#include <certipose/verify/point_check.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace {

using I = certipose::boost_interval;
using solver_t = certipose::pose_solver<certipose::with_camera<certipose::calibrated_camera>>;

struct reference_case {
    const char* mesh;
    double scale;
    std::size_t facet;
    const char* camera;
};

const reference_case cases[] = {{"idler_riser.off", 0.0994878, 102, "camera.json"},
                                {"featuretype.off", 0.0694832, 3262, "camera.json"},
                                {"angle_block.off", 0.186104, 520, "camera_wide.json"},
                                {"plate_holes.off", 0.00109127, 7, "camera.json"}};

/// A case ready to solve: its name, mesh, camera and task, and facet.
struct loaded_case {
    std::string name;
    certipose::triangle_mesh mesh;
    certipose::camera_task input;
    std::size_t facet;
};

/// The case study, then the reference cases when CERTIPOSE_REFERENCE_DATA names their folder.
std::vector<loaded_case> load_cases() {
    std::vector<loaded_case> out;
    certipose::sample_part part = certipose::make_sample_part();
    // CERTIPOSE_BENCH_CAMERA: another camera JSON for the case study (bench/placement_cost.py
    // measures a distorted lens against its pinhole twin so).
    const char* camera = std::getenv("CERTIPOSE_BENCH_CAMERA");
    out.push_back({"sample_part.off", std::move(part.mesh),
                   certipose::read_camera_task(camera && *camera ? std::string(camera)
                                                                 : std::string(CERTIPOSE_EXAMPLE_DATA) + "/camera.json"),
                   part.facet_of_interest});
    const std::string data = CERTIPOSE_REFERENCE_DATA;
    if (data.empty()) {
        std::fprintf(stderr, "bench_completeness: the case study only; for the reference cases configure with "
                             "-DCERTIPOSE_REFERENCE_DATA=DIR (DIR/meshes/*.off, DIR/cases/*.json; "
                             "docs/completeness.md#the-reference-cases)\n");
        return out;
    }
    for (const auto& c : cases)
        out.push_back({c.mesh, certipose::read_mesh(data + "/meshes/" + c.mesh, {.scale = c.scale}),
                       certipose::read_camera_task(data + "/cases/" + c.camera), c.facet});
    return out;
}

using truth = certipose::verify::position_sample;

struct figures {
    std::size_t valid = 0, boundary = 0, inside = 0;
    double seconds = 0, valid_volume = 0;
    std::vector<double> tol, phi, gamma, beta;  // per sample inside a VALID box
};

double quantile(std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
}

figures measure(const certipose::solve_result<I>& r, const truth& t) {
    figures out;
    out.valid = r.stats.valid, out.boundary = r.stats.boundary, out.seconds = r.stats.seconds;
    out.valid_volume = r.stats.valid_volume;
    for (const auto& p : t.valid) {
        double best = -1, phi = 0, gamma = 0, beta = 0;
        for (const auto& b : r.boxes) {
            if (b.cls != certipose::box_class::valid) continue;
            const auto& pos = b.box.position;
            bool in = true;
            for (int k = 0; k < 3 && in; ++k) in = certipose::lower(pos[k]) <= p[k] && p[k] <= certipose::upper(pos[k]);
            if (!in) continue;
            double w = 1e300;
            for (int k = 0; k < 3; ++k) w = std::min(w, certipose::upper(pos[k]) - certipose::lower(pos[k]));
            if (w > best) {
                best = w;
                const auto& o = b.box.orientation;
                phi = certipose::upper(o[0]) - certipose::lower(o[0]);
                gamma = certipose::upper(o[1]) - certipose::lower(o[1]);
                beta = certipose::upper(o[2]) - certipose::lower(o[2]);
            }
        }
        if (best < 0) continue;
        ++out.inside;
        out.tol.push_back(best), out.phi.push_back(phi), out.gamma.push_back(gamma), out.beta.push_back(beta);
    }
    return out;
}

/// The mode's name before '@', and its placement tolerance after it ("T/ROT"), if any.
std::pair<std::string, std::optional<certipose::placement_tolerance>> split_mode(const std::string& mode) {
    const auto at = mode.find('@');
    if (at == std::string::npos) return {mode, std::nullopt};
    const std::string rest = mode.substr(at + 1);
    const auto comma = rest.find('/');
    if (comma == std::string::npos) {
        std::fprintf(stderr, "mode %s: expected NAME@T/ROT\n", mode.c_str());
        std::exit(2);
    }
    const double t = std::strtod(rest.substr(0, comma).c_str(), nullptr), rot = std::strtod(rest.substr(comma + 1).c_str(), nullptr);
    certipose::placement_tolerance tol{.translation = {t, t, t}, .rotation = rot};
    tol.validate();
    return {mode.substr(0, at), tol};
}

/// The task of a case with a mode's placement tolerance.
certipose::inspection_task mode_task(certipose::inspection_task task, const std::string& mode) {
    task.placement = split_mode(mode).second;
    return task;
}

certipose::solve_options mode_options(const std::string& full_mode) {
    const std::string mode = split_mode(full_mode).first;
    certipose::solve_options o{.position_eps = 0.1, .orientation_eps = 0.38};
    if (mode == "paper") o.paving = certipose::paper_paving{};
    else if (mode == "inner") o.paving = certipose::carving{.occlusion_cuts = false, .corner_boxes = false};
    else if (mode == "cuts") o.paving = certipose::carving{.corner_boxes = false};
    else if (mode == "depth1") o.paving = certipose::carving{.corner_depth = 1};  // one corner box per leaf (before corner_depth)
    else if (mode == "rest2") o.paving = certipose::carving{.rest_min_pieces = 2};  // rest boxes' corner boxes down to 2 pieces (before 3)
    else if (mode == "leaf") o.paving = certipose::carving{.occlusion_cuts = false};
    else if (mode == "refine") {
        o.time_limit = std::chrono::seconds(1);
        o.refine = certipose::refinement{};
    } else if (mode == "grow") {
        o.grow = certipose::growth_options{};
    } else if (mode == "refine_grow") {
        o.time_limit = std::chrono::seconds(1);
        o.refine = certipose::refinement{};
        o.grow = certipose::growth_options{};
    } else if (mode != "full") {
        std::fprintf(stderr, "unknown mode %s\n", full_mode.c_str());
        std::exit(2);
    }
    return o;
}

}  // namespace

int main(int argc, char** argv) {
    const std::size_t samples = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 6000;
    std::vector<std::string> modes{"paper", "inner", "full", "refine", "grow", "refine_grow"};
    if (argc > 2) {
        modes.clear();
        std::stringstream in(argv[2]);
        for (std::string m; std::getline(in, m, ',');) modes.push_back(m);
    }
    const std::size_t every = argc > 3 ? std::strtoul(argv[3], nullptr, 10) : 0;
    const std::vector<loaded_case> all = load_cases();
    if (every > 0) {
        for (const auto& c : all) {
            const auto& mesh = c.mesh;
            const auto& in = c.input;
            for (const auto& mode : modes) {
                const solver_t solver(mesh, in.calibrated(), mode_task(in.task, mode));
                double seconds = 0, volume = 0;
                std::size_t facets = 0, valid = 0, boundary = 0;
                for (std::size_t f = 0; f < mesh.num_faces(); f += every, ++facets) {
                    const auto r = solver.solve(f, mode_options(mode));
                    seconds += r.stats.seconds, volume += r.stats.valid_volume;
                    valid += r.stats.valid, boundary += r.stats.boundary;
                }
                std::printf("%s, every %zuth facet (%zu), %s: %.3f s, %zu VALID / %zu BOUNDARY, valid volume %.5f m³\n",
                            c.name.c_str(), every, facets, mode.c_str(), seconds, valid, boundary, volume);
                std::fflush(stdout);
            }
        }
        return 0;
    }
    std::printf("| case | mode | VALID / BOUNDARY | certified share | s per facet | median tol (p10, p90) m | median φ / γ / β width rad | valid volume m³ |\n");
    std::printf("| --- | --- | --- | --- | --- | --- | --- | --- |\n");
    for (const auto& c : all) {
        const auto& mesh = c.mesh;
        const auto& in = c.input;
        const auto camera = in.calibrated();
        const solver_t nominal(mesh, camera, in.task);
        const truth t = certipose::verify::sample_valid_positions(mesh, c.facet, nominal.range().min, nominal.range().max,
                                                                  in.task.min_view_angle, samples, 12345);
        for (const auto& mode : modes) {
            const solver_t solver(mesh, camera, mode_task(in.task, mode));
            auto r = solver.solve(c.facet, mode_options(mode));
            double fastest = r.stats.seconds;  // the least of three runs: this machine's timing noise
            if (mode != "refine" && mode != "refine_grow")
                for (int rep = 0; rep < 2; ++rep) fastest = std::min(fastest, solver.solve(c.facet, mode_options(mode)).stats.seconds);
            r.stats.seconds = fastest;
            const figures f = measure(r, t);
            std::printf("| %s (%zu) | %s | %zu / %zu | %.1f %% of %zu | %.3f | %.4f (%.4f, %.4f) | %.3f / %.3f / %.3f | %.4g |\n",
                        c.name.c_str(), c.facet, mode.c_str(), f.valid, f.boundary,
                        t.valid.empty() ? 0.0 : 100.0 * static_cast<double>(f.inside) / static_cast<double>(t.valid.size()),
                        t.valid.size(), f.seconds, quantile(f.tol, 0.5), quantile(f.tol, 0.1), quantile(f.tol, 0.9),
                        quantile(f.phi, 0.5), quantile(f.gamma, 0.5), quantile(f.beta, 0.5), f.valid_volume);
            std::fflush(stdout);
        }
    }
}
