# Fleets (docs/fleets.md): `monitor --manifest` items run through GNU parallel as a batch engine would; each item's
# directory appears whole; a rerun skips items whose inputs did not change and reruns the one that did; bad manifests
# are named by file, line and column.
include(${CMAKE_CURRENT_LIST_DIR}/cli_support.cmake)
write_model(one)

# Two machines of the one-mass model (one.mdl: k = 1000, c = 1, m1 estimated), five FRF sets each at about 40 dB,
# made here from the closed form H = 1/(k - m w^2 + i c w) with seeded additive noise: machine a keeps m1 = 2.3, machine b's
# m1 steps to 2.6 from set 3 on.
set(make_data [=[
import math, random, sys, os
work = sys.argv[1]
for machine, masses, seed in (("mill-a", [2.3] * 5, 11), ("mill-b", [2.3, 2.3, 2.3, 2.6, 2.6], 12)):
    os.makedirs(os.path.join(work, "fleet", machine), exist_ok=True)
    rng = random.Random(seed)
    for day, m in enumerate(masses):
        rows = ["f_hz,y/F.re,y/F.im"]
        fs = [0.5 + i * 0.05 for i in range(200)]
        hs = [1 / complex(1000 - m * (2 * math.pi * f) ** 2, 1 * 2 * math.pi * f) for f in fs]
        s = 0.01 * math.sqrt(sum(abs(h) ** 2 for h in hs) / len(hs)) / math.sqrt(2)  # additive, 40 dB below the RMS
        for f, h in zip(fs, hs):
            rows.append("%.6g,%.10g,%.10g" % (f, h.real + rng.gauss(0, s), h.imag + rng.gauss(0, s)))
        with open(os.path.join(work, "fleet", machine, "day-%d.csv" % day), "w") as out:
            out.write("\n".join(rows) + "\n")
]=])
file(WRITE "${WORK}/make_data.py" "${make_data}")
execute_process(COMMAND python3 make_data.py "${WORK}" WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "making the fleet's data failed")
endif()
file(COPY_FILE "${WORK}/one.mdl" "${WORK}/fleet/one.mdl")
file(WRITE "${WORK}/fleet/fleet.csv" "# two machines\nmachine,model,data\nmill-a,one.mdl,mill-a/day-*.csv\nmill-b,one.mdl,mill-b/*.csv\n")
set(MONITOR_OPTIONS --starts 2 --warm-starts 1 --no-diagnosis)

expect_run(STATUS 0 STDOUT "^2\n$" ARGS monitor --manifest fleet/fleet.csv --count)

# Both items through GNU parallel, as `parallel ... ::: $(seq 0 $((N-1)))` in the docs.
execute_process(COMMAND parallel --halt now,fail=1 "${MBGEN}" monitor --manifest fleet/fleet.csv --out results
                        --item "{}" ${MONITOR_OPTIONS} ::: 0 1
  WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "parallel run of the fleet: status ${status}\n${out}\n${err}")
endif()
foreach(machine mill-a mill-b)
  foreach(f monitor.json inputs.digest report/report.md .mbgen-report)
    if(NOT EXISTS "${WORK}/results/${machine}/${f}")
      message(SEND_ERROR "results/${machine}/${f} was not written")
    endif()
  endforeach()
endforeach()
file(READ "${WORK}/results/mill-a/monitor.json" a_json)
file(READ "${WORK}/results/mill-b/monitor.json" b_json)
string(JSON a_changes LENGTH "${a_json}" changes)
string(JSON b_changes LENGTH "${b_json}" changes)
if(NOT a_changes EQUAL 0)
  message(SEND_ERROR "machine a (no change) reported ${a_changes} changes")
endif()
if(b_changes EQUAL 1)
  string(JSON index GET "${b_json}" changes 0 index)
  string(JSON moved GET "${b_json}" changes 0 parameters 0)
  if(NOT index EQUAL 3 OR NOT moved STREQUAL "m1")
    message(SEND_ERROR "machine b: the change was found at set ${index} naming ${moved}; expected set 3, m1")
  endif()
else()
  message(SEND_ERROR "machine b (m1 steps at set 3) reported ${b_changes} changes, expected 1")
endif()

# A rerun is idempotent: both items up to date, nothing rewritten.
tree_state(before "${WORK}/results")
file(TIMESTAMP "${WORK}/results/mill-a/monitor.json" stamp_before "%s")
expect_run(STATUS 0 ARGS monitor --manifest fleet/fleet.csv --out results ${MONITOR_OPTIONS})
if(NOT LAST_STDERR MATCHES "mill-a: up to date" OR NOT LAST_STDERR MATCHES "mill-b: up to date")
  message(SEND_ERROR "a rerun did not skip the finished items:\n${LAST_STDERR}")
endif()
tree_state(after "${WORK}/results")
if(NOT before STREQUAL after)
  message(SEND_ERROR "a rerun changed the results")
endif()

# Other options make a different result: the items run again.
expect_run(STATUS 0 ARGS monitor --manifest fleet/fleet.csv --out results --item mill-a ${MONITOR_OPTIONS} --seed 2)
if(LAST_STDERR MATCHES "up to date")
  message(SEND_ERROR "a rerun with another seed was skipped:\n${LAST_STDERR}")
endif()

# A new day for machine b: only b runs again, and its series has six sets.
file(COPY_FILE "${WORK}/fleet/mill-b/day-4.csv" "${WORK}/fleet/mill-b/day-5.csv")
expect_run(STATUS 0 ARGS monitor --manifest fleet/fleet.csv --out results ${MONITOR_OPTIONS} --seed 2)
if(NOT LAST_STDERR MATCHES "mill-a: up to date" OR LAST_STDERR MATCHES "mill-b: up to date")
  message(SEND_ERROR "after a new data set of b only b should run:\n${LAST_STDERR}")
endif()
file(READ "${WORK}/results/mill-b/monitor.json" b_json)
string(JSON sets LENGTH "${b_json}" series)
if(NOT sets EQUAL 6)
  message(SEND_ERROR "machine b's rerun has ${sets} data sets, expected 6")
endif()

# Bad manifests and selections.
file(WRITE "${WORK}/fleet/bad_name.csv" "machine,model,data\nmill/a,one.mdl,mill-a/*.csv\n")
expect_run(STATUS 1 STDERR "^fleet/bad_name.csv:2:1: error: machine `mill/a`" ARGS monitor --manifest fleet/bad_name.csv --out r2)
file(WRITE "${WORK}/fleet/no_match.csv" "machine,model,data\nmill-a,one.mdl,mill-a/*.csv;nothing-*.csv\n")
expect_run(STATUS 1 STDERR "^fleet/no_match.csv:2:29: error: `nothing-\\*.csv` matches no file"
  ARGS monitor --manifest fleet/no_match.csv --out r2)
file(WRITE "${WORK}/fleet/twice.csv" "machine,model,data\nm,one.mdl,mill-a/*.csv\nm,one.mdl,mill-b/*.csv\n")
expect_run(STATUS 1 STDERR "^fleet/twice.csv:3:1: error: machine `m` is listed twice" ARGS monitor --manifest fleet/twice.csv --count)
file(WRITE "${WORK}/fleet/header.csv" "name,model,data\n")
expect_run(STATUS 1 STDERR "^fleet/header.csv:1:1: error: the header must be" ARGS monitor --manifest fleet/header.csv --count)
expect_run(STATUS 2 STDERR "--item: `7` is neither" ARGS monitor --manifest fleet/fleet.csv --out r2 --item 7)
expect_run(STATUS 2 ARGS monitor one.mdl --data one_frf.csv --manifest fleet/fleet.csv --out r2)
expect_run(STATUS 2 STDERR "--manifest needs --out" ARGS monitor --manifest fleet/fleet.csv)
if(EXISTS "${WORK}/r2")
  file(GLOB left "${WORK}/r2/*")
  if(left)
    message(SEND_ERROR "failed runs left ${left}")
  endif()
endif()
