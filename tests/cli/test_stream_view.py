"""touchcloud stream --view: the live view served on 127.0.0.1 while a video
file streams (delivered at its frame rate, as a camera would), read over
HTTP and watched in a real browser (headless Chromium over the DevTools
protocol on a pipe; skipped, saying so, where Chromium is absent): the frame
counter advances, the cloud changes between two presses, no JavaScript
error. A port in use is bad input."""
import fcntl
import json
import os
import pathlib
import select
import shutil
import signal
import socket
import subprocess
import threading
import time
import urllib.request

import cv2
import numpy as np
import pytest

SOURCE = pathlib.Path(os.environ.get("TOUCHCLOUD_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
CLI = pathlib.Path(os.environ.get("TOUCHCLOUD_CLI", SOURCE / "build/bin/touchcloud"))
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
FPS = 2
REPEATS = 4  # frames of each press


def press_video(folder, repeats):
    """The GelSight-type sample presses as an FFV1 video at 2 frames/s: the
    gel at rest, then each press for `repeats` frames."""
    root = SOURCE / "sample_clouds/gelsight_presses"
    lines = (root / "index.csv").read_text().splitlines()[1:]
    frames = [cv2.imread(str(root / line.split(",")[2])) for line in lines]
    sequence = [frames[0]] + [f for f in frames[1:] for _ in range(repeats)]
    video = folder / "presses.mkv"
    h, w = frames[0].shape[:2]
    writer = cv2.VideoWriter(str(video), cv2.VideoWriter_fourcc(*"FFV1"), FPS, (w, h))
    for f in sequence:
        writer.write(f)
    writer.release()
    return video, len(sequence)


@pytest.fixture(scope="module")
def presses(tmp_path_factory):
    """Each press for four frames (21 frames, 10.5 s)."""
    return press_video(tmp_path_factory.mktemp("video"), REPEATS)


@pytest.fixture(scope="module")
def long_presses(tmp_path_factory):
    """Each press for ten frames (51 frames, 25.5 s): a browser that takes
    ten seconds or more to start on 2 shared cores still watches several
    presses."""
    return press_video(tmp_path_factory.mktemp("long_video"), 10)


class Stream:
    """`touchcloud stream --view` on the video, delivered at its pace, until stop()."""

    def __init__(self, video, out, port="0"):
        self.process = subprocess.Popen(
            [str(CLI), "stream", "pipelines/stream_gelsight.yaml", "--view", "--port", str(port), "-q",
             "--set", "cam.frames=~", "--set", f"cam.video={video}", "--set", "cam.realtime=true", "--out", str(out)],
            cwd=SOURCE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        line = self._line(20)
        assert line.startswith("live view: http://127.0.0.1:"), line + self.process.stderr.read()
        self.url = line.split(": ", 1)[1].strip()

    def _line(self, timeout_s):
        ready, _, _ = select.select([self.process.stdout], [], [], timeout_s)
        return self.process.stdout.readline() if ready else "(nothing printed in time)"

    def get(self, path):
        with urllib.request.urlopen(self.url + path, timeout=10) as r:
            return r.read()

    def state(self):
        return json.loads(self.get("state.json"))

    def wait_for_end(self, timeout_s=60):
        deadline = time.monotonic() + timeout_s
        while not self.state()["ended"]:
            assert time.monotonic() < deadline, "the stream did not end"
            time.sleep(0.1)

    def stop(self):
        """SIGTERM, as Ctrl-C: the view closes and the run ends with status 0."""
        self.process.send_signal(signal.SIGTERM)
        out, err = self.process.communicate(timeout=30)
        return self.process.returncode, out, err


def test_the_view_serves_each_frames_pictures_cloud_and_figures(presses, tmp_path):
    video, frames = presses
    stream = Stream(video, tmp_path / "out")
    try:
        seen = set()
        first = stream.state()
        while not (state := stream.state())["ended"]:
            seen.add(state["frame"])
            time.sleep(0.05)
        assert len(seen) >= 5, seen  # the counter advanced as frames came, at 2 frames/s
        assert first["frame"] < frames - 1
        assert state["frame"] == frames - 1  # the first frame is the reference
        assert state["dropped"] == 0 and state["latency_ms"] > 0 and 1 < state["rate_fps"] < 4, state
        assert state["shown"] == {"camera": "cam.frame", "depth": "depth.height", "mask": "depth.height",
                                  "cloud": "cloud.cloud"}
        pictures = {}
        for name in ("camera", "depth", "mask"):
            assert state["sizes"][name] == [320, 240], name
            pictures[name] = np.frombuffer(stream.get(name + ".rgba"), np.uint8).reshape(240, 320, 4)
        # The camera's frame as the video holds it (BGR there, RGBA here); the last press's contact in the mask.
        last = cv2.imread(str(SOURCE / "sample_clouds/gelsight_presses" /
                              (SOURCE / "sample_clouds/gelsight_presses/index.csv").read_text().splitlines()[-1].split(",")[2]))
        assert np.array_equal(pictures["camera"][..., :3], last[..., ::-1])
        assert 0 < (pictures["mask"][..., 0] == 255).mean() < 0.5
        assert len(np.unique(pictures["depth"].reshape(-1, 4), axis=0)) > 20
        cloud = np.frombuffer(stream.get("cloud.bin"), np.float32).reshape(-1, 3)
        assert len(cloud) == state["points"] == 4800
        page = stream.get("").decode()
        assert "three.min.js" in page and "live.js" in page
    finally:
        status, out, err = stream.stop()
    assert status == 0, err
    assert f"streamed {frames - 1} frames" in out
    assert (tmp_path / "out" / "summary.json").exists()


def test_a_port_in_use_is_bad_input_and_nothing_runs(presses, tmp_path):
    video, _ = presses
    taken = socket.socket()
    taken.bind(("127.0.0.1", 0))
    taken.listen()
    port = taken.getsockname()[1]
    r = subprocess.run([str(CLI), "stream", "pipelines/stream_gelsight.yaml", "--view", "--port", str(port),
                        "--set", "cam.frames=~", "--set", f"cam.video={video}", "--out", str(tmp_path / "out")],
                       cwd=SOURCE, capture_output=True, text=True, timeout=60)
    taken.close()
    assert r.returncode == 2, r.stderr
    assert r.stderr.startswith("touchcloud: error:")
    assert f"--port {port}: the live view cannot listen on 127.0.0.1:{port}" in r.stderr
    assert not (tmp_path / "out").exists()


class DevTools:
    """Headless Chromium driven over the DevTools protocol on a pipe (JSON
    messages ending in NUL on descriptors 3 and 4), so that no package
    beyond Chromium and Python is needed."""

    def __init__(self):
        to_chrome_r, self._to_chrome = os.pipe()
        self._from_chrome, from_chrome_w = os.pipe()
        # Above 4, so that the shell's redirections to 3 and 4 overwrite neither (bash: dash takes one digit).
        to_chrome_r, from_chrome_w = (self._above_four(fd) for fd in (to_chrome_r, from_chrome_w))
        self.process = subprocess.Popen(
            ["bash", "-c", f'exec "$0" "$@" 3<&{to_chrome_r} 4>&{from_chrome_w}', CHROMIUM, "--headless=new",
             "--no-sandbox", "--disable-gpu", "--enable-unsafe-swiftshader", "--window-size=1600,900",
             "--remote-debugging-pipe", "about:blank"],
            pass_fds=(to_chrome_r, from_chrome_w), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(to_chrome_r)
        os.close(from_chrome_w)
        self._next_id = 0
        self._replies = {}
        self.events = []
        self._changed = threading.Condition()
        threading.Thread(target=self._read, daemon=True).start()

    @staticmethod
    def _above_four(fd):
        high = fcntl.fcntl(fd, fcntl.F_DUPFD, 10)
        os.close(fd)
        return high

    def _read(self):
        buffer = b""
        while chunk := os.read(self._from_chrome, 1 << 16):
            buffer += chunk
            *messages, buffer = buffer.split(b"\0")
            with self._changed:
                for m in messages:
                    message = json.loads(m)
                    if "id" in message:
                        self._replies[message["id"]] = message
                    else:
                        self.events.append(message)
                self._changed.notify_all()

    def send(self, method, session=None, **params):
        self._next_id += 1
        call = {"id": self._next_id, "method": method, "params": params}
        if session:
            call["sessionId"] = session
        os.write(self._to_chrome, json.dumps(call).encode() + b"\0")
        with self._changed:
            assert self._changed.wait_for(lambda: self._next_id in self._replies, timeout=30), method
            reply = self._replies.pop(self._next_id)
        assert "error" not in reply, (method, reply["error"])
        return reply["result"]

    def errors(self):
        """The page's JavaScript exceptions, console errors and failed loads so far."""
        with self._changed:
            found = []
            for e in self.events:
                p = e.get("params", {})
                if e["method"] == "Runtime.exceptionThrown":
                    found.append(p["exceptionDetails"].get("exception", {}).get("description", p["exceptionDetails"]["text"]))
                elif e["method"] == "Runtime.consoleAPICalled" and p["type"] in ("error", "assert"):
                    found.append(" ".join(str(a.get("value", a.get("description"))) for a in p["args"]))
                elif e["method"] == "Log.entryAdded" and p["entry"]["level"] == "error":
                    found.append(p["entry"]["text"])
            return found

    def close(self):
        try:
            self.send("Browser.close")
        except (AssertionError, OSError):
            pass
        try:
            self.process.wait(timeout=20)
        except subprocess.TimeoutExpired:
            self.process.kill()
        os.close(self._to_chrome)


needs_chromium = pytest.mark.skipif(CHROMIUM is None, reason="chromium is not installed (scripts/install-deps.sh "
                                                               "installs it): the live view is not checked in a browser")


@needs_chromium
def test_the_page_updates_in_a_real_browser_as_frames_arrive(long_presses, tmp_path):
    video, frames = long_presses
    browser = DevTools()
    stream = None
    try:
        target = browser.send("Target.createTarget", url="about:blank")["targetId"]
        session = browser.send("Target.attachToTarget", targetId=target, flatten=True)["sessionId"]
        for domain in ("Runtime", "Log", "Page"):
            browser.send(domain + ".enable", session)
        stream = Stream(video, tmp_path / "out")
        browser.send("Page.navigate", session, url=stream.url)
        probe = ("document.getElementById('frame') && JSON.stringify({frame: document.getElementById('frame').textContent,"
                 " cloud: document.getElementById('cloud').dataset,"
                 " camera: document.getElementById('camera').width,"
                 " depth: document.getElementById('depth').width,"
                 " mask: document.getElementById('mask').width,"
                 " status: document.getElementById('status').textContent, errors: window.tcErrors || []})")
        looks = []
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline:
            result = browser.send("Runtime.evaluate", session, expression=probe, returnByValue=True)["result"]
            if result.get("type") != "string":  # the page is still loading
                time.sleep(0.1)
                continue
            look = json.loads(result["value"])
            looks.append(look)
            if "ended" in look["status"] and look["cloud"].get("frame") == str(frames - 1):
                break
            time.sleep(0.1)
        counters = [int(look["frame"]) for look in looks if look["frame"].isdigit()]
        assert counters and counters[-1] == frames - 1, looks[-1]
        assert len(set(counters)) >= 3, sorted(set(counters))  # it advanced while the page watched
        assert counters == sorted(counters)
        # The cloud drawn changed with the presses: several frames' clouds, of different heights.
        drawn = {(look["cloud"]["frame"], look["cloud"]["zSum"]) for look in looks if look["cloud"].get("frame", "-1") != "-1"}
        assert len({z for _, z in drawn}) >= 2, drawn
        assert all(look["cloud"]["points"] == "4800" for look in looks if look["cloud"].get("frame", "-1") != "-1")
        last = looks[-1]
        assert (last["camera"], last["depth"], last["mask"]) == (320, 320, 320), last
        assert last["errors"] == [] and browser.errors() == [], (last["errors"], browser.errors())
    finally:
        browser.close()
        if stream:
            status, _, err = stream.stop()
            assert status == 0, err
