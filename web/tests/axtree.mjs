// The page as a screen reader sees it, for the browser tests: Chromium's accessibility tree
// (CDP Accessibility.getFullAXTree) and where its nodes' elements are. Not a *.test.mjs
// file, so the test command does not run it on its own.

/** Roles a person operates or reads entry by entry. */
export const CONTROLS = new Set(['button', 'slider', 'spinbutton', 'checkbox', 'combobox', 'textbox', 'radio',
  'tab', 'link', 'menuitem', 'table']);

/** The accessibility tree: every node that is not ignored, with its role, name, value,
 * properties and its parent's id. */
export async function axTree(page) {
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

/** Each node's element: its id attribute and its border box in CSS pixels
 * ({ x, y, width, height }), or null for a node without a box. */
export async function boxes(page, nodes) {
  const cdp = await page.context().newCDPSession(page);
  const out = [];
  for (const n of nodes) {
    try {
      const backendNodeId = n.node.backendDOMNodeId;
      const { model } = await cdp.send('DOM.getBoxModel', { backendNodeId });
      const { node } = await cdp.send('DOM.describeNode', { backendNodeId });
      const attrs = node.attributes ?? [];
      const at = attrs.indexOf('id');
      const [x0, y0, x1, , , y2] = model.border;
      out.push({ el: at >= 0 ? attrs[at + 1] : `backend${backendNodeId}`, x: x0, y: y0, width: x1 - x0, height: y2 - y0 });
    } catch {
      out.push(null);
    }
  }
  await cdp.detach();
  return out;
}
