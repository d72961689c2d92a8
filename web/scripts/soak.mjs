// A long lecture in headless Chromium: for ARMLAB_SOAK_MINUTES (10 by default)
// the page is used as a class uses it — the target dragged, robots switched, a DH cell
// edited, IK solved — and once a minute the JS heap and the wasm memory are sampled.
// Not part of the test command: `node web/scripts/soak.mjs` after `bash tools/test.sh` (or any
// `trunk build --release`) has left the page in dist/.
//
// Prints one JSON line: the samples, the wasm memory's growth between minute 2 and the
// end (it only grows, in steps: 0 means no leak there), the JS heap's change over the
// same minutes in per cent, the slowest frame after the first two minutes, and the counts
// of each action. Exits non-zero when the wasm memory grew after minute 2, the JS heap
// moved by more than 5 %, or the page logged an error.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { serveDist, launchChromium } from '../tests/static-server.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const dist = process.env.ARMLAB_DIST ? path.resolve(process.env.ARMLAB_DIST) : path.resolve(here, '..', '..', 'dist');
const minutes = Number(process.env.ARMLAB_SOAK_MINUTES ?? 10);
const ROBOTS = ['ur10', 'puma560', 'panda', 'rrr', 'scara', 'metrover', 'ur10-standard', 'stanford'];

if (!fs.existsSync(path.join(dist, 'index.html'))) {
  console.error(`No built page in ${dist}: run bash tools/test.sh (or trunk build --release) first.`);
  process.exit(2);
}
const { server, base } = await serveDist(dist);
const browser = await launchChromium(['--enable-precise-memory-info']);
const ctx = await browser.newContext({ viewport: { width: 1366, height: 768 } });
const page = await ctx.newPage();
const errors = [];
page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
page.on('pageerror', (e) => errors.push(String(e)));
await page.goto(`${base}#robot=ur10&task=position&panels=joints,ik,robot`);
await page.waitForFunction(() => { const t = window.armlab?.state(); return Boolean(t) && JSON.parse(t).rendered; }, null, { timeout: 120000 });

const cdp = await ctx.newCDPSession(page);
const state = async () => JSON.parse(await page.evaluate(() => window.armlab.state()));
const point = (name) => page.evaluate((n) => window.armlab.screenPoint(n), name);
const sample = async (minute) => {
  await cdp.send('HeapProfiler.collectGarbage');
  const heap = await cdp.send('Runtime.getHeapUsage');
  const wasm = await page.evaluate(() => window.armlab.memoryBytes());
  return { minute, js_heap_bytes: heap.usedSize, wasm_memory_bytes: wasm };
};

const counts = { drags: 0, robots: 0, dh_edits: 0, solves: 0 };
async function drag() {
  const from = await point('target');
  const base = await point('base');
  if (!from || !base) return;
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  for (let i = 1; i <= 20; i++) {
    const k = Math.sin((i / 20) * Math.PI) * 0.3;
    await page.mouse.move(from.x + (base.x - from.x) * k, from.y + (base.y - from.y) * k);
  }
  await page.mouse.up();
  counts.drags += 1;
}
async function switchRobot(i) {
  await page.evaluate((r) => window.armlab.open(`#robot=${r}&task=position&panels=joints,ik,robot`), ROBOTS[i % ROBOTS.length]);
  await page.mouse.move(10, 10);
  await page.mouse.move(11, 10);
  counts.robots += 1;
}
async function editDh(i) {
  const header = await point('dh-header');
  if (!header) return;
  await page.mouse.click(header.x, header.y);
  const cell = await point('dh-1-2');
  if (!cell) return;
  await page.mouse.click(cell.x, cell.y);
  await page.keyboard.press('Control+A');
  await page.keyboard.type(String(0.1 + (i % 7) * 0.05));
  await page.keyboard.press('Escape');
  counts.dh_edits += 1;
}
async function solve() {
  const button = await point('ik-solve');
  if (!button) return;
  await page.mouse.click(button.x, button.y);
  counts.solves += 1;
}

const samples = [await sample(0)];
const slowest = { after_warmup_ms: 0 };
const started = Date.now();
let round = 0;
while (Date.now() - started < minutes * 60000) {
  await drag();
  if (round % 3 === 0) await switchRobot(round / 3);
  if (round % 4 === 1) await editDh(round);
  if (round % 2 === 0) await solve();
  const frames = await page.evaluate(() => window.armlab.frameTimes());
  if (Date.now() - started > 2 * 60000) {
    for (const f of frames) slowest.after_warmup_ms = Math.max(slowest.after_warmup_ms, f.app + f.render);
  }
  const minute = Math.floor((Date.now() - started) / 60000);
  if (minute > samples[samples.length - 1].minute) samples.push(await sample(minute));
  round += 1;
}
samples.push(await sample(minutes));
const at2 = samples.find((s) => s.minute >= 2) ?? samples[0];
const last = samples[samples.length - 1];
const result = {
  minutes,
  samples,
  wasm_growth_after_minute_2_bytes: last.wasm_memory_bytes - at2.wasm_memory_bytes,
  js_heap_change_after_minute_2_percent: +(((last.js_heap_bytes - at2.js_heap_bytes) / at2.js_heap_bytes) * 100).toFixed(2),
  slowest_frame_after_warmup_ms: +slowest.after_warmup_ms.toFixed(2),
  actions: counts,
  final_robot: (await state()).robot,
  console_errors: errors,
};
console.log(`ARMLAB_SOAK ${JSON.stringify(result)}`);
await browser.close();
server.close();
const ok = result.wasm_growth_after_minute_2_bytes === 0
  && Math.abs(result.js_heap_change_after_minute_2_percent) <= 5 && errors.length === 0;
process.exit(ok ? 0 : 1);
