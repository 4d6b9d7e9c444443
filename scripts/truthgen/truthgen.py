#!/usr/bin/env python3
"""truthgen: write one measured-style data set (FRF or time record) of a truth model, independent of mbgen.

    python3 scripts/truthgen/truthgen.py --example mdof2 --case nominal --kind frf --snr-db 40 --seed 1 -o frf.csv
    python3 scripts/truthgen/truthgen.py --example spindle --case sensor_delay --kind frf --draw 3 -o frf.csv
    python3 scripts/truthgen/truthgen.py --example spindle --case nominal --kind frf --gain xs_rear=0.8 -o frf.csv
    python3 scripts/truthgen/truthgen.py --example mdof2 --case nominal --kind oma --draw 1 --seed 2 -o oma.csv
    python3 scripts/truthgen/truthgen.py --example mdof2 --case nominal --kind oma --draw 1 --seed 3 --duration 20 \
        --series 24 --change k11=0.92@16 -o series/set.csv
    python3 scripts/truthgen/truthgen.py --list

Writes FILE.csv in the formats of docs/interfaces.md ("Measured data") and FILE.truth.json (truth values, the
case and its hidden effect; for people and for checking recovered values, never for deciding verdicts).
See docs/truthgen.md.
"""
import argparse
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from truthlib.bootstrap import ensure_numpy  # noqa: E402

ensure_numpy()

import numpy as np  # noqa: E402

from truthlib import cases, chain, datafiles, generate, models, operational, response, series  # noqa: E402

SET_PATTERN = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)=([-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?)$")


class UsageError(Exception):
    pass


def parse_args(argv):
    ap = argparse.ArgumentParser(prog="truthgen.py", description=__doc__.split("\n")[1])
    ap.add_argument("--list", action="store_true", help="list the cases and exit")
    ap.add_argument("--example", choices=sorted(models.EXAMPLES))
    ap.add_argument("--case", help="truth case (see --list)")
    ap.add_argument("--kind", choices=["frf", "time", "oma"], default="frf",
                    help="frf, time (force and responses) or oma: output-only, the responses to unmeasured white "
                         "Gaussian forces at every input, no force column (default frf)")
    ap.add_argument("--snr-db", default="40", help="signal-to-noise ratio in dB per channel, or inf (default 40)")
    ap.add_argument("--input-snr-db", type=float, metavar="DB",
                    help="time: the written force carries white measurement noise at this SNR (sigma = RMS(force) / "
                         "10^(DB/20), its own stream from --seed); the structure is driven by the clean force")
    ap.add_argument("--seed", type=int, default=1, help="seed of numpy.random.default_rng (default 1)")
    ap.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                    help="set a model parameter for this data set; written as `# set NAME=VALUE`")
    ap.add_argument("-o", "--output", help="output CSV file")
    ap.add_argument("--f-min", type=float, help="FRF grid start, Hz (mdof2 10, spindle 50, frame3 0.03125)")
    ap.add_argument("--f-max", type=float, help="FRF grid end, Hz (mdof2 400, spindle 1200, frame3 128)")
    ap.add_argument("--df", type=float, help="FRF grid spacing, Hz (mdof2 0.25, spindle 1, frame3 0.03125)")
    ap.add_argument("--fs", type=float, help="time record sample rate, Hz (mdof2 4096, spindle 8192; oma: 1024, 4096)")
    ap.add_argument("--duration", type=float, help="time record length, s (default 2; oma: mdof2 300, spindle 60)")
    ap.add_argument("--amplitude", type=float, help="force amplitude, N (mdof2 10, spindle 100; oma: the forces' RMS)")
    ap.add_argument("--excitation", choices=["binary", "gaussian"], default="binary",
                    help="white zero-order-hold force: random +-amplitude (default) or Gaussian")
    ap.add_argument("--draw", type=int, metavar="N",
                    help="draw the truth (parameter offsets and the effect's sizes, within the case's ranges) from "
                         "seed N instead of the case's fixed truth; the noise still comes from --seed")
    ap.add_argument("--averages", type=int, default=1, metavar="N",
                    help="FRF: the average of N measurements: noise variance sigma^2/N, coherence as for one "
                         "measurement (default 1)")
    ap.add_argument("--analyser", type=int, metavar="N",
                    help="FRF: an analyser's H1 estimate from N segments, its coherence from the same segments "
                         "(scatters as a measured one does; N >= 2)")
    ap.add_argument("--no-coherence", action="store_true", help="FRF: write no .coh columns")
    series_options = ap.add_argument_group("a monitored series (--kind oma; docs/truthgen.md)")
    series_options.add_argument("--series", type=int, metavar="N",
                                help="write N output-only records OUT_00.csv .. of the one truth, each with a "
                                     "`# condition temperature=` line that scales the stiffnesses, and "
                                     "OUT.series.json; set i's noise from seed (--seed, i + 1)")
    series_options.add_argument("--temperature", metavar="MEAN,DAILY,PERIOD,TREND,NOISE",
                                help="the condition of set i: MEAN + DAILY sin(2 pi i / PERIOD) + TREND i + NOISE "
                                     "N(0,1), rounded to 0.01 (default 20,4,12,0,0.3)")
    series_options.add_argument("--temperature-coefficient", type=float, default=0.003, metavar="A",
                                help="every stiffness (parameters k...) times 1 - A (T - MEAN) (default 0.003 per "
                                     "unit)")
    series_options.add_argument("--change", metavar="NAME=FACTOR@SET",
                                help="a structural change: the parameter times FACTOR from set SET (0-based) on, "
                                     "e.g. k11=0.92@16")
    chain_options = ap.add_argument_group("measurement chain (applied after the noise; docs/truthgen.md)")
    chain_options.add_argument("--gain", action="append", default=[], metavar="OUTPUT=FACTOR",
                               help="the output's sensor reads FACTOR times the truth, its noise included (-1: "
                                    "mounted reversed; FACTOR=draw with --draw N: 0.7-0.9 or 1.1-1.3)")
    chain_options.add_argument("--input-gain", action="append", default=[], metavar="INPUT=FACTOR",
                               help="the recorded force is FACTOR times the applied one (FRF columns divided by it)")
    chain_options.add_argument("--force-sign", metavar="-1",
                               help="-1: every recorded force is the negative of the applied one")
    chain_options.add_argument("--swap", action="append", default=[], metavar="OUT_A,OUT_B",
                               help="the two outputs' columns are exchanged in the file, names kept")
    chain_options.add_argument("--unit", action="append", default=[], metavar="OUTPUT=mm|g",
                               help="the channel is written in mm (times 1000) or in g (divided by 9.80665; "
                                    "acceleration channels only) while the file means SI units")
    chain_options.add_argument("--frf-form", action="append", default=[], metavar="OUTPUT=mobility|accelerance",
                               help="FRF: the displacement output's receptance is written times i*omega or -omega^2")
    return ap.parse_args(argv)


def parse_settings(texts, case):
    """`# set` lines: the case's defaults (e.g. n_sp=300 for the gyroscopic case), then the user's."""
    nominal = models.EXAMPLES[case.example]["nominal"]
    settings = {name: repr(value) if value != int(value) else str(int(value))
                for name, value in case.default_set.items()}
    for text in texts:
        match = SET_PATTERN.match(text.strip())
        if not match:
            raise UsageError("--set %r: expected NAME=VALUE with VALUE a decimal number" % text)
        name, value = match.group(1), match.group(2)
        if name not in nominal:
            raise UsageError("--set %s: not a parameter of %s (parameters: %s)"
                             % (name, case.example, ", ".join(sorted(nominal))))
        if not math.isfinite(float(value)):
            raise UsageError("--set %s: value must be finite" % name)
        settings[name] = value
    return sorted(settings.items())


def list_cases():
    print("%-8s %-18s %-30s %-9s %s" % ("example", "case", "expected operator", "effect", "hidden effect"))
    for (example, name), c in cases.CASES.items():
        print("%-8s %-18s %-30s %-9s %s" % (example, name, c.operator or "-",
                                           "%g Hz" % c.effect_hz if c.effect_hz else "-", c.hidden))
    print()
    print("--draw N: the estimable parameters' offsets (3-10 %, random sign) and, uniformly, these sizes:")
    for (example, name), c in cases.CASES.items():
        if c.sizes:
            print("%-8s %-18s %s" % (example, name, "; ".join(
                "%s in [%g, %g]%s (%s)" % (s.name, s.low, s.high, " " + s.unit if s.unit else "", s.what)
                for s in c.sizes)))


def truth_document(args, case, p, mats, settings, snr_db, data, outputs, inputs, measurement_chain=()):
    freqs, zetas = response.damped_modes(mats)
    doc = {
        "generator": "scripts/truthgen",
        "command": "python3 scripts/truthgen/truthgen.py " + " ".join(sys.argv[1:]),
        "example": case.example, "case": case.name, "kind": args.kind,
        "hidden_effect": {"expected_operator": case.operator, "effect_hz": case.effect_hz,
                          "description": case.hidden, "values": case.extra_at(p), "notes": case.notes},
        "parameters": p,
        "set": {name: text for name, text in settings},
        "seed": args.seed,
        "noise": {"snr_db": snr_db if math.isfinite(snr_db) else "inf",
                  "definition": ("FRF: complex Gaussian, E|n|^2 = sigma^2, sigma = RMS_grid |H| / 10^(snr/20) per "
                                 "channel; coherence |h|^2/(|h|^2 + sigma^2) of the noisy h" if args.kind == "frf" else
                                 "time: white Gaussian on each output, sigma = RMS(noise-free output) / "
                                 "10^(snr/20); inputs exact"),
                  "sigma": {}},
        "truth_modes": [{"f_hz": round(float(f), 4), "zeta": float("%.5g" % z)} for f, z in zip(freqs, zetas)],
    }
    if case.draw is not None:
        doc["draw"] = case.draw
    if measurement_chain:
        ids = [e["id"] for e in measurement_chain]
        hidden = doc["hidden_effect"]
        hidden["expected_chain"] = ids
        if case.control:     # no structural effect: the chain is what the diagnosis should name
            hidden["expected_operator"] = " + ".join(ids)
        hidden["description"] += "; measurement chain: " + "; ".join(chain.describe(e) for e in measurement_chain)
        doc["measurement_chain"] = list(measurement_chain)
        doc["noise"]["definition"] += ("; noise.sigma is each true channel's, before the measurement chain, which "
                                       "scales a channel's noise with it (same SNR)")
    if case.example == "spindle":
        j_s, j_h = models.spindle_inertias(p)
        doc["derived"] = {"J_sxx": j_s[0, 0], "J_syy": j_s[1, 1], "J_szz": j_s[2, 2],
                          "J_hxx": j_h[0, 0], "J_hyy": j_h[1, 1], "J_hzz": j_h[2, 2]}
    if args.kind == "frf":
        f = data["f_hz"]
        doc["frf"] = {"f_min": float(f[0]), "f_max": float(f[-1]), "df": float(f[1] - f[0]) if len(f) > 1 else 0}
        if args.averages != 1:
            doc["frf"]["averages"] = args.averages
            doc["noise"]["definition"] += ("; the FRF is the average of %d measurements: noise variance sigma^2/%d, "
                                           "coherence as for one" % (args.averages, args.averages))
        if args.analyser is not None:
            doc["frf"]["analyser_segments"] = args.analyser
            doc["noise"]["definition"] += ("; the FRF is an analyser's H1 estimate from %d segments (complex Gaussian "
                                           "force spectra of unit power, output noise sigma per segment), its "
                                           "coherence from the same segments" % args.analyser)
        if args.no_coherence:
            doc["frf"]["coherence_columns"] = False
        for oi, o in enumerate(outputs):
            for ii, i in enumerate(inputs):
                doc["noise"]["sigma"]["%s/%s" % (o, i)] = float(data["sigma"][oi, ii])
    elif args.kind == "oma":
        doc["truth_modes"] = [oma_mode(m) for m in operational.sensor_modes(mats)]
        doc["noise"]["definition"] = ("oma: white Gaussian on each output, sigma = RMS(noise-free output) / "
                                      "10^(snr/20); the forces are not measured")
        doc["oma"] = {"fs": 1.0 / data["dt"], "samples": int(len(data["t"])), "excitation":
                      "unmeasured independent white Gaussian forces (zero-order hold) at every input",
                      "forces": list(inputs), "force_rms": args.amplitude, "burn_in_samples": data["burn_in"],
                      "outputs": list(outputs),
                      "shapes": "C v at the outputs, unit norm, largest component real and positive",
                      "visibility": "peak of the mode's term in the output spectrum, |C v| |w^T B| / |Re lambda|, "
                                    "relative to the largest mode's"}
        for oi, o in enumerate(outputs):
            doc["noise"]["sigma"][o] = float(data["sigma"][oi])
    else:
        doc["time"] = {"fs": 1.0 / data["dt"], "samples": int(len(data["t"])), "excitation": args.excitation,
                       "amplitude": args.amplitude, "hold": "zoh", "initial_state": "at rest"}
        for oi, o in enumerate(outputs):
            doc["noise"]["sigma"][o] = float(data["sigma"][oi])
        if "input_sigma" in data:  # only with --input-snr-db: documents without it stay as they were
            doc["noise"]["input_snr_db"] = args.input_snr_db
            doc["noise"]["input_sigma"] = {i: float(data["input_sigma"][ii]) for ii, i in enumerate(inputs)}
            doc["noise"]["definition"] = doc["noise"]["definition"].replace(
                "inputs exact", "each written input with white Gaussian noise, sigma = RMS(clean input) / "
                "10^(input_snr/20) (an independent stream), the structure driven by the clean input")
    return doc


def oma_mode(m):
    """A truth mode of an output-only record: shapes as [re, im] per output, rounded as the other truth values."""
    return {"f_hz": round(float(m["f_hz"]), 6), "zeta": float("%.6g" % m["zeta"]),
            "shape": [[float("%.8g" % z.real), float("%.8g" % z.imag)] for z in m["shape"]],
            "visibility": float("%.4g" % m["visibility"])}


def run(argv):
    args = parse_args(argv)
    if args.list:
        list_cases()
        return 0
    if not args.example or not args.case or not args.output:
        raise UsageError("--example, --case and -o are required (or --list)")
    try:
        case = cases.get(args.example, args.case)
    except KeyError as error:
        raise UsageError(error.args[0])
    if args.kind == "oma" and (args.input_snr_db is not None or args.gain or args.input_gain or args.force_sign
                               or args.swap or args.unit or args.frf_form or args.excitation != "binary"):
        raise UsageError("--kind oma takes no force or measurement-chain options (its forces are Gaussian and "
                         "unmeasured)")
    if args.kind not in case.kinds and not (args.kind == "oma" and "time" in case.kinds):
        raise UsageError("case %s/%s has no %s data" % (case.example, case.name, args.kind))
    if args.kind != "frf" and (args.averages != 1 or args.no_coherence):
        raise UsageError("--averages and --no-coherence apply to FRFs only")
    if args.analyser is not None and (args.kind != "frf" or args.analyser < 2 or args.averages != 1):
        raise UsageError("--analyser N applies to FRFs only, needs N >= 2 segments and excludes --averages")
    if args.averages < 1:
        raise UsageError("--averages %d: must be at least 1" % args.averages)
    if args.input_snr_db is not None and (args.kind != "time" or not math.isfinite(args.input_snr_db)):
        raise UsageError("--input-snr-db applies to time records only and needs a finite number")
    if args.draw is not None and args.draw < 0:
        raise UsageError("--draw %d: must be a non-negative integer" % args.draw)
    if args.draw is not None:
        case = case.drawn(args.draw)
    try:
        snr_db = float(args.snr_db)
    except ValueError:
        raise UsageError("--snr-db %r: expected a number or inf" % args.snr_db)
    settings = parse_settings(args.set, case)
    p = case.truth_parameters({name: float(text) for name, text in settings})
    if args.series is not None or args.temperature is not None or args.change is not None:
        return run_series(args, case, p, settings, snr_db)
    system = case.build(p)
    mats = system.matrices()
    inputs, outputs = system.input_names(), system.output_names()
    try:
        measurement_chain = chain.parse(outputs, inputs, mats["output_orders"], args.kind, gains=args.gain,
                                        input_gains=args.input_gain, force_sign=args.force_sign, swaps=args.swap,
                                        units=args.unit, forms=args.frf_form, draw_n=args.draw)
    except chain.ChainError as error:
        raise UsageError(error.args[0])
    rng = np.random.default_rng(args.seed)
    if args.kind == "frf":
        f_min, f_max, df = generate.FRF_GRID[case.example]
        f = generate.frequency_grid(args.f_min if args.f_min is not None else f_min,
                                    args.f_max if args.f_max is not None else f_max,
                                    args.df if args.df is not None else df)
        if f[0] < 0 or len(f) < 1:
            raise UsageError("bad frequency grid")
        if args.analyser is not None:
            data = generate.make_analyser_frf(mats, f, snr_db, rng, args.analyser)
        else:
            data = generate.make_frf(mats, f, snr_db, rng, args.averages)
        chain.apply_frf(data, measurement_chain, outputs, inputs)
        datafiles.write_frf_csv(args.output, data, outputs, inputs, settings, coherence=not args.no_coherence)
    elif args.kind == "oma":
        fs = args.fs or operational.SAMPLE_RATE[case.example]
        args.amplitude = args.amplitude or generate.AMPLITUDE[case.example]
        data = operational.make_oma(mats, fs, args.duration or operational.DURATION[case.example], snr_db, rng,
                                    args.amplitude)
        data["u"] = np.zeros((len(data["t"]), 0))   # no force column
        datafiles.write_time_csv(args.output, data, outputs, [], settings)
    else:
        fs = args.fs or generate.SAMPLE_RATE[case.example]
        args.amplitude = args.amplitude or generate.AMPLITUDE[case.example]
        data = generate.make_time(mats, fs, args.duration or generate.DURATION[case.example], snr_db, rng,
                                  args.amplitude, args.excitation)
        if args.input_snr_db is not None:
            generate.add_input_noise(data, args.input_snr_db, args.seed)
        chain.apply_time(data, measurement_chain, outputs, inputs)
        datafiles.write_time_csv(args.output, data, outputs, inputs, settings)
    base = args.output[:-4] if args.output.endswith(".csv") else args.output
    datafiles.write_truth_json(base + ".truth.json",
                               truth_document(args, case, p, mats, settings, snr_db, data, outputs, inputs,
                                              measurement_chain))
    return 0


def run_series(args, case, p, settings, snr_db):
    """--series: N output-only records of one truth under a changing condition (truthlib/series.py)."""
    if args.kind != "oma" or args.series is None or args.series < 1:
        raise UsageError("--temperature and --change go with --series N (N >= 1) and --kind oma")
    try:
        spec = series.parse_temperature(args.temperature)
        change = series.parse_change(args.change, p)
    except series.SeriesError as error:
        raise UsageError(error.args[0])
    if change is not None and change["from_set"] >= args.series:
        raise UsageError("--change: set %d is beyond the series' %d sets" % (change["from_set"], args.series))
    fs = args.fs or operational.SAMPLE_RATE[case.example]
    args.amplitude = args.amplitude or generate.AMPLITUDE[case.example]
    duration = args.duration or operational.DURATION[case.example]
    output = args.output
    temps = series.temperatures(args.series, spec, args.seed)
    summary = {"generator": "scripts/truthgen", "command": "python3 scripts/truthgen/truthgen.py " + " ".join(sys.argv[1:]),
               "example": case.example, "case": case.name, "parameters": p,
               "condition": {"name": "temperature", "mean": spec[0], "daily_amplitude": spec[1],
                             "period_sets": spec[2], "trend_per_set": spec[3], "noise_std": spec[4],
                             "coefficient": args.temperature_coefficient,
                             "stiffnesses": series.stiffness_names(p),
                             "law": "k(T) = k0 (1 - coefficient (T - mean))"},
               "change": change, "sets": []}
    for i, temperature in enumerate(temps):
        try:
            q, factor, changed = series.set_parameters(p, temperature, spec, args.temperature_coefficient, change, i)
        except series.SeriesError as error:
            raise UsageError(error.args[0])
        mats = case.build(q).matrices()
        system = case.build(q)
        inputs, outputs = system.input_names(), system.output_names()
        rng = np.random.default_rng([args.seed, i + 1])
        data = operational.make_oma(mats, fs, duration, snr_db, rng, args.amplitude)
        data["u"] = np.zeros((len(data["t"]), 0))
        path = series.set_path(output, i, args.series)
        datafiles.write_time_csv(path, data, outputs, [], settings,
                                 comments=["# condition temperature=%.2f" % temperature])
        args.output = path
        doc = truth_document(args, case, q, mats, settings, snr_db, data, outputs, inputs)
        doc["series"] = {"index": i, "temperature": temperature, "stiffness_factor": factor, "changed": changed,
                         "noise_stream": [args.seed, i + 1]}
        datafiles.write_truth_json(path[:-4] + ".truth.json", doc)
        summary["sets"].append({"file": os.path.basename(path), "temperature": temperature,
                                "stiffness_factor": factor, "changed": changed,
                                "truth_modes": [{"f_hz": m["f_hz"], "zeta": m["zeta"]} for m in doc["truth_modes"]]})
    base = output[:-4] if output.endswith(".csv") else output
    datafiles.write_truth_json(base + ".series.json", summary)
    return 0


def main():
    try:
        return run(sys.argv[1:])
    except UsageError as error:
        sys.stderr.write("truthgen: error: %s\n" % error)
        return 1


if __name__ == "__main__":
    sys.exit(main())
