#!/usr/bin/env bash
# Builds the user guide into build/docs/ (open build/docs/index.html) with
# `mkdocs build --strict`: a warning or a broken internal link fails it.
# Needs Debian's mkdocs (scripts/install-deps.sh installs it).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${TOUCHCLOUD_BUILD_DIR:-build}
command -v mkdocs >/dev/null || { echo "docs.sh: mkdocs not found; apt-get install mkdocs (scripts/install-deps.sh)" >&2; exit 2; }
config=$(scripts/docs_site.py --out "$build/docs-src" --site "$build/docs")
mkdocs build --strict --quiet -f "$config"
echo "docs.sh: the guide is in $build/docs/index.html"
