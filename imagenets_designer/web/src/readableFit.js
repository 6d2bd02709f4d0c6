// Fitting the net into the canvas without making its text unreadable. The nodes' smallest text is
// 12 px; below READABLE_ZOOM it would be under 10 px on screen (a 65 % fit gave about 7 px).
export const READABLE_ZOOM = 0.85;

// The viewport {x, y, zoom} that shows `bounds` (flow coordinates) in a canvas of width x height:
// the whole net when it fits at a readable zoom (centred, never above 100 %), else the readable
// zoom with the net's top-left corner in view, where its sources are; the rest is a pan away.
export function readableViewport(bounds, width, height, padding = 24) {
  const fit = Math.min((width - 2 * padding) / Math.max(bounds.width, 1), (height - 2 * padding) / Math.max(bounds.height, 1));
  const zoom = Math.min(1, Math.max(READABLE_ZOOM, fit));
  const place = (start, extent, room) => (extent * zoom <= room - 2 * padding
    ? (room - extent * zoom) / 2 - start * zoom
    : padding - start * zoom);
  return { x: place(bounds.x, bounds.width, width), y: place(bounds.y, bounds.height, height), zoom };
}
