#!/usr/bin/env bash
# The product speaks to users, not of how it was developed: no numbered
# development stops and no remarks on how loaded a machine was, outside
# CHANGELOG.md, where history lives ("[ ]" keeps this file from matching its
# own pattern).
# Usage: no_lab_notebook.sh SOURCE_DIR
set -euo pipefail
src=${1:?usage: no_lab_notebook.sh SOURCE_DIR}
pattern='stop [0-9]+|idle[ ]machine|busy[ ]machine|this[ ]stop'
cd "$src"
if git rev-parse --is-inside-work-tree >/dev/null 2>&1 && [ "$(git rev-parse --show-toplevel)" = "$(pwd -P)" ]; then
  hits=$(git grep -n -I -iE "$pattern" -- . ':!CHANGELOG.md' || true)
else
  hits=$(grep -rn -I -iE "$pattern" --exclude=CHANGELOG.md \
           --exclude-dir=.git --exclude-dir='build*' --exclude-dir=out . || true)
fi
if [ -n "$hits" ]; then
  printf '%s\n' "$hits"
  echo "docs.no_lab_notebook: $(printf '%s\n' "$hits" | wc -l) line(s) narrate development; say what is, with the command and the machine, and keep history in CHANGELOG.md" >&2
  exit 1
fi
echo "docs.no_lab_notebook: no development narrative outside CHANGELOG.md"
