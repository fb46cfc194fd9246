#!/usr/bin/env bash
# None of the libraries or programs given (libtouchcloud_sensing, a program
# built on it alone, the other libraries beside the runtime) needs the
# pipeline runtime at load: no libtouchcloud_core (or plugin kit) among the
# libraries their dynamic sections name.
# Usage: no_runtime.sh LIBRARY_OR_PROGRAM...
set -euo pipefail
status=0
for file in "$@"; do
  needed=$(readelf -d "$file" | sed -n 's/.*(NEEDED).*\[\(.*\)\]$/\1/p')
  if [ -z "$needed" ]; then
    echo "$file: readelf found no NEEDED entries; nothing was checked" >&2; exit 1
  fi
  runtime=$(printf '%s\n' "$needed" | grep -E '^libtouchcloud_(core|plugin_kit)\.' || true)
  if [ -n "$runtime" ]; then
    echo "$file needs the pipeline runtime: $runtime" >&2; status=1
  fi
done
[ "$status" -eq 0 ] && echo "no runtime needed by: $*"
exit $status
