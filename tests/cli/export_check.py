"""Checks `mbgen export`'s numbers against each other by hand (numpy, not mbgen's code): the state space and the
FRFs from the exported M, C, K, B and output maps, and the modes from the state matrix.
usage: export_check.py MATRICES.json STATE_SPACE.json MODES.json FRF.json"""
import json
import sys

import numpy as np


def load(path):
    with open(path) as f:
        return json.load(f)


def main():
    mats, ss, modes, frf = (load(p) for p in sys.argv[1:5])
    M, C, K, B = (np.array(mats[k]) for k in ("M", "C", "K", "B"))
    Cd, Cv, Ca = (np.array(mats[k]) for k in ("Cd", "Cv", "Ca"))
    n = M.shape[0]
    Minv = np.linalg.inv(M)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ C]])
    Bs = np.vstack([np.zeros((n, B.shape[1])), Minv @ B])
    Cs = np.hstack([Cd - Ca @ Minv @ K, Cv - Ca @ Minv @ C])
    Ds = Ca @ Minv @ B
    problems = []
    for name, hand in (("A", A), ("B", Bs), ("C", Cs), ("D", Ds)):
        got = np.array(ss[name])
        if got.shape != hand.shape or not np.allclose(got, hand, rtol=1e-12, atol=1e-12 * np.max(np.abs(hand))):
            problems.append("state space %s differs from the exported matrices'" % name)
    lam = np.linalg.eigvals(A)
    lam = lam[lam.imag > 0]
    hand_f = np.sort(np.abs(lam) / (2 * np.pi))
    got_f = np.array([m["f_hz"] for m in modes["modes"]])
    if len(got_f) != len(hand_f) or not np.allclose(got_f, hand_f, rtol=1e-10):
        problems.append("modes %s Hz, by hand %s Hz" % (got_f, hand_f))
    f = np.array(frf["frf"]["f_hz"])
    for o, out in enumerate(mats["outputs"]):
        for i, inp in enumerate(mats["inputs"]):
            ch = frf["frf"]["channels"]["%s/%s" % (out, inp)]
            got = np.array(ch["re"]) + 1j * np.array(ch["im"])
            hand = []
            for fk in f:
                s = 2j * np.pi * fk
                X = np.linalg.solve(K + s * C + s * s * M, B[:, i])
                hand.append((Cd[o] + s * Cv[o] + s * s * Ca[o]) @ X)
            hand = np.array(hand)
            err = np.max(np.abs(got - hand)) / np.max(np.abs(hand))
            if err > 1e-10:
                problems.append("FRF %s/%s differs from (K + sC + s^2 M)^-1 by %.1e" % (out, inp, err))
    for p in problems:
        print(p)
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
