#!/usr/bin/env python3
"""Two closed meshes a user might bring, and their scenes (made by touchcloud-make-scene):

  torus/   a ring 110 mm across, 30 mm tall: its hole and outer sides no press from above reaches
  sphere/  a ball 30 mm across, smaller than the GelStereo's 65 mm gel: every touch covers all of it

    sample_clouds/closed_objects/make_closed_objects.py [build/bin/touchcloud-make-scene]

Meshes are ASCII PLY in mm, outward-facing triangles, written deterministically.
"""
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def torus(major_mm=40.0, minor_mm=15.0, around=72, tube=36):
    verts = []
    for i in range(around):
        u = 2 * math.pi * i / around
        for j in range(tube):
            v = 2 * math.pi * j / tube
            r = major_mm + minor_mm * math.cos(v)
            verts.append((r * math.cos(u), r * math.sin(u), minor_mm * math.sin(v)))
    faces = []
    for i in range(around):
        for j in range(tube):
            a, b = i * tube + j, ((i + 1) % around) * tube + j
            c, d = ((i + 1) % around) * tube + (j + 1) % tube, i * tube + (j + 1) % tube
            faces += [(a, b, c), (a, c, d)]
    return verts, faces


def sphere(radius_mm=15.0, rings=36, segments=72):
    verts = [(0.0, 0.0, radius_mm)]
    for k in range(1, rings):
        t = math.pi * k / rings
        for s in range(segments):
            p = 2 * math.pi * s / segments
            verts.append((radius_mm * math.sin(t) * math.cos(p), radius_mm * math.sin(t) * math.sin(p),
                          radius_mm * math.cos(t)))
    verts.append((0.0, 0.0, -radius_mm))
    faces = []
    ring = lambda k, s: 1 + (k - 1) * segments + s % segments
    for s in range(segments):
        faces.append((0, ring(1, s), ring(1, s + 1)))
    for k in range(1, rings - 1):
        for s in range(segments):
            a, b, c, d = ring(k, s), ring(k + 1, s), ring(k + 1, s + 1), ring(k, s + 1)
            faces += [(a, b, c), (a, c, d)]
    last = len(verts) - 1
    for s in range(segments):
        faces.append((ring(rings - 1, s), last, ring(rings - 1, s + 1)))
    return verts, faces


def write_ply(path, verts, faces, comment):
    with open(path, "w") as f:
        f.write(f"ply\nformat ascii 1.0\ncomment {comment}\nelement vertex {len(verts)}\n"
                "property float x\nproperty float y\nproperty float z\n"
                f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n")
        for v in verts:
            f.write("%.4f %.4f %.4f\n" % v)
        for a, b, c in faces:
            f.write(f"3 {a} {b} {c}\n")


def main():
    make_scene = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "../../build/bin/touchcloud-make-scene")
    for name, (verts, faces), comment in [
            ("torus", torus(), "torus, major radius 40 mm, minor radius 15 mm (CC0, made by make_closed_objects.py)"),
            ("sphere", sphere(), "sphere, radius 15 mm (CC0, made by make_closed_objects.py)")]:
        mesh = os.path.join(HERE, f"{name}.ply")
        write_ply(mesh, verts, faces, comment)
        # The scene beside the mesh; make-scene copies the mesh into the object's folder.
        subprocess.run([make_scene, mesh, "--name", name, "--out", HERE], check=True)
        os.remove(mesh)


if __name__ == "__main__":
    main()
