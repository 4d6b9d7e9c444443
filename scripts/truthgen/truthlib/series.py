"""A monitored output-only series (docs/truthgen.md, "A monitored series"): N operational records of one truth
whose stiffnesses follow a temperature-like condition, optionally with a structural change from a chosen set on.

The condition of set i (0-based) is

    T_i = mean + daily sin(2 pi i / period) + trend i + noise e_i,   e_i ~ N(0, 1), rounded to 0.01,

a slow daily-like cycle over `period` sets, a drift of `trend` per set and a scatter. The rounded value is the one
written in the file's `# condition temperature=` line and the one that drives the truth, so the written condition is
exact. Every stiffness (the parameters named k...) is scaled by

    k(T) = k0 (1 - coefficient (T - mean)),

so all frequencies move together by about -coefficient (T - mean) / 2 relative. A change multiplies one parameter
by a factor from its set on (a stiffness drop of 8 %: k11=0.92).
"""
import math

import numpy as np

DEFAULT_TEMPERATURE = (20.0, 4.0, 12.0, 0.0, 0.3)   # mean, daily amplitude, period (sets), trend per set, noise


class SeriesError(Exception):
    pass


def parse_temperature(text):
    """MEAN,DAILY,PERIOD,TREND,NOISE (all numbers, PERIOD > 0, DAILY and NOISE >= 0)."""
    if text is None:
        return DEFAULT_TEMPERATURE
    try:
        values = tuple(float(v) for v in text.split(","))
    except ValueError:
        values = ()
    if len(values) != 5 or not all(math.isfinite(v) for v in values) or values[2] <= 0 or values[1] < 0 \
            or values[4] < 0:
        raise SeriesError("--temperature %r: expected MEAN,DAILY,PERIOD,TREND,NOISE (numbers; PERIOD > 0, DAILY and "
                          "NOISE >= 0)" % text)
    return values


def parse_change(text, nominal):
    """NAME=FACTOR@SET: the parameter times FACTOR (> 0) from set SET (0-based) on."""
    if text is None:
        return None
    try:
        assignment, at = text.split("@")
        name, factor = assignment.split("=")
        factor, at = float(factor), int(at)
    except ValueError:
        raise SeriesError("--change %r: expected NAME=FACTOR@SET, e.g. k11=0.92@14" % text)
    if name not in nominal:
        raise SeriesError("--change %s: not a parameter (parameters: %s)" % (name, ", ".join(sorted(nominal))))
    if not (math.isfinite(factor) and factor > 0) or at < 0:
        raise SeriesError("--change %r: FACTOR must be positive and SET a non-negative index" % text)
    return {"parameter": name, "factor": factor, "from_set": at}


def temperatures(count, spec, seed):
    """The conditions of `count` sets, rounded to 0.01; the scatter from its own stream (seed, 0)."""
    mean, daily, period, trend, noise = spec
    rng = np.random.default_rng([seed, 0])
    e = rng.standard_normal(count)
    i = np.arange(count)
    t = mean + daily * np.sin(2 * np.pi * i / period) + trend * i + noise * e
    return [round(float(v), 2) for v in t]


def stiffness_names(parameters):
    return sorted(name for name in parameters if name.startswith("k"))


def set_parameters(p, temperature, spec, coefficient, change, index):
    """The truth of one set: the stiffnesses at its temperature, then the change if it has begun."""
    factor = 1.0 - coefficient * (temperature - spec[0])
    if factor <= 0:
        raise SeriesError("the temperature %.2f makes the stiffness factor %g (not positive): lower "
                          "--temperature-coefficient" % (temperature, factor))
    q = dict(p)
    for name in stiffness_names(q):
        q[name] *= factor
    changed = change is not None and index >= change["from_set"]
    if changed:
        q[change["parameter"]] *= change["factor"]
    return q, factor, changed


def set_path(output, index, count):
    """OUT.csv -> OUT_07.csv (as many digits as the largest index needs, at least 2)."""
    base = output[:-4] if output.endswith(".csv") else output
    return "%s_%0*d.csv" % (base, max(2, len(str(count - 1))), index)
