"""Truth variants: one per extension operator of `mbgen diagnose` and example, controls, and effects outside the
operator library. See docs/truthgen.md for what each hides and how large it is.

Every case also moves the nominal model's estimable parameters off their nominal values by 3 to 10 %, with a
sign and size drawn per case from a generator seeded by the case's name (so each case has its own truth, and
a fit cannot succeed by returning the nominal values).

A case is written as a function `make(v)` of its effect's sizes `v` (a dict), so that `--draw N` can draw the
sizes (each `Size` uniformly in its range) as well as the offsets from one generator, while without it every
case keeps the exact values (and texts) it always had: `defaults` are those values, in the form `make` takes
them, and `from_draw` turns drawn sizes into that form where the natural quantity to draw differs (a frequency
rather than a stiffness).
"""
import copy
import math
import zlib

import numpy as np
import scipy.linalg
import scipy.optimize

from . import models


def critical_fraction(zeta, k, m):
    """Damping c giving damping ratio zeta to a mass m on a spring k."""
    return 2 * zeta * math.sqrt(k * m)


def four_digits(x):
    """Truth values are written with 4 significant digits, so that the JSON shows exactly what was used."""
    return float("%.4g" % x)


class Size:
    """One drawable size of a hidden effect: under --draw, uniform in [low, high] (SI units; `unit` for people)."""

    def __init__(self, name, low, high, unit, what):
        self.name, self.low, self.high, self.unit, self.what = name, low, high, unit, what


class Case:
    def __init__(self, example, name, operator, make, defaults=None, sizes=(), from_draw=None, default_set=None,
                 kinds=("frf", "time"), notes="", control=False):
        self.example = example
        self.name = name
        self.operator = operator        # expected candidate id of `mbgen diagnose`, or None
        self.make = make                # function(values) -> dict: hidden, effects, extra, effect_hz, hidden_values
        self.defaults = dict(defaults or {})
        self.sizes = list(sizes)        # what --draw draws
        self.from_draw = from_draw or (lambda d: dict(d))
        self.default_set = default_set or {}   # written as `# set` lines unless the user sets them
        self.kinds = kinds
        self.notes = notes
        self.control = control          # no hidden effect at all
        self.draw = None                # with --draw: what was drawn (for the truth JSON)
        self._offsets = None            # with --draw: the drawn relative offsets of the estimable parameters
        self._bind(self.defaults)

    def _bind(self, values):
        spec = self.make(values)
        self.values = values
        self.hidden = spec["hidden"]            # one sentence: what the truth has that the nominal model lacks
        self.effects = spec.get("effects", lambda p: {})   # function(parameters) -> effects for models.build_*
        self.extra = spec.get("extra", {})      # values of the hidden effect (dict, or function(parameters))
        self.effect_hz = spec.get("effect_hz")  # where the effect shows (Hz), None if everywhere / nowhere
        self.hidden_values = spec.get("hidden_values", {})  # model parameters whose truth differs, NOT written

    def extra_at(self, p):
        """The hidden effect's values for the truth JSON (some, e.g. tuned stiffnesses, depend on parameters)."""
        return self.extra(p) if callable(self.extra) else self.extra

    def drawn(self, n):
        """This case with its truth drawn from --draw n: `default_rng([n, crc32("EXAMPLE/CASE")])` draws first the
        offsets of the estimable parameters (as truth_parameters does from crc32 alone), then each Size in order."""
        c = copy.copy(self)
        rng = np.random.default_rng([n, self._crc()])
        c._offsets = self._draw_offsets(rng)
        drawn = {s.name: four_digits(rng.uniform(s.low, s.high)) for s in self.sizes}
        c._bind(self.from_draw(drawn))
        c.draw = {"n": n, "generator": 'numpy.random.default_rng([%d, crc32("%s/%s")])' % (n, self.example, self.name),
                  "offsets": {name: off for name, off in c._offsets.items()},
                  "sizes": drawn,
                  "ranges": {s.name: {"low": s.low, "high": s.high, "unit": s.unit, "what": s.what}
                             for s in self.sizes}}
        return c

    def at_sizes(self, sizes):
        """This case with its effect at the given sizes (the --draw form, e.g. a range's weak end) and its usual
        fixed offsets: what selftest uses to check the effect is still clear across the documented ranges."""
        c = copy.copy(self)
        c._bind(self.from_draw(dict(sizes)))
        return c

    def _crc(self):
        return zlib.crc32(("%s/%s" % (self.example, self.name)).encode())

    def _draw_offsets(self, rng):
        """Relative offset of each estimable parameter: a size U(3 %, 10 %) with a random sign."""
        offsets = {}
        for name in models.EXAMPLES[self.example]["estimable"]:
            size = rng.uniform(0.03, 0.10)
            sign = 1.0 if rng.uniform() < 0.5 else -1.0
            offsets[name] = sign * size
        return offsets

    def truth_parameters(self, overrides=None):
        """Nominal values, estimable ones moved off by 3-10 % (per case), then `# set` values applied."""
        ex = models.EXAMPLES[self.example]
        p = dict(ex["nominal"])
        offsets = self._offsets
        if offsets is None:
            offsets = self._draw_offsets(np.random.default_rng(self._crc()))
        for name in ex["estimable"]:
            p[name] = float("%.4g" % (p[name] * (1 + offsets[name])))
        p.update(self.hidden_values)
        p.update(self.default_set)
        for name, value in (overrides or {}).items():
            if name not in p:
                raise KeyError(name)
            p[name] = value
        return p

    def build(self, p):
        return models.EXAMPLES[self.example]["build"](p, self.effects(p))


def _pct(zeta):
    return "%.3g %%" % (100 * zeta)


# ---- sensor cases (both examples) ---------------------------------------------------------------------------
SENSOR_OUTPUT = {"mdof2": "d2", "spindle": "xs_front"}
SENSOR_DEFAULTS = {  # example: (low-pass fc Hz, AC-coupling fh Hz, delay s) and the --draw ranges
    "mdof2": {"lowpass": (450.0, 300.0, 700.0), "highpass": (4.0, 2.0, 8.0), "delay": (0.5e-3, 0.2e-3, 1.0e-3)},
    "spindle": {"lowpass": (1500.0, 900.0, 2500.0), "highpass": (20.0, 10.0, 40.0),
                "delay": (0.12e-3, 0.05e-3, 0.2e-3)},
}


def _sensor_cases(example):
    out = SENSOR_OUTPUT[example]
    d = SENSOR_DEFAULTS[example]
    op = "sensor_dynamics:%s" % out

    def lowpass(v):
        fc = v["fc"]
        return {"hidden": "%s is read through an electrical second-order Butterworth low-pass, corner %.4g Hz: "
                          "T(s) = wc^2/(s^2 + sqrt(2) wc s + wc^2) (in the band mostly phase lag, no peak)" % (out, fc),
                "effects": lambda p: {"output_filter": {"output": out, "kind": "lowpass", "value": fc}},
                "extra": {"lowpass_hz_%s" % out: fc}, "effect_hz": fc}

    def highpass(v):
        fh = v["fh"]
        return {"hidden": "%s is AC-coupled: a first-order high-pass T(s) = s/(s + wh), corner %.4g Hz (phase lead "
                          "and a magnitude loss at the low end of the band)" % (out, fh),
                "effects": lambda p: {"output_filter": {"output": out, "kind": "highpass", "value": fh}},
                "extra": {"highpass_hz_%s" % out: fh}, "effect_hz": fh}

    def delay(v):
        tau = v["tau"]
        return {"hidden": "%s is delayed by %.4g ms: exp(-s tau) (a phase lag growing with frequency)"
                          % (out, tau * 1e3),
                "effects": lambda p: {"output_filter": {"output": out, "kind": "delay", "value": tau}},
                "extra": {"delay_s_%s" % out: tau}}

    lo = d["lowpass"]
    hi = d["highpass"]
    de = d["delay"]
    return [
        Case(example, "sensor_lowpass", op, lowpass, {"fc": lo[0]},
             [Size("fc", lo[1], lo[2], "Hz", "low-pass corner frequency")]),
        Case(example, "sensor_highpass", op, highpass, {"fh": hi[0]},
             [Size("fh", hi[1], hi[2], "Hz", "AC-coupling corner frequency")]),
        Case(example, "sensor_delay", op, delay, {"tau": de[0]},
             [Size("tau", de[1], de[2], "s", "delay")],
             notes="In time records the delay is exact: y_d[k] = Cy x(t_k - tau), the state between samples from "
                   "the held input; zero before the record (at rest)."),
    ]


# ---- mdof2 ---------------------------------------------------------------------------------------------------
def _mdof2_cases():
    def compliant_ground(v):
        m_g, k_g, zeta = v["m_wall"], v["k_wall"], v["zeta_wall"]
        c_g = critical_fraction(zeta, k_g, m_g)
        return {"hidden": "the wall is a %.3g kg mass on a spring (k = %.3g N/m, zeta %s) along x"
                          % (m_g, k_g, _pct(zeta)),
                "effects": lambda p: {"ground_body": {"m": m_g, "k": k_g, "c": c_g}},
                "extra": {"m_wall": m_g, "k_wall": k_g, "c_wall": c_g}}

    def free_parameter(v):
        return {"hidden": "the helix is damped: c12 = %g N s/m (the nominal model fixes it at 0)" % v["c12"],
                "extra": {"c12": v["c12"]}, "hidden_values": {"c12": v["c12"]}}

    def added_mass(v):
        ma = v["ma"]
        return {"hidden": "a %.3g kg point mass at mass1's point (input F1)" % ma,
                "effects": lambda p: {"added_mass": {"m": ma}}, "extra": {"ma_mass1": ma}}

    def resonator(v):
        m_r, f_r, zeta = v["m"], v["f"], v["zeta"]
        k_r = m_r * (2 * math.pi * f_r) ** 2
        c_r = critical_fraction(zeta, k_r, m_r)
        return {"hidden": "a local %.3g kg mass on a spring-damper along x on mass1, own mode %.4g Hz, zeta %s"
                          % (m_r, f_r, _pct(zeta)),
                "effects": lambda p: {"resonator": {"m": m_r, "k": k_r, "c": c_r}},
                "extra": {"mr_mass1": m_r, "kr_mass1": k_r, "cr_mass1": c_r}, "effect_hz": f_r}

    def maxwell(v):
        mw_c, mw_fc = v["c"], v["fc"]
        mw_k = 2 * math.pi * mw_fc * mw_c
        return {"hidden": "a Maxwell element (spring %.4g N/m in series with damper %.3g N s/m) between wall and "
                          "mass1: a damping that acts below %.4g Hz and turns into a spring above"
                          % (mw_k, mw_c, mw_fc),
                "effects": lambda p: {"maxwell": {"a": "wall", "b": "mass1", "k": mw_k, "c": mw_c}},
                "extra": {"maxwell_k": mw_k, "maxwell_c": mw_c, "maxwell_corner_hz": mw_fc}, "effect_hz": mw_fc}

    def wall_from_draw(d):
        return {"m_wall": d["m_wall"], "k_wall": d["m_wall"] * (2 * math.pi * d["f_wall"]) ** 2,
                "zeta_wall": d["zeta_wall"]}

    return [
        Case("mdof2", "nominal", None, lambda v: {"hidden": "nothing: the nominal model with its parameters off "
                                                            "nominal"}, control=True),
        Case("mdof2", "compliant_ground", "compliant_ground:wall", compliant_ground,
             {"m_wall": 5.0, "k_wall": 1.6e7, "zeta_wall": 0.02},
             [Size("m_wall", 3.0, 8.0, "kg", "wall mass"),
              Size("f_wall", 200.0, 330.0, "Hz", "wall's own frequency sqrt(k_wall/m_wall)/(2 pi)"),
              Size("zeta_wall", 0.01, 0.03, "", "damping ratio of the wall on its spring")], wall_from_draw),
        Case("mdof2", "free_parameter", "free_parameter:c12", free_parameter, {"c12": 5.0},
             [Size("c12", 3.0, 10.0, "N s/m", "helix damping")]),
        Case("mdof2", "added_mass", "added_mass:mass1", added_mass, {"ma": 0.08},
             [Size("ma", 0.04, 0.16, "kg", "added mass")],
             notes="mass1 is a point with one coordinate and m1 is estimable, so the added mass is exactly a "
                   "larger m1: the fit absorbs it (fitted m1 = m1 + ma) and no extension is justified."),
        Case("mdof2", "resonator", "resonator:mass1", resonator, {"m": 0.05, "f": 130.0, "zeta": 0.01},
             [Size("m", 0.03, 0.08, "kg", "resonator mass"), Size("f", 110.0, 150.0, "Hz", "its own frequency"),
              Size("zeta", 0.005, 0.02, "", "its damping ratio")]),
        Case("mdof2", "outside_maxwell", None, maxwell, {"c": 60.0, "fc": 120.0},
             [Size("c", 55.0, 90.0, "N s/m", "Maxwell damper"),
              Size("fc", 100.0, 140.0, "Hz", "corner frequency k/(2 pi c)")]),
    ] + _sensor_cases("mdof2")


# ---- spindle -------------------------------------------------------------------------------------------------
def base_x_modes_hz(system):
    """Undamped modes (Hz) of a spindle truth with a compliant base body in which the base moves mainly along
    x (|x| > 0.9 of its motion): the mode selftest checks and compliant_ground's draw tunes."""
    m = system.matrices()
    w2, V = scipy.linalg.eigh(m["K"], m["M"])
    base = [system.index("base", d) for d in "xyz"]
    return [math.sqrt(max(w, 0.0)) / (2 * math.pi) for w, v in zip(w2, V.T)
            if abs(v[base[0]]) > 0.9 * np.linalg.norm(v[base])]


def tune_base_stiffness(p, m_base, f_base, zeta):
    """Support stiffness k (isotropic spring3) putting the truth's lowest base-x mode at f_base (Hz)."""
    def mismatch(log_k):
        k = math.exp(log_k)
        s = models.build_spindle(p, {"ground_body": {"m": m_base, "k": k, "c": critical_fraction(zeta, k, m_base)}})
        return base_x_modes_hz(s)[0] - f_base
    k0 = m_base * (2 * math.pi * f_base) ** 2
    return math.exp(scipy.optimize.brentq(mismatch, math.log(k0 / 20), math.log(k0 * 20), xtol=1e-10))


def base_on_feet_feet(p, m_base, f_rock, zeta):
    """Per-foot stiffnesses (kx, ky, kz) = k_ref FOOT_PATTERN with k_ref placing the rocking mode of the machine,
    taken as rigid, on its feet at f_rock (it scales as sqrt(k_ref)), and dampings c = 2 zeta k/w_rock
    (stiffness-proportional: that mode of the rigid machine gets exactly zeta)."""
    f1 = models.base_rocking_hz(p, m_base, 1.0)
    k_ref = (f_rock / f1) ** 2
    w_rock = 2 * math.pi * f_rock
    k3 = tuple(k_ref * r for r in models.FOOT_PATTERN)
    return k3, tuple(2 * zeta * k / w_rock for k in k3)


def feet_modes_hz(system, share=0.5):
    """Undamped modes (Hz) of a base_on_feet truth that x-direction data see (the x/ry/rz block) and in which
    the feet hold more than `share` of the strain energy: the truth's own base modes, which the mounts'
    compliance puts below the rigid-machine rocking frequency (and which cannot pass the machine's own
    lowest x mode, ~210 Hz, by much: the modes veer)."""
    m = system.matrices()
    w2, V = scipy.linalg.eigh(m["K"], m["M"])
    feet = system.stiffness_of("base_foot")
    x_block = [i for i, (_, d) in enumerate(system.coords) if d in ("x", "ry", "rz")]
    out = []
    for w, v in zip(w2, V.T):
        if np.linalg.norm(v[x_block]) > 0.9 * np.linalg.norm(v) and v @ feet @ v > share * (v @ m["K"] @ v):
            out.append(math.sqrt(max(w, 0.0)) / (2 * math.pi))
    return out


def _spindle_cases():
    def compliant_ground(v):
        m_b, zeta = v["m_base"], v["zeta_base"]
        if "k_base" in v:   # the original case: k tuned by hand for a 190 Hz base-x mode (selftest checks it)
            k_b, f_b = v["k_base"], v["f_base"]
            c_b = critical_fraction(zeta, k_b, m_b)
            return {"hidden": "the base is a %.0f kg body (x y z at the mount centroid) on an isotropic spring3 "
                              "(k = %.3g N/m, zeta %s) to a fixed ground: a new mode near %.0f Hz (thesis Sec. "
                              "5.4.3)" % (m_b, k_b, _pct(zeta), f_b),
                    "effects": lambda p: {"ground_body": {"m": m_b, "k": k_b, "c": c_b}},
                    "extra": {"m_base": m_b, "k_base": k_b, "c_base": c_b}, "effect_hz": f_b}
        f_b = v["f_base"]

        def support(p):
            k = tune_base_stiffness(p, m_b, f_b, zeta)
            return k, critical_fraction(zeta, k, m_b)

        def effects(p):
            k, c = support(p)
            return {"ground_body": {"m": m_b, "k": k, "c": c}}

        def extra(p):
            k, c = support(p)
            return {"m_base": m_b, "k_base": k, "c_base": c, "f_base": f_b}

        return {"hidden": "the base is a %.3g kg body (x y z at the mount centroid) on an isotropic spring3 (k tuned "
                          "so that the base-x mode is at %.4g Hz, zeta %s) to a fixed ground" % (m_b, f_b, _pct(zeta)),
                "effects": effects, "extra": extra, "effect_hz": f_b}

    def untie(v):
        loose = v["loose"]
        return {"hidden": "mount1 is loose vertically: its k_hby is %.3g %% of the other mounts'" % (loose * 100),
                "effects": lambda p: {"mount_overrides": {"mount1": {"k_hby": loose * p["k_hby"]}}},
                "extra": {"k_hby_mount1_factor": loose}}

    def gyroscopic(v):
        return {"hidden": "the spindle spins at n_sp rev/s (gyroscopic coupling J_szz*2*pi*n_sp on rx, ry); data at "
                          "n_sp = 0 and n_sp = 300 (default `# set n_sp=300`)",
                "effects": lambda p: {"spin": True}}

    def moment_stiffness(v):
        kr = v["kr"]
        cr = kr * 1000 / 60e6
        return {"hidden": "bearing_fx also resists tilting about y: torsion spindle-housing kr = %.3g N m/rad, "
                          "cr = %.3g N m s/rad" % (kr, cr),
                "effects": lambda p: {"torsions": [{"name": "bearing_fx_ry", "a": "spindle", "b": "housing",
                                                    "about": "y", "k": kr, "c": cr}]},
                "extra": {"kr_bearing_fx": kr, "cr_bearing_fx": cr}}

    def added_mass(v):
        ma = v["ma"]
        return {"hidden": "a %.2f kg point mass on the spindle at the nose (the input point (0, 0, 0.306))" % ma,
                "effects": lambda p: {"added_mass": {"m": ma, "point": models.NOSE}}, "extra": {"ma_spindle": ma}}

    def resonator(v):
        m_r, f_r, zeta = v["m"], v["f"], v["zeta"]
        k_r = m_r * (2 * math.pi * f_r) ** 2
        c_r = critical_fraction(zeta, k_r, m_r)
        return {"hidden": "a local %.2f kg mass on a spring-damper along x at the spindle nose, own mode %.4g Hz, "
                          "zeta %s" % (m_r, f_r, _pct(zeta)),
                "effects": lambda p: {"resonator": {"m": m_r, "k": k_r, "c": c_r, "point": models.NOSE}},
                "extra": {"mr_spindle": m_r, "kr_spindle": k_r, "cr_spindle": c_r}, "effect_hz": f_r}

    def connection(v):
        k_c, c_c = v["k"], v["c"]
        return {"hidden": "an isotropic spring3 (k = %.3g N/m, c = %.3g N s/m) between the spindle's centre of mass "
                          "and the base" % (k_c, c_c),
                "effects": lambda p: {"connection": {"k": k_c, "c": c_c}},
                "extra": {"k_base_spindle": k_c, "c_base_spindle": c_c}}

    def maxwell(v):
        mw_k, mw_fc = v["k"], v["fc"]
        mw_c = mw_k / (2 * math.pi * mw_fc)
        return {"hidden": "a Maxwell element (spring %.3g N/m in series with damper %.4g N s/m) parallel to "
                          "bearing_fx: a bearing damping that acts below %.4g Hz and turns into a spring above"
                          % (mw_k, mw_c, mw_fc),
                "effects": lambda p: {"maxwell": {"name": "bearing_fx_maxwell", "a": "spindle",
                                                  "pa": (-0.025, 0, 0.127), "b": "housing", "pb": (-0.040, 0, 0.127),
                                                  "along": "x", "k": mw_k, "c": mw_c}},
                "extra": {"maxwell_k": mw_k, "maxwell_c": mw_c, "maxwell_corner_hz": mw_fc}, "effect_hz": mw_fc}

    def sensor(v):
        m_sen, f_sen, zeta = v["m"], v["f"], v["zeta"]
        k_sen = m_sen * (2 * math.pi * f_sen) ** 2
        c_sen = critical_fraction(zeta, k_sen, m_sen)
        return {"hidden": "xs_front is read by a %.0f g accelerometer on a mounting (spring-damper along x at its "
                          "point on the spindle) with its own resonance at %.4g Hz, zeta %s: a second-order "
                          "low-pass on that output" % (m_sen * 1000, f_sen, _pct(zeta)),
                "effects": lambda p: {"sensor": {"output": "xs_front", "m": m_sen, "k": k_sen, "c": c_sen}},
                "extra": {"ms_xs_front": m_sen, "ks_xs_front": k_sen, "cs_xs_front": c_sen, "fs_xs_front": f_sen,
                          "zs_xs_front": zeta},
                "effect_hz": f_sen}

    def base_on_feet(v):
        m_b, f_rock, zeta = v["m_base"], v["f_rock"], v["zeta"]

        def effects(p):
            k3, c3 = base_on_feet_feet(p, m_b, f_rock, zeta)
            return {"base_box": {"m": m_b, "k3": k3, "c3": c3}}

        def extra(p):
            k3, c3 = base_on_feet_feet(p, m_b, f_rock, zeta)
            return {"m_base": m_b, "f_rock_rigid_hz": f_rock, "foot_k_xyz": list(k3), "foot_c_xyz": list(c3),
                    "box_size_xyz": list(models.BASE_BOX_SIZE), "box_centre": list(models.BASE_BOX_CENTRE),
                    "feet": [list(f) for f in models.BASE_FEET],
                    "feet_modes_hz": [round(f, 2) for f in feet_modes_hz(models.build_spindle(p, effects(p)))]}

        return {"hidden": "the base is a rigid %.4g kg box 0.30 x 0.10 x 0.40 m (centre (0, -0.130, 0), all six "
                          "coordinates) on four feet at its bottom corners (spring3 to a fixed ground, kx:ky:kz = "
                          "1:3:1, damping 3 %% of critical at the rocking mode) tuned so that the machine, taken as "
                          "rigid, rocks about z on them at %.4g Hz" % (m_b, f_rock),
                "effects": effects, "extra": extra, "effect_hz": f_rock}

    return [
        Case("spindle", "nominal", None, lambda v: {"hidden": "nothing: the nominal model with its parameters off "
                                                              "nominal"}, control=True),
        Case("spindle", "compliant_ground", "compliant_ground:base", compliant_ground,
             {"m_base": 60.0, "k_base": 1.68e8, "f_base": 190.0, "zeta_base": 0.03},
             [Size("m_base", 40.0, 80.0, "kg", "base mass"),
              Size("f_base", 160.0, 220.0, "Hz", "the truth's base-x mode (support stiffness tuned to it; it "
                                                 "cannot pass ~235 Hz, where the machine's own mode is)")],
             lambda d: dict(d, zeta_base=0.03)),
        Case("spindle", "untie_parameter", "untie_parameter:k_hby", untie, {"loose": 0.4},
             [Size("loose", 0.25, 0.6, "", "mount1's k_hby as a fraction of the others'")]),
        Case("spindle", "gyroscopic", "gyroscopic:spindle", gyroscopic, default_set={"n_sp": 300.0}),
        Case("spindle", "moment_stiffness", "moment_stiffness:bearing_fx", moment_stiffness, {"kr": 2e5},
             [Size("kr", 1.5e5, 4e5, "N m/rad", "torsion stiffness (damping kr*1000/60e6 N m s/rad)")]),
        Case("spindle", "added_mass", "added_mass:spindle", added_mass, {"ma": 0.5},
             [Size("ma", 0.3, 1.0, "kg", "added mass at the nose")]),
        Case("spindle", "resonator", "resonator:spindle", resonator, {"m": 0.2, "f": 380.0, "zeta": 0.01},
             [Size("m", 0.1, 0.3, "kg", "resonator mass"), Size("f", 340.0, 420.0, "Hz", "its own frequency"),
              Size("zeta", 0.005, 0.02, "", "its damping ratio")]),
        Case("spindle", "connection", "connection:base-spindle", connection, {"k": 6e6, "c": 1000.0},
             [Size("k", 5e6, 1e7, "N/m", "stiffness"), Size("c", 700.0, 2000.0, "N s/m", "damping")]),
        Case("spindle", "outside_maxwell", None, maxwell, {"k": 6e6, "fc": 300.0},
             [Size("k", 5e6, 9e6, "N/m", "Maxwell spring"),
              Size("fc", 200.0, 400.0, "Hz", "corner frequency k/(2 pi c)")]),
        Case("spindle", "sensor_dynamics", "sensor_dynamics:xs_front", sensor, {"m": 0.01, "f": 1000.0, "zeta": 0.05},
             [Size("f", 800.0, 1150.0, "Hz", "mounting resonance"), Size("zeta", 0.03, 0.08, "", "its damping ratio")],
             lambda d: dict(d, m=0.01)),
    ] + _sensor_cases("spindle") + [
        Case("spindle", "base_on_feet", "compliant_ground:base", base_on_feet,
             {"m_base": 40.0, "f_rock": 190.0, "zeta": 0.03},
             [Size("m_base", 25.0, 60.0, "kg", "base box mass"),
              Size("f_rock", 150.0, 260.0, "Hz", "rocking mode of the rigid machine on the feet (foot stiffness "
                                                 "scaled to it)")],
             lambda d: dict(d, zeta=0.03)),
    ]


# ---- frame3 --------------------------------------------------------------------------------------------------
TORSION_KT = (2.86e4, 3.2e4, 1.6e4)   # N m/rad: with the plates' inertias, torsion modes near 40, 95 and 159 Hz
TORSION_BETA = 1e-4                   # s: ct = beta kt, damping ratio beta w/2 (1.3 % at 40 Hz, 3 % at 95 Hz)


def _frame3_cases():
    def outside_torsion(v):
        e, scale = v["e"], v["kt_scale"]
        kt = tuple(scale * k for k in TORSION_KT)
        ct = tuple(TORSION_BETA * k for k in kt)
        return {"hidden": "each storey also twists about the vertical (its own rotation, torsional springs %s N m/rad "
                          "between the storeys, damping %g s x stiffness), and the forces and accelerometers sit "
                          "%.3g m off the centre line, so two torsion modes (near 40 and 95 Hz at the default "
                          "stiffness) show in the x accelerances" % ("/".join("%.3g" % k for k in kt), TORSION_BETA, e),
                "effects": lambda p: {"torsion": {"kt": kt, "ct": ct, "e": e}},
                "extra": {"eccentricity_m": e, "kt": list(kt), "ct": list(ct), "kt_scale": scale}}

    return [
        Case("frame3", "nominal", None, lambda v: {"hidden": "nothing: the nominal model with its parameters off "
                                                             "nominal"}, kinds=("frf",), control=True),
        Case("frame3", "outside_torsion", None, outside_torsion, {"e": 0.05, "kt_scale": 1.0},
             [Size("e", 0.03, 0.08, "m", "eccentricity of the force and sensor points"),
              Size("kt_scale", 0.8, 1.25, "", "factor on the torsional stiffnesses (modes scale as its root)")],
             kinds=("frf",),
             notes="No operator adds a rotation coordinate to an x-only chain: the honest result is no confident "
                   "extension (unexplained, or a poor approximating candidate)."),
    ]


# ---- tower5 --------------------------------------------------------------------------------------------------
def _tower5_cases():
    return [
        Case("tower5", "nominal", None, lambda v: {"hidden": "nothing: the nominal model with its parameters off "
                                                             "nominal"}, kinds=("frf",), control=True),
    ]


# ---- two effects at once ---------------------------------------------------------------------------------------
def paired(a, b, name):
    """Case `name`: the hidden effects of cases a and b of one example together (their effects, sizes and values
    merged; each keeps its own sizes' names and its own from_draw). The expected result is both operators, in any
    order ("A+B"). The offsets of the estimable parameters are the pair's own (seeded by its name)."""
    names_a = {sz.name for sz in a.sizes}
    if names_a & {sz.name for sz in b.sizes}:
        raise ValueError("paired cases %s and %s share a size's name" % (a.name, b.name))

    def split(values):
        return ({k: v for k, v in values.items() if k in a.defaults or k in names_a},
                {k: v for k, v in values.items() if not (k in a.defaults or k in names_a)})

    def make(values):
        va, vb = split(values)
        sa, sb = a.make(va), b.make(vb)
        ea, eb = sa.get("effects", lambda p: {}), sb.get("effects", lambda p: {})
        xa, xb = sa.get("extra", {}), sb.get("extra", {})

        def effects(p):
            both = dict(ea(p))
            for key, value in eb(p).items():
                if key in both:
                    raise ValueError("paired cases %s and %s change the same part (%s)" % (a.name, b.name, key))
                both[key] = value
            return both

        def extra(p):
            return dict(xa(p) if callable(xa) else xa, **(xb(p) if callable(xb) else xb))

        hz = [h for h in (sa.get("effect_hz"), sb.get("effect_hz")) if h is not None]
        return {"hidden": sa["hidden"] + "; and " + sb["hidden"], "effects": effects, "extra": extra,
                "effect_hz": hz[0] if hz else None,
                "hidden_values": dict(sa.get("hidden_values", {}), **sb.get("hidden_values", {}))}

    def from_draw(drawn):
        da, db = split(drawn)
        return dict(a.from_draw(da), **b.from_draw(db))

    pair = Case(a.example, name, "%s+%s" % (a.operator, b.operator), make, dict(a.defaults, **b.defaults),
                list(a.sizes) + list(b.sizes), from_draw,
                kinds=tuple(k for k in a.kinds if k in b.kinds),
                notes="Two effects at once: %s and %s; both are to be named." % (a.name, b.name))
    pair.parts = (a.name, b.name)
    return pair


def _paired_cases(single):
    by = {(c.example, c.name): c for c in single}
    return [
        paired(by[("spindle", "untie_parameter")], by[("spindle", "added_mass")], "mount_and_mass"),
        paired(by[("spindle", "compliant_ground")], by[("spindle", "sensor_lowpass")], "base_and_lowpass"),
        paired(by[("mdof2", "compliant_ground")], by[("mdof2", "sensor_lowpass")], "wall_and_lowpass"),
    ]


_SINGLE = _mdof2_cases() + _spindle_cases() + _frame3_cases() + _tower5_cases()
CASES = {(c.example, c.name): c for c in _SINGLE + _paired_cases(_SINGLE)}


def get(example, name):
    try:
        return CASES[(example, name)]
    except KeyError:
        names = ", ".join(n for e, n in CASES if e == example)
        raise KeyError("unknown case %r for example %r (cases: %s)" % (name, example, names)) from None
