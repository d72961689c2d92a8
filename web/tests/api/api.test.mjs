// Node test of ArmLab's JS API: the core compiled to wasm, loaded as a Node module
// (wasm-bindgen --target nodejs), called the way another program would: with plain
// objects (answered with objects) and with JSON text (answered with JSON text).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';

const require = createRequire(import.meta.url);
const pkg = process.env.ARMLAB_NODE_PKG ?? '../../../target/armlab-node/armlab.js';
const armlab = require(pkg);

/** The largest difference between two equally shaped nested lists of numbers. */
function maxDifference(a, b) {
  if (Array.isArray(a)) {
    assert.equal(a.length, b.length);
    return Math.max(...a.map((x, i) => maxDifference(x, b[i])));
  }
  return Math.abs(a - b);
}

test('presets lists every robot, as objects', () => {
  const list = armlab.presets();
  assert.ok(Array.isArray(list));
  assert.equal(list.length, 9);
  assert.ok(list.some((r) => r.id === 'ur10' && r.dof === 6 && r.convention === 'modified'));
});

test('fk gives the UR10 reference pose at q = 0, for an object and for JSON text', () => {
  const request = { robot: 'ur10', q: [0, 0, 0, 0, 0, 0] };
  const out = armlab.fk(request);
  const [x, y, z] = out.position;
  assert.ok(Math.abs(x - 1184.5) < 1e-9 && Math.abs(y + 256.1) < 1e-9 && Math.abs(z - 243.7) < 1e-9, out.position);
  assert.deepEqual(out.tool[1].map(Math.round), [0, 0, -1, -256]);
  assert.equal(out.links.length, 6);
  assert.equal(out.frames.length, 6);
  // JSON text in, JSON text out: the same answer.
  const text = armlab.fk(JSON.stringify(request));
  assert.equal(typeof text, 'string');
  assert.deepEqual(JSON.parse(text), out);
});

test('fk takes a robot file object too', () => {
  const robot = {
    name: 'two links', convention: 'standard', length_unit: 'm',
    joints: [
      { type: 'revolute', theta_deg: 0, d: 0, a: 2, alpha_deg: 0 },
      { type: 'revolute', theta_deg: 0, d: 0, a: 1, alpha_deg: 0 },
    ],
  };
  const out = armlab.fk({ robot, q: [Math.PI / 2, 0] });
  assert.ok(Math.abs(out.position[0]) < 1e-12 && Math.abs(out.position[1] - 3) < 1e-12, out.position);
  // robot() normalises it: the file comes back as an object with its joints.
  const file = armlab.robot({ robot });
  assert.equal(file.joints.length, 2);
  assert.equal(file.joints[0].a, 2);
});

test('jacobian: geometric equals numerical and the measures flag singularity', () => {
  const out = armlab.jacobian({ robot: 'planar-2r', q: [0.3, 0], task: 'position' });
  assert.equal(out.geometric.length, 6);
  for (let r = 0; r < 6; r++) {
    for (let c = 0; c < 2; c++) {
      assert.ok(Math.abs(out.geometric[r][c] - out.numerical[r][c]) < 1e-6);
    }
  }
  assert.equal(out.near_singular, true);
  const text = JSON.parse(armlab.jacobian(JSON.stringify({ robot: 'planar-2r', q: [0.3, 0], task: 'position' })));
  assert.equal(text.near_singular, true);
});

test('bad requests throw an Error with the core sentence, as objects and as text', () => {
  assert.throws(() => armlab.fk({ robot: 'ur10', q: [0, 0] }),
    { name: 'Error', message: 'The robot has 6 joints but 2 joint values were given.' });
  assert.throws(() => armlab.fk(JSON.stringify({ robot: 'ur10', q: [0, 0] })),
    { name: 'Error', message: 'The robot has 6 joints but 2 joint values were given.' });
  assert.throws(() => armlab.fk({ robot: 'r2d2' }), /There is no robot called "r2d2"/);
  assert.throws(() => armlab.fk('{'), /Bad request/);
  assert.throws(() => armlab.ik({ robot: 'ur10', target: { position: [1, 2] } }),
    { message: 'Bad request: "target.position" must be 3 numbers' });
  // An object JSON cannot hold is a bad request too, not a crash.
  assert.throws(() => armlab.fk({ robot: 'ur10', q: [0n, 0, 0, 0, 0, 0] }), /^Error: Bad request: not JSON \(.*BigInt/);
});

test('an argument of the wrong kind throws an Error with a sentence, never a wasm trap', () => {
  const cases = [
    [() => armlab.fk(5), 'fk takes a request object, such as {robot: "ur10", q: [0, 0, 0, 0, 0, 0]}, or its JSON text; it was given the number 5.'],
    [() => armlab.fk(true), 'fk takes a request object, such as {robot: "ur10", q: [0, 0, 0, 0, 0, 0]}, or its JSON text; it was given the value true.'],
    [() => armlab.fk(), 'fk takes a request object, such as {robot: "ur10", q: [0, 0, 0, 0, 0, 0]}, or its JSON text; it was given nothing (undefined).'],
    [() => armlab.jacobian(null), 'jacobian takes a request object, such as {robot: "ur10", q: [0, 0, 0, 0, 0, 0], task: "full"}, or its JSON text; it was given an empty value (null).'],
    [() => armlab.ik(['ur10']), 'ik takes a request object, such as {robot: "ur10", target: {position: [800, -200, 400]}}, or its JSON text; it was given a list (an array).'],
    [() => armlab.robot(() => 'ur10'), 'robot takes a request object, such as {robot: "ur10"}, or its JSON text; it was given a value of the type function.'],
    [() => armlab.collide_parts('1, 2'), 'collide_parts takes a list of numbers (a Float64Array or an array); it was given a text.'],
  ];
  for (const [call, message] of cases) {
    assert.throws(call, (e) => {
      assert.ok(e instanceof Error, `${e} is an Error`);
      assert.ok(!(e instanceof WebAssembly.RuntimeError), `${e} is no wasm trap`);
      assert.equal(e.message, message);
      return true;
    });
  }
  // The module is still usable after each of them.
  assert.equal(armlab.fk({ robot: 'ur10' }).links.length, 6);
});

test('ik reaches a position target: FK of its answer is the target', () => {
  const target = [800, -200, 400];
  const out = armlab.ik({
    robot: 'ur10', q: [0, -1, 1, -1, -1, 0],
    target: { position: target }, task: 'position', method: 'dls',
  });
  assert.equal(out.success, true);
  assert.equal(out.q.length, 6);
  // Checked by the API's own FK of the answer's q, not by the answer's `tool` field.
  const [x, y, z] = armlab.fk({ robot: 'ur10', q: out.q }).position;
  assert.ok(Math.hypot(x - target[0], y - target[1], z - target[2]) < 1e-3, `${[x, y, z]}`);
});

test('ik reaches a full pose given as JSON text: FK of its answer is the target pose', () => {
  const goal = armlab.fk({ robot: 'ur10', q: [0.3, -1.0, 1.2, 0.4, 0.8, -0.7] }).tool;
  for (const method of ['dls', 'closed']) {
    const text = armlab.ik(JSON.stringify({
      robot: 'ur10', q: [0.2, -0.9, 1.0, 0.5, 0.7, -0.6], target: goal, method,
    }));
    assert.equal(typeof text, 'string');
    const out = JSON.parse(text);
    assert.equal(out.success, true, method);
    const reached = armlab.fk({ robot: 'ur10', q: out.q }).tool;
    // The rotation within 1e-6, the position within 1e-3 mm (the solvers' tolerances).
    const rotation = (rows) => rows.slice(0, 3).map((row) => row.slice(0, 3));
    const position = (rows) => rows.slice(0, 3).map((row) => row[3]);
    assert.ok(maxDifference(rotation(reached), rotation(goal)) < 1e-6, `${method}: ${reached}`);
    assert.ok(maxDifference(position(reached), position(goal)) < 1e-3, `${method}: ${reached}`);
  }
});

test('the package declares its requests and answers in TypeScript', () => {
  const dts = readFileSync(pkg.replace(/\.js$/, '.d.ts'), 'utf8');
  for (const declaration of [
    'export function fk(request: FkRequest): FkResponse;',
    'export function fk(request: string): string;',
    'export function jacobian(request: JacobianRequest): JacobianResponse;',
    'export function ik(request: IkRequest): IkResponse;',
    'export function robot(request: RobotRequest): RobotFile;',
    'export function presets(): PresetSummary[];',
    'export interface IkResponse {',
  ]) {
    assert.ok(dts.includes(declaration), declaration);
  }
  // No export is left to wasm-bindgen's own declaration, which says `any`.
  assert.equal(/\bany\b/.test(dts), false, dts.match(/.*\bany\b.*/g)?.join('\n'));
});
