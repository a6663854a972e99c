# Builds and runs a downstream project against certipose, either through an install tree
# (MODE=installed: a fresh default configure of certipose and `cmake --install` with nothing
# built, then find_package) or through add_subdirectory.
foreach(var MODE SOURCE_DIR WORK_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_consumer.cmake: ${var} not set")
  endif()
endforeach()
file(REMOVE_RECURSE ${WORK_DIR})
# No build type: -O0 without debug information, the quickest build of what is only a packaging
# test (the default pipeline still runs, in about a second). The parent's compiler launcher
# (ccache) is passed on.
set(consumer_flags -G Ninja -DCMAKE_BUILD_TYPE=)
if(LAUNCHER)
  list(APPEND consumer_flags -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}")
  endif()
  message(STATUS "${out}")
endfunction()
if(MODE STREQUAL "installed")
  # What a user does first: configure with the defaults and install, without building.
  run(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/certipose -G Ninja)
  run(${CMAKE_COMMAND} --install ${WORK_DIR}/certipose --prefix ${WORK_DIR}/prefix)
  if(EXISTS ${WORK_DIR}/prefix/bin/certipose-solve)
    message(FATAL_ERROR "an install without a build installed a program it never built")
  endif()
  run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/consumer/installed -B ${WORK_DIR}/build ${consumer_flags}
      -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix)
else()
  run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/consumer/subdir -B ${WORK_DIR}/build ${consumer_flags}
      -DCERTIPOSE_SOURCE_DIR=${SOURCE_DIR})
endif()
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/consumer)
run(${WORK_DIR}/build/consumer_part)
run(${WORK_DIR}/build/consumer_cgal)
if(MODE STREQUAL "installed")
  run(${WORK_DIR}/build/consumer_downstream --benchmark_min_time=0.05)
  if(EXISTS ${WORK_DIR}/build/consumer_step)
    run(${WORK_DIR}/build/consumer_step)
  endif()
endif()
