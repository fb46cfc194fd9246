#!/usr/bin/env bash
# Fails when a file of the gp library includes the pipeline runtime's stage,
# parameter, port, run-context or plugin header (the library is usable
# without pipelines; the gp_surface plugin adapts it).
# Usage: no_pipeline_runtime.sh GP_DIR
set -euo pipefail
gp=$1
[ -d "$gp/include/touchcloud/gp" ] && [ -d "$gp/src" ] || { echo "no gp library under '$gp'" >&2; exit 1; }
if grep -rnE '#include *[<"]touchcloud/(ports|stage|parameters|run_context|plugin)\.hpp[>"]' "$gp/include" "$gp/src"; then
  echo "the gp library includes the pipeline runtime (above)" >&2
  exit 1
fi
echo "gp library: no pipeline runtime header included"
