#!/bin/sh
# The records of tests/modal's output-only cases, made by truthgen into DIR: mdof2 draw 1 as output-only records
# (two noise seeds: one record, and a second for merging), and a force-driven time record of 30 s (with its force
# column, which the test leaves out with --ignore). Usage: oma_test_data.sh DIR (python3 with numpy on PATH or
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
