// The page as a screen reader sees it: Chromium's accessibility tree (CDP
// Accessibility.getFullAXTree) of the built page at 1366×768, which the app fills by
// mirroring egui's AccessKit tree into unseen DOM elements over the canvas. Checks each
// panel's controls by role and name, a joint slider's value after the joint moves by its
// arrow keys, a button pressed through the DOM, and the keyboard alone.
//
// Prints the named controls per panel (not asserted beyond the minimums below).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { browserSuite } from './browser-suite.mjs';
import { dist, state, settle, until, pageOpener } from './page.mjs';

const suite = browserSuite(dist);
const { open } = pageOpener(suite, { view: { width: 1366, height: 768 } });

/** Roles a person operates or reads entry by entry. */
const CONTROLS = new Set(['button', 'slider', 'spinbutton', 'checkbox', 'combobox', 'textbox', 'radio',
  'tab', 'link', 'menuitem', 'table']);

/** The accessibility tree: every node that is not ignored, with its role, name, value,
 * properties and the names of its section (the panel's title, the first text in it). */
async function axTree(page) {
  const cdp = await page.context().newCDPSession(page);
  const { nodes } = await cdp.send('Accessibility.getFullAXTree');
  await cdp.detach();
  const byId = new Map(nodes.map((n) => [n.nodeId, n]));
  const props = (n) => Object.fromEntries((n.properties ?? []).map((p) => [p.name, p.value.value]));
  return nodes.filter((n) => !n.ignored).map((n) => ({
    id: n.nodeId,
    role: n.role?.value,
    name: n.name?.value ?? '',
    value: n.value?.value,
    props: props(n),
    parent: n.parentId,
    node: n,
    byId,
  }));
}

/** Named controls grouped by the panel they sit in: the mirror's panel sections are the
 * children of its top groups; a section is named by its first text. */
function controlsByPanel(tree) {
  const ids = new Map(tree.map((n) => [n.id, n]));
  const firstText = (n) => {
    const stack = [...(n.node.childIds ?? [])];
    while (stack.length) {
      const c = ids.get(stack.shift());
      if (!c) continue;
      if (c.role === 'StaticText' && c.name) return c.name;
      stack.push(...(c.node.childIds ?? []));
    }
    return '';
  };
  const panels = {};
  for (const n of tree) {
    if (!CONTROLS.has(n.role) || !n.name) continue;
    // The panel: the highest ancestor below the groups that holds a heading text.
    let p = n;
    let panel = 'top bar and edge tabs';
    while (p && p.parent) {
      const up = ids.get(p.parent);
      if (up?.role === 'group') {
        const title = firstText(p);
        if (['Joints', 'Inverse kinematics', 'Robot', 'Matrices', 'Motion'].includes(title)) panel = title;
      }
      p = up;
    }
    (panels[panel] ??= []).push(`${n.role} "${n.name}"${n.value !== undefined && n.value !== '' ? ` = ${n.value}` : ''}`);
  }
  return panels;
}

/** A node's aria-valuetext, read from its DOM element (Chromium's CDP tree leaves its
 * valuetext property empty, while the platform's accessibility API carries it). */
async function valueText(page, node) {
  const cdp = await page.context().newCDPSession(page);
  const { node: dom } = await cdp.send('DOM.describeNode', { backendNodeId: node.node.backendDOMNodeId });
  await cdp.detach();
  const at = dom.attributes.indexOf('aria-valuetext');
  return at >= 0 ? dom.attributes[at + 1] : undefined;
}

const find = (tree, role, name) => tree.find((n) => n.role === role && n.name === name);

test('every panel\'s controls are in the accessibility tree with their roles, names and values', async () => {
  const { page, errors } = await open('#robot=ur10&q=0,-1.1,1.2,-1.5,-1.2,0.3');
  const tree = await axTree(page);
  const panels = controlsByPanel(tree);
  console.log('NAMED_CONTROLS', JSON.stringify(Object.fromEntries(Object.entries(panels).map(([k, v]) => [k, v.length]))));
  for (const [panel, list] of Object.entries(panels)) console.log(`${panel}:\n  ${list.join('\n  ')}`);
  // Before the mirror the tree held the canvas alone: no named control.
  assert.ok(Object.values(panels).flat().length >= 60, 'at least 60 named controls');
  assert.ok(panels.Joints?.length >= 12, 'six joint sliders and their value boxes');
  const slider = find(tree, 'slider', 'θ2');
  assert.ok(slider, 'the slider of joint 2 is named θ2');
  assert.ok(Math.abs(slider.value - (-1.1 * 180 / Math.PI)) < 0.01, `its value in degrees: ${slider.value}`);
  assert.equal(await valueText(page, slider), '−63.0°', 'and its value as shown');
  for (const [role, name] of [['button', 'Solve'], ['button', 'Zero'], ['combobox', 'Preset'], ['combobox', 'Task'],
    ['button', 'Matrices'], ['table', 'T06 (tool pose, mm)']]) {
    assert.ok(find(tree, role, name), `${role} "${name}"`);
  }
  const fold = find(tree, 'button', 'Jacobian');
  assert.equal(fold.props.expanded, true, 'a fold says whether it is open');
  assert.equal(find(tree, 'button', 'DH table (editable)').props.expanded, false);
  // The matrix is a table: 4 rows of 4 cells, entry by entry.
  const table = find(tree, 'table', 'T06 (tool pose, mm)');
  const rows = tree.filter((n) => n.parent === table.id && n.role === 'row');
  assert.equal(rows.length, 4);
  const cells = rows.map((r) => tree.filter((n) => n.parent === r.id && n.role === 'cell').map((c) => c.name));
  assert.deepEqual(cells[3], ['0.000', '0.000', '0.000', '1.000']);
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('a joint slider focused through the DOM moves on the arrow keys, and its value follows', async () => {
  const { page, errors } = await open('#robot=ur10&q=0,-1.1,1.2,-1.5,-1.2,0.3');
  const q0 = (await state(page)).q;
  // A screen reader moves its focus to the slider's element: egui's focus follows.
  await page.evaluate(() => [...document.querySelectorAll('#armlab_a11y [role=slider]')]
    .find((e) => e.getAttribute('aria-label') === 'θ2').focus());
  await settle(page);
  for (let i = 0; i < 5; i++) await page.keyboard.press('ArrowRight');
  await until(page, (st) => Math.abs(st.q[1] - q0[1]) > 1e-3, 'joint 2 to move');
  await settle(page, 5);
  const s = await state(page);
  assert.ok(s.q[1] > q0[1], `θ2 grew: ${q0[1]} → ${s.q[1]}`);
  const degrees = s.q[1] * 180 / Math.PI;
  const slider = find(await axTree(page), 'slider', 'θ2');
  assert.ok(Math.abs(slider.value - degrees) < 0.01, `the tree says the new value: ${slider.value} vs ${degrees}`);
  assert.equal(await valueText(page, slider), `${degrees.toFixed(1)}°`.replace('-', '−'));
  assert.equal(slider.props.focused, true, 'and the slider keeps the focus');
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('a button pressed through the DOM (a screen reader\'s click) does what the button does', async () => {
  const { page, errors } = await open('#robot=ur10&q=0,-1.1,1.2,-1.5,-1.2,0.3');
  await page.evaluate(() => [...document.querySelectorAll('#armlab_a11y [role=button]')]
    .find((e) => e.getAttribute('aria-label') === 'Zero').click());
  const s = await until(page, (st) => st.q.every((v) => Math.abs(v) < 1e-9), 'the joints at zero');
  assert.deepEqual(s.q, [0, 0, 0, 0, 0, 0]);
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('Tab from the canvas walks the controls, and the DOM focus follows egui\'s', async () => {
  const { page, errors } = await open('#robot=ur10');
  await page.focus('#armlab_canvas');
  const seen = [];
  for (let i = 0; i < 12; i++) {
    await page.keyboard.press('Tab');
    await settle(page, 2);
    seen.push(await page.evaluate(() => {
      const a = document.activeElement;
      return a?.closest('#armlab_a11y') ? `${a.getAttribute('role')} ${a.getAttribute('aria-label') ?? a.id}` : a?.id;
    }));
  }
  console.log('TAB_ORDER', JSON.stringify(seen));
  assert.ok(seen.filter((s) => s?.startsWith('button ')).length >= 5, `Tab reached the buttons: ${seen}`);
  assert.deepEqual(errors, []);
  await page.context().close();
});
