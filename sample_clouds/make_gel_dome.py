#!/usr/bin/env python3
"""Writes gel_dome.pcd: points on the GelStereo Palm 2.0 gel, a hemisphere of
65 mm diameter, spread evenly by a Fibonacci spiral (about 1.8 mm apart), in
the sensor frame (mm, z up from the plate). Run from this folder."""
import math

RADIUS_MM = 32.5
N = 2000  # hemisphere area 2*pi*r^2 ~ 6637 mm^2 -> ~1.8 mm spacing

golden = math.pi * (3.0 - math.sqrt(5.0))
points = []
for i in range(N):
    z = 1.0 - (i + 0.5) / N          # cos(polar angle) in (0, 1]: upper half only
    r = math.sqrt(1.0 - z * z)
    phi = golden * i
    points.append((RADIUS_MM * r * math.cos(phi), RADIUS_MM * r * math.sin(phi), RADIUS_MM * z))

with open("gel_dome.pcd", "w") as f:
    f.write("# .PCD v0.7 - GelStereo Palm 2.0 gel dome, mm, sensor frame\n")
    f.write("VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n")
    f.write(f"WIDTH {N}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS {N}\nDATA ascii\n")
    for x, y, z in points:
        f.write(f"{x:.4f} {y:.4f} {z:.4f}\n")
