import React, { useCallback } from 'react';
import { ExportDialog, FileDialog } from './Dialogs.jsx';
import { DataWindow } from './DataWindow.jsx';
import { SubnetView } from './SubnetView.jsx';
import { useCommands } from './commands.js';
import { useStore } from './store.jsx';

// What opens over the page: the dialogs, a port's data window, a sub-net, a block being dragged.
export function Overlays() {
  const { state, set, request, say } = useStore();
  const { net, registry, ghost, dataPort, fullData, subnet, dialog } = state;
  const { save } = useCommands();
  const closeData = useCallback(() => set({ dataPort: null }), [set]);
  const close = () => set({ dialog: null });
  return (
    <>
      {ghost && <div className="drag-ghost" style={{ left: ghost.x + 8, top: ghost.y + 8 }}>{ghost.type}</div>}
      {dataPort && <DataWindow key={dataPort.port} port={dataPort.port} type={dataPort.type}
        data={fullData && fullData.header.port === dataPort.port ? fullData : null} onClose={closeData} />}
      {subnet && <SubnetView {...subnet} colors={registry.types || {}} request={request} onClose={() => set({ subnet: null })} />}
      {dialog?.kind === 'open' && <FileDialog title="Open" initialPath={net.file} request={request}
        onDone={(path) => request('open', { path }).then((r) => say(`opened ${r.file}`))} onClose={close} />}
      {dialog?.kind === 'saveas' && <FileDialog title="Save as" initialPath={net.file} request={request}
        onDone={(path) => save(path)} onClose={close} />}
      {dialog?.kind === 'choose' && <FileDialog title={`Choose ${dialog.title}`} request={request}
        initialPath={net.file} onDone={dialog.onDone} onClose={dialog.onClose} />}
      {dialog?.kind === 'export' && <ExportDialog {...dialog} onClose={close} />}
    </>
  );
}
