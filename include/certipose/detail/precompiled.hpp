// certipose/detail/precompiled.hpp — the pipelines the certipose::precompiled library compiles
// once (not for users to include: <certipose/cgal.hpp> does).
//
// With CERTIPOSE_PRECOMPILED (detail/config.hpp) a user translation unit sees explicit
// instantiation declarations: it calls these solvers' `solve` without compiling it. The library's
// one translation unit (cmake/certipose_precompiled.cpp) also defines
// CERTIPOSE_PRECOMPILED_DEFINITIONS and so holds the explicit instantiation definitions. The list:
// the default pipeline, the same with `calibrated_camera` (any camera model, e.g. one read from
// JSON; camera/calibrated_camera.hpp), and the paper's boolean occlusion policy. (The
// non-template CGAL functions — aabb_occlusion, read_mesh — are CERTIPOSE_DECL, defined there too.)
#pragma once

#include "certipose/camera/calibrated_camera.hpp"
#include "certipose/occlusion/aabb_occlusion.hpp"
#include "certipose/occlusion/boolean_occlusion.hpp"
#include "certipose/solver/pose_solver.hpp"

#if defined(CERTIPOSE_PRECOMPILED)
namespace certipose {
#if defined(CERTIPOSE_PRECOMPILED_DEFINITIONS)
template class basic_boolean_occlusion<void>;
template class pose_solver<default_policies>;
template class pose_solver<with_camera<calibrated_camera>>;
#else
extern template class basic_boolean_occlusion<void>;
extern template class pose_solver<default_policies>;
extern template class pose_solver<with_camera<calibrated_camera>>;
#endif
}  // namespace certipose
#endif
