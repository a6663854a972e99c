// The paper's case study (§8) end to end: sample part (2 300 faces), facet of interest next to a
// protrusion, ε_p = 0.1 m, ε_o = 0.38 rad, the case-study camera. The paper: 1 614 boxes in
// ~53 s on an i5-6440HQ. Counters report boxes per class, the time of each stage and the
// certified volume of positions; `_paper_paving` is the paper's paving (no inner contraction,
// occlusion cuts or corner boxes), `_grown` adds box growth, `_anytime` is refinement and growth
// in a 1 s budget (the most complete answer a second gives).
#include <benchmark/benchmark.h>

#include <certipose/geometry/sample_part.hpp>
#include <certipose/occlusion/cgal_aabb_occlusion.hpp>
#include <certipose/occlusion/cgal_boolean_occlusion.hpp>
#include <certipose/solver/pose_solver.hpp>

#include <chrono>
#include <type_traits>

namespace {

const certipose::sample_part& part() {
    static const certipose::sample_part p = certipose::make_sample_part();
    return p;
}

certipose::solve_options paper_paving() {
    certipose::solve_options o{.position_eps = 0.1, .orientation_eps = 0.38};
    o.paving = certipose::paper_paving{};
    return o;
}
certipose::solve_options grown() {
    certipose::solve_options o{.position_eps = 0.1, .orientation_eps = 0.38};
    o.grow = certipose::growth_options{};
    return o;
}

template <class Occlusion>
void run(benchmark::State& state, const certipose::solve_options& options = {.position_eps = 0.1, .orientation_eps = 0.38}) {
    const certipose::thin_lens_camera camera(certipose::thin_lens_parameters{
        .focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6, .max_blur_circle = 6.9e-6,
        .pixel_pitch = 3.45e-6, .width_px = 2448, .height_px = 2048});
    using solver_t = std::conditional_t<std::is_same_v<Occlusion, certipose::aabb_occlusion>, certipose::pose_solver<>,
                                        certipose::pose_solver<certipose::with_occlusion<Occlusion>>>;
    const solver_t solver(part().mesh, camera, {.min_view_angle = 0.35});
    certipose::solve_stats st;
    for (auto _ : state) {
        auto r = solver.solve(part().facet_of_interest, options);
        st = r.stats;
        benchmark::DoNotOptimize(r);
    }
    state.counters["valid"] = static_cast<double>(st.valid);
    state.counters["boundary"] = static_cast<double>(st.boundary);
    state.counters["position_ms"] = 1e3 * st.seconds_position;
    state.counters["orientation_ms"] = 1e3 * st.seconds_orientation;
    state.counters["occlusion_tests"] = static_cast<double>(st.occlusion_tests);
    state.counters["valid_m3"] = st.valid_volume;
    state.counters["growth_ms"] = 1e3 * st.seconds_growth;
}

void BM_case_study(benchmark::State& state) { run<certipose::aabb_occlusion>(state); }
void BM_case_study_paper_paving(benchmark::State& state) { run<certipose::aabb_occlusion>(state, paper_paving()); }
void BM_case_study_grown(benchmark::State& state) { run<certipose::aabb_occlusion>(state, grown()); }
void BM_case_study_anytime(benchmark::State& state) {
    certipose::solve_options o = grown();
    o.time_limit = std::chrono::seconds(1);
    o.refine = certipose::refinement{};
    run<certipose::aabb_occlusion>(state, o);
}
void BM_case_study_boolean_occlusion(benchmark::State& state) { run<certipose::boolean_occlusion>(state); }

}  // namespace

BENCHMARK(BM_case_study)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_case_study_paper_paving)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_case_study_grown)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_case_study_anytime)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(BM_case_study_boolean_occlusion)->Unit(benchmark::kMillisecond)->Iterations(2);
