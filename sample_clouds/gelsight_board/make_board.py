#!/usr/bin/env python3
"""Writes board.ply: the indenter board the GelSight-type sensor's networks
are trained on (pipelines/tactile_nets_dataset.yaml), nine objects 20 mm apart
on a 3 x 3 grid, each within a 12 mm square and 12 mm high (binary PLY, mm,
z = 0 on the table). None of them is an object of the held-out evaluation
(benchmarks/monocular/: a 5 mm sphere, a standing cylinder's edge, a thread,
text, the fox mask's nose):

    ( -20, 20) ball, radius 4 mm    (0, 20) dome, radius 10 mm    (20, 20) cone, slope 0.5
    ( -20,  0) triangle prism       (0,  0) square prism, 20 deg  (20,  0) pentagon prism
    ( -20,-20) lying cylinder r 3   (0,-20) 90-degree roof edge   (20,-20) 120-degree roof edge

The balls' tops are height fields on a 0.1 mm grid (finer than the
sensor's 0.06 mm pixel would show as facets), the cone has 360 facets, flat
faces are exact. Only upper surfaces and walls: the simulator reads the
highest triangle above each point, and the table elsewhere. Run from this folder: python3 make_board.py"""
import math
import struct

TOP_MM = 12.0
SPACING_MM = 20.0


class Mesh:
    def __init__(self):
        self.vertices, self.faces = [], []

    def add(self, vertices, faces, dx=0.0, dy=0.0, yaw_deg=0.0):
        c, s = math.cos(math.radians(yaw_deg)), math.sin(math.radians(yaw_deg))
        base = len(self.vertices)
        self.vertices += [(c * x - s * y + dx, s * x + c * y + dy, z) for x, y, z in vertices]
        self.faces += [[base + i for i in f] for f in faces]


def height_field(half, step, height):
    """A square grid of +-half (mm) with z = height(x, y), two triangles per cell."""
    n = int(round(2 * half / step))
    vertices = [(-half + i * step, -half + j * step, height(-half + i * step, -half + j * step))
                for j in range(n + 1) for i in range(n + 1)]
    faces = []
    for j in range(n):
        for i in range(n):
            a, b, c, d = j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1, (j + 1) * (n + 1) + i
            faces += [[a, b, c], [a, c, d]]
    return vertices, faces


def cap(radius, cut):
    """Top of a ball of `radius` whose top is at TOP_MM, out to `cut` from its axis."""
    def z(x, y):
        r2 = x * x + y * y
        return TOP_MM - radius + math.sqrt(radius * radius - r2) if r2 <= cut * cut else 0.0
    return z


def cone(radius, slope, segments=360):
    """A cone of `slope` with its apex at TOP_MM over a disc of `radius`, and its wall."""
    ring = [(radius * math.cos(2 * math.pi * k / segments), radius * math.sin(2 * math.pi * k / segments))
            for k in range(segments)]
    vertices = [(0.0, 0.0, TOP_MM)] + [(x, y, TOP_MM - slope * radius) for x, y in ring] + [(x, y, 0.0) for x, y in ring]
    faces = []
    for k in range(segments):
        j = (k + 1) % segments
        faces += [[0, 1 + k, 1 + j], [1 + k, 1 + segments + k, 1 + segments + j], [1 + k, 1 + segments + j, 1 + j]]
    return vertices, faces


def flat_top(corners):
    """A prism's top face at TOP_MM (a fan over a convex polygon) and its walls."""
    n = len(corners)
    vertices = [(x, y, TOP_MM) for x, y in corners] + [(x, y, 0.0) for x, y in corners]
    faces = [[0, i, i + 1] for i in range(1, n - 1)]
    for i in range(n):
        j = (i + 1) % n
        faces += [[i, n + i, n + j], [i, n + j, j]]
    return vertices, faces


def polygon(sides, circumradius):
    return [(circumradius * math.cos(2 * math.pi * k / sides + math.pi / 2),
             circumradius * math.sin(2 * math.pi * k / sides + math.pi / 2)) for k in range(sides)]


def extrusion(profile_yz, length):
    """A profile in the (y, z) plane, from y = -a to y = +a over the table,
    extruded along x over `length`: its upper surface in strips."""
    n = len(profile_yz)
    vertices = [(x, y, z) for x in (-length / 2, length / 2) for y, z in profile_yz]
    faces = []
    for k in range(n - 1):
        faces += [[k, k + 1, n + k + 1], [k, n + k + 1, n + k]]
    return vertices, faces


def roof(angle_deg, half_width):
    drop = half_width / math.tan(math.radians(angle_deg / 2))
    return [(-half_width, 0.0), (-half_width, TOP_MM - drop), (0.0, TOP_MM), (half_width, TOP_MM - drop),
            (half_width, 0.0)]


def lying_cylinder(radius, steps=120):
    axis = TOP_MM - radius
    profile = [(-radius, 0.0)]
    profile += [(-radius * math.cos(math.pi * k / steps), axis + radius * math.sin(math.pi * k / steps))
                for k in range(steps + 1)]
    return profile + [(radius, 0.0)]


board = Mesh()
at = lambda col, row: (col * SPACING_MM, row * SPACING_MM)
board.add(*height_field(4.2, 0.1, cap(4.0, 4.0)), *at(-1, 1))
board.add(*height_field(6.0, 0.1, cap(10.0, 6.0)), *at(0, 1))
board.add(*cone(6.0, 0.5), *at(1, 1))
board.add(*flat_top(polygon(3, 5.0)), *at(-1, 0))
board.add(*flat_top(polygon(4, 5.0)), *at(0, 0), yaw_deg=20)
board.add(*flat_top(polygon(5, 5.0)), *at(1, 0))
board.add(*extrusion(lying_cylinder(3.0), 12.0), *at(-1, -1), yaw_deg=30)
board.add(*extrusion(roof(90, 5.0), 12.0), *at(0, -1), yaw_deg=45)
board.add(*extrusion(roof(120, 5.0), 12.0), *at(1, -1), yaw_deg=-20)

with open("board.ply", "wb") as f:
    f.write(("ply\nformat binary_little_endian 1.0\ncomment touchcloud indenter board, mm, make_board.py\n"
             "element vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
             "element face %d\nproperty list uchar int vertex_indices\nend_header\n"
             % (len(board.vertices), len(board.faces))).encode())
    for v in board.vertices:
        f.write(struct.pack("<fff", *v))
    for face in board.faces:
        f.write(struct.pack("<Biii", 3, *face))
print("board.ply: %d vertices, %d faces" % (len(board.vertices), len(board.faces)))
