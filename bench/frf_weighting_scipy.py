#!/usr/bin/env python3
"""Which |H| belongs in the FRF weights? An independent check with numpy/scipy on mdof2 (docs/estimation.md).

The fit weights an FRF line by var(h) = (1 - g2)/(n g2) |h|^2 (mbgen/data/frf_sigma.hpp). This script fits mdof2's
receptances d1/F1, d2/F1 (10-400 Hz, 0.25 Hz lines, 40 dB) with scipy.optimize.least_squares on that weighted
residual, its own model assembly and noise (no mbgen, no truthgen), over many noise realisations, and prints per
parameter the mean and RMS of z = (estimate - truth) / reported std (s^2 (J^T J)^-1, s^2 = RSS/(n - k)). Honest
error bars give mean z ~ 0 (within its standard error, about 1/sqrt(draws)) and RMS z ~ 1.

Data, each with the coherence the analyser (or generator) would write:
  expected   h = H + noise, g2 = |H|^2/(|H|^2 + sigma^2) from the noise-free H (truthgen before 2026-11-26)
  analyser   h = H + noise, g2 = |h|^2/(|h|^2 + sigma^2) from h itself (truthgen since; what an analyser's
             coherence of an H1 estimate is when its residual spectrum is known exactly)
  h1:N       an H1 estimate from N averages of white input and output noise, g2 the averages' own coherence
Weights, var from:
  measured   the measured |h| (the fit's)
  model      the model's |H| at the current estimate, iterated to a fixed point (4 passes)

    bench/frf_weighting_scipy.py [--draws 60] [--data expected,analyser,h1:5,h1:20,h1:50]
"""
import argparse
import sys

import numpy as np
from scipy.optimize import least_squares

NAMES = ["m1", "m2", "k11", "k22", "k12", "c11", "c22"]
TRUTH = np.array([1.39, 1.09, 1.38e6, 0.24e6, 0.12e6, 13.42, 0.47])  # mdof2's nominal values
F_HZ = np.arange(10.0, 400.0 + 1e-9, 0.25)


def receptances(p, w):
    """d1/F1 and d2/F1 (columns) of mdof2 at angular frequencies w."""
    m1, m2, k11, k22, k12, c11, c22 = p
    M = np.diag([m1, m2])
    K = np.array([[k11 + k12, -k12], [-k12, k22 + k12]])
    C = np.diag([c11, c22])
    P = K[None] + 1j * w[:, None, None] * C[None] - (w ** 2)[:, None, None] * M[None]
    return np.linalg.solve(P, np.broadcast_to(np.array([1.0, 0.0]), (len(w), 2))[..., None])[..., 0]


def fit(h, g2, weights):
    """Estimate and reported std, parameters p = truth exp(theta) started at the truth (a local fit)."""
    w = 2 * np.pi * F_HZ
    rms = np.sqrt(np.mean(np.abs(h) ** 2, axis=0))

    def sigma(mag2):  # per real part, as mbgen: sqrt(max(var, (1e-3 RMS)^2) / 2)
        return np.sqrt(np.maximum((1 - g2) / g2 * mag2, (1e-3 * rms) ** 2) / 2)

    def residual(theta, s):
        r = (receptances(TRUTH * np.exp(theta), w) - h) / s
        return np.concatenate([r.real.ravel(), r.imag.ravel()])

    theta = np.zeros(len(TRUTH))
    s = sigma(np.abs(h) ** 2)
    for it in range(1 if weights == "measured" else 4):
        if it > 0:
            s = sigma(np.abs(receptances(TRUTH * np.exp(theta), w)) ** 2)
        sol = least_squares(residual, theta, args=(s,), method="lm", xtol=1e-14, ftol=1e-14, gtol=1e-14)
        theta = sol.x
    r, J = sol.fun, sol.jac
    s2 = r @ r / (len(r) - len(theta))
    p = TRUTH * np.exp(theta)
    return p, p * np.sqrt(np.diag(s2 * np.linalg.inv(J.T @ J)))


def draw_data(kind, H, sigma, rng):
    def complex_normal(shape):
        return (rng.standard_normal(shape) + 1j * rng.standard_normal(shape)) / np.sqrt(2)

    if kind in ("expected", "analyser"):
        h = H + sigma * complex_normal(H.shape)
        ref = H if kind == "expected" else h
        return h, np.abs(ref) ** 2 / (np.abs(ref) ** 2 + sigma ** 2)
    n = int(kind.split(":")[1])
    u = complex_normal((n,) + H.shape)
    y = H[None] * u + sigma * complex_normal((n,) + H.shape)
    s_yu, s_uu, s_yy = (y * u.conj()).sum(0), (np.abs(u) ** 2).sum(0), (np.abs(y) ** 2).sum(0)
    return s_yu / s_uu, np.abs(s_yu) ** 2 / (s_uu * s_yy)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--draws", type=int, default=60)
    ap.add_argument("--data", default="expected,analyser,h1:5,h1:20,h1:50")
    args = ap.parse_args()
    H = receptances(TRUTH, 2 * np.pi * F_HZ)
    sigma = np.sqrt(np.mean(np.abs(H) ** 2, axis=0)) / 100  # 40 dB per channel, one measurement
    print("mdof2 FRF, %d noise realisations per row: mean z / RMS z per parameter (se of a mean ~ %.2f)"
          % (args.draws, 1 / np.sqrt(args.draws)))
    print("%-10s %-9s " % ("data", "weights") + " ".join("%11s" % n for n in NAMES))
    for kind in args.data.split(","):
        rng = np.random.default_rng(20261126)
        data = [draw_data(kind, H, sigma, rng) for _ in range(args.draws)]
        for weights in ("measured", "model"):
            z = np.array([(lambda e: (e[0] - TRUTH) / e[1])(fit(h, g2, weights)) for h, g2 in data])
            print("%-10s %-9s " % (kind, weights)
                  + " ".join("%+5.2f/%4.2f" % (z[:, j].mean(), np.sqrt(np.mean(z[:, j] ** 2)))
                             for j in range(len(NAMES))))
            sys.stdout.flush()


if __name__ == "__main__":
    main()
