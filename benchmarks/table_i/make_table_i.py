#!/usr/bin/python3
"""Regenerates Table I and Table II of the colour-pattern GelStereo paper
(the GS-DepthNet paper) in simulation, for the classical matchers (OpenCV's BM and SGBM
at the paper's block sizes 7, 15, 21, 33) and for GS-DepthNet (Ours, Ours
no LR, Ours no SE: three checkpoints, each trained by
pipelines/gs_depthnet_train.yaml with one loss term switched off).
Writes, into --out:

  table_i.md     both tables in the paper's layout, the paper's values beside
  table_i.csv    Table I: one row per matcher, all pixels and contact region
  table_ii.csv   Table II: depth-difference errors per workpiece (mm)
  presses.csv    the test set: indenter, press depth, gel area, per pair

The test set: each indenter of sample_clouds/indenters/ (the paper's
triangle, quadrilateral and pentagon workpieces, plus a ball-nosed pin and
an edge) pressed 0.5, 1.0 and 1.5 mm deep at three areas of the gel, by
benchmarks/table_i/press.yaml; each matcher then runs
benchmarks/table_i/evaluate.yaml over it. Table II (the paper's measured
depth differences) uses the matcher with the lowest contact-region RMSE,
and the true disparity beside it, through the paper's Q reprojection and
through the plate's refraction.

The networks: --train trains the three from pipelines/gs_depthnet_dataset.yaml's
simulated presses (the objects of the test set are not among them) into
--networks (default OUT/networks: ours.ckpt, no_lr.ckpt, no_se.ckpt and
their training curves); without --train the checkpoints already in
--networks are evaluated, and the network rows are left out when there are
none.

Ours falls back to the shipped models/gs_depthnet_w8.ckpt (the same
training) when --networks has no ours.ckpt.

With --ranks N the presses and then the evaluations spread over one
`mpirun -n N` job each (scripts/mpi_launch.py: each rank takes the next run
no rank has taken yet); the tables are the same as with one rank.

Usage (from the repository root, after building):
  benchmarks/table_i/make_table_i.py --out benchmarks/table_i --train        # trains: about 1.5 h on 2 cores
  benchmarks/table_i/make_table_i.py --out benchmarks/table_i                # evaluates the networks there
  [--work DIR] [--jobs 2] [--ranks N] [--networks DIR]
"""
import argparse
import concurrent.futures
import csv
import json
import os
import shutil
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CLI = os.path.join(ROOT, "build", "bin", "touchcloud")
sys.path.insert(0, os.path.join(ROOT, "build", "python"))
import touchcloud  # noqa: E402  (the build's Python module: reads the clouds)
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from mpi_launch import run_each  # noqa: E402

SHAPES = ["triangle", "quadrilateral", "pentagon", "round", "edge"]
FLAT_FACED = {"triangle": "Tri", "quadrilateral": "Quad", "pentagon": "Penta"}  # Table II's workpieces
DEPTHS_MM = [0.5, 1.0, 1.5]
# Where the sensor's centre is, relative to the indenter's axis: the paper's
# "different sensor surface areas" (it used ten; three keep the set small).
GEL_AREAS_MM = [(0.0, 0.0), (4.0, 0.0), (0.0, -4.0)]
BLOCK_SIZES = [7, 15, 21, 33]
MATCHERS = [(f"{name} (block_size, {b})", method, b) for name, method in (("BM", "bm"), ("SGBM", "sgbm"))
            for b in BLOCK_SIZES]
METRICS = ["abs_rel", "sq_rel", "rmse", "rmse_log", "delta1", "delta2", "delta3"]
HEADERS = ["Abs Rel", "Sq Rel", "RMSE", "RMSE log", "δ<1.25", "δ<1.25²", "δ<1.25³"]

PAPER_TABLE_I = {
    "BM (block_size, 7)": [1.353, 11.407, 3.353, 12.852, 0.707, 0.713, 0.714],
    "BM (block_size, 15)": [0.456, 1.815, 1.329, 10.366, 0.796, 0.801, 0.802],
    "BM (block_size, 21)": [0.367, 1.131, 1.037, 9.738, 0.818, 0.823, 0.823],
    "BM (block_size, 33)": [0.296, 0.935, 0.929, 8.651, 0.857, 0.861, 0.861],
    "SGBM (block_size, 7)": [2.710, 24.058, 4.859, 17.178, 0.488, 0.495, 0.496],
    "SGBM (block_size, 15)": [1.611, 12.777, 3.472, 14.972, 0.603, 0.608, 0.609],
    "SGBM (block_size, 21)": [1.312, 9.571, 2.974, 14.247, 0.637, 0.642, 0.643],
    "SGBM (block_size, 33)": [0.615, 2.822, 1.627, 11.467, 0.759, 0.762, 0.763],
}
# The network rows: label, checkpoint file in --networks, the training's loss switches.
NETWORKS = [("Ours", "ours", []), ("Ours no LR", "no_lr", ["train.lr_loss=false"]),
            ("Ours no SE", "no_se", ["train.se_loss=false"])]
PAPER_TABLE_I.update({
    "Ours no LR": [0.275, 0.975, 0.956, 3.098, 0.896, 0.918, 0.928],
    "Ours no SE": [1.264, 5.786, 1.872, 9.573, 0.635, 0.718, 0.746],
    "Ours": [0.243, 0.769, 0.815, 2.157, 0.926, 0.937, 0.942],
})
DIFFERENCES = [(1.5, 0.5), (1.5, 1.0), (1.0, 0.5)]
# Table II: mean and sd (mm) for 1.5-0.5, 1.5-1.0, 1.0-0.5, All.
PAPER_TABLE_II = {
    "Tri": ([-0.105, -0.079, -0.035, -0.076], [0.094, 0.081, 0.049, 0.064]),
    "Quad": ([-0.099, -0.083, -0.441, -0.067], [0.083, 0.072, 0.357, 0.059]),
    "Penta": ([-0.045, 0.006, 0.027, -0.014], [0.051, 0.025, 0.018, 0.029]),
    "All": ([-0.083, -0.052, -0.019, -0.051], [0.064, 0.039, 0.042, 0.047]),
}


def run_cli(args):
    done = subprocess.run([CLI] + args, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"make_table_i: `touchcloud {' '.join(args)}` failed ({done.returncode}):\n{done.stderr}")


def run_all(commands, jobs, ranks, work):
    """`touchcloud ARGS` for each ARGS of COMMANDS: JOBS at a time in this
    process, or with RANKS > 1 spread over an `mpirun -n RANKS` job."""
    if ranks <= 1:
        with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
            list(pool.map(run_cli, commands))
        return
    failed = run_each([[CLI] + args for args in commands], ranks, work)
    if failed:
        command, status, stderr = failed[0]
        sys.exit(f"make_table_i: {len(failed)} of {len(commands)} runs failed; `{' '.join(command)}` "
                 f"({status}):\n{stderr}")


def press_name(shape, depth, area):
    return f"{shape}_d{depth:.1f}_x{area[0]:+.0f}_y{area[1]:+.0f}"


def make_test_set(work, jobs, ranks):
    """One press.yaml run per press (kept from an earlier run in WORK); then one
    dataset (index.csv + camera.yaml) over all of them."""
    presses = [(s, d, a) for s in SHAPES for d in DEPTHS_MM for a in GEL_AREAS_MM]
    folders = [os.path.join(work, "presses", press_name(*press)) for press in presses]
    run_all([["run", os.path.join(ROOT, "benchmarks/table_i/press.yaml"), "--out", out, "--quiet",
              "--set", f"sim.scene={ROOT}/sample_clouds/indenters/{shape}.yaml",
              "--set", f"sim.press_depth_mm={depth}",
              "--set", f"sim.target_xy_mm=[{area[0]},{area[1]}]"]
             for (shape, depth, area), out in zip(presses, folders)
             if not os.path.exists(os.path.join(out, "press", "index.csv"))], jobs, ranks, work)
    rows, camera = [], None
    for i, (press, folder) in enumerate(zip(presses, folders)):
        with open(os.path.join(folder, "press", "index.csv")) as f:
            reader = csv.DictReader(f)
            row = next(reader)
            fields = reader.fieldnames
        rel = os.path.relpath(os.path.join(folder, "press"), work)
        rows.append({k: (os.path.join(rel, v) if k not in ("index", "timestamp_s") and v else v)
                     for k, v in row.items()} | {"index": str(i)})
        with open(os.path.join(folder, "press", "camera.yaml")) as f:
            text = f.read()
        if camera is not None and text != camera:
            sys.exit(f"make_table_i: {folder} was rendered by another camera than the first press")
        camera = text
    with open(os.path.join(work, "index.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        w.writerows(rows)
    with open(os.path.join(work, "camera.yaml"), "w") as f:
        f.write(camera)
    return presses


def metric(summary, name):
    m = summary["metrics"][name]
    return m["value"] if "value" in m else m["values"][-1]


def train_networks(work, networks):
    """The dataset (once), then one training per network row; returns {file: seconds}."""
    dataset = os.path.join(work, "gs_depthnet_dataset")
    if not os.path.exists(os.path.join(dataset, "summary.json")):
        run_cli(["run", os.path.join(ROOT, "pipelines/gs_depthnet_dataset.yaml"), "--seed", "1", "--out", dataset,
                 "--quiet"])
    os.makedirs(networks, exist_ok=True)
    seconds = {}
    for label, name, switches in NETWORKS:
        out = os.path.join(work, "train", name)
        shutil.rmtree(out, ignore_errors=True)
        start = time.time()
        args = ["run", os.path.join(ROOT, "pipelines/gs_depthnet_train.yaml"), "--seed", "1", "--out", out, "--quiet",
                "--set", f"train.index={dataset}/fox/index.csv",
                "--set", f"train.extra_index={dataset}/wave/index.csv",
                "--set", f"train.rest_index={dataset}/rest/index.csv",
                # Weights and rest disparity only, as models/gs_depthnet_w8.ckpt: ours.ckpt is that file.
                "--set", "train.save_optimizer=false"]
        for s in switches:
            args += ["--set", s]
        run_cli(args)
        seconds[name] = time.time() - start
        shutil.copy(os.path.join(out, "gs_depthnet.ckpt"), os.path.join(networks, f"{name}.ckpt"))
        for curve in ("training_curve.csv", "training_curve.png"):
            shutil.copy(os.path.join(out, curve), os.path.join(networks, f"{name}_{curve}"))
        print(f"make_table_i: trained {label} in {seconds[name]:.0f} s", flush=True)
    return seconds


def evaluation(work, presses, method, block, checkpoint=None):
    """One evaluation run for run_all, a classical matcher's (evaluate.yaml) or a
    network checkpoint's (evaluate_net.yaml): (its folder, emptied; its arguments)."""
    out = os.path.join(work, "eval", os.path.basename(checkpoint) if checkpoint else f"{method}_{block}")
    shutil.rmtree(out, ignore_errors=True)
    pipeline = "evaluate_net.yaml" if checkpoint else "evaluate.yaml"
    method_args = (["--set", f"disparity.checkpoint={checkpoint}"] if checkpoint else
                   ["--set", f"disparity.method={method}", "--set", f"disparity.block_size_px={block}"])
    return out, ["run", os.path.join(ROOT, "benchmarks/table_i", pipeline), "--out", out, "--quiet",
                 "--set", f"pairs.index={os.path.join(work, 'index.csv')}",
                 "--set", f"pairs_loop.max_iterations={len(presses)}"] + method_args


def evaluate(label, out):
    """Table I's row of the run in OUT."""
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    row = {"method": label}
    for region in ("all", "contact"):
        for m in METRICS:
            key = f"metrics.{m}_{region}_px" if m == "rmse" else f"metrics.{m}_{region}"
            row[f"{m}_{region}"] = metric(summary, key)
        row[f"coverage_{region}"] = metric(summary, f"metrics.coverage_{region}")
    return row


def contact_height_mm(path):
    """Median height (sensor z, mm) of a press's contact cloud; None when the matcher left it empty."""
    if not os.path.exists(path):
        return None
    points = touchcloud.read_cloud(path)
    return statistics.median(points[:, 2].tolist()) if len(points) else None


def table_ii(presses, eval_dir, cloud):
    """Per flat-faced workpiece and depth pair: measured minus commanded depth difference (mm)."""
    height = {}
    for i, press in enumerate(presses):
        height[press] = contact_height_mm(os.path.join(eval_dir, "clouds", f"{cloud}_{i}.pcd"))
    errors = {}  # (workpiece, difference) -> [mm]
    for shape, name in FLAT_FACED.items():
        for deep, shallow in DIFFERENCES:
            for area in GEL_AREAS_MM:
                a, b = height[(shape, shallow, area)], height[(shape, deep, area)]
                if a is None or b is None:
                    continue
                # Pressing deeper moves the gel surface towards the plate (smaller z).
                err = (a - b) - (deep - shallow)
                errors.setdefault((name, (deep, shallow)), []).append(err)
                errors.setdefault((name, "All"), []).append(err)
                errors.setdefault(("All", (deep, shallow)), []).append(err)
                errors.setdefault(("All", "All"), []).append(err)
    return errors


def mean_sd(values):
    if not values:
        return float("nan"), float("nan")
    return statistics.fmean(values), (statistics.stdev(values) if len(values) > 1 else 0.0)


def write_outputs(out, rows, best, ii, presses, seconds, trained):
    with open(os.path.join(out, "table_i.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    with open(os.path.join(out, "presses.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["index", "indenter", "press_depth_mm", "gel_area_x_mm", "gel_area_y_mm"])
        for i, (shape, depth, area) in enumerate(presses):
            w.writerow([i, shape, depth, area[0], area[1]])
    columns = [f"{d}-{s}" for d, s in DIFFERENCES] + ["All"]
    with open(os.path.join(out, "table_ii.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["disparity", "conversion", "workpiece", "statistic"] + columns + ["n"])
        for (source, conversion), errors in ii.items():
            for piece in list(FLAT_FACED.values()) + ["All"]:
                stats = [mean_sd(errors.get((piece, k), [])) for k in DIFFERENCES + ["All"]]
                n = len(errors.get((piece, "All"), []))
                w.writerow([source, conversion, piece, "mean"] + [f"{m:.4f}" for m, _ in stats] + [n])
                w.writerow([source, conversion, piece, "sd"] + [f"{s:.4f}" for _, s in stats] + [n])

    def fmt(v):
        return f"{v:.3f}"

    lines = ["# Table I and II of the colour-pattern GelStereo (the GS-DepthNet paper), simulated", "",
             f"Regenerated by `benchmarks/table_i/make_table_i.py --out benchmarks/table_i"
             f"{' --train' if trained else ''}` "
             f"({len(presses)} presses: {len(SHAPES)} indenters x {len(DEPTHS_MM)} depths x {len(GEL_AREAS_MM)} "
             f"gel areas, 256 x 256; {seconds:.0f} s" +
             ("; trained " + ", ".join(f"{n} in {s / 60:.0f} min" for n, s in trained.items()) if trained else "") +
             "). See README.md here for what differs from the paper.", "",
             "## Table I: disparity errors, contact region (ours) and the paper's", "",
             "| Method | " + " | ".join(HEADERS) + " | coverage |",
             "|---|" + "---|" * (len(HEADERS) + 1)]
    for r in rows:
        lines.append(f"| {r['method']} | " + " | ".join(fmt(r[f'{m}_contact']) for m in METRICS) +
                     f" | {r['coverage_contact']:.3f} |")
        paper = PAPER_TABLE_I.get(r["method"])
        if paper:
            lines.append("| *paper* | " + " | ".join(f"*{v:.3f}*" for v in paper) + " | |")
    lines += ["", "## Table I: disparity errors, all pixels of the gel", "",
              "| Method | " + " | ".join(HEADERS) + " | coverage |", "|---|" + "---|" * (len(HEADERS) + 1)]
    for r in rows:
        lines.append(f"| {r['method']} | " + " | ".join(fmt(r[f'{m}_all']) for m in METRICS) +
                     f" | {r['coverage_all']:.3f} |")
    lines += ["", f"## Table II: measured minus commanded depth difference (mm), mean / sd", "",
              f"Disparity from {best} (the classical matcher of lowest contact RMSE), from GS-DepthNet (Ours) "
              "where it was evaluated, and from the truth; the contact region's median "
              "height, by the paper's Q reprojection and by rays traced through the plate.", "",
              "| disparity | conversion | workpiece | " + " | ".join(columns) + " |",
              "|---|---|---|" + "---|" * len(columns)]
    for (source, conversion), errors in ii.items():
        for piece in list(FLAT_FACED.values()) + ["All"]:
            stats = [mean_sd(errors.get((piece, k), [])) for k in DIFFERENCES + ["All"]]
            lines.append(f"| {source} | {conversion} | {piece} | " +
                         " | ".join(f"{m:.3f} / {s:.3f}" for m, s in stats) + " |")
    for piece, (means, sds) in PAPER_TABLE_II.items():
        lines.append(f"| *paper (GS-DepthNet)* | *Q* | *{piece}* | " +
                     " | ".join(f"*{m:.3f} / {s:.3f}*" for m, s in zip(means, sds)) + " |")
    with open(os.path.join(out, "table_i.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", required=True, help="folder for the tables")
    ap.add_argument("--work", default=None, help="folder for the test set and runs (default: OUT/work, removed)")
    ap.add_argument("--jobs", type=int, default=2, help="runs (presses, evaluations) at once on one rank")
    ap.add_argument("--ranks", type=int, default=1,
                    help="MPI ranks to spread the presses and the evaluations over (mpirun -n N)")
    ap.add_argument("--networks", default=None,
                    help="folder of the network rows' checkpoints (default OUT/networks)")
    ap.add_argument("--train", action="store_true", help="train the three networks into --networks first")
    args = ap.parse_args()
    if not os.access(CLI, os.X_OK):
        sys.exit(f"make_table_i: {CLI} not found: build first (scripts/build.sh)")
    os.makedirs(args.out, exist_ok=True)
    work = os.path.abspath(args.work or os.path.join(args.out, "work"))
    os.makedirs(work, exist_ok=True)
    start = time.time()
    networks = os.path.abspath(args.networks or os.path.join(args.out, "networks"))
    trained = train_networks(work, networks) if args.train else {}
    presses = make_test_set(work, args.jobs, args.ranks)
    evaluations = {label: evaluation(work, presses, method, block) for label, method, block in MATCHERS}
    for label, name, _ in NETWORKS:
        checkpoint = os.path.join(networks, f"{name}.ckpt")
        if name == "ours" and not os.path.exists(checkpoint):
            checkpoint = os.path.join(ROOT, "models", "gs_depthnet_w8.ckpt")
        if os.path.exists(checkpoint):
            evaluations[label] = evaluation(work, presses, None, None, checkpoint)
    run_all([run for _, run in evaluations.values()], args.jobs, args.ranks, work)
    folders = {label: folder for label, (folder, _) in evaluations.items()}
    rows = [evaluate(label, folder) for label, folder in folders.items()]
    best = min((r for r in rows if r["method"] in {m[0] for m in MATCHERS}), key=lambda r: r["rmse_contact"])["method"]
    ii = {}
    sources = [(best, "est", folders[best])] + ([("Ours", "est", folders["Ours"])] if "Ours" in folders else [])
    for source, prefix, folder in sources + [("truth", "truth", folders[best])]:
        for conversion, suffix in (("Q", "q"), ("refraction", "refr")):
            ii[(source, conversion)] = table_ii(presses, folder, f"{prefix}_{suffix}")
    write_outputs(args.out, rows, best, ii, presses, time.time() - start, trained)
    if not args.work:
        shutil.rmtree(work)
    print(f"wrote {args.out}/table_i.md, table_i.csv, table_ii.csv, presses.csv ({time.time() - start:.0f} s)")


if __name__ == "__main__":
    main()
