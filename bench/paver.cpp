// Benchmarks of the paver (paper Algorithm 1) on the spherical shell
// (x−1)² + (y−2)² + (z−0.5)² ∈ [0.09, 0.25] in [−5, 5]³ — the issue-3 reference problem.
// Every paving is depth-first, largest-first at the midpoint, ε = 0.05. Counters give the
// boxes per class, their volumes (exact shell volume 0.4105) and `nodes`, the boxes processed.
// IBEX 2.9.1 on the same machine class: HC4 + CtcNotIn 3 952 inner / 3 952 boundary, volumes
// 0.365 / 0.091, 28–35 ms; HC4 + evaluation-only inner test 2 126 / 4 984, 14–24 ms.
#include <certipose/bisection/largest_first.hpp>
#include <certipose/contractors.hpp>
#include <certipose/interval/boost_interval.hpp>
#include <certipose/paver/paver.hpp>
#include <certipose/pose/interval_box.hpp>

#include <benchmark/benchmark.h>

namespace {

using I = certipose::boost_interval;
using box = certipose::interval_box<I, 3>;
constexpr double eps = 0.05;

constexpr certipose::var<0> x;
constexpr certipose::var<1> y;
constexpr certipose::var<2> z;

auto shell() { return certipose::in(sqr(x - 1.0) + sqr(y - 2.0) + sqr(z - 0.5), 0.09, 0.25); }
// The same set with each variable occurring twice (HC4 is weak here; ACID shaves what it misses).
auto expanded_shell() {
    return certipose::in(sqr(x) + sqr(y) + sqr(z) - 2.0 * x - 4.0 * y - z + 5.25, 0.09, 0.25);
}

box search_box() { return box::from_bounds({{{-5, 5}, {-5, 5}, {-5, 5}}}); }

template <class Outer, class Inner>
void pave_and_report(benchmark::State& state, const Outer& outer, const Inner& inner) {
    certipose::paving<box> r;
    for (auto _ : state) {
        r = certipose::pave(search_box(), outer, inner, certipose::largest_first(eps));
        benchmark::DoNotOptimize(r.valid.data());
    }
    const auto& s = r.stats;
    state.counters["valid"] = static_cast<double>(s.valid);
    state.counters["boundary"] = static_cast<double>(s.boundary);
    state.counters["valid_vol"] = s.valid_volume;
    state.counters["boundary_vol"] = s.boundary_volume;
    state.counters["nodes"] = static_cast<double>(s.boxes);
    state.counters["contractions"] = static_cast<double>(s.contractions);
}

// The headline: HC4 outer contractor, proof of inclusion by the negation (not_in, IBEX's
// CtcNotIn) used as the paver's inner contractor, as IBEX's separator-based paver does.
void BM_pave_distance_shell(benchmark::State& state) {
    pave_and_report(state, certipose::hc4(shell()), certipose::inner_contractor{certipose::not_in(shell())});
}
BENCHMARK(BM_pave_distance_shell)->Unit(benchmark::kMillisecond);

// The paper's Algorithm 1 literally: a yes/no proof of inclusion (not_in_test) per box.
void BM_pave_distance_shell_not_in_test(benchmark::State& state) {
    pave_and_report(state, certipose::hc4(shell()), certipose::not_in_test(shell()));
}
BENCHMARK(BM_pave_distance_shell_not_in_test)->Unit(benchmark::kMillisecond);

// Evaluation-only inner test (compare IBEX's 2 126 / 4 984 boxes in 14–24 ms).
void BM_pave_distance_shell_eval_test(benchmark::State& state) {
    pave_and_report(state, certipose::hc4(shell()), certipose::eval_test(shell()));
}
BENCHMARK(BM_pave_distance_shell_eval_test)->Unit(benchmark::kMillisecond);

// Expanded form, HC4 alone as outer contractor.
void BM_pave_expanded_shell_hc4(benchmark::State& state) {
    pave_and_report(state, certipose::hc4(expanded_shell()),
                    certipose::inner_contractor{certipose::not_in(expanded_shell())});
}
BENCHMARK(BM_pave_expanded_shell_hc4)->Unit(benchmark::kMillisecond);

// Expanded form, HC4 then ACID (IBEX's defaults) as outer contractor.
void BM_pave_expanded_shell_hc4_acid(benchmark::State& state) {
    pave_and_report(state,
                    certipose::compose(certipose::hc4(expanded_shell()), certipose::acid(certipose::hc4(expanded_shell()))),
                    certipose::inner_contractor{certipose::not_in(expanded_shell())});
}
BENCHMARK(BM_pave_expanded_shell_hc4_acid)->Unit(benchmark::kMillisecond);

}  // namespace
