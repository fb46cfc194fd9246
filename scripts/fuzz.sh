#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan) into build-fuzz/ and runs
# each for SECONDS (default 600: the documented 10 minutes) from its seed
# corpus in fuzz/corpus/<target>/. New inputs go to build-fuzz/corpus/; a
# crash is saved as build-fuzz/crashes/<target>-crash-* and fails the script
# (turn it into a regression test that reads that input).
#   scripts/fuzz.sh [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-600}
build=${TOUCHCLOUD_FUZZ_BUILD_DIR:-build-fuzz}
scripts/install-deps.sh --fuzz
targets=(fuzz_pipeline fuzz_scene fuzz_pcd fuzz_ply_cloud fuzz_ply_mesh fuzz_stl fuzz_obj fuzz_png)
# TOUCHCLOUD_FUZZ_SKIP="a b": targets not run (e.g. one with an open find).
for skip in ${TOUCHCLOUD_FUZZ_SKIP:-}; do
  targets=("${targets[@]/$skip}")
done
targets=(${targets[@]})
if [ ! -f "$build/build.ninja" ]; then
  cmake -S . -B "$build" -G Ninja -DTOUCHCLOUD_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ >/dev/null
fi
cmake --build "$build" --target fuzz_all -j "$(nproc)"
mkdir -p "$build/crashes"
# Debian's PCL and VTK are not built with ASan: their leaks are not ours.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=0}
failed=()
for t in "${targets[@]}"; do
  mkdir -p "$build/corpus/$t"
  echo "== $t: ${seconds} s" >&2
  # -timeout: an input that takes 10 s is a hang; -rss_limit_mb: so is one
  # that takes 2 GB.
  # -seed: the same inputs in the same order on every run (TOUCHCLOUD_FUZZ_SEED
  # to explore others), so a short CI run does not fail by chance.
  if ! "$build/fuzz/$t" "$build/corpus/$t" "fuzz/corpus/$t" -max_total_time="$seconds" -timeout=10 \
      -seed="${TOUCHCLOUD_FUZZ_SEED:-1}" \
      -rss_limit_mb=2048 -max_len=65536 -artifact_prefix="$build/crashes/$t-" -print_final_stats=1 \
      2>"$build/$t.log"; then
    failed+=("$t")
    tail -n 40 "$build/$t.log" >&2
  fi
  grep -E "^stat::number_of_executed_units" "$build/$t.log" >&2 || true
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz.sh: crashes in: ${failed[*]} (inputs in $build/crashes/)" >&2
  exit 1
fi
echo "fuzz.sh: ${#targets[@]} targets ran ${seconds} s each without a crash" >&2
