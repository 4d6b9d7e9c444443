#!/usr/bin/env bash
# The diagnosis on hidden effects drawn at random: for each case, DRAWS truths drawn by the independent generator
# (scripts/truthgen --draw N: parameter offsets and the effect's size within the case's ranges) at 40 dB SNR, each
# diagnosed, and the outcomes counted: right (the expected extension alone, or no extension for a control), unexplained,
# wrong (another extension: the worst outcome), failed. A pair of effects ("A+B") is right when both are selected and
# nothing else; partial when only some of them are (nothing else); extra when the expected one is selected first and
# another after it (a spurious second effect). The statistical sweep behind the single-draw tests in
# tests/diagnosis (which keep CI short).
#   bench/diagnose_draws.sh [build-dir] [draws] [case-filter-regex]
#   e.g. bench/diagnose_draws.sh build 5 'mdof2.*frf'
# DRAWS_KEEP=DIR keeps each draw's diagnosis JSON and progress lines there (DIR/EXAMPLE_CASE_KIND_drawN.json, .log).
set -euo pipefail
cd "$(dirname "$0")/.."
mbgen=${1:-build}/compiler/mbgen
draws=${2:-5}
filter=${3:-.}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# example case kind expected [truthgen options]
cases=(
  "mdof2 nominal frf -"
  "mdof2 nominal frf - --no-coherence"
  "mdof2 nominal frf - --analyser 8"
  "mdof2 compliant_ground frf compliant_ground:wall"
  "mdof2 compliant_ground frf compliant_ground:wall --analyser 8"
  "mdof2 free_parameter frf free_parameter:c12"
  "mdof2 resonator frf resonator:mass1"
  "mdof2 resonator frf resonator:mass1 --no-coherence"
  "mdof2 outside_maxwell frf not_extended"
  "mdof2 sensor_lowpass frf sensor_dynamics:d2"
  "mdof2 sensor_highpass frf sensor_dynamics:d2"
  "mdof2 sensor_delay frf sensor_dynamics:d2"
  "mdof2 nominal time -"
  "mdof2 compliant_ground time compliant_ground:wall"
  "mdof2 outside_maxwell time not_extended"
  "mdof2 sensor_lowpass time sensor_dynamics:d2"
  "spindle nominal frf -"
  "spindle nominal frf - --analyser 8"
  "spindle compliant_ground frf compliant_ground:base"
  "spindle compliant_ground frf compliant_ground:base --analyser 8"
  "spindle base_on_feet frf compliant_ground:base"
  "spindle untie_parameter frf untie_parameter:k_hby"
  "spindle resonator frf resonator:spindle"
  "spindle sensor_lowpass frf sensor_dynamics:xs_front"
  "spindle outside_maxwell frf not_extended"
  "spindle nominal frf measurement_chain:gain:xs_rear --gain xs_rear=draw"
  "spindle nominal frf measurement_chain:gain:xh_front --gain xh_front=-1"
  "spindle nominal frf measurement_chain:input:Fx --force-sign -1"
  "spindle nominal frf measurement_chain:swap:xs_front,xs_rear --swap xs_front,xs_rear"
  "spindle nominal frf measurement_chain:gain:xs_front --unit xs_front=mm"
  "spindle untie_parameter frf measurement_chain:gain:xs_rear+untie_parameter:k_hby --gain xs_rear=draw"
  "spindle nominal frf measurement_chain:form:xs_front --frf-form xs_front=mobility"
  "spindle nominal frf measurement_chain:form:xh_front --frf-form xh_front=accelerance"
  "mdof2 nominal frf measurement_chain:form:d2 --frf-form d2=mobility"
  "frame3 nominal frf -"
  "frame3 outside_torsion frf not_extended"
  "tower5 nominal frf - --no-coherence"
  "tower5 nominal frf measurement_chain:input:F --no-coherence --force-sign -1"
  "tower5 nominal frf measurement_chain:gain:a5 --no-coherence --gain a5=-1"
  "spindle mount_and_mass frf untie_parameter:k_hby+added_mass:spindle"
  "spindle base_and_lowpass frf compliant_ground:base+sensor_dynamics:xs_front"
  "mdof2 wall_and_lowpass frf compliant_ground:wall+sensor_dynamics:d2"
)

printf '%-48s %6s %6s %12s %6s %6s %9s %7s %6s\n' case draws right unexplained wrong failed "s/draw" partial extra
for entry in "${cases[@]}"; do
  read -r example case kind expected options <<< "$entry"
  label="$example $case $kind ${options:-}"
  [[ "$label" =~ $filter ]] || continue
  right=0 unexplained=0 wrong=0 failed=0 partial=0 more=0
  t0=$(date +%s)
  for draw in $(seq 1 "$draws"); do
    data="$work/data.csv"
    extra=()
    [ "$kind" = time ] && extra=(--duration 2)
    [ "$example" = spindle ] && [ "$kind" = time ] && extra=(--duration 1)
    # shellcheck disable=SC2086
    python3 scripts/truthgen/truthgen.py --example "$example" --case "$case" --kind "$kind" --snr-db 40 \
      --seed $((1000 + draw)) --draw "$draw" ${options:-} "${extra[@]}" -o "$data" > /dev/null
    if ! "$mbgen" diagnose "examples/$example/$example.mdl" --data "$data" --json "$work/d.json" \
         > /dev/null 2> "$work/err"; then
      failed=$((failed + 1))
      continue
    fi
    if [ -n "${DRAWS_KEEP:-}" ]; then
      mkdir -p "$DRAWS_KEEP"
      kept="$DRAWS_KEEP/${example}_${case}_${kind}$(echo "${options:-}" | tr -c 'A-Za-z0-9=,\n' _)_draw$draw"
      cp "$work/d.json" "$kept.json"
      cp "$work/err" "$kept.log"
    fi
    read -r verdict selected < <(python3 -c "
import json; j = json.load(open('$work/d.json')); print(j['verdict'], '+'.join(j['selected']) or '-')")
    if [ "$expected" = - ]; then
      if [ "$verdict" = no_extension_justified ]; then right=$((right + 1))
      elif [ "$verdict" = extended ]; then wrong=$((wrong + 1))
      else unexplained=$((unexplained + 1)); fi
    elif [ "$expected" = not_extended ]; then
      if [ "$verdict" = extended ]; then wrong=$((wrong + 1)); else right=$((right + 1)); fi
    elif [[ "$expected" == *+* ]] && [ "$verdict" = extended ]; then
      # A pair: every selected extension must be one of the expected ones.
      outcome=$(python3 -c "
e = set('$expected'.split('+')); s = set('$selected'.split('+'))
print('right' if s == e else 'partial' if s < e else 'wrong')")
      case "$outcome" in right) right=$((right + 1)) ;; partial) partial=$((partial + 1)) ;; *) wrong=$((wrong + 1)) ;; esac
    elif [ "$verdict" = extended ] && [ "$selected" = "$expected" ]; then right=$((right + 1))
    elif [ "$verdict" = extended ] && [ "${selected%%+*}" = "$expected" ]; then more=$((more + 1))
    elif [ "$verdict" = extended ]; then wrong=$((wrong + 1))
    else unexplained=$((unexplained + 1)); fi
  done
  per=$(( ($(date +%s) - t0) / draws ))
  printf '%-48s %6d %6d %12d %6d %6d %9d %7d %6d\n' "$label" "$draws" "$right" "$unexplained" "$wrong" "$failed" \
    "$per" "$partial" "$more"
done
