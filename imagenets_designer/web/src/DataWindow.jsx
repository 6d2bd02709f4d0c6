import React, { useMemo } from 'react';
import { FloatingWindow } from './FloatingWindow.jsx';
import { ImageView } from './ImageView.jsx';
import { Scene3D, is3D } from './Scene3D.jsx';
import { TracePlot } from './Preview.jsx';

// One output port shown large (paper Fig. 3.2): images to pixel level, 3D data orbitable. A window
// beside the canvas, not a dialog: it stays open while properties change and shows each new value
// as the run brings it.
export function DataWindow({ port, type, data, onClose }) {
  const items = useMemo(() => (data ? [data] : []), [data]);
  // Over the canvas's right half at first, clear of the block browser and the properties.
  const initial = useMemo(() => ({ x: Math.max(240, window.innerWidth - 350 - 700), y: 60, width: 700, height: 540 }), []);
  const body = (size) => {
    if (!data) return <div className="waiting" data-testid="data-waiting">waiting for a value of {port} (run the net)</div>;
    const { header, value } = data;
    if (header.format === 'none') return <div className="waiting">{port} has no value{header.error ? `: ${header.error}` : ''}</div>;
    if (header.format === 'raw') return <ImageView header={header} payload={data.payload} width={size.width} height={size.height - 26} />;
    if (is3D(header)) return <Scene3D items={items} width={size.width} height={size.height - 30} />;
    if (value && Array.isArray(value.scores)) return <TracePlot trace={value} width={size.width} height={size.height} />;
    return <pre className="data-json" style={{ maxHeight: size.height }}>{JSON.stringify(value, null, 2)}</pre>;
  };
  return (
    <FloatingWindow title={`${port} · ${type}${data ? ` · run ${data.header.run ?? data.header.revision}` : ''}`}
      onClose={onClose} initial={initial} testid="data-dialog">
      {body}
    </FloatingWindow>
  );
}
