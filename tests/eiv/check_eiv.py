#!/usr/bin/env python3
"""`mbgen fit --method eiv` (errors in variables) against output error on mdof2 records whose measured force is
noisy, made by the independent truth-model generator (scripts/truthgen, numpy) with drawn truths.

usage: check_eiv.py MBGEN TRUTHGEN SOURCE_DIR WORK_DIR

Six draws (truthgen --draw 101..106, noise seeds 7101..7106; chosen before any result was seen), 16 s at 2048 Hz,
output noise 40 dB, the written force with white noise at 30, 36, 42, 48, 54, 60 dB (the structure driven by the
clean force). For every parameter of every draw z = (estimate - truth) / reported std, for the eiv estimate and for
the output-error estimate it started from (method_details.eiv, the same data). Asserted:
  - eiv: RMS z over the 42 values within 0.75-1.3 (an honest std gives 1; the RMS of 42 standard normal values has
    a standard error of about 0.11), and every |z| below 4;
  - output error on the same data is worse: its RMS z at least 1.5 times eiv's (its std ignores the force noise);
  - eiv's force noise level within 10 % of the truth's (truth JSON noise.input_sigma).
The truth JSON is read only to compare with; the verdict is this script's.
"""
import json
import math
import os
import shutil
import subprocess
import sys

DRAWS = range(101, 107)
INPUT_SNR_DB = {101: 30, 102: 36, 103: 42, 104: 48, 105: 54, 106: 60}
RMS_BAND = (0.75, 1.3)
MAX_Z = 4.0
OE_FACTOR = 1.5
NOISE_LEVEL_TOLERANCE = 0.10


def run(cmd):
    print("$", " ".join(cmd))
    p = subprocess.run(cmd, capture_output=True, text=True)
    print(p.stdout, p.stderr)
    if p.returncode != 0:
        sys.exit(f"failed with status {p.returncode}")


def main():
    mbgen, truthgen, source, work = sys.argv[1:5]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    model = os.path.join(source, "examples", "mdof2", "mdof2.mdl")
    z_eiv, z_oe, failures = [], [], []
    for draw in DRAWS:
        data = os.path.join(work, f"draw{draw}.csv")
        run([sys.executable, truthgen, "--example", "mdof2", "--case", "nominal", "--kind", "time", "--fs", "2048",
             "--duration", "16", "--snr-db", "40", "--input-snr-db", str(INPUT_SNR_DB[draw]), "--seed",
             str(7000 + draw), "--draw", str(draw), "-o", data])
        with open(data[:-4] + ".truth.json") as f:
            truth_doc = json.load(f)
        truth = truth_doc["parameters"]
        out = data[:-4] + "_eiv.json"
        run([mbgen, "fit", model, "--data", data, "--method", "eiv", "--json", out])
        with open(out) as f:
            result = json.load(f)
        if result["method"] != "eiv":
            failures.append(f"draw {draw}: method {result['method']!r}, not 'eiv'")
        details = result["method_details"]["eiv"]
        for name, p in sorted(result["parameters"].items()):
            if p.get("std") is None:
                failures.append(f"draw {draw}: {name} has no std")
                continue
            ze = (p["value"] - truth[name]) / p["std"]
            zo = (details["output_error_estimate"][name] - truth[name]) / details["output_error_std"][name]
            print(f"draw {draw} ({INPUT_SNR_DB[draw]} dB) {name:4s} z eiv {ze:7.2f}   z output error {zo:7.2f}")
            z_eiv.append(ze)
            z_oe.append(zo)
        found = details["noise"][0]["input_sigma"]["F1"]
        stated = truth_doc["noise"]["input_sigma"]["F1"]
        if abs(found / stated - 1) > NOISE_LEVEL_TOLERANCE:
            failures.append(f"draw {draw}: force noise {found:.4g} found, {stated:.4g} in the truth")
    rms = lambda v: math.sqrt(sum(x * x for x in v) / len(v))
    rms_eiv, rms_oe = rms(z_eiv), rms(z_oe)
    worst = max(abs(v) for v in z_eiv)
    print(f"eiv: RMS z {rms_eiv:.3f} over {len(z_eiv)}, max |z| {worst:.2f}; output error: RMS z {rms_oe:.3f}")
    if not RMS_BAND[0] <= rms_eiv <= RMS_BAND[1]:
        failures.append(f"eiv RMS z {rms_eiv:.3f} outside {RMS_BAND}")
    if worst >= MAX_Z:
        failures.append(f"eiv max |z| {worst:.2f} >= {MAX_Z}")
    if rms_oe < OE_FACTOR * rms_eiv:
        failures.append(f"output error's RMS z {rms_oe:.3f} is not {OE_FACTOR} times eiv's {rms_eiv:.3f}")
    for f in failures:
        print("FAILED:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
