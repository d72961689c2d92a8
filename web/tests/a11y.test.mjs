// The page as a screen reader sees it: Chromium's accessibility tree (CDP
// Accessibility.getFullAXTree) of the built page at 1366×768, which the app fills by
// mirroring egui's AccessKit tree into unseen DOM elements over the canvas. Checks each
// panel's controls by role and name, a joint slider's value after the joint moves by its
// arrow keys, a button pressed through the DOM, the keyboard alone, and the skip links.
//
// Prints the named controls per panel (not asserted beyond the minimums below).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { browserSuite } from './browser-suite.mjs';
import path from 'node:path';
import { dist, shots, state, settle, drawnTo, until, point, pageOpener, pixels, at, close } from './page.mjs';
import { CONTROLS, axTree, boxes, mirrored } from './axtree.mjs';

const suite = browserSuite(dist, { untimed: true });
const { open, openKept } = pageOpener(suite, { view: { width: 1366, height: 768 } });
// The pose the tests that only read the tree share one page of.
const SHOWN = '#robot=ur10&q=0,-1.1,1.2,-1.5,-1.2,0.3';

const PANELS = {
  en: ['Joints', 'Inverse kinematics', 'Robot', 'Matrices', 'Motion'],
};

/** Named controls grouped by the panel they sit in: under the nearest panel title above
 * them in the same column; those above every title are the top bar's and the edge tabs'. */
async function controlsByPanel(page, tree) {
  const ids = new Map(tree.map((n) => [n.id, n]));
  const titleNodes = tree.filter((n) => n.role === 'StaticText' && PANELS.en.includes(n.name));
  const titleBoxes = await boxes(page, titleNodes.map((n) => ids.get(n.parent) ?? n));
  const titles = titleNodes.map((n, i) => titleBoxes[i] && { name: n.name, ...titleBoxes[i] }).filter(Boolean);
  const controls = tree.filter((n) => CONTROLS.has(n.role) && n.name);
  const places = await boxes(page, controls);
  const panels = {};
  for (const [i, n] of controls.entries()) {
    const at = places[i];
    const title = at && titles
      .filter((t) => t.y <= at.y + 1 && Math.abs(t.x - at.x) < 300)
      .sort((a, b) => b.y - a.y)[0];
    const panel = title?.name ?? 'top bar and edge tabs';
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
  const { page, errors } = await openKept(SHOWN);
  const tree = await axTree(page);
  const panels = await controlsByPanel(page, tree);
  console.log('NAMED_CONTROLS', JSON.stringify(Object.fromEntries(Object.entries(panels).map(([k, v]) => [k, v.length]))));
  for (const [panel, list] of Object.entries(panels)) console.log(`${panel}:\n  ${list.join('\n  ')}`);
  // Before the mirror the tree held the canvas alone: no named control.
  assert.ok(Object.values(panels).flat().length >= 60, 'at least 60 named controls');
  assert.ok(panels.Joints?.length >= 12, 'six joint sliders and their value boxes');
  for (const title of ['Inverse kinematics', 'Robot', 'Matrices']) assert.ok(panels[title]?.length >= 2, title);
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
  // The matrix is a table: a row of column headers (a frame's axes and origin), then 4 rows,
  // each with its header and 4 cells, entry by entry.
  const table = find(tree, 'table', 'T06 (tool pose, mm)');
  const rows = tree.filter((n) => n.parent === table.id && n.role === 'row');
  assert.equal(rows.length, 5);
  const named = (r, role) => tree.filter((n) => n.parent === r.id && n.role === role).map((c) => c.name);
  assert.deepEqual(named(rows[0], 'columnheader').filter(Boolean), ['x axis', 'y axis', 'z axis', 'origin']);
  assert.deepEqual(rows.slice(1).map((r) => named(r, 'rowheader')), [['x'], ['y'], ['z'], ['homogeneous']]);
  assert.deepEqual(named(rows[4], 'cell'), ['0.000', '0.000', '0.000', '1.000']);
  assert.deepEqual(errors, []);
});

test('the tree\'s root is no unnamed dialog, and no field is nameless: a screen reader says none before the controls', async () => {
  const { page, errors } = await openKept(SHOWN);
  const tree = await axTree(page);
  const dialogs = tree.filter((n) => n.role === 'dialog' && !n.name);
  assert.equal(dialogs.length, 0, `unnamed dialogs: ${dialogs.length}`);
  // eframe's hidden text field, which takes the keys while no control has them, is said
  // by the 3D view's name.
  assert.equal(await page.evaluate(() => document.querySelector('#armlab_canvas+input')?.getAttribute('aria-labelledby')), 'armlab_canvas');
  const fields = tree.filter((n) => n.role === 'textbox');
  assert.deepEqual(fields.filter((n) => !n.name).length, 0, `nameless fields among ${fields.length}`);
  assert.ok(find(tree, 'textbox', 'The robot arm in 3D'), 'the keys\' field has the view\'s name');
  // The controls are still there, under the mirror's root.
  assert.ok(find(tree, 'button', 'Solve'));
  assert.deepEqual(errors, []);
});

test('a combo box has the choice it shows as its value', async () => {
  const { page, errors } = await open('#robot=ur10&q=0,-1.1,1.2,-1.5,-1.2,0.3&task=position');
  const tree = await axTree(page);
  const combos = tree.filter((n) => n.role === 'combobox');
  console.log('COMBO_BOXES', JSON.stringify(combos.map((c) => [c.name, c.value])));
  assert.equal(find(tree, 'combobox', 'The language of the interface')?.value, 'English');
  assert.equal(find(tree, 'combobox', 'Preset')?.value, 'UR10');
  for (const name of ['Task', 'Method']) assert.ok(find(tree, 'combobox', name)?.value, `${name} has a value`);
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('a joint\'s name is said with its slider and its field, not once more as a text alone', async () => {
  const { page, errors } = await openKept(SHOWN);
  const tree = await axTree(page);
  for (let j = 1; j <= 6; j++) {
    const name = `θ${j}`;
    assert.ok(find(tree, 'slider', name), `slider ${name}`);
    assert.ok(find(tree, 'spinbutton', name), `field ${name}`);
    // (The Jacobian's column header for the joint is a text of its own, in its table.)
    const header = (n) => tree.find((p) => p.id === n.parent)?.role === 'columnheader';
    const alone = tree.filter((n) => n.role === 'StaticText' && n.name === name && !header(n));
    assert.equal(alone.length, 0, `${name} as a text of its own: ${alone.length}`);
  }
  assert.deepEqual(errors, []);
});

test('a matrix table is named by its caption, its first line', async () => {
  const { page, errors } = await openKept(SHOWN);
  const tree = await axTree(page);
  for (const name of ['T06 (tool pose, mm)', 'J (6×n, base frame)']) {
    const table = find(tree, 'table', name);
    assert.ok(table, name);
    const from = table.node.name.sources?.find((s) => s.type === 'relatedElement' && s.value);
    assert.equal(from?.attribute, 'aria-labelledby', `${name}: named by its caption`);
    const first = tree.find((n) => n.parent === table.id);
    assert.equal(first.role, 'caption', `${name}: the first child is a ${first.role}`);
    const words = tree.filter((n) => n.parent === first.id).map((n) => n.name).join('');
    assert.equal(words, name, 'the caption says the name');
  }
  // In the page, each table's caption is its first child, and its name.
  const tables = await page.evaluate(() => [...document.querySelectorAll('#armlab_a11y [role=table]')]
    .map((t) => [t.firstElementChild?.getAttribute('role'), t.getAttribute('aria-labelledby') === t.firstElementChild?.id]));
  assert.equal(tables.length, 14);
  assert.deepEqual(tables.filter(([role, names]) => role !== 'caption' || !names), []);
  assert.deepEqual(errors, []);
});

test('every matrix is a table in the tree, those scrolled out of sight too, and stays one frame after frame', async () => {
  const { page, errors } = await openKept(SHOWN);
  // T06, J, and each link's A_i and T_0i (the link fold is open): 14, most below the fold.
  const titles = ['T06 (tool pose, mm)', 'J (6×n, base frame)'];
  for (let i = 1; i <= 6; i++) titles.push(`T0${i}`);
  for (let pass = 0; pass < 2; pass++) {
    await settle(page, 3);
    await page.evaluate(() => window.armlab.mirrorNow());
    await settle(page, 2);
    const tree = await axTree(page);
    const tables = tree.filter((n) => n.role === 'table');
    assert.equal(tables.length, 14, `tables: ${tables.map((t) => t.name).join(' | ')}`);
    for (const title of titles) assert.ok(find(tree, 'table', title), title);
    const last = find(tree, 'table', 'T06');
    assert.equal(tree.filter((n) => n.parent === last.id && n.role === 'row').length, 5, 'T06 with its headers');
  }
  assert.deepEqual(errors, []);
});

test('a matrix table\'s cells are laid out in its box, row by row', async () => {
  const { page, errors } = await openKept(SHOWN);
  await settle(page, 5);
  // Each cell has a box of its own inside the table's (a highlight or a magnifier shows it).
  const boxes = await page.evaluate(() => [...document.querySelectorAll('#armlab_a11y [role=table]')]
    .filter((t) => t.querySelector('[role=caption]').textContent.startsWith('T06 ')).map((t) => {
      const r = (e) => { const b = e.getBoundingClientRect(); return [b.left, b.top, b.right, b.bottom]; };
      return { table: r(t), cells: [...t.querySelectorAll('[role=cell]')].map(r) };
    })[0]);
  const [l, t, r, b] = boxes.table;
  assert.ok(r - l > 50 && b - t > 20, `the table's box: ${boxes.table}`);
  assert.equal(boxes.cells.length, 16);
  for (const c of boxes.cells) {
    assert.ok(c[2] > c[0] && c[3] > c[1], `a cell with a size: ${c}`);
    assert.ok(c[0] >= l - 0.5 && c[1] >= t - 0.5 && c[2] <= r + 0.5 && c[3] <= b + 0.5, `cell ${c} inside ${boxes.table}`);
  }
  assert.equal(new Set(boxes.cells.map((c) => c.join())).size, 16, 'sixteen distinct boxes');
  // Row by row: the fourth row below the first, the fourth column right of the first.
  assert.ok(boxes.cells[12][1] > boxes.cells[0][1] && boxes.cells[3][0] > boxes.cells[0][0]);
  assert.deepEqual(errors, []);
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

test('a column\'s edge is a separator with the column\'s width, stepped by the arrow keys', async () => {
  const { page, errors } = await open('#robot=ur10&task=position');
  const edge = async (name) => find(await axTree(page), 'separator', name);
  const left = await edge('Width of the left column');
  assert.ok(await edge('Width of the right column'), 'the right column\'s edge too');
  assert.ok(left.value > 0 && left.value <= 0.5, `the column's share of the window: ${left.value}`);
  const before = await page.evaluate(() => window.armlab.viewRect());
  const { target } = await state(page);
  // A screen reader focuses the edge's element, and egui's focus follows; then Right
  // widens the column (the 3D view gives way), Left narrows it.
  await page.evaluate(() => document.querySelector('#armlab_a11y [role=separator][aria-label="Width of the left column"]').focus());
  await mirrored(page);
  for (const k of ['ArrowRight', 'ArrowRight']) await page.keyboard.press(k);
  await mirrored(page);
  const wider = await page.evaluate(() => window.armlab.viewRect());
  assert.ok(wider.x > before.x + 40, `the view's left edge moved right: ${before.x} → ${wider.x}`);
  assert.ok((await edge('Width of the left column')).value > left.value, 'and the edge says the new width');
  await page.keyboard.press('ArrowLeft');
  await mirrored(page);
  const narrower = await page.evaluate(() => window.armlab.viewRect());
  assert.ok(narrower.x < wider.x, `one step back: ${wider.x} → ${narrower.x}`);
  assert.deepEqual((await state(page)).target, target, 'the arrow keys moved the column, not the target');
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

/** Waits (up to 20 s) until the live region's text matches `pattern`, sending no input:
 * the app draws the frames that write it by itself, as for a screen reader's user, who
 * moves no pointer. */
const liveSays = (page, pattern) => page.waitForFunction(
  (source) => new RegExp(source).test(document.getElementById('armlab_live')?.textContent ?? ''),
  pattern.source, { timeout: 20000 });

test('the live region says what the view shows, once a second at most, and out of reach when the target leaves', async () => {
  const { page, errors } = await open('#robot=ur10&q=0,-1.1,1.2,-1.5,-1.2,0.3&task=position');
  const live = () => page.evaluate(() => document.getElementById('armlab_live')?.textContent ?? '');
  await liveSays(page, /Target reached/);
  const said = await live();
  assert.match(said, /^UR10\. Tool at x -?\d+, y -?\d+, z -?\d+ mm\. Target reached\. Branch: shoulder/);
  // The tree has it as a polite live region read whole (as text in a screen reader's
  // reading of the page, not as a status bar), and the canvas a name.
  const tree = await axTree(page);
  const region = tree.find((n) => n.props.live === 'polite');
  assert.ok(region, 'a polite live region');
  assert.equal(region.props.atomic, true, 'read whole when it changes');
  assert.notEqual(region.role, 'status', 'not a status bar');
  assert.ok(tree.some((n) => n.parent === region.id && n.name === said), `the live region says: ${said}`);
  assert.ok(find(tree, 'image', 'The robot arm in 3D') || find(tree, 'img', 'The robot arm in 3D'), 'the canvas has a name');
  // Nothing changes: nothing is said.
  await page.evaluate(() => {
    window.__said = [];
    new MutationObserver(() => window.__said.push([performance.now(), document.getElementById('armlab_live').textContent]))
      .observe(document.getElementById('armlab_live'), { childList: true, characterData: true, subtree: true });
  });
  await settle(page, 30);
  assert.deepEqual(await page.evaluate(() => window.__said), [], 'silent while nothing changes');
  // Drag the target far past the arm's reach for about three seconds: only the change
  // of reach is said while the pointer is down, the whole sentence once it is up.
  const t = await point(page, 'target');
  const view = await page.evaluate(() => window.armlab.viewRect());
  await page.mouse.move(t.x, t.y);
  await page.mouse.down();
  const started = Date.now();
  await page.mouse.move(view.x + view.width - 5, view.y + 5, { steps: 60 });
  while (Date.now() - started < 3000) await page.mouse.move(view.x + view.width - 5 - ((Date.now() / 50) % 2), view.y + 5);
  const during = await page.evaluate(() => window.__said.map(([, text]) => text));
  await page.mouse.up();
  await liveSays(page, /^UR10\. .*out of reach/);
  const changes = await page.evaluate(() => window.__said);
  const seconds = (Date.now() - started) / 1000;
  console.log('LIVE_REGION', JSON.stringify({ seconds, during, changes: changes.length, last: await live() }));
  assert.ok(during.length >= 1 && during.length <= 3, `${during.length} sentences during the drag: ${during}`);
  for (const d of during) assert.match(d, /^Target (reached|out of reach)/, 'a change of reach alone');
  assert.match(during.at(-1), /^Target out of reach/);
  const after = changes.slice(during.length).map(([, text]) => text);
  assert.ok(after.length >= 1 && after.length <= 2, `the whole sentence after it: ${after}`);
  for (const a of after) assert.match(a, /^UR10\. Tool at x /);
  for (let i = 1; i < changes.length; i++) assert.ok(changes[i][0] - changes[i - 1][0] >= 990, 'a second apart');
  assert.match(await live(), /^UR10\. Tool at x .* Target out of reach/);
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('the live region and the names speak Finnish in the Finnish interface', async () => {
  const { page, errors } = await open('#robot=ur10&q=0,-1.1,1.2,-1.5,-1.2,0.3&lang=fi');
  const live = () => page.evaluate(() => document.getElementById('armlab_live')?.textContent ?? '');
  await liveSays(page, /Kohde saavutettu/);
  assert.match(await live(), /^UR10\. Työkalu kohdassa x .* Kohde saavutettu\./);
  const tree = await axTree(page);
  assert.ok(find(tree, 'slider', 'θ2'));
  assert.ok(tree.some((n) => n.name === 'Robottikäsivarsi 3D:nä'), 'the canvas is named in Finnish');
  // The page's language and title follow the interface's (a synthesiser reads Finnish
  // words with Finnish rules), and back to English when the language is switched.
  const page0 = () => page.evaluate(() => [document.documentElement.lang, document.title]);
  assert.deepEqual(await page0(), ['fi', 'ArmLab — robottikäsivarren kinematiikka selaimessa']);
  await page.evaluate(() => { location.hash = '#robot=ur10&lang=en'; });
  for (let i = 0; i < 50 && (await page0())[0] !== 'en'; i++) await settle(page, 2);
  assert.deepEqual(await page0(), ['en', 'ArmLab — robot-arm kinematics in the browser']);
  // No name of the Finnish page is one of the English page's words: those of egui's own
  // widgets (a column's resize handle) included. Names without a word (θ2, 0.000, UR10),
  // the few that are the same in both languages and Chromium's pieces of a text's lines
  // are left out.
  await mirrored(page);
  const names = (nodes) => nodes.filter((n) => n.role !== 'InlineTextBox').map((n) => n.name);
  const english = new Set(names(await axTree(page)));
  const SAME = new Set(['ArmLab', 'LaTeX', 'NumPy', 'det J']);
  const untranslated = [...new Set(names(tree))]
    .filter((name) => english.has(name) && /[A-Za-z]{3}/.test(name) && !SAME.has(name));
  assert.deepEqual(untranslated, [], 'names left in English on the Finnish page');
  assert.deepEqual(errors, []);
  await page.context().close();
});

/** Presses Tab (Shift+Tab with `back`) until the control named `name` has the focus;
 * returns the number of presses. */
async function tabTo(page, name, { back = false, most = 120 } = {}) {
  const seen = [];
  for (let i = 1; i <= most; i++) {
    const before = (await state(page)).frame;
    await page.keyboard.press(back ? 'Shift+Tab' : 'Tab');
    // The key's frame builds the tree, and the DOM focus follows egui's in it: the second
    // frame from here at the latest (the first may be one begun before the key).
    await drawnTo(page, before + 2);
    const at = await page.evaluate(() => {
      const a = document.activeElement;
      const by = a?.getAttribute('aria-labelledby');
      return a?.getAttribute('aria-label') ?? (by ? by.split(' ').map((id) => document.getElementById(id)?.textContent).join(' ')
        : a?.tagName === 'A' ? a.textContent : a?.id);
    });
    if (at === name) return i;
    seen.push(at);
  }
  throw new Error(`Tab never reached "${name}": ${seen.slice(0, 40).join(' | ')}`);
}

test('a lecture by the keyboard alone: robot, joint, target, solve, the Jacobian read entry by entry', async () => {
  const { page, errors } = await open('#robot=ur10&task=position');
  await page.focus('#armlab_canvas');
  const steps = {};
  // Choose a robot: the Preset menu, then the Puma 560.
  steps.preset = await tabTo(page, 'Preset');
  await page.keyboard.press('Enter');
  await settle(page, 3);
  steps.puma = await tabTo(page, 'Puma 560');
  await page.keyboard.press('Enter');
  await until(page, (s) => s.preset === 'puma560', 'the Puma 560');
  // Move joint 2: the key 2 gives its slider the keyboard, the arrows move it.
  await page.keyboard.press('Escape');
  await settle(page, 2);
  const q0 = (await state(page)).q;
  await page.keyboard.press('2');
  await settle(page, 2);
  for (let i = 0; i < 4; i++) await page.keyboard.press('ArrowRight');
  const moved = await until(page, (s) => s.q[1] > q0[1] + 1e-3, 'joint 2 to move');
  assert.deepEqual(moved.q.filter((_, i) => i !== 1), q0.filter((_, i) => i !== 1), 'only joint 2 moved');
  // Move the target: Escape takes the keyboard from the slider, the arrows move the target.
  await page.keyboard.press('Escape');
  await settle(page, 2);
  const t0 = (await state(page)).target.position;
  for (let i = 0; i < 3; i++) await page.keyboard.press('PageUp');
  await until(page, (s) => s.target.position.some((v, i) => Math.abs(v - t0[i]) > 1e-6), 'the target to move');
  // The three presses may take more than one frame: the target where they left it.
  await settle(page, 5);
  const t1 = (await state(page)).target.position;
  // Solve.
  steps.solve = await tabTo(page, 'Solve');
  await page.keyboard.press('Enter');
  const solved = await until(page, (s) => s.reached, 'the target reached');
  assert.deepEqual(solved.target.position, t1);
  // The Jacobian: its fold opened by the keyboard if closed, then read entry by entry.
  const tree0 = await axTree(page);
  const fold = find(tree0, 'button', 'Jacobian');
  if (!fold.props.expanded) {
    steps.jacobian = await tabTo(page, 'Jacobian');
    await page.keyboard.press('Enter');
    await settle(page, 3);
  }
  const tree = await axTree(page);
  const table = find(tree, 'table', 'J (6×n, base frame)');
  assert.ok(table, 'the Jacobian is a table');
  const rows = tree.filter((n) => n.parent === table.id && n.role === 'row');
  assert.equal(rows.length, 7, 'a row of headers and six rows');
  const header = (r, role) => tree.filter((n) => n.parent === r.id && n.role === role).map((n) => n.name);
  assert.deepEqual(header(rows[0], 'columnheader').filter(Boolean), ['θ1', 'θ2', 'θ3', 'θ4', 'θ5', 'θ6']);
  assert.deepEqual(header(rows[6], 'rowheader'), ['angular velocity z']);
  const entry = tree.find((n) => n.parent === rows[6].id && n.role === 'cell');
  assert.match(entry.name, /^-?\d+\.\d+$/, `J's entry (6, 1) reads as a number: ${entry?.name}`);
  console.log('KEYBOARD_LECTURE', JSON.stringify({ tabs: steps, joint2: [q0[1], moved.q[1]], target: [t0, t1], entry61: entry.name }));
  assert.deepEqual(errors, []);
  await page.context().close();
});

/** The focused node of the accessibility tree. */
const focusedNode = async (page) => (await axTree(page)).find((n) => n.props.focused && n.role !== 'RootWebArea');

test('skip links come first: Tab reaches "Skip to the 3D view", seen over the canvas, then one per open panel', async () => {
  const { page, errors } = await open('#robot=ur10&task=position');
  const before = await pixels(page, await page.screenshot());
  await page.keyboard.press('Tab');
  const first = await focusedNode(page);
  assert.equal(first?.role, 'link', `the first Tab reaches a link: ${first?.role} "${first?.name}"`);
  assert.equal(first.name, 'Skip to the 3D view');
  // Seen while focused: a box on screen, drawn over the canvas in the outline's blue.
  const [box] = await boxes(page, [first]);
  assert.ok(box.x >= 0 && box.y >= 0 && box.width >= 120 && box.height >= 24
    && box.x + box.width <= 1366 && box.y + box.height <= 768, `on screen: ${JSON.stringify(box)}`);
  const shot = await pixels(page, await page.screenshot({ path: path.join(shots, 'skip-link-focused.png') }));
  let changed = 0, blue = 0;
  for (let y = Math.floor(box.y) - 3; y < box.y + box.height + 3; y++) {
    for (let x = Math.floor(box.x) - 3; x < box.x + box.width + 3; x++) {
      if (!close(at(shot, x, y), at(before, x, y), 8)) changed++;
      if (close(at(shot, x, y), [0x8a, 0xb4, 0xf8], 12)) blue++;
    }
  }
  assert.ok(changed > box.width * box.height * 0.3, `the link shows: ${changed} pixels changed`);
  assert.ok(blue > 2 * (box.width + box.height), `with its focus outline: ${blue} outline pixels`);
  const links = (await axTree(page)).filter((n) => n.role === 'link' && n.name.startsWith('Skip to')).map((n) => n.name);
  console.log('SKIP_LINKS', JSON.stringify(links));
  assert.equal(links[0], 'Skip to the 3D view');
  for (const panel of ['Joints', 'Inverse kinematics', 'Matrices']) assert.ok(links.includes(`Skip to the ${panel} panel`), panel);
  // Out of sight again once the focus leaves it.
  await page.keyboard.press('Tab');
  const gone = await page.evaluate(() => document.querySelector('#armlab_skip a').getBoundingClientRect().width);
  assert.ok(gone <= 1, `hidden when not focused: ${gone} px wide`);
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('"Skip to the Inverse kinematics panel" gives the keyboard to that panel: the next Tab stays inside it', async () => {
  const { page, errors } = await open('#robot=ur10&task=position');
  await tabTo(page, 'Skip to the Inverse kinematics panel', { most: 10 });
  await page.keyboard.press('Enter');
  await settle(page, 4);
  await page.keyboard.press('Tab');
  await settle(page, 3);
  const tree = await axTree(page);
  const focused = tree.find((n) => n.props.focused && n.role !== 'RootWebArea');
  assert.ok(focused && CONTROLS.has(focused.role), `a control has the focus: ${focused?.role} "${focused?.name}"`);
  const title = (name) => {
    const text = tree.find((n) => n.role === 'StaticText' && n.name === name);
    return text && (tree.find((n) => n.id === text.parent) ?? text);
  };
  const [ik, next, it] = await boxes(page, [title('Inverse kinematics'), title('Robot'), focused]);
  console.log('SKIP_IK', JSON.stringify({ focused: `${focused.role} "${focused.name}"`, at: it, ik, next }));
  assert.ok(it.y > ik.y && (!next || it.y < next.y) && Math.abs(it.x - ik.x) < 300,
    `the focused control is in the IK panel: ${JSON.stringify({ it, ik, next })}`);
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('"Skip to the Robot panel" gives the keyboard to its first control, the Preset menu; Tab goes on to the DH table', async () => {
  const { page, errors } = await open('#robot=ur10&panels=joints,ik,robot,matrices');
  await tabTo(page, 'Skip to the Robot panel', { most: 10 });
  await page.keyboard.press('Enter');
  await settle(page, 4);
  const first = await focusedNode(page);
  assert.equal(`${first?.role} ${first?.name}`, 'combobox Preset');
  await page.keyboard.press('Tab');
  await settle(page, 3);
  const next = await focusedNode(page);
  assert.equal(`${next?.role} ${next?.name}`, 'button DH table (editable)');
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('"Skip to the 3D view" leaves no control focused: the arrow keys move the target', async () => {
  const { page, errors } = await open('#robot=ur10&task=position');
  // From inside the panels: joint 2's slider has the keyboard (key 2), then the focus goes
  // back to the first skip link.
  await page.focus('#armlab_canvas');
  await page.keyboard.press('2');
  await settle(page, 3);
  assert.equal((await focusedNode(page))?.name, 'θ2', 'the slider has the keyboard');
  await page.focus('#armlab_skip a');
  assert.equal((await focusedNode(page))?.name, 'Skip to the 3D view');
  await page.keyboard.press('Enter');
  await settle(page, 4);
  assert.equal(await page.evaluate(() => document.activeElement?.id), 'armlab_canvas', 'the canvas has the DOM focus');
  const t0 = (await state(page)).target.position;
  const q0 = (await state(page)).q;
  for (let i = 0; i < 3; i++) await page.keyboard.press('ArrowRight');
  const s = await until(page, (st) => st.target.position.some((v, i) => Math.abs(v - t0[i]) > 1e-6), 'the target to move');
  console.log('SKIP_VIEW', JSON.stringify({ from: t0, to: s.target.position }));
  assert.ok(s.q.some((v, i) => Math.abs(v - q0[i]) > 1e-6), 'and the arm follows it');
  assert.equal((await focusedNode(page))?.role === 'slider', false, 'no slider took the arrows');
  assert.deepEqual(errors, []);
  await page.context().close();
});

test('the page takes the system\'s reduced motion, and leaves motion on without it', async () => {
  for (const reducedMotion of ['reduce', 'no-preference']) {
    const { page, errors } = await open('#robot=ur10', { contextOptions: { reducedMotion } });
    const s = await state(page);
    assert.equal(s.reduced_motion, reducedMotion === 'reduce', `reducedMotion: ${reducedMotion}`);
    assert.deepEqual(errors, []);
    await page.context().close();
  }
});

test('a label that comes into sight names its control once: "Preset", not "Preset Preset"', async () => {
  // 1920×1080 at 200 %: the Robot panel's Preset menu lies below the fold; scrolled into
  // sight, egui gives its label the words as a part of its own.
  const view = { width: 960, height: 540 };
  const { page, errors } = await open('#robot=ur10&q=0,-1.1,1.2,-1.5,-1.2,0.3&task=position',
    { view, contextOptions: { deviceScaleFactor: 2, reducedMotion: 'reduce' } });
  const rect = await page.evaluate(() => window.armlab.viewRect());
  const inSight = (found) => Boolean(found?.box) && found.box.y + found.box.height < view.height;
  let preset;
  for (let i = 0; i < 8 && !inSight(preset); i++) {
    await page.mouse.move(rect.x / 2, rect.y + rect.height / 2);
    await page.mouse.wheel(0, 150);
    await mirrored(page);
    const tree = await axTree(page);
    const node = tree.find((n) => n.role === 'combobox' && /Preset/.test(n.name));
    preset = node && { name: node.name, box: (await boxes(page, [node]))[0] };
  }
  assert.ok(inSight(preset), `the menu in sight: ${JSON.stringify(preset)}`);
  assert.equal(preset.name, 'Preset');
  // No element of the mirror says words of its own beside its parts.
  const both = await page.evaluate(() => [...document.querySelectorAll('#armlab_a11y *')]
    .filter((e) => e.children.length > 0 && [...e.childNodes].some((c) => c.nodeType === Node.TEXT_NODE && c.textContent.trim()))
    .map((e) => e.textContent));
  assert.deepEqual(both, []);
  assert.deepEqual(errors, []);
  await page.context().close();
});
