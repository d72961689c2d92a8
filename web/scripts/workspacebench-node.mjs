// The workspace benchmark in Node: the core compiled to wasm (wasm-bindgen --target
// nodejs), timed with performance.now(). Prints the same JSON as the native
// `cargo run --release -p armlab-bench --bin workspacebench [samples] [repeats]`.
// Build as for web/scripts/ikbench-node.mjs, then run from the repository root:
//   node web/scripts/workspacebench-node.mjs [samples] [repeats]
// ARMLAB_NODE_PKG points at another build's armlab.js (e.g. one built like the page,
// at opt-level "z" with panic = "abort" and wasm-opt -Oz).
import { createRequire } from 'node:module';
import { fileURLToPath } from 'node:url';
import path from 'node:path';

const require = createRequire(import.meta.url);
const here = path.dirname(fileURLToPath(import.meta.url));
const pkg = process.env.ARMLAB_NODE_PKG ?? path.join(here, '..', '..', 'target', 'armlab-node', 'armlab.js');
const armlab = require(pkg);

const [samples, repeats] = process.argv.slice(2).map(Number);
const report = armlab.workspace_benchmark(
  Number.isInteger(samples) && samples > 0 ? samples : 100000,
  Number.isInteger(repeats) && repeats > 0 ? repeats : 5,
);
report.runtime = `node ${process.version}, wasm32 (wasm-bindgen --target nodejs), clock performance.now()`;
console.log(JSON.stringify(report, null, 2));
