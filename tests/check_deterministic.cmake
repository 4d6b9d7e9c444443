# Runs one `mbgen` command twice, as two processes, each writing its JSON result, and requires the two files to
# be byte-identical. Two processes, not two calls in one: a run-to-run difference can come from where the program
# is loaded (address-space randomization changes GiNaC's hash values and so the order of a sum's terms).
# Usage: cmake -DMBGEN=... "-DARGS=fit;model.mdl;--data;f.csv" -DWORK_DIR=... -P check_deterministic.cmake
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
foreach(run 1 2)
  execute_process(COMMAND "${MBGEN}" ${ARGS} --json "${WORK_DIR}/run${run}.json"
    RESULT_VARIABLE status ERROR_VARIABLE err OUTPUT_QUIET)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "run ${run} failed (exit status ${status}):\n${err}")
  endif()
endforeach()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files "${WORK_DIR}/run1.json" "${WORK_DIR}/run2.json"
  RESULT_VARIABLE differ)
if(NOT differ EQUAL 0)
  message(FATAL_ERROR "two runs of `mbgen ${ARGS}` gave different results: ${WORK_DIR}/run1.json, run2.json")
endif()
