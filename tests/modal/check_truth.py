#!/usr/bin/env python3
"""One `mbgen modal` run on FRFs made by the independent truth-model generator (scripts/truthgen, numpy): every
truth mode inside the band is found once, no other mode is, and each lies within 5 of its reported standard
deviations of the truth (frequency and damping), those being small (f within 1e-4, zeta within 2 %).

usage: check_truth.py MBGEN TRUTHGEN WORK_DIR EXAMPLE CASE SEED [MODEL]
"""
import json
import os
import shutil
import subprocess
import sys


def main():
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
    for t in expected:
        m = min(found, key=lambda m: abs(m["f_hz"] - t["f_hz"]))
        line = (f"truth {t['f_hz']:.4f} Hz zeta {t['zeta']:.6f}: found {m['f_hz']:.4f} +- {m['f_std_hz']:.2g} Hz, "
                f"zeta {m['zeta']:.6f} +- {m['zeta_std']:.2g}")
        print(line)
        ok = (abs(m["f_hz"] - t["f_hz"]) < 5 * m["f_std_hz"] and abs(m["zeta"] - t["zeta"]) < 5 * m["zeta_std"]
              and m["f_std_hz"] < 1e-4 * t["f_hz"] and m["zeta_std"] < 0.02 * t["zeta"])
        if not ok:
            errors.append(line)
    if errors:
        sys.exit("\n".join(errors))


if __name__ == "__main__":
    main()
