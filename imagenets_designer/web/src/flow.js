import { layeredLayout } from './layout.js';

// The handle on a block with feedback where the edge from its score arrives.
export const FEEDBACK_HANDLE = 'feedback';
export const FEEDBACK_COLOR = '#c58af9';

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
    return { id, source, sourceHandle, target, targetHandle, selected: selectedEdges.has(id), data: l, reconnectable: false,
      style: { stroke: colors[l.type] || '#888', strokeWidth: 2.5 } };
  });
  // Feedback (paper Fig. 3.3) as `imagenets graph` draws it: a dashed edge from the score port to
  // the tuned block. Its score end can be dragged onto another score port.
  for (const b of net.blocks) {
    if (!b.feedback?.score) continue;
    const [source, sourceHandle] = split(b.feedback.score);
    if (!net.blocks.some((x) => x.name === source)) continue;
    const id = feedbackEdgeId(b.name);
    edges.push({ id, source, sourceHandle, target: b.name, targetHandle: FEEDBACK_HANDLE, type: 'feedback',
      selected: selectedEdges.has(id), reconnectable: 'source', zIndex: 1,
      data: { feedback: b.feedback, block: b.name } });
  }
  return { nodes, edges };
}

export function feedbackEdgeId(block) {
  return `feedback:${block}`;
}

export function split(portKey) {
  const dot = portKey.lastIndexOf('.');
  return [portKey.slice(0, dot), portKey.slice(dot + 1)];
}
