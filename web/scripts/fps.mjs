// Frames per second of a built page while the view orbits and while the target is dragged,
// at three screen sizes, beside a three.js page of a similar scene (web/bench/three.html)
// in the same run: a benchmark, it prints figures and asserts nothing, and it is not part
// of the test command. Headless Chromium draws through SwiftShader here (no GPU), and on a
// 2-core machine the figures move with the load: the ratio to the three.js page, measured
// minutes apart in one run, is what holds.
//
//   node web/scripts/fps.mjs DIST_DIR [seconds=5] [--sizes=1024x768,1366x768,1920x1080]
//
// Each measurement opens a fresh page at the size (DPR 1), presses the left button (on an
// empty spot of the 3D view to orbit, on the target's ball to drag it) and then moves the
// pointer a few pixels per event, 60 events a second from a timer in the page, for
// `seconds`; it prints the frames the page drew over that wall time (`fps`: egui's frames
// for the app, three.js renders for the reference) and the moves the timer sent
// (`moves_per_s`: under 60 when the page's main thread was too busy to run it), one JSON
// line each, then a table.
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { serveDist, launchChromium } from '../tests/static-server.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const args = process.argv.slice(2);
const option = (name) => args.find((a) => a.startsWith(`--${name}=`))?.slice(name.length + 3);
const [distArg, secondsArg] = args.filter((a) => !a.startsWith('--'));
if (!distArg) {
  console.error('usage: node web/scripts/fps.mjs DIST_DIR [seconds] [--sizes=WxH,...]');
  process.exit(2);
}
const seconds = Number(secondsArg ?? 5);
const sizes = (option('sizes') ?? '1024x768,1366x768,1920x1080').split(',').map((s) => {
  const [width, height] = s.split('x').map(Number);
  return { width, height };
});
const app = await serveDist(path.resolve(distArg));
const bench = await serveDist(path.resolve(here, '..'));
const browser = await launchChromium();

const HASH = '#robot=ur10&q=0,-1,1.2,-1.5,-1.2,0.3&task=position';

// The app: its frame counter, the target's and an empty spot's screen points.
const armlab = {
  name: 'armlab',
  url: app.base + HASH,
  ready: () => {
    const text = window.armlab?.state();
    return Boolean(text) && JSON.parse(text).rendered;
  },
  frames: (page) => page.evaluate(() => JSON.parse(window.armlab.state()).frame),
  target: (page) => page.evaluate(() => window.armlab.screenPoint('target')),
  // Below the base, on the floor: no handle there, so a press orbits.
  empty: async (page) => {
    const b = await page.evaluate(() => window.armlab.screenPoint('base'));
    return { x: b.x, y: b.y + 40 };
  },
};

const three = {
  name: 'three.js',
  url: `${bench.base}bench/three.html`,
  ready: () => Boolean(window.bench?.ready) && window.bench.frames() > 0,
  frames: (page) => page.evaluate(() => window.bench.frames()),
  target: (page) => page.evaluate(() => window.bench.target()),
  empty: async (page) => {
    const v = page.viewportSize();
    return { x: v.width * 0.3, y: v.height * 0.8 };
  },
};

async function measure(subject, size, mode) {
  const ctx = await browser.newContext({ viewport: size, deviceScaleFactor: 1 });
  if (option('init')) await ctx.addInitScript(option('init'));
  const page = await ctx.newPage();
  await page.goto(subject.url, { waitUntil: 'domcontentloaded' });
  await page.waitForFunction(subject.ready, null, { timeout: 120000 });
  await page.waitForTimeout(300);
  const start = mode === 'drag' ? await subject.target(page) : await subject.empty(page);
  await page.mouse.move(start.x, start.y);
  await page.mouse.down();
  // A few warm-up moves, so the shaders and the first drag's set-up are not counted.
  for (let i = 0; i < 10; i++) await page.mouse.move(start.x + i, start.y);
  const frames0 = await subject.frames(page);
  // The moves come from the page itself, 60 a second as a mouse sends them, each a
  // `mousemove` at the canvas (what eframe and the three.js page listen to): they queue
  // while a frame is being drawn, as a person's do, and each frame takes what came.
  const { elapsed, moves } = await page.evaluate(({ start, mode, seconds }) => new Promise((resolve) => {
    const canvas = document.querySelector('canvas');
    const t0 = performance.now();
    let moves = 0;
    const timer = setInterval(() => {
      // Back and forth, 3 px a move: 40 px for a drag, 240 px for an orbit.
      const span = mode === 'drag' ? 40 : 240;
      const phase = (moves * 3) % (2 * span);
      const dx = phase < span ? phase : 2 * span - phase;
      const x = start.x - dx;
      const y = start.y - (mode === 'drag' ? dx / 2 : 0);
      canvas.dispatchEvent(new MouseEvent('mousemove', { clientX: x, clientY: y, buttons: 1, bubbles: true }));
      moves++;
      if (performance.now() - t0 >= seconds * 1000) {
        clearInterval(timer);
        resolve({ elapsed: (performance.now() - t0) / 1000, moves });
      }
    }, 16);
  }), { start, mode, seconds });
  const frames = (await subject.frames(page)) - frames0;
  await page.mouse.up();
  await ctx.close();
  return { page: subject.name, size: `${size.width}x${size.height}`, mode,
    fps: +(frames / elapsed).toFixed(1), moves_per_s: +(moves / elapsed).toFixed(1) };
}

const rows = [];
for (const size of sizes) {
  for (const mode of ['orbit', 'drag']) {
    for (const subject of [armlab, three]) {
      const row = await measure(subject, size, mode);
      console.log(JSON.stringify(row));
      rows.push(row);
    }
  }
}
console.log(`\n| size | mode | ArmLab frames/s | three.js frames/s | ratio |\n|---|---|---|---|---|`);
for (let i = 0; i < rows.length; i += 2) {
  const [a, t] = [rows[i], rows[i + 1]];
  console.log(`| ${a.size} | ${a.mode} | ${a.fps} | ${t.fps} | ${(a.fps / t.fps).toFixed(2)} |`);
}
await browser.close();
app.server.close();
bench.server.close();
