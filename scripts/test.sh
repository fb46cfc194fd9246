#!/usr/bin/env bash
# Quick start 2: builds if needed and runs every test.
set -euo pipefail
cd "$(dirname "$0")/.."
# First the GP and scoring tests without OpenBLAS and SLEEF (scripts/test-fallback.sh),
# then every test of the main build.
scripts/test-fallback.sh
scripts/build.sh
build=${TOUCHCLOUD_BUILD_DIR:-build}
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" "$@"
