# The third hostile probe's findings (issue 36), one check each: outputs that must not replace an input read through
# standard input, write errors on standard output, values without a real value, a zero delay, deterministic and
# valid LaTeX, huge trigonometric arguments, terminal escapes from data, stale part files, header include paths,
# seeds, numbers beyond a double's range, and modal's data errors.
include(${CMAKE_CURRENT_LIST_DIR}/cli_support.cmake)

# --- Standard input is an input: the file it reads is never replaced (3).
file(SHA256 "${WORK}/one.mdl" model_hash)
expect_run(STATUS 2 STDERR "is the file standard input \\(-\\) reads" INPUT "${WORK}/one.mdl" ARGS - -o one.mdl)
expect_run(STATUS 2 STDERR "is the file standard input \\(-\\) reads" INPUT "${WORK}/one.mdl"
  ARGS inspect - -o one.mdl)
file(SHA256 "${WORK}/one.mdl" model_hash_after)
if(NOT model_hash STREQUAL model_hash_after)
  message(SEND_ERROR "the model read through standard input was replaced")
endif()
file(SHA256 "${WORK}/one_frf.csv" data_hash)
expect_run(STATUS 2 STDERR "is the file standard input \\(-\\) reads" INPUT "${WORK}/one_frf.csv"
  ARGS fit one.mdl --data - --json one_frf.csv --starts 1)
file(SHA256 "${WORK}/one_frf.csv" data_hash_after)
if(NOT data_hash STREQUAL data_hash_after)
  message(SEND_ERROR "the data read through standard input were replaced")
endif()
# A pipe or another file on standard input is no collision.
expect_run(STATUS 0 INPUT "${WORK}/one.mdl" ARGS - -o from_stdin.cpp)

# --- Output lost on standard output is a failure (5).
if(EXISTS /dev/full)
  expect_run(STATUS 1 STDERR "error: writing to standard output failed" OUTPUT /dev/full ARGS inspect one.mdl)
  expect_run(STATUS 1 STDERR "error: writing to standard output failed" OUTPUT /dev/full ARGS one.mdl -o -)
  expect_run(STATUS 1 STDERR "error: writing to standard output failed" OUTPUT /dev/full
    ARGS ${FAST_FIT} --json -)
endif()

# --- No real value: an error at the expression, not an internal error or a NaN in emitted code (6).
write_model(imaginary "param u = sqrt(0-1)")
expect_run(STATUS 1 STDERR "^imaginary.mdl:9:11: error: `sqrt\\(0 - 1\\)` has no value at the parameters' values: a negative"
  ARGS inspect imaginary.mdl)
write_model(cube_root "param u = (0-8)^(1/3)")
expect_run(STATUS 1 STDERR "^cube_root.mdl:9:16: error: `\\(0 - 8\\)\\^\\(1/3\\)` has no value at the parameters' values: a negative number \\(-8\\) to the fractional power 1/3"
  ARGS cube_root.mdl -o cube_root.cpp)
if(EXISTS "${WORK}/cube_root.cpp")
  message(SEND_ERROR "code was emitted for a model without a real value")
endif()
file(WRITE "${WORK}/negative_root.mdl" "model r\nparam m = 2\nground g\nbody b { mass sqrt(m-3); dof x }\n"
           "spring s { from g; to b; along x; stiffness 100 }\ninput F force on b along x\n"
           "output y displacement of b along x\n")
expect_run(STATUS 1 STDERR "^negative_root.mdl:4:15: error: `sqrt\\(m - 3\\)` has no value at the parameters' values"
  ARGS negative_root.mdl -o negative_root.cpp)

# --- A delay of zero is the model's error (7).
write_model(zero_delay "filter f on y delay time 0")
expect_run(STATUS 1 STDERR "^zero_delay.mdl:9:26: error: filter `f`: its delay time is 0 s" ARGS inspect zero_delay.mdl)
write_model(set_delay "param tau = 0.001 \"s\" known in [0, 1]" "filter f on y delay time tau")
expect_run(STATUS 1 STDERR "filter `f`: its delay time is 0 s" ARGS inspect set_delay.mdl --set tau=0)

# --- LaTeX: the same text on every run (8), names with several underscores valid (9).
write_model(latex "param m_a_b = 3; param k__2 = 5" "spring t { from g; to b; along x; stiffness m_a_b*k__2 + k }")
expect_run(STATUS 0 ARGS inspect latex.mdl --format latex -o latex1.tex)
expect_run(STATUS 0 ARGS inspect latex.mdl --format latex -o latex2.tex)
file(SHA256 "${WORK}/latex1.tex" tex1)
file(SHA256 "${WORK}/latex2.tex" tex2)
if(NOT tex1 STREQUAL tex2)
  message(SEND_ERROR "inspect --format latex differs between two runs")
endif()
file(READ "${WORK}/latex1.tex" tex)
if(NOT tex MATCHES "m_\\{\\\\mathrm\\{a\\\\_b\\}\\}" OR NOT tex MATCHES "k_\\{\\\\mathrm\\{\\\\_2\\}\\}" OR tex MATCHES "m_a_b")
  message(SEND_ERROR "LaTeX names are not escaped:\n${tex}")
endif()

# --- sin of a huge argument cannot be evaluated reliably: refused (10).
write_model(huge_sine "param u = 1000 + 1000*sin(1e30)")
expect_run(STATUS 1 STDERR "^huge_sine.mdl:9:23: error: `sin\\(.*\\)`: the argument is 1e\\+30 rad" ARGS inspect huge_sine.mdl)

# --- Terminal escapes from data files are not echoed raw (12).
string(ASCII 27 esc)
string(ASCII 7 bel)
file(WRITE "${WORK}/escape.csv" "f_hz,y/F.re,y/F.im\n1,0.001,${esc}[31m${bel}\n")
expect_run(STATUS 1 ARGS fit one.mdl --data escape.csv --starts 1)
if(LAST_STDERR MATCHES "${esc}" OR LAST_STDERR MATCHES "${bel}" OR NOT LAST_STDERR MATCHES "\\\\x1b\\[31m\\\\x07")
  message(SEND_ERROR "a data file's control characters reached the terminal raw: ${LAST_STDERR}")
endif()

# --- Part files an earlier --parts wrote are removed when fewer are written; the user's own are kept (13).
expect_run(STATUS 0 ARGS one.mdl -o q.cpp --parts 3)
foreach(k 1 2)
  if(NOT EXISTS "${WORK}/q_part${k}.cpp")
    message(SEND_ERROR "--parts 3 did not write q_part${k}.cpp")
  endif()
endforeach()
expect_run(STATUS 0 ARGS one.mdl -o q.cpp --parts 2)
if(NOT EXISTS "${WORK}/q_part1.cpp" OR EXISTS "${WORK}/q_part2.cpp")
  message(SEND_ERROR "--parts 2 after --parts 3 left the stale q_part2.cpp (or removed q_part1.cpp)")
endif()
file(WRITE "${WORK}/q_part2.cpp" "// the user's own file\n")
expect_run(STATUS 0 ARGS one.mdl -o q.cpp)
if(EXISTS "${WORK}/q_part1.cpp" OR NOT EXISTS "${WORK}/q_part2.cpp")
  message(SEND_ERROR "a single translation unit left q_part1.cpp, or removed the user's q_part2.cpp")
endif()

# --- The source includes its header by the path from its own directory (14).
file(MAKE_DIRECTORY "${WORK}/inc" "${WORK}/src")
expect_run(STATUS 0 ARGS one.mdl -o src/h.cpp --header inc/h.hpp)
file(READ "${WORK}/src/h.cpp" source)
if(NOT source MATCHES "#include \"../inc/h.hpp\"")
  message(SEND_ERROR "the source does not include ../inc/h.hpp")
endif()
expect_run(STATUS 2 STDERR "--header: - \\(standard output\\) would leave the source's #include naming a header"
  ARGS one.mdl -o lonely.cpp --header -)

# --- Seeds: 0 to 2^64 - 1, recorded in the JSON (15).
expect_run(STATUS 2 STDERR "a seed is a whole number" ARGS ${FAST_FIT} --seed -1)
expect_run(STATUS 2 STDERR "a seed is at most 18446744073709551615" ARGS ${FAST_FIT} --seed 18446744073709551616)
expect_run(STATUS 0 ARGS ${FAST_FIT} --seed 18446744073709551615 --json seed.json)
file(READ "${WORK}/seed.json" seed_json)
if(NOT seed_json MATCHES "\"seed\": ?18446744073709551615")
  message(SEND_ERROR "the fit's JSON does not record the seed")
endif()

# --- Numbers beyond a double's range in data (16): a value under the smallest double is zero, one over the largest
# too large, neither "not a number"; option ranges are short.
file(READ "${WORK}/one_frf.csv" frf)
string(REGEX REPLACE "\n([0-9.e+-]+),([^,\n]*),([^,\n]*)\n" "\n\\1,\\2,1e-400\n" tiny "${frf}")
file(WRITE "${WORK}/tiny.csv" "${tiny}")
expect_run(STATUS 0 ARGS fit one.mdl --data tiny.csv --starts 1)
string(REGEX REPLACE "\n([0-9.e+-]+),([^,\n]*),([^,\n]*)\n" "\n\\1,\\2,1e400\n" huge "${frf}")
file(WRITE "${WORK}/huge.csv" "${huge}")
expect_run(STATUS 1 STDERR "'1e400' is too large" ARGS fit one.mdl --data huge.csv --starts 1)
expect_run(STATUS 2 STDERR "expected a number greater than 0, not 0" ARGS modal --data one_frf.csv --max-order 0)
if(LAST_STDERR MATCHES "[0-9]{40}")
  message(SEND_ERROR "a range message writes out a huge number: ${LAST_STDERR}")
endif()
expect_run(STATUS 1 STDERR "^one_frf.csv: error: " ARGS modal --data one_frf.csv --select 5000)

# --- diagnose on short FRFs gives a verdict or a data error, never a crash (1: a segmentation fault on 2-15 lines,
# where no line stands out of the noise) or an internal error (2: every 8th line of 24, whose nominal fit drove a
# damping to its bound of zero, left a new mode's start value infinite).
file(STRINGS "${MDOF2_FRF}" frf_lines)
set(header "")
set(data_lines "")
foreach(line IN LISTS frf_lines)
  if(line MATCHES "^#")
    continue()
  elseif(header STREQUAL "")
    set(header "${line}")
  else()
    list(APPEND data_lines "${line}")
  endif()
endforeach()
foreach(count 2 8 15)
  list(SUBLIST data_lines 0 ${count} first)
  string(REPLACE ";" "\n" first "${first}")
  file(WRITE "${WORK}/short${count}.csv" "${header}\n${first}\n")
  expect_run(STATUS 0 STDOUT "verdict" ARGS diagnose ${MDOF2} --data short${count}.csv --starts 1)
endforeach()
set(every_eighth "")
foreach(k RANGE 0 191 8)
  list(GET data_lines ${k} line)
  if(NOT line MATCHES "^18,")
    string(APPEND every_eighth "${line}\n")
  endif()
endforeach()
file(WRITE "${WORK}/every_eighth.csv" "${header}\n${every_eighth}")
expect_run(STATUS 0 STDOUT "verdict" ARGS diagnose ${MDOF2} --data every_eighth.csv --starts 1)

# --- Many bounded parameters are emitted in about linear time (11: the bounds' substitution tried every parameter at
# every node, quadratic: 20 000 took over 100 s, 100 000 hours). The run's timeout (60 s) is the check.
set(many "")
foreach(i RANGE 1 20000)
  string(APPEND many "param p${i} = 1 estimate in [0, 10]\n")
endforeach()
file(WRITE "${WORK}/many.mdl" "model many\nground g\nbody b { mass 2; dof x }\n"
           "spring s { from g; to b; along x; stiffness 100 }\ninput F force on b along x\n"
           "output y displacement of b along x\n${many}")
expect_run(STATUS 0 ARGS many.mdl -o many.cpp)

# --- A record too short for the part of it a command fits says so, with `error:` and the count (16: diagnose said
# "needs at least 2 samples" for a record of 2, without `error:`).
file(WRITE "${WORK}/two.csv" "t,F1,d1,d2\n0,1,0.1,0.2\n0.001,1,0.2,0.1\n")
expect_run(STATUS 1 STDERR "two.csv: error: a time record needs at least 2 samples for a fit; the part of it fitted here has 1"
  ARGS diagnose ${MDOF2} --data two.csv --starts 1)
# A method's refusal without a file says `mbgen: error:` (it began with "fit: ").
expect_run(STATUS 1 STDERR "^mbgen: error: --method arx-two-stage needs the mass matrix known"
  ARGS fit ${MDOF2} --data two.csv --method arx-two-stage)

# --- A block of irrational exact values is bounded (11: GiNaC's exponential route took over 120 s at 12 coordinates):
# a 12-mass chain whose springs hold distinct square roots gets run-time transfer functions, within the 60 s timeout.
set(chain "model irrational\nground g\n")
foreach(i RANGE 0 11)
  math(EXPR mass "${i} + 1")
  string(APPEND chain "body b${i} { mass ${mass}; dof x }\n")
endforeach()
string(APPEND chain "spring s0 { from g; to b0; along x; stiffness 1000*sqrt(2); damping 1 }\n")
foreach(i RANGE 1 11)
  math(EXPR prev "${i} - 1")
  math(EXPR root "${i} + 2")
  string(APPEND chain "spring s${i} { from b${prev}; to b${i}; along x; stiffness 1000*sqrt(${root}); damping 1 }\n")
endforeach()
file(WRITE "${WORK}/irrational.mdl" "${chain}input F force on b0 along x\noutput y displacement of b11 along x\n")
expect_run(STATUS 0 ARGS irrational.mdl -o irrational.cpp)
