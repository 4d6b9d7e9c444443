#!/usr/bin/env python3
"""Coverage of the reported standard deviations: do the fits' error bars hold?

For each of N independent draws (scripts/truthgen --draw: the truth's parameters offset 3-10 % at random, its own
noise realisation at 40 dB SNR), `mbgen fit` estimates the parameters; z = (estimate - truth) / reported std per
parameter. If the reported std is honest, z has mean 0 and RMS 1, and |z| < 1 holds about 68 % and |z| < 2 about
95 % of the time. A std too small shows as RMS z well above 1 (the issue that started this: an mdof2 record's c22
landed 3.5 reported std from the truth).

    bench/coverage.py [--mbgen build/compiler/mbgen] [--draws 20] [--kind frf|time] [--example mdof2]
                      [--duration 2] [--first-draw 1] [--fs HZ] [--method NAME] [--input-snr-db DB|LO:HI]

Errors in variables: `--input-snr-db` gives the written force white measurement noise (truthgen --input-snr-db; the
structure driven by the clean force); LO:HI spreads it evenly over the draws (the first draw at LO, the last at HI).
`--method` is passed to `mbgen fit` (e.g. eiv against the default output error on the same draws).

Prints one line per parameter: draws used, mean z and its standard error (RMS z / sqrt(n)), RMS z, the fractions
within 1 and 2 std, and the worst |z|; then all parameters pooled. A mean z several standard errors from 0 is a
bias the std does not cover. Parameters not identifiable or at a bound in a draw are left out of that draw (the
count says how many remain). Draw d uses truthgen --draw d --seed 5000+d. The results of past runs, with their
dates, are in bench/README.md.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def drop_start(path, seconds):
    """Removes the samples before t = seconds from a time record CSV and restarts its clock at 0."""
    lines = open(path).read().splitlines()
    header = next(i for i, line in enumerate(lines) if not line.startswith("#"))
    rows = [line.split(",", 1) for line in lines[header + 1:]]
    t0 = next(float(t) for t, _ in rows if float(t) >= seconds - 1e-12)
    kept = ["%.9g,%s" % (float(t) - t0, rest) for t, rest in rows if float(t) >= t0]
    open(path, "w").write("\n".join(lines[:header + 1] + kept) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--mbgen", default=os.path.join(ROOT, "build", "compiler", "mbgen"))
    ap.add_argument("--draws", type=int, default=20)
    ap.add_argument("--kind", choices=["frf", "time"], default="frf")
    ap.add_argument("--example", default="mdof2")
    ap.add_argument("--duration", type=float, default=2.0, help="time record length, s")
    ap.add_argument("--first-draw", type=int, default=1)
    ap.add_argument("--skip", type=float, default=0.0,
                    help="time records: drop the first SKIP seconds (of a record SKIP + duration long), so that the "
                         "record no longer starts at rest, as a real one seldom does; the fit still assumes rest")
    ap.add_argument("--fs", type=float, help="time record sample rate, Hz (truthgen's default otherwise)")
    ap.add_argument("--snr-db", type=float, default=40.0, help="output SNR, dB (default 40)")
    ap.add_argument("--input-snr-db", help="time records: the written force's SNR, dB, or LO:HI over the draws")
    ap.add_argument("--method", help="mbgen fit --method (default: the fit's own choice, output error)")
    args = ap.parse_args()
    input_snr = None
    if args.input_snr_db:
        lo, _, hi = args.input_snr_db.partition(":")
        input_snr = (float(lo), float(hi or lo))

    model = os.path.join(ROOT, "examples", args.example, args.example + ".mdl")
    z = {}
    with tempfile.TemporaryDirectory() as work:
        for draw in range(args.first_draw, args.first_draw + args.draws):
            data = os.path.join(work, "d.csv")
            cmd = ["/usr/bin/python3", os.path.join(ROOT, "scripts", "truthgen", "truthgen.py"), "--example", args.example,
                   "--case", "nominal", "--kind", args.kind, "--snr-db", "%g" % args.snr_db, "--seed", str(5000 + draw),
                   "--draw", str(draw), "-o", data]
            if args.kind == "time":
                cmd += ["--duration", str(args.duration + args.skip)]
                if args.fs:
                    cmd += ["--fs", "%g" % args.fs]
                if input_snr:
                    step = (draw - args.first_draw) / max(1, args.draws - 1)
                    cmd += ["--input-snr-db", "%g" % (input_snr[0] + step * (input_snr[1] - input_snr[0]))]
            subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
            if args.skip > 0:
                drop_start(data, args.skip)
            truth = json.load(open(os.path.join(work, "d.truth.json")))["parameters"]
            out = os.path.join(work, "fit.json")
            method = ["--method", args.method] if args.method else []
            subprocess.run([args.mbgen, "fit", model, "--data", data, "--json", out] + method, check=True,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            fit = json.load(open(out))["parameters"]
            for name, p in fit.items():
                if not p.get("identifiable") or p.get("std") in (None, 0) or name not in truth:
                    continue
                z.setdefault(name, []).append((p["value"] - truth[name]) / p["std"])
            print(f"draw {draw - args.first_draw + 1}/{args.draws}", file=sys.stderr, end="\r")
    print(file=sys.stderr)
    extra = f", {args.duration:g} s records" if args.kind == "time" else ""
    extra += f" at {args.fs:g} Hz" if args.fs else ""
    extra += f" starting {args.skip:g} s after rest" if args.skip > 0 else ""
    if input_snr:
        extra += (f", force noise {input_snr[0]:g}-{input_snr[1]:g} dB" if input_snr[1] != input_snr[0]
                  else f", force noise {input_snr[0]:g} dB")
    extra += f", --method {args.method}" if args.method else ""
    print(f"{args.example} {args.kind}{extra}, {args.draws} draws at {args.snr_db:g} dB SNR: "
          "z = (estimate - truth) / reported std")
    print(f"{'parameter':12s} {'n':>3s} {'mean z':>8s} {'(se)':>6s} {'RMS z':>7s} {'|z|<1':>6s} {'|z|<2':>6s} {'max |z|':>8s}")
    pooled = [v for values in z.values() for v in values]
    for name, values in sorted(z.items()) + [("all", pooled)]:
        n = len(values)
        mean = sum(values) / n
        rms = math.sqrt(sum(v * v for v in values) / n)
        within1 = sum(abs(v) < 1 for v in values) / n
        within2 = sum(abs(v) < 2 for v in values) / n
        print(f"{name:12s} {n:3d} {mean:8.2f} {rms / math.sqrt(n):6.2f} {rms:7.2f} {within1:6.0%} {within2:6.0%} "
              f"{max(abs(v) for v in values):8.2f}")

if __name__ == "__main__":
    main()
