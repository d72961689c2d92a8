// The set-up shared by the browser test files: the built page served on loopback and one
// headless Chromium for all of a file's tests, started before them and closed after.
import { before, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { serveDist, launchChromium } from './static-server.mjs';

/** Chromium's flags for a file that times nothing: V8 runs the page's wasm as its baseline
 * code only. By default V8 also compiles the hot functions again with its optimising
 * compiler, about 1 s of CPU per page load here, which only the timings need; the page
 * does the same either way. */
export const UNTIMED = ['--js-flags=--liftoff-only'];

/**
 * Registers the file's `before` and `after` hooks and returns `{ base, browser }`, filled
 * in once the hook has run. With `label`, `after` prints `label` and `measurements` as
 * one JSON line (tools/test.sh shows those lines). With `untimed`, for a file whose
 * tests and measurements read no time, the browser runs with [`UNTIMED`]'s flags.
 */
export function browserSuite(dist, { label, measurements, untimed = false } = {}) {
  const suite = { base: '', browser: null, server: null };
  before(async () => {
    assert.ok(fs.existsSync(path.join(dist, 'index.html')), 'dist/ holds the built page (trunk build --release)');
    const { server, base } = await serveDist(dist);
    Object.assign(suite, { server, base, browser: await launchChromium(untimed ? UNTIMED : []) });
  });
  after(async () => {
    if (label) console.log(`${label} ${JSON.stringify(measurements)}`);
    await suite.browser?.close();
    suite.server?.close();
  });
  return suite;
}
