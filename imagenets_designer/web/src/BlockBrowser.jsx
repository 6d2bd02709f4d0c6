import React, { useMemo, useState } from 'react';

// Blocks whose name or doc contain the text and that have an input / output of the given types.
export function matchBlocks(blocks, { text = '', input = '', output = '' }) {
  const t = text.trim().toLowerCase();
  return blocks.filter((b) => (!t || b.type.toLowerCase().includes(t) || (b.doc || '').toLowerCase().includes(t))
    && (!input || b.inputs.some((p) => p.type === input))
    && (!output || b.outputs.some((p) => p.type === output)))
    .sort((a, b) => a.type.localeCompare(b.type));
}

export function allTypes(blocks, side) {
  return [...new Set(blocks.flatMap((b) => b[side].map((p) => p.type)))].sort();
}

// The block browser (paper 3.2): categories, search, type filters; drag an entry onto the canvas.
export function BlockBrowser({ registry, onStartDrag }) {
  const [filter, setFilter] = useState({ text: '', input: '', output: '' });
  const [open, setOpen] = useState(null);
  const blocks = registry.blocks;
  const groups = useMemo(() => {
    const map = new Map();
    for (const b of matchBlocks(blocks, filter)) {
      if (!map.has(b.category)) map.set(b.category, []);
      map.get(b.category).push(b);
    }
    return [...map.entries()].sort(([a], [b]) => a.localeCompare(b));
  }, [blocks, filter]);
  const select = (side, label) => (
    <select data-testid={`filter-${side}`} value={filter[side]} title={`${label} type`}
      onChange={(e) => setFilter({ ...filter, [side]: e.target.value })}>
      <option value="">any {label}</option>
      {allTypes(blocks, `${side}s`).map((t) => <option key={t} value={t}>{t}</option>)}
    </select>
  );
  return (
    <div className="block-browser">
      <input type="search" placeholder="search blocks" data-testid="block-search" value={filter.text}
        onChange={(e) => setFilter({ ...filter, text: e.target.value })} />
      {select('input', 'input')}
      {select('output', 'output')}
      <div className="block-list">
        {groups.map(([category, list]) => (
          <div key={category} className="category">
            <div className="category-name">{category}</div>
            {list.map((b) => (
              <div key={b.type} className="block-entry" data-type={b.type}>
                <div className="entry-name" title="drag onto the canvas; click for details"
                  onMouseDown={(e) => onStartDrag(b.type, e, () => setOpen(open === b.type ? null : b.type))}>
                  {b.type.replace(/^imagenets\//, '')}
                </div>
                {open === b.type && <BlockDoc block={b} colors={registry.types} />}
              </div>
            ))}
          </div>
        ))}
      </div>
    </div>
  );
}

export function BlockDoc({ block, colors }) {
  const port = (p) => (
    <li key={p.name}><span className="swatch" style={{ background: colors[p.type] }} />
      <b>{p.name}</b>{p.optional ? ' (optional)' : ''} <i>{p.type}</i> {p.doc}</li>
  );
  return (
    <div className="block-doc">
      <p>{block.doc}</p>
      {block.inputs.length > 0 && <><div className="doc-head">inputs</div><ul>{block.inputs.map(port)}</ul></>}
      {block.outputs.length > 0 && <><div className="doc-head">outputs</div><ul>{block.outputs.map(port)}</ul></>}
      {block.properties.length > 0 && <><div className="doc-head">properties</div><ul>
        {block.properties.map((p) => (
          <li key={p.name}><b>{p.name}</b> <i>{p.kind}</i> = {String(p.default)}
            {p.min !== undefined && ` [${p.min}..${p.max}]`} {p.doc}</li>
        ))}</ul></>}
    </div>
  );
}
