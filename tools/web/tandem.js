// tandem.js — the page's wrapper over the WebAssembly module
// (tandem_web.js / .wasm, built by the emscripten preset from
// tandem_web.cpp). One Engine holds one world, made from a scene file or a
// replay file; every number the simulation sees comes from the C++ side
// (scene text parsed to Q32 there), so the page computes the same bits as
// the native `tandem run`.
//
// Draw buffer layout (doubles, world metres, y up), one record after another:
//   1 polygon  state sensor count radius x0 y0 … x(count-1) y(count-1)
//   2 circle   state sensor cx cy r rimx rimy
//   3 capsule  state sensor x1 y1 x2 y2 r
//   4 segment  state sensor x1 y1 x2 y2
//   5 joint    type oax oay ax ay bx by obx oby
//   6 contact  px py nx ny separation
//   7 aabb     lx ly ux uy
// state: 0 static, 1 kinematic, 2 awake, 3 asleep, 4 disabled
// (physics/debug_draw.h DrawBodyState); joint type: physics/joint.h JointType.

export const BROAD_PHASES = ['naive', 'sap', 'grid', 'tree'];

export class TandemError extends Error {}

export class Engine {
  static async create(moduleUrl = './tandem_web.js') {
    const factory = await loadFactory(moduleUrl);
    const m = await factory();
    return new Engine(m);
  }

  constructor(m) {
    this.m = m;
  }

  _str(ptr) { return this.m.UTF8ToString(ptr); }
  error() { return this._str(this.m._tw_error()); }

  // Copies bytes (Uint8Array) into the module's heap; returns [ptr, size].
  _bytesIn(bytes) {
    const ptr = this.m._tw_alloc(bytes.length);
    this.m.HEAPU8.set(bytes, ptr);
    return [ptr, bytes.length];
  }
  _cstr(text) {
    const n = this.m.lengthBytesUTF8(text) + 1;
    const ptr = this.m._tw_alloc(n);
    this.m.stringToUTF8(text, ptr, n);
    return ptr;
  }

  // Loads scene text; broadPhase: 'naive'|'sap'|'grid'|'tree' or null (the
  // scene's own). Throws TandemError with the CLI's message on failure; the
  // previous world is kept then.
  loadScene(text, name, broadPhase = null) {
    const bytes = new TextEncoder().encode(text);
    const [ptr, size] = this._bytesIn(bytes);
    const namePtr = this._cstr(name);
    const bp = broadPhase == null ? -1 : BROAD_PHASES.indexOf(broadPhase);
    const rc = this.m._tw_load_scene(ptr, size, namePtr, bp);
    this.m._tw_free(ptr);
    this.m._tw_free(namePtr);
    if (rc !== 0) throw new TandemError(this.error());
  }

  // Loads a replay file image (Uint8Array); throws TandemError on failure.
  // Returns the read warning (a file cut short), or ''.
  loadReplay(bytes, name) {
    const [ptr, size] = this._bytesIn(bytes);
    const namePtr = this._cstr(name);
    const rc = this.m._tw_load_replay(ptr, size, namePtr);
    this.m._tw_free(ptr);
    this.m._tw_free(namePtr);
    if (rc !== 0) throw new TandemError(this.error());
    return this.error();
  }

  isReplay(bytes) {
    const head = bytes.subarray(0, Math.min(bytes.length, 64));
    const [ptr, size] = this._bytesIn(head);
    const r = this.m._tw_is_replay(ptr, size);
    this.m._tw_free(ptr);
    return r === 1;
  }

  // Steps `count` ticks. Returns false when a replay has ended; throws on a refusal.
  step(count = 1) {
    const rc = this.m._tw_step(count);
    if (rc === 2) throw new TandemError(this.error());
    return rc === 0;
  }
  seek(tick) {
    if (this.m._tw_seek(tick) !== 0) throw new TandemError(this.error());
  }
  tick() { return this.m._tw_tick(); }
  hash() { return this._str(this.m._tw_hash()); }
  recordedHash(tick) { return this._str(this.m._tw_recorded_hash(tick)); }
  // Returns {code: 0 match | 1 mismatch | 2 could not run, text}.
  verify() {
    const code = this.m._tw_verify();
    return { code, text: this.error() };
  }
  info() { return JSON.parse(this._str(this.m._tw_info())); }

  // A Float64Array view of the draw records (valid until the next call).
  draw({ aabbs = false, contacts = false, joints = true } = {}) {
    const n = this.m._tw_draw((aabbs ? 1 : 0) | (contacts ? 2 : 0) | (joints ? 4 : 0));
    const ptr = this.m._tw_draw_buffer();
    return new Float64Array(this.m.HEAPF64.buffer, ptr, n);
  }
}

// The Emscripten module is a classic script defining createTandem (MODULARIZE).
function loadFactory(url) {
  if (globalThis.createTandem) return Promise.resolve(globalThis.createTandem);
  return new Promise((resolve, reject) => {
    const s = document.createElement('script');
    s.src = url;
    s.onload = () => resolve(globalThis.createTandem);
    s.onerror = () => reject(new Error(`cannot load ${url}`));
    document.head.appendChild(s);
  });
}
