// The motion lab in the built page (dist/) in headless Chromium: with "move" on, Solve
// makes the arm drive to the IK answer with each controller; the final error is read from
// window.armlab.state().motion. Prints one JSON line of measurements (not asserted): the
// simulation's milliseconds per frame (frameTimes()'s `motion` part, steps and collision
// checks) and the frame's p95 while driving with collision checks on.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { browserSuite } from './browser-suite.mjs';
import { dist, state, pageOpener } from './page.mjs';

const VIEW = { width: 1024, height: 768 }; // the lecture-hall projector
const measurements = {};

const suite = browserSuite(dist, { label: 'ARMLAB_MOTION_MEASUREMENTS', measurements });
// Uncaught exceptions count as errors here, not what the page logs to the console; the
// tests drive the frames themselves once the first is drawn.
const { open: openPage } = pageOpener(suite, { view: VIEW, consoleErrors: false, settled: false });

/** Opens `hash` in the running page and waits for two more frames. */
async function openHash(page, hash) {
  const before = (await state(page)).frame;
  await page.evaluate((h) => window.armlab.open(h), hash);
  for (let i = 0; i < 200 && (await state(page)).frame < before + 2; i++) {
    await page.mouse.move(700 + (i % 2), 40);
    await page.waitForTimeout(20);
  }
}

// How far the tool may stray from the straight lines between waypoints in a visit (mm).
const LINE_TOL = 3;

const quantile = (xs, q) => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length ? s[Math.min(s.length - 1, Math.floor(s.length * q))] : null;
};

// Each controller with its gains (the link's `gains=`) and the largest final joint error
// it must reach: the on/off controller stops inside its dead band (0.05 rad: the motor's
// 20 ms lag coasts 0.03 rad past the band's edge, which stays inside it); the others
// settle to rest (|e| < 1e-4, |q̇| < 1e-3).
const CONTROLLERS = [
  { ctrl: 'onoff', gains: '0.05', tol: 0.05 },
  { ctrl: 'p', gains: '5', tol: 1e-4 },
  { ctrl: 'pd', gains: '100,20', tol: 1e-4 },
  { ctrl: 'pid', gains: '100,200,20', tol: 1e-4 },
  { ctrl: 'trapezoidal', gains: '0', tol: 1e-4 },
  { ctrl: 'cubic', gains: '0', tol: 1e-4 },
  { ctrl: 'quintic', gains: '1', tol: 1e-4 },
];

test('with move on, the arm drives to the target with each controller', async () => {
  // The target: the tool of the RRR arm at another pose (surely reachable).
  const { page, ctx, errors } = await openPage('#robot=rrr&q=0.4,0.3,-0.7&task=position&panels=ik,motion');
  const goal = (await state(page)).tool;
  const start = '#robot=rrr&q=0,0.5,-1&task=position&panels=ik,motion';
  const target = `target=${goal.map((v) => v.toFixed(6)).join(',')},0,0,0`;
  const results = {};
  const totals = { ms: 0, steps: 0 };
  for (const { ctrl, gains, tol } of CONTROLLERS) {
    await openHash(page, `${start}&${target}&move=on&ctrl=${ctrl}&gains=${gains}&timescale=2`);
    let s = await state(page);
    assert.equal(s.motion.on, true, `${ctrl}: move is on`);
    assert.equal(s.motion.controller, ctrl);
    assert.ok(s.position_error > 10 * 1e-3, `${ctrl}: the arm starts away from the target`);
    await page.evaluate(() => window.armlab.frameTimes());
    const solve = await page.evaluate(() => window.armlab.screenPoint('ik-solve'));
    assert.ok(solve, 'the Solve button is on screen');
    await page.mouse.click(solve.x, solve.y);
    // Until at rest, or 8 simulated seconds (on/off rests inside its band, not at |e| < 1e-4).
    for (let i = 0; i < 600; i++) {
      await page.waitForTimeout(50);
      s = await state(page);
      if (s.motion.at_rest && s.motion.time > 0.2) break;
      if (s.motion.time > 8) break;
    }
    for (const f of await page.evaluate(() => window.armlab.frameTimes())) {
      totals.ms += f.motion;
      totals.steps += f.motion_steps;
    }
    const worst = Math.max(...s.motion.error.map(Math.abs));
    results[ctrl] = { final_error: worst, position_error: s.position_error, simulated_s: s.motion.time };
    assert.ok(worst < tol, `${ctrl}: final joint error ${worst} below ${tol}`);
    assert.ok(s.motion.time > 0.3, `${ctrl}: the arm drove there (${s.motion.time} s), it did not jump`);
    assert.ok(s.motion.trail >= 2, `${ctrl}: the tool's path was drawn (${s.motion.trail} points)`);
    if (ctrl !== 'onoff') assert.ok(s.reached, `${ctrl}: the target is reached`);
  }
  measurements.controllers = results;
  measurements.motion_us_per_step = (1000 * totals.ms) / Math.max(1, totals.steps);
  measurements.motion_steps = totals.steps;
  assert.deepEqual(errors, []);
  await ctx.close();
});

test('driving with collide=on in the link: the checks run in the lazily loaded module; the cost per frame', async () => {
  const { page, ctx, errors } = await openPage('#robot=ur10&q=0.4,1.1,-1.3,1.6,1.4,0.2&panels=ik,motion');
  const s0 = await state(page);
  const t = s0.tool;
  const target = `target=${(t[0] - 300).toFixed(3)},${(t[1] + 400).toFixed(3)},${(t[2] + 200).toFixed(3)},0,0,0`;
  await openHash(page, `#robot=ur10&q=0.4,1.1,-1.3,1.6,1.4,0.2&${target}&task=position&panels=ik,motion&move=on&ctrl=quintic&collide=on`);
  await page.evaluate(() => window.armlab.frameTimes());
  const solve = await page.evaluate(() => window.armlab.screenPoint('ik-solve'));
  await page.mouse.click(solve.x, solve.y);
  let s;
  for (let i = 0; i < 300; i++) {
    await page.waitForTimeout(50);
    s = await state(page);
    if (s.motion.at_rest && s.motion.time > 0.2) break;
  }
  const frames = await page.evaluate(() => window.armlab.frameTimes());
  const moving = frames.filter((f) => f.motion > 0);
  assert.ok(moving.length >= 3, `frames while driving: ${moving.length}`);
  // collide=on in the link: the checks ran in the collision module (web/tests/collision.test.mjs).
  assert.equal(s.motion.collisions, true);
  assert.equal(s.motion.checker, 'ready');
  // The drive ended: the arm rests, and nothing on the way stopped it short of the target.
  assert.ok(s.motion.at_rest && !s.motion.moving, `the arm came to rest (${s.motion.time} s simulated)`);
  assert.equal(s.motion.contact, null, 'no part touched on the way');
  assert.ok(s.reached, `the target is reached (${s.position_error} mm off)`);
  assert.ok(Math.max(...s.motion.error.map(Math.abs)) < 1e-4, `at the goal: ${s.motion.error}`);
  measurements.ur10_collide = {
    frames: moving.length,
    motion_ms_p50: quantile(moving.map((f) => f.motion), 0.5),
    motion_ms_p95: quantile(moving.map((f) => f.motion), 0.95),
    steps_per_frame_p50: quantile(moving.map((f) => f.motion_steps), 0.5),
    motion_us_per_step: 1000 * moving.reduce((a, f) => a + f.motion, 0) / Math.max(1, moving.reduce((a, f) => a + f.motion_steps, 0)),
    frame_ms_p95: quantile(moving.map((f) => f.app + f.render), 0.95),
    contact: s.motion.contact,
  };
  assert.deepEqual(errors, []);
  await ctx.close();
});

test('waypoints from a link and the Add waypoint button are visited along a straight line, with collision checks on', async () => {
  // Poses on the same side as the UR10's home (q2 > 0, q3 < 0 in SPEC's table), where no
  // part touches another: with q2 < 0 the forearm reaches into the base's cylinder.
  const start = '0.3,1.2,-1.4,1.8,1.5,0';
  const { page, ctx, errors } = await openPage(`#robot=ur10&q=${start}&panels=motion`);
  // Each waypoint: the tool's pose at a joint vector (a link without target= puts the
  // target on the tool; the written hash gives it as x,y,z,α,β,γ).
  const poses = [];
  for (const q of ['0.6,1.0,-1.2,1.7,1.5,0.3', '0.9,1.4,-1.6,1.9,1.3,0.1', '0.4,0.9,-1.0,1.5,1.6,-0.4']) {
    await openHash(page, `#robot=ur10&q=${q}&panels=motion`);
    const hash = (await state(page)).hash;
    poses.push(hash.split('&').find((p) => p.startsWith('target=')).slice('target='.length));
  }
  // Two waypoints by the link, the third is the target added with the button.
  await openHash(page, `#robot=ur10&q=${start}&target=${poses[2]}&panels=motion&path=line&timescale=2&collide=on&wp=${poses[0]};${poses[1]}`);
  let s = await state(page);
  assert.equal(s.paths.kind, 'line');
  assert.equal(s.paths.waypoints.length, 2);
  const click = async (name) => {
    const p = await page.evaluate((n) => window.armlab.screenPoint(n), name);
    assert.ok(p, `${name} is on screen`);
    // egui draws on input only: a move first draws the frame the click lands in.
    await page.mouse.move(p.x, p.y);
    await page.waitForTimeout(100);
    await page.mouse.click(p.x, p.y);
    await page.waitForTimeout(100);
    await page.mouse.move(p.x + 1, p.y);
    await page.waitForTimeout(100);
  };
  await click('path-fold');
  await click('path-add-waypoint');
  s = await state(page);
  assert.equal(s.paths.waypoints.length, 3, 'Add waypoint stored the target');
  assert.ok(s.position_error > 10, `the arm starts away from the last waypoint (${s.position_error} mm)`);
  await page.evaluate(() => window.armlab.frameTimes());
  const from = s.tool;
  await click('path-visit');
  s = await state(page);
  assert.equal(s.motion.on, true, 'Visit turns Move on');
  assert.ok(s.paths.visiting, 'the visit is under way');
  assert.deepEqual(s.paths.issues, [], 'the line between these waypoints has no problem');
  const frames = [];
  const tools = [];
  for (let i = 0; i < 1200 && !s.paths.visit_done; i++) {
    await page.waitForTimeout(50);
    s = await state(page);
    tools.push(s.tool);
    frames.push(...(await page.evaluate(() => window.armlab.frameTimes())));
  }
  assert.ok(s.paths.visit_done, `the visit ends (${s.motion.time} s simulated)`);
  // Along straight lines: every tool position seen on the way lies on the polyline from
  // where the arm started through the three waypoints, within LINE_TOL mm. The arm moves
  // in joint space toward a goal on the line 0.05 rad ahead of it, so between those goals
  // the tool strays a little (about 1.2 mm at most for these waypoints in the native app;
  // a joint-space visit of them strays 44 mm).
  const corners = [from, ...s.paths.waypoints];
  const sub = (a, b) => a.map((v, i) => v - b[i]);
  const dot = (a, b) => a.reduce((sum, v, i) => sum + v * b[i], 0);
  const toSegment = (p, a, b) => {
    const ab = sub(b, a);
    const t = Math.min(1, Math.max(0, dot(sub(p, a), ab) / dot(ab, ab)));
    return Math.hypot(...sub(p, a.map((v, i) => v + t * ab[i])));
  };
  const offLine = (p) => Math.min(...corners.slice(1).map((b, k) => toSegment(p, corners[k], b)));
  const worst = Math.max(...tools.map(offLine));
  // Points well inside the segments, away from the corners: the check saw the lines.
  const inside = tools.filter((p) => corners.every((c) => Math.hypot(...sub(p, c)) > 20)).length;
  assert.ok(inside >= 5, `${inside} tool positions seen between the waypoints`);
  assert.ok(worst < LINE_TOL, `the tool strays ${worst.toFixed(3)} mm from the straight lines`);
  // The frames below are measured with collision checks on (collide=on: every simulation
  // step's pose goes through the lazily loaded module), and no part touched on the way.
  assert.equal(s.motion.collisions, true);
  assert.equal(s.motion.checker, 'ready');
  assert.equal(s.motion.contact, null, `no contact on the way: ${s.motion.contact}`);
  const last = s.paths.waypoints[2];
  const off = Math.hypot(...s.tool.map((v, i) => v - last[i]));
  // Reached: within 1e-5 m (0.01 mm) of the last waypoint, which is the target.
  assert.ok(off < 0.01, `the tool ends ${off} mm from the last waypoint`);
  assert.ok(s.reached, 'the target (the last waypoint) is reached');
  assert.ok(s.motion.trail > 20, `the tool's path was drawn (${s.motion.trail} points)`);
  // Frames that ran simulation steps (the motion's milliseconds round to 0 on fast frames).
  const moving = frames.filter((f) => f.motion_steps > 0);
  assert.ok(moving.length >= 10, `frames while driving: ${moving.length}`);
  measurements.cartesian_visit = {
    final_error_mm: off,
    largest_distance_from_the_lines_mm: worst,
    positions_between_waypoints: inside,
    position_error: s.position_error,
    simulated_s: s.motion.time,
    frames: moving.length,
    frame_ms_p50: quantile(moving.map((f) => f.app + f.render), 0.5),
    frame_ms_p95: quantile(moving.map((f) => f.app + f.render), 0.95),
    motion_ms_p95: quantile(moving.map((f) => f.motion), 0.95),
  };
  assert.deepEqual(errors, []);
  await ctx.close();
});
