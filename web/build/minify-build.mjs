// Minifies a release build's JavaScript, icon and manifest: trunk runs this as a post_build hook (Trunk.toml),
// before the service worker's hook, in its staging directory ($TRUNK_STAGING_DIR).
//
// Trunk's own minifier (minify = "on_release") handles the HTML but gives up on the
// wasm-bindgen glue ("Failed to minify JS: RequiredTokenNotFound(Identifier)", on its
// `export default`), which then ships as written: about 2.6 kB gzip more of the first load.
// esbuild (npm, pinned in web/package-lock.json) minifies it here instead, keeping it an ES
// module with the same exports. Where trunk has written index.html with a Subresource
// Integrity hash (sha384) for the glue it preloads, that hash is written anew for the
// minified file: a browser refuses a preload whose hash does not match. (index.html asks
// for none, data-integrity="none": the files are the page's own, from its own origin.)
//
// index.html's module script is minified the same way. The icon (web/page/icon.svg) loses its comment and the white space between its tags, the
// manifest its white space: both are fetched on every first visit, and stay readable in
// web/page/.
//
// Only release builds (TRUNK_PROFILE=release): `trunk serve` keeps readable glue.
// Run by hand on a built folder: TRUNK_PROFILE=release TRUNK_STAGING_DIR=dist node web/build/minify-build.mjs
import crypto from 'node:crypto';
import fs from 'node:fs';
import path from 'node:path';
import { transformSync } from 'esbuild';

const dir = process.env.TRUNK_STAGING_DIR;
if (!dir || !fs.existsSync(path.join(dir, 'index.html'))) {
  console.error(`minify-build: TRUNK_STAGING_DIR (${dir}) must be a folder holding a built index.html`);
  process.exit(1);
}
if ((process.env.TRUNK_PROFILE ?? 'release') !== 'release') process.exit(0);

const sri = (data) => `sha384-${crypto.createHash('sha384').update(data).digest('base64')}`;
const indexPath = path.join(dir, 'index.html');
let index = fs.readFileSync(indexPath, 'utf8');
// The page's glue (the first load). The URDF module's glue in urdf/ stays as wasm-bindgen
// wrote it: it loads only when a URDF file is opened or saved.
/** `code` (an ES module) minified for browsers of `target`'s year. */
const minify = (code, target = 'es2020') =>
  transformSync(code, { minify: true, format: 'esm', target, legalComments: 'none' }).code;
const glue = fs.readdirSync(dir).filter((f) => f.endsWith('.js') && f !== 'service-worker.js');
let before = 0;
let after = 0;
for (const file of glue) {
  const full = path.join(dir, file);
  const source = fs.readFileSync(full, 'utf8');
  const code = minify(source);
  fs.writeFileSync(full, code);
  before += source.length;
  after += code.length;
  const old = sri(source);
  if (index.includes(old)) index = index.split(old).join(sri(code));
}
// Trunk's minifier leaves the module script it writes into index.html as written (blank
// lines, long names): esbuild minifies it as it does the glue (its top-level await is ES2022,
// in every browser with WebAssembly SIMD), without what nothing reads: the
// `window.wasmBindings` it sets, and the wasm's exports, kept in a `const` and handed to its
// start event as `detail.wasm` (the event stays, for index.html's service worker). The tags
// HTML lets a page leave out go too (</head><body> before the canvas, </body></html> at the
// end): the parser builds the same document without them.
const loader = (code) => code.replace(/window\.wasmBindings\s*=\s*bindings;?/, '')
  .replace(/const wasm = (await )/, '$1')
  .replace(/new CustomEvent\("TrunkApplicationStarted", \{detail: \{wasm\}\}\)/, 'new Event("TrunkApplicationStarted")');
index = index.replace(/(<script type=module>)([\s\S]*?)(<\/script>)/, (_, open, code, close) =>
  open + minify(loader(code), 'es2022').trim() + close);
fs.writeFileSync(indexPath, index.replace('</head><body>', '').replace(/<\/body><\/html>\s*$/, ''));
console.log(`minify-build: ${glue.length} JS files, ${before} → ${after} bytes`);

// Copies (not the sources): trunk copied web/page/'s files into the staging folder.
const icon = path.join(dir, 'icon.svg');
fs.writeFileSync(icon, fs.readFileSync(icon, 'utf8').replace(/<!--[\s\S]*?-->/g, '').replace(/>\s+</g, '><').trim());
const manifest = path.join(dir, 'manifest.webmanifest');
fs.writeFileSync(manifest, JSON.stringify(JSON.parse(fs.readFileSync(manifest, 'utf8'))));
