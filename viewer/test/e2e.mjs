// End-to-end test of the viewer in headless Chromium (Debian's /usr/bin/chromium driven by
// playwright-core): loads the page, which surfaces the sphere example in WebAssembly, waits
// for the surface, checks the vertex count on the page against the command-line tool's count
// for the same options, checks that the canvas shows a red (positive curvature) surface, turns
// a curve's normals on the cylinder and checks the re-solve, loads a 3D sketch without normals
// (OBJ edge soup) as a file and checks its vertex count against the CLI's, shows an error's
// curve, selects a curve by a click in the view, counts the frames the page paints during a
// 100k-vertex default solve (the solve runs in a Web Worker), downloads the mesh (PLY, GLB) and
// the edited network, checks that a newer request ends an older solve, and saves screenshots
// in viewer/test/out/.
import { chromium } from 'playwright-core';
import http from 'node:http';
import fs from 'node:fs';
import path from 'node:path';
import os from 'node:os';
import { execFileSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const root = path.resolve(here, '..');
const repo = path.resolve(root, '..');
const out = path.join(here, 'out');
fs.mkdirSync(out, { recursive: true });

function fail(msg) { console.error(`FAIL: ${msg}`); process.exitCode = 1; throw new Error(msg); }

// The command-line tool's vertex count for the viewer's defaults (fast, 10^4 vertices).
const cli = path.join(repo, 'target', 'release', 'curvenet');
const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'curvenet-e2e-'));
execFileSync(cli, ['example', 'sphere', '-o', path.join(tmp, 'sphere.json')]);
execFileSync(cli, ['surface', path.join(tmp, 'sphere.json'), '-o', path.join(tmp, 's.ply'), '--fast', '--vertices', '10000', '--stats', path.join(tmp, 's.json'), '-q']);
const expected = JSON.parse(fs.readFileSync(path.join(tmp, 's.json'), 'utf8')).vertices;

const types = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.css': 'text/css', '.wasm': 'application/wasm', '.json': 'application/json' };
const server = http.createServer((req, res) => {
  const url = decodeURIComponent(new URL(req.url, 'http://x').pathname);
  const file = path.join(root, url === '/' ? 'index.html' : url);
  if (!file.startsWith(root) || !fs.existsSync(file) || fs.statSync(file).isDirectory()) { res.writeHead(404); res.end(); return; }
  res.writeHead(200, { 'content-type': types[path.extname(file)] || 'application/octet-stream' });
  fs.createReadStream(file).pipe(res);
});
await new Promise((r) => server.listen(0, '127.0.0.1', r));
const url = `http://127.0.0.1:${server.address().port}/`;

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
    '--disable-component-update', '--disable-sync', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
});
try {
  const page = await browser.newPage({ viewport: { width: 1200, height: 800 } });
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  await page.goto(url);
  await page.waitForFunction(() => +document.getElementById('stats').dataset.vertices > 0, null, { timeout: 120000 });
  const shown = +(await page.getAttribute('#stats', 'data-vertices'));
  console.log(`page: ${await page.textContent('#stats')}`);
  if (shown !== expected) fail(`the page reports ${shown} vertices, the CLI ${expected}`);
  const message = await page.textContent('#message');
  if (message.trim()) fail(`message on the page: ${message}`);
  // The canvas: how much of it is surface, and how much of that is red (H > 0 on a sphere).
  const pixels = await page.evaluate(() => {
    const gl = document.querySelector('#view canvas');
    const c = document.createElement('canvas');
    c.width = gl.width; c.height = gl.height;
    const ctx = c.getContext('2d');
    ctx.drawImage(gl, 0, 0);
    const d = ctx.getImageData(0, 0, c.width, c.height).data;
    let surface = 0, red = 0;
    for (let i = 0; i < d.length; i += 4) {
      if (d[i] > 250 && d[i + 1] > 250 && d[i + 2] > 250) continue;
      surface++;
      if (d[i] > d[i + 1] + 40 && d[i] > d[i + 2] + 40) red++;
    }
    return { total: d.length / 4, surface, red };
  });
  console.log(`canvas: ${pixels.surface} of ${pixels.total} pixels are surface, ${pixels.red} red`);
  if (pixels.surface < 0.1 * pixels.total) fail('the surface covers less than 10% of the canvas');
  if (pixels.red < 0.8 * pixels.surface) fail('the sphere is not red in the curvature colouring');
  await page.screenshot({ path: path.join(out, 'sphere.png') });

  // The barrel experiment: the cylinder, then curve 0's normals turned by 30 degrees.
  await page.selectOption('#example', 'cylinder');
  await page.waitForFunction(() => document.getElementById('stats').textContent.includes('faces') && document.getElementById('curve').options.length === 2);
  const before = await page.textContent('#stats');
  await page.fill('#angle', '30');
  await page.dispatchEvent('#angle', 'input');
  await page.waitForFunction((b) => document.getElementById('stats').textContent !== b, before, { timeout: 60000 });
  console.log(`after turning curve 0 by 30°: ${await page.textContent('#stats')}`);
  await page.screenshot({ path: path.join(out, 'cylinder-turned.png') });

  // A 3D sketch without normals (an OBJ edge soup) loaded as a file: surfaced with inferred
  // normals, as the command line does.
  const sketch = path.join(repo, 'data', 'sketches', 'teapot.obj');
  execFileSync(cli, ['surface', sketch, '-o', path.join(tmp, 't.ply'), '--fast', '--vertices', '10000', '--stats', path.join(tmp, 't.json'), '-q'], { stdio: ['ignore', 'ignore', 'pipe'] });
  const sketchVertices = JSON.parse(fs.readFileSync(path.join(tmp, 't.json'), 'utf8')).vertices;
  const beforeSketch = await page.textContent('#stats');
  await page.setInputFiles('#file', sketch);
  await page.waitForFunction((b) => document.getElementById('stats').textContent !== b && +document.getElementById('stats').dataset.vertices > 0, beforeSketch, { timeout: 120000 });
  const sketchShown = +(await page.getAttribute('#stats', 'data-vertices'));
  console.log(`teapot sketch (no normals): ${await page.textContent('#stats')}`);
  if (sketchShown !== sketchVertices) fail(`the page reports ${sketchShown} vertices for the sketch, the CLI ${sketchVertices}`);
  await page.screenshot({ path: path.join(out, 'teapot-sketch.png') });

  // An error names a curve: the message says so and the curve is highlighted.
  const sphereNet = JSON.parse(fs.readFileSync(path.join(tmp, 'sphere.json'), 'utf8'));
  sphereNet.curves[1].normals[5] = [0, 0, 0];
  const badFile = path.join(tmp, 'bad-normal.json');
  fs.writeFileSync(badFile, JSON.stringify(sphereNet));
  await page.setInputFiles('#file', badFile);
  await page.waitForFunction(() => document.getElementById('message').dataset.errorCurve !== '-1', null, { timeout: 60000 });
  const badMessage = await page.textContent('#message');
  const errorCurve = await page.getAttribute('#message', 'data-error-curve');
  console.log(`error on curve ${errorCurve}: ${badMessage}`);
  // A named curve is named by its name in messages, an unnamed one by its index.
  const label = sphereNet.curves[1].name ? `curve "${sphereNet.curves[1].name}"` : 'curve 1';
  if (errorCurve !== '1' || !badMessage.includes(label)) fail(`the error does not name curve 1 (${label}): ${errorCurve} ${badMessage}`);
  await page.screenshot({ path: path.join(out, 'error-curve.png') });

  // A click on a curve in the view selects it.
  await page.selectOption('#example', 'sphere');
  await page.waitForFunction(() => document.getElementById('stats').dataset.solving === '0' && document.getElementById('curve').options.length === 3 && +document.getElementById('stats').dataset.vertices > 0, null, { timeout: 60000 });
  const [cx, cy] = await page.evaluate(() => window.curvenetViewer.screenPoint(2, 10));
  await page.mouse.click(cx, cy);
  const picked = await page.inputValue('#curve');
  console.log(`clicked at (${cx.toFixed(0)}, ${cy.toFixed(0)}): curve ${picked} selected`);
  if (picked !== '2') fail(`a click on curve 2 selected curve ${picked}`);

  // "A click leaves the patch clicked open": a click on the sphere's middle opens the octant
  // there (7 patches); "fills the open cycle along the curve clicked": a click on one of its
  // curves closes it again (8); "as found" after a second opening gives the 8 back too.
  const patches = () => page.getAttribute('#stats', 'data-patches');
  await page.waitForFunction(() => document.getElementById('stats').dataset.patches === '8' && document.getElementById('stats').dataset.solving === '0', null, { timeout: 60000 })
    .catch(async () => fail(`the sphere shows ${await patches()} patches, not 8`));
  await page.selectOption('#click-mode', 'open');
  const box = await page.locator('#view canvas').boundingBox();
  await page.mouse.click(box.x + box.width / 2 + 5, box.y + box.height / 2 + 5);
  await page.waitForFunction(() => document.getElementById('stats').dataset.patches === '7', null, { timeout: 60000 })
    .catch(() => fail('a click on the sphere in open mode left the 8 patches'));
  console.log(`after a click in open mode: ${await page.textContent('#stats')}`);
  await page.screenshot({ path: path.join(out, 'sphere-octant-open.png') });
  await page.selectOption('#click-mode', 'fill');
  // The octant's border: quarter circles of the three curves; a click on each quarter's middle
  // until one borders the hole.
  let filled = false;
  for (let k = 0; k < 3 && !filled; k++) {
    for (const i of [16, 48, 80, 112]) {
      const [x, y] = await page.evaluate(([k, i]) => window.curvenetViewer.screenPoint(k, i), [k, i]);
      await page.mouse.click(x, y);
      filled = await page.waitForFunction(() => document.getElementById('stats').dataset.patches === '8', null, { timeout: 3000 })
        .then(() => true, () => false);
      if (filled) { console.log(`a click on curve ${k} at sample ${i} filled the octant: ${await page.textContent('#stats')}`); break; }
    }
  }
  if (!filled) fail('no click on the open octant\'s curves filled it');
  await page.selectOption('#click-mode', 'open');
  await page.mouse.click(box.x + box.width / 2 + 5, box.y + box.height / 2 + 5);
  await page.waitForFunction(() => document.getElementById('stats').dataset.patches === '7', null, { timeout: 60000 })
    .catch(() => fail('a second click in open mode left the 8 patches'));
  await page.click('#fill-all');
  await page.waitForFunction(() => document.getElementById('stats').dataset.patches === '8', null, { timeout: 60000 })
    .catch(() => fail('"as found" did not give the 8 patches back'));
  await page.selectOption('#click-mode', 'select');

  // The page keeps painting while a 100k-vertex default-quality solve runs in the worker.
  await page.selectOption('#quality', '1');
  await page.fill('#vertices', '5');
  await page.dispatchEvent('#vertices', 'input');
  await page.waitForFunction(() => document.getElementById('stats').dataset.solving === '1', null, { timeout: 10000 });
  const solveStart = Date.now();
  const painting = await page.evaluate(() => new Promise((resolve) => {
    let frames = 0;
    const t0 = performance.now();
    const tick = () => {
      frames++;
      if (performance.now() - t0 < 1500) requestAnimationFrame(tick);
      else resolve({ frames, solving: document.getElementById('stats').dataset.solving });
    };
    requestAnimationFrame(tick);
  }));
  console.log(`during the 100k solve: ${painting.frames} frames painted in 1.5 s (still solving: ${painting.solving === '1'})`);
  if (painting.solving !== '1') fail('the solve ended before the frames were counted: not a long solve');
  if (painting.frames < 30) fail(`the page painted ${painting.frames} frames in 1.5 s during the solve: frozen`);
  await page.waitForFunction(() => document.getElementById('stats').dataset.solving === '0', null, { timeout: 600000 });
  const big = +(await page.getAttribute('#stats', 'data-vertices'));
  console.log(`100k default solve: ${await page.textContent('#stats')} (${((Date.now() - solveStart) / 1000).toFixed(1)} s)`);
  if (!(big > 90000)) fail(`the 100k solve gave ${big} vertices`);

  // Downloads: the mesh has the vertex count shown; the GLB is glTF.
  const download = async (id) => {
    const [d] = await Promise.all([page.waitForEvent('download'), page.click(id)]);
    const file = path.join(tmp, d.suggestedFilename());
    await d.saveAs(file);
    return { name: d.suggestedFilename(), bytes: fs.readFileSync(file) };
  };
  const ply = await download('#download-ply');
  const header = ply.bytes.subarray(0, 400).toString('latin1');
  const plyVertices = +(/element vertex (\d+)/.exec(header) || [])[1];
  console.log(`downloaded ${ply.name}: ${plyVertices} vertices, ${ply.bytes.length} bytes`);
  if (plyVertices !== big) fail(`the downloaded PLY has ${plyVertices} vertices, the page shows ${big}`);
  const glb = await download('#download-glb');
  if (glb.bytes.subarray(0, 4).toString('latin1') !== 'glTF') fail('the downloaded GLB is not glTF');
  // three.js's own GLTFLoader reads it: one mesh, positions, normals, the curvature attribute.
  const gltf = await page.evaluate(async (b64) => {
    const { GLTFLoader } = await import('three/addons/loaders/GLTFLoader.js');
    const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
    const g = await new GLTFLoader().parseAsync(bytes.buffer, '');
    const meshes = [];
    g.scene.traverse((o) => { if (o.isMesh) meshes.push(o); });
    const a = meshes[0].geometry.attributes;
    return { meshes: meshes.length, positions: a.position.count, normals: a.normal?.count, curvature: a._mean_curvature?.count ?? a._MEAN_CURVATURE?.count, triangles: meshes[0].geometry.index.count / 3 };
  }, glb.bytes.toString('base64'));
  console.log(`three.js GLTFLoader: ${JSON.stringify(gltf)}`);
  if (gltf.meshes !== 1 || !(gltf.positions >= big) || gltf.normals !== gltf.positions || gltf.curvature !== gltf.positions) fail(`three.js read the GLB as ${JSON.stringify(gltf)}`);
  const net = await download('#download-network');
  const edited = JSON.parse(net.bytes.toString('utf8'));
  if (edited.curves.length !== 3) fail(`the downloaded network has ${edited.curves.length} curves`);

  // A newer request ends an older one: a long solve, then at once a small one.
  await page.selectOption('#method', '1');
  await page.waitForFunction(() => document.getElementById('stats').dataset.solving === '1', null, { timeout: 10000 });
  await page.fill('#vertices', '3.5');
  await page.dispatchEvent('#vertices', 'input');
  const cancelStart = Date.now();
  await page.waitForFunction(() => document.getElementById('stats').dataset.solving === '0' && +document.getElementById('stats').dataset.vertices < 10000, null, { timeout: 120000 });
  console.log(`newer request: ${await page.textContent('#stats')} after ${((Date.now() - cancelStart) / 1000).toFixed(1)} s`);

  if (errors.length) fail(`errors in the page: ${errors.join('; ')}`);
  console.log('viewer e2e: ok');
} finally {
  await browser.close();
  server.close();
  fs.rmSync(tmp, { recursive: true, force: true });
}
