#!/usr/bin/env bash
# Compile time of the emitted C++ at machine scale (issue 14): the chain of N six-coordinate bodies
# (compiler/symbolic/test_chain_model.hpp) for each N, emitted with `mbgen MODEL.mdl -o OUT.cpp --parts P`, then
# every translation unit compiled with `$CXX -std=c++17 -O2 -c` (as a project's Release build would). Prints per
# N and P: the CPU time of all units together (user + system), the longest single unit (the wall time of a build
# with P free cores), the largest unit's peak memory, and the source size.
#
#   bench/compile_chain.sh [BUILD] [N...]        (default BUILD=build, N = 4 8 16 32; P = 1 and 4)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
shift || true
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(4 8 16 32)
cmake --build "$build" -j1 --target mbgen write_chain_model >/dev/null
mbgen=$build/compiler/mbgen
writer=$build/tests/generated_code/write_chain_model
cxx=${CXX:-c++}
eigen=$(pkg-config --cflags eigen3 2>/dev/null || echo -I/usr/include/eigen3)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

printf '%4s %5s %6s | %9s %9s | %12s %12s %10s\n' N DOF parts "mbgen [s]" "src [kB]" "CPU all [s]" "longest [s]" "peak [MB]"
for n in "${sizes[@]}"; do
  "$writer" "$n" "$work/chain$n.mdl"
  for parts in 1 4; do
    dir=$work/n${n}_p$parts
    mkdir -p "$dir"
    start=$(date +%s.%N)
    "$mbgen" "$work/chain$n.mdl" -o "$dir/chain_model.cpp" --parts "$parts"
    emit=$(echo "$(date +%s.%N) - $start" | bc)
    kb=$(cat "$dir"/*.cpp "$dir"/*.hpp | wc -c)
    cpu=0 longest=0 peak=0
    for src in "$dir"/*.cpp; do
      # %U %S %e %M: user, system, wall seconds, peak resident kB
      read -r user sys wall mem < <( { /usr/bin/time -f '%U %S %e %M' "$cxx" -std=c++17 -O2 $eigen -Iruntime/include \
          -I"$dir" -c "$src" -o "$src.o" 2>&1 1>/dev/null; } | tail -1)
      cpu=$(echo "$cpu + $user + $sys" | bc)
      longest=$(echo "if ($user + $sys > $longest) $user + $sys else $longest" | bc)
      [ "$mem" -gt "$peak" ] && peak=$mem
    done
    printf '%4d %5d %6d | %9.2f %9d | %12.2f %12.2f %10.0f\n' "$n" $((6 * n)) "$parts" "$emit" $((kb / 1024)) \
      "$cpu" "$longest" "$(echo "$peak / 1024" | bc)"
  done
done
