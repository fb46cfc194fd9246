"""benchmarks/table1/coverage_bands.py's footprint measure: the object's area
within 2 mm (x, y) of each touch's salient points, their sum and their union,
on hand-made touches whose areas are known; and the pipeline copy that writes
each touch's points."""
import math
import os
import sys

import numpy as np
import pytest

ROOT = os.environ.get("TOUCHCLOUD_SOURCE_DIR", os.getcwd())
sys.path.insert(0, os.path.join(ROOT, "benchmarks", "table1"))
import coverage_bands as cb  # noqa: E402


def write_touch(folder, k, xyz):
    cb.write_pcd_xyz(os.path.join(folder, f"touch_{k}.pcd"), np, np.asarray(xyz, dtype=float))


def test_footprints_of_known_touches(tmp_path):
    # The wave surface: 200 x 50 mm. Touch 0: one point at the middle (a 2 mm
    # disc, 12.6 mm^2); touch 1: the same point again (adds area to the sum,
    # nothing to the union); touch 2: no salient point, so no file.
    write_touch(tmp_path, 0, [[0, 0, 14]])
    write_touch(tmp_path, 1, [[0, 0, 15]])
    fp = cb.footprints(np, "wave_surface", 3, str(tmp_path))
    disc = math.pi * 2.0 ** 2
    assert fp["object"] == pytest.approx(10000.0)
    assert fp["mean"] == pytest.approx(2 * disc / 3, rel=0.05)
    assert fp["summed"] == pytest.approx(2 * disc / 10000.0, rel=0.05)
    assert fp["covered"] == pytest.approx(disc / 10000.0, rel=0.05)


def test_footprint_is_clipped_to_the_object(tmp_path):
    # A point on the fox mask's corner (-60, -60): a quarter of its disc lies on the object.
    write_touch(tmp_path, 0, [[-60, -60, 4]])
    fp = cb.footprints(np, "fox_mask", 1, str(tmp_path))
    assert fp["mean"] == pytest.approx(math.pi, rel=0.1)
    assert fp["covered"] == pytest.approx(math.pi / 14400.0, rel=0.1)


def test_pipeline_copy_writes_each_touch_and_finds_its_files(tmp_path):
    pipeline = os.path.join(ROOT, "pipelines", "wave_surface_active_realistic.yaml")
    text = open(cb.with_touch_writer(pipeline, str(tmp_path))).read()
    assert "plugin: cloud_writer\n          params: {path: 'touch_{iteration}.pcd'}\n          inputs: {cloud: salient.cloud}" in text
    assert "../sample_clouds/" not in text
    assert os.path.join(ROOT, "sample_clouds", "wave_surface", "scene_realistic.yaml") in text


def test_pipeline_without_the_thin_stage_is_refused(tmp_path):
    bad = tmp_path / "no_thin.yaml"
    bad.write_text("pipeline: x\nstages:\n  - id: read\n    plugin: cloud_reader\n")
    with pytest.raises(SystemExit, match="no single '- id: thin' stage"):
        cb.with_touch_writer(str(bad), str(tmp_path / "out"))
