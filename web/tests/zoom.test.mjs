// The browser's zoom at 200 %: the page at half a screen's CSS width and height and twice
// its device pixel ratio, as the browser makes it. Nothing may be lost: every named control
// in Chromium's accessibility tree (the top bar's, the edge or bottom tabs', each panel's)
// is seen whole inside the page at some point while a person opens the narrow layout's menu
// and each panel and scrolls each column or sheet to its end, and sideways where something
// is not seen yet (a matrix, wider than most columns, is seen when part of it is). Prints
// what was seen only by scrolling sideways. Leaves a screenshot of each screen, of its menu
// and of each panel in web/tests/screenshots/zoom200-*.png.
//
// The test command walks the laptop (1366×768) here: the same walk at all six screens runs
// natively in the UI tests (tests/ui/zoom.rs; egui lays out one point per CSS pixel, so
// the layout is the same), and this one checks the browser's side of it, the zoom reaching
// the page and the mirror placing its elements where the widgets are drawn. All six here
// (about four minutes): ARMLAB_ZOOM_SCREENS=all node --test web/tests/zoom.test.mjs
import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { browserSuite } from './browser-suite.mjs';
import { dist, shots, SCREENS, settle, pageOpener } from './page.mjs';
import { CONTROLS, axTree, boxes, mirrored } from './axtree.mjs';

const measurements = {};
const suite = browserSuite(dist, { label: 'ARMLAB_ZOOM200', measurements, untimed: true });
const { openAt } = pageOpener(suite);

const HASH = '#robot=ur10&q=0,-1.1,1.2,-1.5,-1.2,0.3&task=position';
const PANELS = ['joints', 'ik', 'robot', 'matrices', 'motion'];

/** The named controls in the tree now: each with its element's id and box. */
async function controls(page) {
  const list = (await axTree(page)).filter((n) => CONTROLS.has(n.role) && n.name);
  const at = await boxes(page, list);
  return list.map((n, i) => ({ key: `${n.role} "${n.name}"`, role: n.role, box: at[i] })).filter((c) => c.box);
}

/** Whether a control is seen in a `w`×`h` page: whole, or a table (it scrolls sideways) in part. */
function seen(c, w, h) {
  const b = c.box;
  if (b.width < 1 || b.height < 1) return false;
  if (c.role === 'table') return b.x < w && b.x + b.width > 0 && b.y < h && b.y + b.height > 0;
  return b.x >= -0.5 && b.y >= -0.5 && b.x + b.width <= w + 0.5 && b.y + b.height <= h + 0.5;
}

/** Records every control in the tree now and which of them are seen; returns where the
 * controls are (to tell whether a scroll moved anything). */
async function look(page, all, where) {
  await mirrored(page);
  const { width, height } = page.viewportSize();
  const now = await controls(page);
  for (const c of now) {
    const id = `${c.box.el} ${c.key}`;
    if (!all.has(id)) all.set(id, null);
    if (all.get(id) === null && seen(c, width, height)) all.set(id, where);
  }
  // Something not seen yet that lies past the page's right edge at this height: the
  // column scrolls sideways to it.
  const wide = now.some((c) => all.get(`${c.box.el} ${c.key}`) === null && c.box.x + c.box.width > width + 0.5
    && c.box.y < height && c.box.y + c.box.height > 0);
  return { where: now.map((c) => `${c.box.el}@${Math.round(c.box.y)}`).join(' '), wide };
}

/** Scrolls the column or sheet under (`x`, `y`), `tall` CSS px of it in sight, to its end,
 * looking after each step of three fifths of that: a control up to two fifths as tall is
 * whole in one of two neighbouring looks. */
async function scrollThrough(page, all, x, y, tall, where) {
  const step = Math.max(60, Math.floor(tall * 0.6));
  let before = '';
  for (let i = 0; i < 60; i++) {
    await page.mouse.move(x, y);
    await page.mouse.wheel(0, step);
    const { where: after, wide } = await look(page, all, `${where}, scrolled`);
    if (wide) {
      await page.mouse.move(x, y);
      await page.mouse.wheel(100000, 0);
      await look(page, all, `${where}, scrolled sideways`);
      await page.mouse.move(x, y);
      await page.mouse.wheel(-100000, 0);
    }
    if (after === before) break;
    before = after;
  }
  await page.mouse.move(x, y);
  await page.mouse.wheel(0, -100000);
  await settle(page, 2);
}

/** Clicks a control found by role and the end of its name in the tree. */
async function press(page, role, name) {
  const node = (await axTree(page)).find((n) => n.role === role && n.name.endsWith(name));
  assert.ok(node, `${role} "${name}" is in the tree`);
  const [b] = await boxes(page, [node]);
  await page.mouse.click(b.x + b.width / 2, b.y + b.height / 2);
  await settle(page, 3);
}

const WALKED = process.env.ARMLAB_ZOOM_SCREENS === 'all' ? SCREENS : SCREENS.filter((s) => s.name === 'laptop-1366x768');

for (const screen of WALKED) {
  test(`${screen.name} at 200 %: every control is in the tree and can be seen`, async () => {
    const zoomed = { ...screen, width: screen.width / 2, height: screen.height / 2, dpr: (screen.dpr ?? 1) * 2 };
    // Scrolls land at once (egui animates them otherwise), so each look sees where a
    // scroll step put the column.
    const { page, errors } = await openAt(zoomed, HASH, { reducedMotion: 'reduce' });
    const shot = (part) => page.screenshot({ path: path.join(shots, `zoom200-${screen.name}${part}.png`) });
    const all = new Map();
    await look(page, all, 'first');
    await shot('');
    const view = await page.evaluate(() => window.armlab.viewRect());
    const narrow = await page.evaluate(() => window.armlab.screenPoint('tab-joints'))
      .then((p) => p && p.y > view.y + view.height);
    if (narrow) {
      await press(page, 'button', 'Menu');
      await look(page, all, 'menu');
      await shot('-menu');
      await page.keyboard.press('Escape');
      await settle(page, 3);
      for (const panel of PANELS) {
        const tab = await page.evaluate((n) => window.armlab.screenPoint(n), `tab-${panel}`);
        await page.mouse.click(tab.x, tab.y);
        await settle(page, 4);
        await look(page, all, panel);
        await shot(`-${panel}`);
        const v = await page.evaluate(() => window.armlab.viewRect());
        const sheet = { top: v.y + v.height, bottom: Math.min(tab.y, zoomed.height) };
        await scrollThrough(page, all, zoomed.width / 2, (sheet.top + sheet.bottom) / 2, sheet.bottom - sheet.top, panel);
        await page.mouse.click(tab.x, tab.y);
        await settle(page, 3);
      }
    } else {
      const middle = view.y + view.height / 2;
      await scrollThrough(page, all, view.x / 2, middle, view.height, 'left column');
      await scrollThrough(page, all, (view.x + view.width + zoomed.width) / 2, middle, view.height, 'right column');
    }
    const lost = [...all].filter(([, where]) => where === null).map(([id]) => id);
    const sideways = [...all].filter(([, where]) => where?.endsWith('sideways')).map(([id]) => id.replace(/^\S+ /, ''));
    measurements[screen.name] = { css: [zoomed.width, zoomed.height], dpr: zoomed.dpr, controls: all.size, sideways, lost };
    console.log(`ZOOM200 ${screen.name}`, JSON.stringify(measurements[screen.name]));
    assert.ok(all.size >= 40, `${screen.name}: ${all.size} named controls`);
    assert.deepEqual(lost, [], `${screen.name} at 200 %: controls never seen whole`);
    assert.deepEqual(errors, []);
    await page.context().close();
  });
}
