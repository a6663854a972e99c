# certipose_add_precompiled(<source> <cgal target>): defines certipose::precompiled, a static
# library of two translation units (<source> = cmake/certipose_precompiled.cpp with the CGAL code,
# and certipose_precompiled_pipelines.cpp beside it: two cores compile them side by side) built
# in the project that uses it, excluded from `all` so that it is compiled only when something
# links it. Used by certipose's own CMakeLists.txt (add_subdirectory, FetchContent) and by
# certiposeConfig.cmake (an installed tree: nothing is built at install time; the sources are
# installed instead).
function(certipose_add_precompiled source cgal_target)
  if(TARGET certipose::precompiled)
    return()
  endif()
  get_filename_component(dir "${source}" DIRECTORY)
  add_library(certipose_precompiled STATIC EXCLUDE_FROM_ALL ${source}
              ${dir}/certipose_precompiled_pipelines.cpp)
  add_library(certipose::precompiled ALIAS certipose_precompiled)
  target_link_libraries(certipose_precompiled PUBLIC ${cgal_target})
  # Every TU that links the library sees declarations only (CERTIPOSE_PRECOMPILED); the
  # library's first TU also compiles the non-template definitions (detail/config.hpp), and each
  # of its TUs the explicit instantiations of some pipelines (detail/precompiled.hpp).
  target_compile_definitions(certipose_precompiled PUBLIC CERTIPOSE_PRECOMPILED)
  set_source_files_properties(${source} PROPERTIES COMPILE_DEFINITIONS CERTIPOSE_PRECOMPILED_DEFINITIONS)
  set_target_properties(certipose_precompiled PROPERTIES POSITION_INDEPENDENT_CODE ON)
endfunction()
