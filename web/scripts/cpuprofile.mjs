// A CPU profile of a built page while the UR10 target is dragged, as frametimes.mjs drags
// it (a benchmark tool: it asserts nothing, and it is not part of the test command).
//
//   node web/scripts/cpuprofile.mjs DIST_DIR [out.cpuprofile] [moves=400]
//
// Writes the Chrome DevTools profile (open it in DevTools' Performance panel, or read it
// as JSON) and prints the functions that take the largest shares of the app's frame
// (`ArmLabApp::ui`, inclusive) as JSON. The page's wasm has no function names after
// wasm-opt's --strip-debug; for a profile that names them, build with `-g` in its place
// in index.html's data-wasm-opt-params (tools/setup.sh's build_web --dist DIR), and put
// index.html back afterwards. The profiler slows the page several times over: read
// shares, not times.
import fs from 'node:fs';
import path from 'node:path';
import { serveDist, launchChromium } from '../tests/static-server.mjs';

const [distArg, outArg, movesArg] = process.argv.slice(2);
if (!distArg) {
  console.error('usage: node web/scripts/cpuprofile.mjs DIST_DIR [out.cpuprofile] [moves]');
  process.exit(2);
}
const out = outArg ?? 'page.cpuprofile';
const moves = Number(movesArg ?? 400);
const { server, base } = await serveDist(path.resolve(distArg));
const browser = await launchChromium();
const ctx = await browser.newContext({ viewport: { width: 1400, height: 860 }, deviceScaleFactor: 1 });
const page = await ctx.newPage();
await page.goto(`${base}#robot=ur10&q=0,-1,1.2,-1.5,-1.2,0.3&task=position`);
await page.waitForFunction(() => {
  const text = window.armlab?.state();
  return Boolean(text) && JSON.parse(text).rendered;
}, null, { timeout: 120000 });
const t = await page.evaluate(() => window.armlab.screenPoint('target'));
const b = await page.evaluate(() => window.armlab.screenPoint('base'));
// Back and forth along the line toward the base, as frametimes.mjs drags.
const moveTo = (i) => {
  const phase = (i % 120) / 120;
  const f = 0.3 * (phase < 0.5 ? phase * 2 : 2 - phase * 2);
  return page.mouse.move(t.x + (b.x - t.x) * f, t.y + (b.y - t.y) * f);
};
await page.mouse.move(t.x, t.y);
await page.mouse.down();
for (let i = 0; i < 60; i++) await moveTo(i); // warm-up, not profiled
const cdp = await ctx.newCDPSession(page);
await cdp.send('Profiler.enable');
await cdp.send('Profiler.setSamplingInterval', { interval: 100 });
await cdp.send('Profiler.start');
for (let i = 0; i < moves; i++) await moveTo(i);
const { profile } = await cdp.send('Profiler.stop');
await page.mouse.up();
fs.writeFileSync(out, JSON.stringify(profile));
await browser.close();
server.close();

// Inclusive samples per function name under the app's frame (a function counted once
// per sample however deep it recurses).
const nodes = new Map(profile.nodes.map((n) => [n.id, n]));
const parent = new Map();
for (const n of profile.nodes) for (const c of n.children ?? []) parent.set(c, n.id);
const named = (id) => (nodes.get(id).callFrame.functionName || '(anonymous)').replace(/\[[0-9a-f]{16}\]|::h[0-9a-f]{16}$/g, '');
const counts = new Map();
for (const id of profile.samples) counts.set(id, (counts.get(id) ?? 0) + 1);
let frame = 0;
const inclusive = new Map();
for (const [id, count] of counts) {
  const stack = new Set();
  for (let x = id; x !== undefined; x = parent.get(x)) stack.add(named(x));
  if (![...stack].some((f) => f.includes('ArmLabApp as eframe::epi::App>::ui'))) continue;
  frame += count;
  for (const f of stack) inclusive.set(f, (inclusive.get(f) ?? 0) + count);
}
const top = [...inclusive].filter(([f]) => /armlab|egui|epaint|wgpu/.test(f))
  .sort((x, y) => y[1] - x[1]).slice(0, 30)
  .map(([f, n]) => ({ share_pct: +(100 * n / Math.max(frame, 1)).toFixed(1), function: f.slice(0, 140) }));
console.log(JSON.stringify({ profile: out, frame_samples: frame, top }, null, 1));
