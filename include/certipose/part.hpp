// certipose/part.hpp — umbrella for the whole-part solver: link certipose::part (oneTBB).
//
// Every facet of a part, or a selection of them, on oneTBB threads over one shared pose_solver,
// streamed to a sink in facet order (`part_solver`, `part_options`, `facet_outcome`, `PartSink`:
// part/part_solver.hpp), and facet selections written as text, "0,5,17-30"
// (`parse_facet_selection`: part/selection.hpp). certipose::part is certipose::certipose plus
// oneTBB and holds no CGAL: `part_solver<>`'s default occlusion policy needs <certipose/cgal.hpp>,
// linked with certipose::cgal or certipose::precompiled as well. Not included here:
// part/mpi.hpp, the same run across machines, which needs MPI (include it yourself).
#pragma once

#include "certipose/part/part_solver.hpp"  // IWYU pragma: export
#include "certipose/part/selection.hpp"  // IWYU pragma: export
