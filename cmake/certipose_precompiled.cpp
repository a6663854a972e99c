// The first translation unit of certipose::precompiled: the CGAL facilities' non-template
// functions (CERTIPOSE_DECL; CMake defines CERTIPOSE_PRECOMPILED_DEFINITIONS for this TU only)
// and the boolean occlusion policy. The pipelines are in certipose_precompiled_pipelines.cpp,
// compiled beside this one. Code linking the target sees the explicit instantiation
// declarations of certipose/detail/precompiled.hpp and compiles none of it.
#include <certipose/cgal.hpp>

template class certipose::basic_boolean_occlusion<void>;
