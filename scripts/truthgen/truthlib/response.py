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
    """H[f, output, input] = Cy D(i w)^-1 B (displacement per force), each output row times (i w)^order for
    velocity or acceleration outputs and times its sensor's T(i w) (output_filter_response)."""
    w = 2 * np.pi * np.asarray(f_hz, dtype=float)
    D = dynamic_stiffness(mats, 1j * w)
    X = np.linalg.solve(D, np.broadcast_to(mats["B"].astype(complex), (len(w),) + mats["B"].shape))
    H = np.einsum("on,fni->foi", mats["Cy"], X)
    for o, order in enumerate(mats.get("output_orders", [])):
        if order:
            H[:, o, :] *= ((1j * w) ** order)[:, None]
    for o, kind, value in mats.get("output_filters", []):
        H[:, o, :] *= output_filter_response(kind, value, 1j * w)[:, None]
    return H


def output_filter_response(kind, value, s):
    """T(s) of a sensor's own dynamics (assembly.System.output_filter): Butterworth low-pass, AC coupling, delay."""
    s = np.asarray(s, dtype=complex)
    if kind == "lowpass":
        wc = 2 * np.pi * value
        return wc ** 2 / (s ** 2 + np.sqrt(2) * wc * s + wc ** 2)
    if kind == "highpass":
        return s / (s + 2 * np.pi * value)
    if kind == "delay":
        return np.exp(-s * value)
    raise ValueError("unknown output filter %r" % kind)


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


def simulation_model(mats):
    """State space of the structure with its sensors: A, Bc, Cc as state_space, plus the states of the output
    filters (a low-pass adds two, AC coupling one, both driven by the output they filter, so the zero-order-hold
    discretisation stays exact), and the delays [(output index, tau)], which are applied to the sampled states
    (delayed_output). Acceleration and velocity outputs are refused: their feedthrough at the sample instants
    would need a convention the data format does not fix.
    """
    if any(mats.get("output_orders", [])):
        raise ValueError("time simulation of velocity or acceleration outputs is not supported (FRF only)")
    A, Bc, Cc = state_space(mats)
    delays = []
    for o, kind, value in mats.get("output_filters", []):
        if kind == "delay":
            delays.append((o, value))
            continue
        extra = 2 if kind == "lowpass" else 1
        ns = A.shape[0]
        A2 = np.zeros((ns + extra, ns + extra))
        A2[:ns, :ns] = A
        Bc = np.vstack([Bc, np.zeros((extra, Bc.shape[1]))])
        Cc = np.hstack([Cc, np.zeros((Cc.shape[0], extra))])
        y_row = Cc[o].copy()                     # what the filter is driven by (the output so far)
        if kind == "lowpass":                    # v'' = wc^2 (y - v) - sqrt(2) wc v', reads v
            wc = 2 * np.pi * value
            A2[ns, ns + 1] = 1.0
            A2[ns + 1, :] += wc ** 2 * y_row
            A2[ns + 1, ns] -= wc ** 2
            A2[ns + 1, ns + 1] = -np.sqrt(2) * wc
            Cc[o] = 0.0
            Cc[o, ns] = 1.0
        else:                                    # w' = wh (y - w), reads y - w: T = 1 - wh/(s + wh) = s/(s + wh)
            wh = 2 * np.pi * value
            A2[ns, :] += wh * y_row
            A2[ns, ns] -= wh
            Cc[o, ns] -= 1.0
        A = A2
    return A, Bc, Cc, delays


def simulate_zoh(mats, u, dt, x0=None):
    """Outputs y[k] (k = 0..N-1) of the model driven by inputs u[k] (N x inputs) held over [k dt, (k+1) dt).

    y[k] is sampled at t = k dt, before u[k] acts (a displacement output has no direct feedthrough).
    Returns (y, final state). With output filters the state includes the filters' states; a delayed output
    reads the state before the record started as at rest, so x0 must be None then.
    """
    if not mats.get("output_filters"):
        A, Bc, Cc = state_space(mats)
        Ad, Bd = zoh_discretise(A, Bc, dt)
        return run_discrete(Ad, Bd, Cc, u, x0)
    A, Bc, Cc, delays = simulation_model(mats)
    if delays and x0 is not None:
        raise ValueError("a delayed output needs the record to start at rest")
    Ad, Bd = zoh_discretise(A, Bc, dt)
    u = np.atleast_2d(np.asarray(u, dtype=float))
    states, x = run_states(Ad, Bd, u, x0)
    y = states @ Cc.T
    for o, tau in delays:
        y[:, o] = delayed_output(A, Bc, Cc[o], states, u, tau, dt)
    return y, x


def run_states(Ad, Bd, u, x0=None):
    """States x[k] at t = k dt (x[0] = x0, at rest by default) and the state after the last step."""
    u = np.atleast_2d(np.asarray(u, dtype=float))
    x = np.zeros(Ad.shape[0]) if x0 is None else np.array(x0, dtype=float)
    states = np.empty((u.shape[0], Ad.shape[0]))
    drive = u @ Bd.T
    for k in range(u.shape[0]):
        states[k] = x
        x = Ad @ x + drive[k]
    return states, x


def run_discrete(Ad, Bd, Cc, u, x0=None):
    states, x = run_states(Ad, Bd, u, x0)
    return states @ Cc.T, x


def split_delay(tau, dt):
    """tau = m dt + delta with 0 <= delta < dt (rounding kept inside the interval)."""
    m = int(np.floor(tau / dt))
    delta = tau - m * dt
    if delta < 0:
        m, delta = m - 1, delta + dt
    if delta >= dt:
        m, delta = m + 1, delta - dt
    return m, max(delta, 0.0)


def delayed_output(A, Bc, c_row, states, u, tau, dt, periodic=False):
    """y_d[k] = c_row x(t_k - tau), exactly. With tau = m dt + delta and j = k - m, x(t_j - delta) =
    expm(A (dt - delta)) x[j-1] + Gamma(dt - delta) u[j-1], since the input is held over [t_{j-1}, t_j).
    Before the record the system is at rest (zero), or with periodic=True the record repeats (steady state).
    """
    m, delta = split_delay(tau, dt)
    Ap, Bp = zoh_discretise(A, Bc, dt - delta)
    count = states.shape[0]
    prev = np.arange(count) - m - 1
    if periodic:
        prev = prev % count
    valid = prev >= 0
    x_between = states[prev[valid]] @ Ap.T + np.atleast_2d(u)[prev[valid]] @ Bp.T
    y = np.zeros(count)
    y[valid] = x_between @ c_row
    return y


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
