#!/usr/bin/python3
"""Plots accuracy against time from a sweep_summary.csv written by
`touchcloud sweep`, marking the Pareto front (settings no other setting beats
in both time and accuracy). The accuracy's unit and which way is better come
from its declaration (`touchcloud sweep` passes them). Writes OUT.png and
OUT.svg with matplotlib."""
import argparse
import csv
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402


def pareto_front(points, higher_is_better=False):
    """Indices of points with no other point at most as slow and strictly more accurate."""
    sign = -1 if higher_is_better else 1
    order = sorted(range(len(points)), key=lambda i: (points[i][0], sign * points[i][1]))
    front, best = [], float("inf")
    for i in order:
        if sign * points[i][1] < best:
            front.append(i)
            best = sign * points[i][1]
    return front


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("summary")
    ap.add_argument("--x", required=True, help="time column")
    ap.add_argument("--y", required=True, help="accuracy column")
    ap.add_argument("--y-unit", default="", help="the accuracy's unit, as declared (mm)")
    ap.add_argument("--y-direction", default="lower_is_better",
                    choices=["lower_is_better", "higher_is_better", "none"], help="which way the accuracy is better")
    ap.add_argument("--out", required=True, help="output path without extension")
    args = ap.parse_args()

    with open(args.summary, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit("plot_sweep: no rows in " + args.summary)
    for col in (args.x, args.y):
        if col not in rows[0]:
            sys.exit(f"plot_sweep: no column '{col}' in {args.summary}")
    axis_keys = list(rows[0])[1:list(rows[0]).index("runs")]
    labels = [", ".join(f"{k.split('.', 1)[1]}={r[k]}" for k in axis_keys) for r in rows]
    pts = [(float(r[args.x]), float(r[args.y])) for r in rows]
    yerr = [float(r.get(args.y + "_std") or 0) for r in rows]
    front = pareto_front(pts, args.y_direction == "higher_is_better")

    fig, ax = plt.subplots(figsize=(8, 5.5))
    ax.errorbar([p[0] for p in pts], [p[1] for p in pts], yerr=yerr, fmt="o", color="0.55",
                ecolor="0.8", capsize=2, label="setting (mean ± sd over seeds)")
    fp = sorted((pts[i] for i in front))
    ax.plot([p[0] for p in fp], [p[1] for p in fp], "-o", color="tab:red", label="Pareto front")
    for i, (x, y) in enumerate(pts):
        ax.annotate(labels[i], (x, y), fontsize=7, xytext=(4, 3), textcoords="offset points",
                    color="tab:red" if i in front else "0.35")
    ax.set_xscale("log")
    ax.set_xlabel(args.x.replace("_s", " (s)") if args.x.endswith("_s") else args.x)
    ax.set_ylabel(args.y + (f" ({args.y_unit})" if args.y_unit else ""))
    ax.set_title("accuracy against time")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="best")
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(f"{args.out}.{ext}", dpi=130)


if __name__ == "__main__":
    main()
