// certipose/cgal.hpp — everything in certipose, the default solver included (certipose::cgal).
//
// <certipose/certipose.hpp> plus what needs CGAL: the certified occlusion policies
// (`aabb_occlusion`, the default, and the paper's `boolean_occlusion`), `read_mesh` for OFF, OBJ,
// PLY and STL, the `cgal_interval` backend, and `visit_occlusion`, the run-time choice among the
// occlusion policies (solver/occlusion_choice.hpp). So `certipose::pose_solver<>` works after this
// one include. Also the independent sampling check (verify/point_check.hpp), which decides close
// calls with GMP and MPFR, as CGAL does.
//
// Compile time: header-only, a translation unit that runs the default pipeline parses CGAL and
// compiles the pipeline itself. Linking `certipose::precompiled` instead of `certipose::cgal`
// defines CERTIPOSE_PRECOMPILED: this header then declares the occlusion policies and read_mesh
// without parsing their CGAL code (kernels, AABB tree, corefinement, readers; only the small
// CGAL/Interval_nt.h of cgal_interval remains), and the default pipelines are compiled once, in
// that library (detail/precompiled.hpp).
#pragma once

#include "certipose/certipose.hpp"  // IWYU pragma: export

#include "certipose/interval/cgal_eigen.hpp"  // IWYU pragma: export
#include "certipose/interval/cgal_interval.hpp"  // IWYU pragma: export
#include "certipose/io/read_mesh.hpp"  // IWYU pragma: export
#include "certipose/occlusion/cgal_aabb_occlusion.hpp"  // IWYU pragma: export
#include "certipose/occlusion/cgal_boolean_occlusion.hpp"  // IWYU pragma: export
#include "certipose/occlusion/cgal_mesh_survey.hpp"  // IWYU pragma: export
#include "certipose/occlusion/cgal_resting_contact.hpp"  // IWYU pragma: export
#include "certipose/solver/occlusion_choice.hpp"  // IWYU pragma: export
#include "certipose/verify/point_check.hpp"  // IWYU pragma: export

#include "certipose/detail/precompiled.hpp"  // IWYU pragma: export
