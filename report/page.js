// The report page's script: draws the data of #tc-data with three.js (3D
// view) and uPlot (plots), fills the tables, then marks #tc-status as drawn
// and records where each drawing is (the browser test checks those places).
(function () {
  "use strict";
  var data = JSON.parse(document.getElementById("tc-data").textContent);
  var drawn = [], waiting = 0, tablesDone = false;
  // uPlot draws after the script (in a microtask): a plot counts as drawn
  // from its first draw hook on.
  function plotHooks(name) {
    waiting += 1;
    var seen = false;
    return { draw: [function (u) { if (seen) return; seen = true; drawn.push([name, u.over]); waiting -= 1; finish(); }] };
  }

  function el(tag, text) { var e = document.createElement(tag); if (text !== undefined) e.textContent = text; return e; }
  function floats(b64) {
    var bin = atob(b64), bytes = new Uint8Array(bin.length);
    for (var i = 0; i < bin.length; ++i) bytes[i] = bin.charCodeAt(i);
    return new Float32Array(bytes.buffer);
  }
  function fmt(v) { return typeof v === "number" ? (Math.abs(v) >= 1e5 || (v !== 0 && Math.abs(v) < 1e-3) ? v.toExponential(4) : +v.toPrecision(6)) + "" : String(v); }
  function table(id, header, rows) {
    var t = document.getElementById(id), tr = el("tr");
    header.forEach(function (h) { tr.appendChild(el("th", h)); });
    t.appendChild(tr);
    rows.forEach(function (r) { var row = el("tr"); r.forEach(function (c) { row.appendChild(el("td", fmt(c))); }); t.appendChild(row); });
  }

  // Header.
  var run = data.run;
  document.getElementById("tc-title").textContent =
    "touchcloud run report: " + run.pipeline + (run.scene ? " on " + run.scene : "");
  document.getElementById("tc-subtitle").textContent = run.file + ", seed " + run.seed + ", ran in " + fmt(run.wall_time_s) +
      " s (+" + fmt(run.load_time_s) + " s loading)" + (data.folder_runs > 1 ? "; the 3D view, times and tables show run '" +
      run.label + "', the chamfer plot all " + data.folder_runs + " runs of the folder" : "");
  // Accuracy beside what it hides: how much of the truth the run missed.
  var titles = { accuracy: "accuracy (Eq. 11)", completeness: "completeness", fscore: "F-score", coverage: "coverage",
                 masked_points: "surface points lost to a mask" };
  document.getElementById("tc-headline").textContent = (data.headline || []).map(function (h) {
    return titles[h.role] + " " + fmt(h.value) + (h.unit ? " " + h.unit : "") + " (" + h.metric + ")";
  }).join("; ");
  var missing = document.getElementById("tc-missing");
  data.missing.forEach(function (m) { missing.appendChild(el("li", "not shown: " + m)); });

  // Colour maps.
  function viridis(t) {  // a 5-stop approximation
    var s = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];
    t = Math.min(1, Math.max(0, t)) * 4; var i = Math.min(3, Math.floor(t)), f = t - i;
    return s[i].map(function (c, k) { return (c + f * (s[i + 1][k] - c)) / 255; });
  }
  function touchColour(k, n) { var c = new THREE.Color(); c.setHSL((k * 0.618034) % 1, 0.85, 0.55); return c; }

  // 3D view.
  (function draw3d() {
    var box = document.getElementById("tc-3d"), clouds = data.clouds;
    var W = box.clientWidth, H = box.clientHeight;
    var renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    renderer.setPixelRatio(1);
    renderer.setSize(W, H);
    box.appendChild(renderer.domElement);
    var scene = new THREE.Scene();
    scene.background = new THREE.Color(0x1d2330);
    var layers = [], bounds = new THREE.Box3();
    var legend = document.getElementById("tc-3d-legend");
    function addPoints(name, xyz, colours, size, colour) {
      var g = new THREE.BufferGeometry();
      g.setAttribute("position", new THREE.BufferAttribute(xyz, 3));
      if (colours) g.setAttribute("color", new THREE.BufferAttribute(colours, 3));
      g.computeBoundingBox();
      bounds.union(g.boundingBox);
      var m = new THREE.PointsMaterial({ size: size, sizeAttenuation: false, vertexColors: !!colours, color: colours ? 0xffffff : colour });
      var p = new THREE.Points(g, m); scene.add(p); layers.push([name, p]); return p;
    }
    function legendLine(html) { var d = el("div"); d.innerHTML = html; legend.appendChild(d); }
    if (clouds.ground_truth) {
      addPoints("ground truth", floats(clouds.ground_truth.xyz), null, 1, 0x8a93a6);
      legendLine('<span class="sw" style="background:#8a93a6"></span>ground truth (' + clouds.ground_truth.shown + " of " + clouds.ground_truth.points + " points)");
    }
    if (clouds.surface) {
      var s = clouds.surface, xyz = floats(s.xyz), n = xyz.length / 3, col = new Float32Array(n * 3);
      var d = s.distance_mm ? floats(s.distance_mm) : null, top = s.distance_mm ? Math.max(s.distance_p95_mm, 1e-6) : 1;
      for (var i = 0; i < n; ++i) {
        var c = d ? viridis(d[i] / top) : [0.9, 0.6, 0.2];
        col[3 * i] = c[0]; col[3 * i + 1] = c[1]; col[3 * i + 2] = c[2];
      }
      addPoints("surface", xyz, col, 2, 0);
      legendLine(d ? 'surface (' + s.source + ', ' + n + ' points) coloured by distance to ground truth: ' +
                 '<span class="sw" style="background:#440154"></span>0 mm &#8230; <span class="sw" style="background:#fde725"></span>' +
                 fmt(top) + ' mm (95th percentile; mean ' + fmt(s.distance_mean_mm) + ' mm)'
               : '<span class="sw" style="background:#e69933"></span>surface (' + s.source + ')');
    }
    if (clouds.touch_points) {
      var t = clouds.touch_points, txyz = floats(t.xyz), tn = txyz.length / 3, tcol = new Float32Array(tn * 3);
      var label = null;
      if (t.touch_counts) {  // touch of original point j: by the cumulative counts
        var ends = [], acc = 0; t.touch_counts.forEach(function (c) { acc += c; ends.push(acc); });
        label = function (j) { for (var k = 0; k < ends.length; ++k) if (j < ends[k]) return k; return ends.length - 1; };
      }
      for (var j = 0; j < tn; ++j) {
        var cc = label ? touchColour(label(j * t.stride), t.touch_counts.length) : new THREE.Color(0xffffff);
        tcol[3 * j] = cc.r; tcol[3 * j + 1] = cc.g; tcol[3 * j + 2] = cc.b;
      }
      addPoints("touch points", txyz, tcol, 4, 0);
      legendLine("touch points (" + t.source + ", " + t.points + ")" + (label ? ", one colour per touch (" + t.touch_counts.length + " touches)" : ""));
    }
    (clouds.other || []).forEach(function (o) { addPoints(o.source, floats(o.xyz), null, 2, 0xffffff); legendLine("other cloud: " + o.source); });
    if (bounds.isEmpty()) bounds.set(new THREE.Vector3(-1, -1, -1), new THREE.Vector3(1, 1, 1));
    if (clouds.touch_targets_xy_mm) {
      var tt = clouds.touch_targets_xy_mm, ztop = bounds.max.z + 5, zlow = bounds.min.z;
      var pos = new Float32Array(tt.length * 3), seg = new Float32Array(tt.length * 6), scol = new Float32Array(tt.length * 3);
      tt.forEach(function (p, k) {
        pos.set([p[0], p[1], ztop], 3 * k); seg.set([p[0], p[1], ztop, p[0], p[1], zlow], 6 * k);
        var c = touchColour(k, tt.length); scol.set([c.r, c.g, c.b], 3 * k);
      });
      addPoints("touch positions", pos, scol, 8, 0);
      var lg = new THREE.BufferGeometry(); lg.setAttribute("position", new THREE.BufferAttribute(seg, 3));
      var lines = new THREE.LineSegments(lg, new THREE.LineBasicMaterial({ color: 0x556070 }));
      scene.add(lines); layers.push(["touch positions' verticals", lines]);
      legendLine("sensor touch positions (" + tt.length + ", planner's grid cells, drawn 5 mm above the scene)");
    }
    var centre = bounds.getCenter(new THREE.Vector3()), size = bounds.getSize(new THREE.Vector3()).length();
    var camera = new THREE.PerspectiveCamera(40, W / H, size / 1000, size * 20);
    camera.up.set(0, 0, 1);
    camera.position.set(centre.x + 0.55 * size, centre.y - 0.75 * size, centre.z + 0.6 * size);
    camera.lookAt(centre);
    function render() { renderer.render(scene, camera); }
    var controls = new THREE.OrbitControls(camera, renderer.domElement);
    controls.target.copy(centre);
    controls.update();
    controls.addEventListener("change", render);
    var panel = document.getElementById("tc-3d-controls");
    panel.appendChild(el("span", "drag: rotate, wheel: zoom, right-drag: pan; show: "));
    layers.forEach(function (l) {
      var lab = el("label"), cb = el("input"); cb.type = "checkbox"; cb.checked = true;
      cb.addEventListener("change", function () { l[1].visible = cb.checked; render(); });
      lab.appendChild(cb); lab.appendChild(document.createTextNode(" " + l[0])); panel.appendChild(lab);
    });
    render();
    drawn.push(["3d", renderer.domElement]);
  })();

  // Chamfer per touch (uPlot): one curve per run of `list`, named by `name`.
  function chamferPlot(box, list, name, plotName, height) {
    var n = Math.max.apply(null, list.map(function (c) { return c.series.length; }));
    var xs = []; for (var i = 1; i <= n; ++i) xs.push(i);
    var cols = [xs], series = [{ label: "touch" }];
    list.forEach(function (c, k) {
      cols.push(xs.map(function (_, i) { return i < c.series.length ? c.series[i] : null; }));
      var colour = touchColour(k + 3, list.length);
      series.push({ label: name(c), stroke: "#" + colour.getHexString(), width: k === 0 ? 2 : 1.25,
                    value: function (u, v) { return v == null ? "-" : v.toFixed(3) + " " + data.chamfer.unit; } });
    });
    new uPlot({ width: box.clientWidth, height: height, series: series, hooks: plotHooks(plotName),
      scales: { x: { time: false } },
      axes: [{ label: "touch" }, { label: "chamfer (" + data.chamfer.unit + ")", size: 60 }] }, cols, box);
  }

  (function drawChamfer() {
    var box = document.getElementById("tc-chamfer"), curves = data.chamfer.curves;
    if (!curves.length) { box.textContent = "no chamfer series in this run"; return; }
    chamferPlot(box, curves, function (c) { return c.label + " (" + c.metric + ")"; }, "chamfer", 280);
  })();

  // A folder of runs (a sweep's): one panel per setting, named by the values
  // varied, with its repeats' curves, final accuracy and time.
  (function drawSettings() {
    var settings = data.settings || [], curves = data.chamfer.curves, unit = data.chamfer.unit;
    if (!settings.length) return;
    document.getElementById("tc-settings-section").hidden = false;
    var holder = document.getElementById("tc-settings"), rows = [];
    function spread(s, u) {
      return s.n === 0 ? "-" : fmt(s.mean) + (s.n > 1 ? " \u00b1 " + fmt(s.sd) : "") + " " + u;
    }
    settings.forEach(function (s, k) {
      var panel = el("div"), box = el("div"), f = s.final, t = s.wall_time_s;
      panel.className = "plot setting";
      box.className = "tc-canvas-box";
      panel.appendChild(el("h3", s.label));
      panel.appendChild(box);
      panel.appendChild(el("p", "final chamfer " + spread(f, unit) + (f.n > 1 ? " (sd; " + fmt(f.min) + " to " + fmt(f.max) + ")" : "") +
                               " over " + s.curves.length + (s.curves.length === 1 ? " run" : " runs") + "; wall time " + spread(t, "s")));
      holder.appendChild(panel);
      chamferPlot(box, s.curves.map(function (i) { return curves[i]; }), function (c) { return "seed " + c.seed; }, "setting" + k, 200);
      rows.push([s.label, s.curves.length, f.mean, f.sd, f.min, f.max, t.mean]);
    });
    table("tc-settings-table", ["setting", "runs", "final chamfer mean (" + unit + ")", "sd", "min", "max", "wall time mean (s)"],
          rows.map(function (r) { return r.map(function (v) { return v === null ? "-" : v; }); }));
  })();

  // Time per stage, stacked by phase (uPlot bars; each series drawn from 0
  // to its cumulative sum, the longest first).
  (function drawTimes() {
    var box = document.getElementById("tc-times"), stages = data.stages;
    if (!stages.length) { box.textContent = "no stage times in this run"; return; }
    var phases = ["check", "configure", "process", "finish"], colours = ["#9467bd", "#ff7f0e", "#1f77b4", "#2ca02c"];
    var xs = stages.map(function (_, i) { return i; }), cum = [], acc = stages.map(function () { return 0; });
    phases.forEach(function (p) { acc = acc.map(function (a, i) { return a + (stages[i][p] || 0); }); cum.push(acc.slice()); });
    var cols = [xs], series = [{ label: "stage", value: function (u, v) { return v == null ? "-" : stages[v].id; } }];
    for (var k = phases.length - 1; k >= 0; --k) {
      cols.push(cum[k]);
      series.push({ label: phases[k] + " (cumulative, s)", fill: colours[k], stroke: colours[k], width: 0,
                    paths: uPlot.paths.bars({ size: [0.7, 60] }), points: { show: false } });
    }
    new uPlot({ width: box.clientWidth, height: 280, series: series, hooks: plotHooks("times"),
      scales: { x: { time: false, range: [-0.5, stages.length - 0.5] }, y: { range: function (u, lo, hi) { return [0, hi * 1.05 || 1]; } } },
      axes: [{ label: "stage", splits: function () { return xs; }, values: function (u, s) { return s.map(function (i) { return stages[i] ? stages[i].id : ""; }); }, rotate: -45 },
             { label: "seconds", size: 60 }] }, cols, box);
  })();

  // Accuracy against time over the folder's runs, with the Pareto front.
  (function drawPareto() {
    var runs = data.chamfer.curves.filter(function (c) { return typeof c.final === "number" && typeof c.wall_time_s === "number"; });
    if (runs.length < 2) return;
    document.getElementById("tc-pareto-panel").hidden = false;
    var box = document.getElementById("tc-pareto");
    runs.sort(function (a, b) { return a.wall_time_s - b.wall_time_s || a.final - b.final; });
    var xs = runs.map(function (r) { return r.wall_time_s; }), ys = runs.map(function (r) { return r.final; });
    var best = Infinity, front = runs.map(function (r) { if (r.final < best) { best = r.final; return r.final; } return null; });
    new uPlot({ width: box.clientWidth, height: 280, hooks: plotHooks("pareto"),
      series: [{ label: "wall time (s)", value: function (u, v) { return v == null ? "-" : v.toFixed(3) + " s"; } },
               { label: "run (" + data.chamfer.unit + ")", stroke: "#1f77b4", paths: function () { return null; }, points: { show: true, size: 8, fill: "#1f77b4" },
                 value: function (u, v, si, i) { return v == null || i == null ? "-" : runs[i].label + ": " + v.toFixed(3); } },
               { label: "Pareto front", stroke: "#d62728", width: 2, spanGaps: true, points: { show: true, size: 5 } }],
      scales: { x: { time: false } },
      axes: [{ label: "wall time (s)" }, { label: "final chamfer (" + data.chamfer.unit + ")", size: 60 }] }, [xs, ys, front], box);
  })();

  // Pictures among the run's outputs (a sensing pipeline's markers, or a map
  // beside its truth), as written, with the caption the stage gave each; a
  // picture counts as drawn once the browser has decoded it.
  (data.images || []).forEach(function (im, k) {
    document.getElementById("tc-images-section").hidden = false;
    var fig = el("figure"), img = el("img");
    waiting += 1;
    img.onload = function () { drawn.push(["image" + k, img]); waiting -= 1; finish(); };
    img.onerror = function () { waiting -= 1; finish(); };  // the page's error listener names it
    img.alt = im.name; img.src = "data:" + im.mime + ";base64," + im.base64;
    fig.appendChild(img);
    fig.appendChild(el("figcaption", (im.caption ? im.caption + " " : "") + "(" + im.name + ")"));
    document.getElementById("tc-images").appendChild(fig);
  });

  // Tables.
  table("tc-metrics", ["metric", "final value", "unit"], data.metrics);
  table("tc-params", ["stage", "plugin", "parameter", "value"], data.params);
  table("tc-versions", ["library", "version"], data.versions);
  table("tc-notes", ["note", "text"], Object.keys(data.notes).sort().map(function (k) { return [k, data.notes[k]]; }));

  tablesDone = true;
  finish();

  // Drawn: where each drawing lies on the page (CSS pixels, page coordinates).
  function finish() {
  if (waiting > 0 || !tablesDone) return;
  var status = document.getElementById("tc-status"), rects = {};
  drawn.forEach(function (d) {
    var r = d[1].getBoundingClientRect();
    rects[d[0]] = [Math.round(r.left + window.scrollX), Math.round(r.top + window.scrollY), Math.round(r.width), Math.round(r.height)];
  });
  status.setAttribute("data-rects", JSON.stringify(rects));
  status.setAttribute("data-drawn", drawn.map(function (d) { return d[0]; }).join(" "));
  status.textContent = "drawn: " + drawn.map(function (d) { return d[0]; }).join(", ");
  }
})();
