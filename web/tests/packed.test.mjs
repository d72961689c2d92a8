// The page's wasm packed with xz (web/build/pack-wasm.mjs, web/page/unxz.mjs) in the built
// page (dist/) in headless Chromium. Here: the first load fetches the packed copy and not
// the wasm, the page's decoder gives back exactly the wasm's bytes, and where the copy is
// missing or broken the page loads the wasm itself and draws; the lazy module (urdf/) the
// same way. (That the module starts from its packed copy: urdf.test.mjs, collision.test.mjs.)
//
// The contexts block service workers: the worker's precaching is not the page's first load.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import crypto from 'node:crypto';
import fs from 'node:fs';
import path from 'node:path';
import zlib from 'node:zlib';
import { browserSuite } from './browser-suite.mjs';
import { dist, state, pageOpener, until, moduleRequests } from './page.mjs';

const suite = browserSuite(dist, { untimed: true });
const { open } = pageOpener(suite, { contextOptions: { serviceWorkers: 'block' }, consoleErrors: false, waitUntil: 'load' });

const wasm = fs.readdirSync(dist).find((f) => f.endsWith('_bg.wasm'));
const unxz = fs.readdirSync(dist).find((f) => /^unxz-[0-9a-f]{16}\.js$/.test(f));
const HASH = '#robot=ur10&q=0.4,-1.1,1.3,-1.6,-1.4,0.2';
/** Half of `file`'s bytes: its decoder fails partway. */
const cut = (file) => { const bytes = fs.readFileSync(file); return bytes.subarray(0, bytes.length >> 1); };

test('the first load fetches the wasm packed, a quarter smaller than gzip, and the page unpacks it to its exact bytes', async () => {
  const raw = fs.readFileSync(path.join(dist, wasm));
  const packed = fs.readFileSync(path.join(dist, `${wasm}.xz`));
  const gzip = zlib.gzipSync(raw, { level: 9 }).length;
  assert.ok(packed.length < 0.8 * gzip, `xz ${packed.length} B against gzip -9 ${gzip} B`);

  const { page, ctx, errors, requests } = await open(HASH);
  assert.equal((await state(page)).robot, 'UR10');
  assert.ok(requests.includes(`/${wasm}.xz`), 'the page fetched the packed copy');
  assert.ok(!requests.includes(`/${wasm}`), 'and not the wasm itself');
  // The page's own decoder, as its loader uses it: the unpacked bytes' SHA-256, read by a
  // reader that lags a moment before each chunk, as a busy page's may (the decoder's chunks
  // would then be overwritten in its memory before they were read, were they not copied).
  const unpacked = await page.evaluate(async ([module, file]) => {
    const { default: packedWasm } = await import(`./${module}`);
    const response = await packedWasm(`./${file}`);
    const reader = response.body.getReader();
    const chunks = [];
    for (;;) {
      await new Promise((resolve) => setTimeout(resolve, 1));
      const { done, value } = await reader.read();
      if (done) break;
      chunks.push(value);
    }
    const bytes = await new Blob(chunks).arrayBuffer();
    const digest = await crypto.subtle.digest('SHA-256', bytes);
    return { type: response.headers.get('content-type'), length: bytes.byteLength,
      sha256: Array.from(new Uint8Array(digest), (b) => b.toString(16).padStart(2, '0')).join('') };
  }, [unxz, wasm]);
  assert.deepEqual(unpacked, { type: 'application/wasm', length: raw.length, sha256: crypto.createHash('sha256').update(raw).digest('hex') });
  assert.deepEqual(errors, []);
  await ctx.close();
});

for (const [what, answer] of [
  ['missing', (route) => route.fulfill({ status: 404, body: '' })],
  // Cut in half: the decoder fails partway, after the app's init has begun compiling.
  ['broken', (route) => route.fulfill({ status: 200, contentType: 'application/x-xz', body: cut(path.join(dist, `${wasm}.xz`)) })],
]) {
  test(`where the packed copy is ${what}, the page loads the wasm itself and draws the arm`, async () => {
    const { page, ctx, errors, requests } = await open(HASH, { setup: (c) => c.route(`**/${wasm}.xz`, answer) });
    const s = await state(page);
    assert.equal(s.robot, 'UR10');
    assert.deepEqual(s.q.map((v) => +v.toFixed(6)), [0.4, -1.1, 1.3, -1.6, -1.4, 0.2]);
    assert.ok(requests.includes(`/${wasm}`), 'the wasm itself was fetched');
    assert.deepEqual(errors, []);
    await ctx.close();
  });
}

test('where the lazy module\'s packed copy is broken, the module starts from its wasm itself', async () => {
  const module = fs.readdirSync(path.join(dist, 'urdf')).find((f) => f.endsWith('_bg.wasm'));
  const broken = (route) => route.fulfill({ status: 200, contentType: 'application/x-xz', body: cut(path.join(dist, 'urdf', `${module}.xz`)) });
  // collide=on: the collision checks load the module at once.
  const { page, ctx, errors, requests } = await open('#robot=ur10&panels=motion&collide=on',
    { setup: (c) => c.route(`**/urdf/${module}.xz`, broken) });
  await until(page, (s) => s.motion.checker === 'ready', 'the collision checks ready');
  const fetched = moduleRequests(requests).map((p) => p.replace(/.*\//, ''));
  assert.deepEqual(fetched, ['armlab_urdf.js', `${module}.xz`, module], 'the glue, the packed copy, then the wasm itself');
  assert.deepEqual(errors, []);
  await ctx.close();
});
