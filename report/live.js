// touchcloud stream --view: polls state.json; when the frame number changes,
// loads that frame's pictures (NAME.rgba: RGBA rows) and cloud (cloud.bin:
// x, y, z float32 per point, mm) and draws the cloud with three.js.
(function () {
  "use strict";
  var POLL_MS = 150;
  var shown = -1, loading = false;
  var $ = function (id) { return document.getElementById(id); };

  var box = $("cloud");
  var renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setSize(box.clientWidth, box.clientHeight);
  renderer.setClearColor(0xffffff);
  box.appendChild(renderer.domElement);
  var scene = new THREE.Scene();
  var camera = new THREE.PerspectiveCamera(40, box.clientWidth / box.clientHeight, 0.1, 10000);
  camera.up.set(0, 0, 1);
  var controls = new THREE.OrbitControls(camera, renderer.domElement);
  var geometry = new THREE.BufferGeometry();
  var points = new THREE.Points(geometry, new THREE.PointsMaterial({ size: 2, sizeAttenuation: false, color: 0x1f77b4 }));
  scene.add(points);
  var framed = false;

  function draw() { renderer.render(scene, camera); }
  controls.addEventListener("change", draw);  // the user turning the view

  function showCloud(xyz, frame) {
    geometry.setAttribute("position", new THREE.BufferAttribute(xyz, 3));
    geometry.computeBoundingSphere();
    var zSum = 0;
    for (var i = 2; i < xyz.length; i += 3) zSum += xyz[i];
    box.dataset.frame = frame;
    box.dataset.points = xyz.length / 3;
    box.dataset.zSum = zSum.toFixed(4);
    if (!framed && xyz.length > 0) {  // the first cloud sets the view; the user's view is kept after
      var s = geometry.boundingSphere, r = Math.max(s.radius, 1);
      controls.target.copy(s.center);
      camera.position.set(s.center.x + r * 1.2, s.center.y - r * 1.8, s.center.z + r * 1.6);
      framed = true;
      controls.update();
    }
    draw();
  }

  // A picture: RGBA rows of the size state.json gives, drawn in its canvas.
  function picture(id, name, from, size, frame, note) {
    var view = $(id + "-view");
    view.hidden = !from;
    if (!from) return Promise.resolve();
    $(id + "-from").textContent = name + " (" + from + ")" + (note || "");
    return fetch(id + ".rgba?frame=" + frame).then(function (r) { return r.ok ? r.arrayBuffer() : null; }).then(function (b) {
      if (!b || b.byteLength !== size[0] * size[1] * 4) return;
      var canvas = $(id);
      canvas.width = size[0];
      canvas.height = size[1];
      canvas.getContext("2d").putImageData(new ImageData(new Uint8ClampedArray(b), size[0], size[1]), 0, 0);
      canvas.dataset.frame = frame;
    });
  }

  function load(state) {
    loading = true;
    var frame = state.frame;
    var cloud = state.shown.cloud
      ? fetch("cloud.bin?frame=" + frame).then(function (r) { return r.arrayBuffer(); })
          .then(function (b) { $("cloud-from").textContent = "cloud (" + state.shown.cloud + ", " + state.points + " points)"; showCloud(new Float32Array(b), frame); })
      : Promise.resolve($("cloud-view").hidden = true);
    var range = ", " + state.depth_range[0].toFixed(3) + " to " + state.depth_range[1].toFixed(3);
    return Promise.all([picture("camera", "camera", state.shown.camera, state.sizes.camera, frame),
                        picture("depth", "depth / height", state.shown.depth, state.sizes.depth, frame, range),
                        picture("mask", "contact mask", state.shown.mask, state.sizes.mask, frame), cloud])
      .then(function () { shown = frame; loading = false; });
  }

  function figures(s) {
    $("frame").textContent = s.frame;
    $("rate").textContent = s.rate_fps.toFixed(1);
    $("latency").textContent = s.latency_ms === null ? "-" : s.latency_ms.toFixed(1);
    $("dropped").textContent = s.dropped;
    $("refused").textContent = s.refused;
    $("refused-figure").hidden = s.refused === 0;
    $("status").textContent = s.ended ? "the stream has ended (Ctrl-C in its terminal closes this view)" : "";
  }

  // A state.json that cannot be fetched is a stream no longer served (its
  // last frame stays on the page); any other failure is an error, reported.
  function poll() {
    fetch("state.json", { cache: "no-store" }).then(function (r) { return r.json(); }, function () { return null; })
      .then(function (s) {
        if (s === null) {
          $("status").textContent = "the stream is no longer served";
          loading = false;
          setTimeout(poll, 1000);
          return;
        }
        figures(s);
        var next = s.frame !== shown && s.frame > 0 && !loading ? load(s) : Promise.resolve();
        return next.then(function () { setTimeout(poll, POLL_MS); });
      })
      .catch(function (e) {
        loading = false;
        if (window.reportError) window.reportError(e); else console.error(e);
        setTimeout(poll, 1000);
      });
  }
  draw();
  poll();
})();
