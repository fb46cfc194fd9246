"""touchcloud.run / validate / plugins against the CLI on the same pipelines."""
import json
import subprocess
import threading

import numpy as np
import pytest

import touchcloud


def test_run_matches_the_cli_bit_for_bit(source, cli, tmp_path):
    pipeline = source / "pipelines/fox_mask_active.yaml"
    r = touchcloud.run(str(pipeline), seed=1, set={"explore.max_iterations": 8})
    subprocess.run([str(cli), "run", str(pipeline), "--seed", "1", "--set", "explore.max_iterations=8",
                    "--out", str(tmp_path), "-q"], check=True, capture_output=True)
    summary = json.loads((tmp_path / "summary.json").read_text())
    final = r.metrics["score.final_chamfer_mm"]
    assert final["unit"] == "mm"
    assert final["value"] == summary["metrics"]["score.final_chamfer_mm"]["value"]
    chamfer = r.metrics["score.chamfer_est_to_gt"]["series"]
    assert len(chamfer) == 8 and chamfer == summary["metrics"]["score.chamfer_est_to_gt"]["series"]
    assert r.summary["metrics"]["score.final_chamfer_mm"]["value"] == final["value"]
    assert r.times["wall_s"] > 0 and r.times["stages"]["fit"]["calls"] == 8
    assert r.out == ""  # wrote to a scratch folder, gone now
    assert r.outputs["contact.state"]["stable"] is True and r.without_python_form == []
    target = r.outputs["plan.target"]
    assert len(target["xy_mm"]) == 2 and target["grid_index"] >= 0


def test_outputs_are_arrays_viewing_the_clouds(source, tmp_path):
    r = touchcloud.run(str(source / "pipelines/downsample_cloud.yaml"), out=str(tmp_path))
    thinned = r.outputs["thin.cloud"]
    assert thinned.dtype == np.float32 and thinned.ndim == 2 and thinned.shape[1] == 3
    assert not thinned.flags.writeable and thinned.base is not None  # a view, not a copy
    assert thinned.strides == (16, 4)  # PCL's padded XYZ points, viewed in place
    written = touchcloud.read_cloud(str(tmp_path / "gel_dome_thinned.ply"))
    np.testing.assert_array_equal(np.sort(written, axis=0), np.sort(np.asarray(thinned), axis=0))
    assert len(r.outputs["read.cloud"]) > len(thinned)


def test_a_surface_answers_mean_and_variance(source):
    pipeline = source / "pipelines/fox_mask_active.yaml"
    r = touchcloud.run(str(pipeline), seed=1, set={"explore.max_iterations": 6}, outputs=["fit.surface", "surface.cloud"])
    surface = r.outputs["fit.surface"]
    cloud = np.asarray(r.outputs["surface.cloud"], dtype=float)
    # The sampled cloud lies on the surface's mean.
    np.testing.assert_allclose(surface.mean(cloud[:50, :2]), cloud[:50, 2], atol=1e-3)
    assert (surface.variance(cloud[:50, :2]) >= 0).all()
    grid = surface.grid(np.linspace(-10, 10, 5), np.linspace(-5, 5, 3))
    assert grid.shape == (3, 5) and np.isfinite(grid).all()


def test_unknown_outputs_are_refused_by_name(source):
    with pytest.raises(touchcloud.InputError, match="stage 'thin' has no output 'clouds'"):
        touchcloud.run(str(source / "pipelines/downsample_cloud.yaml"), outputs=["thin.clouds"])


def test_a_bad_pipeline_raises_with_its_file_position(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("stages:\n  - id: read\n    plugin: cloud_reader\n    params: {path: nowhere.pcd, colour: red}\n")
    with pytest.raises(touchcloud.PipelineError) as e:
        touchcloud.validate(str(bad))
    assert f"{bad}:4:" in str(e.value) and "colour" in str(e.value)
    assert any(d[0] == str(bad) and d[1] == 4 for d in e.value.diagnostics)
    assert isinstance(e.value, touchcloud.Error)
    with pytest.raises(touchcloud.PipelineError, match="nowhere.pcd"):
        touchcloud.run(str(bad))


def test_set_overrides_reach_the_stage(source):
    pipeline = str(source / "pipelines/downsample_cloud.yaml")
    coarse = touchcloud.run(pipeline, set={"thin.leaf_size_mm": 8.0}).outputs["thin.cloud"]
    fine = touchcloud.run(pipeline, set={"thin.leaf_size_mm": 2.0}).outputs["thin.cloud"]
    assert len(coarse) < len(fine)
    with pytest.raises(touchcloud.PipelineError, match="leaf_size_mm"):
        touchcloud.run(pipeline, set={"thin.leaf_size_mm": -1.0})


def test_scene_names_the_object_of_every_stage(source):
    pipeline = str(source / "pipelines/fox_mask_active.yaml")
    wave = str(source / "sample_clouds/wave_surface/scene.yaml")
    touchcloud.validate(pipeline, scene=wave)
    with pytest.raises(touchcloud.PipelineError, match="stage 'score' \\(plugin chamfer\\) names the scene"):
        touchcloud.validate(pipeline, set={"sensor.scene": wave})
    with pytest.raises(touchcloud.PipelineError, match="scene=.*no_scene.yaml"):
        touchcloud.run(pipeline, scene=str(source / "no_scene.yaml"))


@pytest.mark.parametrize("key", [1, None, ("thin", "leaf_size_mm")])
def test_a_set_key_that_is_no_string_is_a_type_error_naming_it(source, key):
    pipeline = str(source / "pipelines/downsample_cloud.yaml")
    with pytest.raises(TypeError, match=r"set: key .* is not a string; keys are 'stage.param'") as e:
        touchcloud.run(pipeline, set={key: 2})
    assert repr(key) in str(e.value)
    with pytest.raises(TypeError, match="is not a string"):
        touchcloud.validate(pipeline, set={key: 2})


def test_plugins_are_what_the_cli_lists(cli):
    listed = json.loads(subprocess.run([str(cli), "plugins", "--json"], check=True, capture_output=True, text=True).stdout)
    assert touchcloud.plugins() == listed
    assert touchcloud.plugins("downsample")["name"] == "downsample"


def test_the_gil_is_released_while_a_pipeline_runs(source):
    ticks = 0
    done = threading.Event()

    def work():
        try:
            touchcloud.run(str(source / "pipelines/fox_mask_active.yaml"), seed=1, set={"explore.max_iterations": 10})
        finally:
            done.set()

    t = threading.Thread(target=work)
    t.start()
    while not done.is_set():
        ticks += 1
        done.wait(0.001)
    t.join()
    assert ticks > 20  # Python code ran beside the pipeline


def test_dense_maps_and_colour_pairs_are_arrays(source):
    r = touchcloud.run(str(source / "pipelines/simulate_touch_dense.yaml"), seed=1,
                       outputs=["sim.colour_frame", "disparity.disparity", "mask.mask", "cloud.cloud"])
    left = r.outputs["sim.colour_frame"]["left"]
    assert left.dtype == np.uint8 and left.ndim == 3 and left.shape[2] == 3
    maps = r.outputs["disparity.disparity"]
    disparity, valid = maps["disparity_left_px"], maps["valid_left"]
    assert disparity.dtype == np.float32 and disparity.shape == left.shape[:2] and valid.shape == disparity.shape
    assert np.isfinite(disparity).all() and (disparity[valid > 0] >= 0).all() and (valid > 0).mean() > 0.5
    assert maps["depth_mm"] is None  # the matcher fills disparities only
    mask = r.outputs["mask.mask"]["contact_mask"]
    # One point per valid contact pixel, in mm.
    assert 0 < len(r.outputs["cloud.cloud"]) <= ((mask > 0) & (valid > 0)).sum()


def test_a_frame_asked_for_inside_a_touch_is_rendered_once_as_the_cli_renders_it(source, cli, tmp_path):
    # Only the touch's last colour pair is handed back, so only the frame that ends the touch is
    # rendered, as for the stages after the loop: the same run as the CLI's, bit for bit.
    pipeline = source / "pipelines/simulate_touch_dense.yaml"
    r = touchcloud.run(str(pipeline), seed=1, out=str(tmp_path / "py"), outputs=["sim.colour_frame", "cloud.cloud"])
    assert r.metrics["sim.frames_rendered"]["value"] == 1 < r.metrics["sim.frames_simulated"]["value"]
    assert r.outputs["sim.colour_frame"]["left"].shape[2] == 3
    subprocess.run([str(cli), "run", str(pipeline), "--seed", "1", "--out", str(tmp_path / "cli"), "-q"],
                   check=True, capture_output=True)
    assert (tmp_path / "py/dense_contact_base.pcd").read_bytes() == (tmp_path / "cli/dense_contact_base.pcd").read_bytes()


def test_metrics_carry_their_declarations_and_artifacts_their_roles(source, tmp_path):
    r = touchcloud.run(str(source / "pipelines/fox_mask_active.yaml"), seed=1, out=str(tmp_path),
                       set={"explore.max_iterations": 3, "surface.resolution": [40, 40]})
    eq11 = r.metrics["score.chamfer_est_to_gt"]
    assert (eq11["unit"], eq11["when"], eq11["direction"], eq11["role"]) == ("mm", "per_item", "lower_is_better",
                                                                             "accuracy")
    assert "Eq. 11" in eq11["doc"] and len(eq11["series"]) == 3
    final = r.metrics["score.final_chamfer_mm"]
    assert (final["when"], final["role"]) == ("final", None)
    assert r.metrics["fit.update_path"]["direction"] is None
    assert r.metrics["dedup.added_points"]["role"] == "points_added"
    roles = {a["role"]: a for a in r.artifacts}
    surface = roles["reconstructed_surface"]
    assert (surface["stage"], surface["file"]) == ("write_surface", "fox_mask_surface.pcd")
    assert surface["path"] == str(tmp_path / "fox_mask_surface.pcd")
    assert len(touchcloud.read_cloud(surface["path"])) == surface["attributes"]["points"]
    assert roles["touch_points"]["path"] == str(tmp_path / "fox_mask_touch_points.pcd")
    truth = roles["ground_truth"]
    assert truth["file"] is None and truth["path"] is None
    assert truth["attributes"]["scene"] == str(source / "sample_clouds/fox_mask/scene.yaml")
    assert (truth["attributes"]["kind"], truth["attributes"]["sample_seed"]) == ("mesh", 0)
    # Without out, the files went with the scratch folder: no paths.
    scratch = touchcloud.run(str(source / "pipelines/downsample_cloud.yaml"))
    assert [(a["role"], a["path"]) for a in scratch.artifacts] == [("cloud", None)]


def test_height_maps_and_colour_frames_are_arrays(source):
    r = touchcloud.run(str(source / "pipelines/simulate_touch_gelsight.yaml"), outputs=["depth.height", "sim.image"])
    height = r.outputs["depth.height"]
    assert height["height_mm"].dtype == np.float32 and height["height_mm"].shape == (240, 320)
    assert height["contact_mask"].dtype == np.uint8 and set(np.unique(height["contact_mask"])) <= {0, 255}
    assert height["height_mm"].max() == pytest.approx(r.metrics["depth.max_height_mm"]["value"], abs=1e-6)
    assert height["mm_per_px"] > 0 and height["gel_thickness_mm"] > 0 and height["sensor"]
    frame = r.outputs["sim.image"]
    assert frame["image"].dtype == np.uint8 and frame["image"].shape == (240, 320, 3)  # BGR
    assert not frame["image"].flags.writeable


def test_every_iteration_returns_each_calls_outputs(source):
    pipeline = str(source / "pipelines/simulate_touch_gelsight.yaml")
    r = touchcloud.run(pipeline, outputs=["sim.image", "contact.state", "depth.height"], every_iteration=True)
    calls = r.times["stages"]["sim"]["calls"]
    frames, states = r.outputs["sim.image"], r.outputs["contact.state"]
    assert isinstance(frames, list) and calls > 3 and len(frames) == len(states) == calls
    assert states[-1]["stable"] is True and states[0]["stable"] is False
    assert not np.array_equal(frames[0]["image"], frames[-1]["image"])  # the press shows
    assert len(r.outputs["depth.height"]) == 1  # outside the loop: one call
    last = touchcloud.run(pipeline, outputs=["sim.image"])
    np.testing.assert_array_equal(last.outputs["sim.image"]["image"], frames[-1]["image"])


def test_displacement_fields_are_n_by_4_arrays(source):
    r = touchcloud.run(str(source / "docs/examples/marker_tracking.yaml"), outputs=["track.displacement"])
    field = r.outputs["track.displacement"]
    vectors = field["vectors_px"]
    assert vectors.dtype == np.float64 and vectors.shape == (63, 4)  # x, y at rest, dx, dy (px)
    assert field["mm_per_px"] == pytest.approx(0.06) and field["reference_markers"] == 63
    largest = float(np.hypot(vectors[:, 2], vectors[:, 3]).max()) * field["mm_per_px"]
    assert largest == pytest.approx(r.metrics["track.max_displacement_mm"]["value"], rel=1e-9)


def test_recorded_frames_with_markers_give_heights_clouds_and_fields(source, tmp_path):
    pipeline = str(source / "pipelines/gelsight_markers_from_images.yaml")
    r = touchcloud.run(pipeline, out=str(tmp_path), outputs=["depth.height", "track.displacement"], every_iteration=True)
    heights, fields = r.outputs["depth.height"], r.outputs["track.displacement"]
    assert len(heights) == len(fields) == 3  # the sample's three frames, the loop ended on the last file
    # checks: error: no frame stopped the run (the calibration was fitted with the dots masked)
    assert r.metrics["depth.depth_warnings"]["value"] == 0 and r.metrics["depth.markers_masked"]["value"] >= 60
    deepest = max(float(h["height_mm"].max()) for h in heights)
    assert 0.5 < deepest < 1.0  # the ball pressed about 0.6 mm past first contact, on a 2.5 mm gel
    for field in fields:
        assert field["vectors_px"].shape[1] == 4 and field["vectors_px"].shape[0] >= 60
    for i in range(3):
        for name in (f"height_{i}.png", f"contact_{i}.png", f"contact_{i}.pcd", f"displacement_{i}.csv",
                     f"displacement_{i}.png"):
            assert (tmp_path / name).is_file(), name
