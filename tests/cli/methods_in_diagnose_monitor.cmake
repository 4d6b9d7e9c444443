# `diagnose --method NAME` and `monitor --method NAME` (docs/methods.md#in-diagnose-and-monitor): the method's
# estimate is one more start of their output-error fits. On mdof2's FRFs output error finds the optimum from its own
# starts, so the verdict stays that without the method, and the JSON names the method; an output-error name changes
# no byte; a method that cannot use the data is refused as `fit --method` refuses it (status 1, nothing written).
include(${CMAKE_CURRENT_LIST_DIR}/cli_support.cmake)

# The JSON member `member` of file `file` (a string, or "" where it is absent).
function(json_member out file member)
  file(READ "${WORK}/${file}" json)
  string(JSON value ERROR_VARIABLE missing GET "${json}" ${member})
  if(missing)
    set(value "")
  endif()
  set(${out} "${value}" PARENT_SCOPE)
endfunction()

# ---- diagnose ----
expect_run(STATUS 0 ARGS diagnose ${MDOF2} --data ${MDOF2_FRF} --json plain.json)
expect_run(STATUS 0 STDERR "diagnose: start from --method direct: its estimate \\(nrmse [0-9.e-]+\\) starts the nominal fit"
  ARGS diagnose ${MDOF2} --data ${MDOF2_FRF} --method direct --json direct.json)
expect_run(STATUS 0 ARGS diagnose ${MDOF2} --data ${MDOF2_FRF} --method two-step --json two_step.json)
json_member(verdict plain.json verdict)
json_member(absent plain.json start_method)
if(NOT verdict OR NOT absent STREQUAL "")
  message(SEND_ERROR "diagnose without --method: verdict '${verdict}', start_method '${absent}' (expected none)")
endif()
foreach(run direct two_step)
  string(REPLACE "_" "-" method ${run})
  json_member(named ${run}.json start_method)
  json_member(run_verdict ${run}.json verdict)
  if(NOT named STREQUAL method OR NOT run_verdict STREQUAL verdict)
    message(SEND_ERROR "diagnose --method ${method}: start_method '${named}', verdict '${run_verdict}' "
                       "(expected ${method}, ${verdict})")
  endif()
endforeach()
# The same input, the same bytes.
expect_run(STATUS 0 ARGS diagnose ${MDOF2} --data ${MDOF2_FRF} --method two-step --json two_step_again.json)
file(READ "${WORK}/two_step.json" first_text)
file(READ "${WORK}/two_step_again.json" again_text)
if(NOT first_text STREQUAL again_text)
  message(SEND_ERROR "diagnose --method two-step wrote other bytes on a second run")
endif()
# An output-error name adds nothing: the same bytes.
expect_run(STATUS 0 ARGS diagnose ${MDOF2} --data ${MDOF2_FRF} --method frf-output-error --json oe.json)
file(READ "${WORK}/plain.json" plain_text)
file(READ "${WORK}/oe.json" oe_text)
if(NOT plain_text STREQUAL oe_text)
  message(SEND_ERROR "diagnose --method frf-output-error wrote other bytes than diagnose without --method")
endif()
# The method's options come with it, as fit has them.
expect_run(STATUS 0 STDOUT "--two-step-route" ARGS diagnose --help)

# Refusals: the data's kind, before any fit, and a method's precondition with its note; nothing written.
expect_run(STATUS 1 STDERR "frf_F1.csv: error: --method ekf needs time records .*\nnote: methods that take FRFs: auto, "
  ARGS diagnose ${MDOF2} --data ${MDOF2_FRF} --method ekf --json refused.json)
write_mdof2_d1_only(d1_only.csv)
expect_run(STATUS 1 STDERR "d1_only.csv: error: --method direct needs .* cannot give mass2.x.*\nnote: --method auto or two-step does without"
  ARGS diagnose ${MDOF2} --data d1_only.csv --method direct --json refused.json)
expect_run(STATUS 2 STDERR "--method" ARGS diagnose ${MDOF2} --data ${MDOF2_FRF} --method directt)
if(EXISTS "${WORK}/refused.json")
  message(SEND_ERROR "a refused diagnose --method wrote its JSON")
endif()

# ---- monitor ----
set(series --data ${MDOF2_FRF} --data ${MDOF2_FRF} --data ${MDOF2_FRF} --data ${MDOF2_FRF} --starts 2
           --warm-starts 2 --no-diagnosis)
expect_run(STATUS 0 ARGS monitor ${MDOF2} ${series} --json m_plain.json)
expect_run(STATUS 0 ARGS monitor ${MDOF2} ${series} --method two-step --json m_two_step.json)
json_member(changes m_plain.json changes)
json_member(absent m_plain.json start_method)
json_member(named m_two_step.json start_method)
json_member(changes_with m_two_step.json changes)
json_member(monitored m_plain.json baseline parameters)
json_member(monitored_with m_two_step.json baseline parameters)
string(JSON n_monitored LENGTH "${monitored}")
string(JSON n_monitored_with LENGTH "${monitored_with}")
if(NOT absent STREQUAL "" OR NOT named STREQUAL "two-step" OR NOT changes STREQUAL changes_with
   OR NOT n_monitored EQUAL n_monitored_with)
  message(SEND_ERROR "monitor --method two-step: start_method '${named}' (without: '${absent}'), changes "
                     "'${changes_with}' against '${changes}', ${n_monitored_with} monitored against ${n_monitored}")
endif()
expect_run(STATUS 0 ARGS monitor ${MDOF2} ${series} --method two-step --json m_two_step_again.json)
file(READ "${WORK}/m_two_step.json" first_text)
file(READ "${WORK}/m_two_step_again.json" again_text)
if(NOT first_text STREQUAL again_text)
  message(SEND_ERROR "monitor --method two-step wrote other bytes on a second run")
endif()
expect_run(STATUS 0 ARGS monitor ${MDOF2} ${series} --method auto --json m_auto.json)
file(READ "${WORK}/m_plain.json" plain_text)
file(READ "${WORK}/m_auto.json" auto_text)
if(NOT plain_text STREQUAL auto_text)
  message(SEND_ERROR "monitor --method auto wrote other bytes than monitor without --method")
endif()
expect_run(STATUS 1 STDERR "frf_F1.csv: error: --method arx-two-stage needs time records"
  ARGS monitor ${MDOF2} ${series} --method arx-two-stage --json m_refused.json)
expect_run(STATUS 2 STDERR "--method: not with --output-only" ARGS monitor --output-only --data ${MDOF2_FRF} --method direct)
if(EXISTS "${WORK}/m_refused.json")
  message(SEND_ERROR "a refused monitor --method wrote its JSON")
endif()
