// Contractor micro-benchmarks on the reference problem: the spherical shell
// (x−1)² + (y−2)² + (z−0.5)² ∈ [0.09, 0.25] on the box [−5, 5]³, and its expanded form
// x² + y² + z² − 2x − 4y − z + 5.25 (variables repeated: where ACID pays).
// IBEX 2.9.1 (gaol, -O3) on this machine class: 0.44–0.60 µs per HC4Revise (CtcFwdBwd),
// 1.1–1.2 µs per CtcHC4. Each iteration copies the initial box and contracts it once; the
// rounding mode is held by the contractor itself (no guard in the loop), as a user would call it.
#include <certipose/contractors.hpp>
#include <certipose/interval/boost_interval.hpp>

#include <benchmark/benchmark.h>

#include <atomic>
#include <cstdlib>
#include <new>

// Counts heap allocations, to report them per iteration (target: none).
static std::atomic<long> allocations{0};
void* operator new(std::size_t n) {
    allocations.fetch_add(1, std::memory_order_relaxed);
    if (void* p = std::malloc(n ? n : 1)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace {

using namespace certipose;
constexpr var<0> x;
constexpr var<1> y;
constexpr var<2> z;

template <class I>
interval_box<I, 3> start_box() {
    return interval_box<I, 3>::from_bounds({{{-5, 5}, {-5, 5}, {-5, 5}}});
}

auto shell() { return in(sqr(x - 1.0) + sqr(y - 2.0) + sqr(z - 0.5), 0.09, 0.25); }
auto expanded() { return in(sqr(x) + sqr(y) + sqr(z) - 2.0 * x - 4.0 * y - z + 5.25, 0.09, 0.25); }

template <class I, class C>
void run(benchmark::State& state, C c) {
    const auto b0 = start_box<I>();
    const long before = allocations.load();
    for (auto _ : state) {
        auto b = b0;
        benchmark::DoNotOptimize(b);
        c.contract(b);
        benchmark::DoNotOptimize(b);
    }
    state.counters["allocs/iter"] =
        benchmark::Counter(static_cast<double>(allocations.load() - before), benchmark::Counter::kAvgIterations);
}

void BM_hc4_distance_shell(benchmark::State& state) { run<boost_interval>(state, hc4(shell())); }
BENCHMARK(BM_hc4_distance_shell);

// The same with the caller holding the rounding mode around the loop (as a paver can): the
// contractor then only checks that it is held, saving the ~25 ns of saving/restoring the mode.
void BM_hc4_distance_shell_guard_held(benchmark::State& state) {
    const hc4 c(shell());
    const auto b0 = start_box<boost_interval>();
    const rounding_guard<boost_interval> held;
    for (auto _ : state) {
        auto b = b0;
        benchmark::DoNotOptimize(b);
        c.contract(b);
        benchmark::DoNotOptimize(b);
    }
}
BENCHMARK(BM_hc4_distance_shell_guard_held);

// One forward–backward pass alone (IBEX's CtcFwdBwd).
void BM_hc4revise_distance_shell(benchmark::State& state) {
    const hc4 c(shell());
    const auto b0 = start_box<boost_interval>();
    for (auto _ : state) {
        auto b = b0;
        benchmark::DoNotOptimize(b);
        benchmark::DoNotOptimize(c.revise<0>(b));
    }
}
BENCHMARK(BM_hc4revise_distance_shell);

// Forward evaluation only (what the evaluation inner test costs).
void BM_eval_test_distance_shell(benchmark::State& state) {
    const eval_test t(shell());
    const auto b0 = start_box<boost_interval>();
    for (auto _ : state) benchmark::DoNotOptimize(t.test(b0));
}
BENCHMARK(BM_eval_test_distance_shell);

void BM_not_in_test_distance_shell(benchmark::State& state) {
    const not_in_test t(shell());
    const auto b0 = interval_box<boost_interval, 3>::from_bounds({{{1.3, 1.35}, {2.0, 2.05}, {0.5, 0.55}}});
    for (auto _ : state) benchmark::DoNotOptimize(t.test(b0));
}
BENCHMARK(BM_not_in_test_distance_shell);

void BM_acid_distance_shell(benchmark::State& state) { run<boost_interval>(state, acid(hc4(shell()))); }
BENCHMARK(BM_acid_distance_shell);

void BM_hc4_expanded_shell(benchmark::State& state) { run<boost_interval>(state, hc4(expanded())); }
BENCHMARK(BM_hc4_expanded_shell);

void BM_hc4_acid_expanded_shell(benchmark::State& state) {
    run<boost_interval>(state, hc4(expanded()) & acid(hc4(expanded())));
}
BENCHMARK(BM_hc4_acid_expanded_shell);

}  // namespace
