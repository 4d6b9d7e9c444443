#!/usr/bin/env bash
# The wall time of every diagnosis case of the test suite (tests/diagnosis: data from scripts/truthgen, each case
# one `mbgen diagnose` run plus its data generation, well under a second), run one at a time so that each has the
# machine's two cores to itself, against the speed targets: a spindle diagnosis from FRFs under 30 s, from a record
# under 60 s, a frame3 diagnosis (9 channels, 4096 lines) under 60 s. Cases of the other examples have no target;
# their time is printed. Run on an otherwise idle machine, with a Release build whose tests are built.
# The machine's pace (bench/machine_pace: a fixed Eigen-only workload, before and after the cases) scales each case's
# seconds to the reference machine's pace (MACHINE_PACE_REFERENCE, the figure of the run in bench/README.md), so
# that a case's time can be compared across machines and sessions; the verdict is given for both.
#   bench/diagnose_wall_times.sh [build-dir] [ctest-regex]      (default: every diagnose_slow case, extended included)
set -euo pipefail
cd "$(dirname "$0")/.."
build=$(realpath "${1:-build}")
filter=${2:-^diagnose_slow:}
reference=${MACHINE_PACE_REFERENCE:-0.870}  # the run of the table in bench/README.md
log=$(mktemp)
trap 'rm -f "$log"' EXIT
pace() { "$build/bench/machine_pace" | sed -n 's/^machine pace: \([0-9.]*\) s.*/\1/p'; }
before=$(pace)
ctest --test-dir "$build" -R "$filter" -j1 --output-on-failure > "$log" 2>&1 || true
after=$(pace)
scale=$(echo "$reference * 2 / ($before + $after)" | bc -l)
printf 'machine pace: %s s before the cases, %s s after; reference %s s: seconds times %.3f at the reference pace\n' \
  "$before" "$after" "$reference" "$scale"
printf '%-62s %9s %9s %8s  %s\n' case seconds at_ref target verdict
# ctest's line: "  12/80 Test  #7: diagnose_slow:mdof2_control_frf ......   Passed   12.34 sec"
sed -n 's/^ *[0-9]*\/[0-9]* Test *#[0-9]*: \([^ ]*\) [ .*]*\([A-Za-z*][^0-9]*\) *\([0-9.]*\) sec$/\1 \3 \2/p' "$log" |
  while read -r name seconds status; do
    case "$name" in
      *spindle*_time*|*spindle*long_time*) target=60 ;;
      *spindle*) target=30 ;;
      *frame3*) target=60 ;;
      *) target=- ;;
    esac
    at_ref=$(echo "$seconds * $scale" | bc -l)
    if [ "$target" = - ]; then verdict="no target"
    elif [ "$(echo "$seconds <= $target" | bc -l)" = 1 ]; then verdict=met
    elif [ "$(echo "$at_ref <= $target" | bc -l)" = 1 ]; then verdict="met at the reference pace"
    else verdict="NOT met"; fi
    [ "$status" = Passed ] || verdict="$verdict (test $status)"
    printf '%-62s %9.1f %9.1f %8s  %s\n' "$name" "$seconds" "$at_ref" "$target" "$verdict"
  done
