// The CPU a built page's frame costs Chromium's processes while the view rests: the GPU
// process (SwiftShader draws there when there is no GPU), the page's renderer process and
// the browser process, in milliseconds of CPU per frame. A benchmark for Linux (it reads
// /proc): it prints figures and asserts nothing, and it is not part of the test command.
// Frames per second (fps.mjs) measure a frame's wall time, which on two cores hides work
// that runs beside the main thread; this measures the work, which is what a machine
// shared with other pages, or the test command's two browser files, pays.
//
//   node web/scripts/framecpu.mjs DIST_DIR [runs=3] [frames=60] [--size=1400x860] [--init=JS]
//
// Each run opens a fresh page (DPR 1) with the UR10, lets it draw, then nudges the pointer
// over the top bar until the app has drawn `frames` more frames (as the browser tests'
// `settle` does: the 3D view's picture is kept, egui draws every panel) and reads each
// process's CPU time before and after. `--init` runs JS in the page before its own scripts
// (to switch a WebGL call off, say, and see what it cost). One JSON line per run.
import fs from 'node:fs';
import path from 'node:path';
import { serveDist, launchChromium } from '../tests/static-server.mjs';
import { newPage, ready, settle, state } from '../tests/page.mjs';

const args = process.argv.slice(2);
const option = (name) => args.find((a) => a.startsWith(`--${name}=`))?.slice(name.length + 3);
const [distArg, runsArg, framesArg] = args.filter((a) => !a.startsWith('--'));
if (!distArg) {
  console.error('usage: node web/scripts/framecpu.mjs DIST_DIR [runs] [frames] [--size=WxH] [--init=JS]');
  process.exit(2);
}
const [width, height] = (option('size') ?? '1400x860').split('x').map(Number);
const init = option('init');

/** CPU seconds (user + system) of this script's Chromium, by process type (`--type`; the
 * browser process has none): the processes descended from this one. */
function chromiumCpu() {
  const procs = new Map();
  for (const pid of fs.readdirSync('/proc').filter((p) => /^\d+$/.test(p))) {
    try {
      const stat = fs.readFileSync(`/proc/${pid}/stat`, 'utf8');
      const fields = stat.slice(stat.lastIndexOf(')') + 2).split(' ');
      const cmd = fs.readFileSync(`/proc/${pid}/cmdline`, 'utf8');
      procs.set(Number(pid), { ppid: Number(fields[1]), cpu: (Number(fields[11]) + Number(fields[12])) / 100, cmd });
    } catch {
      // gone meanwhile
    }
  }
  const ours = new Set([process.pid]);
  for (let grew = true; grew;) {
    grew = false;
    for (const [pid, p] of procs) if (!ours.has(pid) && ours.has(p.ppid)) { ours.add(pid); grew = true; }
  }
  const byType = {};
  for (const pid of ours) {
    const p = procs.get(pid);
    if (!p || !p.cmd.includes('chrom')) continue;
    const type = p.cmd.match(/--type=([a-z-]+)/)?.[1] ?? 'browser';
    byType[type] = (byType[type] ?? 0) + p.cpu;
  }
  return byType;
}

const server = await serveDist(path.resolve(distArg));
const browser = await launchChromium();
for (let run = 0; run < Number(runsArg ?? 3); run++) {
  const { ctx, page } = await newPage(browser, { view: { width, height } });
  if (init) await ctx.addInitScript(init);
  await page.goto(`${server.base}#robot=ur10`, { waitUntil: 'domcontentloaded' });
  await ready(page);
  await settle(page, 10);
  const before = chromiumCpu();
  const f0 = (await state(page)).frame;
  await settle(page, Number(framesArg ?? 60));
  const frames = (await state(page)).frame - f0;
  const after = chromiumCpu();
  const ms = Object.fromEntries(Object.keys(after).map((t) => [t, +((1000 * (after[t] - (before[t] ?? 0))) / frames).toFixed(1)]));
  console.log(JSON.stringify({ size: `${width}x${height}`, frames, cpu_ms_per_frame: ms }));
  await ctx.close();
}
await browser.close();
server.server.close();
