#!/usr/bin/env python3
"""Self-checks of truthgen (exit 1 on any failure).

    python3 scripts/truthgen/selftest.py            # fast checks (~20 s)
    python3 scripts/truthgen/selftest.py --effects  # also the effect size of every case (a few minutes)

1. The assembled reference models against REFERENCE-MODELS.md: spindle inertias and undamped natural
   frequencies (0.1 %), mdof2 modes and damping ratios, mdof2 G11/G21 against the printed closed form.
2. Structure: M, K, C symmetric, G skew, the spindle's two uncoupled blocks, spin couples them.
3. Cases: the spindle's compliant base has its x mode at 190 Hz; resonators add a mode near their frequency.
4. Time simulation against direct solve: a periodic multisine in steady state, simulated with the exact
   zero-order hold, has the FRF sum_n G(i(w + n ws)) H0(i(w + n ws))/T, computed from the direct continuous
   solve (no matrix exponential): agreement to 1e-6 for every case. Then Welch H1 of a long noisy record
   agrees with it within the predicted random error.
5. Noise: FRF noise has the defined sigma; coherence as defined; same seed, same data; the CLI writes files
   in the documented formats.
"""
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from truthlib.bootstrap import ensure_numpy  # noqa: E402

ensure_numpy()

import numpy as np  # noqa: E402
import scipy.signal  # noqa: E402

from truthlib import cases, effects, generate, models, response  # noqa: E402

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
    # Closed form of REFERENCE-MODELS.md, with a damped helix so that every coefficient matters.
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
    import scipy.linalg
    c = cases.get("spindle", "compliant_ground")
    s = c.build(c.truth_parameters())
    m = s.matrices()
    w2, V = scipy.linalg.eigh(m["K"], m["M"])
    base = [s.index("base", d) for d in "xyz"]
    x_modes = [np.sqrt(w) / (2 * np.pi) for w, v in zip(w2, V.T)
               if abs(v[base[0]]) > 0.9 * np.linalg.norm(v[base])]
    check(abs(x_modes[0] - 190.0) < 1.0, "spindle compliant base: lowest base-x mode at %.1f Hz" % x_modes[0])
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
    A, Bc, Cc = response.state_space(mats)
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
        y, x_after = response.run_discrete(Ad, Bd, Cc, u, x0)
        assert np.allclose(x_after, x0, rtol=1e-6, atol=1e-6 * np.abs(x0).max())
        U = np.fft.rfft(u[:, i])[lines]
        Y = np.fft.rfft(y, axis=0)[lines]
        result[:, :, i] = Y / U[:, None]
    return result


def check_time_vs_frf():
    rng = np.random.default_rng(7)
    for (example, name), c in cases.CASES.items():
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
    check(np.allclose(a["coherence"], np.abs(a["clean"]) ** 2 / (np.abs(a["clean"]) ** 2 + a["sigma"] ** 2)),
          "coherence = |H|^2/(|H|^2 + sigma^2)")

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


# ---- 6. effect sizes (slow) ----------------------------------------------------------------------------
def check_effects(snr_db=40.0):
    print("effect sizes at %g dB: excess chi-square of the best local nominal fit to noise-free truth" % snr_db)
    for (example, name), c in cases.CASES.items():
        p = c.truth_parameters()
        f = generate.frequency_grid(*generate.FRF_GRID[example])
        r = effects.nominal_fit(c, p, f, snr_db)
        n = r["points"]
        threshold = max(1000.0, 5 * np.sqrt(2 * n))
        label = "%s/%s: excess %.4g over %d points, max |residual| %.1f sigma" % (example, name, r["excess"], n,
                                                                                 r["max_z"])
        if c.operator is None and c.effect_hz is None:
            check(r["excess"] < 1e-3, label + " (control: ~0)")
        elif (example, name) == ("mdof2", "added_mass"):
            absorbed = abs(r["fitted"]["m1"] - (p["m1"] + c.extra["ma_mass1"])) < 1e-4 * p["m1"]
            check(r["excess"] < 1e-3 and absorbed, label + " (absorbed: fitted m1 = %.5f = m1 + ma)"
                  % r["fitted"]["m1"])
        else:
            check(r["excess"] > threshold, label + " (> %.0f)" % threshold)


def main():
    check_reference()
    check_structure()
    check_cases()
    check_time_vs_frf()
    check_noise_and_files()
    if "--effects" in sys.argv[1:]:
        check_effects()
    print("%d failed" % len(FAILURES) if FAILURES else "all truthgen self-checks passed")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
