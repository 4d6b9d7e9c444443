"""Responses of an assembled model: FRFs by direct solve, and exact zero-order-hold simulation."""
import numpy as np
import scipy.linalg


def dynamic_stiffness(mats, s):
    """D(s) = M s^2 + (C + G) s + K + sum h h^T k c s/(k + c s), for an array of complex s: shape (F, n, n)."""
    s = np.asarray(s, dtype=complex)[:, None, None]
    D = mats["M"] * s ** 2 + (mats["C"] + mats["G"]) * s + mats["K"]
    for h, k, c in mats["maxwell"]:
        D = D + np.outer(h, h) * (k * c * s / (k + c * s))
    return D


def frf(mats, f_hz):
    """H[f, output, input] = Cy D(i w)^-1 B (displacement per force)."""
    w = 2 * np.pi * np.asarray(f_hz, dtype=float)
    D = dynamic_stiffness(mats, 1j * w)
    X = np.linalg.solve(D, np.broadcast_to(mats["B"].astype(complex), (len(w),) + mats["B"].shape))
    return np.einsum("on,fni->foi", mats["Cy"], X)


def state_space(mats):
    """Continuous state space x' = A x + Bc u, y = Cc x with x = [q, q', z] (z: Maxwell internal states)."""
    M, K, CG, B, Cy = mats["M"], mats["K"], mats["C"] + mats["G"], mats["B"], mats["Cy"]
    n, nm, ni = M.shape[0], len(mats["maxwell"]), B.shape[1]
    Minv = np.linalg.inv(M)
    A = np.zeros((2 * n + nm, 2 * n + nm))
    A[:n, n:2 * n] = np.eye(n)
    Kt = K.copy()
    for j, (h, k, c) in enumerate(mats["maxwell"]):
        Kt += k * np.outer(h, h)
        A[n:2 * n, 2 * n + j] = Minv @ (h * k)      # force k (h q - z) pushes back on q
        A[2 * n + j, :n] = (k / c) * h               # c z' = k (h q - z)
        A[2 * n + j, 2 * n + j] = -k / c
    A[n:2 * n, :n] = -Minv @ Kt
    A[n:2 * n, n:2 * n] = -Minv @ CG
    Bc = np.zeros((2 * n + nm, ni))
    Bc[n:2 * n, :] = Minv @ B
    Cc = np.zeros((Cy.shape[0], 2 * n + nm))
    Cc[:, :n] = Cy
    return A, Bc, Cc


def zoh_discretise(A, Bc, dt):
    """Exact zero-order-hold discretisation: expm([[A, B], [0, 0]] dt) = [[Ad, Bd], [0, I]]."""
    ns, ni = Bc.shape
    aug = np.zeros((ns + ni, ns + ni))
    aug[:ns, :ns] = A
    aug[:ns, ns:] = Bc
    E = scipy.linalg.expm(aug * dt)
    return E[:ns, :ns], E[:ns, ns:]


def simulate_zoh(mats, u, dt, x0=None):
    """Outputs y[k] (k = 0..N-1) of the model driven by inputs u[k] (N x inputs) held over [k dt, (k+1) dt).

    y[k] is sampled at t = k dt, before u[k] acts (a displacement output has no direct feedthrough).
    Returns (y, final state).
    """
    A, Bc, Cc = state_space(mats)
    Ad, Bd = zoh_discretise(A, Bc, dt)
    return run_discrete(Ad, Bd, Cc, u, x0)


def run_discrete(Ad, Bd, Cc, u, x0=None):
    u = np.atleast_2d(np.asarray(u, dtype=float))
    x = np.zeros(Ad.shape[0]) if x0 is None else np.array(x0, dtype=float)
    states = np.empty((u.shape[0], Ad.shape[0]))
    drive = u @ Bd.T
    for k in range(u.shape[0]):
        states[k] = x
        x = Ad @ x + drive[k]
    return states @ Cc.T, x


def discrete_frf(Ad, Bd, Cc, f_hz, dt):
    """Frequency response of the sampled system: Cc (e^{i w dt} I - Ad)^-1 Bd, shape (F, outputs, inputs)."""
    z = np.exp(1j * 2 * np.pi * np.asarray(f_hz, dtype=float) * dt)
    eye = np.eye(Ad.shape[0])
    X = np.linalg.solve(z[:, None, None] * eye - Ad, np.broadcast_to(Bd.astype(complex), (len(z),) + Bd.shape))
    return np.einsum("os,fsi->foi", Cc, X)


def undamped_natural_frequencies(mats):
    """Natural frequencies (Hz) of K x = w^2 M x, ascending."""
    w2 = scipy.linalg.eigh(mats["K"], mats["M"], eigvals_only=True)
    return np.sqrt(np.clip(w2, 0, None)) / (2 * np.pi)


def damped_modes(mats):
    """Poles of the full model in the upper half plane: (frequency |s|/(2 pi) Hz, damping ratio), ascending."""
    A, _, _ = state_space(mats)
    s = np.linalg.eigvals(A)
    s = s[s.imag > 1e-9]
    wn = np.abs(s)
    order = np.argsort(wn)
    return wn[order] / (2 * np.pi), -s.real[order] / wn[order]
