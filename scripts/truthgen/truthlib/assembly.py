"""A tiny linear rigid-body assembler by the quadratic-form route (no Lagrange, no symbolic algebra).

Each body has up to six coordinates: translations x y z of its centre of mass c and small rotations rx ry rz
about the global axes through c. A point p on the body moves u = t + theta x (p - c), so its Jacobian is
du/dq = [I3, -[p - c]x] restricted to the body's coordinates. Then, for a one-dimensional element along the
unit vector n between point pa on frame a and point pb on frame b, h = n^T (du_b/dq - du_a/dq) and the
element adds k h h^T to K and c h h^T to C. A torsion uses the rotation Jacobians instead. The kinetic
energy gives M = blockdiag(m I3, J) per body. Equation: M q'' + (C + G) q' + K q = B u, outputs y = Cy q.

A Maxwell element (spring k in series with a damper c, no mass at the joint) adds one internal state z:
the element force is k (h q - z) = c z'. It is how a frequency-dependent damping enters a linear model
that can still be simulated in time.

Outputs are displacements of points, or their accelerations (the FRF row times (i w)^2). An output may be
read through a sensor's own dynamics (output_filter: a low-pass, AC coupling or a delay), which response.py
applies: as T(i w) in FRFs, as extra states (or the exact delay) in time.
"""
import numpy as np

DOF_NAMES = ("x", "y", "z", "rx", "ry", "rz")


def _unit(n):
    n = np.asarray(n, dtype=float)
    norm = np.linalg.norm(n)
    if norm == 0.0:
        raise ValueError("direction vector is zero")
    return n / norm


def _axis(direction):
    if isinstance(direction, str):
        return np.eye(3)["xyz".index(direction)]
    return _unit(direction)


def _cross_matrix(r):
    return np.array([[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]])


class Body:
    def __init__(self, name, mass, inertia, com, dofs):
        self.name = name
        self.mass = float(mass)
        inertia = np.asarray(inertia, dtype=float)
        self.inertia = np.diag(inertia) if inertia.shape == (3,) else inertia
        self.com = np.asarray(com, dtype=float)
        self.dofs = list(dofs)
        for d in self.dofs:
            if d not in DOF_NAMES:
                raise ValueError("body %s: unknown coordinate %s" % (name, d))


class System:
    def __init__(self, name):
        self.name = name
        self.grounds = set()
        self.bodies = {}
        self.coords = []           # (body, dof) in order of declaration
        self._springs = []         # (name, h, k, c)
        self._maxwell = []         # (name, h, k, c)
        self._spins = []           # (body, axis index, omega rad/s)
        self.inputs = []           # (name, column)
        self.outputs = []          # (name, row)
        self._output_orders = {}   # output name -> time derivative (1 velocity, 2 acceleration); 0 if absent
        self._output_filters = []  # (output name, kind, value): the sensor's own dynamics, see output_filter

    # ---- frames -------------------------------------------------------------------------------------
    def ground(self, name):
        self.grounds.add(name)

    def body(self, name, mass, inertia, com=(0, 0, 0), dofs=DOF_NAMES):
        if name in self.bodies or name in self.grounds:
            raise ValueError("frame %s declared twice" % name)
        b = Body(name, mass, inertia, com, dofs)
        self.bodies[name] = b
        self.coords += [(name, d) for d in b.dofs]
        return b

    @property
    def n(self):
        return len(self.coords)

    def index(self, body, dof):
        return self.coords.index((body, dof))

    def coordinate_names(self):
        return ["%s.%s" % c for c in self.coords]

    def _select(self, body, full):
        """Scatter a 3x6 Jacobian in (x y z rx ry rz) of `body` into the global coordinates."""
        out = np.zeros((3, self.n))
        for j, d in enumerate(DOF_NAMES):
            if (body, d) in self.coords:
                out[:, self.index(body, d)] = full[:, j]
        return out

    def point_jacobian(self, frame, point=None):
        """du/dq (3 x n) of a point on a frame; a ground point does not move."""
        if frame in self.grounds:
            return np.zeros((3, self.n))
        b = self.bodies[frame]
        r = (b.com if point is None else np.asarray(point, dtype=float)) - b.com
        return self._select(frame, np.hstack([np.eye(3), -_cross_matrix(r)]))

    def rotation_jacobian(self, frame):
        if frame in self.grounds:
            return np.zeros((3, self.n))
        return self._select(frame, np.hstack([np.zeros((3, 3)), np.eye(3)]))

    def _frame(self, name):
        if name not in self.grounds and name not in self.bodies:
            raise ValueError("unknown frame %s" % name)
        return name

    # ---- elements -----------------------------------------------------------------------------------
    def _translation_row(self, a, pa, b, pb, n):
        n = _axis(n)
        return n @ (self.point_jacobian(self._frame(b), pb) - self.point_jacobian(self._frame(a), pa))

    def spring(self, name, a, pa, b, pb, along, k, c=0.0):
        self._springs.append((name, self._translation_row(a, pa, b, pb, along), float(k), float(c)))

    def spring3(self, name, a, pa, b, pb, k3, c3=(0.0, 0.0, 0.0)):
        for axis, k, c in zip("xyz", k3, c3):
            self.spring("%s.%s" % (name, axis), a, pa, b, pb, axis, k, c)

    def torsion(self, name, a, b, about, k, c=0.0):
        n = _axis(about)
        h = n @ (self.rotation_jacobian(self._frame(b)) - self.rotation_jacobian(self._frame(a)))
        self._springs.append((name, h, float(k), float(c)))

    def maxwell(self, name, a, pa, b, pb, along, k, c):
        """Spring k in series with damper c between two points (massless joint: one internal state)."""
        if k <= 0 or c <= 0:
            raise ValueError("maxwell %s: k and c must be positive" % name)
        self._maxwell.append((name, self._translation_row(a, pa, b, pb, along), float(k), float(c)))

    def spin(self, body, about, omega):
        """Body spins at omega (rad/s) about a principal axis with equal transverse inertias."""
        a = "xyz".index(about)
        self._spins.append((body, a, float(omega)))

    # ---- signals ------------------------------------------------------------------------------------
    def input_force(self, name, frame, point, along):
        self.inputs.append((name, self.point_jacobian(self._frame(frame), point).T @ _axis(along)))

    def input_moment(self, name, frame, about):
        self.inputs.append((name, self.rotation_jacobian(self._frame(frame)).T @ _axis(about)))

    def output_displacement(self, name, frame, point, along):
        self.outputs.append((name, _axis(along) @ self.point_jacobian(self._frame(frame), point)))

    def output_acceleration(self, name, frame, point, along):
        """An accelerometer: the second time derivative of the point's displacement along `along`."""
        self.output_displacement(name, frame, point, along)
        self._output_orders[name] = 2

    def output_filter(self, name, kind, value):
        """Output `name` is read through a sensor of its own: `lowpass` (value: corner in Hz, second-order
        Butterworth wc^2/(s^2 + sqrt(2) wc s + wc^2)), `highpass` (value: corner in Hz, first-order AC coupling
        s/(s + wh)) or `delay` (value: seconds, exp(-s tau)). Filters on one output act in the order given."""
        if kind not in ("lowpass", "highpass", "delay"):
            raise ValueError("output filter %s: unknown kind %s" % (name, kind))
        if name not in self.output_names():
            raise ValueError("output filter on unknown output %s" % name)
        if not value > 0:
            raise ValueError("output filter %s %s: value must be positive" % (name, kind))
        self._output_filters.append((name, kind, float(value)))

    # ---- matrices -----------------------------------------------------------------------------------
    def _pad(self, v):
        """Rows made before later bodies were added are shorter: the new coordinates come last, and don't move."""
        return np.concatenate([v, np.zeros(self.n - v.size)])

    def mass_matrix(self):
        M = np.zeros((self.n, self.n))
        for b in self.bodies.values():
            full = np.zeros((6, 6))
            full[:3, :3] = b.mass * np.eye(3)
            full[3:, 3:] = b.inertia
            idx = [(j, self.index(b.name, d)) for j, d in enumerate(DOF_NAMES) if (b.name, d) in self.coords]
            for jr, gr in idx:
                for jc, gc in idx:
                    M[gr, gc] += full[jr, jc]
        return M

    def stiffness_damping(self):
        K = np.zeros((self.n, self.n))
        C = np.zeros((self.n, self.n))
        for _, h, k, c in self._springs:
            h = self._pad(h)
            K += k * np.outer(h, h)
            C += c * np.outer(h, h)
        return K, C

    def stiffness_of(self, prefix):
        """The part of K from the springs whose names start with `prefix` (a strain-energy share per element)."""
        K = np.zeros((self.n, self.n))
        for name, h, k, _ in self._springs:
            if name.startswith(prefix):
                h = self._pad(h)
                K += k * np.outer(h, h)
        return K

    def gyroscopic_matrix(self):
        G = np.zeros((self.n, self.n))
        for body, a, omega in self._spins:
            b = self.bodies[body]
            i, j = (a + 1) % 3, (a + 2) % 3
            jp = b.inertia[a, a]
            ri, rj = self.index(body, "r" + "xyz"[i]), self.index(body, "r" + "xyz"[j])
            G[ri, rj] += jp * omega
            G[rj, ri] -= jp * omega
        return G

    def input_matrix(self):
        return np.column_stack([self._pad(col) for _, col in self.inputs]) if self.inputs else np.zeros((self.n, 0))

    def output_matrix(self):
        return np.vstack([self._pad(row) for _, row in self.outputs]) if self.outputs else np.zeros((0, self.n))

    def input_names(self):
        return [name for name, _ in self.inputs]

    def output_names(self):
        return [name for name, _ in self.outputs]

    def maxwell_elements(self):
        return [(self._pad(h), k, c) for _, h, k, c in self._maxwell]

    def matrices(self):
        """Return dict M, C, G, K, B, Cy, the Maxwell elements (h, k, c), the outputs' derivative orders and the
        output filters (output index, kind, value)."""
        K, C = self.stiffness_damping()
        return {"M": self.mass_matrix(), "C": C, "G": self.gyroscopic_matrix(), "K": K,
                "B": self.input_matrix(), "Cy": self.output_matrix(), "maxwell": self.maxwell_elements(),
                "inputs": self.input_names(), "outputs": self.output_names(),
                "output_orders": [self._output_orders.get(name, 0) for name in self.output_names()],
                "output_filters": [(self.output_names().index(name), kind, value)
                                   for name, kind, value in self._output_filters]}
