"""Errors of the measurement chain: what the sensors, cables and analyser do to a truth's data (docs/truthgen.md,
"Measurement chain"). They apply to any case, after the noise, and leave the structure alone.

- gain OUTPUT=FACTOR: the output's sensor reads FACTOR times the truth (a calibration error; -1 a sensor mounted
  reversed). Its noise is scaled with it (the noise belongs to the sensor's signal), so the channel's SNR and
  an FRF's coherence are unchanged.
- input_gain INPUT=FACTOR: the recorded force is FACTOR times the applied one (force transducer calibration; -1 a
  polarity error). The system is driven by the applied force, so an FRF's columns of that input are divided by
  FACTOR and a time record's input column is multiplied by it.
- frf_form OUTPUT=mobility|accelerance (FRFs, displacement outputs): the receptance channel is written times
  i w (mobility) or -w^2 (accelerance), the file still calling it the displacement output.
- unit OUTPUT=mm|g: the channel is written in millimetres (factor 1000, any output) or in g (factor 1/9.80665,
  only a channel that is an acceleration: an acceleration output, or a displacement output with frf_form
  accelerance) while the file's unit is the SI one.
- swap OUT_A,OUT_B: the two outputs' columns are exchanged in the file (two cables swapped), names kept. The
  other effects name the sensor (the true output), so they act before the swap.

Every effect is a per-line factor on an output row or an input column of H (or on a record's column), so
coherence columns move with a swap and are otherwise unchanged (coherence is invariant to a channel's scale).
"""
import math
import re
import zlib

import numpy as np

STANDARD_GRAVITY = 9.80665
FACTOR_PATTERN = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")
NAME_PATTERN = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)=(.*)$")
DRAW_RANGES = ((0.7, 0.9), (1.1, 1.3))   # --gain OUTPUT=draw: one of them (equally likely), then uniform in it
KIND_ORDER = ("gain", "input_gain", "frf_form", "unit", "swap")
UNITS = {"mm": 1000.0, "g": 1.0 / STANDARD_GRAVITY}
FORMS = {"mobility": (1, "i*omega"), "accelerance": (2, "-omega^2")}


class ChainError(ValueError):
    pass


def drawn_factor(n, channel):
    """--gain CHANNEL=draw with --draw n: `default_rng([n, crc32("chain/CHANNEL")])` picks a side (uniform() <
    0.5: 0.7-0.9, else 1.1-1.3), then the factor uniformly in it, rounded to 4 significant digits. Its own
    generator, so the truth's draw (crc32("EXAMPLE/CASE")) is untouched."""
    rng = np.random.default_rng([n, zlib.crc32(("chain/%s" % channel).encode())])
    low, high = DRAW_RANGES[0] if rng.uniform() < 0.5 else DRAW_RANGES[1]
    factor = float("%.4g" % rng.uniform(low, high))
    return factor, {"generator": 'numpy.random.default_rng([%d, crc32("chain/%s")])' % (n, channel),
                    "ranges": [list(r) for r in DRAW_RANGES]}


def _split(option, text, names, what, form):
    match = NAME_PATTERN.match(text.strip())
    if not match:
        raise ChainError("%s %r: expected %s" % (option, text, form))
    name, value = match.group(1), match.group(2)
    if name not in names:
        raise ChainError("%s %s: not an %s of the example (%ss: %s)" % (option, name, what, what, ", ".join(names)))
    return name, value


def _factor(option, name, text, draw_n):
    if text == "draw":
        if draw_n is None:
            raise ChainError("%s %s=draw: needs --draw N" % (option, name))
        return drawn_factor(draw_n, name)
    if not FACTOR_PATTERN.match(text):
        raise ChainError("%s %s=%s: FACTOR must be a decimal number (or draw, with --draw N)" % (option, name, text))
    value = float(text)
    if not math.isfinite(value) or value == 0.0:
        raise ChainError("%s %s=%s: FACTOR must be finite and not zero" % (option, name, text))
    return value, None


def parse(outputs, inputs, output_orders, kind, gains=(), input_gains=(), force_sign=None, swaps=(), units=(),
          forms=(), draw_n=None):
    """The chain as a list of entries (the truth JSON's `measurement_chain`), in application order: by kind
    (KIND_ORDER), then in the model's order of outputs or inputs. Raises ChainError on bad usage."""
    entries = []
    seen = set()

    def once(key, option, name):
        if key in seen:
            raise ChainError("%s %s: given twice" % (option, name))
        seen.add(key)

    def factor_entry(kind, option, text, names, what, form, twice):
        """A --gain or --input-gain entry: CHANNEL=FACTOR, the factor given or drawn."""
        name, value = _split(option, text, names, what, form)
        once((kind, name), twice, name)
        factor, drawn = _factor(option, name, value, draw_n)
        entry = {"kind": kind, what: name, "factor": factor}
        if drawn:
            entry["drawn"] = drawn
        entries.append(entry)

    for text in gains:
        factor_entry("gain", "--gain", text, outputs, "output", "OUTPUT=FACTOR", "--gain")
    if force_sign is not None:
        if force_sign.strip() not in ("-1", "1", "+1"):
            raise ChainError("--force-sign %s: expected -1 (or 1, no change)" % force_sign)
        if float(force_sign) < 0:
            for name in inputs:
                once(("input_gain", name), "--force-sign -1 and --input-gain", name)
                entries.append({"kind": "input_gain", "input": name, "factor": -1.0})
    for text in input_gains:
        factor_entry("input_gain", "--input-gain", text, inputs, "input", "INPUT=FACTOR",
                     "--input-gain (or --force-sign)")
    form_order = {}
    for text in forms:
        name, value = _split("--frf-form", text, outputs, "output", "OUTPUT=mobility|accelerance")
        once(("frf_form", name), "--frf-form", name)
        if kind != "frf":
            raise ChainError("--frf-form applies to FRFs only")
        if value not in FORMS:
            raise ChainError("--frf-form %s=%s: expected mobility or accelerance" % (name, value))
        if output_orders[outputs.index(name)] != 0:
            raise ChainError("--frf-form %s: not a displacement output (the form applies to a receptance channel)"
                             % name)
        form_order[name] = FORMS[value][0]
        entries.append({"kind": "frf_form", "output": name, "form": value, "factor": FORMS[value][1]})
    for text in units:
        name, value = _split("--unit", text, outputs, "output", "OUTPUT=mm|g")
        once(("unit", name), "--unit", name)
        if value not in UNITS:
            raise ChainError("--unit %s=%s: expected mm or g" % (name, value))
        order = output_orders[outputs.index(name)] + form_order.get(name, 0)
        if value == "g" and order != 2:
            raise ChainError("--unit %s=g: %s is not an acceleration (g applies to acceleration outputs, or to a "
                             "displacement output given as --frf-form %s=accelerance)" % (name, name, name))
        entries.append({"kind": "unit", "output": name, "unit": value, "factor": UNITS[value]})
    swapped = set()
    for text in swaps:
        pair = [s.strip() for s in text.split(",")]
        if len(pair) != 2:
            raise ChainError("--swap %r: expected OUT_A,OUT_B" % text)
        for name in pair:
            if name not in outputs:
                raise ChainError("--swap %s: not an output of the example (outputs: %s)" % (name, ", ".join(outputs)))
        if pair[0] == pair[1]:
            raise ChainError("--swap %s,%s: an output swapped with itself" % tuple(pair))
        for name in pair:
            if name in swapped:
                raise ChainError("--swap: %s is in two swaps" % name)
            swapped.add(name)
        entries.append({"kind": "swap", "outputs": sorted(pair, key=outputs.index)})

    def position(e):
        if "output" in e:
            return outputs.index(e["output"])
        if "input" in e:
            return inputs.index(e["input"])
        return outputs.index(e["outputs"][0])
    entries.sort(key=lambda e: (KIND_ORDER.index(e["kind"]), position(e)))
    for e in entries:
        e["id"] = candidate_id(e)
    return entries


def candidate_id(entry):
    """measurement_chain:KIND:CHANNEL (a swap: measurement_chain:swap:OUT_A,OUT_B in model order)."""
    channel = entry.get("output") or entry.get("input") or ",".join(entry["outputs"])
    return "measurement_chain:%s:%s" % (entry["kind"], channel)


def describe(entry):
    k = entry["kind"]
    if k == "gain":
        return "%s reads %g times the truth" % (entry["output"], entry["factor"])
    if k == "input_gain":
        return "the recorded %s is %g times the applied force" % (entry["input"], entry["factor"])
    if k == "frf_form":
        return "%s's receptance is given as %s (times %s)" % (entry["output"], entry["form"], entry["factor"])
    if k == "unit":
        return "%s is written in %s (times %.6g)" % (entry["output"], entry["unit"], entry["factor"])
    return "the columns of %s and %s are swapped" % tuple(entry["outputs"])


def _output_factor(entry, w):
    """The factor an output's row gets (scalar, or per line for an FRF form)."""
    if entry["kind"] == "frf_form":
        return 1j * w if entry["form"] == "mobility" else -(w ** 2)
    return entry["factor"]


def apply_frf(data, entries, outputs, inputs):
    """Apply the chain to make_frf's result in place: clean and noisy H (O x I per line), coherence moved by swaps."""
    w = 2 * np.pi * np.asarray(data["f_hz"], dtype=float)
    for key in ("clean", "noisy"):
        H = data[key]
        for e in entries:
            if e["kind"] in ("gain", "unit", "frf_form"):
                factor = _output_factor(e, w)
                H[:, outputs.index(e["output"]), :] *= factor[:, None] if np.ndim(factor) else factor
            elif e["kind"] == "input_gain":
                H[:, :, inputs.index(e["input"])] /= e["factor"]
    for e in entries:
        if e["kind"] == "swap":
            a, b = (outputs.index(name) for name in e["outputs"])
            for key in ("clean", "noisy", "coherence"):
                data[key][:, [a, b], :] = data[key][:, [b, a], :]


def apply_time(data, entries, outputs, inputs):
    """Apply the chain to make_time's result in place: the outputs (clean and noisy) and the written inputs u.
    The record was simulated with the applied force, so scaling u afterwards is the recorded force."""
    for e in entries:
        if e["kind"] in ("gain", "unit"):
            o = outputs.index(e["output"])
            data["clean"][:, o] *= e["factor"]
            data["noisy"][:, o] *= e["factor"]
        elif e["kind"] == "input_gain":
            data["u"] = data["u"].copy()
            data["u"][:, inputs.index(e["input"])] *= e["factor"]
        elif e["kind"] == "frf_form":
            raise ChainError("--frf-form applies to FRFs only")
    for e in entries:
        if e["kind"] == "swap":
            a, b = (outputs.index(name) for name in e["outputs"])
            for key in ("clean", "noisy"):
                data[key][:, [a, b]] = data[key][:, [b, a]]
