import React, { useEffect, useRef, useState } from 'react';
import { pixelValues, toImageData } from './rawImage.js';

// A raw image with wheel zoom (to single pixels), drag to pan, and the pixel under the cursor.
export function ImageView({ header, payload, width = 800, height = 560 }) {
  const canvas = useRef(null);
  const bitmap = useRef(null);
  const [view, setView] = useState(null); // {scale, x, y}: screen = image * scale + offset
  const [cursor, setCursor] = useState(null);
  const drag = useRef(null);

  useEffect(() => {
    const image = document.createElement('canvas');
    image.width = header.width;
    image.height = header.height;
    image.getContext('2d').putImageData(toImageData(header, payload), 0, 0);
    bitmap.current = image;
    const c = canvas.current;
    setView((old) => old && old.width === header.width && old.height === header.height ? { ...old }
      : fit(c, header));
  }, [header, payload]);

  useEffect(() => {
    const c = canvas.current;
    if (!view || !bitmap.current) return;
    const g = c.getContext('2d');
    g.setTransform(1, 0, 0, 1, 0, 0);
    g.fillStyle = '#202020';
    g.fillRect(0, 0, c.width, c.height);
    g.imageSmoothingEnabled = false;
    g.setTransform(view.scale, 0, 0, view.scale, view.x, view.y);
    g.drawImage(bitmap.current, 0, 0);
  }, [view, width, height]);  // a new canvas size clears the canvas

  const toImage = (e) => {
    const r = canvas.current.getBoundingClientRect();
    return [(e.clientX - r.left - view.x) / view.scale, (e.clientY - r.top - view.y) / view.scale];
  };
  const onWheel = (e) => {
    const r = canvas.current.getBoundingClientRect();
    const sx = e.clientX - r.left, sy = e.clientY - r.top;
    const factor = e.deltaY < 0 ? 1.25 : 0.8;
    const scale = Math.min(64, Math.max(0.05, view.scale * factor));
    const k = scale / view.scale;
    setView({ ...view, scale, x: sx - (sx - view.x) * k, y: sy - (sy - view.y) * k });
  };
  const onMove = (e) => {
    if (drag.current) {
      setView({ ...view, x: drag.current.x + e.clientX - drag.current.cx, y: drag.current.y + e.clientY - drag.current.cy });
    }
    const [ix, iy] = toImage(e).map(Math.floor);
    if (ix >= 0 && iy >= 0 && ix < header.width && iy < header.height) {
      setCursor({ x: ix, y: iy, values: pixelValues(header, payload, ix, iy) });
    } else {
      setCursor(null);
    }
  };
  const format = (v) => Number.isInteger(v) ? String(v) : v.toFixed(3);
  return (
    <div className="image-view">
      <canvas ref={canvas} width={Math.max(1, Math.floor(width))} height={Math.max(1, Math.floor(height))} className="image-canvas"
        data-scale={view?.scale} data-offset-x={view?.x} data-offset-y={view?.y}
        onWheel={onWheel} onMouseMove={onMove} onMouseLeave={() => { drag.current = null; setCursor(null); }}
        onMouseDown={(e) => { drag.current = { cx: e.clientX, cy: e.clientY, x: view.x, y: view.y }; }}
        onMouseUp={() => { drag.current = null; }} />
      <div className="pixel-readout" data-testid="pixel-readout">
        {header.width}x{header.height} {header.encoding} · zoom {view ? (view.scale * 100).toFixed(0) : 100}%
        {cursor && <> · x={cursor.x} y={cursor.y} value=<b>{cursor.values.map(format).join(', ')}</b></>}
      </div>
    </div>
  );
}

function fit(c, header) {
  const scale = Math.min(c.width / header.width, c.height / header.height);
  return { width: header.width, height: header.height, scale,
    x: (c.width - header.width * scale) / 2, y: (c.height - header.height * scale) / 2 };
}
