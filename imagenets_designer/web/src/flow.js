import { layeredLayout } from './layout.js';

// Canvas nodes and edges from the server's net state; positions and selection kept locally.
export function flowFromNet(net, colors, oldNodes = [], oldEdges = []) {
  const old = new Map(oldNodes.map((n) => [n.id, n]));
  const layout = net.blocks.some((b) => !b.position && !old.has(b.name)) ? layeredLayout(net.blocks, net.links) : {};
  const nodes = net.blocks.map((b) => {
    const kept = old.get(b.name);
    const p = b.position || (kept && [kept.position.x, kept.position.y]) || layout[b.name];
    // An unchanged node stays the same object: the canvas keeps its measured state (and a link
    // being dragged meanwhile keeps its handles).
    if (kept && kept.position.x === p[0] && kept.position.y === p[1]) return kept;
    return { ...(kept || {}), id: b.name, type: 'block', position: { x: p[0], y: p[1] }, data: kept?.data || {} };
  });
  const selectedEdges = new Set(oldEdges.filter((e) => e.selected).map((e) => e.id));
  const edges = net.links.map((l) => {
    const [source, sourceHandle] = split(l.from);
    const [target, targetHandle] = split(l.to);
    const id = `${l.from}->${l.to}`;
    return { id, source, sourceHandle, target, targetHandle, selected: selectedEdges.has(id), data: l,
      style: { stroke: colors[l.type] || '#888', strokeWidth: 2.5 } };
  });
  return { nodes, edges };
}

export function split(portKey) {
  const dot = portKey.lastIndexOf('.');
  return [portKey.slice(0, dot), portKey.slice(dot + 1)];
}

