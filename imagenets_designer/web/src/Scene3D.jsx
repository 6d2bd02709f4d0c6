import React, { useEffect, useRef } from 'react';
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';

// One orbitable 3D view of every 3D value given: point clouds (xyzrgb), frames and poses (axes),
// pose arrays and marker arrays. Coordinates are ROS metres; the view looks along +z by default.
export function Scene3D({ items }) {
  const host = useRef(null);
  useEffect(() => {
    const width = 800, height = 560;
    const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    renderer.setSize(width, height);
    renderer.setClearColor(0x101418);
    host.current.appendChild(renderer.domElement);
    renderer.domElement.dataset.testid = 'scene3d';
    const scene = new THREE.Scene();
    scene.add(new THREE.AxesHelper(0.2));
    scene.add(new THREE.AmbientLight(0xffffff, 0.8));
    const light = new THREE.DirectionalLight(0xffffff, 1.5);
    light.position.set(1, -2, -3);
    scene.add(light);
    for (const item of items) scene.add(objectFor(item));
    const camera = new THREE.PerspectiveCamera(50, width / height, 0.01, 1000);
    frameAll(scene, camera);
    const controls = new OrbitControls(camera, renderer.domElement);
    controls.target.copy(sceneCentre(scene));
    controls.update();
    let frame = 0;
    const render = () => { renderer.render(scene, camera); frame = requestAnimationFrame(render); };
    render();
    return () => {
      cancelAnimationFrame(frame);
      controls.dispose();
      renderer.dispose();
      renderer.domElement.remove();
    };
  }, [items]);
  return <div ref={host} className="scene3d" />;
}

export function is3D(header) {
  return header.format === 'xyzrgb' || ['geometry_msgs/TransformStamped', 'geometry_msgs/PoseStamped',
    'geometry_msgs/PoseArray', 'visualization_msgs/MarkerArray'].includes(header.type);
}

function objectFor({ header, payload, value }) {
  if (header.format === 'xyzrgb') return pointCloud(payload);
  if (header.type === 'geometry_msgs/PoseArray') {
    const group = new THREE.Group();
    for (const pose of value.poses || []) group.add(axes(pose, 0.05));
    return group;
  }
  if (header.type === 'visualization_msgs/MarkerArray') {
    const group = new THREE.Group();
    for (const m of value.markers || []) group.add(marker(m));
    return group;
  }
  return axes(value, 0.1);
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

// visualization_msgs/Marker types: 0 arrow, 1 cube, 2 sphere, 3 cylinder, 4 line strip,
// 5 line list, 6 cube list, 7 sphere list, 8 points.
function marker(m) {
  const c = m.color || { r: 1, g: 1, b: 1, a: 1 };
  const color = new THREE.Color(c.r, c.g, c.b);
  const s = m.scale || { x: 0.05, y: 0.05, z: 0.05 };
  const points = (m.points || []).map((p) => new THREE.Vector3(p.x, p.y, p.z));
  let object;
  if (m.type === 4 || m.type === 5) {
    const geometry = new THREE.BufferGeometry().setFromPoints(points);
    const material = new THREE.LineBasicMaterial({ color });
    object = m.type === 4 ? new THREE.Line(geometry, material) : new THREE.LineSegments(geometry, material);
  } else if (m.type >= 6) {
    object = new THREE.Points(new THREE.BufferGeometry().setFromPoints(points),
      new THREE.PointsMaterial({ color, size: Math.max(s.x, 0.005) }));
  } else {
    const geometry = m.type === 2 ? new THREE.SphereGeometry(0.5, 16, 12)
      : m.type === 3 ? new THREE.CylinderGeometry(0.5, 0.5, 1, 16).rotateX(Math.PI / 2)
        : new THREE.BoxGeometry(1, 1, 1);
    object = new THREE.Mesh(geometry, new THREE.MeshStandardMaterial({ color, transparent: c.a < 1, opacity: c.a }));
    object.scale.set(s.x || 0.01, s.y || 0.01, s.z || 0.01);
  }
  return place(object, m.pose || {});
}

function sceneCentre(scene) {
  const box = new THREE.Box3().setFromObject(scene);
  return box.isEmpty() ? new THREE.Vector3() : box.getCenter(new THREE.Vector3());
}

// Camera behind the scene's centre (ROS optical frames look along +z, y down).
function frameAll(scene, camera) {
  const box = new THREE.Box3().setFromObject(scene);
  const size = box.isEmpty() ? 1 : Math.max(...box.getSize(new THREE.Vector3()).toArray(), 0.2);
  const centre = sceneCentre(scene);
  camera.up.set(0, -1, 0);
  camera.position.set(centre.x + 0.3 * size, centre.y - 0.5 * size, centre.z - 1.6 * size);
  camera.lookAt(centre);
}
