#!/usr/bin/env bash
# Quick start 2: builds if needed and runs every test.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
build=${TOUCHCLOUD_BUILD_DIR:-build}
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" "$@"
