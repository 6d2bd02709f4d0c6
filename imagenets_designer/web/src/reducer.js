import { flowFromNet } from './flow.js';

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
