// certipose/detail/precompiled.hpp — the pipelines the certipose::precompiled library compiles
// once (not for users to include: <certipose/cgal.hpp> does).
//
// With CERTIPOSE_PRECOMPILED (detail/config.hpp) a translation unit sees explicit instantiation
// declarations: it calls these solvers' `solve` without compiling it. The library's translation
// units (cmake/certipose_precompiled.cpp, cmake/certipose_precompiled_pipelines.cpp) hold the
// explicit instantiation definitions. The list: the default pipeline, and the pipelines with
// `calibrated_camera` (any camera model, e.g. one read from JSON; camera/calibrated_camera.hpp)
// under each occlusion policy — what the programs offer — and the paper's boolean occlusion
// policy. (The non-template CGAL functions — aabb_occlusion, read_mesh — are CERTIPOSE_DECL,
// defined in the first of the two.)
#pragma once

#include "certipose/camera/calibrated_camera.hpp"
#include "certipose/occlusion/aabb_occlusion.hpp"
#include "certipose/occlusion/boolean_occlusion.hpp"
#include "certipose/occlusion/no_occlusion.hpp"
#include "certipose/solver/pose_solver.hpp"

#if defined(CERTIPOSE_PRECOMPILED)
namespace certipose {
extern template class basic_boolean_occlusion<void>;
extern template class pose_solver<default_policies>;
extern template class pose_solver<with_camera<calibrated_camera>>;
extern template class pose_solver<with_occlusion<basic_boolean_occlusion<void>, with_camera<calibrated_camera>>>;
extern template class pose_solver<with_occlusion<no_occlusion, with_camera<calibrated_camera>>>;
}  // namespace certipose
#endif
