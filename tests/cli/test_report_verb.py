"""touchcloud report and run --report, as a user runs them, and the page in a
real browser (headless Chromium; skipped, saying so, where it is absent)."""
import json
import os
import pathlib
import re
import shutil
import statistics
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
    # The headline: Eq. 11 beside what it hides, found by role, and the
    # surface the extrapolation mask dropped; the title names the scene.
    m = summary["metrics"]
    assert [(h["role"], h["metric"], h["value"]) for h in data["headline"]] == [
        ("accuracy", "score.chamfer_est_to_gt", m["score.chamfer_est_to_gt"]["value"]),
        ("completeness", "score.chamfer_gt_to_est", m["score.chamfer_gt_to_est"]["value"]),
        ("fscore", "score.fscore", m["score.fscore"]["value"]),
        ("coverage", "score.recall", m["score.recall"]["value"]),
        ("masked_points", "surface.masked_points", m["surface.masked_points"]["value"])]
    assert data["run"]["scene"] == "fox_mask" and summary["scene"]["name"] == "fox_mask"
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
    for name in ("runs/setting0_seed1", "runs/setting10_seed1", "runs/setting2_seed1"):
        shutil.copytree(run_dir, tmp_path / name)
    # One run's curve differs: its summary says so.
    s = json.loads((tmp_path / "runs/setting10_seed1/summary.json").read_text())
    s["metrics"]["score.chamfer_est_to_gt"]["series"] = [2.0, 1.0]
    (tmp_path / "runs/setting10_seed1/summary.json").write_text(json.dumps(s))
    r = cli("report", tmp_path)
    assert r.returncode == 0, r.stderr
    data = embedded_data((tmp_path / "report.html").read_text())
    # In the order of the numbers in their names; copies of one run (the same
    # overrides and seed) are one setting, told apart by their folders.
    assert [(c["label"], len(c["series"])) for c in data["chamfer"]["curves"]] == [
        ("fox_mask_active, seed 1 (runs/setting0_seed1)", 6), ("fox_mask_active, seed 1 (runs/setting2_seed1)", 6),
        ("fox_mask_active, seed 1 (runs/setting10_seed1)", 2)]
    assert [(t["label"], t["curves"]) for t in data["settings"]] == [("fox_mask_active", [0, 1, 2])]
    assert data["folder_runs"] == 3


def test_runs_given_different_overrides_are_named_by_them(run_dir, tmp_path):
    # Runs of one pipeline by hand, not a sweep: named by the --set values that differ.
    for name, value in (("a", "0.9"), ("b", "3.6")):
        shutil.copytree(run_dir, tmp_path / name)
        s = json.loads((tmp_path / name / "summary.json").read_text())
        s["overrides"].append({"key": "dedup.threshold_mm", "value": value, "origin": "--set"})
        (tmp_path / name / "summary.json").write_text(json.dumps(s))
    r = cli("report", tmp_path)
    assert r.returncode == 0, r.stderr
    data = embedded_data((tmp_path / "report.html").read_text())
    assert [c["label"] for c in data["chamfer"]["curves"]] == ["dedup.threshold_mm=0.9, seed 1",
                                                                "dedup.threshold_mm=3.6, seed 1"]
    assert [t["label"] for t in data["settings"]] == ["dedup.threshold_mm=0.9", "dedup.threshold_mm=3.6"]


def test_image_outputs_are_embedded_and_missing_ones_named(run_dir, tmp_path):
    import base64
    import numpy as np
    import matplotlib.image
    folder = tmp_path / "run"
    shutil.copytree(run_dir, folder)
    matplotlib.image.imsave(str(folder / "left.png"), np.linspace(0, 1, 64 * 48).reshape(48, 64))
    s = json.loads((folder / "summary.json").read_text())
    s["outputs"] += ["left.png", "gone.png", "right.png"]
    # Pictures are what the stages record as images; a PNG of another role is not one.
    s["artifacts"] += [{"stage": "view", "role": "image", "file": "left.png", "attributes": {"caption": "Left view"}},
                       {"stage": "view", "role": "image", "file": "gone.png", "attributes": {}},
                       {"stage": "view", "role": "dataset", "file": "right.png", "attributes": {}}]
    matplotlib.image.imsave(str(folder / "right.png"), np.zeros((4, 4)))
    (folder / "summary.json").write_text(json.dumps(s))
    r = cli("report", folder)
    assert r.returncode == 0, r.stderr
    data = embedded_data((folder / "report.html").read_text())
    (image,) = data["images"]
    assert (image["name"], image["mime"], image["caption"]) == ("left.png", "image/png", "Left view")
    assert base64.b64decode(image["base64"]) == (folder / "left.png").read_bytes()
    assert data["missing"] == ["image gone.png: not found"]


# A small scoring run written here: an estimate read from a file, scored by
# chamfer against a square mesh sampled at `samples` points with
# `sample_seed`. Paths in the pipeline are relative to its folder.
SQUARE_OBJ = "v 0 0 0\nv 10 0 0\nv 10 10 0\nv 0 10 0\nf 1 2 3\nf 1 3 4\n"


def scoring_run(folder, sample_seed, samples=500):
    import numpy as np
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "square.obj").write_text(SQUARE_OBJ)
    grid = np.stack(np.meshgrid(np.linspace(0.5, 9.5, 7), np.linspace(0.5, 9.5, 7)), -1).reshape(-1, 2)
    estimate = np.column_stack([grid, np.full(len(grid), 0.25)])
    (folder / "estimate.pcd").write_text(
        f"VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH {len(estimate)}\nHEIGHT 1\n"
        f"VIEWPOINT 0 0 0 1 0 0 0\nPOINTS {len(estimate)}\nDATA ascii\n" +
        "".join(f"{x} {y} {z}\n" for x, y, z in estimate))
    (folder / "score.yaml").write_text(
        "pipeline: square\nstages:\n"
        "  - id: read\n    plugin: cloud_reader\n    params: {path: estimate.pcd}\n"
        f"  - id: score\n    plugin: chamfer\n    params: {{ground_truth: square.obj, samples: {samples}, "
        f"sample_seed: {sample_seed}}}\n    inputs: {{cloud: read.cloud}}\n")
    out = folder / "out"
    # Run from the pipeline's folder, with the pipeline named relative to it.
    r = subprocess.run([str(CLI), "run", "score.yaml", "--out", "out", "-q"], cwd=folder, capture_output=True,
                       text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    return out, estimate


def ground_truth_shown(data):
    import base64
    import numpy as np
    gt = data["clouds"]["ground_truth"]
    return np.frombuffer(base64.b64decode(gt["xyz"]), dtype="<f4").reshape(-1, 3).astype(float)


def test_report_draws_the_ground_truth_the_stage_scored_against(tmp_path):
    import numpy as np
    out, estimate = scoring_run(tmp_path / "run", sample_seed=7)
    summary = json.loads((out / "summary.json").read_text())
    report = lambda folder: subprocess.run([str(CLI), "report", "out"], cwd=folder, capture_output=True, text=True,
                                           timeout=120)
    r = report(tmp_path / "run")  # from the folder the run started in
    assert r.returncode == 0, r.stderr
    data = embedded_data((out / "report.html").read_text())
    gt = ground_truth_shown(data)
    assert len(gt) == 500 and data["clouds"]["ground_truth"]["shown"] == 500
    # The points drawn give the chamfer the stage reported (Eq. 11: each
    # estimated point's distance to its nearest ground-truth point) ...
    nearest = np.sqrt(((estimate[:, None, :] - gt[None, :, :]) ** 2).sum(-1)).min(1)
    reported = summary["metrics"]["score.chamfer_est_to_gt"]["value"]
    assert nearest.mean() == pytest.approx(reported, rel=1e-5, abs=1e-5)
    (truth,) = [a for a in summary["artifacts"] if a["role"] == "ground_truth"]
    assert truth["attributes"]["sample_seed"] == 7 and truth["attributes"]["samples"] == 500
    # ... which other samples (sample_seed 0's) would not.
    seed0_out, _ = scoring_run(tmp_path / "seed0", sample_seed=0)
    assert report(tmp_path / "seed0").returncode == 0
    seed0 = ground_truth_shown(embedded_data((seed0_out / "report.html").read_text()))
    assert not np.array_equal(seed0, gt)
    nearest0 = np.sqrt(((estimate[:, None, :] - seed0[None, :, :]) ** 2).sum(-1)).min(1)
    assert abs(nearest0.mean() - reported) > 1e-4


def test_report_finds_the_ground_truth_from_any_folder(tmp_path):
    out, _ = scoring_run(tmp_path / "started_here", sample_seed=3)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    r = subprocess.run([str(CLI), "report", str(out)], cwd=elsewhere, capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    data = embedded_data((out / "report.html").read_text())
    assert not [m for m in data["missing"] if "ground truth" in m], data["missing"]
    assert data["clouds"]["ground_truth"]["points"] == 500
    assert data["clouds"]["ground_truth"]["source"] == str(tmp_path / "started_here/square.obj")


@pytest.fixture(scope="module")
def sweep_dir(tmp_path_factory):
    out = tmp_path_factory.mktemp("sweep") / "sweep"
    r = cli("sweep", "pipelines/fox_mask_active.yaml", "--vary", "explore.max_iterations=4,5", "--repeats", "2",
            "--set", "surface.resolution=[60, 60]", "--out", out, "--report")
    assert r.returncode == 0, r.stderr
    assert f"wrote {out / 'report.html'}" in r.stdout
    return out


def test_sweep_report_has_a_panel_per_setting_named_by_the_values_varied(sweep_dir):
    data = embedded_data((sweep_dir / "report.html").read_text())
    curves = data["chamfer"]["curves"]
    assert [(c["label"], c["folder"], len(c["series"])) for c in curves] == [
        ("explore.max_iterations=4, seed 0", "runs/setting0_seed0", 4),
        ("explore.max_iterations=4, seed 1", "runs/setting0_seed1", 4),
        ("explore.max_iterations=5, seed 0", "runs/setting1_seed0", 5),
        ("explore.max_iterations=5, seed 1", "runs/setting1_seed1", 5)]
    for c in curves:
        summary = json.loads((sweep_dir / c["folder"] / "summary.json").read_text())
        assert c["series"] == summary["metrics"]["score.chamfer_est_to_gt"]["series"]
        assert c["final"] == summary["metrics"]["score.chamfer_est_to_gt"]["value"]
        assert c["wall_time_s"] == summary["wall_time_s"]
    assert curves[0]["series"] != curves[1]["series"], "the seeds' curves differ"
    # Each setting: its repeats, their final chamfer and wall time.
    assert [(t["label"], t["curves"]) for t in data["settings"]] == [
        ("explore.max_iterations=4", [0, 1]), ("explore.max_iterations=5", [2, 3])]
    for t in data["settings"]:
        finals = [curves[i]["final"] for i in t["curves"]]
        times = [curves[i]["wall_time_s"] for i in t["curves"]]
        assert t["final"]["n"] == 2 and t["final"]["mean"] == pytest.approx(statistics.fmean(finals), rel=1e-12)
        assert t["final"]["sd"] == pytest.approx(statistics.stdev(finals), rel=1e-9)
        assert (t["final"]["min"], t["final"]["max"]) == (min(finals), max(finals))
        assert t["wall_time_s"]["mean"] == pytest.approx(statistics.fmean(times), rel=1e-12)
    assert data["run"]["label"] == "explore.max_iterations=4, seed 0"


def chromium(*args, size=(1200, 1300)):
    return subprocess.run([CHROMIUM, "--headless=new", "--no-sandbox", "--disable-gpu", "--enable-unsafe-swiftshader",
                           "--hide-scrollbars", f"--window-size={size[0]},{size[1]}", *args],
                          capture_output=True, text=True, timeout=60)


needs_chromium = pytest.mark.skipif(CHROMIUM is None, reason="chromium is not installed (scripts/install-deps.sh "
                                                               "installs it): the report is not checked in a browser")


def check_in_browser(report, tmp_path, expected, looked_at=None):
    """Opens `report` in headless Chromium: no JavaScript error or failed
    resource, the drawings `expected` (and no others) finished, and each of
    them (or of `looked_at`) drawn, not blank, in a screenshot of the whole
    page."""
    import numpy as np
    import matplotlib.image
    url = report.as_uri()
    dom = chromium("--dump-dom", url)
    assert dom.returncode == 0, dom.stderr
    errors = re.search(r'<pre id="tc-errors"[^>]*>(.*?)</pre>', dom.stdout, re.S)
    assert errors and errors.group(1).strip() == "", "JavaScript errors or failed resources: " + errors.group(1)
    status = re.search(r'<div id="tc-status" data-drawn="([^"]*)" data-rects="([^"]*)"', dom.stdout)
    assert status, "the page never finished drawing"
    assert sorted(status.group(1).split()) == sorted(expected)
    rects = json.loads(status.group(2).replace("&quot;", '"'))
    # The page is 1200 px wide whatever the window; the window as tall as the drawings reach.
    height = max(1300, max(y + h for x, y, w, h in rects.values()) + 20)
    png = tmp_path / "report.png"
    shot = chromium("--screenshot=" + str(png), url, size=(1200, height))
    assert shot.returncode == 0 and png.exists(), shot.stderr
    image = (matplotlib.image.imread(str(png))[..., :3] * 255).round().astype(np.int32)
    assert image.shape[:2] == (height, 1200)
    for name, (x, y, w, h) in rects.items():
        if looked_at is not None and name not in looked_at:
            continue
        assert w > 100 and h > 100 and y + h <= image.shape[0] and x + w <= image.shape[1], (name, rects)
        region = image[y:y + h, x:x + w].reshape(-1, 3)
        background = np.median(region, axis=0)
        drawn = np.abs(region - background).max(axis=1) > 40
        colours = len(np.unique(region[drawn], axis=0))
        # Drawn: the 3D view and pictures a few percent of their pixels off the background, in
        # many colours; a plot's marks (its area only: axes and labels lie outside it) a few
        # hundred pixels (the 4 points and the front of a 4-run Pareto plot: 0.17 to 0.6 %, fewer
        # where wall times measured under load put points on top of each other; blank: 0).
        least = 0.05 if name == "3d" else 0.01 if name.startswith("image") else 0.0005
        assert drawn.mean() > least, (name, drawn.mean())
        assert colours >= (200 if name == "3d" else 2), (name, colours)
    return dom.stdout


@needs_chromium
def test_report_draws_in_a_real_browser(run_dir, tmp_path):
    check_in_browser(run_dir / "report.html", tmp_path, ["3d", "chamfer", "times"])


@needs_chromium
def test_sweep_report_draws_each_settings_panel_in_a_real_browser(sweep_dir, tmp_path):
    dom = check_in_browser(sweep_dir / "report.html", tmp_path,
                           ["3d", "chamfer", "times", "pareto", "setting0", "setting1"])
    assert "<h3>explore.max_iterations=4</h3>" in dom and "<h3>explore.max_iterations=5</h3>" in dom


# The shipped sensing pipelines' pictures: the file, its caption, and the picture in the page.
PICTURES = {
    "simulate_touch_gelsight": ("height.png", "Height (mm) estimated (left) beside the ground truth (right), on one "
                                              "colour scale from 0 to "),
    "simulate_touch_images": ("markers.png", "Left and right images of frame "),
}


@pytest.fixture(scope="module", params=sorted(PICTURES))
def sensing_dir(request, tmp_path_factory):
    out = tmp_path_factory.mktemp("sensing") / request.param
    r = cli("run", f"pipelines/{request.param}.yaml", "--seed", "1", "--out", out, "-q", "--report")
    assert r.returncode == 0, r.stderr
    return out


def test_sensing_pipelines_pictures_are_in_the_report_with_their_captions(sensing_dir):
    import base64
    name, caption = PICTURES[sensing_dir.name]
    summary = json.loads((sensing_dir / "summary.json").read_text())
    assert name in summary["outputs"]
    (image,) = embedded_data((sensing_dir / "report.html").read_text())["images"]
    assert (image["name"], image["mime"]) == (name, "image/png")
    assert image["caption"].startswith(caption), image["caption"]
    (record,) = [a for a in summary["artifacts"] if a["role"] == "image"]
    assert (record["stage"], record["file"]) == ("picture", name)
    assert image["caption"] == record["attributes"]["caption"]
    assert base64.b64decode(image["base64"]) == (sensing_dir / name).read_bytes()


# One pipeline's page in the browser (a picture loads as a picture); both pages' data are checked above.
@needs_chromium
@pytest.mark.parametrize("sensing_dir", ["simulate_touch_images"], indirect=True)
def test_sensing_pictures_load_in_a_real_browser(sensing_dir, tmp_path):
    name, caption = PICTURES[sensing_dir.name]
    dom = check_in_browser(sensing_dir / "report.html", tmp_path, ["3d", "times", "image0"], looked_at=["image0"])
    assert re.search(r"<figcaption>" + re.escape(caption) + r"[^<]*\(" + re.escape(name) + r"\)</figcaption>", dom)
