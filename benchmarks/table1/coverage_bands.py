#!/usr/bin/python3
"""Where a Table 1 surface's error lies: near the touches' points or far from them.

Runs one Table 1 method for a given number of touches (the first T touches of
the 34-touch run: the loop does not look ahead), splits the sampled surface's
lattice points into bands by their (x, y) distance to the nearest fitted touch
point, and scores each band against the CAD mesh with `touchcloud score`
(Eq. 11, estimate -> CAD, the run's own ground-truth sampling). A band's mean
times its share of the lattice adds up to the run's chamfer distance, so the
table says whether the error after T touches is coverage (lattice far from any
touch) or the estimate near the data (sensing, the GP's fit). A second table
per run measures each touch's footprint (the object within 2 mm (x, y) of
that touch's salient points), their sum and their union: how much of the
object a touch can cover at all.

Usage (from the repository root, after building):
  benchmarks/table1/coverage_bands.py --out benchmarks/table1/coverage_bands.md   # both objects, both sensors
  benchmarks/table1/coverage_bands.py --object fox_mask --sensor realistic \\
      --method FVR+SF+M52 --seed 1 --touches 17 34

Prints Markdown tables (and writes them with --out). Needs python3-numpy.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(ROOT, "benchmarks", "peers"))
from make_table1 import METHODS, PIPELINE  # noqa: E402
from score_scipy import read_pcd_xyz  # noqa: E402

BANDS_MM = [0.0, 2.0, 5.0, 10.0, float("inf")]  # 2 mm: about one marker spacing


def nearest_xy_distance(np, queries, points, chunk=1024):
    """(x, y) distance of each query to its nearest point; brute force in chunks."""
    out = np.empty(len(queries))
    p = points[:, :2]
    for s in range(0, len(queries), chunk):
        q = queries[s:s + chunk, :2]
        d2 = (q[:, None, 0] - p[None, :, 0]) ** 2 + (q[:, None, 1] - p[None, :, 1]) ** 2
        out[s:s + chunk] = np.sqrt(d2.min(axis=1))
    return out


def write_pcd_xyz(path, np, xyz):
    with open(path, "wb") as f:
        f.write(("VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                 f"WIDTH {len(xyz)}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS {len(xyz)}\nDATA binary\n").encode())
        f.write(np.asarray(xyz, dtype="<f4").tobytes())


def bands_after(args, np, obj, sensor, touches, work):
    out = os.path.join(work, f"t{touches}")
    pipeline = os.path.join(ROOT, "pipelines", PIPELINE[sensor].format(object=obj))
    cmd = [args.touchcloud, "run", with_touch_writer(pipeline, work), "--out", out, "--seed", str(args.seed), "--quiet",
           "--set", f"explore.max_iterations={touches}"]
    for kv in METHODS[args.method] + args.set:
        cmd += ["--set", kv]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    chamfer = summary["metrics"]["score.final_chamfer_mm"]["value"]
    # The files by their roles, whatever the pipeline names them.
    by_role = {a["role"]: a["file"] for a in summary["artifacts"] if a.get("file")}
    surface = read_pcd_xyz(os.path.join(out, by_role["reconstructed_surface"]), np)
    points = read_pcd_xyz(os.path.join(out, by_role["touch_points"]), np)
    near = nearest_xy_distance(np, surface, points)
    files, shares = [], []
    for k, (lo, hi) in enumerate(zip(BANDS_MM[:-1], BANDS_MM[1:])):
        sel = (near >= lo) & (near < hi)
        if sel.any():
            files.append(os.path.join(work, f"t{touches}_band{k}.pcd"))
            write_pcd_xyz(files[-1], np, surface[sel])
        shares.append((lo, hi, sel.mean()))
    scored = json.loads(subprocess.run(
        [args.touchcloud, "score", "--gt", os.path.join(ROOT, "sample_clouds", obj, "mesh.ply"),
         "--metrics", "chamfer_est_to_gt", "--json"] + files, check=True, capture_output=True, text=True).stdout)
    means = {os.path.basename(r["estimate"]): r["metrics"]["chamfer_est_to_gt_mm"] for r in scored}
    rows = []
    for k, (lo, hi, share) in enumerate(shares):
        mean = means.get(f"t{touches}_band{k}.pcd")
        rows.append((lo, hi, share, mean))
    # The bands must add up to the run's own score (the same ground-truth
    # samples); otherwise the table would split some other number.
    total = sum(share * mean for _, _, share, mean in rows if mean is not None)
    if abs(total - chamfer) > 1e-6 * max(1.0, chamfer):
        sys.exit(f"{obj}, {sensor}, {touches} touches: the bands add up to {total} mm, the run scored {chamfer} mm")
    return chamfer, len(points), rows, footprints(np, obj, touches, out)


def with_touch_writer(pipeline, work):
    """A copy of `pipeline` that also writes each touch's salient points (touch_<k>.pcd)."""
    with open(pipeline) as f:
        text = f.read()
    anchor = "        - id: thin\n"
    if text.count(anchor) != 1:
        sys.exit(f"{pipeline}: no single '- id: thin' stage in the explore loop to write the salient points beside")
    writer = ("        - id: write_touch\n          plugin: cloud_writer\n"
              "          params: {path: 'touch_{iteration}.pcd'}\n          inputs: {cloud: salient.cloud}\n")
    text = text.replace(anchor, writer + anchor).replace("../sample_clouds/", os.path.join(ROOT, "sample_clouds") + "/")
    copy = os.path.join(work, os.path.basename(pipeline))
    with open(copy, "w") as f:
        f.write(text)
    return copy


def object_rectangle(obj):
    """The object's (x, y) rectangle from its scene's workspace: section (the objects fill it)."""
    box = {}
    with open(os.path.join(ROOT, "sample_clouds", obj, "scene.yaml")) as f:
        for line in f:
            for axis in ("x_mm", "y_mm"):
                if line.strip().startswith(axis + ":"):
                    lo, hi = line.split("[", 1)[1].split("]", 1)[0].split(",")
                    box[axis] = (float(lo), float(hi))
    return box["x_mm"], box["y_mm"]


def footprints(np, obj, touches, out):
    """Mean area one touch observes, their sum and their union, over the object's rectangle."""
    (x0, x1), (y0, y1) = object_rectangle(obj)
    step = 0.5
    gx, gy = np.meshgrid(np.arange(x0 + step / 2, x1, step), np.arange(y0 + step / 2, y1, step))
    raster = np.c_[gx.ravel(), gy.ravel()]
    union = np.zeros(len(raster), bool)
    areas = []
    for k in range(touches):
        path = os.path.join(out, f"touch_{k}.pcd")
        seen = np.zeros(len(raster), bool)
        if os.path.exists(path):  # a touch with no salient point writes nothing
            pts = read_pcd_xyz(path, np)
            if len(pts):
                seen = nearest_xy_distance(np, raster, pts) <= BANDS_MM[1]
        areas.append(seen.sum() * step * step)
        union |= seen
    area = (x1 - x0) * (y1 - y0)
    return {"object": area, "mean": float(np.mean(areas)), "summed": sum(areas) / area, "covered": float(union.mean())}


def table(args, np, obj, sensor):
    lines = [f"{obj}, {sensor} sensor, {args.method}, seed {args.seed}"
             + (f", {' '.join(args.set)}" if args.set else "") + ":", "",
             "| touches | chamfer (mm) | touch points | nearest touch point (x, y) | share of lattice | "
             "mean distance to CAD (mm) | share of the chamfer |", "|---|---|---|---|---|---|---|"]
    prints = ["", "Each touch's footprint: the object's area within 2 mm (x, y) of that touch's salient points "
              "(before dedup), on a 0.5 mm raster of the object's rectangle:", "",
              "| touches | object (mm^2) | one touch's footprint, mean (mm^2) | object / footprint | "
              "footprints summed / object | object covered by their union |", "|---|---|---|---|---|---|"]
    with tempfile.TemporaryDirectory(prefix="coverage_bands_") as work:
        for t in args.touches:
            chamfer, n, rows, fp = bands_after(args, np, obj, sensor, t, work)
            prints.append(f"| {t} | {fp['object']:.0f} | {fp['mean']:.0f} | {fp['object'] / fp['mean']:.1f} | "
                          f"{fp['summed']:.2f} | {100 * fp['covered']:.1f} % |")
            for lo, hi, share, mean in rows:
                band = f"{lo:g}-{hi:g} mm" if hi != float("inf") else f">= {lo:g} mm"
                part = "-" if mean is None else f"{mean * share / chamfer:.2f}"
                lines.append(f"| {t} | {chamfer:.3f} | {n} | {band} | {100 * share:.1f} % | "
                             f"{'-' if mean is None else f'{mean:.3f}'} | {part} |")
    return lines + prints + [""]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--object", choices=["fox_mask", "wave_surface"], help="default: both")
    ap.add_argument("--sensor", choices=list(PIPELINE), help="default: both")
    ap.add_argument("--method", choices=list(METHODS), default="FVR+SF+M52")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--touches", type=int, nargs="+", default=[17, 34])
    ap.add_argument("--set", action="append", default=[], metavar="K=V", help="another override, as for touchcloud run")
    ap.add_argument("--touchcloud", default=os.path.join(ROOT, "build", "bin", "touchcloud"))
    ap.add_argument("--out", help="also write the table to this file")
    args = ap.parse_args()
    import numpy as np

    lines = [f"Made by `benchmarks/table1/coverage_bands.py {' '.join(sys.argv[1:])}`.", ""]
    objects = [args.object] if args.object else ["fox_mask", "wave_surface"]
    sensors = [args.sensor] if args.sensor else list(PIPELINE)
    for obj in objects:
        for sensor in sensors:
            lines += table(args, np, obj, sensor)
    text = "\n".join(lines) + "\n"
    sys.stdout.write(text)
    if args.out:
        with open(args.out, "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
