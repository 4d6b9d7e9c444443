# `fit`'s validation (docs/estimation.md): the residual tests of a record fit, `--validate` on other data (MATLAB's
# compare fit %), and the refusal of validation data that do not fit the model before anything is written.
# Data from the independent truth generator (scripts/truthgen): mdof2 records of 0.5 s and an FRF.
include(${CMAKE_CURRENT_LIST_DIR}/cli_support.cmake)

function(truthgen name case kind seed)
  execute_process(COMMAND /usr/bin/python3 "${SOURCE}/scripts/truthgen/truthgen.py" --example mdof2 --case ${case}
                          --kind ${kind} --seed ${seed} --duration 0.5 -o "${WORK}/${name}.csv"
                  RESULT_VARIABLE status ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "truthgen failed: ${err}")
  endif()
endfunction()

# One truth (the nominal case), three draws of noise and input; the same model with an added mass; a delayed sensor.
truthgen(fitted nominal time 701)
truthgen(other_record nominal time 702)
truthgen(other_frf nominal frf 703)
truthgen(added_mass added_mass time 704)
truthgen(delayed sensor_delay time 705)

expect_run(STATUS 0 ARGS fit ${MDOF2} --data fitted.csv --validate other_record.csv --validate other_frf.csv
  --validate added_mass.csv --json fit.json --report report)
file(READ "${WORK}/fit.json" json)

# The fit's residuals at 40 dB white noise: white and independent of the force, on both outputs.
string(JSON channels LENGTH "${json}" residual_tests channels)
if(NOT channels EQUAL 2)
  message(SEND_ERROR "expected residual tests of 2 outputs, got ${channels}")
endif()
foreach(c 0 1)
  string(JSON white GET "${json}" residual_tests channels ${c} whiteness verdict)
  string(JSON independent GET "${json}" residual_tests channels ${c} inputs F1 verdict)
  if(NOT white STREQUAL "white" OR NOT independent STREQUAL "independent of the input")
    message(SEND_ERROR "residual test ${c} of the nominal fit: ${white}, ${independent}")
  endif()
endforeach()

# Fit % per file and channel: high on the same truth (another record, an FRF), clearly lower with the added mass.
function(fit_percent var file channel)
  string(JSON n LENGTH "${json}" validation)
  math(EXPR last "${n} - 1")
  foreach(i RANGE ${last})
    string(JSON name GET "${json}" validation ${i} file)
    if(name STREQUAL "${file}")
      string(JSON value GET "${json}" validation ${i} fit_percent ${channel})
      set(${var} ${value} PARENT_SCOPE)
      return()
    endif()
  endforeach()
  message(SEND_ERROR "no validation of ${file}")
endfunction()
foreach(check "other_record.csv;d1;90;100" "other_record.csv;d2;90;100" "other_frf.csv;d1/F1;90;100"
              "other_frf.csv;d2/F1;90;100" "added_mass.csv;d1;-1000;70" "added_mass.csv;d2;-1000;70")
  list(GET check 0 file)
  list(GET check 1 channel)
  list(GET check 2 lo)
  list(GET check 3 hi)
  fit_percent(value ${file} ${channel})
  if(NOT value GREATER ${lo} OR NOT value LESS_EQUAL ${hi})
    message(SEND_ERROR "fit % of ${channel} on ${file}: ${value}, expected in (${lo}, ${hi}]")
  endif()
endforeach()

# The report: a section each, with their plots' data and scripts.
file(READ "${WORK}/report/report.md" md)
foreach(expected "## Residual tests" "| `fitted.csv` | d2 | cross-correlation with F1 |" "## Validation on other data"
                 "| `added_mass.csv` | d1 |" "resid1_d1.svg" "validate3_d2.svg" "validate2_d1_F1.svg")
  string(FIND "${md}" "${expected}" at)
  if(at EQUAL -1)
    message(SEND_ERROR "report.md lacks `${expected}`")
  endif()
endforeach()
foreach(f resid1_d1.dat resid1_d1.gp validate1_d1.dat validate2_d2_F1.gp)
  if(NOT EXISTS "${WORK}/report/${f}")
    message(SEND_ERROR "the report lacks ${f}")
  endif()
endforeach()

# A sensor that lags the force by 0.5 ms: its residual is correlated with the input; the other output's is not.
expect_run(STATUS 0 ARGS fit ${MDOF2} --data delayed.csv --json delayed.json)
file(READ "${WORK}/delayed.json" json)
string(JSON output GET "${json}" residual_tests channels 1 output)
string(JSON delayed_verdict GET "${json}" residual_tests channels 1 inputs F1 verdict)
string(JSON other_verdict GET "${json}" residual_tests channels 0 inputs F1 verdict)
if(NOT output STREQUAL "d2" OR NOT delayed_verdict STREQUAL "correlated with the input"
   OR NOT other_verdict STREQUAL "independent of the input")
  message(SEND_ERROR "the delayed sensor's residual tests: ${output}: ${delayed_verdict}; d1: ${other_verdict}")
endif()

# FRF fits have no records: no residual tests in the JSON.
expect_run(STATUS 0 ARGS fit ${MDOF2} --data other_frf.csv --starts 2 --json frf.json)
file(READ "${WORK}/frf.json" json)
string(JSON tests ERROR_VARIABLE missing GET "${json}" residual_tests)
if(NOT missing)
  message(SEND_ERROR "an FRF fit's JSON has residual_tests")
endif()

# Bad validation data: a clear message, status 1, nothing written.
file(WRITE "${WORK}/other_channel.csv" "t,F1,d1,z\n0,1,0,0\n0.001,1,0,0\n")
file(WRITE "${WORK}/malformed.csv" "t,F1,d1,d2\n0,1,0,0\n0.001,1,0\n")
file(WRITE "${WORK}/no_force.csv" "t,d1,d2\n0,0,0\n0.001,0,0\n")
foreach(case "other_channel.csv;other_channel.csv:1:4: error: column 'z' is neither a model input nor output"
             "malformed.csv;malformed.csv:3:4: error: row has 3 fields, the header has 4"
             "no_force.csv;no_force.csv: error: time record lacks model input\\(s\\) F1")
  list(GET case 0 file)
  list(GET case 1 message)
  expect_run(STATUS 1 STDERR "${message}" STDOUT "^$"  # refused before the fit: no summary
    ARGS fit ${MDOF2} --data fitted.csv --validate ${file} --json refused.json --report refused_report)
  if(EXISTS "${WORK}/refused.json" OR EXISTS "${WORK}/refused_report")
    message(SEND_ERROR "--validate ${file}: an output was written")
  endif()
endforeach()

# --residual-lags: longer lags (capped at a quarter of the record) leave the nominal fit white and independent too;
# 0 is a usage error.
expect_run(STATUS 0 STDOUT "residual tests, fitted.csv: d1 white, independent of F1; d2 white, independent of F1;"
  ARGS fit ${MDOF2} --data fitted.csv --residual-lags 5000 --json long.json)
file(READ "${WORK}/long.json" json)
string(JSON lags LENGTH "${json}" residual_tests channels 0 inputs F1 lags)
if(NOT lags EQUAL 1025)  # 2048 samples: L = 512, lags -512..512
  message(SEND_ERROR "--residual-lags 5000 on 2048 samples: ${lags} lags, expected 1025")
endif()
expect_run(STATUS 2 STDERR "--residual-lags" ARGS fit ${MDOF2} --data fitted.csv --residual-lags 0)
