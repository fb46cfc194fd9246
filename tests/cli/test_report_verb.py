"""touchcloud report and run --report, as a user runs them, and the page in a
real browser (headless Chromium; skipped, saying so, where it is absent)."""
import json
import os
import pathlib
import re
import shutil
import subprocess

import pytest

SOURCE = pathlib.Path(os.environ.get("TOUCHCLOUD_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
CLI = pathlib.Path(os.environ.get("TOUCHCLOUD_CLI", SOURCE / "build/bin/touchcloud"))
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
# The main job, short: 6 touches, the surface on an 80 x 80 lattice (as
# tests/pipelines/test_active_reconstruction.cpp shortens it).
SHORT = ["--seed", "1", "--set", "explore.max_iterations=6", "--set", "surface.resolution=[80, 80]"]


def cli(*args):
    return subprocess.run([str(CLI), *map(str, args)], cwd=SOURCE, capture_output=True, text=True, timeout=120)


@pytest.fixture(scope="module")
def run_dir(tmp_path_factory):
    out = tmp_path_factory.mktemp("run") / "fox"
    r = cli("run", "pipelines/fox_mask_active.yaml", *SHORT, "--out", out, "-q", "--report")
    assert r.returncode == 0, r.stderr
    assert f"wrote {out / 'report.html'}" in r.stdout
    return out


def embedded_data(html):
    m = re.search(r'<script type="application/json" id="tc-data">(.*?)</script>', html, re.S)
    assert m, "no data element"
    return json.loads(m.group(1))


def assert_bad_input(r, *words):
    assert r.returncode == 2, (r.returncode, r.stdout, r.stderr)
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("touchcloud: error: "), r.stderr
    for w in words:
        assert w in lines[0], (w, lines[0])


def test_folder_without_summary_is_exit_2_and_writes_nothing(tmp_path):
    (tmp_path / "notes.txt").write_text("not a run\n")
    assert_bad_input(cli("report", tmp_path), str(tmp_path / "summary.json"))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["notes.txt"]


def test_missing_folder_is_exit_2(tmp_path):
    assert_bad_input(cli("report", tmp_path / "nowhere"), str(tmp_path / "nowhere"))


@pytest.mark.parametrize("text,words", [
    ("{not json", ["is not JSON"]),
    ('{"pipeline": {"name": "x"}, "metrics": {}}', ["no 'versions' key"]),
    ('{"versions": {}, "metrics": {}}', ["no 'pipeline' key"]),
    ('[1, 2]', ["not a JSON object"]),
])
def test_foreign_summary_is_exit_2_naming_the_file(tmp_path, text, words):
    (tmp_path / "summary.json").write_text(text)
    assert_bad_input(cli("report", tmp_path), str(tmp_path / "summary.json"), *words)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["summary.json"]
    assert_bad_input(cli("report", tmp_path, "--out", tmp_path / "elsewhere.html"))
    assert not (tmp_path / "elsewhere.html").exists()


def test_report_is_self_contained_complete_and_deterministic(run_dir, tmp_path):
    html = (run_dir / "report.html").read_text()
    assert not re.search(r"<(script|link|img)[^>]+(src|href)=", html), "the page fetches a resource"
    assert "Three.js Authors" in html and "SPDX-License-Identifier: MIT" in html  # three's licence header kept
    assert len(html) < 6_000_000
    data = embedded_data(html)
    summary = json.loads((run_dir / "summary.json").read_text())
    # Chamfer per touch: the run's series, one value per touch.
    (curve,) = data["chamfer"]["curves"]
    assert curve["metric"] == "score.chamfer_est_to_gt"
    assert curve["series"] == summary["metrics"]["score.chamfer_est_to_gt"]["series"]
    assert len(curve["series"]) == 6
    clouds = data["clouds"]
    assert data["missing"] == [] and data["images"] == [], data["missing"]
    assert clouds["surface"]["points"] == 80 * 80 - summary["metrics"]["surface.extrapolated_points"]["value"]
    assert clouds["ground_truth"]["points"] > 1_000_000 and clouds["ground_truth"]["shown"] <= 50_000
    assert clouds["touch_points"]["points"] == summary["metrics"]["dedup.total_points"]["value"]
    assert clouds["touch_points"]["touch_counts"] == summary["metrics"]["dedup.added_points"]["series"]
    assert len(clouds["touch_targets_xy_mm"]) == 6
    # The surface's mean distance to the ground truth is of the order of the chamfer score.
    assert 0 < clouds["surface"]["distance_mean_mm"] < 3 * curve["series"][-1]
    assert [s["id"] for s in data["stages"]] == [s["id"] for s in summary["stages"]]
    assert ["touchcloud", summary["versions"]["touchcloud"]] in data["versions"]
    # The same folder gives the same bytes; --out puts them elsewhere.
    again = tmp_path / "again.html"
    r = cli("report", run_dir, "--out", again)
    assert r.returncode == 0, r.stderr
    assert again.read_bytes() == (run_dir / "report.html").read_bytes()


def test_out_naming_a_folder_is_exit_2(run_dir, tmp_path):
    assert_bad_input(cli("report", run_dir, "--out", tmp_path), str(tmp_path), "is a folder")
    assert list(tmp_path.iterdir()) == []


def test_folder_of_runs_draws_every_runs_curve(run_dir, tmp_path):
    for name in ("runs/setting0_seed1", "runs/setting1_seed1"):
        shutil.copytree(run_dir, tmp_path / name)
    # The second run's curve differs: its summary says so.
    s = json.loads((tmp_path / "runs/setting1_seed1/summary.json").read_text())
    s["metrics"]["score.chamfer_est_to_gt"]["series"] = [2.0, 1.0]
    (tmp_path / "runs/setting1_seed1/summary.json").write_text(json.dumps(s))
    r = cli("report", tmp_path)
    assert r.returncode == 0, r.stderr
    data = embedded_data((tmp_path / "report.html").read_text())
    assert [(c["label"], len(c["series"])) for c in data["chamfer"]["curves"]] == [
        ("runs/setting0_seed1", 6), ("runs/setting1_seed1", 2)]
    assert data["folder_runs"] == 2


def test_image_outputs_are_embedded_and_missing_ones_named(run_dir, tmp_path):
    import base64
    import numpy as np
    import matplotlib.image
    folder = tmp_path / "run"
    shutil.copytree(run_dir, folder)
    matplotlib.image.imsave(str(folder / "left.png"), np.linspace(0, 1, 64 * 48).reshape(48, 64))
    s = json.loads((folder / "summary.json").read_text())
    s["outputs"] += ["left.png", "gone.png"]
    (folder / "summary.json").write_text(json.dumps(s))
    r = cli("report", folder)
    assert r.returncode == 0, r.stderr
    data = embedded_data((folder / "report.html").read_text())
    (image,) = data["images"]
    assert (image["name"], image["mime"]) == ("left.png", "image/png")
    assert base64.b64decode(image["base64"]) == (folder / "left.png").read_bytes()
    assert data["missing"] == ["image gone.png: not found"]


def test_sweep_report_has_each_runs_curve_and_time(tmp_path):
    out = tmp_path / "sweep"
    r = cli("sweep", "pipelines/fox_mask_active.yaml", "--vary", "explore.max_iterations=4,5",
            "--set", "surface.resolution=[60, 60]", "--out", out, "--report")
    assert r.returncode == 0, r.stderr
    assert f"wrote {out / 'report.html'}" in r.stdout
    data = embedded_data((out / "report.html").read_text())
    curves = data["chamfer"]["curves"]
    assert [(c["label"], len(c["series"])) for c in curves] == [("runs/setting0_seed0", 4), ("runs/setting1_seed0", 5)]
    for c in curves:
        summary = json.loads((out / c["label"] / "summary.json").read_text())
        assert c["final"] == summary["metrics"]["score.chamfer_est_to_gt"]["value"]
        assert c["wall_time_s"] == summary["wall_time_s"]


def chromium(*args):
    return subprocess.run([CHROMIUM, "--headless=new", "--no-sandbox", "--disable-gpu", "--enable-unsafe-swiftshader",
                           "--hide-scrollbars", "--window-size=1200,1300", *args],
                          capture_output=True, text=True, timeout=60)


@pytest.mark.skipif(CHROMIUM is None, reason="chromium is not installed (scripts/install-deps.sh installs it): "
                                             "the report is not checked in a browser")
def test_report_draws_in_a_real_browser(run_dir, tmp_path):
    import numpy as np
    import matplotlib.image
    url = (run_dir / "report.html").as_uri()
    dom = chromium("--dump-dom", url)
    assert dom.returncode == 0, dom.stderr
    errors = re.search(r'<pre id="tc-errors"[^>]*>(.*?)</pre>', dom.stdout, re.S)
    assert errors and errors.group(1).strip() == "", "JavaScript errors or failed resources: " + errors.group(1)
    status = re.search(r'<div id="tc-status" data-drawn="([^"]*)" data-rects="([^"]*)"', dom.stdout)
    assert status, "the page never finished drawing"
    assert status.group(1) == "3d chamfer times"
    rects = json.loads(status.group(2).replace("&quot;", '"'))
    png = tmp_path / "report.png"
    shot = chromium("--screenshot=" + str(png), url)
    assert shot.returncode == 0 and png.exists(), shot.stderr
    image = (matplotlib.image.imread(str(png))[..., :3] * 255).round().astype(np.int32)
    assert image.shape[:2] == (1300, 1200)
    for name, (x, y, w, h) in rects.items():
        assert w > 100 and h > 100 and y + h <= image.shape[0] and x + w <= image.shape[1], (name, rects)
        region = image[y:y + h, x:x + w].reshape(-1, 3)
        background = np.median(region, axis=0)
        drawn = np.abs(region - background).max(axis=1) > 40
        colours = len(np.unique(region[drawn], axis=0))
        # Drawn: a few percent of the region's pixels off the background, in many colours.
        assert drawn.mean() > (0.05 if name == "3d" else 0.01), (name, drawn.mean())
        assert colours >= (200 if name == "3d" else 2), (name, colours)
