// Occlusion policies on the bundled sample part (~2 300 faces), facet of interest (next to the
// central boss): one visible, one partial and one occluded box, and a sweep over every 0.1 m
// grid box whose centre lies 0.5–0.8 m from the facet centroid (1 624 boxes, all round the
// facet: the half behind its plane is answered by the facing test alone; the front half is
// reported separately).
//
// Reference (issue 4 probe on this machine class): the exact boolean test 2–7 ms per box; a
// straightforward exact AABB + separating-axis certificate 20–180 µs, 50–89 µs on average over
// a sweep. Target: aabb_occlusion <= 30 µs per box on average and >= 100x faster than
// boolean_occlusion over the sweep. `per_box` counters are seconds per box.
#include <certipose/geometry/sample_part.hpp>
#include <certipose/occlusion/cgal_aabb_occlusion.hpp>
#include <certipose/occlusion/cgal_boolean_occlusion.hpp>

#include <benchmark/benchmark.h>

#include <Eigen/Geometry>

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace certipose;
using box3 = Eigen::AlignedBox3d;
using V = Eigen::Vector3d;

struct fixture {
    sample_part part = make_sample_part();
    aabb_occlusion fast{part.mesh};
    boolean_occlusion exact{part.mesh};
    std::size_t foi = part.facet_of_interest;
    std::vector<box3> sweep, front;
    std::array<box3, 3> pick{};  // a box both policies call visible, partial, occluded

    fixture() {
        const V c = part.mesh.facet(foi).centroid;
        const V n = part.mesh.facet(foi).normal;
        for (int i = -9; i < 9; ++i)
            for (int j = -9; j < 9; ++j)
                for (int k = -9; k < 9; ++k) {
                    const V centre = c + 0.1 * V(i + 0.5, j + 0.5, k + 0.5);
                    const double d = (centre - c).norm();
                    if (d < 0.5 || d > 0.8) continue;
                    const box3 b(centre - V::Constant(0.05), centre + V::Constant(0.05));
                    sweep.push_back(b);
                    if ((centre - c).dot(n) > 0) front.push_back(b);
                }
        std::array<bool, 3> found{};
        for (const box3& b : sweep) {
            const visibility v = fast.classify(b, foi);
            const auto k = static_cast<std::size_t>(v);
            if (found[k]) continue;
            // Picks lie wholly in front of the facet plane: a box behind or across it is
            // settled by the facing test alone, which would flatter aabb_occlusion.
            if (!((b.center() - c).dot(n) > 0.05)) continue;
            if (exact.classify(b, foi) != v) continue;
            pick[k] = b, found[k] = true;
        }
        if (!found[2]) {  // none certified occluded from in front: take one from behind
            for (const box3& b : sweep)
                if (fast.classify(b, foi) == visibility::occluded &&
                    exact.classify(b, foi) == visibility::occluded) {
                    pick[2] = b, found[2] = true;
                    break;
                }
        }
        if (!found[0] || !found[1] || !found[2]) throw std::runtime_error("bench: no box of some class");
    }
};

const fixture& fx() {
    static const fixture f;
    return f;
}

template <class Policy>
void run_one(benchmark::State& state, const Policy& p, visibility v) {
    const fixture& f = fx();
    const box3& b = f.pick[static_cast<std::size_t>(v)];
    for (auto _ : state) benchmark::DoNotOptimize(p.classify(b, f.foi));
    const facet& F = f.part.mesh.facet(f.foi);
    const bool behind = (b.center() - F.centroid).dot(F.normal) < 0;
    state.SetLabel(std::string(to_string(v)) + (behind ? " (box behind the facet plane)" : ""));
}

template <class Policy>
void run_sweep(benchmark::State& state, const Policy& p, const std::vector<box3>& boxes) {
    const fixture& f = fx();
    std::array<std::size_t, 3> count{};
    for (auto _ : state) {
        count = {};
        for (const box3& b : boxes) ++count[static_cast<std::size_t>(p.classify(b, f.foi))];
    }
    state.counters["boxes"] = static_cast<double>(boxes.size());
    state.counters["visible"] = static_cast<double>(count[0]);
    state.counters["partial"] = static_cast<double>(count[1]);
    state.counters["occluded"] = static_cast<double>(count[2]);
    state.counters["per_box"] = benchmark::Counter(static_cast<double>(boxes.size()),
                                                   benchmark::Counter::kIsIterationInvariantRate |
                                                       benchmark::Counter::kInvert);
}

void BM_occlusion_aabb(benchmark::State& state, visibility v) { run_one(state, fx().fast, v); }
void BM_occlusion_boolean(benchmark::State& state, visibility v) { run_one(state, fx().exact, v); }
void BM_occlusion_aabb_sweep(benchmark::State& state) { run_sweep(state, fx().fast, fx().sweep); }
void BM_occlusion_aabb_sweep_front(benchmark::State& state) { run_sweep(state, fx().fast, fx().front); }
void BM_occlusion_boolean_sweep(benchmark::State& state) { run_sweep(state, fx().exact, fx().sweep); }
void BM_occlusion_boolean_sweep_front(benchmark::State& state) { run_sweep(state, fx().exact, fx().front); }

}  // namespace

BENCHMARK_CAPTURE(BM_occlusion_aabb, visible, certipose::visibility::visible)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_occlusion_aabb, partial, certipose::visibility::partial)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_occlusion_aabb, occluded, certipose::visibility::occluded)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_occlusion_boolean, visible, certipose::visibility::visible)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_occlusion_boolean, partial, certipose::visibility::partial)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_occlusion_boolean, occluded, certipose::visibility::occluded)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_occlusion_aabb_sweep)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_occlusion_aabb_sweep_front)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_occlusion_boolean_sweep)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_occlusion_boolean_sweep_front)->Unit(benchmark::kMillisecond)->Iterations(1);
