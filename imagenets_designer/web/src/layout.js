// Automatic layout: columns by longest path from the sources, rows in net-file order. With the
// nodes' measured sizes (previews make them tall) columns and rows are spaced to fit; without,
// a default size is assumed. Returns {name: [x, y]}.
export function layeredLayout(blocks, links, sizes = {}, gap = { x: 80, y: 40 }) {
  const layer = new Map(blocks.map((b) => [b.name, 0]));
  // Longest path by relaxation; nets are acyclic, so |blocks| rounds suffice.
  for (let round = 0; round < blocks.length; ++round) {
    let changed = false;
    for (const l of links) {
      const from = l.from.split('.')[0], to = l.to.split('.')[0];
      if (layer.has(from) && layer.has(to) && layer.get(to) < layer.get(from) + 1) {
        layer.set(to, layer.get(from) + 1);
        changed = true;
      }
    }
    if (!changed) break;
  }
  const size = (name) => sizes[name] || { width: 220, height: 160 };
  const columns = [];
  for (const b of blocks) (columns[layer.get(b.name)] ||= []).push(b.name);
  const positions = {};
  let x = 0;
  for (const column of columns.filter(Boolean)) {
    let y = 0;
    for (const name of column) {
      positions[name] = [x, y];
      y += size(name).height + gap.y;
    }
    x += Math.max(...column.map((name) => size(name).width)) + gap.x;
  }
  return positions;
}
