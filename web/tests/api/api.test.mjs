// Node test of ArmLab's JS API: the core compiled to wasm, loaded as a Node module
// (wasm-bindgen --target nodejs), called with JSON the way another program would.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { createRequire } from 'node:module';

const require = createRequire(import.meta.url);
const armlab = require(process.env.ARMLAB_NODE_PKG ?? '../../../target/armlab-node/armlab.js');

test('presets lists every robot', () => {
  const list = JSON.parse(armlab.presets());
  assert.equal(list.length, 9);
  assert.ok(list.some((r) => r.id === 'ur10' && r.dof === 6 && r.convention === 'modified'));
});

test('fk gives the UR10 reference pose at q = 0', () => {
  const out = JSON.parse(armlab.fk(JSON.stringify({ robot: 'ur10', q: [0, 0, 0, 0, 0, 0] })));
  const [x, y, z] = out.position;
  assert.ok(Math.abs(x - 1184.5) < 1e-9 && Math.abs(y + 256.1) < 1e-9 && Math.abs(z - 243.7) < 1e-9, out.position);
  assert.deepEqual(out.tool[1].map(Math.round), [0, 0, -1, -256]);
  assert.equal(out.links.length, 6);
  assert.equal(out.frames.length, 6);
});

test('fk takes a robot file object too', () => {
  const robot = {
    name: 'two links', convention: 'standard', length_unit: 'm',
    joints: [
      { type: 'revolute', theta_deg: 0, d: 0, a: 2, alpha_deg: 0 },
      { type: 'revolute', theta_deg: 0, d: 0, a: 1, alpha_deg: 0 },
    ],
  };
  const out = JSON.parse(armlab.fk(JSON.stringify({ robot, q: [Math.PI / 2, 0] })));
  assert.ok(Math.abs(out.position[0]) < 1e-12 && Math.abs(out.position[1] - 3) < 1e-12);
});

test('jacobian: geometric equals numerical and the measures flag singularity', () => {
  const out = JSON.parse(armlab.jacobian(JSON.stringify({ robot: 'planar-2r', q: [0.3, 0], task: 'position' })));
  assert.equal(out.geometric.length, 6);
  for (let r = 0; r < 6; r++) {
    for (let c = 0; c < 2; c++) {
      assert.ok(Math.abs(out.geometric[r][c] - out.numerical[r][c]) < 1e-6);
    }
  }
  assert.equal(out.near_singular, true);
});

test('bad requests throw an Error with the core sentence', () => {
  assert.throws(() => armlab.fk(JSON.stringify({ robot: 'ur10', q: [0, 0] })),
    { message: 'The robot has 6 joints but 2 joint values were given.' });
  assert.throws(() => armlab.fk(JSON.stringify({ robot: 'r2d2' })), /There is no robot called "r2d2"/);
  assert.throws(() => armlab.fk('{'), /Bad request/);
});

test('ik reaches a position target with the tool and reports the run', () => {
  const out = JSON.parse(armlab.ik(JSON.stringify({
    robot: 'ur10', q: [0, -1, 1, -1, -1, 0],
    target: { position: [800, -200, 400] }, task: 'position', method: 'dls',
  })));
  assert.equal(out.success, true);
  assert.ok(out.position_error < 1e-3, `${out.position_error} mm`);
  const [x, y, z] = [out.tool[0][3], out.tool[1][3], out.tool[2][3]];
  assert.ok(Math.hypot(x - 800, y + 200, z - 400) < 1e-3);
  assert.equal(out.q.length, 6);
});
