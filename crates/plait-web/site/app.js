// The live page: plait's engine (plait_web.js + its wasm) renders a gallery
// pipeline offscreen on this page's WebGPU device; the frame is read back and
// drawn into a 2D canvas. Controls as `plait view` has them: a drop-down per
// choice point, a field per param; drag the picture to orbit the camera.
//
// A test drives the page through its URL: `?test=a.toml,b.toml&size=96x72`
// renders each pipeline once and POSTs the frames (or errors) to /result on
// the server that served the page. `?screenshot` asks /release once the first
// frame is drawn: scripts/web-screenshot.py takes its picture then.
import init, { open, gallery } from './plait_web.js';

const $ = (id) => document.getElementById(id);
const state = { pipeline: 'occupancy.toml', sets: {}, size: [480, 360], yaw: 0, pitch: 0, busy: false, again: false };
let engine = null;

function request() {
  const [width, height] = state.size;
  return JSON.stringify({
    pipeline: state.pipeline, width, height,
    sets: Object.entries(state.sets).map(([k, v]) => `${k}=${v}`),
    yaw: state.yaw, pitch: state.pitch, read: state.read,
  });
}

function draw(frame) {
  const canvas = $('view');
  canvas.width = frame.width; canvas.height = frame.height;
  const pixels = new Uint8ClampedArray(frame.pixels.buffer, frame.pixels.byteOffset, frame.pixels.byteLength);
  canvas.getContext('2d').putImageData(new ImageData(pixels, frame.width, frame.height), 0, 0);
}

// The table `plait render` prints (the engine builds its rows): pass, type,
// technique, GPU ms; culled passes with their reason; the frame last. Without
// timestamp queries the times are `n/a` and the line below names the feature.
function showTimings(timings, notes) {
  const body = $('timings').tBodies[0];
  body.replaceChildren();
  for (const r of timings.rows) {
    const row = body.insertRow();
    for (const text of [r.pass, r.type_name, r.technique, r.gpu_ms]) row.insertCell().textContent = text;
    row.insertCell().textContent = r.note || '';
  }
  $('no-timestamps').textContent = timings.missing ? `(${timings.missing})` : '';
  $('no-timestamps').hidden = !timings.missing;
  $('notes').replaceChildren(...notes.map((n) => Object.assign(document.createElement('li'), { textContent: n })));
}

// The schedule as `plait graph --format svg` draws it; redrawn when it changes.
function showGraph(svg) {
  const box = $('graph');
  if (box.dataset.svg !== svg) {
    box.innerHTML = svg;
    box.dataset.svg = svg;
  }
}

function showControls(controls) {
  const choices = $('choices');
  choices.replaceChildren();
  for (const t of controls.techniques) {
    const select = document.createElement('select');
    for (const c of t.choices) select.add(new Option(c, c, false, c === t.chosen));
    select.onchange = () => { state.sets[`techniques.${t.point}`] = select.value; render(); };
    const label = document.createElement('label');
    label.append(t.point, select);
    choices.append(label);
  }
  const params = $('params');
  params.replaceChildren();
  for (const [name, value] of controls.params) {
    const input = Object.assign(document.createElement('input'), { value });
    input.onchange = () => { state.sets[`params.${name}`] = input.value; render(); };
    const label = document.createElement('label');
    label.append(name, input);
    params.append(label);
  }
}

// One frame at a time; a change while one renders asks for one more.
// Resolves to the frame's report and timing table, or null when the engine
// refused or failed.
async function render() {
  if (state.busy) { state.again = true; return null; }
  state.busy = true;
  const started = performance.now();
  try {
    const frame = await engine.render(request());
    draw(frame);
    const report = JSON.parse(frame.report);
    const timings = JSON.parse(frame.timings);
    showTimings(timings, JSON.parse(frame.notes));
    showGraph(frame.graph);
    showControls(JSON.parse(frame.controls));
    $('error').hidden = true;
    $('status').textContent = `${state.pipeline}: ${(performance.now() - started).toFixed(0)} ms`;
    return { report, timings };
  } catch (e) {
    // The last good frame stays; the error is the CLI's text.
    $('error').textContent = String(e);
    $('error').hidden = false;
    $('status').textContent = 'error';
    return null;
  } finally {
    state.busy = false;
    if (state.again) { state.again = false; render(); }
  }
}

// `name.toml;params.x=1;techniques.p=t` as the page's state.
// A test may add `;read=RESOURCE`: that resource is shown instead of the output.
function choose(entry) {
  const [name, ...sets] = entry.split(';');
  state.pipeline = name;
  const pairs = sets.map((s) => [s.slice(0, s.indexOf('=')), s.slice(s.indexOf('=') + 1)]);
  state.read = (pairs.find(([k]) => k === 'read') || [])[1];
  state.sets = Object.fromEntries(pairs.filter(([k]) => k !== 'read'));
}

function orbitWithMouse() {
  const canvas = $('view');
  let last = null;
  canvas.onpointerdown = (e) => { last = [e.clientX, e.clientY]; canvas.setPointerCapture(e.pointerId); };
  canvas.onpointerup = () => { last = null; };
  canvas.onpointermove = (e) => {
    if (!last) return;
    state.yaw -= (e.clientX - last[0]) * 0.01;
    state.pitch += (e.clientY - last[1]) * 0.01;
    last = [e.clientX, e.clientY];
    render();
  };
}

// Each entry rendered as a reader's change would be (the same `render`): what
// the page then shows is posted — the canvas, the error text, the report.
async function test(entries, width, height) {
  state.size = [width, height];
  const results = [];
  for (const entry of entries) {
    choose(entry);
    const started = performance.now();
    const done = await render();
    const ms = performance.now() - started;
    const canvas = $('view');
    const shown = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height);
    // What the page shows beside the picture, as text: the timing table's
    // cells row by row, the line naming a missing feature, the graph's SVG.
    const table = Array.from($('timings').tBodies[0].rows, (row) => Array.from(row.cells, (c) => c.textContent));
    const missing = $('no-timestamps').hidden ? null : $('no-timestamps').textContent;
    results.push({ pipeline: entry, ms, error: $('error').hidden ? null : $('error').textContent,
      width: canvas.width, height: canvas.height, pixels: Array.from(shown.data), report: done && done.report,
      table, missing, graph: $('graph').dataset.svg || null,
      graph_drawn: $('graph').querySelector('svg') != null });
  }
  return results;
}

async function main() {
  const query = new URLSearchParams(location.search);
  if (!(navigator.gpu && await navigator.gpu.requestAdapter().catch(() => null))) {
    throw new Error('this browser offers no WebGPU adapter (navigator.gpu is missing or gives none): the pictures in the book are static renders');
  }
  await init();
  engine = await open();
  $('adapter').textContent = `adapter: ${engine.adapter()}`;
  if (query.has('test')) {
    const [w, h] = (query.get('size') || '96x72').split('x').map(Number);
    const results = await test(query.get('test').split(','), w, h);
    await fetch('/result', { method: 'POST', body: JSON.stringify({ adapter: engine.adapter(), results }) });
    $('status').textContent = 'test done';
    return;
  }
  // A link from the book chooses the pipeline and its sets:
  // `?pipeline=default.toml&set=techniques.shading=marschner`.
  if (query.has('pipeline')) choose([query.get('pipeline'), ...query.getAll('set')].join(';'));
  const select = $('pipeline');
  for (const name of JSON.parse(gallery())) select.add(new Option(name, name, false, name === state.pipeline));
  select.onchange = () => { state.pipeline = select.value; state.sets = {}; render(); };
  orbitWithMouse();
  await render();
  if (query.has('screenshot')) await fetch('/release');
}

main().catch(async (e) => {
  $('error').textContent = String(e);
  $('error').hidden = false;
  $('status').textContent = 'error';
  console.error(e);
  if (new URLSearchParams(location.search).has('test')) {
    await fetch('/result', { method: 'POST', body: JSON.stringify({ fatal: String(e) }) });
  }
});
