# `fit --method modal` on the spindle (docs/methods.md#modal). "slow" in the name: 30 s in the normal build, over a
# minute under the sanitizers, whose pass skips it (the mdof2 cases of methods_modal.cmake run there). On a slower
# machine beside other tests it took 97-210 s, beyond the default limits (120 s, each run's 60 s):
# ctest-timeout: 600
include(${CMAKE_CURRENT_LIST_DIR}/cli_support.cmake)

# The spindle, its x FRFs, the damping known (8 damping parameters, 4 modes in the data): the y/z bearing stiffnesses
# move none of the four x modes (Sobol total index < 0.01) and are kept at their priors, not estimated; the five
# others reach the truth within 2 % (measured at most 1.5 %, k_hby); the subproblem {k_fx, k_hbx} finds local optima
# from some of its starts (measured 11 of 16 agree), reported with their costs.
file(READ "${SOURCE}/examples/spindle/spindle.mdl" spindle)
string(REGEX REPLACE "(param c_[a-z]+ *= *[0-9.e]+ *\"N s/m\") *estimate" "\\1 known" spindle "${spindle}")
file(WRITE "${WORK}/spindle_known_damping.mdl" "${spindle}")
expect_run(STATUS 0 STDOUT "modal\\)" TIMEOUT 300
  ARGS fit spindle_known_damping.mdl --data ${SOURCE}/examples/spindle/data/frf_Fx.csv
  --method modal --json s.json)
execute_process(COMMAND python3 -c "
import json, sys
r = json.load(open('s.json'))
t = json.load(open(sys.argv[1]))['parameters']
d = r['method_details']['modal']
bad = []
if not r['fit']['converged']: bad.append('not converged: ' + r['fit']['stop_reason'])
if sorted(d['partition']['not_influential']) != ['k_fy', 'k_fz', 'k_ry']: bad.append('not influential: %s' % d['partition']['not_influential'])
for name, p in r['parameters'].items():
    if name in ('k_fy', 'k_fz', 'k_ry'):
        if p['value'] != p['prior'] or p['identifiable']: bad.append(name + ' moved or claimed identifiable')
    elif abs(p['value'] / t[name] - 1) > 0.02: bad.append('%s = %g, truth %g' % (name, p['value'], t[name]))
reps = d['repetitions']['last_sweep']
if not any(s['agreeing'] < s['repetitions'] for s in reps): bad.append('no local optima reported')
for s in reps:
    if 2 * s['agreeing'] < s['repetitions'] or any(c <= 1.01 * s['best_cost'] for c in s['local_optimum_costs']): bad.append('spread %s' % s)
print('; '.join(bad))
" "${SOURCE}/examples/spindle/data/frf_Fx.truth.json" WORKING_DIRECTORY "${WORK}" OUTPUT_VARIABLE problems RESULT_VARIABLE status)
if(NOT status EQUAL 0 OR NOT problems STREQUAL "\n")
  message(SEND_ERROR "modal on the spindle: status ${status}: ${problems}")
endif()

# Truths drawn by truthgen (40 dB FRFs, the dampers known at the truth's values). From the priors the subproblem sweeps
# end at a wrong optimum on draws 2, 3 and 5 (k_hbz at its lower bound, k_hbx 56-66 % high; 1 of 16 repetitions
# reaching it); the joint repetitions (docs/methods.md#modal, step 6) find the optimum below it. Every draw must
# converge with its repetitions agreeing, and the five stiffnesses the x modes move lie within 2 % of the truth
# (measured at most 0.9 %, draw 3's k_hbz).
foreach(case IN ITEMS "2;52" "3;53" "4;54" "5;55")
  list(GET case 0 draw)
  list(GET case 1 seed)
  execute_process(COMMAND python3 ${SOURCE}/scripts/truthgen/truthgen.py --example spindle --case nominal --kind frf
                          --draw ${draw} --seed ${seed} --snr-db 40 -o draw${draw}.csv
                  WORKING_DIRECTORY "${WORK}" OUTPUT_QUIET RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "truthgen failed for draw ${draw}")
  endif()
  file(READ "${WORK}/draw${draw}.truth.json" truth)
  set(sets "")
  foreach(c IN ITEMS c_h c_fx c_fy c_fz c_rx c_ry c_hbx c_hby c_hbz)
    string(JSON value GET "${truth}" parameters ${c})
    list(APPEND sets --set ${c}=${value})
  endforeach()
  expect_run(STATUS 0 TIMEOUT 300
    ARGS fit spindle_known_damping.mdl --data draw${draw}.csv --method modal --json d${draw}.json
    ${sets})
  execute_process(COMMAND python3 -c "
import json, sys
r = json.load(open(sys.argv[1]))
t = json.load(open(sys.argv[2]))['parameters']
bad = []
if not r['fit']['converged']: bad.append('not converged: ' + r['fit']['stop_reason'])
if not r['method_details']['modal']['repetitions_agree']: bad.append('repetitions disagree')
for name in ('k_fx', 'k_rx', 'k_hbx', 'k_hby', 'k_hbz'):
    v = r['parameters'][name]['value']
    if abs(v / t[name] - 1) > 0.02: bad.append('%s = %g, truth %g' % (name, v, t[name]))
print('; '.join(bad))
" d${draw}.json draw${draw}.truth.json WORKING_DIRECTORY "${WORK}" OUTPUT_VARIABLE problems RESULT_VARIABLE status)
  if(NOT status EQUAL 0 OR NOT problems STREQUAL "\n")
    message(SEND_ERROR "modal on the spindle, draw ${draw}: status ${status}: ${problems}")
  endif()
endforeach()

# The shipped spindle model with every damper estimated: refused before fitting, naming the option that makes some of
# them known; following the advice fits (the refusal's option works).
expect_run(STATUS 1 STDERR "fewer than the 8 damping parameters to estimate .*; make at least 4 of them known with --fix NAME\\[=VALUE\\] \\(c_fx, c_fy"
  ARGS fit ${SOURCE}/examples/spindle/spindle.mdl --data ${SOURCE}/examples/spindle/data/frf_Fx.csv --method modal)
expect_run(STATUS 0 STDOUT "modal\\)" TIMEOUT 300
  ARGS fit ${SOURCE}/examples/spindle/spindle.mdl --data ${SOURCE}/examples/spindle/data/frf_Fx.csv --method modal
  --fix c_fy --fix c_fz --fix c_ry --fix c_hby)
