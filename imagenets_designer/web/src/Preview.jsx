import React, { useLayoutEffect, useRef } from 'react';

// What a watched output shows on its node (paper Fig. 3.3): thumbnails, numbers, frames, traces.
export function Preview({ port, data }) {
  const { header, value } = data;
  const revision = header.run ?? header.revision;
  if (header.format === 'none') {
    return <div className="preview-value none" data-revision={revision}>no value{header.error ? `: ${header.error}` : ''}</div>;
  }
  if (data.image) return <Thumbnail port={port} image={data.image} revision={revision} />;
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

// The thumbnails on the page by port: a new preview of the same size is drawn straight onto them
// when it arrives (drawNow), before the page re-renders.
const thumbnails = new Map();

function Thumbnail({ port, image, revision }) {
  const canvas = useRef(null);
  useLayoutEffect(() => {
    const c = canvas.current;
    if (c.drawn !== image) {
      c.getContext('2d').putImageData(image, 0, 0);
      c.drawn = image;
      noteShown(port, revision);
    }
  }, [image]);
  useLayoutEffect(() => {
    const c = canvas.current;
    if (!thumbnails.has(port)) thumbnails.set(port, new Set());
    thumbnails.get(port).add(c);
    return () => thumbnails.get(port)?.delete(c);
  }, [port]);
  return <canvas ref={canvas} className="preview-image" width={image.width} height={image.height}
    data-revision={revision} title={port} />;
}

// A thumbnail frame's pixels (gray, or blue-green-red; PROTOCOL.md) as RGBA for a canvas.
export function thumbnailImage(header, payload) {
  const { preview_width: width, preview_height: height, channels } = header;
  const image = new ImageData(width, height);
  const out = image.data;
  for (let i = 0, o = 0; o < out.length; i += channels, o += 4) {
    out[o] = payload[i + (channels === 3 ? 2 : 0)];
    out[o + 1] = payload[i + (channels === 3 ? 1 : 0)];
    out[o + 2] = payload[i];
    out[o + 3] = 255;
  }
  return image;
}

// Draws a preview onto the port's thumbnails of its size; false when there is none (the page's
// next render shows it).
export function drawNow(port, image, revision) {
  let drawn = false;
  for (const c of thumbnails.get(port) || []) {
    if (c.width !== image.width || c.height !== image.height) continue;
    c.getContext('2d').putImageData(image, 0, 0);
    c.drawn = image;
    c.dataset.revision = revision;
    drawn = true;
  }
  if (drawn) noteShown(port, revision);
  return drawn;
}

function round(v) {
  return typeof v === 'number' ? (Math.abs(v) >= 100 ? v.toFixed(1) : v.toFixed(3)) : String(v);
}

// A number as short as it can be while saying what it is: integers as integers ("40", not
// "40.000"), others to 4 significant digits.
export function short(v) {
  if (typeof v !== 'number') return String(v);
  return Number.isInteger(v) ? String(v) : String(Number(v.toPrecision(4)));
}

// The two ends of an axis, with as many digits as it takes to tell them apart (0.99268 / 0.99274,
// not 0.9927 twice); one label when both ends are the same value.
export function axisEnds(lo, hi) {
  if (lo === hi) return [short(lo)];
  for (let digits = 4; digits <= 15; ++digits) {
    const a = Number.isInteger(lo) ? String(lo) : String(Number(lo.toPrecision(digits)));
    const b = Number.isInteger(hi) ? String(hi) : String(Number(hi.toPrecision(digits)));
    if (a !== b) return [a, b];
  }
  return [String(lo), String(hi)];
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

// Feedback trace: score over the tried values, the chosen value marked; the x axis is the tuned
// property, the y axis the score.
export function TracePlot({ trace, width = 240, height = 130 }) {
  const xs = trace.values || [], ys = trace.scores || [];
  const finite = ys.filter(Number.isFinite);
  const [x0, x1] = xs.length ? [Math.min(...xs), Math.max(...xs)] : [0, 1];
  // The scores' own range (a nearly flat curve still shows its maximum), 5% margin.
  const [lo, hi] = finite.length ? [Math.min(...finite), Math.max(...finite)] : [0, 1];
  const xEnds = axisEnds(x0, x1), yEnds = axisEnds(lo, hi);
  // Room on the left for the longer score label (about 5.5 px a character at the labels' size).
  const pad = { left: Math.max(24, 6 + 5.5 * Math.max(...yEnds.map((t) => t.length))), bottom: 24 };
  const margin = (hi - lo) * 0.05 || Math.abs(hi) * 0.05 || 0.5;
  const [y0, y1] = [lo - margin, hi + margin];
  const plotW = width - pad.left - 6, plotH = height - pad.bottom - 6;
  // A single tried value sits in the middle of its axis.
  const sx = (x) => pad.left + (x1 > x0 ? ((x - x0) / (x1 - x0)) * plotW : plotW / 2);
  const sy = (y) => 4 + plotH - ((y - y0) / ((y1 - y0) || 1)) * plotH;
  const points = xs.map((x, i) => (Number.isFinite(ys[i]) ? `${sx(x)},${sy(ys[i])}` : null)).filter(Boolean);
  const chosen = trace.chosen_value;
  const right = sx(chosen) > pad.left + plotW / 2;
  return (
    <svg className="trace-plot" data-testid="trace-plot" width={width} height={height}>
      <rect x={pad.left} y={2} width={plotW} height={plotH + 4} className="plot-frame" />
      <polyline points={points.join(' ')} className="plot-line" />
      {xs.map((x, i) => Number.isFinite(ys[i]) && <circle key={i} cx={sx(x)} cy={sy(ys[i])} r={1.6} className="plot-dot" />)}
      {Number.isFinite(chosen) && <line x1={sx(chosen)} x2={sx(chosen)} y1={2} y2={plotH + 6} className="plot-chosen" />}
      {xEnds.length === 1
        ? <text x={sx(x0)} y={height - 12} textAnchor="middle" className="plot-label x-label">{xEnds[0]}</text>
        : <>
          <text x={pad.left} y={height - 12} className="plot-label x-label">{xEnds[0]}</text>
          <text x={width - 6} y={height - 12} textAnchor="end" className="plot-label x-label">{xEnds[1]}</text>
        </>}
      <text x={pad.left + plotW / 2} y={height - 2} textAnchor="middle" className="plot-axis">{trace.property}</text>
      {yEnds.length === 1
        ? <text x={pad.left - 3} y={sy(lo) + 3} textAnchor="end" className="plot-label y-label">{yEnds[0]}</text>
        : <>
          <text x={pad.left - 3} y={sy(hi) + 3} textAnchor="end" className="plot-label y-label">{yEnds[1]}</text>
          <text x={pad.left - 3} y={sy(lo) + 3} textAnchor="end" className="plot-label y-label">{yEnds[0]}</text>
        </>}
      {Number.isFinite(chosen) && <text x={sx(chosen) + (right ? -3 : 3)} y={12}
        textAnchor={right ? 'end' : 'start'} className="plot-chosen-label">
        {short(chosen)} → {short(trace.chosen_score)}</text>}
    </svg>
  );
}
