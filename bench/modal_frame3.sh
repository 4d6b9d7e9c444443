#!/usr/bin/env bash
# `mbgen modal` on a 9-channel, 4096-line FRF matrix made by the independent truth generator: frame3's 3 x 3
# accelerances (scripts/truthgen, nominal case, 40 dB), with and without the report, wall and CPU time (median of
# 3 runs each). Target (issue 16): seconds.
#   bench/modal_frame3.sh [build-dir]
set -euo pipefail
cd "$(dirname "$0")/.."
mbgen=$(realpath "${1:-build}/compiler/mbgen")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 scripts/truthgen/truthgen.py --example frame3 --case nominal --kind frf --seed 1 -o "$work/frame3.csv" > /dev/null
# wall and user+system seconds of one run
run() { /usr/bin/time -f '%e %U %S' "$@" 2>&1 > /dev/null | tail -1 | awk '{printf "%.2f %.2f\n", $1, $2 + $3}'; }
median() { sort -n | sed -n 2p; }
for label in "JSON only" "JSON and report"; do
  extra=()
  [[ $label == "JSON and report" ]] && extra=(--report "$work/report")
  walls=(); cpus=()
  for i in 1 2 3; do
    read -r wall cpu < <(run "$mbgen" modal --data "$work/frame3.csv" --json "$work/modal.json" "${extra[@]}")
    walls+=("$wall"); cpus+=("$cpu")
  done
  printf '%-16s wall %5.2f s, CPU %5.2f s (median of 3)\n' "$label:" "$(printf '%s\n' "${walls[@]}" | median)" \
    "$(printf '%s\n' "${cpus[@]}" | median)"
done
"$mbgen" modal --data "$work/frame3.csv" | head -5
