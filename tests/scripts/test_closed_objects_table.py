"""benchmarks/closed_objects/make_closed_objects_table.py on one shape, one
seed and two touches from above and from any side: every file it promises,
one summary row per method (the all-sides rows with the Palm's dome, the
fingertip's and the realistic sensor's), a curve row per touch, the F-score off the table, a variant
(--set) kept apart from the plain runs, and bad arguments refused before anything runs."""
import csv
import json
import math
import os
import pathlib
import subprocess
import sys

SOURCE = pathlib.Path(os.environ.get("TOUCHCLOUD_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
CLI = pathlib.Path(os.environ.get("TOUCHCLOUD_CLI", SOURCE / "build/bin/touchcloud"))
SCRIPT = SOURCE / "benchmarks/closed_objects/make_closed_objects_table.py"


def table(out, *args):
    return subprocess.run([sys.executable, str(SCRIPT), "--out", str(out), "--touchcloud", str(CLI), *args],
                          capture_output=True, text=True, timeout=600, cwd=SOURCE)


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_one_shape_one_seed_two_touches(tmp_path):
    r = table(tmp_path, "--shapes", "pebble", "--seeds", "1", "--touches", "2", "--all-sides-touches", "2")
    assert r.returncode == 0, r.stderr
    summary = rows(tmp_path / "results.csv")
    methods = ["height field", "implicit surface", "implicit surface, all sides",
               "implicit surface, all sides, 20 mm fingertip", "implicit surface, all sides, realistic sensor"]
    assert [(s["shape"], s["method"].split(" (")[0]) for s in summary] == [("pebble", m) for m in methods]
    for s in summary:
        assert s["seeds"] == "1" and float(s["touches"]) == 2
        for name in ("chamfer_est_to_gt", "p95_est_to_gt", "hausdorff", "fscore", "recall", "fscore_off_table"):
            assert math.isfinite(float(s[name])), (name, s)
            assert float(s[name + "_sd"]) == 0.0  # one seed
        assert float(s["chamfer_est_to_gt"]) <= float(s["hausdorff"]) and float(s["p95_est_to_gt"]) <= float(s["hausdorff"])
        assert 0 < float(s["fscore_off_table"]) <= 1
        assert float(s["on_table_share"]) == 0  # the pebble has no face on the table
    # Refusals are side_touch's: counted for the touches from any side alone.
    assert [s["refused_touches"] != "" for s in summary] == [False, False, True, True, True]
    assert len(rows(tmp_path / "runs.csv")) == 5
    curves = rows(tmp_path / "curves.csv")
    assert [(c["method"].split(" (")[0], c["touch"]) for c in curves] == [(m, t) for m in methods for t in "12"]
    assert "± 0.000" in (tmp_path / "results.md").read_text()
    # Coverage by region: the pebble's faces looking up, sideways and down, for every run.
    regions = rows(tmp_path / "regions.csv")
    assert [(r["method"].split(" (")[0], r["region"]) for r in regions] == \
        [(m, g) for m in methods for g in ("facing down", "facing sideways", "facing up")]
    assert math.isclose(sum(float(r["area_share"]) for r in regions[:3]), 1.0)
    assert all(0 <= float(r["recall"]) <= 1 for r in regions)
    assert "| pebble | height field (GP, max variance) | facing down (" in (tmp_path / "results.md").read_text()


def test_the_mugs_regions_cover_it_once_and_a_surface_there_recalls_only_its_region(tmp_path):
    sys.path.insert(0, str(SCRIPT.parent))
    from region_recall import region_meshes, region_recalls
    meshes = region_meshes("mug", str(tmp_path))
    shares = {region: share for region, _, share in meshes}
    assert sorted(shares) == ["bottom, on the table", "handle", "inner floor", "inner wall", "outer wall", "rim"]
    assert math.isclose(sum(shares.values()), 1.0) and round(shares["bottom, on the table"], 3) == 0.093
    # A cloud on the inside floor alone (the mug's axis at x = -13.5, the floor
    # at z = 6, radius 36): that region recalled, the rim and the bottom not.
    floor = tmp_path / "floor.pcd"
    points = [(-13.5 + r * math.cos(a), r * math.sin(a), 6.0) for r in range(0, 36) for a in
              [k * 2 * math.pi / max(1, round(2 * math.pi * r)) for k in range(max(1, round(2 * math.pi * r)))]]
    floor.write_text("VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                     f"WIDTH {len(points)}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS {len(points)}\nDATA ascii\n" +
                     "".join(f"{x:.3f} {y:.3f} {z:.3f}\n" for x, y, z in points))
    recall = {region: r for region, _, r in region_recalls(str(CLI), "mug", str(floor), 2.0, meshes)}
    assert recall["inner floor"] > 0.95 and recall["rim"] == 0 and recall["bottom, on the table"] == 0, recall


def test_the_score_off_the_table_leaves_out_the_surfaces_points_on_the_table(tmp_path):
    sys.path.insert(0, str(SCRIPT.parent))
    from make_closed_objects_table import write_off_table_points
    import struct
    points = [(1.0, 2.0, 0.0), (3.0, 4.0, 0.0004), (5.0, 6.0, 0.002), (7.0, 8.0, 12.5), (9.0, 1.0, -0.0002)]
    surface = tmp_path / "s.pcd"
    surface.write_bytes(("# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                         f"WIDTH {len(points)}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS {len(points)}\n"
                         "DATA binary\n").encode() + b"".join(struct.pack("<fff", *p) for p in points))
    assert write_off_table_points(str(surface), str(tmp_path / "off.pcd")) == 3
    # The CLI reads what is left: the two points off the table, as they were.
    r = subprocess.run([str(CLI), "score", str(tmp_path / "off.pcd"), "--gt", str(tmp_path / "off.pcd"), "--json",
                        "--metrics", "chamfer_est_to_gt"], capture_output=True, text=True)
    assert r.returncode == 0 and json.loads(r.stdout)[0]["metrics"]["chamfer_est_to_gt_mm"] == 0.0, r.stderr
    lines = (tmp_path / "off.pcd").read_text().splitlines()
    assert "POINTS 2" in lines and [tuple(map(float, l.split())) for l in lines[-2:]] == \
        [struct.unpack("<fff", struct.pack("<fff", *p)) for p in points[2:4]]
    surface.write_text("VERSION 0.7\nFIELDS x y z\nDATA ascii\n1 2 3\n")
    try:
        write_off_table_points(str(surface), str(tmp_path / "off.pcd"))
        assert False, "an ASCII PCD was taken"
    except RuntimeError as e:
        assert "not a binary PCD" in str(e)


def test_bad_arguments_are_refused_before_any_run(tmp_path):
    for args, says in ((["--shapes", "cube"], "no shape cube"), (["--seeds", "one"], "--seeds 'one'"),
                       (["--touches", "0"], "--touches"), (["--all-sides-touches", "0"], "--all-sides-touches"),
                       (["--methods", "all_sides,above"], "no method above"),
                       (["--set", "reselect_growth=0.2"], "--set reselect_growth=0.2: give STAGE.PARAM=VALUE")):
        r = table(tmp_path / "out", *args)
        assert r.returncode == 2 and says in r.stderr, (args, r.stderr)
    assert not (tmp_path / "out").exists()


def test_a_failed_run_is_listed_and_a_kept_run_is_not_made_again(tmp_path):
    runs = tmp_path / "runs"
    first = table(tmp_path / "first", "--shapes", "pebble", "--touches", "2", "--methods", "height_field",
                  "--runs", str(runs))
    assert first.returncode == 0, first.stderr
    # A touchcloud whose runs all fail: the kept height-field run is tabulated
    # as before, the implicit surface's run fails and is listed, not averaged.
    failing = tmp_path / "touchcloud"
    failing.write_text(f'#!/bin/sh\nif [ "$1" = run ]; then echo "touchcloud: error: no run here" >&2; exit 2; fi\n'
                       f'exec "{CLI}" "$@"\n')
    failing.chmod(0o755)
    second = table(tmp_path / "second", "--shapes", "pebble", "--touches", "2", "--methods", "height_field,implicit",
                   "--runs", str(runs), "--touchcloud", str(failing))
    assert second.returncode == 0, second.stderr
    before, after = rows(tmp_path / "first/results.csv"), rows(tmp_path / "second/results.csv")
    assert [(s["seeds"], s["failed"]) for s in after] == [("1", "0"), ("0", "1")]
    assert after[0]["chamfer_est_to_gt"] == before[0]["chamfer_est_to_gt"] and after[1]["chamfer_est_to_gt"] == ""
    assert "- pebble, implicit surface (GPIS, max variance), seed 1: no run here" in \
        (tmp_path / "second/results.md").read_text()
    assert [r["failure"] for r in rows(tmp_path / "second/runs.csv")] == ["", "no run here"]
    # The failure is kept with the run: a seeded run would fail again.
    assert "no run here" in next(runs.glob("pebble-implicit-*/failure.txt")).read_text()


def test_a_variant_set_on_every_run_is_kept_apart_and_named(tmp_path):
    runs = tmp_path / "runs"
    common = ["--shapes", "pebble", "--methods", "all_sides", "--all-sides-touches", "2", "--runs", str(runs)]
    plain = table(tmp_path / "plain", *common)
    assert plain.returncode == 0, plain.stderr
    variant = table(tmp_path / "variant", *common, "--set", "fit.reselect_growth=0", "--set", "fit.offset_mm=3")
    assert variant.returncode == 0, variant.stderr
    # Two runs in --runs, the variant's named by its parameters, and each
    # made with its own: the kept plain run is not taken for the variant.
    made = sorted(p.name for p in runs.iterdir())
    assert made == ["pebble-all_sides-2touches-seed1-fscore2mm",
                    "pebble-all_sides-2touches-seed1-fscore2mm-fit.reselect_growth_0-fit.offset_mm_3"], made
    summary = lambda name: json.loads((runs / name / "summary.json").read_text())
    fit = lambda name: next(s for s in summary(name)["stages"] if s["id"] == "fit")["params"]
    assert fit(made[0])["offset_mm"] == 2.0 and fit(made[1])["offset_mm"] == 3.0
    assert {"key": "fit.reselect_growth", "origin": "--set", "value": "0"} in summary(made[1])["overrides"]
    assert rows(tmp_path / "plain/results.csv")[0]["chamfer_est_to_gt"] != \
        rows(tmp_path / "variant/results.csv")[0]["chamfer_est_to_gt"]
    assert "--methods all_sides --set fit.reselect_growth=0 --set fit.offset_mm=3`" in \
        (tmp_path / "variant/results.md").read_text()


def write_binary_pcd(path, points):
    import struct
    path.write_bytes(("VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                      f"WIDTH {len(points)}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS {len(points)}\n"
                      "DATA binary\n").encode() + b"".join(struct.pack("<fff", *p) for p in points))


def test_coverage_by_distance_to_the_touches_tells_a_part_never_touched_from_one_missed_between_touches(tmp_path):
    sys.path.insert(0, str(SCRIPT.parent))
    from touch_distance_coverage import band_table, samples
    points, _, _ = samples("sphere", 30000, seed=7)
    centre_z = points[:, 2].mean()
    top = [tuple(p) for p in points if p[2] > centre_z]
    whole, upper = tmp_path / "whole", tmp_path / "upper"
    for run, surface in ((whole, [tuple(p) for p in points]), (upper, top)):
        run.mkdir()
        write_binary_pcd(run / "sphere_touch_points.pcd", top)
        write_binary_pcd(run / "sphere_surface.pcd", surface)
    # Touched on its upper half (a 60 mm sphere): the faces looking up lie within 3 mm of a
    # touch, those looking down (more than 30 degrees below the equator) 8 mm or more from one.
    t = band_table("sphere", [str(whole)], 2.0, 20000, seed=1)
    assert t[("facing up", 0)][0] > 0.99 and t[("facing up", 0)][1] == 1.0, t
    assert t[("facing down", 2)][0] + t[("facing down", 3)][0] > 0.95, t
    assert t[("facing down", 2)][1] == 1.0 and t[("facing down", 3)][1] == 1.0, t
    # A surface that stops where the touches stop covers nothing far from them.
    t = band_table("sphere", [str(upper)], 2.0, 20000, seed=1)
    assert t[("facing up", 0)][1] == 1.0 and t[("facing down", 2)][1] == 0.0 and t[("facing down", 3)][1] == 0.0, t
    # Two runs: their mean.
    t = band_table("sphere", [str(whole), str(upper)], 2.0, 20000, seed=1)
    assert t[("facing down", 3)][1] == 0.5, t
    script = SCRIPT.parent / "touch_distance_coverage.py"
    r = subprocess.run([sys.executable, str(script), "--shape", "sphere", "--run", str(whole)],
                       capture_output=True, text=True)
    assert r.returncode == 0 and "| facing down |" in r.stdout, r.stderr
    (whole / "sphere_surface.pcd").unlink()
    r = subprocess.run([sys.executable, str(script), "--shape", "sphere", "--run", str(whole)],
                       capture_output=True, text=True)
    assert r.returncode == 2 and "no sphere_surface.pcd" in r.stderr, r.stderr


def test_a_touch_on_one_face_of_a_thin_wall_does_not_count_as_near_the_other_face(tmp_path):
    sys.path.insert(0, str(SCRIPT.parent))
    from touch_distance_coverage import band_table, samples
    points, regions, _ = samples("mug", 30000, seed=7)
    outer = [tuple(p) for p, r in zip(points, regions) if r == "outer wall"]
    run = tmp_path / "outer"
    run.mkdir()
    write_binary_pcd(run / "mug_touch_points.pcd", outer)
    write_binary_pcd(run / "mug_surface.pcd", outer)
    # Touched all over its outer wall: the inner wall, 4 mm inside, lies within 8 mm of a touch...
    t = band_table("mug", [str(run)], 2.0, 20000, seed=1)
    assert t[("inner wall", 0)][0] + t[("inner wall", 1)][0] > 0.99, t
    # ...but no touch on its side reached it: beyond the last band, and never covered.
    t = band_table("mug", [str(run)], 2.0, 20000, seed=1, same_side=True)
    assert t[("inner wall", 3)][0] > 0.99 and t[("inner wall", 3)][1] < 0.01, t
    assert t[("outer wall", 0)][0] > 0.99 and t[("outer wall", 0)][1] > 0.99, t
