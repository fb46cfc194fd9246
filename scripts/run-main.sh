#!/usr/bin/env bash
# Quick start 1: builds if needed and runs the main job.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
build/bin/touchcloud run pipelines/fox_mask_active.yaml --seed 1 --out out/main "$@"
