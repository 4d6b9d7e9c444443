#!/usr/bin/env python3
"""Self-checks of truthgen (exit 1 on any failure).

    python3 scripts/truthgen/selftest.py            # fast checks (~75 s on a shared 2-core machine)
    python3 scripts/truthgen/selftest.py --effects  # also the effect size of every case (~5 min more)
    python3 scripts/truthgen/selftest.py --corners  # and at the weak ends of the --draw ranges (~4 min more)
    python3 scripts/truthgen/selftest.py --only=CASE[,CASE] [--corners]   # just those cases' effect sizes

0. Existing command lines write byte-identical files: recorded hashes of their files (the test data of
   tests/diagnosis and the committed example data depend on them).
1. The assembled reference models against docs/reference-models.md: spindle inertias and undamped natural
   frequencies (0.1 %), mdof2 modes and damping ratios, mdof2 G11/G21 against the printed closed form; frame3
   against its hand-written characteristic polynomial and accelerance, and against examples/frame3/frame3.mdl.
2. Structure: M, K, C symmetric, G skew, the spindle's two uncoupled blocks, spin couples them.
3. Cases: the spindle's compliant base has its x mode at 190 Hz; resonators add a mode near their frequency;
   the sensor filters are T(s) times the structure's FRF (hand-written T); base_on_feet's rocking mode; the
   frame's torsion modes; --draw stays in its ranges.
4. Time simulation against direct solve: a periodic multisine in steady state, simulated with the exact
   zero-order hold, has the FRF sum_n G(i(w + n ws)) H0(i(w + n ws))/T, computed from the direct continuous
   solve (no matrix exponential): agreement to 1e-6 for every case with time records, filters and delays
   included. A delayed record from rest equals a record simulated 4 times finer and shifted. Then Welch H1 of
   long noisy records agrees with the sampled-system FRF within the predicted random error.
5. Noise: FRF noise has the defined sigma, also averaged; coherence as defined; same seed, same data; the CLI
   writes files in the documented formats. The measurement chain (--gain, --input-gain, --force-sign, --swap,
   --unit, --frf-form): each file against the one without the option, read back from the CSVs.
7. Output-only records (--kind oma): no force column; the truth modes are the damped modes and their shapes those
   of the hand-solved quadratic eigenproblem (M s^2 + C s + K) phi = 0 at the outputs; the clean responses'
   covariance and lag-1 covariance agree with the stationary covariance of the discrete Lyapunov equation
   P = Ad P Ad^T + Bd Q Bd^T (Q = force RMS^2 I): the record is stationary; the noise has the defined sigma.
"""
import hashlib
import json
import os
import re
import subprocess
import sys
import tempfile
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from truthlib.bootstrap import ensure_numpy  # noqa: E402

ensure_numpy()

import numpy as np  # noqa: E402
import scipy.linalg  # noqa: E402
import scipy.signal  # noqa: E402

import truthgen  # noqa: E402
from truthlib import cases, chain, effects, generate, models, response  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.normpath(os.path.join(HERE, "..", ".."))

FAILURES = []


def check(condition, what):
    print("%s  %s" % ("ok  " if condition else "FAIL", what))
    if not condition:
        FAILURES.append(what)


def close(a, b, rel):
    return abs(a - b) <= rel * abs(b)


# ---- 1. reference numbers ------------------------------------------------------------------------------
SPINDLE_REFERENCE_HZ = [212.1, 231.2, 276.1, 285.4, 451.4, 526.1, 639.7, 744.1, 814.8, 869.1, 1103.0]


def check_reference():
    p = models.SPINDLE_NOMINAL
    j_s, j_h = models.spindle_inertias(p)
    for got, want, name in [(j_s[0, 0], 0.33515, "J_sxx"), (j_s[2, 2], 0.0042360, "J_szz"),
                            (j_h[0, 0], 0.269121, "J_hxx"), (j_h[1, 1], 0.259687, "J_hyy"),
                            (j_h[2, 2], 0.0546547, "J_hzz")]:
        check(close(got, want, 1e-4), "spindle %s = %.7g (reference %.7g)" % (name, got, want))
    f = response.undamped_natural_frequencies(models.build_spindle(p).matrices())
    worst = max(abs(a - b) / b for a, b in zip(f, SPINDLE_REFERENCE_HZ))
    check(len(f) == 11 and worst <= 1e-3,
          "spindle undamped frequencies %s within 0.1 %% of the reference (worst %.3f %%)"
          % (np.round(f, 1).tolist(), 100 * worst))
    fx = np.arange(220.0, 300.0, 0.05)
    mag = np.abs(response.frf(models.build_spindle(p).matrices(), fx)[:, 0, 0])
    peaks = fx[scipy.signal.argrelmax(mag)[0]]
    check(len(peaks) == 2 and abs(peaks[0] - 231.1) < 0.3 and abs(peaks[1] - 286.3) < 0.3,
          "spindle Fx -> xs_front peaks %s (reference 231.1, 286.3 Hz)" % np.round(peaks, 2).tolist())

    mats = models.build_mdof2(models.MDOF2_NOMINAL).matrices()
    fr, zeta = response.damped_modes(mats)
    check(abs(fr[1] - 166.29) < 0.01 and abs(fr[0] - 89.72) < 0.01,
          "mdof2 modes %.3f, %.3f Hz (reference 89.72, 166.29)" % (fr[0], fr[1]))
    check(abs(zeta[1] - 0.00455) < 5e-6 and abs(zeta[0] - 0.000514) < 5e-7,
          "mdof2 damping ratios %.6f, %.6f (reference 0.000514, 0.00455)" % (zeta[0], zeta[1]))
    # Closed form of docs/reference-models.md, with a damped helix so that every coefficient matters.
    q = dict(models.MDOF2_NOMINAL, c12=3.0)
    m1, m2, k11, k22, k12, c11, c22, c12 = (q[n] for n in ("m1", "m2", "k11", "k22", "k12", "c11", "c22", "c12"))
    mm = m1 * m2
    den = [1, (c11 * m2 + c12 * m1 + c12 * m2 + c22 * m1) / mm,
           (c11 * c12 + c11 * c22 + c12 * c22 + k11 * m2 + k12 * m1 + k12 * m2 + k22 * m1) / mm,
           (c11 * k12 + c11 * k22 + c12 * k11 + c12 * k22 + c22 * k11 + c22 * k12) / mm,
           (k11 * k12 + k11 * k22 + k12 * k22) / mm]
    f = np.linspace(10, 400, 300)
    s = 2j * np.pi * f
    g11 = np.polyval([1 / m1, (c12 + c22) / mm, (k12 + k22) / mm], s) / np.polyval(den, s)
    g21 = np.polyval([c12 / mm, k12 / mm], s) / np.polyval(den, s)
    H = response.frf(models.build_mdof2(q).matrices(), f)
    err = max(np.max(np.abs(H[:, 0, 0] - g11) / np.abs(g11)), np.max(np.abs(H[:, 1, 0] - g21) / np.abs(g21)))
    check(err < 1e-9, "mdof2 G11, G21 equal the closed-form transfer functions (max rel. error %.1e)" % err)


# ---- 2. structure --------------------------------------------------------------------------------------
def check_structure():
    s = models.build_spindle(dict(models.SPINDLE_NOMINAL, n_sp=300), {"spin": True})
    m = s.matrices()
    check(all(np.allclose(m[k], m[k].T, rtol=0, atol=1e-9 * np.abs(m[k]).max()) for k in ("M", "K", "C")),
          "spindle M, K, C symmetric")
    check(np.allclose(m["G"], -m["G"].T) and abs(m["G"][s.index("spindle", "rx"), s.index("spindle", "ry")]
                                                 - 0.0042360 * 2 * np.pi * 300) < 1e-3,
          "spindle G skew with G[rx, ry] = +J_szz * Omega")
    nominal = models.build_spindle(models.SPINDLE_NOMINAL)
    mats = nominal.matrices()
    x_block = [i for i, (b, d) in enumerate(nominal.coords) if d in ("x", "ry", "rz")]
    y_block = [i for i in range(nominal.n) if i not in x_block]
    coupling = max(np.abs(mats[k][np.ix_(x_block, y_block)]).max() for k in ("M", "K", "C"))
    check(coupling == 0.0, "spindle splits into x/ry/rz and y/z/rx blocks")
    check(np.abs(m["G"][np.ix_(x_block, y_block)]).max() > 0, "spin couples the two blocks")


# ---- 3. cases ------------------------------------------------------------------------------------------
def check_cases():
    c = cases.get("spindle", "compliant_ground")
    x_modes = cases.base_x_modes_hz(c.build(c.truth_parameters()))
    check(abs(x_modes[0] - 190.0) < 1.0, "spindle compliant base: lowest base-x mode at %.1f Hz" % x_modes[0])
    for n in (1, 2):
        d = c.drawn(n)
        got = cases.base_x_modes_hz(d.build(d.truth_parameters()))[0]
        check(abs(got - d.values["f_base"]) < 0.01 and 160 <= got <= 220,
              "spindle compliant base, --draw %d: base-x mode %.2f Hz (drawn %.4g, range 160-220)"
              % (n, got, d.values["f_base"]))
    for example in ("mdof2", "spindle"):
        c = cases.get(example, "resonator")
        fr, _ = response.damped_modes(c.build(c.truth_parameters()).matrices())
        nearest = fr[np.argmin(np.abs(fr - c.effect_hz))]
        check(abs(nearest / c.effect_hz - 1) < 0.05,
              "%s resonator: truth has a mode at %.1f Hz (own mode %g Hz)" % (example, nearest, c.effect_hz))
    for (example, name), c in cases.CASES.items():
        p = c.truth_parameters()
        ex = models.EXAMPLES[example]
        moved = [abs(p[n] / ex["nominal"][n] - 1) for n in ex["estimable"]]
        check(min(moved) >= 0.029 and max(moved) <= 0.101,
              "%s/%s: estimable parameters moved by %.1f..%.1f %%" % (example, name, 100 * min(moved),
                                                                       100 * max(moved)))


# ---- 4. time simulation against direct solve -----------------------------------------------------------
def aliased_zoh_frf(mats, f_hz, dt, aliases=400):
    """G_d = (1/T) sum_n G(i v_n) (1 - exp(-i v_n T))/(i v_n), v_n = w + 2 pi n/T, from the direct solve."""
    total = 0
    for n in range(-aliases, aliases + 1):
        v = 2 * np.pi * (np.asarray(f_hz) + n / dt)
        hold = (1 - np.exp(-1j * v * dt)) / (1j * v * dt)
        total = total + response.frf(mats, v / (2 * np.pi)) * hold[:, None, None]
    return total


def steady_state_multisine_frf(mats, fs, period, lines, rng):
    """Periodic steady state (initial state solved exactly), output spectrum over input spectrum. A delayed
    output reads the periodic record before its start, as the steady state has it."""
    A, Bc, Cc, delays = response.simulation_model(mats)
    Ad, Bd = response.zoh_discretise(A, Bc, 1.0 / fs)
    ni = Bc.shape[1]
    k = np.arange(period)
    result = np.zeros((len(lines), Cc.shape[0], ni), complex)
    for i in range(ni):
        phases = rng.uniform(0, 2 * np.pi, len(lines))
        u = np.zeros((period, ni))
        u[:, i] = np.sum(np.cos(2 * np.pi * np.outer(k, lines) / period + phases), axis=1)
        _, x_end = response.run_discrete(Ad, Bd, Cc, u)
        x0 = np.linalg.solve(np.eye(Ad.shape[0]) - np.linalg.matrix_power(Ad, period), x_end)
        states, x_after = response.run_states(Ad, Bd, u, x0)
        y = states @ Cc.T
        for o, tau in delays:
            y[:, o] = response.delayed_output(A, Bc, Cc[o], states, u, tau, 1.0 / fs, periodic=True)
        assert np.allclose(x_after, x0, rtol=1e-6, atol=1e-6 * np.abs(x0).max())
        U = np.fft.rfft(u[:, i])[lines]
        Y = np.fft.rfft(y, axis=0)[lines]
        result[:, :, i] = Y / U[:, None]
    return result


def check_time_vs_frf():
    rng = np.random.default_rng(7)
    for (example, name), c in cases.CASES.items():
        if "time" not in c.kinds:
            continue
        mats = c.build(c.truth_parameters()).matrices()
        fs = generate.SAMPLE_RATE[example]
        period = int(fs)                       # 1 Hz lines
        f_lo, f_hi, _ = generate.FRF_GRID[example]
        lines = np.arange(int(f_lo), int(f_hi) + 1, 7)
        Hs = steady_state_multisine_frf(mats, fs, period, lines, rng)
        Hd = aliased_zoh_frf(mats, lines.astype(float), 1.0 / fs)
        err = np.max(np.abs(Hs - Hd)) / np.max(np.abs(Hd))
        check(err < 1e-6, "%s/%s: ZOH simulation = direct solve with hold and aliasing (max error %.1e of max|H|)"
              % (example, name, err))

    # Welch H1 of a long noisy record, against the exact sampled-system FRF.
    c = cases.get("spindle", "nominal")
    mats = c.build(c.truth_parameters()).matrices()
    fs, seconds, nseg = 8192.0, 64.0, 32768
    data = generate.make_time(mats, fs, seconds, 40.0, np.random.default_rng(11), 100.0)
    u = data["u"][:, 0]
    _, Puu = scipy.signal.welch(u, fs, window="hann", nperseg=nseg)
    segments = (len(u) - nseg) // (nseg // 2) + 1
    A, Bc, Cc = response.state_space(mats)
    Ad, Bd = response.zoh_discretise(A, Bc, 1.0 / fs)
    for o, name in enumerate(["xs_front", "xs_rear", "xh_front"]):
        f, Puy = scipy.signal.csd(u, data["noisy"][:, o], fs, window="hann", nperseg=nseg)
        _, Puy_clean = scipy.signal.csd(u, data["clean"][:, o], fs, window="hann", nperseg=nseg)
        band = (f >= 50) & (f <= 1200)
        Gd = response.discrete_frf(Ad, Bd, Cc, f[band], 1.0 / fs)[:, o, 0]
        predicted = data["sigma"][o] ** 2 / (100.0 ** 2 * segments / 1.06)   # Snn/(Suu n_d), white input
        z = np.abs(Puy[band] / Puu[band] - Gd) ** 2 / predicted
        bias = np.abs(Puy_clean[band] / Puu[band] - Gd) ** 2 / predicted
        # Pure noise gives |error|^2/predicted ~ chi2_2/2: median 0.69, 95 % below 3. The Hann window's bias
        # near the sharpest features (resonances, anti-resonances) adds to a few per cent of the bins.
        check(0.5 < np.median(z) < 0.95 and np.mean(z < 3) > 0.85 and np.median(bias) < 0.01,
              "Welch H1 of a 64 s record at 40 dB, %s/Fx vs the FRF: median normalised error %.2f (noise alone "
              "0.69), %.1f %% below 3; without noise median %.1e" % (name, np.median(z), 100 * np.mean(z < 3),
                                                                    np.median(bias)))


# ---- 5. noise, determinism, files ----------------------------------------------------------------------
def check_noise_and_files():
    c = cases.get("spindle", "nominal")
    mats = c.build(c.truth_parameters()).matrices()
    f = generate.frequency_grid(50, 1200, 0.25)
    a = generate.make_frf(mats, f, 40.0, np.random.default_rng(5))
    b = generate.make_frf(mats, f, 40.0, np.random.default_rng(5))
    check(np.array_equal(a["noisy"], b["noisy"]), "same seed, same FRF noise")
    for o in range(3):
        H = a["clean"][:, o, 0]
        rms = np.sqrt(np.mean(np.abs(H) ** 2))
        ratio = np.sqrt(np.mean(np.abs(a["noisy"][:, o, 0] - H) ** 2)) / (rms / 100)
        check(abs(ratio - 1) < 0.05, "FRF noise RMS / (RMS|H| / 100) = %.3f at 40 dB" % ratio)
    check(np.allclose(a["coherence"], np.abs(a["noisy"]) ** 2 / (np.abs(a["noisy"]) ** 2 + a["sigma"] ** 2)),
          "coherence = |h|^2/(|h|^2 + sigma^2) of the noisy h")

    cli = os.path.join(os.path.dirname(os.path.abspath(__file__)), "truthgen.py")
    with tempfile.TemporaryDirectory() as tmp:
        outs = []
        for run in range(2):
            path = os.path.join(tmp, "g%d.csv" % run)
            subprocess.run([sys.executable, cli, "--example", "spindle", "--case", "gyroscopic", "--kind", "time",
                            "--duration", "0.25", "--seed", "3", "--set", "n_sp=300", "-o", path], check=True)
            outs.append(open(path).read())
        check(outs[0] == outs[1], "CLI: same seed, identical time record")
        lines = outs[0].splitlines()
        header = [ln for ln in lines if not ln.startswith("#")][0]
        check("# set n_sp=300" in lines and header == "t,Fx,xs_front,xs_rear,xh_front",
              "CLI: time record has `# set n_sp=300` and header t,Fx,xs_front,xs_rear,xh_front")
        rows = np.array([[float(v) for v in ln.split(",")] for ln in lines[lines.index(header) + 1:]])
        dt = 1 / 8192
        grid_err = np.max(np.abs(rows[:, 0] - rows[0, 0] - dt * np.arange(len(rows)))) / dt
        check(len(rows) == 2048 and grid_err < 0.01, "CLI: 2048 samples on a uniform grid (max error %.4f dt)"
              % grid_err)
        path = os.path.join(tmp, "f.csv")
        subprocess.run([sys.executable, cli, "--example", "mdof2", "--case", "free_parameter", "--kind", "frf",
                        "-o", path], check=True)
        text = open(path).read()
        check("d1/F1.re,d1/F1.im,d1/F1.coh,d2/F1.re,d2/F1.im,d2/F1.coh" in text and "# set" not in text
              and os.path.exists(os.path.join(tmp, "f.truth.json")),
              "CLI: FRF columns, no `# set` line for a hidden value, truth JSON beside it")
        bad = subprocess.run([sys.executable, cli, "--example", "mdof2", "--case", "nominal", "--set", "zz=1",
                              "-o", path], capture_output=True, text=True)
        check(bad.returncode == 1 and "zz" in bad.stderr, "CLI: unknown --set parameter is an error")


# ---- 0. existing command lines: byte-identical files ---------------------------------------------------
# (name, arguments, sha256 of CSV + truth JSON, first 16 hex digits) of files written with `-o NAME.csv` in an
# empty directory: the command lines of tests/diagnosis, make_examples.sh (b01-b04: the committed example CSVs) and
# a few options. They hold the data of existing command lines fixed while options and cases are added. A mismatch
# on another machine may be a numpy/LAPACK difference in the last written digit; on this one it means existing
# data changed.
EXISTING_OUTPUTS = [
    ("b01", "--example mdof2 --case nominal --kind frf --snr-db 40 --seed 1", "6f5cdb9af216dadc"),
    ("b02", "--example mdof2 --case nominal --kind time --snr-db 40 --seed 2", "f53a904663018163"),
    ("b03", "--example spindle --case nominal --kind frf --snr-db 40 --seed 3", "30507ee068c3c6be"),
    ("b04", "--example spindle --case compliant_ground --kind frf --snr-db 40 --seed 4", "434ddd9d8f7faf23"),
    ("d11", "--example mdof2 --case nominal --kind frf --snr-db 40 --seed 11", "10acc8e92e237fdd"),
    ("d12", "--example mdof2 --case compliant_ground --kind frf --snr-db 40 --seed 12", "dd39f01aa70fbdb8"),
    ("d13", "--example mdof2 --case free_parameter --kind frf --snr-db 40 --seed 13", "bdee4bb4e49d02d0"),
    ("d14", "--example mdof2 --case resonator --kind frf --snr-db 40 --seed 14", "c67a85a3f206d360"),
    ("d15", "--example mdof2 --case outside_maxwell --kind frf --snr-db 40 --seed 15", "8d304920d05a4b96"),
    ("d21", "--example mdof2 --case nominal --kind time --snr-db 40 --seed 21", "0caf744d5084f71a"),
    ("d22", "--example mdof2 --case compliant_ground --kind time --snr-db 40 --seed 22", "008b6372e559473f"),
    ("d61", "--example mdof2 --case free_parameter --kind time --snr-db 40 --seed 61", "cbea37ed94960ff3"),
    ("d63", "--example mdof2 --case outside_maxwell --kind time --snr-db 40 --seed 63", "93894d75ddcf99c4"),
    ("d62", "--example mdof2 --case resonator --kind time --snr-db 40 --seed 62", "5a4708a8ec443caf"),
    ("d53", "--example spindle --case nominal --kind time --snr-db 40 --seed 53 --duration 1", "8c4383febd8282d4"),
    ("d52", "--example spindle --case compliant_ground --kind time --snr-db 40 --seed 52 --duration 1",
     "5b966daa2d7d49fb"),
    ("d54", "--example spindle --case added_mass --kind time --snr-db 40 --seed 54 --duration 1", "bf82c3652dab64aa"),
    ("d55", "--example spindle --case resonator --kind time --snr-db 40 --seed 55 --duration 1", "84acd9644b325b26"),
    ("d56", "--example spindle --case moment_stiffness --kind time --snr-db 40 --seed 56 --duration 1",
     "e184dd59b8fa590e"),
    ("d57", "--example spindle --case connection --kind time --snr-db 40 --seed 57 --duration 1", "333948f0aaa8da75"),
    ("d58", "--example spindle --case sensor_dynamics --kind time --snr-db 40 --seed 58 --duration 1",
     "759f99e5c95b28f9"),
    ("d59", "--example spindle --case untie_parameter --kind time --snr-db 40 --seed 59 --duration 1",
     "758ad63baff1cc98"),
    ("d60", "--example spindle --case gyroscopic --kind time --snr-db 40 --seed 60 --set n_sp=0 --duration 1",
     "b60de3b9035948ac"),
    ("d64", "--example spindle --case gyroscopic --kind time --snr-db 40 --seed 64 --set n_sp=300 --duration 1",
     "0d51aaf8d2f385aa"),
    ("d31", "--example spindle --case nominal --kind frf --snr-db 40 --seed 31", "997a1bec31838a9c"),
    ("d32", "--example spindle --case compliant_ground --kind frf --snr-db 40 --seed 32", "ca54c81fba3e1548"),
    ("d33", "--example spindle --case untie_parameter --kind frf --snr-db 40 --seed 33", "6e414856a43b49d6"),
    ("d34", "--example spindle --case added_mass --kind frf --snr-db 40 --seed 34", "5ae3da20b33d51b1"),
    ("d35", "--example spindle --case resonator --kind frf --snr-db 40 --seed 35", "2bbc86f7492c1f87"),
    ("d36", "--example spindle --case moment_stiffness --kind frf --snr-db 40 --seed 36", "3627f2f47a4fc3cb"),
    ("d37", "--example spindle --case gyroscopic --kind frf --snr-db 40 --seed 37 --set n_sp=0", "6428adbce04a9391"),
    ("d38", "--example spindle --case gyroscopic --kind frf --snr-db 40 --seed 38 --set n_sp=300", "13e1f5415c50dd27"),
    ("d39", "--example spindle --case connection --kind frf --snr-db 40 --seed 39", "9624fa0c487e069a"),
    ("d40", "--example spindle --case outside_maxwell --kind frf --snr-db 40 --seed 40", "6035c59db73db2c9"),
    ("d41", "--example spindle --case sensor_dynamics --kind frf --snr-db 40 --seed 41", "59e4a30a794ac9b5"),
    ("x01", "--example mdof2 --case added_mass --kind frf --seed 5 --snr-db inf", "7f98bff06612a6b8"),
    ("x02", "--example spindle --case outside_maxwell --kind time --seed 6 --excitation gaussian --duration 0.5 "
            "--snr-db 30", "564092e3e6d7de3c"),
    ("x03", "--example mdof2 --case nominal --kind frf --seed 7 --f-min 20 --f-max 200 --df 0.5 --set m1=1.5",
     "5e9829d9950ccba0"),
    # --draw, --averages, --no-coherence and frame3
    ("e01", "--example spindle --case untie_parameter --kind frf --draw 1", "082c6db6625f7d42"),
    ("e02", "--example frame3 --case nominal --kind frf --seed 5", "0e36d81918f464c6"),
    ("e03", "--example spindle --case sensor_delay --kind time --draw 2 --duration 0.5 --seed 9", "d0363b7262311847"),
    ("e04", "--example mdof2 --case sensor_lowpass --kind frf --averages 4 --no-coherence --draw 7",
     "5665864056001aa4"),
    ("e05", "--example spindle --case base_on_feet --kind frf --draw 4 --seed 8", "27d19e6b9dddc796"),
]


def run_cli_here(argv, directory):
    """truthgen.run in this process (no interpreter start per file), in `directory`, with sys.argv as the CLI
    has it (the truth JSON records the command line). Not for byte comparisons (run_cli)."""
    saved_argv, saved_cwd = sys.argv, os.getcwd()
    sys.argv = ["truthgen.py"] + argv
    os.chdir(directory)
    try:
        return truthgen.run(argv)
    finally:
        sys.argv = saved_argv
        os.chdir(saved_cwd)


def file_digest(directory, name):
    data = b""
    for suffix in (".csv", ".truth.json"):
        with open(os.path.join(directory, name + suffix), "rb") as f:
            data += f.read()
    return hashlib.sha256(data).hexdigest()[:16]


def run_cli(argv, directory):
    """The CLI in a fresh interpreter, as tests run it. (In one long process numpy's results can differ in the
    last bit with the alignment of its arrays, which depends on what ran before: the written digits of a sigma
    in the JSON did, so the byte-identity check must not run in-process.)"""
    subprocess.run([sys.executable, os.path.join(HERE, "truthgen.py")] + argv, cwd=directory, check=True)


def check_existing_outputs():
    changed = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, args, digest in EXISTING_OUTPUTS:
            run_cli(args.split() + ["-o", name + ".csv"], tmp)
            if file_digest(tmp, name) != digest:
                changed.append(name)
        for path, name in [("examples/mdof2/data/frf_F1.csv", "b01"), ("examples/spindle/data/frf_Fx.csv", "b03"),
                           ("examples/mdof2/data/time_F1.csv", "b02"),
                           ("examples/spindle/data/frf_Fx_base_mode.csv", "b04")]:
            with open(os.path.join(REPO, path), "rb") as f, open(os.path.join(tmp, name + ".csv"), "rb") as g:
                if f.read() != g.read():
                    changed.append(path)
    check(not changed, "%d existing command lines write byte-identical CSV and truth JSON, and the 4 committed "
                       "example CSVs regenerate byte-identical%s"
          % (len(EXISTING_OUTPUTS), (" (changed: %s)" % ", ".join(changed)) if changed else ""))


# ---- 3b. sensor filters, base on feet, frame3, --draw ----------------------------------------------------
def hand_filter(kind, value, f_hz):
    """T(i w) written out again, not through response.output_filter_response."""
    w = 2 * np.pi * np.asarray(f_hz, dtype=float)
    if kind == "lowpass":
        wc = 2 * np.pi * value
        return wc ** 2 / (wc ** 2 - w ** 2 + 1j * np.sqrt(2) * wc * w)
    if kind == "highpass":
        wh = 2 * np.pi * value
        return 1j * w / (wh + 1j * w)
    return np.cos(w * value) - 1j * np.sin(w * value)


SENSOR_CASES = [("sensor_lowpass", "lowpass", "fc"), ("sensor_highpass", "highpass", "fh"),
                ("sensor_delay", "delay", "tau")]


def check_sensor_filters():
    for example in ("mdof2", "spindle"):
        out = cases.SENSOR_OUTPUT[example]
        f = generate.frequency_grid(*generate.FRF_GRID[example])
        for name, kind, size in SENSOR_CASES:
            for c in (cases.get(example, name), cases.get(example, name).drawn(5)):
                p = c.truth_parameters()
                system = c.build(p)
                o = system.output_names().index(out)
                H = response.frf(system.matrices(), f)
                H0 = response.frf(models.EXAMPLES[example]["build"](p, None).matrices(), f)
                T = hand_filter(kind, c.values[size], f)
                err = np.max(np.abs(H[:, o, :] - T[:, None] * H0[:, o, :])) / np.max(np.abs(H0[:, o, :]))
                others = np.delete(np.arange(H.shape[1]), o)
                untouched = np.array_equal(H[:, others, :], H0[:, others, :])
                phase = np.degrees(np.angle(T))
                lo, hi = c.sizes[0].low, c.sizes[0].high
                check(err < 1e-12 and untouched and lo <= c.values[size] <= hi,
                      "%s/%s%s: %s = T(s) x structure (T by hand, error %.0e), other outputs untouched; %s = %.4g "
                      "in [%g, %g]; in the band |T| %.3f..%.3f, phase %+.1f..%+.1f deg"
                      % (example, name, " --draw 5" if c.draw else "", out, err, size, c.values[size], lo, hi,
                         np.min(np.abs(T)), np.max(np.abs(T)), phase.min(), phase.max()))


def check_delay_from_rest():
    """A delayed record from rest against the undelayed structure simulated 4 times finer (the same held input)
    and shifted by tau: an independent route for y_d[k] = Cy x(t_k - tau), zero before the record."""
    c = cases.get("mdof2", "sensor_delay")
    p = c.truth_parameters()
    dt, fine = 1 / 4096.0, 4
    u = np.random.default_rng(3).uniform(-10, 10, (400, 1))
    plain = models.build_mdof2(p).matrices()
    y_fine, _ = response.simulate_zoh(plain, np.repeat(u, fine, axis=0), dt / fine)
    for steps in (2.25, 3.0, 0.5, 9.75):
        tau = steps * dt
        mats = models.build_mdof2(p, {"output_filter": {"output": "d2", "kind": "delay", "value": tau}}).matrices()
        y, _ = response.simulate_zoh(mats, u, dt)
        shift = int(round(steps * fine))
        index = np.arange(len(u)) * fine - shift
        expect = np.where(index >= 0, y_fine[np.clip(index, 0, None), 1], 0.0)
        err = np.max(np.abs(y[:, 1] - expect)) / np.max(np.abs(expect))
        err_d1 = np.max(np.abs(y[:, 0] - y_fine[::fine, 0])) / np.max(np.abs(y[:, 0]))
        check(err < 1e-9 and err_d1 < 1e-9,
              "delay %.2f dt from rest = the 4x finer record shifted by tau (max error %.1e; d1 undelayed)"
              % (steps, err))


def sampled_frf(mats, f_hz, dt):
    """Exact FRF of the sampled record, filters and delays included: a delayed output reads
    z^-(m+1) c (A_p X + B_p U) with X = (zI - Ad)^-1 Bd U (response.delayed_output's formula in z)."""
    A, Bc, Cc, delays = response.simulation_model(mats)
    Ad, Bd = response.zoh_discretise(A, Bc, dt)
    G = response.discrete_frf(Ad, Bd, Cc, f_hz, dt)
    z = np.exp(1j * 2 * np.pi * np.asarray(f_hz, dtype=float) * dt)
    X = np.linalg.solve(z[:, None, None] * np.eye(Ad.shape[0]) - Ad,
                        np.broadcast_to(Bd.astype(complex), (len(z),) + Bd.shape))
    for o, tau in delays:
        m, delta = response.split_delay(tau, dt)
        Ap, Bp = response.zoh_discretise(A, Bc, dt - delta)
        G[:, o, :] = z[:, None] ** -(m + 1) * np.einsum("s,fsi->fi", Cc[o], np.einsum("st,fti->fsi", Ap, X) + Bp)
    return G


def check_sensor_records():
    """Welch H1 of generated records (truthgen's own path: make_time from rest, output noise) of the spindle's
    delayed and low-passed xs_front against the exact sampled FRF, which the multisine check ties to the direct
    continuous solve."""
    fs, seconds, nseg = 8192.0, 32.0, 16384
    for name in ("sensor_delay", "sensor_lowpass"):
        c = cases.get("spindle", name)
        mats = c.build(c.truth_parameters()).matrices()
        data = generate.make_time(mats, fs, seconds, 40.0, np.random.default_rng(17), 100.0)
        u = data["u"][:, 0]
        f, Puu = scipy.signal.welch(u, fs, window="hann", nperseg=nseg)
        _, Puy = scipy.signal.csd(u, data["noisy"][:, 0], fs, window="hann", nperseg=nseg)
        segments = (len(u) - nseg) // (nseg // 2) + 1
        band = (f >= 50) & (f <= 1200)
        Gd = sampled_frf(mats, f[band], 1.0 / fs)[:, 0, 0]
        G_no_sensor = sampled_frf(models.build_spindle(c.truth_parameters()).matrices(), f[band], 1.0 / fs)[:, 0, 0]
        predicted = data["sigma"][0] ** 2 / (100.0 ** 2 * segments / 1.06)
        z = np.abs(Puy[band] / Puu[band] - Gd) ** 2 / predicted
        z0 = np.abs(Puy[band] / Puu[band] - G_no_sensor) ** 2 / predicted
        check(0.5 < np.median(z) < 0.95 and np.mean(z < 3) > 0.85 and np.median(z0) > 10,
              "spindle/%s: Welch H1 of a 32 s record, xs_front/Fx vs the sampled FRF with the sensor: median "
              "normalised error %.2f (noise alone 0.69), %.1f %% below 3; without the sensor %.3g"
              % (name, np.median(z), 100 * np.mean(z < 3), np.median(z0)))


def rigid_motion_map(system, reference=(0.0, 0.0, 0.0)):
    """Coordinates of every body when the whole assembly moves as one rigid body (x y z rx ry rz about
    `reference`): a body's translation is t + theta x (c - reference), its rotations theta."""
    T = np.zeros((system.n, 6))
    for j in range(6):
        t, theta = np.eye(6)[j, :3], np.eye(6)[j, 3:]
        for body, dof in system.coords:
            u = t + np.cross(theta, system.bodies[body].com - np.asarray(reference))
            T[system.index(body, dof), j] = u["xyz".index(dof)] if dof in "xyz" else theta["xyz".index(dof[1])]
    return T


def check_base_on_feet():
    """The draw tunes the feet so that the machine, taken as one rigid body, rocks about z at f_rock
    (models.base_rocking_hz, from a parallel-axis sum). Independent route: the truth's own mass matrix and feet
    stiffness projected on rigid motions of the whole assembly (6 x 6). For the default and four draws; also the
    truth's own lowest feet mode (the mounts' compliance puts it lower) and, for information, the assembly with
    mounts and bearings 1e4 times stiffer (about 1 % higher than the rigid body: a stiff x spring between a mount's
    two points, 16 mm apart in y, also resists the rigid rotation about z, by the linear model's convention)."""
    case = cases.get("spindle", "base_on_feet")
    for c in [case] + [case.drawn(n) for n in (1, 2, 3, 4)]:
        p = c.truth_parameters()
        f_rock, m_base = c.values["f_rock"], c.values["m_base"]
        system = c.build(p)
        T = rigid_motion_map(system)
        M6 = T.T @ system.mass_matrix() @ T
        K6 = T.T @ system.stiffness_of("base_foot") @ T
        w2, V = scipy.linalg.eigh(K6, M6)
        x_rz = [np.sqrt(w) / (2 * np.pi) for w, v in zip(w2, V.T) if np.linalg.norm(v[[1, 2, 3, 4]]) < 1e-9]
        rigid = min(x_rz)
        stiff = dict(p)
        for name in ("k_fx", "k_fy", "k_fz", "k_rx", "k_ry", "k_hbx", "k_hby", "k_hbz"):
            stiff[name] = p[name] * 1e4
        stiff_mounts = cases.feet_modes_hz(models.build_spindle(stiff, c.effects(p)))[0]
        truth = cases.feet_modes_hz(system)
        k3, c3 = c.effects(p)["base_box"]["k3"], c.effects(p)["base_box"]["c3"]
        damping_ok = all(abs(cc - 2 * 0.03 * k / (2 * np.pi * f_rock)) < 1e-9 * cc for k, cc in zip(k3, c3))
        check(abs(rigid / f_rock - 1) < 1e-9 and 150 <= f_rock <= 260 and 25 <= m_base <= 60 and damping_ok
              and abs(stiff_mounts / f_rock - 1) < 0.03 and 0.7 * f_rock <= truth[0] <= f_rock,
              "spindle/base_on_feet%s: base %.4g kg; rigid machine on the feet rocks at %.3f Hz (drawn %.4g, range "
              "150-260; stiff mounts %.1f); the truth's lowest feet mode %.1f Hz; foot k = %.3g/%.3g/%.3g N/m"
              % (" --draw %d" % c.draw["n"] if c.draw else "", m_base, rigid, f_rock, stiff_mounts, truth[0], *k3))


def frame3_hand_matrices(p):
    m = np.diag([p["m1"], p["m2"], p["m3"]])

    def chain(a, b, c):
        return np.array([[a + b, -b, 0.0], [-b, b + c, -c], [0.0, -c, c]])
    return m, chain(p["k1"], p["k2"], p["k3"]), chain(p["c1"], p["c2"], p["c3"])


def check_frame3():
    p = models.FRAME3_NOMINAL
    M, K, C = frame3_hand_matrices(p)
    # det(K - lam M) by hand, as a cubic in lam
    P = np.polynomial.Polynomial
    a, b, c = P([p["k1"] + p["k2"], -p["m1"]]), P([p["k2"] + p["k3"], -p["m2"]]), P([p["k3"], -p["m3"]])
    det = a * (b * c - p["k3"] ** 2) - p["k2"] ** 2 * c
    hand = np.sort(np.sqrt(det.roots().real)) / (2 * np.pi)
    mats = models.build_frame3(p).matrices()
    got = response.undamped_natural_frequencies(mats)
    fr, zeta = response.damped_modes(mats)
    check(np.max(np.abs(got / hand - 1)) < 1e-9 and 19 < fr[0] < 20 and 71 < fr[2] < 72
          and 0.008 < zeta[0] < 0.01 and zeta[2] < 0.032,
          "frame3 modes %s Hz (characteristic polynomial by hand: %s), damping ratios %s %%"
          % (np.round(fr, 2).tolist(), np.round(hand, 2).tolist(), np.round(100 * zeta, 2).tolist()))
    f = generate.frequency_grid(*generate.FRF_GRID["frame3"])
    w = 2 * np.pi * f
    hand_H = np.array([-wi ** 2 * np.linalg.inv(K + 1j * wi * C - wi ** 2 * M) for wi in w[::37]])
    H = response.frf(mats, f[::37])
    err = np.max(np.abs(H - hand_H)) / np.max(np.abs(hand_H))
    check(len(f) == 4096 and f[0] == 0.03125 and f[-1] == 128.0 and err < 1e-10,
          "frame3 accelerances (9 channels) = -w^2 (K + i w C - w^2 M)^-1 by hand (error %.0e); grid 4096 lines "
          "0.03125-128 Hz" % err)

    # outside_torsion: modes = the x chain's plus the torsion chain's, two of them in the band near 40 and 95 Hz
    for c in (cases.get("frame3", "outside_torsion"), cases.get("frame3", "outside_torsion").drawn(2)):
        q = c.truth_parameters()
        extra = c.extra_at(q)
        J = np.diag([q["m%d" % i] * 2 * models.PLATE ** 2 / 12 for i in (1, 2, 3)])
        kt = extra["kt"]
        Kt = np.array([[kt[0] + kt[1], -kt[1], 0], [-kt[1], kt[1] + kt[2], -kt[2]], [0, -kt[2], kt[2]]])
        torsion = np.sqrt(scipy.linalg.eigh(Kt, J, eigvals_only=True)) / (2 * np.pi)
        x_chain = response.undamped_natural_frequencies(models.build_frame3(q).matrices())
        truth = response.undamped_natural_frequencies(c.build(q).matrices())
        union = np.sort(np.concatenate([torsion, x_chain]))
        fq = np.array([torsion[0], torsion[1]])
        H = response.frf(c.build(q).matrices(), fq)
        H0 = response.frf(models.build_frame3(q).matrices(), fq)
        rise = np.max(np.abs(H) / np.abs(H0), axis=(1, 2))
        in_band = torsion[(torsion > 0) & (torsion < 128)]
        default = c.draw is None
        check(np.max(np.abs(truth / union - 1)) < 1e-9 and len(in_band) == 2 and np.all(rise > 2)
              and (not default or (abs(torsion[0] - 40) < 2 and abs(torsion[1] - 95) < 3)),
              "frame3/outside_torsion%s: truth modes = x chain %s + torsion %s Hz (two in the band); |H| at the "
              "torsion modes up to %.1fx, %.1fx the x chain's" % ("" if default else " --draw 2",
                                                          np.round(x_chain, 1).tolist(), np.round(torsion, 1).tolist(),
                                                          *rise))

    # examples/frame3/frame3.mdl declares exactly the truth's nominal model
    text = open(os.path.join(REPO, "examples", "frame3", "frame3.mdl")).read()
    params = {m.group(1): (float(m.group(2)), m.group(3))
              for m in re.finditer(r"^param\s+(\w+)\s*=\s*([-+0-9.eE]+)\s+\"[^\"]*\"\s*(\w+)?", text, re.M)}
    same = {n: v for n, (v, _) in params.items()} == p
    roles = sorted(n for n, (_, role) in params.items() if role == "estimate") == sorted(models.FRAME3_ESTIMABLE)
    signals = re.findall(r"^(input|output)\s+(\w+)\s+(\w+)\s+(?:on|of)\s+(\w+)\s+along\s+x\s*$", text, re.M)
    want = [("input", "F%d" % i, "force", "storey%d" % i) for i in (1, 2, 3)] + \
           [("output", "a%d" % i, "acceleration", "storey%d" % i) for i in (1, 2, 3)]
    springs = re.findall(r"spring (column\d) \{\s*from (\w+)\s*to (\w+)\s*along x\s*stiffness (\w+)\s*damping (\w+)",
                         text)
    want_springs = [("column1", "floor", "storey1", "k1", "c1"), ("column2", "storey1", "storey2", "k2", "c2"),
                    ("column3", "storey2", "storey3", "k3", "c3")]
    check(same and roles and signals == want and springs == want_springs,
          "examples/frame3/frame3.mdl: parameters, roles, columns, inputs and outputs match the truth's nominal model")


def check_tower5():
    """tower5: a five-mass shear chain shaken at the roof; its matrices and accelerances written out by hand here."""
    p = dict(models.TOWER5_NOMINAL)
    mats = models.build_tower5(p).matrices()
    M, C, K = mats["M"], mats["C"], mats["K"]
    k = [p["k%d" % i] for i in range(1, 6)]
    c = [p["c%d" % i] for i in range(1, 6)]

    def chain(v):  # storey i is joined to i-1 (the ground for storey 1) by element i
        A = np.zeros((5, 5))
        for i in range(5):
            A[i, i] += v[i]
            if i + 1 < 5:
                A[i, i] += v[i + 1]
                A[i, i + 1] = A[i + 1, i] = -v[i + 1]
        return A
    hand_M = np.diag([p["m%d" % i] for i in range(1, 6)])
    same = (np.allclose(M, hand_M, rtol=1e-12) and np.allclose(K, chain(k), rtol=1e-12)
            and np.allclose(C, chain(c), rtol=1e-12))
    f = generate.frequency_grid(*generate.FRF_GRID["tower5"])
    w = 2 * np.pi * f[::29]
    B = np.zeros((5, 1))
    B[4, 0] = 1.0   # the roof shaker
    hand_H = np.array([-wi ** 2 * np.linalg.solve(chain(k) + 1j * wi * chain(c) - wi ** 2 * hand_M, B) for wi in w])
    H = response.frf(mats, f[::29])
    err = np.max(np.abs(H - hand_H)) / np.max(np.abs(hand_H))
    fr, zeta = response.damped_modes(mats)
    check(same and err < 1e-10 and len(f) == 591 and 0.5 < fr[0] < 0.8 and fr[-1] < 5,
          "tower5: M, K, C of the shear chain and the roof accelerances (5 channels) by hand (error %.0e); modes %s Hz "
          "in the 0.1-6 Hz grid" % (err, np.round(fr, 2).tolist()))

    # examples/tower5/tower5.mdl: the truth's parameters (a first guess of their values), shear elements and signals
    text = open(os.path.join(REPO, "examples", "tower5", "tower5.mdl")).read()
    roles = sorted(re.findall(r"^param\s+(\w+)\s*=\s*[-+0-9.eE]+\s+\"[^\"]*\"\s+estimate", text, re.M))
    springs = re.findall(r"spring (shear\d) \{ from (\w+); to (\w+); along x; stiffness (\w+); damping (\w+) \}",
                         text)
    want_springs = [("shear%d" % i, "ground" if i == 1 else "storey%d" % (i - 1), "storey%d" % i, "k%d" % i,
                     "c%d" % i) for i in range(1, 6)]
    signals = re.findall(r"^(input|output)\s+(\w+)\s+(\w+)\s+(?:on|of)\s+(\w+)\s+along\s+x\s*$", text, re.M)
    want = [("input", "F", "force", "storey5")] + \
           [("output", "a%d" % i, "acceleration", "storey%d" % i) for i in range(1, 6)]
    check(roles == sorted(models.TOWER5_ESTIMABLE) and springs == want_springs and signals == want,
          "examples/tower5/tower5.mdl: estimable parameters, shear elements, the roof force and the five "
          "accelerometers match the truth's model")


def check_pairs():
    """A pair of effects is both singles' effects at once: at the same truth parameters its effects are the union of
    theirs, and its FRF differs from the nominal model's where each single's does (neither effect is lost)."""
    for (example, name), c in cases.CASES.items():
        if not hasattr(c, "parts"):
            continue
        singles = [cases.CASES[(example, part)] for part in c.parts]
        p = c.truth_parameters()
        keys = set(c.effects(p))
        check(len(singles) == 2 and keys == set(singles[0].effects(p)) | set(singles[1].effects(p)),
              "%s/%s: effects %s are both singles' (%s)" % (example, name, sorted(keys),
                                                           ", ".join(s.name for s in singles)))
        f = generate.frequency_grid(*generate.FRF_GRID[example])
        H_pair = response.frf(c.build(p).matrices(), f)
        for single in singles:
            H_single = response.frf(single.build(p).matrices(), f)
            check(np.max(np.abs(H_pair - H_single)) > 1e-6 * np.max(np.abs(H_single)),
                  "%s/%s: differs from %s alone (the other effect is there)" % (example, name, single.name))


def check_draws():
    """--draw: sizes inside their ranges, offsets 3-10 %, deterministic, different draws differ, and the
    default truth untouched."""
    bad = []
    for (example, name), case in cases.CASES.items():
        before = case.truth_parameters()
        for n in (1, 2, 3):
            c = case.drawn(n)
            p = c.truth_parameters()
            nominal = models.EXAMPLES[example]["nominal"]
            moved = [abs(p[k] / nominal[k] - 1) for k in models.EXAMPLES[example]["estimable"]]
            inside = all(s.low <= c.draw["sizes"][s.name] <= s.high for s in case.sizes)
            again = case.drawn(n).truth_parameters() == p and case.drawn(n).values == c.values
            if not (inside and again and min(moved) >= 0.029 and max(moved) <= 0.101):
                bad.append("%s/%s --draw %d" % (example, name, n))
        if case.truth_parameters() != before or case.draw is not None:
            bad.append("%s/%s default changed" % (example, name))
        if case.drawn(1).truth_parameters() == case.drawn(2).truth_parameters():
            bad.append("%s/%s draws 1 and 2 equal" % (example, name))
    check(not bad, "--draw 1-3 of every case: sizes inside the ranges, offsets 3-10 %%, same draw same truth, "
                   "draws differ, default unchanged%s" % ((": " + ", ".join(bad)) if bad else ""))


# ---- 5b. averages, coherence columns, new CLI options --------------------------------------------------
def check_averages_and_options():
    c = cases.get("spindle", "nominal")
    mats = c.build(c.truth_parameters()).matrices()
    f = generate.frequency_grid(50, 1200, 0.25)
    one = generate.make_frf(mats, f, 40.0, np.random.default_rng(5))
    avg = generate.make_frf(mats, f, 40.0, np.random.default_rng(5), averages=8)
    H, h, coh = avg["clean"], avg["noisy"], avg["coherence"]
    predicted = (1 - coh) / (8 * coh) * np.abs(h) ** 2       # variance of H1 from N averages at coherence coh
    ratio = np.mean(np.abs(h - H) ** 2, axis=0) / np.mean(predicted, axis=0)
    check(np.allclose(predicted, avg["sigma"][None] ** 2 / 8) and np.all(np.abs(ratio - 1) < 0.05)
          and np.allclose(h - H, (one["noisy"] - H) / np.sqrt(8)),
          "--averages 8: (1 - coh)/(8 coh) |h|^2 = sigma^2/8 on every line, noise power / it = %s"
          % np.round(ratio.ravel(), 3).tolist())
    # An analyser's H1 from N segments: (1 - coh)/(N coh) |h|^2 is the residual power of the N segments' least
    # squares over N sum|X|^2, an estimate of h's variance with 2 (N - 1) degrees of freedom and mean (N - 1)/N of
    # it, so |h - H|^2 over it has mean N/(N - 1) (N - 1)/(N - 2) = N/(N - 2): 4/3 for N = 8 (over its average
    # instead, the ratio is (N - 1)/N)
    an = generate.make_analyser_frf(mats, f, 40.0, np.random.default_rng(5), 8)
    H, h, coh = an["clean"], an["noisy"], an["coherence"]
    estimate = (1 - coh) / (8 * coh) * np.abs(h) ** 2
    z = np.abs(h - H) ** 2 / estimate
    pooled = np.mean(np.abs(h - H) ** 2, axis=0) / np.mean(estimate, axis=0)
    again = generate.make_analyser_frf(mats, f, 40.0, np.random.default_rng(5), 8)
    check(np.all(np.abs(np.mean(z, axis=0) / (8 / 6) - 1) < 0.1) and np.all(np.abs(pooled / (8 / 7) - 1) < 0.1)
          and np.all((coh > 0) & (coh < 1)) and np.array_equal(again["noisy"], h),
          "--analyser 8: |h - H|^2 over its coherence's variance estimate has mean %s (4/3 predicted), over its mean "
          "%s (8/7); coherence inside (0, 1); same seed same data"
          % (np.round(np.mean(z, axis=0).ravel(), 3).tolist(), np.round(pooled.ravel(), 3).tolist()))
    with tempfile.TemporaryDirectory() as tmp:
        run_cli_here(["--example", "mdof2", "--case", "sensor_delay", "--kind", "frf", "--averages", "4",
                      "--no-coherence", "--draw", "7", "-o", "a.csv"], tmp)
        text = open(os.path.join(tmp, "a.csv")).read()
        doc = json.load(open(os.path.join(tmp, "a.truth.json")))
        header = [ln for ln in text.splitlines() if not ln.startswith("#")][0]
        tau = doc["hidden_effect"]["values"]["delay_s_d2"]
        check(header == "f_hz,d1/F1.re,d1/F1.im,d2/F1.re,d2/F1.im" and doc["frf"]["averages"] == 4
              and doc["frf"]["coherence_columns"] is False and doc["draw"]["n"] == 7
              and doc["draw"]["sizes"]["tau"] == tau and 0.2e-3 <= tau <= 1e-3
              and set(doc["draw"]["offsets"]) == set(models.MDOF2_ESTIMABLE),
              "CLI: --no-coherence header %s; JSON records averages, no coherence, the draw (tau = %.4g ms)"
              % (header, tau * 1e3))
        run_cli_here(["--example", "frame3", "--case", "outside_torsion", "--kind", "frf", "-o", "f3.csv"], tmp)
        lines = open(os.path.join(tmp, "f3.csv")).read().splitlines()
        header = [ln for ln in lines if not ln.startswith("#")][0].split(",")
        want = ["f_hz"] + ["a%d/F%d.%s" % (o, i, part) for o in (1, 2, 3) for i in (1, 2, 3)
                           for part in ("re", "im", "coh")]
        check(header == want and len(lines) == 2 + 4096, "CLI: frame3 FRF, 9 channels, 4096 lines")
        for argv, what in [(["--example", "frame3", "--case", "nominal", "--kind", "time"], "no frame3 time records"),
                           (["--example", "mdof2", "--case", "nominal", "--kind", "time", "--averages", "2"],
                            "--averages on a time record"),
                           (["--example", "mdof2", "--case", "nominal", "--averages", "0"], "--averages 0"),
                           (["--example", "mdof2", "--case", "nominal", "--analyser", "1"], "--analyser 1"),
                           (["--example", "mdof2", "--case", "nominal", "--analyser", "4", "--averages", "2"],
                            "--analyser with --averages"),
                           (["--example", "mdof2", "--case", "nominal", "--draw", "-1"], "--draw -1")]:
            bad = subprocess.run([sys.executable, os.path.join(HERE, "truthgen.py")] + argv + ["-o", "e.csv"],
                                 capture_output=True, text=True, cwd=tmp)
            check(bad.returncode == 1 and "truthgen: error" in bad.stderr, "CLI: %s is an error" % what)


# ---- 5c. measurement chain ------------------------------------------------------------------------------
def read_csv(directory, name):
    """(header, rows of strings) of a written CSV, comment lines skipped."""
    lines = [ln for ln in open(os.path.join(directory, name + ".csv")).read().splitlines() if not ln.startswith("#")]
    return lines[0].split(","), [ln.split(",") for ln in lines[1:]]


def column(table, name):
    header, rows = table
    j = header.index(name)
    return [row[j] for row in rows]


def numbers(table, name):
    return np.array([float(v) for v in column(table, name)])


def complex_column(table, pair):
    return numbers(table, pair + ".re") + 1j * numbers(table, pair + ".im")


def negated(texts):
    """The written text of -x for each written x (the writer's "%.*g" of -x is "-" and that of x)."""
    return [t if t == "0" else t[1:] if t.startswith("-") else "-" + t for t in texts]


def scaled(got, base, factor, rel):
    """Written values `got` equal factor times the written `base`, within the rounding of the written digits."""
    want = factor * base
    return bool(np.all(np.abs(got - want) <= rel * np.abs(want) + 1e-300))


def check_input_noise():
    """--input-snr-db: the written force minus the same record's force without it is white noise at the stated
    level (read back from the CSVs); the outputs are byte-identical (the structure is driven by the clean force and
    the output noise keeps its stream); the truth JSON records the level; FRFs refuse the option."""
    with tempfile.TemporaryDirectory() as tmp:
        base = "--example mdof2 --case nominal --kind time --seed 12 --duration 4".split()
        check(run_cli_here(base + ["-o", "clean.csv"], tmp) == 0, "--input-snr-db: record without it")
        check(run_cli_here(base + ["--input-snr-db", "30", "-o", "noisy.csv"], tmp) == 0, "--input-snr-db 30")
        clean, noisy = read_csv(tmp, "clean"), read_csv(tmp, "noisy")
        f_clean, f_noisy = numbers(clean, "F1"), numbers(noisy, "F1")
        rms_clean = np.sqrt(np.mean(f_clean ** 2))
        diff = f_noisy - f_clean
        want = rms_clean / 10 ** (30 / 20.0)
        n = len(diff)
        # The sample std of n Gaussian draws is within 5 of its standard errors (sigma / sqrt(2n)) of sigma.
        check(abs(np.std(diff) - want) < 5 * want / np.sqrt(2 * n),
              "--input-snr-db 30: force noise std %.5g, stated %.5g" % (np.std(diff), want))
        check(abs(np.mean(diff)) < 5 * want / np.sqrt(n), "--input-snr-db: the force noise has zero mean")
        lag1 = np.sum(diff[1:] * diff[:-1]) / np.sum(diff ** 2)
        check(abs(lag1) < 5 / np.sqrt(n), "--input-snr-db: the force noise is white (lag-1 correlation %.3g)" % lag1)
        check(column(clean, "d1") == column(noisy, "d1") and column(clean, "d2") == column(noisy, "d2"),
              "--input-snr-db: outputs identical to the record without it (driven by the clean force)")
        with open(os.path.join(tmp, "noisy.truth.json")) as f:
            doc = json.load(f)
        check(doc["noise"]["input_snr_db"] == 30 and close(doc["noise"]["input_sigma"]["F1"], want, 1e-4),
              "--input-snr-db: truth JSON records the level and sigma")
        with open(os.path.join(tmp, "clean.truth.json")) as f:
            check("input_sigma" not in json.load(f)["noise"], "without --input-snr-db: no input noise in the JSON")
        bad = subprocess.run([sys.executable, os.path.join(HERE, "truthgen.py"), "--example", "mdof2", "--case",
                              "nominal", "--kind", "frf", "--input-snr-db", "40", "-o", os.path.join(tmp, "x.csv")],
                             capture_output=True, text=True)
        check(bad.returncode == 1 and "--input-snr-db" in bad.stderr, "--input-snr-db on FRFs is an error")


def check_measurement_chain():
    """Each chain option against the file without it, read back from the CSVs (not through truthlib.chain)."""
    with tempfile.TemporaryDirectory() as tmp:
        frf = "--example mdof2 --case nominal --kind frf --seed 11".split()
        runs = {"base": [], "gain": ["--gain", "d2=0.8"], "reversed": ["--gain", "d1=-1"],
                "sign": ["--force-sign", "-1"], "swap": ["--swap", "d1,d2"], "mm": ["--unit", "d2=mm"],
                "mobility": ["--frf-form", "d2=mobility"],
                "acc_g": ["--frf-form", "d2=accelerance", "--unit", "d2=g"]}
        for name, extra in runs.items():
            run_cli(frf + extra + ["-o", name + ".csv"], tmp)
        t = {name: read_csv(tmp, name) for name in runs}
        base = t["base"]
        f = numbers(base, "f_hz")
        w = 2 * np.pi * f
        same_header = all(t[name][0] == base[0] for name in runs)
        sigma = json.load(open(os.path.join(tmp, "base.truth.json")))["noise"]["sigma"]

        h = complex_column(t["gain"], "d2/F1")
        coh = numbers(t["gain"], "d2/F1.coh")
        own = np.abs(h) ** 2 / (np.abs(h) ** 2 + (0.8 * sigma["d2/F1"]) ** 2)
        doc = json.load(open(os.path.join(tmp, "gain.truth.json")))
        check(same_header and scaled(h, complex_column(base, "d2/F1"), 0.8, 1e-7)
              and column(t["gain"], "d2/F1.coh") == column(base, "d2/F1.coh") and np.max(np.abs(coh - own)) < 1e-6
              and all(column(t["gain"], c) == column(base, c) for c in ("d1/F1.re", "d1/F1.im", "d1/F1.coh"))
              and doc["measurement_chain"] == [{"kind": "gain", "output": "d2", "factor": 0.8,
                                                "id": "measurement_chain:gain:d2"}]
              and doc["hidden_effect"]["expected_operator"] == "measurement_chain:gain:d2"
              and doc["hidden_effect"]["expected_chain"] == ["measurement_chain:gain:d2"]
              and doc["noise"]["sigma"] == sigma,
              "--gain d2=0.8 (FRF): d2's columns = 0.8 x the file without it, its coherence unchanged and equal to "
              "|h|^2/(|h|^2 + (0.8 sigma)^2) (max difference %.1e), d1 untouched; JSON measurement_chain, expected "
              "operator measurement_chain:gain:d2, noise.sigma the truth's" % np.max(np.abs(coh - own)))
        check(all(column(t["reversed"], c) == negated(column(base, c)) for c in ("d1/F1.re", "d1/F1.im"))
              and all(column(t["reversed"], c) == column(base, c) for c in ("d1/F1.coh", "d2/F1.re", "d2/F1.im")),
              "--gain d1=-1 (FRF): d1's values negated digit for digit, its coherence and d2 unchanged")
        check(all(column(t["sign"], "%s/F1.%s" % (o, part)) == negated(column(base, "%s/F1.%s" % (o, part)))
                  for o in ("d1", "d2") for part in ("re", "im"))
              and all(column(t["sign"], "%s/F1.coh" % o) == column(base, "%s/F1.coh" % o) for o in ("d1", "d2")),
              "--force-sign -1 (FRF): every column's values negated, coherence unchanged")
        check(all(column(t["swap"], "d1/F1." + part) == column(base, "d2/F1." + part)
                  and column(t["swap"], "d2/F1." + part) == column(base, "d1/F1." + part)
                  for part in ("re", "im", "coh")),
              "--swap d1,d2 (FRF): the two outputs' columns (values and coherence) exchanged, header kept")
        check(scaled(complex_column(t["mm"], "d2/F1"), complex_column(base, "d2/F1"), 1000.0, 1e-7)
              and scaled(complex_column(t["mobility"], "d2/F1"), complex_column(base, "d2/F1"), 1j * w, 2e-7)
              and scaled(complex_column(t["acc_g"], "d2/F1"), complex_column(base, "d2/F1"), -w ** 2 / 9.80665, 2e-7)
              and all(column(t[n], "d2/F1.coh") == column(base, "d2/F1.coh") for n in ("mm", "mobility", "acc_g")),
              "--unit d2=mm: d2 x 1000; --frf-form d2=mobility: x i w; --frf-form d2=accelerance --unit d2=g: "
              "x -w^2/9.80665; coherence unchanged")

        # frame3 (three inputs): one force transducer's gain divides that input's columns; g on an accelerometer
        grid = "--example frame3 --case nominal --kind frf --seed 5 --f-min 1 --f-max 40 --df 0.5".split()
        run_cli(grid + ["-o", "f0.csv"], tmp)
        run_cli(grid + ["--input-gain", "F2=0.5", "--unit", "a3=g", "-o", "f1.csv"], tmp)
        f0, f1 = read_csv(tmp, "f0"), read_csv(tmp, "f1")
        ok = f0[0] == f1[0]
        for o in (1, 2, 3):
            for i in (1, 2, 3):
                pair = "a%d/F%d" % (o, i)
                factor = (2.0 if i == 2 else 1.0) / (9.80665 if o == 3 else 1.0)
                if factor == 1.0:
                    ok = ok and all(column(f1, pair + p) == column(f0, pair + p) for p in (".re", ".im"))
                else:
                    ok = ok and scaled(complex_column(f1, pair), complex_column(f0, pair), factor, 1e-7)
                ok = ok and column(f1, pair + ".coh") == column(f0, pair + ".coh")
        check(ok, "frame3 --input-gain F2=0.5 --unit a3=g: columns */F2 x 2, a3/* / 9.80665, the rest and every "
                  "coherence unchanged")

        # time records: the written force column negated while the system was driven by the true force
        rec = "--example mdof2 --case compliant_ground --kind time --seed 22 --duration 0.25".split()
        for name, extra in [("t0", []), ("t1", ["--force-sign", "-1"]), ("t2", ["--gain", "d2=-3", "--unit", "d1=mm"]),
                            ("t3", ["--swap", "d1,d2"])]:
            run_cli(rec + extra + ["-o", name + ".csv"], tmp)
        t0, t1, t2, t3 = (read_csv(tmp, n) for n in ("t0", "t1", "t2", "t3"))
        check(t1[0] == t0[0] and column(t1, "F1") == negated(column(t0, "F1"))
              and all(column(t1, c) == column(t0, c) for c in ("t", "d1", "d2")),
              "--force-sign -1 (time): the force column negated, t and the outputs unchanged (the structure was "
              "driven by the true force)")
        check(scaled(numbers(t2, "d2"), numbers(t0, "d2"), -3.0, 1.1e-4)
              and scaled(numbers(t2, "d1"), numbers(t0, "d1"), 1000.0, 1.1e-4)
              and column(t2, "F1") == column(t0, "F1"),
              "--gain d2=-3 --unit d1=mm (time): d2 = -3 x, d1 = 1000 x the record without them, noise included "
              "(same SNR), force unchanged")
        check(column(t3, "d1") == column(t0, "d2") and column(t3, "d2") == column(t0, "d1") and t3[0] == t0[0],
              "--swap d1,d2 (time): the output columns exchanged, header kept")

        # --gain OUTPUT=draw: its own generator; the truth's draw untouched
        drawn = "--example mdof2 --case compliant_ground --kind frf --seed 4 --draw 3".split()
        run_cli(drawn + ["-o", "d0.csv"], tmp)
        run_cli(drawn + ["--gain", "d2=draw", "-o", "d1.csv"], tmp)
        d0, d1 = read_csv(tmp, "d0"), read_csv(tmp, "d1")
        j0 = json.load(open(os.path.join(tmp, "d0.truth.json")))
        j1 = json.load(open(os.path.join(tmp, "d1.truth.json")))
        factor = j1["measurement_chain"][0]["factor"]
        rng = np.random.default_rng([3, zlib.crc32(b"chain/d2")])
        low, high = (0.7, 0.9) if rng.uniform() < 0.5 else (1.1, 1.3)
        independent = float("%.4g" % rng.uniform(low, high))
        sides = {chain_draw_side(n) for n in range(40)}
        check(factor == independent and low <= factor <= high and sides == {"low", "high"}
              and scaled(complex_column(d1, "d2/F1"), complex_column(d0, "d2/F1"), factor, 1e-7)
              and all(column(d1, c) == column(d0, c) for c in ("d1/F1.re", "d1/F1.im"))
              and j1["parameters"] == j0["parameters"] and j1["draw"] == j0["draw"]
              and j1["hidden_effect"]["expected_operator"] == "compliant_ground:wall"
              and j1["hidden_effect"]["expected_chain"] == ["measurement_chain:gain:d2"],
              "--draw 3 --gain d2=draw: factor %g from default_rng([3, crc32(\"chain/d2\")]) (in [%g, %g]; draws "
              "0-39 fall on both sides), d2 = factor x the file without it, the truth's draw unchanged; a structural "
              "case keeps its expected operator and lists the chain in expected_chain" % (factor, low, high))

        for argv, what in [(["--gain", "zz=2"], "--gain of an unknown output"),
                           (["--gain", "d2=abc"], "a malformed factor"),
                           (["--gain", "d2=0"], "a zero factor"),
                           (["--input-gain", "F1=0"], "a zero input factor"),
                           (["--swap", "d1,d1"], "--swap of an output with itself"),
                           (["--unit", "d2=g"], "--unit g on a displacement output"),
                           (["--gain", "d2=draw"], "--gain OUTPUT=draw without --draw"),
                           (["--force-sign", "2"], "--force-sign 2"),
                           (["--kind", "time", "--frf-form", "d2=mobility"], "--frf-form on a time record"),
                           (["--gain", "d2=1.1", "--gain", "d2=0.9"], "two gains on one output")]:
            bad = subprocess.run([sys.executable, os.path.join(HERE, "truthgen.py"), "--example", "mdof2", "--case",
                                  "nominal"] + argv + ["-o", "e.csv"], capture_output=True, text=True, cwd=tmp)
            check(bad.returncode == 1 and bad.stderr.startswith("truthgen: error: ")
                  and not os.path.exists(os.path.join(tmp, "e.csv")), "CLI: %s is an error" % what)


def chain_draw_side(n):
    """Which side of 1 --gain OUTPUT=draw falls on for --draw n (through truthlib.chain)."""
    return "low" if chain.drawn_factor(n, "d2")[0] < 1 else "high"


# ---- 6. effect sizes (slow) ----------------------------------------------------------------------------
def effect_check(c, p, snr_db, label_suffix=""):
    f = generate.frequency_grid(*generate.FRF_GRID[c.example])
    r = effects.nominal_fit(c, p, f, snr_db)
    n = r["points"]
    threshold = max(1000.0, 5 * np.sqrt(2 * n))
    label = "%s/%s%s: excess %.4g over %d points, max |residual| %.1f sigma" % (c.example, c.name, label_suffix,
                                                                               r["excess"], n, r["max_z"])
    if c.control:
        check(r["excess"] < 1e-3, label + " (control: ~0)")
    elif (c.example, c.name) == ("mdof2", "added_mass"):
        absorbed = abs(r["fitted"]["m1"] - (p["m1"] + c.extra["ma_mass1"])) < 1e-4 * p["m1"]
        check(r["excess"] < 1e-3 and absorbed, label + " (absorbed: fitted m1 = %.5f = m1 + ma)" % r["fitted"]["m1"])
    else:
        check(r["excess"] > threshold, label + " (> %.0f)" % threshold)


def check_effects(snr_db=40.0):
    print("effect sizes at %g dB: excess chi-square of the best local nominal fit to noise-free truth" % snr_db)
    for (example, name), c in cases.CASES.items():
        effect_check(c, c.truth_parameters(), snr_db)


# The weak ends of the --draw ranges (in the --draw form): the effect must stay clear across each range.
WEAK_CORNERS = {
    ("mdof2", "compliant_ground"): [{"m_wall": 3.0, "f_wall": 330.0, "zeta_wall": 0.03},
                                    {"m_wall": 8.0, "f_wall": 200.0, "zeta_wall": 0.03}],
    ("mdof2", "free_parameter"): [{"c12": 3.0}],
    ("mdof2", "added_mass"): [{"ma": 0.16}],
    ("mdof2", "resonator"): [{"m": 0.03, "f": 110.0, "zeta": 0.02}, {"m": 0.03, "f": 150.0, "zeta": 0.02}],
    ("mdof2", "outside_maxwell"): [{"c": 55.0, "fc": 100.0}, {"c": 55.0, "fc": 140.0}],
    ("mdof2", "sensor_lowpass"): [{"fc": 700.0}],
    ("mdof2", "sensor_highpass"): [{"fh": 2.0}],
    ("mdof2", "sensor_delay"): [{"tau": 0.2e-3}],
    ("spindle", "compliant_ground"): [{"m_base": 40.0, "f_base": 220.0}, {"m_base": 80.0, "f_base": 160.0}],
    ("spindle", "untie_parameter"): [{"loose": 0.6}],
    ("spindle", "moment_stiffness"): [{"kr": 1.5e5}],
    ("spindle", "added_mass"): [{"ma": 0.3}],
    ("spindle", "resonator"): [{"m": 0.1, "f": 340.0, "zeta": 0.02}, {"m": 0.1, "f": 420.0, "zeta": 0.02}],
    ("spindle", "connection"): [{"k": 5e6, "c": 700.0}],
    ("spindle", "outside_maxwell"): [{"k": 5e6, "fc": 200.0}, {"k": 5e6, "fc": 400.0}],
    ("spindle", "sensor_dynamics"): [{"f": 800.0, "zeta": 0.08}],
    ("spindle", "sensor_lowpass"): [{"fc": 2500.0}],
    ("spindle", "sensor_highpass"): [{"fh": 10.0}],
    ("spindle", "sensor_delay"): [{"tau": 0.05e-3}],
    ("spindle", "base_on_feet"): [{"m_base": 25.0, "f_rock": 260.0}, {"m_base": 60.0, "f_rock": 150.0}],
    ("frame3", "outside_torsion"): [{"e": 0.03, "kt_scale": 1.25}],
}


def check_corners(snr_db=40.0, only=None):
    print("effect sizes at the weak ends of the --draw ranges (%g dB)" % snr_db)
    for (example, name), corners in WEAK_CORNERS.items():
        if only and name not in only:
            continue
        for sizes in corners:
            c = cases.get(example, name).at_sizes(sizes)
            effect_check(c, c.truth_parameters(), snr_db,
                         " at " + ", ".join("%s=%g" % kv for kv in sorted(sizes.items())))


# ---- 7. output-only records ----------------------------------------------------------------------------
def check_oma():
    from truthlib import operational
    with tempfile.TemporaryDirectory() as tmp:
        for example, fs, duration in [("mdof2", 1024.0, 60.0), ("spindle", 4096.0, 8.0)]:
            argv = ["--example", example, "--case", "nominal", "--kind", "oma", "--draw", "2", "--seed", "5",
                    "--fs", str(fs), "--duration", str(duration), "-o", example + ".csv"]
            run_cli_here(argv, tmp)
            table = read_csv(tmp, example)
            case = cases.get(example, "nominal").drawn(2)
            p = case.truth_parameters({})
            system = case.build(p)
            mats = system.matrices()
            outputs = system.output_names()
            check(table[0] == ["t"] + outputs, "oma %s: columns t and the outputs only, no force" % example)
            with open(os.path.join(tmp, example + ".truth.json")) as f:
                doc = json.load(f)
            modes = doc["truth_modes"]
            freqs, zetas = response.damped_modes(mats)
            check(len(modes) == len(freqs) and all(close(m["f_hz"], f, 1e-6) and close(m["zeta"], z, 1e-5)
                                                   for m, f, z in zip(modes, freqs, zetas)),
                  "oma %s: truth modes are the damped modes" % example)
            worst = 1.0
            for m, f, z in zip(modes, freqs, zetas):
                # By hand: the null vector of the dynamic stiffness at the pole (smallest singular vector).
                s = 2 * np.pi * f * (-z + 1j * np.sqrt(1 - z * z))   # unrounded (damped_modes)
                D = response.dynamic_stiffness(mats, [s])[0]
                phi = np.linalg.svd(D)[2][-1].conj()
                want = mats["Cy"] @ phi
                got = np.array([complex(a, b) for a, b in m["shape"]])
                if not np.any(got):   # not seen by the sensors: C phi is rounding noise
                    check(np.linalg.norm(want) < 1e-9 * np.linalg.norm(mats["Cy"], 2) * np.linalg.norm(phi)
                          and m["visibility"] == 0, "oma %s: the %.1f Hz mode, shape 0, is unseen" % (example, f))
                    continue
                mac = abs(np.vdot(want, got)) ** 2 / (np.vdot(want, want).real * np.vdot(got, got).real)
                worst = min(worst, mac)
            check(worst > 1 - 1e-6, "oma %s: shapes at the sensors match the hand-solved eigenvectors (worst MAC "
                                    "%.9f)" % (example, worst))
            # Stationarity: the clean responses' covariance at lags 0 and 1 against the discrete Lyapunov solution.
            rng = np.random.default_rng(5)
            data = operational.make_oma(mats, fs, duration, float("inf"), rng, generate.AMPLITUDE[example])
            A, Bc, Cc = response.state_space(mats)
            Ad, Bd = response.zoh_discretise(A, Bc, 1.0 / fs)
            P = scipy.linalg.solve_discrete_lyapunov(Ad, generate.AMPLITUDE[example] ** 2 * Bd @ Bd.T)
            y = data["clean"]
            for lag, want in [(0, Cc @ P @ Cc.T), (1, Cc @ Ad @ P @ Cc.T)]:
                got = y[lag:].T @ y[:len(y) - lag] / (len(y) - lag)
                err = np.max(np.abs(got - want)) / np.max(np.abs(want))
                # The sample covariance of a record of T seconds scatters by about sqrt(2 / (T zeta w)) of the
                # slowest mode (its correlation time): 10 % for mdof2's 60 s, 14 % for the spindle's 8 s.
                check(err < 0.25, "oma %s: covariance at lag %d within %.1f %% of the Lyapunov solution"
                      % (example, lag, 100 * err))
            sigma = np.array([doc["noise"]["sigma"][o] for o in outputs])
            written = np.array([numbers(table, o) for o in outputs]).T
            check(np.allclose(sigma, np.sqrt(np.mean(y ** 2, axis=0)) / 100, rtol=1e-9),
                  "oma %s: noise sigma = RMS / 10^(40/20)" % example)
            resid = written - y
            check(np.all(np.abs(np.std(resid, axis=0) / sigma - 1) < 0.05),
                  "oma %s: written responses = clean + noise of that sigma" % example)
        again = os.path.join(tmp, "again")
        os.mkdir(again)
        argv = ["--example", "mdof2", "--case", "nominal", "--kind", "oma", "--draw", "2", "--seed", "5", "--fs",
                "1024", "--duration", "60", "-o", "mdof2.csv"]
        run_cli(argv, again)
        run_cli(argv, tmp)
        check(file_digest(tmp, "mdof2") == file_digest(again, "mdof2"), "oma: same seed, same bytes")


def check_oma_series():
    """--series: each file's `# condition temperature=` line, the stiffnesses and the truth's frequencies following
    it by k(T) = k0 (1 - a (T - mean)), and the change from its set on."""
    with tempfile.TemporaryDirectory() as tmp:
        argv = ["--example", "mdof2", "--case", "nominal", "--kind", "oma", "--draw", "1", "--seed", "4",
                "--duration", "2", "--series", "8", "--temperature", "20,5,6,0.5,0.3",
                "--temperature-coefficient", "0.004", "--change", "k11=0.9@5", "-o", "s.csv"]
        run_cli_here(argv, tmp)
        with open(os.path.join(tmp, "s.series.json")) as f:
            summary = json.load(f)
        base = cases.get("mdof2", "nominal").drawn(1).truth_parameters({})
        mats0 = cases.get("mdof2", "nominal").drawn(1).build(base).matrices()
        f0 = np.sqrt(np.sort(np.linalg.eigvals(np.linalg.solve(mats0["M"], mats0["K"])).real)) / (2 * np.pi)
        lines_ok, params_ok, freqs_ok, temps = True, True, True, []
        for i in range(8):
            with open(os.path.join(tmp, "s_%02d.csv" % i)) as f:
                head = [f.readline().rstrip("\n") for _ in range(3)]
            match = re.match(r"^# condition temperature=(-?\d+\.\d\d)$", head[1])
            lines_ok = lines_ok and match is not None and head[2] == "t,d1,d2"
            if not match:
                continue
            t = float(match.group(1))
            temps.append(t)
            with open(os.path.join(tmp, "s_%02d.truth.json" % i)) as f:
                doc = json.load(f)
            factor = 1 - 0.004 * (t - 20)
            want = dict(base)
            for name in ("k11", "k12", "k22"):
                want[name] = base[name] * factor
            if i >= 5:
                want["k11"] *= 0.9
            params_ok = params_ok and all(close(doc["parameters"][k], v, 1e-12) for k, v in want.items())
            # Undamped frequencies by hand (K/M eigenvalues): before the change all scale by sqrt(factor).
            mats = cases.get("mdof2", "nominal").drawn(1).build(want).matrices()
            f = np.sqrt(np.sort(np.linalg.eigvals(np.linalg.solve(mats["M"], mats["K"])).real)) / (2 * np.pi)
            got = np.array([m["f_hz"] for m in doc["truth_modes"]])
            freqs_ok = freqs_ok and np.all(np.abs(got / f - 1) < 1e-4)
            if i < 5:
                freqs_ok = freqs_ok and np.all(np.abs(f / f0 - np.sqrt(factor)) < 1e-12)
            freqs_ok = freqs_ok and summary["sets"][i]["temperature"] == t and summary["sets"][i]["changed"] == (i >= 5)
        check(lines_ok, "series: every file has its `# condition temperature=` line before the header")
        check(params_ok, "series: the stiffnesses follow k0 (1 - a (T - mean)), k11 0.9 times from set 5 on")
        check(freqs_ok, "series: the truth's frequencies follow the temperature (undamped ones by sqrt(factor))")
        spread = max(temps) - min(temps) if temps else 0
        check(spread > 5, "series: the temperature moves over the series (range %.2f)" % spread)


def main():
    args = sys.argv[1:]
    only = [a.split("=", 1)[1] for a in args if a.startswith("--only=")]
    if only:   # --only=CASE[,CASE]: just the effect sizes of those cases (to look at one case)
        names = only[0].split(",")
        for (example, name), c in cases.CASES.items():
            if name in names:
                effect_check(c, c.truth_parameters(), 40.0)
        if "--corners" in args:
            check_corners(only=names)
    else:
        check_existing_outputs()
        check_reference()
        check_structure()
        check_cases()
        check_sensor_filters()
        check_base_on_feet()
        check_frame3()
        check_tower5()
        check_draws()
        check_pairs()
        check_time_vs_frf()
        check_delay_from_rest()
        check_sensor_records()
        check_noise_and_files()
        check_averages_and_options()
        check_measurement_chain()
        check_input_noise()
        check_oma()
        check_oma_series()
        if "--effects" in args:
            check_effects()
        if "--corners" in args:
            check_corners()
    print("%d failed" % len(FAILURES) if FAILURES else "all truthgen self-checks passed")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
