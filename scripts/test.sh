#!/usr/bin/env bash
# Quick start 2: builds if needed and runs every test (the GP's tests twice:
# as built, and as test_gp_fallback without OpenBLAS and SLEEF).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
build=${TOUCHCLOUD_BUILD_DIR:-build}
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" "$@"
