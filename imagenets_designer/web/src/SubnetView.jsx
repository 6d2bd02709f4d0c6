import React, { useMemo } from 'react';
import { ReactFlow, ReactFlowProvider, Background, Controls } from '@xyflow/react';
import { Modal } from './Dialogs.jsx';
import { BlockNode } from './BlockNode.jsx';
import { FeedbackEdge } from './FeedbackEdge.jsx';
import { flowFromNet } from './flow.js';

const nodeTypes = { block: BlockNode };
const edgeTypes = { feedback: FeedbackEdge };
const noActions = { toggleWatch: () => {}, openData: () => {}, openSubnet: () => {} };

// The inner net of an imagenets/Executor block (paper 3.5), read-only, with its blocks' stats.
export function SubnetView({ block, state, colors, request, onClose }) {
  const { nodes, edges } = useMemo(() => {
    const flow = flowFromNet(state, colors);
    flow.nodes = flow.nodes.map((n) => ({ ...n, draggable: false, connectable: false,
      data: { block: state.blocks.find((b) => b.name === n.id), colors, running: false, cached: false,
        previews: {}, watched: new Set(), actions: noActions } }));
    return flow;
  }, [state, colors]);
  const edit = async () => { await request('subnet_open', { block }); onClose(); };
  return (
    <Modal title={`sub-net of ${block}${state.file ? ` · ${state.file}` : ''} (read-only)`} onClose={onClose} wide
      testid="subnet-view">
      <button data-testid="subnet-edit" onClick={edit}>Edit the inner net (opens its file)</button>
      <div className="subnet-canvas">
        <ReactFlowProvider>
          <ReactFlow nodes={nodes} edges={edges} nodeTypes={nodeTypes} edgeTypes={edgeTypes} nodesConnectable={false}
            nodesDraggable={false} elementsSelectable={false} colorMode="dark" fitView>
            <Background />
            <Controls showInteractive={false} />
          </ReactFlow>
        </ReactFlowProvider>
      </div>
    </Modal>
  );
}
