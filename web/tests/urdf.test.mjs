// URDF in the built page (dist/, from `trunk build --release`), in Debian's headless Chromium
// driven by playwright-core. URDF support is a module of its own (dist/urdf/, built by
// tools/setup.sh's build_urdf_module): the page must not fetch it on its first load, must
// fetch it once when a URDF file is opened, load the robot the file describes through the
// robot file's way in, answer a broken file with the core's sentence naming the element
// while the robot stays, and save the robot as URDF.
//
// The contexts block service workers: the worker precaches every file of the build after
// the page has loaded (urdf/ too, for offline use; web/tests/offline.test.mjs checks its list),
// and those fetches are the worker's, not the page's first load.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { browserSuite } from './browser-suite.mjs';
import { dist, state, point, until as waitFor, moduleRequests as urdfRequests, pageOpener } from './page.mjs';

// The Franka Emika Panda as franka_description's panda_arm.urdf.xacro publishes its joint
// origins and limits (metres, radians; the same data as tests/urdf.rs), the flange a fixed
// joint 0.107 m along joint 7's axis; two links carry mesh visuals, as the real file's do.
const PANDA_URDF = `<?xml version="1.0"?>
<robot name="panda">
  <link name="panda_link0">
    <visual><geometry><mesh filename="package://franka_description/meshes/visual/link0.dae"/></geometry></visual>
  </link>
  <link name="panda_link1">
    <visual><geometry><mesh filename="package://franka_description/meshes/visual/link1.dae"/></geometry></visual>
  </link>
  <link name="panda_link2"/>
  <link name="panda_link3"/>
  <link name="panda_link4"/>
  <link name="panda_link5"/>
  <link name="panda_link6"/>
  <link name="panda_link7"/>
  <link name="panda_link8"/>
  <joint name="panda_joint1" type="revolute">
    <origin xyz="0 0 0.333" rpy="0 0 0"/>
    <parent link="panda_link0"/><child link="panda_link1"/>
    <axis xyz="0 0 1"/><limit lower="-2.8973" upper="2.8973" effort="87" velocity="2.1750"/>
  </joint>
  <joint name="panda_joint2" type="revolute">
    <origin xyz="0 0 0" rpy="-1.5707963267948966 0 0"/>
    <parent link="panda_link1"/><child link="panda_link2"/>
    <axis xyz="0 0 1"/><limit lower="-1.7628" upper="1.7628" effort="87" velocity="2.1750"/>
  </joint>
  <joint name="panda_joint3" type="revolute">
    <origin xyz="0 -0.316 0" rpy="1.5707963267948966 0 0"/>
    <parent link="panda_link2"/><child link="panda_link3"/>
    <axis xyz="0 0 1"/><limit lower="-2.8973" upper="2.8973" effort="87" velocity="2.1750"/>
  </joint>
  <joint name="panda_joint4" type="revolute">
    <origin xyz="0.0825 0 0" rpy="1.5707963267948966 0 0"/>
    <parent link="panda_link3"/><child link="panda_link4"/>
    <axis xyz="0 0 1"/><limit lower="-3.0718" upper="-0.0698" effort="87" velocity="2.1750"/>
  </joint>
  <joint name="panda_joint5" type="revolute">
    <origin xyz="-0.0825 0.384 0" rpy="-1.5707963267948966 0 0"/>
    <parent link="panda_link4"/><child link="panda_link5"/>
    <axis xyz="0 0 1"/><limit lower="-2.8973" upper="2.8973" effort="12" velocity="2.6100"/>
  </joint>
  <joint name="panda_joint6" type="revolute">
    <origin xyz="0 0 0" rpy="1.5707963267948966 0 0"/>
    <parent link="panda_link5"/><child link="panda_link6"/>
    <axis xyz="0 0 1"/><limit lower="-0.0175" upper="3.7525" effort="12" velocity="2.6100"/>
  </joint>
  <joint name="panda_joint7" type="revolute">
    <origin xyz="0.088 0 0" rpy="1.5707963267948966 0 0"/>
    <parent link="panda_link6"/><child link="panda_link7"/>
    <axis xyz="0 0 1"/><limit lower="-2.8973" upper="2.8973" effort="12" velocity="2.6100"/>
  </joint>
  <joint name="panda_joint8" type="fixed">
    <origin xyz="0 0 0.107" rpy="0 0 0"/>
    <parent link="panda_link7"/><child link="panda_link8"/>
  </joint>
</robot>
`;

// Well-formed URDF whose second joint names a link the file does not define.
const BROKEN_URDF = `<?xml version="1.0"?>
<robot name="broken">
  <link name="base"/>
  <link name="arm"/>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="arm"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <joint name="elbow" type="revolute">
    <parent link="arm"/><child link="forearm"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
</robot>
`;

// SPEC §1.5: the Panda's ready pose and its flange position there (metres).
const READY = [0, -Math.PI / 4, 0, -3 * Math.PI / 4, 0, Math.PI / 2, Math.PI / 4];
const READY_FLANGE = [0.3069, 0, 0.5903];

const suite = browserSuite(dist, { untimed: true });

/** A fresh page on `hash` (own storage, no service worker), every request's URL and the
 * console errors recorded. */
const { open } = pageOpener(suite, {
  contextOptions: { serviceWorkers: 'block' },
  waitUntil: 'load',
  // Playwright intercepts file choosers once the page has a listener, and turning that on
  // takes a round trip: a listener added just before the click can miss the chooser.
  setup: (ctx, page) => page.on('filechooser', () => {}),
});

/** Opens a file through the robot panel's "Load robot file…" button and the browser's
 * file chooser (the page's `<input type="file">`). Clicks again when no chooser came within
 * 5 s: in a fresh browser the first one is missed now and then. */
async function chooseFile(page, name, text) {
  const load = await point(page, 'robot-load');
  let chooser;
  for (let attempt = 1; !chooser; attempt++) {
    const [opened] = await Promise.all([
      page.waitForEvent('filechooser', { timeout: 5000 }).catch(() => null),
      page.mouse.click(load.x, load.y),
    ]);
    chooser = opened;
    if (attempt === 3 && !chooser) throw new Error('three clicks on "Load robot file…" opened no file chooser');
  }
  assert.equal(await chooser.element().getAttribute('accept'), '.json,.urdf,application/json');
  await chooser.setFiles({ name, mimeType: 'application/xml', buffer: Buffer.from(text) });
}

/** Waits until `check(state)` holds (the URDF module loads and converts asynchronously). */
const until = (page, check, what) => waitFor(page, check, what, { pause: 50, detail: (s) => s.message });

test('the URDF module is built beside the page and outside its first load', async () => {
  // Beside the glue and the wasm their copies compressed ahead (`.br`, `.gz`), which a server
  // sends instead; beside the wasm its copy packed with xz, which the page fetches.
  const all = fs.readdirSync(path.join(dist, 'urdf'));
  const files = all.filter((f) => !/\.(br|gz)$/.test(f));
  assert.equal(files.length, 3, `dist/urdf/ holds the glue, the wasm and its packed copy: ${files}`);
  assert.ok(files.includes('armlab_urdf.js'), `the glue: ${files}`);
  const wasm = files.find((f) => /^armlab_urdf-[0-9a-f]{16}_bg\.wasm$/.test(f));
  assert.ok(wasm, `the wasm, named by its hash: ${files}`);
  assert.ok(files.includes(`${wasm}.xz`), `its packed copy: ${files}`);
  for (const f of ['armlab_urdf.js', wasm]) for (const ext of ['br', 'gz']) assert.ok(all.includes(`${f}.${ext}`), `${f}.${ext} beside it`);
  const glue = fs.readFileSync(path.join(dist, 'urdf', 'armlab_urdf.js'), 'utf8');
  assert.ok(glue.includes(wasm), 'the glue names its own wasm');
  assert.match(glue, /export \{ startPacked \} from '\.\.\/unxz-[0-9a-f]{16}\.js';/, 'it hands on the page\'s decoder');
  assert.ok(glue.includes(`export const wasmUrl = new URL('${wasm}', import.meta.url).href;`), 'and its wasm\'s address');
  assert.ok(/export function urdf_import\b/.test(glue) && /export function robot_to_urdf\b/.test(glue), 'it exports the page\'s two calls');
  assert.ok(!fs.readFileSync(path.join(dist, 'index.html'), 'utf8').includes('urdf/'), 'index.html does not name it');
});

test('a URDF file opened in the page loads its robot (Panda flange at SPEC §1.5); a broken one gets the sentence and the robot stays', async () => {
  const { page, ctx, requests, errors } = await open('#robot=ur10&panels=robot');
  assert.equal((await state(page)).robot, 'UR10');
  assert.ok(requests.some((p) => p.endsWith('_bg.wasm.xz')), 'the first load fetched the page\'s packed wasm');
  assert.deepEqual(urdfRequests(requests), [], 'the first load does not fetch the URDF module');

  await chooseFile(page, 'panda.urdf', PANDA_URDF);
  let s = await until(page, (st) => st.robot === 'panda', 'the Panda from its URDF');
  assert.equal(s.preset, null);
  assert.equal(s.dof, 7);
  assert.equal(s.length_unit, 'm');
  assert.equal(s.message, 'Loaded panda. Its meshes (2) are not drawn: ArmLab draws its own boxes and cylinders along the DH table.');
  const fetched = urdfRequests(requests);
  assert.equal(fetched.length, 2, `the glue and the packed wasm, once: ${fetched}`);
  assert.ok(fetched.some((p) => p.endsWith('/urdf/armlab_urdf.js')) && fetched.some((p) => p.endsWith('_bg.wasm.xz')));

  // The ready pose through a link of the loaded robot: its flange where SPEC §1.5 has it.
  const hash = s.hash.split('&').map((kv) => (kv.startsWith('q=') ? `q=${READY.join(',')}` : kv)).join('&');
  assert.notEqual(hash, s.hash, 'the link has a q to replace');
  await page.evaluate((h) => window.armlab.open(h), hash);
  s = await until(page, (st) => st.q.every((v, i) => Math.abs(v - READY[i]) < 1e-12), 'the ready pose');
  assert.equal(s.robot, 'panda');
  s.tool.forEach((v, i) => assert.ok(Math.abs(v - READY_FLANGE[i]) <= 1e-4, `flange ${s.tool} vs ${READY_FLANGE}`));
  const good = s;

  // A broken file: the robot file's message with the core's sentence; nothing else moves.
  await chooseFile(page, 'broken.urdf', BROKEN_URDF);
  s = await until(page, (st) => st.message?.includes('forearm'), 'the broken file\'s sentence');
  assert.equal(s.message, 'That robot file was not loaded: The URDF joint "elbow" names the link "forearm", which the file does not define.');
  assert.equal(s.robot, 'panda');
  assert.deepEqual(s.q, good.q);
  assert.deepEqual(s.tool, good.tool);
  assert.equal(s.hash, good.hash);
  assert.equal(urdfRequests(requests).length, 2, 'the module is not fetched again');
  assert.deepEqual(errors, []);
  await ctx.close();
});

test('"Save as URDF" downloads the robot as URDF that opens again to the same arm', async () => {
  const { page, ctx, requests, errors } = await open('#robot=rrr&q=0.3,0.4,-0.5&panels=robot');
  const before = await state(page);
  const save = await point(page, 'robot-urdf');
  const [download] = await Promise.all([page.waitForEvent('download'), page.mouse.click(save.x, save.y)]);
  assert.equal(download.suggestedFilename(), `${before.robot.toLowerCase().replace(/ /g, '-')}.urdf`);
  const urdf = fs.readFileSync(await download.path(), 'utf8');
  assert.match(urdf, /<robot name="/);
  assert.equal((urdf.match(/type="revolute"/g) ?? []).length, 3, 'three revolute joints');
  assert.equal((urdf.match(/type="fixed"/g) ?? []).length, 1, 'the tool joint');
  await until(page, (st) => st.message?.startsWith('Saved the robot as a URDF download'), 'the saved message');
  assert.equal(urdfRequests(requests).length, 2, 'the module came for the download');

  // Opened again: another robot (custom, in metres) with the same tool position.
  await chooseFile(page, 'again.urdf', urdf);
  const s = await until(page, (st) => st.preset === null && st.length_unit === 'm', 'the saved URDF opened again');
  const hash = s.hash.split('&').map((kv) => (kv.startsWith('q=') ? `q=${before.q.join(',')}` : kv)).join('&');
  await page.evaluate((h) => window.armlab.open(h), hash);
  const again = await until(page, (st) => st.q.every((v, i) => Math.abs(v - before.q[i]) < 1e-12), 'the same q');
  // The RRR is in mm; URDF is in metres.
  again.tool.forEach((v, i) => assert.ok(Math.abs(v * 1000 - before.tool[i]) <= 1e-6, `tool ${again.tool} m vs ${before.tool} mm`));
  assert.deepEqual(errors, []);
  await ctx.close();
});

test('in Finnish, a broken URDF file gets the Finnish sentence and the preset stays', async () => {
  const { page, ctx, errors } = await open('#robot=puma560&panels=robot&lang=fi');
  const before = await state(page);
  await chooseFile(page, 'broken.urdf', BROKEN_URDF);
  const s = await until(page, (st) => st.message?.includes('forearm'), 'the broken file\'s sentence');
  assert.equal(s.message, 'Robottitiedostoa ei ladattu: URDF-nivel "elbow" viittaa linkkiin "forearm", jota tiedostossa ei ole.');
  assert.equal(s.preset, 'puma560');
  assert.deepEqual(s.q, before.q);
  assert.deepEqual(errors, []);
  await ctx.close();
});
