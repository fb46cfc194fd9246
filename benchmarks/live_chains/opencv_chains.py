"""The three live chains of make_live_chains.py written with OpenCV's Python
binding and NumPy, doing the steps touchcloud's stages do, and the stream
around them as touchcloud stream runs it: a capture thread decoding the
video (cv2.VideoCapture) into a bounded queue, the chain on the main thread,
latency from capture to the chain's end.

  gelsight: colour difference to the reference, the calibration's polynomial
            gradients, Poisson integration by DCT (cv2.dct, the free border
            photometric_depth's `border: free` solves), offset to the flat
            pixels, contact mask, a cloud of every 4th pixel
  colour:   rectification maps from cv2.stereoRectify, the contact mask (max
            channel difference, 5 x 5 box, open and close), cv2.StereoSGBM on
            the pair and the mirrored pair, left-right check, the Eq. 7
            average, reprojection by the Q matrix
  markers:  cv2.SimpleBlobDetector in both views, left-right pairs on the
            rows of the first pair, tracked by the mutual nearest marker
            within 6 px (a cv2.flann k-d tree), cv2.triangulatePoints
"""
import collections
import threading
import time

import cv2
import numpy as np
import yaml


class Feed:
    """A capture thread over cv2.VideoCapture into a bounded queue: `block` holds
    capture back, `drop_oldest` loses the oldest frame (counted); `realtime`
    delivers frame k at k / fps, as a camera, stamped with that time (its
    latency counts from when it was due)."""

    def __init__(self, paths, queue_frames=4, drop_oldest=False, realtime=False, grey=False):
        self.caps = [cv2.VideoCapture(p, cv2.CAP_FFMPEG) for p in paths]
        for p, c in zip(paths, self.caps):
            if not c.isOpened():
                raise RuntimeError(f"cannot open {p}")
        self.fps = self.caps[0].get(cv2.CAP_PROP_FPS)
        self.queue = collections.deque()
        self.capacity, self.drop_oldest, self.realtime, self.grey = queue_frames, drop_oldest, realtime, grey
        self.cond = threading.Condition()
        self.ended = False
        self.dropped = 0
        self.thread = threading.Thread(target=self._capture, daemon=True)
        self.thread.start()

    def _read(self):
        views = []
        for c in self.caps:
            ok, image = c.read()
            if not ok:
                return None
            views.append(cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) if self.grey else image)
        return views

    def _capture(self):
        start, k = time.perf_counter(), 0
        while True:
            views = self._read()
            if views is None:
                break
            captured_at = time.perf_counter()
            if self.realtime:  # captured when due, however late this thread wakes, as touchcloud's feed
                captured_at = start + k / self.fps
                delay = captured_at - time.perf_counter()
                if delay > 0:
                    time.sleep(delay)
            k += 1
            with self.cond:
                if len(self.queue) >= self.capacity:
                    if self.drop_oldest:
                        self.queue.popleft()
                        self.dropped += 1
                    else:
                        self.cond.wait_for(lambda: len(self.queue) < self.capacity)
                self.queue.append((views, captured_at))
                self.cond.notify_all()
        with self.cond:
            self.ended = True
            self.cond.notify_all()

    def next(self):
        with self.cond:
            self.cond.wait_for(lambda: self.queue or self.ended)
            if not self.queue:
                return None
            item = self.queue.popleft()
            self.cond.notify_all()
            return item


def stream(chain, paths, grey=False, reference_processed=False, queue_frames=4, drop_oldest=False, realtime=False,
           keep_clouds=False):
    """Runs `chain` (the first frame's views -> per-frame function of the views
    giving a cloud) over the videos: rate, latency percentiles (nearest rank, as
    touchcloud's), drops, and the clouds when asked. The first frame is the
    reference, processed too when `reference_processed` (as marker_matching
    takes its first frame)."""
    feed = Feed(paths, queue_frames, drop_oldest, realtime, grey)
    first = feed.next()
    process = chain(first[0])
    latencies, clouds, first_at, processed = [], [], None, 0
    while True:
        item = first if reference_processed and processed == 0 and first_at is None else feed.next()
        if item is None:
            break
        views, captured_at = item
        if first_at is None:
            first_at = time.perf_counter()
        cloud = process(views)
        done = time.perf_counter()
        latencies.append((done - captured_at) * 1e3)
        processed += 1
        if keep_clouds:
            clouds.append(cloud)
    span = time.perf_counter() - first_at
    ordered = sorted(latencies)
    rank = lambda q: ordered[max(0, int(np.ceil(q * len(ordered))) - 1)]
    return {"frames": processed, "rate_fps": processed / span, "p50_ms": rank(0.50), "p95_ms": rank(0.95),
            "p99_ms": rank(0.99), "dropped": feed.dropped, "clouds": clouds}


def gelsight_chain(calibration_file, flat_grey=3.0, contact_height_mm=0.05, contact_grey=6.0, stride_px=4):
    c = yaml.safe_load(open(calibration_file))["photometric_calibration"]
    degree, scale, pitch, thickness = c["degree"], c["scale_grey"], c["mm_per_px"], c["gel_thickness_mm"]
    cgx, cgy = np.array(c["gx"]), np.array(c["gy"])
    terms = [(i, j, k) for i in range(degree + 1) for j in range(degree + 1 - i) for k in range(degree + 1 - i - j)]
    w, h = c["image_size_px"]
    # The Laplacian's eigenvalues in the DCT-II basis (no flux through the border).
    eigen = (2 * np.cos(np.pi * np.arange(w) / w) - 2)[None, :] + (2 * np.cos(np.pi * np.arange(h) / h) - 2)[:, None]
    eigen[0, 0] = 1.0
    flat_level = np.floor(flat_grey)
    vs, us = np.mgrid[stride_px // 2:h:stride_px, stride_px // 2:w:stride_px]
    xs, ys = (us - 0.5 * (w - 1)) * pitch, (vs - 0.5 * (h - 1)) * pitch

    def chain(reference_views):
        reference = reference_views[0].astype(np.int16)

        def process(views):
            d = views[0].astype(np.int16) - reference  # B, G, R
            largest = np.abs(d).max(axis=2)
            flat = largest <= flat_level
            # The polynomial only where the colour changed (most of the gel is flat).
            moved = ~flat
            dm = d[moved] / scale
            r, g, b = dm[:, 2], dm[:, 1], dm[:, 0]
            rp, gp, bp = [np.ones_like(r)], [np.ones_like(g)], [np.ones_like(b)]
            for _ in range(degree):
                rp.append(rp[-1] * r), gp.append(gp[-1] * g), bp.append(bp[-1] * b)
            monomials = np.stack([rp[i] * gp[j] * bp[k] for i, j, k in terms], axis=1)
            gx, gy = np.zeros((h, w)), np.zeros((h, w))
            gx[moved] = monomials @ cgx
            gy[moved] = monomials @ cgy
            p = 0.5 * (gx[:, :-1] + gx[:, 1:]) * pitch
            q = 0.5 * (gy[:-1] + gy[1:]) * pitch
            f = np.zeros((h, w))
            f[:, :-1] += p
            f[:, 1:] -= p
            f[:-1] += q
            f[1:] -= q
            spectrum = cv2.dct(f) / eigen
            spectrum[0, 0] = 0
            height = cv2.idct(spectrum)
            height -= height[flat].mean() if flat.any() else height.min()
            height = height.astype(np.float32)
            smoothed = cv2.blur(largest.astype(np.uint8), (5, 5))
            contact = (height > contact_height_mm) & (smoothed > contact_grey)  # noqa: F841 (the stage's mask)
            return np.stack([xs, ys, thickness - height[vs, us]], axis=-1).reshape(-1, 3).astype(np.float32)

        return process

    return chain


def stereo_camera(sensor_file):
    """The left camera's matrix, the image size, the baseline (mm) and the left
    camera's centre in the sensor frame (between the cameras, plate_gap_mm +
    the plate's thickness below the gel's face), of a sensor file whose
    cameras are alike, side by side along x, without lens distortion."""
    s = yaml.safe_load(open(sensor_file))["sensor"]
    cameras, left = s["cameras"], s["cameras"]["left"]
    k = np.array([[left["fx_px"], 0, left["cx_px"]], [0, left["fy_px"], left["cy_px"]], [0, 0, 1]], float)
    baseline = float(cameras["baseline_mm"])
    centre = np.array([-0.5 * baseline, 0.0, -(s["plate"]["thickness_mm"] + cameras["plate_gap_mm"])])
    return k, (left["width_px"], left["height_px"]), baseline, centre


def rectification(sensor_file):
    """The rectified pair's size, the left camera's centre in the sensor frame,
    R1, Q and a function rectifying one view (0 left, 1 right)."""
    k, size, baseline, centre = stereo_camera(sensor_file)
    r1, r2, p1, p2, q, _, _ = cv2.stereoRectify(k, None, k, None, size, np.eye(3), np.array([-baseline, 0.0, 0.0]),
                                                flags=cv2.CALIB_ZERO_DISPARITY, alpha=0, newImageSize=size)
    maps = [cv2.initUndistortRectifyMap(k, None, r, p, size, cv2.CV_32FC1) for r, p in ((r1, p1), (r2, p2))]
    rect = lambda image, side: cv2.remap(image, maps[side][0], maps[side][1], cv2.INTER_LINEAR,
                                         borderMode=cv2.BORDER_CONSTANT)
    return size, centre, r1, q, rect


def colour_chain(sensor_file, threshold_grey, block, min_disparity, num_disparities, uniqueness=10,
                 max_lr_difference=1.0, smoothing_px=5, cleanup_px=5, contact_margin=None):
    """With `contact_margin` (chain_colour_fast.yaml): one SGBM_3WAY pass with
    OpenCV's own left-right check over the contact's bounding box and that
    margin, the cloud from the left disparity."""
    if contact_margin is not None:
        return colour_fast_chain(sensor_file, threshold_grey, block, min_disparity, num_disparities, uniqueness,
                                 max_lr_difference, smoothing_px, cleanup_px, contact_margin)
    size, centre, r1, q, rect = rectification(sensor_file)
    w, h = size
    area = block * block
    sgbm = cv2.StereoSGBM_create(min_disparity, num_disparities, block, 8 * 3 * area, 32 * 3 * area, -1, 0, uniqueness,
                                 0, 0, cv2.STEREO_SGBM_MODE_SGBM)
    square = cv2.getStructuringElement(cv2.MORPH_RECT, (cleanup_px, cleanup_px))
    cols = np.arange(w, dtype=np.float64)[None, :].repeat(h, 0)
    rows = np.arange(h, dtype=np.float64)[:, None].repeat(w, 1)
    row_index = np.arange(h)[:, None].repeat(w, 1)
    left_from_rect = r1.T

    def to_px(raw):
        valid = raw >= min_disparity * 16
        px = raw.astype(np.float32) / 16
        px[~valid] = 0
        return px, valid

    def chain(reference_views):
        reference_left = rect(reference_views[0], 0)

        def process(views):
            left, right = rect(views[0], 0), rect(views[1], 1)
            difference = cv2.absdiff(left, reference_left).max(axis=2)
            difference = cv2.blur(difference, (smoothing_px, smoothing_px))
            mask = ((difference > threshold_grey) * 255).astype(np.uint8)
            mask = cv2.morphologyEx(cv2.morphologyEx(mask, cv2.MORPH_OPEN, square), cv2.MORPH_CLOSE, square) > 0
            dl, vl = to_px(sgbm.compute(left, right))
            dr, vr = to_px(cv2.flip(sgbm.compute(cv2.flip(right, 1), cv2.flip(left, 1)), 1))
            # Left-right check: each map against the other before either is pruned.
            xr = np.rint(cols - dl).astype(np.int64)
            inside = (xr >= 0) & (xr < w)
            xr_c = np.clip(xr, 0, w - 1)
            ok_l = vl & inside & vr[row_index, xr_c] & (np.abs(dr[row_index, xr_c] - dl) <= max_lr_difference)
            xl = np.rint(cols + dr).astype(np.int64)
            inside = (xl >= 0) & (xl < w)
            xl_c = np.clip(xl, 0, w - 1)
            ok_r = vr & inside & vl[row_index, xl_c] & (np.abs(dl[row_index, xl_c] - dr) <= max_lr_difference)
            dl = np.where(ok_l, dl, 0)
            dr = np.where(ok_r, dr, 0)
            # Eq. 7: the mean of the left disparity and the right one where it points.
            pick = mask & ok_l
            y, x = np.nonzero(pick)
            d_left = dl[y, x].astype(np.float64)
            xr = x - d_left
            x0 = np.floor(xr).astype(np.int64)
            a = xr - x0
            good = (x0 >= 0) & (x0 < w)
            x0c, x1c = np.clip(x0, 0, w - 1), np.clip(x0 + 1, 0, w - 1)
            exact = a == 0
            good &= np.where(exact, ok_r[y, x0c], (x0 + 1 < w) & ok_r[y, x0c] & ok_r[y, x1c])
            d_right = np.where(exact, dr[y, x0c], (1 - a) * dr[y, x0c] + a * dr[y, x1c])
            d = 0.5 * (d_left + d_right)
            points = q @ np.stack([x, y, d, np.ones_like(d)])
            good &= points[3] > 0
            xyz = (left_from_rect @ (points[:3, good] / points[3, good])).T + centre
            return xyz.astype(np.float32)

        return process

    return chain


def colour_fast_chain(sensor_file, threshold_grey, block, min_disparity, num_disparities, uniqueness,
                      max_lr_difference, smoothing_px, cleanup_px, margin):
    size, centre, r1, q, rect = rectification(sensor_file)
    w, h = size
    area = block * block
    sgbm = cv2.StereoSGBM_create(min_disparity, num_disparities, block, 8 * 3 * area, 32 * 3 * area,
                                 int(np.ceil(max_lr_difference)), 0, uniqueness, 0, 0, cv2.STEREO_SGBM_MODE_SGBM_3WAY)
    square = cv2.getStructuringElement(cv2.MORPH_RECT, (cleanup_px, cleanup_px))
    reach = min_disparity + num_disparities
    left_from_rect = r1.T

    def chain(reference_views):
        reference_left = rect(reference_views[0], 0)

        def process(views):
            left, right = rect(views[0], 0), rect(views[1], 1)
            difference = cv2.blur(cv2.absdiff(left, reference_left).max(axis=2), (smoothing_px, smoothing_px))
            mask = ((difference > threshold_grey) * 255).astype(np.uint8)
            mask = cv2.morphologyEx(cv2.morphologyEx(mask, cv2.MORPH_OPEN, square), cv2.MORPH_CLOSE, square)
            x, y, bw, bh = cv2.boundingRect(mask)
            if bw == 0:
                return np.zeros((0, 3), np.float32)
            # The contact's box and margin, its search range to its left, at least a block high.
            x0, y0 = max(0, x - margin), max(0, y - margin)
            x1, y1 = min(w, x + bw + margin), min(h, y + bh + margin)
            grow = max(0, block - (y1 - y0))
            y0, y1 = max(0, y0 - grow // 2), min(h, y1 + (grow + 1) // 2)
            if x1 <= reach:
                return np.zeros((0, 3), np.float32)
            cx0 = max(0, x0 - reach)
            cx1 = max(x1, cx0 + reach + 1)
            raw = sgbm.compute(np.ascontiguousarray(left[y0:y1, cx0:cx1]), np.ascontiguousarray(right[y0:y1, cx0:cx1]))
            d = np.zeros((h, w), np.float32)
            d[y0:y1, x0:x1] = raw[:, x0 - cx0:x1 - cx0].astype(np.float32) / 16
            valid = d >= min_disparity
            ys, xs = np.nonzero((mask > 0) & valid)
            disparity = d[ys, xs].astype(np.float64)
            points = q @ np.stack([xs, ys, disparity, np.ones_like(disparity)])
            good = points[3] > 0
            xyz = (left_from_rect @ (points[:3, good] / points[3, good])).T + centre
            return xyz.astype(np.float32)

        return process

    return chain


def marker_chain(sensor_file, diameter_px, disparity_px, row_gate_px=1.5, track_gate_px=6.0):
    k, size, baseline, centre = stereo_camera(sensor_file)
    p_left = k @ np.hstack([np.eye(3), np.zeros((3, 1))])
    p_right = k @ np.hstack([np.eye(3), np.array([[-baseline], [0], [0]])])
    params = cv2.SimpleBlobDetector_Params()
    params.blobColor = 0
    params.minArea = np.pi / 4 * diameter_px[0] ** 2 * 0.5
    params.maxArea = np.pi / 4 * diameter_px[1] ** 2 * 1.5
    params.filterByCircularity = False
    params.filterByInertia = True
    params.minInertiaRatio = 0.25  # axes within 2:1, as marker_detection's max_elongation
    params.filterByConvexity = False
    params.minDistBetweenBlobs = diameter_px[0]
    # Three thresholds between the dots (grey 30-100) and the gel (about 160),
    # not OpenCV's default seventeen: the same dots, a fifth of the time.
    params.minThreshold, params.maxThreshold, params.thresholdStep = 80, 131, 25
    params.minRepeatability = 2
    detector = cv2.SimpleBlobDetector_create(params)
    detect = lambda image: np.array([kp.pt for kp in detector.detect(image)], dtype=np.float64).reshape(-1, 2)

    def nearest(previous, now, gate):
        """For each previous position, the index of the nearest marker now within
        gate (-1: none), one to one: a marker wanted twice goes to the closer
        (a FLANN k-d tree over the markers now)."""
        taken = np.full(len(previous), -1)
        if len(previous) == 0 or len(now) == 0:
            return taken
        index = cv2.flann_Index(now.astype(np.float32), {"algorithm": 1, "trees": 1})
        found, distance2 = index.knnSearch(previous.astype(np.float32), 1, params={"checks": 32})
        found, distance = found[:, 0], np.sqrt(distance2[:, 0])
        order = np.argsort(distance, kind="stable")
        _, first = np.unique(found[order], return_index=True)
        keep = np.zeros(len(order), bool)
        keep[first] = True
        keep &= distance[order] <= gate
        taken[order[keep]] = found[order][keep]
        return taken

    def chain(reference_views):
        left, right = detect(reference_views[0]), detect(reference_views[1])
        # The gel at rest: a right marker on the left one's row whose disparity
        # fits a smooth disparity of the resting gel (the dome and the plate
        # make it vary by a third), grown from the gel's centre in rings of
        # 10 px: each ring takes the pairs that a polynomial in (x, y), fitted
        # to the pairs inside it, predicts within 1.5 px.
        dy = np.abs(left[:, None, 1] - right[None, :, 1])
        d = left[:, None, 0] - right[None, :, 0]
        possible = (dy <= row_gate_px) & (d >= disparity_px[0]) & (d <= disparity_px[1])
        u0, v0 = k[0, 2] - k[0, 0] * centre[0] / -centre[2], k[1, 2]  # the sensor's axis in the left view
        x, y = (left[:, 0] - u0) / size[0], (left[:, 1] - v0) / size[1]
        radius = np.hypot(x * size[0], y * size[1])
        terms = lambda degree: np.stack([x ** i * y ** j for i in range(degree + 1) for j in range(degree + 1 - i)], 1)
        counts = np.bincount(np.rint(d[possible & (radius < 20)[:, None]]).astype(int))
        expected = np.full(len(left), float(counts.argmax()))  # the most common disparity at the centre
        rings = [(r, 0 if r <= 20 else 2 if r < 80 else 3 if r < 120 else 4) for r in range(20, 260, 10)]
        for ring, degree in rings + [(np.inf, 4)] * 3:
            miss = np.where(possible & (radius < ring)[:, None], np.abs(d - expected[:, None]), np.inf)
            best = miss.argmin(axis=1)
            chosen = miss[np.arange(len(left)), best] <= 1.5
            a = terms(degree)
            model, *_ = np.linalg.lstsq(a[chosen], d[chosen, best[chosen]], rcond=None)
            expected = a @ model
        pairs, used = [], set()
        for i in np.argsort(miss[np.arange(len(left)), best]):
            if chosen[i] and best[i] not in used:
                used.add(best[i])
                pairs.append((left[i], right[best[i]]))
        track = {"left": np.array([p[0] for p in pairs]).reshape(-1, 2),
                 "right": np.array([p[1] for p in pairs]).reshape(-1, 2)}

        def process(views):
            now_left, now_right = detect(views[0]), detect(views[1])
            il = nearest(track["left"], now_left, track_gate_px)
            ir = nearest(track["right"], now_right, track_gate_px)
            seen = (il >= 0) & (ir >= 0)
            track["left"][il >= 0] = now_left[il[il >= 0]]
            track["right"][ir >= 0] = now_right[ir[ir >= 0]]
            if not seen.any():
                return np.zeros((0, 3), np.float32)
            h = cv2.triangulatePoints(p_left, p_right, track["left"][seen].T, track["right"][seen].T)
            return ((h[:3] / h[3]).T + centre).astype(np.float32)

        return process

    return chain
