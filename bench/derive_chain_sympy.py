#!/usr/bin/env python3
"""Independent SymPy derivation of the chain of N six-coordinate bodies, for bench/derive_chain --sympy.

The chain is compiler/symbolic/test_chain_model.hpp's (its numbers copied here: keep them in step): body i has
mass m_i, an inertia tensor of numbers, its centre at (0, 0, 0.5 i) and all six coordinates; three spring3 elements
(stiffness k_i times fixed factors per axis, damping c_i likewise) join it at the corners of a triangle to body
i - 1 (the first to the ground); a force on the last body along x; outputs x of the last body and y of the middle
one. The route is the straightforward one of derive_spindle_sympy.py: T, V and D built as whole expressions from
translations and full rotation matrices (sin/cos), M = hessian(T, qd), K = hessian(V, q), C = hessian(D, qd) at
q = 0, B and the output rows from the Jacobians of the points: M, C, K, B, Cd with the 3N parameters as symbols.
No transfer functions (mbgen's are exact rationals up to 100 coordinates; SymPy's Berkowitz determinant of a
48 x 48 polynomial matrix does not come near finishing).

    derive_chain_sympy.py N

Prints one JSON line: {"n": N, "seconds": ..., "frequencies_hz": [...]} (the undamped natural frequencies at the
nominal values, from the derived M and K, for the comparison with mbgen's).
"""
import json
import sys
import time

import sympy as sp

from derive_spindle_sympy import rot  # the same rotation matrices (this directory)

R = sp.Rational


def chain(n):
    """Parameters (symbol -> exact nominal value), bodies, springs, input and outputs as in test_chain_model.hpp."""
    values, bodies, springs = {}, [], []
    for i in range(1, n + 1):
        m, k, c = sp.Symbol(f"m{i}"), sp.Symbol(f"k{i}"), sp.Symbol(f"c{i}")
        values[m] = R(1500 + 97 * ((i * 37) % 23), 100)
        values[k] = R(40 + 3 * ((i * 11) % 17)) * 10**6
        values[c] = R(500 + 41 * ((i * 13) % 19))
        v = (i * 29) % 31
        xx, yy, zz = R(210 + 7 * v, 1000), R(230 + 5 * v, 1000), R(90 + 3 * v, 1000)
        xy, xz, yz = R(v, 10**4), 0, R(2 * v, 10**4)
        inertia = sp.Matrix([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
        bodies.append((f"b{i}", m, inertia, sp.Matrix([0, 0, R(500 * i, 1000)])))
    corners = [(-120, -70), (120, -70), (0, 140)]
    for i in range(1, n + 1):
        k, c = sp.Symbol(f"k{i}"), sp.Symbol(f"c{i}")
        frm = "base" if i == 1 else f"b{i - 1}"
        for j, (cx, cy) in enumerate(corners):
            point = sp.Matrix([R(cx + i % 5, 1000), R(cy, 1000), R(500 * i - 250, 1000)])
            kz = (2 * k, R(3, 2) * k, R(5, 2) * k)[j]
            springs.append((frm, f"b{i}", point, (k, R(8 + j, 10) * k, kz), (c, c, (j + 2) * c)))
    mid = (n + 1) // 2
    inputs = [(f"b{n}", sp.Matrix([R(5, 100), 0, R(500 * n, 1000)]), (1, 0, 0))]
    outputs = [(f"b{n}", sp.Matrix([0, R(3, 100), R(500 * n + 100, 1000)]), (1, 0, 0)),
               (f"b{mid}", sp.Matrix([R(2, 100), 0, R(500 * mid, 1000)]), (0, 1, 0))]
    return values, bodies, springs, inputs, outputs


def derive(n):
    values, bodies, springs, inputs, outputs = chain(n)
    q, qd, frames = [], [], {}
    for name, mass, inertia, centre in bodies:
        qs = [sp.Symbol(f"{name}.{d}") for d in ("x", "y", "z", "rx", "ry", "rz")]
        q += qs
        qd += [sp.Symbol(f"{name}.{d}_dot") for d in ("x", "y", "z", "rx", "ry", "rz")]
        t = sp.Matrix(qs[:3])
        R_ = rot(0, qs[3]) * rot(1, qs[4]) * rot(2, qs[5])
        frames[name] = (t, R_, mass, inertia, centre)
    rest = {s: 0 for s in q + qd}

    def position(frame, point):
        if frame not in frames:
            return point
        t, R_, _, _, centre = frames[frame]
        return centre + t + R_ * (point - centre)

    def velocity(r):
        return r.jacobian(q) * sp.Matrix(qd)

    T = 0
    for name, (t, R_, mass, inertia, centre) in frames.items():
        v = velocity(position(name, centre))
        R_dot = sum((R_.diff(qi) * qdi for qi, qdi in zip(q, qd)), sp.zeros(3, 3))
        W = R_dot * R_.T
        w = sp.Matrix([W[2, 1], W[0, 2], W[1, 0]])
        T += (mass * v.dot(v) + (w.T * R_ * inertia * R_.T * w)[0]) / 2
    V, D = 0, 0
    for fa, fb, point, ks, cs in springs:
        ra, rb = position(fa, point), position(fb, point)
        va, vb = velocity(ra), velocity(rb)
        for axis in range(3):
            V += ks[axis] * (rb[axis] - ra[axis]) ** 2 / 2  # the two points coincide at rest: unloaded
            D += cs[axis] * (vb[axis] - va[axis]) ** 2 / 2
    M = sp.hessian(T, qd).subs(rest)
    K = sp.hessian(V, q).subs(rest)
    C = sp.hessian(D, qd).subs(rest)
    B = sp.Matrix.hstack(*[position(f, pt).jacobian(q).subs(rest).T * sp.Matrix(d) for f, pt, d in inputs])
    Cd = sp.Matrix.vstack(*[(sp.Matrix(d).T * position(f, pt).jacobian(q)).subs(rest) for f, pt, d in outputs])
    return M, C, K, B, Cd, values


def main():
    n = int(sys.argv[1])
    start = time.perf_counter()
    M, C, K, B, Cd, values = derive(n)
    seconds = time.perf_counter() - start
    import mpmath
    A = mpmath.matrix((M.subs(values).inv() * K.subs(values)).evalf(30).tolist())
    freqs = sorted(float(mpmath.sqrt(mpmath.re(ev)) / (2 * mpmath.pi)) for ev in mpmath.eig(A, left=False, right=False))
    print(json.dumps({"n": n, "seconds": seconds, "frequencies_hz": freqs}))


if __name__ == "__main__":
    main()
