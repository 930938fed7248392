// tumble's run viewer: the bodies of one run in 3D, played back from the page's frames
// (poses interpolated between them), with the lab and body axes, the angular velocity and
// angular momentum, a smooth trail, and the run's columns plotted with a cursor at the time
// shown.
import * as THREE from 'three';
import { stage, axes, body, arrow, floats, el, credits } from './common.js';

// Points of the trail between two frames (centripetal Catmull–Rom through the frames).
const SUBDIVISIONS = 8;

export function start(data) {
  const values = floats(data.data);
  const n = data.frames;
  const arrays = {};
  for (const a of data.layout) arrays[a.name] = { width: a.width, data: values.subarray(a.offset, a.offset + a.width * n) };
  const time = arrays['col:t'].data;
  const tEnd = time[n - 1];
  const reach = data.reach;

  // Where time t falls: frame i and the fraction to frame i + 1.
  function locate(t) {
    let lo = 0, hi = n - 1;
    if (t <= time[0]) return [0, 0];
    if (t >= time[n - 1]) return [n - 1, 0];
    while (hi - lo > 1) { const mid = (lo + hi) >> 1; if (time[mid] <= t) lo = mid; else hi = mid; }
    return [lo, (t - time[lo]) / (time[lo + 1] - time[lo])];
  }
  function vec(name, i, f) {
    const a = arrays[name], w = a.width, d = a.data;
    const j = Math.min(i + 1, n - 1);
    const out = [];
    for (let k = 0; k < w; k++) out.push(d[w * i + k] + f * (d[w * j + k] - d[w * i + k]));
    return out;
  }
  const q0 = new THREE.Quaternion(), q1 = new THREE.Quaternion();
  function quat(name, i, f, target) {
    const d = arrays[name].data, j = Math.min(i + 1, n - 1);
    q0.fromArray(d, 4 * i);
    q1.fromArray(d, 4 * j);
    target.slerpQuaternions(q0, q1, f);
  }

  const state = { t: 0, playing: false, speed: 1, last: null, loop: false };
  const { scene } = stage(reach, (now) => {
    if (state.playing && state.last !== null) {
      state.t += (now - state.last) / 1000 * state.speed;
      if (state.t >= tEnd) {
        if (state.loop) state.t = 0; else { state.t = tEnd; state.playing = false; }
      }
    }
    state.last = now;
    show();
  });

  // Lab axes (dashed), the bodies, their axes, the vectors and the trail.
  const lab = axes(1.35 * reach, ['X', 'Y', 'Z'], true);
  scene.add(lab);
  const objects = data.objects.map((o) => {
    const group = body(o.parts, o.colour);
    let frame = null;
    if (o.axes) { frame = axes(0.9 * reach, ['x', 'y', 'z'], false); group.add(frame); }
    scene.add(group);
    return { spec: o, group, frame };
  });
  const vectors = data.vectors.map((v) => {
    const a = arrow(v.colour, reach);
    scene.add(a.object);
    return { spec: v, arrow: a };
  });
  const trailPoints = [];
  const tr = arrays.trail.data;
  for (let i = 0; i < n; i++) trailPoints.push(new THREE.Vector3(tr[3 * i], tr[3 * i + 1], tr[3 * i + 2]));
  const curve = new THREE.CatmullRomCurve3(trailPoints, false, 'centripetal');
  const densePoints = [];
  for (let i = 0; i + 1 < n; i++) {
    for (let s = 0; s < SUBDIVISIONS; s++) densePoints.push(curve.getPoint((i + s / SUBDIVISIONS) / (n - 1)));
  }
  densePoints.push(trailPoints[n - 1]);
  const trailGeometry = new THREE.BufferGeometry().setFromPoints(densePoints);
  const trail = new THREE.Line(trailGeometry, new THREE.LineBasicMaterial({ color: 0xe69f00 }));
  trail.frustumCulled = false;
  scene.add(trail);

  // Controls under the view.
  const controls = document.getElementById('controls');
  const play = el('button', { id: 'play', type: 'button', text: 'Play' });
  const speed = el('select', { id: 'speed', title: 'playback speed' });
  for (const s of [0.05, 0.1, 0.25, 0.5, 1, 2, 4, 8]) speed.append(el('option', { value: s, text: s + '×' }));
  speed.value = '1';
  const scrub = el('input', { id: 'scrub', type: 'range', min: 0, max: 10000, step: 1, value: 0, title: 'time' });
  const clock = el('span', { id: 'clock', class: 'muted' });
  const toggles = {};
  function toggle(name, text, on) {
    const box = el('input', { type: 'checkbox', id: 'show-' + name });
    box.checked = on;
    toggles[name] = box;
    box.addEventListener('change', show);
    return el('label', {}, box, ' ' + text);
  }
  const loop = el('input', { type: 'checkbox', id: 'loop' });
  loop.addEventListener('change', () => { state.loop = loop.checked; });
  controls.append(play, speed, scrub, clock, toggle('trail', 'trail', true),
    toggle('vectors', 'ω, L', true), toggle('body-axes', 'body axes', true),
    toggle('lab-axes', 'lab axes', true), el('label', {}, loop, ' loop'));
  play.addEventListener('click', () => {
    if (!state.playing && state.t >= tEnd) state.t = 0;
    state.playing = !state.playing;
    state.last = null;
  });
  speed.addEventListener('change', () => { state.speed = Number(speed.value); });
  scrub.addEventListener('input', () => { state.t = tEnd * Number(scrub.value) / 10000; state.playing = false; });
  // Space plays and pauses; arrows step a frame.
  window.addEventListener('keydown', (e) => {
    if (e.target.tagName === 'SELECT' || e.target.tagName === 'INPUT' && e.target.type !== 'range') return;
    if (e.key === ' ') { e.preventDefault(); play.click(); }
    if (e.key === 'ArrowRight' || e.key === 'ArrowLeft') {
      const [i] = locate(state.t);
      const k = Math.max(0, Math.min(n - 1, i + (e.key === 'ArrowRight' ? 1 : -1)));
      state.t = time[k]; state.playing = false;
    }
  });

  // The side panel: what this is, the legend and the plots.
  const side = document.getElementById('side');
  const legend = el('div', { class: 'legend' });
  for (const v of data.vectors) legend.append(el('span', {}, el('span', { class: 'swatch', style: 'background:' + v.colour }), v.label));
  legend.append(el('span', {}, el('span', { class: 'swatch', style: 'background:#e69f00' }), 'trail'));
  side.append(
    el('h1', { text: data.title }),
    el('div', { class: 'muted', text: `${data.origin === 'builtin' ? 'built-in scene' : data.origin}; ${n} frames over t in [0, ${+tEnd.toPrecision(6)}] s; largest relative energy error ${data.max_energy_rel_err.toExponential(1)}` }),
    el('div', { class: 'muted', text: 'Drag to turn, scroll to zoom, right-drag to pan; space plays, arrows step. Dashed: lab axes X Y Z; solid: body axes x y z.' }),
    legend);
  const plotted = data.columns.filter((c) => c !== 't');
  const preferred = ['tilt', 'alpha', 'omega_x', 'phi', 'energy'].find((c) => plotted.includes(c)) || plotted[0];
  const plots = [preferred, plotted.includes('energy_rel_err') ? 'energy_rel_err' : plotted[1] || plotted[0]].map((name, k) => plot(k, name));

  function plot(k, initial) {
    const select = el('select', { id: 'plot-' + k });
    for (const c of plotted) select.append(el('option', { value: c, text: c }));
    select.value = initial;
    const canvas = el('canvas', { class: 'plot', id: 'plot-canvas-' + k });
    const readout = el('span', { class: 'muted', id: 'plot-value-' + k });
    side.append(el('div', {}, select, ' ', readout), canvas);
    const p = { select, canvas, readout, image: null, frame: null };
    select.addEventListener('change', () => { draw(p); show(); });
    return p;
  }
  // Margins of a plot, CSS pixels.
  const M = { l: 62, r: 8, t: 8, b: 20 };
  function draw(p) {
    const ratio = window.devicePixelRatio || 1;
    const w = p.canvas.clientWidth, h = p.canvas.clientHeight;
    p.canvas.width = Math.round(w * ratio);
    p.canvas.height = Math.round(h * ratio);
    const ctx = p.canvas.getContext('2d');
    ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
    ctx.clearRect(0, 0, w, h);
    const y = arrays['col:' + p.select.value].data;
    let lo = Infinity, hi = -Infinity;
    for (const v of y) { if (v < lo) lo = v; if (v > hi) hi = v; }
    if (!(hi > lo)) { const pad = Math.abs(lo) * 0.1 || 1; lo -= pad; hi += pad; }
    const sx = (t) => M.l + (w - M.l - M.r) * t / tEnd;
    const sy = (v) => h - M.b - (h - M.t - M.b) * (v - lo) / (hi - lo);
    ctx.strokeStyle = '#ccc'; ctx.lineWidth = 1;
    ctx.strokeRect(M.l, M.t, w - M.l - M.r, h - M.t - M.b);
    ctx.fillStyle = '#555'; ctx.font = '11px sans-serif';
    ctx.textAlign = 'right'; ctx.textBaseline = 'middle';
    const fmt = (v) => (Math.abs(v) >= 1e4 || (Math.abs(v) < 1e-3 && v !== 0)) ? v.toExponential(2) : +v.toPrecision(4) + '';
    ctx.fillText(fmt(hi), M.l - 4, M.t + 4);
    ctx.fillText(fmt(lo), M.l - 4, h - M.b - 4);
    ctx.textAlign = 'center'; ctx.textBaseline = 'top';
    ctx.fillText('0', M.l, h - M.b + 4);
    ctx.fillText(+tEnd.toPrecision(4) + ' s', w - M.r - 14, h - M.b + 4);
    ctx.strokeStyle = '#0072b2'; ctx.lineWidth = 1.4;
    ctx.beginPath();
    for (let i = 0; i < n; i++) { const X = sx(time[i]), Y = sy(y[i]); if (i) ctx.lineTo(X, Y); else ctx.moveTo(X, Y); }
    ctx.stroke();
    p.image = ctx.getImageData(0, 0, p.canvas.width, p.canvas.height);
    p.sx = sx; p.w = w; p.h = h; p.frame = null;
  }
  function cursor(p, t, i, f) {
    if (!p.image) draw(p);
    const ctx = p.canvas.getContext('2d');
    ctx.putImageData(p.image, 0, 0);
    const X = p.sx(t);
    ctx.strokeStyle = '#d55e00'; ctx.lineWidth = 1.2;
    ctx.beginPath(); ctx.moveTo(X, M.t); ctx.lineTo(X, p.h - M.b); ctx.stroke();
    const v = vec('col:' + p.select.value, i, f)[0];
    p.readout.textContent = `${p.select.value} = ${v.toPrecision(6)}`;
  }
  window.addEventListener('resize', () => { for (const p of plots) draw(p); });

  const shownAt = { t: NaN };
  function show() {
    const t = state.t;
    const [i, f] = locate(t);
    for (const o of objects) {
      o.group.position.fromArray(vec(o.spec.position, i, f));
      quat(o.spec.quaternion, i, f, o.group.quaternion);
      if (o.frame) o.frame.visible = toggles['body-axes'].checked;
    }
    lab.visible = toggles['lab-axes'].checked;
    const shown = {};
    for (const v of vectors) {
      shown[v.spec.name] = vec(v.spec.array, i, f);
      v.arrow.set(shown[v.spec.name], v.spec.scale);
      if (!toggles.vectors.checked) v.arrow.object.visible = false;
    }
    trail.visible = toggles.trail.checked;
    trailGeometry.setDrawRange(0, Math.min(densePoints.length, i * SUBDIVISIONS + Math.floor(f * SUBDIVISIONS) + 1));
    if (t !== shownAt.t) {
      for (const p of plots) cursor(p, t, i, f);
      scrub.value = String(Math.round(10000 * t / tEnd));
      shownAt.t = t;
    }
    clock.textContent = `t = ${t.toFixed(3)} s`;
    play.textContent = state.playing ? 'Pause' : 'Play';
    // The angle between ω and L: zero only for a spin about a principal axis.
    let between = '';
    if (shown.omega && shown.L) {
      const [a, b] = [shown.omega, shown.L];
      const dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
      const norms = Math.hypot(...a) * Math.hypot(...b);
      if (norms > 0) between = ` · angle between ω and L ${(Math.acos(Math.max(-1, Math.min(1, dot / norms))) * 180 / Math.PI).toFixed(1)}°`;
    }
    document.getElementById('overlay').textContent = `t = ${t.toFixed(2)} s${between}`;
  }
  for (const p of plots) draw(p);
  show();
  credits();

  // For tests and scripting: the time shown, seeking and playing.
  Object.assign(window.tumble, {
    state: () => ({ t: state.t, tEnd, playing: state.playing, frame: locate(state.t)[0], frames: n }),
    seek: (t) => { state.t = Math.max(0, Math.min(tEnd, t)); state.playing = false; show(); },
    setSpeed: (s) => { state.speed = s; speed.value = String(s); },
  });
}
