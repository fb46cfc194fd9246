#!/bin/sh
# The colour-pattern GelStereo's per-frame stages against the same OpenCV
# calls from OpenCV's Python binding, in one run, both on one core
# (taskset -c 0, one OpenCV thread each side):
#
#   benchmarks/run_dense_stereo_bench.sh [BUILD_DIR]
#
# BUILD_DIR (default: build) must hold benchmarks/bin/bench_dense_stereo.
# The peer runs under Debian's /usr/bin/python3 with python3-opencv
# (PEER_PYTHON overrides it); without it only our figures are printed.
# REPEATS (default 3) runs of each, both sides; the fastest counts.
set -eu
build=${1:-build}
here=$(cd "$(dirname "$0")" && pwd)
bench="$build/benchmarks/bin/bench_dense_stereo"
python=${PEER_PYTHON:-/usr/bin/python3}
repeats=${REPEATS:-3}
[ -x "$bench" ] || { echo "run_dense_stereo_bench: $bench not found; build the bench_dense_stereo target" >&2; exit 2; }
pin="taskset -c 0"
command -v taskset >/dev/null 2>&1 || pin=""

data=$(mktemp -d)
trap 'rm -rf "$data"' EXIT
"$bench" --write-data "$data"
$pin "$bench" --benchmark_repetitions="$repeats" --benchmark_min_time=1 --benchmark_format=json >"$data/ours.json"
$pin "$python" "$here/peers/stereo_opencv.py" "$data" --repeats "$repeats" --json >"$data/peer.json"

"$python" - "$data" "$repeats" <<'PY'
import json, sys
data, repeats = sys.argv[1], sys.argv[2]
doc = json.load(open(f"{data}/ours.json"))
ours = {}
for b in doc["benchmarks"]:
    if b.get("run_type") != "iteration":
        continue
    if b["run_name"] not in ours or b["real_time"] < ours[b["run_name"]]["real_time"]:
        ours[b["run_name"]] = b
ms = lambda name: ours[name]["real_time"]  # the benchmarks report ms
peer = json.load(open(f"{data}/peer.json"))
sizes = {0: "256 x 256", 1: "1280 x 720"}
print(f"Dense stereo on one core, fastest of {repeats} runs (ms per frame; pentagon press, noise and blur on)")
if "skipped" in peer:
    print("peer skipped: " + peer["skipped"])
else:
    print(f"peer: OpenCV {peer['opencv']} Python binding (NumPy {peer['numpy']}, Python {peer['python']}), "
          f"{peer['opencv_threads']} OpenCV thread")
print("| matcher | size | stage, no LR check | stage, LR check | same calls, C++ | same calls, Python | stage / Python |")
print("|---|---|---|---|---|---|---|")
for method in ("sgbm", "bm"):
    for size in (0, 1):
        stage, checked = ms(f"Match/{method}/{size}/0"), ms(f"Match/{method}/{size}/1")
        calls = ms(f"OpenCvCalls/{method}/{size}")
        py = peer.get("ms_per_frame", {}).get(f"{method}/{size}")
        ratio = f"{stage / py:.3f}" if py else "-"
        print(f"| {method.upper()} block 7 | {sizes[size]} | {stage:.2f} | {checked:.2f} | {calls:.2f} | "
              f"{py:.2f} | {ratio} |" if py else f"| {method} | {sizes[size]} | {stage:.2f} | {checked:.2f} | {calls:.2f} | - | - |")
for size in (0, 1):
    b = ours[f"CloudRefraction/{size}"]
    print(f"disparity_to_cloud through the plate, {sizes[size]}, contact region ({b['points']:.0f} points): "
          f"{b['real_time']:.2f} ms")
b = ours["DenseFrame256"]
print(f"dense frame at 256 x 256 (contact_mask + SGBM with LR check + cloud through the plate, {b['points']:.0f} "
      f"points): {b['real_time']:.2f} ms = {1e3 / b['real_time']:.0f} frames/s")
PY
