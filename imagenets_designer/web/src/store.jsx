import React, { createContext, useContext, useEffect, useMemo, useReducer, useRef } from 'react';
import { Connection } from './connection.js';
import { split } from './flow.js';
import { drawNow, thumbnailImage } from './Preview.jsx';
import { initialState, reducer } from './reducer.js';

const Store = createContext(null);

// The page's one store (reducer.js), the connection to the server and what the page keeps outside
// the state (the clipboard, the canvas element, the last pointer position).
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
    // The document of the net state the page was last handed: a preview of another is not drawn
    // ahead of the render (the reducer decides once the held state is handed on).
    let shownDocument;
    const onData = ({ header, payload }) => {
      const data = { header, payload, value: header.value };
      const hand = (action) => { conn.flush(); dispatch(action); };
      if (header.mode === 'full') { hand({ type: 'fullData', data }); return; }
      const store = (value) => hand({ type: 'preview', port: header.port, document: header.document, value });
      if (header.format === 'pixels') {
        // A thumbnail is drawn in this task, before the page re-renders, then kept for the render.
        const image = thumbnailImage(header, payload);
        if (header.document === undefined || header.document === shownDocument) drawNow(header.port, image, header.run ?? header.revision);
        store({ ...data, image });
      } else {
        store(data);
      }
    };
    const offs = [
      conn.on('net', (net) => dispatch({ type: 'net', net })),
      conn.on('net', (net) => { shownDocument = net.document; }),
      conn.on('event', (event) => dispatch({ type: 'event', event })),
      conn.on('error', (e) => tools.say(e.error, true)),
      conn.on('closed', () => { dispatch({ type: 'closed' }); tools.say('connection to the designer closed', true); }),
      conn.on('data', onData),
    ];
    conn.request('hello').then((reply) => {
      shownDocument = reply.net.document;
      dispatch({ type: 'hello', registry: reply.registry, net: reply.net });
    })
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
