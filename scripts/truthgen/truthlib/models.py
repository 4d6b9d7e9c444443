"""The reference models (docs/reference-models.md) and the three-storey frame, written by hand, with
optional hidden effects.

Parameter names are exactly those of examples/mdof2/mdof2.mdl, examples/spindle/spindle.mdl and
examples/frame3/frame3.mdl. A hidden effect is passed as `effects`, a dict whose keys each builder's docstring
lists; the cases module fills it in.
"""
import math

import numpy as np

from .assembly import System

# ---------------------------------------------------------------------------------------------------------
# mdof2

MDOF2_NOMINAL = {
    "m1": 1.39, "m2": 1.09,
    "k11": 1.38e6, "k22": 0.24e6, "k12": 0.12e6,
    "c11": 13.42, "c22": 0.47, "c12": 0.0,
}
MDOF2_ESTIMABLE = ["m1", "m2", "k11", "k12", "k22", "c11", "c22"]


def build_mdof2(p, effects=None):
    """Two masses on cantilever beams, coupled by a helix. Effects (all optional):
    ground_body {m, k, c}: the wall is a body (x only) held by a spring to a fixed ground;
    added_mass {m}: a point mass at mass1's point (mass1 is a point, so its mass just grows);
    resonator {m, k, c}: a mass on a spring-damper along x on mass1;
    maxwell {a, b, k, c}: a Maxwell element along x between frames a and b;
    output_filter {output, kind, value}: that output is read through a low-pass, AC coupling or delay
        (assembly.System.output_filter).
    """
    e = effects or {}
    s = System("mdof2")
    if "ground_body" in e:
        g = e["ground_body"]
        s.body("wall", g["m"], [0.0, 0.0, 0.0], (0, 0, 0), ["x"])
        s.ground("wall_fixed")
        s.spring3("wall_support", "wall", None, "wall_fixed", (0, 0, 0), (g["k"],) * 3, (g["c"],) * 3)
    else:
        s.ground("wall")
    m1 = p["m1"] + e.get("added_mass", {}).get("m", 0.0)
    s.body("mass1", m1, [0.0, 0.0, 0.0], (0, 0, 0), ["x"])
    s.body("mass2", p["m2"], [0.0, 0.0, 0.0], (0, 0, 0), ["x"])
    s.spring("beam1", "wall", (0, 0, 0), "mass1", None, "x", p["k11"], p["c11"])
    s.spring("beam2", "wall", (0, 0, 0), "mass2", None, "x", p["k22"], p["c22"])
    s.spring("helix", "mass1", None, "mass2", None, "x", p["k12"], p["c12"])
    if "resonator" in e:
        r = e["resonator"]
        s.body("res_mass1", r["m"], [0.0, 0.0, 0.0], (0, 0, 0), ["x"])
        s.spring("res_mass1_spring", "mass1", None, "res_mass1", None, "x", r["k"], r["c"])
    if "maxwell" in e:
        mw = e["maxwell"]
        s.maxwell("maxwell", mw["a"], None, mw["b"], None, "x", mw["k"], mw["c"])
    s.input_force("F1", "mass1", None, "x")
    s.output_displacement("d1", "mass1", None, "x")
    s.output_displacement("d2", "mass2", None, "x")
    _output_filter(s, e)
    return s


def _output_filter(s, e):
    if "output_filter" in e:
        of = e["output_filter"]
        s.output_filter(of["output"], of["kind"], of["value"])


# ---------------------------------------------------------------------------------------------------------
# spindle

SPINDLE_NOMINAL = {
    "m_s": 10.67, "L_s": 0.612, "R_so": 0.025, "R_si": 0.013,
    "m_h": 24.61, "a_h": 0.105, "b_h": 0.125, "c_h": 0.340,
    "k_fx": 60e6, "k_fy": 60e6, "k_fz": 30e6, "k_rx": 60e6, "k_ry": 60e6,
    "c_fx": 1000.0, "c_fy": 1000.0, "c_fz": 1000.0, "c_rx": 1000.0, "c_ry": 1000.0,
    "k_hbx": 65e6, "k_hby": 130e6, "k_hbz": 65e6,
    "c_hbx": 1000.0, "c_hby": 1000.0, "c_hbz": 1000.0,
    "n_sp": 0.0,
}
SPINDLE_ESTIMABLE = ["k_fx", "k_fy", "k_fz", "k_rx", "k_ry", "c_fx", "c_fy", "c_fz", "c_rx", "c_ry",
                     "k_hbx", "k_hby", "k_hbz", "c_hbx", "c_hby", "c_hbz"]

BEARINGS = [  # name, spindle point, housing point, axis, stiffness, damping
    ("bearing_fx", (-0.025, 0, 0.127), (-0.040, 0, 0.127), "x", "k_fx", "c_fx"),
    ("bearing_fy", (0, -0.025, 0.127), (0, -0.040, 0.127), "y", "k_fy", "c_fy"),
    ("bearing_fz", (0, 0, 0.127), (0, 0, 0.200), "z", "k_fz", "c_fz"),
    ("bearing_rx", (-0.025, 0, -0.162), (-0.040, 0, -0.162), "x", "k_rx", "c_rx"),
    ("bearing_ry", (0, -0.025, -0.162), (0, -0.040, -0.162), "y", "k_ry", "c_ry"),
]
MOUNTS = [  # name, housing point, base point
    ("mount1", (-0.048, -0.064, 0.060), (-0.048, -0.080, 0.060)),
    ("mount2", (0.048, -0.064, 0.060), (0.048, -0.080, 0.060)),
    ("mount3", (-0.048, -0.064, -0.060), (-0.048, -0.080, -0.060)),
    ("mount4", (0.048, -0.064, -0.060), (0.048, -0.080, -0.060)),
]
NOSE = (0.0, 0.0, 0.306)
# base_on_feet: the base as a rigid box 0.30 x 0.10 x 0.40 m (x, y, z), its top face at the mounts' base points
# (y = -0.080), on four feet at its bottom corners.
BASE_BOX_SIZE = (0.30, 0.10, 0.40)
BASE_BOX_CENTRE = (0.0, -0.130, 0.0)
BASE_FEET = [(sx * 0.15, -0.180, sz * 0.20) for sx in (-1, 1) for sz in (1, -1)]
FOOT_PATTERN = (1.0, 3.0, 1.0)   # per-foot stiffness kx : ky : kz (a levelling foot is stiffer vertically)


def spindle_inertias(p):
    """Inertias from geometry (docs/reference-models.md): hollow cylinder and solid box."""
    r2 = p["R_so"] ** 2 + p["R_si"] ** 2
    j_sxx = p["m_s"] * (3 * r2 + p["L_s"] ** 2) / 12
    j_szz = p["m_s"] * r2 / 2
    j_h = [p["m_h"] * (p["b_h"] ** 2 + p["c_h"] ** 2) / 12,
           p["m_h"] * (p["a_h"] ** 2 + p["c_h"] ** 2) / 12,
           p["m_h"] * (p["a_h"] ** 2 + p["b_h"] ** 2) / 12]
    return np.diag([j_sxx, j_sxx, j_szz]), np.diag(j_h)


def _with_point_mass(mass, com, inertia, ma, point):
    """Body plus a point mass: total mass, new centre of mass, inertia tensor about it (parallel axes)."""
    com = np.asarray(com, float)
    point = np.asarray(point, float)
    total = mass + ma
    new_com = (mass * com + ma * point) / total

    def shift(m, d):
        return m * (np.dot(d, d) * np.eye(3) - np.outer(d, d))

    return total, new_com, inertia + shift(mass, com - new_com) + shift(ma, point - new_com)


def build_spindle(p, effects=None):
    """Spindle in a housing on four mounts. Effects (all optional):
    ground_body {m, k, c}: the base is a body (x y z) at the centroid of the mount points, held by an
        isotropic spring3 to a fixed ground;
    mount_overrides {mount: {param: value}}: one mount's own value of a shared mount parameter;
    spin: True: the spindle spins about z at n_sp rev/s (gyroscopic coupling);
    torsions [{name, a, b, about, k, c}]: rotational springs between spindle and housing;
    added_mass {m, point}: a point mass on the spindle;
    resonator {m, k, c, point}: a mass on a spring-damper along x at a spindle point;
    connection {k, c}: an isotropic spring3 between the spindle's centre of mass and the base;
    maxwell {name, a, pa, b, pb, along, k, c}: a Maxwell element;
    sensor {output, m, k, c}: that output is read by a sensor, a mass m on a spring-damper (k, c) along the
        output's direction at its point on the spindle, with the one coordinate along it: the output measures
        the sensor's mass (an accelerometer's mounting resonance; the sensor also loads the spindle);
    base_box {m, k3, c3}: the base is a rigid box of mass m (BASE_BOX_SIZE, centre BASE_BOX_CENTRE, all six
        coordinates) standing on four feet (BASE_FEET; spring3 to a fixed ground, each with stiffnesses k3 and
        dampings c3); the mounts attach to it at their base points;
    output_filter {output, kind, value}: that output is read through a low-pass, AC coupling or delay.
    """
    e = effects or {}
    s = System("spindle")
    j_s, j_h = spindle_inertias(p)
    m_s, com_s = p["m_s"], np.zeros(3)
    if "added_mass" in e:
        m_s, com_s, j_s = _with_point_mass(m_s, com_s, j_s, e["added_mass"]["m"], e["added_mass"]["point"])
    if "ground_body" in e:
        g = e["ground_body"]
        points = np.array([bp for _, _, bp in MOUNTS])
        centroid = points.mean(axis=0)
        radius = max(np.linalg.norm(points - centroid, axis=1))
        s.body("base", g["m"], np.eye(3) * 2 * g["m"] * radius ** 2 / 5, centroid, ["x", "y", "z"])
        s.ground("base_fixed")
        s.spring3("base_support", "base", centroid, "base_fixed", centroid, (g["k"],) * 3, (g["c"],) * 3)
    elif "base_box" in e:
        bb = e["base_box"]
        s.body("base", bb["m"], box_inertia(bb["m"], BASE_BOX_SIZE), BASE_BOX_CENTRE)
        s.ground("base_fixed")
        for i, foot in enumerate(BASE_FEET):
            s.spring3("base_foot%d" % (i + 1), "base", foot, "base_fixed", foot, bb["k3"], bb["c3"])
    else:
        s.ground("base")
    s.body("spindle", m_s, j_s, com_s, ["x", "y", "z", "rx", "ry"])
    s.body("housing", p["m_h"], j_h, (0, 0, 0), ["x", "y", "z", "rx", "ry", "rz"])
    for name, ps, ph, axis, k, c in BEARINGS:
        s.spring(name, "spindle", ps, "housing", ph, axis, p[k], p[c])
    overrides = e.get("mount_overrides", {})
    for name, ph, pb in MOUNTS:
        q = dict(p)
        q.update(overrides.get(name, {}))
        s.spring3(name, "housing", ph, "base", pb, (q["k_hbx"], q["k_hby"], q["k_hbz"]),
                  (q["c_hbx"], q["c_hby"], q["c_hbz"]))
    if e.get("spin"):
        s.spin("spindle", "z", 2 * math.pi * p["n_sp"])
    for t in e.get("torsions", []):
        s.torsion(t["name"], t["a"], t["b"], t["about"], t["k"], t["c"])
    if "resonator" in e:
        r = e["resonator"]
        s.body("res_spindle", r["m"], [0.0, 0.0, 0.0], r["point"], ["x"])
        s.spring("res_spindle_spring", "spindle", r["point"], "res_spindle", r["point"], "x", r["k"], r["c"])
    if "connection" in e:
        cn = e["connection"]
        s.spring3("base_spindle_link", "base", com_s, "spindle", com_s, (cn["k"],) * 3, (cn["c"],) * 3)
    if "maxwell" in e:
        mw = e["maxwell"]
        s.maxwell(mw["name"], mw["a"], mw["pa"], mw["b"], mw["pb"], mw["along"], mw["k"], mw["c"])
    s.input_force("Fx", "spindle", NOSE, "x")
    sensor = e.get("sensor")
    for name, frame, point in [("xs_front", "spindle", (0, 0, 0.250)), ("xs_rear", "spindle", (0, 0, -0.250)),
                               ("xh_front", "housing", (0, 0.0625, 0.170))]:
        if sensor and sensor["output"] == name:
            body = "sensor_" + name
            s.body(body, sensor["m"], [0.0, 0.0, 0.0], point, ["x"])
            s.spring(body + "_mount", frame, point, body, point, "x", sensor["k"], sensor["c"])
            frame = body
        s.output_displacement(name, frame, point, "x")
    _output_filter(s, e)
    return s


def box_inertia(m, size):
    """Solid box of mass m and edges (a, b, c) along x, y, z: inertia about its centre."""
    a, b, c = size
    return np.array([m * (b ** 2 + c ** 2) / 12, m * (a ** 2 + c ** 2) / 12, m * (a ** 2 + b ** 2) / 12])


def machine_rigid_inertia(p, m_base):
    """Mass, centre of mass and inertia tensor of base box + housing + spindle welded together (the spindle
    still turns freely about its own axis, so its J_szz is left out): the body that rocks on the feet when the
    mounts are taken as rigid (base_on_feet's tuning)."""
    j_s, j_h = spindle_inertias(p)
    j_s = j_s.copy()
    j_s[2, 2] = 0.0
    parts = [(m_base, np.diag(box_inertia(m_base, BASE_BOX_SIZE)), np.array(BASE_BOX_CENTRE)),
             (p["m_h"], j_h, np.zeros(3)), (p["m_s"], j_s, np.zeros(3))]
    total = sum(m for m, _, _ in parts)
    com = sum(m * c for m, _, c in parts) / total
    inertia = sum(j + m * (np.dot(c - com, c - com) * np.eye(3) - np.outer(c - com, c - com)) for m, j, c in parts)
    return total, com, inertia


def base_rocking_hz(p, m_base, k_ref):
    """Frequency (Hz) of the lowest rocking mode about z (tilting in the x-y plane, with x sway: the one that
    x-direction data see) of the machine taken as rigid on the four feet, each foot k_ref * FOOT_PATTERN."""
    total, com, inertia = machine_rigid_inertia(p, m_base)
    s = System("rigid_machine_on_feet")
    s.body("machine", total, inertia, com, ["x", "rz"])
    s.ground("floor")
    for i, foot in enumerate(BASE_FEET):
        s.spring3("foot%d" % i, "machine", foot, "floor", foot, tuple(k_ref * r for r in FOOT_PATTERN))
    K, _ = s.stiffness_damping()
    w2 = np.linalg.eigvals(np.linalg.solve(s.mass_matrix(), K)).real
    return float(np.sqrt(min(w2)) / (2 * np.pi))


# ---------------------------------------------------------------------------------------------------------
# frame3: a three-storey shear frame (like the Los Alamos "bookshelf"), y vertical

FRAME3_NOMINAL = {
    "m1": 5.8, "m2": 5.6, "m3": 5.4,
    "k1": 6.0e5, "k2": 3.2e5, "k3": 2.9e5,
    "c1": 160.0, "c2": 25.0, "c3": 28.0,
}
FRAME3_ESTIMABLE = ["m1", "m2", "m3", "k1", "k2", "k3", "c1", "c2", "c3"]
STOREY_HEIGHT = 0.177
PLATE = 0.305   # square storey plate, m (its torsional inertia in outside_torsion)


def build_frame3(p, effects=None):
    """Ground `floor`, storeys 1-3 along x joined by columns (spring-dampers along x), forces F1-F3 on the
    storeys along x, accelerations a1-a3 of the storeys along x. Effects (optional):
    torsion {kt: (kt1, kt2, kt3), ct: (...), e}: each storey also twists about the vertical y (its own
        coordinate ry, the inertia of a square plate of side PLATE), with torsional springs floor-storey1,
        storey1-storey2, storey2-storey3; the forces act and the accelerations are read at (0, h, e) on each
        storey, an eccentricity e off the centre line, so the twist shows in the x data.
    """
    e = effects or {}
    tor = e.get("torsion")
    s = System("frame3")
    s.ground("floor")
    storeys = ["storey1", "storey2", "storey3"]
    for i, name in enumerate(storeys):
        m = p["m%d" % (i + 1)]
        inertia = [0.0, m * 2 * PLATE ** 2 / 12, 0.0]
        s.body(name, m, inertia, (0, STOREY_HEIGHT * (i + 1), 0), ["x", "ry"] if tor else ["x"])
    for i, (a, b) in enumerate(zip(["floor"] + storeys[:-1], storeys)):
        s.spring("column%d" % (i + 1), a, None, b, None, "x", p["k%d" % (i + 1)], p["c%d" % (i + 1)])
        if tor:
            s.torsion("twist%d" % (i + 1), a, b, "y", tor["kt"][i], tor["ct"][i])
    points = [(0, STOREY_HEIGHT * (i + 1), tor["e"] if tor else 0.0) for i in range(3)]
    for i, name in enumerate(storeys):
        s.input_force("F%d" % (i + 1), name, points[i], "x")
    for i, name in enumerate(storeys):
        s.output_acceleration("a%d" % (i + 1), name, points[i], "x")
    return s


# ---------------------------------------------------------------------------------------------------------
# tower5: a five-storey shear tower shaken at the roof (like a building's forced-vibration test), y vertical

TOWER5_NOMINAL = {
    "m1": 5200.0, "m2": 5000.0, "m3": 4900.0, "m4": 4700.0, "m5": 4000.0,
    "k1": 1.05e6, "k2": 0.92e6, "k3": 0.80e6, "k4": 0.70e6, "k5": 0.58e6,
    "c1": 3200.0, "c2": 2800.0, "c3": 2500.0, "c4": 2200.0, "c5": 1900.0,
}
TOWER5_ESTIMABLE = ["m1", "m2", "m3", "m4", "m5", "k1", "k2", "k3", "k4", "k5", "c1", "c2", "c3", "c4", "c5"]
TOWER_STOREY_HEIGHT = 3.0


def build_tower5(p, effects=None):
    """Ground `ground`, storeys 1-5 along x joined by shear springs-dampers along x, one force F at the roof
    (storey5) along x, accelerations a1-a5 of the storeys along x. No effects."""
    s = System("tower5")
    s.ground("ground")
    storeys = ["storey%d" % (i + 1) for i in range(5)]
    for i, name in enumerate(storeys):
        s.body(name, p["m%d" % (i + 1)], [0.0, 0.0, 0.0], (0, TOWER_STOREY_HEIGHT * (i + 1), 0), ["x"])
    for i, (a, b) in enumerate(zip(["ground"] + storeys[:-1], storeys)):
        s.spring("shear%d" % (i + 1), a, None, b, None, "x", p["k%d" % (i + 1)], p["c%d" % (i + 1)])
    s.input_force("F", "storey5", (0, TOWER_STOREY_HEIGHT * 5, 0), "x")
    for i, name in enumerate(storeys):
        s.output_acceleration("a%d" % (i + 1), name, (0, TOWER_STOREY_HEIGHT * (i + 1), 0), "x")
    return s


EXAMPLES = {
    "mdof2": {"nominal": MDOF2_NOMINAL, "estimable": MDOF2_ESTIMABLE, "build": build_mdof2},
    "spindle": {"nominal": SPINDLE_NOMINAL, "estimable": SPINDLE_ESTIMABLE, "build": build_spindle},
    "frame3": {"nominal": FRAME3_NOMINAL, "estimable": FRAME3_ESTIMABLE, "build": build_frame3},
    "tower5": {"nominal": TOWER5_NOMINAL, "estimable": TOWER5_ESTIMABLE, "build": build_tower5},
}
