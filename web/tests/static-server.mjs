// The built page (dist/) served on loopback, and headless Chromium, for the scripts that
// drive the page: the browser tests (through browser-suite.mjs) and the developer scripts
// outside the test command (web/scripts/: frametimes.mjs, cpuprofile.mjs, soak.mjs). It
// lives with the tests, which run on every test command, so that a change that breaks it
// fails there and not only in a script run by hand.
import http from 'node:http';
import fs from 'node:fs';
import path from 'node:path';
import zlib from 'node:zlib';
import { chromium } from 'playwright-core';

const types = {
  '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.wasm': 'application/wasm', '.css': 'text/css',
  '.json': 'application/json', '.png': 'image/png', '.svg': 'image/svg+xml', '.xz': 'application/x-xz',
};

/**
 * Serves the folder `dist` on a free loopback port; returns the server and its URL. With
 * `encoding` 'gzip' or 'br' it compresses each answer, where the request accepts it, as a
 * host does: 'gzip' as GitHub Pages and Apache's mod_deflate (level 9 here, the page's
 * budget figure), 'br' as Apache's mod_brotli (quality 11 here: a host compressing on the
 * fly uses less, a host serving files compressed ahead, the same). Compressed once per file;
 * where the build wrote the file compressed ahead (`NAME.br`, `NAME.gz`:
 * web/build/precompress.mjs), that copy is sent, as nginx's `gzip_static` and the classroom
 * server do (the answer's `x-precompressed` header says so). An `.xz` file is sent as it is.
 */
export async function serveDist(dist, { encoding } = {}) {
  const packed = new Map();
  const pack = (file, data) => {
    const key = `${encoding} ${file}`;
    if (!packed.has(key)) {
      packed.set(key, encoding === 'br'
        ? zlib.brotliCompressSync(data, { params: { [zlib.constants.BROTLI_PARAM_QUALITY]: 11 } })
        : zlib.gzipSync(data, { level: 9 }));
    }
    return packed.get(key);
  };
  const server = http.createServer((req, res) => {
    const url = new URL(req.url, 'http://localhost');
    let file = path.join(dist, decodeURIComponent(url.pathname));
    if (!file.startsWith(dist)) { res.writeHead(403); res.end(); return; }
    if (file.endsWith('/')) file = path.join(file, 'index.html');
    fs.readFile(file, (err, data) => {
      if (err) { res.writeHead(404); res.end(); return; }
      const headers = { 'content-type': types[path.extname(file)] ?? 'application/octet-stream' };
      // An .xz (the page's packed wasm) is sent as it is: compressed already, it would not
      // shrink, and hosts compress text types only.
      if (encoding && !file.endsWith('.xz') && (req.headers['accept-encoding'] ?? '').includes(encoding)) {
        headers['content-encoding'] = encoding;
        headers.vary = 'Accept-Encoding';
        const ahead = `${file}.${encoding === 'br' ? 'br' : 'gz'}`;
        if (fs.existsSync(ahead)) {
          headers['x-precompressed'] = '1';
          data = fs.readFileSync(ahead);
        } else {
          data = pack(file, data);
        }
      }
      res.writeHead(200, headers);
      res.end(data);
    });
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  return { server, base: `http://127.0.0.1:${server.address().port}/` };
}

/** Debian's Chromium, headless (CHROMIUM overrides the path), with `extraArgs`. */
export function launchChromium(extraArgs = []) {
  return chromium.launch({
    executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-background-networking',
      '--disable-component-update', '--disable-sync', '--no-first-run', '--disable-quic', ...extraArgs],
  });
}
