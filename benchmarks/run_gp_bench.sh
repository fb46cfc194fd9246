#!/bin/sh
# GP model selection, ours against scikit-learn's GaussianProcessRegressor,
# on the same 2,000 fox-mask points in one run; and our per-touch cost with
# one and with every BLAS thread.
#
#   benchmarks/run_gp_bench.sh [BUILD_DIR]
#
# BUILD_DIR (default: build) must hold benchmarks/bin/bench_gp (configure with
# -DTOUCHCLOUD_BUILD_BENCHMARKS=ON, then `ninja bench_gp`). The peer runs
# under Debian's /usr/bin/python3 with python3-sklearn (PEER_PYTHON overrides
# it); without scikit-learn it is skipped and only our figures are printed.
# REPEATS (default 3) runs of each selection, both sides; the fastest counts.
# Both optima's log marginal likelihoods are evaluated with our formula
# (bench_gp --lml-at) on the same data, so they compare like for like.
set -eu
build=${1:-build}
here=$(cd "$(dirname "$0")" && pwd)
bench="$build/benchmarks/bin/bench_gp"
python=${PEER_PYTHON:-/usr/bin/python3}
repeats=${REPEATS:-3}
[ -x "$bench" ] || { echo "run_gp_bench: $bench not found; build the bench_gp target" >&2; exit 2; }
[ -x "$python" ] || { echo "run_gp_bench: $python not found (Debian: apt-get install python3)" >&2; exit 2; }

cores=$(nproc)
# The selections use every core on both sides through OpenBLAS (ours: the
# dense factor algebra; scikit-learn: NumPy/SciPy's Cholesky and solves).
export OMP_NUM_THREADS="$cores" OPENBLAS_NUM_THREADS="$cores"
# Both sides on the OpenBLAS kernels the CLI chooses for this CPU (bench_gp
# would choose them for itself; NumPy would not).
coretype=$("$bench" --openblas-coretype)
if [ -z "${OPENBLAS_CORETYPE:-}" ] && [ -n "$coretype" ]; then
  export OPENBLAS_CORETYPE="$coretype"
fi
if ! dpkg -s libopenblas0-pthread >/dev/null 2>&1; then
  echo "note: libopenblas0-pthread is not installed (apt-get install libopenblas0-pthread);" \
       "NumPy and SciPy run on the default BLAS, which may be far slower" >&2
fi

data=$(mktemp -d)
trap 'rm -rf "$data"' EXIT
"$bench" --write-data "$data"
OPENBLAS_NUM_THREADS=1 "$bench" --benchmark_filter=TouchUpdate --benchmark_repetitions="$repeats" \
  --benchmark_format=json >"$data/touch_1.json"
"$bench" --benchmark_filter=TouchUpdate --benchmark_repetitions="$repeats" --benchmark_format=json >"$data/touch_all.json"
"$bench" --data-dir "$data" --benchmark_filter=ModelSelection --benchmark_repetitions="$repeats" \
  --benchmark_format=json >"$data/ours.json"
"$python" "$here/peers/gp_sklearn.py" "$data" --repeats "$repeats" --json >"$data/peer.json"

# Our optimum (from scikit-learn's start) and scikit-learn's, by our formula.
lml_at() {
  "$python" -c 'import json, sys; h = json.load(open(sys.argv[1]))
print("%.17g,%.17g,%.17g" % (h["signal_variance_mm2"], h["lengthscale_mm"], h["noise_variance_mm2"]))' "$1"
}
"$python" - "$data" <<'PY'
import json, sys
data = sys.argv[1]
runs = [b for b in json.load(open(f"{data}/ours.json"))["benchmarks"]
        if b.get("run_type") == "iteration" and b["run_name"].startswith("BM_ModelSelection/0")]
best = min(runs, key=lambda b: b["real_time"])
json.dump({k: best[k] for k in ("signal_variance_mm2", "lengthscale_mm", "noise_variance_mm2")},
          open(f"{data}/ours_h.json", "w"))
PY
"$bench" --data-dir "$data" --lml-at "$(lml_at "$data/ours_h.json")" >"$data/ours_lml.json"
if "$python" -c 'import json, sys; sys.exit(0 if "skipped" in json.load(open(sys.argv[1])) else 1)' "$data/peer.json"; then
  : >"$data/peer_lml.json"
else
  "$python" -c 'import json, sys; json.dump(json.load(open(sys.argv[1]))["hyperparameters"], open(sys.argv[2], "w"))' \
    "$data/peer.json" "$data/peer_h.json"
  "$bench" --data-dir "$data" --lml-at "$(lml_at "$data/peer_h.json")" >"$data/peer_lml.json"
fi

"$python" - "$data" "$cores" "$repeats" <<'PY'
import json, sys
data, cores, repeats = sys.argv[1], sys.argv[2], sys.argv[3]

def fastest(path):
    doc = json.load(open(path))
    out = {}
    for b in doc["benchmarks"]:
        if b.get("run_type") != "iteration":
            continue
        name = b["run_name"].split("/iterations")[0].replace("/real_time", "")
        if name not in out or b["real_time"] < out[name]["real_time"]:
            out[name] = b
    return doc["context"], out

ctx, ours = fastest(f"{data}/ours.json")
_, touch_1 = fastest(f"{data}/touch_1.json")
_, touch_all = fastest(f"{data}/touch_all.json")
print(f"GP surface at n = 2,000 fox-mask points, {cores} cores, fastest of {repeats} runs; "
      f"ours: {ctx.get('gp_linear_algebra', '?')}; exp: {ctx.get('gp_vector_exp', '?')}")
for arg, what in (("0", "variance solved afresh"), ("1", "V = L^-1 K(X, C) cached and extended"),
                  ("2", "as above, then the mean on the 200 x 200 grid")):
    one, every = touch_1[f"BM_TouchUpdateAndChoice/{arg}"], touch_all[f"BM_TouchUpdateAndChoice/{arg}"]
    print(f"  per touch (add 60 points + next-touch choice, {what}): {one['real_time']:.1f} ms with 1 BLAS thread, "
          f"{every['real_time']:.1f} ms with {cores}")
rows = (("0", "from scikit-learn's start (1 start)"), ("1", "3 default starts"),
        ("2", "warm-started from the optimum and curvature on 90 % of the points (as between touches)"))
for arg, what in rows:
    b = ours[f"BM_ModelSelection/{arg}"]
    print(f"  model selection, {what}: {b['real_time'] / 1e3:.2f} s, LML {b['lml']:.4f}, "
          f"{b['full_data_gradients']:.0f} gradients and {b['full_data_evaluations'] - b['full_data_gradients']:.0f} "
          f"values on all points, {b['refinement_evaluations']:.0f} on 1,000, {b['subset_evaluations']:.0f} on 500")
sel = ours["BM_ModelSelection/0"]
print(f"    ours: s2 = {sel['signal_variance_mm2']:.6g} mm^2, l = {sel['lengthscale_mm']:.6g} mm, "
      f"noise = {sel['noise_variance_mm2']:.6g} mm^2")
peer = json.load(open(f"{data}/peer.json"))
if "skipped" in peer:
    print("peer skipped: " + peer["skipped"])
    sys.exit(0)
ours_lml = json.load(open(f"{data}/ours_lml.json"))
peer_lml = json.load(open(f"{data}/peer_lml.json"))
h = peer["hyperparameters"]
print(f"peer: scikit-learn {peer['sklearn']} (NumPy {peer['numpy']}, {peer['python']}), {peer['restarts']} restarts; "
      f"BLAS loaded: {', '.join(peer['blas_loaded']) or 'none'}; threads {peer['thread_env']}")
print(f"    sklearn: s2 = {h['signal_variance_mm2']:.6g} mm^2, l = {h['lengthscale_mm']:.6g} mm, "
      f"noise = {h['noise_variance_mm2']:.6g} mm^2; runs {', '.join(f'{t:.2f}' for t in peer['times_s'])} s")
print(f"  selection time, same start: ours {sel['real_time'] / 1e3:.2f} s, scikit-learn {peer['min_s']:.2f} s: "
      f"scikit-learn / ours = {peer['min_s'] * 1e3 / sel['real_time']:.1f}x")
print(f"  LML by our formula: ours {ours_lml['lml']:.8f}, scikit-learn's optimum {peer_lml['lml']:.8f} "
      f"(scikit-learn's own value there: {peer['lml_sklearn']:.8f}); ours - theirs = {ours_lml['lml'] - peer_lml['lml']:+.3e}")
PY
