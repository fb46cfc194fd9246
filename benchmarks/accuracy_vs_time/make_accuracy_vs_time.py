#!/usr/bin/python3
"""What accuracy costs in time on the fox mask: `touchcloud sweep` of
pipelines/fox_mask_active_pixels.yaml (the whole exploration through marker
pixels, matching and RSRT triangulation), one trade-off at a time against
the shipped settings (the baseline):

  GP             exact GP vs the sparse VFE approximation with m inducing points
  kernel         RBF (shipped) vs Matern 5/2
  dedup          de-duplication threshold (Eq. 7)
  touches        exploration budget
  LSR            fraction of each touch's points kept (1/4 mimics a low-resolution sensor)
  triangulation  refractive (RSRT) vs pinhole, which ignores the plate

Writes, into --out: accuracy_vs_time.csv and .md (final chamfer distance,
Eq. 11, and wall time per setting, mean and sd over seeds, plus where the time
goes) and accuracy_vs_time.png/.svg (accuracy against time, Pareto front
marked). Usage, from the repository root after building:

  benchmarks/accuracy_vs_time/make_accuracy_vs_time.py --out benchmarks/accuracy_vs_time
  benchmarks/accuracy_vs_time/make_accuracy_vs_time.py --out DIR --ranks 2   # each sweep under mpirun -n 2

With --ranks N every sweep runs under mpirun -n N (touchcloud sweep hands
each run to the next free rank); the accuracies are the same, the times
differ.
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from mpi_launch import mpirun_command  # noqa: E402
from plot_sweep import pareto_front  # noqa: E402

PIPELINE = "pipelines/fox_mask_active_pixels.yaml"
ACCURACY = "score.final_chamfer_mm"
# (trade-off, --vary arguments); the baseline is the pipeline as shipped.
FACTORS = [
    ("baseline", ["dedup.threshold_mm=1.8"]),
    ("GP", ["fit.method=sparse", "fit.inducing_points=64,128,256"]),
    ("kernel", ["fit.kernel=matern52"]),
    ("dedup", ["dedup.threshold_mm=0.9,3.6"]),
    ("touches", ["explore.max_iterations=10,20"]),
    ("LSR", ["thin.keep_ratio=0.25,0.5"]),
    ("triangulation", ["rsrt.refraction=false"]),
]
STAGE_TIMES = ["time_sensor_s", "time_match_s", "time_rsrt_s", "time_fit_s", "time_plan_s", "time_score_s"]


def run_sweep(args, name, varies, out):
    cmd = [args.touchcloud, "sweep", PIPELINE, "--repeats", str(args.repeats), "--out", out]
    if args.ranks > 1:  # the sweep spreads its runs over the ranks; rank 0 writes the same files
        cmd = mpirun_command(args.ranks) + cmd
    for v in varies:
        cmd += ["--vary", v]
    print(f"{name}: {' '.join(cmd)}", file=sys.stderr, flush=True)
    done = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        sys.exit(f"make_accuracy_vs_time: the {name} sweep failed ({done.returncode}):\n{done.stderr}")
    with open(os.path.join(out, "sweep_summary.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    keys = list(rows[0])[1:list(rows[0]).index("runs")]
    for r in rows:
        r["factor"] = name
        r["setting_label"] = "as shipped" if name == "baseline" else ", ".join(f"{k}={r[k]}" for k in keys)
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--touchcloud", default="build/bin/touchcloud")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--out", required=True)
    ap.add_argument("--ranks", type=int, default=1, help="MPI ranks each sweep spreads its runs over (mpirun -n N)")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)

    rows = []
    with tempfile.TemporaryDirectory(prefix="accuracy-vs-time-") as work:
        for name, varies in FACTORS:
            rows += run_sweep(args, name, varies, os.path.join(work, name))

    columns = ["factor", "setting_label", "runs", ACCURACY, ACCURACY + "_std", "wall_time_s", "wall_time_s_std",
               "dedup.total_points"] + STAGE_TIMES
    with open(os.path.join(args.out, "accuracy_vs_time.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["factor", "setting", "runs", "final_chamfer_mm", "final_chamfer_mm_sd", "wall_time_s",
                    "wall_time_s_sd", "final_points"] + STAGE_TIMES)
        for r in rows:
            w.writerow([r.get(c, "") for c in columns])

    pts = [(float(r["wall_time_s"]), float(r[ACCURACY])) for r in rows]
    front = set(pareto_front(pts))
    with open(os.path.join(args.out, "accuracy_vs_time.md"), "w") as f:
        f.write("# What accuracy costs in time (fox mask, simulation)\n\n")
        f.write(f"`{PIPELINE}`: 4 random + up to 30 variance-driven touches, every touch through marker pixels, "
                f"stereo matching and RSRT triangulation; {args.repeats} seeds per setting; one trade-off changed "
                "at a time from the shipped settings. Final chamfer distance: Eq. 11, GP mean on the 200 x 200 "
                "grid -> CAD mesh. Time: wall time of the whole run on one machine (simulation included; "
                "`fit` is the GP, `sensor` the simulator). * marks the Pareto front.\n\n")
        f.write("Made by `benchmarks/accuracy_vs_time/make_accuracy_vs_time.py --out benchmarks/accuracy_vs_time`.\n\n")
        f.write("| trade-off | setting | final chamfer (mm) | wall time (s) | GP fit (s) | final points | Pareto |\n")
        f.write("|---|---|---|---|---|---|---|\n")
        for i, r in enumerate(rows):
            f.write(f"| {r['factor']} | {r['setting_label']} | {float(r[ACCURACY]):.3f} +- "
                    f"{float(r[ACCURACY + '_std']):.3f} | {float(r['wall_time_s']):.2f} +- "
                    f"{float(r['wall_time_s_std']):.2f} | {float(r.get('time_fit_s') or 0):.2f} | "
                    f"{float(r.get('dedup.total_points') or 0):.0f} | {'*' if i in front else ''} |\n")

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("make_accuracy_vs_time: no plot (python3-matplotlib is missing); the tables are complete",
              file=sys.stderr)
        return
    fig, ax = plt.subplots(figsize=(9, 6))
    for name, _ in FACTORS:
        idx = [i for i, r in enumerate(rows) if r["factor"] == name]
        ax.errorbar([pts[i][0] for i in idx], [pts[i][1] for i in idx],
                    yerr=[float(rows[i][ACCURACY + "_std"]) for i in idx], fmt="o", capsize=2, label=name)
        for i in idx:
            ax.annotate(rows[i]["setting_label"].replace("fit.", "").replace("dedup.", "").replace("explore.", "")
                        .replace("thin.", "").replace("rsrt.", ""), pts[i], fontsize=7, xytext=(4, 3),
                        textcoords="offset points")
    fp = sorted(pts[i] for i in front)
    ax.plot([p[0] for p in fp], [p[1] for p in fp], "-", color="tab:red", linewidth=1, label="Pareto front")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time per run (s)")
    ax.set_ylabel("final chamfer distance, estimate -> CAD (mm)")
    ax.set_title(f"Fox mask: accuracy against time (mean +- sd over {args.repeats} seeds)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(args.out, f"accuracy_vs_time.{ext}"), dpi=120)


if __name__ == "__main__":
    main()
