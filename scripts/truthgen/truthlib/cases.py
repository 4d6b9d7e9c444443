"""Truth variants: one per extension operator of `mbgen diagnose` and example, controls, and one effect outside the
operator library. See docs/truthgen.md for what each hides and how large it is.

Every case also moves the nominal model's estimable parameters off their nominal values by 3 to 10 %, with a
sign and size drawn per case from a generator seeded by the case's name (so each case has its own truth, and
a fit cannot succeed by returning the nominal values).
"""
import math
import zlib

import numpy as np

from . import models


def critical_fraction(zeta, k, m):
    """Damping c giving damping ratio zeta to a mass m on a spring k."""
    return 2 * zeta * math.sqrt(k * m)


class Case:
    def __init__(self, example, name, operator, effect_hz, hidden, effects, extra=None, default_set=None,
                 hidden_values=None, kinds=("frf", "time"), notes=""):
        self.example = example
        self.name = name
        self.operator = operator        # expected candidate id of `mbgen diagnose`, or None
        self.effect_hz = effect_hz      # where the effect shows (Hz), None if everywhere / nowhere
        self.hidden = hidden            # one sentence: what the truth has that the nominal model lacks
        self.effects = effects          # function(parameters) -> effects dict for models.build_*
        self.extra = extra or {}        # values of the hidden effect, for the truth JSON
        self.default_set = default_set or {}   # written as `# set` lines unless the user sets them
        self.hidden_values = hidden_values or {}  # model parameters whose truth differs, NOT written
        self.kinds = kinds
        self.notes = notes

    def truth_parameters(self, overrides=None):
        """Nominal values, estimable ones moved off by 3-10 % (per case), then `# set` values applied."""
        ex = models.EXAMPLES[self.example]
        p = dict(ex["nominal"])
        rng = np.random.default_rng(zlib.crc32(("%s/%s" % (self.example, self.name)).encode()))
        for name in ex["estimable"]:
            size = rng.uniform(0.03, 0.10)
            sign = 1.0 if rng.uniform() < 0.5 else -1.0
            p[name] = float("%.4g" % (p[name] * (1 + sign * size)))
        p.update(self.hidden_values)
        p.update(self.default_set)
        for name, value in (overrides or {}).items():
            if name not in p:
                raise KeyError(name)
            p[name] = value
        return p

    def build(self, p):
        return models.EXAMPLES[self.example]["build"](p, self.effects(p))


def _mdof2_cases():
    k_g, m_g = 1.6e7, 5.0
    c_g = critical_fraction(0.02, k_g, m_g)
    m_r, f_r = 0.05, 130.0
    k_r = m_r * (2 * math.pi * f_r) ** 2
    c_r = critical_fraction(0.01, k_r, m_r)
    ma = 0.08
    mw_c, mw_fc = 60.0, 120.0
    mw_k = 2 * math.pi * mw_fc * mw_c
    return [
        Case("mdof2", "nominal", None, None, "nothing: the nominal model with its parameters off nominal",
             lambda p: {}),
        Case("mdof2", "compliant_ground", "compliant_ground:wall", None,
             "the wall is a %.0f kg mass on a spring (k = %.3g N/m, zeta 2 %%) along x" % (m_g, k_g),
             lambda p: {"ground_body": {"m": m_g, "k": k_g, "c": c_g}},
             {"m_wall": m_g, "k_wall": k_g, "c_wall": c_g}),
        Case("mdof2", "free_parameter", "free_parameter:c12", None,
             "the helix is damped: c12 = 5 N s/m (the nominal model fixes it at 0)",
             lambda p: {}, {"c12": 5.0}, hidden_values={"c12": 5.0}),
        Case("mdof2", "added_mass", "added_mass:mass1", None,
             "a %.2f kg point mass at mass1's point (input F1)" % ma,
             lambda p: {"added_mass": {"m": ma}}, {"ma_mass1": ma},
             notes="mass1 is a point with one coordinate and m1 is estimable, so the added mass is exactly a "
                   "larger m1: the fit absorbs it (fitted m1 = m1 + ma) and no extension is justified."),
        Case("mdof2", "resonator", "resonator:mass1", f_r,
             "a local %.2f kg mass on a spring-damper along x on mass1, own mode %.0f Hz, zeta 1 %%" % (m_r, f_r),
             lambda p: {"resonator": {"m": m_r, "k": k_r, "c": c_r}},
             {"mr_mass1": m_r, "kr_mass1": k_r, "cr_mass1": c_r}),
        Case("mdof2", "outside_maxwell", None, mw_fc,
             "a Maxwell element (spring %.4g N/m in series with damper %.3g N s/m) between wall and mass1: a "
             "damping that acts below %.0f Hz and turns into a spring above" % (mw_k, mw_c, mw_fc),
             lambda p: {"maxwell": {"a": "wall", "b": "mass1", "k": mw_k, "c": mw_c}},
             {"maxwell_k": mw_k, "maxwell_c": mw_c, "maxwell_corner_hz": mw_fc}),
    ]


def _spindle_cases():
    m_b, f_b = 60.0, 190.0
    # The base's support stiffness is tuned so that the mode in which the base moves along x (the whole
    # machine on its base) lies at 190 Hz; selftest checks it.
    k_b = 1.68e8
    c_b = critical_fraction(0.03, k_b, m_b)
    loose = 0.4
    kr, cr = 2e5, 2e5 * 1000 / 60e6
    ma = 0.5
    m_r, f_r = 0.2, 380.0
    k_r = m_r * (2 * math.pi * f_r) ** 2
    c_r = critical_fraction(0.01, k_r, m_r)
    k_c = 6e6
    c_c = 1000.0
    mw_k, mw_fc = 6e6, 300.0
    mw_c = mw_k / (2 * math.pi * mw_fc)
    m_sen, f_sen = 0.01, 1000.0
    k_sen = m_sen * (2 * math.pi * f_sen) ** 2
    c_sen = critical_fraction(0.05, k_sen, m_sen)
    return [
        Case("spindle", "nominal", None, None, "nothing: the nominal model with its parameters off nominal",
             lambda p: {}),
        Case("spindle", "compliant_ground", "compliant_ground:base", f_b,
             "the base is a %.0f kg body (x y z at the mount centroid) on an isotropic spring3 "
             "(k = %.3g N/m, zeta 3 %%) to a fixed ground: a new mode near %.0f Hz (thesis Sec. 5.4.3)"
             % (m_b, k_b, f_b),
             lambda p: {"ground_body": {"m": m_b, "k": k_b, "c": c_b}},
             {"m_base": m_b, "k_base": k_b, "c_base": c_b}),
        Case("spindle", "untie_parameter", "untie_parameter:k_hby", None,
             "mount1 is loose vertically: its k_hby is %.0f %% of the other mounts'" % (loose * 100),
             lambda p: {"mount_overrides": {"mount1": {"k_hby": loose * p["k_hby"]}}},
             {"k_hby_mount1_factor": loose}),
        Case("spindle", "gyroscopic", "gyroscopic:spindle", None,
             "the spindle spins at n_sp rev/s (gyroscopic coupling J_szz*2*pi*n_sp on rx, ry); data at "
             "n_sp = 0 and n_sp = 300 (default `# set n_sp=300`)",
             lambda p: {"spin": True}, {}, default_set={"n_sp": 300.0}),
        Case("spindle", "moment_stiffness", "moment_stiffness:bearing_fx", None,
             "bearing_fx also resists tilting about y: torsion spindle-housing kr = %.3g N m/rad, "
             "cr = %.3g N m s/rad" % (kr, cr),
             lambda p: {"torsions": [{"name": "bearing_fx_ry", "a": "spindle", "b": "housing", "about": "y",
                                      "k": kr, "c": cr}]},
             {"kr_bearing_fx": kr, "cr_bearing_fx": cr}),
        Case("spindle", "added_mass", "added_mass:spindle", None,
             "a %.2f kg point mass on the spindle at the nose (the input point (0, 0, 0.306))" % ma,
             lambda p: {"added_mass": {"m": ma, "point": models.NOSE}}, {"ma_spindle": ma}),
        Case("spindle", "resonator", "resonator:spindle", f_r,
             "a local %.2f kg mass on a spring-damper along x at the spindle nose, own mode %.0f Hz, zeta 1 %%"
             % (m_r, f_r),
             lambda p: {"resonator": {"m": m_r, "k": k_r, "c": c_r, "point": models.NOSE}},
             {"mr_spindle": m_r, "kr_spindle": k_r, "cr_spindle": c_r}),
        Case("spindle", "connection", "connection:base-spindle", None,
             "an isotropic spring3 (k = %.3g N/m, c = %.3g N s/m) between the spindle's centre of mass and "
             "the base" % (k_c, c_c),
             lambda p: {"connection": {"k": k_c, "c": c_c}}, {"k_base_spindle": k_c, "c_base_spindle": c_c}),
        Case("spindle", "outside_maxwell", None, mw_fc,
             "a Maxwell element (spring %.3g N/m in series with damper %.4g N s/m) parallel to bearing_fx: a "
             "bearing damping that acts below %.0f Hz and turns into a spring above" % (mw_k, mw_c, mw_fc),
             lambda p: {"maxwell": {"name": "bearing_fx_maxwell", "a": "spindle", "pa": (-0.025, 0, 0.127),
                                    "b": "housing", "pb": (-0.040, 0, 0.127), "along": "x",
                                    "k": mw_k, "c": mw_c}},
             {"maxwell_k": mw_k, "maxwell_c": mw_c, "maxwell_corner_hz": mw_fc}),
        Case("spindle", "sensor_dynamics", "sensor_dynamics:xs_front", f_sen,
             "xs_front is read by a %.0f g accelerometer on a mounting (spring-damper along x at its point on the "
             "spindle) with its own resonance at %.0f Hz, zeta 5 %%: a second-order low-pass on that output"
             % (m_sen * 1000, f_sen),
             lambda p: {"sensor": {"output": "xs_front", "m": m_sen, "k": k_sen, "c": c_sen}},
             {"ms_xs_front": m_sen, "ks_xs_front": k_sen, "cs_xs_front": c_sen, "fs_xs_front": f_sen,
              "zs_xs_front": 0.05}),
    ]


CASES = {(c.example, c.name): c for c in _mdof2_cases() + _spindle_cases()}


def get(example, name):
    try:
        return CASES[(example, name)]
    except KeyError:
        names = ", ".join(n for e, n in CASES if e == example)
        raise KeyError("unknown case %r for example %r (cases: %s)" % (name, example, names)) from None
