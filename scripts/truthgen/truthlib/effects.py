"""How large is each hidden effect, measured in noise standard deviations?

The nominal model (estimable parameters free, as in the .mdl files) is fitted by least squares to the
NOISE-FREE truth FRF on the case's grid, each channel weighted by 1/sigma of the noise that truthgen adds at
the given SNR. What the best nominal fit leaves, `excess = sum |residual/sigma|^2`, is the chi-square that the
hidden effect adds to a fit of noisy data (whose own chi-square is about 2 x points, with spread ~2 sqrt(points)).
An effect is clearly detectable when the excess is far above that spread and above a BIC penalty of a few
parameters x ln(points); the control cases must come out ~0.

The fit starts at the truth's estimable values (plus the effect absorbed as far as possible), so it finds the
nearest local optimum: the excess is the effect size seen by a local fitter, not a proof about global fits.
"""
import numpy as np
import scipy.optimize

from . import generate, models, response


def nominal_fit(case, p_truth, f_hz, snr_db, channels=None):
    """Fit the nominal model to the case's noise-free FRF. Returns dict(excess, points, max_z, fitted)."""
    example = models.EXAMPLES[case.example]
    truth = case.build(p_truth).matrices()
    H_truth = response.frf(truth, f_hz)
    sigma = np.array([[generate.noise_sigma(np.sqrt(np.mean(np.abs(H_truth[:, o, i]) ** 2)), snr_db)
                       for i in range(H_truth.shape[2])] for o in range(H_truth.shape[1])])
    names = [n for n in example["estimable"] if p_truth[n] > 0]
    nominal_p = dict(p_truth)
    nominal_p.update({n: example["nominal"][n] for n in case.hidden_values})  # what the nominal model assumes
    x0 = np.log([p_truth[n] for n in names])

    def residual(x):
        p = dict(nominal_p)
        p.update({n: float(np.exp(v)) for n, v in zip(names, x)})
        H = response.frf(example["build"](p, None).matrices(), f_hz)
        z = (H - H_truth) / sigma[None, :, :]
        return np.concatenate([z.real.ravel(), z.imag.ravel()])

    start_excess = float(np.sum(residual(x0) ** 2))
    # Within a factor 100 of the start: parameters the data cannot see (y-plane ones in x data) stay bounded.
    result = scipy.optimize.least_squares(residual, x0, bounds=(x0 - np.log(100), x0 + np.log(100)),
                                          method="trf", x_scale=1.0, max_nfev=400)
    r = residual(result.x)
    fitted = {n: float(np.exp(v)) for n, v in zip(names, result.x)}
    return {"excess": float(np.sum(r ** 2)), "points": int(r.size), "max_z": float(np.max(np.abs(r))),
            "start_excess": start_excess, "fitted": fitted}
