#!/usr/bin/python3
"""Regenerates Table 1 of the GelStereo Palm 2.0 paper in simulation: both
objects x the five methods x N seeds, each a `touchcloud run` of
pipelines/<object>_active.yaml with the method's overrides. Writes, into
--out:

  table1.md      the table in the paper's layout, with the paper's numbers beside ours
  table1.csv     the same, one row per object and method
  runs.csv       every run: final chamfer, convergence touches, points, wall time
  curves.csv     mean and standard deviation of the chamfer distance after each touch
  curves.png     those curves, one panel per object (needs python3-matplotlib)

Usage (from the repository root, after building):
  benchmarks/table1/make_table1.py --out benchmarks/table1
  benchmarks/table1/make_table1.py --out benchmarks/table1 --ranks 2   # or under mpirun / srun

With --ranks N (or when started by mpirun or srun on several ranks) the runs
spread over the ranks: each rank takes the next run no rank has claimed yet
(an exclusive file in a folder under --out, which every rank must see), and
rank 0 writes the same files; only the times differ.
"""
import argparse
import concurrent.futures
import csv
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from mpi_launch import launched_ranks, mpirun_command  # noqa: E402

# The methods of Table 1 as overrides of the "Ours" pipelines.
METHODS = {
    "SP": ["salient.keep=deepest"],
    "w/o PCP": ["dedup.enabled=false"],
    "w/o SSG": ["plan.strategy=random"],
    "LSR": ["thin.keep_ratio=0.25"],
    "Ours": [],
}
OBJECTS = {"wave_surface": "wave surface", "fox_mask": "fox mask"}
# Table 1 of the paper (real robot): final mean CD (mm), convergence steps, final points.
PAPER = {
    ("wave_surface", "SP"): ("4.294", "30+", "-"),
    ("wave_surface", "w/o PCP"): ("2.734", "17", "2165.0"),
    ("wave_surface", "w/o SSG"): ("5.268", "17", "-"),
    ("wave_surface", "LSR"): ("2.583", "22", "-"),
    ("wave_surface", "Ours"): ("2.781", "16", "1664.6"),
    ("fox_mask", "SP"): ("6.042", "30+", "-"),
    ("fox_mask", "w/o PCP"): ("2.299", "18", "2036.4"),
    ("fox_mask", "w/o SSG"): ("2.678", "20", "-"),
    ("fox_mask", "LSR"): ("2.282", "27", "-"),
    ("fox_mask", "Ours"): ("2.325", "18", "1632.2"),
}
INITIAL_RANDOM = 4  # touches before the first exploration (the pipelines' next_touch.initial_random)


def run_one(args, obj, method, seed, workdir):
    out = os.path.join(workdir, obj, method.replace("/", "").replace(" ", "_"), f"seed{seed}")
    cmd = [args.touchcloud, "run", os.path.join("pipelines", f"{obj}_active.yaml"), "--seed", str(seed), "--out", out]
    for o in METHODS[method] + args.set:
        cmd += ["--set", o]
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({done.returncode}):\n{done.stderr}")
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    m = summary["metrics"]
    return {
        "object": obj,
        "method": method,
        "seed": seed,
        "curve": m["score.chamfer_est_to_gt"]["series"],
        "final_chamfer_mm": m["score.final_chamfer_mm"]["value"],
        "convergence_touches": m["score.convergence_touches"]["value"],
        "points": m["dedup.total_points"]["value"],
        "wall_time_s": summary["wall_time_s"],
    }


def run_on_ranks(args, todo, rank, size):
    """Every rank runs the next unclaimed run; rank 0 returns all results, the others None."""
    job = os.environ.get("PMIX_NAMESPACE") or os.environ.get("SLURM_JOB_ID", "job")
    shared = os.path.join(os.path.abspath(args.out), f".table1-ranks-{job}")
    os.makedirs(shared, exist_ok=True)
    for i, (o, m, s) in enumerate(todo):
        try:
            os.close(os.open(os.path.join(shared, f"claim-{i}"), os.O_CREAT | os.O_EXCL))
        except FileExistsError:
            continue
        result = run_one(args, o, m, s, shared)
        with open(os.path.join(shared, f"run-{i}.tmp{rank}"), "w") as f:
            json.dump(result, f)
        os.rename(os.path.join(shared, f"run-{i}.tmp{rank}"), os.path.join(shared, f"run-{i}.json"))
        print(f"run {i + 1}/{len(todo)} on rank {rank}", file=sys.stderr, flush=True)
    if rank != 0:
        return None
    # mpirun ends the job if a rank dies, so waiting for the others is safe.
    files = [os.path.join(shared, f"run-{i}.json") for i in range(len(todo))]
    while not all(os.path.exists(f) for f in files):
        time.sleep(0.2)
    runs = []
    for f in files:
        with open(f) as fh:
            runs.append(json.load(fh))
    subprocess.run(["rm", "-rf", shared], check=True)
    return runs


def convergence(curve, tolerance=0.05):
    """First touch (1-based) after which the curve stays within 5% of its last value."""
    final = curve[-1]
    touch = len(curve)
    for i in range(len(curve) - 1, -1, -1):
        if abs(curve[i] - final) > tolerance * final:
            break
        touch = i + 1
    return touch


def mean_sd(values):
    return statistics.fmean(values), (statistics.stdev(values) if len(values) > 1 else 0.0)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--touchcloud", default="build/bin/touchcloud")
    ap.add_argument("--seeds", type=int, default=5)
    ap.add_argument("--jobs", type=int, default=1,
                    help="runs at a time (default 1: a run keeps two cores busy, its background stages "
                         "beside the loop, so more at once slows each and skews the run times)")
    ap.add_argument("--out", required=True)
    ap.add_argument("--ranks", type=int, default=1,
                    help="MPI ranks to spread the runs over (runs this script under mpirun -n N)")
    ap.add_argument("--set", action="append", default=[], metavar="K=V",
                    help="an override for every run (e.g. explore.max_iterations=10 for a quick look)")
    args = ap.parse_args()
    if not os.path.exists(args.touchcloud):
        sys.exit(f"make_table1: no {args.touchcloud}; build first (scripts/build.sh)")
    os.makedirs(args.out, exist_ok=True)
    rank, size = launched_ranks()
    if args.ranks > 1 and size == 1:
        argv = [a for i, a in enumerate(sys.argv[1:]) if a != "--ranks" and not a.startswith("--ranks=")
                and not (i > 0 and sys.argv[i] == "--ranks")]
        cmd = mpirun_command(args.ranks) + [sys.executable, os.path.abspath(__file__), *argv]
        sys.exit(subprocess.run(cmd).returncode)

    runs = []
    todo = [(o, m, s) for o in OBJECTS for m in METHODS for s in range(1, args.seeds + 1)]
    if size > 1:
        runs = run_on_ranks(args, todo, rank, size)
        if runs is None:
            return
    else:
        with tempfile.TemporaryDirectory(prefix="table1-") as workdir, \
                concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
            jobs = [pool.submit(run_one, args, o, m, s, workdir) for o, m, s in todo]
            for i, job in enumerate(concurrent.futures.as_completed(jobs), 1):
                runs.append(job.result())
                print(f"\r{i}/{len(jobs)} runs", end="", file=sys.stderr, flush=True)
        print(file=sys.stderr)
    runs.sort(key=lambda r: (list(OBJECTS).index(r["object"]), list(METHODS).index(r["method"]), r["seed"]))

    with open(os.path.join(args.out, "runs.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["object", "method", "seed", "final_chamfer_mm", "convergence_touches", "final_points", "wall_time_s"])
        for r in runs:
            w.writerow([r["object"], r["method"], r["seed"], f"{r['final_chamfer_mm']:.4f}",
                        int(r["convergence_touches"]), int(r["points"]), f"{r['wall_time_s']:.2f}"])

    rows, curves = [], []
    for obj in OBJECTS:
        for method in METHODS:
            group = [r for r in runs if r["object"] == obj and r["method"] == method]
            touches = min(len(r["curve"]) for r in group)
            mean_curve = [statistics.fmean(r["curve"][t] for r in group) for t in range(touches)]
            sd_curve = [statistics.stdev(r["curve"][t] for r in group) if len(group) > 1 else 0.0
                        for t in range(touches)]
            for t in range(touches):
                curves.append([obj, method, t + 1, f"{mean_curve[t]:.4f}", f"{sd_curve[t]:.4f}"])
            cd_mean, cd_sd = mean_sd([r["final_chamfer_mm"] for r in group])
            conv = convergence(mean_curve)
            # Steps as the paper counts them: explorations after the random start.
            steps = conv - INITIAL_RANDOM
            explorations = touches - INITIAL_RANDOM
            pts_mean, _ = mean_sd([r["points"] for r in group])
            time_mean, _ = mean_sd([r["wall_time_s"] for r in group])
            rows.append({
                "object": obj, "method": method, "final_cd_mm": cd_mean, "final_cd_sd_mm": cd_sd,
                "convergence_steps": steps if conv < touches else f"{explorations}+",
                "final_points": pts_mean, "wall_time_s": time_mean, "seeds": len(group),
            })

    with open(os.path.join(args.out, "table1.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["object", "method", "final_mean_cd_mm", "cd_sd_mm", "convergence_steps", "final_points",
                    "seeds", "mean_wall_time_s", "paper_cd_mm", "paper_steps", "paper_points"])
        for r in rows:
            p = PAPER[(r["object"], r["method"])]
            w.writerow([r["object"], r["method"], f"{r['final_cd_mm']:.3f}", f"{r['final_cd_sd_mm']:.3f}",
                        r["convergence_steps"], f"{r['final_points']:.1f}", r["seeds"], f"{r['wall_time_s']:.2f}",
                        *p])
    with open(os.path.join(args.out, "curves.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["object", "method", "touch", "mean_chamfer_mm", "sd_chamfer_mm"])
        w.writerows(curves)

    with open(os.path.join(args.out, "table1.md"), "w") as f:
        f.write("# Table 1 in simulation\n\n")
        f.write(f"Point-level simulation (marker truth, no images), {args.seeds} seeds per cell; "
                "final mean chamfer distance (Eq. 11, estimate -> CAD) after the last touch, mean +- sd over seeds; "
                "convergence steps: explorations (touches after the 4 random ones) until the seed-averaged "
                "curve stays within 5% of its final value; final points: mean training points of the GP. "
                "Paper: real robot, 3D-printed objects (its Table 1).\n\n")
        f.write("Made by `benchmarks/table1/make_table1.py --out benchmarks/table1` "
                "(see benchmarks/table1/README.md).\n\n")
        f.write("| object | method | final mean CD (mm) | convergence steps | final points | paper CD (mm) | "
                "paper steps | paper points | mean run time (s) |\n")
        f.write("|---|---|---|---|---|---|---|---|---|\n")
        for r in rows:
            p = PAPER[(r["object"], r["method"])]
            f.write(f"| {OBJECTS[r['object']]} | {r['method']} | {r['final_cd_mm']:.3f} +- {r['final_cd_sd_mm']:.3f} | "
                    f"{r['convergence_steps']} | {r['final_points']:.1f} | {p[0]} | {p[1]} | {p[2]} | "
                    f"{r['wall_time_s']:.2f} |\n")

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("make_table1: no plot (python3-matplotlib is missing); the CSV and Markdown files are complete",
              file=sys.stderr)
        return
    fig, axes = plt.subplots(1, len(OBJECTS), figsize=(11, 4.2), sharey=False)
    for ax, obj in zip(axes, OBJECTS):
        for method in METHODS:
            pts = [c for c in curves if c[0] == obj and c[1] == method]
            xs = [c[2] for c in pts]
            ys = [float(c[3]) for c in pts]
            sd = [float(c[4]) for c in pts]
            ax.plot(xs, ys, label=method, linewidth=2 if method == "Ours" else 1.2)
            ax.fill_between(xs, [y - s for y, s in zip(ys, sd)], [y + s for y, s in zip(ys, sd)], alpha=0.12)
        ax.axvline(INITIAL_RANDOM + 0.5, color="grey", linestyle=":", linewidth=1)
        ax.set_title(OBJECTS[obj])
        ax.set_xlabel("touch")
        ax.set_ylabel("chamfer distance, estimate -> CAD (mm)")
        ax.set_yscale("log")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend()
    fig.suptitle(f"Chamfer distance after each touch (mean +- sd over {args.seeds} seeds, simulation)")
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "curves.png"), dpi=110)


if __name__ == "__main__":
    main()
