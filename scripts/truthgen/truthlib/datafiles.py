"""Writers for the measured-data CSV formats of docs/interfaces.md ("Measured data") and the truth sidecar JSON."""
import json
import math

HEADER_NOTE = "# measured-style data made by scripts/truthgen (truth model and noise: the .truth.json beside it)"


def _number(value, digits):
    text = "%.*g" % (digits, value)
    return "0" if text in ("-0", "0") else text


def _set_lines(settings):
    return ["# set %s=%s" % (name, text) for name, text in settings]


def write_frf_csv(path, data, outputs, inputs, settings, digits=8, coherence=True):
    """f_hz, then per output and input OUT/IN.re, OUT/IN.im and (unless coherence=False, as many analysers'
    exports) OUT/IN.coh."""
    lines = [HEADER_NOTE] + _set_lines(settings)
    columns = ["f_hz"]
    for o in outputs:
        for i in inputs:
            columns += ["%s/%s.re" % (o, i), "%s/%s.im" % (o, i)] + (["%s/%s.coh" % (o, i)] if coherence else [])
    lines.append(",".join(columns))
    H, coh = data["noisy"], data["coherence"]
    for k, f in enumerate(data["f_hz"]):
        row = ["%.10g" % f]
        for oi in range(len(outputs)):
            for ii in range(len(inputs)):
                h = H[k, oi, ii]
                row += [_number(h.real, digits), _number(h.imag, digits)]
                if coherence:
                    row.append(_number(coh[k, oi, ii], 6))
        lines.append(",".join(row))
    _write(path, lines)


def time_decimals(dt):
    """Decimals for t so that every written time is within 0.5 % of dt of its grid point."""
    return max(0, int(math.ceil(-math.log10(0.01 * dt))))


def write_time_csv(path, data, outputs, inputs, settings, digits=5, comments=()):
    """t, inputs, outputs; inputs held over each sample interval (zero-order hold, the default). `comments`: more
    header lines after the `# set` lines (a series' `# condition` line)."""
    lines = [HEADER_NOTE] + _set_lines(settings) + list(comments)
    lines.append(",".join(["t"] + list(inputs) + list(outputs)))
    decimals = time_decimals(data["dt"])
    for k, t in enumerate(data["t"]):
        row = ["%.*f" % (decimals, t)]
        row += [_number(v, 6) for v in data["u"][k]]
        row += [_number(v, digits) for v in data["noisy"][k]]
        lines.append(",".join(row))
    _write(path, lines)


def write_truth_json(path, document):
    with open(path, "w") as out:
        json.dump(document, out, indent=2, sort_keys=False)
        out.write("\n")


def _write(path, lines):
    with open(path, "w", newline="\n") as out:
        out.write("\n".join(lines))
        out.write("\n")
