import React, { useEffect, useRef, useState } from 'react';

// A window over the page that leaves the rest of it usable (no backdrop): moved by its title bar,
// resized by its corner, closed by ✕ or Escape (unless a field has the focus, where Escape belongs
// to the field). `children` is a function of the body's size in pixels.
export function FloatingWindow({ title, onClose, initial, min = { width: 320, height: 240 }, testid, children }) {
  const [box, setBox] = useState(() => fitScreen(initial));
  const gesture = useRef(null);
  useEffect(() => {
    const key = (e) => {
      if (e.key === 'Escape' && !['INPUT', 'TEXTAREA', 'SELECT'].includes(e.target.tagName)) onClose();
    };
    window.addEventListener('keydown', key);
    return () => window.removeEventListener('keydown', key);
  }, [onClose]);

  // Moving and resizing follow the pointer anywhere on the page until it is released.
  const start = (kind) => (e) => {
    if (e.button !== 0 || e.target.closest('button')) return;
    e.preventDefault();
    gesture.current = { kind, x: e.clientX, y: e.clientY, box };
    const move = (m) => {
      const g = gesture.current;
      const dx = m.clientX - g.x, dy = m.clientY - g.y;
      setBox(g.kind === 'move'
        ? { ...g.box, x: clamp(g.box.x + dx, 0, window.innerWidth - 80), y: clamp(g.box.y + dy, 0, window.innerHeight - 30) }
        : { ...g.box, width: Math.max(min.width, g.box.width + dx), height: Math.max(min.height, g.box.height + dy) });
    };
    const up = () => {
      window.removeEventListener('pointermove', move);
      window.removeEventListener('pointerup', up);
      gesture.current = null;
    };
    window.addEventListener('pointermove', move);
    window.addEventListener('pointerup', up);
  };

  const titleHeight = 30, padding = 8;
  const body = { width: box.width - 2 * padding, height: box.height - titleHeight - 2 * padding };
  return (
    <div className="floating-window" data-testid={testid}
      style={{ left: box.x, top: box.y, width: box.width, height: box.height }}>
      <div className="window-title" data-testid={testid && `${testid}-title`} onPointerDown={start('move')}
        style={{ height: titleHeight }}>
        <span className="window-title-text">{title}</span>
        <button className="close" title="close (Esc)" onClick={onClose}>✕</button>
      </div>
      <div className="window-body" style={{ padding }}>{children(body)}</div>
      <div className="window-resize" data-testid={testid && `${testid}-resize`} title="drag to resize"
        onPointerDown={start('resize')} />
    </div>
  );
}

function clamp(v, lo, hi) {
  return Math.min(Math.max(v, lo), Math.max(lo, hi));
}

// The window inside the page, smaller if the page is.
function fitScreen({ x, y, width, height }) {
  const w = Math.min(width, window.innerWidth - 20), h = Math.min(height, window.innerHeight - 20);
  return { x: clamp(x, 0, window.innerWidth - w), y: clamp(y, 0, window.innerHeight - h), width: w, height: h };
}
