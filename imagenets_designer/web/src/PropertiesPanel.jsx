import React, { useEffect, useRef, useState } from 'react';
import { FileDialog } from './Dialogs.jsx';

// The selected block's properties with typed editors; the engine checks every value (paper 3.2).
export function PropertiesPanel({ block, entry, net, request, onRename }) {
  const [errors, setErrors] = useState({});
  useEffect(() => setErrors({}), [block.name]);
  const set = async (property, text) => {
    try {
      await request('set_property', { block: block.name, property, text: String(text) });
      setErrors((e) => ({ ...e, [property]: null }));
    } catch (err) {
      setErrors((e) => ({ ...e, [property]: err.message }));
    }
  };
  return (
    <div className="properties-panel" data-block={block.name}>
      <div className="panel-head">
        <input className="rename" defaultValue={block.name} key={block.name} title="block name"
          onKeyDown={(e) => { if (e.key === 'Enter') onRename(block.name, e.target.value); }} />
        <div className="block-type-full">{block.type}</div>
        {entry && <p className="doc">{entry.doc}</p>}
      </div>
      {(entry?.properties || []).map((p) => (
        <div key={p.name} className="property" data-property={p.name}>
          <label title={p.doc}>{p.name} <i>{p.kind}</i></label>
          <PropertyEditor prop={p} key={`${block.name}.${p.name}`}
            text={block.properties[p.name] ?? String(p.default ?? '')} onCommit={(t) => set(p.name, t)} request={request} />
          {errors[p.name] && <div className="error" data-testid="property-error">{errors[p.name]}</div>}
          <div className="doc">{p.doc}</div>
          {(p.kind === 'int' || p.kind === 'double') &&
            <FeedbackEditor block={block} prop={p} net={net} request={request} />}
        </div>
      ))}
    </div>
  );
}

function PropertyEditor({ prop, text, onCommit, request }) {
  const [draft, setDraft] = useState(text);
  const [browsing, setBrowsing] = useState(false);
  const committed = useRef(text); // Enter then blur must not send the same value twice
  const wanted = useRef(null); // the newest value not sent yet
  const sending = useRef(false);
  const dragging = useRef(false);
  // A value set elsewhere (undo, another tab, the net's own state after a change) is shown, except
  // under the user's hand on the slider.
  useEffect(() => {
    if (dragging.current) return;
    committed.current = text;
    setDraft(text);
  }, [text]);
  // One change in flight at a time; while it runs, newer values replace each other, so a slider
  // dragged faster than the net runs sends only the newest value next, never a queue of stale ones.
  const commit = async (value = draft) => {
    wanted.current = String(value);
    if (sending.current) return;
    sending.current = true;
    while (wanted.current !== null && wanted.current !== committed.current) {
      const next = wanted.current;
      committed.current = next;
      await onCommit(next);
    }
    wanted.current = null;
    sending.current = false;
  };
  const onKey = (e) => { if (e.key === 'Enter') commit(e.target.value); };
  if (prop.kind === 'bool') {
    return <input type="checkbox" checked={text === 'true'} onChange={(e) => onCommit(e.target.checked)} />;
  }
  if (prop.kind === 'enum') {
    return (
      <select value={text} onChange={(e) => onCommit(e.target.value)}>
        {(prop.choices || []).map((c) => <option key={c} value={c}>{c}</option>)}
      </select>
    );
  }
  const numeric = prop.kind === 'int' || prop.kind === 'double';
  const ranged = numeric && prop.min !== undefined && prop.max !== undefined;
  const step = prop.kind === 'int' ? 1 : ranged ? (prop.max - prop.min) / 1000 : 'any';
  return (
    <div className="editor">
      {ranged && <input type="range" min={prop.min} max={prop.max} step={step} value={draft}
        data-testid={`slider-${prop.name}`}
        onPointerDown={() => {
          dragging.current = true;
          window.addEventListener('pointerup', () => { dragging.current = false; }, { once: true });
        }}
        onChange={(e) => { setDraft(e.target.value); commit(e.target.value); }}
        onKeyUp={(e) => commit(e.target.value)} />}
      <input type="text" className={numeric ? 'number' : prop.path ? 'path' : 'text'} value={draft}
        data-testid={`property-${prop.name}`} placeholder={prop.path ? 'file path' : ''}
        onChange={(e) => setDraft(e.target.value)} onKeyDown={onKey} onBlur={() => commit()} />
      {prop.path && <button title="choose a file" onClick={() => setBrowsing(true)}>…</button>}
      {browsing && <FileDialog title="Choose" initialPath={text} request={request}
        onDone={async (path) => commit(path)} onClose={() => setBrowsing(false)} />}
    </div>
  );
}

// The outputs of type std_msgs/Float64 on the block itself and downstream of it.
export function downstreamScores(net, blockName) {
  const seen = new Set([blockName]);
  const queue = [blockName];
  while (queue.length) {
    const name = queue.shift();
    for (const l of net.links) {
      const [from] = l.from.split('.');
      const [to] = l.to.split('.');
      if (from === name && !seen.has(to)) { seen.add(to); queue.push(to); }
    }
  }
  return net.blocks.filter((b) => seen.has(b.name))
    .flatMap((b) => b.outputs.filter((p) => p.type === 'std_msgs/Float64').map((p) => `${b.name}.${p.name}`));
}

// Feedback (paper 3.4) on one numeric property, with the net file's own keys.
function FeedbackEditor({ block, prop, net, request }) {
  const current = block.feedback && block.feedback.property === prop.name ? block.feedback : null;
  const scores = downstreamScores(net, block.name);
  const initial = () => current || { property: prop.name, from: prop.min ?? 0, to: prop.max ?? 10,
    step: prop.kind === 'int' ? 1 : ((prop.max ?? 10) - (prop.min ?? 0)) / 20, score: scores[0] || '',
    goal: 'maximize', search: 'exhaustive', parallel: true };
  const [fb, setFb] = useState(initial);
  const [on, setOn] = useState(!!current);
  const [error, setError] = useState(null);
  useEffect(() => { setFb(initial()); setOn(!!current); }, [JSON.stringify(current)]);
  const apply = async (feedback) => {
    try {
      await request('set_feedback', { block: block.name, feedback });
      setError(null);
    } catch (err) { setError(err.message); }
  };
  const useValues = Array.isArray(fb.values);
  const field = (key, label = key) => (
    <label>{label} <input type="text" data-testid={`feedback-${key}`} value={fb[key] ?? ''}
      onChange={(e) => setFb({ ...fb, [key]: e.target.value })} /></label>
  );
  const number = (v) => (v === '' || isNaN(Number(v)) ? v : Number(v));
  const toSend = () => {
    const out = { ...fb };
    for (const k of ['from', 'to', 'step']) if (k in out) out[k] = number(out[k]);
    if (useValues) { delete out.from; delete out.to; delete out.step; }
    return out;
  };
  return (
    <div className="feedback-editor">
      <label><input type="checkbox" data-testid="feedback-on" checked={on}
        onChange={(e) => { setOn(e.target.checked); if (!e.target.checked && current) apply(null); }} />
        feedback</label>
      {on && <div className="feedback-fields">
        <label className="wide check"><input type="checkbox" checked={useValues}
          onChange={(e) => setFb(e.target.checked ? { ...fb, values: [fb.from, fb.to] } : (({ values, ...rest }) => rest)(fb))} />
          list of values</label>
        {useValues
          ? <label className="wide">values <input type="text" value={fb.values.join(', ')}
            onChange={(e) => setFb({ ...fb, values: e.target.value.split(',').map((s) => number(s.trim())) })} /></label>
          : <>{field('from')}{field('to')}{field('step')}</>}
        <label className="wide">score <select data-testid="feedback-score" value={fb.score}
          onChange={(e) => setFb({ ...fb, score: e.target.value })}>
          {!scores.includes(fb.score) && <option value={fb.score}>{fb.score || '(no Float64 port downstream)'}</option>}
          {scores.map((s) => <option key={s} value={s}>{s}</option>)}
        </select></label>
        <label>goal <select value={fb.goal} onChange={(e) => setFb({ ...fb, goal: e.target.value })}>
          <option>maximize</option><option>minimize</option></select></label>
        <label>search <select value={fb.search} onChange={(e) => setFb({ ...fb, search: e.target.value })}>
          <option>exhaustive</option><option>coarse_to_fine</option></select></label>
        <label className="check"><input type="checkbox" checked={!!fb.parallel}
          onChange={(e) => setFb({ ...fb, parallel: e.target.checked })} /> parallel</label>
        <button className="wide" data-testid="feedback-apply" onClick={() => apply(toSend())}>apply feedback</button>
        {error && <div className="error wide" data-testid="feedback-error">{error}</div>}
      </div>}
    </div>
  );
}
