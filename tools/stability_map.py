#!/usr/bin/python3
"""Plot of `crashlink stability-map`: stability_map.py CSV PNG.

Maximum energy rise above the running minimum (% of E0, log scale) against the step ratio H/h,
one curve per shape and configuration (`layer` with and without interface damping, `lts`, `paper`
with drift correction on and off); the issue's 0.1 % line; runs stopped by the guard marked x at the
top of the plot (the guard stops before the rise is sampled); runs the scheme refused (`paper`
on shell links) left out.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    rows = list(csv.DictReader(open(sys.argv[1])))
    curves = {}
    for r in rows:
        curves.setdefault((r["shape"], r["configuration"]), []).append(r)
    fig, ax = plt.subplots(figsize=(9, 5.5))
    markers = {"bar": "o", "plate": "s", "block": "^", "contact": "D"}
    top = 20.0  # % of E0: where stopped runs are drawn
    for (shape, config), rs in sorted(curves.items()):
        rs = [r for r in rs if float(r["nested_ratio"]) > 0]  # refused by the scheme: not run
        if not rs:
            continue
        x = [float(r["ratio"]) for r in rs]
        y = [top if r["stopped"] else max(100.0 * float(r["max_rise"]), 1e-6) for r in rs]
        style = (":" if config.startswith("paper") else "-." if config == "lts"
                 else ("--" if "damping" in config else "-"))
        ax.plot(x, y, marker=markers.get(shape, "o"), ls=style, ms=4, label=f"{shape}, {config}")
        for r, xv, yv in zip(rs, x, y):
            if r["stopped"]:
                ax.plot([xv], [yv], "kx", ms=9)
    ax.axhline(0.1, color="r", lw=1, label="issue #4 bound 0.1 %")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("step ratio H/h")
    ax.set_ylabel("max energy rise above running minimum [% of E0]")
    steps = rows[0]["fine_steps"] if rows else "?"
    ax.set_title(f"layer, lts and paper couplings, energy rise over {steps} fine steps "
                 f"(x: stopped by the guard)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=120)
    print(sys.argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main())
