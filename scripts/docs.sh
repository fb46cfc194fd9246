#!/usr/bin/env bash
# Builds the user guide into build/docs/ (open build/docs/index.html) with
# `mkdocs build --strict`: a warning or a broken internal link fails it, and
# so does a plugin without a page or an example (scripts/plugin_pages.py).
# Needs Debian's mkdocs and doxygen (scripts/install-deps.sh installs them)
# and the built CLI, whose plugins' declarations make the plugin pages. The
# C++ API for plugin authors (Doxyfile) goes into the guide's api/ folder; a
# Doxygen warning fails the build as a MkDocs one does.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${TOUCHCLOUD_BUILD_DIR:-build}
command -v mkdocs >/dev/null || { echo "docs.sh: mkdocs not found; apt-get install mkdocs (scripts/install-deps.sh)" >&2; exit 2; }
command -v doxygen >/dev/null || { echo "docs.sh: doxygen not found; apt-get install doxygen (scripts/install-deps.sh)" >&2; exit 2; }
src=$build/docs-src
mkdir -p "$src"
scripts/plugin_pages.py --cli "$build/bin/touchcloud" --out "$src/plugin_pages" --nav "$src/plugin_nav.yaml"
config=$(scripts/docs_site.py --out "$src/site" --site "$build/docs" --plugin-pages "$src/plugin_pages" \
         --extra-nav "$src/plugin_nav.yaml")
mkdir -p "$src/site/docs/api"
TOUCHCLOUD_API_DOCS="$src/site/docs/api" doxygen Doxyfile
mkdocs build --strict --quiet -f "$config"
echo "docs.sh: the guide is in $build/docs/index.html"
