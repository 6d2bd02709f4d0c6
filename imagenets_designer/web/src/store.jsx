import React, { createContext, useContext, useEffect, useMemo, useReducer, useRef } from 'react';
import { Connection } from './connection.js';
import { flowFromNet, split } from './flow.js';

// The page's one store: what the server sent (registry, net, run events, port values) and what
// the page shows (dialogs, message, selection on the canvas), changed only through `reducer`.
export const initialState = {
  registry: null,
  net: null,
  document: undefined, // the net's `document`: another one shows nothing of the last
  nodes: [],
  edges: [],
  running: new Set(),
  cached: new Set(),
  previews: {},
  watched: new Set(),
  message: null, // {text, error, at}
  search: null, // {at, flowAt, inputType, from}
  dataPort: null, // {port, type}
  fullData: null,
  dialog: null,
  subnet: null,
  showYaml: true,
  ghost: null,
  connected: false,
  refusal: null, // {text, at}: a refused link, where it was dropped
  minimap: null, // null: by the canvas's size
  pendingFit: false, // fit once the nodes of a newly shown net are measured
};

const without = (set, key) => { const n = new Set(set); n.delete(key); return n; };

// Another net opened (here or in another tab): nothing shown of the old one carries over, not
// even to a block of the same name (previews, data, run results, selection).
function forgetShown(state) {
  Object.values(state.previews).forEach((v) => v?.bitmap?.close());
  return { ...state, previews: {}, watched: new Set(), cached: new Set(), running: new Set(), message: null,
    dataPort: null, fullData: null, subnet: null, search: null, refusal: null };
}

function applyNet(state, net) {
  const first = state.document === undefined;
  const another = !first && state.document !== net.document;
  let next = another ? forgetShown(state) : state;
  // A net shown anew is fitted once measured; an empty one stays at 100 % (its first block
  // stays where it was dropped).
  const pendingFit = first || another ? net.blocks.length > 0 : state.pendingFit;
  const built = flowFromNet(net, state.registry?.types || {}, another ? [] : state.nodes, another ? [] : state.edges);
  return { ...next, net, document: net.document, pendingFit, nodes: built.nodes, edges: built.edges };
}

function applyEvent(state, e) {
  if (!e.block || e.block.includes('/')) return e.kind === 'run_finished' ? { ...state, running: new Set() } : state;
  let { running, cached, net } = state;
  if (e.kind === 'started') {
    running = new Set(running).add(e.block);
    cached = without(cached, e.block);
  } else if (e.kind === 'finished' || e.kind === 'cached') {
    running = without(running, e.block);
    if (e.kind === 'cached') cached = new Set(cached).add(e.block);
  }
  if (e.stats && net) {
    net = { ...net, blocks: net.blocks.map((b) => (b.name === e.block ? { ...b, stats: { ...b.stats, ...e.stats } } : b)) };
  }
  return { ...state, running, cached, net };
}

export function reducer(state, action) {
  switch (action.type) {
    case 'hello': return { ...applyNet({ ...state, registry: action.registry }, action.net), connected: true };
    case 'net': return applyNet(state, action.net);
    case 'event': return applyEvent(state, action.event);
    case 'closed': return { ...state, connected: false };
    case 'preview': {
      if (action.document !== undefined && action.document !== state.document) return state; // another net's value
      state.previews[action.port]?.bitmap?.close();
      return { ...state, previews: { ...state.previews, [action.port]: action.value } };
    }
    case 'fullData': {
      const old = state.fullData, data = action.data;
      if (data.header.document !== undefined && data.header.document !== state.document) return state;
      return { ...state, fullData: old && old.header.port !== data.header.port ? old : data };
    }
    case 'toggleWatch': {
      const watched = new Set(state.watched);
      if (watched.has(action.port)) watched.delete(action.port); else watched.add(action.port);
      return { ...state, watched };
    }
    case 'say': return { ...state, message: { text: action.text, error: action.error, at: Date.now() } };
    case 'runDone': return { ...state, running: new Set() };
    case 'nodesChanged': return { ...state, nodes: action.change(state.nodes) };
    case 'edgesChanged': return { ...state, edges: action.change(state.edges) };
    case 'fitted': return { ...state, pendingFit: false };
    // Plain fields of what the page shows: search, dataPort, fullData, dialog, subnet, showYaml,
    // ghost, refusal, minimap.
    case 'set': return { ...state, ...action.fields };
    default: throw new Error(`unknown action ${action.type}`);
  }
}

const Store = createContext(null);

// The store, the connection to the server and what the page keeps outside the state (the
// clipboard, the canvas element, the last pointer position).
export function DesignerProvider({ children }) {
  const [state, dispatch] = useReducer(reducer, initialState);
  const conn = useMemo(() => new Connection(`${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}/ws`), []);
  const refs = { wrapper: useRef(null), clipboard: useRef(null), pointer: useRef({ x: 0, y: 0 }) };
  const tools = useMemo(() => {
    const request = (op, args) => conn.request(op, args);
    const say = (text, error = false) => dispatch({ type: 'say', text, error });
    const attempt = async (op, args) => {
      try { return await request(op, args); } catch (err) { say(err.message, true); return null; }
    };
    const set = (fields) => dispatch({ type: 'set', fields });
    return { conn, dispatch, request, say, attempt, set };
  }, [conn]);

  useEffect(() => {
    const onData = ({ header, payload }) => {
      const data = { header, payload, value: header.value };
      if (header.mode === 'full') { dispatch({ type: 'fullData', data }); return; }
      const store = (value) => dispatch({ type: 'preview', port: header.port, document: header.document, value });
      // Thumbnails are decoded off the main thread, then drawn straight onto the node's canvas.
      if (header.format === 'jpeg' || header.format === 'png') {
        createImageBitmap(new Blob([payload], { type: `image/${header.format}` }))
          .then((bitmap) => store({ ...data, bitmap }))
          .catch((err) => store({ header: { ...header, format: 'none', error: `cannot decode: ${err.message}` } }));
      } else {
        store(data);
      }
    };
    const offs = [
      conn.on('net', (net) => dispatch({ type: 'net', net })),
      conn.on('event', (event) => dispatch({ type: 'event', event })),
      conn.on('error', (e) => tools.say(e.error, true)),
      conn.on('closed', () => { dispatch({ type: 'closed' }); tools.say('connection to the designer closed', true); }),
      conn.on('data', onData),
    ];
    conn.request('hello').then((reply) => dispatch({ type: 'hello', registry: reply.registry, net: reply.net }))
      .catch((err) => tools.say(err.message, true));
    return () => offs.forEach((off) => off());
  }, [conn]);

  // Only ports that still exist are watched (a block may have gone by an edit in any tab).
  const { watched, net, connected, dataPort } = state;
  const watchedPorts = useMemo(() => JSON.stringify([...watched].filter((key) => {
    const [block, port] = split(key);
    return net?.blocks.some((b) => b.name === block && b.outputs.some((p) => p.name === port));
  }).sort()), [watched, net]);
  useEffect(() => { if (connected) tools.attempt('watch', { ports: JSON.parse(watchedPorts), mode: 'preview' }); }, [watchedPorts, connected]);
  useEffect(() => {
    if (!connected) return;
    tools.set({ fullData: null });
    tools.attempt('watch', { ports: dataPort ? [dataPort.port] : [], mode: 'full' });
  }, [dataPort, connected]);

  const value = useMemo(() => ({ state, ...tools, refs }), [state, tools]);
  return <Store.Provider value={value}>{children}</Store.Provider>;
}

// The state and the means to change it: { state, dispatch, set, request, attempt, say, refs }.
export function useStore() {
  return useContext(Store);
}

// The block of the one selected node, if exactly one is selected.
export function useSelectedBlock() {
  const { net, nodes } = useStore().state;
  const selected = nodes.filter((n) => n.selected);
  return selected.length === 1 ? net.blocks.find((b) => b.name === selected[0].id) : null;
}
