#!/usr/bin/env python3
"""One `mbgen modal` run on FRFs made by the independent truth-model generator (scripts/truthgen, numpy): every
truth mode inside the band is found once, no other mode is, and each lies within 5 of its reported standard
deviations of the truth (frequency and damping), those being small (f within 1e-4, zeta within 2 %).

usage: check_truth.py MBGEN TRUTHGEN WORK_DIR EXAMPLE CASE SEED [MODEL]
       check_truth.py --observed MBGEN DATA.csv WORK_DIR MODEL EXPECT_HZ
  The second form takes committed data (its truth in DATA.truth.json) whose inputs do not excite every truth mode:
  every mode found must be a truth mode (within 5 std, the std below 1e-3 of f and 2 % of zeta), and one of them must
  lie within 0.1 % of EXPECT_HZ.
"""
import json
import os
import shutil
import subprocess
import sys


def check(found, truth, f_std_max=1e-4, zeta_std_max=0.02):
    """The errors of the found modes against their nearest truth modes: within 5 std, the std no larger than the
    given fractions of f and zeta (so that the test cannot pass on vague estimates)."""
    errors = []
    for m in found:
        t = min(truth, key=lambda t: abs(m["f_hz"] - t["f_hz"]))
        line = (f"truth {t['f_hz']:.4f} Hz zeta {t['zeta']:.6f}: found {m['f_hz']:.4f} +- {m['f_std_hz']:.2g} Hz, "
                f"zeta {m['zeta']:.6f} +- {m['zeta_std']:.2g}")
        print(line)
        ok = (abs(m["f_hz"] - t["f_hz"]) < 5 * m["f_std_hz"] and abs(m["zeta"] - t["zeta"]) < 5 * m["zeta_std"]
              and m["f_std_hz"] < f_std_max * t["f_hz"] and m["zeta_std"] < zeta_std_max * t["zeta"])
        if not ok:
            errors.append(line)
    return errors


def observed():
    mbgen, data, work, model, expect = sys.argv[2:7]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    with open(os.path.splitext(data)[0] + ".truth.json") as f:
        truth = json.load(f)["truth_modes"]
    out = os.path.join(work, "modal.json")
    run = subprocess.run([mbgen, "modal", "--data", data, "--model", model, "--json", out], capture_output=True,
                         text=True)
    print(run.stdout)
    if run.returncode != 0:
        sys.exit(f"mbgen modal failed ({run.returncode}): {run.stderr}")
    with open(out) as f:
        found = json.load(f)["modes"]
    # The spindle's upper modes are damped 3-4 % and weak at these sensors: their std reach 4e-4 of f and 1 % of zeta.
    errors = check(found, truth, f_std_max=1e-3, zeta_std_max=0.02)
    if not any(abs(m["f_hz"] / float(expect) - 1) < 1e-3 for m in found):
        errors.append(f"no mode found near {expect} Hz")
    if errors:
        sys.exit("\n".join(errors))


def main():
    if sys.argv[1] == "--observed":
        return observed()
    mbgen, truthgen, work, example, case, seed = sys.argv[1:7]
    model = sys.argv[7] if len(sys.argv) > 7 else None
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    data = os.path.join(work, "frf.csv")
    subprocess.run([sys.executable, truthgen, "--example", example, "--case", case, "--kind", "frf", "--seed", seed,
                    "-o", data], check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(work, "frf.truth.json")) as f:
        truth = json.load(f)["truth_modes"]
    command = [mbgen, "modal", "--data", data, "--json", os.path.join(work, "modal.json")]
    if model:
        command += ["--model", model]
    run = subprocess.run(command, capture_output=True, text=True)
    print(run.stdout)
    if run.returncode != 0:
        sys.exit(f"mbgen modal failed ({run.returncode}): {run.stderr}")
    with open(os.path.join(work, "modal.json")) as f:
        result = json.load(f)
    lo, hi = result["band_hz"]
    expected = [m for m in truth if lo <= m["f_hz"] <= hi]
    found = result["modes"]
    errors = []
    if len(found) != len(expected):
        errors.append(f"{len(found)} modes found, {len(expected)} truth modes in the band")
    if len(found) == len(expected):
        errors += check(found, expected)
    if errors:
        sys.exit("\n".join(errors))


if __name__ == "__main__":
    main()
