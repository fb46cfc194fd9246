#!/usr/bin/env bash
# Quick start 2: builds if needed and runs every test (the GP's tests twice:
# as built, and as test_gp_fallback without OpenBLAS and SLEEF).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
build=${TOUCHCLOUD_BUILD_DIR:-build}
# One job more than the cores: some tests wait on subprocesses, a browser or
# files (on 2 cores, with ctest's timings of an earlier run, 521 and 543 s in
# two runs with 3 jobs against 555 s with 2: a small gain).
ctest --test-dir "$build" --output-on-failure -j "$(( $(nproc) + 1 ))" "$@"
