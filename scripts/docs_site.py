#!/usr/bin/python3
"""Assembles the user guide's sources for MkDocs: the pages under docs/, the
generated plugin pages (plugins/NAME.md, scripts/plugin_pages.py), the
benchmark tables (each benchmarks/NAME/README.md with the tables and figures
beside it, as tables/NAME/), and a MkDocs configuration whose nav lists them.

  scripts/docs_site.py --out DIR --site build/docs [--plugin-pages P --extra-nav NAV]   # writes DIR/mkdocs.yml
"""
import argparse
import pathlib
import shutil
import sys

import yaml

SOURCE = pathlib.Path(__file__).resolve().parents[1]
# Files of a benchmark folder the site shows or links to; the scripts stay in the repository.
TABLE_FILES = {".md", ".png", ".svg", ".csv"}


def copy_tables(out):
    """benchmarks/NAME/ -> tables/NAME/ (README.md becomes its index.md); returns the nav entries."""
    nav = []
    for readme in sorted(SOURCE.glob("benchmarks/*/README.md")):
        folder = readme.parent
        for f in sorted(folder.rglob("*")):
            if f.is_file() and f.suffix in TABLE_FILES:
                rel = f.relative_to(folder)
                dest = out / "tables" / folder.name / ("index.md" if rel == pathlib.Path("README.md") else rel)
                dest.parent.mkdir(parents=True, exist_ok=True)
                shutil.copyfile(f, dest)
        title = readme.read_text().split("\n", 1)[0].lstrip("# ").strip() or folder.name
        nav.append({title: f"tables/{folder.name}/index.md"})
    return nav


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True, help="folder for the assembled sources (emptied first)")
    ap.add_argument("--site", required=True, help="where mkdocs writes the site")
    ap.add_argument("--plugin-pages", help="a folder of generated plugin pages, copied into plugins/")
    ap.add_argument("--extra-nav", help="a YAML file: a list of nav entries for the Plugins section")
    args = ap.parse_args()
    out = pathlib.Path(args.out).resolve()
    if out.exists():
        shutil.rmtree(out)
    shutil.copytree(SOURCE / "docs", out / "docs")
    if args.plugin_pages:
        for page in sorted(pathlib.Path(args.plugin_pages).glob("*.md")):
            dest = out / "docs/plugins" / page.name
            if dest.exists():
                sys.exit(f"docs_site: docs/plugins/{page.name} is generated; remove the committed one")
            shutil.copyfile(page, dest)
    tables = copy_tables(out / "docs")
    config = yaml.safe_load((SOURCE / "mkdocs.yml").read_text())
    config["docs_dir"] = str(out / "docs")
    config["site_dir"] = str(pathlib.Path(args.site).resolve())
    for section in config["nav"]:
        (name, entries), = section.items()
        if name == "Results":
            entries.extend(tables)
        if name == "Plugins" and args.extra_nav:
            entries.extend(yaml.safe_load(pathlib.Path(args.extra_nav).read_text()))
    (out / "mkdocs.yml").write_text(yaml.safe_dump(config, sort_keys=False))
    print(out / "mkdocs.yml")


if __name__ == "__main__":
    sys.exit(main())
