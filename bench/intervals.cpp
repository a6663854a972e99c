// Cost of the interval primitives every contractor is made of: one multiply, one sin, one 3×3
// matrix–vector product (Eigen, the shape of the rotation in the field-of-view constraint), per
// backend, with the rounding mode
//   held    — one rounding_guard outside the loop, as library entry points do;
//   per_op  — a guard around every single operation, i.e. what Boost's default `save_state`
//             policy does (two mode switches per operation).
// For comparison: Boost's stock `boost::numeric::interval<double>` (default policies: per-op
// switching, checking_strict) and raw `CGAL::Interval_nt` (the ~23 ns reference of STYLE.md).
// This file includes CGAL, so it links certipose::cgal.
#include <certipose/interval/boost_interval.hpp>
#include <certipose/interval/cgal_eigen.hpp>
#include <certipose/interval/cgal_interval.hpp>
#include <certipose/interval/eigen.hpp>

#include <benchmark/benchmark.h>

#include <Eigen/Core>

#include <boost/numeric/interval.hpp>

#include <CGAL/Interval_nt.h>

namespace {

using certipose::boost_interval;
using certipose::cgal_interval;
using certipose::rounding_guard;

template <class I>
using mat3 = Eigen::Matrix<I, 3, 3>;
template <class I>
using vec3 = Eigen::Matrix<I, 3, 1>;

// Boost with every default policy: rounded_math<double> = save_state<rounded_arith_opp>.
using boost_stock = boost::numeric::interval<double>;
// Stock Boost has no transcendental policy by default; this one (libm in the current rounding
// mode, unsound per STYLE.md) is only here to time the per-operation switching of sin.
using boost_stock_transc = boost::numeric::interval<
    double, boost::numeric::interval_lib::policies<
                boost::numeric::interval_lib::save_state<
                    boost::numeric::interval_lib::rounded_transc_opp<double>>,
                boost::numeric::interval_lib::checking_base<double>>>;

// A rotation-like matrix and a position-difference-like vector of narrow intervals.
template <class I>
mat3<I> sample_matrix() {
    const double c[3][3] = {{0.36, -0.48, 0.8}, {0.8, 0.6, 0.0}, {-0.48, 0.64, 0.6}};
    mat3<I> m;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m(i, j) = I(c[i][j] - 1e-3, c[i][j] + 1e-3);
    return m;
}
template <class I>
vec3<I> sample_vector() {
    return vec3<I>(I(0.4, 0.5), I(-0.2, 0.1), I(0.9, 1.0));
}

// ---- one multiply ---------------------------------------------------------------------------

template <class I>
void BM_multiply_held(benchmark::State& state) {
    I a(1.0, 1.1), b(-0.3, 0.7);
    const rounding_guard<I> guard;
    for (auto _ : state) {
        benchmark::DoNotOptimize(a);
        benchmark::DoNotOptimize(b);
        I r = a * b;
        benchmark::DoNotOptimize(r);
    }
}
template <class I>
void BM_multiply_per_op(benchmark::State& state) {
    I a(1.0, 1.1), b(-0.3, 0.7);
    for (auto _ : state) {
        benchmark::DoNotOptimize(a);
        benchmark::DoNotOptimize(b);
        const rounding_guard<I> guard;
        I r = a * b;
        benchmark::DoNotOptimize(r);
    }
}
template <class I>  // types that switch the mode themselves (Boost stock, Interval_nt<true>)
void BM_multiply_self_switching(benchmark::State& state) {
    I a(1.0, 1.1), b(-0.3, 0.7);
    for (auto _ : state) {
        benchmark::DoNotOptimize(a);
        benchmark::DoNotOptimize(b);
        I r = a * b;
        benchmark::DoNotOptimize(r);
    }
}
void BM_multiply_held_raw_cgal(benchmark::State& state) {
    CGAL::Interval_nt<false> a(1.0, 1.1), b(-0.3, 0.7);
    const CGAL::Protect_FPU_rounding<true> guard;
    for (auto _ : state) {
        benchmark::DoNotOptimize(a);
        benchmark::DoNotOptimize(b);
        CGAL::Interval_nt<false> r = a * b;
        benchmark::DoNotOptimize(r);
    }
}

// ---- one sin --------------------------------------------------------------------------------

template <class I>
void BM_sin_held(benchmark::State& state) {
    I a(0.3, 0.31);
    const rounding_guard<I> guard;
    for (auto _ : state) {
        benchmark::DoNotOptimize(a);
        I r = sin(a);
        benchmark::DoNotOptimize(r);
    }
}
template <class I>
void BM_sin_per_op(benchmark::State& state) {
    I a(0.3, 0.31);
    for (auto _ : state) {
        benchmark::DoNotOptimize(a);
        const rounding_guard<I> guard;
        I r = sin(a);
        benchmark::DoNotOptimize(r);
    }
}
void BM_sin_self_switching_boost_stock(benchmark::State& state) {
    boost_stock_transc a(0.3, 0.31);
    for (auto _ : state) {
        benchmark::DoNotOptimize(a);
        boost_stock_transc r = sin(a);
        benchmark::DoNotOptimize(r);
    }
}

// ---- one 3×3 matrix–vector product ----------------------------------------------------------

template <class I>
void BM_matvec_held(benchmark::State& state) {
    mat3<I> m = sample_matrix<I>();
    vec3<I> v = sample_vector<I>();
    const rounding_guard<I> guard;
    for (auto _ : state) {
        benchmark::DoNotOptimize(m);
        benchmark::DoNotOptimize(v);
        vec3<I> r = m * v;
        benchmark::DoNotOptimize(r);
    }
}
void BM_matvec_held_raw_cgal(benchmark::State& state) {
    using R = CGAL::Interval_nt<false>;
    mat3<R> m;
    vec3<R> v;
    const mat3<cgal_interval> mi = sample_matrix<cgal_interval>();
    const vec3<cgal_interval> vi = sample_vector<cgal_interval>();
    for (int i = 0; i < 3; ++i) {
        v(i) = vi(i).base();
        for (int j = 0; j < 3; ++j) m(i, j) = mi(i, j).base();
    }
    const CGAL::Protect_FPU_rounding<true> guard;
    for (auto _ : state) {
        benchmark::DoNotOptimize(m);
        benchmark::DoNotOptimize(v);
        vec3<R> r = m * v;
        benchmark::DoNotOptimize(r);
    }
}
// Per-operation switching: every one of the 9 products and 6 sums under its own guard.
template <class I>
I guarded_mul(const I& a, const I& b) {
    const rounding_guard<I> guard;
    return a * b;
}
template <class I>
I guarded_add(const I& a, const I& b) {
    const rounding_guard<I> guard;
    return a + b;
}
template <class I>
void BM_matvec_per_op(benchmark::State& state) {
    mat3<I> m = sample_matrix<I>();
    vec3<I> v = sample_vector<I>();
    for (auto _ : state) {
        benchmark::DoNotOptimize(m);
        benchmark::DoNotOptimize(v);
        vec3<I> r;
        for (int i = 0; i < 3; ++i) {
            I acc = guarded_mul(m(i, 0), v(0));
            acc = guarded_add(acc, guarded_mul(m(i, 1), v(1)));
            r(i) = guarded_add(acc, guarded_mul(m(i, 2), v(2)));
        }
        benchmark::DoNotOptimize(r);
    }
}
// Boost's stock interval cannot be an Eigen scalar (its converting constructor makes the
// product ambiguous, STYLE.md), so its product is written out; it switches per operation.
void BM_matvec_self_switching_boost_stock(benchmark::State& state) {
    const mat3<boost_interval> mi = sample_matrix<boost_interval>();
    const vec3<boost_interval> vi = sample_vector<boost_interval>();
    boost_stock m[3][3], v[3];
    for (int i = 0; i < 3; ++i) {
        v[i] = boost_stock(lower(vi(i)), upper(vi(i)));
        for (int j = 0; j < 3; ++j) m[i][j] = boost_stock(lower(mi(i, j)), upper(mi(i, j)));
    }
    for (auto _ : state) {
        benchmark::DoNotOptimize(m);
        benchmark::DoNotOptimize(v);
        boost_stock r[3];
        for (int i = 0; i < 3; ++i) r[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
        benchmark::DoNotOptimize(r);
    }
}

}  // namespace

BENCHMARK_TEMPLATE(BM_multiply_held, boost_interval);
BENCHMARK_TEMPLATE(BM_multiply_held, cgal_interval);
BENCHMARK(BM_multiply_held_raw_cgal);
BENCHMARK_TEMPLATE(BM_multiply_per_op, boost_interval);
BENCHMARK_TEMPLATE(BM_multiply_per_op, cgal_interval);
BENCHMARK_TEMPLATE(BM_multiply_self_switching, boost_stock);
BENCHMARK_TEMPLATE(BM_multiply_self_switching, CGAL::Interval_nt<true>);

BENCHMARK_TEMPLATE(BM_sin_held, boost_interval);
BENCHMARK_TEMPLATE(BM_sin_held, cgal_interval);
BENCHMARK_TEMPLATE(BM_sin_per_op, boost_interval);
BENCHMARK_TEMPLATE(BM_sin_per_op, cgal_interval);
BENCHMARK(BM_sin_self_switching_boost_stock);

BENCHMARK_TEMPLATE(BM_matvec_held, boost_interval);
BENCHMARK_TEMPLATE(BM_matvec_held, cgal_interval);
BENCHMARK(BM_matvec_held_raw_cgal);
BENCHMARK_TEMPLATE(BM_matvec_per_op, boost_interval);
BENCHMARK_TEMPLATE(BM_matvec_per_op, cgal_interval);
BENCHMARK(BM_matvec_self_switching_boost_stock);
