# `mbgen convert` and `mbgen modal --synthesis` (docs/data.md, "Writing data"): measured FRFs written as UFF 58 and
# CSV and read back, checked by hand (convert_check.py parses the CSV files with numpy), on data from the truth
# generator and on the real UFF files of tests/data/uff and examples/beam.
include(${CMAKE_CURRENT_LIST_DIR}/cli_support.cmake)

set(CHECK /usr/bin/python3 "${CMAKE_CURRENT_LIST_DIR}/convert_check.py")
function(check what)
  execute_process(COMMAND ${CHECK} ${ARGN} WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE status OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(SEND_ERROR "${what}:\n${out}${err}")
  endif()
endfunction()

# mdof2's FRFs with coherence and a `# set` line, from the independent truth generator (8 significant digits).
execute_process(COMMAND /usr/bin/python3 ${SOURCE}/scripts/truthgen/truthgen.py --example mdof2 --case nominal
                        --kind frf --set k12=130000 --f-min 10 --f-max 400 --df 0.5 -o truth.csv
                WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "truthgen failed")
endif()

# CSV -> UFF -> CSV: UFF 58 holds 13 significant digits, the truth's 8 come back bit for bit, coherence and the `set`
# value with them (in the mapping file).
expect_run(STATUS 0 ARGS convert truth.csv -o truth.uff)
expect_run(STATUS 0 ARGS convert truth.uff -o back.csv)
check("CSV -> UFF -> CSV changed the numbers" same truth.csv back.csv 17)
file(READ "${WORK}/truth.uff.map" map)
if(NOT map MATCHES "\nset k12=130000\n1:[+]X = d1\n1001:[+]X = F1\n2:[+]X = d2\n")
  message(SEND_ERROR "truth.uff.map lacks the set value or the default points:\n${map}")
endif()
file(READ "${WORK}/truth.uff" uff)
string(REGEX MATCHALL "\n    6         0    0         0 mbgen" coherences "${uff}")
list(LENGTH coherences n)
if(NOT n EQUAL 2)
  message(SEND_ERROR "truth.uff holds ${n} coherence records (function type 6), not 2")
endif()
# Deterministic.
expect_run(STATUS 0 ARGS convert truth.csv -o truth_again.uff)
foreach(f truth.uff truth.uff.map)
  string(REPLACE "truth" "truth_again" again "${f}")
  file(SHA256 "${WORK}/${f}" first)
  file(SHA256 "${WORK}/${again}" second)
  if(NOT first STREQUAL second)
    message(SEND_ERROR "convert is not deterministic: ${f}")
  endif()
endforeach()

# What convert writes, converted again, is the same file: its points come back from its mapping file, its `set` value
# and coherence with them.
expect_run(STATUS 0 ARGS convert truth.uff -o truth_twice.uff)
foreach(f truth.uff truth.uff.map)
  string(REPLACE "truth" "truth_twice" twice "${f}")
  file(SHA256 "${WORK}/${f}" first)
  file(SHA256 "${WORK}/${twice}" second)
  if(NOT first STREQUAL second)
    message(SEND_ERROR "UFF -> UFF is not a fixed point: ${f} and ${twice} differ")
  endif()
endforeach()

# Lines that record 7's minimum and increment cannot give back bit for bit (0.1 Hz apart, or uneven) are written with
# each point, and come back so.
file(WRITE "${WORK}/uneven.csv" "f_hz,y/F.re,y/F.im\n0.1,1.5,-2.25\n0.2,3,1e-300\n0.3,-4.125,0.5\n0.45,7,8\n1e3,9,-1\n")
file(WRITE "${WORK}/tenth.csv" "f_hz,y/F.re,y/F.im\n0.1,1,2\n0.2,3,4\n0.3,5,6\n0.4,7,8\n")
foreach(name uneven tenth)
  expect_run(STATUS 0 ARGS convert ${name}.csv -o ${name}.uff)
  expect_run(STATUS 0 ARGS convert ${name}.uff -o ${name}_back.csv)
  check("${name} lines: CSV -> UFF -> CSV changed the numbers" same ${name}.csv ${name}_back.csv 17)
  file(READ "${WORK}/${name}.uff" uff)
  if(NOT uff MATCHES "\n         6         [45]         0  0.00000E[+]00  0.00000E[+]00")
    message(SEND_ERROR "${name}.uff: the lines are not written with each point (record 7 spacing 0)")
  endif()
endforeach()

# With the model: its sensor points (d1 and d2 on distinct bodies, along x), its input at 1001, its outputs'
# quantity (displacement, record 9 type 8); channels checked as fit checks them.
expect_run(STATUS 0 ARGS convert truth.csv --model ${MDOF2} -o model.uff)
file(READ "${WORK}/model.uff" uff)
if(NOT uff MATCHES "\n         8    0    0    0 displacement ")
  message(SEND_ERROR "convert --model did not write the outputs' quantity (displacement, type 8)")
endif()
expect_run(STATUS 0 ARGS convert model.uff -o model.csv)
check("CSV -> UFF (--model) -> CSV changed the numbers" same truth.csv model.csv 17)
write_model(other)
expect_run(STATUS 1 STDERR "truth.csv.*'d1' is not a model output" ARGS convert truth.csv --model other.mdl -o x.uff)

# The real FRF files: UFF -> UFF -> read gives the values the original gives, to the last bit (both read as CSV,
# which writes the shortest text of each double), and modal finds the same modes in the converted file.
foreach(real ${SOURCE}/examples/beam/measurement.uff ${SOURCE}/tests/data/uff/non_ascii_header.uff)
  get_filename_component(name "${real}" NAME_WE)
  expect_run(STATUS 0 ARGS convert ${real} -o ${name}_original.csv)
  expect_run(STATUS 0 ARGS convert ${real} -o ${name}.uff)
  expect_run(STATUS 0 ARGS convert ${name}.uff -o ${name}_converted.csv)
  check("${name}: UFF -> UFF changed the values" same ${name}_original.csv ${name}_converted.csv 17)
endforeach()
file(READ "${WORK}/measurement.uff" uff)
if(NOT uff MATCHES "\n        12    0    0    0 acceleration ")
  message(SEND_ERROR "the beam's accelerance (record 9 type 12) was not kept")
endif()
expect_run(STATUS 0 ARGS modal --data ${SOURCE}/examples/beam/measurement.uff --json beam.json)
expect_run(STATUS 0 ARGS modal --data measurement.uff --json beam_converted.json)
check("modal found other modes in the converted beam FRFs" same-modes beam.json beam_converted.json 0)
# The CSV copy of the beam data (no quantity) as UFF, declared accelerance: modal reads the quantity from the file.
expect_run(STATUS 0 ARGS convert ${SOURCE}/examples/beam/frf_beam_3pt.csv --quantity accelerance -o beam3.uff)
expect_run(STATUS 0 ARGS modal --data ${SOURCE}/examples/beam/frf_beam_3pt.csv --quantity accelerance --json b1.json)
expect_run(STATUS 0 ARGS modal --data beam3.uff --json b2.json STDOUT "accelerance")
check("modal found other modes in the beam CSV converted to UFF" same-modes b1.json b2.json 0)

# Two FRF files with the same lines are joined; a time record converts CSV -> CSV.
execute_process(COMMAND /usr/bin/python3 -c "
lines = open('truth.csv').read().splitlines()
for name, columns in (('half_d1.csv', range(0, 4)), ('half_d2.csv', [0, 4, 5, 6])):
    with open(name, 'w') as f:
        for line in lines:
            f.write((line if line.startswith('#') else ','.join(line.split(',')[c] for c in columns)) + '\\n')"
                WORKING_DIRECTORY "${WORK}")
expect_run(STATUS 0 ARGS convert half_d1.csv half_d2.csv -o joined.csv)
check("two FRF files joined are not the file they were cut from" same truth.csv joined.csv 17)
expect_run(STATUS 1 STDERR "truth.csv: error: the FRF d1/F1 is in half_d1.csv already"
           ARGS convert half_d1.csv truth.csv -o x.uff)
expect_run(STATUS 1 STDERR "truth.csv: error: the FRF d1/F1 is in half_d1.csv already"
           ARGS convert half_d2.csv half_d1.csv truth.csv -o x.uff)
# The points: the default ones in order of appearance (d2 first here), the model's sensor points with --model.
expect_run(STATUS 0 ARGS convert half_d2.csv half_d1.csv -o reversed.uff)
file(READ "${WORK}/reversed.uff.map" map)
if(NOT map MATCHES "\n1:[+]X = d2\n1001:[+]X = F1\n2:[+]X = d1\n$")
  message(SEND_ERROR "reversed.uff.map: not the default points in order of appearance:\n${map}")
endif()
expect_run(STATUS 0 ARGS convert half_d2.csv half_d1.csv --model ${MDOF2} -o reversed_model.uff)
file(READ "${WORK}/reversed_model.uff.map" map)
if(NOT map MATCHES "\n2:[+]X = d2\n1001:[+]X = F1\n1:[+]X = d1\n$")
  message(SEND_ERROR "reversed_model.uff.map: not the model's sensor points (d1 node 1, d2 node 2):\n${map}")
endif()
# Two outputs at one place along one axis are one UFF point: refused, naming both.
write_model(two_at_one "output a acceleration of b along x")
file(WRITE "${WORK}/two_at_one.csv" "f_hz,y/F.re,y/F.im,a/F.re,a/F.im\n1,1,2,3,4\n2,5,6,7,8\n")
expect_run(STATUS 1 STDERR "two_at_one.csv: error: the channels `y` and `a` would both be the UFF point 1:[+]X"
           ARGS convert two_at_one.csv --model two_at_one.mdl -o x.uff)
expect_run(STATUS 0 ARGS convert two_at_one.csv -o two_at_one.uff)
execute_process(COMMAND /usr/bin/python3 ${SOURCE}/scripts/truthgen/truthgen.py --example mdof2 --case nominal
                        --kind time --duration 0.25 -o time.csv WORKING_DIRECTORY "${WORK}")
expect_run(STATUS 0 ARGS convert time.csv -o time_back.csv)
execute_process(COMMAND /usr/bin/python3 -c "
import numpy as np, sys
a = np.loadtxt('time.csv', delimiter=',', comments='#', skiprows=2)
b = np.loadtxt('time_back.csv', delimiter=',', comments='#', skiprows=1)
sys.exit(0 if a.shape == b.shape and np.array_equal(a, b) else 1)" WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE differ)
if(differ)
  message(SEND_ERROR "time record CSV -> CSV changed the numbers")
endif()

# `# time=` and `# condition` lines (monitor's) go with a CSV, not into UFF, which cannot carry them: a warning.
file(WRITE "${WORK}/stamped.csv" "# time=2026-03-07T08:00:00Z\n# condition temperature=21.5\nf_hz,y/F.re,y/F.im\n1,1,2\n2,3,4\n")
expect_run(STATUS 0 ARGS convert stamped.csv -o stamped_back.csv STDERR "^$")
file(READ "${WORK}/stamped_back.csv" text)
if(NOT text STREQUAL "# time=2026-03-07T08:00:00Z\n# condition temperature=21.5\nf_hz,y/F.re,y/F.im\n1,1,2\n2,3,4\n")
  message(SEND_ERROR "stamped.csv -> CSV lost its time or condition:\n${text}")
endif()
expect_run(STATUS 0 ARGS convert stamped.csv -o stamped.uff
           STDERR "^warning: UFF 58 carries no `# time=` or `# condition` line: stamped.uff goes without them")
file(WRITE "${WORK}/stamped2.csv" "# time=2026-03-08\nf_hz,z/F.re,z/F.im\n1,1,2\n2,3,4\n")
expect_run(STATUS 1 STDERR "stamped2.csv: error: its `# time=` or `# condition` lines differ from those of stamped.csv"
           ARGS convert stamped.csv stamped2.csv -o x.csv)

# Refusals: a clear message, nothing written.
tree_state(before "${WORK}")
expect_run(STATUS 2 STDERR "-o: the name says the format: OUT.uff or OUT.unv [(]UFF 58[)] or OUT.csv, got `x.txt`"
           ARGS convert truth.csv -o x.txt)
expect_run(STATUS 1 STDERR "time.csv: error: a time record is written as CSV only" ARGS convert time.csv -o x.uff)
expect_run(STATUS 1 STDERR "truth.csv: error: its frequency lines differ from those of .*frf_F1.csv"
           ARGS convert ${MDOF2_FRF} truth.csv -o x.csv)
expect_run(STATUS 1 STDERR "a time record is converted alone" ARGS convert time.csv truth.csv -o x.csv)
expect_run(STATUS 2 STDERR "--set: needs --model" ARGS convert truth.csv --set k12=1 -o x.uff)
expect_run(STATUS 2 STDERR "--quantity: only for a UFF output" ARGS convert truth.csv --quantity mobility -o x.csv)
expect_run(STATUS 2 ARGS convert truth.csv -o truth.csv)
expect_run(STATUS 2 STDERR "input" ARGS convert truth.uff -o truth.uff)
file(WRITE "${WORK}/bad name.csv" "f_hz,a b/F.re,a b/F.im\n1,1,0\n2,1,0\n")
tree_state(before "${WORK}")
expect_run(STATUS 1 STDERR "the channel name `a b` cannot stand in a UFF mapping file" ARGS convert "bad name.csv" -o x.uff)
expect_unchanged("${before}" "${WORK}" "refused conversions")
expect_no_temporaries("${WORK}")

# modal --synthesis: the synthesized FRFs are those channel_error compares with the data (recomputed here from the
# written CSV and the measured CSV), the UFF copy holds them to its 13 digits, and modal finds the same modes in it.
expect_run(STATUS 0 ARGS modal --data truth.csv --band 20:390 --json modal.json --synthesis synth.csv)
check("the written synthesis is not what channel_error measures" channel-error truth.csv synth.csv modal.json)
expect_run(STATUS 0 ARGS modal --data truth.csv --band 20:390 --synthesis synth.uff)
expect_run(STATUS 0 ARGS convert synth.uff -o synth_back.csv)
check("the UFF synthesis differs from the CSV one" same synth.csv synth_back.csv 13)
file(READ "${WORK}/synth.uff.map" map)
if(NOT map MATCHES "\n1:[+]X = d1\n1001:[+]X = F1\n2:[+]X = d2\n$")
  message(SEND_ERROR "synth.uff.map does not name the measured channels:\n${map}")
endif()
expect_run(STATUS 0 ARGS modal --data synth.uff --json modal_synth.json)
check("modal on the written synthesis found other modes" same-modes modal.json modal_synth.json 0.001)
expect_run(STATUS 2 STDERR "--synthesis: the name says the format" ARGS modal --data truth.csv --synthesis s.txt)
expect_run(STATUS 2 STDERR "--synthesis: not with --output-only" ARGS modal --data time.csv --output-only --synthesis s.csv)
