// How soon a cold first visit draws its first frame, over a throttled link and on
// loopback: a benchmark, it prints figures and asserts nothing, and it is not part of the
// test command.
//
//   node web/scripts/firstframe.mjs DIST_DIR [runs=5] [--encoding=gzip|br] [--down=9] [--up=3] [--rtt=100] [--revisit]
//
// The build is served compressed as a host serves it (gzip, as GitHub Pages; br, as an
// Apache with mod_brotli), and each run opens the page in a fresh browser context (an
// empty HTTP cache, no service worker) with Chromium's network throttling (CDP
// Network.emulateNetworkConditions: `down` and `up` Mbit/s, `rtt` ms round trip, 9/3/100
// by default, a crowded lecture-hall Wi-Fi or a phone's connection), then five runs the
// same on loopback without throttling. `shown_ms`: when that first frame reached the
// canvas (the blit into it after firstFrameAt), after egui's paint. Where the build holds files compressed ahead
// (NAME.br, NAME.gz, as build_web writes them), the server sends those. It prints, per run, the ms from the navigation's
// start to the app's first drawn frame (window.armlab.firstFrameAt()), to the wasm's
// request and to its last byte, the bytes that came over the wire, and which files were
// requested more than once, and how many wasm files the server had sent by the first
// frame (the page's own, and any a service worker fetched meanwhile: its fetches pass
// through the server but not through the page's emulated link); then the median of each set.
// With --revisit, instead, a returning visitor on loopback: one visit, and once the service
// worker has cached the build, `runs` reloads, each page from the worker's cache (the
// first frame of each, and its median).
import fs from 'node:fs';
import path from 'node:path';
import { serveDist, launchChromium } from '../tests/static-server.mjs';

const args = process.argv.slice(2);
const option = (name, fallback) => args.find((a) => a.startsWith(`--${name}=`))?.slice(name.length + 3) ?? fallback;
const [distArg, runsArg] = args.filter((a) => !a.startsWith('--'));
if (!distArg) {
  console.error('usage: node web/scripts/firstframe.mjs DIST_DIR [runs] [--encoding=gzip|br] [--down=9] [--up=3] [--rtt=100]');
  process.exit(2);
}
const runs = Number(runsArg ?? 5);
const encoding = option('encoding', 'gzip');
const link = { down: Number(option('down', 9)), up: Number(option('up', 3)), rtt: Number(option('rtt', 100)) };
const { server, base } = await serveDist(path.resolve(distArg), { encoding });
const browser = await launchChromium();
// The server compresses each file once, on its first request: that is done here, before
// any run is timed (brotli's quality 11 takes the 4 MB wasm most of a minute).
for (const file of fs.readdirSync(path.resolve(distArg)).filter((f) => !/\.(br|gz)$/.test(f))) {
  await fetch(base + file, { headers: { 'accept-encoding': encoding } }).then((r) => r.arrayBuffer());
}
// Every answer the server finished, with when (epoch ms): the service worker's fetches do
// not pass through the page's network emulation, but they do through the server.
const served = [];
server.on('request', (req, res) => res.on('finish', () => served.push({ path: new URL(req.url, 'http://x').pathname, at: Date.now() })));

async function run(throttled) {
  const ctx = await browser.newContext({ viewport: { width: 1366, height: 768 }, deviceScaleFactor: 1 });
  // When each picture reached the canvas: wgpu's WebGL2 backend shows a frame by a blit
  // into the canvas's own framebuffer. firstFrameAt() is taken while the app builds its
  // first frame; the blit after it is that frame handed to the browser, after egui's
  // paint (and after any pass egui ran again before painting).
  await ctx.addInitScript(() => {
    const GL = window.WebGL2RenderingContext?.prototype;
    if (!GL) return;
    const blit = GL.blitFramebuffer;
    window.armlabCanvasBlits = [];
    GL.blitFramebuffer = function (...args) {
      const r = blit.apply(this, args);
      if (this.getParameter(this.DRAW_FRAMEBUFFER_BINDING) === null) window.armlabCanvasBlits.push(performance.now());
      return r;
    };
  });
  const page = await ctx.newPage();
  const cdp = await ctx.newCDPSession(page);
  await cdp.send('Network.enable');
  await cdp.send('Network.setCacheDisabled', { cacheDisabled: false });
  if (throttled) {
    await cdp.send('Network.emulateNetworkConditions', {
      offline: false,
      latency: link.rtt,
      downloadThroughput: (link.down * 1e6) / 8,
      uploadThroughput: (link.up * 1e6) / 8,
    });
  }
  const wire = new Map();
  const urls = new Map();
  cdp.on('Network.requestWillBeSent', (e) => urls.set(e.requestId, new URL(e.request.url).pathname));
  cdp.on('Network.loadingFinished', (e) => wire.set(e.requestId, e.encodedDataLength));
  // Whether the server sent the wasm from the build's copy compressed ahead (NAME.br, NAME.gz).
  let precompressed = false;
  cdp.on('Network.responseReceived', (e) => {
    if (/\.wasm(\.xz)?$/.test(e.response.url)) precompressed = e.response.headers['x-precompressed'] === '1';
  });
  served.length = 0;
  await page.goto(`${base}#robot=ur10`, { waitUntil: 'commit' });
  await page.waitForFunction(() => {
    const at = window.armlab?.firstFrameAt?.();
    return at && window.armlabCanvasBlits.some((t) => t >= at);
  }, null, { timeout: 120000, polling: 100 });
  const timing = await page.evaluate(() => {
    const wasm = performance.getEntriesByType('resource').filter((e) => /\.wasm(\.xz)?$/.test(e.name));
    return {
      first_frame_ms: Math.round(window.armlab.firstFrameAt()),
      shown_ms: Math.round(window.armlabCanvasBlits.find((t) => t >= window.armlab.firstFrameAt())),
      first_frame_epoch_ms: performance.timeOrigin + window.armlab.firstFrameAt(),
      wasm_start_ms: Math.round(Math.min(...wasm.map((e) => e.startTime))),
      wasm_end_ms: Math.round(Math.max(0, ...wasm.map((e) => e.responseEnd))),
      // The load event: index.html registers the service worker then.
      load_ms: Math.round(performance.getEntriesByType('navigation')[0]?.loadEventStart ?? -1),
    };
  });
  const requested = [...urls.values()];
  const twice = [...new Set(requested.filter((u, i) => requested.indexOf(u) !== i))];
  const bytes = [...wire.values()].reduce((a, b) => a + b, 0);
  await ctx.close();
  const { first_frame_epoch_ms: firstAt, ...shown } = timing;
  // The wasm files the server sent before the first frame: the page's, and a worker's.
  const wasmServed = served.filter((s) => s.at <= firstAt && /\.wasm(\.xz)?$/.test(s.path)).length;
  return { ...shown, wire_bytes: bytes, requests: requested.length, requested_twice: twice, wasm_files_served_before_first_frame: wasmServed, wasm_precompressed: precompressed };
}

/** A returning visitor: the first frames of `runs` reloads once the worker has cached the build. */
async function revisits() {
  const ctx = await browser.newContext({ viewport: { width: 1366, height: 768 }, deviceScaleFactor: 1 });
  const page = await ctx.newPage();
  const drawn = () => page.waitForFunction(() => window.armlab?.firstFrameAt?.(), null, { timeout: 120000, polling: 100 });
  await page.goto(`${base}#robot=ur10`);
  await drawn();
  await page.evaluate(() => Promise.race([navigator.serviceWorker.ready,
    new Promise((_, reject) => setTimeout(() => reject(new Error('no service worker became ready in 60 s')), 60000))]));
  const times = [];
  for (let i = 0; i < runs; i++) {
    await page.reload();
    await drawn();
    const { at, controlled } = await page.evaluate(() => ({ at: window.armlab.firstFrameAt(), controlled: !!navigator.serviceWorker.controller }));
    if (!controlled) throw new Error('the reload did not come from the service worker');
    times.push(Math.round(at));
  }
  await ctx.close();
  return times;
}

const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];
for (const throttled of args.includes('--revisit') ? [] : [true, false]) {
  const label = throttled ? `${link.down}/${link.up} Mbit/s, ${link.rtt} ms RTT, ${encoding}` : `loopback, ${encoding}`;
  const results = [];
  for (let i = 1; i <= runs; i++) {
    const r = await run(throttled);
    console.log(JSON.stringify({ link: label, run: i, ...r }));
    results.push(r);
  }
  console.log(JSON.stringify({ link: label, median_first_frame_ms: median(results.map((r) => r.first_frame_ms)),
    first_frame_ms: results.map((r) => r.first_frame_ms), median_shown_ms: median(results.map((r) => r.shown_ms)),
    shown_ms: results.map((r) => r.shown_ms), median_wasm_end_ms: median(results.map((r) => r.wasm_end_ms)) }));
}
if (args.includes('--revisit')) {
  const times = await revisits();
  console.log(JSON.stringify({ link: `loopback, ${encoding}, a returning visit (the service worker's cache)`, median_first_frame_ms: median(times), first_frame_ms: times }));
}
await browser.close();
server.close();
