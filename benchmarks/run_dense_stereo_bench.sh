#!/bin/sh
# The colour-pattern GelStereo's per-frame stages against the same OpenCV
# calls from OpenCV's Python binding, in one run, both on one core
# (taskset -c 0, one OpenCV thread each side); disparity_to_cloud also on
# two threads:
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
$pin "$bench" --benchmark_filter='Match|OpenCvCalls|DenseFrame' --benchmark_repetitions="$repeats" \
  --benchmark_min_time=1 --benchmark_format=json >"$data/ours.json"
# The conversion may use every core (its threads parameter): not pinned.
"$bench" --benchmark_filter=CloudRefraction --benchmark_repetitions="$repeats" --benchmark_min_time=1 \
  --benchmark_format=json >"$data/cloud.json"
$pin "$python" "$here/peers/stereo_opencv.py" "$data" --repeats "$repeats" --json >"$data/peer.json"

"$python" - "$data" "$repeats" <<'PY'
import json, sys
data, repeats = sys.argv[1], sys.argv[2]
ours = {}
for b in json.load(open(f"{data}/ours.json"))["benchmarks"] + json.load(open(f"{data}/cloud.json"))["benchmarks"]:
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
cpu = lambda name: ours[name]["cpu_time"]
print("Wall time (ms per frame), and in brackets CPU time, which other jobs on the machine disturb less:")
print("| matcher | size | stage, no LR check | stage, LR check | same calls, C++ | same calls, Python | stage / Python |")
print("|---|---|---|---|---|---|---|")
for method in ("sgbm", "bm"):
    for size in (0, 1):
        key = f"{method}/{size}"
        stage, checked, calls = f"Match/{key}/0", f"Match/{key}/1", f"OpenCvCalls/{key}"
        py, py_cpu = peer.get("ms_per_frame", {}).get(key), peer.get("cpu_ms_per_frame", {}).get(key)
        cells = [f"{ms(n):.2f} ({cpu(n):.2f})" for n in (stage, checked, calls)]
        if py:
            cells += [f"{py:.2f} ({py_cpu:.2f})", f"{ms(stage) / py:.3f} ({cpu(stage) / py_cpu:.3f})"]
        else:
            cells += ["-", "-"]
        print(f"| {method.upper()} block 7 | {sizes[size]} | " + " | ".join(cells) + " |")
for size, threads in ((0, 1), (1, 1), (1, 2)):
    b = ours[f"CloudRefraction/{size}/{threads}"]
    print(f"disparity_to_cloud through the plate, {sizes[size]}, contact region ({b['points']:.0f} points), "
          f"{b['threads']:.0f} threads: {b['real_time']:.2f} ms ({b['cpu_time']:.2f} ms CPU of this thread)")
b = ours["DenseFrame256"]
print(f"dense frame at 256 x 256 (contact_mask + SGBM with LR check + cloud through the plate, {b['points']:.0f} "
      f"points): {b['real_time']:.2f} ms = {1e3 / b['real_time']:.0f} frames/s")
PY
