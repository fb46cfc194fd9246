#!/usr/bin/env bash
# docs.commands fails on guide blocks that drifted from the code: a pipeline
# block with a parameter its plugin lacks, a command run with an unknown
# --set key, a validated command with an option its verb lacks, an untagged
# block of output, a test named by `elsewhere` that does not exist, a
# validated command reading a file that no earlier command of its block
# would write; and passes the same page mended.
# Usage: commands_catch_drift.sh PYTHON SOURCE_DIR BUILD_DIR CTEST
set -euo pipefail
python=$1 src=$2 build=$3 ctest=$4
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
check() { "$python" "$src/scripts/docs_commands.py" --cli "$build/bin/touchcloud" --build "$build" --ctest "$ctest" "$@"; }

cat > "$work/broken.md" <<'MD'
# A page

```yaml
pipeline: demo
stages:
  - id: read
    plugin: cloud_reader
    params: {path: ../sample_clouds/gel_dome.pcd, colour: red}
```

```sh
touchcloud run pipelines/downsample_cloud.yaml --out out/demo --set thin.leaf_mm=2
```

<!-- docs-test: validate -->
```sh
touchcloud run pipelines/fox_mask_active.yaml --seed 1 --out out/fox --fast
```

```
touchcloud: error: 1 problem found; nothing was written
```

<!-- docs-test: elsewhere install.no_such_test -->
```sh
cmake --install build --prefix /opt/touchcloud
```

<!-- docs-test: validate -->
```sh
touchcloud run pipelines/downsample_cloud.yaml --out out/made
touchcloud run pipelines/downsample_cloud.yaml --set read.path=out/gone/gel_dome_thinned.ply
```
MD
set +e
check "$work/broken.md" > "$work/broken.log" 2>&1
status=$?
set -e
cat "$work/broken.log"
[ "$status" -eq 1 ] || { echo "docs_commands.py exited $status on the broken page, expected 1" >&2; exit 1; }
for expect in "broken.md:3: error: \[validate\]" "colour" \
              "broken.md:11: error: \[run\]" "leaf_mm" \
              "broken.md:16: error: \[validate\]" "--fast" \
              "broken.md:20: error: \[untagged\]" "broken.md:25: error: \[elsewhere\]" \
              "broken.md:30: error: \[validate\]" "out/gone" "6 blocks, 6 failed"; do
  grep -q -e "$expect" "$work/broken.log" || { echo "expected '$expect' in the report above" >&2; exit 1; }
done

sed -e 's/, colour: red//' -e 's/thin.leaf_mm/thin.leaf_size_mm/' -e 's/ --fast//' \
    -e 's/^```$/```text/' -e 's/install.no_such_test/install.deb/' -e 's|out/gone/|out/made/|' "$work/broken.md" > "$work/mended.md"
# Only opening fences take the tag; closing ones stay bare.
"$python" - "$work/mended.md" <<'PY'
import re, sys
lines, inside = open(sys.argv[1]).read().split("\n"), False
for i, l in enumerate(lines):
    if l.startswith("```"):
        if inside:
            lines[i] = "```"
        inside = not inside
open(sys.argv[1], "w").write("\n".join(lines))
PY
check "$work/mended.md"
echo "docs.commands: each drifted block reported; the mended page passes"
