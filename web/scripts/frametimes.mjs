// Frame times of a built page while the UR10 target is dragged, for comparing two builds
// back to back (a benchmark: it prints figures, it asserts nothing, and it is not part of
// the test command). Headless Chromium draws through SwiftShader here, so compare runs
// made one after the other on the same machine, and read no difference under ~1 ms.
//
//   node web/scripts/frametimes.mjs DIST_DIR [runs=3] [frames=300] [--pin] [--eager] [--no-mirror]
//
// Each run opens the page at 1400×860 with the arm, the target and the DH frames shown,
// grabs the target ball and drags it in small steps, holding the button, until the app
// has drawn at least `frames` frames, then prints the median, p95 and max of the app's
// own main-thread milliseconds (`app` with its `ik` and `scene` parts and the rest,
// `render`, app + render, and `hook`, the tests' hook after the frame) from
// window.armlab.frameTimes(), and of the whole animation-frame callbacks (`callback_ms`:
// also egui's paint and index.html's shims, which frameTimes() leaves out), one JSON line
// per run and one for all runs together.
//
// With --pin (Linux, `taskset`), each run first moves every Chromium thread and this
// script to CPU 0 and then the page's main thread alone to CPU 1. On a 2-core machine
// without a GPU, SwiftShader's raster threads otherwise share the main thread's core and
// preempt it; pinned, the figures are the app's own main-thread time. Compare the two to
// tell the app's work from that contention.
//
// With --eager, Chromium runs with V8's `--no-wasm-dynamic-tiering`: every wasm function is
// compiled by the optimising compiler in the background from the start, instead of running
// in the baseline compiler's code until it has run enough (V8's default, which no page can
// change). Compared with a run without it, the difference is V8's warm-up, not the app's.
// With --no-mirror, the page starts without its accessibility mirror (the DOM copy of the
// interface for screen readers, window.armlabNoMirror): against a run without the flag, on
// the same build, the difference is the mirror's cost.
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { serveDist, launchChromium } from '../tests/static-server.mjs';

const args = process.argv.slice(2);
const pin = args.includes('--pin');
const eager = args.includes('--eager');
const noMirror = args.includes('--no-mirror');
const [distArg, runsArg, framesArg] = args.filter((a) => !a.startsWith('--'));
if (!distArg) {
  console.error('usage: node web/scripts/frametimes.mjs DIST_DIR [runs] [frames] [--pin] [--eager]');
  process.exit(2);
}
const dist = path.resolve(distArg);
const runs = Number(runsArg ?? 3);
const wanted = Number(framesArg ?? 300);
const VIEW = { width: 1400, height: 860 };
const { server, base } = await serveDist(dist);
const browser = await launchChromium(eager ? ['--js-flags=--no-wasm-dynamic-tiering'] : []);

// The process ids of the running Chromium processes whose command line matches `pattern`.
function pids(pattern) {
  try {
    return execFileSync('pgrep', ['-f', '--', pattern], { encoding: 'utf8' }).split(/\s+/).filter(Boolean);
  } catch {
    return [];
  }
}

// Every Chromium thread and this script on CPU 0, then each renderer's main thread (its
// thread id is the process id) alone on CPU 1.
function pinRendererMainThread() {
  const taskset = (...a) => execFileSync('taskset', a, { stdio: 'ignore' });
  for (const p of pids('chromium')) taskset('-a', '-p', '1', p);
  taskset('-a', '-p', '1', String(process.pid));
  const renderers = pids('--type=renderer');
  for (const p of renderers) taskset('-p', '2', p);
  if (renderers.length === 0) throw new Error('--pin: no renderer process found');
}

const state = async (page) => JSON.parse(await page.evaluate(() => window.armlab.state()));

function summary(values) {
  const sorted = [...values].sort((a, b) => a - b);
  const pick = (p) => sorted[Math.min(sorted.length - 1, Math.round((sorted.length - 1) * p))];
  return { median: +pick(0.5).toFixed(3), p95: +pick(0.95).toFixed(3), max: +pick(1).toFixed(3) };
}

function report(label, frames, callbacks) {
  return {
    label,
    frames: frames.length,
    app_ms: summary(frames.map((f) => f.app)),
    ik_ms: summary(frames.map((f) => f.ik)),
    scene_ms: summary(frames.map((f) => f.scene)),
    // The app's time outside the IK and the scene: egui's layout of the panels.
    panels_ms: summary(frames.map((f) => f.app - f.ik - f.scene)),
    render_ms: summary(frames.map((f) => f.render)),
    // Publishing the state for window.armlab after the frame (not part of app).
    hook_ms: summary(frames.map((f) => f.hook ?? 0)),
    app_plus_render_ms: summary(frames.map((f) => f.app + f.render)),
    // The whole animation-frame callbacks of the drag (see the init script below).
    callbacks: callbacks.length,
    callback_ms: summary(callbacks),
  };
}

// Times every animation-frame callback whole, from a script that runs before the page's:
// the app and the render (what frameTimes() measures) and also egui's paint and
// index.html's shims, so a change that moves work out of the app's frame shows here.
// Callbacks under 0.3 ms (put off by the back-pressure, or with nothing to draw) are
// left out: a drawn frame takes longer.
function timeCallbacks() {
  const times = (window.__armlabCallbackMs = []);
  const request = window.requestAnimationFrame.bind(window);
  window.requestAnimationFrame = (callback) => request((time) => {
    const start = performance.now();
    try { callback(time); } finally { times.push(performance.now() - start); }
  });
}
const takeCallbacks = (page) => page.evaluate(() => window.__armlabCallbackMs.splice(0).filter((ms) => ms >= 0.3));

const all = [];
const allCallbacks = [];
for (let run = 1; run <= runs; run++) {
  const ctx = await browser.newContext({ viewport: VIEW, deviceScaleFactor: 1 });
  await ctx.addInitScript(timeCallbacks);
  if (noMirror) await ctx.addInitScript(() => { window.armlabNoMirror = true; });
  const page = await ctx.newPage();
  await page.goto(`${base}#robot=ur10&q=0,-1,1.2,-1.5,-1.2,0.3&task=position`, { waitUntil: 'domcontentloaded' });
  await page.waitForFunction(() => {
    const text = window.armlab?.state();
    return Boolean(text) && JSON.parse(text).rendered;
  }, null, { timeout: 120000 });
  if (pin) pinRendererMainThread();
  const t = await page.evaluate(() => window.armlab.screenPoint('target'));
  const b = await page.evaluate(() => window.armlab.screenPoint('base'));
  await page.mouse.move(t.x, t.y);
  await page.mouse.down();
  await page.evaluate(() => window.armlab.frameTimes());
  await takeCallbacks(page);
  const frames = [];
  // Back and forth along the line toward the base, a pixel or two per event.
  for (let i = 0; frames.length < wanted && i < 20 * wanted; i++) {
    const phase = (i % 120) / 120;
    const f = 0.3 * (phase < 0.5 ? phase * 2 : 2 - phase * 2);
    await page.mouse.move(t.x + (b.x - t.x) * f, t.y + (b.y - t.y) * f);
    if (i % 20 === 19) frames.push(...await page.evaluate(() => window.armlab.frameTimes()));
  }
  frames.push(...await page.evaluate(() => window.armlab.frameTimes()));
  const callbacks = await takeCallbacks(page);
  await page.mouse.up();
  const s = await state(page);
  const how = [pin && 'main thread pinned', eager && 'wasm optimised up front'].filter(Boolean).join(', ');
  const r = report(`run ${run}${how ? ` (${how})` : ''}`, frames, callbacks);
  r.dragging_ended_reached = s.reached;
  console.log(JSON.stringify(r));
  all.push(...frames);
  allCallbacks.push(...callbacks);
  await ctx.close();
}
console.log(JSON.stringify(report(`all ${runs} runs of ${dist}`, all, allCallbacks)));
await browser.close();
server.close();
