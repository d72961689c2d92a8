// Writes the page's service worker into a build: trunk runs this as a post_build hook
// (Trunk.toml), after it has written the finished index.html into its staging directory
// (dist/.stage, in $TRUNK_STAGING_DIR) and before it moves that directory's files into
// dist/. So the files listed here are exactly the build's files, with trunk's hashed names
// (armlab-<hash>.js, armlab-<hash>_bg.wasm), and the worker is part of the same build.
//
// The worker (dist/service-worker.js) is web/page/service-worker.js, minified by esbuild
// (every browser's first visit fetches it: its comments were half its bytes), preceded by
// one line,
//   const ARMLAB_BUILD = {"version":"…","files":["icon.svg","index.html",…]};
// `files`: every file of the build except the worker itself, dot files, the copies
// compressed ahead (`.br`, `.gz`: web/build/precompress.mjs; a browser never asks for them
// by name, the server sends them in place of the file) and the wasm the page unpacks from
// its `.xz` (web/build/pack-wasm.mjs), relative to the
// folder, sorted; `version`: the first 16 hex digits of the SHA-256 of, for each file in
// that order, its path, a newline, the SHA-256 (hex) of its contents and a newline. Every
// build whose files differ has another version, so its worker installs and replaces the
// cache (web/tests/offline.test.mjs recomputes it from dist/).
//
// `files` includes urdf/, the URDF module (tools/setup.sh, build_urdf_module), which the
// page itself fetches only when a URDF file is opened or saved, collisions are checked or
// the symbolic matrices are shown. The worker precaches it anyway, on purpose: it installs
// after the page's load event, so the first load and the first frame do not wait for it,
// and then opening a URDF file or ticking "symbolic" works offline too, like the
// rest of the page (the lecture hall whose Wi-Fi fails). The cost is the module's ~250 kB
// (its wasm packed with xz: web/build/pack-wasm.mjs) once per build per browser, in the
// background.
//
// Run by hand on a built folder: TRUNK_STAGING_DIR=dist node web/build/service-worker-build.mjs
import crypto from 'node:crypto';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { transformSync } from 'esbuild';

const WORKER = 'service-worker.js';
const PRECOMPRESSED = /\.(br|gz)$/;
const template = path.join(path.dirname(fileURLToPath(import.meta.url)), '..', 'page', 'service-worker.js');

/** The build's files under `dir`, as sorted relative paths with forward slashes. */
function buildFiles(dir, prefix = '') {
  const files = [];
  for (const entry of fs.readdirSync(path.join(dir, prefix), { withFileTypes: true })) {
    if (entry.name.startsWith('.')) continue;
    const rel = prefix ? `${prefix}/${entry.name}` : entry.name;
    if (entry.isDirectory()) files.push(...buildFiles(dir, rel));
    else if (entry.isFile() && rel !== WORKER && !PRECOMPRESSED.test(rel)) files.push(rel);
  }
  // A file packed beside itself (NAME.xz: web/build/pack-wasm.mjs) is fetched only where the
  // packed copy cannot be, online: the worker caches the copy, which the page asks for.
  return files.filter((f) => !files.includes(`${f}.xz`)).sort();
}

const sha256 = (data) => crypto.createHash('sha256').update(data).digest('hex');

const dir = process.env.TRUNK_STAGING_DIR;
if (!dir || !fs.existsSync(path.join(dir, 'index.html'))) {
  console.error(`service-worker-build: TRUNK_STAGING_DIR (${dir}) must be a folder holding a built index.html`);
  process.exit(1);
}
const files = buildFiles(dir);
const version = sha256(files.map((f) => `${f}\n${sha256(fs.readFileSync(path.join(dir, f)))}\n`).join('')).slice(0, 16);
const header = `const ARMLAB_BUILD = ${JSON.stringify({ version, files })};\n`;
// As a function's body (format iife): its names are its own, so the minifier shortens them
// (a classic script's top-level names are globals, kept whole).
const { code } = transformSync(fs.readFileSync(template, 'utf8'),
  { minify: true, target: 'es2020', legalComments: 'none', format: 'iife' });
fs.writeFileSync(path.join(dir, WORKER), header + code);
console.log(`service-worker-build: ${WORKER} caches ${files.length} files as version ${version}`);
