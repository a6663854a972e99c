# A downstream project consumes certipose through `find_package(certipose CONFIG)` on an
# installed tree (linking certipose::precompiled), and through `add_subdirectory` (header-only
# certipose::cgal); each also links certipose::part alone (oneTBB, main_part.cpp). Each builds
# the default pipeline (at -O0), a minute or two, mostly in one large TU
# (certipose_precompiled.cpp; main_cgal.cpp header-only): run one after the other, each left a
# core idle most of the time, so they claim one processor each and run side by side.
foreach(mode installed subdir)
  add_test(NAME consumer.${mode}
    COMMAND ${CMAKE_COMMAND} -DMODE=${mode} -DSOURCE_DIR=${PROJECT_SOURCE_DIR}
            -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/consumer-${mode} "-DLAUNCHER=${CMAKE_CXX_COMPILER_LAUNCHER}"
            -P ${CMAKE_CURRENT_LIST_DIR}/run_consumer.cmake)
  set_tests_properties(consumer.${mode} PROPERTIES LABELS consumer TIMEOUT 1500 PROCESSORS 1)
endforeach()
