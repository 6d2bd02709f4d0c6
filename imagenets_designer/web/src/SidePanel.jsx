import React from 'react';
import { PropertiesPanel } from './PropertiesPanel.jsx';
import { YamlPane } from './YamlPane.jsx';
import { useSelectedBlock, useStore } from './store.jsx';

// The selected block's properties (or how to begin) and the net's YAML.
export function SidePanel() {
  const { state, request, attempt } = useStore();
  const { net, registry, showYaml } = state;
  const selectedBlock = useSelectedBlock();
  return (
    <div className="side">
      {selectedBlock ? <PropertiesPanel block={selectedBlock} net={net} request={request}
        entry={registry.blocks.find((b) => b.type === selectedBlock.type)}
        onRename={(block, name) => attempt('rename_block', { block, name })} />
        : <div className="hint">Select a block to edit its properties. Drag blocks in from the left,
          or double-click the canvas to search. Drag from an output to an input to link.</div>}
      {showYaml && <YamlPane net={net} request={request} />}
    </div>
  );
}
