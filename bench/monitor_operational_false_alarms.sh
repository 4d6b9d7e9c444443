#!/usr/bin/env bash
# The false-alarm rate of `mbgen monitor --output-only` (docs/monitor.md, "Monitoring in operation"): series with a
# temperature drift and no change, made by the independent truth generator (mdof2 draw 1, 24 output-only records of
# 20 s, a daily cycle of 4 degrees over 12 sets, a trend of 0.6 per set, scatter 0.3; seeds FIRST..FIRST+N-1), the
# first 12 sets the baseline. Counts the alarms over the 12 tested sets of each series: with the temperature
# measured (regression), without it (the `# condition` lines removed: principal components), and the raw
# frequencies (no compensation), against the stated 1 % per set.
#   bench/monitor_operational_false_alarms.sh [build-dir] [N] [FIRST]
set -euo pipefail
cd "$(dirname "$0")/.."
mbgen=$(realpath "${1:-build}/compiler/mbgen")
count=${2:-10}
first=${3:-100}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
reg=0 pca=0 raw=0 tested=0
for ((s = first; s < first + count; s++)); do
  /usr/bin/python3 scripts/truthgen/truthgen.py --example mdof2 --case nominal --kind oma --draw 1 --duration 20 \
    --series 24 --temperature 20,4,12,0.6,0.3 --seed "$s" -o "$work/s.csv"
  mkdir -p "$work/nc"
  args=() nc=()
  for f in "$work"/s_*.csv; do
    grep -v '^# condition ' "$f" > "$work/nc/$(basename "$f")"
    args+=(--data "$f")
    nc+=(--data "$work/nc/$(basename "$f")")
  done
  "$mbgen" monitor --output-only "${args[@]}" --baseline 12 --json "$work/r.json" > /dev/null 2>&1
  "$mbgen" monitor --output-only "${nc[@]}" --baseline 12 --json "$work/p.json" > /dev/null 2>&1
  read -r a b c < <(/usr/bin/python3 - "$work/r.json" "$work/p.json" <<'PY'
import json, sys
r, p = (json.load(open(f)) for f in sys.argv[1:3])
alarms = lambda d: sum(1 for s in d["series"] if s["alarm"])
print(alarms(r), alarms(p), len(r["uncompensated"]["alarms"]))
PY
)
  printf 'seed %d: alarms regression %d, principal components %d, uncompensated %d (of 12)\n' "$s" "$a" "$b" "$c"
  reg=$((reg + a)) pca=$((pca + b)) raw=$((raw + c)) tested=$((tested + 12))
done
printf 'over %d tested sets: regression %d (%.2f %%), principal components %d (%.2f %%), uncompensated %d (%.1f %%); stated 1 %%\n' \
  "$tested" "$reg" "$(awk -v a="$reg" -v t="$tested" 'BEGIN{print 100*a/t}')" "$pca" \
  "$(awk -v a="$pca" -v t="$tested" 'BEGIN{print 100*a/t}')" "$raw" "$(awk -v a="$raw" -v t="$tested" 'BEGIN{print 100*a/t}')"
