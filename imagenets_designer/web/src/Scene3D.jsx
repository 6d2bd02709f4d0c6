import React, { useEffect, useRef, useState } from 'react';
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { CSS2DObject, CSS2DRenderer } from 'three/examples/jsm/renderers/CSS2DRenderer.js';

// Backgrounds a point cloud of any colour stands out from: mid grey by default, so dark and
// light points both show; dark and light for clouds of one kind.
export const BACKGROUNDS = { grey: 0x5c6670, dark: 0x101418, light: 0xd8dde2 };

// One orbitable 3D view (paper Fig. 3.2) of every 3D value given: point clouds (xyzrgb), frames and
// poses (axes), pose arrays and marker arrays (a Joiner3D scene). Coordinates are ROS metres.
// Frames and objects carry their names, a grid under the scene and the axes at its origin give the
// scale in metres. The view keeps its camera when a new value of the same data comes.
export function Scene3D({ items, width = 800, height = 560 }) {
  const host = useRef(null);
  const view = useRef(null);
  const [background, setBackground] = useState('grey');
  const [legend, setLegend] = useState('');

  useEffect(() => {
    const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    renderer.domElement.dataset.testid = 'scene3d';
    host.current.appendChild(renderer.domElement);
    const labels = new CSS2DRenderer();
    labels.domElement.className = 'scene-labels';
    host.current.appendChild(labels.domElement);
    const scene = new THREE.Scene();
    // Meshes (objects, arrows) lit from above and from the camera's side; points are unlit.
    scene.add(new THREE.HemisphereLight(0xffffff, 0x445566, 1.6));
    const light = new THREE.DirectionalLight(0xffffff, 1.4);
    light.position.set(2, -3, 4);
    scene.add(light);
    const camera = new THREE.PerspectiveCamera(50, 1, 0.01, 1000);
    const v = { renderer, labels, scene, camera, controls: null, content: null, up: null };
    view.current = v;
    let frame = 0;
    const render = () => {
      renderer.render(scene, camera);
      labels.render(scene, camera);
      frame = requestAnimationFrame(render);
    };
    render();
    return () => {
      cancelAnimationFrame(frame);
      v.controls?.dispose();
      if (v.content) dispose(v.content);
      renderer.dispose();
      renderer.domElement.remove();
      labels.domElement.remove();
    };
  }, []);

  useEffect(() => {
    const v = view.current;
    v.renderer.setSize(width, height);
    v.labels.setSize(width, height);
    v.camera.aspect = width / height;
    v.camera.updateProjectionMatrix();
  }, [width, height]);

  useEffect(() => { view.current.renderer.setClearColor(BACKGROUNDS[background]); }, [background]);

  useEffect(() => {
    const v = view.current;
    if (v.content) dispose(v.content);
    const content = new THREE.Group();
    for (const item of items) content.add(objectFor(item));
    const { frame, optical } = frameOf(items);
    const up = optical ? new THREE.Vector3(0, -1, 0) : new THREE.Vector3(0, 0, 1);
    const scale = addScale(content, up, frame);
    v.scene.add(content);
    v.content = content;
    setLegend(`grid ${metres(scale.step)} squares · axes ${metres(scale.axis)} at ${frame || 'the origin'}`
      + ' (x red, y green, z blue) · drag to turn, right-drag to pan, wheel to zoom');
    // The camera is placed for the first value, and again only when the scene's up changes: new
    // values of the same data keep the user's view.
    if (!v.up || !v.up.equals(up)) {
      v.up = up;
      v.camera.up.copy(up);
      v.controls?.dispose();
      const centre = frameAll(content, v.camera, up);
      v.controls = new OrbitControls(v.camera, v.labels.domElement);
      v.controls.target.copy(centre);
      v.controls.update();
    }
  }, [items]);

  return (
    <div className="scene3d-view">
      <div ref={host} className="scene3d" style={{ width, height }} />
      <div className="scene-legend" data-testid="scene-legend">
        <span>{legend}</span>
        <label>background{' '}
          <select data-testid="scene-background" value={background} onChange={(e) => setBackground(e.target.value)}>
            {Object.keys(BACKGROUNDS).map((b) => <option key={b} value={b}>{b}</option>)}
          </select>
        </label>
      </div>
    </div>
  );
}

export function is3D(header) {
  return header.format === 'xyzrgb' || ['geometry_msgs/TransformStamped', 'geometry_msgs/PoseStamped',
    'geometry_msgs/PoseArray', 'visualization_msgs/MarkerArray'].includes(header.type);
}

// The frame the data is given in, and whether it is a camera's optical frame (z forward, y down)
// rather than a body frame (REP-103: z up).
function frameOf(items) {
  let frame = '';
  for (const { header, value } of items) {
    frame ||= header.frame_id || value?.frame_id || (value?.markers || []).map((m) => m.frame_id).find(Boolean) || '';
  }
  return { frame, optical: /optical/.test(frame) };
}

function label(text, className = '') {
  const element = document.createElement('div');
  element.className = `scene-label ${className}`;
  element.textContent = text;
  return new CSS2DObject(element);
}

function labelAt(text, position, className) {
  const l = label(text, className);
  l.position.copy(position);
  return l;
}

function objectFor({ header, payload, value }) {
  const group = new THREE.Group();
  if (header.format === 'xyzrgb') {
    const cloud = pointCloud(payload);
    group.add(cloud);
    // The cloud's name above its middle.
    const box = new THREE.Box3().setFromObject(cloud);
    if (!box.isEmpty()) group.add(labelAt(`${header.port} (${header.points ?? ''} points)`, box.getCenter(new THREE.Vector3()), 'object'));
  } else if (header.type === 'geometry_msgs/PoseArray') {
    (value.poses || []).forEach((pose, i) => {
      const a = axes(pose, 0.05);
      a.add(label(`${header.port}[${i}]`, 'frame'));
      group.add(a);
    });
  } else if (header.type === 'visualization_msgs/MarkerArray') {
    for (const m of value.markers || []) {
      const object = marker(m);
      if (object) group.add(object);
    }
  } else {
    // A frame (parent -> child) or a pose: axes named by the child frame or the port.
    const a = axes(value, 0.1);
    a.add(label(value.child_frame_id || header.port, 'frame'));
    group.add(a);
  }
  return group;
}

function pointCloud(payload) {
  const stride = 16; // float32 x, y, z + uint8 r, g, b, pad
  const count = Math.floor(payload.byteLength / stride);
  const view = new DataView(payload.buffer, payload.byteOffset, payload.byteLength);
  const positions = new Float32Array(count * 3);
  const colors = new Float32Array(count * 3);
  for (let i = 0; i < count; ++i) {
    for (let k = 0; k < 3; ++k) {
      positions[3 * i + k] = view.getFloat32(i * stride + 4 * k, true);
      colors[3 * i + k] = view.getUint8(i * stride + 12 + k) / 255;
    }
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  geometry.setAttribute('color', new THREE.BufferAttribute(colors, 3));
  return new THREE.Points(geometry, new THREE.PointsMaterial({ size: 2, sizeAttenuation: false, vertexColors: true }));
}

// A frame or pose: {xyz, q:[x,y,z,w]} or {position:{x,y,z}, orientation:{x,y,z,w}}.
function place(object, pose) {
  const p = pose.xyz || (pose.position && [pose.position.x, pose.position.y, pose.position.z]) || [0, 0, 0];
  const q = pose.q || (pose.orientation && [pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w]) || [0, 0, 0, 1];
  object.position.set(p[0], p[1], p[2]);
  object.quaternion.set(q[0], q[1], q[2], q[3]);
  return object;
}

function axes(pose, size) {
  return place(new THREE.AxesHelper(size), pose);
}

const vector = (p) => new THREE.Vector3(p.x, p.y, p.z);
// Namespaces of a Joiner3D scene that are not objects of their own.
const UNNAMED = new Set(['frames', 'frame_names', 'clouds', '']);

// visualization_msgs/Marker: 0 arrow, 1 cube, 2 sphere, 3 cylinder, 4 line strip, 5 line list,
// 6 cube list, 7 sphere list, 8 points, 9 text, 10 mesh (drawn as its box), 11 triangle list.
// Actions 2 (delete) and 3 (delete all) draw nothing. Objects are named by their namespace.
function marker(m) {
  if (m.action === 2 || m.action === 3) return null;
  const c = m.color || { r: 1, g: 1, b: 1, a: 1 };
  const color = new THREE.Color(c.r, c.g, c.b);
  const s = m.scale || { x: 0.05, y: 0.05, z: 0.05 };
  const points = (m.points || []).map(vector);
  const perPoint = m.colors?.length === points.length && points.length > 0;
  let object;
  if (m.type === 9) {
    return place(new THREE.Group(), m.pose || {}).add(label(m.text || '', 'frame'));
  } else if (m.type === 0 && points.length >= 2) {
    const direction = points[1].clone().sub(points[0]);
    object = new THREE.ArrowHelper(direction.clone().normalize(), points[0], direction.length(), color,
      Math.min(direction.length() * 0.3, (s.y || s.x * 2) * 2), s.y || s.x * 2);
    return place(new THREE.Group(), m.pose || {}).add(object);
  } else if (m.type === 4 || m.type === 5) {
    const geometry = new THREE.BufferGeometry().setFromPoints(points);
    const material = new THREE.LineBasicMaterial({ color });
    object = m.type === 4 ? new THREE.Line(geometry, material) : new THREE.LineSegments(geometry, material);
  } else if (m.type >= 6 && m.type <= 8) {
    const geometry = new THREE.BufferGeometry().setFromPoints(points);
    if (perPoint) geometry.setAttribute('color', new THREE.Float32BufferAttribute(m.colors.flatMap((k) => [k.r, k.g, k.b]), 3));
    object = new THREE.Points(geometry, new THREE.PointsMaterial({ color: perPoint ? 0xffffff : color, vertexColors: perPoint,
      size: 2, sizeAttenuation: false }));
  } else if (m.type === 11) {
    const geometry = new THREE.BufferGeometry().setFromPoints(points);
    geometry.computeVertexNormals();
    object = new THREE.Mesh(geometry, new THREE.MeshStandardMaterial({ color, side: THREE.DoubleSide, transparent: c.a < 1, opacity: c.a }));
  } else {
    const geometry = m.type === 2 ? new THREE.SphereGeometry(0.5, 24, 16)
      : m.type === 3 ? new THREE.CylinderGeometry(0.5, 0.5, 1, 24).rotateX(Math.PI / 2)
        : new THREE.BoxGeometry(1, 1, 1);
    const mesh = new THREE.Mesh(geometry, new THREE.MeshStandardMaterial({ color, transparent: c.a < 1, opacity: c.a }));
    mesh.scale.set(s.x || 0.01, s.y || 0.01, s.z || 0.01);
    object = new THREE.Group().add(mesh);
  }
  place(object, m.pose || {});
  if (!UNNAMED.has(m.ns || '')) object.add(label(m.ns, 'object'));
  return object;
}

// A step of 1, 2 or 5 times a power of ten that cuts `span` into about eight.
export function niceStep(span) {
  const raw = Math.max(span, 1e-6) / 8;
  const power = 10 ** Math.floor(Math.log10(raw));
  const m = raw / power;
  return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * power;
}

export function metres(v) {
  return v >= 1 ? `${Number(v.toPrecision(3))} m` : `${Number((v * 100).toPrecision(3))} cm`;
}

// A grid under the scene (its floor, seen along `up`) in steps of a round number of metres, with
// distances along two of its edges, and the axes of `frame` at the origin with their names.
function addScale(content, up, frame) {
  const box = new THREE.Box3().setFromObject(content).expandByPoint(new THREE.Vector3());
  const size = box.getSize(new THREE.Vector3());
  // The two horizontal axes and the vertical one, as indices of x, y, z.
  const vertical = Math.abs(up.z) > 0.5 ? 2 : 1;
  const [a, b] = [0, 1, 2].filter((k) => k !== vertical);
  const step = niceStep(Math.max(size.getComponent(a), size.getComponent(b), 0.2));
  const lo = [Math.floor(box.min.getComponent(a) / step) * step, Math.floor(box.min.getComponent(b) / step) * step];
  const hi = [Math.ceil(box.max.getComponent(a) / step) * step, Math.ceil(box.max.getComponent(b) / step) * step];
  // The floor: below everything, seen from `up` (y grows downwards in an optical frame).
  const floor = up.getComponent(vertical) > 0 ? Math.min(box.min.getComponent(vertical), 0) : Math.max(box.max.getComponent(vertical), 0);
  const point = (u, w) => {
    const p = new THREE.Vector3();
    p.setComponent(a, u);
    p.setComponent(b, w);
    p.setComponent(vertical, floor);
    return p;
  };
  const lines = [];
  for (let u = lo[0]; u <= hi[0] + step / 2; u += step) lines.push(point(u, lo[1]), point(u, hi[1]));
  for (let w = lo[1]; w <= hi[1] + step / 2; w += step) lines.push(point(lo[0], w), point(hi[0], w));
  const grid = new THREE.LineSegments(new THREE.BufferGeometry().setFromPoints(lines),
    new THREE.LineBasicMaterial({ color: 0xa9b3bd, transparent: true, opacity: 0.55 }));
  content.add(grid);
  // Distances from the origin along both edges, at most about six each.
  const distance = (v) => (Math.abs(v) < step / 100 ? '0' : `${v < 0 ? '-' : ''}${metres(Math.abs(v))}`);
  const every = (n) => Math.max(1, Math.ceil(n / 6));
  const nA = Math.round((hi[0] - lo[0]) / step), nB = Math.round((hi[1] - lo[1]) / step);
  for (let i = 0; i <= nA; i += every(nA)) {
    const u = lo[0] + i * step;
    content.add(labelAt(`${'xyz'[a]} ${distance(u)}`, point(u, lo[1]), 'distance'));
  }
  for (let i = every(nB); i <= nB; i += every(nB)) {  // the corner has its label from the first edge
    const w = lo[1] + i * step;
    content.add(labelAt(`${'xyz'[b]} ${distance(w)}`, point(lo[0], w), 'distance'));
  }
  const axis = 2 * step;
  const origin = new THREE.AxesHelper(axis);
  content.add(origin);
  ['x', 'y', 'z'].forEach((name, k) => {
    const tip = new THREE.Vector3();
    tip.setComponent(k, axis * 1.08);
    content.add(labelAt(name, tip, `axis axis-${name}`));
  });
  if (frame) content.add(labelAt(frame, new THREE.Vector3(), 'frame origin'));
  return { step, axis };
}

function dispose(group) {
  group.removeFromParent();
  group.traverse((o) => {
    o.geometry?.dispose();
    if (o.material) [].concat(o.material).forEach((m) => m.dispose());
    if (o.isCSS2DObject) o.element.remove();
  });
}

// The camera looking at the whole scene from behind and above (an optical frame: from behind the
// camera; a body frame: from behind-left of x, looking forward).
function frameAll(content, camera, up) {
  const box = new THREE.Box3().setFromObject(content);
  const size = box.isEmpty() ? 1 : Math.max(...box.getSize(new THREE.Vector3()).toArray(), 0.2);
  const centre = box.isEmpty() ? new THREE.Vector3() : box.getCenter(new THREE.Vector3());
  const offset = up.z > 0.5 ? new THREE.Vector3(-1.3, -0.9, 0.8) : new THREE.Vector3(0.3, -0.5, -1.6);
  camera.position.copy(centre).addScaledVector(offset, size);
  camera.lookAt(centre);
  return centre;
}
