#!/usr/bin/env python3
"""Writes ball_cap.ply: the top of a calibration ball (radius 4 mm, its top
10 mm above the table) for photometric_calibration, as a height-field mesh on
a 0.05 mm grid (binary PLY, mm). Only the cap within 3.6 mm of the axis (a
press never reaches further); beyond it the rim is flat. Run from this
folder: python3 make_ball_cap.py"""
import math
import struct

RADIUS_MM, TOP_MM, REACH_MM, GRID_MM = 4.0, 10.0, 3.6, 0.05

n = int(round(REACH_MM / GRID_MM))
side = 2 * n + 1
vertices = []
for j in range(side):
    for i in range(side):
        x, y = (i - n) * GRID_MM, (j - n) * GRID_MM
        r2 = min(x * x + y * y, REACH_MM * REACH_MM)
        vertices.append((x, y, TOP_MM - RADIUS_MM + math.sqrt(RADIUS_MM * RADIUS_MM - r2)))
faces = []
for j in range(side - 1):
    for i in range(side - 1):
        a, b, c, d = j * side + i, j * side + i + 1, (j + 1) * side + i + 1, (j + 1) * side + i
        faces += [(a, b, c), (a, c, d)]
with open("ball_cap.ply", "wb") as f:
    f.write(("ply\nformat binary_little_endian 1.0\ncomment calibration ball cap, radius %g mm, make_ball_cap.py\n"
             "element vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
             "element face %d\nproperty list uchar int vertex_indices\nend_header\n"
             % (RADIUS_MM, len(vertices), len(faces))).encode())
    for v in vertices:
        f.write(struct.pack("<fff", *v))
    for face in faces:
        f.write(struct.pack("<Biii", 3, *face))
print("ball_cap.ply: %d vertices, %d faces" % (len(vertices), len(faces)))
