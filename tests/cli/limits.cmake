# Numbers whose exact value would fill the memory are refused with their location (docs/limits.md); a long sum is
# read in linear time (it took quadratic time: ~27 s for 10 000 terms).
include(${CMAKE_CURRENT_LIST_DIR}/cli_support.cmake)

write_model(big "param u = 1e99999999999999999999")
expect_run(STATUS 1 STDERR "^big.mdl:9:11: error: number `1e99999999999999999999` is out of range" ARGS inspect big.mdl)
write_model(power "param u = 2^(2^64)")
expect_run(STATUS 1 STDERR "^power.mdl:9:12: error: `2\\^2\\^64`: the exponent must be a number within" ARGS inspect power.mdl)
write_model(m)
expect_run(STATUS 2 STDERR "--set: m1=1e999999999999999999: out of range" ARGS inspect m.mdl --set m1=1e999999999999999999)

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
