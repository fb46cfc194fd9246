#!/usr/bin/python3
"""Speed of each sensor family's live chain at 320 x 240 px (DIGIT's and
GelSight Mini's size) on one core, through `touchcloud stream`, beside the
same chain written with OpenCV's Python binding (opencv_chains.py) in the
same run.

The simulator presses the fox mask with each family's sensor
(simulate_*.yaml); its frames, the gel at rest first, then press and release
repeated, become videos at 60 frames/s written by OpenCV, uncompressed as a
camera delivers them (--codec ffv1: lossless FFV1, costly to decode). Each
chain (chain_*.yaml and its peer) runs on core 0 (taskset -c 0) twice:
  rate:    the video as fast as it decodes (queue policy block), frames/s
  latency: the video at its 60 frames/s (realtime, drop_oldest as a camera),
           p50/p95/p99 from capture to the chain's end, frames dropped
Both sides capture on a thread into a queue of 4 frames. Fastest of
--repeats for the rate, lowest p99 for the latency. The clouds of both sides
are compared frame by frame: points, mean depth in the sensor frame, and
each point where both sides give the same pixels.

Writes results.md, results.csv and stages.csv into --out.

Usage (from the repository root, after building the CLI, the plugins and
the Python module; Debian's python3 with python3-opencv):
  benchmarks/live_chains/make_live_chains.py --out benchmarks/live_chains [--frames 600] [--repeats 3]
"""
import argparse
import csv
import json
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time

import cv2
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
import opencv_chains  # noqa: E402

GOAL_FPS, GOAL_P99_MS = 120.0, 1000.0 / 60
FPS = 60
PIN = ["taskset", "-c", "0"] if shutil.which("taskset") else []

CHAINS = {
    "gelsight": {
        "title": "GelSight-type: photometric depth to cloud",
        "videos": ["gelsight.avi"], "sources": ["cam.video"], "cloud": "cloud.cloud", "grey": False,
        "peer": lambda: opencv_chains.gelsight_chain(
            os.path.join(ROOT, "sample_clouds/gelsight_ball/photometric_calibration.yaml")),
        "reference_processed": False, "same_pixels": True,
    },
    "colour": {
        "title": "colour-pattern GelStereo: SGBM to cloud",
        "videos": ["colour_left.avi", "colour_right.avi"], "sources": ["cam.left_video", "cam.right_video"],
        "cloud": "cloud.cloud", "grey": False,
        "peer": lambda: opencv_chains.colour_chain(os.path.join(HERE, "scene_colour.yaml"), threshold_grey=20,
                                                   block=7, min_disparity=48, num_disparities=96),
        "reference_processed": False, "same_pixels": True,
    },
    "colour_fast": {
        "title": "colour-pattern GelStereo, fast: one-pass SGBM of the contact to cloud",
        "videos": ["colour_left.avi", "colour_right.avi"], "sources": ["cam.left_video", "cam.right_video"],
        "cloud": "cloud.cloud", "grey": False,
        "peer": lambda: opencv_chains.colour_chain(os.path.join(HERE, "scene_colour.yaml"), threshold_grey=20,
                                                   block=7, min_disparity=64, num_disparities=48, contact_margin=8),
        "reference_processed": False, "same_pixels": True, "against": "colour",
    },
    "markers": {
        "title": "marker GelStereo: markers, matching and tracking to cloud",
        "videos": ["markers_left.avi", "markers_right.avi"], "sources": ["cam.left_video", "cam.right_video"],
        "cloud": "rsrt.tactile", "grey": True,
        "peer": lambda: opencv_chains.marker_chain(os.path.join(HERE, "scene_markers.yaml"), diameter_px=(3, 8),
                                                   disparity_px=(40, 160)),
        "reference_processed": True, "same_pixels": False,
    },
}


def load():
    return os.getloadavg()[0]


def cli():
    return os.path.join(ROOT, "build", "bin", "touchcloud")


def touchcloud_module():
    sys.path.insert(0, os.path.join(ROOT, "build", "python"))
    import touchcloud
    return touchcloud


def press_cycle(frames, count, press_frames):
    """The gel at rest, then the press's last `press_frames` frames down and up again, to `count` frames."""
    press = frames[max(1, len(frames) - press_frames):]
    loop = press + press[-2:0:-1]
    return [frames[0]] + [loop[k % len(loop)] for k in range(count - 1)]


# How the videos hold their frames: uncompressed (as a camera delivers them
# in a raw pixel format; grey for the marker sensor's grey cameras, BGR for
# the colour ones), or FFV1, lossless but costly to decode (about 3 ms a
# 320 x 240 frame on one core, twice per stereo pair).
CODECS = {"raw": {"grey": ("GREY", False), "colour": ("RGBA", True)},
          "ffv1": {"grey": ("FFV1", True), "colour": ("FFV1", True)}}


def write_video(path, frames, codec):
    h, w = frames[0].shape[:2]
    fourcc, colour = CODECS[codec]["grey" if frames[0].ndim == 2 else "colour"]
    writer = cv2.VideoWriter(path, cv2.CAP_FFMPEG, cv2.VideoWriter_fourcc(*fourcc), FPS, (w, h), colour)
    if not writer.isOpened():
        raise SystemExit(f"make_live_chains: this OpenCV cannot write {fourcc} to {path}")
    for f in frames:
        writer.write(f if (f.ndim == 3) == colour else cv2.cvtColor(f, cv2.COLOR_GRAY2BGR))
    writer.release()


def make_videos(tc, folder, count, press_frames, simulated_frames, codec):
    """Each family's simulated press (its first `simulated_frames` frames when
    given) as videos of `count` frames."""
    sims = {"gelsight": "sim.image", "colour": "sim.colour_frame", "markers": "sim.frame"}
    limit = {"touch.max_iterations": str(simulated_frames)} if simulated_frames else {}
    for family, port in sims.items():
        r = tc.run(os.path.join(HERE, f"simulate_{family}.yaml"), set=limit, outputs=[port], every_iteration=True)
        shots = r.outputs[port]
        if family == "gelsight":
            write_video(os.path.join(folder, "gelsight.avi"), press_cycle([s["image"] for s in shots], count, press_frames),
                        codec)
        else:
            for side in ("left", "right"):
                write_video(os.path.join(folder, f"{family}_{side}.avi"),
                            press_cycle([s[side] for s in shots], count, press_frames), codec)


def stream_touchcloud(name, videos, out, realtime):
    chain = CHAINS[name]
    cmd = PIN + [cli(), "stream", os.path.join(HERE, f"chain_{name}.yaml"), "--quiet", "--out", out]
    for source, video in zip(chain["sources"], videos):
        cmd += ["--set", f"{source}={video}"]
    if realtime:
        cmd += ["--set", "cam.realtime=true", "--set", "cam.when_behind=drop_oldest"]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    m = lambda k: s["metrics"][f"cam.{k}"]["value"]
    stages = {st["id"]: st["latency_ms"] for st in s["stages"] if "latency_ms" in st}
    return {"frames": m("frames_processed"), "rate_fps": m("rate_fps"), "p50_ms": m("latency_p50_ms"),
            "p95_ms": m("latency_p95_ms"), "p99_ms": m("latency_p99_ms"), "dropped": m("frames_dropped"),
            "stages": stages}


PEER_SCRIPT = """
import json, sys
sys.path.insert(0, {here!r})
import cv2, make_live_chains as m, opencv_chains
cv2.setNumThreads(1)
c = m.CHAINS[{name!r}]
r = opencv_chains.stream(c["peer"](), {videos!r}, grey=c["grey"], reference_processed=c["reference_processed"],
                         drop_oldest={realtime!r}, realtime={realtime!r})
r.pop("clouds")
print(json.dumps(r))
"""


def stream_peer(name, videos, realtime):
    """The peer in its own process on core 0, as touchcloud stream."""
    script = PEER_SCRIPT.format(here=HERE, name=name, videos=videos, realtime=realtime)
    out = subprocess.run(PIN + [sys.executable, "-c", script], check=True, capture_output=True, text=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def compare_clouds(tc, name, videos):
    """Both sides' clouds of every frame, over the frames with at least 20 points
    on both sides: the largest difference in points (share of touchcloud's),
    in the mean z (depth into the gel, sensor frame, mm), and, where both give
    the same pixels, in any point (mm)."""
    chain = CHAINS[name]
    sets = {source: video for source, video in zip(chain["sources"], videos)}
    r = tc.run(os.path.join(HERE, f"chain_{name}.yaml"), set=sets, outputs=[chain["cloud"]], every_iteration=True)
    ours = [c["points"] if isinstance(c, dict) else c for c in r.outputs[chain["cloud"]]]
    cv2.setNumThreads(1)
    theirs = opencv_chains.stream(chain["peer"](), videos, grey=chain["grey"],
                                  reference_processed=chain["reference_processed"], keep_clouds=True)["clouds"]
    if len(ours) != len(theirs):
        raise SystemExit(f"make_live_chains: {name}: touchcloud gave {len(ours)} clouds, the peer {len(theirs)}")
    counts, depths, points, compared = 0.0, 0.0, None, 0
    for a, b in zip(ours, theirs):
        if len(a) < 20 or len(b) < 20:
            continue
        compared += 1
        counts = max(counts, abs(len(a) - len(b)) / len(a))
        depths = max(depths, abs(float(a[:, 2].mean()) - float(b[:, 2].mean())))
        if chain["same_pixels"] and a.shape == b.shape:
            points = max(points or 0.0, float(np.abs(a - b).max()))
    return {"frames_compared": compared, "points_ours": float(np.mean([len(a) for a in ours])),
            "points_peer": float(np.mean([len(b) for b in theirs])), "max_points_difference": counts,
            "max_mean_z_difference_mm": depths, "max_point_difference_mm": points}


def clouds_of(tc, name, videos):
    chain = CHAINS[name]
    sets = {source: video for source, video in zip(chain["sources"], videos)}
    r = tc.run(os.path.join(HERE, f"chain_{name}.yaml"), set=sets, outputs=[chain["cloud"]], every_iteration=True)
    return [c["points"] if isinstance(c, dict) else c for c in r.outputs[chain["cloud"]]]


def accuracy_cost(tc, name, videos):
    """A chain set for speed against the chain it stands for, on the same
    frames with at least 20 points on both: points per frame, the mean over
    frames of each point's distance to the nearest point of the other chain's
    cloud (mm), and the largest difference in mean depth (z, mm)."""
    fast, full = clouds_of(tc, name, videos), clouds_of(tc, CHAINS[name]["against"], videos)
    nearest, depths, compared = [], 0.0, 0
    for a, b in zip(fast, full):
        if len(a) < 20 or len(b) < 20:
            continue
        compared += 1
        d = np.sqrt(((a[:, None, :].astype(np.float64) - b[None, :, :]) ** 2).sum(axis=2)).min(axis=1)
        nearest.append(float(d.mean()))
        depths = max(depths, abs(float(a[:, 2].mean()) - float(b[:, 2].mean())))
    return {"chain": name, "against": CHAINS[name]["against"], "frames_compared": compared,
            "points": float(np.mean([len(a) for a in fast])), "points_against": float(np.mean([len(b) for b in full])),
            "mean_nearest_mm": float(np.mean(nearest)) if nearest else float("nan"), "max_mean_z_difference_mm": depths}


def machine():
    model = "unknown CPU"
    flags = ""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name") and model == "unknown CPU":
                    model = line.split(":", 1)[1].strip()
                if line.startswith("flags") and not flags:
                    flags = line
    except OSError:
        pass
    simd = "AVX-512" if "avx512f" in flags else "AVX2" if "avx2" in flags else "no AVX2"
    return f"{model}, {os.cpu_count()} cores, {simd}, {platform.system()} {platform.release()}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", required=True)
    parser.add_argument("--frames", type=int, default=600, help="frames per video (60 frames/s)")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--press-frames", type=int, default=16, help="frames of each press kept from the simulation")
    parser.add_argument("--codec", choices=sorted(CODECS), default="raw",
                        help="the videos uncompressed (raw, as a camera delivers) or FFV1 (lossless, costly to decode)")
    parser.add_argument("--simulated-frames", type=int, help="simulate only this many frames of each press (a quick check)")
    args = parser.parse_args()
    tc = touchcloud_module()
    os.makedirs(args.out, exist_ok=True)
    rows, stage_rows, costs = [], [], []
    with tempfile.TemporaryDirectory() as scratch:
        make_videos(tc, scratch, args.frames, args.press_frames, args.simulated_frames, args.codec)
        for name, chain in CHAINS.items():
            videos = [os.path.join(scratch, v) for v in chain["videos"]]
            same = compare_clouds(tc, name, videos)
            if "against" in chain:
                costs.append(accuracy_cost(tc, name, videos))
            best = {"ours_rate": None, "ours_latency": None, "peer_rate": None, "peer_latency": None}
            loads = []
            for k in range(args.repeats):
                loads.append(load())
                rate = stream_touchcloud(name, videos, os.path.join(scratch, f"{name}_rate_{k}"), False)
                latency = stream_touchcloud(name, videos, os.path.join(scratch, f"{name}_latency_{k}"), True)
                peer_rate = stream_peer(name, videos, False)
                peer_latency = stream_peer(name, videos, True)
                loads.append(load())
                for key, r, better in (("ours_rate", rate, lambda a, b: a["rate_fps"] > b["rate_fps"]),
                                       ("peer_rate", peer_rate, lambda a, b: a["rate_fps"] > b["rate_fps"]),
                                       ("ours_latency", latency, lambda a, b: a["p99_ms"] < b["p99_ms"]),
                                       ("peer_latency", peer_latency, lambda a, b: a["p99_ms"] < b["p99_ms"])):
                    if best[key] is None or better(r, best[key]):
                        best[key] = r
                print(name, k, f"ours {rate['rate_fps']:.1f} fps p99 {latency['p99_ms']:.2f} ms; "
                      f"peer {peer_rate['rate_fps']:.1f} fps p99 {peer_latency['p99_ms']:.2f} ms; "
                      f"load {loads[-1]:.2f}", flush=True)
            o, ol, p, pl = best["ours_rate"], best["ours_latency"], best["peer_rate"], best["peer_latency"]
            rows.append({
                "chain": name, "description": chain["title"], "frames": int(o["frames"]),
                "touchcloud_fps": o["rate_fps"], "touchcloud_p50_ms": ol["p50_ms"], "touchcloud_p95_ms": ol["p95_ms"],
                "touchcloud_p99_ms": ol["p99_ms"], "touchcloud_dropped_at_60fps": int(ol["dropped"]),
                "opencv_python_fps": p["rate_fps"], "opencv_python_p99_ms": pl["p99_ms"],
                "opencv_python_dropped_at_60fps": int(pl["dropped"]),
                "fps_ratio": o["rate_fps"] / p["rate_fps"],
                "goal_met": o["rate_fps"] >= GOAL_FPS and ol["p99_ms"] < GOAL_P99_MS,
                "load_min": min(loads), "load_max": max(loads),
                "points_touchcloud": same["points_ours"], "points_opencv_python": same["points_peer"],
                "max_points_difference": same["max_points_difference"],
                "max_mean_z_difference_mm": same["max_mean_z_difference_mm"],
                "max_point_difference_mm": same["max_point_difference_mm"], "frames_compared": same["frames_compared"],
            })
            for stage, lat in o["stages"].items():
                stage_rows.append({"chain": name, "stage": stage, "p50_ms": lat["p50"], "p95_ms": lat["p95"],
                                   "p99_ms": lat["p99"]})
    write_tables(args, rows, stage_rows, costs)


def write_tables(args, rows, stage_rows, costs):
    with open(os.path.join(args.out, "results.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.4g}" if isinstance(v, float) else v) for k, v in r.items()})
    with open(os.path.join(args.out, "stages.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["chain", "stage", "p50_ms", "p95_ms", "p99_ms"])
        w.writeheader()
        for r in stage_rows:
            w.writerow({k: (f"{v:.4g}" if isinstance(v, float) else v) for k, v in r.items()})
    loads = [r["load_min"] for r in rows] + [r["load_max"] for r in rows]
    with open(os.path.join(args.out, "results.md"), "w") as f:
        f.write("# Live chains at 320 x 240 px on one core\n\n"
                f"Made by `benchmarks/live_chains/make_live_chains.py --out benchmarks/live_chains --frames {args.frames} "
                f"--repeats {args.repeats}{'' if args.codec == 'raw' else ' --codec ' + args.codec}` on {machine()}; every run pinned to core 0 (`taskset -c 0`), "
                f"OpenCV {cv2.__version__}, NumPy {np.__version__}, Python {platform.python_version()}. "
                f"Load average (1 min) from {min(loads):.2f} to {max(loads):.2f} while it ran.\n\n"
                f"Each video: {args.frames} frames at {FPS} frames/s, "
                f"{'uncompressed (grey for the marker cameras, BGR for the others)' if args.codec == 'raw' else 'FFV1 (lossless)'}"
                " written by OpenCV from the "
                "simulator's press of the fox mask (the gel at rest, then press and release repeated). "
                "Rate: the video as fast as it decodes; latency: the video at its 60 frames/s as a camera "
                "delivers it (drop_oldest), from capture to the chain's end. Fastest of "
                f"{args.repeats} runs for the rate, lowest p99 for the latency. "
                f"Goal: at least {GOAL_FPS:.0f} frames/s and p99 under {GOAL_P99_MS:.1f} ms (one frame at 60 frames/s).\n\n"
                "| chain | touchcloud frames/s | p50 ms | p95 ms | p99 ms | dropped at 60 fps | OpenCV-Python "
                "frames/s | its p99 ms | its dropped | touchcloud / Python | goal met |\n"
                "|---|---|---|---|---|---|---|---|---|---|---|\n")
        for r in rows:
            f.write(f"| {r['description']} | {r['touchcloud_fps']:.1f} | {r['touchcloud_p50_ms']:.2f} | "
                    f"{r['touchcloud_p95_ms']:.2f} | {r['touchcloud_p99_ms']:.2f} | {r['touchcloud_dropped_at_60fps']} | "
                    f"{r['opencv_python_fps']:.1f} | {r['opencv_python_p99_ms']:.2f} | "
                    f"{r['opencv_python_dropped_at_60fps']} | {r['fps_ratio']:.2f} | "
                    f"{'yes' if r['goal_met'] else 'no'} |\n")
        f.write("\nThe two sides' clouds, frame by frame (frames with at least 20 points on both sides): mean points "
                "per frame, the largest difference in points, in the mean depth (z in the sensor frame) and, where "
                "both sides give the same pixels, in any point.\n\n| chain | points, touchcloud | points, "
                "OpenCV-Python | largest points difference | largest mean depth difference (mm) | largest point "
                "difference (mm) | frames compared |\n|---|---|---|---|---|---|---|\n")
        for r in rows:
            f.write(f"| {r['chain']} | {r['points_touchcloud']:.0f} | {r['points_opencv_python']:.0f} | "
                    f"{100 * r['max_points_difference']:.1f} % | {r['max_mean_z_difference_mm']:.4f} | "
                    f"{'-' if r['max_point_difference_mm'] is None else format(r['max_point_difference_mm'], '.2g')} | "
                    f"{r['frames_compared']} |\n")
        f.write("\nWhat a chain set for speed costs in accuracy: its clouds against those of the chain it stands "
                "for, frame by frame on the same frames (those with at least 20 points on both): mean points per "
                "frame, the mean over frames of each point's distance to the nearest point of the other cloud, and "
                "the largest difference in mean depth (z in the sensor frame).\n\n| chain | against | points | "
                "points, against | mean distance to the nearest point (mm) | largest mean depth difference (mm) | "
                "frames compared |\n|---|---|---|---|---|---|---|\n")
        for c in costs:
            f.write(f"| {c['chain']} | {c['against']} | {c['points']:.0f} | {c['points_against']:.0f} | "
                    f"{c['mean_nearest_mm']:.4f} | {c['max_mean_z_difference_mm']:.4f} | {c['frames_compared']} |\n")
        f.write("\nWhere touchcloud's time goes (its rate runs' per-stage latency, ms; `cam` is the source's call, "
                "taking the frame from the queue):\n\n| chain | stage | p50 | p95 | p99 |\n|---|---|---|---|---|\n")
        for r in stage_rows:
            f.write(f"| {r['chain']} | {r['stage']} | {r['p50_ms']:.2f} | {r['p95_ms']:.2f} | {r['p99_ms']:.2f} |\n")


if __name__ == "__main__":
    main()
