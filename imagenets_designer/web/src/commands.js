import { useCallback, useEffect, useRef } from 'react';
import { useReactFlow } from '@xyflow/react';
import { layeredLayout } from './layout.js';
import { FEEDBACK_HANDLE, split } from './flow.js';
import { readableViewport } from './readableFit.js';
import { useStore } from './store.jsx';

// What the user does on the page, as requests to the server and changes of the store; each
// component takes the ones its controls need.
export function useCommands() {
  const { state, dispatch, set, request, attempt, say, refs } = useStore();
  const { net, nodes, edges, registry, search } = state;
  const flow = useReactFlow();

  const run = async (op, args) => {
    say(`${op.replaceAll('_', ' ')}…`);
    const r = await attempt(op, args);
    if (r) say(`ran ${r.ran.length}, failed ${r.failed.length}, not run ${r.not_run.length}${r.cancelled ? ', cancelled' : ''}`, r.failed.length > 0);
    dispatch({ type: 'runDone' });
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
      return new Promise((resolve) => set({ dialog: { kind: 'choose', title: `${property.name} of the new ${type.replace(/^imagenets\//, '')}`,
        onDone: async (path) => {
          const base = type.replace(/^.*\//, '').replace(/([a-z])([A-Z])/g, '$1_$2').toLowerCase();
          const r = await request('paste', { blocks: [{ name: base, type, properties: { [property.name]: path }, position: at }], links: [] });
          say(`added ${r.names[base]}`);
          resolve(r.names[base]);
        },
        onClose: () => { set({ dialog: null }); resolve(null); } } }));
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
    const r = refs.wrapper.current.getBoundingClientRect();
    const x = refs.pointer.current.x - r.left, y = Math.max(4, Math.min(refs.pointer.current.y - r.top + 14, r.height - 140));
    // Below and right of the drop point, or left of it where the canvas ends.
    const at = x + 14 + 390 <= r.width ? { left: x + 14, top: y } : { right: Math.max(4, r.width - x + 14), top: y };
    set({ refusal: { text, at } });
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
      set({ refusal: null });
    } catch (err) { refuse(err.message); }
  };
  const reconnect = (old, c) => {
    if (old.type === 'feedback' && c.target === old.target && c.targetHandle === FEEDBACK_HANDLE) connect(c);
  };
  const copy = () => {
    const names = new Set(selectedNames());
    if (!names.size) return;
    refs.clipboard.current = {
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
    if (!refs.clipboard.current) return;
    const c = refs.clipboard.current;
    const blocks = c.blocks.map((b) => ({ ...b, position: [b.position[0] + 40, b.position[1] + 40] }));
    refs.clipboard.current = { ...c, blocks };
    const r = await attempt('paste', { blocks, links: c.links });
    if (r) {
      const names = new Set(Object.values(r.names || {}).concat(Array.isArray(r.names) ? r.names : []));
      dispatch({ type: 'nodesChanged', change: (ns) => ns.map((n) => ({ ...n, selected: names.has(n.id) })) });
    }
  };
  const fitReadable = useCallback(() => {
    const shown = flow.getNodes();
    if (!shown.length || !refs.wrapper.current) return;
    const r = refs.wrapper.current.getBoundingClientRect();
    flow.setViewport(readableViewport(flow.getNodesBounds(shown), r.width, r.height));
  }, [flow]);
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
  // Save, or Save as for a net that has no file yet.
  const saveOrAsk = () => (net.file ? save().catch((err) => say(err.message, true)) : set({ dialog: { kind: 'saveas' } }));
  const exportLaunch = async () => {
    const r = await attempt('export_launch');
    if (r) set({ dialog: { kind: 'export', title: 'launch file', text: r.text, fileName: 'net.launch' } });
  };
  const exportGraph = async () => {
    const r = await attempt('export_graph', { expand: true });
    if (r) set({ dialog: { kind: 'export', title: 'Graphviz picture', svg: r.svg, fileName: 'net.svg' } });
  };

  // Dragging a block from the browser (pointer events, so it works everywhere).
  const startDrag = (type, down, onClick) => {
    down.preventDefault();
    let moved = false;
    const move = (e) => {
      if (!moved && Math.hypot(e.clientX - down.clientX, e.clientY - down.clientY) < 5) return;
      moved = true;
      set({ ghost: { type, x: e.clientX, y: e.clientY } });
    };
    const up = (e) => {
      window.removeEventListener('mousemove', move);
      window.removeEventListener('mouseup', up);
      set({ ghost: null });
      if (!moved) { onClick(); return; }
      const r = refs.wrapper.current.getBoundingClientRect();
      if (e.clientX >= r.left && e.clientX <= r.right && e.clientY >= r.top && e.clientY <= r.bottom) {
        addBlock(type, flow.screenToFlowPosition({ x: e.clientX, y: e.clientY }));
      }
    };
    window.addEventListener('mousemove', move);
    window.addEventListener('mouseup', up);
  };

  const openSearch = (clientX, clientY, inputType = null, from = null) => {
    const r = refs.wrapper.current.getBoundingClientRect();
    const x = Math.min(clientX - r.left, r.width - 270), y = Math.min(clientY - r.top, r.height - 310); // stays inside
    set({ search: { at: { x: Math.max(0, x), y: Math.max(0, y) }, flowAt: flow.screenToFlowPosition({ x: clientX, y: clientY }), inputType, from } });
  };
  const pickSearch = async (type) => {
    const s = search;
    set({ search: null });
    const name = await addBlock(type, s.flowAt);
    if (name && s.from) {
      const input = registry.blocks.find((b) => b.type === type).inputs.find((p) => p.type === s.inputType);
      if (input) await attempt('add_link', { from: s.from, to: `${name}.${input.name}` });
    }
  };

  return { run, addBlock, removeSelected, connect, reconnect, copy, paste, fitReadable, autoLayout, save, saveOrAsk,
    exportLaunch, exportGraph, startDrag, openSearch, pickSearch };
}

// The page's keys, and where the pointer was last (a refused link is shown there).
export function useKeyboard() {
  const { state, attempt, refs } = useStore();
  const commands = useCommands();
  const keys = useRef();
  keys.current = (e) => {
    const { net } = state;
    const inField = ['INPUT', 'TEXTAREA', 'SELECT'].includes(e.target.tagName);
    const ctrl = e.ctrlKey || e.metaKey;
    if (ctrl && e.key === 'Enter' && e.target.tagName !== 'TEXTAREA') { e.preventDefault(); commands.run('run'); return; }
    if (ctrl && e.key.toLowerCase() === 's') { e.preventDefault(); commands.saveOrAsk(); return; }
    if (inField || !net) return;
    if (ctrl && e.key.toLowerCase() === 'z' && !e.shiftKey) { e.preventDefault(); attempt('undo'); }
    else if (ctrl && (e.key.toLowerCase() === 'y' || (e.key.toLowerCase() === 'z' && e.shiftKey))) { e.preventDefault(); attempt('redo'); }
    else if (ctrl && e.key.toLowerCase() === 'c') commands.copy();
    else if (ctrl && e.key.toLowerCase() === 'v') commands.paste();
    else if (e.key === 'Delete' || e.key === 'Backspace') commands.removeSelected();
  };
  useEffect(() => {
    const handler = (e) => keys.current(e);
    const track = (e) => { refs.pointer.current = { x: e.clientX, y: e.clientY }; };
    window.addEventListener('keydown', handler);
    window.addEventListener('pointermove', track, true);
    window.addEventListener('pointerup', track, true);
    return () => {
      window.removeEventListener('keydown', handler);
      window.removeEventListener('pointermove', track, true);
      window.removeEventListener('pointerup', track, true);
    };
  }, []);
}
