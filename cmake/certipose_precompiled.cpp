// The one translation unit of certipose::precompiled: the CGAL facilities' non-template
// functions (CERTIPOSE_DECL) and the explicit instantiations of certipose/detail/precompiled.hpp,
// compiled once so that code linking the target compiles none of it. CMake defines
// CERTIPOSE_PRECOMPILED and CERTIPOSE_PRECOMPILED_DEFINITIONS here (detail/config.hpp).
#include <certipose/cgal.hpp>
