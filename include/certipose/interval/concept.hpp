// certipose/interval/concept.hpp — what an interval type must provide, and the operations
// every algorithm may use on one.
//
// An interval backend is a class in some namespace with free functions found by ADL (as
// Boost.Interval and CGAL::Interval_nt do) plus an `interval_traits<I>` specialisation. The
// concept asks for the primitives that need the backend's rounding (arithmetic, sqr, sqrt,
// sin, cos, acos, atan, integer pow); everything that only reads bounds (hull, intersection,
// width, midpoint, bisection, the named comparisons) is written once in
// interval/operations.hpp on top of `lower`/`upper`/`is_empty`.
//
// Rounding protocol (STYLE.md): switching the FPU rounding mode per operation costs ~4x, so
// backends assume the mode is held *upward* by an RAII `rounding_guard<I>` for the duration of
// a hot block. Every library entry point that computes with intervals holds one; user code that
// computes with intervals directly must too. Debug builds assert it.
#pragma once

#include <concepts>
#include <type_traits>

namespace certipose {

/// Per-backend facts a generic algorithm needs: the empty and the whole interval and the RAII
/// type that holds the rounding mode the backend's arithmetic relies on.
template <class I>
struct interval_traits;  // specialised by each backend

/// The RAII guard that must be alive while `I` arithmetic runs (nestable).
template <class I>
using rounding_guard = typename interval_traits<I>::rounding_guard;

// clang-format off
template <class I>
concept Interval =
    std::regular<I> && std::constructible_from<I, double> && std::constructible_from<I, double, double> &&
    requires(const I a, const I b, double d, int n) {
        typename interval_traits<I>::rounding_guard;
        { interval_traits<I>::empty() } -> std::same_as<I>;
        { interval_traits<I>::whole() } -> std::same_as<I>;
        { lower(a) } -> std::same_as<double>;
        { upper(a) } -> std::same_as<double>;
        { is_empty(a) } -> std::same_as<bool>;
        { a + b } -> std::same_as<I>;  { a - b } -> std::same_as<I>;
        { a * b } -> std::same_as<I>;  { a / b } -> std::same_as<I>;
        { a + d } -> std::same_as<I>;  { d * a } -> std::same_as<I>;
        { -a } -> std::same_as<I>;
        { sqr(a) } -> std::same_as<I>;  { sqrt(a) } -> std::same_as<I>;
        { sin(a) } -> std::same_as<I>;  { cos(a) } -> std::same_as<I>;
        { acos(a) } -> std::same_as<I>; { atan(a) } -> std::same_as<I>;
        { abs(a) } -> std::same_as<I>;  { pow(a, n) } -> std::same_as<I>;
    };
// clang-format on

}  // namespace certipose
