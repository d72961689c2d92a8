// The symbolic matrices in the built page (dist/) in headless Chromium. The page's own wasm
// leaves the symbolic algebra out (its first-load budget); the module in dist/urdf/
// (tools/setup.sh, build_urdf_module) makes the tables, and the page imports it only when
// "symbolic" is ticked in the Matrices panel. Here: the first load does not fetch it;
// ticking fetches it once and the RRR's T_03 reads as in the lecture; another robot is
// asked for again without a second fetch; a module that cannot be loaded gets a sentence
// and ticking again loads it.
//
// The contexts block service workers: the worker precaches every file of the build after
// the first load (urdf/ too), and those fetches are not the page's.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { browserSuite } from './browser-suite.mjs';
import { dist, state, until as waitFor, point, moduleRequests, pageOpener } from './page.mjs';

// Tall enough that the Matrices panel's "symbolic" tick is on screen below the Jacobian.
const VIEW = { width: 1400, height: 1400 };

const suite = browserSuite(dist, { untimed: true });
const { open } = pageOpener(suite, {
  view: VIEW, contextOptions: { serviceWorkers: 'block' }, consoleErrors: false, waitUntil: 'load', settled: false,
});

/** The state's `symbolic`: `idle`, `loading`, `failed: <the words>` or `ready: ` and the
 * last T_0i's position column, the entries apart by ` | `; as `{ state, rest }`. */
const symbolic = (s) => {
  const [, word, rest] = /^(\w+)(?:: (.*))?$/s.exec(s.symbolic) ?? [];
  return { state: word, rest };
};
const position = (s) => symbolic(s).rest.split(' | ');

/** Waits until `check(state)` holds, nudging the mouse so that egui draws frames. */
const until = (page, check, what, tries = 600) => waitFor(page, check, what, { tries, x: 700, detail: (s) => s.symbolic });

/** Ticks (or unticks) "symbolic". */
async function tick(page) {
  const p = await point(page, 'matrices-symbolic');
  assert.ok(p.y < VIEW.height, `the tick is on screen (${p.y})`);
  await page.mouse.click(p.x, p.y);
}

// SPEC §1.4: the RRR's tool position, T_03's last column.
const RRR_POSITION = ['c1(222.1 c2 + 136.2 c23)', 's1(222.1 c2 + 136.2 c23)', '100.9 + 222.1 s2 + 136.2 s23'];

test('ticked, the module loads once and makes the RRR\'s symbolic T_03; another robot is asked for without a second fetch', async () => {
  const { page, ctx, requests, errors } = await open('#robot=rrr&panels=matrices');
  let s = await until(page, (st) => st.frame > 3, 'a few frames');
  assert.ok(requests.some((p) => p.endsWith('_bg.wasm.xz')), 'the first load fetched the page\'s packed wasm');
  assert.deepEqual(moduleRequests(requests), [], 'the first load does not fetch the module');
  assert.equal(s.symbolic, 'idle', 'nothing asked for before the tick');

  await tick(page);
  s = await until(page, (st) => symbolic(st).state === 'ready', 'the symbolic tables');
  assert.deepEqual(position(s), RRR_POSITION);
  const fetched = moduleRequests(requests);
  assert.equal(fetched.length, 2, `the glue and the wasm, once: ${fetched}`);

  await page.evaluate((h) => window.armlab.open(h), '#robot=ur10&panels=matrices');
  s = await until(page, (st) => st.preset === 'ur10' && symbolic(st).state === 'ready'
    && JSON.stringify(position(st)) !== JSON.stringify(RRR_POSITION), 'the UR10\'s tables');
  assert.equal(position(s).length, 3);
  assert.ok(position(s).every((t) => /[cs]\d/.test(t)), `the UR10's position depends on its joints: ${s.symbolic}`);
  assert.equal(moduleRequests(requests).length, 2, 'the module is not fetched again');
  assert.deepEqual(errors, []);
  await ctx.close();
});

test('a module that cannot be loaded (offline, no cache): the panel says so; ticked again, it loads', async () => {
  let offline = true;
  const { page, ctx, requests, errors } = await open('#robot=rrr&panels=matrices', { setup: async (c) => {
    await c.route('**/urdf/**', (route) => (offline ? route.abort('internetdisconnected') : route.continue()));
  } });
  await until(page, (st) => st.frame > 3, 'a few frames');
  await tick(page);
  let s = await until(page, (st) => symbolic(st).state === 'failed', 'the failed import');
  assert.ok(symbolic(s).rest.length > 0, 'the browser\'s words are kept for the sentence');
  offline = false;
  await tick(page);
  await until(page, (st) => st.frame > s.frame + 2, 'unticked');
  await tick(page);
  s = await until(page, (st) => symbolic(st).state === 'ready', 'the tables on the second try');
  assert.deepEqual(position(s), RRR_POSITION);
  assert.ok(moduleRequests(requests).some((p) => p.endsWith('_bg.wasm.xz')), 'the packed wasm came on the second try');
  assert.ok(errors.every((e) => /urdf|import|fetch/i.test(e)), `only the failed import: ${errors}`);
  await ctx.close();
});
