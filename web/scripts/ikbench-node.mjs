// The IK benchmark (TRAC-IK protocol) in Node: the core compiled to wasm
// (wasm-bindgen --target nodejs), timed with performance.now(). Prints the same JSON as
// the native `cargo run --release -p armlab-bench --bin ikbench`.
//
// Build, then run from the repository root:
//   cargo rustc -p armlab-js --lib --crate-type cdylib --release --target wasm32-unknown-unknown
//   wasm-bindgen --target nodejs --out-dir target/armlab-node --out-name armlab target/wasm32-unknown-unknown/release/armlab_js.wasm
//   node web/scripts/ikbench-node.mjs [samples] [budget]
// ARMLAB_NODE_PKG points at another build's armlab.js.
import { createRequire } from 'node:module';
import { fileURLToPath } from 'node:url';
import path from 'node:path';

const require = createRequire(import.meta.url);
const here = path.dirname(fileURLToPath(import.meta.url));
const pkg = process.env.ARMLAB_NODE_PKG ?? path.join(here, '..', '..', 'target', 'armlab-node', 'armlab.js');
const armlab = require(pkg);

const request = {};
const [samples, budget] = process.argv.slice(2).map(Number);
if (Number.isInteger(samples) && samples > 0) request.samples = samples;
if (Number.isInteger(budget) && budget > 0) request.budget = budget;

const report = JSON.parse(armlab.ik_benchmark(JSON.stringify(request)));
report.runtime = `node ${process.version}, wasm32 (wasm-bindgen --target nodejs), clock performance.now()`;
console.log(JSON.stringify(report, null, 2));
