#!/usr/bin/env python3
"""The two-step method's analytical route against its minimisation on noiseless truthgen data.

    check_routes_agree.py MBGEN TRUTHGEN WORKDIR EXAMPLE KIND DRAW

Makes a noiseless data set (--snr-db inf) of EXAMPLE (mdof2) of KIND (frf or time) whose truth is drawn from DRAW
(scripts/truthgen: an independent numpy generator), fits it by `--two-step-route analytical` and by
`--two-step-route minimisation`, and requires both estimates to agree within TOLERANCE (relative, per parameter),
the analytical one to be within TOLERANCE of the truth, the JSON and the summary to name the route, and the check
equations left out of the exact solution to be met to the same tolerance. Exit 1 on failure.
"""
import json
import os
import subprocess
import sys

# What the noiseless data allow: the FRF CSV's digits and the rational fit leave the coefficients consistent to about
# 1e-7 (measured: the routes agree to 1.3e-6, the analytical one is within 9e-7 of the truth); a record's ARX
# regression at 25 samples per period of the highest mode loses more (routes 3.3e-4, truth 1.8e-4, c22 the worst).
TOLERANCE = {"frf": 1e-5, "time": 1e-3}


def run(cmd):
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        sys.exit("command failed (%d): %s\n%s%s" % (p.returncode, " ".join(cmd), p.stdout, p.stderr))
    return p.stdout


def main():
    mbgen, truthgen, work, example, kind, draw = sys.argv[1:7]
    os.makedirs(work, exist_ok=True)
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    model = os.path.join(root, "examples", example, example + ".mdl")
    data = os.path.join(work, "%s_%s_%s_noiseless.csv" % (example, kind, draw))
    run([sys.executable, truthgen, "--example", example, "--case", "nominal", "--kind", kind, "--seed",
         str(100 + int(draw)), "--draw", draw, "--snr-db", "inf", "-o", data])
    truth = json.load(open(data[:-4] + ".truth.json"))["parameters"]
    results, summaries = {}, {}
    for route in ("analytical", "minimisation"):
        out = os.path.join(work, "%s.json" % route)
        summaries[route] = run([mbgen, "fit", model, "--data", data, "--method", "two-step", "--two-step-route", route,
                                "--json", out])
        results[route] = json.load(open(out))
    failures = []
    tol = TOLERANCE[kind]
    for route, r in results.items():
        taken = r["method_details"]["two_step"]["step_two"]["route"]
        if taken != route:
            failures.append("route %s taken, %s asked for" % (taken, route))
        if "step two by the %s route" % route not in summaries[route]:
            failures.append("the summary does not name the %s route" % route)
    a = results["analytical"]["method_details"]["two_step"]["step_two"]["analytical"]
    chosen = a["subsystems"][a["chosen"]["subsystem"]]
    solution = chosen["solutions"][a["chosen"]["solution"]]
    print("analytical: %d of %d equations, closed form e.g. %s" % (len(chosen["equations"]), len(a["coefficients"]),
                                                                 chosen["closed_form"][0]))
    for c in solution["checks"]:
        print("  check %s: relative mismatch %.2e" % (c["coefficient"], c["relative_mismatch"]))
        if not abs(c["relative_mismatch"]) <= tol:
            failures.append("check %s mismatch %.3g beyond %g" % (c["coefficient"], c["relative_mismatch"], tol))
    for name, p in results["analytical"]["parameters"].items():
        if not p["identifiable"]:
            continue
        m = results["minimisation"]["parameters"][name]["value"]
        d_routes = abs(p["value"] - m) / abs(truth[name])
        d_truth = abs(p["value"] - truth[name]) / abs(truth[name])
        print("  %-4s analytical %.10g  minimisation %.10g  truth %.10g  |a-m| %.1e  |a-t| %.1e"
              % (name, p["value"], m, truth[name], d_routes, d_truth))
        if not d_routes <= tol:
            failures.append("%s: the routes differ by %.3g (beyond %g)" % (name, d_routes, tol))
        if not d_truth <= tol:
            failures.append("%s: the analytical estimate is %.3g off the truth (beyond %g)" % (name, d_truth, tol))
    for f in failures:
        print("FAIL: " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
