# --fix, --free and --bound (docs/cli.md, "Parameter roles"): a parameter's role changed for one run, without
# editing the model file; refusals name the option and what to do instead.
include(${CMAKE_CURRENT_LIST_DIR}/cli_support.cmake)
set(MDOF2_TIME "${SOURCE}/examples/mdof2/data/time_F1.csv")

# The arx-two-stage method needs the masses known: its refusal names the option that makes them so, which works.
expect_run(STATUS 1 STDERR "make them known with their values \\(--fix NAME=VALUE\\)"
  ARGS fit ${MDOF2} --data ${MDOF2_TIME} --method arx-two-stage)
expect_run(STATUS 0 ARGS fit ${MDOF2} --data ${MDOF2_TIME} --method arx-two-stage --fix m1=1.39 --fix m2=1.09
  --json arx.json)
file(READ "${WORK}/arx.json" json)
string(JSON m1 ERROR_VARIABLE absent GET "${json}" parameters m1)
if(NOT absent)
  message(SEND_ERROR "--fix m1: m1 is still estimated: ${m1}")
endif()

# --free estimates a fixed parameter within --bound's bounds; the fit reports it.
expect_run(STATUS 0 ARGS fit ${MDOF2} --data ${MDOF2_FRF} --starts 2 --free c12 --bound c12=0:100 --json free.json)
file(READ "${WORK}/free.json" json)
string(JSON c12 ERROR_VARIABLE missing GET "${json}" parameters c12 value)
if(missing OR c12 LESS 0 OR c12 GREATER 100)
  message(SEND_ERROR "--free c12 --bound c12=0:100: c12 not estimated within its bounds (${c12} ${missing})")
endif()
# --fix NAME without a value keeps the model's value; sensitivity and diagnose take the options too.
expect_run(STATUS 0 ARGS fit ${MDOF2} --data ${MDOF2_FRF} --starts 2 --fix m1 --json fixed.json)
file(READ "${WORK}/fixed.json" json)
string(JSON m1 ERROR_VARIABLE absent GET "${json}" parameters m1)
if(NOT absent)
  message(SEND_ERROR "--fix m1: m1 is still estimated")
endif()
expect_run(STATUS 0 ARGS sensitivity ${MDOF2} --free c12 --json sens.json)
file(READ "${WORK}/sens.json" json)
if(NOT json MATCHES "\"c12\"")
  message(SEND_ERROR "sensitivity --free c12: c12 is not among the parameters")
endif()

# diagnose: the nominal fit estimates what the run says (its model text is rewritten to match, line by line).
expect_run(STATUS 0 ARGS diagnose ${MDOF2} --data ${MDOF2_FRF} --starts 2 --full-fits 1 --fix m1 --free c12
  --bound c12=0:50 --json diagnosis.json)
file(READ "${WORK}/diagnosis.json" json)
string(JSON m1 ERROR_VARIABLE m1_absent GET "${json}" nominal parameters m1)
string(JSON c12 ERROR_VARIABLE c12_missing GET "${json}" nominal parameters c12 value)
if(NOT m1_absent OR c12_missing)
  message(SEND_ERROR "diagnose --fix m1 --free c12: the nominal fit's parameters are not the run's (${m1_absent} ${c12_missing})")
endif()

# Refusals: status 2, the option named, and what to do.
expect_run(STATUS 2 STDERR "--fix: the model has no parameter `nosuch`" ARGS fit ${MDOF2} --data ${MDOF2_FRF} --fix nosuch)
expect_run(STATUS 2 STDERR "--fix: `c12` is not estimated \\(it is fixed\\); --set c12=VALUE changes its value"
  ARGS fit ${MDOF2} --data ${MDOF2_FRF} --fix c12)
expect_run(STATUS 2 STDERR "--free: `m1` is already estimated" ARGS fit ${MDOF2} --data ${MDOF2_FRF} --free m1)
expect_run(STATUS 2 STDERR "--bound: `c12` is not estimated: --free c12 estimates it"
  ARGS fit ${MDOF2} --data ${MDOF2_FRF} --bound c12=0:1)
expect_run(STATUS 2 STDERR "--bound: m1: the lower bound `a` must be a decimal number"
  ARGS fit ${MDOF2} --data ${MDOF2_FRF} --bound m1=a:b)
expect_run(STATUS 2 STDERR "--bound: expected NAME=LO:HI, got `m1=0`" ARGS fit ${MDOF2} --data ${MDOF2_FRF} --bound m1=0)
expect_run(STATUS 2 STDERR "--fix: m1 is given a value by --set and by --fix"
  ARGS fit ${MDOF2} --data ${MDOF2_FRF} --fix m1=2 --set m1=3)
expect_run(STATUS 2 STDERR "--free: `m1` is named twice by --fix and --free"
  ARGS fit ${MDOF2} --data ${MDOF2_FRF} --fix m1 --free m1)
expect_run(STATUS 2 STDERR "--fix: m1=abc: the value must be a decimal number"
  ARGS fit ${MDOF2} --data ${MDOF2_FRF} --fix m1=abc)
write_model(derived "param J = m1*0.1 \"kg\"")
expect_run(STATUS 2 STDERR "--free: `J` is derived \\(an expression of other parameters\\): --free the parameters it is built from"
  ARGS sensitivity derived.mdl --free J)
