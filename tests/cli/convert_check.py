"""Checks of `mbgen convert` and `mbgen modal --synthesis` (convert.cmake), by hand with numpy: the FRF CSV files
are parsed here, not by mbgen.

  convert_check.py same A.csv B.csv DIGITS    same names, `# set` lines and frequencies, values equal to DIGITS
                                              significant digits (17: bit for bit)
  convert_check.py channel-error DATA.csv SYNTH.csv MODAL.json
                                              MODAL.json's channel_error recomputed from the measured and the written
                                              synthesized FRFs on the synthesis's lines
  convert_check.py same-modes A.json B.json TOL
                                              the modes' frequencies agree within TOL (relative)
"""
import json
import sys

import numpy as np


def read_csv(path):
    sets, rows, header = [], [], None
    with open(path) as f:
        for line in f:
            line = line.strip()
            if not line:
                continue
            if line.startswith("#"):
                if line.startswith("# set "):
                    sets.append(line)
                continue
            if header is None:
                header = line.split(",")
            else:
                rows.append([float(v) for v in line.split(",")])
    return sets, header, np.array(rows)


def same(a, b, digits):
    sa, ha, va = read_csv(a)
    sb, hb, vb = read_csv(b)
    if sa != sb:
        return f"set lines differ: {sa} vs {sb}"
    if ha != hb:
        return f"columns differ: {ha} vs {hb}"
    if va.shape != vb.shape:
        return f"shapes differ: {va.shape} vs {vb.shape}"
    if not np.array_equal(va[:, 0], vb[:, 0]):
        return "frequencies differ"
    if digits >= 17:
        bad = va != vb
    else:
        # DIGITS significant digits: a value printed so is within half a unit of its last digit.
        bad = np.abs(va - vb) > 0.5 * 10.0 ** (1 - digits) * np.abs(va)
    if bad.any():
        r, c = np.argwhere(bad)[0]
        return f"{ha[c]} at {va[r, 0]} Hz: {va[r, c]!r} vs {vb[r, c]!r}"
    return None


def complex_columns(header, values):
    out = {}
    for c, name in enumerate(header):
        if name.endswith(".re"):
            out[name[:-3]] = values[:, c] + 1j * values[:, header.index(name[:-3] + ".im")]
    return out


def channel_error(data, synth, modal):
    _, hd, vd = read_csv(data)
    _, hs, vs = read_csv(synth)
    lines = np.isin(vd[:, 0], vs[:, 0])
    if lines.sum() != len(vs):
        return "the synthesis's lines are not lines of the data"
    measured, synthesized = complex_columns(hd, vd[lines]), complex_columns(hs, vs)
    expected = json.load(open(modal))["channel_error"]
    if sorted(expected) != sorted(synthesized):
        return f"channels differ: {sorted(expected)} vs {sorted(synthesized)}"
    for name, e in expected.items():
        h = measured[name]
        got = np.linalg.norm(h - synthesized[name]) / np.linalg.norm(h)
        if abs(got - e) > 1e-9 * e:
            return f"{name}: channel_error {e!r} in the JSON, {got!r} from the written synthesis"
        print(f"{name}: channel_error {e:.6g} (JSON) = {got:.6g} (from the file)")
    return None


def same_modes(a, b, tol):
    fa = [m["f_hz"] for m in json.load(open(a))["modes"]]
    fb = [m["f_hz"] for m in json.load(open(b))["modes"]]
    if len(fa) != len(fb):
        return f"{len(fa)} modes vs {len(fb)}: {fa} vs {fb}"
    for x, y in zip(fa, fb):
        if abs(y / x - 1) > tol:
            return f"mode at {x} Hz found at {y} Hz"
        print(f"{x:.6f} Hz vs {y:.6f} Hz")
    return None


if __name__ == "__main__":
    what, args = sys.argv[1], sys.argv[2:]
    if what == "same":
        problem = same(args[0], args[1], int(args[2]))
    elif what == "channel-error":
        problem = channel_error(*args)
    elif what == "same-modes":
        problem = same_modes(args[0], args[1], float(args[2]))
    else:
        problem = f"unknown check {what}"
    if problem:
        print(problem)
        sys.exit(1)
