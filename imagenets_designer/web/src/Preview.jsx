import React, { useLayoutEffect, useRef } from 'react';

// What a watched output shows on its node (paper Fig. 3.3): thumbnails, numbers, frames, traces.
export function Preview({ port, data }) {
  const { header, value } = data;
  const revision = header.run ?? header.revision;
  if (header.format === 'none') {
    return <div className="preview-value none" data-revision={revision}>no value{header.error ? `: ${header.error}` : ''}</div>;
  }
  if (data.bitmap) return <Thumbnail port={port} bitmap={data.bitmap} revision={revision} />;
  const shown = (element) => <div className="preview-value" ref={(e) => e && noteShown(port, revision)}
    data-revision={revision}>{element}</div>;
  if (header.format === 'xyzrgb') return shown(`${Math.floor(data.payload.byteLength / 16)} points`);
  if (value && Array.isArray(value.scores)) return shown(<TracePlot trace={value} />);
  if (value && typeof value.data === 'number') return shown(<b>{round(value.data)}</b>);
  if (value && value.xyz) {
    return shown(<>xyz {value.xyz.map(round).join(' ')}<br />rpy {(value.rpy || []).map(round).join(' ')}</>);
  }
  if (value && Array.isArray(value.poses)) return shown(`${value.poses.length} poses`);
  if (value && Array.isArray(value.markers)) return shown(`${value.markers.length} markers`);
  return shown(<pre>{summary(value)}</pre>);
}

function Thumbnail({ port, bitmap, revision }) {
  const canvas = useRef(null);
  useLayoutEffect(() => {
    canvas.current.getContext('2d').drawImage(bitmap, 0, 0);
    noteShown(port, revision);
  }, [bitmap]);
  return <canvas ref={canvas} className="preview-image" width={bitmap.width} height={bitmap.height}
    data-revision={revision} title={port} />;
}

function round(v) {
  return typeof v === 'number' ? (Math.abs(v) >= 100 ? v.toFixed(1) : v.toFixed(3)) : String(v);
}

function precise(v) {
  return typeof v === 'number' ? String(Number(v.toPrecision(4))) : String(v);
}

function summary(value) {
  const text = JSON.stringify(value, (k, v) => (typeof v === 'number' ? Number(round(v)) : v), 1) || '';
  return text.length > 240 ? `${text.slice(0, 240)}…` : text;
}

// The browser benchmark and tests read when a preview of a given revision was put on screen.
function noteShown(port, revision) {
  const shown = (window.designerShown ||= []);
  shown.push({ port, revision, time: performance.now() });
  if (shown.length > 1000) shown.splice(0, shown.length - 1000);
}

// Feedback trace: score over the tried values, the chosen value marked.
export function TracePlot({ trace, width = 240, height = 130 }) {
  const xs = trace.values || [], ys = trace.scores || [];
  const pad = 22;
  const finite = ys.filter(Number.isFinite);
  const [x0, x1] = [Math.min(...xs), Math.max(...xs)];
  // The scores' own range (a nearly flat curve still shows its maximum), 5% margin.
  const [lo, hi] = finite.length ? [Math.min(...finite), Math.max(...finite)] : [0, 1];
  const margin = (hi - lo) * 0.05 || Math.abs(hi) * 0.05 || 0.5;
  const [y0, y1] = [lo - margin, hi + margin];
  const sx = (x) => pad + ((x - x0) / ((x1 - x0) || 1)) * (width - pad - 6);
  const sy = (y) => height - pad + 4 - ((y - y0) / ((y1 - y0) || 1)) * (height - pad - 6);
  const points = xs.map((x, i) => (Number.isFinite(ys[i]) ? `${sx(x)},${sy(ys[i])}` : null)).filter(Boolean);
  const chosen = trace.chosen_value;
  return (
    <svg className="trace-plot" data-testid="trace-plot" width={width} height={height}>
      <rect x={pad} y={2} width={width - pad - 4} height={height - pad} className="plot-frame" />
      <polyline points={points.join(' ')} className="plot-line" />
      {xs.map((x, i) => Number.isFinite(ys[i]) && <circle key={i} cx={sx(x)} cy={sy(ys[i])} r={1.6} className="plot-dot" />)}
      {Number.isFinite(chosen) && <line x1={sx(chosen)} x2={sx(chosen)} y1={2} y2={height - pad + 2} className="plot-chosen" />}
      <text x={pad} y={height - 8} className="plot-label">{round(x0)}</text>
      <text x={width - 6} y={height - 8} textAnchor="end" className="plot-label">{round(x1)}</text>
      <text x={2} y={10} className="plot-label">{precise(hi)}</text>
      <text x={2} y={height - pad} className="plot-label">{precise(lo)}</text>
      {Number.isFinite(chosen) && <text x={sx(chosen) + (sx(chosen) > width / 2 ? -3 : 3)} y={height - pad - 4}
        textAnchor={sx(chosen) > width / 2 ? 'end' : 'start'} className="plot-chosen-label">
        {round(chosen)} → {precise(trace.chosen_score)}</text>}
    </svg>
  );
}
