# certipose_add_step(<cgal target>): defines certipose::step, what <certipose/io/read_step.hpp>
# needs: certipose::cgal and the OpenCASCADE toolkits that read STEP and tessellate (Debian
# libocct-data-exchange-dev, libocct-modeling-algorithms-dev and their dependencies; LGPL-2.1 with
# the OCCT exception). Debian 12's OpenCASCADEConfig.cmake refuses to load unless the visualisation
# and application-framework packages are installed too, although reading STEP uses neither: the
# headers and the toolkits are found one by one instead. Sets certipose_has_step in the caller.
# Used by certipose's CMakeLists.txt and by the installed certiposeConfig.cmake.
function(certipose_add_step cgal_target)
  set(certipose_has_step OFF PARENT_SCOPE)
  if(TARGET certipose::step)
    set(certipose_has_step ON PARENT_SCOPE)
    return()
  endif()
  find_path(CERTIPOSE_OCCT_INCLUDE_DIR STEPControl_Reader.hxx PATH_SUFFIXES opencascade)
  set(toolkits TKXDESTEP TKSTEP TKSTEPAttr TKSTEP209 TKSTEPBase TKXSBase TKMesh TKShHealing TKTopAlgo TKGeomAlgo
               TKBRep TKGeomBase TKG3d TKG2d TKMath TKernel)
  set(libraries "")
  foreach(tk IN LISTS toolkits)
    find_library(CERTIPOSE_OCCT_${tk} ${tk})
    if(NOT CERTIPOSE_OCCT_${tk})
      message(STATUS "certipose: OpenCASCADE's ${tk} not found (Debian libocct-data-exchange-dev): no STEP reader")
      return()
    endif()
    list(APPEND libraries ${CERTIPOSE_OCCT_${tk}})
  endforeach()
  if(NOT CERTIPOSE_OCCT_INCLUDE_DIR)
    message(STATUS "certipose: OpenCASCADE's headers not found (Debian libocct-*-dev): no STEP reader")
    return()
  endif()
  add_library(certipose_step INTERFACE IMPORTED GLOBAL)
  add_library(certipose::step ALIAS certipose_step)
  target_include_directories(certipose_step SYSTEM INTERFACE ${CERTIPOSE_OCCT_INCLUDE_DIR})
  target_link_libraries(certipose_step INTERFACE ${cgal_target} ${libraries})
  set(certipose_has_step ON PARENT_SCOPE)
endfunction()
