#!/usr/bin/env python3
"""Writes the two known objects of benchmarks/sensor_accuracy (binary PLY, mm,
z up, the table at z = 0), as height-field meshes over 60 x 60 mm:
  plane.ply   a flat top 10 mm above the table (eight triangles)
  sphere.ply  a ball of radius 20 mm whose top is 30 mm above the table, on a
              1 mm grid; its cap out to 18 mm from the axis (11.3 mm below the
              top), a flat rim beyond (a press 5.5 mm past first contact
              reaches 14.3 mm from the axis)
A 1 mm grid departs from the sphere by at most 1^2 / (8 x 20) = 0.006 mm.
Run from this folder: python3 make_objects.py"""
import math
import struct

HALF_MM = 30.0


def write(name, height, comment, grid_mm):
    n = int(round(HALF_MM / grid_mm))
    side = 2 * n + 1
    vertices = [((i - n) * grid_mm, (j - n) * grid_mm, height((i - n) * grid_mm, (j - n) * grid_mm))
                for j in range(side) for i in range(side)]
    faces = []
    for j in range(side - 1):
        for i in range(side - 1):
            a, b, c, d = j * side + i, j * side + i + 1, (j + 1) * side + i + 1, (j + 1) * side + i
            faces += [(a, b, c), (a, c, d)]
    with open(name, "wb") as f:
        f.write(("ply\nformat binary_little_endian 1.0\ncomment %s, make_objects.py\n"
                 "element vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
                 "element face %d\nproperty list uchar int vertex_indices\nend_header\n"
                 % (comment, len(vertices), len(faces))).encode())
        for v in vertices:
            f.write(struct.pack("<fff", *v))
        for face in faces:
            f.write(struct.pack("<Biii", 3, *face))
    print("%s: %d vertices, %d faces" % (name, len(vertices), len(faces)))


RADIUS_MM, TOP_MM, REACH_MM = 20.0, 30.0, 18.0
write("plane.ply", lambda x, y: 10.0, "plane 10 mm above the table", HALF_MM)
write("sphere.ply", lambda x, y: TOP_MM - RADIUS_MM + math.sqrt(RADIUS_MM ** 2 - min(x * x + y * y, REACH_MM ** 2)),
      "sphere radius 20 mm, top 30 mm above the table", 1.0)
