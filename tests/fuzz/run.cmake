# Runs one libFuzzer harness from a fresh working corpus (so every run fuzzes the same inputs):
#   cmake -DFUZZER=<binary> -DWORK=<dir> -DARGS=<flags separated by |> -DDIRS=<corpora separated by |> -P run.cmake
# The working corpus comes first: libFuzzer writes the inputs it finds into the first folder, and
# the seed folders are in the source tree.
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
string(REPLACE "|" ";" args "${ARGS}")
string(REPLACE "|" ";" dirs "${DIRS}")
execute_process(COMMAND "${FUZZER}" ${args} "${WORK}" ${dirs} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${FUZZER} failed (${rc}): the input is in the artifacts folder named above; once fixed, "
                      "copy it to tests/fuzz/regressions/<harness>/")
endif()
