// The library in a Web Worker: every call into the WebAssembly module (pkg/curvenet.wasm, plain
// C ABI: see viewer/wasm/src/lib.rs) runs here, off the page's thread, so the page keeps
// painting and answering while a surface is solved. No numerics here either.
//
// Messages in: { id, op, args } (op `init` first, with the compiled module). Out: { id, ok,
// result } or { id, ok: false, error, curve } (curve: the curve the error names, or -1).
const enc = new TextEncoder();
const dec = new TextDecoder();
let module = null;
let wasm = null;

async function instantiate() {
  wasm = (await WebAssembly.instantiate(module, {})).exports;
}
function withText(s, f) {
  const b = enc.encode(s);
  const p = wasm.cn_alloc(b.length);
  new Uint8Array(wasm.memory.buffer, p, b.length).set(b);
  try { return f(p, b.length); } finally { wasm.cn_free(p, b.length); }
}
const text = () => dec.decode(new Uint8Array(wasm.memory.buffer, wasm.cn_text_ptr(), wasm.cn_text_len()).slice());
function buffer(kind, Type) {
  return new Type(wasm.memory.buffer, wasm.cn_buffer_ptr(kind), wasm.cn_buffer_len(kind)).slice();
}
/** A library error: its message and the curve it names. */
function failure() {
  const c = wasm.cn_error_curve();
  const e = new Error(text());
  e.curve = c === 0xffffffff ? -1 : c;
  return e;
}
const check = (rc) => { if (rc !== 0) throw failure(); };
const curves = () => ({ curves: buffer(5, Float32Array), offsets: buffer(6, Uint32Array) });

const ops = {
  example(name) { check(withText(name, (p, n) => wasm.cn_example(p, n))); return text(); },
  curveCount(body, format) {
    const n = withText(body, (p, k) => wasm.cn_curve_count(p, k, format));
    return n === 0xffffffff ? 0 : n;
  },
  curves(body, format) { check(withText(body, (p, n) => wasm.cn_network_curves(p, n, format))); return curves(); },
  rotate(body, format, curve, angle) {
    check(withText(body, (p, n) => wasm.cn_rotate_normals(p, n, format, curve, angle)));
    return text();
  },
  surface(body, format, method, vertices, soft, quality) {
    check(withText(body, (p, n) => wasm.cn_surface(p, n, format, method, vertices, soft, quality)));
    return {
      positions: buffer(0, Float32Array), faces: buffer(1, Uint32Array), normals: buffer(2, Float32Array),
      curvature: buffer(3, Float32Array), deviation: buffer(4, Float32Array), facePatch: buffer(8, Uint32Array), ...curves(),
      vertices: wasm.cn_stat(0), faceCount: wasm.cn_stat(1), curveVertices: wasm.cn_stat(2), patches: wasm.cn_stat(3),
      range: wasm.cn_stat(4), deviationMax: wasm.cn_stat(5), warnings: text(),
    };
  },
  cycles(body, format, method, vertices, quality) {
    check(withText(body, (p, n) => wasm.cn_cycles(p, n, format, method, vertices, quality)));
    return text();
  },
  openPatch(body, format, patch, method, vertices, quality) {
    check(withText(body, (p, n) => wasm.cn_open_patch(p, n, format, patch, method, vertices, quality)));
    return text();
  },
  fillCycle(body, format, curve, method, vertices, quality) {
    check(withText(body, (p, n) => wasm.cn_fill_cycle(p, n, format, curve, method, vertices, quality)));
    return text();
  },
  exportMesh(format) {
    check(wasm.cn_export_mesh(format));
    return new Uint8Array(wasm.memory.buffer, wasm.cn_bytes_ptr(), wasm.cn_bytes_len()).slice();
  },
};

/** The typed arrays of a result, moved (not copied) to the page. */
function transfers(result) {
  if (result instanceof Uint8Array) return [result.buffer];
  if (result && typeof result === 'object') {
    return Object.values(result).filter((v) => ArrayBuffer.isView(v)).map((v) => v.buffer);
  }
  return [];
}

self.onmessage = async (e) => {
  const { id, op, args } = e.data;
  if (op === 'init') {
    module = e.data.module;
    await instantiate();
    self.postMessage({ id, ok: true });
    return;
  }
  try {
    const result = ops[op](...args);
    self.postMessage({ id, ok: true, result }, transfers(result));
  } catch (err) {
    if (err instanceof WebAssembly.RuntimeError) {
      // A trap is a bug, not bad input: a fresh instance for the next call.
      await instantiate();
      self.postMessage({ id, ok: false, error: `internal error: ${err.message}`, curve: -1 });
    } else {
      self.postMessage({ id, ok: false, error: err.message, curve: err.curve ?? -1 });
    }
  }
};
