#!/usr/bin/env python3
"""Every `mbgen fit --method` on the same data sets, in one run: parameter errors against the truth and time.

usage: bench/methods_table.py [MBGEN] [--draw N] [--work DIR] [--only LABEL ...]

Data: scripts/truthgen (the independent numpy generator), 40 dB, the truth drawn with --draw (default 1): mdof2 FRFs
(10-400 Hz), an mdof2 record (2 s at 4096 Hz), spindle FRFs (50-1200 Hz) and a spindle record (1 s at 8192 Hz).
Each method runs on each data set it accepts; a refusal (exit 1) is shown with its reason. Two-step from records
runs with step one by ARMAX (the default) and by ARX, and with the covariance weighting on both kinds of data.
arx-two-stage needs the masses known: it runs on tests/ekf_arx/mdof2_known_mass.mdl with the masses set to the
truth's, as weighed.
Errors are over the parameters each run reports identifiable (relative, per cent): the largest and the RMS. Time is
wall time of the whole command on this machine, so ratios between rows mean more than the seconds.
Prints a Markdown table (bench/README.md keeps the last one). Before it, the thesis's Table 5.3 (the changes of
mdof2's natural frequencies and damping ratios for a +-10 % change of each parameter) beside the same changes in
mbgen's mdof2 model (`mbgen inspect --set`, its modes), which say which parameters the two modes can determine.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TRUTHGEN = os.path.join(ROOT, "scripts", "truthgen", "truthgen.py")
# (label, --method, further arguments, data kinds it runs on: None = all). Two-step from records twice, step one by
# ARMAX (the default) and by ARX; and once with the covariance weighting (the Markov estimate) on both kinds.
METHODS = [
    ("auto", "auto", [], None),
    ("direct", "direct", [], None),
    ("two-step", "two-step", [], ("frf",)),
    ("two-step (ARMAX)", "two-step", [], ("time",)),
    ("two-step (ARX)", "two-step", ["--two-step-model", "arx"], ("time",)),
    ("two-step, covariance weighting", "two-step", ["--two-step-weighting", "covariance"], None),
    ("hybrid", "hybrid", [], None),
    ("ekf", "ekf", [], None),
    ("arx-two-stage", "arx-two-stage", [], None),
    ("modal", "modal", [], None),
    # The modal method with the dampers made known at the truth's values (--fix): the spindle's x FRFs show 4 modes,
    # fewer than its 9 damping parameters, so with them estimated it refuses.
    ("modal, dampers known", "modal-known-damping", [], ("frf",)),
]
DATA = [  # name, example, kind, extra truthgen arguments
    ("mdof2 FRF", "mdof2", "frf", []),
    ("mdof2 record", "mdof2", "time", ["--duration", "2"]),
    ("spindle FRF", "spindle", "frf", []),
    ("spindle record", "spindle", "time", ["--duration", "1"]),
]


# Thesis Table 5.3 as printed: per parameter and change (+10 %, -10 %) the changes in per cent of f1, f2, xi1, xi2
# (mode 1 the mass-1 mode, the higher one; "~ 0" printed as 0). Its k12 row is wrong as printed (the design notes:
# columns swapped, the -10 % case's sign).
THESIS_TABLE_5_3 = {
    "m1": ((-4.7, 0, -4.7, 0), (5.4, 0, 5.4, 0)),
    "m2": ((0, -4.7, 0, -4.7), (0, 5.4, 0, 5.4)),
    "k11": ((4.8, 0, -4.6, 0), (-5.0, 0, 5.3, 0)),
    "k22": ((0, 4.1, 0, -3.9), (0, -4.3, 0, 4.4)),
    "k12": ((0.8, 0.1, -0.6, -0.1), (0.8, 0.1, -0.6, -0.1)),
    "c11": ((0, 0, 10.0, 0), (0, 0, -10.0, 0)),
    "c22": ((0, 0, 0, 9.9), (0, 0, 0, -9.9)),
}


def modes(mbgen, model, values):
    """(f1, f2, zeta1, zeta2) of mdof2 at `values`: mode 1 the higher (mass 1's), as the thesis numbers them."""
    cmd = [mbgen, "inspect", model, "--format", "json"]
    for name, value in values.items():
        cmd += ["--set", "%s=%r" % (name, value)]
    m = sorted(json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)["modes"],
               key=lambda x: -x["f_hz"])
    return (m[0]["f_hz"], m[1]["f_hz"], m[0]["zeta"], m[1]["zeta"])


def sensitivity_table(mbgen):
    model = os.path.join(ROOT, "examples", "mdof2", "mdof2.mdl")
    nominal = {p["name"]: p["value"] for p in json.loads(subprocess.run(
        [mbgen, "inspect", model, "--format", "json"], check=True, capture_output=True, text=True).stdout)["parameters"]}
    base = modes(mbgen, model, {})
    print("Thesis Table 5.3 (printed) beside mbgen's mdof2 at its values (f1 %.2f Hz, f2 %.2f Hz, xi1 %.4g, xi2 %.4g):"
          % base)
    print()
    print("| parameter | change | f1 thesis / mbgen | f2 thesis / mbgen | xi1 thesis / mbgen | xi2 thesis / mbgen |")
    print("|---|---|---|---|---|---|")
    for name, rows in THESIS_TABLE_5_3.items():
        for factor, printed in zip((1.1, 0.9), rows):
            changed = modes(mbgen, model, {name: nominal[name] * factor})
            ours = [100 * (c / b - 1) for c, b in zip(changed, base)]
            print("| %s | %+d %% | %s |" % (name, round(100 * (factor - 1)), " | ".join(
                "%+.1f / %+.2f" % (t, o) for t, o in zip(printed, ours))))
    print()


def make_data(work, draw):
    sets = []
    for i, (name, example, kind, extra) in enumerate(DATA):
        out = os.path.join(work, "%s_%s.csv" % (example, kind))
        subprocess.run([sys.executable, TRUTHGEN, "--example", example, "--case", "nominal", "--kind", kind,
                        "--seed", str(700 + i), "--draw", str(draw), "-o", out] + extra, check=True,
                       stdout=subprocess.DEVNULL)
        truth = json.load(open(out[:-4] + ".truth.json"))["parameters"]
        sets.append((name, example, kind, out, truth))
    return sets


def run_method(mbgen, method, arguments, example, data, truth, work):
    model = os.path.join(ROOT, "examples", example, example + ".mdl")
    extra = []
    if method == "arx-two-stage" and example == "mdof2":
        model = os.path.join(ROOT, "tests", "ekf_arx", "mdof2_known_mass.mdl")
        extra = ["--set", "m1=%r" % truth["m1"], "--set", "m2=%r" % truth["m2"]]
    if method == "modal-known-damping":
        estimated = [p["name"] for p in json.loads(subprocess.run(
            [mbgen, "inspect", model, "--format", "json"], check=True, capture_output=True, text=True).stdout)["parameters"]
            if p["role"] == "estimate"]
        extra = [a for name in estimated if name.startswith("c") and name in truth
                 for a in ("--fix", "%s=%r" % (name, truth[name]))]
    out = os.path.join(work, "%s_%s_%s.json" % (os.path.basename(data)[:-4], method, "_".join(arguments[1::2])))
    cmd = [mbgen, "fit", model, "--data", data, "--json", out] + extra + arguments
    if method != "auto":
        cmd += ["--method", "modal" if method == "modal-known-damping" else method]
    t0 = time.time()
    p = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    seconds = time.time() - t0
    if p.returncode != 0:
        reason = p.stderr.strip().splitlines()[-1] if p.stderr.strip() else "status %d" % p.returncode
        return {"refused": reason.replace(work + os.sep, "")[:110], "seconds": seconds}
    r = json.load(open(out))
    errors = {}
    for name, e in r["parameters"].items():
        if e["identifiable"] and name in truth and truth[name] != 0:
            errors[name] = abs(e["value"] - truth[name]) / abs(truth[name])
    return {"method": r["method"], "errors": errors, "seconds": seconds, "nrmse": r["fit"]["nrmse"],
            "with_std": sum(1 for e in r["parameters"].values() if e["std"] is not None)}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("mbgen", nargs="?", default=os.path.join(ROOT, "build", "compiler", "mbgen"))
    ap.add_argument("--draw", type=int, default=1)
    ap.add_argument("--work", default=os.path.join(ROOT, "build", "bench_methods"))
    ap.add_argument("--only", action="append", default=[], help="run only the rows of this method (label; repeatable)")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    if not a.only:
        sensitivity_table(a.mbgen)
    sets = make_data(a.work, a.draw)
    print("| data | method | max error | RMS error | parameters (with std) | nrmse | time |")
    print("|---|---|---|---|---|---|---|")
    for name, example, kind, data, truth in sets:
        for label, method, arguments, kinds in METHODS:
            if (kinds and kind not in kinds) or (a.only and label not in a.only):
                continue
            r = run_method(a.mbgen, method, arguments, example, data, truth, a.work)
            if "refused" in r:
                print("| %s | %s | refused: %s | | | | %.1f s |" % (name, label, r["refused"].replace("|", "/"), r["seconds"]))
                continue
            e = list(r["errors"].values())
            worst = max(e) if e else float("nan")
            rms = math.sqrt(sum(x * x for x in e) / len(e)) if e else float("nan")
            label = label if method != "auto" else r["method"]
            print("| %s | %s | %.2f %% | %.2f %% | %d (%d) | %.4g | %.1f s |"
                  % (name, label, 100 * worst, 100 * rms, len(e), r["with_std"], r["nrmse"], r["seconds"]))
            sys.stdout.flush()


if __name__ == "__main__":
    main()
