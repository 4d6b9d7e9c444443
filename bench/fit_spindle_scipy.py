#!/usr/bin/env python3
"""SciPy reference for bench/fit_spindle.cpp: the spindle FRF output-error fit with scipy.optimize.least_squares.

Usage: fit_spindle_scipy.py DATA.csv REPEATS

The model is assembled by scripts/truthgen/truthlib (numpy, independent of mbgen) and cut to the 5 coordinates the
x-direction data excites (spindle x, ry; housing x, ry, rz), a local fit of the 10 parameters acting there from the
model's nominal values, like mbgen's local fit. Same residuals as mbgen: model minus measured FRF, real and
imaginary parts, divided by sigma from the coherence column, var|H| = (1 - g2)/g2 |H|^2, at least (1e-3 RMS|H|)^2,
half to each part. Parameterisation p = p0 exp(theta); analytic Jacobian (batched solves); method 'trf' with
x_scale='jac'. Prints one JSON line: wall-clock and CPU seconds per fit (medians), cost, nfev, parameter values.
"""
import json
import os
import sys
import time

import numpy as np
from scipy.optimize import least_squares

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts", "truthgen"))
from truthlib import models  # noqa: E402

NAMES = ["k_fx", "k_rx", "k_hbx", "k_hby", "k_hbz", "c_fx", "c_rx", "c_hbx", "c_hby", "c_hbz"]
BLOCK = [("spindle", "x"), ("spindle", "ry"), ("housing", "x"), ("housing", "ry"), ("housing", "rz")]
OUTPUTS = ["xs_front", "xs_rear", "xh_front"]


def read(path):
    rows = [line for line in open(path) if not line.startswith("#")]
    header = rows[0].strip().split(",")
    data = np.array([[float(x) for x in r.split(",")] for r in rows[1:]])
    h = np.stack([data[:, header.index(f"{o}/Fx.re")] + 1j * data[:, header.index(f"{o}/Fx.im")] for o in OUTPUTS], 1)
    g = np.stack([data[:, header.index(f"{o}/Fx.coh")] for o in OUTPUTS], 1)
    return data[:, 0], h, g


def block_matrices(p):
    """M, K, C, b, Cy of the x block at parameters p (a dict of all spindle parameters)."""
    s = models.build_spindle(p)
    idx = [s.index(b, d) for b, d in BLOCK]
    K, C = s.stiffness_damping()
    sub = np.ix_(idx, idx)
    return s.mass_matrix()[sub], K[sub], C[sub], s.input_matrix()[idx, 0], s.output_matrix()[:, idx]


def main():
    f, hd, g = read(sys.argv[1])
    repeats = int(sys.argv[2])
    w = 2 * np.pi * f
    rms = np.sqrt(np.mean(np.abs(hd) ** 2, axis=0))
    g2 = np.clip(g, 1e-12, 1.0)
    var = np.maximum((1 - g2) / g2 * np.abs(hd) ** 2, (1e-3 * rms) ** 2)
    sigma = np.sqrt(var / 2)

    nominal = dict(models.SPINDLE_NOMINAL)
    p0 = np.array([nominal[n] for n in NAMES])
    M, _, _, b, Cy = block_matrices(nominal)
    # K and C are linear in the stiffnesses and dampers: the derivative matrices from assemblies with one unit value.
    zero = dict(nominal, **{n: 0.0 for n in NAMES})
    dK, dC = [], []
    for n in NAMES:
        _, K1, C1, _, _ = block_matrices(dict(zero, **{n: 1.0}))
        dK.append(K1)
        dC.append(C1)
    dK, dC = np.array(dK), np.array(dC)

    def solve(theta):
        p = p0 * np.exp(theta)
        K = np.einsum("j,jab->ab", p[:5], dK[:5])
        C = np.einsum("j,jab->ab", p[5:], dC[5:])
        P = K[None] + 1j * w[:, None, None] * C[None] - (w ** 2)[:, None, None] * M[None]
        X = np.linalg.solve(P, np.broadcast_to(b, (len(f), 5))[..., None])[..., 0]  # (nf, 5)
        return p, P, X

    def stack(e):
        e = e / sigma
        return np.concatenate([np.concatenate([e[:, c].real, e[:, c].imag]) for c in range(3)])

    def residual(theta):
        _, _, X = solve(theta)
        return stack(X @ Cy.T - hd)

    def jacobian(theta):
        p, P, X = solve(theta)
        Yt = np.linalg.solve(np.transpose(P, (0, 2, 1)), np.broadcast_to(Cy.T, (len(f), 5, 3)))  # P^-T Cy^T
        cols = []
        for j in range(10):
            dP = dK[j] if j < 5 else 1j * w[:, None, None] * dC[j][None]
            dPX = np.einsum("fab,fb->fa", np.broadcast_to(dP, P.shape), X)
            dH = -np.einsum("fao,fa->fo", Yt, dPX) * p[j]
            cols.append(stack(dH))
        return np.stack(cols, axis=1)

    times, cpu = [], []
    for _ in range(repeats):
        t0, c0 = time.perf_counter(), time.process_time()
        r = least_squares(residual, np.zeros(10), jac=jacobian, method="trf", x_scale="jac", xtol=1e-10, ftol=1e-10,
                          gtol=1e-12)
        times.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
    p = p0 * np.exp(r.x)
    print(json.dumps({"seconds": float(np.median(times)), "cpu_seconds": float(np.median(cpu)), "cost": float(np.sum(r.fun ** 2)), "nfev": int(r.nfev),
                      "values": dict(zip(NAMES, map(float, p)))}))


if __name__ == "__main__":
    main()
