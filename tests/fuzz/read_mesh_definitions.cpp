// read_mesh and CGAL's readers, compiled once for the four mesh harnesses (which see only the
// declaration: CERTIPOSE_PRECOMPILED, as in certipose::precompiled).
#include <certipose/io/read_mesh.hpp>
