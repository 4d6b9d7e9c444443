#!/usr/bin/env python3
"""Fit the mdof2 example (examples/mdof2) from Python: estimates against the truth the data were made from, and the
measured FRFs against the model's at the estimate (a plot, when matplotlib is installed).

    PYTHONPATH=build/python python3 examples/python/fit_mdof2.py [--plot fit_mdof2.png] [--no-plot]
"""
import argparse
import json
import pathlib
import sys

import numpy as np

import mbgen

HERE = pathlib.Path(__file__).resolve().parent
MDOF2 = HERE.parent / "mdof2"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plot", default="fit_mdof2.png", help="where to write the plot (PNG)")
    parser.add_argument("--no-plot", action="store_true", help="print the estimates only")
    args = parser.parse_args()

    model_path = MDOF2 / "mdof2.mdl"
    data_path = MDOF2 / "data" / "frf_F1.csv"
    truth = json.loads((MDOF2 / "data" / "frf_F1.truth.json").read_text())["parameters"]

    result = mbgen.fit(model_path, data_path)  # the content of `mbgen fit --json` (schema mbgen-fit/1)
    print(f"{'parameter':10} {'prior':>12} {'estimate':>12} {'std':>10} {'truth':>12}")
    worst = 0.0
    for name, p in result["parameters"].items():
        print(f"{name:10} {p['prior']:12.6g} {p['value']:12.6g} {p['std']:10.3g} {truth[name]:12.6g}")
        worst = max(worst, abs(p["value"] - truth[name]) / abs(truth[name]))
    print(f"nrmse {result['fit']['nrmse']:.4g}; largest deviation from the truth {100 * worst:.2f} %")
    print("modes at the estimate: " + ", ".join(f"{m['f_hz']:.2f} Hz ({m['zeta']:.3g})" for m in result["modes"]))

    if not args.no_plot:
        plot(model_path, data_path, {n: p["value"] for n, p in result["parameters"].items()}, args.plot)
    # 40 dB data: a fit that misses the truth by more than 1 % has gone wrong (the example doubles as a test).
    return 0 if worst < 0.01 else 1


def plot(model_path, data_path, estimate, out):
    try:
        import matplotlib

        matplotlib.use("Agg")  # a file, no display needed
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no plot")
        return
    measured = mbgen.read_data(data_path)
    model = mbgen.load_model(model_path)
    f = measured["f_hz"]
    fitted = model.frf(f, params=estimate)  # lines x outputs x inputs
    fig, axes = plt.subplots(2, 1, sharex=True, figsize=(8, 6))
    for c, name in enumerate(measured["channels"]):
        o, i = model.outputs.index(measured["outputs"][c]), model.inputs.index(measured["inputs"][c])
        # measured as faint dots, the fitted model as a dark line over them
        line = axes[0].semilogy(f, np.abs(measured["values"][:, c]), ".", ms=2, alpha=0.4, label=f"{name} measured")[0]
        axes[0].semilogy(f, np.abs(fitted[:, o, i]), "-", color=line.get_color(), lw=1.5, label=f"{name} fitted")
        axes[1].plot(f, np.degrees(np.angle(measured["values"][:, c])), ".", ms=2, alpha=0.4, color=line.get_color())
        axes[1].plot(f, np.degrees(np.angle(fitted[:, o, i])), "-", color=line.get_color(), lw=1.5)
    axes[0].set_ylabel("|H| [m/N]")
    axes[0].legend(fontsize=8)
    axes[1].set_ylabel("phase [deg]")
    axes[1].set_xlabel("frequency [Hz]")
    fig.suptitle("mdof2: measured and fitted FRFs")
    fig.savefig(out, dpi=120)
    print(f"plot: {out}")


if __name__ == "__main__":
    sys.exit(main())
