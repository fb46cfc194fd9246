#!/usr/bin/python3
"""The peer of bench_dense_stereo's Match and OpenCvCalls: the same OpenCV
calls stereo_disparity makes (both views' maps, the right one on the
mirrored pair, then to px), from OpenCV's Python binding (python3-opencv),
on the same rendered pairs, one OpenCV thread.

  stereo_opencv.py DATA_DIR [--repeats N] [--min-seconds S] [--json]

DATA_DIR holds pair_<size>_{left,right}.png (bench_dense_stereo --write-data).
Each figure is the fastest of N runs of the mean time per frame, as Google
Benchmark's repetitions of ours: wall time, and this process's CPU time
(which other jobs on the machine disturb less).
"""
import argparse
import json
import os
import sys
import time

SIZES = {0: (48, 48), 1: (272, 160)}  # min disparity, number of disparities, as bench_dense_stereo


def matcher(cv2, method, size):
    lo, n = SIZES[size]
    if method == "bm":
        bm = cv2.StereoBM_create(n, 7)
        bm.setMinDisparity(lo)
        bm.setUniquenessRatio(10)
        bm.setDisp12MaxDiff(-1)
        bm.setSpeckleWindowSize(0)
        return bm
    return cv2.StereoSGBM_create(lo, n, 7, 8 * 3 * 49, 32 * 3 * 49, -1, 0, 10, 0, 0, cv2.STEREO_SGBM_MODE_SGBM)


def frame(cv2, np, m, method, left, right):
    if method == "bm":
        left = cv2.cvtColor(left, cv2.COLOR_BGR2GRAY)
        right = cv2.cvtColor(right, cv2.COLOR_BGR2GRAY)
    raw = m.compute(left, right)
    mirrored = cv2.flip(m.compute(cv2.flip(right, 1), cv2.flip(left, 1)), 1)
    return raw.astype(np.float32) / 16, mirrored.astype(np.float32) / 16


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("data")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--min-seconds", type=float, default=1.0)
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args()
    try:
        import cv2
        import numpy as np
    except ImportError as e:
        print(json.dumps({"skipped": f"{e} (Debian: apt-get install python3-opencv)"}))
        return
    cv2.setNumThreads(1)
    out = {"opencv": cv2.__version__, "numpy": np.__version__, "python": sys.version.split()[0],
           "opencv_threads": cv2.getNumThreads(), "ms_per_frame": {}, "cpu_ms_per_frame": {}}
    for size in (0, 1):
        left = cv2.imread(os.path.join(args.data, f"pair_{size}_left.png"), cv2.IMREAD_COLOR)
        right = cv2.imread(os.path.join(args.data, f"pair_{size}_right.png"), cv2.IMREAD_COLOR)
        for method in ("sgbm", "bm"):
            m = matcher(cv2, method, size)
            frame(cv2, np, m, method, left, right)  # warm up
            best, best_cpu = float("inf"), float("inf")
            for _ in range(args.repeats):
                start, cpu_start, n = time.perf_counter(), time.process_time(), 0
                while True:
                    frame(cv2, np, m, method, left, right)
                    n += 1
                    elapsed = time.perf_counter() - start
                    if elapsed >= args.min_seconds:
                        break
                best = min(best, elapsed / n)
                best_cpu = min(best_cpu, (time.process_time() - cpu_start) / n)
            out["ms_per_frame"][f"{method}/{size}"] = best * 1e3
            out["cpu_ms_per_frame"][f"{method}/{size}"] = best_cpu * 1e3
    print(json.dumps(out))


if __name__ == "__main__":
    main()
