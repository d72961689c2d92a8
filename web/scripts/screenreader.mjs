// What a real screen reader says on the built page: Orca reads ArmLab in Chromium on a
// virtual display, its speech goes to Orca's debug log, and this script prints the spoken
// lines step by step (a record to read, it asserts nothing, and it is not part of the test
// command). No sound card or speech synthesiser is needed: Orca writes each utterance to
// its log before it hands it to speech-dispatcher, and goes on without one.
//
//   apt-get install -y --no-install-recommends orca xvfb xdotool at-spi2-core dbus-daemon
//   (Debian 12 has Orca 43.1; Chromium and web/node_modules as for the browser tests)
//   cd web && node scripts/screenreader.mjs [DIST_DIR=../dist] [--log FILE] [--lang=fi]
//
// It starts, each in a process group of its own and all ended at the end: Xvfb on a free
// display, a D-Bus session bus, the AT-SPI bus, Orca with its debug log, the page served on
// loopback, and Debian's Chromium (CHROMIUM overrides the path) headful on that display
// with its renderer's accessibility on. Keys Orca must see (its own commands, Tab, the
// arrows, Enter) are real X key events from xdotool; a focus move a screen reader would
// make by its own navigation is done through the DOM, and a drag by the mouse through
// Chromium's DevTools protocol. Steps: the page loads; Tab five times; joint 2's slider
// focused and moved by the arrow keys; Orca's table commands in the Jacobian; the target
// dragged out of reach (the live region); a button pressed by Enter; the left column's edge
// focused and widened by an arrow key; the page read from its top by Orca's Say all
// (logged at once: with no synthesiser nothing paces it). With --log, Orca's whole debug log
// is kept in FILE; with --lang=fi, the page is the Finnish one (Orca's own words stay in its
// language). Takes about two minutes.
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { spawn, execFileSync } from 'node:child_process';
import { chromium } from 'playwright-core';
import { serveDist } from '../tests/static-server.mjs';

const args = process.argv.slice(2);
const logAt = args.indexOf('--log');
const keepLog = logAt >= 0 ? path.resolve(args[logAt + 1]) : null;
const distArg = args.filter((a, i) => !a.startsWith('--') && (logAt < 0 || i !== logAt + 1))[0];
const dist = path.resolve(distArg ?? path.join(import.meta.dirname, '..', '..', 'dist'));
// The words the scenario waits for and the button it focuses, in the page's language.
const WORDS = args.includes('--lang=fi')
  ? { lang: '&lang=fi', reached: 'Kohde saavutettu', outOfReach: 'ulottumattomissa', closeJoints: 'Sulje paneeli Nivelet',
    leftColumn: 'Vasemman sarakkeen leveys' }
  : { lang: '', reached: 'Target reached', outOfReach: 'out of reach', closeJoints: 'Close the Joints panel',
    leftColumn: 'Width of the left column' };
const HASH = `#robot=ur10&q=0,-1.1,1.2,-1.5,-1.2,0.3&task=position${WORDS.lang}`;

const work = fs.mkdtempSync(path.join(os.tmpdir(), 'armlab-orca-'));
const debugLog = path.join(work, 'orca.debug');
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const started = [];

/** Starts a program in a process group of its own (ended with the group at the end). */
function start(cmd, argv, env, { out = 'ignore' } = {}) {
  const child = spawn(cmd, argv, { env, detached: true, stdio: ['ignore', out, 'ignore'] });
  started.push(child);
  return child;
}

/** Ends what this script started, last first. */
async function stopAll() {
  for (const child of started.reverse()) {
    try { process.kill(-child.pid, 'SIGTERM'); } catch { /* already gone */ }
  }
  await sleep(1000);
  for (const child of started) {
    try { process.kill(-child.pid, 'SIGKILL'); } catch { /* already gone */ }
  }
}

/** The first X display number from 99 up that no server holds. */
function freeDisplay() {
  for (let n = 99; n < 200; n++) if (!fs.existsSync(`/tmp/.X11-unix/X${n}`) && !fs.existsSync(`/tmp/.X${n}-lock`)) return n;
  throw new Error('no free X display');
}

/** The D-Bus session bus: its address once the daemon printed it. */
async function sessionBus(env) {
  const bus = start('dbus-daemon', ['--session', '--nofork', '--print-address=1'], env, { out: 'pipe' });
  const address = await new Promise((resolve, reject) => {
    bus.stdout.once('data', (d) => resolve(String(d).trim()));
    bus.once('exit', () => reject(new Error('dbus-daemon exited')));
  });
  return address;
}

// Orca opens its debug log block-buffered; run it with the log line-buffered so that each
// utterance is in the file when it is spoken.
const ORCA_LINE_BUFFERED = `
import builtins, runpy, sys
log = sys.argv[sys.argv.index('--debug-file') + 1]
plain = builtins.open
def opened(f, mode='r', *a, **k):
    if str(f) == log and mode == 'w':
        return plain(f, mode, 1, **k)
    return plain(f, mode, *a, **k)
builtins.open = opened
sys.argv[0] = '/usr/bin/orca'
runpy.run_path('/usr/bin/orca', run_name='__main__')
`;

/** The spoken lines in the debug log from byte `from` on: [{ at, text }]. */
function spoken(from = 0) {
  // `from` is a size in bytes (logSize): slice the bytes, not the decoded text, whose
  // characters are fewer wherever Orca logged a θ, a × or a Finnish ä before.
  const text = fs.existsSync(debugLog) ? fs.readFileSync(debugLog).subarray(from).toString('utf8') : '';
  const lines = [];
  // An utterance is logged with its voice ("{...}") after it, but without one in Say all.
  for (const m of text.matchAll(/^(\d\d:\d\d:\d\d\.\d+) - SPEECH OUTPUT: '(.*)'(?: voice=\w+)?\s*(?:\{.*)?$/gm)) {
    lines.push({ at: m[1], text: m[2] });
  }
  return lines;
}

const logSize = () => (fs.existsSync(debugLog) ? fs.statSync(debugLog).size : 0);

/** Orca's mode in the page as it last announced it ("Browse mode" or "Focus mode"). */
let mode = 'Browse mode';

/** Runs `action`, waits until Orca has been quiet for `quiet` ms (at most `most` ms),
 * prints and returns what it said meanwhile. */
async function step(title, action, { quiet = 2000, most = 12000 } = {}) {
  const from = logSize();
  await action();
  const t0 = Date.now();
  let count = -1;
  let since = Date.now();
  while (Date.now() - t0 < most) {
    await sleep(250);
    const n = spoken(from).length;
    if (n !== count) { count = n; since = Date.now(); }
    if (Date.now() - since >= quiet) break;
  }
  const said = spoken(from);
  for (const s of said) if (/^(Browse|Focus) mode$/.test(s.text)) mode = s.text;
  console.log(`\n== ${title}`);
  for (const s of said) console.log(`  ${s.at}  ${JSON.stringify(s.text)}`);
  if (said.length === 0) console.log('  (nothing)');
  return said;
}

/** Real X key presses to the focused window, each given time to be handled. */
async function keys(env, ...names) {
  for (const k of names) {
    execFileSync('xdotool', ['key', k], { env });
    await sleep(700);
  }
}

/** Puts Orca in the page into `want` ("Browse mode" or "Focus mode") by its toggle, Orca+A. */
async function orcaMode(env, want) {
  for (let i = 0; i < 2 && mode !== want; i++) await step(`Orca+A (want ${want})`, () => keys(env, 'Insert+a'), { quiet: 1000 });
}

/** Focuses the mirror's element of the control with this role and name, as a screen
 * reader's own navigation does. */
async function focusControl(page, role, name) {
  const found = await page.evaluate(([r, n]) => {
    const el = [...document.querySelectorAll(`#armlab_a11y [role=${r}]`)].find((e) => e.getAttribute('aria-label') === n);
    el?.focus();
    return Boolean(el);
  }, [role, name]);
  if (!found) throw new Error(`no ${role} "${name}" in the page's mirror`);
}

async function scenario(page, env, base) {
  await step('page load', async () => {
    await page.goto(base + HASH);
    await page.waitForFunction((w) => (document.getElementById('armlab_live')?.textContent ?? '').includes(w),
      WORDS.reached, { timeout: 120000 });
  }, { quiet: 3000, most: 20000 });
  for (let i = 1; i <= 5; i++) await step(`Tab ${i}`, () => keys(env, 'Tab'));
  await step('joint 2\'s slider focused (through the DOM)', () => focusControl(page, 'slider', 'θ2'));
  await orcaMode(env, 'Focus mode');
  for (let i = 1; i <= 3; i++) await step(`Right arrow ${i} on the slider`, () => keys(env, 'Right'), { quiet: 3000 });
  await step('Left arrow on the slider', () => keys(env, 'Left'), { quiet: 3000 });
  await orcaMode(env, 'Browse mode');
  await step('T: next table', () => keys(env, 't'));
  await step('T: next table', () => keys(env, 't'));
  for (const k of ['alt+shift+Right', 'alt+shift+Down', 'alt+shift+Down', 'alt+shift+Left']) {
    await step(`table command ${k}`, () => keys(env, k));
  }
  await step('target dragged out of reach for about 3 s', async () => {
    await dragTargetAway(page);
    // On a loaded machine the arm follows the target a few seconds late.
    await page.waitForFunction((w) => (document.getElementById('armlab_live')?.textContent ?? '').includes(w),
      WORDS.outOfReach, { timeout: 30000 }).catch(() => console.log(`(the live region never said "${WORDS.outOfReach}")`));
  }, { quiet: 3000, most: 15000 });
  // Orca passes over a focus change that follows its own caret commands: the button is
  // reached by Tab from the control before it.
  await step(`"${WORDS.closeJoints}" focused (through the DOM)`, () => focusControl(page, 'button', WORDS.closeJoints));
  await step('Tab to "Zero"', () => keys(env, 'Tab'));
  await step('Enter on "Zero"', () => keys(env, 'Return'), { quiet: 2500 });
  await step(`"${WORDS.leftColumn}" focused (through the DOM)`, () => focusControl(page, 'separator', WORDS.leftColumn));
  // In browse mode Orca keeps the arrows for its own caret; a user switches to focus mode.
  await orcaMode(env, 'Focus mode');
  const viewX = () => page.evaluate(() => window.armlab.viewRect().x);
  const x0 = await viewX();
  await step('Right arrow on the column\'s edge', () => keys(env, 'Right'));
  console.log(`  (the 3D view's left edge: ${x0} → ${await viewX()} px)`);
  await orcaMode(env, 'Browse mode');
  await step('Control+Home, then Orca\'s Say all (KP_Add)', () => keys(env, 'ctrl+Home', 'KP_Add'), { quiet: 3000, most: 30000 });
}

/** Drags the target ball to the view's top-right corner, far past the arm's reach. */
async function dragTargetAway(page) {
  const t = await page.evaluate(() => window.armlab.screenPoint('target'));
  const view = await page.evaluate(() => window.armlab.viewRect());
  await page.mouse.move(t.x, t.y);
  await page.mouse.down();
  const t0 = Date.now();
  await page.mouse.move(view.x + view.width - 5, view.y + 5, { steps: 60 });
  while (Date.now() - t0 < 3000) await page.mouse.move(view.x + view.width - 5 - ((Date.now() / 50) % 2), view.y + 5);
  await page.mouse.up();
}

async function main() {
  const display = freeDisplay();
  // Chromium's and Orca's settings in the scratch folder, not in the user's.
  const env = { ...process.env, DISPLAY: `:${display}`, XDG_CONFIG_HOME: path.join(work, 'config') };
  start('Xvfb', [`:${display}`, '-screen', '0', '1366x800x24', '-nolisten', 'tcp'], env);
  for (let i = 0; i < 50 && !fs.existsSync(`/tmp/.X11-unix/X${display}`); i++) await sleep(100);
  env.DBUS_SESSION_BUS_ADDRESS = await sessionBus(env);
  start('/usr/libexec/at-spi-bus-launcher', ['--launch-immediately'], env);
  await sleep(1000);
  start('/usr/bin/python3', ['-c', ORCA_LINE_BUFFERED, '-u', path.join(work, 'orca-prefs'), '--debug-file', debugLog], env);
  for (let i = 0; i < 100 && !spoken().some((s) => s.text === 'Screen reader on.'); i++) await sleep(200);
  if (!spoken().length) throw new Error(`Orca said nothing: see ${debugLog}`);

  const { server, base } = await serveDist(dist);
  const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
    headless: false,
    env,
    args: ['--no-sandbox', '--force-renderer-accessibility', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
      '--window-position=0,0', '--window-size=1366,768', '--disable-background-networking', '--disable-component-update',
      '--disable-sync', '--no-first-run', '--disable-quic'],
  });
  try {
    const page = await browser.newContext({ viewport: null }).then((c) => c.newPage());
    // The X keyboard focus on Chromium's window (no window manager runs here).
    const win = execFileSync('xdotool', ['search', '--sync', '--onlyvisible', '--class', 'chromium'], { env })
      .toString().trim().split('\n')[0];
    execFileSync('xdotool', ['windowfocus', '--sync', win], { env });
    await scenario(page, env, base);
  } finally {
    await browser.close();
    server.close();
    if (keepLog) fs.copyFileSync(debugLog, keepLog);
    await stopAll();
    fs.rmSync(work, { recursive: true, force: true });
  }
}

main().catch(async (e) => {
  console.error(e);
  if (keepLog && fs.existsSync(debugLog)) fs.copyFileSync(debugLog, keepLog);
  await stopAll();
  process.exit(1);
});
