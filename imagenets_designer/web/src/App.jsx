import React, { useCallback, useEffect, useMemo, useRef, useState } from 'react';
import {
  ReactFlow, ReactFlowProvider, Background, Controls, ControlButton, MiniMap, applyNodeChanges, applyEdgeChanges, useReactFlow,
  useUpdateNodeInternals, useNodesInitialized,
} from '@xyflow/react';
import { Connection } from './connection.js';
import { BlockNode } from './BlockNode.jsx';
import { BlockBrowser } from './BlockBrowser.jsx';
import { PropertiesPanel } from './PropertiesPanel.jsx';
import { BlockSearch, ExportDialog, FileDialog } from './Dialogs.jsx';
import { DataWindow } from './DataWindow.jsx';
import { FeedbackEdge } from './FeedbackEdge.jsx';
import { LinkRefusal } from './LinkRefusal.jsx';
import { SubnetView } from './SubnetView.jsx';
import { YamlPane } from './YamlPane.jsx';
import { layeredLayout } from './layout.js';
import { FEEDBACK_HANDLE, flowFromNet, split } from './flow.js';
import { readableViewport } from './readableFit.js';

const nodeTypes = { block: BlockNode };
const edgeTypes = { feedback: FeedbackEdge };
// Below this canvas width the minimap would cover nodes (a 1366 px screen): off unless asked for.
const MINIMAP_MIN_WIDTH = 1000;

export function App() {
  return <ReactFlowProvider><Designer /></ReactFlowProvider>;
}

function Designer() {
  const flow = useReactFlow();
  const conn = useMemo(() => new Connection(`${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}/ws`), []);
  const request = useCallback((op, args) => conn.request(op, args), [conn]);
  const [registry, setRegistry] = useState(null);
  const [net, setNet] = useState(null);
  const [nodes, setNodes] = useState([]);
  const [edges, setEdges] = useState([]);
  const [running, setRunning] = useState(new Set());
  const [cached, setCached] = useState(new Set());
  const [previews, setPreviews] = useState({});
  const [watched, setWatched] = useState(new Set());
  const [message, setMessage] = useState(null); // {text, error}
  const [search, setSearch] = useState(null); // {at, flowAt, inputType, from}
  const [dataPort, setDataPort] = useState(null); // {port, type}
  const [fullData, setFullData] = useState(null);
  const [dialog, setDialog] = useState(null);
  const [subnet, setSubnet] = useState(null);
  const [showYaml, setShowYaml] = useState(true);
  const [ghost, setGhost] = useState(null);
  const [connected, setConnected] = useState(false);
  const [refusal, setRefusal] = useState(null); // {text, at}: a refused link, where it was dropped
  const [minimap, setMinimap] = useState(null); // null: by the canvas's size
  const wrapper = useRef(null);
  const clipboard = useRef(null);
  const pendingFit = useRef(false); // fit once the nodes of a newly shown net are measured
  const pointer = useRef({ x: 0, y: 0 });
  const colors = registry?.types || {};

  const say = (text, error = false) => setMessage({ text, error, at: Date.now() });
  const attempt = async (op, args) => {
    try { return await request(op, args); } catch (err) { say(err.message, true); return null; }
  };

  const colorsRef = useRef({});
  const flowRef = useRef({ nodes, edges });
  flowRef.current = { nodes, edges };
  // Another net opened (here or in another tab): nothing shown of the old one carries over, not
  // even to a block of the same name (previews, data, run results, selection).
  const documentRef = useRef(undefined);
  const nodeData = useRef(new Map());
  const forgetShown = useCallback(() => {
    setPreviews((p) => { Object.values(p).forEach((v) => v?.bitmap?.close()); return {}; });
    setWatched(new Set());
    setCached(new Set());
    setRunning(new Set());
    setMessage(null);
    setDataPort(null);
    setFullData(null);
    setSubnet(null);
    setSearch(null);
    setRefusal(null);
    nodeData.current.clear();
  }, []);
  const applyNet = useCallback((state) => {
    const first = documentRef.current === undefined;
    const another = !first && documentRef.current !== state.document;
    documentRef.current = state.document;
    if (another) forgetShown();
    // A net shown anew is fitted once measured; an empty one stays at 100 % (its first block
    // stays where it was dropped).
    if (first || another) pendingFit.current = state.blocks.length > 0;
    setNet(state);
    const built = flowFromNet(state, colorsRef.current, another ? [] : flowRef.current.nodes, another ? [] : flowRef.current.edges);
    flowRef.current = built;
    setNodes(built.nodes);
    setEdges(built.edges);
  }, []);
  colorsRef.current = colors;

  useEffect(() => {
    const offs = [
      conn.on('net', applyNet),
      conn.on('event', (e) => onEvent(e)),
      conn.on('error', (e) => say(e.error, true)),
      conn.on('closed', () => { setConnected(false); say('connection to the designer closed', true); }),
      conn.on('data', onData),
    ];
    conn.request('hello').then((reply) => {
      setRegistry(reply.registry);
      colorsRef.current = reply.registry.types;
      applyNet(reply.net);
      setConnected(true);
    }).catch((err) => say(err.message, true));
    return () => offs.forEach((off) => off());
  }, [conn]);

  const onEvent = (e) => {
    if (!e.block || e.block.includes('/')) {
      if (e.kind === 'run_finished') setRunning(new Set());
      return;
    }
    if (e.kind === 'started') {
      setRunning((s) => new Set(s).add(e.block));
      setCached((s) => { const n = new Set(s); n.delete(e.block); return n; });
    } else if (e.kind === 'finished' || e.kind === 'cached') {
      setRunning((s) => { const n = new Set(s); n.delete(e.block); return n; });
      if (e.kind === 'cached') setCached((s) => new Set(s).add(e.block));
    }
    if (e.stats) {
      setNet((n) => n && { ...n, blocks: n.blocks.map((b) => (b.name === e.block ? { ...b, stats: { ...b.stats, ...e.stats } } : b)) });
    }
  };

  const onData = ({ header, payload }) => {
    if (header.document !== undefined && header.document !== documentRef.current) return; // another net's value
    const data = { header, payload, value: header.value };
    if (header.mode === 'full') {
      setFullData((old) => (old && old.header.port !== header.port ? old : data));
      return;
    }
    const store = (value) => setPreviews((p) => {
      p[header.port]?.bitmap?.close();
      return { ...p, [header.port]: value };
    });
    // Thumbnails are decoded off the main thread, then drawn straight onto the node's canvas.
    if (header.format === 'jpeg' || header.format === 'png') {
      createImageBitmap(new Blob([payload], { type: `image/${header.format}` }))
        .then((bitmap) => store({ ...data, bitmap }))
        .catch((err) => store({ header: { ...header, format: 'none', error: `cannot decode: ${err.message}` } }));
    } else {
      store(data);
    }
  };

  // A link to a block that has just appeared may come before the canvas measured the block's
  // ports; measuring the ends of new links again makes sure every link is drawn.
  const updateNodeInternals = useUpdateNodeInternals();
  const drawnLinks = useRef(new Set());
  useEffect(() => {
    const fresh = edges.filter((e) => !drawnLinks.current.has(e.id));
    drawnLinks.current = new Set(edges.map((e) => e.id));
    if (fresh.length) requestAnimationFrame(() => updateNodeInternals([...new Set(fresh.flatMap((e) => [e.source, e.target]))]));
  }, [edges]);

  // Only ports that still exist are watched (a block may have gone by an edit in any tab).
  const watchedPorts = useMemo(() => JSON.stringify([...watched].filter((key) => {
    const [block, port] = split(key);
    return net?.blocks.some((b) => b.name === block && b.outputs.some((p) => p.name === port));
  }).sort()), [watched, net]);
  useEffect(() => { if (connected) attempt('watch', { ports: JSON.parse(watchedPorts), mode: 'preview' }); }, [watchedPorts, connected]);
  useEffect(() => {
    if (!connected) return;
    setFullData(null);
    attempt('watch', { ports: dataPort ? [dataPort.port] : [], mode: 'full' });
  }, [dataPort, connected]);

  const closeData = useCallback(() => setDataPort(null), []);
  const actions = useMemo(() => ({
    toggleWatch: (key) => setWatched((w) => { const n = new Set(w); if (n.has(key)) n.delete(key); else n.add(key); return n; }),
    openData: (port, type) => setDataPort({ port, type }),
    openSubnet: async (block) => {
      const state = await attempt('subnet', { block });
      if (state) setSubnet({ block, state: state.net || state });
    },
  }), []);

  // Each node's data object changes only when something it shows changes, so that the memoized
  // BlockNode re-renders only the nodes a message concerns (previews arrive many times a second).
  const shownNodes = useMemo(() => {
    const blocks = new Map((net?.blocks || []).map((b) => [b.name, b]));
    return nodes.filter((n) => blocks.has(n.id)).map((n) => {
      const own = [...watched].filter((k) => split(k)[0] === n.id);
      const data = { block: blocks.get(n.id), colors, running: running.has(n.id), cached: cached.has(n.id),
        previews: Object.fromEntries(own.map((k) => [k, previews[k]])), watched: new Set(own), actions };
      const old = nodeData.current.get(n.id);
      const same = old && ['block', 'colors', 'running', 'cached', 'actions'].every((k) => old[k] === data[k])
        && own.length === old.watched.size && own.every((k) => old.watched.has(k) && old.previews[k] === data.previews[k]);
      if (!same) nodeData.current.set(n.id, data);
      return { ...n, data: same ? old : data };
    });
  }, [nodes, net, colors, running, cached, previews, watched, actions]);

  // --- edits -----------------------------------------------------------------------------------
  const run = async (op, args) => {
    say(`${op.replaceAll('_', ' ')}…`);
    const r = await attempt(op, args);
    if (r) say(`ran ${r.ran.length}, failed ${r.failed.length}, not run ${r.not_run.length}${r.cancelled ? ', cancelled' : ''}`, r.failed.length > 0);
    setRunning(new Set());
  };
  const selectedNames = () => nodes.filter((n) => n.selected).map((n) => n.id);
  const addBlock = async (type, position) => {
    const at = [Math.round(position.x), Math.round(position.y)];
    try {
      return (await request('add_block', { type, position: at })).name;
    } catch (err) {
      // A block built from a file (a sub-net's `net`) cannot exist without it: ask for the file,
      // but only when the engine said so of this block type and named the path property.
      const entry = registry.blocks.find((b) => b.type === type);
      const paths = (entry?.properties || []).filter((p) => p.path);
      const property = err.message.includes(`(${type})`) && paths.find((p) => err.message.includes(`'${p.name}'`));
      if (!property) { say(err.message, true); return null; }
      say(err.message, true);
      return new Promise((resolve) => setDialog({ kind: 'choose', title: `${property.name} of the new ${type.replace(/^imagenets\//, '')}`,
        onDone: async (path) => {
          const base = type.replace(/^.*\//, '').replace(/([a-z])([A-Z])/g, '$1_$2').toLowerCase();
          const r = await request('paste', { blocks: [{ name: base, type, properties: { [property.name]: path }, position: at }], links: [] });
          say(`added ${r.names[base]}`);
          resolve(r.names[base]);
        },
        onClose: () => { setDialog(null); resolve(null); } }));
    }
  };
  const removeSelected = async () => {
    const names = selectedNames();
    if (names.length) await attempt('remove_blocks', { names });
    for (const e of edges.filter((x) => x.selected && !names.includes(x.source) && !names.includes(x.target))) {
      // A feedback edge removed is the feedback turned off.
      if (e.type === 'feedback') await attempt('set_feedback', { block: e.target, feedback: null });
      else await attempt('remove_link', { from: e.data.from, to: e.data.to });
    }
  };
  // A link dropped on a port, or a feedback's score moved onto another port; a refusal is shown
  // whole where the drag ended.
  const refuse = (text) => {
    const r = wrapper.current.getBoundingClientRect();
    const x = pointer.current.x - r.left, y = Math.max(4, Math.min(pointer.current.y - r.top + 14, r.height - 140));
    // Below and right of the drop point, or left of it where the canvas ends.
    const at = x + 14 + 390 <= r.width ? { left: x + 14, top: y } : { right: Math.max(4, r.width - x + 14), top: y };
    setRefusal({ text, at });
    say(text, true);
  };
  const connect = async (c) => {
    const from = `${c.source}.${c.sourceHandle}`;
    try {
      if (c.targetHandle === FEEDBACK_HANDLE) {
        const block = net.blocks.find((b) => b.name === c.target);
        await request('set_feedback', { block: c.target, feedback: { ...block.feedback, score: from } });
        say(`${c.target}'s feedback scores by ${from}`);
      } else {
        await request('add_link', { from, to: `${c.target}.${c.targetHandle}` });
      }
      setRefusal(null);
    } catch (err) { refuse(err.message); }
  };
  const reconnect = (old, c) => {
    if (old.type === 'feedback' && c.target === old.target && c.targetHandle === FEEDBACK_HANDLE) connect(c);
  };
  const copy = () => {
    const names = new Set(selectedNames());
    if (!names.size) return;
    clipboard.current = {
      blocks: net.blocks.filter((b) => names.has(b.name)).map((b) => {
        const n = nodes.find((x) => x.id === b.name);
        // Like links, feedback is kept only when its score port is inside the selection too.
        const feedback = b.feedback && names.has(split(b.feedback.score)[0]) ? b.feedback : null;
        return { name: b.name, type: b.type, properties: b.properties, feedback,
          position: [Math.round(n.position.x), Math.round(n.position.y)] };
      }),
      links: net.links.filter((l) => names.has(split(l.from)[0]) && names.has(split(l.to)[0])).map(({ from, to }) => ({ from, to })),
    };
    say(`copied ${names.size} blocks`);
  };
  const paste = async () => {
    if (!clipboard.current) return;
    const c = clipboard.current;
    const blocks = c.blocks.map((b) => ({ ...b, position: [b.position[0] + 40, b.position[1] + 40] }));
    clipboard.current = { ...c, blocks };
    const r = await attempt('paste', { blocks, links: c.links });
    if (r) {
      const names = new Set(Object.values(r.names || {}).concat(Array.isArray(r.names) ? r.names : []));
      setNodes((ns) => ns.map((n) => ({ ...n, selected: names.has(n.id) })));
    }
  };
  const fitReadable = useCallback(() => {
    const shown = flow.getNodes();
    if (!shown.length || !wrapper.current) return;
    const r = wrapper.current.getBoundingClientRect();
    flow.setViewport(readableViewport(flow.getNodesBounds(shown), r.width, r.height));
  }, [flow]);
  const measured = useNodesInitialized();
  useEffect(() => {
    if (measured && pendingFit.current && nodes.length) {
      pendingFit.current = false;
      fitReadable();
    }
  }, [measured, nodes, fitReadable]);
  const autoLayout = () => {
    const sizes = Object.fromEntries(flow.getNodes().filter((n) => n.measured?.width)
      .map((n) => [n.id, { width: n.measured.width, height: n.measured.height }]));
    const positions = layeredLayout(net.blocks, net.links, sizes);
    attempt('move_blocks', { positions }).then(() => setTimeout(fitReadable, 50));
  };
  const save = async (path) => {
    const r = await request('save', path ? { path } : {});
    say(`saved ${r.file || path || net.file}`);
  };
  const exportLaunch = async () => {
    const r = await attempt('export_launch');
    if (r) setDialog({ kind: 'export', title: 'launch file', text: r.text, fileName: 'net.launch' });
  };
  const exportGraph = async () => {
    const r = await attempt('export_graph', { expand: true });
    if (r) setDialog({ kind: 'export', title: 'Graphviz picture', svg: r.svg, fileName: 'net.svg' });
  };

  // --- keyboard --------------------------------------------------------------------------------
  const keys = useRef();
  keys.current = (e) => {
    const inField = ['INPUT', 'TEXTAREA', 'SELECT'].includes(e.target.tagName);
    const ctrl = e.ctrlKey || e.metaKey;
    if (ctrl && e.key === 'Enter' && e.target.tagName !== 'TEXTAREA') { e.preventDefault(); run('run'); return; }
    if (ctrl && e.key.toLowerCase() === 's') { e.preventDefault(); if (net.file) save().catch((err) => say(err.message, true)); else setDialog({ kind: 'saveas' }); return; }
    if (inField || !net) return;
    if (ctrl && e.key.toLowerCase() === 'z' && !e.shiftKey) { e.preventDefault(); attempt('undo'); }
    else if (ctrl && (e.key.toLowerCase() === 'y' || (e.key.toLowerCase() === 'z' && e.shiftKey))) { e.preventDefault(); attempt('redo'); }
    else if (ctrl && e.key.toLowerCase() === 'c') copy();
    else if (ctrl && e.key.toLowerCase() === 'v') paste();
    else if (e.key === 'Delete' || e.key === 'Backspace') removeSelected();
  };
  useEffect(() => {
    const handler = (e) => keys.current(e);
    const track = (e) => { pointer.current = { x: e.clientX, y: e.clientY }; };
    window.addEventListener('keydown', handler);
    window.addEventListener('pointermove', track, true);
    window.addEventListener('pointerup', track, true);
    return () => {
      window.removeEventListener('keydown', handler);
      window.removeEventListener('pointermove', track, true);
      window.removeEventListener('pointerup', track, true);
    };
  }, []);

  // --- dragging a block from the browser (pointer events, so it works everywhere) --------------
  const startDrag = (type, down, onClick) => {
    down.preventDefault();
    let moved = false;
    const move = (e) => {
      if (!moved && Math.hypot(e.clientX - down.clientX, e.clientY - down.clientY) < 5) return;
      moved = true;
      setGhost({ type, x: e.clientX, y: e.clientY });
    };
    const up = (e) => {
      window.removeEventListener('mousemove', move);
      window.removeEventListener('mouseup', up);
      setGhost(null);
      if (!moved) { onClick(); return; }
      const r = wrapper.current.getBoundingClientRect();
      if (e.clientX >= r.left && e.clientX <= r.right && e.clientY >= r.top && e.clientY <= r.bottom) {
        addBlock(type, flow.screenToFlowPosition({ x: e.clientX, y: e.clientY }));
      }
    };
    window.addEventListener('mousemove', move);
    window.addEventListener('mouseup', up);
  };

  const openSearch = (clientX, clientY, inputType = null, from = null) => {
    const r = wrapper.current.getBoundingClientRect();
    const x = Math.min(clientX - r.left, r.width - 270), y = Math.min(clientY - r.top, r.height - 310); // stays inside
    setSearch({ at: { x: Math.max(0, x), y: Math.max(0, y) }, flowAt: flow.screenToFlowPosition({ x: clientX, y: clientY }), inputType, from });
  };
  const pickSearch = async (type) => {
    const s = search;
    setSearch(null);
    const name = await addBlock(type, s.flowAt);
    if (name && s.from) {
      const input = registry.blocks.find((b) => b.type === type).inputs.find((p) => p.type === s.inputType);
      if (input) await attempt('add_link', { from: s.from, to: `${name}.${input.name}` });
    }
  };

  if (!registry || !net) {
    return <div className="loading">{message ? message.text : 'connecting to the designer…'}</div>;
  }
  const canvasWidth = wrapper.current?.getBoundingClientRect().width ?? window.innerWidth - 550;
  const showMinimap = minimap ?? canvasWidth >= MINIMAP_MIN_WIDTH;
  const selected = nodes.filter((n) => n.selected);
  const selectedBlock = selected.length === 1 ? net.blocks.find((b) => b.name === selected[0].id) : null;
  const fileName = net.file ? net.file.split('/').pop() : 'untitled net';
  return (
    <div className="designer">
      <div className="toolbar">
        <span className="title" data-testid="file-name" title={net.file || ''}>{fileName}{net.dirty ? ' •' : ''}</span>
        <button data-testid="open" onClick={() => setDialog({ kind: 'open' })}>Open</button>
        <button data-testid="save" onClick={() => (net.file ? save().catch((err) => say(err.message, true)) : setDialog({ kind: 'saveas' }))}>Save</button>
        <button data-testid="save-as" onClick={() => setDialog({ kind: 'saveas' })}>Save as</button>
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
        <label><input type="checkbox" checked={showYaml} onChange={(e) => setShowYaml(e.target.checked)} /> YAML</label>
        <span className={`message ${message?.error ? 'error' : ''}`} data-testid="message"
          title={message?.text}>{message?.text}</span>
      </div>
      <div className="main">
        <BlockBrowser registry={registry} onStartDrag={startDrag} />
        <div className="canvas" ref={wrapper} onDoubleClick={(e) => {
          if (e.target.closest('.react-flow__pane')) openSearch(e.clientX, e.clientY);
        }}>
          {refusal && <LinkRefusal refusal={refusal} onClose={() => setRefusal(null)} />}
          {net.errors?.length > 0 && <div className="net-errors" data-testid="net-errors">{net.errors.join('\n')}</div>}
          <ReactFlow nodes={shownNodes} edges={edges} nodeTypes={nodeTypes} edgeTypes={edgeTypes} minZoom={0.1} maxZoom={4}
            onNodesChange={(changes) => setNodes((ns) => applyNodeChanges(changes, ns))}
            onEdgesChange={(changes) => setEdges((es) => applyEdgeChanges(changes.filter((c) => c.type !== 'remove'), es))}
            onNodeDragStop={(e, node, dragged) => attempt('move_blocks', {
              positions: Object.fromEntries(dragged.map((n) => [n.id, [Math.round(n.position.x), Math.round(n.position.y)]])),
            })}
            onConnect={connect} onReconnect={reconnect}
            onConnectStart={() => setRefusal(null)} onPaneClick={() => setRefusal(null)}
            onConnectEnd={(e, state) => {
              if (state.toNode || !state.fromHandle || state.fromHandle.type !== 'source') return;
              const point = 'changedTouches' in e ? e.changedTouches[0] : e;
              const port = state.fromNode && net.blocks.find((b) => b.name === state.fromNode.id)
                ?.outputs.find((p) => p.name === state.fromHandle.id);
              if (port) openSearch(point.clientX, point.clientY, port.type, `${state.fromNode.id}.${port.name}`);
            }}
            deleteKeyCode={null} zoomOnDoubleClick={false} colorMode="dark">
            <Background />
            {/* Our own fit button: the built-in one runs React Flow's fitView as well, which would
                undo the readable zoom. */}
            <Controls showFitView={false}>
              <ControlButton data-testid="fit-view" title="fit the net at a readable zoom" onClick={fitReadable}>⛶</ControlButton>
              <ControlButton data-testid="toggle-minimap" title="show or hide the minimap"
                onClick={() => setMinimap(!showMinimap)}>▦</ControlButton>
            </Controls>
            {showMinimap && <MiniMap pannable zoomable nodeColor={(n) => (running.has(n.id) ? '#f5c542' : '#8aa')} />}
          </ReactFlow>
          {search && <BlockSearch registry={registry} inputType={search.inputType} at={search.at}
            onPick={pickSearch} onClose={() => setSearch(null)} />}
        </div>
        <div className="side">
          {selectedBlock ? <PropertiesPanel block={selectedBlock} net={net} request={request}
            entry={registry.blocks.find((b) => b.type === selectedBlock.type)}
            onRename={(block, name) => attempt('rename_block', { block, name })} />
            : <div className="hint">Select a block to edit its properties. Drag blocks in from the left,
              or double-click the canvas to search. Drag from an output to an input to link.</div>}
          {showYaml && <YamlPane net={net} request={request} />}
        </div>
      </div>
      {ghost && <div className="drag-ghost" style={{ left: ghost.x + 8, top: ghost.y + 8 }}>{ghost.type}</div>}
      {dataPort && <DataWindow key={dataPort.port} port={dataPort.port} type={dataPort.type}
        data={fullData && fullData.header.port === dataPort.port ? fullData : null} onClose={closeData} />}
      {subnet && <SubnetView {...subnet} colors={colors} request={request} onClose={() => setSubnet(null)} />}
      {dialog?.kind === 'open' && <FileDialog title="Open" initialPath={net.file} request={request}
        onDone={(path) => request('open', { path }).then((r) => say(`opened ${r.file}`))}
        onClose={() => setDialog(null)} />}
      {dialog?.kind === 'saveas' && <FileDialog title="Save as" initialPath={net.file} request={request}
        onDone={(path) => save(path)} onClose={() => setDialog(null)} />}
      {dialog?.kind === 'choose' && <FileDialog title={`Choose ${dialog.title}`} request={request}
        initialPath={net.file} onDone={dialog.onDone} onClose={dialog.onClose} />}
      {dialog?.kind === 'export' && <ExportDialog {...dialog} onClose={() => setDialog(null)} />}
    </div>
  );
}
