# Runs one `mbgen` command twice, as two processes, and requires the files each run writes to be byte-identical.
# Two processes, not two calls in one: a run-to-run difference can come from where the program is loaded
# (address-space randomization changes GiNaC's hash values, and so the order of a sum's terms and the signs of the
# sums in a product).
# Each run writes into its own directory, named by @OUT@ in ARGS; with STDOUT_FILE set, its standard output goes to
# that file there; with neither, the run writes its JSON result there (`--json @OUT@/result.json`).
# Usage: cmake -DMBGEN=... "-DARGS=fit;model.mdl;--data;f.csv" [-DSTDOUT_FILE=name] -DWORK_DIR=...
#              -P check_deterministic.cmake
file(REMOVE_RECURSE "${WORK_DIR}")
if(NOT ARGS MATCHES "@OUT@" AND NOT STDOUT_FILE)
  list(APPEND ARGS --json @OUT@/result.json)
endif()
foreach(run 1 2)
  set(out "${WORK_DIR}/run${run}")
  file(MAKE_DIRECTORY "${out}")
  string(REPLACE "@OUT@" "${out}" run_args "${ARGS}")
  if(STDOUT_FILE)
    execute_process(COMMAND "${MBGEN}" ${run_args} RESULT_VARIABLE status ERROR_VARIABLE err
      OUTPUT_FILE "${out}/${STDOUT_FILE}")
  else()
    execute_process(COMMAND "${MBGEN}" ${run_args} RESULT_VARIABLE status ERROR_VARIABLE err OUTPUT_QUIET)
  endif()
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "run ${run} failed (exit status ${status}):\n${err}")
  endif()
endforeach()
file(GLOB_RECURSE files RELATIVE "${WORK_DIR}/run1" "${WORK_DIR}/run1/*")
file(GLOB_RECURSE files2 RELATIVE "${WORK_DIR}/run2" "${WORK_DIR}/run2/*")
if(NOT files STREQUAL files2 OR files STREQUAL "")
  message(FATAL_ERROR "two runs of `mbgen ${ARGS}` wrote different sets of files: [${files}] and [${files2}]")
endif()
foreach(f IN LISTS files)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files "${WORK_DIR}/run1/${f}" "${WORK_DIR}/run2/${f}"
    RESULT_VARIABLE differ)
  if(NOT differ EQUAL 0)
    message(FATAL_ERROR "two runs of `mbgen ${ARGS}` gave different results: ${WORK_DIR}/run1/${f}, run2/${f}")
  endif()
endforeach()
