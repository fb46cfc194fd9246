#!/bin/sh
# GP model selection, ours against scikit-learn's GaussianProcessRegressor,
# on the same 2,000 fox-mask points in one run; and our per-touch cost.
#
#   benchmarks/run_gp_bench.sh [BUILD_DIR]
#
# BUILD_DIR (default: build) must hold benchmarks/bin/bench_gp (configure with
# -DTOUCHCLOUD_BUILD_BENCHMARKS=ON, then `ninja bench_gp`). The peer runs
# under Debian's /usr/bin/python3 with python3-sklearn (PEER_PYTHON overrides
# it); without scikit-learn it is skipped and only our figures are printed.
# Both log marginal likelihoods are also evaluated with our formula
# (bench_gp --lml-at) on the same data, so they compare like for like.
set -eu
build=${1:-build}
here=$(cd "$(dirname "$0")" && pwd)
bench="$build/benchmarks/bin/bench_gp"
python=${PEER_PYTHON:-/usr/bin/python3}
[ -x "$bench" ] || { echo "run_gp_bench: $bench not found; build the bench_gp target" >&2; exit 2; }
[ -x "$python" ] || { echo "run_gp_bench: $python not found (Debian: apt-get install python3)" >&2; exit 2; }

cores=$(nproc)
# Both sides use every core through OpenBLAS (ours: the dense factor algebra;
# scikit-learn: NumPy/SciPy's Cholesky and solves).
export OMP_NUM_THREADS="$cores" OPENBLAS_NUM_THREADS="$cores"
if ! dpkg -s libopenblas0-pthread >/dev/null 2>&1; then
  echo "note: libopenblas0-pthread is not installed (apt-get install libopenblas0-pthread);" \
       "NumPy and SciPy run on the default BLAS, which may be far slower" >&2
fi

data=$(mktemp -d)
trap 'rm -rf "$data"' EXIT
"$bench" --write-data "$data"
"$bench" --data-dir "$data" --benchmark_format=json >"$data/ours.json"
"$python" "$here/peers/gp_sklearn.py" "$data" --json >"$data/peer.json"
if "$python" -c 'import json, sys; sys.exit(0 if "skipped" in json.load(open(sys.argv[1])) else 1)' "$data/peer.json"; then
  : >"$data/peer_lml.json"
else
  h=$("$python" -c 'import json, sys; h = json.load(open(sys.argv[1]))["hyperparameters"]; print("%.17g,%.17g,%.17g" % (h["signal_variance_mm2"], h["lengthscale_mm"], h["noise_variance_mm2"]))' "$data/peer.json")
  "$bench" --data-dir "$data" --lml-at "$h" >"$data/peer_lml.json"
fi

"$python" - "$data" "$cores" <<'PY'
import json, sys
data, cores = sys.argv[1], sys.argv[2]
ours = json.load(open(f"{data}/ours.json"))
bench = {b["run_name"].split("/iterations")[0].replace("/real_time", ""): b for b in ours["benchmarks"]}
ctx = ours["context"]
print(f"GP surface at n = 2,000 fox-mask points, {cores} cores; ours: {ctx.get('gp_linear_algebra', '?')}")
for arg, what in (("0", "variance solved afresh"), ("1", "V = L^-1 K(X, C) cached and extended")):
    b = bench[f"BM_TouchUpdateAndChoice/{arg}"]
    print(f"  per touch (add 60 points + next-touch choice, {what}): {b['real_time']:.1f} ms wall, "
          f"{b['cpu_time']:.1f} ms CPU of the calling thread")
sel = bench["BM_ModelSelection/0"]
warm = bench["BM_ModelSelection/1"]
print(f"  model selection, 3 starts: {sel['real_time'] / 1e3:.2f} s (LML {sel['lml']:.3f}); "
      f"warm-started, 1 start: {warm['real_time'] / 1e3:.2f} s (LML {warm['lml']:.3f})")
print(f"    ours: s2 = {sel['signal_variance_mm2']:.5g} mm^2, l = {sel['lengthscale_mm']:.5g} mm, "
      f"noise = {sel['noise_variance_mm2']:.5g} mm^2")
peer = json.load(open(f"{data}/peer.json"))
if "skipped" in peer:
    print("peer skipped: " + peer["skipped"])
    sys.exit(0)
peer_lml = json.load(open(f"{data}/peer_lml.json"))
h = peer["hyperparameters"]
print(f"peer: scikit-learn {peer['sklearn']} (NumPy {peer['numpy']}, {peer['python']}), {peer['restarts']} restarts; "
      f"BLAS loaded: {', '.join(peer['blas_loaded']) or 'none'}; threads {peer['thread_env']}")
print(f"    sklearn: s2 = {h['signal_variance_mm2']:.5g} mm^2, l = {h['lengthscale_mm']:.5g} mm, "
      f"noise = {h['noise_variance_mm2']:.5g} mm^2")
print(f"  selection time: ours {sel['real_time'] / 1e3:.2f} s, scikit-learn {peer['min_s']:.2f} s: "
      f"scikit-learn / ours = {peer['min_s'] * 1e3 / sel['real_time']:.1f}x")
print(f"  LML by our formula: ours {sel['lml']:.4f}, scikit-learn's optimum {peer_lml['lml']:.4f} "
      f"(scikit-learn's own value there: {peer['lml_sklearn']:.4f}); ours - theirs = {sel['lml'] - peer_lml['lml']:+.4f}")
PY
