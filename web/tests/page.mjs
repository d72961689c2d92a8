// What the browser test files share besides their set-up (browser-suite.mjs): where the
// built page is, reading the test hook (window.armlab, docs/test-hook.md), waiting for the
// app's frames, and opening a fresh page with its errors collected. Not a *.test.mjs file,
// so the test command does not run it on its own.
import { after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
/** The built page (`trunk build --release`): ARMLAB_DIST, else dist/ at the repository's top. */
export const dist = process.env.ARMLAB_DIST ? path.resolve(process.env.ARMLAB_DIST) : path.resolve(here, '..', '..', 'dist');
/** Where the tests leave their screenshots (not kept in git). */
export const shots = path.resolve(here, 'screenshots');
fs.mkdirSync(shots, { recursive: true });
/** The desktop size the page opens at unless a file or a test asks for another. */
export const VIEW = { width: 1400, height: 860 };

/** The screens people use: projectors, laptops, a portrait tablet, a phone (touch, DPR 2). */
export const SCREENS = [
  { name: 'projector-1024x768', width: 1024, height: 768 },
  { name: 'projector-1280x720', width: 1280, height: 720 },
  { name: 'laptop-1366x768', width: 1366, height: 768 },
  { name: 'laptop-1920x1080', width: 1920, height: 1080 },
  { name: 'tablet-820x1180', width: 820, height: 1180, touch: true },
  { name: 'phone-390x844', width: 390, height: 844, touch: true, dpr: 2 },
];

/** The app's state, as window.armlab.state() publishes it. */
export const state = async (page) => JSON.parse(await page.evaluate(() => window.armlab.state()));

/** Of the paths a page requested, those of dist/urdf/ (the URDF and collision module). */
export const moduleRequests = (requests) => requests.filter((p) => p.includes('/urdf/'));

/** Where the app drew `name` (window.armlab.screenPoint); fails when it is not on screen. */
export async function point(page, name) {
  const p = await page.evaluate((n) => window.armlab.screenPoint(n), name);
  assert.ok(p, `screenPoint("${name}") is on screen`);
  return p;
}

/** Waits (up to 2 minutes) until the app has drawn its first frame. */
export async function rendered(page) {
  await page.waitForFunction(() => {
    const text = window.armlab?.state();
    return Boolean(text) && JSON.parse(text).rendered;
  }, null, { timeout: 120000 });
}

/** Waits until the app has drawn a few more frames (egui draws on input: nudge it). */
export async function settle(page, frames = 3) {
  const start = (await state(page)).frame;
  const size = page.viewportSize() ?? VIEW;
  for (let i = 0; i < 400; i++) {
    await page.mouse.move(size.width / 2 - (i % 2), 40);
    if ((await state(page)).frame >= start + frames) return;
    await page.waitForTimeout(20);
  }
  throw new Error('the app stopped drawing frames');
}

/**
 * Waits until the app's frame count reaches `frame` after input already sent (a key, a
 * wheel), drawing no frame of its own unless none comes for half a second (then one, as
 * `settle` does). A key's frame and the one egui draws after every input come by
 * themselves; a nudge of the pointer is one input more, so a frame and its follow-up
 * more, each about a tenth of a CPU-second on the software renderer.
 */
export async function drawnTo(page, frame) {
  for (let i = 0; i < 25; i++) {
    if ((await state(page)).frame >= frame) return;
    await page.waitForTimeout(20);
  }
  await settle(page, 1);
}

/** The first frame drawn, and a few more. */
export async function ready(page) {
  await rendered(page);
  await settle(page);
}

/**
 * Waits until `check(state)` holds, nudging the pointer at (`x`, 40) so that egui draws
 * frames (`x` by default the middle of the page): `tries` reads, `pause` ms apart, then it
 * fails with `detail(state)`.
 */
export async function until(page, check, what, { tries = 600, pause = 20, x, detail = (s) => s } = {}) {
  const at = x ?? (page.viewportSize() ?? VIEW).width / 2;
  for (let i = 0; i < tries; i++) {
    const s = await state(page);
    if (check(s)) return s;
    await page.mouse.move(at - (i % 2), 40);
    await page.waitForTimeout(pause);
  }
  throw new Error(`waited ${(tries * pause) / 1000} s for ${what}: ${JSON.stringify(detail(await state(page)))}`);
}

/**
 * Where the app drew `name` in two frames running: a panel that is still laying itself out
 * (its first frames, a fold opening, a line appearing above) moves its widgets between
 * frames, and a click at the older place misses.
 */
export async function steadyPoint(page, name) {
  let p = await point(page, name);
  for (let i = 0; i < 20; i++) {
    await settle(page, 1);
    const q = await point(page, name);
    if (q.x === p.x && q.y === p.y) return q;
    p = q;
  }
  throw new Error(`"${name}" kept moving for 20 frames`);
}

/** Clicks where the app draws `name` (steadyPoint), then waits for `frames` more frames
 * (none: no wait). */
export async function click(page, name, frames = 3) {
  const p = await steadyPoint(page, name);
  await page.mouse.click(p.x, p.y);
  if (frames > 0) await settle(page, frames);
}

/** Clicks the DH cell `cellName` (then runs `afterClick`), selects all of it and types
 * `text` in its place at the keyboard's full speed. */
export async function retype(page, cellName, text, afterClick = async () => {}) {
  const cell = await point(page, cellName);
  await page.mouse.click(cell.x, cell.y);
  await afterClick();
  await page.keyboard.press('Control+A');
  await page.keyboard.type(text);
}

/** Opens the DH table, clicks a cell, selects its text and types over it. */
export async function typeIntoDhCell(page, cellName, text) {
  const header = await point(page, 'dh-header');
  await page.mouse.click(header.x, header.y);
  await settle(page);
  await retype(page, cellName, text, () => settle(page));
  await settle(page, 4);
}

/**
 * A page in a context of its own (a fresh one at `view`, DPR 1, with `contextOptions`,
 * unless `context` is given). `errors` collects the page's uncaught exceptions and, with
 * `consoleErrors`, what it logs as console errors too.
 */
export async function newPage(browser, { context, view = VIEW, contextOptions = {}, consoleErrors = true } = {}) {
  const ctx = context ?? await browser.newContext({ viewport: view, deviceScaleFactor: 1, ...contextOptions });
  const page = await ctx.newPage();
  const errors = [];
  if (consoleErrors) page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(String(e)));
  return { ctx, page, errors };
}

/**
 * `open(hash, options)` and `openAt(screen, hash, contextOptions)` for the browser and
 * server of `suite` (browserSuite), each option defaulting to the file's `defaults`.
 *
 * `open` opens `hash` on a fresh page (newPage's options) and waits until the app has drawn
 * (and, with `settled`, a few frames more). Before the page loads it runs `setup(ctx, page)`
 * and, with `slowWasm`, holds the wasm back 1.5 s. It returns `{ page, ctx, errors, requests
 * (the path of every request of the context), loading (the page's text when its document
 * had loaded), started (Date.now() before the navigation) }`.
 *
 * `openAt` opens `hash` in a context at `screen`'s size and device pixel ratio, a touch
 * screen emulated as a mobile one.
 *
 * `openKept` opens `hash` as `open` does the first time and returns that same page to
 * every later call: for tests that only read the page (they leave it open and unchanged).
 */
export function pageOpener(suite, defaults = {}) {
  async function open(hash = '', options = {}) {
    const {
      setup = async () => {}, slowWasm = false, waitUntil = 'domcontentloaded', settled = true, ...pageOptions
    } = { ...defaults, ...options };
    const { ctx, page, errors } = await newPage(suite.browser, pageOptions);
    if (slowWasm) {
      // Hold the wasm back a moment so the page's loading text can be seen, as on slow Wi-Fi.
      await ctx.route(/_bg\.wasm(\.xz)?$/, async (route) => { await new Promise((r) => setTimeout(r, 1500)); await route.continue(); });
    }
    await setup(ctx, page);
    const requests = [];
    ctx.on('request', (r) => requests.push(new URL(r.url()).pathname));
    const started = Date.now();
    await page.goto(suite.base + hash, { waitUntil });
    const loading = await page.textContent('#armlab_message');
    if (settled) await ready(page); else await rendered(page);
    return { page, ctx, errors, requests, loading, started };
  }
  async function openAt(screen, hash, extra = {}) {
    const context = await suite.browser.newContext({
      viewport: { width: screen.width, height: screen.height },
      deviceScaleFactor: screen.dpr ?? 1,
      hasTouch: Boolean(screen.touch),
      isMobile: Boolean(screen.touch),
      ...extra,
    });
    return open(hash, { context });
  }
  // One page per hash for the tests that only read what it shows: a page load is about
  // 5 s of CPU on the software renderer, and the suite makes some 70.
  const kept = new Map();
  after(async () => { // before the browser closes, or with it (browserSuite's hook)
    if (!suite.browser?.isConnected()) return;
    for (const opened of kept.values()) await (await opened).ctx.close();
  });
  function openKept(hash) {
    if (!kept.has(hash)) kept.set(hash, open(hash));
    return kept.get(hash);
  }
  return { open, openAt, openKept };
}

/** Pixels of a PNG (as RGBA rows) decoded by the browser itself. The bytes come back as
 * base64 text: a plain array of millions of numbers takes the protocol about a minute. */
export async function pixels(page, png) {
  const { width, height, rgba } = await page.evaluate(async (b64) => {
    const img = new Image();
    img.src = `data:image/png;base64,${b64}`;
    await img.decode();
    const c = document.createElement('canvas');
    c.width = img.width; c.height = img.height;
    const g = c.getContext('2d');
    g.drawImage(img, 0, 0);
    const bytes = g.getImageData(0, 0, img.width, img.height).data;
    let text = '';
    for (let i = 0; i < bytes.length; i += 0x8000) text += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
    return { width: img.width, height: img.height, rgba: btoa(text) };
  }, png.toString('base64'));
  const data = Buffer.from(rgba, 'base64');
  assert.equal(data.length, width * height * 4, 'every pixel came back');
  return { width, height, data };
}
/** The RGB of pixel (`x`, `y`) of `pixels`' image. */
export const at = (img, x, y) => { const i = (Math.round(y) * img.width + Math.round(x)) * 4; return Array.from(img.data.subarray(i, i + 3)); };
/** Whether two colours differ by at most `tol` in each channel. */
export const close = (a, b, tol) => a.every((v, i) => Math.abs(v - b[i]) <= tol);
