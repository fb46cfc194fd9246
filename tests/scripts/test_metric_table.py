"""scripts/metric_table.py: the first-run page's metric table is what the plugins
declare, and a table that differs is caught."""
import json
import os
import pathlib
import subprocess
import sys

SOURCE = pathlib.Path(os.environ.get("TOUCHCLOUD_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
CLI = pathlib.Path(os.environ.get("TOUCHCLOUD_CLI", SOURCE / "build/bin/touchcloud"))
SCRIPT = SOURCE / "scripts/metric_table.py"


def table_script(*args):
    return subprocess.run([sys.executable, str(SCRIPT), "--cli", str(CLI), *map(str, args)], capture_output=True,
                          text=True, timeout=120)


def test_the_first_run_pages_metric_table_is_the_declarations():
    r = table_script("--check", "--page", SOURCE / "docs/first-run.md")
    assert r.returncode == 0, r.stderr


def test_rows_come_from_the_plugins_declarations():
    r = table_script()
    assert r.returncode == 0, r.stderr
    chamfer = {m["name"]: m for m in json.loads(subprocess.run([str(CLI), "plugins", "chamfer", "--json"],
                                                               capture_output=True, text=True, check=True).stdout)["metrics"]}
    eq11 = chamfer["chamfer_est_to_gt"]
    assert (f"| `score.chamfer_est_to_gt` | mm | each touch | lower | {eq11['doc']} (role `accuracy`) |"
            in r.stdout.splitlines()), r.stdout
    assert "| `score.final_chamfer_mm` | mm | once, at the end | lower |" in r.stdout


def test_a_table_that_differs_is_caught_and_rewritten(tmp_path):
    page = tmp_path / "first-run.md"
    text = (SOURCE / "docs/first-run.md").read_text()
    stale = text.replace("| `score.final_chamfer_mm` | mm |", "| `score.final_chamfer_mm` | cm |")
    assert stale != text
    page.write_text(stale)
    r = table_script("--check", "--page", page)
    assert r.returncode == 1 and "differs from the declarations" in r.stderr, r.stderr
    assert table_script("--write", "--page", page).returncode == 0
    assert page.read_text() == text
