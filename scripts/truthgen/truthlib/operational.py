"""Output-only (operational) records: the structure driven by unmeasured white Gaussian forces, only the responses
written, and the truth's modes with their shapes at the sensors (docs/truthgen.md, "Output-only records").

The forces are independent, white (zero-order hold over each sample), Gaussian with RMS `amplitude`, at every
input of the model. The record starts after a burn-in from rest long enough for the slowest mode's transient to
decay below 1e-6 of its stationary level, so it is a stationary random response as an operational measurement is.
Output noise as for time records: white Gaussian, sigma = RMS(noise-free output) / 10^(snr/20) per output.
"""
import math

import numpy as np

from . import generate, response

# Defaults: long records at a sample rate a few times the highest mode (the identification needs many periods of the
# lightest-damped mode; mdof2's first mode has zeta 0.00055, a decay time of 3 s).
SAMPLE_RATE = {"mdof2": 1024.0, "spindle": 4096.0}
DURATION = {"mdof2": 300.0, "spindle": 60.0}
DECAY = math.log(1e6)   # burn-in: exp(-zeta w t) below 1e-6


def burn_in_samples(mats, fs):
    A, _, _ = response.state_space(mats)
    s = np.linalg.eigvals(A)
    slowest = min(-s.real)
    return int(math.ceil(DECAY / slowest * fs))


def make_oma(mats, fs, duration, snr_db, rng, amplitude):
    """Stationary responses to unmeasured white forces. Returns dict with t, clean and noisy y, sigma, dt and the
    burn-in that was simulated and dropped."""
    count = int(round(duration * fs))
    dt = 1.0 / fs
    burn = burn_in_samples(mats, fs)
    u = generate.excitation("gaussian", burn + count, mats["B"].shape[1], amplitude, rng)
    y, _ = response.simulate_zoh(mats, u, dt)
    y = y[burn:]
    sigma = np.array([generate.noise_sigma(np.sqrt(np.mean(y[:, o] ** 2)), snr_db) for o in range(y.shape[1])])
    noisy = y.copy()
    if np.isfinite(snr_db):
        noisy += rng.standard_normal(y.shape) * sigma
    return {"t": np.arange(count) * dt, "clean": y, "noisy": noisy, "sigma": sigma, "dt": dt, "burn_in": burn}


def sensor_modes(mats):
    """The truth's modes (one per pole pair with positive imaginary part, by frequency) seen at the sensors:
    frequency, damping ratio, the shape C v (unit norm, its largest component real and positive), and its
    visibility: the peak of the mode's term in the output spectrum, |C v| |w^T B| / |Re lambda| (v, w right and left
    eigenvectors, w^T v = 1), relative to the largest mode's. A mode the forces do not excite or the sensors do not
    see has visibility near 0 and cannot be identified from the responses; one the sensors do not see at all
    (|C v| below 1e-9 |C| |v|: the spindle's y-plane modes at x sensors) has shape 0 and visibility 0, since the
    direction of rounding noise is no shape."""
    A, Bc, Cc = response.state_space(mats)
    s, V = np.linalg.eig(A)
    W = np.linalg.inv(V)   # rows: left eigenvectors with w^T v = 1
    keep = [k for k in range(len(s)) if s[k].imag > 1e-9]
    keep.sort(key=lambda k: abs(s[k]))
    modes = []
    for k in keep:
        shape = Cc @ V[:, k]
        norm = np.linalg.norm(shape)
        if norm <= 1e-9 * np.linalg.norm(Cc, 2) * np.linalg.norm(V[:, k]):
            shape, norm = np.zeros_like(shape), 0.0
        peak = norm * np.linalg.norm(W[k] @ Bc) / abs(s[k].real) if norm > 0 else 0.0
        if norm > 0:
            big = shape[np.argmax(np.abs(shape))]
            shape = shape / norm * (abs(big) / big)
        modes.append({"f_hz": abs(s[k]) / (2 * np.pi), "zeta": -s[k].real / abs(s[k]), "shape": shape,
                      "peak": peak})
    top = max(m["peak"] for m in modes)
    for m in modes:
        m["visibility"] = m.pop("peak") / top
    return modes
