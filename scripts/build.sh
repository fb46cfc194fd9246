#!/usr/bin/env bash
# Configures (once) and builds touchcloud into build/. Extra arguments go to
# the first cmake configure, e.g. -DTOUCHCLOUD_SANITIZE=ON.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
build=${TOUCHCLOUD_BUILD_DIR:-build}
if [ ! -f "$build/build.ninja" ]; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "$@"
fi
cmake --build "$build" -j "$(nproc)"
