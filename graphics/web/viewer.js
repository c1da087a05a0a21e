// mechflow's animation viewer: builds the scene of MECHFLOW_DATA with
// three.js (THREE, inlined before this script) and plays it. Runs offline
// from one HTML file (graphics/animation.h).
//
// MECHFLOW_DATA (arrays of numbers are base64 of float32 / uint32):
//   bodies   labels "mechanism.body" of the moving bodies
//   shapes   {name, kind, body (-1: ground), color, opacity, line, doubleSided,
//             positions, indices} in the body's frame; a spring's mesh is a
//             helix of unit length along +y placed onto point1 (on body) and
//             point2 (on body2) at every frame
//   versions {shape, t, positions}: a shape's geometry from t on (shapes that
//            follow identifiers a control script changes)
//   times, poses  frames; per frame and body x y z qx qy qz qw
//   columns  the logged signals' names
//   plot     {times, values, binned}: the logged signals for the plot, at
//            the output rows (values float64, point-major, as the results
//            CSV has them); binned (a long run): two points per bin of time,
//            its smallest and largest value in the order they came
//            (graphics/signal_track.h)
// World axes are mechflow's: z up.
//
// "#t=1.5" in the URL opens the page at that time.
// Test interface (tests/graphics/browser_test.cc): window.mechflowTest; with
// "#test=t1,t2,...[&trace=BODY][&plot=COLUMN]" in the URL the page traces
// BODY's origin and plots COLUMN, seeks to each time after loading and
// writes what it saw as JSON into <pre id="mechflow-test">; with
// "#frametime=N" it draws N frames of a playing animation and reports the
// time each took.
(function () {
  'use strict';
  const errors = [];
  window.addEventListener('error', (e) => errors.push(String(e.message)));
  const consoleError = console.error.bind(console);
  console.error = (...args) => { errors.push(args.map(String).join(' ')); consoleError(...args); };

  const data = MECHFLOW_DATA;
  const bytes = (b64) => Uint8Array.from(atob(b64), (c) => c.charCodeAt(0)).buffer;
  const floats = (b64) => new Float32Array(bytes(b64));
  const doubles = (b64) => new Float64Array(bytes(b64));
  const times = data.times;
  const poses = floats(data.poses);
  const plotTimes = doubles(data.plot.times), plotValues = doubles(data.plot.values);
  const nb = data.bodies.length, nc = data.columns.length;
  const last = times.length - 1;

  // --- the three.js scene ---------------------------------------------------
  const canvasHolder = document.getElementById('view');
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  canvasHolder.appendChild(renderer.domElement);
  const world = new THREE.Scene();
  world.background = new THREE.Color(0xf2f2f2);
  world.add(new THREE.HemisphereLight(0xffffff, 0x777788, 0.75));
  const sun = new THREE.DirectionalLight(0xffffff, 0.6);
  sun.position.set(3, -5, 8);
  world.add(sun);
  const camera = new THREE.PerspectiveCamera(40, 1, 0.001, 1000);
  camera.up.set(0, 0, 1);
  const controls = new THREE.OrbitControls(camera, renderer.domElement);

  const ground = new THREE.Group();
  ground.name = 'Base0';
  world.add(ground);
  const bodies = data.bodies.map((label) => {
    const g = new THREE.Group();
    g.name = label;
    world.add(g);
    return g;
  });
  const holder = (index) => (index < 0 ? ground : bodies[index]);

  const shapes = data.shapes.map((s) => {
    const geometry = new THREE.BufferGeometry();
    const original = floats(s.positions);
    geometry.setAttribute('position', new THREE.BufferAttribute(original.slice(), 3));
    let object;
    const opacity = { transparent: s.opacity < 1, opacity: s.opacity };
    if (s.line) {
      object = new THREE.Line(geometry, new THREE.LineBasicMaterial({ color: s.color, ...opacity }));
    } else {
      geometry.setIndex(new THREE.BufferAttribute(new Uint32Array(bytes(s.indices)), 1));
      geometry.computeVertexNormals();
      object = new THREE.Mesh(geometry, new THREE.MeshStandardMaterial({
        color: new THREE.Color(s.color), roughness: 0.6, metalness: 0.1,
        side: s.doubleSided ? THREE.DoubleSide : THREE.FrontSide, ...opacity,
      }));
    }
    object.name = s.name;
    object.userData.owner = s.kind === 'spring' ? s.name : s.name + ' on ' + (s.body < 0 ? 'Base0' : data.bodies[s.body]);
    (s.kind === 'spring' ? world : holder(s.body)).add(object);
    return { spec: s, object, original, versions: [], shown: -1 };
  });
  for (const v of data.versions) shapes[v.shape].versions.push({ t: v.t, positions: floats(v.positions) });
  const springs = shapes.filter((s) => s.spec.kind === 'spring');
  const changing = shapes.filter((s) => s.versions.length > 0);

  // --- poses and shape versions ----------------------------------------------
  function frameAt(t) {  // the frame at or before t
    let lo = 0, hi = last;
    if (t <= times[0]) return 0;
    if (t >= times[hi]) return hi;
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (times[mid] <= t) lo = mid; else hi = mid;
    }
    return lo;
  }
  function pose(frame, b, position, quaternion) {
    const k = 7 * (frame * nb + b);
    position.set(poses[k], poses[k + 1], poses[k + 2]);
    quaternion.set(poses[k + 3], poses[k + 4], poses[k + 5], poses[k + 6]);
  }
  // a changing shape's geometry at t: its versions interpolated
  function reshape(shape, t) {
    const v = shape.versions;
    let i = -1;
    while (i + 1 < v.length && v[i + 1].t <= t) ++i;
    const from = i < 0 ? shape.original : v[i].positions;
    const next = i + 1 < v.length ? v[i + 1] : null;
    const w = next && i >= 0 ? (t - v[i].t) / (next.t - v[i].t) : 0;
    const key = i + w;
    if (key === shape.shown) return;
    const out = shape.object.geometry.attributes.position;
    for (let k = 0; k < from.length; ++k) out.array[k] = w > 0 ? from[k] + w * (next.positions[k] - from[k]) : from[k];
    out.needsUpdate = true;
    if (!shape.spec.line) shape.object.geometry.computeVertexNormals();
    shape.object.geometry.computeBoundingSphere();
    shape.shown = key;
  }
  const p0 = new THREE.Vector3(), p1 = new THREE.Vector3(), q0 = new THREE.Quaternion(), q1 = new THREE.Quaternion();
  const unitY = new THREE.Vector3(0, 1, 0);
  let current = times[0], currentFrame = 0;
  function show(t) {
    const f = frameAt(t);
    const g = Math.min(f + 1, last);
    const w = g > f ? Math.min(1, Math.max(0, (t - times[f]) / (times[g] - times[f]))) : 0;
    for (let b = 0; b < nb; ++b) {
      pose(f, b, p0, q0);
      pose(g, b, p1, q1);
      bodies[b].position.copy(p0.lerp(p1, w));
      bodies[b].quaternion.copy(q0.slerp(q1, w));
    }
    world.updateMatrixWorld(true);
    for (const { spec: s, object } of springs) {
      const a = new THREE.Vector3(...s.point1).applyMatrix4(holder(s.body).matrixWorld);
      const d = new THREE.Vector3(...s.point2).applyMatrix4(holder(s.body2).matrixWorld).sub(a);
      const length = Math.max(d.length(), 1e-9);
      object.position.copy(a);
      object.quaternion.setFromUnitVectors(unitY, d.divideScalar(length));
      object.scale.set(1, length, 1);
    }
    for (const shape of changing) reshape(shape, t);
    current = t;
    currentFrame = f;
    clock.textContent = 't = ' + t.toFixed(3) + ' s';
    slider.value = String(Math.round(1000 * (t - times[0]) / Math.max(times[last] - times[0], 1e-12)));
    updateTrace();
    drawPlot();
  }

  // --- path trace: a point of a body over the whole run, drawn up to now ------
  const traceSelect = document.getElementById('trace');
  data.bodies.forEach((label, b) => traceSelect.add(new Option(label, String(b))));
  let trace = null;  // {body, point, line}
  function setTrace(body, point) {
    if (trace) world.remove(trace.line);
    trace = null;
    if (body < 0) return;
    const path = new Float32Array(3 * times.length);
    const m = new THREE.Matrix4(), x = new THREE.Vector3(), q = new THREE.Quaternion(), one = new THREE.Vector3(1, 1, 1);
    for (let f = 0; f < times.length; ++f) {
      pose(f, body, x, q);
      const y = point.clone().applyMatrix4(m.compose(x, q, one));
      path.set([y.x, y.y, y.z], 3 * f);
    }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(path, 3));
    trace = { body, point: point.clone(), line: new THREE.Line(geometry, new THREE.LineBasicMaterial({ color: 0xd02090 })) };
    world.add(trace.line);
    traceSelect.value = String(body);
    updateTrace();
  }
  function updateTrace() { if (trace) trace.line.geometry.setDrawRange(0, currentFrame + 1); }
  traceSelect.onchange = () => setTrace(traceSelect.value === '' ? -1 : Number(traceSelect.value), new THREE.Vector3());

  // --- names on hover; a double click traces the point clicked ---------------
  const hover = document.getElementById('hover');
  const raycaster = new THREE.Raycaster();
  // the nearest shape under a point of the view (-1..1 both ways)
  function hitAt(at) {
    raycaster.params.Line.threshold = camera.position.distanceTo(controls.target) / 200;
    raycaster.setFromCamera(at, camera);
    const hits = raycaster.intersectObjects(shapes.map((s) => s.object), false);
    return hits.length ? hits[0] : null;
  }
  function picked(event) {
    const r = renderer.domElement.getBoundingClientRect();
    return hitAt(new THREE.Vector2(((event.clientX - r.left) / r.width) * 2 - 1, -((event.clientY - r.top) / r.height) * 2 + 1));
  }
  renderer.domElement.addEventListener('pointermove', (event) => {
    const hit = picked(event);
    hover.style.display = hit ? 'block' : 'none';
    if (!hit) return;
    hover.textContent = hit.object.userData.owner;
    hover.style.left = (event.clientX + 12) + 'px';
    hover.style.top = (event.clientY + 12) + 'px';
  });
  renderer.domElement.addEventListener('dblclick', (event) => {
    const hit = picked(event);
    const body = hit ? bodies.indexOf(hit.object.parent) : -1;
    if (body >= 0) setTrace(body, bodies[body].worldToLocal(hit.point.clone()));
  });

  // --- a plot of one logged signal with a cursor at the time shown -----------
  const plot = document.getElementById('plot');
  const signalSelect = document.getElementById('signal');
  data.columns.forEach((name, c) => signalSelect.add(new Option(name, String(c))));
  let curve = null;  // {column, image, lo, hi, points}
  const value = (p, column) => plotValues[p * nc + column];
  // the column's value at t: its points interpolated (at the instant of an
  // event, the value after it)
  function valueAt(column, t) {
    const n = plotTimes.length;
    if (n === 0) return NaN;
    if (t < plotTimes[0]) return value(0, column);
    let lo = 0, hi = n;  // the last point at or before t: lo
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (plotTimes[mid] <= t) lo = mid; else hi = mid;
    }
    if (lo + 1 >= n || !(plotTimes[lo + 1] > plotTimes[lo])) return value(lo, column);
    const w = (t - plotTimes[lo]) / (plotTimes[lo + 1] - plotTimes[lo]);
    return value(lo, column) + w * (value(lo + 1, column) - value(lo, column));
  }
  function setSignal(column) {
    curve = null;
    plot.style.display = column < 0 ? 'none' : 'block';
    if (column < 0) return;
    let lo = Infinity, hi = -Infinity;
    for (let p = 0; p < plotTimes.length; ++p) { const y = value(p, column); lo = Math.min(lo, y); hi = Math.max(hi, y); }
    const drawn = { lo, hi };  // the extremes of the curve, before the axis is widened
    if (!(hi > lo)) { lo -= 1; hi += 1; }
    const image = document.createElement('canvas');
    image.width = plot.width; image.height = plot.height;
    const c = image.getContext('2d');
    c.font = '11px sans-serif';
    c.fillStyle = '#333';
    c.fillText(data.columns[column], 6, 12);
    c.fillText(hi.toPrecision(4), 6, 26);
    c.fillText(lo.toPrecision(4), 6, plot.height - 6);
    c.strokeStyle = '#1f5fbf';
    c.beginPath();
    for (let p = 0; p < plotTimes.length; ++p) {
      const [x, y] = plotPoint(plotTimes[p], value(p, column), lo, hi);
      if (p === 0) c.moveTo(x, y); else c.lineTo(x, y);
    }
    c.stroke();
    curve = { column, image, lo, hi, drawn };
    signalSelect.value = String(column);
    drawPlot();
  }
  function plotPoint(t, v, lo, hi) {
    const x = 4 + (plot.width - 8) * (t - times[0]) / Math.max(times[last] - times[0], 1e-12);
    const y = plot.height - 4 - (plot.height - 34) * (v - lo) / (hi - lo);
    return [x, y];
  }
  function drawPlot() {
    if (!curve) return;
    const c = plot.getContext('2d');
    c.clearRect(0, 0, plot.width, plot.height);
    c.drawImage(curve.image, 0, 0);
    const v = valueAt(curve.column, current);
    const [x, y] = plotPoint(current, v, curve.lo, curve.hi);
    c.strokeStyle = '#d02020';
    c.beginPath(); c.moveTo(x, 30); c.lineTo(x, plot.height); c.stroke();
    c.fillStyle = '#d02020';
    c.fillRect(x - 2, y - 2, 5, 5);
    c.fillText(v.toPrecision(5), Math.min(x + 4, plot.width - 60), 26);
  }
  signalSelect.onchange = () => setSignal(signalSelect.value === '' ? -1 : Number(signalSelect.value));

  // --- controls -------------------------------------------------------------
  const clock = document.getElementById('clock');
  const slider = document.getElementById('time');
  const playButton = document.getElementById('play');
  const speed = document.getElementById('speed');
  const loop = document.getElementById('loop');
  let playing = false, lastNow = null;
  playButton.onclick = () => { playing = !playing; playButton.textContent = playing ? 'pause' : 'play'; lastNow = null; };
  slider.oninput = () => show(times[0] + (times[last] - times[0]) * Number(slider.value) / 1000);
  function fitView() {
    show(current);
    const box = new THREE.Box3().setFromObject(world);
    const centre = box.isEmpty() ? new THREE.Vector3() : box.getCenter(new THREE.Vector3());
    const size = box.isEmpty() ? 1 : Math.max(box.getSize(new THREE.Vector3()).length(), 1e-3);
    // far enough that the bounding sphere fits the narrower field of view
    const half = THREE.MathUtils.degToRad(camera.fov) / 2;
    const narrower = Math.min(half, Math.atan(Math.tan(half) * camera.aspect));
    const distance = 1.2 * (size / 2) / Math.sin(narrower);
    camera.position.copy(centre).add(new THREE.Vector3(1.1, -0.75, 0.5).normalize().multiplyScalar(distance));
    camera.near = size / 1000;
    camera.far = size * 100;
    camera.updateProjectionMatrix();
    controls.target.copy(centre);
    controls.update();
  }
  document.getElementById('reset').onclick = fitView;
  function resize() {
    const w = canvasHolder.clientWidth || 800, h = canvasHolder.clientHeight || 600;
    renderer.setSize(w, h, false);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
  }
  window.addEventListener('resize', resize);
  // the time after `t` when playing for `seconds` of wall time
  function advance(t, seconds) {
    let next = t + Number(speed.value) * seconds;
    if (next > times[last]) {
      if (loop.checked) next = times[0];
      else { next = times[last]; playing = false; playButton.textContent = 'play'; }
    }
    return next;
  }
  function tick(now) {
    if (playing) {
      if (lastNow !== null) show(advance(current, (now - lastNow) / 1000));
      lastNow = now;
    }
    controls.update();
    renderer.render(world, camera);
    requestAnimationFrame(tick);
  }

  resize();
  fitView();
  document.title = data.title;
  document.getElementById('title').textContent = data.title;

  // --- test interface -------------------------------------------------------
  window.mechflowTest = {
    seek(t) { show(t); renderer.render(world, camera); },
    transforms() {
      const out = {};
      bodies.forEach((g) => {
        const p = new THREE.Vector3(), q = new THREE.Quaternion();
        g.matrixWorld.decompose(p, q, new THREE.Vector3());
        out[g.name] = [p.x, p.y, p.z, q.x, q.y, q.z, q.w];
      });
      return out;
    },
    // the share of pixels that differ from the background, and the colour
    // at the screen position of the body's origin
    pixels(body) {
      const gl = renderer.getContext();
      const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
      const rgba = new Uint8Array(4 * w * h);
      gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, rgba);
      let differing = 0;
      for (let i = 0; i < rgba.length; i += 4)
        if (Math.abs(rgba[i] - 242) + Math.abs(rgba[i + 1] - 242) + Math.abs(rgba[i + 2] - 242) > 30) ++differing;
      const g = bodies[data.bodies.indexOf(body)];
      const at = new THREE.Vector3().setFromMatrixPosition(g.matrixWorld).project(camera);
      const x = Math.round((at.x + 1) / 2 * (w - 1)), y = Math.round((at.y + 1) / 2 * (h - 1));
      const k = 4 * (y * w + x);
      return { share: differing / (w * h), colour: [rgba[k], rgba[k + 1], rgba[k + 2]] };
    },
    // the body-frame vertices of the changing shapes as shown now
    geometry() {
      const out = {};
      for (const s of changing) out[s.spec.name] = Array.from(s.object.geometry.attributes.position.array);
      return out;
    },
    trace(body, point) { setTrace(data.bodies.indexOf(body), new THREE.Vector3(...point)); },
    // the traced path's vertices drawn now
    traced() {
      if (!trace) return [];
      const a = trace.line.geometry.attributes.position.array;
      return Array.from(a.slice(0, 3 * Math.min(trace.line.geometry.drawRange.count, times.length)));
    },
    plot(column) { setSignal(data.columns.indexOf(column)); },
    // the plot's cursor: the time shown and the signal's value there
    cursor() { return curve ? [current, valueAt(curve.column, current)] : null; },
    // the plotted curve: its points, whether binned, its smallest and largest value
    plotted() {
      return curve ? { points: plotTimes.length, binned: data.plot.binned, min: curve.drawn.lo, max: curve.drawn.hi } : null;
    },
    // what hovering at the screen position of body's origin names
    hoverName(body) {
      const g = bodies[data.bodies.indexOf(body)];
      const at = new THREE.Vector3().setFromMatrixPosition(g.matrixWorld).project(camera);
      const hit = hitAt(new THREE.Vector2(at.x, at.y));
      return hit ? hit.object.userData.owner : '';
    },
    errors,
  };
  const hash = window.location.hash;
  const test = /#test=([^&]*)/.exec(hash);
  const frametime = /#frametime=([0-9]+)/.exec(hash);
  if (test) {
    const report = { frames: times.length, seen: [] };
    const traced = /&trace=([^&]*)/.exec(hash), plotted = /&plot=([^&]*)/.exec(hash);
    if (traced) window.mechflowTest.trace(decodeURIComponent(traced[1]), [0, 0, 0]);
    if (plotted) window.mechflowTest.plot(decodeURIComponent(plotted[1]));
    for (const t of test[1].split(',').map(Number)) {
      window.mechflowTest.seek(t);
      const path = window.mechflowTest.traced();
      const seen = { t, transforms: window.mechflowTest.transforms(), pixels: {}, hover: {},
                     geometry: window.mechflowTest.geometry(), cursor: window.mechflowTest.cursor(),
                     traced: path.length / 3, traceEnd: path.slice(-3) };
      for (const label of data.bodies) {
        seen.pixels[label] = window.mechflowTest.pixels(label);
        seen.hover[label] = window.mechflowTest.hoverName(label);
      }
      report.seen.push(seen);
    }
    report.plotted = window.mechflowTest.plotted();
    report.errors = errors;
    document.getElementById('mechflow-test').textContent = JSON.stringify(report);
    requestAnimationFrame(() => renderer.render(world, camera));  // the page shows the last time seen
  } else if (frametime) {
    // frames of the animation playing at speed 1 and 60 frames per second,
    // each timed from the new time to the finished image (reading a pixel
    // back waits for the drawing)
    const n = Number(frametime[1]), gl = renderer.getContext(), spent = [], pixel = new Uint8Array(4);
    let t = times[0];
    for (let i = 0; i < n; ++i) {
      const start = performance.now();
      t = advance(t, 1 / 60);
      show(t);
      renderer.render(world, camera);
      gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
      spent.push(performance.now() - start);
    }
    spent.sort((a, b) => a - b);
    document.getElementById('mechflow-test').textContent = JSON.stringify({
      frames: n, median_ms: spent[n >> 1], p95_ms: spent[Math.floor(0.95 * (n - 1))], max_ms: spent[n - 1], errors });
  } else {
    const start = /#t=([0-9.eE+-]+)/.exec(hash);  // a link to a time: NAME.html#t=1.5
    if (start) show(Number(start[1]));
    requestAnimationFrame(tick);
  }
})();
