// The page's store without a browser: what each message from the server does to the state.
import test from 'node:test';
import assert from 'node:assert/strict';
import { initialState, reducer } from '../src/reducer.js';

const port = (name, type = 'sensor_msgs/Image') => ({ name, type });
const block = (name, position) => ({ name, type: 'imagenets/Grayscale', position, inputs: [port('image')],
  outputs: [port('image')], properties: {}, stats: { runs: 0 } });
const net = (document, blocks, links = []) => ({ document, blocks, links, errors: [] });
const registry = { blocks: [], types: { 'sensor_msgs/Image': '#4a4' } };

function hello() {
  return reducer(initialState, { type: 'hello', registry, net: net(0, [block('a', [0, 0]), block('b', [200, 0])],
    [{ from: 'a.image', to: 'b.image', type: 'sensor_msgs/Image' }]) });
}

test('the first net is drawn as nodes and coloured edges, and fitted once measured', () => {
  const s = hello();
  assert.equal(s.connected, true);
  assert.deepEqual(s.nodes.map((n) => [n.id, n.position]), [['a', { x: 0, y: 0 }], ['b', { x: 200, y: 0 }]]);
  assert.equal(s.edges.length, 1);
  assert.equal(s.edges[0].style.stroke, '#4a4');
  assert.equal(s.pendingFit, true);
});

test('a new state of the same net keeps the selection and what is shown', () => {
  let s = hello();
  s = reducer(s, { type: 'nodesChanged', change: (ns) => ns.map((n) => ({ ...n, selected: n.id === 'b' })) });
  s = reducer(s, { type: 'toggleWatch', port: 'a.image' });
  s = reducer(s, { type: 'preview', port: 'a.image', document: 0, value: { header: { port: 'a.image' } } });
  s = reducer(s, { type: 'fitted' });
  s = reducer(s, { type: 'net', net: net(0, [block('a', [0, 0]), block('b', [200, 0])]) });
  assert.equal(s.nodes.find((n) => n.id === 'b').selected, true);
  assert.ok(s.previews['a.image']);
  assert.ok(s.watched.has('a.image'));
  assert.equal(s.pendingFit, false);
  assert.equal(s.edges.length, 0);
});

test('another net opened shows nothing of the last; its late values are dropped', () => {
  let s = hello();
  s = reducer(s, { type: 'toggleWatch', port: 'a.image' });
  s = reducer(s, { type: 'preview', port: 'a.image', document: 0, value: { header: { port: 'a.image' } } });
  s = reducer(s, { type: 'event', event: { kind: 'started', block: 'a' } });
  s = reducer(s, { type: 'net', net: net(1, [block('a', [50, 50])]) });
  assert.deepEqual(s.previews, {});
  assert.equal(s.watched.size, 0);
  assert.equal(s.running.size, 0);
  assert.deepEqual(s.nodes[0].position, { x: 50, y: 50 });
  assert.equal(reducer(s, { type: 'preview', port: 'a.image', document: 0, value: {} }), s);
  assert.equal(reducer(s, { type: 'fullData', data: { header: { port: 'a.image', document: 0 } } }), s);
});

test('run events mark blocks running or cached and bring their stats', () => {
  let s = hello();
  s = reducer(s, { type: 'event', event: { kind: 'started', block: 'a' } });
  assert.ok(s.running.has('a'));
  s = reducer(s, { type: 'event', event: { kind: 'finished', block: 'a', stats: { runs: 1 } } });
  assert.equal(s.running.size, 0);
  assert.equal(s.net.blocks[0].stats.runs, 1);
  s = reducer(s, { type: 'event', event: { kind: 'cached', block: 'b' } });
  assert.ok(s.cached.has('b'));
  // Blocks inside a sub-net are not on this canvas.
  assert.equal(reducer(s, { type: 'event', event: { kind: 'started', block: 'sub/x' } }), s);
  s = reducer(s, { type: 'event', event: { kind: 'started', block: 'a' } });
  assert.equal(reducer(s, { type: 'event', event: { kind: 'run_finished' } }).running.size, 0);
});

test('the data window keeps the port it shows', () => {
  let s = hello();
  const first = { header: { port: 'a.image', document: 0, run: 1 } };
  s = reducer(s, { type: 'fullData', data: first });
  s = reducer(s, { type: 'fullData', data: { header: { port: 'b.image', document: 0 } } });
  assert.equal(s.fullData, first);
  const next = { header: { port: 'a.image', document: 0, run: 2 } };
  assert.equal(reducer(s, { type: 'fullData', data: next }).fullData, next);
});
