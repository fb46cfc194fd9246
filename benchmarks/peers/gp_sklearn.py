#!/usr/bin/python3
"""Peer of bench_gp's BM_ModelSelection: scikit-learn's GaussianProcessRegressor.

    /usr/bin/python3 benchmarks/peers/gp_sklearn.py DATA_DIR [--repeats N] [--restarts R] [--json]

Reads DATA_DIR/points.csv (x_mm, y_mm, z_mm; bench_gp --write-data writes
it), centres z by its mean as touchcloud does (normalize_y=False), and times
GaussianProcessRegressor(kernel=C * RBF + WhiteKernel, optimizer L-BFGS-B).
One start, as scikit-learn runs by default: signal variance var(z),
lengthscale 10 mm, noise var(z) / 100 (touchcloud's starts use the same
variances); bounds are scikit-learn's defaults (noise down to 1e-10 mm^2).
Reports the selected hyperparameters in touchcloud's units (mm^2, mm, mm^2)
and scikit-learn's own log marginal likelihood; run_gp_bench.sh evaluates
both sides' optima with touchcloud's formula as well.
Run it with Debian's /usr/bin/python3 (python3-sklearn); without scikit-learn
it says so and exits 0.
"""
import argparse
import json
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from peer_common import blas_in_use  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("data_dir")
    ap.add_argument("--repeats", type=int, default=1)
    ap.add_argument("--restarts", type=int, default=0, help="n_restarts_optimizer (scikit-learn's default: 0)")
    ap.add_argument("--json", action="store_true", help="one JSON object on stdout")
    args = ap.parse_args()

    try:
        import numpy as np
        import sklearn
        from sklearn.gaussian_process import GaussianProcessRegressor
        from sklearn.gaussian_process.kernels import RBF, ConstantKernel, WhiteKernel
    except ImportError as e:
        reason = (f"scikit-learn not available to {sys.executable} ({e}); "
                  "on Debian: apt-get install python3-sklearn")
        print(json.dumps({"skipped": reason}) if args.json else f"SKIP: {reason}")
        return 0

    data = np.loadtxt(os.path.join(args.data_dir, "points.csv"), delimiter=",", skiprows=1)
    xy, z = data[:, :2], data[:, 2]
    zc = z - z.mean()
    var_z = float(zc.var())
    kernel = (ConstantKernel(var_z, (1e-5, 1e5)) * RBF(10.0, (1e-5, 1e5))
              + WhiteKernel(var_z / 100.0, (1e-10, 1e5)))

    times, gpr = [], None
    for r in range(args.repeats):
        gpr = GaussianProcessRegressor(kernel=kernel, optimizer="fmin_l_bfgs_b", normalize_y=False,
                                       n_restarts_optimizer=args.restarts, random_state=r, alpha=1e-10)
        t0 = time.perf_counter()
        gpr.fit(xy, zc)
        times.append(time.perf_counter() - t0)
    k = gpr.kernel_
    h = {"signal_variance_mm2": float(k.k1.k1.constant_value), "lengthscale_mm": float(k.k1.k2.length_scale),
         # alpha (1e-10) is added to the diagonal like noise; count it as noise.
         "noise_variance_mm2": float(k.k2.noise_level) + 1e-10}
    report = {
        "peer": "sklearn.gaussian_process.GaussianProcessRegressor (C * RBF + WhiteKernel, L-BFGS-B)",
        "python": sys.executable,
        "numpy": np.__version__,
        "sklearn": sklearn.__version__,
        "blas_loaded": blas_in_use(),
        "cpu_count": os.cpu_count(),
        "thread_env": {v: os.environ.get(v) for v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS")},
        "n": int(xy.shape[0]),
        "restarts": args.restarts,
        "min_s": min(times),
        "times_s": times,
        "hyperparameters": h,
        "lml_sklearn": float(gpr.log_marginal_likelihood_value_),
    }
    print(json.dumps(report) if args.json else json.dumps(report, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
