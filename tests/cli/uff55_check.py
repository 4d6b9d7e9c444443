"""Checks UFF 55 mode files by a reader written from the specification (fixed columns, not mbgen's code): the modes
`mbgen export --what modes --format uff` writes are the exported JSON modes at the outputs (Cd + Cv + Ca times the
shape, six significant digits), and those `mbgen modal --uff` writes from the model's FRFs are the same modes (the
frequencies, and the shapes by MAC). The UFF 15 nodes come before the modes, one per output's point, and after them
the UFF 82 trace lines of the model's structure: mdof2's one element between its two masses, the helix (the beams go
to the wall, which has no node), is the one line from node 1 to node 2.
usage: uff55_check.py MATRICES.json MODES.json EXPORTED.uff IDENTIFIED.uff"""
import json
import math
import sys

import numpy as np


def datasets(path):
    """The datasets of a UFF file: (number, lines between the number line and the closing -1)."""
    with open(path) as f:
        lines = f.read().split("\n")
    out, i = [], 0
    while i < len(lines):
        if lines[i].strip() == "-1" and i + 1 < len(lines):
            number = lines[i + 1][:6].strip()
            j = i + 2
            while lines[j].strip() != "-1":
                j += 1
            out.append((number, lines[i + 2:j]))
            i = j + 1
        else:
            i += 1
    return out


def reals(line):
    """Record 8 and 10: 6E13.5, by column."""
    return [float(line[k:k + 13]) for k in range(0, len(line), 13) if line[k:k + 13].strip()]


def read_mode(body):
    """One dataset 55 (records 1-5 are body[0:5]): eigenvalue, {node: [x, y, z]}."""
    r6 = [int(body[5][k:k + 10]) for k in range(0, 60, 10)]
    model_type, analysis, characteristic, specific, data_type, per_node = r6
    assert (model_type, analysis, characteristic, data_type, per_node) == (1, 3, 2, 5, 3), r6
    r7 = [int(body[6][k:k + 10]) for k in range(0, 40, 10)]
    assert r7[:2] == [2, 6], r7
    r8 = reals(body[7])
    shapes = {}
    for k in range(8, len(body) - 1, 2):
        node = int(body[k][:10])
        v = reals(body[k + 1])
        shapes[node] = [complex(v[2 * i], v[2 * i + 1]) for i in range(3)]
    return r7[3], complex(r8[0], r8[1]), specific, shapes


def mac(a, b):
    return abs(np.vdot(a, b)) ** 2 / (np.vdot(a, a).real * np.vdot(b, b).real)


def main():
    with open(sys.argv[1]) as f:
        mats = json.load(f)
    with open(sys.argv[2]) as f:
        modes = json.load(f)["modes"]
    maps = np.array(mats["Cd"]) + np.array(mats["Cv"]) + np.array(mats["Ca"])
    problems = []
    exported = datasets(sys.argv[3])
    if (exported[0][0] != "15" or [d[0] for d in exported[1:]] != ["82"] + ["55"] * len(modes)):
        problems.append("export: expected a dataset 15, an 82, then one 55 per mode, found %s" % [d[0] for d in exported])
    nodes = {int(l[:10]) for l in exported[0][1]}
    for number, body in exported:
        if number == "82":
            count = int(body[0][10:20])  # record 1: 3I10; record 3: 8I10
            trace = [int(l[k:k + 10]) for l in body[2:] for k in range(0, len(l), 10) if l[k:k + 10].strip()]
            if count != len(trace) or trace != [1, 2]:
                problems.append("export: trace line %s (count %d), expected [1, 2]" % (trace, count))
    model_shapes = []
    for number, body in [d for d in exported if d[0] == "55"]:
        n, lam, specific, shapes = read_mode(body)
        m = modes[n - 1]
        if specific != 8 or set(shapes) != nodes:
            problems.append("export mode %d: specific data type %d, nodes %s" % (n, specific, sorted(shapes)))
        if abs(lam - complex(m["eigenvalue"]["re"], m["eigenvalue"]["im"])) > 1e-5 * abs(lam):
            problems.append("export mode %d: eigenvalue %s, the JSON's %s" % (n, lam, m["eigenvalue"]))
        shape = np.array(m["shape"]["re"]) + 1j * np.array(m["shape"]["im"])
        at_outputs = maps @ shape
        got = np.array([shapes[o + 1][0] for o in range(len(at_outputs))])  # mdof2: output o at node o+1, +X
        if np.max(np.abs(got - at_outputs)) > 1e-5 * np.max(np.abs(at_outputs)):
            problems.append("export mode %d: shape %s, at the outputs %s" % (n, got, at_outputs))
        model_shapes.append(at_outputs)
    identified = [d for d in datasets(sys.argv[4]) if d[0] == "55"]
    if len(identified) != len(modes):
        problems.append("modal --uff: %d modes, the model has %d" % (len(identified), len(modes)))
    for number, body in identified:
        n, lam, specific, shapes = read_mode(body)
        f = abs(lam) / (2 * math.pi)
        if abs(f / modes[n - 1]["f_hz"] - 1) > 1e-4:
            problems.append("modal --uff mode %d at %.6g Hz, the model's at %.6g Hz" % (n, f, modes[n - 1]["f_hz"]))
        got = np.array([shapes[node][0] for node in sorted(shapes)])
        if mac(got, model_shapes[n - 1]) < 0.9999:
            problems.append("modal --uff mode %d: MAC %.6f with the model's shape" % (n, mac(got, model_shapes[n - 1])))
    for p in problems:
        print(p)
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
