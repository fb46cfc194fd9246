#!/usr/bin/env bash
# Fails when a file of a library beside the runtime (gp, simulation, imaging,
# calibration) includes the pipeline runtime's stage, parameter, port,
# run-context or plugin header: each is usable without pipelines, and its
# plugins adapt it.
# Usage: no_pipeline_runtime.sh LIBRARY_DIR...
set -euo pipefail
[ $# -gt 0 ] || { echo "usage: no_pipeline_runtime.sh LIBRARY_DIR..." >&2; exit 2; }
status=0
for lib in "$@"; do
  [ -d "$lib/include/touchcloud" ] && [ -d "$lib/src" ] || { echo "no library under '$lib'" >&2; exit 1; }
  if grep -rnE '#include *[<"]touchcloud/(ports|stage|parameters|run_context|plugin)\.hpp[>"]' "$lib"; then
    echo "$lib includes the pipeline runtime (above)" >&2
    status=1
  else
    echo "$lib: no pipeline runtime header included"
  fi
done
exit $status
