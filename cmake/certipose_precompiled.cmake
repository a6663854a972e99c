# certipose_add_precompiled(<source> <cgal target>): defines certipose::precompiled, a static
# library of one translation unit (cmake/certipose_precompiled.cpp) built in the project that
# uses it, excluded from `all` so that it is compiled only when something links it. Used by
# certipose's own CMakeLists.txt (add_subdirectory, FetchContent) and by certiposeConfig.cmake
# (an installed tree: nothing is built at install time; the source is installed instead).
function(certipose_add_precompiled source cgal_target)
  if(TARGET certipose::precompiled)
    return()
  endif()
  add_library(certipose_precompiled STATIC EXCLUDE_FROM_ALL ${source})
  add_library(certipose::precompiled ALIAS certipose_precompiled)
  target_link_libraries(certipose_precompiled PUBLIC ${cgal_target})
  # Every TU that links the library sees declarations only (CERTIPOSE_PRECOMPILED); the library
  # itself also compiles the definitions (detail/config.hpp).
  target_compile_definitions(certipose_precompiled PUBLIC CERTIPOSE_PRECOMPILED
                                                   PRIVATE CERTIPOSE_PRECOMPILED_DEFINITIONS)
  set_target_properties(certipose_precompiled PROPERTIES POSITION_INDEPENDENT_CODE ON)
endfunction()
