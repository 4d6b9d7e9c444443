"""Checks `mbgen export`'s numbers against each other by hand (numpy, not mbgen's code): the state space and the
FRFs from the exported M, C, K, B and output maps, and the modes from the state matrix; with the .mat files of the
same requests, that they hold the same numbers and names (read by scipy.io.loadmat).
usage: export_check.py MATRICES.json STATE_SPACE.json MODES.json FRF.json [MATRICES.mat STATE_SPACE.mat MODES.mat
                       FRF.mat]"""
import json
import sys

import numpy as np


def load(path):
    with open(path) as f:
        return json.load(f)


def check_mat(mats, ss, modes, frf, paths):
    """The .mat files against the JSON of the same requests: every number equal (both hold the same doubles)."""
    import scipy.io

    problems = []

    def names(cell):
        return [str(c[0][0]) if len(c[0]) else "" for c in cell]

    def same(what, got, want):
        got, want = np.asarray(got), np.asarray(want)
        if got.shape != want.shape or not np.array_equal(got, want):
            problems.append("%s in the .mat file: %s, the JSON's %s" % (what, got, want))

    m_mat, ss_mat, modes_mat, frf_mat = (scipy.io.loadmat(p) for p in paths)
    for name, mat, json_ in (("matrices", m_mat, mats), ("state-space", ss_mat, ss), ("modes", modes_mat, modes),
                             ("frf", frf_mat, frf)):
        if str(mat["what"][0]) != name or str(mat["schema"][0]) != "mbgen-export/1":
            problems.append("%s.mat: what %s, schema %s" % (name, mat["what"], mat["schema"]))
        for key in ("coordinates", "inputs", "outputs"):
            if names(mat[key]) != json_[key]:
                problems.append("%s.mat: %s %s, the JSON's %s" % (name, key, names(mat[key]), json_[key]))
        same(name + " parameter_values", mat["parameter_values"].ravel(),
             [json_["parameters"][n] for n in names(mat["parameter_names"])])
    for key in ("M", "C", "K", "B", "Cd", "Cv", "Ca"):
        same(key, m_mat[key], mats[key])
    for key in ("A", "B", "C", "D"):
        same("state-space " + key, ss_mat[key], ss[key])
    same("modes f_hz", modes_mat["f_hz"].ravel(), [m["f_hz"] for m in modes["modes"]])
    same("modes zeta", modes_mat["zeta"].ravel(), [m["zeta"] for m in modes["modes"]])
    same("modes eigenvalue", modes_mat["eigenvalue"].ravel(),
         [complex(m["eigenvalue"]["re"], m["eigenvalue"]["im"]) for m in modes["modes"]])
    same("modes shape", modes_mat["shape"],
         np.array([np.array(m["shape"]["re"]) + 1j * np.array(m["shape"]["im"]) for m in modes["modes"]]).T)
    same("frf f_hz", frf_mat["f_hz"].ravel(), frf["frf"]["f_hz"])
    H = frf_mat["H"].reshape(len(frf["frf"]["f_hz"]), len(mats["outputs"]), len(mats["inputs"]))
    for o, out in enumerate(mats["outputs"]):
        for i, inp in enumerate(mats["inputs"]):
            ch = frf["frf"]["channels"]["%s/%s" % (out, inp)]
            same("H(:, %d, %d)" % (o + 1, i + 1), H[:, o, i], np.array(ch["re"]) + 1j * np.array(ch["im"]))
    return problems


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
    if len(sys.argv) == 9:
        problems += check_mat(mats, ss, modes, frf, sys.argv[5:9])
    for p in problems:
        print(p)
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
