import React, { useMemo, useState } from 'react';

// Blocks whose name or doc contain the text and that have an input / output of the given types.
export function matchBlocks(blocks, { text = '', input = '', output = '' }) {
  const t = text.trim().toLowerCase();
  return blocks.filter((b) => (!t || b.type.toLowerCase().includes(t) || (b.doc || '').toLowerCase().includes(t))
    && (!input || b.inputs.some((p) => p.type === input))
    && (!output || b.outputs.some((p) => p.type === output)))
    .sort((a, b) => a.type.localeCompare(b.type, 'en', { sensitivity: 'base' }));
}

export function allTypes(blocks, side) {
  return [...new Set(blocks.flatMap((b) => b[side].map((p) => p.type)))].sort();
}

const shortType = (type) => type.replace(/^imagenets\//, '');

// How the browser lists the blocks (paper 3.2: "sorted by category, alphabetically, by input and
// output data type"): each returns [group name, blocks] in order. Under a data type a block is
// listed once for each type it takes (or gives).
const ORDERS = {
  category: { label: 'category', groups: (list) => groupBy(list, (b) => [b.category]) },
  // By the name shown (imagenets/ left out), so that imagenets_test/StampProbe files under I.
  name: { label: 'A-Z', groups: (list) => groupBy([...list].sort((a, b) => shortType(a.type).localeCompare(shortType(b.type), 'en', { sensitivity: 'base' })),
    (b) => [shortType(b.type)[0].toUpperCase()]) },
  input: { label: 'input type', groups: (list) => groupBy(list, (b) => portTypes(b.inputs, 'no inputs')) },
  output: { label: 'output type', groups: (list) => groupBy(list, (b) => portTypes(b.outputs, 'no outputs')) },
};

function portTypes(ports, none) {
  return ports.length ? [...new Set(ports.map((p) => p.type))] : [none];
}

// Groups in name order ("no ..." last), blocks in each by name; `list` is sorted by name already.
function groupBy(list, keys) {
  const map = new Map();
  for (const b of list) {
    for (const key of keys(b)) {
      if (!map.has(key)) map.set(key, []);
      map.get(key).push(b);
    }
  }
  const rank = (key) => (key.startsWith('no ') ? 1 : 0);
  // Code-point order keeps a package's types together (imagenets/... before imagenets_calibration_msgs/...).
  return [...map.entries()].sort(([a], [b]) => rank(a) - rank(b) || (a < b ? -1 : a > b ? 1 : 0));
}

// The block browser (paper 3.2): grouped by category, name or data type, with search and type
// filters; drag an entry onto the canvas.
export function BlockBrowser({ registry, onStartDrag }) {
  const [filter, setFilter] = useState({ text: '', input: '', output: '' });
  const [order, setOrder] = useState('category');
  const [open, setOpen] = useState(null);
  const blocks = registry.blocks;
  const groups = useMemo(() => ORDERS[order].groups(matchBlocks(blocks, filter)), [blocks, filter, order]);
  const select = (side, label) => (
    <select data-testid={`filter-${side}`} value={filter[side]} title={`only blocks with an ${label} of this type`}
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
      <label className="browser-order" title="how the blocks are listed">sort by{' '}
        <select data-testid="browser-sort" value={order} onChange={(e) => setOrder(e.target.value)}>
          {Object.entries(ORDERS).map(([key, o]) => <option key={key} value={key}>{o.label}</option>)}
        </select>
      </label>
      <div className="block-list">
        {groups.map(([group, list]) => (
          <div key={group} className="category" data-group={group}>
            <div className="category-name">{group}</div>
            {list.map((b) => (
              <div key={b.type} className="block-entry" data-type={b.type}>
                <div className="entry-name" title="drag onto the canvas; click for details"
                  onMouseDown={(e) => onStartDrag(b.type, e, () => setOpen(open === `${group}|${b.type}` ? null : `${group}|${b.type}`))}>
                  {shortType(b.type)}
                </div>
                {open === `${group}|${b.type}` && <BlockDoc block={b} colors={registry.types} />}
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
