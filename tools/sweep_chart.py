#!/usr/bin/python3
"""Chart of `crashlink sweep`: sweep_chart.py CSV PNG.

x: CPU time relative to mono; y: |error| against mono (%) of HIC15, peak head acceleration and the
displacement probe's peak, one marker per quantity, one label per configuration; the runs that
did not reach the end time (the `paper` scheme stopped by its guard) are named at the bottom.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    every = list(csv.DictReader(open(sys.argv[1])))
    rows = [r for r in every if r["cpu_over_mono"]]
    stopped = [r for r in every if not r["cpu_over_mono"]]
    fig, ax = plt.subplots(figsize=(8, 5))
    quantities = (("hic15_error_pct", "HIC15", "o"), ("peak_error_pct", "peak acceleration", "s"),
                  ("disp_error_pct", "displacement probe", "^"))
    for key, label, marker in quantities:
        x = [float(r["cpu_over_mono"]) for r in rows]
        y = [max(abs(float(r[key])), 1e-3) for r in rows]
        ax.scatter(x, y, marker=marker, s=45, label=label)
    for r in rows:
        ax.annotate(r["configuration"], (float(r["cpu_over_mono"]),
                                         max(abs(float(r["hic15_error_pct"])), 1e-3)),
                    textcoords="offset points", xytext=(6, 6), fontsize=8)
    ax.axhline(1.0, color="r", lw=0.8, ls="--", label="1 % (HIC target)")
    ax.set_yscale("log")
    ax.set_xlabel("CPU time relative to mono")
    ax.set_ylabel("|error| against mono [%] (floor 1e-3)")
    ax.set_title("speed against accuracy")
    if stopped:  # runs that did not reach the end (the paper scheme's guard, a failure)
        text = "not plotted: " + "; ".join(
            f"{r['configuration']} ({r['note'].split(':')[0]})" for r in stopped)
        fig.text(0.01, 0.01, text[:160], fontsize=7)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=120)
    print(sys.argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main())
