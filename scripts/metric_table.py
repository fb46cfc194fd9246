#!/usr/bin/python3
"""Writes the first-run page's table of the main job's metrics from what the plugins
declare (`touchcloud plugins NAME --json`): each key's unit, when it is
reported, which way is better, its role and its one-line doc. The keys are
chosen here; their stages' plugins are read from the main job's pipeline.

  scripts/metric_table.py              # print the table
  scripts/metric_table.py --write      # put it into docs/first-run.md between its markers
  scripts/metric_table.py --check      # exit 1 when docs/first-run.md's table differs
"""
import argparse
import json
import pathlib
import re
import subprocess
import sys

SOURCE = pathlib.Path(__file__).resolve().parents[1]
PIPELINE = "pipelines/fox_mask_active.yaml"
KEYS = [
    "score.chamfer_est_to_gt", "score.chamfer_gt_to_est", "score.fscore", "score.recall",
    "score.final_chamfer_mm", "score.convergence_touches",
    "surface.masked_points",
    "plan.unreachable_cells", "plan.cells_without_gain", "plan.touches_planned",
    "dedup.added_points", "dedup.total_points",
    "plan.target_x_mm", "plan.target_y_mm",
    "fit.update_path", "fit.selections", "fit.jitter_mm2",
]
BEGIN = "<!-- metric table: written by scripts/metric_table.py from the plugins' declarations -->"
END = "<!-- end of metric table -->"


def stage_plugins(pipeline):
    """Stage id -> plugin, from the pipeline's `- id: X` / `plugin: Y` line pairs."""
    text = (SOURCE / pipeline).read_text()
    return dict(re.findall(r"-\s+id:\s*(\w+)\s*\n\s+plugin:\s*(\w+)", text))


def table(cli):
    stages = stage_plugins(PIPELINE)
    declared = {}
    rows = ["| key | unit | reported | better | what |", "|---|---|---|---|---|"]
    for key in KEYS:
        stage, name = key.split(".", 1)
        if stage not in stages:
            sys.exit(f"metric_table: {PIPELINE} has no stage '{stage}' (key {key})")
        plugin = stages[stage]
        if plugin not in declared:
            out = subprocess.run([str(cli), "plugins", plugin, "--json"], capture_output=True, text=True, check=True)
            declared[plugin] = {m["name"]: m for m in json.loads(out.stdout)["metrics"]}
        if name not in declared[plugin]:
            sys.exit(f"metric_table: plugin '{plugin}' (stage {stage}) declares no metric '{name}'")
        m = declared[plugin][name]
        # Inside the main job's touch loop a per-item metric comes once per touch.
        reported = "each touch" if m["when"] == "per_item" else "once, at the end"
        better = {"lower_is_better": "lower", "higher_is_better": "higher"}.get(m["direction"], "")
        what = m["doc"] + (f" (role `{m['role']}`)" if "role" in m else "")
        rows.append(f"| `{key}` | {m['unit'] or '-'} | {reported} | {better} | {what} |")
    return "\n".join(rows) + "\n"


def with_table(page, text):
    if page.count(BEGIN) != 1 or page.count(END) != 1:
        sys.exit(f"metric_table: the page needs one '{BEGIN}' and one '{END}' line")
    head, rest = page.split(BEGIN + "\n", 1)
    _, tail = rest.split(END, 1)
    return head + BEGIN + "\n" + text + END + tail


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cli", default=str(SOURCE / "build/bin/touchcloud"), help="the touchcloud CLI")
    ap.add_argument("--page", default=str(SOURCE / "docs/first-run.md"), help="the guide page that holds the table")
    mode = ap.add_mutually_exclusive_group()
    mode.add_argument("--write", action="store_true", help="rewrite the page's table")
    mode.add_argument("--check", action="store_true", help="exit 1 when the page's table differs")
    args = ap.parse_args()
    text = table(args.cli)
    if not (args.write or args.check):
        sys.stdout.write(text)
        return
    page = pathlib.Path(args.page)
    old = page.read_text()
    new = with_table(old, text)
    if args.check:
        if new != old:
            sys.exit(f"metric_table: {page}'s metric table differs from the declarations; "
                     "run scripts/metric_table.py --write")
        return
    page.write_text(new)


if __name__ == "__main__":
    main()
