# Exit statuses (docs/cli.md): usage errors 2, bad input 1 with the file (and line and column) named; `diagnose -`
# reads the model from standard input; a byte order mark is not an error; JSON output stays valid UTF-8.
include(${CMAKE_CURRENT_LIST_DIR}/cli_support.cmake)
write_model(m)

expect_run(STATUS 2 STDERR "--set: m1=abc: the value must be a decimal number" ARGS inspect m.mdl --set m1=abc)
expect_run(STATUS 2 STDERR "--set: m1=abc" ARGS ${FAST_FIT} --set m1=abc)

write_model(zz "param z = 0^0")
expect_run(STATUS 1 STDERR "^zz.mdl:9:12: error: `0\\^0`: 0\\^0 is undefined" ARGS inspect zz.mdl)
string(REPEAT "0" 309 zeros)
write_model(range "param r = 1 in [0, 1${zeros}]")
expect_run(STATUS 1 STDERR "^range.mdl:9:20: error: the bound `1${zeros}` of `r` is beyond the range of a double"
  ARGS inspect range.mdl)

file(MAKE_DIRECTORY "${WORK}/adir")
expect_run(STATUS 1 STDERR "^adir: error: is a directory, not a data file" ARGS fit one.mdl --data adir --starts 1)

# `diagnose -`: the model comes from standard input (it used to fail opening a file named `-`); here the data is
# bad, so the run stops at reading it, after the model was read.
file(WRITE "${WORK}/bad.csv" "f_hz,d1/F1.re\n10,x\n")
execute_process(COMMAND "${MBGEN}" diagnose - --data bad.csv WORKING_DIRECTORY "${WORK}" INPUT_FILE "${MDOF2}"
  RESULT_VARIABLE status ERROR_VARIABLE err OUTPUT_QUIET TIMEOUT 60)
if(NOT status EQUAL 1 OR NOT err MATCHES "^bad.csv:2:2: error: 'x' is not a number")
  message(SEND_ERROR "diagnose - with bad data: status ${status}, stderr: ${err}")
endif()

# A UTF-8 byte order mark before a model or a data file is skipped.
string(ASCII 239 187 191 bom)
file(READ "${WORK}/m.mdl" text)
file(WRITE "${WORK}/bom.mdl" "${bom}${text}")
expect_run(STATUS 0 ARGS inspect bom.mdl)
file(READ "${WORK}/one_frf.csv" frf)
file(WRITE "${WORK}/bom.csv" "${bom}${frf}")
expect_run(STATUS 0 ARGS fit one.mdl --data bom.csv --starts 1)

# A data file name that is not UTF-8 (Latin-1 "é"): the JSON result is still valid UTF-8, the name with U+FFFD.
string(ASCII 233 latin1)
file(COPY_FILE "${WORK}/one_frf.csv" "${WORK}/d${latin1}.csv")
file(COPY_FILE "${WORK}/one.mdl" "${WORK}/m${latin1}.mdl")
expect_run(STATUS 0 STDOUT "\"d�.csv\"" ARGS fit one.mdl --data "d${latin1}.csv" --starts 1 --json -)
expect_run(STATUS 0 STDOUT "\"d�.csv\"" ARGS modal --data "d${latin1}.csv" --json -)
expect_run(STATUS 0 STDOUT "\"m�.mdl\"" ARGS sensitivity "m${latin1}.mdl" --json -)

# A valid model the numeric evaluator cannot run (a parameter in an exponent) is the model's limit, status 1 with the
# file named; it was reported as a bare exception message.
file(WRITE "${WORK}/power.mdl" "model power\nparam a = 2\nparam m1 = a^a\nground g\nbody b { mass m1; dof x }\n"
           "spring s { from g; to b; along x; stiffness 1000 }\ninput F force on b along x\n"
           "output y displacement of b along x\n")
expect_run(STATUS 1 STDERR "^power.mdl: error: cannot fit or simulate this model: a power whose exponent depends"
  ARGS fit power.mdl --data one_frf.csv --starts 1)

# A named method that cannot use the data is bad input (status 1, naming the file), not a usage error.
expect_run(STATUS 1 STDERR "^one_frf.csv: error: --method time-output-error needs time records"
  ARGS ${FAST_FIT} --method time-output-error)
file(WRITE "${WORK}/rec.csv" "t,F,y\n0,1,0\n0.001,1,0.0001\n0.002,1,0.0002\n0.003,1,0.0003\n")
expect_run(STATUS 1 STDERR "^rec.csv: error: --method frf-output-error needs FRF data"
  ARGS fit one.mdl --data rec.csv --starts 1 --method frf-output-error)
# The refusal names the methods that take the data given (the method table, mbgen/methods/method_table.hpp).
expect_run(STATUS 1 STDERR "needs FRF data, but this is a time record\nnote: methods that take time records: auto, time-output-error, direct, two-step, hybrid, ekf, arx-two-stage or eiv\n"
  ARGS fit one.mdl --data rec.csv --starts 1 --method frf-output-error)
expect_run(STATUS 1 STDERR "^one_frf.csv: error: --method ekf needs time records \\(sampled inputs and outputs\\), but this file holds FRFs\nnote: methods that take FRFs: auto, frf-output-error, direct, two-step, hybrid or modal\n"
  ARGS ${FAST_FIT} --method ekf)

# A UFF file read from standard input or under another name: the FRFs' quantity is still the one its records declare.
# It was taken from the records only for a name ending in .uff (by reading the file again), so the beam came out
# "unknown" there, with other modes and std than from measurement.uff.
set(beam "${SOURCE}/examples/beam/measurement.uff")
execute_process(COMMAND "${MBGEN}" modal --data - --json - WORKING_DIRECTORY "${WORK}" INPUT_FILE "${beam}"
  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_QUIET TIMEOUT 60)
if(NOT status EQUAL 0 OR NOT out MATCHES "\"quantity\": \"accelerance\"")
  message(SEND_ERROR "modal --data - < measurement.uff: status ${status}, not accelerance")
endif()
file(COPY_FILE "${beam}" "${WORK}/beam.dat")
expect_run(STATUS 0 STDOUT "\"quantity\": \"accelerance\"" ARGS modal --data beam.dat --json -)
