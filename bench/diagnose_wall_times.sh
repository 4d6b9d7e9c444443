#!/usr/bin/env bash
# The wall time of every diagnosis case of the test suite (tests/diagnosis: data from scripts/truthgen, each case
# one `mbgen diagnose` run plus its data generation, well under a second), run one at a time so that each has the
# machine's two cores to itself, against the speed targets: a spindle diagnosis from FRFs under 30 s, from a record
# under 60 s, a frame3 diagnosis (9 channels, 4096 lines) under 60 s. Cases of the other examples have no target;
# their time is printed. Run on an otherwise idle machine, with a Release build whose tests are built.
# The machine's pace (bench/machine_pace: a fixed Eigen-only workload, before the first case and after each) scales
# each case's seconds to the reference machine's pace (MACHINE_PACE_REFERENCE, the figure of the run in
# bench/README.md), by the mean of the paces measured just before and just after it: the pace moves by 10-40 % within
# minutes on a shared machine, so one figure for the whole run could not tell a change of the code from one of the
# machine. The verdict is given for both.
#   bench/diagnose_wall_times.sh [build-dir] [ctest-regex]      (default: every diagnose_slow case, extended included)
set -euo pipefail
cd "$(dirname "$0")/.."
build=$(realpath "${1:-build}")
filter=${2:-^diagnose_slow:}
reference=${MACHINE_PACE_REFERENCE:-0.870}  # the run of the table in bench/README.md
log=$(mktemp)
trap 'rm -f "$log"' EXIT
pace() { "$build/bench/machine_pace" | sed -n 's/^machine pace: \([0-9.]*\) s.*/\1/p'; }
# ctest -N's line: "  Test  #7: diagnose_slow:mdof2_control_frf"
mapfile -t cases < <(ctest --test-dir "$build" -N -R "$filter" | sed -n 's/^ *Test *#[0-9]*: \(.*\)$/\1/p')
printf '%-62s %9s %7s %9s %8s  %s\n' case seconds pace at_ref target verdict
before=$(pace)
first=$before
for name in "${cases[@]}"; do
  exact="^$(printf '%s' "$name" | sed 's/[][\.*^$+?(){}|]/\\&/g')\$"
  ctest --test-dir "$build" -R "$exact" -j1 --output-on-failure > "$log" 2>&1 || true
  after=$(pace)
  # ctest's line: "  1/1 Test #7: diagnose_slow:mdof2_control_frf ......   Passed   12.34 sec"
  read -r seconds status < <(sed -n 's/^ *[0-9]*\/[0-9]* Test *#[0-9]*: [^ ]* [ .*]*\([A-Za-z*][^0-9]*\) *\([0-9.]*\) sec$/\2 \1/p' \
                               "$log" | head -1) || { seconds=0; status="not run"; }
  pace_here=$(echo "($before + $after) / 2" | bc -l)
  before=$after
  case "$name" in
    *spindle*_time*|*spindle*long_time*) target=60 ;;
    *spindle*) target=30 ;;
    *frame3*) target=60 ;;
    *) target=- ;;
  esac
  at_ref=$(echo "$seconds * $reference / $pace_here" | bc -l)
  if [ "$target" = - ]; then verdict="no target"
  elif [ "$(echo "$seconds <= $target" | bc -l)" = 1 ]; then verdict=met
  elif [ "$(echo "$at_ref <= $target" | bc -l)" = 1 ]; then verdict="met at the reference pace"
  else verdict="NOT met"; fi
  [ "$status" = Passed ] || verdict="$verdict (test $status)"
  printf '%-62s %9.1f %7.3f %9.1f %8s  %s\n' "$name" "$seconds" "$pace_here" "$at_ref" "$target" "$verdict"
done
printf 'machine pace: %s s before the first case, %s s after the last; reference %s s\n' "$first" "$after" "$reference"
