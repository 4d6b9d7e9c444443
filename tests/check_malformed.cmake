# Runs `mbgen MODEL -o OUT` on a malformed model and checks: exit status 1, the message named in the model's
# first line (`# expect: LINE:COL: error: ...`) printed after the file name, and no output file left behind.
# Usage: cmake -DMBGEN=... -DMODEL=... -DOUT_DIR=... -P check_malformed.cmake
file(READ "${MODEL}" text)
string(REGEX MATCH "^# expect: [^\n]*" first "${text}")  # file(READ), not file(STRINGS): keeps `;` intact
string(REGEX REPLACE "^# expect: " "" expected "${first}")
file(REMOVE_RECURSE "${OUT_DIR}")
file(MAKE_DIRECTORY "${OUT_DIR}")
execute_process(COMMAND "${MBGEN}" "${MODEL}" -o "${OUT_DIR}/out.cpp"
  RESULT_VARIABLE status ERROR_VARIABLE err OUTPUT_VARIABLE out)
string(STRIP "${err}" err)
if(NOT status EQUAL 1)
  message(FATAL_ERROR "expected exit status 1, got ${status}; stderr: ${err}")
endif()
if(NOT err STREQUAL "${MODEL}:${expected}")
  message(FATAL_ERROR "unexpected message:\n  got:      ${err}\n  expected: ${MODEL}:${expected}")
endif()
file(GLOB left "${OUT_DIR}/*" "${OUT_DIR}/.*")
if(left)
  message(FATAL_ERROR "output left behind after a failed run: ${left}")
endif()
