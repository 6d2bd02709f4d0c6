// Automatic layout for nets without positions: columns by longest path from the sources,
// rows in net-file order. Returns {name: [x, y]}.
export function layeredLayout(blocks, links, spacing = { x: 300, y: 200 }) {
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
  const rows = new Map();
  const positions = {};
  for (const b of blocks) {
    const column = layer.get(b.name);
    const row = rows.get(column) || 0;
    rows.set(column, row + 1);
    positions[b.name] = [column * spacing.x, row * spacing.y];
  }
  return positions;
}
