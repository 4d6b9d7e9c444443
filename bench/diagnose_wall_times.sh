#!/usr/bin/env bash
# The wall time of every diagnosis case of the test suite (tests/diagnosis: data from scripts/truthgen, each case
# one `mbgen diagnose` run plus its data generation, well under a second), run one at a time so that each has the
# machine's two cores to itself, against the speed targets: a spindle diagnosis from FRFs under 30 s, from a record
# under 60 s, a frame3 diagnosis (9 channels, 4096 lines) under 60 s. Cases of the other examples have no target;
# their time is printed. Run on an otherwise idle machine, with a Release build whose tests are built.
#   bench/diagnose_wall_times.sh [build-dir] [ctest-regex]      (default: every diagnose_slow case, extended included)
set -euo pipefail
cd "$(dirname "$0")/.."
build=$(realpath "${1:-build}")
filter=${2:-^diagnose_slow:}
log=$(mktemp)
trap 'rm -f "$log"' EXIT
ctest --test-dir "$build" -R "$filter" -j1 --output-on-failure > "$log" 2>&1 || true
printf '%-62s %9s %8s  %s\n' case seconds target verdict
# ctest's line: "  12/80 Test  #7: diagnose_slow:mdof2_control_frf ......   Passed   12.34 sec"
sed -n 's/^ *[0-9]*\/[0-9]* Test *#[0-9]*: \([^ ]*\) [ .*]*\([A-Za-z*][^0-9]*\) *\([0-9.]*\) sec$/\1 \3 \2/p' "$log" |
  while read -r name seconds status; do
    case "$name" in
      *spindle*_time*|*spindle*long_time*) target=60 ;;
      *spindle*) target=30 ;;
      *frame3*) target=60 ;;
      *) target=- ;;
    esac
    if [ "$target" = - ]; then verdict="no target"
    elif [ "$(echo "$seconds <= $target" | bc -l)" = 1 ]; then verdict=met
    else verdict="NOT met"; fi
    [ "$status" = Passed ] || verdict="$verdict (test $status)"
    printf '%-62s %9.1f %8s  %s\n' "$name" "$seconds" "$target" "$verdict"
  done
