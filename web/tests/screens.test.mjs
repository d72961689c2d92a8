// The screens of a lecture: the built page (dist/) in Debian's headless Chromium on WebGL2,
// driven by playwright-core, at projector, laptop, tablet and phone sizes, in presentation
// mode and at device pixel ratios 1 to 3: the 3D view keeps its share and shows the arm.
//
// Prints one JSON line of measurements (not asserted): the 3D view's share of the width on
// each screen.
import { test, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { browserSuite } from './browser-suite.mjs';
import { dist, shots, SCREENS, state, point, settle, typeIntoDhCell, pageOpener } from './page.mjs';

const measurements = {};

const suite = browserSuite(dist, { label: 'ARMLAB_SCREENS_MEASUREMENTS', measurements, untimed: true });
const { openAt } = pageOpener(suite);

after(() => fs.writeFileSync(path.join(shots, 'screens-measurements.json'), JSON.stringify(measurements, null, 2)));

// The UR10 at its home pose, the target 450 mm above the tool (so the tool point is
// not under the ball).
const LAYOUT_HASH = '#robot=ur10&q=0,1.0472,-1.5708,2.0944,1.5708,0&target=685.77,-163.9,915.19,1.5708,0,0&task=position';

const inside = (p, r) => p.x > r.x && p.x < r.x + r.width && p.y > r.y && p.y < r.y + r.height;

/** The view's rectangle, its share of the width, and the base, tool and target inside it. */
async function checkView(page, screen, minShare) {
  const rect = await page.evaluate(() => window.armlab.viewRect());
  assert.ok(rect, 'viewRect() is published');
  const share = rect.width / screen.width;
  assert.ok(share >= minShare, `${screen.name}: the 3D view has ${(share * 100).toFixed(1)} % of the width (at least ${minShare * 100} %)`);
  for (const name of ['base', 'tool', 'target']) {
    const p = await point(page, name);
    assert.ok(inside(p, rect), `${screen.name}: the ${name} (${p.x.toFixed(0)}, ${p.y.toFixed(0)}) lies in the view ${JSON.stringify(rect)}`);
  }
  return { rect, share };
}

for (const screen of SCREENS) {
  // A touch screen has no hovering pointer to tell what covers the tool.
  test(`${screen.name}: the arm, its tool and target are in the 3D view${screen.touch ? '' : ' and nothing covers the tool'}`, async () => {
    const { page, ctx, errors } = await openAt(screen, LAYOUT_HASH);
    const narrow = screen.width < 900;
    const { share } = await checkView(page, screen, narrow ? 0.99 : 0.5);
    measurements[`view_share_${screen.name}`] = +share.toFixed(3);
    // Nothing covers the tool: the pointer there hovers the last link (the view answers).
    if (!screen.touch) {
      const tool = await point(page, 'tool');
      await page.mouse.move(tool.x, tool.y);
      await settle(page, 2);
      await page.mouse.move(tool.x + 0.5, tool.y);
      const s = await state(page);
      assert.equal(s.hovered_link, 6, `${screen.name}: the pointer on the tool hovers link 6`);
    }
    const s = await state(page);
    assert.equal(s.touch, Boolean(screen.touch), 'touch sizing follows the pointer');
    if (narrow) {
      // The bottom tab opens the joints as a sheet; the view shrinks above it and still
      // shows the whole arm.
      const tab = await point(page, 'tab-joints');
      const tap = () => (screen.touch ? page.touchscreen.tap(tab.x, tab.y) : page.mouse.click(tab.x, tab.y));
      await tap();
      await settle(page, 4);
      assert.equal((await state(page)).sheet, 'joints');
      const open = await checkView(page, screen, 0.99);
      assert.ok(open.rect.height < screen.height * 0.6, 'the sheet takes the lower part');
      await page.screenshot({ path: path.join(shots, `layout-${screen.name}-sheet.png`) });
      await tap();
      await settle(page, 4);
    }
    await page.screenshot({ path: path.join(shots, `layout-${screen.name}.png`) });
    assert.deepEqual(errors, []);
    await ctx.close();
  });
}

test('presentation mode at 1024×768: the view keeps 60 % and the arm, the chosen panels open, the joints beside it', async () => {
  const screen = SCREENS[0];
  const { page, ctx, errors } = await openAt(screen, `${LAYOUT_HASH}&present=on&ppanels=joints,matrices`);
  const s = await state(page);
  assert.equal(s.presentation, true);
  assert.equal(s.open_panels, 'joints,matrices');
  const { rect, share } = await checkView(page, screen, 0.6);
  measurements.view_share_presentation_1024x768 = +share.toFixed(3);
  // The joints' sliders sit in a column beside the view, inside the window.
  for (const end of ['slider-1-min', 'slider-6-max']) {
    const p = await point(page, end);
    assert.ok((p.x < rect.x || p.x > rect.x + rect.width) && p.x > 0 && p.x < screen.width,
      `${end} at x ${p.x.toFixed(0)} lies beside the view (x ${rect.x.toFixed(0)} to ${(rect.x + rect.width).toFixed(0)})`);
  }
  // The P key leaves presentation mode (no text field has the keyboard).
  await page.screenshot({ path: path.join(shots, 'layout-presentation-1024x768.png') });
  await page.keyboard.press('p');
  await settle(page, 3);
  assert.equal((await state(page)).presentation, false);
  assert.deepEqual(errors, []);
  await ctx.close();
});

// At a phone's size, where DPR 3 is real (a 1280×720 page at DPR 3 would make the software
// renderer draw 8.3 million pixels a frame, and this test take about twice as long).
test('the UI has the same size in CSS pixels at device pixel ratios 1, 2 and 3', async () => {
  const seen = [];
  for (const dpr of [1, 2, 3]) {
    const { page, ctx } = await openAt({ ...SCREENS[5], dpr }, LAYOUT_HASH);
    const rect = await page.evaluate(() => window.armlab.viewRect());
    const tab = await point(page, 'tab-joints');
    seen.push({ dpr, rect, tab });
    await ctx.close();
  }
  for (const { dpr, rect, tab } of seen.slice(1)) {
    for (const k of ['x', 'y', 'width', 'height']) {
      assert.ok(Math.abs(rect[k] - seen[0].rect[k]) <= 1.5, `DPR ${dpr}: view ${k} ${rect[k]} vs ${seen[0].rect[k]}`);
    }
    assert.ok(Math.abs(tab.y - seen[0].tab.y) <= 1.5, `DPR ${dpr}: the joints tab sits at the same CSS height`);
  }
});

test('typing 1e999 into a DH cell at 1024×768 leaves the 3D view its share', async () => {
  const screen = SCREENS[0];
  // The robot panel alone: with the joints' rails on lines of their own the table
  // starts below this screen's bottom.
  const { page, ctx } = await openAt(screen, '#robot=rrr&panels=robot');
  const before = await page.evaluate(() => window.armlab.viewRect());
  await typeIntoDhCell(page, 'dh-1-2', '1e999');
  const after = await page.evaluate(() => window.armlab.viewRect());
  assert.ok(Math.abs(after.width - before.width) <= 1, `the view stays ${before.width} px wide (now ${after.width})`);
  // Every cell of the first joint sits in the column, left of the view (the table turns
  // into a block per joint here; one line per joint put the limits at x 323-407).
  for (let c = 1; c <= 6; c++) {
    const cell = await point(page, `dh-1-${c}`);
    assert.ok(cell.x > 30 && cell.x < after.x, `cell dh-1-${c} at x ${cell.x.toFixed(0)} lies in the column (the view starts at ${after.x})`);
  }
  // The cell says what is wrong, and the keys typed into it did not act as shortcuts.
  const s = await state(page);
  assert.match(s.editor_error ?? '', /finite/);
  assert.equal(s.presentation, false);
  await page.screenshot({ path: path.join(shots, 'dh-cell-1e999-1024x768.png') });
  await ctx.close();
});
