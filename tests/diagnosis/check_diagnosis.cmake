# One hidden-effect test: make data with the independent truth-model generator (scripts/truthgen, numpy; not
# mbgen's code), run `mbgen diagnose`, and check the verdict and the selected extensions in its JSON.
#   -DMBGEN=... -DPYTHON=... -DTRUTHGEN=... -DMODEL=... -DWORK_DIR=...
#   -DDATA="example:case:kind:seed[:NAME=VALUE][:duration=S][:draw=N][:averages=N][:nocoh][:fs=HZ]|..."
#                                                                     one or more data sets
#         or "file=PATH|..." for measured data as they are (real data, no generator)
#   -DDIAGNOSE_ARGS="--fit-band;20:320" (optional): more arguments of `mbgen diagnose`
#   -DEXPECT_VERDICT=extended|no_extension_justified|unexplained|not_extended
#   -DEXPECT_SELECTED=id (first selected extension, when extended)
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
string(REPLACE "|" ";" sets "${DATA}")
set(data_args "")
set(index 0)
foreach(set IN LISTS sets)
  if(set MATCHES "^file=(.*)$")
    list(APPEND data_args --data "${CMAKE_MATCH_1}")
    continue()
  endif()
  string(REPLACE ":" ";" f "${set}")
  list(GET f 0 example)
  list(GET f 1 case)
  list(GET f 2 kind)
  list(GET f 3 seed)
  set(extra "")
  list(LENGTH f n)
  if(n GREATER 4)
    list(SUBLIST f 4 -1 options)
    foreach(option IN LISTS options)
      if(option MATCHES "^duration=(.*)$")
        list(APPEND extra --duration "${CMAKE_MATCH_1}")  # a time record's length, s
      elseif(option MATCHES "^draw=(.*)$")
        list(APPEND extra --draw "${CMAKE_MATCH_1}")  # the truth drawn at random from this seed
      elseif(option MATCHES "^averages=(.*)$")
        list(APPEND extra --averages "${CMAKE_MATCH_1}")  # an FRF averaged this many times
      elseif(option STREQUAL "nocoh")
        list(APPEND extra --no-coherence)  # an FRF file without coherence columns
      elseif(option MATCHES "^fs=(.*)$")
        list(APPEND extra --fs "${CMAKE_MATCH_1}")  # a time record's sample rate, Hz
      else()
        list(APPEND extra --set "${option}")
      endif()
    endforeach()
  endif()
  set(file "${WORK_DIR}/data${index}.csv")
  execute_process(COMMAND "${PYTHON}" "${TRUTHGEN}" --example ${example} --case ${case} --kind ${kind} --snr-db 40
                          --seed ${seed} ${extra} -o "${file}"
                  RESULT_VARIABLE status ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "truthgen failed: ${err}")
  endif()
  list(APPEND data_args --data "${file}")
  math(EXPR index "${index} + 1")
endforeach()

execute_process(COMMAND "${MBGEN}" diagnose "${MODEL}" ${data_args} ${DIAGNOSE_ARGS} --json "${WORK_DIR}/diagnosis.json"
                        --report "${WORK_DIR}/report" --extended "${WORK_DIR}/extended.mdl"
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "mbgen diagnose failed (${status}):\n${err}")
endif()
file(READ "${WORK_DIR}/diagnosis.json" json)
string(JSON verdict GET "${json}" verdict)
string(JSON n_selected LENGTH "${json}" selected)
set(selected "")
if(n_selected GREATER 0)
  string(JSON selected GET "${json}" selected 0)
endif()
message(STATUS "verdict ${verdict}, selected '${selected}'\n${out}")
if(EXPECT_VERDICT STREQUAL "not_extended")
  if(verdict STREQUAL "extended")
    message(FATAL_ERROR "a confident wrong extension: ${selected} (expected no extension)")
  endif()
elseif(NOT verdict STREQUAL EXPECT_VERDICT)
  message(FATAL_ERROR "verdict ${verdict}, expected ${EXPECT_VERDICT} (selected '${selected}')")
endif()
if(EXPECT_SELECTED AND NOT selected STREQUAL EXPECT_SELECTED)
  message(FATAL_ERROR "selected '${selected}', expected ${EXPECT_SELECTED}")
endif()
if(verdict STREQUAL "extended" AND NOT EXISTS "${WORK_DIR}/extended.mdl")
  message(FATAL_ERROR "extended, but no extended model was written")
endif()
# -DEXPECT_VARIANT="a|b": the selected candidate's variant (the element an untie frees) must be one of these.
if(EXPECT_VARIANT)
  cmake_policy(SET CMP0057 NEW)  # if(IN_LIST) in script mode
  string(REPLACE "|" ";" EXPECT_VARIANT "${EXPECT_VARIANT}")
  string(JSON n_candidates LENGTH "${json}" candidates)
  math(EXPR last "${n_candidates} - 1")
  set(variant "")
  foreach(i RANGE ${last})
    string(JSON id GET "${json}" candidates ${i} id)
    if(id STREQUAL selected AND variant STREQUAL "")
      string(JSON variant ERROR_VARIABLE no_variant GET "${json}" candidates ${i} variant)
    endif()
  endforeach()
  if(NOT variant IN_LIST EXPECT_VARIANT)
    message(FATAL_ERROR "selected ${selected} with variant '${variant}', expected one of ${EXPECT_VARIANT}")
  endif()
endif()
