"""Measured-style data sets: FRFs with complex Gaussian noise, and zero-order-hold time records with output noise.

Noise definitions (docs/truthgen.md):
- FRF: per channel OUT/IN, sigma = RMS over the grid of |H| divided by 10^(SNR/20); the noise is complex
  Gaussian with E|n|^2 = sigma^2 (real and imaginary parts each of variance sigma^2/2), independent per
  frequency and channel. Coherence column: |h|^2/(|h|^2 + sigma^2) with the noisy h, as an analyser's: its
  coherence of an H1 estimate h is |h|^2/(|h|^2 + s^2), s^2 the output power the input does not explain (per
  unit input power) of the same averages, so (1 - coh)/coh |h|^2 = s^2, here sigma^2 exactly. (From the
  noise-free H instead, as until 2026-11-26, the fit's weights (1 - coh)/coh |h|^2 = sigma^2 |h|^2/|H|^2
  followed the noise and biased its estimates: bench/README.md.)
  An FRF averaged over N measurements (--averages N) has noise of variance sigma^2/N, and the coherence column
  is |h|^2/(|h|^2 + sigma^2) with that average h and the sigma of one measurement: averaging does not improve
  the coherence, it shrinks the estimate's variance (1 - coh)/(N coh) |h|^2 = sigma^2/N.
  An analyser's FRF (--analyser N, make_analyser_frf) is the H1 estimate of N segments instead, each input driven
  alone with complex Gaussian spectra of unit power per line and every output with noise of the one measurement's
  sigma: h = sum(Y conj X) / sum|X|^2 and coherence |sum(Y conj X)|^2 / (sum|X|^2 sum|Y|^2), both from the same
  N segments. Its coherence scatters as a real one does: (1 - coh)/(N coh) |h|^2 is an estimate of h's variance
  with 2 (N - 1) degrees of freedom, where the two constructions above give it exactly.
- Time: per output, sigma = RMS of the noise-free output record divided by 10^(SNR/20), white Gaussian,
  independent per sample and channel. Inputs are exact (a measured force taken as clean).
"""
import numpy as np

from . import response

FRF_GRID = {"mdof2": (10.0, 400.0, 0.25), "spindle": (50.0, 1200.0, 1.0), "frame3": (0.03125, 128.0, 0.03125),
            "tower5": (0.1, 6.0, 0.01)}
SAMPLE_RATE = {"mdof2": 4096.0, "spindle": 8192.0}
DURATION = {"mdof2": 2.0, "spindle": 2.0}
AMPLITUDE = {"mdof2": 10.0, "spindle": 100.0}


def frequency_grid(f_min, f_max, df):
    count = int(round((f_max - f_min) / df)) + 1
    return f_min + df * np.arange(count)


def noise_sigma(rms, snr_db):
    return rms / 10 ** (snr_db / 20.0)


def channel_sigmas(H, snr_db):
    """One measurement's noise sigma of every output/input pair of H (F x O x I): RMS |H| over the grid / SNR."""
    _, O, I = H.shape
    sigma = np.zeros((O, I))
    for o in range(O):
        for i in range(I):
            # |H| of a contiguous copy: numpy's abs of the strided column took its vectorised or its scalar
            # (hypot) route, whose last bits differ, by the alignment of the arrays, i.e. by what the process had
            # allocated before; the contiguous copy always takes the vectorised one (the sigma's written digits)
            magnitude = np.abs(np.ascontiguousarray(H[:, o, i]))
            sigma[o, i] = noise_sigma(np.sqrt(np.mean(magnitude ** 2)), snr_db)
    return sigma


def make_frf(mats, f_hz, snr_db, rng, averages=1):
    """Noisy FRF of every output/input pair, the average of `averages` measurements. Returns dict with f, clean
    H, noisy H, coherence, sigma (O x I; the noise of one measurement: the average's is sigma/sqrt(averages))."""
    H = response.frf(mats, f_hz)
    F, O, I = H.shape
    sigma = channel_sigmas(H, snr_db)
    noisy = H.copy()
    coh = np.ones(H.shape)
    for o in range(O):
        for i in range(I):
            if np.isfinite(snr_db):
                n = rng.standard_normal(F) + 1j * rng.standard_normal(F)
                scale = sigma[o, i] if averages == 1 else sigma[o, i] / np.sqrt(averages)
                noisy[:, o, i] += scale / np.sqrt(2) * n
                coh[:, o, i] = np.abs(noisy[:, o, i]) ** 2 / (np.abs(noisy[:, o, i]) ** 2 + sigma[o, i] ** 2)
    return {"f_hz": np.asarray(f_hz, float), "clean": H, "noisy": noisy, "coherence": coh, "sigma": sigma,
            "averages": averages}


def make_analyser_frf(mats, f_hz, snr_db, rng, segments):
    """An analyser's H1 estimate of every output/input pair from `segments` averages, with its own coherence
    (module docstring). Returns make_frf's dict; sigma is one segment's noise, the estimate's about
    sigma/sqrt(segments)."""
    H = response.frf(mats, f_hz)
    F, O, I = H.shape
    sigma = channel_sigmas(H, snr_db)
    noisy = H.copy()
    coh = np.ones(H.shape)
    for i in range(I):
        # one test per input: its force spectra are shared by every output measured in that test
        X = (rng.standard_normal((segments, F)) + 1j * rng.standard_normal((segments, F))) / np.sqrt(2)
        power_x = np.sum(np.abs(X) ** 2, axis=0)
        for o in range(O):
            n = (rng.standard_normal((segments, F)) + 1j * rng.standard_normal((segments, F))) / np.sqrt(2)
            Y = H[:, o, i] * X + sigma[o, i] * n
            cross = np.sum(Y * np.conj(X), axis=0)
            noisy[:, o, i] = cross / power_x
            coh[:, o, i] = np.abs(cross) ** 2 / (power_x * np.sum(np.abs(Y) ** 2, axis=0))
    return {"f_hz": np.asarray(f_hz, float), "clean": H, "noisy": noisy, "coherence": coh, "sigma": sigma,
            "averages": segments, "analyser": True}


def excitation(kind, count, inputs, amplitude, rng):
    """White zero-order-hold force: `binary` (+-amplitude, random signs) or `gaussian` (RMS amplitude)."""
    if kind == "binary":
        return amplitude * np.where(rng.uniform(size=(count, inputs)) < 0.5, -1.0, 1.0)
    if kind == "gaussian":
        return amplitude * rng.standard_normal((count, inputs))
    raise ValueError("unknown excitation %r (binary, gaussian)" % kind)


def add_input_noise(data, snr_db, seed):
    """The written force with white measurement noise at `snr_db` per input (sigma = RMS of the clean force /
    10^(snr/20)), drawn from its own stream (seed, 0x5eed) so that the output noise and the excitation are those of
    the same record without it. The structure stays driven by the clean force (data["u_clean"])."""
    rng = np.random.default_rng([seed, 0x5eed])
    u = data["u"]
    sigma = np.array([noise_sigma(np.sqrt(np.mean(u[:, i] ** 2)), snr_db) for i in range(u.shape[1])])
    data["u_clean"] = u
    data["u"] = u + rng.standard_normal(u.shape) * sigma
    data["input_sigma"] = sigma


def make_time(mats, fs, duration, snr_db, rng, amplitude, kind="binary"):
    """Time record from rest at t = 0: inputs held over each sample interval, outputs sampled at t_k.

    Returns dict with t, u (N x inputs), clean y, noisy y (N x outputs), sigma per output.
    """
    count = int(round(duration * fs))
    dt = 1.0 / fs
    u = excitation(kind, count, mats["B"].shape[1], amplitude, rng)
    y, _ = response.simulate_zoh(mats, u, dt)
    sigma = np.array([noise_sigma(np.sqrt(np.mean(y[:, o] ** 2)), snr_db) for o in range(y.shape[1])])
    noisy = y.copy()
    if np.isfinite(snr_db):
        noisy += rng.standard_normal(y.shape) * sigma
    return {"t": np.arange(count) * dt, "u": u, "clean": y, "noisy": noisy, "sigma": sigma, "dt": dt}
