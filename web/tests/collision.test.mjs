// Collision checks in the built page (dist/) in headless Chromium. The page's own wasm
// leaves the collision library out (its first-load budget); the checks run in the module
// in dist/urdf/ (tools/setup.sh, build_urdf_module), which the page imports only when
// checks go on. Here: the first load does not fetch it; turning checks on fetches it once;
// the UR10 driving into a keep-out box stops at a collision-free pose and the panel names
// the parts that touch; stepped with the time paused, it rests at the last free pose and
// the next step of the same motion touches the box; a module that cannot be loaded gets a
// sentence and a later try loads it. Prints one JSON line of measurements (not asserted):
// the module's load time on loopback and the check's cost per pose through the module
// boundary (UR10, Panda).
//
// The contexts block service workers: the worker precaches every file of the build after
// the first load (urdf/ too), and those fetches are not the page's.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { browserSuite } from './browser-suite.mjs';
import { dist, state, point, steadyPoint, until as waitFor, click as clickAndWait, moduleRequests, pageOpener } from './page.mjs';

const VIEW = { width: 1024, height: 768 }; // the lecture-hall projector
const measurements = {};

const suite = browserSuite(dist, { label: 'ARMLAB_COLLISION_MEASUREMENTS', measurements });
// Uncaught exceptions count as errors here, not what the page logs to the console; no
// service worker; the tests wait for what they need once the first frame is drawn.
const { open } = pageOpener(suite, {
  view: VIEW, contextOptions: { serviceWorkers: 'block' }, consoleErrors: false, waitUntil: 'load', settled: false,
});

/** Waits until `check(state)` holds, nudging the mouse so that egui draws frames. */
const until = (page, check, what, tries = 600) => waitFor(page, check, what, { tries, x: 700, detail: (s) => s.motion });

/** A click alone: the tests wait with until() for what it does. */
const click = (page, name) => clickAndWait(page, name, 0);

// The UR10 (mm) at home (standing straight up, collision-free), its tool 500 mm from the
// target; the keep-out box (250 mm cube) around the target, so the hand must enter it on
// the way.
const OFFSET = [400, 0, -300];

/** The scene's link: the target OFFSET from the UR10's tool at home, the box around it. */
async function boxScene() {
  const first = await open('#robot=ur10&panels=ik,motion');
  const tool = (await state(first.page)).tool;
  await first.ctx.close();
  const target = tool.map((v, i) => v + OFFSET[i]);
  const box = `keepout=${target.map((v) => v.toFixed(3)).join(',')},250,250,250`;
  return `#robot=ur10&target=${target.map((v) => v.toFixed(3)).join(',')},0,0,0&task=position&panels=ik,motion&${box}`;
}

/** With the time paused, presses Step (10 simulated ms) `count` times or until a contact;
 * returns the state after each press. */
async function steps(page, count) {
  const seen = [];
  // Step's place, found steady once (about three frames); before each press the last
  // frame's place is read, which draws nothing, and found steady again only if it moved.
  let at = await steadyPoint(page, 'motion-step');
  for (let i = 0; i < count; i++) {
    const before = await state(page);
    const drawn = await point(page, 'motion-step');
    if (drawn.x !== at.x || drawn.y !== at.y) at = await steadyPoint(page, 'motion-step');
    await page.mouse.click(at.x, at.y);
    const s = await until(page, (st) => st.motion.time >= before.motion.time + 0.0095, `step ${i + 1}`);
    seen.push(s);
    if (s.motion.contact !== null) break;
  }
  return seen;
}

test('checks on: the module loads once, the driving UR10 stops at a collision-free pose before a keep-out box, the panel names the parts', async () => {
  const scene = await boxScene();
  const { page, ctx, requests, errors } = await open(`${scene}&move=on&ctrl=quintic`);
  let s = await until(page, (st) => st.frame > 3, 'a few frames');
  assert.equal(s.motion.keep_outs, 1, 'the link brought the box');
  assert.equal(s.motion.collisions, false);
  assert.ok(requests.some((p) => p.endsWith('_bg.wasm.xz')), 'the first load fetched the page\'s packed wasm');
  assert.deepEqual(moduleRequests(requests), [], 'the first load does not fetch the collision module');

  const clicked = Date.now();
  await click(page, 'motion-collisions');
  s = await until(page, (st) => st.motion.collisions && st.motion.checker === 'ready', 'the module');
  measurements.module_load_ms_click_to_ready = Date.now() - clicked;
  measurements.module_resources = await page.evaluate(() => performance.getEntriesByType('resource')
    .filter((e) => e.name.includes('/urdf/'))
    .map((e) => ({ file: e.name.replace(/.*\//, ''), ms: Math.round(e.responseEnd - e.startTime), bytes: e.encodedBodySize })));
  const fetched = moduleRequests(requests);
  assert.equal(fetched.length, 2, `the glue and the wasm, once: ${fetched}`);
  s = await until(page, (st) => st.motion.colliding_parts === 0 && st.motion.contact === null, 'the start checked');

  await click(page, 'ik-solve');
  s = await until(page, (st) => st.motion.contact !== null && !st.motion.moving, 'the arm stopped at the box', 1500);
  assert.match(s.motion.contact, /^Contact: (the hand|link \d|joint \d's housing) touches keep-out box 1\.$/);
  assert.ok(s.motion.colliding_parts >= 1, 'a part is drawn red');
  assert.match(s.message, /The arm stopped at the last collision-free pose\.$/);
  assert.ok(s.position_error > 20, `the tool stopped short of the target (${s.position_error} mm off)`);
  const stopped = s.q;
  for (let i = 0; i < 10; i++) {
    await page.mouse.move(700 + (i % 2), 40);
    await page.waitForTimeout(30);
  }
  s = await state(page);
  assert.deepEqual(s.q, stopped, 'the arm stays where it stopped');

  // The pose it stopped at, checked on its own (the same visit: no second fetch): free.
  const back = `${scene}&q=${stopped.join(',')}`;
  await page.evaluate((h) => window.armlab.open(h), `${back}&collide=on`);
  s = await until(page, (st) => st.q.every((v, i) => v === stopped[i]) && st.motion.collisions, 'the stop pose');
  s = await until(page, (st) => st.frame > s.frame + 2, 'two more frames');
  assert.equal(s.motion.contact, null, 'the pose it stopped at is collision-free');
  assert.equal(s.motion.colliding_parts, 0);
  assert.equal(moduleRequests(requests).length, 2, 'the module is not fetched again');

  for (const robot of ['ur10', 'panda']) {
    measurements[`${robot}_check`] = await page.evaluate((r) => window.armlab.collisionBenchmark(r, 4000), robot);
    assert.ok(measurements[`${robot}_check`], `the benchmark ran for ${robot}`);
  }
  assert.deepEqual(errors, []);
  await ctx.close();
});

// The check runs once per frame (docs/kinematics.md §20.2): the arm rests at the pose of the
// last frame that was free, and the frame after it is the one that touched. Stepped with
// the time paused, every frame is one press of Step, so the test sees each pose.
test('stepped 10 ms at a time, the UR10 rests at the last pose it stepped to before the box, and one step more of the same motion touches it', async () => {
  const scene = await boxScene();
  const drive = '&move=on&ctrl=quintic&timescale=0';
  const { page, ctx, errors } = await open(`${scene}${drive}&collide=on`);
  let s = await until(page, (st) => st.motion.checker === 'ready' && st.motion.collisions
    && st.motion.colliding_parts === 0 && st.motion.contact === null, 'the module and the start checked');
  assert.equal(s.motion.time_scale, 0, 'the time is paused');
  const start = s.q;
  await click(page, 'ik-solve');
  const seen = await steps(page, 400);
  const last = seen[seen.length - 1];
  assert.ok(last.motion.contact !== null, `a contact within ${seen.length} steps`);
  assert.match(last.motion.contact, /touches keep-out box 1\.$/);
  assert.ok(seen.length >= 3, `the arm stepped toward the box first (${seen.length} steps)`);
  const free = seen.slice(0, -1);
  assert.ok(free.every((st) => st.motion.contact === null), 'no contact before the last step');
  // The last free pose: where the step before the contact took the arm.
  const stopped = last.q;
  assert.deepEqual(stopped, free[free.length - 1].q, 'the arm rests at the pose of the step before the contact');
  const path = [start, ...free.map((st) => st.q)];
  assert.ok(path.every((q, i) => i === 0 || q.some((v, j) => v !== path[i - 1][j])), 'every step before the contact moved the arm');

  // The same motion again with the checks off: the same poses, then the step that was
  // refused, which touches the box when checked on its own.
  await page.evaluate((h) => window.armlab.open(h), `${scene}&q=${start.join(',')}${drive}&collide=off`);
  s = await until(page, (st) => !st.motion.collisions && st.q.every((v, i) => v === start[i]), 'the start again');
  await click(page, 'ik-solve');
  const again = await steps(page, seen.length);
  assert.equal(again.length, seen.length);
  again.slice(0, -1).forEach((st, i) => assert.deepEqual(st.q, free[i].q, `step ${i + 1} repeats`));
  const next = again[again.length - 1].q;
  assert.ok(next.some((v, i) => Math.abs(v - stopped[i]) > 1e-6), 'the refused step moves on from the stop pose');
  for (const [q, touches] of [[next, true], [stopped, false]]) {
    await page.evaluate((h) => window.armlab.open(h), `${scene}&q=${q.join(',')}&collide=on`);
    s = await until(page, (st) => st.q.every((v, i) => v === q[i]) && st.motion.collisions, 'the pose on its own');
    s = await until(page, (st) => st.frame > s.frame + 2, 'two more frames');
    assert.equal(s.motion.contact !== null, touches, `${touches ? 'the next step' : 'the stop pose'} on its own: ${s.motion.contact}`);
  }
  assert.deepEqual(errors, []);
  await ctx.close();
});

test('a module that cannot be loaded (offline, no cache): the checks say so; on again, it loads', async () => {
  let offline = true;
  const { page, ctx, requests, errors } = await open('#robot=ur10&panels=motion&collide=on', { setup: async (c) => {
    await c.route('**/urdf/**', (route) => (offline ? route.abort('internetdisconnected') : route.continue()));
  } });
  let s = await until(page, (st) => st.motion.checker === 'failed', 'the failed import');
  assert.equal(s.motion.collisions, true, 'collide=on in the link turned the checks on');
  assert.equal(s.motion.contact, null);
  offline = false;
  await click(page, 'motion-collisions');
  s = await until(page, (st) => !st.motion.collisions, 'checks off');
  await click(page, 'motion-collisions');
  s = await until(page, (st) => st.motion.collisions && st.motion.checker === 'ready', 'the module on the second try');
  assert.ok(moduleRequests(requests).some((p) => p.endsWith('_bg.wasm.xz')), 'the packed wasm came on the second try');
  assert.ok(errors.every((e) => /urdf|import|fetch/i.test(e)), `only the failed import: ${errors}`);
  await ctx.close();
});
