import React from 'react';
import { useCommands } from './commands.js';
import { useSelectedBlock, useStore } from './store.jsx';

// The file's name, file, run, edit and export buttons, and the last message.
export function Toolbar() {
  const { state, set, attempt } = useStore();
  const { net, running, showYaml, message } = state;
  const { run, saveOrAsk, autoLayout, exportLaunch, exportGraph } = useCommands();
  const selectedBlock = useSelectedBlock();
  const fileName = net.file ? net.file.split('/').pop() : 'untitled net';
  return (
    <div className="toolbar">
      <span className="title" data-testid="file-name" title={net.file || ''}>{fileName}{net.dirty ? ' •' : ''}</span>
      <button data-testid="open" onClick={() => set({ dialog: { kind: 'open' } })}>Open</button>
      <button data-testid="save" onClick={saveOrAsk}>Save</button>
      <button data-testid="save-as" onClick={() => set({ dialog: { kind: 'saveas' } })}>Save as</button>
      <span className="sep" />
      <button data-testid="run" title="Ctrl+Enter" onClick={() => run('run')}>▶ Run</button>
      <button data-testid="run-all" title="run every block, cached or not" onClick={() => run('run_all')}>Run all</button>
      <button data-testid="run-block-only" disabled={!selectedBlock}
        title="run this block only, on the values its inputs hold now (what follows it is left out of date)"
        onClick={() => run('run_block_only', { block: selectedBlock.name })}>Run block only</button>
      <button data-testid="run-block" disabled={!selectedBlock}
        title="run this block again and everything downstream of it"
        onClick={() => run('run_block', { block: selectedBlock.name })}>Run from here</button>
      <button data-testid="cancel" disabled={!running.size} onClick={() => attempt('cancel')}>Cancel</button>
      <label title="re-run the changed block and its downstream after each property change">
        <input type="checkbox" data-testid="auto-run" checked={net.auto_run !== false}
          onChange={(e) => attempt('auto_run', { on: e.target.checked })} /> auto-run</label>
      <span className="sep" />
      <button data-testid="undo" disabled={!net.can_undo} title="Ctrl+Z" onClick={() => attempt('undo')}>Undo</button>
      <button data-testid="redo" disabled={!net.can_redo} title="Ctrl+Y" onClick={() => attempt('redo')}>Redo</button>
      <button data-testid="layout" onClick={autoLayout}>Layout</button>
      <span className="sep" />
      <button data-testid="export-launch" onClick={exportLaunch}>Export launch</button>
      <button data-testid="export-svg" onClick={exportGraph}>Export SVG</button>
      <label><input type="checkbox" checked={showYaml} onChange={(e) => set({ showYaml: e.target.checked })} /> YAML</label>
      <span className={`message ${message?.error ? 'error' : ''}`} data-testid="message"
        title={message?.text}>{message?.text}</span>
    </div>
  );
}
