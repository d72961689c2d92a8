// The page as a screen reader sees it, for the browser tests: Chromium's accessibility tree
// (CDP Accessibility.getFullAXTree) and where its nodes' elements are. Not a *.test.mjs
// file, so the test command does not run it on its own.
import { state, drawnTo } from './page.mjs';

/** Roles a person operates or reads entry by entry. */
export const CONTROLS = new Set(['button', 'slider', 'spinbutton', 'checkbox', 'combobox', 'textbox', 'radio',
  'tab', 'link', 'menuitem', 'table']);

const sessions = new WeakMap();

/** The page's one CDP session for these helpers, kept open: Chromium then keeps its
 * accessibility tree from one call to the next instead of building it anew for each
 * (about 90 ms against 5 ms for a panel's tree on this machine). It ends with the page. */
async function session(page) {
  let cdp = sessions.get(page);
  if (!cdp) sessions.set(page, (cdp = await page.context().newCDPSession(page)));
  return cdp;
}

/**
 * Waits for the frame that takes in the input just sent (a scroll moves a column on the
 * next), then for one that places it and builds the tree for the mirror
 * (`window.armlab.mirrorNow`; while only the pointer moves the mirror follows twice a
 * second). The input's frames and the one mirrorNow asks for come by themselves: a nudge
 * of the pointer would draw two more.
 */
export async function mirrored(page) {
  await drawnTo(page, (await state(page)).frame + 1);
  const placed = (await state(page)).frame;
  await page.evaluate(() => window.armlab.mirrorNow());
  await drawnTo(page, placed + 1);
}

/** The accessibility tree: every node that is not ignored, with its role, name, value,
 * properties and its parent's id. */
export async function axTree(page) {
  const { nodes } = await (await session(page)).send('Accessibility.getFullAXTree');
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

/** Each page's elements' id attributes by backend node id (a mirror's element keeps its
 * node and its id while it lives), so that a page asked again costs one evaluate. */
const elementIds = new WeakMap();

/** Each node's element: its id attribute and its border box in CSS pixels
 * ({ x, y, width, height }), or null for a node without a box (or no node). */
export async function boxes(page, nodes) {
  let ids = elementIds.get(page);
  if (!ids) elementIds.set(page, (ids = new Map()));
  const unknown = nodes.map((n) => n?.node.backendDOMNodeId).filter((b) => b !== undefined && !ids.has(b));
  if (unknown.length) {
    const cdp = await session(page);
    for (const backendNodeId of unknown) {
      try {
        const { node } = await cdp.send('DOM.describeNode', { backendNodeId });
        const attrs = node.attributes ?? [];
        const at = attrs.indexOf('id');
        ids.set(backendNodeId, at >= 0 ? attrs[at + 1] : null);
      } catch {
        ids.set(backendNodeId, null);
      }
    }
  }
  const wanted = nodes.map((n) => (n ? ids.get(n.node.backendDOMNodeId) ?? null : null));
  // An element without an id is found by its own backend node id, one call each.
  const rects = await page.evaluate((list) => list.map((id) => {
    const el = id && document.getElementById(id);
    if (!el || el.getClientRects().length === 0) return null;
    const r = el.getBoundingClientRect();
    return { x: r.x, y: r.y, width: r.width, height: r.height };
  }), wanted);
  const out = [];
  for (const [i, n] of nodes.entries()) {
    if (wanted[i] !== null) {
      out.push(rects[i] && { el: wanted[i], ...rects[i] });
      continue;
    }
    const backendNodeId = n?.node.backendDOMNodeId;
    if (backendNodeId === undefined) {
      out.push(null);
      continue;
    }
    try {
      const { model } = await (await session(page)).send('DOM.getBoxModel', { backendNodeId });
      const [x0, y0, x1, , , y2] = model.border;
      out.push({ el: `backend${backendNodeId}`, x: x0, y: y0, width: x1 - x0, height: y2 - y0 });
    } catch {
      out.push(null);
    }
  }
  return out;
}
