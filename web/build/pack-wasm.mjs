// Packs a release build's wasm with xz and has the page unpack it: trunk runs this first in
// its post_build hook (Trunk.toml), in its staging directory ($TRUNK_STAGING_DIR), before
// the loader is minified and the service worker lists the files.
//
// The wasm is 99 % of the first load. A host compresses it as it sends it: GitHub Pages with
// gzip, which makes 4.1 MB about 1.74 MB; xz (LZMA2 at its strongest setting) makes it about
// 1.31 MB, a quarter less, and brotli at quality 11, which few hosts send, 1.35 MB. A browser
// unpacks no xz by itself, so the page does (web/page/unxz.mjs, bundled here with its
// decoder), while the download runs, and the app's init compiles the bytes as they come out:
// on a 9 Mbit/s link about 0.4 s less before the first frame, on every host. The .xz is
// served as a plain file (no host compresses it again: it would not shrink).
//
// Writes NAME_bg.wasm.xz beside the wasm (kept: the loader falls back to it where the packed
// copy cannot be fetched or unpacked) and unxz-HASH.js, and rewrites index.html: the preload
// asks for the .xz, the decoder is preloaded beside the glue, and the loader starts the app
// with the decoder's `startPacked` (from the packed copy, or, where that fails, the wasm).
//
// The lazily loaded module in urdf/ (tools/setup.sh, build_urdf_module) is packed the same
// way, and its glue exports `startPacked` and its wasm's address (`wasmUrl`), with which
// the page's import starts it (src/app/platform/web/modules.rs).
//
// Only release builds (TRUNK_PROFILE=release): `trunk serve` loads the wasm as trunk wrote it.
// Run by hand on a built folder: TRUNK_PROFILE=release TRUNK_STAGING_DIR=dist node web/build/pack-wasm.mjs
import crypto from 'node:crypto';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { buildSync } from 'esbuild';

const dir = process.env.TRUNK_STAGING_DIR;
if (!dir || !fs.existsSync(path.join(dir, 'index.html'))) {
  console.error(`pack-wasm: TRUNK_STAGING_DIR (${dir}) must be a folder holding a built index.html`);
  process.exit(1);
}
if ((process.env.TRUNK_PROFILE ?? 'release') !== 'release') process.exit(0);

/** The one file of `folder` (under the staging directory) whose name ends with `end`. */
function single(folder, end) {
  const found = fs.readdirSync(path.join(dir, folder)).filter((f) => f.endsWith(end));
  if (found.length !== 1) {
    console.error(`pack-wasm: expected one *${end} in ${path.join(dir, folder)}, found ${found.join(', ') || 'none'}`);
    process.exit(1);
  }
  return found[0];
}

/** Writes `wasmPath`.xz; logs and returns nothing. LZMA2's dictionary is as large as the
 * wasm (a power of two): a larger one finds nothing more, and the decoder allocates all of it. */
function pack(wasmPath) {
  const size = fs.statSync(wasmPath).size;
  const dict = 2 ** Math.max(12, Math.ceil(Math.log2(size)));
  const packed = execFileSync('xz', ['--format=xz', `--lzma2=preset=9e,dict=${dict}`, '--threads=1', '--stdout', wasmPath],
    { maxBuffer: 2 * size });
  fs.writeFileSync(`${wasmPath}.xz`, packed);
  console.log(`pack-wasm: ${path.relative(dir, wasmPath)} ${size} → ${packed.length} bytes (xz)`);
}

const indexPath = path.join(dir, 'index.html');
let index = fs.readFileSync(indexPath, 'utf8');
const wasm = single('.', '_bg.wasm');
pack(path.join(dir, wasm));

// The decoder, bundled as an ES module under a name that changes with its contents.
const source = path.join(path.dirname(fileURLToPath(import.meta.url)), '..', 'page', 'unxz.mjs');
const { outputFiles: [bundle] } = buildSync({ entryPoints: [source], bundle: true, format: 'esm', write: false,
  target: 'es2020', legalComments: 'none' });
const unxz = `unxz-${crypto.createHash('sha256').update(bundle.contents).digest('hex').slice(0, 16)}.js`;
fs.writeFileSync(path.join(dir, unxz), bundle.contents);

/** `text` with `pattern` replaced, or the build stops: trunk's output must be as expected. */
const rewrite = (text, pattern, replacement, what) => {
  if (!pattern.test(text)) {
    console.error(`pack-wasm: index.html has no ${what} (${pattern})`);
    process.exit(1);
  }
  return text.replace(pattern, replacement);
};
const file = wasm.replace(/[.]/g, '[.]');
index = rewrite(index, new RegExp(`(<link[^>]*href=["']?[^"' >]*${file})(["']?)([^>]*?)\\s*type=["']?application/wasm["']?`),
  '$1.xz$2$3', 'preload of the wasm');
index = rewrite(index, /(<link[^>]*rel=["']?modulepreload["']?[^>]*>)/, `$1<link rel=modulepreload href=./${unxz} crossorigin>`,
  'modulepreload of the glue');
index = rewrite(index, /(<script type=["']?module["']?>)([\s\S]*?)await init\(\{\s*module_or_path:\s*(['"][^'"]+['"])\s*\}\)/,
  (_, open, head, url) => `${open}import { startPacked } from './${unxz}';${head}await startPacked(init, ${url})`,
  'loader calling init with the wasm');
fs.writeFileSync(indexPath, index);
console.log(`pack-wasm: decoder ${unxz} ${bundle.contents.length} bytes`);

// The lazy module: its glue (wasm-bindgen's, for `--target web`) gains two exports.
const lazyWasm = single('urdf', '_bg.wasm');
pack(path.join(dir, 'urdf', lazyWasm));
const gluePath = path.join(dir, 'urdf', single('urdf', '.js'));
fs.appendFileSync(gluePath, `\nexport { startPacked } from '../${unxz}';\n`
  + `export const wasmUrl = new URL('${lazyWasm}', import.meta.url).href;\n`);
