#!/usr/bin/python3
"""One guide page per plugin, from what it declares (`touchcloud plugins NAME
--json`): description, category, parameters with units, defaults and ranges,
ports, metrics, the roles of the files it writes, and an example pipeline.

A plugin's example is docs/examples/NAME.yaml, or else the smallest example
or shipped pipeline (docs/examples/*.yaml, pipelines/*.yaml) with a stage of
that plugin. A plugin without
one fails: every plugin has a page with an example.

  scripts/plugin_pages.py --out DIR --nav NAV.yaml   # DIR/NAME.md for every plugin; NAV.yaml lists them
  scripts/plugin_pages.py --validate                 # touchcloud validate on every example; exit 1 on a failure
"""
import argparse
import json
import pathlib
import re
import subprocess
import sys

import yaml

SOURCE = pathlib.Path(__file__).resolve().parents[1]


def cli_json(cli, *args):
    out = subprocess.run([str(cli), "plugins", *args, "--json"], capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"plugin_pages: touchcloud plugins {' '.join(args)} --json failed: {out.stderr.strip()}")
    return json.loads(out.stdout)


def uses_plugin(path, name):
    return re.search(rf"^\s*plugin:\s*{re.escape(name)}\s*(#.*)?$", path.read_text(), re.M) is not None


def example_for(name):
    """docs/examples/NAME.yaml, else the smallest example or shipped pipeline with a stage of the plugin."""
    own = SOURCE / "docs/examples" / f"{name}.yaml"
    if own.exists():
        if not uses_plugin(own, name):
            sys.exit(f"plugin_pages: {own.relative_to(SOURCE)} is {name}'s example but has no stage of {name}")
        return own
    files = sorted(SOURCE.glob("docs/examples/*.yaml")) + sorted(SOURCE.glob("pipelines/*.yaml"))
    uses = [p for p in files if uses_plugin(p, name)]
    return min(uses, key=lambda p: (p.stat().st_size, p.name)) if uses else None


def cell(value):
    if value is None:
        return "not set"
    text = json.dumps(value) if not isinstance(value, str) else (value if value else '""')
    return "`" + text.replace("|", "\\|") + "`"


def esc(text):
    return str(text).replace("|", "\\|")


def page(info, example):
    name = info["name"]
    lines = [f"# {name}", "", esc(info["description"]), "",
             f"Category: **{info['category']}**. `touchcloud plugins {name}` prints this from the plugin itself.", ""]
    lines += ["## Parameters", ""]
    if info["parameters"]:
        lines += ["| name | type | default | unit | valid | what |", "|---|---|---|---|---|---|"]
        for p in info["parameters"]:
            default = "not set" if p.get("optional") and p.get("default") is None else cell(p.get("default"))
            lines.append(f"| `{p['name']}` | {esc(p['type'])} | {default} | {esc(p['unit']) or '-'} | "
                         f"{esc(p['rule']) or '-'} | {esc(p['doc'])} |")
    else:
        lines.append("None.")
    lines += ["", "## Ports", ""]
    ports = [("input", x) for x in info["inputs"]] + [("output", x) for x in info["outputs"]]
    if ports:
        lines += ["| port | name | type | what |", "|---|---|---|---|"]
        for kind, x in ports:
            note = " (optional)" if x.get("optional") else ""
            if x.get("one_of"):
                note += " (one of " + ", ".join(f"`{o}`" for o in x["one_of"]) + ")"
            lines.append(f"| {kind}{note} | `{x['name']}` | {esc(x['type'])} | {esc(x['doc'])} |")
    else:
        lines.append("None.")
    lines += ["", "## Metrics", ""]
    if info["metrics"]:
        lines += ["| name | unit | reported | better | role | what |", "|---|---|---|---|---|---|"]
        for m in info["metrics"]:
            when = "per item" if m["when"] == "per_item" else "once, at the end"
            better = {"lower_is_better": "lower", "higher_is_better": "higher"}.get(m["direction"], "-")
            lines.append(f"| `{m['name']}` | {esc(m['unit']) or '-'} | {when} | {better} | "
                         f"{m.get('role', '-')} | {esc(m['doc'])} |")
    else:
        lines.append("None.")
    if info["artifacts"]:
        lines += ["", "## Files it writes", "", "| role | what |", "|---|---|"]
        lines += [f"| {a['role']} | {esc(a['doc'])} |" for a in info["artifacts"]]
    rel = example.relative_to(SOURCE)
    lines += ["", "## Example", "",
              f"`{rel}` (a test validates it: ctest's `docs.plugin_examples`):", "",
              "```sh", f"touchcloud validate {rel}", f"touchcloud run {rel} --seed 1 --out out/{name}", "```", "",
              "```yaml", example.read_text().rstrip(), "```", ""]
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cli", default=str(SOURCE / "build/bin/touchcloud"), help="the touchcloud CLI")
    ap.add_argument("--out", help="folder for the pages")
    ap.add_argument("--nav", help="write the pages' nav entries (YAML) here")
    ap.add_argument("--validate", action="store_true", help="validate every plugin's example")
    args = ap.parse_args()
    names = [p["name"] for p in cli_json(args.cli)]
    examples = {n: example_for(n) for n in names}
    missing = [n for n, e in examples.items() if e is None]
    if missing:
        sys.exit("plugin_pages: no example pipeline for " + ", ".join(missing) +
                 " (add docs/examples/NAME.yaml, or a shipped pipeline that uses it)")
    if args.validate:
        failed = []
        for n, e in examples.items():
            r = subprocess.run([str(args.cli), "validate", str(e)], capture_output=True, text=True)
            print(f"{n}: {e.relative_to(SOURCE)}: {'ok' if r.returncode == 0 else 'FAILED'}")
            if r.returncode != 0:
                failed.append(n)
                print(r.stderr, file=sys.stderr)
        if failed:
            sys.exit("plugin_pages: examples that do not validate: " + ", ".join(failed))
        return
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    for n in names:
        (out / f"{n}.md").write_text(page(cli_json(args.cli, n), examples[n]))
    if args.nav:
        pathlib.Path(args.nav).write_text(yaml.safe_dump([{n: f"plugins/{n}.md"} for n in names], sort_keys=False))


if __name__ == "__main__":
    main()
