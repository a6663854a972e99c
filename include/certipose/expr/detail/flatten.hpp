// certipose/expr/detail/flatten.hpp — CERTIPOSE_DETAIL_FLATTEN, applied to the few functions
// that run a whole expression tree (HC4Revise, forward evaluation).
//
// Not for users. `[[gnu::flatten]]` inlines every call in the function, so a constraint becomes
// one straight-line function: HC4 on the shell went from ~225 ns to ~85 ns with the Boost
// backend (GCC 12's heuristics leave the backend's operators as calls otherwise). Only with
// NDEBUG: with assertions on, CGAL's Interval_nt constructors carry their assertion/exception
// code, and inlining that at every node made one constraint take minutes to compile at -O2.
// A macro because an attribute cannot be chosen by constexpr.
#pragma once

#if defined(NDEBUG) && (defined(__GNUC__) || defined(__clang__))
#define CERTIPOSE_DETAIL_FLATTEN [[gnu::flatten]]
#else
#define CERTIPOSE_DETAIL_FLATTEN
#endif
