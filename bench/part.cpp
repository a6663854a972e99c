// Whole parts (docs/part.md): every 25th facet of the sample part (92 facets) with part_solver at
// the paper's settings (ε_p = 0.1 m, ε_o = 0.38 rad, the case-study camera, aabb occlusion),
// on 1 and 2 threads, into a sink that only counts. Counters: facets per second and VALID boxes.
// The whole part and the 20 000-face part are timed with certipose-part (docs/part.md, "Speed").
#include <benchmark/benchmark.h>

#include <certipose/cgal.hpp>
#include <certipose/part/part_solver.hpp>

#include <cstddef>

namespace {

struct counting_sink {
    std::size_t boxes = 0;
    void facet(const certipose::facet_outcome<certipose::boost_interval>& o) { boxes += o.boxes.size(); }
};

void BM_part_every_25th_facet(benchmark::State& state) {
    static const certipose::sample_part part = certipose::make_sample_part();
    const certipose::thin_lens_camera camera(certipose::thin_lens_parameters{
        .focal_length = 0.012, .f_stop = 8, .focus_distance = 0.6, .max_blur_circle = 6.9e-6,
        .pixel_pitch = 3.45e-6, .width_px = 2448, .height_px = 2048});
    const certipose::part_solver<> solver(part.mesh, camera, {.min_view_angle = 0.35});
    certipose::part_options options;
    options.facet = {.position_eps = 0.1, .orientation_eps = 0.38};
    for (std::size_t f = 0; f < part.mesh.num_faces(); f += 25) options.facets.push_back(f);
    options.threads = static_cast<std::size_t>(state.range(0));
    std::size_t boxes = 0;
    for (auto _ : state) {
        counting_sink sink;
        const auto r = solver.solve(options, sink);
        boxes = sink.boxes;
        benchmark::DoNotOptimize(r);
    }
    state.counters["facets/s"] = benchmark::Counter(static_cast<double>(options.facets.size()), benchmark::Counter::kIsIterationInvariantRate);
    state.counters["valid"] = static_cast<double>(boxes);
}
BENCHMARK(BM_part_every_25th_facet)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);

}  // namespace
