#!/usr/bin/env python3
"""Closed meshes a user might bring, and their scenes (made by touchcloud-make-scene):

  torus/   a ring 110 mm across, 30 mm tall: its hole and outer sides no press from above reaches
  sphere/  a ball 30 mm across, smaller than the GelStereo's 65 mm gel: every touch covers all of it
  mug/     a cup 80 mm across and 90 mm tall with a handle: a thin rim, a deep inside, a loop
  pebble/  an organic shape about 80 x 60 x 45 mm: smooth, no symmetry, no flat face
  step/    an L-shaped block 90 x 50 x 40 mm: sharp edges, flat faces and an inner corner

Every mesh is closed (each edge shared by two triangles, in opposite directions)
and faces outwards; the mug is two such surfaces, its cup and its handle, meeting.

Beside each scene.yaml, scene_fingertip.yaml: the same scene touched by a
fingertip-sized marker GelStereo, a 20 mm dome (markers 0.9 mm apart on
average, 0.75 mm at least) instead of the Palm 2.0's 65 mm one; its cameras,
plate and robot are the Palm's. A simulated sensor, not a published one: it
is small enough to press inside the mug and the torus's 50 mm hole, which the
65 mm dome cannot enter.

And scene_realistic.yaml: the Palm 2.0 as imperfect as the fox mask's
realistic scene (sample_clouds/fox_mask/scene_realistic.yaml: its tilted
plate and gel, rendered images with vignetting, noise, blur and marker
dropout, the robot's pose noise), for pipelines/closed_object_all_sides_realistic.yaml,
which reads the dots from the images and triangulates them with the sensor
that pipelines/rsrt_calibration.yaml estimated for that true sensor.

    sample_clouds/closed_objects/make_closed_objects.py [build/bin/touchcloud-make-scene]

Meshes are ASCII PLY in mm, outward-facing triangles, written deterministically.
"""
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def torus(major_mm=40.0, minor_mm=15.0, around=72, tube=36, sweep=None):
    """A ring about z; with sweep (u0, u1), only that arc of it, closed by its end discs."""
    verts = []
    steps = around if sweep is None else around + 1
    for i in range(steps):
        u = 2 * math.pi * i / around if sweep is None else sweep[0] + (sweep[1] - sweep[0]) * i / around
        for j in range(tube):
            v = 2 * math.pi * j / tube
            r = major_mm + minor_mm * math.cos(v)
            verts.append((r * math.cos(u), r * math.sin(u), minor_mm * math.sin(v)))
    faces = []
    for i in range(around):
        for j in range(tube):
            a, b = i * tube + j, ((i + 1) % steps) * tube + j
            c, d = ((i + 1) % steps) * tube + (j + 1) % tube, i * tube + (j + 1) % tube
            faces += [(a, b, c), (a, c, d)]
    if sweep is not None:  # the end discs, each a fan round its centre
        for i, flip in ((0, False), (around, True)):
            u = sweep[0] + (sweep[1] - sweep[0]) * i / around
            centre = len(verts)
            verts.append((major_mm * math.cos(u), major_mm * math.sin(u), 0.0))
            for j in range(tube):
                a, b = i * tube + j, i * tube + (j + 1) % tube
                faces.append((centre, b, a) if flip else (centre, a, b))
    return verts, faces


def lat_long(point, rings, segments):
    """A closed surface round the origin from point(theta, phi): poles at
    theta 0 and pi, `rings` bands between them, `segments` around."""
    verts = [point(0.0, 0.0)]
    for k in range(1, rings):
        for s in range(segments):
            verts.append(point(math.pi * k / rings, 2 * math.pi * s / segments))
    verts.append(point(math.pi, 0.0))
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


def sphere(radius_mm=15.0):
    return lat_long(lambda t, p: (radius_mm * math.sin(t) * math.cos(p), radius_mm * math.sin(t) * math.sin(p),
                                  radius_mm * math.cos(t)), rings=36, segments=72)


def revolve(profile, segments=72):
    """A closed surface of revolution about z from a profile of (r, z) points
    that starts and ends on the axis (r = 0), traced so the surface faces out."""
    verts, index = [], []
    for r, z in profile:
        if r == 0:
            index.append([len(verts)] * segments)
            verts.append((0.0, 0.0, z))
        else:
            index.append([len(verts) + s for s in range(segments)])
            verts += [(r * math.cos(2 * math.pi * s / segments), r * math.sin(2 * math.pi * s / segments), z)
                      for s in range(segments)]
    faces = []
    for k in range(len(profile) - 1):
        for s in range(segments):
            a, b = index[k][s], index[k + 1][s]
            c, d = index[k + 1][(s + 1) % segments], index[k][(s + 1) % segments]
            # (a, d, c, b) runs round the quad facing out; a point on the axis
            # makes it a triangle.
            quad = [a, d, c, b]
            corners = [q for i, q in enumerate(quad) if q != quad[i - 1]]
            faces.append((corners[0], corners[1], corners[2]))
            if len(corners) == 4:
                faces.append((corners[0], corners[2], corners[3]))
    return verts, faces


def mug(radius_mm=40.0, height_mm=90.0, wall_mm=4.0, base_mm=6.0):
    # Outer bottom, outer wall, rim, inner wall, inner floor: a profile from the
    # bottom centre round to the floor's centre, so the surface faces out.
    inner = radius_mm - wall_mm
    profile = [(0.0, 0.0), (radius_mm, 0.0), (radius_mm, height_mm), (inner, height_mm), (inner, base_mm), (0.0, base_mm)]
    verts, faces = revolve(profile)
    # The handle: half a torus on the +x side, its ends sunk into the wall.
    hv, hf = torus(major_mm=24.0, minor_mm=5.0, around=48, tube=24, sweep=(-math.pi / 2, math.pi / 2))
    offset = len(verts)
    verts += [(x + radius_mm - wall_mm / 2, y, z + height_mm / 2) for x, z, y in hv]  # in the x-z plane, ends in the wall
    faces += [(a + offset, c + offset, b + offset) for a, b, c in hf]  # the swap of y and z mirrors: flip
    return verts, faces


def pebble():
    """A sphere whose radius varies smoothly with direction, stretched and flattened."""
    def point(t, p):
        r = 36.0 * (1 + 0.12 * math.sin(2 * t) * math.cos(3 * p + 0.4) + 0.08 * math.cos(3 * t) +
                    0.06 * math.sin(p) * math.sin(t) ** 2)
        return (1.1 * r * math.sin(t) * math.cos(p), 0.8 * r * math.sin(t) * math.sin(p), 0.6 * r * math.cos(t))
    return lat_long(point, rings=48, segments=96)


def step():
    """An L-shaped outline (counter-clockwise, mm) extruded 40 mm high on x-y,
    the tall part 40 mm, the step 20 mm: built as a prism per rectangle would
    leave inner faces, so the L is one prism with its top stepped."""
    # Bottom outline, counter-clockwise seen from above.
    outline = [(0, 0), (90, 0), (90, 50), (0, 50)]
    # Top: x in [0, 50] at 40 mm, x in [50, 90] at 20 mm, joined by a vertical riser at x = 50.
    v = [(x, y, 0.0) for x, y in outline]                                        # 0-3 bottom corners
    v += [(0, 0, 40.0), (50, 0, 40.0), (50, 50, 40.0), (0, 50, 40.0)]            # 4-7 high top
    v += [(50, 0, 20.0), (90, 0, 20.0), (90, 50, 20.0), (50, 50, 20.0)]          # 8-11 low top
    f = [(0, 2, 1), (0, 3, 2),                                                   # bottom, facing down
         (4, 5, 6), (4, 6, 7),                                                   # high top, up
         (8, 9, 10), (8, 10, 11),                                                # low top, up
         (5, 8, 11), (5, 11, 6),                                                 # riser at x = 50, facing +x
         (1, 2, 10), (1, 10, 9),                                                 # x = 90 wall
         (0, 7, 3), (0, 4, 7),                                                   # x = 0 wall
         (0, 1, 9), (0, 9, 8), (0, 8, 5), (0, 5, 4),                             # y = 0 wall (an L)
         (3, 11, 2), (2, 11, 10), (3, 6, 11), (3, 7, 6)]                         # y = 50 wall (an L)
    return [tuple(float(c) for c in p) for p in v], f


FINGERTIP = {"gel: {diameter_mm: 65}": "gel: {diameter_mm: 20}   # a fingertip: see make_closed_objects.py",
             "markers: {min_spacing_mm: 1.5, mean_spacing_mm: 1.8,": "markers: {min_spacing_mm: 0.75, mean_spacing_mm: 0.9,"}


REALISTIC = {
    "plate: {thickness_mm: 5, tilt_deg: [0, 0], mu_air: 1.0, mu_acrylic: 1.49, mu_silicone: 1.41}":
        "plate: {thickness_mm: 5, tilt_deg: [1.5, -2.0], mu_air: 1.0, mu_acrylic: 1.49, mu_silicone: 1.45}",
    "plate_gap_mm: 45": "plate_gap_mm: 44",
    "effects: [contact, refraction]": """effects:
  - contact
  - elastic_spread: {sigma_mm: 3.0}
  - refraction
  - lens_distortion
  - render: {background_grey: 200, vignetting: 0.35, marker_grey: 40}
  - pixel_noise: {sigma_grey: 2.0, sigma_px: 0}
  - blur: {sigma_px: 0.9}
  - marker_dropout: {probability: 0.02}
  - pose_noise: {sigma_mm: 0.01, sigma_deg: 0.005}"""}


def write_variant(folder, name, changes, header):
    """name from the folder's scene.yaml with each of changes made."""
    with open(os.path.join(folder, "scene.yaml")) as f:
        text = f.read()
    for palm, other in changes.items():
        if palm not in text:
            raise SystemExit(f"{folder}/scene.yaml: no '{palm}' to make {name} from")
        text = text.replace(palm, other)
    text = text.replace("touched by the marker GelStereo Palm 2.0.", header, 1)
    with open(os.path.join(folder, name), "w") as f:
        f.write(text)


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
            ("sphere", sphere(), "sphere, radius 15 mm (CC0, made by make_closed_objects.py)"),
            ("mug", mug(), "mug, 80 mm across, 90 mm tall, with a handle (CC0, made by make_closed_objects.py)"),
            ("pebble", pebble(), "pebble, about 80 x 60 x 45 mm (CC0, made by make_closed_objects.py)"),
            ("step", step(), "L-shaped step block, 90 x 50 x 40 mm (CC0, made by make_closed_objects.py)")]:
        mesh = os.path.join(HERE, f"{name}.ply")
        write_ply(mesh, verts, faces, comment)
        # The scene beside the mesh; make-scene copies the mesh into the object's folder.
        subprocess.run([make_scene, mesh, "--name", name, "--out", HERE], check=True)
        os.remove(mesh)
        folder = os.path.join(HERE, name)
        write_variant(folder, "scene_fingertip.yaml", FINGERTIP, "touched by a 20 mm fingertip GelStereo\n"
                      "# (scene.yaml with a smaller dome and denser markers).")
        write_variant(folder, "scene_realistic.yaml", REALISTIC, "touched by the marker GelStereo Palm 2.0\n"
                      "# as imperfect as the fox mask's scene_realistic.yaml (images, noise, a tilted plate).")


if __name__ == "__main__":
    main()
