#!/usr/bin/env bash
# The GP's and scoring's tests on the build without OpenBLAS and SLEEF: the
# Eigen paths behind their #ifdefs, which the main build never compiles.
# Builds only those tests, into build-fallback/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
build=${TOUCHCLOUD_FALLBACK_BUILD_DIR:-build-fallback}
if [ ! -f "$build/build.ninja" ]; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTOUCHCLOUD_BUILD_BENCHMARKS=OFF \
    -DTOUCHCLOUD_GP_USE_OPENBLAS=OFF -DTOUCHCLOUD_GP_USE_SLEEF=OFF
fi
cmake --build "$build" -j "$(nproc)" --target test_gp_surface test_scoring
# The suites of those two programs, as ctest names their tests (Suite.Test).
suites=$(for t in test_gp_surface test_scoring; do "$build/tests/bin/$t" --gtest_list_tests | grep -v '^ '; done |
         tr -d '.' | sort -u | paste -sd'|')
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" -R "^($suites)\." "$@"
