// The curvenet browser viewer: the library runs as WebAssembly (pkg/curvenet.wasm, built by
// build.sh from viewer/wasm); three.js displays its output. No numerics here: surfacing,
// curvature, colour maps and the rotation of normals all come from the library.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const $ = (id) => document.getElementById(id);
const enc = new TextEncoder();
const dec = new TextDecoder();

// ---- The WebAssembly module (plain C ABI: see viewer/wasm/src/lib.rs) ----
let wasm = null;
async function loadWasm() {
  const bytes = await (await fetch('pkg/curvenet.wasm')).arrayBuffer();
  const { instance } = await WebAssembly.instantiate(bytes, {});
  wasm = instance.exports;
}
function withText(s, f) {
  const b = enc.encode(s);
  const p = wasm.cn_alloc(b.length);
  new Uint8Array(wasm.memory.buffer, p, b.length).set(b);
  try { return f(p, b.length); } finally { wasm.cn_free(p, b.length); }
}
const text = () => dec.decode(new Uint8Array(wasm.memory.buffer, wasm.cn_text_ptr(), wasm.cn_text_len()).slice());
function buffer(kind, Type) {
  const n = wasm.cn_buffer_len(kind);
  return new Type(wasm.memory.buffer, wasm.cn_buffer_ptr(kind), n).slice();
}
/** Runs a library call; a trap (a bug, not bad input) reloads the module and reports it. */
async function call(f) {
  try { return f(); } catch (e) { await loadWasm(); throw new Error(`internal error: ${e.message}`); }
}
const FORMATS = { json: 0, obj: 1, net: 2 };

// ---- State ----
const state = { name: 'sphere', format: 0, base: '', result: null, fitted: false };

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

function show(r) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(r.positions, 3));
  g.setAttribute('normal', new THREE.BufferAttribute(r.normals, 3));
  g.setIndex(new THREE.BufferAttribute(r.faces, 1));
  mesh.geometry.dispose();
  mesh.geometry = g;
  const seg = [];
  for (let k = 0; k + 1 < r.offsets.length; k++) {
    for (let i = r.offsets[k]; i + 1 < r.offsets[k + 1]; i++) {
      seg.push(r.curves[3 * i], r.curves[3 * i + 1], r.curves[3 * i + 2], r.curves[3 * i + 3], r.curves[3 * i + 4], r.curves[3 * i + 5]);
    }
  }
  const cg = new THREE.BufferGeometry();
  cg.setAttribute('position', new THREE.BufferAttribute(new Float32Array(seg), 3));
  curveLines.geometry.dispose();
  curveLines.geometry = cg;
  if (!state.fitted) {
    g.computeBoundingSphere();
    const s = g.boundingSphere;
    controls.target.copy(s.center);
    const d = 1.1 * s.radius / Math.sin(THREE.MathUtils.degToRad(camera.fov / 2));
    const dir = new THREE.Vector3(Math.cos(0.52) * Math.cos(0.44), Math.sin(0.52) * Math.cos(0.44), Math.sin(0.44));
    camera.position.copy(s.center).addScaledVector(dir, d);
    camera.near = d / 100; camera.far = d * 10;
    camera.updateProjectionMatrix();
    controls.update();
    state.fitted = true;
  }
  updateColoring();
}

// ---- Solving ----
function networkText() {
  const angle = +$('angle').value;
  const curve = +$('curve').value;
  if (!angle || !(curve >= 0)) return { text: state.base, format: state.format };
  const rc = withText(state.base, (p, n) => wasm.cn_rotate_normals(p, n, state.format, curve, angle));
  if (rc !== 0) throw new Error(text());
  return { text: text(), format: 0 };
}

let solving = false, again = false;
async function solve() {
  if (solving) { again = true; return; }
  solving = true;
  $('message').textContent = '';
  try {
    const vertices = Math.round(10 ** +$('vertices').value);
    const soft = +$('soft').value;
    const t0 = performance.now();
    const result = await call(() => {
      const net = networkText();
      const rc = withText(net.text, (p, n) => wasm.cn_surface(p, n, net.format, +$('method').value, vertices, soft, +$('quality').value));
      if (rc !== 0) throw new Error(text());
      return {
        positions: buffer(0, Float32Array), faces: buffer(1, Uint32Array), normals: buffer(2, Float32Array),
        curvature: buffer(3, Float32Array), deviation: buffer(4, Float32Array),
        curves: buffer(5, Float32Array), offsets: buffer(6, Uint32Array),
        vertices: wasm.cn_stat(0), faceCount: wasm.cn_stat(1), curveVertices: wasm.cn_stat(2), patches: wasm.cn_stat(3),
        range: wasm.cn_stat(4), deviationMax: wasm.cn_stat(5), warnings: text(),
      };
    });
    const ms = performance.now() - t0;
    state.result = result;
    show(result);
    const stats = $('stats');
    stats.dataset.vertices = String(result.vertices);
    stats.dataset.faces = String(result.faceCount);
    stats.textContent = `${result.vertices} vertices (${result.curveVertices} on curves), ${result.faceCount} faces, ${result.patches} patches, ${ms.toFixed(0)} ms`;
    if (result.warnings) $('message').textContent = 'warning: ' + result.warnings;
  } catch (e) {
    $('message').textContent = e.message;
  } finally {
    solving = false;
    if (again) { again = false; solve(); }
  }
}

function setNetwork(name, body, format) {
  // A network that does not parse gets no curve list; the solve reports the error with its
  // line and column.
  const count = withText(body, (p, n) => wasm.cn_curve_count(p, n, format));
  state.name = name; state.base = body; state.format = format; state.fitted = false;
  const sel = $('curve');
  sel.innerHTML = '';
  for (let i = 0; i < (count === 0xffffffff ? 0 : count); i++) sel.add(new Option(`curve ${i}`, String(i)));
  $('angle').value = 0;
  updateLabels();
  solve();
}

function loadExample(name) {
  const rc = withText(name, (p, n) => wasm.cn_example(p, n));
  if (rc !== 0) { $('message').textContent = text(); return; }
  setNetwork(name, text(), 0);
}

async function loadFile(file) {
  const ext = file.name.split('.').pop().toLowerCase();
  if (!(ext in FORMATS)) { $('message').textContent = `${file.name}: use a .json, .obj or .net network`; return; }
  setNetwork(file.name, await file.text(), FORMATS[ext]);
}

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
for (const id of ['method', 'quality', 'curve']) $(id).addEventListener('change', () => { if (id === 'curve') $('angle').value = 0; debounced(); });
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
