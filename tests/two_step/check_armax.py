#!/usr/bin/env python3
"""Two-step from records: step one by ARMAX against step one by ARX, on data from the independent generator.

    check_armax.py MBGEN TRUTHGEN WORKDIR EXAMPLE DRAW

Makes a 40 dB record of EXAMPLE (mdof2 or spindle; case nominal, white noise on the outputs) whose truth is drawn from
DRAW, and the noiseless FRFs of the same truth (--snr-db inf: the truth's own transfer functions). Fits the record by
`--method two-step` with `--two-step-model arx` and `armax` (step two's default route) and requires of ARMAX:
  - its identified transfer function closer to the truth's than ARX's: the RMS over channels of the relative error
    |H_identified - H_truth| / |H_truth| on the FRF lines up to 1.2 times the highest identified mode (above it the
    spindle's fifth x mode, which neither shows at 40 dB, would dominate both);
  - its parameters' RMS relative error below ARX's.
The truth files are read only to score the results. Exit 1 on failure.
"""
import json
import os
import subprocess
import sys

import numpy as np


def run(cmd):
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        sys.exit("command failed (%d): %s\n%s%s" % (p.returncode, " ".join(cmd), p.stdout, p.stderr))
    return p.stdout


def read_frf(path):
    """The truthgen FRF CSV: the frequencies and per channel name (OUTPUT/INPUT) the complex values."""
    rows = [line.strip() for line in open(path) if line.strip() and not line.startswith("#")]
    header = rows[0].split(",")
    values = np.array([[float(x) for x in r.split(",")] for r in rows[1:]])
    channels = {}
    for i, name in enumerate(header):
        if name.endswith(".re"):
            channels[name[:-3]] = values[:, i] + 1j * values[:, header.index(name[:-3] + ".im")]
    return values[:, 0], channels


def tf_error(result, f_hz, truth_frf):
    """RMS over channels of the identified transfer function's RMS relative error, lines up to 1.2 x its highest
    mode; and the per-channel values."""
    one = result["method_details"]["two_step"]["step_one"][0]
    den = np.array(one["denominator"])[::-1]  # descending powers for numpy
    top = 1.2 * max(abs(np.roots(den))) / (2 * np.pi)
    lines = f_hz <= top
    s = 2j * np.pi * f_hz[lines]
    per = {}
    for output, num in one["numerators"].items():
        h = np.polyval(np.array(num)[::-1], s) / np.polyval(den, s)
        t = truth_frf[output + "/" + one["input"]][lines]
        per[output] = float(np.sqrt(np.mean(np.abs(h - t) ** 2 / np.abs(t) ** 2)))
    return float(np.sqrt(np.mean([v * v for v in per.values()]))), per


def parameter_rms(result, truth):
    errs = [(p["value"] - truth[n]) / truth[n] for n, p in result["parameters"].items() if p["identifiable"]]
    return float(np.sqrt(np.mean(np.square(errs))))


def main():
    mbgen, truthgen, work, example, draw = sys.argv[1:6]
    os.makedirs(work, exist_ok=True)
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    model = os.path.join(root, "examples", example, example + ".mdl")
    record = os.path.join(work, "%s_time_%s.csv" % (example, draw))
    frf = os.path.join(work, "%s_frf_%s_noiseless.csv" % (example, draw))
    run([sys.executable, truthgen, "--example", example, "--case", "nominal", "--kind", "time", "--seed",
         str(100 + int(draw)), "--draw", draw, "-o", record])
    run([sys.executable, truthgen, "--example", example, "--case", "nominal", "--kind", "frf", "--snr-db", "inf",
         "--draw", draw, "-o", frf])
    truth = json.load(open(record[:-4] + ".truth.json"))["parameters"]
    f_hz, truth_frf = read_frf(frf)
    scores = {}
    for step_one in ("arx", "armax"):
        out = os.path.join(work, "%s.json" % step_one)
        run([mbgen, "fit", model, "--data", record, "--method", "two-step", "--two-step-model", step_one,
             "--json", out])
        result = json.load(open(out))
        tf, per = tf_error(result, f_hz, truth_frf)
        scores[step_one] = (tf, parameter_rms(result, truth))
        print("%-5s transfer function error %.4f (%s), parameters' RMS error %.4f, route %s"
              % (step_one, tf, ", ".join("%s %.4f" % kv for kv in per.items()), scores[step_one][1],
                 result["method_details"]["two_step"]["step_two"]["route"]))
    failures = []
    if not scores["armax"][0] < scores["arx"][0]:
        failures.append("ARMAX's transfer function (%.4f) is not closer to the truth than ARX's (%.4f)"
                        % (scores["armax"][0], scores["arx"][0]))
    if not scores["armax"][1] < scores["arx"][1]:
        failures.append("ARMAX's parameters (RMS %.4f) are not closer to the truth than ARX's (%.4f)"
                        % (scores["armax"][1], scores["arx"][1]))
    for f in failures:
        print("FAIL: " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
