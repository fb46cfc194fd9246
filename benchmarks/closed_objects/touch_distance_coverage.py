#!/usr/bin/env python3
"""Where a reconstruction of a shipped closed shape misses it: near the
touches or away from them.

The shape's area (uniform samples on its mesh, placed as its scene places
it) is split by region (region_recall.py's) and by the distance from each
sample to the nearest touched point (`<shape>_touch_points.pcd`); each band's
coverage is the share of its samples within the threshold of the final
surface (`<shape>_surface.pcd`). A region with little area near the touches
was not reached; one with a low coverage close to the touches is missed by
the model between them. With several --run folders the figures are their
means.

A second table counts only touched points on the same side of the shape:
where its outward normal (the mesh's at the sample nearest the touched
point) lies within 60 degrees of the sample's. On a thin wall a touch on
one face lies a wall's thickness from the other face, which no press
reached; the second table does not count it there.

  benchmarks/closed_objects/touch_distance_coverage.py --shape mug --run out/mug [--run out/mug2]

Needs NumPy and SciPy (python3-numpy, python3-scipy).
"""
import argparse
import os
import sys

import numpy as np
from scipy.spatial import cKDTree

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from region_recall import placed_mesh, read_xyz_pcd, region_of  # noqa: E402

BANDS_MM = [0.0, 3.0, 8.0, 15.0, float("inf")]
SAME_SIDE_COS = 0.5  # outward normals within 60 degrees: the same side of the shape


def samples(shape, count, seed):
    """`count` points uniform by area on the placed mesh, each one's region and its triangle's
    outward unit normal."""
    verts, faces, offset = placed_mesh(shape)
    v = np.asarray(verts)
    tri = np.asarray(faces)
    a, b, c = v[tri[:, 0]], v[tri[:, 1]], v[tri[:, 2]]
    areas = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    rng = np.random.default_rng(seed)
    which = rng.choice(len(tri), size=count, p=areas / areas.sum())
    u, w = rng.random(count), rng.random(count)
    flip = u + w > 1
    u[flip], w[flip] = 1 - u[flip], 1 - w[flip]
    points = a[which] + u[:, None] * (b - a)[which] + w[:, None] * (c - a)[which]
    names = np.array([region_of(shape, verts, f, offset) for f in faces], dtype=object)
    n = np.cross(b - a, c - a)[which]
    return points, names[which], n / np.linalg.norm(n, axis=1)[:, None]


def fibonacci_directions(count):
    """`count` unit vectors spread evenly over the sphere."""
    k = np.arange(count) + 0.5
    z = 1 - 2 * k / count
    phi = np.pi * (1 + 5 ** 0.5) * k
    r = np.sqrt(1 - z * z)
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1)


def same_side_distance(points, normals, touched, touched_normals, bins=256):
    """Distance from each sample to the nearest touched point on its side (normals within 60 degrees,
    judged against the sample's normal rounded to one of `bins` directions); inf where there is none."""
    directions = fibonacci_directions(bins)
    which = np.argmax(normals @ directions.T, axis=1)
    out = np.full(len(points), np.inf)
    for j in np.unique(which):
        mine = which == j
        facing = touched[touched_normals @ directions[j] > SAME_SIDE_COS]
        if len(facing):
            out[mine] = cKDTree(facing).query(points[mine])[0]
    return out


def band_tables(shape, runs, fscore_mm, count, seed):
    """{same_side: {(region, band index): (share of the region's area, coverage)}} averaged over
    `runs`, banded by the distance to the nearest touched point anywhere (False) and to the nearest
    on the sample's side of the shape (True)."""
    points, regions, normals = samples(shape, count, seed)
    sample_tree = cKDTree(points)
    sums = {False: {}, True: {}}
    for run in runs:
        touched = np.asarray(read_xyz_pcd(os.path.join(run, f"{shape}_touch_points.pcd")))
        surface = np.asarray(read_xyz_pcd(os.path.join(run, f"{shape}_surface.pcd")))
        if len(touched) == 0 or len(surface) == 0:
            raise RuntimeError(f"{run}: no touched points or no surface points")
        covered = cKDTree(surface).query(points)[0] <= fscore_mm
        touched_normals = normals[sample_tree.query(touched)[1]]
        nearest = {False: cKDTree(touched).query(points)[0],
                   True: same_side_distance(points, normals, touched, touched_normals)}
        for same_side, near in nearest.items():
            # No touched point on its side at all: the farthest band.
            band = np.minimum(np.searchsorted(BANDS_MM, near, side="right") - 1, len(BANDS_MM) - 2)
            for region in sorted(set(regions)):
                mine = regions == region
                for k in range(len(BANDS_MM) - 1):
                    cell = mine & (band == k)
                    s = sums[same_side].setdefault((region, k), [0.0, 0.0, 0])
                    s[0] += cell.sum() / mine.sum()
                    if cell.any():
                        s[1] += covered[cell].mean()
                        s[2] += 1
    return {side: {key: (s[0] / len(runs), s[1] / s[2] if s[2] else float("nan")) for key, s in table.items()}
            for side, table in sums.items()}


def band_table(shape, runs, fscore_mm, count, seed, same_side=False):
    """One of band_tables' two tables."""
    return band_tables(shape, runs, fscore_mm, count, seed)[same_side]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--shape", required=True, help="a shipped closed shape: sphere, pebble, step, torus, mug")
    parser.add_argument("--run", action="append", required=True,
                        help="a run's output folder (with <shape>_surface.pcd and <shape>_touch_points.pcd); repeat")
    parser.add_argument("--fscore-mm", type=float, default=2.0, help="coverage threshold (mm)")
    parser.add_argument("--samples", type=int, default=100000, help="points sampled on the shape")
    args = parser.parse_args()
    for run in args.run:
        for name in ("surface", "touch_points"):
            if not os.path.exists(os.path.join(run, f"{args.shape}_{name}.pcd")):
                parser.error(f"--run {run}: no {args.shape}_{name}.pcd there")
    bands = [f"{lo:g}-{hi:g} mm" if hi != float("inf") else f"over {lo:g} mm" for lo, hi in zip(BANDS_MM, BANDS_MM[1:])]
    tables = band_tables(args.shape, args.run, args.fscore_mm, args.samples, seed=1)
    for same_side, which in ((False, "the nearest touched point"),
                             (True, "the nearest touched point on the same side (normals within 60 degrees)")):
        table = tables[same_side]
        if same_side:
            print()
        print(f"Share of each region's area by distance to {which}, and its coverage at "
              f"{args.fscore_mm:g} mm ({len(args.run)} run(s)):\n")
        print("| region | " + " | ".join(bands) + " |\n|---|" + "---|" * len(bands))
        for region in sorted({r for r, _ in table}):
            cells = []
            for k in range(len(bands)):
                share, coverage = table[(region, k)]
                cells.append(f"{share:.2f}" + ("" if coverage != coverage else f" ({coverage:.2f})"))
            print(f"| {region} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    sys.exit(main())
