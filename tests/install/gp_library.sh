#!/usr/bin/env bash
# Installs the toolkit into a temporary prefix and builds a program against
# its gp library with find_package(touchcloud) and touchcloud::gp
# (tests/install/gp_consumer), then runs it: the headers, the library and
# the package's target are all installed.
# Usage: gp_library.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src=$1 build=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
cmake -S "$src/tests/install/gp_consumer" -B "$work/consumer" -G Ninja \
      -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release > "$work/configure.log"
cmake --build "$work/consumer" > "$work/build.log"
out=$("$work/consumer/fit_touches")
# Three touches of 9 points: selections at 9, 18 (>= 13.5) and 27 (>= 27)
# points; a plane's mean between its touches is the plane (6.1 mm at x = 11).
case "$out" in
  "selections 3 mean 6.100") echo "gp library: installed, built against and run ($out)" ;;
  *) echo "fit_touches printed '$out', expected 'selections 3 mean 6.100'" >&2; exit 1 ;;
esac
