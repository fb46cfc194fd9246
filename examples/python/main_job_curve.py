"""Runs the main job from Python and plots its chamfer curve.

    PYTHONPATH=build/python python3 examples/python/main_job_curve.py [--out curve.png]

The run is the same as `touchcloud run pipelines/fox_mask_active.yaml --seed 1`
(the same numbers, bit for bit); the surface and the touch points come back as
NumPy arrays, in mm, in the base frame.
"""
import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import touchcloud  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--out", default="main_job_curve.png", help="the plot (PNG)")
args = parser.parse_args()

run = touchcloud.run(str(ROOT / "pipelines/fox_mask_active.yaml"), seed=1,
                     outputs=["surface.cloud", "dedup.accumulated"])
chamfer = run.metrics["score.chamfer_est_to_gt"]
surface = run.outputs["surface.cloud"]
points = run.outputs["dedup.accumulated"]
print(f"final chamfer {chamfer['value']:.5f} {chamfer['unit']} after {len(chamfer['series'])} touches; "
      f"surface {len(surface)} points, touch points {len(points)}; ran in {run.times['wall_s']:.2f} s")

fig, (curve, top) = plt.subplots(1, 2, figsize=(10, 4))
curve.plot(np.arange(1, len(chamfer["series"]) + 1), chamfer["series"], marker="o", markersize=3)
curve.set_xlabel("touch")
curve.set_ylabel(f"chamfer, estimate to ground truth ({chamfer['unit']})")
curve.set_yscale("log")
curve.grid(True, which="both", alpha=0.3)
shade = top.scatter(surface[:, 0], surface[:, 1], c=surface[:, 2], s=2, cmap="viridis")
top.scatter(points[:, 0], points[:, 1], s=1, c="k", alpha=0.3)
top.set_aspect("equal")
top.set_xlabel("x (mm)")
top.set_ylabel("y (mm)")
fig.colorbar(shade, ax=top, label="surface z (mm)")
fig.tight_layout()
fig.savefig(args.out, dpi=120)
print(f"wrote {args.out}")
