import React, { memo } from 'react';
import { Handle, Position } from '@xyflow/react';
import { Preview } from './Preview.jsx';
import { FEEDBACK_COLOR, FEEDBACK_HANDLE } from './flow.js';

// One block on the canvas: ports coloured by type, status, wall and CPU time, preview boxes.
export const BlockNode = memo(function BlockNode({ data, selected }) {
  const { block, colors, running, cached, previews, watched, actions } = data;
  const stats = block.stats || {};
  const status = stats.status || 'pending';
  const classes = ['block-node', `status-${status.replace(' ', '-')}`];
  if (running) classes.push('running');
  if (selected) classes.push('selected');
  return (
    <div className={classes.join(' ')} data-block={block.name}>
      {block.feedback && <Handle type="target" position={Position.Top} id={FEEDBACK_HANDLE} className="feedback-handle"
        title={`feedback on ${block.feedback.property}: drop a std_msgs/Float64 output here to score by it`}
        style={{ background: FEEDBACK_COLOR }} />}
      <div className="block-title">
        <span className="block-name">{block.name}</span>
        <span className="block-type">{block.type.replace(/^imagenets\//, '')}</span>
        {block.has_subnet && <button className="small nodrag" title="open the sub-net"
          onClick={() => actions.openSubnet(block.name)}>⊞</button>}
      </div>
      <div className="block-status" data-testid="block-status">
        <span className="status-word">{running ? 'running' : status}</span>
        {cached && !running && <span className="cached">cached</span>}
        <span className="stats" data-runs={stats.runs ?? 0}>
          runs {stats.runs ?? 0} · {fmt(stats.last_ms)} / {fmt(stats.mean_ms)} ms
        </span>
        <span className="cpu" data-ms={stats.last_cpu_ms ?? 0}
          title="CPU time of the thread that ran the block: last / mean (work handed to other threads is not in it)">
          CPU {fmt(stats.last_cpu_ms)} / {fmt(stats.mean_cpu_ms)} ms
        </span>
        {block.feedback && <span className="feedback-tag" title="feedback">fb {block.feedback.property}</span>}
      </div>
      {stats.message && status !== 'ok' && <div className="block-message">{stats.message}</div>}
      <div className="ports">
        <div className="inputs">
          {block.inputs.map((p) => (
            // An optional port: hollow handle and a dimmed italic name (a '?' read like a digit).
            <div key={p.name} className={`port in ${p.optional ? 'optional' : ''}`}
              title={`${p.type}${p.optional ? ' (optional: the block runs without it)' : ''}${p.doc ? ` — ${p.doc}` : ''}`}>
              <Handle type="target" position={Position.Left} id={p.name}
                style={p.optional ? { background: 'transparent', borderColor: colors[p.type] || '#888' }
                  : { background: colors[p.type] || '#888' }} />
              <span className="port-name">{p.name}</span>
            </div>
          ))}
        </div>
        <div className="outputs">
          {block.outputs.map((p) => {
            const key = `${block.name}.${p.name}`;
            return (
              <div key={p.name} className="port out" title={`${p.type}${p.doc ? ` — ${p.doc}` : ''}`}>
                <button className={`small nodrag watch ${watched.has(key) ? 'on' : ''}`} title="preview on the node"
                  data-port={key} onClick={() => actions.toggleWatch(key)}>◉</button>
                <button className="small nodrag open-data" title="open the data dialog" data-port={key}
                  onClick={() => actions.openData(key, p.type)}>⤢</button>
                <span className="port-name">{p.name}</span>
                <Handle type="source" position={Position.Right} id={p.name}
                  style={{ background: colors[p.type] || '#888' }} />
              </div>
            );
          })}
        </div>
      </div>
      {[...watched].filter((k) => previews[k]).map((k) => (
        <div key={k} className="preview" data-port={k}>
          <div className="preview-port">{k.slice(block.name.length + 1)}</div>
          <Preview port={k} data={previews[k]} />
        </div>
      ))}
    </div>
  );
});

function fmt(ms) {
  return typeof ms === 'number' ? ms.toFixed(ms < 10 ? 2 : 1) : '–';
}
