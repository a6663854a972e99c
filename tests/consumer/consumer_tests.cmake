# A downstream project consumes certipose through `find_package(certipose CONFIG)` on an
# installed tree (linking certipose::precompiled), and through `add_subdirectory` (header-only
# certipose::cgal). Each builds the default pipeline (at -O0), so each takes a minute or two of both cores.
foreach(mode installed subdir)
  add_test(NAME consumer.${mode}
    COMMAND ${CMAKE_COMMAND} -DMODE=${mode} -DSOURCE_DIR=${PROJECT_SOURCE_DIR}
            -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/consumer-${mode} "-DLAUNCHER=${CMAKE_CXX_COMPILER_LAUNCHER}"
            -P ${CMAKE_CURRENT_LIST_DIR}/run_consumer.cmake)
  set_tests_properties(consumer.${mode} PROPERTIES LABELS consumer TIMEOUT 1500 PROCESSORS 2 RUN_SERIAL ON)
endforeach()
