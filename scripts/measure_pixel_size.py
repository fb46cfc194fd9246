#!/usr/bin/env python3
"""The pixel size (mm per pixel) of a GelSight-type sensor from one press of
known contact size and its no-contact reference image.

The contact is where the press image differs from the reference by more than
--threshold grey levels on some channel; a least-squares circle (Kasa's
algebraic fit) through the outer edge of that region gives its radius in
pixels. The contact's true diameter is either given (--diameter-mm: a flat
disc such as a coin pressed fully into the gel) or follows from a ball of
radius R pressed d past first contact (--ball-radius-mm R --depth-mm d,
a robot's or a micrometer stage's travel): 2 sqrt(2 R d - d^2).

  PYTHONPATH=build/python scripts/measure_pixel_size.py press.png reference.png \\
      --ball-radius-mm 3 --depth-mm 0.8

Prints the fitted circle and mm_per_px (with --json, one JSON object). Needs
the touchcloud module (which reads and checks the images) and NumPy.
"""
import argparse
import json
import math
import pathlib
import sys
import tempfile

import numpy as np

import touchcloud


def read_colour(files):
    """The images as H x W x 3 uint8 BGR arrays, read by touchcloud's image_reader."""
    with tempfile.TemporaryDirectory() as folder:
        stages = "".join(
            f"  - {{id: read{i}, plugin: image_reader, params: {{path: {json.dumps(str(pathlib.Path(f).resolve()))}}}}}\n"
            for i, f in enumerate(files))
        pipeline = pathlib.Path(folder) / "read.yaml"
        pipeline.write_text("pipeline: read\nstages:\n" + stages)
        r = touchcloud.run(str(pipeline), outputs=[f"read{i}.colour" for i in range(len(files))])
        return [r.outputs[f"read{i}.colour"]["image"] for i in range(len(files))]


def contact_circle(press, reference, threshold):
    """(u, v, radius) in px of the circle through the outer edge of the contact."""
    if press.shape != reference.shape:
        raise ValueError(f"the press is {press.shape[1]} x {press.shape[0]} px, the reference "
                         f"{reference.shape[1]} x {reference.shape[0]} px")
    difference = np.abs(press.astype(np.int16) - reference.astype(np.int16)).max(axis=2)
    contact = difference > threshold
    if contact.sum() < 20:
        raise ValueError(f"fewer than 20 pixels differ from the reference by more than {threshold} grey levels: "
                         "no contact found (press deeper, or lower --threshold)")
    # The outer edge: per row, the first and last contact pixel.
    edge = []
    for v in np.flatnonzero(contact.any(axis=1)):
        u = np.flatnonzero(contact[v])
        edge += [(u[0], v), (u[-1], v)]
    for u in np.flatnonzero(contact.any(axis=0)):
        v = np.flatnonzero(contact[:, u])
        edge += [(u, v[0]), (u, v[-1])]
    xy = np.asarray(edge, dtype=float)
    # Kasa: x^2 + y^2 = 2 a x + 2 b y + c, linear in a, b, c.
    a, b, c = np.linalg.lstsq(np.c_[2 * xy, np.ones(len(xy))], (xy ** 2).sum(axis=1), rcond=None)[0]
    return a, b, math.sqrt(c + a * a + b * b)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("press")
    p.add_argument("reference")
    p.add_argument("--diameter-mm", type=float, help="the contact's diameter (a flat disc pressed fully)")
    p.add_argument("--ball-radius-mm", type=float, help="radius of the ball pressed")
    p.add_argument("--depth-mm", type=float, help="how far the ball was pressed past first contact")
    p.add_argument("--threshold", type=float, default=12, help="grey levels of difference that count as contact")
    p.add_argument("--json", action="store_true")
    a = p.parse_args(argv)
    if a.diameter_mm is not None:
        diameter = a.diameter_mm
    elif a.ball_radius_mm is not None and a.depth_mm is not None:
        if not 0 < a.depth_mm < a.ball_radius_mm:
            p.error("--depth-mm must be above 0 and below --ball-radius-mm")
        diameter = 2 * math.sqrt(2 * a.ball_radius_mm * a.depth_mm - a.depth_mm ** 2)
    else:
        p.error("give --diameter-mm, or --ball-radius-mm with --depth-mm")
    try:
        press, reference = read_colour([a.press, a.reference])
        u, v, radius = contact_circle(press, reference, a.threshold)
    except (touchcloud.InputError, ValueError) as e:
        print(f"measure_pixel_size: error: {e}", file=sys.stderr)
        return 2
    result = {"centre_px": [u, v], "radius_px": radius, "diameter_mm": diameter, "mm_per_px": diameter / (2 * radius)}
    if a.json:
        print(json.dumps(result))
    else:
        print(f"contact circle at ({u:.1f}, {v:.1f}) px, radius {radius:.2f} px; diameter {diameter:.3f} mm: "
              f"mm_per_px {result['mm_per_px']:.5f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
