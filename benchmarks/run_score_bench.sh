#!/bin/sh
# Scoring speed, ours against SciPy's cKDTree, on the same data in one run:
# 40,000 estimated points against 1,000,000 ground-truth points, near the
# surface and 10 mm above it.
#
#   benchmarks/run_score_bench.sh [BUILD_DIR] [ROUNDS]
#
# BUILD_DIR (default: build) must hold benchmarks/bin/bench_score (configure
# with -DTOUCHCLOUD_BUILD_BENCHMARKS=ON, then `ninja bench_score`). The peer
# runs under Debian's /usr/bin/python3 with python3-scipy (PEER_PYTHON
# overrides it); without SciPy it is skipped and only our times are printed.
set -eu
build=${1:-build}
rounds=${2:-5}
here=$(cd "$(dirname "$0")" && pwd)
bench="$build/benchmarks/bin/bench_score"
python=${PEER_PYTHON:-/usr/bin/python3}
[ -x "$bench" ] || { echo "run_score_bench: $bench not found; build the bench_score target" >&2; exit 2; }
[ -x "$python" ] || { echo "run_score_bench: $python not found (Debian: apt-get install python3)" >&2; exit 2; }

cores=$(nproc)
# Both sides use every core: ours its default (all hardware threads), SciPy
# workers=-1. BLAS does not take part in cKDTree, but it is pinned and
# reported as the project's peers do.
export OMP_NUM_THREADS="$cores" OPENBLAS_NUM_THREADS="$cores"
if ! dpkg -s libopenblas0-pthread >/dev/null 2>&1; then
  echo "note: libopenblas0-pthread is not installed (apt-get install libopenblas0-pthread); NumPy runs on" \
       "the default BLAS, which cKDTree does not use" >&2
fi

data=$(mktemp -d)
trap 'rm -rf "$data"' EXIT
"$bench" --write-data "$data" >/dev/null
# Rounds alternate ours and the peer, so that both meet the same load on a
# shared machine; each side's best round is compared.
i=1
while [ "$i" -le "$rounds" ]; do
  "$bench" --data-dir "$data" --benchmark_filter='BM_ChamferEstToGt|BM_ChamferEstToGtFar|BM_AllMetrics' \
    --benchmark_format=json >"$data/ours_$i.json"
  "$python" "$here/peers/score_scipy.py" "$data" --repeats 1 --json >"$data/peer_$i.json"
  i=$((i + 1))
done

"$python" - "$data" "$rounds" "$cores" <<'PY'
import json, sys
data, rounds, cores = sys.argv[1], int(sys.argv[2]), sys.argv[3]
ours, peer = {}, {}
for r in range(1, rounds + 1):
    for b in json.load(open(f"{data}/ours_{r}.json"))["benchmarks"]:
        name = b["run_name"].split("/")[0]  # names end in /real_time
        ours[name] = min(ours.get(name, float("inf")), b["real_time"])  # ms per build + query
        points = (int(b["gt_points"]), int(b["est_points"]), int(b["threads"]))
    p = json.load(open(f"{data}/peer_{r}.json"))
    if "skipped" in p:
        peer = p
        continue
    info = p
    for case, res in p["results"].items():
        for variant, v in res["variants"].items():
            if v["min_ms"] < peer.get(case, (float("inf"),))[0]:
                peer[case] = (v["min_ms"], variant)
print(f"scoring {points[1]} estimated points against {points[0]} ground-truth points, {cores} cores; "
      f"best of {rounds} alternating rounds, build + query")
print(f"ours: touchcloud NearestPointIndex (box tree over point clusters), {points[2]} threads")
if "skipped" in peer:
    print("peer skipped: " + peer["skipped"])
    for name, ms in ours.items():
        print(f"  {name:24s} ours {ms:9.1f} ms")
    sys.exit(0)
print(f"peer: SciPy {info['scipy']} cKDTree (NumPy {info['numpy']}, {info['python']}), workers=-1 "
      f"({info['cpu_count']} cores); BLAS loaded: {', '.join(info['blas_loaded']) or 'none'}")
print(f"{'':26s}{'ours ms':>10s}{'SciPy ms':>10s}{'SciPy/ours':>12s}  SciPy's faster build")
for case, bench in (("chamfer_est_to_gt", "BM_ChamferEstToGt"), ("chamfer_est_to_gt_far", "BM_ChamferEstToGtFar"),
                    ("all_metrics", "BM_AllMetrics")):
    o = ours[bench]
    p_ms, variant = peer[case]
    print(f"  {case:24s}{o:10.1f}{p_ms:10.1f}{p_ms / o:11.2f}x  {variant}")
PY
