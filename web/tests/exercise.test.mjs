// The DH-table exercise in the built page (dist/), in Debian's headless Chromium: a
// lecturer's link opens the RRR as an exercise with its table hidden; a student types a
// table with the keyboard, presses Check, and reads the verdict (window.armlab.state()),
// which the lazily loaded module (dist/urdf/) gives: the page's own wasm holds no check.
// Run as tools/test.sh runs web/tests/e2e.test.mjs (after build_web).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { browserSuite } from './browser-suite.mjs';
import { dist, shots, state, settle, click, until, moduleRequests, pageOpener } from './page.mjs';

const VIEW = { width: 1280, height: 720 }; // a lecture-hall projector

const suite = browserSuite(dist, { untimed: true });
// Uncaught exceptions count as errors here, not what the page logs to the console. No
// service worker: it would fetch the lazily loaded module for the cache after the first
// frame, and the tests count the page's own fetches of it.
const { open } = pageOpener(suite, { view: VIEW, consoleErrors: false, contextOptions: { serviceWorkers: 'block' } });

/** Clicks an answer cell, selects its text and replaces it. The text arrives as one input
 * event (as a paste or an on-screen keyboard's word does), not a key press per character:
 * each frame costs the software renderer a few hundred milliseconds. The keys themselves
 * are tested in web/tests/interaction.test.mjs (a bad DH cell typed with the keyboard). */
async function type(page, cell, text) {
  await click(page, cell);
  await page.keyboard.press('Control+A');
  await page.keyboard.insertText(text);
  await settle(page, 4);
}

/** Presses Check and waits for the verdict (or for the check to fail). */
async function check(page) {
  await click(page, 'exercise-check');
  return until(page, (st) => st.exercise.check !== 'checking', 'the check\'s answer');
}

test('an exercise link hides the table; a wrong table is named by joint, a right one is correct', async () => {
  const { page, ctx, errors, requests } = await open('#exercise=rrr&panels=robot,matrices');
  let s = await state(page);
  assert.deepEqual(s.exercise, { id: 'rrr', solved: false, verdict: null, check: null });
  assert.deepEqual(moduleRequests(requests), [], 'the check\'s module waits for a check');
  assert.equal(s.robot, '', 'the preset is not named');
  assert.equal(s.dof, 3);
  assert.match(s.hash, /^exercise=rrr&/);
  assert.doesNotMatch(s.hash, /dh=|robot=/, 'the link carries no table');
  assert.doesNotMatch(page.url(), /dh=/, 'nor does the address bar');

  // a2 = 222.1 written in row 1: the verdict names joint 2.
  await type(page, 'dh-1-2', '100.9');
  await type(page, 'dh-1-4', '90');
  await type(page, 'dh-1-3', '222.1');
  await type(page, 'dh-3-3', '136.2');
  s = await check(page);
  assert.equal(s.exercise.verdict,
    "Joint 2's frame is the first to disagree: the length a in row 1 belongs in column a of row 2.");
  assert.equal(s.exercise.solved, false);
  await page.screenshot({ path: path.join(shots, 'exercise-wrong.png') });

  // The length moved to row 2: correct.
  await type(page, 'dh-1-3', '0');
  await type(page, 'dh-2-3', '222.1');
  s = await check(page);
  assert.match(s.exercise.verdict, /^Correct: /);
  assert.equal(s.exercise.solved, true);
  assert.deepEqual(moduleRequests(requests).filter((p) => /\.wasm(\.xz)?$/.test(p)).map((p) => p.replace(/.*\./, '.')), ['.xz'],
    'the module\'s packed wasm is fetched once');
  await page.screenshot({ path: path.join(shots, 'exercise-correct.png') });
  assert.deepEqual(errors, []);
  await ctx.close();
});

test('a check whose module cannot be loaded (offline, no cache) says so; Check again checks', async () => {
  let offline = true;
  const { page, ctx } = await open('#exercise=rrr&panels=robot', { setup: async (c) => {
    await c.route('**/urdf/**', (route) => (offline ? route.abort('internetdisconnected') : route.continue()));
  } });
  await type(page, 'dh-1-2', '100.9');
  let s = await check(page);
  assert.match(s.exercise.check, /^failed: ./, 'the browser\'s words are kept for the sentence');
  assert.equal(s.exercise.verdict, null);
  offline = false;
  s = await check(page);
  assert.equal(s.exercise.check, null);
  assert.ok(s.exercise.verdict, 'a verdict on the second try');
  await ctx.close();
});

test('a broken exercise link says why and opens the default robot', async () => {
  const { page, ctx } = await open('#exercise=mystery-x');
  const s = await state(page);
  assert.equal(s.exercise, null);
  assert.equal(s.robot, 'UR10');
  assert.match(s.message, /the link's exercise "mystery-x" is neither a preset id nor mystery- and a whole number/);
  await ctx.close();
});
