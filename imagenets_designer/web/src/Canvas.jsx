import React, { useEffect, useMemo, useRef } from 'react';
import {
  ReactFlow, Background, Controls, ControlButton, MiniMap, applyNodeChanges, applyEdgeChanges,
  useUpdateNodeInternals, useNodesInitialized,
} from '@xyflow/react';
import { BlockNode } from './BlockNode.jsx';
import { BlockSearch } from './Dialogs.jsx';
import { FeedbackEdge } from './FeedbackEdge.jsx';
import { LinkRefusal } from './LinkRefusal.jsx';
import { split } from './flow.js';
import { useCommands } from './commands.js';
import { useStore } from './store.jsx';

const nodeTypes = { block: BlockNode };
const edgeTypes = { feedback: FeedbackEdge };
const NO_COLORS = {};
// Below this canvas width the minimap would cover nodes (a 1366 px screen): off unless asked for.
const MINIMAP_MIN_WIDTH = 1000;

// The net drawn as blocks and links, with the block search, a refused link and the net's errors.
export function Canvas() {
  const { state, dispatch, set, attempt, refs } = useStore();
  const { net, registry, nodes, edges, running, cached, previews, watched, search, refusal, minimap, pendingFit, document } = state;
  const colors = registry?.types || NO_COLORS;
  const { connect, reconnect, fitReadable, openSearch, pickSearch } = useCommands();

  // A link to a block that has just appeared may come before the canvas measured the block's
  // ports; measuring the ends of new links again makes sure every link is drawn.
  const updateNodeInternals = useUpdateNodeInternals();
  const drawnLinks = useRef(new Set());
  useEffect(() => {
    const fresh = edges.filter((e) => !drawnLinks.current.has(e.id));
    drawnLinks.current = new Set(edges.map((e) => e.id));
    if (fresh.length) requestAnimationFrame(() => updateNodeInternals([...new Set(fresh.flatMap((e) => [e.source, e.target]))]));
  }, [edges]);

  const measured = useNodesInitialized();
  useEffect(() => {
    if (measured && pendingFit && nodes.length) {
      dispatch({ type: 'fitted' });
      fitReadable();
    }
  }, [measured, nodes, pendingFit, fitReadable]);

  const actions = useMemo(() => ({
    toggleWatch: (port) => dispatch({ type: 'toggleWatch', port }),
    openData: (port, type) => set({ dataPort: { port, type } }),
    openSubnet: async (block) => {
      const state = await attempt('subnet', { block });
      if (state) set({ subnet: { block, state: state.net || state } });
    },
  }), []);

  // Each node's data object changes only when something it shows changes, so that the memoized
  // BlockNode re-renders only the nodes a message concerns (previews arrive many times a second).
  // Kept per document: another net shares nothing with the last.
  const nodeData = useMemo(() => new Map(), [document]);
  const shownNodes = useMemo(() => {
    const blocks = new Map((net?.blocks || []).map((b) => [b.name, b]));
    return nodes.filter((n) => blocks.has(n.id)).map((n) => {
      const own = [...watched].filter((k) => split(k)[0] === n.id);
      const data = { block: blocks.get(n.id), colors, running: running.has(n.id), cached: cached.has(n.id),
        previews: Object.fromEntries(own.map((k) => [k, previews[k]])), watched: new Set(own), actions };
      const old = nodeData.get(n.id);
      const same = old && ['block', 'colors', 'running', 'cached', 'actions'].every((k) => old[k] === data[k])
        && own.length === old.watched.size && own.every((k) => old.watched.has(k) && old.previews[k] === data.previews[k]);
      if (!same) nodeData.set(n.id, data);
      return { ...n, data: same ? old : data };
    });
  }, [nodes, net, colors, running, cached, previews, watched, actions, nodeData]);

  const canvasWidth = refs.wrapper.current?.getBoundingClientRect().width ?? window.innerWidth - 550;
  const showMinimap = minimap ?? canvasWidth >= MINIMAP_MIN_WIDTH;
  return (
    <div className="canvas" ref={refs.wrapper} onDoubleClick={(e) => {
      if (e.target.closest('.react-flow__pane')) openSearch(e.clientX, e.clientY);
    }}>
      {refusal && <LinkRefusal refusal={refusal} onClose={() => set({ refusal: null })} />}
      {net.errors?.length > 0 && <div className="net-errors" data-testid="net-errors">{net.errors.join('\n')}</div>}
      <ReactFlow nodes={shownNodes} edges={edges} nodeTypes={nodeTypes} edgeTypes={edgeTypes} minZoom={0.1} maxZoom={4}
        onNodesChange={(changes) => dispatch({ type: 'nodesChanged', change: (ns) => applyNodeChanges(changes, ns) })}
        onEdgesChange={(changes) => dispatch({ type: 'edgesChanged',
          change: (es) => applyEdgeChanges(changes.filter((c) => c.type !== 'remove'), es) })}
        onNodeDragStop={(e, node, dragged) => attempt('move_blocks', {
          positions: Object.fromEntries(dragged.map((n) => [n.id, [Math.round(n.position.x), Math.round(n.position.y)]])),
        })}
        onConnect={connect} onReconnect={reconnect}
        onConnectStart={() => set({ refusal: null })} onPaneClick={() => set({ refusal: null })}
        onConnectEnd={(e, connection) => {
          if (connection.toNode || !connection.fromHandle || connection.fromHandle.type !== 'source') return;
          const point = 'changedTouches' in e ? e.changedTouches[0] : e;
          const port = connection.fromNode && net.blocks.find((b) => b.name === connection.fromNode.id)
            ?.outputs.find((p) => p.name === connection.fromHandle.id);
          if (port) openSearch(point.clientX, point.clientY, port.type, `${connection.fromNode.id}.${port.name}`);
        }}
        deleteKeyCode={null} zoomOnDoubleClick={false} colorMode="dark">
        <Background />
        {/* Our own fit button: the built-in one runs React Flow's fitView as well, which would
            undo the readable zoom. */}
        <Controls showFitView={false}>
          <ControlButton data-testid="fit-view" title="fit the net at a readable zoom" onClick={fitReadable}>⛶</ControlButton>
          <ControlButton data-testid="toggle-minimap" title="show or hide the minimap"
            onClick={() => set({ minimap: !showMinimap })}>▦</ControlButton>
        </Controls>
        {showMinimap && <MiniMap pannable zoomable nodeColor={(n) => (running.has(n.id) ? '#f5c542' : '#8aa')} />}
      </ReactFlow>
      {search && <BlockSearch registry={registry} inputType={search.inputType} at={search.at}
        onPick={pickSearch} onClose={() => set({ search: null })} />}
    </div>
  );
}
