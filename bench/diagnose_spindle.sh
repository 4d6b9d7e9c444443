#!/usr/bin/env bash
# Speed of the full spindle diagnosis (all applicable candidates, both cores) beside the nominal fit on the same
# data, measured in the same run. Target (issue): the diagnosis under a minute on a 2-core machine.
#   bench/diagnose_spindle.sh [build-dir]
set -euo pipefail
cd "$(dirname "$0")/.."
mbgen=${1:-build}/compiler/mbgen
data=examples/spindle/data/frf_Fx_base_mode.csv
model=examples/spindle/spindle.mdl
seconds() { local t0 t1; t0=$(date +%s.%N); "$@" > /dev/null 2>&1; t1=$(date +%s.%N); echo "$t1 - $t0" | bc; }
fit=$(seconds "$mbgen" fit "$model" --data "$data")
diagnose=$(seconds "$mbgen" diagnose "$model" --data "$data")
printf 'nominal fit (16 starts):  %8.2f s\n' "$fit"
printf 'full diagnosis:           %8.2f s\n' "$diagnose"
printf 'ratio diagnosis / fit:    %8.1f\n' "$(echo "$diagnose / $fit" | bc -l)"
