#!/usr/bin/env python3
"""The beam's measured FRFs through both paths of `mbgen modal`: the FRF path (LSCF, refined) and the output-only
FDD/EFDD path, which reads the FRFs as the spectra of an unmeasured white force (`--output-only --method fdd`).
Both must find the same modes:

- as many modes, paired one to one by frequency;
- frequencies within 1 % of the FRF path's (or its reported standard deviation, if larger) and within half of
  FDD's line spacing (its resolution);
- MAC of the shapes above 0.99 (the target was 0.9; the FRF path's shape of a mode is its residues over the
  channels, FDD's the first singular vector at the peak, compared over the same points), and higher than with any
  other of the FRF path's modes;
- damping: printed side by side, not checked (EFDD cannot resolve these modes' bandwidths on the data's lines:
  docs/modal.md); each FDD mode must carry a damping ratio or EFDD's note saying why it has none.

Plain Python (no numpy): the numbers come from mbgen's JSON only.

usage: check_fdd_vs_frf.py MBGEN DATA WORK_DIR
"""
import json
import os
import shutil
import subprocess
import sys


def run(mbgen, args, out):
    subprocess.run([mbgen, "modal", *args, "--json", out], check=True, stdout=subprocess.DEVNULL)
    with open(out) as f:
        return json.load(f)


def mac(a, b):
    dot = sum(x.conjugate() * y for x, y in zip(a, b))
    return abs(dot) ** 2 / (sum(abs(x) ** 2 for x in a) * sum(abs(y) ** 2 for y in b))


def frf_shape(frf, mode, force, points):
    """The FRF path's shape over FDD's points: its channels from the white force's point to each (a roving hammer,
    fewer outputs than inputs: FDD reads the FRFs transposed, by reciprocity)."""
    outputs = {c.split("/")[0] for c in frf["channels"]}
    inputs = {c.split("/")[1] for c in frf["channels"]}
    transposed = len(outputs) < len(inputs)
    return [complex(*mode["shape"][f"{force}/{c}" if transposed else f"{c}/{force}"]) for c in points]


def main():
    mbgen, data, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    frf = run(mbgen, ["--data", data], os.path.join(work, "frf.json"))
    fdd = run(mbgen, ["--output-only", "--method", "fdd", "--data", data], os.path.join(work, "fdd.json"))
    errors = []
    if len(frf["modes"]) != len(fdd["modes"]):
        errors.append(f"{len(frf['modes'])} modes by the FRF path, {len(fdd['modes'])} by FDD")
    half_line = 0.5 * fdd["df_hz"]
    points = fdd["channels"]
    print(f"{'FRF f [Hz]':>11} {'+- std':>7} {'FDD f [Hz]':>11} {'df [%]':>7} {'FRF zeta [%]':>12} "
          f"{'EFDD zeta [%]':>13} {'MAC':>7}")
    for m in fdd["modes"]:
        p = min(frf["modes"], key=lambda p: abs(p["f_hz"] - m["f_hz"]))
        if min(fdd["modes"], key=lambda q: abs(p["f_hz"] - q["f_hz"])) is not m:
            errors.append(f"the FDD mode at {m['f_hz']:.3f} Hz pairs with none of the FRF path's")
            continue
        a = frf_shape(frf, p, fdd["white_force_inputs"][0], points)
        b = [complex(*m["shape"][c]) for c in points]
        value = mac(a, b)
        deviation = m["f_hz"] - p["f_hz"]
        zeta = "none" if m["zeta"] is None else f"{100 * m['zeta']:.4f}"
        note = f"  ({m['efdd_note']})" if m.get("efdd_note") else ""
        print(f"{p['f_hz']:11.3f} {p['f_std_hz']:7.4f} {m['f_hz']:11.3f} {100 * deviation / p['f_hz']:7.3f} "
              f"{100 * p['zeta']:12.4f} {zeta:>13} {value:7.4f}{note}")
        if abs(deviation) > max(0.01 * p["f_hz"], p["f_std_hz"]) or abs(deviation) > half_line:
            errors.append(f"{p['f_hz']:.3f} Hz: FDD's {m['f_hz']:.3f} Hz is off by more than 1 % or half a line")
        if not value > 0.99:
            errors.append(f"{p['f_hz']:.3f} Hz: MAC {value:.4f} <= 0.99")
        # Three points leave neighbouring modes alike (auto-MAC up to 0.94): the pair must also be the best match.
        for q in frf["modes"]:
            if q is not p and mac(frf_shape(frf, q, fdd["white_force_inputs"][0], points), b) >= value:
                errors.append(f"{p['f_hz']:.3f} Hz: FDD's shape matches the FRF path's {q['f_hz']:.3f} Hz as well")
        if m["zeta"] is None and not m.get("efdd_note"):
            errors.append(f"{p['f_hz']:.3f} Hz: no damping and no note why")
    for e in errors:
        print("FAIL:", e)
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
