# Outputs appear whole or not at all (docs/cli.md): colliding outputs are refused before any work, a failed run
# leaves nothing, and temporaries left by a killed run are removed by the next one.
include(${CMAKE_CURRENT_LIST_DIR}/cli_support.cmake)
write_model(m)

# `-o x.hpp`: the default header would be x.hpp too. Refused (usage), nothing written.
tree_state(before "${WORK}")
expect_run(STATUS 2 STDERR "x.hpp is also the output of" ARGS m.mdl -o x.hpp)
expect_unchanged("${before}" "${WORK}" "-o x.hpp")

# An output that is an input.
expect_run(STATUS 2 STDERR "is an input of this command" ARGS m.mdl -o m.mdl --header m.hpp)
expect_unchanged("${before}" "${WORK}" "-o m.mdl")

# A destination that is a directory, or in a directory that does not exist: bad output (1), nothing written.
file(MAKE_DIRECTORY "${WORK}/d.cpp")
tree_state(before "${WORK}")
expect_run(STATUS 1 STDERR "d.cpp: error: cannot write: it is a directory" ARGS m.mdl -o d.cpp --header d.hpp)
expect_run(STATUS 1 STDERR "missing/m.[ch]pp: error: cannot write: directory `missing` does not exist" ARGS m.mdl -o missing/m.cpp)
expect_unchanged("${before}" "${WORK}" "unwritable destinations")

# A failure late in the run (the model is bad only as C++: its name is a keyword) leaves nothing.
file(WRITE "${WORK}/kw.mdl" "model int\nground g\nbody b { mass 1; dof x }\nspring s { from g; to b; along x; stiffness 1 }\n")
tree_state(before "${WORK}")
expect_run(STATUS 1 STDERR "kw.mdl:1:7: error: the model's name `int` cannot name its C\\+\\+ namespace" ARGS kw.mdl -o kw.cpp)
expect_unchanged("${before}" "${WORK}" "a failed compile")

# Temporaries of a killed run (this host, a process that no longer exists) are removed by the next run writing the
# same destination; one of a live process (pid 1) is left alone.
cmake_host_system_information(RESULT host QUERY HOSTNAME)
string(REGEX REPLACE "[^A-Za-z0-9-]" "_" host "${host}")
file(WRITE "${WORK}/.out.cpp.mbgen-tmp-${host}-99999999" "half-written\n")
file(WRITE "${WORK}/.out.cpp.mbgen-tmp-${host}-1" "someone else's\n")
expect_run(STATUS 0 ARGS m.mdl -o out.cpp)
if(EXISTS "${WORK}/.out.cpp.mbgen-tmp-${host}-99999999")
  message(SEND_ERROR "the stale temporary of a dead process was not removed")
endif()
if(NOT EXISTS "${WORK}/.out.cpp.mbgen-tmp-${host}-1")
  message(SEND_ERROR "the temporary of a live process was removed")
endif()
file(REMOVE "${WORK}/.out.cpp.mbgen-tmp-${host}-1")
expect_no_temporaries("${WORK}")
if(NOT EXISTS "${WORK}/out.cpp" OR NOT EXISTS "${WORK}/out.hpp")
  message(SEND_ERROR "the outputs are missing")
endif()

# Standard input may be read once.
expect_run(STATUS 2 STDERR "standard input \\(-\\) can be read only once" ARGS fit - --data - --starts 1)

# `--parts N` writes OUT.cpp and OUT_part1.cpp .. OUT_part<N-1>.cpp; a part that collides with another output is
# refused before any work; `-o -` cannot hold several translation units (usage).
expect_run(STATUS 0 ARGS m.mdl -o split.cpp --parts 3)
foreach(f split.cpp split.hpp split_part1.cpp split_part2.cpp)
  if(NOT EXISTS "${WORK}/${f}")
    message(SEND_ERROR "--parts 3 did not write ${f}")
  endif()
endforeach()
if(EXISTS "${WORK}/split_part3.cpp")
  message(SEND_ERROR "--parts 3 wrote a fourth source")
endif()
tree_state(before "${WORK}")
expect_run(STATUS 2 STDERR "several translation units need a file name" ARGS m.mdl -o - --parts 2)
expect_run(STATUS 2 STDERR "x_part1.cpp is also the output of" ARGS m.mdl -o x.cpp --header x_part1.cpp --parts 2)
expect_run(STATUS 2 ARGS m.mdl -o y.cpp --parts 0)
expect_unchanged("${before}" "${WORK}" "refused --parts")

# An empty name names nothing: a usage error, nothing written. `-o ''` wrote the header `.hpp` and then failed with
# status 1; `--header ''`, `--report ''` and `--json ''` were taken for "not given" (the run exited 0 without them).
# (execute_process directly: an empty element of expect_run's ARGS list would be dropped.)
tree_state(before "${WORK}")
foreach(case "--output|m.mdl;-o" "--header|m.mdl;-o;e.cpp;--header" "--report|${FAST_FIT};--report"
             "--json|${FAST_FIT};--json" "model|inspect")
  string(REPLACE "|" ";" case "${case}")
  list(POP_FRONT case option)
  execute_process(COMMAND "${MBGEN}" ${case} "" WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE status
    ERROR_VARIABLE err OUTPUT_QUIET TIMEOUT 60)
  if(NOT status EQUAL 2 OR NOT err MATCHES "^mbgen: ${option}: an empty value names nothing")
    message(SEND_ERROR "`mbgen ${case} ''`: expected status 2 and `${option}: an empty value`, got ${status}: ${err}")
  endif()
endforeach()
expect_unchanged("${before}" "${WORK}" "empty output names")
