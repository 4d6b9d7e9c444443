#!/usr/bin/env python3
"""Independent SymPy derivation of the spindle model (examples/spindle/spindle.mdl), for bench/derive_spindle.

Lagrange's method with the same kinematics as mbgen (centre-of-mass translations, rotations Rx Ry Rz with full
sin/cos) but written directly in SymPy: T, V and D are built as expressions and differentiated as a whole
(M = hessian(T, qd), K = hessian(V, q), C = hessian(D, qd), all at q = 0), then the transfer functions of the
x/ry/rz block at the nominal values, exactly (rational arithmetic). The model data are copied from
examples/spindle/spindle.mdl (keep them in step).

Prints one JSON line: {"median_s": ..., "repeats": ..., "frequencies_hz": [...], "tf_degrees": [...]}.
"""
import json
import statistics
import sys
import time

import sympy as sp

R = sp.Rational


def spindle_data():
    """Parameters (name -> exact value) and the model, as in spindle.mdl."""
    v = {
        "m_s": R("10.67"), "L_s": R("0.612"), "R_so": R("0.025"), "R_si": R("0.013"),
        "m_h": R("24.61"), "a_h": R("0.105"), "b_h": R("0.125"), "c_h": R("0.340"),
        "k_fx": R(60 * 10**6), "k_fy": R(60 * 10**6), "k_fz": R(30 * 10**6), "k_rx": R(60 * 10**6),
        "k_ry": R(60 * 10**6), "c_fx": R(1000), "c_fy": R(1000), "c_fz": R(1000), "c_rx": R(1000), "c_ry": R(1000),
        "k_hbx": R(65 * 10**6), "k_hby": R(130 * 10**6), "k_hbz": R(65 * 10**6),
        "c_hbx": R(1000), "c_hby": R(1000), "c_hbz": R(1000),
    }
    p = {name: sp.Symbol(name) for name in v}
    J_sxx = p["m_s"] * (3 * (p["R_so"] ** 2 + p["R_si"] ** 2) + p["L_s"] ** 2) / 12
    J_szz = p["m_s"] * (p["R_so"] ** 2 + p["R_si"] ** 2) / 2
    J_hxx = p["m_h"] * (p["b_h"] ** 2 + p["c_h"] ** 2) / 12
    J_hyy = p["m_h"] * (p["a_h"] ** 2 + p["c_h"] ** 2) / 12
    J_hzz = p["m_h"] * (p["a_h"] ** 2 + p["b_h"] ** 2) / 12
    bodies = [
        ("spindle", p["m_s"], sp.diag(J_sxx, J_sxx, J_szz), ["x", "y", "z", "rx", "ry"]),
        ("housing", p["m_h"], sp.diag(J_hxx, J_hyy, J_hzz), ["x", "y", "z", "rx", "ry", "rz"]),
    ]
    X, Y, Z = (1, 0, 0), (0, 1, 0), (0, 0, 1)
    springs = [  # (frame a, point a, frame b, point b, direction, k, c)
        ("spindle", ("-0.025", 0, "0.127"), "housing", ("-0.040", 0, "0.127"), X, p["k_fx"], p["c_fx"]),
        ("spindle", (0, "-0.025", "0.127"), "housing", (0, "-0.040", "0.127"), Y, p["k_fy"], p["c_fy"]),
        ("spindle", (0, 0, "0.127"), "housing", (0, 0, "0.200"), Z, p["k_fz"], p["c_fz"]),
        ("spindle", ("-0.025", 0, "-0.162"), "housing", ("-0.040", 0, "-0.162"), X, p["k_rx"], p["c_rx"]),
        ("spindle", (0, "-0.025", "-0.162"), "housing", (0, "-0.040", "-0.162"), Y, p["k_ry"], p["c_ry"]),
    ]
    for sx in ("-0.048", "0.048"):
        for sz in ("0.060", "-0.060"):
            for axis, k, c in ((X, "k_hbx", "c_hbx"), (Y, "k_hby", "c_hby"), (Z, "k_hbz", "c_hbz")):
                springs.append(("housing", (sx, "-0.064", sz), "base", (sx, "-0.080", sz), axis, p[k], p[c]))
    inputs = [("spindle", (0, 0, "0.306"), X)]
    outputs = [("spindle", (0, 0, "0.250"), X), ("spindle", (0, 0, "-0.250"), X), ("housing", (0, "0.0625", "0.170"), X)]
    values = {p[name]: val for name, val in v.items()}
    return bodies, springs, inputs, outputs, values


def vec(t):
    return sp.Matrix([R(c) for c in t])


def rot(axis, a):
    c, s = sp.cos(a), sp.sin(a)
    if axis == 0:
        return sp.Matrix([[1, 0, 0], [0, c, -s], [0, s, c]])
    if axis == 1:
        return sp.Matrix([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    return sp.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def derive():
    bodies, springs, inputs, outputs, values = spindle_data()
    q, qd, frames = [], [], {}
    for name, mass, inertia, dofs in bodies:
        t, R_ = sp.zeros(3, 1), sp.eye(3)
        for d in dofs:
            qi, qdi = sp.Symbol(f"{name}.{d}"), sp.Symbol(f"{name}.{d}_dot")
            q.append(qi)
            qd.append(qdi)
            if d in ("x", "y", "z"):
                t["xyz".index(d)] = qi
        for axis, d in enumerate(("rx", "ry", "rz")):
            if d in dofs:
                R_ = R_ * rot(axis, q[len(q) - len(dofs) + dofs.index(d)])
        frames[name] = (t, R_, mass, inertia)
    rest = {s: 0 for s in q + qd}
    centre = sp.zeros(3, 1)  # both centres of mass at the origin

    def position(frame, point):
        if frame not in frames:
            return vec(point)
        t, R_, _, _ = frames[frame]
        return centre + t + R_ * (vec(point) - centre)

    def velocity(r):
        return r.jacobian(q) * sp.Matrix(qd)

    T = 0
    for name, (t, R_, mass, inertia) in frames.items():
        v = velocity(position(name, (0, 0, 0)))
        R_dot = sum((R_.diff(qi) * qdi for qi, qdi in zip(q, qd)), sp.zeros(3, 3))
        W = R_dot * R_.T
        w = sp.Matrix([W[2, 1], W[0, 2], W[1, 0]])
        T += (mass * v.dot(v) + (w.T * R_ * inertia * R_.T * w)[0]) / 2
    V, D = 0, 0
    for fa, pa, fb, pb, n, k, c in springs:
        n = vec(n)
        e = n.dot(position(fb, pb) - position(fa, pa)) - n.dot(vec(pb) - vec(pa))
        V += k * e**2 / 2
        D += c * (n.dot(velocity(position(fb, pb)) - velocity(position(fa, pa)))) ** 2 / 2
    M = sp.hessian(T, qd).subs(rest)
    K = sp.hessian(V, q).subs(rest)
    C = sp.hessian(D, qd).subs(rest)
    B = sp.Matrix.hstack(*[position(f, pt).jacobian(q).subs(rest).T * vec(n) for f, pt, n in inputs])
    Cd = sp.Matrix.vstack(*[(vec(n).T * position(f, pt).jacobian(q)).subs(rest) for f, pt, n in outputs])

    # Transfer functions of the x/ry/rz block at the nominal values.
    s = sp.Symbol("s")
    block = [i for i, qi in enumerate(q) if str(qi).split(".")[1] in ("x", "ry", "rz")]
    P = (M * s**2 + C * s + K).subs(values)
    Pb = P.extract(block, block)
    den = sp.Poly(sp.expand(Pb.det(method="berkowitz")), s)
    tfs = []
    for o in range(Cd.rows):
        border = Pb.row_join(B.subs(values).extract(block, [0])).col_join(
            Cd.subs(values).extract([o], block).row_join(sp.zeros(1, 1)))
        num = sp.Poly(-sp.expand(border.det(method="berkowitz")), s)
        lead = den.LC()
        tfs.append((num.monic() * (num.LC() / lead), den.monic()))
    return M, K, values, tfs


def main():
    repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        M, K, values, tfs = derive()
        times.append(time.perf_counter() - start)
    import mpmath
    A = mpmath.matrix((M.subs(values).inv() * K.subs(values)).evalf(30).tolist())
    freqs = sorted(float(mpmath.sqrt(mpmath.re(ev)) / (2 * mpmath.pi)) for ev in mpmath.eig(A, left=False, right=False))
    print(json.dumps({"median_s": statistics.median(times), "repeats": repeats,
                      "frequencies_hz": [float(f) for f in freqs],
                      "tf_degrees": [[num.degree(), den.degree()] for num, den in tfs]}))


if __name__ == "__main__":
    main()
