#!/usr/bin/env python3
"""End-to-end test of `mbgen fit --method two-step` on data from the independent generator scripts/truthgen.

    check_two_step.py MBGEN TRUTHGEN WORKDIR EXAMPLE KIND DRAW [--versus-one-step] [--route=ROUTE] [--model=MODEL]

Makes a data set of EXAMPLE (mdof2 or spindle; case nominal, 40 dB SNR) of KIND (frf or time) whose truth is drawn
from DRAW, fits it by two-step and checks each identifiable parameter's relative error against the bound below (what
the method reaches; docs/methods.md#two-step). With --versus-one-step (time records), also fits the same record by
time-output-error and requires two-step's RMS relative error to exceed one step's by the factor below (the thesis's
Ch. 5 finding). --route=ROUTE passes `--two-step-route ROUTE` and requires that route to be the one taken; the
bounds are the route's (the analytical route's below, measured on draws 1-4 in docs/methods.md#two-step).
--model=MODEL (time records: armax, the default, or arx) passes `--two-step-model MODEL`; the bounds are the model's.
The truth JSON is read only to score the result. Exit 1 on failure.
"""
import json
import os
import subprocess
import sys
import time

# Bounds on |relative error| by parameter, for the draws the tests use (1 and 2; measured values in
# docs/methods.md#two-step, with draws 3 and 4 beside them), keyed by (example, kind, step one's model for records).
# The mass-2 group of mdof2 (m2, k22, k12) and the spindle's mounts are what the coefficient comparison determines
# worst.
MDOF2_MASS2 = ("m2", "k22", "k12")
SPINDLE_BEARINGS = ("k_fx", "k_rx", "c_fx", "c_rx")
BOUNDS = {
    ("mdof2", "frf", None): dict([(n, 0.02) for n in ("m1", "k11", "c11")] + [("c22", 0.05)] +
                                 [(n, 0.15) for n in MDOF2_MASS2]),
    ("mdof2", "time", "arx"): dict([("m1", 0.03), ("k11", 0.10), ("c11", 0.10), ("c22", 1.0)] +
                                   [(n, 1.0) for n in MDOF2_MASS2]),
    # ARMAX, the minimisation: measured on draws 1-4 m1 <= 0.6 %, k11 and c11 <= 2.7 %, c22 <= 15 %, the mass-2 group
    # 2.2-34 % (draw 2 the worst): the normalised weighting, not step one, is what moves the group.
    ("mdof2", "time", "armax"): dict([("m1", 0.02), ("k11", 0.05), ("c11", 0.05), ("c22", 0.3)] +
                                     [(n, 0.5) for n in MDOF2_MASS2]),
    ("spindle", "frf", None): {"k_fx": 0.05, "k_rx": 0.05, "c_fx": 0.10, "c_rx": 0.10, "k_hbx": 0.5, "k_hby": 0.5,
                               "k_hbz": 0.5, "c_hbx": 1.5, "c_hby": 1.5, "c_hbz": 1.5},
    ("spindle", "time", "arx"): {"k_fx": 0.10, "k_rx": 0.10, "c_fx": 0.10, "c_rx": 0.10, "k_hbx": 0.3, "k_hby": 0.3,
                                 "k_hbz": 0.3, "c_hbx": 4.0, "c_hby": 4.0, "c_hbz": 4.0},
    # ARMAX: measured on draws 1-2 bearings within 3.7 %, mounts' stiffnesses 12 %, mounts' dampers 42 %.
    ("spindle", "time", "armax"): {"k_fx": 0.06, "k_rx": 0.05, "c_fx": 0.05, "c_rx": 0.05, "k_hbx": 0.2,
                                   "k_hby": 0.2, "k_hbz": 0.2, "c_hbx": 0.7, "c_hby": 0.7, "c_hbz": 0.7},
}
# The analytical route (mdof2: the exact solution of 7 of the 8 coefficient equations, the one left out chosen by
# the predicted error where step one gives a covariance, else the check met best). It determines the mass-2 group
# far better than the minimisation, and c22 worse: c22 = b1 m1 m2 exactly, b1 the poorly identified antiresonance
# damping, where the least squares also draw on a3 and a1.
ANALYTICAL_BOUNDS = {
    ("mdof2", "frf", None): dict([(n, 0.02) for n in ("m1", "k11", "c11")] + [("c22", 0.10)] +
                                 [(n, 0.02) for n in MDOF2_MASS2]),
    ("mdof2", "time", "arx"): dict([("m1", 0.01), ("k11", 0.02), ("c11", 0.05), ("c22", 1.0)] +
                                   [(n, 0.02) for n in MDOF2_MASS2]),
    # ARMAX, measured on draws 1-4: m1, k11 <= 0.05 %, c11 <= 1.04 %, the mass-2 group <= 0.37 %, c22 2.7-27 %.
    ("mdof2", "time", "armax"): dict([("m1", 0.005), ("k11", 0.005), ("c11", 0.03), ("c22", 0.5)] +
                                     [(n, 0.01) for n in MDOF2_MASS2]),
}
# Step one's order (the model's: mdof2 4, the spindle's x block 10): at 40 dB the spindle's fifth x-block mode
# (~1060 Hz) is below the noise, so the data show four modes and the fit has eight poles.
ORDER = {"mdof2": 4, "spindle": 8}
# Where the propagated std is honest, each error within this many stds: mdof2 from FRFs (the model's full order);
# mdof2 from records by ARMAX (measured within 2.2 std on draws 1-4, both routes). Not for the analytical route from
# FRFs: its std covers its error on the closed-form data of the unit test but not on truthgen's draw 1 (m2 +0.32 %
# with a std of 0.07 %). Not for the spindle: its data show fewer modes than the model, and the truncation's bias is
# not in the std (k_fx +3.6 % with a std of 0.14 % from records).
STD_COVERAGE = {("mdof2", "frf", None, "minimisation"): 4.0, ("mdof2", "time", "armax", "minimisation"): 4.0,
                ("mdof2", "time", "armax", "analytical"): 4.0}
# Two-step's RMS relative error over one step's on the same record at least this (ARX measured 23-266, ARMAX 3.2-64
# on the draws of docs/methods.md#two-step).
VERSUS_FACTOR = {"arx": 5.0, "armax": 2.5}


def run(cmd):
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        sys.exit("command failed (%d): %s\n%s%s" % (p.returncode, " ".join(cmd), p.stdout, p.stderr))
    return p.stdout


def errors(result, truth):
    out = {}
    for name, p in result["parameters"].items():
        if p["identifiable"]:
            out[name] = (p["value"] - truth[name]) / truth[name]
    return out


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    versus = "--versus-one-step" in sys.argv
    route = next((a.split("=", 1)[1] for a in sys.argv[1:] if a.startswith("--route=")), None)
    mbgen, truthgen, work, example, kind, draw = args
    model_kind = next((a.split("=", 1)[1] for a in sys.argv[1:] if a.startswith("--model=")), "armax") \
        if kind == "time" else None
    os.makedirs(work, exist_ok=True)
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    model = os.path.join(root, "examples", example, example + ".mdl")
    data = os.path.join(work, "%s_%s_%s.csv" % (example, kind, draw))
    run([sys.executable, truthgen, "--example", example, "--case", "nominal", "--kind", kind, "--seed",
         str(100 + int(draw)), "--draw", draw, "-o", data])
    truth = json.load(open(data[:-4] + ".truth.json"))["parameters"]
    out = os.path.join(work, "two_step_%s_%s_%s.json" % (example, kind, draw))
    t0 = time.time()
    run([mbgen, "fit", model, "--data", data, "--method", "two-step", "--json", out] +
        (["--two-step-route", route] if route else []) + (["--two-step-model", model_kind] if model_kind else []))
    seconds = time.time() - t0
    result = json.load(open(out))
    failures = []
    if result["method"] != "two-step":
        failures.append("method is %s" % result["method"])
    details = result.get("method_details", {}).get("two_step", {})
    for key in ("step_one", "step_two", "zero_pole", "checks"):
        if key not in details:
            failures.append("method_details.two_step lacks " + key)
    one = details["step_one"][0]
    if one["order"] != ORDER[example]:
        failures.append("step one's order %d, expected %d" % (one["order"], ORDER[example]))
    if kind == "time":
        if one["source"] != model_kind:
            failures.append("step one's source %s, expected %s" % (one["source"], model_kind))
        identification = one[model_kind]
        kept = sum(p["kept"] for p in identification["poles"])
        if identification["selected_order"] < one["model_order"] or kept != ORDER[example] // 2:
            failures.append("%s order %d with %d kept poles" % (model_kind, identification["selected_order"], kept))
    # Every identified pole of mdof2 has its model counterpart at the estimate; the checks say so.
    if example == "mdof2" and not details["checks"]["verdict"].startswith("valid"):
        failures.append("checks: " + details["checks"]["verdict"])
    err = errors(result, truth)
    bounds = (ANALYTICAL_BOUNDS if route == "analytical" else BOUNDS)[(example, kind, model_kind)]
    taken = details["step_two"].get("route")
    print("step two's route: %s (%s)" % (taken, details["step_two"].get("route_reason")))
    if route and route != "auto" and taken != route:
        failures.append("route %s taken, %s asked for" % (taken, route))
    print("two-step %s %s draw %s%s (%.1f s): %s" % (example, kind, draw, " by " + model_kind if model_kind else "",
                                                   seconds, details["checks"]["verdict"]))
    if set(err) != set(bounds):
        failures.append("identifiable parameters %s, expected %s" % (sorted(err), sorted(bounds)))
    coverage = STD_COVERAGE.get((example, kind, model_kind, taken))
    for name, e in err.items():
        bound = bounds.get(name, 0)
        std = result["parameters"][name]["std"]
        print("  %-6s error %+8.2f %%  (bound %g %%)  std %s" % (name, 100 * e, 100 * bound,
                                                                 "%.2f %%" % (100 * std / truth[name]) if std else "null"))
        if not abs(e) <= bound:
            failures.append("%s: relative error %.4f beyond %.4f" % (name, e, bound))
        if coverage and not (std and abs(e) * truth[name] <= coverage * std):
            failures.append("%s: error %.4g beyond %g std (%s)" % (name, e * truth[name], coverage, std))
    rms_two = (sum(e * e for e in err.values()) / len(err)) ** 0.5
    print("  RMS relative error %.4f, nrmse %.4g" % (rms_two, result["fit"]["nrmse"]))
    if versus:
        one_out = os.path.join(work, "one_step_%s_%s_%s.json" % (example, kind, draw))
        run([mbgen, "fit", model, "--data", data, "--method", "time-output-error", "--json", one_out])
        one = json.load(open(one_out))
        err_one = errors(one, truth)
        common = [n for n in err if n in err_one]
        rms_one = (sum(err_one[n] ** 2 for n in common) / len(common)) ** 0.5
        rms_two = (sum(err[n] ** 2 for n in common) / len(common)) ** 0.5
        print("  one step (time-output-error) on the same record: RMS relative error %.4f; two-step / one step = %.1f"
              % (rms_one, rms_two / rms_one))
        factor = VERSUS_FACTOR[model_kind]
        if not rms_two > factor * rms_one:
            failures.append("two-step (%.4f) is not poorer than %g x one step (%.4f)" % (rms_two, factor, rms_one))
    for f in failures:
        print("FAIL: " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
