# `mbgen export` (docs/interfaces.md, "mbgen-export/1"): the model's numbers for another tool, checked against each
# other by hand (export_check.py, numpy), read back by mbgen itself (the FRF CSV), at a fit's estimate, and refused
# with a clear message where the request cannot be met.
include(${CMAKE_CURRENT_LIST_DIR}/cli_support.cmake)

foreach(what matrices state-space modes)
  expect_run(STATUS 0 ARGS export ${MDOF2} --what ${what} -o ${what}.json)
endforeach()
expect_run(STATUS 0 ARGS export ${MDOF2} --what frf --frf 10:400:40 -o frf.json)
# The same as MATLAB .mat files (libmatio), which export_check.py reads back with scipy and compares with the JSON.
foreach(what matrices state-space modes)
  expect_run(STATUS 0 ARGS export ${MDOF2} --what ${what} --format mat -o ${what}.mat)
endforeach()
expect_run(STATUS 0 ARGS export ${MDOF2} --what frf --frf 10:400:40 --format mat -o frf.mat)
expect_run(STATUS 0 ARGS export ${MDOF2} --what frf --frf 10:400:40 --format mat -o frf_again.mat)
file(SHA256 "${WORK}/frf.mat" first)
file(SHA256 "${WORK}/frf_again.mat" second)
if(NOT first STREQUAL second)
  message(SEND_ERROR "export --format mat is not deterministic")
endif()
execute_process(COMMAND /usr/bin/python3 "${CMAKE_CURRENT_LIST_DIR}/export_check.py" matrices.json state-space.json
                        modes.json frf.json matrices.mat state-space.mat modes.mat frf.mat
                WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(SEND_ERROR "export's numbers disagree with each other:\n${out}${err}")
endif()
file(READ "${WORK}/matrices.json" json)
string(JSON m11 GET "${json}" M 0 0)
string(JSON m22 GET "${json}" M 1 1)
if(NOT m11 EQUAL 1.39 OR NOT m22 EQUAL 1.09)
  message(SEND_ERROR "M's diagonal is ${m11}, ${m22}, not the model's masses 1.39, 1.09")
endif()

# The FRF CSV is the layout mbgen reads: modal analysis of it finds the model's modes, and the same request gives the
# same bytes.
expect_run(STATUS 0 ARGS export ${MDOF2} --what frf --frf 60:200:2801 --format csv -o frf.csv)
expect_run(STATUS 0 ARGS export ${MDOF2} --what frf --frf 60:200:2801 --format csv -o frf_again.csv)
file(SHA256 "${WORK}/frf.csv" first)
file(SHA256 "${WORK}/frf_again.csv" second)
if(NOT first STREQUAL second)
  message(SEND_ERROR "export is not deterministic")
endif()
expect_run(STATUS 0 ARGS modal --data frf.csv --json modal.json)
file(READ "${WORK}/modal.json" json)
file(READ "${WORK}/modes.json" model_json)
foreach(k 0 1)
  string(JSON identified GET "${json}" modes ${k} f_hz)
  string(JSON expected GET "${model_json}" modes ${k} f_hz)
  math(EXPR dummy "0")
  execute_process(COMMAND /usr/bin/python3 -c "import sys; a, b = float(sys.argv[1]), float(sys.argv[2]); sys.exit(abs(a / b - 1) > 1e-3)"
                          ${identified} ${expected} RESULT_VARIABLE far)
  if(far)
    message(SEND_ERROR "modal on the exported FRFs found ${identified} Hz, the model's mode is at ${expected} Hz")
  endif()
endforeach()

# UFF 58 with its mapping file: modal finds the same modes in it, and fit reads its channels by the model's names.
expect_run(STATUS 0 ARGS export ${MDOF2} --what frf --frf 60:200:2801 --format uff -o frf.uff)
if(NOT EXISTS "${WORK}/frf.uff.map")
  message(SEND_ERROR "export --format uff wrote no mapping file beside the UFF file")
endif()
expect_run(STATUS 0 ARGS modal --data frf.uff --json modal_uff.json)
file(READ "${WORK}/modal_uff.json" json)
foreach(k 0 1)
  string(JSON identified GET "${json}" modes ${k} f_hz)
  string(JSON expected GET "${model_json}" modes ${k} f_hz)
  execute_process(COMMAND /usr/bin/python3 -c "import sys; a, b = float(sys.argv[1]), float(sys.argv[2]); sys.exit(abs(a / b - 1) > 1e-3)"
                          ${identified} ${expected} RESULT_VARIABLE far)
  if(far)
    message(SEND_ERROR "modal on the exported UFF found ${identified} Hz, the model's mode is at ${expected} Hz")
  endif()
endforeach()
expect_run(STATUS 0 ARGS fit ${MDOF2} --data frf.uff --starts 1 --json fit_uff.json)
file(READ "${WORK}/fit_uff.json" json)
string(JSON nrmse GET "${json}" fit nrmse)
if(nrmse GREATER 1e-6)
  message(SEND_ERROR "the model fitted to its own exported UFF FRFs leaves nrmse ${nrmse}")
endif()

# At a fit's estimate.
expect_run(STATUS 0 ARGS fit ${MDOF2} --data ${MDOF2_FRF} --starts 2 --json fit.json)
expect_run(STATUS 0 ARGS export ${MDOF2} --fit-result fit.json -o at_fit.json)
file(READ "${WORK}/fit.json" fit)
file(READ "${WORK}/at_fit.json" exported)
foreach(p m1 k12 c22)
  string(JSON fitted GET "${fit}" parameters ${p} value)
  string(JSON value GET "${exported}" parameters ${p})
  if(NOT fitted EQUAL value)
    message(SEND_ERROR "--fit-result: ${p} is ${value}, the fit's estimate ${fitted}")
  endif()
endforeach()

# Modes as UFF 55 at the sensor points (with UFF 15 nodes), and the modes `modal --uff` identifies in the exported UFF
# FRFs: both checked by a reader written from the specification (uff55_check.py) against the JSON modes.
expect_run(STATUS 0 ARGS export ${MDOF2} --what modes --format uff -o modes.uff)
expect_run(STATUS 0 ARGS export ${MDOF2} --what modes --format uff -o modes_again.uff)
file(SHA256 "${WORK}/modes.uff" first)
file(SHA256 "${WORK}/modes_again.uff" second)
if(NOT first STREQUAL second)
  message(SEND_ERROR "export --what modes --format uff is not deterministic")
endif()
file(READ "${WORK}/modes.uff.map" map)
if(NOT map MATCHES "\n1:[+]X = d1\n2:[+]X = d2\n")
  message(SEND_ERROR "modes.uff.map does not name the points d1 and d2:\n${map}")
endif()
expect_run(STATUS 0 ARGS modal --data frf.uff --uff modal_modes.uff)
file(READ "${WORK}/modal_modes.uff.map" map)
if(NOT map MATCHES "\n1:[+]X = d1\n2:[+]X = d2\n")
  message(SEND_ERROR "modal --uff's map does not keep the points of frf.uff.map:\n${map}")
endif()
execute_process(COMMAND /usr/bin/python3 "${CMAKE_CURRENT_LIST_DIR}/uff55_check.py" matrices.json modes.json modes.uff
                        modal_modes.uff
                WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(SEND_ERROR "UFF 55 modes disagree with the JSON modes:\n${out}${err}")
endif()
# A UFF file without a mapping names its points by the 58 headers (node1:+X, ...), and its nodes (dataset 15, here
# before the FRFs) go with the modes: the two response nodes, not the reference node 1001.
file(READ "${WORK}/frf.uff" frfs)
set(nodes "    -1\n    15\n")
foreach(node 1 2 1001)
  string(APPEND nodes "         ${node}         0         0         0  0.00000E+00  ${node}.00000E+00  0.00000E+00\n")
endforeach()
file(WRITE "${WORK}/bare.uff" "${nodes}    -1\n${frfs}")
expect_run(STATUS 0 ARGS modal --data bare.uff --uff bare_modes.uff)
file(READ "${WORK}/bare_modes.uff.map" map)
if(NOT map MATCHES "\n1:[+]X = node1:[+]X\n2:[+]X = node2:[+]X\n$")
  message(SEND_ERROR "modal --uff on UFF FRFs without a mapping: the points are not the headers' nodes:\n${map}")
endif()
file(READ "${WORK}/bare_modes.uff" modes)
if(NOT modes MATCHES "^    -1\n    15 *\n         1         0         0         0  0.00000E[+]00  1.00000E[+]00[^\n]*\n         2 [^\n]*\n    -1\n    -1\n    55")
  message(SEND_ERROR "modal --uff did not carry the data's nodes 1 and 2 (dataset 15) before the modes")
endif()
# Trace lines (dataset 82) in the data are kept as geometry: modal --uff writes those between the nodes it writes
# (1-2, as read), not those to a node it does not write (the reference node 1001), byte for byte as they were.
set(trace "    -1\n    82                                                                          \n         1         2         0\nsensors\n         1         2\n    -1\n")
set(to_reference "    -1\n    82                                                                          \n         2         2         0\nforce\n         2      1001\n    -1\n")
file(WRITE "${WORK}/traced.uff" "${nodes}    -1\n${trace}${to_reference}${frfs}")
expect_run(STATUS 0 ARGS modal --data traced.uff --uff traced_modes.uff)
file(READ "${WORK}/traced_modes.uff" modes)
if(NOT modes MATCHES "^    -1\n    15 *\n[^-]*    -1\n    -1\n    82 *\n         1         2         0\nsensors *\n         1         2\n    -1\n    -1\n    55")
  message(SEND_ERROR "modal --uff did not keep the data's trace line 1-2 (dataset 82) after the nodes:\n${modes}")
endif()
if(modes MATCHES "\nforce *\n")
  message(SEND_ERROR "modal --uff wrote a trace line to the reference node 1001, which it writes no node for")
endif()
# frame3's storeys in a chain (columns 1-2 and 2-3; column 1 goes to the floor, which has no node): two lines.
expect_run(STATUS 0 ARGS export ${SOURCE}/examples/frame3/frame3.mdl --what modes --format uff -o frame3.uff)
file(READ "${WORK}/frame3.uff" modes)
if(NOT modes MATCHES "    -1\n    82 *\n         1         2         0\n[^\n]*\n         1         2\n    -1\n    -1\n    82 *\n         2         2         0\n[^\n]*\n         2         3\n    -1\n    -1\n    55")
  message(SEND_ERROR "export frame3 modes: not the trace lines 1-2 and 2-3 of its columns:\n${modes}")
endif()
# CSV FRFs name no points: modal places them by the model's sensor points, or refuses naming the output.
expect_run(STATUS 0 ARGS modal --data frf.csv --model ${MDOF2} --uff modal_csv.uff)
expect_run(STATUS 1 STDERR "frf.csv: error: --uff: the output `d1` has no UFF node and direction"
  ARGS modal --data frf.csv --uff refused.uff)
if(EXISTS "${WORK}/refused.uff" OR EXISTS "${WORK}/refused.uff.map")
  message(SEND_ERROR "a refused modal --uff left a file behind")
endif()
# Sensor points: one node per place (frame and point) with its coordinates, the direction from the axis (-Y for a
# sensor along (0, -1, 0)); two sensors at one place share its node.
write_model(placed "output y2 displacement of b at (0.5, 0.25, -1) along (0, -1, 0)"
  "output y3 acceleration of b at (0.5, 0.25, -1) along z")
expect_run(STATUS 0 ARGS export placed.mdl --what modes --format uff -o placed.uff)
file(READ "${WORK}/placed.uff.map" map)
if(NOT map MATCHES "\n1:[+]X = y\n2:-Y = y2\n2:[+]Z = y3\n$")
  message(SEND_ERROR "placed.uff.map: the sensor points are not nodes 1 and 2 with their axes:\n${map}")
endif()
file(READ "${WORK}/placed.uff" placed)
if(NOT placed MATCHES "\n         2         0         0         0  5.00000E-01  2.50000E-01 -1.00000E[+]00\n")
  message(SEND_ERROR "placed.uff: node 2 is not at (0.5, 0.25, -1):\n${placed}")
endif()
# No outputs, no points to write modes at.
file(WRITE "${WORK}/blind.mdl" "model blind\nparam m1 = 2\nparam k = 1000; param c = 1\nground g\nbody b { mass m1; dof x }\n"
  "spring s { from g; to b; along x; stiffness k; damping c }\ninput F force on b along x\n")
expect_run(STATUS 1 STDERR "blind.mdl: error: UFF modes are written at the model's outputs.*it has none"
  ARGS export blind.mdl --what modes --format uff -o blind.uff)
# A sensor along no global axis has no place in dataset 55.
write_model(oblique "output y2 displacement of b along (1, 1, 0)")
expect_run(STATUS 1 STDERR "oblique.mdl:9:.*output `y2` measures along a direction that is not a global axis"
  ARGS export oblique.mdl --what modes --format uff -o oblique.uff)

# Refusals.
expect_run(STATUS 2 STDERR "-o: a .mat file is binary: name a file" ARGS export ${MDOF2} --format mat)
expect_run(STATUS 2 STDERR "--what frf needs the grid: --frf LO:HI:N" ARGS export ${MDOF2} --what frf)
expect_run(STATUS 2 STDERR "--frf: expected LO:HI:N" ARGS export ${MDOF2} --what frf --frf 10:5:3)
expect_run(STATUS 2 STDERR "--format: csv holds one table" ARGS export ${MDOF2} --format csv)
expect_run(STATUS 2 STDERR "--format: uff holds FRFs \\(--what frf, UFF 58\\) or modes" ARGS export ${MDOF2} --format uff
  -o m.uff)
expect_run(STATUS 2 STDERR "-o: a UFF file comes with its mapping file" ARGS export ${MDOF2} --what frf --frf 10:20:3
  --format uff)
expect_run(STATUS 1 STDERR "matrices.json: .*not a fit result" ARGS export ${MDOF2} --fit-result matrices.json)
file(WRITE "${WORK}/other.json" "{\"schema\": \"mbgen-fit/1\", \"parameters\": {\"nosuch\": {\"value\": 1}}}")
expect_run(STATUS 1 STDERR "other.json: .*parameter `nosuch` of the fit result is not in the model"
  ARGS export ${MDOF2} --fit-result other.json)
