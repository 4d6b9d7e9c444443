# A driving point whose phase a passive structure cannot have (docs/diagnosis.md, "The measurement chain"): `fit`
# and `diagnose` say so first, in the summary and the JSON's `warnings`; data with the right sign give no warning.
# Data from the independent truth generator (scripts/truthgen): mdof2, whose d1 sits at F1's point.
# The diagnosis below takes 10-20 s in the normal build and over 120 s under the sanitizers on a slow machine:
# ctest-timeout: 900
include(${CMAKE_CURRENT_LIST_DIR}/cli_support.cmake)

function(truthgen name)
  execute_process(COMMAND /usr/bin/python3 "${SOURCE}/scripts/truthgen/truthgen.py" --example mdof2 --case nominal
                          --kind frf ${ARGN} -o "${WORK}/${name}.csv"
                  RESULT_VARIABLE status ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "truthgen failed: ${err}")
  endif()
endfunction()

truthgen(force_reversed --seed 501 --draw 21 --force-sign -1)
truthgen(sensor_reversed --seed 502 --draw 22 --gain d1=-1)
truthgen(right --seed 503 --draw 23)

expect_run(STATUS 0 STDOUT "^warning: d1/F1 in force_reversed.csv is a driving point \\(d1 at F1's point, along its direction\\), but on (99|100) % of the [0-9]+ lines"
  ARGS fit ${MDOF2} --data force_reversed.csv --starts 2 --json force_reversed.json)
file(READ "${WORK}/force_reversed.json" json)
string(JSON warning GET "${json}" warnings 0)
if(NOT warning MATCHES "the force F1 or the sensor d1 is recorded with the wrong sign")
  message(SEND_ERROR "the fit's JSON does not carry the warning: ${warning}")
endif()
expect_run(STATUS 0 STDOUT "^warning: d1/F1 in sensor_reversed.csv is a driving point"
  ARGS fit ${MDOF2} --data sensor_reversed.csv --starts 2)
expect_run(STATUS 0 STDOUT "^warning: d1/F1 in force_reversed.csv is a driving point" TIMEOUT 600
  ARGS diagnose ${MDOF2} --data force_reversed.csv --starts 2)
execute_process(COMMAND "${MBGEN}" fit ${MDOF2} --data right.csv --starts 2 WORKING_DIRECTORY "${WORK}"
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_QUIET)
if(NOT status EQUAL 0 OR out MATCHES "warning")
  message(SEND_ERROR "data with the right sign: status ${status}, or a warning:\n${out}")
endif()
# A model that declares the reversal itself (an input gain of -1, or a gain filter of -1 on the sensor) expects such
# data: no warning.
file(READ ${MDOF2} mdof2_text)
string(REPLACE "input F1 force on mass1 along x" "input F1 force on mass1 along x gain -1" force_declared "${mdof2_text}")
file(WRITE "${WORK}/force_declared.mdl" "${force_declared}")
file(WRITE "${WORK}/sensor_declared.mdl" "${mdof2_text}\nfilter d1_sign on d1 gain factor -1\n")
foreach(pair "force_declared.mdl;force_reversed.csv" "sensor_declared.mdl;sensor_reversed.csv")
  list(GET pair 0 model)
  list(GET pair 1 data)
  execute_process(COMMAND "${MBGEN}" fit ${model} --data ${data} --starts 2 WORKING_DIRECTORY "${WORK}"
                  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0 OR out MATCHES "warning")
    message(SEND_ERROR "${model} on ${data}, the reversal declared: status ${status}, or a warning:\n${out}${err}")
  endif()
endforeach()
