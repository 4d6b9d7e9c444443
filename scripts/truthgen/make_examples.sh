#!/usr/bin/env bash
# Regenerates the committed example data sets from their truth models (docs/truthgen.md).
set -euo pipefail
cd "$(dirname "$0")/../.."
tg() { /usr/bin/python3 scripts/truthgen/truthgen.py "$@"; }

tg --example mdof2 --case nominal --kind frf --snr-db 40 --seed 1 -o examples/mdof2/data/frf_F1.csv
tg --example mdof2 --case nominal --kind time --snr-db 40 --seed 2 -o examples/mdof2/data/time_F1.csv
tg --example spindle --case nominal --kind frf --snr-db 40 --seed 3 -o examples/spindle/data/frf_Fx.csv
tg --example spindle --case compliant_ground --kind frf --snr-db 40 --seed 4 \
   -o examples/spindle/data/frf_Fx_base_mode.csv
tg --example tower5 --case nominal --kind frf --snr-db 40 --seed 7 --draw 1 --no-coherence --force-sign -1 \
   -o examples/tower5/data/frf_roof_shaker.csv
