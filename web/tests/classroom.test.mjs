// The lecture room in one Chromium: the built page served by the classroom server (built by
// the test command's classroom step), one lecturer's page and three students' pages, each in
// a browser context of its own (its own localStorage, as on separate devices). Students
// follow, one explores and follows again, a question is answered by all three and shown on
// the lecturer's page, the server stops and restarts and every page comes back, and the
// lecturer closes the tab and reopens it with control kept; a student's network drops for 30 s.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import net from 'node:net';
import path from 'node:path';

import { dist, newPage, ready, settle, state, point } from './page.mjs';
import { launchChromium } from './static-server.mjs';
import { UNTIMED } from './browser-suite.mjs';

/** The classroom server the test command's classroom step built (debug), unless named. */
const SERVER = process.env.ARMLAB_CLASSROOM_BIN
  ?? path.join(process.env.CARGO_TARGET_DIR ?? path.join(process.env.HOME, '.cache/armlab/target'), 'debug', 'armlab-classroom');
const VIEW = { width: 900, height: 640 };

let browser;
let server;
let port;

/** A free loopback port. */
async function freePort() {
  const probe = net.createServer();
  await new Promise((resolve) => probe.listen(0, '127.0.0.1', resolve));
  const { port: free } = probe.address();
  await new Promise((resolve) => probe.close(resolve));
  return free;
}

/** Starts the classroom server on `port`, serving dist/; resolves once it answers. */
async function startServer() {
  const child = spawn(SERVER, ['--port', String(port), '--dist', dist], { stdio: ['ignore', 'ignore', 'inherit'] });
  for (let i = 0; i < 200; i++) {
    try {
      const answer = await fetch(`http://127.0.0.1:${port}/classroom/hello`);
      if (answer.ok) return child;
    } catch { /* not listening yet */ }
    await new Promise((r) => setTimeout(r, 50));
  }
  child.kill();
  throw new Error('the classroom server did not answer');
}

async function stopServer() {
  const exited = new Promise((resolve) => server.once('exit', resolve));
  server.kill('SIGTERM');
  await exited;
}

before(async () => {
  assert.ok(fs.existsSync(path.join(dist, 'index.html')), 'dist/ holds the built page');
  assert.ok(fs.existsSync(SERVER), `the classroom server is built (${SERVER}: cargo test -p armlab-classroom builds it)`);
  port = await freePort();
  server = await startServer();
  browser = await launchChromium(UNTIMED);
});

after(async () => {
  await browser?.close();
  if (server && server.exitCode === null) await stopServer();
});

/** `window.armlab.classroom()` (`{}` until a frame has built it after the first call). */
async function room(page) {
  const text = await page.evaluate(() => window.armlab.classroom());
  return text ? JSON.parse(text) : {};
}

/** Waits until `check(room)` holds, sending no input: the page draws the frames a
 * message, a closed connection or a reconnection's wait brings by itself, as for a
 * student who watches without touching the pointer. Fails naming `what`. */
async function roomUntil(page, check, what, seconds = 30) {
  const end = Date.now() + seconds * 1000;
  let last;
  while (Date.now() < end) {
    last = await room(page);
    if (check(last)) return last;
    await page.waitForTimeout(40);
  }
  throw new Error(`waited ${seconds} s for ${what}: ${JSON.stringify(last)}`);
}

/** Waits until the page's joint values are `q` (to the link's decimals), sending no
 * input (as `roomUntil`). */
async function qUntil(page, q, what) {
  const end = Date.now() + 30000;
  let s;
  while (Date.now() < end) {
    s = await state(page);
    if (s.q.length === q.length && s.q.every((v, i) => Math.abs(v - q[i]) < 1e-5)) return s;
    await page.waitForTimeout(40);
  }
  throw new Error(`waited for ${what}: q = ${JSON.stringify(s?.q)}, not ${JSON.stringify(q)}`);
}

/**
 * A loopback TCP relay to the classroom server: a student's network, which `drop()` cuts
 * (every connection closed, new ones refused) until `restore()`. Chromium's offline
 * emulation leaves an open WebSocket open, as a real network drop does not.
 */
async function network() {
  const sockets = new Set();
  let down = false;
  const relay = net.createServer((client) => {
    if (down) { client.destroy(); return; }
    const upstream = net.connect(port, '127.0.0.1');
    for (const [a, b] of [[client, upstream], [upstream, client]]) {
      sockets.add(a);
      a.pipe(b);
      a.on('error', () => b.destroy());
      a.on('close', () => { sockets.delete(a); b.destroy(); });
    }
  });
  await new Promise((resolve) => relay.listen(0, '127.0.0.1', resolve));
  return {
    port: relay.address().port,
    drop() { down = true; for (const s of sockets) s.destroy(); },
    restore() { down = false; },
    close() { relay.close(); for (const s of sockets) s.destroy(); },
  };
}

/** Opens `hash` on a page served by the classroom server (through `via`, a port of a
 * relay to it), in a context of its own. */
async function open(hash, via = port) {
  const opened = await newPage(browser, { view: VIEW });
  await opened.page.goto(`http://127.0.0.1:${via}/${hash}`, { waitUntil: 'domcontentloaded' });
  await ready(opened.page);
  return opened;
}

/** The lecturer shows the PUMA 560 at `q` (as a click on a preset and slides would). */
async function show(page, q) {
  await page.evaluate((hash) => window.armlab.open(hash), `robot=puma560&q=${q.join(',')}&task=position`);
  await settle(page);
}

test('students follow, explore, follow again and answer; every page comes back after a server restart, a student after 30 s offline, the lecturer after reopening the tab', async () => {
  const lecturer = await open('#class=new');
  const made = await roomUntil(lecturer.page, (r) => r.role === 'lecturer' && r.code && r.connected, 'the class to be created');
  // The third student's network can be cut.
  const wifi = await network();
  const students = [];
  for (let i = 0; i < 3; i++) students.push(await open(`#class=${made.code}`, i === 2 ? wifi.port : port));
  for (const s of students) {
    const joined = await roomUntil(s.page, (r) => r.role === 'student' && r.connected && r.following, 'a student to join');
    assert.equal(joined.code, made.code);
  }
  await roomUntil(lecturer.page, (r) => r.students === 3, 'three students counted');

  // Follow: each student's page shows the lecturer's robot and pose.
  const q1 = [0.3, -0.4, 0.5, 0.1, 0.6, -0.2];
  await show(lecturer.page, q1);
  for (const s of students) {
    const followed = await qUntil(s.page, q1, 'a student to follow');
    assert.equal(followed.robot, 'Puma 560');
  }

  // Explore: the first student drags on their own; the others keep following.
  await point(students[0].page, 'class-explore').then((p) => students[0].page.mouse.click(p.x, p.y));
  await roomUntil(students[0].page, (r) => !r.following, 'the student to explore');
  const q2 = [-0.5, 0.2, 0.1, 0.0, 0.4, 0.3];
  await show(lecturer.page, q2);
  await qUntil(students[1].page, q2, 'a following student to follow');
  assert.deepEqual((await state(students[0].page)).q.map((v) => v.toFixed(5)), q1.map((v) => v.toFixed(5)));
  await point(students[0].page, 'class-follow').then((p) => students[0].page.mouse.click(p.x, p.y));
  await qUntil(students[0].page, q2, 'the student to follow again');

  // Ask the room: is the target reachable? All three answer; the lecturer's page counts them.
  await point(lecturer.page, 'class-ask').then((p) => lecturer.page.mouse.click(p.x, p.y));
  await settle(lecturer.page);
  const asks = await lecturer.page.evaluate(() => window.armlab.screenPoint('class-ask-0') !== null);
  assert.ok(asks, 'the question menu is open');
  // The reachable question comes after the point, the three tool coordinates, six joints and det J.
  await point(lecturer.page, 'class-ask-11').then((p) => lecturer.page.mouse.click(p.x, p.y));
  const asked = await roomUntil(lecturer.page, (r) => r.question !== null, 'the question to be asked');
  for (const s of students) {
    await roomUntil(s.page, (r) => r.question === asked.question, 'the question to reach a student');
    await point(s.page, 'class-option-0').then((p) => s.page.mouse.click(p.x, p.y));
  }
  await roomUntil(lecturer.page, (r) => r.answers === 3, 'three answers on the lecturer\'s page');
  await point(lecturer.page, 'class-reveal').then((p) => lecturer.page.mouse.click(p.x, p.y));
  for (const s of students) await roomUntil(s.page, (r) => r.revealed && r.answers === 3, 'the truth beside the answers');
  await lecturer.page.screenshot({ path: path.join(path.dirname(new URL(import.meta.url).pathname), 'screenshots', 'classroom-lecturer.png') });

  // The server stops mid-lecture: every page says so and reconnects once it is back.
  await stopServer();
  for (const p of [lecturer, ...students]) await roomUntil(p.page, (r) => !r.connected, 'the page to notice the server is gone');
  server = await startServer();
  await roomUntil(lecturer.page, (r) => r.role === 'lecturer' && r.connected && r.code === made.code, 'the lecturer to re-create the class');
  for (const s of students) await roomUntil(s.page, (r) => r.connected && r.role === 'student', 'a student to come back');
  await roomUntil(lecturer.page, (r) => r.students === 3, 'three students counted again');
  const q3 = [0.1, 0.1, 0.1, 0.1, 0.1, 0.1];
  await show(lecturer.page, q3);
  for (const s of students) await qUntil(s.page, q3, 'a student to follow after the restart');

  // A student's network drops for 30 s: the page says so, the others go on, and it
  // follows again once the network is back.
  wifi.drop();
  await roomUntil(students[2].page, (r) => !r.connected, 'the offline student to notice', 20);
  const qOffline = [0.4, -0.1, 0.2, 0.1, 0.3, 0.1];
  await show(lecturer.page, qOffline);
  await qUntil(students[0].page, qOffline, 'an online student to follow meanwhile');
  await students[2].page.waitForTimeout(30000 - 2000);
  wifi.restore();
  await roomUntil(students[2].page, (r) => r.connected && r.following, 'the student to come back', 30);
  await qUntil(students[2].page, qOffline, 'the student back online to show the state it missed');

  // The lecturer closes the tab and opens the class again: the token kept in the browser
  // gives control back.
  const reopened = await lecturer.ctx.newPage();
  await lecturer.page.close();
  await reopened.goto(`http://127.0.0.1:${port}/#class=${made.code}`, { waitUntil: 'domcontentloaded' });
  await ready(reopened);
  await roomUntil(reopened, (r) => r.role === 'lecturer' && r.connected, 'the lecturer to take control again');
  const q4 = [0.2, -0.2, 0.3, 0.0, 0.2, 0.0];
  await show(reopened, q4);
  for (const s of students) await qUntil(s.page, q4, 'a student to follow the reopened lecturer');
  wifi.close();
  for (const p of [lecturer, ...students]) assert.deepEqual(p.errors.filter((e) => !/WebSocket/.test(e)), []);
});
