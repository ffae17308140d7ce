// app.js — the web test page (tools/web/index.html): draws the current world
// through the engine's debug-draw interface (physics/debug_draw.h via
// tandem_web.cpp), runs it one step per animation frame, and wires the
// controls: bundled or dropped scenes and replays, the report's circles
// sliders, the broad phase, pause/step/reset, replay scrubbing and
// verification, the step-time graph. window.tandemPage is the hook the
// browser tests (tests/web.test.mjs) drive.
import { Engine, TandemError } from './tandem.js';

const $ = (id) => document.getElementById(id);

// Cairo renderer's palette (tools/render/render.cpp), by DrawBodyState.
const STATE_RGB = [[0.55, 0.65, 0.55], [0.55, 0.6, 0.9], [0.95, 0.65, 0.35], [0.7, 0.7, 0.7], [0.85, 0.85, 0.85]];
const JOINT_RGB = [[0.1, 0.5, 0.1], [0.1, 0.6, 0.7], [0.4, 0.4, 0.4], [0.6, 0.2, 0.6], [0.8, 0.1, 0.1], [0.2, 0.3, 0.8],
  [0.7, 0.5, 0.1]];
const rgb = (c, k = 1, a = 1) => `rgba(${Math.round(c[0] * k * 255)},${Math.round(c[1] * k * 255)},${Math.round(c[2] * k * 255)},${a})`;
const FILL = STATE_RGB.map((c) => rgb(c, 1, 0.85));
const STROKE = STATE_RGB.map((c) => rgb(c, 0.45));

const SLIDERS = [
  ['s-count', 'o-count', 0], ['s-rmin', 'o-rmin', 2], ['s-rmax', 'o-rmax', 2],
  ['s-speed', 'o-speed', 1], ['s-rest', 'o-rest', 2], ['s-grav', 'o-grav', 1],
];

const page = {
  engine: null,
  running: true,
  source: null,          // {kind: 'scene', text, name} | {kind: 'replay', bytes, name}
  info: null,
  view: [-10, -10, 10, 10],
  stepMs: [],            // last steps' times, ms
  frameTimes: [],        // animation frame timestamps, ms
  circlesTemplate: null, // scenes/circles.json parsed
  replayEnded: false,
};

// --- status and errors ---------------------------------------------------------
function setStatus(text) { $('status').textContent = text; }
function showError(message) {
  $('error').textContent = message;
  $('error-section').hidden = false;
  setStatus('error — the page keeps the previous world');
}
function clearError() {
  $('error').textContent = '';
  $('error-section').hidden = true;
}

// --- loading ---------------------------------------------------------------------
function broadPhase() { return $('broad-phase').value || null; }

function afterLoad(source, warning = '') {
  page.source = source;
  page.info = page.engine.info();
  page.view = page.info.view;
  page.stepMs = [];
  page.replayEnded = false;
  clearError();
  if (warning) showError(warning);
  const replay = page.info.mode === 'replay';
  $('replay-section').hidden = !replay;
  if (replay) {
    $('scrub').max = String(page.info.replay_ticks);
    $('scrub').value = '0';
    $('o-scrub').textContent = '0';
    $('verify-result').textContent = '';
    $('verify-result').className = 'verify';
  }
  $('scene-desc').textContent = replay
    ? `replay: ${page.info.replay_ticks} ticks at ${Math.round(page.info.step_hz)} Hz`
    : (page.info.description || page.info.title || '');
  $('scene-desc').title = $('scene-desc').textContent;
  setStatus(`${page.info.name}: ${page.info.bodies} bodies, ${page.info.joints} joints, broad phase ${page.info.broad_phase}`);
  updateReadouts();
  render();
}

// Loads scene text; on a malformed scene shows the CLI's message and keeps
// the current world. Returns true when loaded.
function loadSceneText(text, name) {
  try {
    page.engine.loadScene(text, name, broadPhase());
  } catch (e) {
    if (!(e instanceof TandemError)) throw e;
    showError(e.message);
    return false;
  }
  afterLoad({ kind: 'scene', text, name });
  return true;
}

function loadReplayBytes(bytes, name) {
  let warning;
  try {
    warning = page.engine.loadReplay(bytes, name);
  } catch (e) {
    if (!(e instanceof TandemError)) throw e;
    showError(e.message);
    return false;
  }
  afterLoad({ kind: 'replay', bytes, name }, warning);
  showFileName(name);
  return true;
}

// A dropped or opened file: a replay when it starts with the replay magic,
// otherwise scene text.
function loadBytes(bytes, name) {
  if (page.engine.isReplay(bytes)) return loadReplayBytes(bytes, name);
  const ok = loadSceneText(new TextDecoder().decode(bytes), name);
  if (ok) showFileName(name);
  return ok;
}

// The scene menu names a file that is not a bundled scene.
function showFileName(name) {
  const o = $('file-option');
  o.textContent = `file: ${name}`;
  o.hidden = false;
  $('scene-select').value = '';
  o.selected = true;
}

async function loadBundled(name) {
  const response = await fetch(`scenes/${name}`);
  if (!response.ok) {
    showError(`scenes/${name}: HTTP ${response.status}`);
    return false;
  }
  $('scene-select').value = name;
  return loadSceneText(await response.text(), name);
}

function reload() {
  const s = page.source;
  if (!s) return;
  if (s.kind === 'scene') loadSceneText(s.text, s.name);
  else loadReplayBytes(s.bytes, s.name);
}

// --- the circles sliders ----------------------------------------------------------
function sliderValue(id, decimals) { return Number(Number($(id).value).toFixed(decimals)); }

function circlesSceneText() {
  const scene = JSON.parse(JSON.stringify(page.circlesTemplate));
  const g = scene.generators[0];
  g.count = sliderValue('s-count', 0);
  g.size_min = sliderValue('s-rmin', 2);
  g.size_max = sliderValue('s-rmax', 2);
  g.speed = sliderValue('s-speed', 1);
  g.shape.restitution = sliderValue('s-rest', 2);
  scene.world.gravity = [0, sliderValue('s-grav', 1)];
  fitBox(scene, g);
  return JSON.stringify(scene, null, 1);
}

// The random generator refuses more bodies than its region holds (cells of
// 2.2 × size_max). When the count needs more room, the box, the region and
// the view grow by a factor k (a multiple of 1/4, so the file keeps short
// decimals) until the circles fit; the density stays what the sliders say.
function fitBox(scene, g) {
  const cell = 2.2 * g.size_max;
  const [[lx, ly], [ux, uy]] = [g.region.lower, g.region.upper];
  const fits = (k) => Math.floor(((ux - lx + 1) * k - 1) / cell) * Math.floor(((uy - ly + 1) * k - 1) / cell) >= g.count;
  let k = 1;
  while (!fits(k) && k < 64) k += 0.25;
  if (k === 1) return;
  const box = scene.bodies[0].shapes[0];
  box.points = box.points.map(([x, y]) => [x * k, y * k]);
  g.region.lower = [lx * k - 0.5 * (k - 1), ly];
  g.region.upper = [ux * k + 0.5 * (k - 1), (uy + 0.5) * k - 0.5];
  scene.view = { lower: [scene.view.lower[0] * k, scene.view.lower[1] * k], upper: [scene.view.upper[0] * k, scene.view.upper[1] * k] };
}

function showSliderValues() {
  for (const [input, output, decimals] of SLIDERS) $(output).textContent = Number($(input).value).toFixed(decimals);
}

function sliderChanged(event) {
  // Keep radius min ≤ radius max by moving the other slider.
  const min = $('s-rmin'), max = $('s-rmax');
  if (Number(min.value) > Number(max.value)) {
    if (event && event.target === min) max.value = min.value;
    else min.value = max.value;
  }
  showSliderValues();
  $('scene-select').value = 'circles.json';
  loadSceneText(circlesSceneText(), 'circles.json');
}

function setSlidersFromTemplate() {
  const t = page.circlesTemplate, g = t.generators[0];
  $('s-count').value = g.count;
  $('s-rmin').value = g.size_min;
  $('s-rmax').value = g.size_max;
  $('s-speed').value = g.speed;
  $('s-rest').value = g.shape.restitution;
  $('s-grav').value = (t.world.gravity || [0, -10])[1];
  showSliderValues();
}

// --- stepping ------------------------------------------------------------------------
function stepOnce() {
  const t0 = performance.now();
  let advanced;
  try {
    advanced = page.engine.step(1);
  } catch (e) {
    if (!(e instanceof TandemError)) throw e;
    showError(e.message);
    setRunning(false);
    return;
  }
  const ms = performance.now() - t0;
  if (!advanced) {
    page.replayEnded = true;
    setRunning(false);
    setStatus(`${page.info.name}: end of the replay (tick ${page.engine.tick()})`);
    return;
  }
  page.stepMs.push(ms);
  if (page.stepMs.length > 240) page.stepMs.shift();
}

function setRunning(on) {
  page.running = on;
  $('play').textContent = on ? 'Pause' : 'Play';
}

// --- drawing ---------------------------------------------------------------------------
function canvasTransform(canvas) {
  const [lx, ly, ux, uy] = page.view;
  const w = canvas.width, h = canvas.height;
  const scale = Math.min(w / Math.max(ux - lx, 1e-9), h / Math.max(uy - ly, 1e-9));
  const ox = 0.5 * w - 0.5 * (lx + ux) * scale, oy = 0.5 * h + 0.5 * (ly + uy) * scale;
  return { scale, x: (x) => ox + x * scale, y: (y) => oy - y * scale };
}

function finishShape(ctx, state, sensor, solid) {
  ctx.setLineDash(sensor ? [4, 3] : []);
  if (solid && !sensor && state !== 4) {
    ctx.fillStyle = FILL[state];
    ctx.fill();
  }
  ctx.strokeStyle = STROKE[state];
  ctx.lineWidth = solid ? 1 : 2;
  ctx.stroke();
  ctx.setLineDash([]);
}

function render() {
  const canvas = $('view');
  const dpr = window.devicePixelRatio || 1;
  const w = Math.max(1, Math.round(canvas.clientWidth * dpr)), h = Math.max(1, Math.round(canvas.clientHeight * dpr));
  if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
  const ctx = canvas.getContext('2d');
  ctx.setTransform(1, 0, 0, 1, 0, 0);
  ctx.fillStyle = '#ffffff';
  ctx.fillRect(0, 0, w, h);
  if (!page.engine) return;
  const m = canvasTransform(canvas);
  const b = page.engine.draw({
    joints: $('show-joints').checked, contacts: $('show-contacts').checked, aabbs: $('show-aabbs').checked,
  });
  ctx.lineJoin = 'round';
  ctx.lineCap = 'round';
  ctx.scale(dpr, dpr);
  const X = (x) => m.x(x) / dpr, Y = (y) => m.y(y) / dpr, S = m.scale / dpr;
  let i = 0;
  while (i < b.length) {
    const op = b[i];
    switch (op) {
      case 1: { // polygon
        const state = b[i + 1], sensor = b[i + 2] === 1, n = b[i + 3];
        ctx.beginPath();
        for (let k = 0; k < n; ++k) {
          const x = X(b[i + 5 + 2 * k]), y = Y(b[i + 6 + 2 * k]);
          if (k === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
        }
        ctx.closePath();
        finishShape(ctx, state, sensor, true);
        i += 5 + 2 * n;
        break;
      }
      case 2: { // circle + radius line
        const state = b[i + 1], sensor = b[i + 2] === 1;
        const cx = X(b[i + 3]), cy = Y(b[i + 4]);
        ctx.beginPath();
        ctx.arc(cx, cy, b[i + 5] * S, 0, 2 * Math.PI);
        finishShape(ctx, state, sensor, true);
        ctx.beginPath();
        ctx.moveTo(cx, cy);
        ctx.lineTo(X(b[i + 6]), Y(b[i + 7]));
        ctx.stroke();
        i += 8;
        break;
      }
      case 3: { // capsule
        const state = b[i + 1], sensor = b[i + 2] === 1;
        const x1 = X(b[i + 3]), y1 = Y(b[i + 4]), x2 = X(b[i + 5]), y2 = Y(b[i + 6]), r = b[i + 7] * S;
        const a = Math.atan2(y2 - y1, x2 - x1);
        ctx.beginPath();
        ctx.arc(x2, y2, r, a - Math.PI / 2, a + Math.PI / 2);
        ctx.arc(x1, y1, r, a + Math.PI / 2, a + 3 * Math.PI / 2);
        ctx.closePath();
        finishShape(ctx, state, sensor, true);
        i += 8;
        break;
      }
      case 4: { // segment / chain segment
        const state = b[i + 1], sensor = b[i + 2] === 1;
        ctx.beginPath();
        ctx.moveTo(X(b[i + 3]), Y(b[i + 4]));
        ctx.lineTo(X(b[i + 5]), Y(b[i + 6]));
        finishShape(ctx, state, sensor, false);
        i += 7;
        break;
      }
      case 5: { // joint: origin A → anchor A → anchor B → origin B
        const type = b[i + 1];
        const c = JOINT_RGB[type] || JOINT_RGB[2];
        ctx.strokeStyle = rgb(c, 1, 0.9);
        ctx.fillStyle = rgb(c, 1, 0.9);
        ctx.lineWidth = 1.5;
        ctx.beginPath();
        if (type !== 4 && type !== 1) {
          ctx.moveTo(X(b[i + 2]), Y(b[i + 3]));
          ctx.lineTo(X(b[i + 4]), Y(b[i + 5]));
        } else {
          ctx.moveTo(X(b[i + 4]), Y(b[i + 5]));
        }
        ctx.lineTo(X(b[i + 6]), Y(b[i + 7]));
        if (type !== 1) ctx.lineTo(X(b[i + 8]), Y(b[i + 9]));
        ctx.stroke();
        for (const k of [4, 6]) {
          ctx.beginPath();
          ctx.arc(X(b[i + k]), Y(b[i + k + 1]), 2.5, 0, 2 * Math.PI);
          ctx.fill();
        }
        i += 10;
        break;
      }
      case 6: { // contact point and normal
        const px = X(b[i + 1]), py = Y(b[i + 2]), touching = b[i + 5] <= 0;
        ctx.fillStyle = touching ? 'rgb(217,26,26)' : 'rgb(102,26,217)';
        ctx.strokeStyle = ctx.fillStyle;
        ctx.beginPath();
        ctx.arc(px, py, 2.5, 0, 2 * Math.PI);
        ctx.fill();
        ctx.lineWidth = 1;
        ctx.beginPath();
        ctx.moveTo(px, py);
        ctx.lineTo(px + b[i + 3] * 12, py - b[i + 4] * 12);
        ctx.stroke();
        i += 6;
        break;
      }
      case 7: { // AABB
        ctx.strokeStyle = 'rgba(204,51,204,0.6)';
        ctx.lineWidth = 0.7;
        ctx.strokeRect(X(b[i + 1]), Y(b[i + 4]), (b[i + 3] - b[i + 1]) * S, (b[i + 4] - b[i + 2]) * S);
        i += 5;
        break;
      }
      default:
        throw new Error(`draw buffer: unknown record ${op} at ${i}`);
    }
  }
}

function drawGraph() {
  const canvas = $('graph');
  const dpr = window.devicePixelRatio || 1;
  const w = Math.max(1, Math.round(canvas.clientWidth * dpr)), h = Math.max(1, Math.round(canvas.clientHeight * dpr));
  if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
  const ctx = canvas.getContext('2d');
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  const cw = w / dpr, ch = h / dpr;
  ctx.clearRect(0, 0, cw, ch);
  const data = page.stepMs;
  const top = Math.max(1, ...data) * 1.15;
  // 16.7 ms (one 60 Hz frame) reference line when in range.
  ctx.font = '11px system-ui, sans-serif';
  ctx.fillStyle = '#5c6578';
  ctx.fillText(`${top.toFixed(top < 10 ? 2 : 1)} ms`, 4, 11);
  if (top > 16.7) {
    const y = ch - (16.7 / top) * ch;
    ctx.strokeStyle = 'rgba(179,38,30,0.5)';
    ctx.setLineDash([3, 3]);
    ctx.beginPath(); ctx.moveTo(0, y); ctx.lineTo(cw, y); ctx.stroke();
    ctx.setLineDash([]);
  }
  if (data.length < 2) return;
  ctx.strokeStyle = '#d9782d';
  ctx.lineWidth = 1.5;
  ctx.beginPath();
  data.forEach((v, k) => {
    const x = (k / 239) * cw, y = ch - (v / top) * ch;
    if (k === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
  });
  ctx.stroke();
}

function median(values) {
  if (values.length === 0) return NaN;
  const s = [...values].sort((a, b) => a - b);
  return s[Math.floor(s.length / 2)];
}

function updateReadouts() {
  $('tick').textContent = String(page.engine.tick());
  $('hash').textContent = page.engine.hash();
  $('bodies').textContent = page.info ? `${page.info.bodies} (${page.info.dynamic_bodies} dynamic)` : '–';
  const last = page.stepMs[page.stepMs.length - 1];
  $('step-ms').textContent = last === undefined ? '–' : `${last.toFixed(2)} ms`;
  const med = median(page.stepMs);
  $('step-median').textContent = Number.isNaN(med) ? '–' : `${med.toFixed(2)} ms (last ${page.stepMs.length})`;
  const f = page.frameTimes;
  $('fps').textContent = f.length > 1 ? `${((f.length - 1) * 1000 / (f[f.length - 1] - f[0])).toFixed(0)} fps` : '–';
  if (page.info && page.info.mode === 'replay') {
    $('scrub').value = String(page.engine.tick());
    $('o-scrub').textContent = String(page.engine.tick());
  }
}

function frame(now) {
  page.frameTimes.push(now);
  while (page.frameTimes.length > 1 && now - page.frameTimes[0] > 1000) page.frameTimes.shift();
  if (page.running && page.source) stepOnce();
  render();
  drawGraph();
  updateReadouts();
  requestAnimationFrame(frame);
}

// --- wiring ----------------------------------------------------------------------------
function wire() {
  $('play').addEventListener('click', () => {
    if (!page.running && page.replayEnded) reload();
    setRunning(!page.running);
  });
  $('step').addEventListener('click', () => { setRunning(false); stepOnce(); render(); updateReadouts(); });
  $('reset').addEventListener('click', reload);
  $('broad-phase').addEventListener('change', reload);
  $('scene-select').addEventListener('change', (e) => {
    if (e.target.value === 'circles.json') {
      setSlidersFromTemplate();
    }
    loadBundled(e.target.value);
  });
  for (const [input] of SLIDERS) $(input).addEventListener('input', sliderChanged);
  $('scrub').addEventListener('input', (e) => {
    setRunning(false);
    try {
      page.engine.seek(Number(e.target.value));
      page.replayEnded = false;
    } catch (err) {
      if (!(err instanceof TandemError)) throw err;
      showError(err.message);
    }
    render();
    updateReadouts();
  });
  $('verify').addEventListener('click', () => {
    const r = page.engine.verify();
    const out = $('verify-result');
    out.textContent = r.code === 0 ? 'verified: every recorded hash matches' : r.code === 1 ? 'MISMATCH' : 'could not run';
    out.className = `verify ${r.code === 0 ? 'ok' : 'bad'}`;
    out.title = r.text;
    if (r.code !== 0) showError(r.text);
  });
  $('file-input').addEventListener('change', async (e) => {
    const file = e.target.files[0];
    if (file) loadBytes(new Uint8Array(await file.arrayBuffer()), file.name);
    e.target.value = '';
  });
  const stage = $('stage');
  stage.addEventListener('dragover', (e) => { e.preventDefault(); stage.classList.add('dragging'); });
  stage.addEventListener('dragleave', () => stage.classList.remove('dragging'));
  stage.addEventListener('drop', async (e) => {
    e.preventDefault();
    stage.classList.remove('dragging');
    const file = e.dataTransfer.files[0];
    if (file) loadBytes(new Uint8Array(await file.arrayBuffer()), file.name);
  });
  window.addEventListener('keydown', (e) => {
    if (e.target instanceof HTMLInputElement || e.target instanceof HTMLSelectElement) return;
    if (e.key === ' ') { e.preventDefault(); $('play').click(); }
    else if (e.key === 's') $('step').click();
    else if (e.key === 'r') $('reset').click();
  });
}

// --- test hooks (tests/web.test.mjs) ------------------------------------------------------
// chain(): loads scene text and returns the hash after every tick 0..ticks
// (the page's own world is replaced and paused). bench(): median ms per step.
function chain(text, name, ticks, broad = null) {
  setRunning(false);
  page.engine.loadScene(text, name, broad);
  const hashes = [page.engine.hash()];
  for (let t = 0; t < ticks; ++t) {
    page.engine.step(1);
    hashes.push(page.engine.hash());
  }
  afterLoad({ kind: 'scene', text, name });
  return hashes;
}

// Times `ticks` steps in batches of `batch` (performance.now() is coarse in
// a page: 0.1 ms in Chromium); returns the median and mean ms per step.
function bench(text, name, ticks, warmup = 20, batch = 10) {
  setRunning(false);
  page.engine.loadScene(text, name, null);
  page.engine.step(warmup);
  const ms = [];
  let total = 0;
  for (let t = 0; t < ticks; t += batch) {
    const t0 = performance.now();
    page.engine.step(batch);
    const dt = performance.now() - t0;
    total += dt;
    ms.push(dt / batch);
  }
  return { median: median(ms), mean: total / ticks, ticks, hash: page.engine.hash(), tick: page.engine.tick() };
}

async function main() {
  wire();
  page.engine = await Engine.create();
  const list = await (await fetch('scenes/index.json')).json();
  const select = $('scene-select');
  for (const name of list) {
    const o = document.createElement('option');
    o.value = name;
    o.textContent = name.replace(/\.json$/, '');
    select.appendChild(o);
  }
  page.circlesTemplate = JSON.parse(await (await fetch('scenes/circles.json')).text());
  setSlidersFromTemplate();
  await loadBundled('circles.json');
  requestAnimationFrame(frame);
  document.body.dataset.ready = '1';
}

window.tandemPage = {
  page, chain, bench, loadSceneText, loadReplayBytes, loadBytes, loadBundled, setRunning, render,
  info: () => page.engine.info(),
  ready: main(),
};
