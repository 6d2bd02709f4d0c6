import React, { useMemo } from 'react';
import { Modal } from './Dialogs.jsx';
import { ImageView } from './ImageView.jsx';
import { Scene3D, is3D } from './Scene3D.jsx';
import { TracePlot } from './Preview.jsx';

// One output port shown large (paper Fig. 3.2): images to pixel level, 3D data orbitable.
export function DataDialog({ port, type, data, onClose }) {
  const items = useMemo(() => (data ? [data] : []), [data]);
  let body = <div className="waiting" data-testid="data-waiting">waiting for a value of {port} (run the net)</div>;
  if (data) {
    const { header, value } = data;
    if (header.format === 'none') body = <div className="waiting">{port} has no value{header.error ? `: ${header.error}` : ''}</div>;
    else if (header.format === 'raw') body = <ImageView header={header} payload={data.payload} />;
    else if (is3D(header)) body = <Scene3D items={items} />;
    else if (value && Array.isArray(value.scores)) body = <TracePlot trace={value} width={760} height={400} />;
    else body = <pre className="data-json">{JSON.stringify(value, null, 2)}</pre>;
  }
  return (
    <Modal title={`${port} · ${type}${data ? ` · run ${data.header.run ?? data.header.revision}` : ''}`} onClose={onClose} wide
      testid="data-dialog">
      {body}
    </Modal>
  );
}
