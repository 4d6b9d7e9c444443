# One hidden-effect test: make data with the independent truth-model generator (scripts/truthgen, numpy; not
# mbgen's code), run `mbgen diagnose`, and check the verdict and the selected extensions in its JSON.
#   -DMBGEN=... -DPYTHON=... -DTRUTHGEN=... -DMODEL=... -DWORK_DIR=...
#   -DDATA="example:case:kind:seed[:NAME=VALUE][:duration=S][:draw=N][:averages=N][:analyser=N][:nocoh][:fs=HZ]
#           [:gain=OUTPUT=FACTOR][:inputgain=INPUT=FACTOR][:forcesign=-1][:swap=A,B][:unit=OUTPUT=UNIT]
#           [:form=OUTPUT=FORM]|..."
#                                                                     one or more data sets; gain, inputgain,
#                                                                     forcesign, swap, unit, form: errors of the
#                                                                     measurement chain (docs/truthgen.md)
#         or "file=PATH|..." for measured data as they are (real data, no generator)
#   -DDIAGNOSE_ARGS="--fit-band;20:320" (optional): more arguments of `mbgen diagnose`
#   -DEXPECT_VERDICT=extended|no_extension_justified|unexplained|not_extended
#   -DEXPECT_SELECTED=id (first selected extension, when extended), or A+B, A+B+C (several effects: all selected,
#                     in any order, nothing else)
#   -DEXPECT_ALSO=id (optional: another extension that must be among the selected)
#   -DEXPECT_FACTOR=PARAM:TOL (optional: the extended model's PARAM, a new parameter of a selected extension at the
#                     final model's estimate, is the factor of the first data set's measurement-chain error, from its
#                     .truth.json, within a relative TOL; so is what the summary and the JSON say of the extension)
cmake_policy(SET CMP0057 NEW)  # if(... IN_LIST ...)
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
string(REPLACE "|" ";" sets "${DATA}")
set(data_args "")
set(index 0)
foreach(set IN LISTS sets)
  if(set MATCHES "^file=(.*)$")
    list(APPEND data_args --data "${CMAKE_MATCH_1}")
    continue()
  endif()
  string(REPLACE ":" ";" f "${set}")
  list(GET f 0 example)
  list(GET f 1 case)
  list(GET f 2 kind)
  list(GET f 3 seed)
  set(extra "")
  list(LENGTH f n)
  if(n GREATER 4)
    list(SUBLIST f 4 -1 options)
    foreach(option IN LISTS options)
      if(option MATCHES "^duration=(.*)$")
        list(APPEND extra --duration "${CMAKE_MATCH_1}")  # a time record's length, s
      elseif(option MATCHES "^draw=(.*)$")
        list(APPEND extra --draw "${CMAKE_MATCH_1}")  # the truth drawn at random from this seed
      elseif(option MATCHES "^averages=(.*)$")
        list(APPEND extra --averages "${CMAKE_MATCH_1}")  # an FRF averaged this many times
      elseif(option MATCHES "^analyser=(.*)$")
        list(APPEND extra --analyser "${CMAKE_MATCH_1}")  # an analyser's H1 of this many segments
      elseif(option STREQUAL "nocoh")
        list(APPEND extra --no-coherence)  # an FRF file without coherence columns
      elseif(option MATCHES "^fs=(.*)$")
        list(APPEND extra --fs "${CMAKE_MATCH_1}")  # a time record's sample rate, Hz
      elseif(option MATCHES "^gain=(.*)$")
        list(APPEND extra --gain "${CMAKE_MATCH_1}")  # an output's calibration or polarity error
      elseif(option MATCHES "^inputgain=(.*)$")
        list(APPEND extra --input-gain "${CMAKE_MATCH_1}")  # the force transducer's calibration
      elseif(option MATCHES "^forcesign=(.*)$")
        list(APPEND extra --force-sign "${CMAKE_MATCH_1}")  # the recorded force's sign
      elseif(option MATCHES "^swap=(.*)$")
        list(APPEND extra --swap "${CMAKE_MATCH_1}")  # two outputs' columns exchanged
      elseif(option MATCHES "^unit=(.*)$")
        list(APPEND extra --unit "${CMAKE_MATCH_1}")  # a channel written in another unit
      elseif(option MATCHES "^form=(.*)$")
        list(APPEND extra --frf-form "${CMAKE_MATCH_1}")  # a channel written as a mobility or an accelerance
      else()
        list(APPEND extra --set "${option}")
      endif()
    endforeach()
  endif()
  set(file "${WORK_DIR}/data${index}.csv")
  execute_process(COMMAND "${PYTHON}" "${TRUTHGEN}" --example ${example} --case ${case} --kind ${kind} --snr-db 40
                          --seed ${seed} ${extra} -o "${file}"
                  RESULT_VARIABLE status ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "truthgen failed: ${err}")
  endif()
  list(APPEND data_args --data "${file}")
  math(EXPR index "${index} + 1")
endforeach()

execute_process(COMMAND "${MBGEN}" diagnose "${MODEL}" ${data_args} ${DIAGNOSE_ARGS} --json "${WORK_DIR}/diagnosis.json"
                        --report "${WORK_DIR}/report" --extended "${WORK_DIR}/extended.mdl"
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "mbgen diagnose failed (${status}):\n${err}")
endif()
file(READ "${WORK_DIR}/diagnosis.json" json)
file(READ "${WORK_DIR}/report/report.md" report_md)
string(JSON verdict GET "${json}" verdict)
string(JSON n_selected LENGTH "${json}" selected)
set(selected "")
if(n_selected GREATER 0)
  string(JSON selected GET "${json}" selected 0)
endif()
message(STATUS "verdict ${verdict}, selected '${selected}'\n${out}")
if(EXPECT_VERDICT STREQUAL "not_extended")
  if(verdict STREQUAL "extended")
    message(FATAL_ERROR "a confident wrong extension: ${selected} (expected no extension)")
  endif()
elseif(NOT verdict STREQUAL EXPECT_VERDICT)
  message(FATAL_ERROR "verdict ${verdict}, expected ${EXPECT_VERDICT} (selected '${selected}')")
endif()
# The report's first screen: with findings, the strongest ones and the overlay on the strongest one's channel come
# under the verdict, before the full list of findings.
string(JSON n_findings LENGTH "${json}" discrepancies)
if(n_findings GREATER 0)
  file(READ "${WORK_DIR}/report/report.html" report)
  string(FIND "${report}" "where the strongest finding is" overlay_at)
  string(FIND "${report}" "What the nominal model gets wrong" findings_at)
  if(overlay_at LESS 0 OR overlay_at GREATER findings_at)
    message(FATAL_ERROR "the report does not open with the strongest finding's overlay (${overlay_at}, ${findings_at})")
  endif()
endif()
set(all_selected "")
if(n_selected GREATER 0)
  math(EXPR last "${n_selected} - 1")
  foreach(i RANGE ${last})
    string(JSON id GET "${json}" selected ${i})
    list(APPEND all_selected "${id}")
  endforeach()
endif()
# When extended: which nominal findings each selected extension explains, one entry per selected, in order.
if(verdict STREQUAL "extended")
  string(JSON n_explains LENGTH "${json}" extended explains)
  if(NOT n_explains EQUAL n_selected)
    message(FATAL_ERROR "extended.explains has ${n_explains} entries for ${n_selected} selected")
  endif()
  math(EXPR last "${n_selected} - 1")
  foreach(i RANGE ${last})
    string(JSON id GET "${json}" selected ${i})
    string(JSON explains_id GET "${json}" extended explains ${i} id)
    string(JSON n_explained LENGTH "${json}" extended explains ${i} discrepancies)
    if(NOT explains_id STREQUAL id)
      message(FATAL_ERROR "extended.explains[${i}] is ${explains_id}, selected[${i}] ${id}")
    endif()
    # Several effects at once: each named effect explains at least one of the nominal model's findings of its own.
    if(EXPECT_SELECTED MATCHES "\\+" AND n_explained EQUAL 0)
      message(FATAL_ERROR "${id} is selected but explains none of the nominal model's findings")
    endif()
    # One that clears none on its own says so, on standard output and in the report (diagnosis_report.hpp).
    if(n_explained EQUAL 0)
      string(FIND "${out}" "clears none of the nominal model's findings on its own" said_in_summary)
      string(FIND "${report_md}" "clears none of the nominal model's findings on its own" said_in_report)
      if(said_in_summary EQUAL -1 OR said_in_report EQUAL -1)
        message(FATAL_ERROR "${id} explains none of the nominal model's findings and does not say so "
                            "(summary ${said_in_summary}, report ${said_in_report})")
      endif()
    endif()
    # The report's list of findings marks each one an extension explains with that extension.
    if(n_explained GREATER 0)
      string(REGEX MATCHALL "explained by `${id}`" marks "${report_md}")
      list(LENGTH marks n_marks)
      if(NOT n_marks EQUAL n_explained)
        message(FATAL_ERROR "the report marks ${n_marks} findings as explained by ${id}, the JSON ${n_explained}")
      endif()
    endif()
  endforeach()
endif()
# With one data file the findings in the report and on standard output do not repeat its path (the report's "Data:"
# line names it once).
if(index EQUAL 1 AND n_findings GREATER 0)
  string(FIND "${report_md}" "/data0.csv)" path_in_report)
  string(FIND "${out}" "/data0.csv)" path_in_summary)
  if(path_in_report GREATER -1 OR path_in_summary GREATER -1)
    message(FATAL_ERROR "the findings repeat the data file's path (${path_in_report}, ${path_in_summary})")
  endif()
endif()
if(EXPECT_SELECTED MATCHES "\\+")
  # Several effects at once ("A+B", "A+B+C"): every one selected, in any order, and nothing else.
  string(REPLACE "+" ";" expected_all "${EXPECT_SELECTED}")
  list(SORT expected_all)
  set(sorted_selected ${all_selected})
  list(SORT sorted_selected)
  if(NOT sorted_selected STREQUAL expected_all)
    message(FATAL_ERROR "selected '${all_selected}', expected all of ${EXPECT_SELECTED} and nothing else")
  endif()
elseif(EXPECT_SELECTED AND NOT selected STREQUAL EXPECT_SELECTED)
  message(FATAL_ERROR "selected '${selected}', expected ${EXPECT_SELECTED}")
elseif(EXPECT_SELECTED AND NOT EXPECT_ALSO AND NOT n_selected EQUAL 1)
  # One effect: named once, with nothing beside it (a second filter on the same sensor is an extra effect).
  message(FATAL_ERROR "selected '${all_selected}', expected ${EXPECT_SELECTED} alone")
endif()
string(JSON n_variants LENGTH "${json}" selected_variants)
if(NOT n_variants EQUAL n_selected)
  message(FATAL_ERROR "selected_variants has ${n_variants} entries for ${n_selected} selected")
endif()
if(EXPECT_ALSO AND NOT EXPECT_ALSO IN_LIST all_selected)
  message(FATAL_ERROR "selected '${all_selected}', expected ${EXPECT_ALSO} among them")
endif()
# An error of the measurement chain alone is never answered with a structural extension as well.
if(EXPECT_SELECTED MATCHES "^measurement_chain:" AND NOT EXPECT_ALSO AND NOT EXPECT_SELECTED MATCHES "\\+")
  foreach(id IN LISTS all_selected)
    if(NOT id MATCHES "^measurement_chain:")
      message(FATAL_ERROR "a structural extension (${id}) beside the chain's error: selected '${all_selected}'")
    endif()
  endforeach()
endif()
if(verdict STREQUAL "extended" AND NOT EXISTS "${WORK_DIR}/extended.mdl")
  message(FATAL_ERROR "extended, but no extended model was written")
endif()
# -DEXPECT_VARIANT="a|b": the selected candidate's variant (the element an untie frees) must be one of these.
if(EXPECT_VARIANT)
  cmake_policy(SET CMP0057 NEW)  # if(IN_LIST) in script mode
  string(REPLACE "|" ";" EXPECT_VARIANT "${EXPECT_VARIANT}")
  set(variant "")
  if(n_selected GREATER 0)
    string(JSON variant GET "${json}" selected_variants 0)
  endif()
  if(NOT variant IN_LIST EXPECT_VARIANT)
    message(FATAL_ERROR "selected ${selected} with variant '${variant}', expected one of ${EXPECT_VARIANT}")
  endif()
endif()
# One feature is one finding: no two of the nominal model's discrepancies share kind, channel, data set and
# frequency (a wide band and the sub-band standing out inside it were once listed twice).
cmake_policy(SET CMP0057 NEW)  # if(IN_LIST) in script mode
string(JSON n_found LENGTH "${json}" discrepancies)
set(seen "")
if(n_found GREATER 0)
  math(EXPR last "${n_found} - 1")
  foreach(i RANGE ${last})
    string(JSON kind GET "${json}" discrepancies ${i} kind)
    string(JSON channel GET "${json}" discrepancies ${i} channel)
    string(JSON data_set GET "${json}" discrepancies ${i} data_set)
    string(JSON f GET "${json}" discrepancies ${i} f_hz)
    set(key "${kind} ${channel} ${data_set} ${f}")
    if(key IN_LIST seen)
      message(FATAL_ERROR "a finding listed twice: ${key}")
    endif()
    list(APPEND seen "${key}")
  endforeach()
endif()
# The factor a measurement-chain candidate estimates, against the truth's (the generator's own record of it).
if(EXPECT_FACTOR)
  string(REPLACE ":" ";" factor_args "${EXPECT_FACTOR}")
  list(GET factor_args 0 factor_param)
  list(GET factor_args 1 factor_tolerance)
  execute_process(COMMAND "${PYTHON}" -c "
import json, re, sys
d = json.load(open(sys.argv[1])); t = json.load(open(sys.argv[2]))
m = re.search(r'^param\\s+' + sys.argv[3] + r'\\s*=\\s*(\\S+)', open(sys.argv[5]).read(), re.M)
got = float(m.group(1))
truth = t['measurement_chain'][0]['factor']
tol = float(sys.argv[4])
print('%s = %.6g, the truth %.6g (relative error %.2g, tolerance %s)' % (sys.argv[3], got, truth, abs(got / truth - 1), tol))
said = [float(x) for e in d['extended']['explains'] for x in re.findall(r' (?:reads|is) (-?[0-9.e+-]+) \\+- ', e['description'])]
print('the extended model is described as reading:', said)
sys.exit(0 if abs(got / truth - 1) <= tol and any(abs(s / truth - 1) <= tol for s in said) else 1)
" "${WORK_DIR}/diagnosis.json" "${WORK_DIR}/data0.truth.json" "${factor_param}" "${factor_tolerance}"
                          "${WORK_DIR}/extended.mdl"
                  RESULT_VARIABLE status OUTPUT_VARIABLE factor_out ERROR_VARIABLE factor_err)
  message(STATUS "${factor_out}")
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "the estimated factor is off: ${factor_out}${factor_err}")
  endif()
endif()
