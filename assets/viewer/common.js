// Shared by tumble's run viewer and principal-axes explorer: the three.js stage (renderer,
// camera, orbit controls, light), bodies built from the page's part descriptions, and axes.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

// Colour-blind-safe colours (Okabe–Ito) for x, y, z.
export const AXIS_COLOURS = ['#d55e00', '#009e73', '#0072b2'];

// The stage: a renderer in #view, a camera looking at the origin from (1, -1.6, 0.9) reach
// (lab z up), orbit controls, lights, and a render loop calling `frame(now)` first.
export function stage(reach, frame) {
  const host = document.getElementById('view');
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
  renderer.setClearColor(0xffffff, 1);
  host.prepend(renderer.domElement);
  const scene = new THREE.Scene();
  const camera = new THREE.PerspectiveCamera(40, 1, reach / 100, reach * 100);
  camera.up.set(0, 0, 1);
  camera.position.set(2.5 * reach, -3.9 * reach, 2.0 * reach);
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.target.set(0, 0, 0);
  controls.enableDamping = true;
  controls.update();
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8899aa, 1.6));
  const sun = new THREE.DirectionalLight(0xffffff, 2.0);
  sun.position.set(3 * reach, -2 * reach, 5 * reach);
  scene.add(sun);
  function resize() {
    const w = Math.max(host.clientWidth, 1), h = Math.max(host.clientHeight, 1);
    renderer.setSize(w, h, false);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
  }
  window.addEventListener('resize', resize);
  resize();
  function loop(now) {
    frame(now);
    controls.update();
    renderer.render(scene, camera);
    requestAnimationFrame(loop);
  }
  requestAnimationFrame(loop);
  return { scene, camera, controls, renderer };
}

// three.js's licence, at the end of the side panel.
export function credits() {
  const credits = document.getElementById('credits');
  if (credits) {
    credits.style.display = '';
    document.getElementById('side').append(credits);
  }
}

// A text label as a sprite, `size` high.
export function label(text, colour, size) {
  const canvas = document.createElement('canvas');
  const ctx = canvas.getContext('2d');
  ctx.font = 'bold 48px sans-serif';
  const w = Math.ceil(ctx.measureText(text).width) + 8;
  canvas.width = w;
  canvas.height = 64;
  ctx.font = 'bold 48px sans-serif';
  ctx.fillStyle = colour;
  ctx.textBaseline = 'middle';
  ctx.fillText(text, 4, 34);
  const texture = new THREE.CanvasTexture(canvas);
  texture.colorSpace = THREE.SRGBColorSpace;
  const sprite = new THREE.Sprite(new THREE.SpriteMaterial({ map: texture, depthTest: false }));
  sprite.scale.set(size * w / 64, size, 1);
  sprite.renderOrder = 10;
  return sprite;
}

// Three axes of `length` from the origin, labelled with `names` (x, y, z colours), as lines
// (`dashed` for the lab).
export function axes(length, names, dashed) {
  const group = new THREE.Group();
  const unit = [[1, 0, 0], [0, 1, 0], [0, 0, 1]];
  unit.forEach((u, k) => {
    const geometry = new THREE.BufferGeometry().setFromPoints([
      new THREE.Vector3(0, 0, 0), new THREE.Vector3(u[0] * length, u[1] * length, u[2] * length)]);
    const material = dashed
      ? new THREE.LineDashedMaterial({ color: AXIS_COLOURS[k], dashSize: length / 20, gapSize: length / 40 })
      : new THREE.LineBasicMaterial({ color: AXIS_COLOURS[k] });
    const line = new THREE.Line(geometry, material);
    if (dashed) line.computeLineDistances();
    group.add(line);
    const tag = label(names[k], AXIS_COLOURS[k], length * 0.09);
    tag.position.set(u[0] * length * 1.08, u[1] * length * 1.08, u[2] * length * 1.08);
    group.add(tag);
  });
  return group;
}

// One part (see src/view/geometry.rs) as a mesh of `material`.
export function part(description, material) {
  let geometry;
  const d = description.dims || [];
  switch (description.kind) {
    case 'mesh': {
      geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.Float32BufferAttribute(description.positions, 3));
      geometry.setIndex(description.indices);
      // Flat shading: a face normal per triangle (meshes are made of flat faces).
      geometry = geometry.toNonIndexed();
      geometry.computeVertexNormals();
      break;
    }
    case 'box': geometry = new THREE.BoxGeometry(d[0], d[1], d[2]); break;
    case 'sphere': geometry = new THREE.SphereGeometry(d[0], 32, 16); break;
    case 'torus': geometry = new THREE.TorusGeometry(d[0], d[1], 24, 128); break;
    case 'cylinder':
      // three's cylinders stand along y; the page's along z.
      geometry = new THREE.CylinderGeometry(d[0], d[0], d[1], 48).rotateX(Math.PI / 2);
      break;
    default: throw new Error('unknown part ' + description.kind);
  }
  const mesh = new THREE.Mesh(geometry, material);
  if (description.position) mesh.position.fromArray(description.position);
  if (description.quaternion) mesh.quaternion.fromArray(description.quaternion);
  return mesh;
}

// A group of parts in one colour.
export function body(parts, colour) {
  const group = new THREE.Group();
  const material = new THREE.MeshStandardMaterial({ color: colour, roughness: 0.55, metalness: 0.1, flatShading: false });
  for (const p of parts) group.add(part(p, material));
  return group;
}

// An arrow that can be set to any vector.
export function arrow(colour, reach) {
  const a = new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), new THREE.Vector3(0, 0, 0), reach, colour, 0.12 * reach, 0.06 * reach);
  a.line.material.linewidth = 2;
  return {
    object: a,
    set(v, scale) {
      const length = Math.hypot(v[0], v[1], v[2]) * scale;
      if (!(length > 1e-9 * reach)) { a.visible = false; return; }
      a.visible = true;
      a.setDirection(new THREE.Vector3(v[0], v[1], v[2]).normalize());
      const head = Math.min(0.12 * reach, 0.4 * length);
      a.setLength(length, head, 0.5 * head);
    },
  };
}

// 10^k with a superscript exponent.
export function power(k) {
  const sup = { '-': '⁻', 0: '⁰', 1: '¹', 2: '²', 3: '³', 4: '⁴', 5: '⁵', 6: '⁶', 7: '⁷', 8: '⁸', 9: '⁹' };
  return '10' + [...String(k)].map((c) => sup[c]).join('');
}

// Decodes base64 little-endian float32s.
export function floats(base64) {
  const bytes = Uint8Array.from(atob(base64), (c) => c.charCodeAt(0));
  const view = new DataView(bytes.buffer);
  const out = new Float32Array(bytes.length / 4);
  for (let i = 0; i < out.length; i++) out[i] = view.getFloat32(4 * i, true);
  return out;
}

// An element with attributes and children.
export function el(tag, attrs, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (k === 'text') e.textContent = v; else e.setAttribute(k, v);
  }
  for (const c of children) e.append(c);
  return e;
}
