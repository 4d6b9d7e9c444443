#!/bin/sh
# The records of tests/modal's output-only cases, made by truthgen into DIR: mdof2 draw 1 as output-only records
# (two noise seeds: one record, and a second for merging), a force-driven time record of 120 s (with its force
# column, which the test leaves out with --ignore), and two setups of the spindle. Usage: oma_test_data.sh DIR (python3 with numpy on PATH or
# PYTHON set).
set -eu
dir=$1
py=${PYTHON:-/usr/bin/python3}
here=$(dirname "$0")
mkdir -p "$dir"
"$py" "$here/truthgen.py" --example mdof2 --case nominal --kind oma --draw 1 --seed 11 -o "$dir/mdof2.csv"
"$py" "$here/truthgen.py" --example mdof2 --case nominal --kind oma --draw 1 --seed 12 --duration 100 -o "$dir/mdof2_b.csv"
"$py" "$here/truthgen.py" --example mdof2 --case nominal --kind time --draw 1 --seed 13 --fs 1024 --duration 120 \
  --excitation gaussian -o "$dir/time_F1.csv"
# Two setups of the spindle's three sensors sharing xs_rear: (xs_front, xs_rear) and (xs_rear, xh_front), each cut
# from its own record (draw 1, seeds 41 and 42).
for seed in 41 42; do
  "$py" "$here/truthgen.py" --example spindle --case nominal --kind oma --draw 1 --seed $seed -o "$dir/spindle_$seed.csv"
done
"$py" - "$dir" <<'PY'
import sys
d = sys.argv[1]
for seed, drop in ((41, "xh_front"), (42, "xs_front")):
    lines = open("%s/spindle_%d.csv" % (d, seed)).read().splitlines()
    header = next(i for i, line in enumerate(lines) if not line.startswith("#"))
    j = lines[header].split(",").index(drop)
    out = [line if line.startswith("#") else ",".join(v for k, v in enumerate(line.split(",")) if k != j)
           for line in lines]
    open("%s/setup_%d.csv" % (d, seed), "w").write("\n".join(out) + "\n")
PY
