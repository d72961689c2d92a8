// The lecture-hall PC: Chrome without a GPU draws WebGL2 with its software renderer
// (SwiftShader, as this headless Chromium does), where every pixel and MSAA sample is the
// CPU's work. There the 3D view draws a moving scene with fewer pixels and no MSAA, and
// the full-quality picture, the same as on a GPU, once the scene rests. Here at 1366×768:
// an orbit and a drag with the frames per second printed (not asserted: timing on a
// shared machine), and the moving picture against the resting one where the arm's tool
// and the target are.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { browserSuite } from './browser-suite.mjs';
import { dist, shots, state, point, pageOpener, pixels, at, close } from './page.mjs';

const measurements = {};
const suite = browserSuite(dist, { label: 'ARMLAB_LECTURE_HALL_MEASUREMENTS', measurements });
const VIEW = { width: 1366, height: 768 };
const { open } = pageOpener(suite, { view: VIEW });
const HASH = '#robot=ur10&q=0.4,-1.1,1.3,-1.6,-1.4,0.2&task=position';


/**
 * With the left button held at `from`, moves the pointer back and forth (`span` px to the
 * left and `span / 2` up, 3 px a move) for `ms`, 60 moves a second from a timer in the
 * page as a mouse sends them; returns the frames the app drew a second meanwhile, and
 * whether any of them showed a moving picture.
 */
async function framesPerSecond(page, from, span, ms) {
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  for (let i = 1; i <= 5; i++) await page.mouse.move(from.x - i, from.y);
  const frame0 = (await state(page)).frame;
  const { seconds, moving } = await page.evaluate(({ from, span, ms }) => new Promise((resolve) => {
    const canvas = document.querySelector('canvas');
    const t0 = performance.now();
    let n = 0;
    let moving = false;
    const timer = setInterval(() => {
      const phase = (n++ * 3) % (2 * span);
      const d = phase < span ? phase : 2 * span - phase;
      canvas.dispatchEvent(new MouseEvent('mousemove', { clientX: from.x - d, clientY: from.y - d / 2, buttons: 1, bubbles: true }));
      moving ||= JSON.parse(window.armlab.state()).moving_picture;
      if (performance.now() - t0 >= ms) {
        clearInterval(timer);
        resolve({ seconds: (performance.now() - t0) / 1000, moving });
      }
    }, 16);
  }), { from, span, ms });
  const frames = (await state(page)).frame - frame0;
  await page.mouse.up();
  return { fps: +(frames / seconds).toFixed(1), moving };
}

/**
 * Installed in the page: after each animation frame's callback (egui's paint), when
 * `window.__grab` asks for a picture of the kind (`moving`) with the target drawn at `at`,
 * copies the canvas in that same frame (a WebGL canvas keeps its picture only until the
 * frame ends) into `window.__grabbed`, a PNG data URL. Only a callback in which the app drew
 * a frame counts.
 */
function grabber() {
  const request = window.requestAnimationFrame;
  window.requestAnimationFrame = (callback) => request((time) => {
    const before = window.__grab && JSON.parse(window.armlab.state()).frame;
    callback(time);
    const want = window.__grab;
    if (!want) return;
    const s = JSON.parse(window.armlab.state());
    const t = window.armlab.screenPoint('target');
    // A callback that drew nothing leaves a canvas the browser has already shown and
    // cleared: only a frame the app drew in this callback is copied.
    if (s.frame === before) return;
    if (s.moving_picture !== want.moving || !t || Math.hypot(t.x - want.at.x, t.y - want.at.y) > 0.01) return;
    const canvas = document.querySelector('canvas');
    const copy = document.createElement('canvas');
    copy.width = canvas.width;
    copy.height = canvas.height;
    copy.getContext('2d').drawImage(canvas, 0, 0);
    window.__grabbed = copy.toDataURL('image/png');
    window.__grab = null;
  });
}

/** The next frame's picture of the kind asked (see `grabber`), as pixels. */
async function grab(page, moving, at) {
  await page.evaluate(({ moving, at }) => { window.__grabbed = null; window.__grab = { moving, at }; }, { moving, at });
  if (!moving) await page.mouse.move(at.x, 20);
  await page.waitForFunction(() => window.__grabbed, null, { timeout: 20000 });
  const url = await page.evaluate(() => window.__grabbed);
  const png = Buffer.from(url.slice(url.indexOf(',') + 1), 'base64');
  fs.writeFileSync(path.join(shots, `lecturehall-${moving ? 'moving' : 'sharp'}.png`), png);
  return pixels(page, png);
}

/** Waits past the rest time until the view shows its full-quality picture. */
async function rested(page) {
  await page.waitForTimeout(600);
  await page.waitForFunction(() => !JSON.parse(window.armlab.state()).moving_picture, null, { timeout: 10000 });
}

test('on the software renderer at 1366×768 the view orbits and drags; its moving picture shows the same arm and target', async () => {
  const { page, ctx, errors } = await open(HASH);
  const renderer = await page.evaluate(() => {
    const gl = document.createElement('canvas').getContext('webgl2');
    const info = gl.getExtension('WEBGL_debug_renderer_info');
    return gl.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : gl.RENDERER);
  });
  measurements.renderer = renderer;
  assert.match(renderer, /SwiftShader|llvmpipe/i, 'the browser draws with a software renderer (launched with --disable-gpu)');

  await rested(page);
  const target = await point(page, 'target');
  const tool = await point(page, 'tool');
  const base = await point(page, 'base');
  await page.evaluate(grabber);
  const sharp = await grab(page, false, target);

  // Orbit right and back to where the press began (the camera turns by the pointer's
  // path, so it ends where it started): the frame that shows the camera back there
  // draws the moving picture, copied from the canvas in that frame.
  const empty = { x: base.x, y: base.y + 40 };
  await page.mouse.move(empty.x, empty.y);
  await page.mouse.down();
  await page.mouse.move(empty.x + 30, empty.y, { steps: 3 });
  await page.mouse.move(empty.x + 10, empty.y, { steps: 2 });
  const grabbed = grab(page, true, target);
  await page.mouse.move(empty.x, empty.y);
  const moving = await grabbed;
  await page.mouse.up();
  await rested(page);
  // The same arm and target where the tool and the target are (and the base): the
  // moving picture has a quarter of the pixels, its colours there stay. One of its texels
  // covers two pixels each way, so near an edge a pixel of it shows what the sharp
  // picture shows a pixel away: each colour is looked for within a pixel.
  for (const [name, p] of [['target', target], ['tool', tool], ['base', base]]) {
    for (const [dx, dy] of [[0, 0], [-2, 0], [2, 0], [0, -2], [0, 2]]) {
      const b = at(moving, p.x + dx, p.y + dy);
      const near = [-1, 0, 1].flatMap((ex) => [-1, 0, 1].map((ey) => at(sharp, p.x + dx + ex, p.y + dy + ey)));
      const a = at(sharp, p.x + dx, p.y + dy);
      assert.ok(near.some((c) => close(c, b, 24)), `at the ${name} (${dx}, ${dy}): moving ${b}, sharp ${a} (${near.join(' ')} around it)`);
    }
  }
  // ... and it is the moving picture: the edges differ.
  let differ = 0;
  for (let y = 0; y < VIEW.height; y += 2) {
    for (let x = 0; x < VIEW.width; x += 2) {
      if (!close(at(sharp, x, y), at(moving, x, y), 24)) differ++;
    }
  }
  measurements.moving_pixels_differing_of_every_4th = differ;
  assert.ok(differ > 20, `the moving picture differs from the sharp one at edges (${differ} samples)`);
  // At rest again, the sharp picture.
  const again = await grab(page, false, target);
  for (const p of [target, tool, base]) assert.deepEqual(at(again, p.x, p.y), at(sharp, p.x, p.y));

  const orbit = await framesPerSecond(page, empty, 240, 3000);
  measurements.orbit_fps = orbit.fps;
  assert.ok(orbit.moving, 'the orbit drew moving pictures');
  await rested(page);
  const drag = await framesPerSecond(page, await point(page, 'target'), 40, 3000);
  measurements.drag_fps = drag.fps;
  assert.ok(drag.moving, 'the drag drew moving pictures');
  assert.deepEqual(errors, []);
  await ctx.close();
});
