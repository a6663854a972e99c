// The contractor micro-benchmarks of bench/contractors.cpp with the CGAL interval backend
// (CGAL::Interval_nt, SSE2), on the same shell constraint and box [−5, 5]³.
#include <certipose/contractors.hpp>
#include <certipose/interval/cgal_interval.hpp>

#include <benchmark/benchmark.h>

namespace {

using namespace certipose;
using I = cgal_interval;
constexpr var<0> x;
constexpr var<1> y;
constexpr var<2> z;

interval_box<I, 3> start_box() { return interval_box<I, 3>::from_bounds({{{-5, 5}, {-5, 5}, {-5, 5}}}); }
auto shell() { return in(sqr(x - 1.0) + sqr(y - 2.0) + sqr(z - 0.5), 0.09, 0.25); }
auto expanded() { return in(sqr(x) + sqr(y) + sqr(z) - 2.0 * x - 4.0 * y - z + 5.25, 0.09, 0.25); }

template <class C>
void run(benchmark::State& state, C c) {
    const auto b0 = start_box();
    for (auto _ : state) {
        auto b = b0;
        benchmark::DoNotOptimize(b);
        c.contract(b);
        benchmark::DoNotOptimize(b);
    }
}

void BM_hc4_distance_shell_cgal(benchmark::State& state) { run(state, hc4(shell())); }
BENCHMARK(BM_hc4_distance_shell_cgal);

void BM_hc4revise_distance_shell_cgal(benchmark::State& state) {
    const hc4 c(shell());
    const auto b0 = start_box();
    for (auto _ : state) {
        auto b = b0;
        benchmark::DoNotOptimize(b);
        benchmark::DoNotOptimize(c.revise<0>(b));
    }
}
BENCHMARK(BM_hc4revise_distance_shell_cgal);

void BM_acid_distance_shell_cgal(benchmark::State& state) { run(state, acid(hc4(shell()))); }
BENCHMARK(BM_acid_distance_shell_cgal);

void BM_hc4_acid_expanded_shell_cgal(benchmark::State& state) { run(state, hc4(expanded()) & acid(hc4(expanded()))); }
BENCHMARK(BM_hc4_acid_expanded_shell_cgal);

}  // namespace
