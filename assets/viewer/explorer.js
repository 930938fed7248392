// tumble's principal-axes explorer: a body turned by Euler angles (any of the 12 sequences,
// intrinsic or extrinsic; the article's intrinsic ZYZ by default) while its inertia tensor in
// the lab frame, R I Rᵀ, is recomputed, with its principal moments and axes, and a button that
// turns it into its principal frame (the off-diagonal terms vanish). The numbers are those of
// `tumble inertia --euler … --json`.
import * as THREE from 'three';
import { stage, axes, body, el, label, credits, power } from './common.js';

// The principal axes' colours (the lab's and the body's x, y, z use AXIS_COLOURS).
const PRINCIPAL_COLOURS = ['#cc79a7', '#e69f00', '#444444'];

const SEQUENCES = ['ZYZ', 'ZXZ', 'XYX', 'XZX', 'YXY', 'YZY', 'XYZ', 'XZY', 'YXZ', 'YZX', 'ZXY', 'ZYX'];
// Digits after the point of the displayed numbers (in the unit shown).
const DECIMALS = 6;

// The rotation about axis k (0, 1, 2) by a, as tumble-kinematics' Axis::rotation writes it.
function axisRotation(k, a) {
  const c = Math.cos(a), s = Math.sin(a);
  if (k === 0) return [[1, 0, 0], [0, c, -s], [0, s, c]];
  if (k === 1) return [[c, 0, s], [0, 1, 0], [-s, 0, c]];
  return [[c, -s, 0], [s, c, 0], [0, 0, 1]];
}
function mul(a, b) {
  const out = [[0, 0, 0], [0, 0, 0], [0, 0, 0]];
  for (let i = 0; i < 3; i++) for (let j = 0; j < 3; j++) {
    let sum = 0;
    for (let k = 0; k < 3; k++) sum += a[i][k] * b[k][j];
    out[i][j] = sum;
  }
  return out;
}
function transpose(a) { return [0, 1, 2].map((i) => [0, 1, 2].map((j) => a[j][i])); }
function apply(a, v) { return [0, 1, 2].map((i) => a[i][0] * v[0] + a[i][1] * v[1] + a[i][2] * v[2]); }

// R for `angles` in the convention: intrinsic R = R_a1 R_a2 R_a3; extrinsic (about fixed axes
// a1, a2, a3 in turn) R = R_a3(γ) R_a2(β) R_a1(α).
export function rotation(sequence, extrinsic, angles) {
  let axes = [...sequence].map((c) => 'XYZ'.indexOf(c));
  let a = angles.slice();
  if (extrinsic) { axes = axes.reverse(); a = a.reverse(); }
  return mul(mul(axisRotation(axes[0], a[0]), axisRotation(axes[1], a[1])), axisRotation(axes[2], a[2]));
}

// Fixed-point in units of 10^k, without a negative zero.
export function fixed(value, k) {
  const text = (value / Math.pow(10, k)).toFixed(DECIMALS);
  return /^-0\.0*$/.test(text) ? text.slice(1) : text;
}
function exponent(x) { return x > 0 ? Math.floor(Math.log10(x)) : 0; }
function unit(k, what) { return k === 0 ? what : `${power(k)} ${what}`; }

export function start(data) {
  const reach = data.reach;
  const tensorK = exponent(Math.max(...data.principal_moments));
  const lengthK = exponent(reach);
  // No playback: the view takes the controls' row too.
  document.getElementById('controls').style.display = 'none';
  document.getElementById('view').style.gridRow = '1 / span 2';
  const { scene } = stage(reach, () => {});
  scene.add(axes(1.4 * reach, ['X', 'Y', 'Z'], true));
  const group = body(data.parts, '#56b4e9');
  group.add(axes(0.9 * reach, ['x', 'y', 'z'], false));
  // The principal axes: thick bars through the centre of mass, labelled 1, 2, 3.
  const Q = data.principal_axes;
  for (let k = 0; k < 3; k++) {
    const dir = new THREE.Vector3(Q[0][k], Q[1][k], Q[2][k]);
    const length = 1.25 * reach;
    const bar = new THREE.Mesh(new THREE.CylinderGeometry(0.012 * reach, 0.012 * reach, 2 * length, 12),
      new THREE.MeshStandardMaterial({ color: PRINCIPAL_COLOURS[k], roughness: 0.4 }));
    bar.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), dir);
    group.add(bar);
    const tag = label(`e${k + 1}`, PRINCIPAL_COLOURS[k], 0.12 * reach);
    tag.position.copy(dir.clone().multiplyScalar(length * 1.08));
    group.add(tag);
  }
  scene.add(group);

  // The side panel.
  const side = document.getElementById('side');
  const sequence = el('select', { id: 'sequence', title: 'axis sequence' });
  for (const s of SEQUENCES) sequence.append(el('option', { value: s, text: s }));
  const kind = el('select', { id: 'kind' }, el('option', { value: 'intrinsic', text: 'intrinsic (moving axes)' }),
    el('option', { value: 'extrinsic', text: 'extrinsic (fixed axes)' }));
  const sliders = [0, 1, 2].map((k) => {
    const range = el('input', { type: 'range', id: 'angle-range-' + k, min: -Math.PI, max: Math.PI, step: 0.001 });
    const number = el('input', { type: 'number', id: 'angle-' + k, step: 0.001 });
    const name = el('span', { id: 'angle-name-' + k });
    range.addEventListener('input', () => { angles[k] = Number(range.value); number.value = angles[k].toFixed(4); update(); });
    number.addEventListener('input', () => { const v = Number(number.value); if (Number.isFinite(v)) { angles[k] = v; range.value = v; update(); } });
    return { range, number, name };
  });
  const angles = data.start.slice();
  const snap = el('button', { type: 'button', id: 'snap', text: 'Snap to the principal frame' });
  const zero = el('button', { type: 'button', id: 'zero', text: 'Angles to 0' });
  const tensor = el('table', { class: 'tensor', id: 'tensor' });
  const cells = [0, 1, 2].map(() => [0, 1, 2].map(() => el('td')));
  cells.forEach((row) => tensor.append(el('tr', {}, ...row)));
  const axesTable = el('table', { class: 'tensor', id: 'axes' });
  const axisCells = [0, 1, 2].map(() => [0, 1, 2].map(() => el('td')));
  axisCells.forEach((row) => axesTable.append(el('tr', {}, ...row)));
  const centre = el('div', { id: 'centre', class: 'mono' });
  const note = el('div', { id: 'note', class: 'muted' });
  const m = data.principal_moments;
  side.append(
    el('h1', { text: 'Principal axes' }),
    el('div', { class: 'muted', text: data.sources.join('; ') }),
    el('div', { class: 'muted', text: `mass ${+data.mass.toPrecision(6)} kg; turn the body with Euler angles until the off-diagonal terms vanish.` }),
    el('p', {}, sequence, ' ', kind),
    ...sliders.map((s) => el('div', { class: 'slider' }, s.name, s.range, s.number)),
    el('p', {}, snap, ' ', zero),
    note,
    el('div', { text: `Inertia tensor about the centre of mass, lab frame, R I Rᵀ (${unit(tensorK, 'kg·m²')}):` }),
    tensor,
    el('div', { id: 'moments', text: `Principal moments (${unit(tensorK, 'kg·m²')}): I1 = ${fixed(m[0], tensorK)}, I2 = ${fixed(m[1], tensorK)}, I3 = ${fixed(m[2], tensorK)}` }),
    el('div', { text: 'Principal axes e1 e2 e3 in the lab frame (columns), R Q:' }),
    axesTable,
    el('div', {}, `Centre of mass in the lab frame, R c (${unit(lengthK, 'm')}): `, centre));
  tensor.dataset.exponent = tensorK;
  centre.dataset.exponent = lengthK;

  function convention() { return { sequence: sequence.value, extrinsic: kind.value === 'extrinsic' }; }
  function names() {
    const c = convention();
    const s = c.sequence;
    const greek = s === 'ZYZ' || s === 'ZXZ' ? ['φ', 'θ', 'ψ'] : ['α', 'β', 'γ'];
    sliders.forEach((sl, k) => {
      sl.name.textContent = greek[k];
      sl.name.title = `about ${s[k]}${c.extrinsic ? ' (fixed)' : k === 0 ? '' : "'".repeat(k)}`;
    });
  }
  function set(values) {
    values.forEach((v, k) => { angles[k] = v; sliders[k].range.value = v; sliders[k].number.value = v.toFixed(4); });
    update();
  }
  let lastKey = null;
  function update() {
    const c = convention();
    const R = rotation(c.sequence, c.extrinsic, angles);
    const I = mul(mul(R, data.inertia), transpose(R));
    const largest = Math.max(...m);
    for (let i = 0; i < 3; i++) for (let j = 0; j < 3; j++) {
      const v = 0.5 * (I[i][j] + I[j][i]);
      const td = cells[i][j];
      td.textContent = fixed(v, tensorK);
      td.className = i === j ? '' : Number(td.textContent) === 0 ? 'off zero' : 'off';
      if (i !== j && Number(td.textContent) !== 0) {
        // Yellow fading to white as the term approaches zero.
        const share = Math.min(1, Math.abs(v) / largest * 4);
        td.style.background = `rgba(255, 193, 7, ${0.15 + 0.6 * share})`;
      } else td.style.background = '';
    }
    const RQ = mul(R, Q);
    for (let i = 0; i < 3; i++) for (let j = 0; j < 3; j++) axisCells[i][j].textContent = fixed(RQ[i][j], 0);
    const c0 = apply(R, data.center_of_mass);
    centre.textContent = `(${c0.map((x) => fixed(x, lengthK)).join(', ')})`;
    const key = (c.extrinsic ? 'extrinsic-' : 'intrinsic-') + c.sequence.toLowerCase();
    if (key !== lastKey) { names(); lastKey = key; }
    const p = data.principal_euler[key];
    note.textContent = `The principal frame in ${c.extrinsic ? 'extrinsic' : 'intrinsic'} ${c.sequence}: (${p.angles.map((x) => x.toFixed(4)).join(', ')}) rad${p.gimbal_lock ? ' (gimbal lock: only the sum or difference of the first and third is determined)' : ''}.`;
    const M4 = new THREE.Matrix4().set(R[0][0], R[0][1], R[0][2], 0, R[1][0], R[1][1], R[1][2], 0, R[2][0], R[2][1], R[2][2], 0, 0, 0, 0, 1);
    group.quaternion.setFromRotationMatrix(M4);
  }
  sequence.addEventListener('change', update);
  kind.addEventListener('change', update);
  snap.addEventListener('click', () => {
    const c = convention();
    set(data.principal_euler[(c.extrinsic ? 'extrinsic-' : 'intrinsic-') + c.sequence.toLowerCase()].angles);
  });
  zero.addEventListener('click', () => set([0, 0, 0]));
  set(angles);
  credits();

  Object.assign(window.tumble, {
    setAngles: (values, seq, extrinsic) => {
      if (seq) sequence.value = seq;
      kind.value = extrinsic ? 'extrinsic' : 'intrinsic';
      set(values);
    },
    tensor: () => cells.map((row) => row.map((td) => td.textContent)),
    axes: () => axisCells.map((row) => row.map((td) => td.textContent)),
    centre: () => centre.textContent,
    exponents: { tensor: tensorK, length: lengthK },
  });
}
