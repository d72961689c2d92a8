// Writes, beside each compressible file of a release build, the file compressed ahead:
// `NAME.br` (brotli, quality 11) and `NAME.gz` (gzip -9). A host that serves files
// compressed ahead sends these instead of compressing each answer itself: nginx
// (`gzip_static`, `brotli_static`), Apache (rewrite rules or MultiViews with
// `AddEncoding`), Caddy (`precompressed`) and the classroom server (tower-http's
// `ServeDir` with `precompressed_br` and `precompressed_gzip`). Brotli at quality 11 is
// about a fifth smaller than gzip for the wasm, but too slow for a server to run on each
// answer; a host compressing on the fly uses quality 5 or less.
//
// Trunk runs this as the last step of its post_build hook (Trunk.toml), after the service
// worker is written (so the worker has its compressed copies too) and in release builds
// only (it takes seconds: a debug build is for `trunk serve`, which compresses nothing).
// The worker's list and the first load's size leave `.br` and `.gz` files out: a browser
// never asks for them by name (web/build/service-worker-build.mjs, web/tests/e2e.test.mjs).
//
// By hand on a built folder: node web/build/precompress.mjs dist
import fs from 'node:fs';
import path from 'node:path';
import zlib from 'node:zlib';
import { promisify } from 'node:util';

/** The extensions worth compressing (images other than SVG are compressed already). */
const COMPRESSIBLE = new Set(['.wasm', '.js', '.mjs', '.html', '.css', '.svg', '.json', '.webmanifest', '.txt']);

const brotli = promisify(zlib.brotliCompress);
const gzip = promisify(zlib.gzip);

/** Every compressible file under `dir` (dot files and folders left out), as full paths. */
function compressible(dir) {
  const files = [];
  for (const entry of fs.readdirSync(dir, { withFileTypes: true })) {
    if (entry.name.startsWith('.')) continue;
    const full = path.join(dir, entry.name);
    if (entry.isDirectory()) files.push(...compressible(full));
    else if (entry.isFile() && COMPRESSIBLE.has(path.extname(entry.name))) files.push(full);
  }
  return files;
}

/** Writes `file.br` and `file.gz`; returns the three sizes. */
async function precompress(file) {
  const data = fs.readFileSync(file);
  const [br, gz] = await Promise.all([
    brotli(data, {
      params: {
        [zlib.constants.BROTLI_PARAM_QUALITY]: 11,
        [zlib.constants.BROTLI_PARAM_SIZE_HINT]: data.length,
        [zlib.constants.BROTLI_PARAM_MODE]: file.endsWith('.wasm') ? zlib.constants.BROTLI_MODE_GENERIC : zlib.constants.BROTLI_MODE_TEXT,
      },
    }),
    gzip(data, { level: 9 }),
  ]);
  fs.writeFileSync(`${file}.br`, br);
  fs.writeFileSync(`${file}.gz`, gz);
  return { raw: data.length, br: br.length, gz: gz.length };
}

const dir = process.argv[2] ?? process.env.TRUNK_STAGING_DIR;
if (!dir || !fs.existsSync(path.join(dir, 'index.html'))) {
  console.error(`precompress: give a folder holding a built index.html (or set TRUNK_STAGING_DIR): ${dir}`);
  process.exit(1);
}
if (!process.argv[2] && (process.env.TRUNK_PROFILE ?? 'release') !== 'release') {
  console.log('precompress: a debug build, nothing written');
  process.exit(0);
}
const sizes = await Promise.all(compressible(dir).map(async (f) => [path.relative(dir, f), await precompress(f)]));
for (const [f, s] of sizes) console.log(`precompress: ${f} ${s.raw} B, .br ${s.br} B, .gz ${s.gz} B`);
