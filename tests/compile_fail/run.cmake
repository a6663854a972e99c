# A compile-fail test: builds TARGET (expected to fail) and checks that the first line of the
# compiler's output containing "error: " matches EXPECT (from the source's "// expect:" line).
foreach(var BINARY_DIR TARGET SOURCE)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run.cmake: ${var} not set")
  endif()
endforeach()
file(STRINGS ${SOURCE} expect_line REGEX "^// expect: " LIMIT_COUNT 1)
string(REGEX REPLACE "^// expect: " "" expect "${expect_line}")
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BINARY_DIR} --target ${TARGET}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(rc EQUAL 0)
  message(FATAL_ERROR "${TARGET} compiled, but it must not:\n${out}")
endif()
string(REGEX MATCH "[^\n]*error: [^\n]*" first "${out}")
# GCC quotes with typographic quotes; compare without them.
string(REGEX REPLACE "[‘’']" "" first_plain "${first}")
if(NOT first_plain MATCHES "${expect}")
  message(FATAL_ERROR "${TARGET}: the first error line does not match '${expect}':\n${first}\n\nfull output:\n${out}")
endif()
message(STATUS "${TARGET} fails to compile as expected: ${first}")
