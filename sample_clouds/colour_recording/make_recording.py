#!/usr/bin/python3
"""Writes a colour-pattern GelStereo "recording" as a user's cameras would
give it: raw, distorted, unrectified pairs of one press of the fox mask and
of the gel at rest, for pipelines/dense_from_recordings.yaml and its test.

The simulator renders rectified pairs (its own rectification of the rig);
this script maps them back through each camera's rotation into its
rectified frame, intrinsics and lens distortion (OpenCV's camera model) to
the raw images a calibrated sensor would record. The true contact cloud
(sensor frame) comes along, so the chain from raw images can be scored.

Needs the build (build/bin/touchcloud) and python3-opencv. Run from the
repository root: sample_clouds/colour_recording/make_recording.py
"""
import os
import shutil
import subprocess
import sys
import tempfile

import cv2
import numpy as np
import yaml

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

# 640 x 360 cameras with lens distortion; the right one 30 mm along x,
# turned 2 degrees inwards and 0.5 degrees about its axis, so that the raw
# rows are not epipolar lines.
SENSOR = """  gel: {diameter_mm: 65}
  pattern: colour_pattern
  colour_pattern: {feature_mm: 1.0, opacity: 0.8, seed: 1, vignetting: 0.1, image_size_px: [0, 0]}
  plate: {thickness_mm: 5, tilt_deg: [0, 0], mu_air: 1.0, mu_acrylic: 1.49, mu_silicone: 1.41}
  cameras:
    left: {width_px: 640, height_px: 360, fx_px: 326, fy_px: 326.5, cx_px: 300.2, cy_px: 188.4,
           distortion: [-0.05, 0.02, 0.0005, -0.0003, 0]}
    right: {width_px: 640, height_px: 360, fx_px: 324, fy_px: 324.2, cx_px: 318.7, cy_px: 176.9,
            distortion: [-0.04, 0.015, -0.0002, 0.0004, 0]}
    right_from_left: {xyz_mm: [-30, 0, 0], rpy_deg: [0.5, -2, 0]}
    plate_gap_mm: 45
  fps: 30
"""

SCENE = """# Written by make_recording.py: the fox mask pressed by a colour-pattern
# GelStereo whose cameras have lens distortion and a toed-in right camera.
name: colour_recording
object:
  mesh: ../fox_mask/mesh.ply
  scale: 1.0
  pose: {xyz_mm: [0, 0, 0], rpy_deg: [0, 0, 0]}
workspace: {x_mm: [-60, 60], y_mm: [-60, 60], grid: [14, 14]}
sensor:
""" + SENSOR + """robot: {speed_mm_s: 6, approach_speed_mm_s: 30, press_depth_mm: 1.5, safe_clearance_mm: 2, max_contact_depth_mm: 10}
effects: [contact, elastic_spread, refraction, render]
"""


def camera(side):
    c = yaml.safe_load("sensor:\n" + SENSOR)["sensor"]["cameras"][side]
    k = np.array([[c["fx_px"], 0, c["cx_px"]], [0, c["fy_px"], c["cy_px"]], [0, 0, 1]], float)
    return k, np.array(c["distortion"], float), (c["width_px"], c["height_px"])


def unrectify(image, k, dist, size, rect_from_cam, p):
    """The raw view: each raw pixel takes the rectified image's colour where its ray lands."""
    w, h = size
    u, v = np.meshgrid(np.arange(w, dtype=np.float32), np.arange(h, dtype=np.float32))
    raw = np.stack([u.ravel(), v.ravel()], axis=1).reshape(-1, 1, 2)
    rect = cv2.undistortPoints(raw, k, dist, R=rect_from_cam, P=p).reshape(h, w, 2)
    return cv2.remap(image, rect[..., 0], rect[..., 1], cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT)


def main():
    cli = os.path.join(ROOT, "build", "bin", "touchcloud")
    with open(os.path.join(HERE, "sensor.yaml"), "w") as f:
        f.write("# Written by make_recording.py: the sensor file (stereo calibration) of the recording.\nsensor:\n" + SENSOR)
    with open(os.path.join(HERE, "scene.yaml"), "w") as f:
        f.write(SCENE)
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run([cli, "run", os.path.join(HERE, "record.yaml"), "--out", tmp, "--quiet"], check=True)
        cam = yaml.safe_load(open(os.path.join(tmp, "press", "camera.yaml")))
        fx, fy, cy = cam["fx_px"], cam["fy_px"], cam["cy_px"]
        for side in ("left", "right"):
            k, dist, size = camera(side)
            rot = np.array(cam[f"{side}_rect_from_{side}"], float).reshape(3, 3)
            p = np.array([[fx, 0, cam[f"cx_{side}_px"]], [0, fy, cy], [0, 0, 1]], float)
            for folder, name in (("press", f"press_{side}_0.png"), ("reference", f"reference_{side}.png")):
                rectified = cv2.imread(os.path.join(tmp, folder, "pairs", f"000000_{side}.png"), cv2.IMREAD_COLOR)
                cv2.imwrite(os.path.join(HERE, name), unrectify(rectified, k, dist, size, rot, p),
                            [cv2.IMWRITE_PNG_COMPRESSION, 9])
        shutil.copy(os.path.join(tmp, "truth_contact_sensor.pcd"), HERE)
    print("wrote", ", ".join(sorted(n for n in os.listdir(HERE) if n.endswith((".png", ".pcd", ".yaml")))))


if __name__ == "__main__":
    sys.exit(main())
