// The live page: plait's engine (plait_web.js + its wasm) renders a gallery
// pipeline offscreen on this page's WebGPU device; the frame is read back and
// drawn into a 2D canvas. Controls as `plait view` has them: a drop-down per
// choice point, a field per param; drag the picture to orbit the camera.
//
// A test drives the page through its URL: `?test=a.toml,b.toml&size=96x72`
// renders each pipeline once and POSTs the frames (or errors) to /result on
// the server that served the page. `?screenshot` keeps a request to /hold
// open until the first frame is drawn, then asks /release: headless
// Chromium's virtual time waits for open requests, so its --screenshot shows
// the frame (scripts/web-screenshot.py serves both).
import init, { open, gallery } from './plait_web.js';

const $ = (id) => document.getElementById(id);
const state = { pipeline: 'occupancy.toml', sets: {}, yaw: 0, pitch: 0, busy: false, again: false };
let engine = null;

function request(width, height) {
  return JSON.stringify({
    pipeline: state.pipeline, width, height,
    sets: Object.entries(state.sets).map(([k, v]) => `${k}=${v}`),
    yaw: state.yaw, pitch: state.pitch,
  });
}

function draw(frame) {
  const canvas = $('view');
  canvas.width = frame.width; canvas.height = frame.height;
  const pixels = new Uint8ClampedArray(frame.pixels.buffer, frame.pixels.byteOffset, frame.pixels.byteLength);
  canvas.getContext('2d').putImageData(new ImageData(pixels, frame.width, frame.height), 0, 0);
}

function showTimings(report, notes) {
  const body = $('timings').tBodies[0];
  body.replaceChildren();
  for (const p of report.passes) {
    const row = body.insertRow();
    row.insertCell().textContent = p.name;
    row.insertCell().textContent = p.gpu_ms == null ? 'no timestamp queries' : p.gpu_ms.toFixed(3) + ' ms';
  }
  if (report.total_gpu_ms != null) {
    const row = body.insertRow();
    row.insertCell().textContent = 'frame';
    row.insertCell().textContent = report.total_gpu_ms.toFixed(3) + ' ms';
  }
  $('notes').replaceChildren(...notes.map((n) => Object.assign(document.createElement('li'), { textContent: n })));
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
async function render() {
  if (state.busy) { state.again = true; return; }
  state.busy = true;
  const started = performance.now();
  try {
    const frame = await engine.render(request(480, 360));
    draw(frame);
    showTimings(JSON.parse(frame.report), JSON.parse(frame.notes));
    showControls(JSON.parse(frame.controls));
    $('error').hidden = true;
    $('status').textContent = `${state.pipeline}: ${(performance.now() - started).toFixed(0)} ms`;
  } catch (e) {
    // The last good frame stays; the error is the CLI's text.
    $('error').textContent = String(e);
    $('error').hidden = false;
    $('status').textContent = 'error';
  } finally {
    state.busy = false;
    if (state.again) { state.again = false; render(); }
  }
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

async function test(names, width, height) {
  const results = [];
  for (const name of names) {
    state.pipeline = name;
    const started = performance.now();
    try {
      const frame = await engine.render(request(width, height));
      results.push({ pipeline: name, ms: performance.now() - started, width: frame.width,
        height: frame.height, pixels: Array.from(frame.pixels), report: JSON.parse(frame.report) });
    } catch (e) {
      results.push({ pipeline: name, ms: performance.now() - started, error: String(e) });
    }
  }
  return results;
}

async function main() {
  const query = new URLSearchParams(location.search);
  if (query.has('screenshot')) fetch('/hold');
  if (!navigator.gpu) throw new Error('this browser has no WebGPU (navigator.gpu): the pictures in the book are static renders');
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
