#!/usr/bin/env python3
"""Writes the indenters of the colour-pattern GelStereo's evaluation
(benchmarks/table_i/) as PLY meshes in mm, z = 0 on the table: the paper's
flat-faced workpieces (triangle, quadrilateral, pentagon prisms, each face
inscribed in a 6 mm circle, 12 mm tall) and two shapes they lack, a
ball-nosed pin (5 mm radius) and a 90-degree edge 20 mm long. Faces of 6 mm
keep the polygon inside the contact patch of the 32.5 mm gel dome at 1.5 mm
(about 10 mm across). Run from this folder."""
import math

HEIGHT_MM = 12.0


def write_ply(name, vertices, faces):
    with open(name + ".ply", "w") as f:
        f.write("ply\nformat ascii 1.0\ncomment touchcloud indenter, mm, z = 0 on the table\n")
        f.write(f"element vertex {len(vertices)}\nproperty float x\nproperty float y\nproperty float z\n")
        f.write(f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n")
        for v in vertices:
            f.write("{:.4f} {:.4f} {:.4f}\n".format(*v))
        for face in faces:
            f.write(f"{len(face)} " + " ".join(str(i) for i in face) + "\n")


def prism(corners_xy, height):
    """A vertical prism over a convex polygon (counter-clockwise)."""
    n = len(corners_xy)
    vertices = [(x, y, 0.0) for x, y in corners_xy] + [(x, y, height) for x, y in corners_xy]
    faces = [[0, i + 1, i] for i in range(1, n - 1)]            # bottom, facing down
    faces += [[n, n + i, n + i + 1] for i in range(1, n - 1)]   # top, facing up
    for i in range(n):
        j = (i + 1) % n
        faces += [[i, j, n + j], [i, n + j, n + i]]
    return vertices, faces


def polygon(sides, circumradius):
    return [(circumradius * math.cos(2 * math.pi * k / sides + math.pi / 2),
             circumradius * math.sin(2 * math.pi * k / sides + math.pi / 2)) for k in range(sides)]


def ball_nosed_pin(radius, height, rings=12, segments=32):
    """A cylinder of `radius` capped by a hemisphere, the tip at `height`."""
    shoulder = height - radius
    profile = [(radius, 0.0), (radius, shoulder)]
    profile += [(radius * math.cos(a), shoulder + radius * math.sin(a))
                for a in (math.pi / 2 * k / rings for k in range(1, rings))]
    vertices = [(r * math.cos(2 * math.pi * s / segments), r * math.sin(2 * math.pi * s / segments), z)
                for r, z in profile for s in range(segments)]
    tip, bottom = len(vertices), len(vertices) + 1
    vertices += [(0.0, 0.0, height), (0.0, 0.0, 0.0)]
    faces = []
    for ring in range(len(profile) - 1):
        for s in range(segments):
            a, b = ring * segments + s, ring * segments + (s + 1) % segments
            faces += [[a, b, b + segments], [a, b + segments, a + segments]]
    last = (len(profile) - 1) * segments
    faces += [[last + s, last + (s + 1) % segments, tip] for s in range(segments)]
    faces += [[(s + 1) % segments, s, bottom] for s in range(segments)]
    return vertices, faces


def edge(length, half_width, shoulder, height):
    """A ridge along x: a prism over the (y, z) profile of a block with a
    90-degree roof, the edge on top at `height` (half_width = height - shoulder)."""
    profile = [(-half_width, 0.0), (half_width, 0.0), (half_width, shoulder), (0.0, height), (-half_width, shoulder)]
    vertices, faces = prism(profile, length)
    # (y, z, x) -> (x, y, z): a cyclic permutation of the axes, a rotation, so faces keep facing out.
    return [(c - length / 2, a, b) for a, b, c in vertices], faces


write_ply("triangle", *prism(polygon(3, 6.0), HEIGHT_MM))
write_ply("quadrilateral", *prism(polygon(4, 6.0), HEIGHT_MM))
write_ply("pentagon", *prism(polygon(5, 6.0), HEIGHT_MM))
write_ply("round", *ball_nosed_pin(5.0, HEIGHT_MM))
write_ply("edge", *edge(20.0, 5.0, HEIGHT_MM - 5.0, HEIGHT_MM))

# One scene per indenter: the object on the table under the colour-pattern
# GelStereo of sample_clouds/fox_mask/scene_dense.yaml, rendered at the
# paper's network input (256 x 256), with the pixel noise and blur of a real
# camera (as scene_images.yaml): a noiseless rendering makes block matching
# all but exact. The press depth is the pipeline's.
SCENE = """# Written by make_indenters.py: the {name} indenter pressed by the
# colour-pattern GelStereo (benchmarks/table_i/).
name: {name}
object:
  mesh: {name}.ply
  scale: 1.0
  pose: {{xyz_mm: [0, 0, 0], rpy_deg: [0, 0, 0]}}
workspace:
  x_mm: [-15, 15]
  y_mm: [-15, 15]
  grid: [6, 6]
sensor:
  gel: {{diameter_mm: 65}}
  pattern: colour_pattern
  colour_pattern: {{feature_mm: 1.0, opacity: 0.8, seed: 1, vignetting: 0.1, image_size_px: [256, 256]}}
  plate: {{thickness_mm: 5, tilt_deg: [0, 0], mu_air: 1.0, mu_acrylic: 1.49, mu_silicone: 1.41}}
  cameras:
    left: {{width_px: 1280, height_px: 720, fx_px: 651.5, fy_px: 652.0, cx_px: 598.6, cy_px: 377.1,
           distortion: [-0.05, 0.02, 0.0005, -0.0003, 0]}}
    baseline_mm: 30
    plate_gap_mm: 45
  fps: 30
robot:
  speed_mm_s: 6
  approach_speed_mm_s: 30
  press_depth_mm: 1.0
  safe_clearance_mm: 2
  max_contact_depth_mm: 10
effects:
  - contact
  - elastic_spread
  - refraction
  - render
  - pixel_noise: {{sigma_grey: 3, sigma_px: 0}}
  - blur: {{sigma_px: 0.8}}
"""
for name in ("triangle", "quadrilateral", "pentagon", "round", "edge"):
    with open(name + ".yaml", "w") as f:
        f.write(SCENE.format(name=name))
