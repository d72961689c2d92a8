// "Offline after one load": the built page (dist/, from `trunk build --release`) in Debian's
// headless Chromium, driven by playwright-core, served by an HTTP server of this test's own
// that the test then shuts down. (Playwright's setOffline does not reach a service worker's
// own fetches, so it would prove nothing: only a server that is gone shows that the page
// comes from the worker's cache.) The server answers `Cache-Control: no-store`, so nothing
// can come back from Chromium's HTTP cache either.
//
// Prints one JSON line of measurements (not asserted): navigation → first drawn frame for
// the first (cold) load from the server and for the load from the worker's cache.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import http from 'node:http';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import crypto from 'node:crypto';
import { execFileSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';
import { launchChromium } from './static-server.mjs';
import { dist, state, rendered as drawn, newPage, point, settle, until } from './page.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
// The target ball sits on the tool when a link opens: green (reached) where the tool is.
const HASH = '#robot=ur10&q=0.4,-1.1,1.3,-1.6,-1.4,0.2';
const WORKER = 'service-worker.js';
const measurements = {};
let browser;

const types = {
  '.html': 'text/html', '.js': 'text/javascript', '.wasm': 'application/wasm', '.svg': 'image/svg+xml',
  '.webmanifest': 'application/manifest+json', '.json': 'application/json', '.css': 'text/css',
};

/** Serves `dir` on a random port of 127.0.0.1. `close()` stops it and cuts every open
 * connection (keep-alive ones included), so the browser finds nothing there afterwards. */
async function serve(dir) {
  const sockets = new Set();
  const server = http.createServer((req, res) => {
    const { pathname } = new URL(req.url, 'http://localhost');
    let file = path.join(dir, decodeURIComponent(pathname));
    if (!file.startsWith(dir)) { res.writeHead(403); res.end(); return; }
    if (pathname.endsWith('/')) file = path.join(file, 'index.html');
    fs.readFile(file, (err, data) => {
      if (err) { res.writeHead(404); res.end('not found'); return; }
      res.writeHead(200, { 'content-type': types[path.extname(file)] ?? 'application/octet-stream', 'cache-control': 'no-store' });
      res.end(data);
    });
  });
  server.on('connection', (socket) => {
    sockets.add(socket);
    socket.on('close', () => sockets.delete(socket));
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  const url = `http://127.0.0.1:${server.address().port}/`;
  const close = async () => {
    const closed = new Promise((resolve) => server.close(resolve));
    for (const socket of sockets) socket.destroy();
    await closed;
    await assert.rejects(fetch(url), 'nothing answers at the server\'s address any more');
  };
  return { url, close };
}

before(async () => {
  assert.ok(fs.existsSync(path.join(dist, 'index.html')), 'dist/ holds the built page (trunk build --release)');
  browser = await launchChromium();
});

after(async () => {
  console.log(`ARMLAB_OFFLINE_MEASUREMENTS ${JSON.stringify(measurements)}`);
  await browser?.close();
});

/** Waits for the first drawn frame; returns its time in ms since navigation started. */
async function rendered(page) {
  await drawn(page);
  return Math.round(await page.evaluate(() => window.armlab.firstFrameAt()));
}

/** Waits until a service worker controls the page (the worker claims the page that
 * registered it once its files are cached); reloads once if it does not. */
async function controlled(page) {
  const wait = (timeout) => page.waitForFunction(() => navigator.serviceWorker.controller !== null, null, { timeout });
  try {
    await wait(60000);
  } catch {
    await page.reload({ waitUntil: 'domcontentloaded' });
    await wait(30000);
  }
}

/** The cache names of this origin and the number of entries in each. */
const caches = (page) => page.evaluate(async () => {
  const out = {};
  for (const name of await window.caches.keys()) out[name] = (await (await window.caches.open(name)).keys()).length;
  return out;
});

/** The worker's build line, as dist/service-worker.js (or the copy's) has it. */
function workerBuild(dir) {
  const first = fs.readFileSync(path.join(dir, WORKER), 'utf8').split('\n')[0];
  const match = /^const ARMLAB_BUILD = (\{.*\});$/.exec(first);
  assert.ok(match, `${WORKER} starts with the build's line: ${first.slice(0, 80)}`);
  return JSON.parse(match[1]);
}

/** The version a build of `dir` must carry: SHA-256 over each file (sorted by path, the
 * worker, dot files, the copies compressed ahead, `.br` and `.gz`, and the wasm the page
 * unpacks from its `.xz` left out) of "path\n" + the hex SHA-256 of its bytes + "\n". */
function expectedBuild(dir) {
  const files = fs.readdirSync(dir, { recursive: true, withFileTypes: true })
    .filter((e) => e.isFile())
    .map((e) => path.relative(dir, path.join(e.parentPath ?? e.path, e.name)).split(path.sep).join('/'))
    .filter((f) => f !== WORKER && !f.split('/').some((part) => part.startsWith('.')) && !/\.(br|gz)$/.test(f))
    .filter((f, _, files) => !files.includes(`${f}.xz`))
    .sort();
  const hash = crypto.createHash('sha256');
  for (const f of files) hash.update(`${f}\n${crypto.createHash('sha256').update(fs.readFileSync(path.join(dir, f))).digest('hex')}\n`);
  return { version: hash.digest('hex').slice(0, 16), files };
}

/** Checks that the arm is drawn: the canvas is not all background, and the target ball
 * (on the tool) is green where the app says it is. */
async function assertArmDrawn(page) {
  const s = await state(page);
  assert.equal(s.rendered, true);
  assert.equal(s.robot, 'UR10');
  const ball = await page.evaluate(() => window.armlab.screenPoint('target'));
  assert.ok(ball, 'the target ball is on screen');
  const png = await page.locator('#armlab_canvas').screenshot();
  // Decoded by the page itself (it needs no network for that): the share of pixels that
  // are not the page's background #1b1d21, and the colour at the ball.
  const seen = await page.evaluate(async ({ b64, x, y }) => {
    const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
    const bitmap = await createImageBitmap(new Blob([bytes], { type: 'image/png' }));
    const g = new OffscreenCanvas(bitmap.width, bitmap.height).getContext('2d');
    g.drawImage(bitmap, 0, 0);
    const { data } = g.getImageData(0, 0, bitmap.width, bitmap.height);
    let drawn = 0;
    for (let i = 0; i < data.length; i += 4) {
      if (Math.abs(data[i] - 0x1b) + Math.abs(data[i + 1] - 0x1d) + Math.abs(data[i + 2] - 0x21) > 12) drawn++;
    }
    const at = (Math.round(y) * bitmap.width + Math.round(x)) * 4;
    return { share: drawn / (data.length / 4), ball: Array.from(data.subarray(at, at + 3)) };
  }, { b64: png.toString('base64'), x: ball.x, y: ball.y });
  assert.ok(seen.share > 0.05, `the canvas is not all background (${(100 * seen.share).toFixed(1)} % drawn)`);
  const [r, g, b] = seen.ball;
  assert.ok(g > r + 40 && g > b + 20, `the target ball is drawn green at the tool: ${seen.ball}`);
}

test('the worker lists exactly the build\'s files, under a version hashed from their contents', () => {
  const build = workerBuild(dist);
  const expected = expectedBuild(dist);
  assert.deepEqual(build.files, expected.files);
  assert.equal(build.version, expected.version);
  for (const kind of [/^index\.html$/, /^armlab-[0-9a-f]+\.js$/, /^armlab-[0-9a-f]+_bg\.wasm\.xz$/, /^unxz-[0-9a-f]+\.js$/,
    /^manifest\.webmanifest$/, /^icon\.svg$/,
    /^urdf\/armlab_urdf\.js$/, /^urdf\/armlab_urdf-[0-9a-f]+_bg\.wasm\.xz$/]) {
    assert.ok(build.files.some((f) => kind.test(f)), `the worker caches ${kind}`);
  }
  const manifest = JSON.parse(fs.readFileSync(path.join(dist, 'manifest.webmanifest'), 'utf8'));
  assert.equal(manifest.name, 'ArmLab');
  assert.ok(manifest.icons.every((icon) => build.files.includes(icon.src)), 'the manifest\'s icons are cached');
});

test('after one visit the page opens and draws the arm with the server gone, and the lazy module (symbolic matrices) loads', async () => {
  const server = await serve(dist);
  const { ctx: context, page, errors } = await newPage(browser);
  try {
    await page.goto(server.url + HASH, { waitUntil: 'domcontentloaded' });
    measurements.cold_first_frame_ms = await rendered(page);
    await controlled(page);
    const { version, files } = workerBuild(dist);
    const cached = await caches(page);
    assert.equal(Object.keys(cached).length, 1, `one cache: ${JSON.stringify(cached)}`);
    assert.ok(Object.keys(cached)[0].endsWith(` ${version}`), `the cache is named by the build's version ${version}`);
    assert.equal(Object.values(cached)[0], files.length, 'the cache holds every file of the build');

    await server.close();
    await page.reload({ waitUntil: 'domcontentloaded' });
    measurements.offline_first_frame_ms = await rendered(page);
    await assertArmDrawn(page);
    assert.deepEqual((await state(page)).q.map((v) => +v.toFixed(6)), [0.4, -1.1, 1.3, -1.6, -1.4, 0.2], 'the link\'s pose');

    // The module the page fetches later (here for the symbolic matrices) comes from the
    // cache too. Tall, so that the Matrices panel's "symbolic" tick is on screen.
    await page.setViewportSize({ width: 1400, height: 1400 });
    await page.evaluate((h) => window.armlab.open(h), '#robot=rrr&panels=matrices');
    await until(page, (s) => s.preset === 'rrr', 'the RRR');
    // A few frames for the taller page's columns to take their places: a point read in the
    // frame the robot changed can be where the tick no longer is.
    await settle(page, 3);
    const tick = await point(page, 'matrices-symbolic');
    await page.mouse.click(tick.x, tick.y);
    await until(page, (s) => s.symbolic === 'ready: c1(222.1 c2 + 136.2 c23) | s1(222.1 c2 + 136.2 c23) | 100.9 + 222.1 s2 + 136.2 s23', 'the symbolic T_03 offline');
    assert.deepEqual(errors, []);
  } finally {
    await context.close();
    await server.close().catch(() => {});
  }
});

test('a new build\'s worker replaces the cache on the next load', async () => {
  // A copy of dist/ to build "again": index.html changes, then the hook writes the worker.
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armlab-offline-'));
  fs.cpSync(dist, dir, { recursive: true });
  const server = await serve(dir);
  const { ctx: context, page, errors } = await newPage(browser);
  try {
    await page.goto(server.url + HASH, { waitUntil: 'domcontentloaded' });
    await rendered(page);
    await controlled(page);
    const first = workerBuild(dir).version;
    assert.deepEqual(Object.keys(await caches(page)).map((name) => name.split(' ').at(-1)), [first]);

    const marker = '<!-- the second build -->';
    const index = path.join(dir, 'index.html');
    fs.appendFileSync(index, marker);
    execFileSync(process.execPath, [path.join(here, '..', 'build', 'service-worker-build.mjs')], { env: { ...process.env, TRUNK_STAGING_DIR: dir } });
    const second = workerBuild(dir);
    assert.notEqual(second.version, first, 'another build, another version');
    assert.deepEqual(second, expectedBuild(dir));

    // One reload: the page is already the second build (index.html comes from the network
    // first), and the browser finds the changed worker, which installs, takes over and
    // deletes the first build's cache.
    const reloaded = Date.now();
    await page.reload({ waitUntil: 'domcontentloaded' });
    await rendered(page);
    assert.ok((await page.content()).includes(marker), 'online, the reload shows the second build at once');
    const deadline = Date.now() + 60000;
    let names;
    do {
      await page.waitForTimeout(250);
      names = Object.keys(await caches(page));
    } while (!(names.length === 1 && names[0].endsWith(` ${second.version}`)) && Date.now() < deadline);
    assert.deepEqual(names.map((name) => name.split(' ').at(-1)), [second.version], 'only the second build\'s cache is left');
    measurements.new_build_cache_replaced_ms = Date.now() - reloaded;

    // And offline it is the second build that opens.
    await server.close();
    await page.reload({ waitUntil: 'domcontentloaded' });
    await rendered(page);
    assert.ok((await page.content()).includes(marker), 'the page came from the second build\'s cache');
    await assertArmDrawn(page);
    assert.deepEqual(errors, []);
  } finally {
    await context.close();
    await server.close().catch(() => {});
    fs.rmSync(dir, { recursive: true, force: true });
  }
});
