// A three.js page of a scene like ArmLab's 3D view, for web/scripts/fps.mjs to measure
// beside the app in the same run: about 14 lit boxes and cylinders (an arm), a sphere (the
// target), a ground grid, 4× MSAA, a full-window canvas, no UI. Left drag on the sphere
// moves it in the view plane; elsewhere it orbits the camera. It draws a frame only when
// something moved, as the app does. `window.bench` gives the frames drawn and the
// sphere's screen point.
import * as THREE from 'three';

const renderer = new THREE.WebGLRenderer({ antialias: true });
renderer.setPixelRatio(window.devicePixelRatio);
renderer.setSize(window.innerWidth, window.innerHeight);
document.body.appendChild(renderer.domElement);

const scene = new THREE.Scene();
scene.background = new THREE.Color(0x1b1d21);
const camera = new THREE.PerspectiveCamera(45, window.innerWidth / window.innerHeight, 0.05, 50);
scene.add(new THREE.HemisphereLight(0xffffff, 0x404040, 1.2));
const key = new THREE.DirectionalLight(0xffffff, 2.0);
key.position.set(2, 3, 4);
scene.add(key);
const grid = new THREE.GridHelper(4, 40, 0x555555, 0x333333);
scene.add(grid);

// An arm: a base, six joints (cylinders) and links (boxes), a tool.
const grey = new THREE.MeshStandardMaterial({ color: 0x9aa4b0, metalness: 0.2, roughness: 0.6 });
const blue = new THREE.MeshStandardMaterial({ color: 0x4a7bd0, metalness: 0.2, roughness: 0.5 });
const cylinder = new THREE.CylinderGeometry(0.5, 0.5, 1, 32);
const box = new THREE.BoxGeometry(1, 1, 1);
let parent = scene;
const add = (geometry, material, scale, position, rotation = [0, 0, 0]) => {
  const mesh = new THREE.Mesh(geometry, material);
  mesh.scale.set(...scale);
  mesh.position.set(...position);
  mesh.rotation.set(...rotation);
  parent.add(mesh);
  return mesh;
};
add(cylinder, grey, [0.3, 0.15, 0.3], [0, 0.075, 0]);
let y = 0.15;
for (let i = 0; i < 6; i++) {
  const joint = new THREE.Group();
  joint.position.set(0, y, 0);
  joint.rotation.set(i % 2 ? 0.5 : 0, i % 2 ? 0 : 0.4, i % 2 ? 0.3 : 0);
  parent.add(joint);
  parent = joint;
  add(cylinder, blue, [0.14, 0.16, 0.14], [0, 0, 0], [Math.PI / 2, 0, 0]);
  add(box, grey, [0.09, 0.32, 0.09], [0, 0.18, 0]);
  y = 0.34;
}
parent = scene;
const target = add(new THREE.SphereGeometry(0.5, 32, 16), new THREE.MeshStandardMaterial({ color: 0x3cc36a }),
  [0.08, 0.08, 0.08], [0.5, 0.6, 0.4]);

const orbit = { yaw: 0.7, pitch: 0.45, distance: 3.2 };
function place() {
  const { yaw, pitch, distance } = orbit;
  camera.position.set(distance * Math.cos(pitch) * Math.sin(yaw), 0.6 + distance * Math.sin(pitch),
    distance * Math.cos(pitch) * Math.cos(yaw));
  camera.lookAt(0, 0.6, 0);
  camera.updateMatrixWorld();
}

let frames = 0;
let dirty = true;
function draw() {
  requestAnimationFrame(draw);
  if (!dirty) return;
  dirty = false;
  place();
  renderer.render(scene, camera);
  frames++;
}
requestAnimationFrame(draw);

function screenPoint(object) {
  const p = object.getWorldPosition(new THREE.Vector3()).project(camera);
  return { x: (p.x + 1) / 2 * window.innerWidth, y: (1 - p.y) / 2 * window.innerHeight };
}

let drag = null;
const canvas = renderer.domElement;
canvas.addEventListener('pointerdown', (e) => {
  const t = screenPoint(target);
  drag = Math.hypot(e.clientX - t.x, e.clientY - t.y) < 20 ? 'target' : 'orbit';
  drag = { kind: drag, x: e.clientX, y: e.clientY };
});
window.addEventListener('pointerup', () => { drag = null; });
canvas.addEventListener('mousemove', (e) => {
  if (!drag) return;
  const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
  drag.x = e.clientX;
  drag.y = e.clientY;
  if (drag.kind === 'orbit') {
    orbit.yaw -= dx * 0.01;
    orbit.pitch = Math.min(1.4, Math.max(-1.4, orbit.pitch + dy * 0.01));
  } else {
    // In the view plane at the sphere's depth.
    const p = target.position.clone().project(camera);
    p.x += dx / window.innerWidth * 2;
    p.y -= dy / window.innerHeight * 2;
    target.position.copy(p.unproject(camera));
  }
  dirty = true;
});

window.bench = { frames: () => frames, target: () => screenPoint(target), ready: true };
