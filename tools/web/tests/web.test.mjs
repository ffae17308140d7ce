// web.test.mjs — browser tests of the web test page (tools/web), run by
// ctest in the emscripten build (tools/web/CMakeLists.txt) and so by
// scripts/test.sh's `web` row. Drives Debian's /usr/bin/chromium headless
// through playwright-core (no browser download), serving the built page
// (build/emscripten/web) from a small static server on 127.0.0.1, and
// compares with the native `tandem` command line.
//
// Usage: node web.test.mjs --web DIR --tandem PATH --data DIR [--only GROUP]
//        [--ticks N] [--screenshot PNG] [--bench]
//   groups: chains, canvas, sliders, replay, errors (default: all)
//   --screenshot  also save a picture of the page (the README's)
//   --bench       ms per step in the page vs native (docs/benchmarks.md)
// Prints one line per check ("ok ..." / "FAIL ...") and exits 1 on a failure.
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, readdirSync, writeFileSync, rmSync } from 'node:fs';
import { createServer } from 'node:http';
import { tmpdir } from 'node:os';
import { extname, join, resolve, basename } from 'node:path';

const args = { only: null, ticks: 120, screenshot: null, bench: false };
for (let i = 2; i < process.argv.length; ++i) {
  const a = process.argv[i];
  if (a === '--web') args.web = resolve(process.argv[++i]);
  else if (a === '--tandem') args.tandem = resolve(process.argv[++i]);
  else if (a === '--data') args.data = resolve(process.argv[++i]);
  else if (a === '--only') args.only = process.argv[++i];
  else if (a === '--ticks') args.ticks = Number(process.argv[++i]);
  else if (a === '--screenshot') args.screenshot = resolve(process.argv[++i]);
  else if (a === '--bench') args.bench = true;
  else { console.error(`web.test.mjs: unknown argument ${a}`); process.exit(2); }
}
if (!args.web || !args.tandem || !args.data) {
  console.error('usage: node web.test.mjs --web DIR --tandem PATH --data DIR [--only GROUP]');
  process.exit(2);
}
const CHROMIUM = process.env.TANDEM_CHROMIUM || '/usr/bin/chromium';
for (const [what, path] of [['the native tandem', args.tandem], ['Chromium', CHROMIUM], ['the built page', join(args.web, 'tandem_web.wasm')]]) {
  if (!existsSync(path)) {
    console.error(`web.test.mjs: ${what} is missing: ${path}` +
      (what === 'the native tandem' ? ' (build it: cmake --build build/gcc-release --target tandem)' : ''));
    process.exit(1);
  }
}
let chromium;
try {
  ({ chromium } = await import('playwright-core'));
} catch (e) {
  console.error(`web.test.mjs: playwright-core is not installed (scripts/setup-deps.sh web runs npm ci in tools/web): ${e.message}`);
  process.exit(1);
}

let failures = 0;
function check(ok, what, detail = '') {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}${detail ? `: ${detail}` : ''}`);
  if (!ok) failures++;
}

// --- a static server for the built page --------------------------------------------
const TYPES = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.css': 'text/css',
  '.json': 'application/json', '.wasm': 'application/wasm', '.png': 'image/png' };
function serve(dir) {
  const server = createServer((req, res) => {
    const path = decodeURIComponent(new URL(req.url, 'http://x').pathname);
    const file = join(dir, path.endsWith('/') ? `${path}index.html` : path);
    if (!file.startsWith(dir)) { res.writeHead(403).end(); return; }
    try {
      const body = readFileSync(file);
      // Cross-origin isolated, so performance.now() has 5 µs resolution (0.1 ms otherwise) for --bench.
      res.writeHead(200, { 'Content-Type': TYPES[extname(file)] || 'application/octet-stream',
        'Cross-Origin-Opener-Policy': 'same-origin', 'Cross-Origin-Embedder-Policy': 'require-corp' }).end(body);
    } catch {
      res.writeHead(404).end('not found');
    }
  });
  return new Promise((ok) => server.listen(0, '127.0.0.1', () => ok(server)));
}

// --- the native side ---------------------------------------------------------------
function tandem(argv, cwd) {
  try {
    return { code: 0, out: execFileSync(args.tandem, argv, { cwd, encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] }) };
  } catch (e) {
    return { code: e.status, out: e.stdout || '', err: e.stderr || '' };
  }
}
function nativeChain(scenePath, ticks) {
  const r = tandem(['run', scenePath, '--ticks', String(ticks), '--hash-every', '1', '--json']);
  if (r.code !== 0) throw new Error(`tandem run ${scenePath}: ${r.err}`);
  const j = JSON.parse(r.out);
  const hashes = j.hashes.map((h) => h.hash);
  hashes.push(j.final_hash);
  return hashes;
}

// --- one page ------------------------------------------------------------------------
async function openPage(browser, base) {
  const page = await browser.newPage({ viewport: { width: 1366, height: 768 } });
  const problems = [];
  page.on('console', (m) => { if (m.type() === 'error' || m.type() === 'warning') problems.push(`console ${m.type()}: ${m.text()}`); });
  page.on('pageerror', (e) => problems.push(`uncaught: ${e.message}`));
  await page.goto(`${base}/index.html`);
  await page.waitForFunction(() => document.body.dataset.ready === '1', null, { timeout: 30000 });
  return { page, problems };
}

const groups = {
  // Every bundled scene: the page's hash after each tick equals `tandem run`'s.
  async chains(page) {
    const scenes = JSON.parse(readFileSync(join(args.web, 'scenes/index.json'), 'utf8'));
    check(scenes.length >= 5, 'bundled scenes listed', `${scenes.length}`);
    for (const name of scenes) {
      const text = readFileSync(join(args.web, 'scenes', name), 'utf8');
      const native = nativeChain(join(args.web, 'scenes', name), args.ticks);
      const web = await page.evaluate(([t, n, k]) => window.tandemPage.chain(t, n, k), [text, name, args.ticks]);
      let first = -1;
      for (let t = 0; t < Math.max(native.length, web.length); ++t) if (native[t] !== web[t]) { first = t; break; }
      check(first === -1 && web.length === args.ticks + 1, `hash chain ${name}, ticks 0..${args.ticks}`,
        first === -1 ? `final ${web[web.length - 1]}` : `first difference at tick ${first}: native ${native[first]} page ${web[first]}`);
    }
    // One scene under every broad phase (results must not depend on it).
    const text = readFileSync(join(args.web, 'scenes/rain.json'), 'utf8');
    const native = nativeChain(join(args.web, 'scenes/rain.json'), 60);
    for (const bp of ['naive', 'sap', 'grid', 'tree']) {
      const web = await page.evaluate(([t, b]) => window.tandemPage.chain(t, 'rain.json', 60, b), [text, bp]);
      check(web[60] === native[60], `rain.json under broad phase ${bp} ends on the native hash`, web[60]);
    }
  },

  // The canvas shows the world after load and while running.
  async canvas(page) {
    await page.evaluate(() => window.tandemPage.loadBundled('bridge.json'));
    await page.waitForTimeout(300);
    const stats = await page.evaluate(() => {
      const c = document.getElementById('view');
      const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      let ink = 0;
      const colours = new Set();
      for (let i = 0; i < d.length; i += 4) {
        if (d[i] < 250 || d[i + 1] < 250 || d[i + 2] < 250) { ink++; colours.add((d[i] << 16) | (d[i + 1] << 8) | d[i + 2]); }
      }
      return { ink, total: d.length / 4, colours: colours.size };
    });
    check(stats.ink > stats.total * 0.005 && stats.colours > 3, 'canvas not blank after load',
      `${stats.ink} of ${stats.total} pixels drawn, ${stats.colours} colours`);
    const t0 = await page.evaluate(() => window.tandemPage.page.engine.tick());
    await page.evaluate(() => window.tandemPage.setRunning(true));
    await page.waitForTimeout(500);
    const t1 = await page.evaluate(() => window.tandemPage.page.engine.tick());
    check(t1 > t0, 'the page steps while running', `tick ${t0} → ${t1}`);
    const shown = await page.textContent('#tick');
    check(/^\d+$/.test(shown), 'tick readout', shown);
    check(/^0x[0-9a-f]{16}$/.test(await page.textContent('#hash')), 'hash readout');
    await page.click('#play');
    await page.click('#step');
    const a = await page.evaluate(() => window.tandemPage.page.engine.tick());
    await page.click('#step');
    const b = await page.evaluate(() => window.tandemPage.page.engine.tick());
    check(b === a + 1, 'single step advances one tick', `${a} → ${b}`);
    for (const box of ['#show-contacts', '#show-aabbs']) await page.check(box);
    await page.waitForTimeout(100);
  },

  // Each circles slider changes what it says.
  async sliders(page) {
    const set = (id, value) => page.evaluate(([i, v]) => {
      const el = document.getElementById(i);
      el.value = String(v);
      el.dispatchEvent(new Event('input', { bubbles: true }));
      window.tandemPage.setRunning(false);
      return window.tandemPage.info();
    }, [id, value]);
    let info = await set('s-count', 1000);
    check(info.dynamic_bodies === 1000 && info.circles === 1000, 'circle count slider → 1000 circles', `${info.dynamic_bodies}`);
    info = await set('s-count', 50);
    check(info.dynamic_bodies === 50, 'circle count slider → 50 circles', `${info.dynamic_bodies}`);
    info = await set('s-rmin', 0.5);
    check(info.radius_min >= 0.5 - 1e-9, 'radius min slider → no circle under 0.5 m', `${info.radius_min}`);
    info = await set('s-rmax', 0.6);
    check(info.radius_max <= 0.6 + 1e-9 && info.radius_min >= 0.5 - 1e-9, 'radius max slider → radii within 0.5..0.6 m',
      `${info.radius_min}..${info.radius_max}`);
    info = await set('s-rmin', 0.8);  // above max: max follows
    check(info.radius_min >= 0.8 - 1e-9 && info.radius_max <= 0.8 + 1e-9, 'radius min above max moves max along',
      `${info.radius_min}..${info.radius_max}`);
    info = await set('s-speed', 12);
    check(Math.abs(info.mean_speed - 12) < 1e-3 && Math.abs(info.max_speed - 12) < 1e-3, 'speed slider → every circle starts at 12 m/s',
      `mean ${info.mean_speed}, max ${info.max_speed}`);
    info = await set('s-speed', 0);
    check(info.max_speed === 0, 'speed slider → 0 m/s', `${info.max_speed}`);
    info = await set('s-rest', 0.3);
    check(Math.abs(info.mean_restitution - 0.3) < 1e-6, 'restitution slider → 0.3', `${info.mean_restitution}`);
    info = await set('s-grav', -25);
    check(Math.abs(info.gravity[1] + 25) < 1e-9 && info.gravity[0] === 0, 'gravity slider → (0, −25)', `${info.gravity}`);
    // Gravity acts: from rest, 6 ticks of 1/60 s in free fall give 25 · 0.1 = 2.5 m/s.
    const v = await page.evaluate(() => {
      window.tandemPage.page.engine.step(6);
      return window.tandemPage.info().mean_speed;
    });
    check(Math.abs(v - 2.5) < 0.05, 'circles fall at the new gravity', `mean speed ${v.toFixed(4)} m/s after 6 ticks`);
    // The slider scene is the CLI's too: same hash chain as `tandem run` on the same text.
    const text = await page.evaluate(() => {
      const e = document.getElementById('s-count');
      return e && window.tandemPage.page.source.text;
    });
    const dir = mkdtempSync(join(tmpdir(), 'tandem-web-'));
    writeFileSync(join(dir, 'circles.json'), text);
    const native = nativeChain(join(dir, 'circles.json'), 30);
    const web = await page.evaluate(([t]) => window.tandemPage.chain(t, 'circles.json', 30), [text]);
    check(native[30] === web[30], 'slider-built circles scene: page and native agree after 30 ticks', web[30]);
    rmSync(dir, { recursive: true });
    // Broad phase selector reloads under the chosen one.
    await page.selectOption('#broad-phase', 'tree');
    info = await page.evaluate(() => window.tandemPage.info());
    check(info.broad_phase === 'tree', 'broad phase selector → tree', info.broad_phase);
    await page.selectOption('#broad-phase', '');
  },

  // A replay recorded natively verifies and scrubs in the page.
  async replay(page) {
    const dir = mkdtempSync(join(tmpdir(), 'tandem-web-'));
    const file = join(dir, 'dominoes.tandem-replay');
    const r = tandem(['record', join(args.web, 'scenes/dominoes.json'), '-o', file, '--ticks', '150', '--keyframe-every', '50']);
    check(r.code === 0, 'tandem record dominoes', r.err || '');
    const bytes = [...readFileSync(file)];
    const res = await page.evaluate(([b]) => {
      const ok = window.tandemPage.loadBytes(new Uint8Array(b), 'dominoes.tandem-replay');
      window.tandemPage.setRunning(false);
      return { ok, info: window.tandemPage.info() };
    }, [bytes]);
    check(res.ok && res.info.mode === 'replay' && res.info.replay_ticks === 150, 'replay loads', JSON.stringify(res.info.replay_ticks));
    await page.click('#verify');
    const verdict = await page.textContent('#verify-result');
    check(/verified/.test(verdict), 'replay verifies in the page', verdict);
    const native = tandem(['verify', file]);
    check(native.code === 0, 'the same replay verifies natively');
    // Scrub: every tick's hash equals the recorded one.
    const scrub = await page.evaluate(() => {
      const e = window.tandemPage.page.engine, out = [];
      for (const t of [150, 1, 77, 50, 149, 0, 100]) {
        const s = document.getElementById('scrub');
        s.value = String(t);
        s.dispatchEvent(new Event('input', { bubbles: true }));
        out.push([t, e.tick(), e.hash(), e.recordedHash(t)]);
      }
      return out;
    });
    const bad = scrub.filter(([t, tick, h, rec]) => tick !== t || (t > 0 && h !== rec));
    check(bad.length === 0, 'scrubbing lands on the recorded hash', bad.length ? JSON.stringify(bad[0]) : `${scrub.length} positions`);
    const last = tandem(['replay', file]).out.match(/final tick 150 {2}hash (0x[0-9a-f]+)/);
    check(last && scrub[0][2] === last[1], 'tick 150 equals `tandem replay`', last ? last[1] : 'no native hash');
    // Plays to the end and stops.
    await page.evaluate(() => { const s = document.getElementById('scrub'); s.value = '140'; s.dispatchEvent(new Event('input')); window.tandemPage.setRunning(true); });
    await page.waitForFunction(() => !window.tandemPage.page.running, null, { timeout: 10000 });
    check(await page.evaluate(() => window.tandemPage.page.engine.tick()) === 150, 'playing stops at the replay\'s end');
    rmSync(dir, { recursive: true });
  },

  // Malformed scenes and replays: the CLI's message, and the page keeps working.
  async errors(page) {
    await page.evaluate(() => window.tandemPage.loadBundled('stack.json'));
    const cases = [];
    for (const f of readdirSync(args.data).filter((n) => n.endsWith('.json')).sort()) {
      const r = tandem(['run', f, '--ticks', '1'], args.data);
      if (r.code === 2 && r.err.startsWith('tandem run: ')) cases.push({ name: f, bytes: [...readFileSync(join(args.data, f))], cli: r.err.replace(/\n$/, '').slice('tandem run: '.length) });
    }
    // Replays: cut short inside the header, one byte flipped in the magic, garbage.
    const dir = mkdtempSync(join(tmpdir(), 'tandem-web-'));
    const good = join(dir, 'good.tandem-replay');
    tandem(['record', join(args.web, 'scenes/stack.json'), '-o', good, '--ticks', '10']);
    const image = readFileSync(good);
    const bads = { 'cut.tandem-replay': image.subarray(0, 40), 'flipped.tandem-replay': Buffer.concat([image.subarray(0, 60), Buffer.from([image[60] ^ 0xff]), image.subarray(61)]) };
    for (const [n, b] of Object.entries(bads)) {
      writeFileSync(join(dir, n), b);
      const r = tandem(['verify', n], dir);
      if (r.code === 2) cases.push({ name: n, bytes: [...b], cli: r.err.split('\n')[0].replace(/^tandem verify: /, '') });
      else check(false, `tandem verify ${n} refuses`, `exit ${r.code}`);
    }
    check(cases.length >= 5, 'malformed inputs the CLI refuses', `${cases.length}`);
    for (const c of cases) {
      const shown = await page.evaluate(([b, n]) => {
        const ok = window.tandemPage.loadBytes(new Uint8Array(b), n);
        return { ok, text: document.getElementById('error').textContent, visible: !document.getElementById('error-section').hidden, name: window.tandemPage.info().name };
      }, [c.bytes, c.name]);
      check(!shown.ok && shown.visible && shown.text === c.cli && shown.name === 'stack.json', `${c.name}: the page shows the CLI's error`,
        shown.text === c.cli ? c.cli : `page "${shown.text}" vs CLI "${c.cli}"`);
    }
    const t0 = await page.evaluate(() => { window.tandemPage.setRunning(false); return window.tandemPage.page.engine.tick(); });
    await page.click('#step');
    const t1 = await page.evaluate(() => window.tandemPage.page.engine.tick());
    check(t1 === t0 + 1, 'after the errors the previous world still steps', `${t0} → ${t1}`);
    const ok = await page.evaluate(() => window.tandemPage.loadBundled('dominoes.json'));
    const hidden = await page.evaluate(() => document.getElementById('error-section').hidden);
    check(ok && hidden, 'a good scene loads afterwards and clears the error');
    rmSync(dir, { recursive: true });
  },
};

async function bench(page) {
  const dir = mkdtempSync(join(tmpdir(), 'tandem-web-bench-'));
  // circles-1k/4k: the page's own slider scene (circles.json; the box grows to fit the count).
  const scenes = {};
  for (const n of [1000, 4000]) {
    scenes[`circles-${n / 1000}k`] = await page.evaluate((count) => {
      const el = document.getElementById('s-count');
      el.value = String(count);
      el.dispatchEvent(new Event('input', { bubbles: true }));
      window.tandemPage.setRunning(false);
      return window.tandemPage.page.source.text;
    }, n);
  }
  scenes['pyramid-20'] = readFileSync(join(args.web, 'scenes/pyramid.json'), 'utf8');
  // Sleep off, so every timed step does the full work.
  for (const k of Object.keys(scenes)) {
    const s = JSON.parse(scenes[k]);
    s.world.sleep = false;
    scenes[k] = JSON.stringify(s);
  }
  const warmup = 20, reps = 3;
  const ticksOf = { 'circles-1k': 200, 'circles-4k': 100, 'pyramid-20': 300 };
  const rows = [];
  const med = (v) => [...v].sort((a, b) => a - b)[Math.floor(v.length / 2)];
  for (const [name, text] of Object.entries(scenes)) {
    const ticks = ticksOf[name];
    const path = join(dir, `${name}.json`);
    writeFileSync(path, text);
    const web = [], webMean = [], native = [], nativeMean = [];
    let wh = '', nh = '';
    for (let rep = 0; rep < reps; ++rep) {
      const w = await page.evaluate(([t, n, k, u]) => window.tandemPage.bench(t, n, k, u, 1), [text, `${name}.json`, ticks, warmup]);
      web.push(w.median); webMean.push(w.mean); wh = w.hash;
      const r = JSON.parse(tandem(['run', path, '--ticks', String(ticks + warmup), '--hash-every', '0', '--json', '-q']).out);
      native.push(r.step_ms.median); nativeMean.push(r.step_ms.mean); nh = r.final_hash;
    }
    rows.push({ name, bodies: JSON.parse(text).generators[0].count ?? null, ticks, page_median_ms: med(web), page_mean_ms: med(webMean),
      native_median_ms: med(native), native_mean_ms: med(nativeMean), ratio: med(web) / med(native), same_final_hash: wh === nh });
  }
  const isolated = await page.evaluate(() => window.crossOriginIsolated);
  console.log(JSON.stringify({ load: readFileSync('/proc/loadavg', 'utf8').trim(), isolated, rows }, null, 1));
  rmSync(dir, { recursive: true });
}

async function main() {
  const server = await serve(args.web);
  const base = `http://127.0.0.1:${server.address().port}`;
  const browser = await chromium.launch({ executablePath: CHROMIUM, headless: true, args: ['--no-sandbox'] });
  try {
    const names = args.only ? [args.only] : Object.keys(groups);
    for (const name of names) {
      if (!groups[name]) { check(false, `unknown group ${name}`); continue; }
      const { page, problems } = await openPage(browser, base);
      try {
        await groups[name](page);
      } catch (e) {
        check(false, `${name} threw`, e.stack);
      }
      check(problems.length === 0, `${name}: no console errors or uncaught exceptions`, problems.join(' | '));
      await page.close();
    }
    if (args.screenshot) {
      const { page, problems } = await openPage(browser, base);
      await page.evaluate(() => window.tandemPage.setRunning(true));
      await page.waitForTimeout(2500);
      await page.screenshot({ path: args.screenshot });
      check(problems.length === 0, 'screenshot: no console errors', problems.join(' | '));
      console.log(`screenshot written to ${args.screenshot}`);
    }
    if (args.bench) {
      const { page } = await openPage(browser, base);
      await bench(page);
    }
  } finally {
    await browser.close();
    server.close();
  }
  console.log(failures === 0 ? 'all checks passed' : `${failures} check(s) failed`);
  process.exit(failures === 0 ? 0 : 1);
}

main().catch((e) => { console.error(e); process.exit(1); });
