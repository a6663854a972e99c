// Coverage (docs/coverage.md): the certified facet set C(B) of one pose box on the 2 300-face
// sample part (one thread, aabb occlusion, the case-study camera), and the greedy choice over
// the candidates. Candidates: the largest VALID box of every 25th facet at ε_p = 0.1 m, ε_o =
// 0.38 rad (92 solves, done once before timing), whole (Arg 0) or cut to ±5 mm, ±0.02 rad around
// its centre (Arg 1, certipose-plan's default). The whole plan is timed with certipose-plan.
#include <benchmark/benchmark.h>

#include <certipose/cgal.hpp>
#include <certipose/coverage/candidates.hpp>
#include <certipose/coverage/deployment.hpp>
#include <certipose/coverage/inspection.hpp>

#include <cstddef>
#include <vector>

namespace {

using I = certipose::boost_interval;

struct setup {
    certipose::sample_part part = certipose::make_sample_part();
    certipose::pose_solver<> solver{part.mesh,
                                    certipose::thin_lens_camera(certipose::thin_lens_parameters{
                                        .focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6,
                                        .max_blur_circle = 6.9e-6, .pixel_pitch = 3.45e-6, .width_px = 2448,
                                        .height_px = 2048}),
                                    {.min_view_angle = 0.35}};
    std::vector<certipose::pose_box<I>> boxes, cut;
    setup() {
        certipose::candidate_pool<I> pool(1);
        for (std::size_t f = 0; f < part.mesh.num_faces(); f += 25) {
            const auto r = solver.solve(f, {.position_eps = 0.1, .orientation_eps = 0.38});
            for (const auto& b : r.boxes)
                if (b.cls == certipose::box_class::valid) pool.add(f, b.box);
        }
        for (const auto& c : pool.boxes()) {
            boxes.push_back(c.box);
            cut.push_back(certipose::around_centre(c.box, {0.005, 0.005, 0.005, 0.02, 0.02, 0.02}));
        }
    }
};

const setup& fixture() {
    static const setup s;
    return s;
}

void BM_certified_facets_per_box(benchmark::State& state) {
    const setup& s = fixture();
    const auto& boxes = state.range(0) ? s.cut : s.boxes;
    certipose::facet_inspector<> inspector(s.solver);
    std::size_t i = 0, certified = 0, possible = 0, n = 0;
    for (auto _ : state) {
        const auto c = inspector.inspect(boxes[i++ % boxes.size()]);
        certified += c.certified.size(), possible += c.possible.size(), ++n;
        benchmark::DoNotOptimize(c);
    }
    state.counters["C(B)"] = static_cast<double>(certified) / static_cast<double>(n);
    state.counters["P(B)"] = static_cast<double>(possible) / static_cast<double>(n);
    state.counters["culled"] = static_cast<double>(inspector.stats().culled) / static_cast<double>(inspector.stats().boxes);
}
BENCHMARK(BM_certified_facets_per_box)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MinTime(3.0);

void BM_build_inspector(benchmark::State& state) {
    const setup& s = fixture();
    for (auto _ : state) {
        certipose::facet_inspector<> inspector(s.solver);
        benchmark::DoNotOptimize(inspector);
    }
}
BENCHMARK(BM_build_inspector)->Unit(benchmark::kMillisecond);

void BM_greedy_plan(benchmark::State& state) {
    const setup& s = fixture();
    certipose::facet_inspector<> inspector(s.solver);
    std::vector<certipose::deployment_candidate> sets;
    for (const auto& b : state.range(0) ? s.cut : s.boxes) sets.push_back({inspector.inspect(b).certified});
    std::size_t cameras = 0;
    for (auto _ : state) {
        const auto p = certipose::plan_greedy(sets, inspector.areas(), {.coverage = 0.95});
        cameras = p.chosen.size();
        benchmark::DoNotOptimize(p);
    }
    state.counters["candidates"] = static_cast<double>(sets.size());
    state.counters["cameras"] = static_cast<double>(cameras);
}
BENCHMARK(BM_greedy_plan)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
