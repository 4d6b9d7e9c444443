# Helpers for the command-line regression tests (cmake -P scripts in this directory). Each script gets
# -DMBGEN=<the mbgen to test> -DWORK=<a scratch directory of its own> -DSOURCE=<the source tree>, runs mbgen on
# inputs it writes into WORK, and checks the exit status, the message and the files before and after.

if(NOT MBGEN OR NOT WORK OR NOT SOURCE)
  message(FATAL_ERROR "usage: cmake -DMBGEN=... -DWORK=... -DSOURCE=... -P SCRIPT")
endif()
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(MDOF2 "${SOURCE}/examples/mdof2/mdof2.mdl")
set(MDOF2_FRF "${SOURCE}/examples/mdof2/data/frf_F1.csv")

# A small valid model, written to WORK/NAME.mdl; extra statements in ARGN (one per argument), from line 9 on.
function(write_model name)
  set(text "model one\nparam m1 = 2 \"kg\" estimate in [0.5, 10]\nparam k = 1000; param c = 1\nground g\n")
  string(APPEND text "body b { mass m1; dof x }\nspring s { from g; to b; along x; stiffness k; damping c }\n")
  string(APPEND text "input F force on b along x\noutput y displacement of b along x\n")
  foreach(line IN LISTS ARGN)
    string(APPEND text "${line}\n")
  endforeach()
  file(WRITE "${WORK}/${name}.mdl" "${text}")
endfunction()

# mdof2's example FRFs with the driving point d1/F1 alone (f_hz and the three d1/F1 columns), written to WORK/NAME.
function(write_mdof2_d1_only name)
  file(STRINGS "${MDOF2_FRF}" lines)
  set(text "")
  foreach(line IN LISTS lines)
    if(line MATCHES "^#")
      continue()
    endif()
    string(REGEX REPLACE "^([^,]*,[^,]*,[^,]*,[^,]*),.*$" "\\1" line "${line}")  # f_hz and d1/F1 only
    string(APPEND text "${line}\n")
  endforeach()
  file(WRITE "${WORK}/${name}" "${text}")
endfunction()

# A fit that takes milliseconds: the model above (one.mdl) and its FRF with m1 = 2.3 (one_frf.csv), both in WORK.
write_model(one)
file(COPY "${CMAKE_CURRENT_LIST_DIR}/one_frf.csv" DESTINATION "${WORK}")
set(FAST_FIT fit one.mdl --data one_frf.csv --starts 1)

# expect_run(STATUS n [STDERR regex] [STDOUT regex] [DIR dir] ARGS ...): runs mbgen with ARGS in DIR (default WORK)
# and checks its exit status and that standard error (output) matches the regular expression. The run's standard
# error is left in LAST_STDERR. Like the checks below, a failure is reported and the script goes on (SEND_ERROR):
# one run shows every check that fails. INPUT file: standard input; OUTPUT file: standard output goes there.
# TIMEOUT seconds (default 60): a diagnosis takes minutes under the sanitizers.
function(expect_run)
  cmake_parse_arguments(PARSE_ARGV 0 arg "" "STATUS;STDERR;STDOUT;DIR;INPUT;OUTPUT;TIMEOUT" "ARGS")
  if(NOT arg_TIMEOUT)
    set(arg_TIMEOUT 60)
  endif()
  if(NOT arg_DIR)
    set(arg_DIR "${WORK}")
  endif()
  set(redirect OUTPUT_VARIABLE out)
  if(arg_OUTPUT)
    set(redirect OUTPUT_FILE "${arg_OUTPUT}")
  endif()
  if(arg_INPUT)
    list(APPEND redirect INPUT_FILE "${arg_INPUT}")
  endif()
  execute_process(COMMAND "${MBGEN}" ${arg_ARGS} WORKING_DIRECTORY "${arg_DIR}"
    RESULT_VARIABLE status ${redirect} ERROR_VARIABLE err TIMEOUT ${arg_TIMEOUT})
  string(REPLACE ";" " " shown "${arg_ARGS}")
  if(NOT status STREQUAL "${arg_STATUS}")
    message(SEND_ERROR "`mbgen ${shown}`: expected exit status ${arg_STATUS}, got ${status}\nstderr: ${err}")
  endif()
  if(DEFINED arg_STDERR AND NOT err MATCHES "${arg_STDERR}")
    message(SEND_ERROR "`mbgen ${shown}`: standard error does not match `${arg_STDERR}`:\n${err}")
  endif()
  if(DEFINED arg_STDOUT AND NOT out MATCHES "${arg_STDOUT}")
    message(SEND_ERROR "`mbgen ${shown}`: standard output does not match `${arg_STDOUT}`:\n${out}")
  endif()
  set(LAST_STDERR "${err}" PARENT_SCOPE)
endfunction()

# tree_state(var dir): every path below dir (hidden ones too) with the hash of each file's content.
function(tree_state var dir)
  file(GLOB_RECURSE paths LIST_DIRECTORIES true RELATIVE "${dir}" "${dir}/*" "${dir}/.*" "${dir}/*/.*")
  list(REMOVE_DUPLICATES paths)
  list(SORT paths)
  set(state "")
  foreach(p IN LISTS paths)
    if(IS_DIRECTORY "${dir}/${p}")
      list(APPEND state "${p}/")
    else()
      file(SHA256 "${dir}/${p}" hash)
      list(APPEND state "${p}:${hash}")
    endif()
  endforeach()
  set(${var} "${state}" PARENT_SCOPE)
endfunction()

# expect_unchanged(before dir what): the tree at dir is as tree_state recorded it in `before`.
function(expect_unchanged before dir what)
  tree_state(after "${dir}")
  if(NOT after STREQUAL before)
    message(SEND_ERROR "${what}: the files changed.\nbefore: ${before}\nafter:  ${after}")
  endif()
endfunction()

# expect_no_temporaries(dir): no `.NAME.mbgen-tmp-...` or `.mbgen-old-` entries left in dir.
function(expect_no_temporaries dir)
  file(GLOB left "${dir}/.*.mbgen-tmp-*" "${dir}/.*.mbgen-old-*")
  if(left)
    message(SEND_ERROR "temporaries left behind: ${left}")
  endif()
endfunction()
