#!/usr/bin/env bash
# `mbgen monitor` per data set against a warm-started fit (issue 16: no slower). Eight mdof2 FRF sets made by the
# independent truth generator (nominal case, 40 dB, different noise); the monitor without diagnosis, against one
# cold `mbgen fit` (16 starts) and one 4-start fit of a single set; CPU seconds (user + system), median of 3 runs.
# Per set, monitor = (monitor - cold fit) / 7: the later sets' warm fits plus their residual analysis.
#   bench/monitor_mdof2.sh [build-dir]
set -euo pipefail
cd "$(dirname "$0")/.."
mbgen=$(realpath "${1:-build}/compiler/mbgen")
model=examples/mdof2/mdof2.mdl
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
args=()
for i in 0 1 2 3 4 5 6 7; do
  python3 scripts/truthgen/truthgen.py --example mdof2 --case nominal --kind frf --seed $((900 + i)) \
    -o "$work/set$i.csv" > /dev/null
  args+=(--data "$work/set$i.csv")
done
cpu() { /usr/bin/time -f '%U %S' "$@" 2>&1 > /dev/null | tail -1 | awk '{printf "%.2f\n", $1 + $2}'; }
median() { sort -n | sed -n 2p; }
measure() { for i in 1 2 3; do cpu "$@"; done | median; }
monitor=$(measure "$mbgen" monitor "$model" "${args[@]}" --no-diagnosis --json "$work/m.json")
cold=$(measure "$mbgen" fit "$model" --data "$work/set0.csv" --json "$work/f.json")
warm=$(measure "$mbgen" fit "$model" --data "$work/set1.csv" --starts 4 --json "$work/f.json")
per_set=$(awk -v m="$monitor" -v c="$cold" 'BEGIN {printf "%.2f", (m - c) / 7}')
printf 'monitor, 8 sets:        %6.2f s CPU\n' "$monitor"
printf 'cold fit (16 starts):   %6.2f s CPU\n' "$cold"
printf 'monitor per later set:  %6.2f s CPU\n' "$per_set"
printf 'fit with 4 starts:      %6.2f s CPU\n' "$warm"
