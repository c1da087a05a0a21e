// mechflow's animation viewer: builds the scene of MECHFLOW_SCENE with
// three.js (THREE, inlined before this script) and plays the body poses of
// MECHFLOW_POSES. Runs offline from one HTML file (graphics/animation.h).
//
// MECHFLOW_POSES: { times: [t...], data: base64 of float32, per frame and
// body x y z qx qy qz qw }. World axes are mechflow's: z up.
//
// "#t=1.5" in the URL opens the page at that time.
// Test interface (tests/graphics/browser_test.cc): window.mechflowTest.seek(t)
// shows time t; .transforms() gives every body's world position and
// quaternion; with "#test=t1,t2,..." in the URL the page seeks to each time
// after loading and writes what it saw as JSON into <pre id="mechflow-test">.
(function () {
  'use strict';
  const errors = [];
  window.addEventListener('error', (e) => errors.push(String(e.message)));
  const consoleError = console.error.bind(console);
  console.error = (...args) => { errors.push(args.map(String).join(' ')); consoleError(...args); };

  const scene = MECHFLOW_SCENE;
  const times = MECHFLOW_POSES.times;
  const poses = (() => {
    const bytes = Uint8Array.from(atob(MECHFLOW_POSES.data), (c) => c.charCodeAt(0));
    return new Float32Array(bytes.buffer);
  })();
  const nb = scene.bodies.length;

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
  world.add(ground);
  const bodies = scene.bodies.map((label) => {
    const g = new THREE.Group();
    g.name = label;
    world.add(g);
    return g;
  });
  const holder = (index) => (index < 0 ? ground : bodies[index]);

  function material(s) {
    return new THREE.MeshStandardMaterial({
      color: new THREE.Color(s.color), transparent: s.opacity < 1, opacity: s.opacity,
      roughness: 0.6, metalness: 0.1,
    });
  }
  function placed(object, s) {
    const r = s.rotation;  // row-major: the shape's axes in the body frame
    const m = new THREE.Matrix4().set(r[0], r[1], r[2], s.position[0], r[3], r[4], r[5], s.position[1],
                                      r[6], r[7], r[8], s.position[2], 0, 0, 0, 1);
    const holderOfShape = new THREE.Group();
    holderOfShape.applyMatrix4(m);
    holderOfShape.add(object);
    return holderOfShape;
  }

  const springs = [];
  for (const s of scene.shapes) {
    let object;
    if (s.kind === 'box') {
      object = new THREE.Mesh(new THREE.BoxGeometry(s.size[0], s.size[1], s.size[2]), material(s));
    } else if (s.kind === 'sphere') {
      object = new THREE.Mesh(new THREE.SphereGeometry(s.radius, 32, 16), material(s));
    } else if (s.kind === 'cylinder') {
      object = new THREE.Mesh(new THREE.CylinderGeometry(s.radius, s.radius, s.length, 32), material(s));
      object.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), new THREE.Vector3(...s.axis));
    } else if (s.kind === 'polyline') {
      const geometry = new THREE.BufferGeometry().setFromPoints(s.points.map((p) => new THREE.Vector3(...p)));
      object = new THREE.Line(geometry, new THREE.LineBasicMaterial({ color: s.color, transparent: s.opacity < 1,
                                                                      opacity: s.opacity }));
    } else if (s.kind === 'spring') {
      // a helix of unit length along +y, stretched and turned onto its two points each frame
      const points = [];
      const n = 24 * s.coils;
      for (let i = 0; i <= n; ++i) {
        const a = 2 * Math.PI * s.coils * i / n;
        points.push(new THREE.Vector3(s.radius * Math.cos(a), i / n, s.radius * Math.sin(a)));
      }
      object = new THREE.Line(new THREE.BufferGeometry().setFromPoints(points),
                              new THREE.LineBasicMaterial({ color: s.color }));
      world.add(object);
      springs.push({ shape: s, object });
      object.name = s.name;
      continue;
    }
    object.name = s.name;
    holder(s.body).add(placed(object, s));
  }

  // --- poses ----------------------------------------------------------------
  const position = new THREE.Vector3(), q0 = new THREE.Quaternion(), q1 = new THREE.Quaternion();
  function frameAt(t) {  // the frame at or before t
    let lo = 0, hi = times.length - 1;
    if (t <= times[0]) return 0;
    if (t >= times[hi]) return hi;
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (times[mid] <= t) lo = mid; else hi = mid;
    }
    return lo;
  }
  function pose(frame, b, out, quaternion) {
    const k = 7 * (frame * nb + b);
    out.set(poses[k], poses[k + 1], poses[k + 2]);
    quaternion.set(poses[k + 3], poses[k + 4], poses[k + 5], poses[k + 6]);
  }
  function show(t) {
    const f = frameAt(t);
    const g = Math.min(f + 1, times.length - 1);
    const w = g > f ? Math.min(1, Math.max(0, (t - times[f]) / (times[g] - times[f]))) : 0;
    const p1 = new THREE.Vector3();
    for (let b = 0; b < nb; ++b) {
      pose(f, b, position, q0);
      pose(g, b, p1, q1);
      bodies[b].position.copy(position.lerp(p1, w));
      bodies[b].quaternion.copy(q0.slerp(q1, w));
    }
    world.updateMatrixWorld(true);
    for (const { shape: s, object } of springs) {
      const a = new THREE.Vector3(...s.point1).applyMatrix4(holder(s.body).matrixWorld);
      const b = new THREE.Vector3(...s.point2).applyMatrix4(holder(s.body2).matrixWorld);
      const d = b.clone().sub(a);
      const length = Math.max(d.length(), 1e-9);
      object.position.copy(a);
      object.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), d.divideScalar(length));
      object.scale.set(1, length, 1);
    }
    current = t;
    clock.textContent = 't = ' + t.toFixed(3) + ' s';
    slider.value = String(Math.round(1000 * (t - times[0]) / Math.max(times[times.length - 1] - times[0], 1e-12)));
  }

  // --- controls -------------------------------------------------------------
  const clock = document.getElementById('clock');
  const slider = document.getElementById('time');
  const playButton = document.getElementById('play');
  const speed = document.getElementById('speed');
  const loop = document.getElementById('loop');
  let current = times[0], playing = false, last = null;
  playButton.onclick = () => { playing = !playing; playButton.textContent = playing ? 'pause' : 'play'; last = null; };
  slider.oninput = () => show(times[0] + (times[times.length - 1] - times[0]) * Number(slider.value) / 1000);
  function fitView() {
    show(current);
    const box = new THREE.Box3().setFromObject(world);
    const centre = box.isEmpty() ? new THREE.Vector3() : box.getCenter(new THREE.Vector3());
    const size = box.isEmpty() ? 1 : Math.max(box.getSize(new THREE.Vector3()).length(), 1e-3);
    camera.position.copy(centre).add(new THREE.Vector3(1.5, -1.0, 0.7).multiplyScalar(size));
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

  function tick(now) {
    if (playing) {
      if (last !== null) {
        let t = current + Number(speed.value) * (now - last) / 1000;
        const end = times[times.length - 1];
        if (t > end) {
          if (loop.checked) t = times[0];
          else { t = end; playing = false; playButton.textContent = 'play'; }
        }
        show(t);
      }
      last = now;
    }
    controls.update();
    renderer.render(world, camera);
    requestAnimationFrame(tick);
  }

  resize();
  fitView();
  document.title = scene.title;
  document.getElementById('title').textContent = scene.title;

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
      const data = new Uint8Array(4 * w * h);
      gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, data);
      let differing = 0;
      for (let i = 0; i < data.length; i += 4)
        if (Math.abs(data[i] - 242) + Math.abs(data[i + 1] - 242) + Math.abs(data[i + 2] - 242) > 30) ++differing;
      const g = bodies[scene.bodies.indexOf(body)];
      const at = new THREE.Vector3().setFromMatrixPosition(g.matrixWorld).project(camera);
      const x = Math.round((at.x + 1) / 2 * (w - 1)), y = Math.round((at.y + 1) / 2 * (h - 1));
      const k = 4 * (y * w + x);
      return { share: differing / (w * h), colour: [data[k], data[k + 1], data[k + 2]] };
    },
    errors,
  };
  const test = /#test=([^&]*)/.exec(window.location.hash);
  if (test) {
    const report = { frames: times.length, seen: [] };
    for (const t of test[1].split(',').map(Number)) {
      window.mechflowTest.seek(t);
      const seen = { t, transforms: window.mechflowTest.transforms(), pixels: {} };
      for (const label of scene.bodies) seen.pixels[label] = window.mechflowTest.pixels(label);
      report.seen.push(seen);
    }
    report.errors = errors;
    document.getElementById('mechflow-test').textContent = JSON.stringify(report);
    requestAnimationFrame(() => renderer.render(world, camera));  // the page shows the last time seen
  } else {
    const start = /#t=([0-9.eE+-]+)/.exec(window.location.hash);  // a link to a time: NAME.html#t=1.5
    if (start) show(Number(start[1]));
    requestAnimationFrame(tick);
  }
})();
