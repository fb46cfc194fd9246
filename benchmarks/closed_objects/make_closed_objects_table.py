#!/usr/bin/python3
"""The shipped closed shapes (sample_clouds/closed_objects/) reconstructed
by up to six methods with the same seeds: touched from above (at most --touches)
as the height-field GP of the main job (pipelines/fox_mask_active.yaml, its
max-variance choice) and as the implicit surface
(pipelines/closed_object_active.yaml, its variance as a press from above
meets it); touched from any side (at most --all-sides-touches) as the
implicit surface with side_touch's choice (pipelines/closed_object_all_sides.yaml),
by the Palm 2.0's 65 mm dome (scene.yaml), by a 20 mm fingertip dome
(scene_fingertip.yaml), and by the Palm 2.0 as imperfect as the real one
(pipelines/closed_object_all_sides_realistic.yaml on scene_realistic.yaml:
the touches read from rendered images); and, with --methods fingertip_whole,
by the fingertip with the options that reconstruct whole objects
(pipelines/closed_object_fingertip.yaml). Each run is scored against the whole closed mesh
after every touch: Eq. 11 (estimate -> object, the mean chamfer), its 95th
percentile, Hausdorff, completeness (object -> estimate), F-score and
coverage at --fscore-mm, of the whole object and of what a press from above
sees (visible coverage). The final surface less its points on the table (a
face the implicit surface's table_z_mm closed there) is also scored
(touchcloud score) against the object without the faces resting on the
table, which no touch can reach: F-score off the table.

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
the figures do not depend on it. With --runs DIR the runs' folders are kept
in DIR and a run already there (its summary.json, or the failure.txt of a
run that failed) is not made again (a seeded run reproduces bit for bit, so
only its time is the earlier run's): a long table can be finished after it
was stopped. A run that fails is listed with its error
and left out of the means; the others are tabulated.
"""
import argparse
import csv
import json
import os
import platform
import re
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from mpi_launch import run_all  # noqa: E402
from region_recall import (area, on_table as is_on_table, placed_mesh, read_xyz_pcd, region_meshes,  # noqa: E402
                           region_recalls, write_ply)

SHAPES = ["sphere", "pebble", "step", "torus", "mug"]
# key: (method as the table names it, pipeline, scene file in the shape's folder, touched from any side)
METHODS = {
    "height_field": ("height field (GP, max variance)", "pipelines/fox_mask_active.yaml", "scene.yaml", False),
    "implicit": ("implicit surface (GPIS, max variance)", "pipelines/closed_object_active.yaml", "scene.yaml", False),
    "all_sides": ("implicit surface, all sides (GPIS, side_touch)", "pipelines/closed_object_all_sides.yaml",
                  "scene.yaml", True),
    "all_sides_fingertip": ("implicit surface, all sides, 20 mm fingertip", "pipelines/closed_object_all_sides.yaml",
                            "scene_fingertip.yaml", True),
    "all_sides_realistic": ("implicit surface, all sides, realistic sensor",
                            "pipelines/closed_object_all_sides_realistic.yaml", "scene_realistic.yaml", True),
    "fingertip_whole": ("whole object, 20 mm fingertip (closed_object_fingertip)",
                        "pipelines/closed_object_fingertip.yaml", "scene_fingertip.yaml", True),
}
# What --methods is when not given: the five methods of the top-level table.
DEFAULT_METHODS = ["height_field", "implicit", "all_sides", "all_sides_fingertip", "all_sides_realistic"]
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


def command(args, method, shape, seed, out):
    _, pipeline, scene, all_sides = METHODS[method]
    touches = args.all_sides_touches if all_sides else args.touches
    return [args.touchcloud, "run", pipeline, "--seed", str(seed), "--quiet", "--out", out,
            "--scene", f"sample_clouds/closed_objects/{shape}/{scene}",
            "--set", f"explore.max_iterations={touches}", "--set", "score.metrics=all",
            "--set", f"score.fscore_threshold_mm={args.fscore_mm}"] + \
        [word for override in args.set for word in ("--set", override)]


def run_name(args, shape, method, seed):
    """A run's folder: named by everything its figures depend on, so a kept one is only taken for the same run."""
    touches = args.all_sides_touches if METHODS[method][3] else args.touches
    name = f"{shape}-{method}-{touches}touches-seed{seed}-fscore{args.fscore_mm:g}mm"
    return name + "".join("-" + re.sub(r"[^A-Za-z0-9._]", "_", override) for override in args.set)


# A surface point this close to z = 0 lies on the table (a face
# gpis_surface's table_z_mm closed there, not one a touch found).
TABLE_TOLERANCE_MM = 1e-3


def write_off_table_mesh(shape, path):
    """The shape's mesh placed as its scene places it (a translation), less
    the triangles lying on the table (every corner at z = 0): what a touch
    could reach at best. Returns the share of the area left out."""
    verts, faces, _ = placed_mesh(shape)
    on_table = [f for f in faces if is_on_table(verts, f)]
    write_ply(path, verts, [f for f in faces if f not in on_table] if on_table else faces)
    return sum(area(verts, f) for f in on_table) / sum(area(verts, f) for f in faces)


def write_off_table_points(surface, path):
    """The points of a binary x y z PCD (cloud_writer's) that do not lie on
    the table (z = 0, where gpis_surface's table_z_mm closes a surface),
    written to `path` as an ASCII PCD; how many were left out."""
    points = read_xyz_pcd(surface)
    kept = [p for p in points if abs(p[2]) > TABLE_TOLERANCE_MM]
    with open(path, "w") as f:
        f.write("VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                f"WIDTH {len(kept)}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS {len(kept)}\nDATA ascii\n")
        f.writelines(f"{x!r} {y!r} {z!r}\n" for x, y, z in kept)
    return len(points) - len(kept)


def off_table_fscore(args, shape, out, gt, scratch):
    """F-score of the run's final surface less its points on the table
    against the object off the table."""
    surface = os.path.join(scratch, f"{shape}_surface_off_table.pcd")
    write_off_table_points(os.path.join(out, f"{shape}_surface.pcd"), surface)
    done = subprocess.run([args.touchcloud, "score", surface, "--gt", gt, "--json",
                           "--metrics", "fscore", "--fscore-threshold", str(args.fscore_mm),
                           "--samples", "100000", "--threads", "1"], capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError(f"touchcloud score {out} failed ({done.returncode}):\n{done.stderr}")
    return json.loads(done.stdout)[0]["metrics"]["fscore"]


def read_run(out):
    """The final figures and the per-touch series of one run."""
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    final = {"touches": s["loops"]["explore"]["iterations"], "wall_time_s": s["wall_time_s"],
             "refused_touches": s["metrics"].get("plan.refused_touches", {}).get("value")}
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
        # a colour per shape, a line style per method
        style = (":", "--", "-.", "-", "x-", "o-")[[name for name, _, _, _ in METHODS.values()].index(method)]
        for ax, name in zip(axes, ("chamfer_est_to_gt", "fscore")):
            ax.plot(touches, [statistics.fmean(by_touch[t][name]) for t in touches], style,
                    color=f"C{SHAPES.index(shape)}", label=f"{shape}, {method.split(' (')[0]}")
    axes[0].set_ylabel("Eq. 11, estimate -> object (mm)")
    axes[0].set_yscale("log")
    axes[1].set_ylabel(f"F-score at {args.fscore_mm:g} mm")
    for ax in axes:
        ax.set_xlabel("touches")
        ax.grid(True, alpha=0.3)
    axes[1].legend(fontsize=7)
    fig.suptitle(f"Closed shapes touched from above and from any side (mean over seeds {args.seeds_text})")
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "curves.png"), dpi=120)
    return True


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", required=True)
    parser.add_argument("--touchcloud", default="build/bin/touchcloud")
    parser.add_argument("--touches", type=int, default=24, help="touches from above (default 24)")
    parser.add_argument("--all-sides-touches", type=int, default=60, help="touches from any side (default 60)")
    parser.add_argument("--methods", default=",".join(DEFAULT_METHODS),
                        help="of " + ", ".join(METHODS) + " (default: all but fingertip_whole)")
    parser.add_argument("--seeds", default="1", help="e.g. 1-5 or 1,3 (default 1)")
    parser.add_argument("--shapes", default=",".join(SHAPES), help="of " + ", ".join(SHAPES))
    parser.add_argument("--fscore-mm", type=float, default=2.0, help="F-score and coverage threshold (mm)")
    parser.add_argument("--ranks", type=int, default=1, help="MPI ranks to spread the runs over (mpirun -n N)")
    parser.add_argument("--runs", help="keep each run's folder here (default: a temporary folder, removed); a run "
                                       "whose folder already holds its summary.json (or failure.txt) is not made "
                                       "again")
    parser.add_argument("--set", action="append", default=[], metavar="STAGE.PARAM=VALUE",
                        help="a parameter of every run's pipeline, as touchcloud run --set takes it (repeat for "
                             "more; with --methods whose pipelines have that stage): a variant of the table, its "
                             "runs kept apart in --runs")
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
    methods = args.methods.split(",")
    unknown = [m for m in methods if m not in METHODS]
    if unknown:
        parser.error(f"--methods: no method {', '.join(unknown)} (of {', '.join(METHODS)})")
    malformed = [o for o in args.set if not re.fullmatch(r"[A-Za-z0-9_]+\.[A-Za-z0-9_]+=.+", o)]
    if malformed:
        parser.error(f"--set {malformed[0]}: give STAGE.PARAM=VALUE")
    if args.touches < 1 or args.all_sides_touches < 1:
        parser.error("--touches and --all-sides-touches must be at least 1")
    os.makedirs(args.out, exist_ok=True)

    runs = [(shape, key, seed) for shape in shapes for key in methods for seed in seeds]
    rows, per_touch, series_of, failures, region_rows = [], {}, {}, [], []
    with tempfile.TemporaryDirectory(dir=os.path.abspath(args.out)) as scratch:
        folder = os.path.abspath(args.runs) if args.runs else scratch
        outs = [os.path.join(folder, run_name(args, shape, key, seed)) for shape, key, seed in runs]
        made = lambda out: any(os.path.exists(os.path.join(out, f)) for f in ("summary.json", "failure.txt"))
        todo = [command(args, key, shape, seed, out) for (shape, key, seed), out in zip(runs, outs) if not made(out)]
        kept = len(runs) - len(todo)
        for cmd, _, stderr in (run_all(todo, args.ranks, scratch, keep_going=True) if todo else []):
            out = cmd[cmd.index("--out") + 1]
            os.makedirs(out, exist_ok=True)
            with open(os.path.join(out, "failure.txt"), "w") as f:  # a seeded run fails again: kept as made
                f.write(stderr)
        off_table, on_table_share, regions = {}, {}, {}
        for shape in shapes:
            off_table[shape] = os.path.join(scratch, f"{shape}_off_table.ply")
            on_table_share[shape] = write_off_table_mesh(shape, off_table[shape])
            regions[shape] = region_meshes(shape, scratch)
        for (shape, key, seed), out in zip(runs, outs):
            method = METHODS[key][0]
            if not os.path.exists(os.path.join(out, "summary.json")):  # failed: recorded, left out of the means
                with open(os.path.join(out, "failure.txt")) as f:
                    stderr = f.read()
                lines = stderr.strip().splitlines() or ["(no message)"]
                # The located error first ("FILE:LINE:COL: error: stage ..."), else the
                # closing "touchcloud: error: ..." line (a validation's count of problems).
                errors = [l for l in lines if ": error: " in l or l.startswith("touchcloud: error: ")]
                located = [l for l in errors if not l.startswith("touchcloud: error: ")]
                why = (located or errors or lines[-1:])[0]
                why = why.split("error: ", 1)[1] if "error: " in why else why
                failures.append({"shape": shape, "method": method, "seed": seed, "failure": why})
                rows.append({"shape": shape, "method": method, "seed": seed, "failure": why})
                continue
            final, series = read_run(out)
            final["fscore_off_table"] = off_table_fscore(args, shape, out, off_table[shape], scratch)
            surface = os.path.join(out, f"{shape}_surface.pcd")
            for region, share, recall in region_recalls(args.touchcloud, shape, surface, args.fscore_mm, regions[shape]):
                region_rows.append({"shape": shape, "method": method, "seed": seed, "region": region,
                                    "area_share": share, "recall": recall})
            rows.append({"shape": shape, "method": method, "seed": seed, **final})
            by_touch = per_touch.setdefault((shape, method), {})
            for name, values in series.items():
                for t, v in enumerate(values, 1):
                    by_touch.setdefault(t, {n: [] for n, _, _ in METRICS})[name].append(v)
            series_of[(shape, method, seed)] = series

    names = [m for m, _, _ in METRICS]
    extra = ["fscore_off_table", "refused_touches"]
    with open(os.path.join(args.out, "runs.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["shape", "method", "seed", "touches"] + names + extra + ["wall_time_s", "failure"])
        w.writeheader()
        w.writerows(rows)
    with open(os.path.join(args.out, "regions.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["shape", "method", "seed", "region", "area_share", "recall"])
        w.writeheader()
        w.writerows(region_rows)
    with open(os.path.join(args.out, "curves.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["shape", "method", "seed", "touch"] + names)
        for (shape, key, seed) in runs:
            method = METHODS[key][0]
            series = series_of.get((shape, method, seed))
            if series is None:  # failed
                continue
            for t in range(max(len(v) for v in series.values())):
                w.writerow([shape, method, seed, t + 1] +
                           [series[n][t] if t < len(series[n]) else "" for n in names])
    summary = []
    for shape in shapes:
        for key in methods:
            method = METHODS[key][0]
            mine = [r for r in rows if r["shape"] == shape and r["method"] == method and "failure" not in r]
            row = {"shape": shape, "method": method, "seeds": len(mine), "on_table_share": on_table_share[shape],
                   "failed": sum(1 for f in failures if f["shape"] == shape and f["method"] == method)}
            for name in names + extra + ["touches", "wall_time_s"]:
                row[name], row[name + "_sd"] = mean_sd([r[name] for r in mine])
            summary.append(row)
    with open(os.path.join(args.out, "results.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(summary[0].keys()))
        w.writeheader()
        w.writerows(summary)

    plotted = plot(args, per_touch)
    fmt = lambda r, n, d: "-" if r[n] is None else f"{r[n]:.{d}f} ± {r[n + '_sd']:.{d}f}"
    table_share = ", ".join(f"{shape} {on_table_share[shape]:.3f}" for shape in shapes)
    with open(os.path.join(args.out, "results.md"), "w") as f:
        f.write(f"# Closed shapes: touched from above and from any side\n\n"
                f"Made by `benchmarks/closed_objects/make_closed_objects_table.py --out {args.out} "
                f"--seeds {args.seeds} --touches {args.touches} --all-sides-touches {args.all_sides_touches} "
                f"--shapes {','.join(shapes)} --methods {','.join(methods)}"
                f"{''.join(' --set ' + o for o in args.set)}` (at most {args.touches} touches from "
                f"above, {args.all_sides_touches} from any side, fewer where nothing reachable is left; the "
                f"simulator's ideal sensor, but for the realistic sensor's rows) on {platform.machine()} Linux with {os.cpu_count()} cores. Mean ± sd "
                f"over {len(seeds)} seed(s). Distances in mm against the whole closed mesh; F-score and coverage at "
                f"{args.fscore_mm:g} mm; visible coverage is the share of what a press from above can see. "
                f"F-score off the table: the final surface less its points on the table (z = 0) against the object "
                f"without the faces resting on the "
                f"table (their share of the area: {table_share}), which no touch can reach. Refused: touches whose "
                f"first choice the reach check refused (side_touch). Per-touch figures: curves.csv"
                f"{' and curves.png' if plotted else ''}." +
                (f" {kept} of {len(runs)} runs were kept in --runs from an earlier invocation of the same command "
                 f"(a seeded run reproduces bit for bit; their times are those runs')." if kept else "") +
                "\n\n| shape | method | touches | " + " | ".join(t for _, t, _ in METRICS) +
                " | F-score off the table | refused | time (s) |\n"
                "|---|---|---|" + "---|" * len(METRICS) + "---|---|---|\n")
        for r in summary:
            f.write(f"| {r['shape']} | {r['method']} | {fmt(r, 'touches', 1)} | " +
                    " | ".join(fmt(r, n, d) for n, _, d in METRICS) +
                    f" | {fmt(r, 'fscore_off_table', 3)} | {fmt(r, 'refused_touches', 1)} | "
                    f"{fmt(r, 'wall_time_s', 1)} |\n")
        f.write(f"\nCoverage at {args.fscore_mm:g} mm by region of each shape (regions.csv; region_recall.py names "
                f"them; mean over the seeds that ran), the share of the shape's area in brackets:\n\n"
                "| shape | method | coverage by region |\n|---|---|---|\n")
        for shape in shapes:
            for key in methods:
                method = METHODS[key][0]
                mine = [r for r in region_rows if r["shape"] == shape and r["method"] == method]
                cells = [f"{region} ({share:.3f}) {statistics.fmean(r['recall'] for r in mine if r['region'] == region):.3f}"
                         for region, _, share in regions[shape] if any(r["region"] == region for r in mine)]
                f.write(f"| {shape} | {method} | {'; '.join(cells) or '-'} |\n")
        if failures:
            f.write("\nFailed runs (left out of the means above; '-' where every seed failed):\n\n")
            f.writelines(f"- {x['shape']}, {x['method']}, seed {x['seed']}: {x['failure']}\n" for x in failures)


if __name__ == "__main__":
    main()
