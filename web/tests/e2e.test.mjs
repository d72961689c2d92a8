// End-to-end tests of the built page (dist/, from `trunk build --release`) in Debian's
// headless Chromium, driven by playwright-core. Chromium here has no WebGPU, so eframe
// runs on WebGL2: the page must work and look right on that path. Here: loading, the
// colours against the native snapshot, a browser without SIMD, the first load's size,
// links, reloads, a crash and the language. The mouse, the keyboard and touch are in
// interaction.test.mjs; the screen sizes in screens.test.mjs.
//
// Prints one JSON line of measurements (not asserted): time to the first drawn frame, the
// wasm size and every file's size gzip -9.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import zlib from 'node:zlib';
import { fileURLToPath } from 'node:url';
import { browserSuite } from './browser-suite.mjs';
import { dist, shots, VIEW, state, point, settle, ready, pageOpener, pixels, at, close } from './page.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const snapshot = path.resolve(here, '..', '..', 'tests', 'snapshots', 'ur10.png');
// The UI tests' snapshot shows this state at this size (tests/ui/basics.rs).
const SNAPSHOT_HASH = '#robot=ur10&q=0.4,-1.1,1.3,-1.6,-1.4,0.2';
const measurements = {};

const suite = browserSuite(dist, { label: 'ARMLAB_E2E_MEASUREMENTS', measurements });
const { open, openAt } = pageOpener(suite);

before(() => {
  const wasm = fs.readdirSync(dist).find((f) => f.endsWith('.wasm'));
  if (wasm) {
    const bytes = fs.readFileSync(path.join(dist, wasm));
    measurements.wasm_bytes = bytes.length;
    measurements.wasm_gzip_bytes = zlib.gzipSync(bytes, { level: 9 }).length;
    measurements.wasm_xz_bytes = fs.statSync(path.join(dist, `${wasm}.xz`)).size;
  }
});
after(() => fs.writeFileSync(path.join(shots, 'measurements.json'), JSON.stringify(measurements, null, 2)));


test('loads without console errors, shows its loading text, then draws the arm in 3D', async () => {
  const { page, ctx, errors, loading, started } = await open(SNAPSHOT_HASH, { slowWasm: true });
  assert.match(loading, /Loading ArmLab/);
  void started;
  assert.equal(await page.isVisible('#armlab_message'), false, 'the loading text is gone');
  const s = await state(page);
  assert.equal(s.robot, 'UR10');
  const shotA = await page.screenshot({ path: path.join(shots, 'ur10.png') });
  const toolA = await point(page, 'tool');

  // Another pose: the drawing must follow the tool, not only the panels' numbers.
  await page.evaluate(() => window.armlab.open('#robot=ur10&q=1.6,-0.6,0.4,-1.6,-1.4,0.2'));
  await settle(page, 4);
  const shotB = await page.screenshot({ path: path.join(shots, 'ur10-other-pose.png') });
  const toolB = await point(page, 'tool');
  assert.ok(Math.hypot(toolB.x - toolA.x, toolB.y - toolA.y) > 40, 'the tool moved on screen');
  const a = await pixels(page, shotA);
  const b = await pixels(page, shotB);
  // The target ball sits on the tool (a link opens with the target there): green where
  // the tool is, in each picture, and something else there in the other one.
  const green = (c) => c[1] > c[0] + 40 && c[1] > c[2] + 20;
  for (const [name, p, here, there] of [['before', toolA, a, b], ['after', toolB, b, a]]) {
    assert.ok(green(at(here, p.x, p.y)), `the ball is drawn at the tool ${name}: ${at(here, p.x, p.y)}`);
    let differ = 0;
    for (let dy = -3; dy <= 3; dy++) {
      for (let dx = -3; dx <= 3; dx++) {
        if (!close(at(here, p.x + dx, p.y + dy), at(there, p.x + dx, p.y + dy), 24)) differ++;
      }
    }
    assert.ok(differ >= 40, `the pixels at the tool ${name} changed with the pose (${differ} of 49)`);
  }
  assert.deepEqual(errors, []);
  await ctx.close();
});

test('WebGL2 colours match the native (lavapipe) snapshot', async () => {
  const { page, ctx, started } = await open(SNAPSHOT_HASH);
  // Navigation to the first drawn frame (performance.now() counts from navigation start).
  measurements.first_frame_ms = Math.round(await page.evaluate(() => window.armlab.firstFrameAt()));
  measurements.ready_wall_ms = Date.now() - started;
  // index.html's shim gives egui's fragment shader the page's values of two options (0:
  // no snapshot-test filtering, no dithering) in place of the uniforms it reads, so that
  // SwiftShader does not run the unused sides for every pixel. If an egui or naga update
  // renames what the GLSL reads, the shim finds nothing: this fails, and the colours below
  // check the folded shader.
  const folds = await page.evaluate(() => window.armlabShaderFolds ?? {});
  for (const option of ['predictable_texture_filtering', 'dithering']) {
    assert.ok(folds[option] >= 1, `egui's fragment shader's ${option} was folded by index.html's shim (${JSON.stringify(folds)})`);
  }
  const web = await pixels(page, await page.screenshot());
  const native = await pixels(page, fs.readFileSync(snapshot));
  assert.equal(native.width, web.width);
  const target = await point(page, 'target');
  // The target ball (green: reached), lit from the same light: same colour within 12/255.
  const ballWeb = at(web, target.x, target.y);
  const ballNative = at(native, target.x, target.y);
  assert.ok(close(ballWeb, ballNative, 12), `ball ${ballWeb} vs native ${ballNative}`);
  assert.ok(ballWeb[1] > ballWeb[0] + 40, `the ball is green: ${ballWeb}`);
  // Most of the 3D view matches: a 20 × 10 grid of samples between the side panels.
  let same = 0;
  const samples = [];
  for (let i = 0; i < 20; i++) {
    for (let j = 0; j < 10; j++) {
      const x = 350 + (i + 0.5) * (560 / 20);
      const y = 60 + (j + 0.5) * (780 / 10);
      const ok = close(at(web, x, y), at(native, x, y), 16);
      if (ok) same++; else samples.push([Math.round(x), Math.round(y), at(web, x, y), at(native, x, y)]);
    }
  }
  measurements.view_samples_matching_native = same;
  assert.ok(same >= 180, `${same} of 200 samples of the 3D view match the native snapshot; differ: ${JSON.stringify(samples.slice(0, 5))}`);
  // The grid is mostly background: the arm itself must match too. Every 6th pixel of the
  // view where the snapshot is not the background (the arm, the marker, the grid lines).
  let drawn = 0;
  let drawnSame = 0;
  for (let y = 60; y < 840; y += 6) {
    for (let x = 350; x < 910; x += 6) {
      const n = at(native, x, y);
      if (close(n, [30, 33, 38], 10)) continue;
      drawn++;
      if (close(at(web, x, y), n, 24)) drawnSame++;
    }
  }
  measurements.drawn_samples_matching_native = `${drawnSame}/${drawn}`;
  assert.ok(drawn >= 100, `the snapshot has the arm in the view (${drawn} drawn samples)`);
  assert.ok(drawnSame >= 0.85 * drawn, `${drawnSame} of ${drawn} drawn samples match the native snapshot`);
  // Background of the viewport (a corner above the grid's horizon, no text there).
  const bgWeb = at(web, 900, 70);
  const bgNative = at(native, 900, 70);
  assert.ok(close(bgWeb, bgNative, 6), `background ${bgWeb} vs native ${bgNative}`);
  assert.ok(close(bgWeb, [30, 33, 38], 6), `background is the opaque theme colour: ${bgWeb}`);
  // The panels (the top bar, the columns beside the view) look as natively: the page
  // leaves out their fills and clears the canvas to their colour instead. A 60 × 30 grid
  // of samples outside the view; text is drawn by two rasterisers, so a few may differ.
  const { x: vx, y: vy, width: vw, height: vh } = await page.evaluate(() => window.armlab.viewRect());
  let panelSamples = 0;
  let panelSame = 0;
  const panelDiffer = [];
  for (let i = 0; i < 60; i++) {
    for (let j = 0; j < 30; j++) {
      const x = (i + 0.5) * (web.width / 60);
      const y = (j + 0.5) * (web.height / 30);
      if (x >= vx - 2 && x < vx + vw + 2 && y >= vy - 2 && y < vy + vh + 2) continue;
      panelSamples++;
      if (close(at(web, x, y), at(native, x, y), 6)) panelSame++;
      else panelDiffer.push([Math.round(x), Math.round(y), at(web, x, y), at(native, x, y)]);
    }
  }
  measurements.panel_samples_matching_native = `${panelSame}/${panelSamples}`;
  assert.ok(panelSamples >= 400, `the panels take ${panelSamples} samples`);
  assert.ok(panelSame >= 0.95 * panelSamples,
    `${panelSame} of ${panelSamples} samples of the panels match the native snapshot; differ: ${JSON.stringify(panelDiffer.slice(0, 5))}`);
  await ctx.close();
});

test('a browser without WebAssembly SIMD gets a sentence, not an endless loading text', async () => {
  const ctx = await suite.browser.newContext({ viewport: VIEW, deviceScaleFactor: 1 });
  // Such a browser rejects SIMD modules: it neither validates nor compiles the page's wasm.
  await ctx.addInitScript(() => {
    WebAssembly.validate = () => false;
    window.armlabRefusedWasm = 0;
    const refuse = () => {
      window.armlabRefusedWasm += 1;
      return Promise.reject(new WebAssembly.CompileError('SIMD is not supported'));
    };
    WebAssembly.instantiateStreaming = refuse;
    WebAssembly.instantiate = refuse;
    WebAssembly.compileStreaming = refuse;
    WebAssembly.compile = refuse;
  });
  const page = await ctx.newPage();
  await page.goto(suite.base, { waitUntil: 'load' });
  // The sentence shows, and stays once the page has tried to start its wasm and failed.
  const sentence = /needs a browser with WebAssembly SIMD/;
  await page.waitForFunction((source) => new RegExp(source).test(document.getElementById('armlab_message')?.textContent ?? ''),
    sentence.source, { timeout: 10000 });
  await page.waitForFunction(() => window.armlabRefusedWasm > 0, null, { timeout: 10000 });
  await page.evaluate(() => new Promise((r) => setTimeout(r, 0))); // the refusal's handlers ran
  assert.match(await page.textContent('#armlab_message'), sentence);
  assert.equal(await page.isVisible('#armlab_message'), true);
  await ctx.close();
});

// The budget holds the lecture room's client (about 30.6 kB: its bar and cards, the
// WebSocket, the messages) and the accessibility mirror, keys and live region (about
// 9.3 kB), which the first frame does not need but a page cannot load later: they are egui
// code in the app's own wasm (the QR encoder and the symbolic algebra are in the lazy
// module). Within the 1.8 MB the page was first given.
test('the first load (every file the page fetches, gzip -9) stays within 1,333,400 B', () => {
  let total = 0;
  const files = fs.readdirSync(dist);
  for (const f of files) {
    // Folders hold what the page fetches later, not on its first load: urdf/, the URDF
    // module, only when a URDF file is opened or saved, collisions are checked or the
    // symbolic matrices are shown (urdf.test.mjs, collision.test.mjs, symbolic.test.mjs).
    if (!fs.statSync(path.join(dist, f)).isFile()) continue;
    // The copies compressed ahead (`.br`, `.gz`) are sent in place of a file, never besides.
    if (/\.(br|gz)$/.test(f)) continue;
    // The wasm comes packed (NAME.xz, counted as the rest, though no host compresses it
    // again): the page fetches the wasm itself only where that copy fails (packed.test.mjs).
    if (files.includes(`${f}.xz`)) continue;
    const bytes = zlib.gzipSync(fs.readFileSync(path.join(dist, f)), { level: 9 }).length;
    measurements[`gzip_${f.replace(/-[0-9a-f]{16}/, '')}`] = bytes;
    total += bytes;
  }
  measurements.first_load_gzip_bytes = total;
  assert.ok(total <= 1_333_400, `the page's files are ${total} bytes gzip -9 (budget 1,333,400)`);
});

// For hosts that send a file's copy compressed ahead (nginx gzip_static and brotli_static,
// Caddy, the classroom server): each is the file's bytes, and brotli's is the smaller.
test('the build writes each file of the page compressed ahead, brotli and gzip', () => {
  for (const dir of [dist, path.join(dist, 'urdf')]) {
    for (const f of fs.readdirSync(dir).filter((f) => /\.(wasm|js|html|svg|webmanifest)$/.test(f))) {
      const file = path.join(dir, f);
      const raw = fs.readFileSync(file);
      const br = fs.readFileSync(`${file}.br`);
      const gz = fs.readFileSync(`${file}.gz`);
      assert.ok(zlib.brotliDecompressSync(br).equals(raw), `${f}.br holds ${f}`);
      assert.ok(zlib.gunzipSync(gz).equals(raw), `${f}.gz holds ${f}`);
      if (f.endsWith('.wasm')) {
        measurements[`br_${f.replace(/-[0-9a-f]{16}/, '')}`] = br.length;
        assert.ok(br.length < gz.length * 0.9, `${f}: brotli ${br.length} B against gzip ${gz.length} B`);
      }
    }
  }
});

/** Z-Y-X Euler angles [α, β, γ] (radians) of a rotation matrix, R = Rz(α)·Ry(β)·Rx(γ),
 * as a link's target writes them (away from β = ±90°). */
const zyxEuler = (r) => [
  Math.atan2(r[1][0], r[0][0]),
  Math.atan2(-r[2][0], Math.hypot(r[0][0], r[1][0])),
  Math.atan2(r[2][1], r[2][2]),
];

test('a link opens exactly its robot, pose and target', async () => {
  const hash = '#robot=puma560&q=0.1,0.2,-0.3,0.4,0.5,-0.6&target=0.5,-0.1,0.6,0.2,0.1,0.3&task=position&method=pinv';
  const { page, ctx } = await open(hash);
  const s = await state(page);
  assert.equal(s.robot, 'Puma 560');
  assert.equal(s.preset, 'puma560');
  assert.deepEqual(s.q.map((v) => +v.toFixed(6)), [0.1, 0.2, -0.3, 0.4, 0.5, -0.6]);
  assert.deepEqual(s.target.position.map((v) => +v.toFixed(6)), [0.5, -0.1, 0.6]);
  // The target's angles in the link's units: α, β, γ = 0.2, 0.1, 0.3 rad about Z, Y, X.
  const angles = zyxEuler(s.target.rotation);
  assert.ok(angles.every((v, i) => Math.abs(v - [0.2, 0.1, 0.3][i]) < 1e-9), `the target's Z-Y-X angles: ${angles}`);
  const written = /target=([^&]+)/.exec(s.hash)[1].split(',').map(Number);
  assert.deepEqual(written.map((v) => +v.toFixed(6)), [0.5, -0.1, 0.6, 0.2, 0.1, 0.3], 'the link it writes back');
  assert.equal(s.task, 'position');
  assert.equal(s.method, 'pinv');
  await ctx.close();
});

test('a garbage link shows a message and the default robot', async () => {
  const { page, ctx, errors } = await open('#robot=banana&q=1,2,banana&&%%');
  const s = await state(page);
  assert.equal(s.robot, 'UR10');
  assert.match(s.message, /This link could not be opened/);
  assert.deepEqual(errors, []);
  await ctx.close();
});

test('a reload restores the last session', async () => {
  const context = await suite.browser.newContext({ viewport: VIEW, deviceScaleFactor: 1 });
  const { page } = await open('#robot=scara&q=0.3,-0.5,0.1,0.7&task=position', { context });
  const lo = await point(page, 'slider-1-min');
  const hi = await point(page, 'slider-1-max');
  await page.mouse.click(lo.x + (hi.x - lo.x) * 0.3, lo.y);
  await settle(page);
  const before = await state(page);
  await page.reload({ waitUntil: 'domcontentloaded' });
  await ready(page);
  const reloaded = await state(page);
  assert.equal(reloaded.robot, before.robot);
  assert.deepEqual(reloaded.q.map((v) => +v.toFixed(5)), before.q.map((v) => +v.toFixed(5)));
  // Without any hash, the stored session returns too.
  await page.goto(suite.base, { waitUntil: 'domcontentloaded' });
  await ready(page);
  const fresh = await state(page);
  assert.equal(fresh.robot, before.robot);
  assert.deepEqual(fresh.q.map((v) => +v.toFixed(5)), before.q.map((v) => +v.toFixed(5)));
  // It is kept as the session's JSON; a session kept as a link still opens, and one that
  // cannot be read says so and shows the default robot.
  const kept = JSON.parse(await page.evaluate(() => localStorage.getItem('armlab.session')));
  assert.equal(kept.source, 'scara');
  for (const [stored, robot, message] of [
    ['robot=rrr&q=0.1,0.2,0.3', /RRR/, null],
    ['{"robot": 5}', /UR10/, /last session could not be reopened \(the stored session could not be read\)/],
  ]) {
    await page.evaluate((s) => localStorage.setItem('armlab.session', s), stored);
    await page.goto(suite.base, { waitUntil: 'domcontentloaded' });
    await ready(page);
    const s = await state(page);
    assert.match(s.robot, robot, stored);
    if (message) assert.match(s.message ?? '', message, stored);
  }
  await context.close();
});

test('a crash shows a sentence and Reload, and the reload restores the robot changed just before', async () => {
  const { page, ctx, errors } = await open('#robot=ur10');
  const view = await page.evaluate(() => window.armlab.viewRect());
  // A finger or mouse held on the view (an orbit): the address bar is not written while a
  // pointer is held, so only localStorage can carry the change across the crash.
  await page.mouse.move(view.x + view.width / 2, view.y + view.height / 2);
  await page.mouse.down();
  await page.evaluate(() => window.armlab.open('#robot=scara&q=0.3,-0.6,0.1,0.2'));
  const start = (await state(page)).frame;
  for (let i = 0; i < 400 && (await state(page)).frame < start + 3; i++) {
    await page.mouse.move(view.x + view.width / 2 + (i % 2), view.y + view.height / 2);
    await page.waitForTimeout(20);
  }
  assert.match((await state(page)).robot, /SCARA/);
  const saved = await page.evaluate(() => ({ stored: localStorage.getItem('armlab.session'), hash: location.hash }));
  const kept = JSON.parse(saved.stored);
  assert.equal(kept.source, 'scara', 'the robot change is in localStorage at once, during a drag, as the session\'s JSON');
  assert.deepEqual(kept.q, [0.3, -0.6, 0.1, 0.2]);
  assert.doesNotMatch(saved.hash, /scara/, 'the address bar still shows the UR10 (it is written on release)');
  await page.evaluate(() => window.armlab.panicForTest());
  await page.mouse.move(view.x + 10, view.y + 10);
  await page.waitForSelector('#armlab_reload', { timeout: 20000 });
  const sentence = await page.textContent('#armlab_message');
  assert.match(sentence, /ArmLab stopped after an error in its own code \(a panic asked for by window\.armlab\.panicForTest\(\)\)/);
  assert.match(sentence, /saved in this browser/);
  assert.ok(errors.some((e) => /panicForTest/.test(e)), 'the panic is logged to the console');
  await page.screenshot({ path: path.join(shots, 'crash-1400x860.png') });
  await page.mouse.up();
  await Promise.all([page.waitForNavigation(), page.click('#armlab_reload')]);
  await ready(page);
  const s = await state(page);
  assert.match(s.robot, /SCARA/, 'the reload restored the robot changed just before the crash');
  assert.deepEqual(s.q.map((v) => +v.toFixed(6)), [0.3, -0.6, 0.1, 0.2]);
  await ctx.close();
});

test('with the browser language fi the page opens in Finnish; a link and the switch choose too', async () => {
  const { page, ctx } = await openAt({ width: 1280, height: 720 }, '#robot=ur10', { locale: 'fi-FI' });
  assert.equal((await state(page)).lang, 'fi');
  await page.screenshot({ path: path.join(shots, 'finnish-1280x720.png') });
  await ctx.close();
  const en = await openAt({ width: 1280, height: 720 }, '#robot=ur10&lang=en', { locale: 'fi-FI' });
  assert.equal((await state(en.page)).lang, 'en', 'the link wins over the browser');
  await en.ctx.close();

  // The switch in the top bar, in a browser whose language is English: what the app
  // writes (here the sentence of a link that cannot be opened) follows it.
  const sw = await openAt({ width: 1280, height: 720 }, '#robot=ur10', { locale: 'en-US' });
  const broken = '#robot=banana&q=1,2';
  const english = /^This link could not be opened/;
  const finnish = /^Linkkiä ei voitu avata/;
  const sentence = async () => {
    await sw.page.evaluate((h) => window.armlab.open(h), broken);
    await settle(sw.page);
    return (await state(sw.page)).message;
  };
  const choose = async (lang) => {
    const menu = await point(sw.page, 'language');
    await sw.page.mouse.click(menu.x, menu.y);
    await settle(sw.page);
    const choice = await point(sw.page, `language-${lang}`);
    await sw.page.mouse.click(choice.x, choice.y);
    await settle(sw.page);
  };
  assert.equal((await state(sw.page)).lang, 'en');
  assert.match(await sentence(), english);
  await choose('fi');
  let s = await state(sw.page);
  assert.equal(s.lang, 'fi', 'Suomi chosen in the menu');
  assert.match(s.hash, /lang=fi/);
  let text = await sentence();
  assert.match(text, finnish, 'the app writes Finnish');
  assert.doesNotMatch(text, english);
  await choose('en');
  s = await state(sw.page);
  assert.equal(s.lang, 'en', 'English chosen in the menu');
  text = await sentence();
  assert.match(text, english, 'the app writes English again');
  assert.doesNotMatch(text, finnish);
  assert.deepEqual(sw.errors, []);
  await sw.ctx.close();
});

test('a link carries the angle unit, presentation, language, panels and camera', async () => {
  const hash = '#robot=scara&units=rad&frames=off&decimals=5&present=off&lang=fi&panels=joints,matrices'
    + '&ppanels=ik&camera=0.3,0.2,1800,100,50,200';
  const { page, ctx } = await open(hash);
  let s = await state(page);
  assert.equal(s.degrees, false);
  assert.equal(s.lang, 'fi');
  assert.equal(s.presentation, false);
  assert.equal(s.open_panels, 'joints,matrices');
  const camera = /camera=([^&]+)/.exec(s.hash)[1].split(',').map(Number);
  assert.deepEqual(camera.map((v) => +v.toFixed(3)), [0.3, 0.2, 1800, 100, 50, 200]);
  assert.match(s.hash, /units=rad/);
  assert.match(s.hash, /decimals=5/);
  assert.match(s.hash, /(^|&)frames=off(&|$)/);
  assert.match(s.hash, /(^|&)ppanels=ik(&|$)/);
  // Presentation on (off is the default): its own panels show, the normal ones are kept.
  await page.evaluate((h) => window.armlab.open(h), hash.replace('present=off', 'present=on'));
  await settle(page);
  s = await state(page);
  assert.equal(s.presentation, true);
  assert.equal(s.open_panels, 'ik', 'the presentation layout shows its own panels');
  assert.match(s.hash, /(^|&)present=on(&|$)/);
  assert.match(s.hash, /(^|&)panels=joints,matrices(&|$)/);
  await ctx.close();
});
