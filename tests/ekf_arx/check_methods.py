#!/usr/bin/env python3
"""`mbgen fit --method ekf` and `--method arx-two-stage` on mdof2 time records made by the independent truth-model
generator (scripts/truthgen, numpy), with the truth drawn at random (--draw).

usage: check_methods.py accuracy MBGEN TRUTHGEN SOURCE_DIR WORK_DIR DRAW
         40 dB. ekf on examples/mdof2/mdof2.mdl (all seven parameters, from the model's nominal values): each within
         3 of its std of the truth and within the stated relative errors. arx-two-stage on the same record with the
         masses known (tests/ekf_arx/mdof2_known_mass.mdl, --set to the truth's masses, as weighed): the stiffnesses
         within the stated relative errors (its dampings are reported, not asserted: see docs/methods.md).
       check_methods.py spindle MBGEN TRUTHGEN SOURCE_DIR WORK_DIR DRAW
         ekf on a 1 s spindle record (8192 Hz, x force, three x sensors), 40 dB, from the model's nominal values: the
         ten parameters the x motion moves within 3 of their std and the stated relative errors; the six it does not
         move (the y/z bearing stiffnesses and dampers) left near their priors with about their prior std (30 %),
         not claimed known.
       check_methods.py noise MBGEN TRUTHGEN SOURCE_DIR WORK_DIR DRAW
         arx-two-stage at 60, 40 and 20 dB on the same draw, force and noise sequence: the mean relative error of the
         stiffnesses grows with the noise (Tikrit 2024, Fig. 7).
The truth JSON is read only to compare with (and for the known masses); the verdict is this script's.
"""
import json
import os
import shutil
import subprocess
import sys

STIFFNESSES = ("k11", "k22", "k12")
# Relative errors the ekf reaches at 40 dB on 2 s records with its default drift, about 3 of its std (measured on
# draws 1-6: at most 1.0 % for the masses and stiffnesses (std 0.4-0.9 %), 0.5 % for c11, 4.5 % for c22 (std 5-8 %)).
EKF_LIMITS = {"m1": 0.025, "m2": 0.025, "k11": 0.025, "k22": 0.025, "k12": 0.025, "c11": 0.05, "c22": 0.2}
# The spindle's x record (1 s at 8192 Hz, noise seeds 31-32): measured on draws 1-2 the bearings' k_fx, k_rx within
# 0.23 %, the mounts' stiffnesses 0.67 %, c_fx, c_rx 1.1 %, the mounts' dampers 5.2 %, all within 1.1 std; the limits
# below are two to ten times that. The y/z-plane parameters are not moved by an x force (modal's Sobol indices
# are 0 for them too), so the filter must leave them where they start, uncertain.
SPINDLE_SEEN = {"k_fx": 0.01, "k_rx": 0.01, "k_hbx": 0.02, "k_hby": 0.02, "k_hbz": 0.02,
                "c_fx": 0.05, "c_rx": 0.05, "c_hbx": 0.10, "c_hby": 0.15, "c_hbz": 0.15}
SPINDLE_UNSEEN = ("k_fy", "k_fz", "k_ry", "c_fy", "c_fz", "c_ry")
# arx-two-stage at 40 dB, 4096 Hz: the ARX's noise bias (measured on draws 1-6: up to 2.1 %, k22 the worst).
ARX_STIFFNESS_LIMIT = 0.04


def run(cmd):
    print("$", " ".join(cmd))
    p = subprocess.run(cmd, capture_output=True, text=True)
    print(p.stdout, p.stderr)
    if p.returncode != 0:
        sys.exit(f"failed with status {p.returncode}")


def record(truthgen, work, draw, snr):
    out = os.path.join(work, f"draw{draw}_{snr}dB.csv")
    run([sys.executable, truthgen, "--example", "mdof2", "--case", "nominal", "--kind", "time", "--snr-db", str(snr),
         "--seed", str(20 + draw), "--draw", str(draw), "-o", out])
    with open(out[:-4] + ".truth.json") as f:
        return out, json.load(f)["parameters"]


def fit(mbgen, model, data, method, work, extra=()):
    out = os.path.join(work, os.path.basename(data)[:-4] + "_" + method + ".json")
    run([mbgen, "fit", model, "--data", data, "--method", method, "--json", out, *extra])
    with open(out) as f:
        return json.load(f)


def arx(mbgen, source, work, data, truth):
    model = os.path.join(source, "tests", "ekf_arx", "mdof2_known_mass.mdl")
    return fit(mbgen, model, data, "arx-two-stage", work, ["--set", f"m1={truth['m1']}", "--set", f"m2={truth['m2']}"])


def accuracy(mbgen, truthgen, source, work, draw):
    errors = []
    data, truth = record(truthgen, work, draw, 40)
    r = fit(mbgen, os.path.join(source, "examples", "mdof2", "mdof2.mdl"), data, "ekf", work)
    for name, limit in EKF_LIMITS.items():
        p = r["parameters"][name]
        rel = abs(p["value"] / truth[name] - 1)
        z = abs(p["value"] - truth[name]) / p["std"]
        line = f"ekf {name}: {p['value']:.6g} +- {p['std']:.3g}, truth {truth[name]:.6g}: {rel:.2%}, {z:.2f} std"
        print(line)
        if rel > limit or z > 3:
            errors.append(line)
    a = arx(mbgen, source, work, data, truth)
    for name in STIFFNESSES + ("c11", "c22"):
        p = a["parameters"][name]
        rel = abs(p["value"] / truth[name] - 1)
        line = f"arx-two-stage {name}: {p['value']:.6g}, truth {truth[name]:.6g}: {rel:.2%}"
        print(line)
        if name in STIFFNESSES and rel > ARX_STIFFNESS_LIMIT:
            errors.append(line)
    return errors


def spindle(mbgen, truthgen, source, work, draw):
    errors = []
    out = os.path.join(work, f"spindle_draw{draw}.csv")
    run([sys.executable, truthgen, "--example", "spindle", "--case", "nominal", "--kind", "time", "--duration", "1",
         "--seed", str(30 + draw), "--draw", str(draw), "-o", out])
    with open(out[:-4] + ".truth.json") as f:
        truth = json.load(f)["parameters"]
    r = fit(mbgen, os.path.join(source, "examples", "spindle", "spindle.mdl"), out, "ekf", work)
    for name, p in sorted(r["parameters"].items()):
        rel = abs(p["value"] / truth[name] - 1)
        z = abs(p["value"] - truth[name]) / p["std"]
        moved = abs(p["value"] / p["prior"] - 1)
        line = (f"ekf {name}: {p['value']:.6g} +- {p['std']:.3g}, prior {p['prior']:.6g}, truth {truth[name]:.6g}: "
                f"{rel:.2%}, {z:.2f} std, moved {moved:.2%}")
        print(line)
        if name in SPINDLE_SEEN and (rel > SPINDLE_SEEN[name] or z > 3):
            errors.append(line)
        if name in SPINDLE_UNSEEN and (moved > 0.01 or p["std"] < 0.25 * p["prior"]):
            errors.append(line + ": an unseen parameter moved or claimed known")
    if set(SPINDLE_SEEN) | set(SPINDLE_UNSEEN) != set(r["parameters"]):
        errors.append(f"parameters {sorted(r['parameters'])}")
    return errors


def noise(mbgen, truthgen, source, work, draw):
    means = []
    for snr in (60, 40, 20):
        data, truth = record(truthgen, work, draw, snr)
        a = arx(mbgen, source, work, data, truth)
        mean = sum(abs(a["parameters"][k]["value"] / truth[k] - 1) for k in STIFFNESSES) / len(STIFFNESSES)
        print(f"{snr} dB: mean relative stiffness error {mean:.3%}")
        means.append(mean)
    return [] if means[0] < means[1] < means[2] else [f"not growing with the noise: {means}"]


def main():
    if len(sys.argv) != 7 or sys.argv[1] not in ("accuracy", "spindle", "noise"):
        sys.exit(__doc__)
    mode, mbgen, truthgen, source, work, draw = sys.argv[1:]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    errors = {"accuracy": accuracy, "spindle": spindle, "noise": noise}[mode](mbgen, truthgen, source, work, int(draw))
    if errors:
        print("FAILED:\n  " + "\n  ".join(errors))
        sys.exit(1)
    print("passed")


if __name__ == "__main__":
    main()
