// certipose/certipose.hpp — everything in certipose that needs no CGAL (certipose::certipose).
//
// Intervals (the default Boost backend and the operations on any backend), cameras, poses and
// rotations, compile-time expressions, contractors and box tests, bisectors, pavers, position
// constraint sets, the orientation policies and their interval certification, the pose solver
// and its policies (with `no_occlusion`; the certified occlusion policies, mesh reading and the
// default solver are in <certipose/cgal.hpp>), triangle meshes and the sample part, the
// independent point checker, and the writers that need neither CGAL nor JSON (OFF, PLY, the
// result document), the all-or-nothing output files, and the whole-part solver (oneTBB). The JSON
// readers/writers are <certipose/io/json.hpp> and <certipose/io/part_files.hpp> (nlohmann-json).
// The one-facility headers under certipose/ stay available for those who want less.
#pragma once

#include "certipose/error.hpp"

#include "certipose/interval/boost_interval.hpp"
#include "certipose/interval/concept.hpp"
#include "certipose/interval/eigen.hpp"
#include "certipose/interval/operations.hpp"

#include "certipose/camera.hpp"
#include "certipose/camera/calibrated_camera.hpp"

#include "certipose/pose/interval_box.hpp"
#include "certipose/pose/pose_box.hpp"
#include "certipose/pose/rotation.hpp"

#include "certipose/geometry/sample_part.hpp"
#include "certipose/geometry/triangle_mesh.hpp"

#include "certipose/contractors.hpp"
#include "certipose/expr.hpp"

#include "certipose/bisection/concept.hpp"
#include "certipose/bisection/largest_first.hpp"
#include "certipose/bisection/precision.hpp"
#include "certipose/bisection/round_robin.hpp"
#include "certipose/paver/paver.hpp"

#include "certipose/constraints/box_triangle_distance.hpp"
#include "certipose/constraints/concept.hpp"
#include "certipose/constraints/keep_in_sphere.hpp"
#include "certipose/constraints/paper_position_constraints.hpp"

#include "certipose/occlusion/concept.hpp"
#include "certipose/occlusion/no_occlusion.hpp"

#include "certipose/orientation/certify.hpp"
#include "certipose/orientation/concept.hpp"
#include "certipose/orientation/paper_orientation.hpp"
#include "certipose/orientation/paving_orientation.hpp"

#include "certipose/solver/contraction.hpp"
#include "certipose/solver/policies.hpp"
#include "certipose/solver/pose_solver.hpp"
#include "certipose/solver/position_stage.hpp"
#include "certipose/solver/result.hpp"
#include "certipose/solver/task.hpp"

#include "certipose/io/output_files.hpp"
#include "certipose/io/ply.hpp"
#include "certipose/io/result_document.hpp"
#include "certipose/io/write_file.hpp"
#include "certipose/io/write_mesh.hpp"

#include "certipose/part/part_solver.hpp"
#include "certipose/part/selection.hpp"
