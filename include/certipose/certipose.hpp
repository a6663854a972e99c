// certipose/certipose.hpp — everything in certipose that needs no CGAL (certipose::certipose).
//
// Intervals (the default Boost backend and the operations on any backend), cameras, poses and
// rotations, compile-time expressions, contractors and box tests, bisectors, pavers, position
// constraint sets, the orientation policies and their interval certification, the pose solver
// and its policies (with `no_occlusion`; the certified occlusion policies, mesh reading and the
// default solver are in <certipose/cgal.hpp>, as is the exact point checker), triangle meshes and
// the sample part, and the writers that need neither CGAL nor JSON (OFF, PLY, the
// result document) and the all-or-nothing output files. The whole-part solver (oneTBB) is
// <certipose/part.hpp> (certipose::part); the JSON readers/writers are <certipose/io/json.hpp>
// and <certipose/io/part_files.hpp> (nlohmann-json). The one-facility headers under certipose/
// stay available for those who want less.
#pragma once

#include "certipose/error.hpp"  // IWYU pragma: export

#include "certipose/interval/boost_interval.hpp"  // IWYU pragma: export
#include "certipose/interval/concept.hpp"  // IWYU pragma: export
#include "certipose/interval/eigen.hpp"  // IWYU pragma: export
#include "certipose/interval/operations.hpp"  // IWYU pragma: export

#include "certipose/camera.hpp"  // IWYU pragma: export
#include "certipose/camera/calibrated_camera.hpp"  // IWYU pragma: export

#include "certipose/pose/interval_box.hpp"  // IWYU pragma: export
#include "certipose/pose/part_pose.hpp"  // IWYU pragma: export
#include "certipose/pose/pose_box.hpp"  // IWYU pragma: export
#include "certipose/pose/rotation.hpp"  // IWYU pragma: export

#include "certipose/geometry/cad_faces.hpp"  // IWYU pragma: export
#include "certipose/geometry/sample_part.hpp"  // IWYU pragma: export
#include "certipose/geometry/triangle_mesh.hpp"  // IWYU pragma: export

#include "certipose/contractors.hpp"  // IWYU pragma: export
#include "certipose/expr.hpp"  // IWYU pragma: export

#include "certipose/bisection/concept.hpp"  // IWYU pragma: export
#include "certipose/bisection/largest_first.hpp"  // IWYU pragma: export
#include "certipose/bisection/precision.hpp"  // IWYU pragma: export
#include "certipose/bisection/round_robin.hpp"  // IWYU pragma: export
#include "certipose/paver/paver.hpp"  // IWYU pragma: export

#include "certipose/constraints/box_triangle_distance.hpp"  // IWYU pragma: export
#include "certipose/constraints/concept.hpp"  // IWYU pragma: export
#include "certipose/constraints/keep_in_sphere.hpp"  // IWYU pragma: export
#include "certipose/constraints/paper_position_constraints.hpp"  // IWYU pragma: export

#include "certipose/occlusion/concept.hpp"  // IWYU pragma: export
#include "certipose/occlusion/no_occlusion.hpp"  // IWYU pragma: export

#include "certipose/orientation/certify.hpp"  // IWYU pragma: export
#include "certipose/orientation/concept.hpp"  // IWYU pragma: export
#include "certipose/orientation/paper_orientation.hpp"  // IWYU pragma: export
#include "certipose/orientation/paving_orientation.hpp"  // IWYU pragma: export

#include "certipose/solver/camera_regions.hpp"  // IWYU pragma: export
#include "certipose/solver/contraction.hpp"  // IWYU pragma: export
#include "certipose/solver/policies.hpp"  // IWYU pragma: export
#include "certipose/solver/pose_solver.hpp"  // IWYU pragma: export
#include "certipose/solver/position_stage.hpp"  // IWYU pragma: export
#include "certipose/solver/result.hpp"  // IWYU pragma: export
#include "certipose/solver/solve_settings.hpp"  // IWYU pragma: export
#include "certipose/solver/task.hpp"  // IWYU pragma: export

#include "certipose/io/output_files.hpp"  // IWYU pragma: export
#include "certipose/io/ply.hpp"  // IWYU pragma: export
#include "certipose/io/result_document.hpp"  // IWYU pragma: export
#include "certipose/io/scene_record.hpp"  // IWYU pragma: export
#include "certipose/io/write_file.hpp"  // IWYU pragma: export
#include "certipose/io/write_mesh.hpp"  // IWYU pragma: export
