#!/usr/bin/python3
"""Regenerates Table 1 of the GelStereo Palm 2.0 paper in simulation: both
objects x the five methods (and the next-touch strategies added since) x N
seeds, each a `touchcloud run` of pipelines/<object>_active.yaml (--sensor
ideal: marker truth) or pipelines/<object>_active_realistic.yaml (--sensor
realistic: rendered images through detection, matching and RSRT with a
calibrated sensor) with the method's overrides. Writes, into --out:

  table1.md      the table in the paper's layout, with the paper's numbers beside ours
                 (and, for --sensor realistic, the ideal table's beside them)
  table1.csv     the same, one row per object and method
  runs.csv       every run: final chamfer, p95, Hausdorff, F-score, convergence touches, points, wall time
  curves.csv     mean and standard deviation of each metric after each touch
  curves.png     those curves, one column per object, one row per metric (needs python3-matplotlib)

Besides the mean chamfer distance (Eq. 11) every touch is scored with what
the mean hides: the 95th percentile of the estimate -> CAD distance, the
Hausdorff distance (both directions) and the F-score at 1.5 mm, the
sensor's spatial resolution (--fscore-threshold).

Usage (from the repository root, after building):
  benchmarks/table1/make_table1.py --out benchmarks/table1
  benchmarks/table1/make_table1.py --out benchmarks/table1 --ranks 2   # or under mpirun / srun
  benchmarks/table1/make_table1.py --sensor realistic --out benchmarks/table1/realistic --ranks 2

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

# The methods of Table 1 as overrides of the "Ours" pipelines, then the
# next-touch strategies beside Eq. 10 (touchcloud/planning/: footprint_choice.hpp,
# space_filling.hpp) and the Matern 5/2 kernel, which keeps sharp features
# that the RBF rings at:
#   SF   plan.start=space_filling: the 4 first touches at k-means centroids
#   FVR  plan.strategy=footprint_variance_reduction: the press that leaves
#        the least variance over the workspace
#   M52  fit.kernel=matern52
FVR = "plan.strategy=footprint_variance_reduction"
SF = "plan.start=space_filling"
M52 = "fit.kernel=matern52"
METHODS = {
    "SP": ["salient.keep=deepest"],
    "w/o PCP": ["dedup.enabled=false"],
    "w/o SSG": ["plan.strategy=random"],
    "LSR": ["thin.keep_ratio=0.25"],
    "Ours": [],
    "Ours+SF": [SF],
    "FVR": [FVR],
    "FVR+SF": [FVR, SF],
    "Ours+M52": [M52],
    "FVR+SF+M52": [FVR, SF, M52],
}
# The realistic table leaves out the two rows that only take the ideal one apart.
DEFAULT_METHODS = {"ideal": list(METHODS),
                   "realistic": [m for m in METHODS if m not in ("Ours+SF", "FVR")]}
PAPER_METHODS = ["SP", "w/o PCP", "w/o SSG", "LSR", "Ours"]
# Per-touch metrics of the score stage: (summary.json name, column stem, label, unit).
METRICS = [
    ("chamfer_est_to_gt", "chamfer", "mean chamfer (Eq. 11), estimate -> CAD", "mm"),
    ("p95_est_to_gt", "p95", "95th percentile of the distance, estimate -> CAD", "mm"),
    ("hausdorff", "hausdorff", "Hausdorff distance (both directions)", "mm"),
    ("fscore", "fscore", "F-score", ""),
    ("chamfer_gt_to_est", "completeness", "completeness: mean distance CAD -> estimate", "mm"),
    ("recall", "coverage", "coverage: share of the CAD samples within the F-score threshold of the estimate", ""),
]
# The ground truth -> estimate half of the Hausdorff distance and the F-score's
# recall from 100,000 of the mesh's ~1.7 M (fox) / 1.1 M (wave) samples: four
# times cheaper per touch on this machine; on the fox mask's final surface
# the F-score moved by 1e-4 and the Hausdorff distance not at all.
GT_TO_EST_SAMPLES = 100000
PIPELINE = {"ideal": "{object}_active.yaml", "realistic": "{object}_active_realistic.yaml"}
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
    out = os.path.join(workdir, obj, method.replace("/", "").replace(" ", "_").replace("+", "_"), f"seed{seed}")
    pipeline = os.path.join("pipelines", PIPELINE[args.sensor].format(object=obj))
    cmd = [args.touchcloud, "run", pipeline, "--seed", str(seed), "--out", out]
    metrics = ",".join(name for name, *_ in METRICS)
    for o in [f"score.metrics={metrics}", f"score.fscore_threshold_mm={args.fscore_threshold}",
              f"score.gt_to_est_samples={GT_TO_EST_SAMPLES}"] + METHODS[method] + args.set:
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
        "curves": {stem: m[f"score.{name}"]["series"] for name, stem, *_ in METRICS},
        "final_chamfer_mm": m["score.final_chamfer_mm"]["value"],
        "final_p95_mm": m["score.final_p95_mm"]["value"],
        "final_hausdorff_mm": m["score.final_hausdorff_mm"]["value"],
        "final_fscore": m["score.final_fscore"]["value"],
        "final_completeness_mm": m["score.chamfer_gt_to_est"]["series"][-1],
        "final_coverage": m["score.recall"]["series"][-1],
        "convergence_touches": m["score.convergence_touches"]["value"],
        "points": m["dedup.total_points"]["value"],
        # Lattice points of the final surface more than near_data_margin_mm
        # outside the data near them (surface_sampler's warning).
        "off_data_points": m["surface.off_data_points"]["value"],
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


def touches_to_reach(curve, target):
    """First touch (1-based) whose value is at or below `target`; None if none is."""
    for t, v in enumerate(curve):
        if v <= target:
            return t + 1
    return None


def read_ideal(path):
    """The ideal table's final chamfer per (object, method), for the realistic table; {} without one."""
    if not path or not os.path.exists(path):
        return {}
    with open(path) as f:
        return {(r["object"], r["method"]): r for r in csv.DictReader(f)}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--touchcloud", default="build/bin/touchcloud")
    ap.add_argument("--sensor", choices=sorted(PIPELINE), default="ideal",
                    help="ideal: marker truth (pipelines/<object>_active.yaml); realistic: rendered images, "
                         "detection, matching, RSRT with the calibrated sensor (<object>_active_realistic.yaml)")
    ap.add_argument("--seeds", type=int, default=5)
    ap.add_argument("--jobs", type=int, default=1,
                    help="runs at a time (default 1: a run keeps two cores busy, its background stages "
                         "beside the loop, so more at once slows each and skews the run times)")
    ap.add_argument("--out", required=True)
    ap.add_argument("--ranks", type=int, default=1,
                    help="MPI ranks to spread the runs over (runs this script under mpirun -n N)")
    ap.add_argument("--methods", default=None,
                    help="comma-separated rows to run (default: all for --sensor ideal, all but Ours+SF and FVR "
                         "for realistic)")
    ap.add_argument("--fscore-threshold", type=float, default=1.5,
                    help="F-score threshold in mm (default 1.5, the sensor's spatial resolution)")
    ap.add_argument("--ideal-table", default=None,
                    help="--sensor realistic: the ideal table1.csv to print beside it "
                         "(default: benchmarks/table1/table1.csv)")
    ap.add_argument("--set", action="append", default=[], metavar="K=V",
                    help="an override for every run (e.g. explore.max_iterations=10 for a quick look)")
    args = ap.parse_args()
    if not os.path.exists(args.touchcloud):
        sys.exit(f"make_table1: no {args.touchcloud}; build first (scripts/build.sh)")
    methods = ([m.strip() for m in args.methods.split(",") if m.strip()] if args.methods
               else DEFAULT_METHODS[args.sensor])
    unknown = [m for m in methods if m not in METHODS]
    if unknown:
        print(f"make_table1: --methods: unknown method(s) {', '.join(unknown)} (known: {', '.join(METHODS)})",
              file=sys.stderr)
        sys.exit(2)
    os.makedirs(args.out, exist_ok=True)
    rank, size = launched_ranks()
    if args.ranks > 1 and size == 1:
        argv = [a for i, a in enumerate(sys.argv[1:]) if a != "--ranks" and not a.startswith("--ranks=")
                and not (i > 0 and sys.argv[i] == "--ranks")]
        cmd = mpirun_command(args.ranks) + [sys.executable, os.path.abspath(__file__), *argv]
        sys.exit(subprocess.run(cmd).returncode)

    started = time.monotonic()
    runs = []
    todo = [(o, m, s) for o in OBJECTS for m in methods for s in range(1, args.seeds + 1)]
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
    elapsed_s = time.monotonic() - started
    runs.sort(key=lambda r: (list(OBJECTS).index(r["object"]), methods.index(r["method"]), r["seed"]))

    with open(os.path.join(args.out, "runs.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["object", "method", "seed", "final_chamfer_mm", "final_p95_mm", "final_hausdorff_mm",
                    "final_fscore", "final_completeness_mm", "final_coverage", "convergence_touches", "final_points",
                    "off_data_points", "wall_time_s"])
        for r in runs:
            w.writerow([r["object"], r["method"], r["seed"], f"{r['final_chamfer_mm']:.4f}", f"{r['final_p95_mm']:.4f}",
                        f"{r['final_hausdorff_mm']:.4f}", f"{r['final_fscore']:.4f}",
                        f"{r['final_completeness_mm']:.4f}", f"{r['final_coverage']:.4f}",
                        int(r["convergence_touches"]), int(r["points"]), int(r["off_data_points"]),
                        f"{r['wall_time_s']:.2f}"])

    rows, curves = [], []
    for obj in OBJECTS:
        ours_final = None
        for method in methods:
            group = [r for r in runs if r["object"] == obj and r["method"] == method]
            touches = min(len(r["curves"]["chamfer"]) for r in group)
            mean_curves, sd_curves = {}, {}
            for _, stem, *_ in METRICS:
                mean_curves[stem] = [statistics.fmean(r["curves"][stem][t] for r in group) for t in range(touches)]
                sd_curves[stem] = [statistics.stdev(r["curves"][stem][t] for r in group) if len(group) > 1 else 0.0
                                   for t in range(touches)]
            for t in range(touches):
                row = [obj, method, t + 1]
                for _, stem, *_ in METRICS:
                    row += [f"{mean_curves[stem][t]:.4f}", f"{sd_curves[stem][t]:.4f}"]
                curves.append(row)
            mean_curve = mean_curves["chamfer"]
            cd_mean, cd_sd = mean_sd([r["final_chamfer_mm"] for r in group])
            if method == "Ours":
                ours_final = mean_curve[-1]
            conv = convergence(mean_curve)
            # Steps as the paper counts them: explorations after the random start.
            steps = conv - INITIAL_RANDOM
            explorations = touches - INITIAL_RANDOM
            pts_mean, _ = mean_sd([r["points"] for r in group])
            time_mean, _ = mean_sd([r["wall_time_s"] for r in group])
            off = [int(r["off_data_points"]) for r in group]
            finals = {k: mean_sd([r[k] for r in group])
                      for k in ("final_p95_mm", "final_hausdorff_mm", "final_fscore", "final_completeness_mm",
                                "final_coverage")}
            rows.append({
                "object": obj, "method": method, "final_cd_mm": cd_mean, "final_cd_sd_mm": cd_sd,
                "final_p95_mm": finals["final_p95_mm"], "final_hausdorff_mm": finals["final_hausdorff_mm"],
                "final_fscore": finals["final_fscore"], "mean_curve": mean_curve,
                "final_completeness_mm": finals["final_completeness_mm"], "final_coverage": finals["final_coverage"],
                "convergence_steps": steps if conv < touches else f"{explorations}+",
                "final_points": pts_mean, "wall_time_s": time_mean, "seeds": len(group),
                "off_data_points": statistics.fmean(off), "off_data_runs": sum(1 for v in off if v > 0),
            })
        # Touches each row needs to reach Ours' final (touch 34) mean chamfer.
        for r in rows:
            if r["object"] == obj:
                t = touches_to_reach(r["mean_curve"], ours_final) if ours_final is not None else None
                r["touches_to_ours_final"] = "-" if ours_final is None else (str(t) if t else f">{len(r['mean_curve'])}")

    ideal = read_ideal(args.ideal_table or os.path.join("benchmarks", "table1", "table1.csv")) \
        if args.sensor == "realistic" else {}
    paper = lambda r: PAPER.get((r["object"], r["method"]), ("-", "-", "-"))  # noqa: E731
    pm = lambda v, d=3: f"{v[0]:.{d}f} +- {v[1]:.{d}f}"  # noqa: E731
    with open(os.path.join(args.out, "table1.csv"), "w", newline="") as f:
        w = csv.writer(f)
        header = ["object", "method", "final_mean_cd_mm", "cd_sd_mm", "final_p95_mm", "p95_sd_mm",
                  "final_hausdorff_mm", "hausdorff_sd_mm", "final_fscore", "fscore_sd", "final_completeness_mm",
                  "completeness_sd_mm", "final_coverage", "coverage_sd", "convergence_steps",
                  "touches_to_ours_final", "final_points", "off_data_points", "off_data_runs", "seeds",
                  "mean_wall_time_s",
                  "paper_cd_mm", "paper_steps", "paper_points"]
        if ideal:
            header.append("ideal_cd_mm")
        w.writerow(header)
        for r in rows:
            row = [r["object"], r["method"], f"{r['final_cd_mm']:.3f}", f"{r['final_cd_sd_mm']:.3f}",
                   f"{r['final_p95_mm'][0]:.3f}", f"{r['final_p95_mm'][1]:.3f}",
                   f"{r['final_hausdorff_mm'][0]:.3f}", f"{r['final_hausdorff_mm'][1]:.3f}",
                   f"{r['final_fscore'][0]:.3f}", f"{r['final_fscore'][1]:.3f}",
                   f"{r['final_completeness_mm'][0]:.3f}", f"{r['final_completeness_mm'][1]:.3f}",
                   f"{r['final_coverage'][0]:.3f}", f"{r['final_coverage'][1]:.3f}",
                   r["convergence_steps"], r["touches_to_ours_final"], f"{r['final_points']:.1f}",
                   f"{r['off_data_points']:.1f}", r["off_data_runs"], r["seeds"],
                   f"{r['wall_time_s']:.2f}", *paper(r)]
            if ideal:
                i = ideal.get((r["object"], r["method"]))
                row.append(i["final_mean_cd_mm"] if i else "-")
            w.writerow(row)
    with open(os.path.join(args.out, "curves.csv"), "w", newline="") as f:
        w = csv.writer(f)
        header = ["object", "method", "touch"]
        for _, stem, _, unit in METRICS:
            suffix = f"_{unit}" if unit else ""
            header += [f"mean_{stem}{suffix}", f"sd_{stem}{suffix}"]
        w.writerow(header)
        w.writerows(curves)

    level = ("Point-level simulation (marker truth, no images)" if args.sensor == "ideal" else
             "Realistic sensor (sample_clouds/<object>/scene_realistic.yaml: the true sensor's images rendered "
             "with lens distortion, pixel noise, blur, marker dropout, elastic spread and robot pose noise; "
             "detection, matching and RSRT with the sensor calibrated by rsrt_calibration)")
    command = ("benchmarks/table1/make_table1.py --out " + args.out + (" --sensor realistic" if args.sensor != "ideal" else "")
               + (f" --seeds {args.seeds}" if args.seeds != 5 else "") + (f" --methods '{args.methods}'" if args.methods else ""))
    with open(os.path.join(args.out, "table1.md"), "w") as f:
        f.write("# Table 1 in simulation\n\n")
        f.write(f"{level}, {args.seeds} seeds per cell; final mean chamfer distance (Eq. 11, estimate -> CAD) "
                "after the last touch, mean +- sd over seeds; beside it what the mean hides, after the last touch: "
                "the 95th percentile of the estimate -> CAD distance (p95), the Hausdorff distance (both "
                f"directions) and the F-score at {args.fscore_threshold:g} mm (the sensor's spatial resolution); "
                "what it misses: completeness (mean distance CAD -> estimate) and coverage (share of the CAD "
                f"samples within {args.fscore_threshold:g} mm of the estimate, the F-score's recall); "
                "convergence steps: explorations (touches after the 4 first ones) until the seed-averaged "
                "curve stays within 5% of its final value; to Ours' final: the first touch at which the "
                "seed-averaged curve reaches Ours' final mean chamfer (Ours: touch 34); final points: mean "
                "training points of the GP; off-data: lattice points of the final surface more than 5 mm "
                "(near_data_margin_mm) outside the heights of the data within 2 mm of them, which surface_sampler "
                "warns of, mean over seeds (in how many runs). Paper: real robot, 3D-printed objects (its Table 1).\n\n")
        f.write(f"Made by `{command}` (see benchmarks/table1/README.md); {len(runs)} runs in "
                f"{elapsed_s / 60:.1f} min.\n\n")
        cols = ["object", "method", "final mean CD (mm)", "p95 (mm)", "Hausdorff (mm)",
                f"F@{args.fscore_threshold:g}mm", "completeness (mm)", "coverage", "convergence steps", "touches to Ours' final CD", "final points",
                "off-data lattice points (runs)",
                "paper CD (mm)", "paper steps", "paper points"]
        if ideal:
            cols.append("ideal CD (mm)")
        cols.append("mean run time (s)")
        f.write("| " + " | ".join(cols) + " |\n")
        f.write("|" + "---|" * len(cols) + "\n")
        for r in rows:
            p = paper(r)
            cells = [OBJECTS[r["object"]], r["method"], pm((r["final_cd_mm"], r["final_cd_sd_mm"])),
                     pm(r["final_p95_mm"]), pm(r["final_hausdorff_mm"], 2), pm(r["final_fscore"]),
                     pm(r["final_completeness_mm"]), pm(r["final_coverage"]),
                     str(r["convergence_steps"]), r["touches_to_ours_final"], f"{r['final_points']:.1f}",
                     f"{r['off_data_points']:.1f} ({r['off_data_runs']})", *p]
            if ideal:
                i = ideal.get((r["object"], r["method"]))
                cells.append(i["final_mean_cd_mm"] if i else "-")
            cells.append(f"{r['wall_time_s']:.2f}")
            f.write("| " + " | ".join(cells) + " |\n")

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("make_table1: no plot (python3-matplotlib is missing); the CSV and Markdown files are complete",
              file=sys.stderr)
        return
    fig, axes = plt.subplots(len(METRICS), len(OBJECTS), figsize=(11, 3.3 * len(METRICS)), sharex=True)
    for col, obj in enumerate(OBJECTS):
        for row, (_, stem, label, unit) in enumerate(METRICS):
            ax = axes[row][col]
            for method in methods:
                pts = [c for c in curves if c[0] == obj and c[1] == method]
                xs = [c[2] for c in pts]
                ys = [float(c[3 + 2 * row]) for c in pts]
                sd = [float(c[4 + 2 * row]) for c in pts]
                style = "--" if method not in PAPER_METHODS else "-"
                ax.plot(xs, ys, style, label=method, linewidth=2 if method in ("Ours", "FVR+SF+M52") else 1.2)
                ax.fill_between(xs, [y - s for y, s in zip(ys, sd)], [y + s for y, s in zip(ys, sd)], alpha=0.08)
            ax.axvline(INITIAL_RANDOM + 0.5, color="grey", linestyle=":", linewidth=1)
            if row == 0:
                ax.set_title(OBJECTS[obj])
            if row == len(METRICS) - 1:
                ax.set_xlabel("touch")
            ax.set_ylabel(f"{stem} ({unit})" if unit else f"{stem} at {args.fscore_threshold:g} mm")
            if unit:
                ax.set_yscale("log")
            ax.grid(True, which="both", alpha=0.3)
    axes[0][0].legend(fontsize=8, ncol=2)
    fig.suptitle(f"After each touch, mean +- sd over {args.seeds} seeds ({args.sensor} sensor, simulation)")
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "curves.png"), dpi=100)


if __name__ == "__main__":
    main()
