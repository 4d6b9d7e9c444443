#!/usr/bin/env python3
"""SciPy reference for bench/fit_mdof2_frf.cpp: the same mdof2 FRF output-error fit with scipy.optimize.least_squares.

Usage: fit_scipy.py DATA.csv PRIOR_JSON REPEATS
Same residuals as mbgen (model minus measured, real and imaginary parts stacked, each channel divided by its RMS |H|
over sqrt(2)), same parameterisation (p = lower + (p0 - lower) exp(theta), lower = 0), analytic Jacobian (batched
solves), method 'trf' with x_scale='jac' ('lm' from theta = 0 starts with MINPACK's step bound of 100 in theta and
ends in a wrong minimum). Prints one JSON line: seconds per fit (median), cost, nfev, parameter values.
"""
import json
import sys
import time

import numpy as np
from scipy.optimize import least_squares

NAMES = ["m1", "m2", "k11", "k22", "k12", "c11", "c22"]


def read(path):
    rows = [l for l in open(path) if not l.startswith("#")]
    header = rows[0].strip().split(",")
    data = np.array([[float(x) for x in r.split(",")] for r in rows[1:]])
    f = data[:, 0]
    h = np.stack([data[:, header.index(f"{o}/F1.re")] + 1j * data[:, header.index(f"{o}/F1.im")] for o in ("d1", "d2")], axis=1)
    return f, h


def matrices(p):
    m1, m2, k11, k22, k12, c11, c22 = p
    M = np.diag([m1, m2])
    K = np.array([[k11 + k12, -k12], [-k12, k22 + k12]])
    C = np.array([[c11, 0.0], [0.0, c22]])
    return M, C, K


def derivative_matrices():
    z = np.zeros((2, 2))
    def e(i, j, v=1.0):
        a = z.copy(); a[i, j] = v; return a
    dM = [e(0, 0), e(1, 1), z, z, z, z, z]
    dK = [z, z, e(0, 0), e(1, 1), np.array([[1.0, -1.0], [-1.0, 1.0]]), z, z]
    dC = [z, z, z, z, z, e(0, 0), e(1, 1)]
    return dM, dC, dK


def main():
    f, hd = read(sys.argv[1])
    p0 = np.array(json.loads(sys.argv[2]))
    repeats = int(sys.argv[3])
    w = 2 * np.pi * f
    sigma = np.sqrt(np.mean(np.abs(hd) ** 2, axis=0)) / np.sqrt(2)  # per channel
    dM, dC, dK = derivative_matrices()
    b = np.array([1.0, 0.0])

    def solve(theta):
        p = p0 * np.exp(theta)
        M, C, K = matrices(p)
        P = K[None] + 1j * w[:, None, None] * C[None] - (w ** 2)[:, None, None] * M[None]
        X = np.linalg.solve(P, np.broadcast_to(b, (len(f), 2))[..., None])[..., 0]  # (nf, 2): H for d1, d2
        return p, P, X

    def residual(theta):
        _, _, X = solve(theta)
        e = (X - hd) / sigma
        return np.concatenate([e[:, 0].real, e[:, 0].imag, e[:, 1].real, e[:, 1].imag])

    def jacobian(theta):
        p, P, X = solve(theta)
        cols = []
        for j in range(7):
            dP = dK[j][None] + 1j * w[:, None, None] * dC[j][None] - (w ** 2)[:, None, None] * dM[j][None]
            dX = -np.linalg.solve(P, np.einsum("fij,fj->fi", dP, X)[..., None])[..., 0] * p[j]
            d = dX / sigma
            cols.append(np.concatenate([d[:, 0].real, d[:, 0].imag, d[:, 1].real, d[:, 1].imag]))
        return np.stack(cols, axis=1)

    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        r = least_squares(residual, np.zeros(7), jac=jacobian, method="trf", x_scale="jac", xtol=1e-10, ftol=1e-10, gtol=1e-12)
        times.append(time.perf_counter() - t0)
    p = p0 * np.exp(r.x)
    print(json.dumps({"seconds": float(np.median(times)), "cost": float(np.sum(r.fun ** 2)), "nfev": int(r.nfev),
                      "values": dict(zip(NAMES, map(float, p)))}))


if __name__ == "__main__":
    main()
