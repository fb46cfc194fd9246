#!/usr/bin/env python3
"""Which parts of a shipped closed shape a reconstruction recalls.

The shape's mesh, placed as its scene places it, is split into named
regions (the mug: bottom on the table, outer wall, rim, inner wall, inner
floor, handle; the torus: the outer half, the hole's side; every other
shape: faces looking up, sideways and down), and a run's final surface
(`<shape>_surface.pcd`) is scored with `touchcloud score` against each
region alone: the region's coverage (recall) is the share of its surface
within the threshold of the reconstruction. Regions a touch cannot reach
(a face on the table) are named as such; nothing is left out.

  benchmarks/closed_objects/region_recall.py --shape mug --run out/mug [--fscore-mm 2]

make_closed_objects_table.py writes these figures for every run in regions.csv.
"""
import argparse
import json
import math
import os
import re
import struct
import subprocess
import sys
import tempfile

# The mug as make_closed_objects.py builds it: a cup of radius 40 mm and
# height 90 mm about z, a 4 mm wall, a 6 mm base, a handle on +x.
MUG_RADIUS_MM, MUG_WALL_MM, MUG_HEIGHT_MM, MUG_BASE_MM = 40.0, 4.0, 90.0, 6.0
MUG_CUP_VERTICES = 2 + 4 * 72  # the revolved cup's; the handle's vertices follow
TORUS_MAJOR_MM = 40.0


def placed_mesh(shape):
    """The shape's mesh (vertices in mm, triangles) placed as its scene.yaml
    places it (a translation), and that translation."""
    folder = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "sample_clouds", "closed_objects",
                          shape)
    with open(os.path.join(folder, "scene.yaml")) as f:
        xyz = re.search(r"pose: \{xyz_mm: \[([^\]]*)\], rpy_deg: \[0, 0, 0\]\}", f.read())
    if not xyz:
        raise SystemExit(f"{folder}/scene.yaml: the object's pose is not a translation; cannot place its mesh here")
    offset = [float(v) for v in xyz.group(1).split(",")]
    with open(os.path.join(folder, f"{shape}.ply")) as f:
        lines = f.read().split("\n")
    count = {l.split()[1]: int(l.split()[2]) for l in lines if l.startswith("element ")}
    start = lines.index("end_header") + 1
    verts = [[float(v) + o for v, o in zip(l.split(), offset)] for l in lines[start:start + count["vertex"]]]
    faces = [tuple(int(i) for i in l.split()[1:4])
             for l in lines[start + count["vertex"]:start + count["vertex"] + count["face"]]]
    return verts, faces, offset


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def area(verts, face):
    a, b, c = (verts[i] for i in face)
    return 0.5 * math.dist((0, 0, 0), cross([b[i] - a[i] for i in range(3)], [c[i] - a[i] for i in range(3)]))


def on_table(verts, face):
    return all(abs(verts[i][2]) < 1e-6 for i in face)


def region_of(shape, verts, face, offset):
    """The region a triangle belongs to, by its centroid in the mesh's own frame (and its normal)."""
    c = [sum(verts[i][k] for i in face) / 3 - offset[k] for k in range(3)]
    if on_table(verts, face):
        return "bottom, on the table"
    if shape == "mug":
        r = math.hypot(c[0], c[1])
        if min(face) >= MUG_CUP_VERTICES:
            return "handle"
        if abs(c[2] - MUG_HEIGHT_MM) < 1e-3:
            return "rim"
        if r > MUG_RADIUS_MM - MUG_WALL_MM / 2:
            return "outer wall"
        if abs(c[2] - MUG_BASE_MM) < 1e-3:
            return "inner floor"
        return "inner wall"
    if shape == "torus":
        return "hole's side" if math.hypot(c[0], c[1]) < TORUS_MAJOR_MM else "outer half"
    a, b, d = (verts[i] for i in face)
    n = cross([b[k] - a[k] for k in range(3)], [d[k] - a[k] for k in range(3)])
    nz = n[2] / (math.dist((0, 0, 0), n) or 1)
    return "facing up" if nz > 0.5 else "facing down" if nz < -0.5 else "facing sideways"


def read_xyz_pcd(path):
    """The points [(x, y, z)] of a binary x y z float PCD (cloud_writer's)."""
    with open(path, "rb") as f:
        data = f.read()
    marker = b"DATA binary\n"
    if marker not in data:
        raise RuntimeError(f"{path}: not a binary PCD")
    body = data.index(marker) + len(marker)
    header = data[:body].decode("ascii")
    count = re.search(r"^POINTS (\d+)$", header, re.M)
    if "FIELDS x y z\n" not in header or "TYPE F F F\n" not in header or not count:
        raise RuntimeError(f"{path}: not an x y z float PCD")
    return list(struct.iter_unpack("<fff", data[body:body + 12 * int(count.group(1))]))


def write_ply(path, verts, faces):
    with open(path, "w") as f:
        f.write(f"ply\nformat ascii 1.0\nelement vertex {len(verts)}\nproperty float x\nproperty float y\n"
                f"property float z\nelement face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n")
        f.writelines("%.4f %.4f %.4f\n" % tuple(v) for v in verts)
        f.writelines(f"3 {a} {b} {c}\n" for a, b, c in faces)


def region_meshes(shape, folder):
    """Writes one PLY per region into `folder`: [(region, path, share of the area)]."""
    verts, faces, offset = placed_mesh(shape)
    by_region = {}
    for face in faces:
        by_region.setdefault(region_of(shape, verts, face, offset), []).append(face)
    total = sum(area(verts, f) for f in faces)
    out = []
    for k, (region, mine) in enumerate(sorted(by_region.items())):
        path = os.path.join(folder, f"{shape}_region{k}.ply")
        write_ply(path, verts, mine)
        out.append((region, path, sum(area(verts, f) for f in mine) / total))
    return out


def region_recalls(touchcloud, shape, surface, fscore_mm, meshes):
    """[(region, share of the area, recall)] of the cloud `surface` against each of `meshes` (region_meshes)."""
    out = []
    for region, path, share in meshes:
        done = subprocess.run([touchcloud, "score", surface, "--gt", path, "--json", "--metrics", "fscore",
                               "--fscore-threshold", str(fscore_mm), "--samples", "100000", "--threads", "1"],
                              capture_output=True, text=True)
        if done.returncode != 0:
            raise RuntimeError(f"touchcloud score {surface} against {shape}'s {region} failed ({done.returncode}):\n"
                               f"{done.stderr}")
        out.append((region, share, json.loads(done.stdout)[0]["metrics"]["recall"]))
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--shape", required=True, help="a shipped closed shape: sphere, pebble, step, torus, mug")
    parser.add_argument("--run", required=True, help="a run's output folder (with <shape>_surface.pcd)")
    parser.add_argument("--touchcloud", default="build/bin/touchcloud")
    parser.add_argument("--fscore-mm", type=float, default=2.0, help="coverage threshold (mm)")
    args = parser.parse_args()
    surface = os.path.join(args.run, f"{args.shape}_surface.pcd")
    if not os.path.exists(surface):
        parser.error(f"--run {args.run}: no {args.shape}_surface.pcd there")
    with tempfile.TemporaryDirectory() as scratch:
        rows = region_recalls(args.touchcloud, args.shape, surface, args.fscore_mm, region_meshes(args.shape, scratch))
    print(f"| region of the {args.shape} | share of the area | coverage at {args.fscore_mm:g} mm |\n|---|---|---|")
    for region, share, recall in rows:
        print(f"| {region} | {share:.3f} | {recall:.3f} |")


if __name__ == "__main__":
    sys.exit(main())
