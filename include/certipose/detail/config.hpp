// certipose/detail/config.hpp — the build switches of certipose (not for users to include).
//
// Macros, because nothing else can choose an attribute or a linkage:
//
// CERTIPOSE_DETAIL_INLINE forces inlining (GCC and Clang, with NDEBUG) of the small functions an
// expression tree is made of — each node's forward and backward step and the interval primitives
// they call (+, −, ×, sqr, intersect, ...). A constraint then compiles to one straight-line
// function, as `[[gnu::flatten]]` once made it, but the large helpers it calls (division and
// trigonometric projections, libm, error paths) stay out of line: the same instructions at run
// time (callgrind on the case study: within 0.4 %), and a third less compile time for a TU that
// instantiates the default pipeline. With assertions on it is plain `inline`: CGAL's
// Interval_nt constructors carry their assertion code, and forcing that into every node made
// one constraint take minutes to compile.
//
// CERTIPOSE_DECL marks the non-template functions behind the CGAL-heavy facilities (building
// and querying the occlusion scenes, reading meshes). Header-only (the default) it is `inline`
// and their definitions come with the headers. When CERTIPOSE_PRECOMPILED is defined — the
// `certipose::precompiled` CMake target does it for the code that links it — the headers only
// declare them, and the first translation unit of that target defines them once; its
// translation units also hold the explicit instantiations of the pipelines listed in
// certipose/detail/precompiled.hpp. Every
// translation unit of a program must agree on CERTIPOSE_PRECOMPILED; the target sees to it.
#pragma once

#if defined(NDEBUG) && (defined(__GNUC__) || defined(__clang__))
#define CERTIPOSE_DETAIL_INLINE [[gnu::always_inline]] inline
#else
#define CERTIPOSE_DETAIL_INLINE inline
#endif

#if defined(CERTIPOSE_PRECOMPILED) && !defined(CERTIPOSE_PRECOMPILED_DEFINITIONS)
#define CERTIPOSE_DECL
#define CERTIPOSE_DETAIL_WITH_DEFINITIONS 0
#elif defined(CERTIPOSE_PRECOMPILED)
#define CERTIPOSE_DECL
#define CERTIPOSE_DETAIL_WITH_DEFINITIONS 1
#else
#define CERTIPOSE_DECL inline
#define CERTIPOSE_DETAIL_WITH_DEFINITIONS 1
#endif
