#!/usr/bin/python3
"""The shipped closed shapes (sample_clouds/closed_objects/) touched from
above, reconstructed two ways with the same touch budget and seeds: the
height-field GP of the main job (pipelines/fox_mask_active.yaml, its
max-variance choice) and the implicit surface (pipelines/closed_object_active.yaml,
its variance as a press from above meets it). Each run is scored against the
whole closed mesh after every touch: Eq. 11 (estimate -> object, the mean
chamfer), its 95th percentile, Hausdorff, completeness (object -> estimate),
F-score and coverage at --fscore-mm, of the whole object and of what a press
from above sees (visible coverage).

Writes into --out:
  runs.csv     one row per shape, method and seed: the final figures
  results.csv  per shape and method: mean and sd over the seeds
  results.md   the same as a table
  curves.csv   per shape, method, seed and touch: the figures after that touch
  curves.png   mean Eq. 11 and F-score against touches (needs python3-matplotlib)

Usage (from the repository root, after building):
  benchmarks/closed_objects/make_closed_objects_table.py --out benchmarks/closed_objects \\
      [--seeds 1-5] [--touches 24] [--shapes pebble,torus] [--ranks 2]
With --ranks N the runs spread over one `mpirun -n N` job (scripts/mpi_launch.py);
the figures do not depend on it. The sensor is the simulator's ideal one (the
closed shapes have no realistic scene).
"""
import argparse
import csv
import json
import os
import platform
import statistics
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from mpi_launch import run_all  # noqa: E402

SHAPES = ["sphere", "pebble", "step", "torus", "mug"]
PIPELINES = {"height field (GP, max variance)": "pipelines/fox_mask_active.yaml",
             "implicit surface (GPIS, max variance)": "pipelines/closed_object_active.yaml"}
# summary.json metric (score.<name>), column title, decimals in results.md
METRICS = [("chamfer_est_to_gt", "Eq. 11", 3), ("p95_est_to_gt", "p95", 2), ("hausdorff", "Hausdorff", 1),
           ("chamfer_gt_to_est", "completeness", 2), ("fscore", "F-score", 3), ("recall", "coverage", 3),
           ("visible_recall", "visible coverage", 3)]


def seed_list(text):
    """'1-5' or '1,3,4' (or a mix) -> [1, 2, 3, 4, 5]."""
    seeds = []
    for part in text.split(","):
        first, _, last = part.partition("-")
        seeds += range(int(first), int(last or first) + 1)
    if not seeds:
        raise argparse.ArgumentTypeError(f"no seeds in '{text}'")
    return seeds


def command(args, pipeline, shape, seed, out):
    return [args.touchcloud, "run", pipeline, "--seed", str(seed), "--quiet", "--out", out,
            "--scene", f"sample_clouds/closed_objects/{shape}/scene.yaml",
            "--set", f"explore.max_iterations={args.touches}", "--set", "score.metrics=all",
            "--set", f"score.fscore_threshold_mm={args.fscore_mm}"]


def read_run(out):
    """The final figures and the per-touch series of one run."""
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    final = {"touches": s["loops"]["explore"]["iterations"], "wall_time_s": s["wall_time_s"]}
    series = {}
    for name, _, _ in METRICS:
        m = s["metrics"].get("score." + name)
        final[name] = m["value"] if m else None
        series[name] = m.get("series", []) if m else []
    return final, series


def mean_sd(values):
    values = [v for v in values if v is not None]
    if not values:
        return None, None
    return statistics.fmean(values), statistics.stdev(values) if len(values) > 1 else 0.0


def plot(args, curves):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("make_closed_objects_table: no plot (python3-matplotlib is missing); the tables are complete",
              file=sys.stderr)
        return False
    fig, axes = plt.subplots(1, 2, figsize=(12, 5))
    for (shape, method), by_touch in curves.items():
        touches = sorted(by_touch)
        style = "-" if method.startswith("implicit") else "--"
        for ax, name in zip(axes, ("chamfer_est_to_gt", "fscore")):
            ax.plot(touches, [statistics.fmean(by_touch[t][name]) for t in touches], style,
                    label=f"{shape}, {method.split(' (')[0]}")
    axes[0].set_ylabel("Eq. 11, estimate -> object (mm)")
    axes[0].set_yscale("log")
    axes[1].set_ylabel(f"F-score at {args.fscore_mm:g} mm")
    for ax in axes:
        ax.set_xlabel("touches")
        ax.grid(True, alpha=0.3)
    axes[1].legend(fontsize=7)
    fig.suptitle(f"Closed shapes touched from above (mean over seeds {args.seeds_text})")
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "curves.png"), dpi=120)
    return True


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", required=True)
    parser.add_argument("--touchcloud", default="build/bin/touchcloud")
    parser.add_argument("--touches", type=int, default=24)
    parser.add_argument("--seeds", default="1", help="e.g. 1-5 or 1,3 (default 1)")
    parser.add_argument("--shapes", default=",".join(SHAPES), help="of " + ", ".join(SHAPES))
    parser.add_argument("--fscore-mm", type=float, default=2.0, help="F-score and coverage threshold (mm)")
    parser.add_argument("--ranks", type=int, default=1, help="MPI ranks to spread the runs over (mpirun -n N)")
    args = parser.parse_args()
    try:
        seeds = seed_list(args.seeds)
    except (ValueError, argparse.ArgumentTypeError):
        parser.error(f"--seeds '{args.seeds}': give seeds as 1-5 or 1,3")
    args.seeds_text = args.seeds
    shapes = args.shapes.split(",")
    unknown = [s for s in shapes if s not in SHAPES]
    if unknown:
        parser.error(f"--shapes: no shape {', '.join(unknown)} (shipped: {', '.join(SHAPES)})")
    if args.touches < 1:
        parser.error("--touches must be at least 1")
    os.makedirs(args.out, exist_ok=True)

    runs = [(shape, method, pipeline, seed) for shape in shapes for method, pipeline in PIPELINES.items()
            for seed in seeds]
    rows, per_touch, series_of = [], {}, {}
    with tempfile.TemporaryDirectory(dir=os.path.abspath(args.out)) as scratch:
        outs = [os.path.join(scratch, f"{shape}-{i}-{seed}") for i, (shape, _, _, seed) in enumerate(runs)]
        run_all([command(args, pipeline, shape, seed, out) for (shape, _, pipeline, seed), out in zip(runs, outs)],
                args.ranks, scratch)
        for (shape, method, _, seed), out in zip(runs, outs):
            final, series = read_run(out)
            rows.append({"shape": shape, "method": method, "seed": seed, **final})
            by_touch = per_touch.setdefault((shape, method), {})
            for name, values in series.items():
                for t, v in enumerate(values, 1):
                    by_touch.setdefault(t, {n: [] for n, _, _ in METRICS})[name].append(v)
            series_of[(shape, method, seed)] = series

    names = [m for m, _, _ in METRICS]
    with open(os.path.join(args.out, "runs.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["shape", "method", "seed", "touches"] + names + ["wall_time_s"])
        w.writeheader()
        w.writerows(rows)
    with open(os.path.join(args.out, "curves.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["shape", "method", "seed", "touch"] + names)
        for (shape, method, _, seed) in runs:
            series = series_of[(shape, method, seed)]
            for t in range(max(len(v) for v in series.values())):
                w.writerow([shape, method, seed, t + 1] +
                           [series[n][t] if t < len(series[n]) else "" for n in names])
    summary = []
    for shape in shapes:
        for method in PIPELINES:
            mine = [r for r in rows if r["shape"] == shape and r["method"] == method]
            row = {"shape": shape, "method": method, "seeds": len(mine)}
            for name in names + ["touches", "wall_time_s"]:
                row[name], row[name + "_sd"] = mean_sd([r[name] for r in mine])
            summary.append(row)
    with open(os.path.join(args.out, "results.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(summary[0].keys()))
        w.writeheader()
        w.writerows(summary)

    plotted = plot(args, per_touch)
    fmt = lambda r, n, d: "-" if r[n] is None else f"{r[n]:.{d}f} ± {r[n + '_sd']:.{d}f}"
    with open(os.path.join(args.out, "results.md"), "w") as f:
        f.write(f"# Closed shapes touched from above: height field and implicit surface\n\n"
                f"Made by `benchmarks/closed_objects/make_closed_objects_table.py --out {args.out} "
                f"--seeds {args.seeds} --touches {args.touches}` (at most {args.touches} touches, fewer where "
                f"no reachable cell is left; the simulator's ideal sensor) on {platform.machine()} Linux with "
                f"{os.cpu_count()} cores. Mean ± sd over {len(seeds)} seed(s). Distances in mm against the "
                f"whole closed mesh; F-score and coverage at {args.fscore_mm:g} mm; visible coverage is the "
                f"share of what a press from above can see. Per-touch figures: curves.csv"
                f"{' and curves.png' if plotted else ''}."
                "\n\n| shape | method | touches | " + " | ".join(t for _, t, _ in METRICS) + " | time (s) |\n"
                "|---|---|---|" + "---|" * len(METRICS) + "---|\n")
        for r in summary:
            f.write(f"| {r['shape']} | {r['method']} | {fmt(r, 'touches', 1)} | " +
                    " | ".join(fmt(r, n, d) for n, _, d in METRICS) + f" | {fmt(r, 'wall_time_s', 1)} |\n")


if __name__ == "__main__":
    main()
