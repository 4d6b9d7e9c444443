# Numbers whose exact value would fill the memory are refused with their location (docs/limits.md); a long sum is
# read in linear time (it took quadratic time: ~27 s for 10 000 terms).
include(${CMAKE_CURRENT_LIST_DIR}/cli_support.cmake)

write_model(big "param u = 1e99999999999999999999")
expect_run(STATUS 1 STDERR "^big.mdl:9:11: error: number `1e99999999999999999999` is out of range" ARGS inspect big.mdl)
write_model(power "param u = 2^(2^64)")
expect_run(STATUS 1 STDERR "^power.mdl:9:12: error: `2\\^2\\^64`: the exponent must be a number within" ARGS inspect power.mdl)
# An exponent that depends on parameters is bounded at their values: q^(q^(q^q)) with q = 3 hung computing
# 3^7625597484987 exactly. So is the exact size of a power at those values, and a value too small for a double
# (1e-400 is positive exactly and 0 in a fit).
write_model(tower "param q = 3" "param t = q^(q^(q^q))")
expect_run(STATUS 1 STDERR "^tower.mdl:10:12: error: `q\\^q\\^q\\^q`: at the parameters' values the exponent is 7.6256e\\+12"
  ARGS inspect tower.mdl)
write_model(wide "param q = 1e300" "param t = q^150")
expect_run(STATUS 1 STDERR "^wide.mdl:10:12: error: `q\\^150` is too large an exact number at the parameters' values"
  ARGS inspect wide.mdl)
# The power itself is bounded too, whatever the values: GiNaC raises the product's 10^1000 to the power at once. With
# q = 0 its value passed, and ((q*10^1000)^1000)^1000 hung (found by the fuzzer, tests/fuzz/corpus).
write_model(zero_base "param q = 0" "param t = ((q*10^1000)^1000)^1000")
expect_run(STATUS 1 STDERR "^zero_base.mdl:10:23: error: `\\(q\\*10\\^1000\\)\\^1000` is too large an exact number: "
  ARGS inspect zero_base.mdl)
# What has no value at the parameters' values is the model's error, named where it is, not a crash (GiNaC threw from
# its substitution): q^(q^(q^q)) with q = 0 holds 0^0 (found by the fuzzer); 2/q and q^(q-1) divide by zero.
write_model(zero_tower "param q = 0" "param t = q^(q^(q^q))")
expect_run(STATUS 1 STDERR "^zero_tower.mdl:10:18: error: `q\\^q` has no value at the parameters' values: 0\\^0 is undefined"
  ARGS inspect zero_tower.mdl)
write_model(zero_negative "param q = 0" "param t = q^(q-1)")
expect_run(STATUS 1 STDERR "^zero_negative.mdl:10:12: error: `q\\^\\(q - 1\\)` has no value at the parameters' values: division by zero"
  ARGS inspect zero_negative.mdl)
write_model(zero_divisor "param q = 0" "param t = 2/q")
expect_run(STATUS 1 STDERR "^zero_divisor.mdl:10:12: error: `2/q` has no value at the parameters' values: division by zero"
  ARGS inspect zero_divisor.mdl)
# The same in an element's field (it was an internal error, exit 3, from wherever the model was first evaluated).
file(WRITE "${WORK}/zero_element.mdl" "model z\nparam q = 0\nground g\nbody b { mass 2; dof x }\n"
           "spring s { from g; to b; along x; stiffness 2/q }\ninput F force on b along x\n"
           "output y displacement of b along x\n")
expect_run(STATUS 1 STDERR "^zero_element.mdl:5:46: error: `2/q` has no value at the parameters' values: division by zero"
  ARGS inspect zero_element.mdl)
write_model(tiny "param t = 1e-400")
expect_run(STATUS 1 STDERR "^tiny.mdl:9:11: error: the value of `t` is beyond the range of a double" ARGS inspect tiny.mdl)
write_model(fine "param q = 3" "param t = 2^(q^q)")
expect_run(STATUS 0 ARGS inspect fine.mdl)

write_model(m)
expect_run(STATUS 2 STDERR "--set: m1=1e999999999999999999: out of range" ARGS inspect m.mdl --set m1=1e999999999999999999)

# The number of starts is bounded (docs/limits.md): every start's point and result are held at once, and
# `fit --starts 2000000000` took 9 GB within 20 s. One above the bound is refused as usage (the old code would run
# 100 001 starts here and time out); so is 0, which CLI11 described as "not in range 0.000000 to 1797693...".
expect_run(STATUS 2 STDERR "^mbgen: --starts: Value 100001 not in range 1 to 100000" ARGS ${FAST_FIT} --starts 100001)
expect_run(STATUS 2 STDERR "^mbgen: --starts: Value 0 not in range 1 to 100000" ARGS ${FAST_FIT} --starts 0)
expect_run(STATUS 2 STDERR "^mbgen: --starts: Value 100001 not in range"
  ARGS diagnose one.mdl --data one_frf.csv --starts 100001)
expect_run(STATUS 2 STDERR "^mbgen: --warm-starts: Value 100001 not in range"
  ARGS monitor one.mdl --data one_frf.csv --warm-starts 100001)

# A model file is read up to 16 MiB (`inspect /dev/zero` read until the memory ran out): 17 MiB of comments.
string(REPEAT "# a comment line of exactly sixty-four characters, newline too.\n" 16 line16)
string(REPEAT "${line16}" 17408 comments)  # 17408 * 16 * 64 bytes = 17 MiB
file(WRITE "${WORK}/big_file.mdl" "${comments}")
expect_run(STATUS 1 STDERR "^big_file.mdl: error: the model file is larger than 16 MiB" ARGS inspect big_file.mdl)
file(REMOVE "${WORK}/big_file.mdl")

# Data files are read as they come, a line at most 16 MiB (docs/limits.md): standard input and UFF files were read
# whole first, so `--data -` from a pipe that never ends, or a UFF "file" that is /dev/zero, took memory until there
# was none (a pipe from /dev/zero ran for minutes under a 3 GB limit).
if(EXISTS /dev/zero)
  foreach(command "fit;one.mdl;--data;-;--starts;1" "modal;--data;-")
    execute_process(COMMAND cat /dev/zero COMMAND "${MBGEN}" ${command} WORKING_DIRECTORY "${WORK}"
      RESULT_VARIABLE status ERROR_VARIABLE err TIMEOUT 60)
    if(NOT status EQUAL 1 OR NOT err MATCHES "^-:1: error: line longer than 16 MiB")
      message(SEND_ERROR "`cat /dev/zero | mbgen ${command}`: status ${status}, stderr: ${err}")
    endif()
  endforeach()
  file(CREATE_LINK /dev/zero "${WORK}/zero.uff" SYMBOLIC)
  expect_run(STATUS 1 STDERR "^zero.uff:1: error: line longer than 16 MiB" ARGS modal --data zero.uff)
endif()

string(REPEAT " + 0.001" 99999 terms)
file(WRITE "${WORK}/sum.mdl" "model m\nparam m1 = 0.001${terms}\nground g\nbody b { mass m1; dof x }\n"
           "spring s { from g; to b; along x; stiffness 1 }\n")
string(TIMESTAMP start "%s")
expect_run(STATUS 0 STDOUT "\\| `m1` \\| 100 \\|" ARGS inspect sum.mdl)
string(TIMESTAMP end "%s")
math(EXPR seconds "${end} - ${start}")
if(seconds GREATER 20)
  message(SEND_ERROR "a 100 000-term sum took ${seconds} s")
endif()
