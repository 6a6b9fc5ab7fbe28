// The curvenet browser viewer: the library runs as WebAssembly (pkg/curvenet.wasm, built by
// build.sh from viewer/wasm); three.js displays its output. No numerics here: surfacing,
// curvature, colour maps and the rotation of normals all come from the library.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const $ = (id) => document.getElementById(id);
const enc = new TextEncoder();
const dec = new TextDecoder();

// ---- The library, in Web Workers (worker.js) ----
// Two workers: `util` for the quick calls (examples, curve lists, turned normals) and `solver`
// for surfaces and exports. A newer solve while one runs ends the old one: the solver worker
// is terminated and a new one started (the module stays compiled), so the page never waits
// for an answer nobody wants.
let wasmModule = null;
class Worker1 {
  constructor() { this.next = 1; this.pending = new Map(); this.start(); }
  start() {
    this.worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
    this.worker.onmessage = (e) => {
      const { id, ok, result, error, curve } = e.data;
      const p = this.pending.get(id);
      if (!p) return;
      this.pending.delete(id);
      if (ok) p.resolve(result);
      else { const err = new Error(error); err.curve = curve; p.reject(err); }
    };
    this.ready = this.post('init', [], { module: wasmModule });
  }
  post(op, args, extra = {}) {
    const id = this.next++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
      this.worker.postMessage({ id, op, args, ...extra });
    });
  }
  async call(op, ...args) { await this.ready; return this.post(op, args); }
  /** Ends what runs (its callers get a `cancelled` error) and starts afresh. */
  restart() {
    this.worker.terminate();
    for (const p of this.pending.values()) { const e = new Error('cancelled'); e.cancelled = true; p.reject(e); }
    this.pending.clear();
    this.start();
  }
}
let util = null, solver = null;
async function loadWasm() {
  wasmModule = await WebAssembly.compile(await (await fetch('pkg/curvenet.wasm')).arrayBuffer());
  util = new Worker1();
  solver = new Worker1();
}
const FORMATS = { json: 0, obj: 1, net: 2 };

// ---- State ----
const state = { name: 'sphere', format: 0, base: '', result: null, fitted: false, curves: null, errorCurve: -1, original: null };

// ---- three.js ----
const view = $('view');
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
renderer.setClearColor(0xffffff);
view.appendChild(renderer.domElement);
const scene = new THREE.Scene();
const camera = new THREE.PerspectiveCamera(28, 1, 0.01, 1000);
camera.up.set(0, 0, 1);
const controls = new OrbitControls(camera, renderer.domElement);
controls.addEventListener('change', draw);

// The same shading as the library's PNG renderer (src/render): two lights in view space, a
// Blinn–Phong highlight; mode 0 shaded, 1 vertex colours, 2 isophotes (zebra of the reflected
// view direction).
const material = new THREE.ShaderMaterial({
  uniforms: { mode: { value: 1 }, stripes: { value: 12 } },
  side: THREE.DoubleSide,
  polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
  vertexShader: `
    attribute vec3 vcolor;
    varying vec3 vNormal;
    varying vec3 vColor;
    void main() {
      vNormal = normalize(normalMatrix * normal);
      vColor = vcolor;
      gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
    }`,
  fragmentShader: `
    uniform int mode;
    uniform float stripes;
    varying vec3 vNormal;
    varying vec3 vColor;
    void main() {
      vec3 n = normalize(vNormal);
      float tint = 1.0;
      if (!gl_FrontFacing) { n = -n; tint = 0.75; }
      vec3 key = normalize(vec3(-0.45, 0.6, 0.66));
      vec3 fill = normalize(vec3(0.5, -0.3, 0.8));
      float diffuse = 0.75 * max(dot(n, key), 0.0) + 0.3 * max(dot(n, fill), 0.0);
      float spec = pow(max(dot(n, normalize(key + vec3(0.0, 0.0, 1.0))), 0.0), 48.0);
      vec3 c;
      if (mode == 0) {
        c = vec3(0.72, 0.76, 0.84) * (0.22 + 0.85 * diffuse) + 0.35 * spec;
      } else if (mode == 1) {
        c = vColor * (0.5 + 0.55 * diffuse) + 0.12 * spec;
      } else {
        vec3 r = 2.0 * n.z * n - vec3(0.0, 0.0, 1.0);
        float phi = asin(clamp(r.y, -1.0, 1.0));
        float band = floor((phi / 3.14159265 + 0.5) * stripes);
        float v = mod(band, 2.0) < 0.5 ? 0.95 : 0.08;
        c = vec3(v) * (0.75 + 0.25 * diffuse);
      }
      gl_FragColor = vec4(c * tint, 1.0);
    }`,
});
const mesh = new THREE.Mesh(new THREE.BufferGeometry(), material);
scene.add(mesh);
const curveLines = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0x1a1a1a }));
scene.add(curveLines);
const selectedLine = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0xff8c00, depthTest: false }));
const errorLine = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0xe00000, depthTest: false }));
selectedLine.renderOrder = errorLine.renderOrder = 1;
scene.add(selectedLine, errorLine);

function resize() {
  const w = view.clientWidth, h = view.clientHeight;
  renderer.setSize(w, h);
  camera.aspect = w / Math.max(h, 1);
  camera.updateProjectionMatrix();
  draw();
}
function draw() { renderer.render(scene, camera); }
window.addEventListener('resize', resize);

// ---- Display of a result ----
function colorsFor(r) {
  const c = $('coloring').value;
  if (c === 'curvature') return r.curvature;
  if (c === 'deviation' && r.deviation.length) return r.deviation;
  return new Float32Array(r.positions.length).fill(0.8);
}
function updateColoring() {
  const r = state.result;
  if (!r) return;
  const c = $('coloring').value;
  material.uniforms.mode.value = c === 'shaded' ? 0 : c === 'isophotes' ? 2 : (c === 'deviation' && !r.deviation.length) ? 0 : 1;
  mesh.geometry.setAttribute('vcolor', new THREE.BufferAttribute(colorsFor(r), 3));
  curveLines.visible = $('curves').checked;
  const legend = $('legend');
  legend.hidden = !(c === 'curvature' || (c === 'deviation' && r.deviation.length));
  if (c === 'curvature') {
    $('legend-bar').style.background = 'linear-gradient(to right, rgb(59,76,192), rgb(141,176,254), rgb(221,221,221), rgb(244,154,123), rgb(180,4,38))';
    $('legend-min').textContent = (-r.range).toPrecision(3);
    $('legend-mid').textContent = '0';
    $('legend-max').textContent = '+' + r.range.toPrecision(3);
  } else if (c === 'deviation') {
    $('legend-bar').style.background = 'linear-gradient(to right, rgb(68,1,84), rgb(65,68,135), rgb(42,120,142), rgb(34,168,132), rgb(122,209,81), rgb(253,231,37))';
    $('legend-min').textContent = '0°';
    $('legend-mid').textContent = (r.deviationMax / 2).toPrecision(3) + '°';
    $('legend-max').textContent = r.deviationMax.toPrecision(3) + '°';
  }
  if (c === 'deviation' && !r.deviation.length) $('message').textContent = 'This method has no propagated normals N*: shown shaded.';
  draw();
}

/** The network's curves as line segments; `segCurve[k]`: the curve of segment k. */
let segCurve = new Uint32Array(0);
function showCurves(c) {
  const seg = [], owner = [];
  for (let k = 0; k + 1 < c.offsets.length; k++) {
    for (let i = c.offsets[k]; i + 1 < c.offsets[k + 1]; i++) {
      seg.push(c.curves[3 * i], c.curves[3 * i + 1], c.curves[3 * i + 2], c.curves[3 * i + 3], c.curves[3 * i + 4], c.curves[3 * i + 5]);
      owner.push(k);
    }
  }
  const cg = new THREE.BufferGeometry();
  cg.setAttribute('position', new THREE.BufferAttribute(new Float32Array(seg), 3));
  curveLines.geometry.dispose();
  curveLines.geometry = cg;
  segCurve = Uint32Array.from(owner);
  state.curves = c;
  highlight();
}

/** Draws the selected curve (orange) and the curve an error names (red) over the others. */
function highlight() {
  const c = state.curves;
  const pick = (k) => {
    if (!c || !(k >= 0) || k + 1 >= c.offsets.length) return new Float32Array(0);
    const seg = [];
    for (let i = c.offsets[k]; i + 1 < c.offsets[k + 1]; i++) {
      for (let j = 0; j < 6; j++) seg.push(c.curves[3 * i + j]);
    }
    return new Float32Array(seg);
  };
  for (const [line, k] of [[selectedLine, $('curve').value === '' ? -1 : +$('curve').value], [errorLine, state.errorCurve]]) {
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(pick(k), 3));
    line.geometry.dispose();
    line.geometry = g;
  }
  $('message').dataset.errorCurve = String(state.errorCurve);
  draw();
}

function fit(g) {
  g.computeBoundingSphere();
  const s = g.boundingSphere;
  if (!s || !(s.radius > 0)) return;
  controls.target.copy(s.center);
  const d = 1.1 * s.radius / Math.sin(THREE.MathUtils.degToRad(camera.fov / 2));
  const dir = new THREE.Vector3(Math.cos(0.52) * Math.cos(0.44), Math.sin(0.52) * Math.cos(0.44), Math.sin(0.44));
  camera.position.copy(s.center).addScaledVector(dir, d);
  camera.near = d / 100; camera.far = d * 10;
  camera.updateProjectionMatrix();
  controls.update();
  raycaster.params.Line.threshold = 0.015 * s.radius;
  state.fitted = true;
}

function show(r) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(r.positions, 3));
  g.setAttribute('normal', new THREE.BufferAttribute(r.normals, 3));
  g.setIndex(new THREE.BufferAttribute(r.faces, 1));
  mesh.geometry.dispose();
  mesh.geometry = g;
  mesh.visible = true;
  showCurves(r);
  if (!state.fitted) fit(g);
  updateColoring();
}

// ---- Solving ----
async function networkText() {
  const angle = +$('angle').value;
  const curve = +$('curve').value;
  if (!angle || !(curve >= 0)) return { text: state.base, format: state.format };
  return { text: await util.call('rotate', state.base, state.format, curve, angle), format: 0 };
}

/** Shows that a solve runs (a bar and the seconds so far), or that none does. */
let ticker = 0;
function solvingIndicator(on) {
  const p = $('progress');
  p.hidden = !on;
  $('stats').dataset.solving = on ? '1' : '0';
  clearInterval(ticker);
  if (on) {
    const t0 = performance.now();
    $('progress-text').textContent = 'solving…';
    ticker = setInterval(() => { $('progress-text').textContent = `solving… ${((performance.now() - t0) / 1000).toFixed(1)} s`; }, 100);
  }
  for (const b of document.querySelectorAll('.download-mesh')) b.disabled = on || !state.result;
}

/** Solves the current network with the current controls. A solve asked for while another runs
 * ends that one (its worker is restarted): the newest request wins. */
let solveCount = 0;
async function solve() {
  const mine = ++solveCount;
  if ($('stats').dataset.solving === '1') solver.restart();
  solvingIndicator(true);
  $('message').textContent = '';
  try {
    const vertices = Math.round(10 ** +$('vertices').value);
    const soft = +$('soft').value;
    const t0 = performance.now();
    const net = await networkText();
    if (mine !== solveCount) return; // a newer request came while the normals were turned
    const result = await solver.call('surface', net.text, net.format, +$('method').value, vertices, soft, +$('quality').value);
    if (mine !== solveCount) return;
    const ms = performance.now() - t0;
    state.result = result;
    state.errorCurve = -1;
    show(result);
    const stats = $('stats');
    stats.dataset.vertices = String(result.vertices);
    stats.dataset.faces = String(result.faceCount);
    stats.dataset.patches = String(result.patches);
    stats.textContent = `${result.vertices} vertices (${result.curveVertices} on curves), ${result.faceCount} faces, ${result.patches} patches, ${ms.toFixed(0)} ms`;
    if (result.warnings) $('message').textContent = 'warning: ' + result.warnings;
  } catch (e) {
    if (e.cancelled || mine !== solveCount) return;
    state.result = null;
    mesh.visible = false;
    state.errorCurve = e.curve ?? -1;
    $('message').textContent = e.message;
    highlight();
  } finally {
    if (mine === solveCount) solvingIndicator(false);
  }
}

/** Fills the curve selector with the curves of the network `body`; their number. */
async function listCurves(body, format) {
  const sel = $('curve');
  sel.innerHTML = '';
  const count = await util.call('curveCount', body, format);
  for (let i = 0; i < count; i++) sel.add(new Option(`curve ${i}`, String(i)));
  return count;
}

async function setNetwork(name, body, format) {
  state.name = name; state.base = body; state.format = format; state.fitted = false;
  state.original = null; $('fill-all').disabled = true;
  state.result = null; state.errorCurve = -1;
  // A network that does not parse gets no curve list; the solve reports the error with its
  // line and column.
  const count = await listCurves(body, format);
  $('angle').value = 0;
  updateLabels();
  // The curves at once, the surface when it is solved.
  if (count > 0) {
    try {
      const c = await util.call('curves', body, format);
      mesh.visible = false;
      showCurves(c);
      fit(curveLines.geometry);
    } catch { /* the solve reports it */ }
  }
  solve();
}

async function loadExample(name) {
  try {
    setNetwork(name, await util.call('example', name), 0);
  } catch (e) {
    $('message').textContent = e.message;
  }
}

async function loadFile(file) {
  const ext = file.name.split('.').pop().toLowerCase();
  if (!(ext in FORMATS)) { $('message').textContent = `${file.name}: use a .json, .obj or .net network`; return; }
  setNetwork(file.name, await file.text(), FORMATS[ext]);
}

// ---- Downloads ----
function save(bytes, name, type) {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(new Blob([bytes], { type }));
  a.download = name;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}
const stem = () => state.name.replace(/\.[^.]*$/, '') || 'network';
const MESH_FORMATS = { ply: [0, 'application/octet-stream'], obj: [1, 'text/plain'], glb: [2, 'model/gltf-binary'] };
for (const [ext, [code, type]] of Object.entries(MESH_FORMATS)) {
  $(`download-${ext}`).addEventListener('click', async () => {
    try { save(await solver.call('exportMesh', code), `${stem()}.${ext}`, type); } catch (e) { $('message').textContent = e.message; }
  });
}
$('download-network').addEventListener('click', async () => {
  try {
    // The network with the turned normals, as JSON (the library's writer).
    const curve = +$('curve').value;
    const json = await util.call('rotate', state.base, state.format, curve >= 0 ? curve : 0, +$('angle').value || 0);
    save(json, `${stem()}-edited.json`, 'application/json');
  } catch (e) { $('message').textContent = e.message; }
});

// ---- Picking a curve in the view ----
const raycaster = new THREE.Raycaster();
/** The curve under the pixel (x, y) of the canvas, or -1. */
function curveAt(x, y) {
  const rect = renderer.domElement.getBoundingClientRect();
  const ndc = new THREE.Vector2(2 * (x - rect.left) / rect.width - 1, 1 - 2 * (y - rect.top) / rect.height);
  raycaster.setFromCamera(ndc, camera);
  const hit = raycaster.intersectObject(curveLines, false)[0];
  return hit ? segCurve[hit.index / 2 | 0] ?? -1 : -1;
}
function selectCurve(k) {
  if (!(k >= 0) || k >= $('curve').options.length) return;
  if (+$('curve').value !== k) {
    $('curve').value = String(k);
    if (+$('angle').value !== 0) { $('angle').value = 0; updateLabels(); solve(); }
  }
  highlight();
}
// ---- Leaving a patch open ----
/** The patch of the surface under the pixel (x, y), or -1. */
function patchAt(x, y) {
  if (!state.result || !mesh.visible) return -1;
  const rect = renderer.domElement.getBoundingClientRect();
  const ndc = new THREE.Vector2(2 * (x - rect.left) / rect.width - 1, 1 - 2 * (y - rect.top) / rect.height);
  raycaster.setFromCamera(ndc, camera);
  const hit = raycaster.intersectObject(mesh, false)[0];
  return hit ? state.result.facePatch[hit.faceIndex] ?? -1 : -1;
}
/** The network with its cycles changed by the library — `op` `openPatch` (patch `k` left open)
 * or `fillCycle` (the open cycle along curve `k` filled) — then solved. The edit is made on
 * the network as shown (its turned normals included) and only while no solve runs (the patch
 * and curve numbers are the surface's on the screen). */
async function editCycles(op, k) {
  if (!(k >= 0)) return;
  if ($('stats').dataset.solving === '1' || !state.result) { $('message').textContent = 'wait for the surface, then click again'; return; }
  const before = state.base;
  try {
    const vertices = Math.round(10 ** +$('vertices').value);
    const opts = [+$('method').value, vertices, +$('quality').value];
    let net = await networkText();
    const shown = $('curve').options.length;
    if (op === 'fillCycle' && state.original === null) {
      // The first edit: the network as surfaced (consolidated, with its cycles). Where that
      // renumbered the curves, the curve clicked is not the one to fill: show it, ask again.
      const surfaced = await util.call('cycles', net.text, net.format, ...opts);
      if (await util.call('curveCount', surfaced, 0) !== shown) {
        if (state.base !== before) return;
        commit(surfaced);
        $('message').textContent = 'the strokes were consolidated into other curves: click the curve again';
        return;
      }
      net = { text: surfaced, format: 0 };
    }
    const json = await util.call(op, net.text, net.format, k, ...opts);
    if (state.base !== before) return; // a new network or edit came meanwhile
    commit(json);
  } catch (e) {
    $('message').textContent = e.message;
  }
}
/** Makes `json` (an edited network) the one shown, the one before the first edit kept. */
function commit(json) {
  if (state.original === null) state.original = { body: state.base, format: state.format };
  state.base = json; state.format = 0;
  $('fill-all').disabled = false;
  // Consolidation may have joined or merged curves: the selector lists the network's own.
  listCurves(json, 0).then(() => { $('angle').value = 0; updateLabels(); solve(); });
}
$('fill-all').addEventListener('click', () => {
  if (state.original === null) return;
  state.base = state.original.body; state.format = state.original.format;
  state.original = null; $('fill-all').disabled = true;
  listCurves(state.base, state.format).then(() => { $('angle').value = 0; updateLabels(); solve(); });
});

let downAt = null;
renderer.domElement.addEventListener('pointerdown', (e) => { downAt = [e.clientX, e.clientY]; });
renderer.domElement.addEventListener('pointerup', (e) => {
  // A click, not the end of a drag of the orbit controls.
  if (downAt && Math.hypot(e.clientX - downAt[0], e.clientY - downAt[1]) < 4) {
    const mode = $('click-mode').value;
    if (mode === 'open') editCycles('openPatch', patchAt(e.clientX, e.clientY));
    else if (mode === 'fill') editCycles('fillCycle', curveAt(e.clientX, e.clientY));
    else selectCurve(curveAt(e.clientX, e.clientY));
  }
  downAt = null;
});
/** For tests: the page pixel of sample `i` of curve `k`. */
window.curvenetViewer = {
  screenPoint(k, i) {
    const c = state.curves;
    const j = c.offsets[k] + i;
    const v = new THREE.Vector3(c.curves[3 * j], c.curves[3 * j + 1], c.curves[3 * j + 2]).project(camera);
    const rect = renderer.domElement.getBoundingClientRect();
    return [rect.left + (v.x + 1) / 2 * rect.width, rect.top + (1 - v.y) / 2 * rect.height];
  },
};

// ---- Controls ----
function updateLabels() {
  $('vertices-out').textContent = Math.round(10 ** +$('vertices').value);
  const s = +$('soft').value;
  $('soft-out').textContent = s > 0 ? `S = ${s}` : 'off (hard)';
  $('angle-out').textContent = `${$('angle').value}°`;
}
let timer = 0;
const debounced = () => { updateLabels(); clearTimeout(timer); timer = setTimeout(solve, 120); };
$('example').addEventListener('change', (e) => loadExample(e.target.value));
$('file').addEventListener('change', (e) => e.target.files[0] && loadFile(e.target.files[0]));
for (const id of ['vertices', 'soft', 'angle']) $(id).addEventListener('input', debounced);
for (const id of ['method', 'quality', 'curve']) $(id).addEventListener('change', () => { if (id === 'curve') { $('angle').value = 0; highlight(); } debounced(); });
$('coloring').addEventListener('change', () => { $('message').textContent = ''; updateColoring(); });
$('curves').addEventListener('change', updateColoring);
const drop = $('drop');
for (const ev of ['dragenter', 'dragover']) document.addEventListener(ev, (e) => { e.preventDefault(); drop.classList.add('over'); });
document.addEventListener('dragleave', () => drop.classList.remove('over'));
document.addEventListener('drop', (e) => {
  e.preventDefault();
  drop.classList.remove('over');
  const f = e.dataTransfer.files[0];
  if (f) loadFile(f);
});

await loadWasm();
resize();
updateLabels();
loadExample($('example').value);
