"""touchcloud.read_cloud / write_cloud / score on clouds made here."""
import numpy as np
import pytest

import touchcloud


def grid(n, z=0.0):
    x, y = np.meshgrid(np.arange(n, dtype=np.float32), np.arange(n, dtype=np.float32))
    return np.column_stack([x.ravel(), y.ravel(), np.full(n * n, z, dtype=np.float32)])


@pytest.mark.parametrize("name,binary", [("a.pcd", True), ("a.pcd", False), ("a.ply", True), ("a.ply", False)])
def test_clouds_round_trip(tmp_path, name, binary):
    points = grid(7) + np.float32(0.125)
    touchcloud.write_cloud(str(tmp_path / name), points, binary=binary)
    back = touchcloud.read_cloud(str(tmp_path / name))
    np.testing.assert_array_equal(back, points)
    assert not back.flags.writeable


def test_bad_clouds_are_errors_naming_the_file(tmp_path):
    with pytest.raises(ValueError, match="N x 3"):
        touchcloud.write_cloud(str(tmp_path / "x.pcd"), np.zeros((4, 2)))
    with pytest.raises(ValueError, match="point 1 is not finite"):
        touchcloud.write_cloud(str(tmp_path / "x.pcd"), np.array([[0, 0, 0], [np.nan, 0, 0]]))
    (tmp_path / "bad.pcd").write_text("FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 2\nDATA ascii\n1 2 3\nhello 2 3\n")
    with pytest.raises(touchcloud.InputError, match=r"bad.pcd:7: 'hello' is not a number"):
        touchcloud.read_cloud(str(tmp_path / "bad.pcd"))
    assert not (tmp_path / "x.pcd").exists()


def test_score_gives_one_row_per_estimate_and_goes_on_past_a_bad_one(tmp_path):
    touchcloud.write_cloud(str(tmp_path / "gt.pcd"), grid(20))
    touchcloud.write_cloud(str(tmp_path / "same.pcd"), grid(20))
    touchcloud.write_cloud(str(tmp_path / "raised.pcd"), grid(20, z=0.5))
    (tmp_path / "broken.pcd").write_text("not a cloud\n")
    rows = touchcloud.score(str(tmp_path / "gt.pcd"),
                            [str(tmp_path / n) for n in ("same.pcd", "broken.pcd", "raised.pcd")])
    assert [r["estimate"].rsplit("/", 1)[1] for r in rows] == ["same.pcd", "broken.pcd", "raised.pcd"]
    assert rows[0]["chamfer_est_to_gt_mm"] == 0 and rows[0]["fscore"] == 1
    assert "no valid PCD header" in rows[1]["error"]
    assert rows[2]["chamfer_est_to_gt_mm"] == pytest.approx(0.5, abs=1e-6)
    assert rows[2]["hausdorff_mm"] == pytest.approx(0.5, abs=1e-6)
    with pytest.raises(touchcloud.InputError, match="missing.pcd"):
        touchcloud.score(str(tmp_path / "missing.pcd"), [str(tmp_path / "same.pcd")])


def test_a_cloud_that_cannot_be_written_is_an_error_and_leaves_no_file(tmp_path):
    with pytest.raises(touchcloud.InputError, match=r"x.xyz: unsupported extension '.xyz' \(use .pcd or .ply\)"):
        touchcloud.write_cloud(str(tmp_path / "x.xyz"), grid(3))
    with pytest.raises(touchcloud.InputError, match="empty.ply: the cloud has no points"):
        touchcloud.write_cloud(str(tmp_path / "empty.ply"), np.zeros((0, 3), dtype=np.float32))
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("threshold", [float("nan"), float("inf"), 0.0, -1.0])
def test_score_refuses_a_threshold_the_cli_refuses(tmp_path, threshold):
    touchcloud.write_cloud(str(tmp_path / "gt.pcd"), grid(5))
    with pytest.raises(ValueError, match="fscore_threshold_mm must be a positive, finite number of mm"):
        touchcloud.score(str(tmp_path / "gt.pcd"), [str(tmp_path / "gt.pcd")], fscore_threshold_mm=threshold)


def test_a_closed_mesh_scored_whole_gets_the_coverage_of_what_a_press_from_above_sees(tmp_path):
    # A 20 mm cube as an OBJ; the estimate is its top, 1 mm apart.
    corners = [(20 * (i & 1), 20 * ((i >> 1) & 1), 20 * ((i >> 2) & 1)) for i in range(8)]
    faces = [(0, 1, 3, 2), (4, 5, 7, 6), (0, 1, 5, 4), (2, 3, 7, 6), (0, 2, 6, 4), (1, 3, 7, 5)]
    (tmp_path / "cube.obj").write_text("".join(f"v {x} {y} {z}\n" for x, y, z in corners) +
                                       "".join(f"f {a + 1} {b + 1} {c + 1} {d + 1}\n" for a, b, c, d in faces))
    touchcloud.write_cloud(str(tmp_path / "top.pcd"), grid(21, z=20.0))
    row = touchcloud.score(str(tmp_path / "cube.obj"), [str(tmp_path / "top.pcd")], mesh_samples=60000)[0]
    assert row["recall"] < 0.3                         # the top and a band of the walls
    assert row["visible_recall"] > 0.99                # all a press from above can see
