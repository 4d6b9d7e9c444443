#!/usr/bin/env bash
# The diagnosis speed targets of the real-data issue, measured in one run on data made by scripts/truthgen:
#   - a frame-like 3-DOF model fitted to 4096 lines x 9 channels without coherence   (target: under 2 s)
#   - the spindle diagnosis from FRFs (3 channels, 1151 lines, a hidden base mode)    (target: under 15 s)
#   - the spindle diagnosis from a 1 s record at 8192 Hz (a hidden base mode)         (target: under 60 s)
# each beside the nominal fit on the same data (the ratio says what the diagnosis adds to one fit).
#   bench/speed_targets.sh [build-dir]      (Release build; run on an otherwise idle machine)
set -euo pipefail
cd "$(dirname "$0")/.."
mbgen=$(realpath "${1:-build}")/compiler/mbgen
truthgen=scripts/truthgen/truthgen.py
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 "$truthgen" --example frame3 --case nominal --kind frf --seed 83 --draw 3 --no-coherence -o "$work/frame3.csv"
python3 "$truthgen" --example spindle --case compliant_ground --kind frf --seed 32 -o "$work/spindle_frf.csv"
python3 "$truthgen" --example spindle --case compliant_ground --kind time --seed 52 --duration 1 \
  -o "$work/spindle_time.csv"

seconds() { local t0 t1; t0=$(date +%s.%N); "$@" > /dev/null 2>&1; t1=$(date +%s.%N); echo "$t1 - $t0" | bc; }
row() {  # name target seconds reference-seconds
  printf '%-34s %8.2f s   target %5.0f s  (%s)   %6.1f x its nominal fit (%.2f s)\n' "$1" "$3" "$2" \
    "$(echo "$3 <= $2" | bc -l | sed 's/1/met/;s/0/NOT met/')" "$(echo "$3 / $4" | bc -l)" "$4"
}
frame3_fit=$(seconds "$mbgen" fit examples/frame3/frame3.mdl --data "$work/frame3.csv")
printf '%-34s %8.2f s   target %5.0f s  (%s)\n' "frame3 fit (4096 lines, 9 ch.)" "$frame3_fit" 2 \
  "$(echo "$frame3_fit <= 2" | bc -l | sed 's/1/met/;s/0/NOT met/')"
for kind in frf time; do
  data="$work/spindle_$kind.csv"
  fit=$(seconds "$mbgen" fit examples/spindle/spindle.mdl --data "$data")
  diagnose=$(seconds "$mbgen" diagnose examples/spindle/spindle.mdl --data "$data")
  if [ "$kind" = frf ]; then row "spindle diagnosis from FRFs" 15 "$diagnose" "$fit"
  else row "spindle diagnosis from a 1 s record" 60 "$diagnose" "$fit"; fi
done
