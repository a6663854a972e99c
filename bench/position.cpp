// The position stage (paper Algorithm 3 lines 1–27) for the sample part's facet of interest at
// ε_p = 0.1 m, with each occlusion policy.
#include <benchmark/benchmark.h>

#include <chrono>
#include <optional>

#include <certipose/camera.hpp>
#include <certipose/constraints/paper_position_constraints.hpp>
#include <certipose/geometry/sample_part.hpp>
#include <certipose/interval/boost_interval.hpp>
#include <certipose/occlusion/cgal_aabb_occlusion.hpp>
#include <certipose/occlusion/no_occlusion.hpp>
#include <certipose/solver/position_stage.hpp>

namespace {

using I = certipose::boost_interval;

const certipose::sample_part& part() {
    static const certipose::sample_part p = certipose::make_sample_part();
    return p;
}

certipose::position_problem problem() {
    const certipose::thin_lens_camera camera(certipose::thin_lens_parameters{
        .focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6, .max_blur_circle = 6.9e-6,
        .pixel_pitch = 3.45e-6, .width_px = 2448, .height_px = 2048});
    return {part().mesh.facet(part().facet_of_interest), camera.distance_range(), {.min_view_angle = 0.35}};
}

// The paper's paving (no inner contraction, occlusion cuts or corner boxes) and the default.
const certipose::paving_choice paper = certipose::paper_paving{};
const certipose::paving_choice inner_only = certipose::carving{.occlusion_cuts = false, .corner_boxes = false};
const certipose::paving_choice carving = certipose::carving{};

template <class Occlusion>
void run(benchmark::State& state, const certipose::paving_choice& stage,
         std::optional<std::chrono::milliseconds> refine = {}) {
    const auto pb = problem();
    const Occlusion occlusion(part().mesh);
    std::size_t valid = 0, boundary = 0, tests = 0;
    double volume = 0;
    for (auto _ : state) {
        std::optional<certipose::position_refinement> r2;
        if (refine) r2 = certipose::position_refinement{0.1 / 16, std::chrono::steady_clock::now() + *refine};
        auto r = certipose::pave_positions<I, certipose::paper_position_constraints<I>>(
            pb, part().facet_of_interest, occlusion, {}, 0.1, {}, {}, stage, r2);
        valid = r.boxes.valid.size(), boundary = r.boxes.boundary.size(), tests = r.counters.occlusion_tests;
        volume = r.boxes.stats.valid_volume;
        benchmark::DoNotOptimize(r);
    }
    state.counters["valid"] = static_cast<double>(valid);
    state.counters["boundary"] = static_cast<double>(boundary);
    state.counters["occlusion_tests"] = static_cast<double>(tests);
    state.counters["valid_m3"] = volume;
}

void BM_position_paving_sample_part(benchmark::State& state) { run<certipose::aabb_occlusion>(state, carving); }
void BM_position_paving_sample_part_paper(benchmark::State& state) { run<certipose::aabb_occlusion>(state, paper); }
void BM_position_paving_sample_part_inner_contraction_only(benchmark::State& state) {
    run<certipose::aabb_occlusion>(state, inner_only);
}
void BM_position_paving_sample_part_refined_200ms(benchmark::State& state) {
    run<certipose::aabb_occlusion>(state, carving, std::chrono::milliseconds(200));
}
void BM_position_paving_sample_part_no_occlusion(benchmark::State& state) {
    run<certipose::no_occlusion>(state, carving);
}

}  // namespace

BENCHMARK(BM_position_paving_sample_part)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_position_paving_sample_part_paper)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_position_paving_sample_part_inner_contraction_only)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_position_paving_sample_part_refined_200ms)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_position_paving_sample_part_no_occlusion)->Unit(benchmark::kMillisecond);
