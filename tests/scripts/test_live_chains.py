"""benchmarks/live_chains/make_live_chains.py end to end on tiny videos: it
simulates each family's press, writes the videos, streams each chain through
touchcloud and through the OpenCV-Python peer, and writes its tables. The
figures themselves are timings and are not asserted; the clouds' agreement
is (both sides do the same arithmetic), and the fast colour chain's accuracy
against the default one is stated."""
import csv
import os
import subprocess
import sys

ROOT = os.environ.get("TOUCHCLOUD_SOURCE_DIR", os.getcwd())
SCRIPT = os.path.join(ROOT, "benchmarks", "live_chains", "make_live_chains.py")


def test_writes_the_tables_for_every_chain(tmp_path):
    subprocess.run([sys.executable, SCRIPT, "--out", str(tmp_path), "--frames", "12", "--repeats", "1",
                    "--simulated-frames", "40"], check=True, cwd=ROOT, timeout=600)
    with open(tmp_path / "results.csv") as f:
        rows = {r["chain"]: r for r in csv.DictReader(f)}
    assert set(rows) == {"gelsight", "colour", "colour_fast", "markers"}
    for r in rows.values():
        assert int(r["frames"]) > 0
        assert float(r["touchcloud_fps"]) > 0 and float(r["opencv_python_fps"]) > 0
        assert r["goal_met"] in ("True", "False")
    # The same pixels give the same points on both sides.
    for chain in ("gelsight", "colour", "colour_fast"):
        assert float(rows[chain]["max_points_difference"]) == 0
    with open(tmp_path / "stages.csv") as f:
        stages = {(r["chain"], r["stage"]) for r in csv.DictReader(f)}
    assert ("gelsight", "depth") in stages and ("colour", "disparity") in stages and ("markers", "detect") in stages
    table = (tmp_path / "results.md").read_text()
    assert "taskset -c 0" in table and "| GelSight-type" in table
    assert "| colour_fast | colour |" in table
