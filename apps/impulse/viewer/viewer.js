// SPDX-License-Identifier: MIT
// The impulse replay viewer: the bodies of a trajectory in a three.js scene with an orbit camera,
// a time slider with play/pause, and plots of height, speed and energy with a cursor at the time
// shown. Its data (meshes in body frame, poses, series) is written into the page by `impulse view`.
(function () {
  'use strict';

  var data = JSON.parse(document.getElementById('impulse-data').textContent);
  var viewer = { ready: false, errors: [] };
  window.impulseViewer = viewer;
  window.addEventListener('error', function (event) { viewer.errors.push(String(event.message)); });

  var times = data.times;
  var last = times.length - 1;
  var up = new THREE.Vector3(data.up[0], data.up[1], data.up[2]);

  // ---- the 3D scene ----
  var stage = document.getElementById('stage');
  var renderer;
  try {
    renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  } catch (error) {
    document.getElementById('message').textContent = 'This browser cannot draw WebGL: ' + error.message;
    throw error;
  }
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setClearColor(0xdfe8f2);
  stage.insertBefore(renderer.domElement, stage.firstChild);

  var scene = new THREE.Scene();
  var camera = new THREE.PerspectiveCamera(35, 1, data.radius * 0.01, data.radius * 100);
  camera.up.copy(up);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8090a0, 0.55));
  var sun = new THREE.DirectionalLight(0xffffff, 0.75);
  scene.add(sun);

  function buildMesh(mesh) {
    var geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.Float32BufferAttribute(mesh.positions, 3));
    geometry.setAttribute('normal', new THREE.Float32BufferAttribute(mesh.normals, 3));
    geometry.setAttribute('color', new THREE.Float32BufferAttribute(mesh.colours, 3));
    geometry.setIndex(mesh.indices);
    var material = new THREE.MeshPhongMaterial({
      vertexColors: THREE.VertexColors, shininess: 40, specular: 0x333333, side: THREE.DoubleSide
    });
    return new THREE.Mesh(geometry, material);
  }

  data.statics.forEach(function (body) {
    var object = buildMesh(body.mesh);
    object.position.fromArray(body.pose, 0);
    object.quaternion.fromArray(body.pose, 3);
    scene.add(object);
  });

  var legend = document.getElementById('legend');
  var bodies = data.bodies.map(function (body) {
    var object = buildMesh(body.mesh);
    scene.add(object);
    // the path of the centre, revealed up to the time shown
    var path = new THREE.BufferGeometry();
    var points = new Float32Array(times.length * 3);
    for (var i = 0; i < times.length; ++i) {
      for (var c = 0; c < 3; ++c) points[3 * i + c] = body.poses[7 * i + c];
    }
    path.setAttribute('position', new THREE.BufferAttribute(points, 3));
    var line = new THREE.Line(path, new THREE.LineBasicMaterial({ color: body.colour }));
    scene.add(line);
    var entry = document.createElement('span');
    entry.style.color = body.colour;
    entry.textContent = '\u25cf ' + body.name;
    legend.appendChild(entry);
    return { object: object, poses: body.poses, line: line, path: path };
  });

  var centre = new THREE.Vector3().fromArray(data.centre);
  var controls = new THREE.OrbitControls(camera, renderer.domElement);
  controls.target.copy(centre);
  // the camera of the rendered frames (impulse render), which the page is given
  // (a little farther: the page's view is rarely as wide as the frames)
  camera.position.fromArray(data.eye).sub(centre).multiplyScalar(1.2).add(centre);
  controls.update();
  var toEye = camera.position.clone().sub(centre).normalize();
  sun.position.copy(centre).addScaledVector(up, data.radius * 4).addScaledVector(toEye, data.radius);
  controls.addEventListener('change', draw);

  // ---- plots ----
  function niceStep(span) {
    var raw = span / 4, decade = Math.pow(10, Math.floor(Math.log10(raw))), m = raw / decade;
    return decade * (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10);
  }

  function makePlot(id, title, series, colours) {
    var canvas = document.getElementById(id);
    var plot = { canvas: canvas, title: title, series: series, colours: colours };
    var low = Infinity, high = -Infinity;
    series.forEach(function (values) {
      values.forEach(function (v) { if (v < low) low = v; if (v > high) high = v; });
    });
    if (!(high > low)) { var pad = Math.abs(high) * 0.1 || 1; low -= pad; high += pad; }
    var margin = (high - low) * 0.05;
    plot.low = low - margin; plot.high = high + margin;
    return plot;
  }

  function drawPlot(plot, index) {
    var canvas = plot.canvas, ratio = window.devicePixelRatio || 1;
    var width = canvas.clientWidth, height = canvas.clientHeight;
    if (canvas.width !== Math.round(width * ratio) || canvas.height !== Math.round(height * ratio)) {
      canvas.width = Math.round(width * ratio); canvas.height = Math.round(height * ratio);
    }
    var g = canvas.getContext('2d');
    g.setTransform(ratio, 0, 0, ratio, 0, 0);
    g.clearRect(0, 0, width, height);
    var left = 52, right = width - 18, top = 20, bottom = height - 22;
    var t0 = times[0], t1 = times[last] > t0 ? times[last] : t0 + 1;
    function x(t) { return left + (t - t0) / (t1 - t0) * (right - left); }
    function y(v) { return bottom - (v - plot.low) / (plot.high - plot.low) * (bottom - top); }
    g.fillStyle = '#222'; g.font = 'bold 12px sans-serif'; g.fillText(plot.title, left, 14);
    g.font = '11px sans-serif'; g.strokeStyle = '#e2e4e8'; g.lineWidth = 1;
    var step = niceStep(plot.high - plot.low);
    for (var v = Math.ceil(plot.low / step) * step; v <= plot.high; v += step) {
      g.beginPath(); g.moveTo(left, y(v)); g.lineTo(right, y(v)); g.stroke();
      g.fillText(Number(v.toPrecision(6)).toString(), 4, y(v) + 4);
    }
    var tstep = niceStep(t1 - t0);
    for (var t = Math.ceil(t0 / tstep) * tstep; t <= t1; t += tstep) {
      g.beginPath(); g.moveTo(x(t), top); g.lineTo(x(t), bottom); g.stroke();
      g.fillText(Number(t.toPrecision(6)) + ' s', x(t) - 8, height - 6);
    }
    g.lineWidth = 1.5;
    plot.series.forEach(function (values, k) {
      g.strokeStyle = plot.colours[k];
      g.beginPath();
      for (var i = 0; i < values.length; ++i) {
        if (i === 0) g.moveTo(x(times[i]), y(values[i])); else g.lineTo(x(times[i]), y(values[i]));
      }
      g.stroke();
    });
    g.strokeStyle = '#c00'; g.lineWidth = 1;
    g.beginPath(); g.moveTo(x(times[index]), top); g.lineTo(x(times[index]), bottom); g.stroke();
  }

  var colours = data.bodies.map(function (body) { return body.colour; });
  var plots = [
    makePlot('plot-height', 'height (m)', data.series.height, colours),
    makePlot('plot-speed', 'speed (m/s)', data.series.speed, colours),
    makePlot('plot-energy', data.series.energyLabel, [data.series.energy], ['#333333'])
  ];

  // ---- time ----
  var slider = document.getElementById('slider');
  var clock = document.getElementById('clock');
  var playButton = document.getElementById('play');
  var trails = document.getElementById('trails');
  slider.max = String(last);
  var current = 0;
  var playing = false;
  var playClock = 0; // simulated seconds shown while playing

  function show(index) {
    current = Math.max(0, Math.min(last, index));
    slider.value = String(current);
    bodies.forEach(function (body) {
      body.object.position.fromArray(body.poses, 7 * current);
      body.object.quaternion.fromArray(body.poses, 7 * current + 3);
      body.path.setDrawRange(0, current + 1);
      body.line.visible = trails.checked;
    });
    clock.textContent = 't = ' + times[current].toFixed(3) + ' s';
    draw();
  }

  function draw() {
    var width = stage.clientWidth, height = stage.clientHeight;
    var size = renderer.getSize(new THREE.Vector2());
    if (size.x !== width || size.y !== height) {
      renderer.setSize(width, height);
      camera.aspect = width / Math.max(height, 1);
      camera.updateProjectionMatrix();
    }
    renderer.render(scene, camera);
    plots.forEach(function (plot) { drawPlot(plot, current); });
  }

  function indexAt(t) {
    var lo = 0, hi = last;
    while (lo < hi) {
      var mid = (lo + hi + 1) >> 1;
      if (times[mid] <= t) lo = mid; else hi = mid - 1;
    }
    return lo;
  }

  var lastTick = 0;
  function tick(now) {
    if (!playing) return;
    if (lastTick) playClock += (now - lastTick) / 1000;
    lastTick = now;
    if (playClock >= times[last]) { playClock = times[last]; setPlaying(false); }
    show(indexAt(playClock));
    if (playing) requestAnimationFrame(tick);
  }

  function setPlaying(on) {
    playing = on;
    playButton.textContent = on ? 'Pause' : 'Play';
    if (on) {
      if (current >= last) current = 0;
      playClock = times[current];
      lastTick = 0;
      requestAnimationFrame(tick);
    }
  }

  playButton.addEventListener('click', function () { setPlaying(!playing); });
  slider.addEventListener('input', function () { setPlaying(false); show(Number(slider.value)); });
  trails.addEventListener('change', function () { show(current); });
  window.addEventListener('resize', draw);

  viewer.frame = function () { return current; };
  viewer.time = function () { return times[current]; };
  viewer.frameCount = function () { return times.length; };
  viewer.playing = function () { return playing; };
  viewer.bodyPosition = function (k) { return bodies[k].object.position.toArray(); };
  viewer.show = show;
  show(0);
  viewer.ready = true;
})();
