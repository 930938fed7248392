// Browser tests of `tumble view`: the generated pages opened from file:// in headless Chromium
// (Debian's, driven by playwright-core), checked for script errors, a picture that shows the
// body and changes as it moves, playback that reaches the final frame, and explorer numbers
// equal to `tumble inertia --euler … --json` to the digits shown.
//
//   node .ci/browser/test.mjs TUMBLE_BINARY [--screenshots DIR]
import { chromium } from 'playwright-core';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, statSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

const args = process.argv.slice(2);
const tumble = resolve(args[0]);
const shots = args.includes('--screenshots') ? resolve(args[args.indexOf('--screenshots') + 1]) : null;
const work = mkdtempSync(join(tmpdir(), 'tumble-view-'));
let failures = 0;
function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures++;
}
function run(...argv) {
  return execFileSync(tumble, argv, { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });
}

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync',
    '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
});

// Opens a page; returns it with the errors it raised and its load time (to `tumble.ready`).
async function open(file) {
  const page = await browser.newPage({ viewport: { width: 1280, height: 720 } });
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  const requests = [];
  page.on('request', (r) => { if (!r.url().startsWith('file:') && !r.url().startsWith('blob:') && !r.url().startsWith('data:')) requests.push(r.url()); });
  const t0 = Date.now();
  await page.goto(pathToFileURL(file).href);
  await page.waitForFunction(() => window.tumble && (window.tumble.ready || window.tumble.errors.length > 0), null, { timeout: 30000 });
  const loaded = Date.now() - t0;
  errors.push(...await page.evaluate(() => window.tumble.errors));
  return { page, errors, loaded, requests };
}

// Pixels of the 3D view: how many are not white, and how many are close to `colour`.
async function pixels(page, colour) {
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  return page.evaluate((target) => {
    const gl = document.querySelector('#view canvas');
    const c = document.createElement('canvas');
    c.width = gl.width; c.height = gl.height;
    const ctx = c.getContext('2d');
    ctx.drawImage(gl, 0, 0);
    const d = ctx.getImageData(0, 0, c.width, c.height).data;
    let ink = 0, body = 0;
    const sample = [];
    for (let i = 0; i < d.length; i += 4) {
      if (d[i] < 240 || d[i + 1] < 240 || d[i + 2] < 240) ink++;
      // The body's hue: blue dominant over red (shaded #0072b2 / #56b4e9).
      if (d[i + 2] > d[i] + 60 && d[i + 2] > 90) body++;
      if (i % 64 === 0) sample.push(d[i] + d[i + 1] + d[i + 2]);
    }
    return { ink, body, total: d.length / 4, sample };
  }, colour);
}
function differ(a, b) {
  let n = 0;
  for (let i = 0; i < a.sample.length; i++) if (Math.abs(a.sample[i] - b.sample[i]) > 30) n++;
  return n;
}

async function runPage(name, file) {
  const size = statSync(file).size;
  // Opened twice: the first load in this browser also starts its WebGL (software) renderer.
  const cold = await open(file);
  await cold.page.close();
  check(cold.errors.length === 0, `${name}: no script error on the first load ${cold.errors.join(' | ')}`);
  const { page, errors, loaded, requests } = await open(file);
  console.log(`     ${name}: ${(size / 1e6).toFixed(2)} MB, loaded in ${cold.loaded} ms (first load), ${loaded} ms (again)`);
  check(errors.length === 0, `${name}: no script error ${errors.join(' | ')}`);
  check(requests.length === 0, `${name}: no network request ${requests.join(' ')}`);
  const first = await pixels(page);
  check(first.ink > 0.02 * first.total, `${name}: t = 0 is drawn (${first.ink} of ${first.total} pixels not white)`);
  check(first.body > 0.002 * first.total, `${name}: the body is shown (${first.body} body-coloured pixels)`);
  if (shots) await page.screenshot({ path: join(shots, `view-${name}-t0.png`) });
  const { tEnd, frames } = await page.evaluate(() => window.tumble.state());
  await page.evaluate((t) => window.tumble.seek(t), tEnd / 2);
  const middle = await pixels(page);
  check(differ(first, middle) > 20, `${name}: the picture at t = ${tEnd / 2} differs from t = 0 (${differ(first, middle)} samples)`);
  const cursor = await page.textContent('#plot-value-0');
  check(/=/.test(cursor), `${name}: the plot's cursor reads a value (${cursor})`);
  if (shots) await page.screenshot({ path: join(shots, `view-${name}-mid.png`) });
  // Playback from the start, 8× speed, by the page's own buttons: it reaches the final frame.
  await page.evaluate(() => window.tumble.seek(0));
  await page.selectOption('#speed', '8');
  await page.click('#play');
  await page.waitForFunction(() => window.tumble.state().playing, null, { timeout: 5000 });
  await page.waitForFunction(() => !window.tumble.state().playing, null, { timeout: 60000 });
  const end = await page.evaluate(() => window.tumble.state());
  check(end.t === end.tEnd && end.frame === frames - 1, `${name}: playback reached the final frame (${end.frame + 1} of ${frames}, t = ${end.t})`);
  const all = await page.evaluate(() => window.tumble.errors);
  check(all.length === 0 && errors.length === 0, `${name}: no script error during playback`);
  await page.close();
}

// The hoop and the T-handle.
const hoop = join(work, 'hoop.html');
run('view', 'free-hoop', '--t-end', '10', '-o', hoop);
await runPage('free-hoop', hoop);
const flip = join(work, 'flip.html');
run('view', 'scenes/t-handle-flip.toml', '-o', flip);
await runPage('t-handle-flip', flip);
// A model file: the gyroscope's gimbal rings and rotor, placed by the model's expressions.
const gimbals = join(work, 'gimbals.html');
run('view', 'models/gyroscope-gimbals.toml', '--t-end', '2', '-o', gimbals);
await runPage('gyroscope-gimbals', gimbals);

// The explorer against `tumble inertia --euler … --json`.
const explorer = join(work, 'explorer.html');
run('view', '--inertia', 'scenes/t-handle.obj', '--mass', '0.05', '-o', explorer);
{
  const { page, errors, loaded } = await open(explorer);
  console.log(`     explorer: loaded in ${loaded} ms`);
  check(errors.length === 0, `explorer: no script error ${errors.join(' | ')}`);
  const drawn = await pixels(page);
  check(drawn.body > 0.002 * drawn.total, `explorer: the body is shown (${drawn.body} body-coloured pixels)`);
  if (shots) await page.screenshot({ path: join(shots, 'view-explorer.png') });
  const fixed = (v, k) => { const t = (v / 10 ** k).toFixed(6); return /^-0\.0*$/.test(t) ? t.slice(1) : t; };
  for (const angles of [[0, 0, 0], [0.3, -1.2, 2.5], [2.9, 0.7, -0.4], [-3.1, 3.0, 1.0]]) {
    const json = JSON.parse(run('inertia', 'scenes/t-handle.obj', '--mass', '0.05', '--euler', angles.join(','), '--json'));
    // Typed into the page's number fields, as a user would.
    await page.selectOption('#sequence', 'ZYZ');
    await page.selectOption('#kind', 'intrinsic');
    for (let k = 0; k < 3; k++) await page.fill(`#angle-${k}`, String(angles[k]));
    const k = Math.floor(Math.log10(Math.max(...json.principal_moments)));
    const shown = await page.evaluate(() => ({ tensor: window.tumble.tensor(), axes: window.tumble.axes(), centre: window.tumble.centre(), k: window.tumble.exponents }));
    const want = json.inertia.map((row) => row.map((v) => fixed(v, k)));
    check(JSON.stringify(shown.tensor) === JSON.stringify(want), `explorer ZYZ ${angles}: R I Rᵀ ${JSON.stringify(shown.tensor)} = inertia --json ${JSON.stringify(want)}`);
    const axes = json.principal_axes.map((row) => row.map((v) => fixed(v, 0)));
    check(JSON.stringify(shown.axes) === JSON.stringify(axes), `explorer ZYZ ${angles}: principal axes R Q = --json's`);
    const l = shown.k.length;
    const centre = `(${json.center_of_mass.map((v) => fixed(v, l)).join(', ')})`;
    check(shown.centre === centre, `explorer ZYZ ${angles}: centre of mass ${shown.centre} = ${centre}`);
  }
  // Snapping to the principal frame makes the tensor diagonal in every convention.
  const sequences = ['ZYZ', 'ZXZ', 'XYX', 'XZX', 'YXY', 'YZY', 'XYZ', 'XZY', 'YXZ', 'YZX', 'ZXY', 'ZYX'];
  let diagonal = 0;
  const json = JSON.parse(run('inertia', 'scenes/t-handle.obj', '--mass', '0.05', '--json'));
  const k = Math.floor(Math.log10(Math.max(...json.principal_moments)));
  const moments = json.principal_moments.map((v) => fixed(v, k));
  for (const kind of ['intrinsic', 'extrinsic']) {
    for (const s of sequences) {
      await page.selectOption('#sequence', s);
      await page.selectOption('#kind', kind);
      await page.click('#snap');
      const t = await page.evaluate(() => window.tumble.tensor());
      const off = [t[0][1], t[0][2], t[1][0], t[1][2], t[2][0], t[2][1]];
      const ok = off.every((x) => x === fixed(0, k)) && [t[0][0], t[1][1], t[2][2]].join() === moments.join();
      if (ok) diagonal++; else console.log(`     ${kind} ${s}: ${JSON.stringify(t)}`);
    }
  }
  check(diagonal === 24, `explorer: snapping gives diag(I1, I2, I3) = diag(${moments}) with off-diagonal terms 0 in ${diagonal} of 24 conventions`);
  if (shots) {
    await page.selectOption('#sequence', 'ZYZ');
    await page.selectOption('#kind', 'intrinsic');
    await page.click('#snap');
    await page.screenshot({ path: join(shots, 'view-explorer-principal.png') });
  }
  const late = await page.evaluate(() => window.tumble.errors);
  check(late.length === 0, `explorer: no script error after use`);
  await page.close();
}

await browser.close();
if (failures > 0) {
  console.log(`${failures} browser check(s) failed`);
  process.exit(1);
}
console.log('browser checks passed');
