"""touchcloud.stream: a recording of presses (pipelines/stream_gelsight.yaml) frame after frame as NumPy arrays with
their stamps, the clouds those the stream writes; frames=N and leaving the loop early stop it."""
import numpy as np
import pytest

import touchcloud


def test_each_frame_comes_with_its_stamp_as_arrays(source, tmp_path):
    pipeline = str(source / "pipelines/stream_gelsight.yaml")
    stream = touchcloud.stream(pipeline, out=str(tmp_path),
                               outputs=["cam.frame", "depth.height", "cloud.cloud"])
    frames = list(stream)
    assert len(frames) == 5  # six recorded, the first the no-contact reference
    for k, f in enumerate(frames):
        assert f["iteration"] == k
        assert f["stamp"]["sequence"] == k + 1
        assert f["stamp"]["timestamp_s"] == pytest.approx(0.04 * (k + 1))
        image = f["outputs"]["cam.frame"]["image"]  # BGR, with the frame's sensor, pixel size and time
        assert image.shape == (240, 320, 3) and image.dtype == np.uint8
        height = f["outputs"]["depth.height"]
        assert height["height_mm"].shape == (240, 320) and height["height_mm"].dtype == np.float32
        cloud = f["outputs"]["cloud.cloud"]
        written = touchcloud.read_cloud(str(tmp_path / f"cloud_{k}.pcd"))
        np.testing.assert_array_equal(np.asarray(cloud), written)
    # The press deepens frame after frame.
    depths = [float(f["outputs"]["depth.height"]["height_mm"].max()) for f in frames]
    assert depths == sorted(depths) and depths[-1] > 0.3
    result = stream.result
    assert result.metrics["cam.frames_processed"]["value"] == 5
    assert result.metrics["cam.frames_dropped"]["value"] == 0
    assert result.summary["stages"][0]["latency_ms"]["p99"] > 0


def test_frames_and_leaving_early_stop_the_run(source, tmp_path):
    pipeline = str(source / "pipelines/stream_gelsight.yaml")
    two = touchcloud.stream(pipeline, frames=2, out=str(tmp_path / "two"))
    assert [f["iteration"] for f in two] == [0, 1]
    assert two.result.metrics["cam.frames_processed"]["value"] == 2
    with touchcloud.stream(pipeline, out=str(tmp_path / "early")) as early:
        first = next(early)
        assert first["stamp"]["sequence"] == 1
    assert (tmp_path / "early" / "summary.json").exists()
    with pytest.raises(ValueError, match="out"):
        touchcloud.stream(pipeline)
