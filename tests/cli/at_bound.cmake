# A parameter the data pull beyond its bound is reported at the bound, said to be so, and without a std, wherever
# it shows (docs/estimation.md, "Parameters at a bound"): `mbgen fit`'s summary, its JSON and report, and `mbgen
# monitor`'s JSON and report. (The diagnosis writes it as the fit's JSON does: its tests' spindle base-mode case has
# k_hby at its upper bound.) The data: one_frf.csv, made with m1 = 2.3; the model allows m1 up to 2.
include(${CMAKE_CURRENT_LIST_DIR}/cli_support.cmake)
file(WRITE "${WORK}/bounded.mdl"
  "model one\nparam m1 = 1.5 \"kg\" estimate in [0.5, 2]\nparam k = 900 \"N/m\" estimate in [0, 1e6]\n"
  "param c = 1 \"N s/m\"\nground g\nbody b { mass m1; dof x }\n"
  "spring s { from g; to b; along x; stiffness k; damping c }\n"
  "input F force on b along x\noutput y displacement of b along x\n")

# Checks one parameter entry of a JSON document: at the upper bound 2, std null, not identifiable.
function(expect_at_upper_bound json what)
  string(JSON side ERROR_VARIABLE e GET "${json}" ${ARGN} at_bound)
  string(JSON std_type ERROR_VARIABLE e2 TYPE "${json}" ${ARGN} std)
  string(JSON value ERROR_VARIABLE e3 GET "${json}" ${ARGN} value)
  if(NOT side STREQUAL "upper" OR NOT std_type STREQUAL "NULL" OR NOT value EQUAL 2)
    message(SEND_ERROR "${what}: m1 should be at its upper bound 2 with a null std; at_bound `${side}`, std ${std_type}, value ${value}")
  endif()
endfunction()

expect_run(STATUS 0 STDOUT "\nm1 +1\\.5 +2 +- +at its upper bound: the data pull it beyond; no std\n"
  ARGS fit bounded.mdl --data one_frf.csv --starts 2 --json fit.json --report fit-report)
file(READ "${WORK}/fit.json" json)
expect_at_upper_bound("${json}" "fit JSON" parameters m1)
string(JSON identifiable GET "${json}" parameters m1 identifiable)
string(JSON k_std_type TYPE "${json}" parameters k std)
if(identifiable OR NOT k_std_type STREQUAL "NUMBER")
  message(SEND_ERROR "fit JSON: m1 identifiable `${identifiable}` (should be false), k's std ${k_std_type} (should be a number)")
endif()
file(READ "${WORK}/fit-report/report.md" md)
if(NOT md MATCHES "\n\\| m1 \\| 1\\.5 \\| 2 \\| — \\| — \\| \\*\\*no\\*\\*: at its upper bound \\| kg \\|\n")
  message(SEND_ERROR "fit report.md: no row saying m1 is at its upper bound without a std:\n${md}")
endif()
file(READ "${WORK}/fit-report/report.html" html)
if(NOT html MATCHES "<strong>no</strong>: at its upper bound")
  message(SEND_ERROR "fit report.html does not say m1 is at its upper bound")
endif()

foreach(set a b c)
  file(COPY_FILE "${WORK}/one_frf.csv" "${WORK}/${set}.csv")
endforeach()
expect_run(STATUS 0 ARGS monitor bounded.mdl --data a.csv --data b.csv --data c.csv --baseline 2 --starts 2
  --warm-starts 1 --no-diagnosis --json monitor.json --report monitor-report)
file(READ "${WORK}/monitor.json" json)
foreach(i 0 1 2)
  expect_at_upper_bound("${json}" "monitor JSON, data set ${i}" series ${i} parameters m1)
endforeach()
file(READ "${WORK}/monitor-report/report.md" md)
if(NOT md MATCHES "data set 0: `m1` at its upper bound \\(2\\)")
  message(SEND_ERROR "monitor report.md does not say m1 is at its upper bound:\n${md}")
endif()
