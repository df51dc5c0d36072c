// bentstraw explore: the page. All physics is bentstraw's engine: `bentstraw explore` answers the
// page's requests over HTTP, the static site answers the very same requests with the engine
// compiled to WebAssembly in Web Workers. This script only keeps the state (in the address), asks
// for frames and draws them.
"use strict";

// ---- the scene's fixed sizes (the glass and the straw), for drawing outlines only ----
const GLASS_R = 0.04, GLASS_H = 0.20, STRAW_R = 0.005, STRAW_H = 0.25;
// A new coin's radius when the file gives none (a one-euro coin, as the engine's default).
const COIN_R = 0.0115;
// Colour codes 1..5 a straw's sections; in the gallery's scenes also 6 a coin, 7 a card, 8 its arrow.
const SECTION_RGB = ["#ff0000", "#edb120", "#ff00ff", "#00cc00", "#0000ff", "#c79938", "#edebe0", "#1f1f24"];
// Quick frames (while dragging) have this many times fewer pixels along each side, and this many
// times fewer image points (the full frame, when the input stops, has them all).
const QUICK = 4;
const QUICK_POINTS = 6;
// The full frame is asked for this long after the last quick one: soon, in the page's own engine
// (a full frame superseded by new input is stopped at once); later from the server, whose two
// threads every open page shares.
const FULL_AFTER_MS = document.body.dataset.engine === "wasm" ? 80 : 150;
// The centre the eye orbits round: the middle of the glass.
const ORBIT = [0, 0, 0.1];

// Their names are the texts "preset.0", "preset.1"… (i18n.js).
const PRESETS = [
  { v: { observer: [0, 0.1, 0.1], straw: [0.02, 0.01], he: 0.15 } },
  { v: { observer: [0.1, 0, 0.1], straw: [0.02, 0.01], he: 0.15 } },
  { v: { observer: [0.1, 0, 0.3], straw: [0.02, 0.01], he: 0.2 } },
  { v: { observer: [0.1, 0, -0.1], straw: [0, 0], he: 0.2 } },
  { v: { observer: [0.3, 0, 0.16], straw: [0, 0.025], he: 0.12 } },
  { v: { observer: [0.3, 0, 0.07], straw: [0, 0], he: 0.15 } },
  { v: { observer: [0.3, 0, 0.07], straw: [0, 0.034], he: 0.15 } },
  { v: { observer: [0.03, 0, 0.45], straw: [0.02, 0.01], he: 0.15 } },
  { v: { observer: [0.06, 0, -0.25], straw: [0.02, 0.01], he: 0.15 } },
  { v: { observer: [0.1, 0, 0.3], straw: [0.02, 0.01], he: 0.2, color: "path" } },
];

// ---- state: everything the address holds ----
const state = {
  scene: "", // "" the assignment's glass, else a scene of the gallery (scenes/NAME.toml)
  file: "", // the text of the page's own scene file (scene.toml), when it shows one
  // The first view shows the effect: the straw seen from the side, broken at the water's surface.
  observer: [0.3, 0, 0.25], straw: [0, 0.03], he: 0.15, n: 1.333, events: 10, points: 20000,
  mode: "fresnel", backdrop: "checker", color: "section", models: ["course"],
  view: [-35, 22, 1], pick: "",
};

/** Shortest text of a number rounded to 0.1 µm (no float noise in addresses and commands). */
function num(x) { return String(Math.round(x * 1e7) / 1e7); }

// ---- a scene file in the address: deflate (raw), then base64url ----
const MAX_FILE_BYTES = 1 << 20; // a scene file is at most 1 MB, as on the command line
const fileCode = { text: "", code: "" }; // the last file packed, and its code
async function streamBytes(bytes, stream) {
  const out = new Response(new Blob([bytes]).stream().pipeThrough(stream));
  return new Uint8Array(await out.arrayBuffer());
}
async function packFile(text) {
  if (fileCode.text === text) return fileCode.code;
  const z = await streamBytes(new TextEncoder().encode(text), new CompressionStream("deflate-raw"));
  let bin = "";
  for (const b of z) bin += String.fromCharCode(b);
  fileCode.text = text;
  fileCode.code = btoa(bin).replace(/\+/g, "-").replace(/\//g, "_").replace(/=+$/, "");
  return fileCode.code;
}
async function unpackFile(code) {
  const bin = atob(code.replace(/-/g, "+").replace(/_/g, "/"));
  if (bin.length > MAX_FILE_BYTES) throw new Error(t("error.packed-size"));
  const z = Uint8Array.from(bin, (c) => c.charCodeAt(0));
  // Unpacked a piece at a time, stopping past 1 MB: a link cannot make the page unpack more.
  const reader = new Blob([z]).stream().pipeThrough(new DecompressionStream("deflate-raw")).getReader();
  const parts = [];
  let size = 0;
  for (;;) {
    const { done, value } = await reader.read();
    if (done) break;
    size += value.length;
    if (size > MAX_FILE_BYTES) { reader.cancel(); throw new Error(t("error.file-size")); }
    parts.push(value);
  }
  return new TextDecoder("utf-8", { fatal: true }).decode(await new Blob(parts).arrayBuffer());
}

/** The engine's query for the state (names as the command line's flags). */
function viewQuery(s, extra) {
  const p = new URLSearchParams();
  if (s.file) p.set("scene-file", s.file);
  else if (s.scene) p.set("scene", s.scene);
  p.set("observer", s.observer.map(num).join(","));
  // A scene file has its own straws and liquids: only the assignment's glass takes these.
  if (!s.scene && !s.file) {
    p.set("straw", s.straw.map(num).join(","));
    p.set("water-height", num(s.he));
    p.set("n-water", num(s.n));
  }
  p.set("max-events", String(s.events));
  p.set("points", String(s.points));
  p.set("mode", s.mode);
  p.set("backdrop", s.backdrop);
  for (const [k, v] of Object.entries(extra || {})) p.set(k, String(v));
  return p.toString();
}

/** The address's fragment for the state: a scene file travels compressed (`file`). */
function stateHash(s) {
  const p = new URLSearchParams(viewQuery(s));
  if (s.file) { p.delete("scene-file"); p.set("file", fileCode.text === s.file ? fileCode.code : ""); }
  p.set("color", s.color);
  p.set("models", s.models.join(","));
  p.set("view", s.view.map((x) => Math.round(x * 100) / 100).join(","));
  if (s.pick) p.set("pick", s.pick);
  p.set("lang", LANG);
  return "#" + p.toString();
}

/** Reads a query or fragment into the state; values are kept as text-parsed numbers, checked by
 * the engine. A compressed scene file (`file`) is unpacked before the state changes. */
async function readParams(text, s) {
  const p = new URLSearchParams(text.replace(/^[#?]/, ""));
  const list = (v) => v.split(",").map(Number);
  s.scene = p.get("scene") || "";
  s.file = p.get("scene-file") || "";
  if (p.get("file")) {
    try { s.file = await unpackFile(p.get("file")); } catch (e) { s.file = ""; showError({ key: "error.link-file", params: { message: e.message } }); }
  }
  if (s.file) { s.scene = ""; await packFile(s.file); }
  if (p.has("observer")) s.observer = list(p.get("observer"));
  if (p.has("straw")) s.straw = list(p.get("straw"));
  if (p.has("water-height")) s.he = Number(p.get("water-height"));
  if (p.has("n-water")) s.n = Number(p.get("n-water"));
  if (p.has("max-events")) s.events = Number(p.get("max-events"));
  if (p.has("points")) s.points = Number(p.get("points"));
  if (p.has("mode")) s.mode = p.get("mode");
  if (p.has("backdrop")) s.backdrop = p.get("backdrop");
  if (p.has("color")) s.color = p.get("color");
  if (p.has("models")) s.models = p.get("models").split(",").filter(Boolean);
  if (p.has("view")) { const v = list(p.get("view")); if (v.length === 3 && v.every(Number.isFinite)) s.view = v; }
  s.pick = p.get("pick") || "";
  // The page's language (not the view's): a link opens in the language it was copied in.
  if (p.has("lang") && p.get("lang") !== LANG && setLang(p.get("lang"), false)) relabel();
}

// ---- vectors and the orbit ----
const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const scale = (a, k) => [a[0] * k, a[1] * k, a[2] * k];

/** The observer's azimuth and elevation (degrees) and distance round the orbit centre. */
function orbitOf(o) {
  const d = sub(o, ORBIT), r = Math.hypot(d[0], d[1]);
  return { az: Math.atan2(d[1], d[0]) * 180 / Math.PI, el: Math.atan2(d[2], r) * 180 / Math.PI, dist: Math.hypot(r, d[2]) };
}
function fromOrbit(az, el, dist) {
  const a = az * Math.PI / 180, e = el * Math.PI / 180;
  return add(ORBIT, [dist * Math.cos(e) * Math.cos(a), dist * Math.cos(e) * Math.sin(a), dist * Math.sin(e)]);
}

// ---- the page's elements ----
const $ = (id) => document.getElementById(id);
const pictureCanvas = $("picture"), cloudCanvas = $("cloud"), sideCanvas = $("map-side"), topCanvas = $("map-top");

// ---- the engine: bentstraw explore's server over HTTP, or the WebAssembly engine in Web Workers;
// the same requests, the same answers (as `Response`s) ----
const ENGINE = document.body.dataset.engine === "wasm" ? "wasm" : "server";
const wasm = ENGINE === "wasm" ? wasmEngine() : null;
// The site keeps a copy of itself, to open again without a network.
if (wasm && "serviceWorker" in navigator) navigator.serviceWorker.register("sw.js").catch(() => {});

/** The engine compiled to WebAssembly, one Web Worker per channel (so a picture never waits for
 * a model). Everything it needs is fetched once, at the start: afterwards the page needs no
 * network. A request superseded while it runs stops its worker at once; a fresh one takes over. */
function wasmEngine() {
  const files = Promise.all([
    // Compiled while it downloads; a host that does not call it application/wasm gets it compiled after.
    WebAssembly.compileStreaming(fetch("pkg/bentstraw_web_bg.wasm")).catch(() =>
      fetch("pkg/bentstraw_web_bg.wasm").then((r) => r.arrayBuffer()).then((b) => WebAssembly.compile(b))),
    fetch("pkg/bentstraw_web.js").then((r) => r.text()),
    fetch("worker.js").then((r) => r.text()),
  ]).then(([module, glue, worker]) => ({ module, url: URL.createObjectURL(new Blob([glue, "\n", worker], { type: "text/javascript" })) }));
  const workers = {};
  let nextId = 1;
  function spawn(name, f) {
    const w = { worker: new Worker(f.url), current: null, queue: [] };
    w.worker.postMessage({ module: f.module });
    w.worker.onmessage = (e) => {
      const m = e.data, job = w.current;
      if (!job || job.id !== m.id) return;
      w.current = null;
      const headers = { "Content-Type": m.contentType };
      if (m.fileName) headers["Content-Disposition"] = `attachment; filename="${m.fileName}"`;
      // A crash's message is the page's own, in the page's language.
      const r = new Response(m.broken ? t("error.engine-broken") : m.body, { status: m.status, headers });
      r.engineMs = m.ms;
      if (m.broken) restart(name, f);
      job.resolve(r);
      pump(name, f);
    };
    w.worker.onerror = (e) => {
      const job = w.current;
      w.current = null;
      restart(name, f);
      if (job) job.reject(new Error(e.message || t("error.engine-stopped")));
    };
    return w;
  }
  function restart(name, f) {
    const old = workers[name];
    if (old) old.worker.terminate();
    const w = spawn(name, f);
    if (old) w.queue = old.queue;
    workers[name] = w;
    pump(name, f);
  }
  function pump(name, f) {
    const w = workers[name];
    if (!w || w.current || !w.queue.length) return;
    w.current = w.queue.shift();
    w.worker.postMessage({ id: w.current.id, path: w.current.path, query: w.current.query });
  }
  return {
    ready: files.then(() => true),
    async request(name, path, query, signal) {
      const f = await files;
      if (!workers[name]) workers[name] = spawn(name, f);
      return new Promise((resolve, reject) => {
        const job = { id: nextId++, path, query, resolve, reject };
        if (signal) {
          signal.addEventListener("abort", () => {
            const w = workers[name];
            if (w.current === job) { w.current = null; restart(name, f); }
            else w.queue = w.queue.filter((j) => j !== job);
            resolve(null);
          });
        }
        workers[name].queue.push(job);
        pump(name, f);
      });
    },
  };
}

/** Asks the engine for `route?query` on channel `name`: a `Response`, or null if aborted. */
function engineFetch(name, route, query, signal) {
  if (wasm) return wasm.request(name, route, query, signal);
  return fetch(`${route}?${query}`, { signal });
}

// ---- at most one request per channel in flight; newer input waits for it and is then sent as
// one request for the latest state (intermediate states are dropped) ----
const clientId = Math.random().toString(36).slice(2, 10);
const channels = {};
function channel(name) {
  return channels[name] || (channels[name] = { seq: 0, controller: null, busy: false, pending: null });
}

/** Asks for `route?query` on channel `name`, aborting what that channel had in flight; resolves
 * to the response or null when superseded. In the page's own engine, `worker` names the worker
 * that computes it (the channel's by default). */
async function ask(name, route, query, worker) {
  const ch = channel(name);
  if (ch.controller) ch.controller.abort();
  const controller = new AbortController();
  ch.controller = controller;
  ch.seq += 1;
  try {
    const r = await engineFetch(worker || name, route, `${query}&chan=${clientId}-${name}&seq=${ch.seq}`, controller.signal);
    if (r === null) return null;
    if (r.status === 409 || controller.signal.aborted) return null;
    return r;
  } catch (e) {
    if (e.name === "AbortError") return null;
    throw e;
  } finally {
    if (ch.controller === controller) ch.controller = null;
  }
}

// ---- frames ----
let frame = null;          // the last good frame: picture, points, header
let models = { eye: null, stereo: null };
let path = null;           // the clicked ray's path (JSON from the server)
let inputSince = null;     // time of the oldest input the painted frame does not show yet
let inFlight = null;       // { quick, since }
let dirty = false;
let fullTimer = null;
const latencies = [];      // input-to-paint times of painted frames (ms), for the benchmark
let fullPending = false;
window.bentstraw = {
  state, latencies, frames: 0,
  get frame() { return frame; }, get path() { return path; }, get models() { return models; },
  /** Whether a frame is being computed or the full-quality frame is still to come. */
  busy: () => inFlight !== null || fullPending || dirty || (frame !== null && frame.quick),
};

/** Picture size for the eye panel (full quality) in the screen's pixels: its box times the
 * screen's density, at most 2 (a phone's 3 would cost over twice the time for little to see)
 * and at most 1600x1200; the third number is the density used. */
function pictureSize() {
  const r = pictureCanvas.getBoundingClientRect();
  let d = Math.min(2, Math.max(1, window.devicePixelRatio || 1));
  // Within the cap, with the box's shape, while the density is above 1.
  d = Math.max(1, Math.min(d, 1600 / Math.max(1, r.width), 1200 / Math.max(1, r.height)));
  const w = Math.max(40, Math.min(1600, Math.round(r.width * d))), h = Math.max(30, Math.min(1200, Math.round(r.height * d)));
  return [w, h, d];
}

/** Called on every change of the state by the user. */
function changed(options) {
  if (inputSince === null) inputSince = performance.now();
  document.body.dataset.ready = "0";
  history.replaceState(null, "", stateHash(state));
  syncControls();
  drawMaps();
  if (!(options && options.keepPath)) {
    path = null; state.pick = "";
    showHint();
  }
  // The models' points belong to the previous view: they come back with the full frame.
  models = { eye: null, stereo: null };
  requestFrame(true);
}

function requestFrame(quick) {
  clearTimeout(fullTimer);
  fullPending = false;
  if (inFlight && inFlight.quick && quick) { dirty = true; return; }
  sendFrame(quick);
}

async function sendFrame(quick) {
  const [w, h, d] = pictureSize();
  // Quick frames are QUICK times coarser than the box in CSS pixels, whatever the screen's density.
  const size = quick ? [Math.max(40, Math.round(w / (QUICK * d))), Math.max(30, Math.round(h / (QUICK * d)))] : [w, h];
  const extra = { size: `${size[0]}x${size[1]}`, samples: quick ? 1 : 3 };
  if (quick) extra.points = Math.max(1000, Math.round(state.points / QUICK_POINTS));
  const query = viewQuery(state, extra);
  // This request is the first to show the inputs since `since`: its paint ends their wait.
  const since = inputSince;
  inputSince = null;
  inFlight = { quick, since };
  dirty = false;
  const sent = performance.now();
  let r;
  // In the page's engine, full frames have a worker of their own: one superseded by a drag is
  // stopped without holding up the quick frames, which the other core computes meanwhile.
  try { r = await ask("frame", "/api/frame", query, quick ? "frame" : "frame-full"); } catch (e) { showError({ key: "error.no-answer", params: { message: e.message } }); inFlight = null; return; }
  // Not painted: its inputs still wait (for the request that replaced it, or the retry).
  const unpainted = () => { if (since !== null && (inputSince === null || since < inputSince)) inputSince = since; };
  if (r === null) { unpainted(); return; } // superseded by a newer request
  inFlight = null;
  if (r.status === 503) unpainted();
  if (r.status === 503) { fullPending = true; fullTimer = setTimeout(() => { fullPending = false; sendFrame(quick); }, 60); return; }
  if (!r.ok) {
    showError(await refusalOf(r));
    if (frame) frame.quick = false; // the last good view stays, as it is
    document.body.dataset.refused = String(Number(document.body.dataset.refused || 0) + 1);
    return;
  }
  const answered = performance.now();
  const bytes = await r.arrayBuffer();
  const received = performance.now();
  frame = decodeFrame(bytes, quick);
  frame.query = query;
  frame.engineMs = r.engineMs || 0;
  showError("");
  const t = performance.now();
  paintAll();
  const paintMs = performance.now() - t;
  requestAnimationFrame(() => {
    // Where the time went: waiting to be sent, the request (server included), the body, painting.
    if (since !== null) latencies.push({ ms: performance.now() - since, quick, mode: state.mode, server: frame.header.ms, paint: paintMs, wait: sent - since, request: answered - sent, body: received - answered });
    window.bentstraw.frames += 1;
    document.body.dataset.frames = String(window.bentstraw.frames);
  });
  if (dirty) { sendFrame(true); return; }
  if (quick) { fullPending = true; fullTimer = setTimeout(() => { fullPending = false; sendFrame(false); }, FULL_AFTER_MS); }
  else {
    document.body.dataset.ready = "1";
    window.bentstraw.fullPaintedAt = performance.now();
    requestModels();
    if (state.pick && !path) restorePick();
    syncSceneText();
  }
}

/** The server's binary frame: header, RGBA picture, points. */
function decodeFrame(buffer, quick) {
  const view = new DataView(buffer);
  const len = view.getUint32(0, true);
  const header = JSON.parse(new TextDecoder().decode(new Uint8Array(buffer, 4, len)));
  let at = 4 + len;
  const npx = header.width * header.height * 4;
  const rgba = new Uint8ClampedArray(buffer, at, npx); at += npx;
  const n = header.n;
  const xyz = new Float32Array(buffer.slice(at, at + 12 * n)); at += 12 * n;
  const color = new Uint8Array(buffer, at, n); at += n;
  const kind = new Uint8Array(buffer, at, n);
  return { header, rgba, xyz, color, kind, quick };
}

/** Asks for the eye and stereo models switched on and not yet shown for this view, both at once
 * (each on its own channel): first every 4th point, painted at once, then all of them. */
function requestModels() {
  for (const m of ["eye", "stereo"]) {
    if (!state.models.includes(m)) { models[m] = null; continue; }
    if (models[m] && models[m].query === viewQuery(state)) continue; // shown, or on its way
    requestModel(m);
  }
}

async function requestModel(m) {
  const query = viewQuery(state);
  models[m] = { xyz: new Float32Array(0), color: new Uint8Array(0), query, pending: true, all: false };
  const steps = state.points >= 4000 ? [4, 1] : [1];
  for (const every of steps) {
    const r = await ask("model-" + m, "/api/model", viewQuery(state, { model: m, every }));
    if (!r || !r.ok || !models[m] || models[m].query !== query) return; // superseded or refused
    const b = await r.arrayBuffer();
    if (!models[m] || models[m].query !== query) return;
    const n = new DataView(b).getUint32(0, true);
    models[m] = { xyz: new Float32Array(b.slice(4, 4 + 12 * n)), color: new Uint8Array(b, 4 + 12 * n, n), query, pending: false, all: every === 1 };
    drawCloud(); drawLegend();
    document.body.dataset.models = state.models.join(",");
  }
}

/** A refusal's answer: its broken rules as data ({ refusal, message }) when the engine sends
 * them, else its message as text. */
async function refusalOf(r) {
  const text = await r.text();
  if (/^application\/json/.test(r.headers.get("Content-Type") || "")) {
    try { const refusal = JSON.parse(text); return { refusal, message: refusal.message }; } catch (_) { /* text, then */ }
  }
  return text;
}

/** One broken rule's line in the page's language: `key = value: rule`, its numbers written as
 * the language writes them, words from the file as they are. */
function ruleLine(r) {
  const params = {};
  for (const [k, v] of Object.entries(r.params || {})) params[k] = typeof v === "string" ? localNumber(v) : v.text;
  const rule = t("rule." + r.code, params);
  let line = !r.key ? rule : r.value !== null ? t("refusal.value", { key: r.key, value: localNumber(r.value), rule }) : t("refusal.key", { key: r.key, rule });
  if (r.line) line = t("refusal.line", { line: r.line, rule: line });
  return line;
}

/** A refusal's text in the page's language, a line per broken rule (the English is the command
 * line's message, to the character). */
function refusalText(f) {
  const lines = f.rules.map(ruleLine);
  const rules = lines.length === 1 ? lines[0] : [t("refusal.many", { n: lines.length }), ...lines.map((l) => "  " + l)].join("\n");
  return f.file === null ? rules : t(f.flagged ? "refusal.flagged" : "refusal.file", { file: f.file, rules });
}

/** The text of something to show: the engine's message (text, as it comes), its broken rules
 * ({ refusal }), or one of the page's own ({ key, params }); the last two in the page's language. */
function errorText(error) {
  if (error === null) return "";
  if (typeof error === "string") return error;
  return error.refusal ? refusalText(error.refusal) : t(error.key, error.params);
}

/** Shows an error (see errorText), translated again when the language changes. */
let errorShown = "";
function showError(error) {
  errorShown = error;
  const e = $("error");
  const text = errorText(error);
  e.textContent = text;
  e.hidden = !text;
}

// ---- painting ----
function paintAll() {
  drawPicture();
  drawCloud();
  drawLegend();
  showStatus();
  if (!$("commands").hidden) showCommands();
}

/** The status line: the frame's size, its points and the time it took. */
function showStatus() {
  if (!frame) return;
  const h = frame.header;
  const where = wasm ? t("status.wasm", { ms: frame.engineMs.toFixed(0) }) : t("status.server", { ms: h.ms.toFixed(0) });
  $("status").textContent = t("status.frame", { w: h.width, h: h.height, n: h.n, rays: h.rays_traced, fov: localNumber(h.fov_deg.toFixed(1)), where });
}

function drawPicture() {
  if (!frame) return;
  const { width, height } = frame.header;
  pictureCanvas.width = width; pictureCanvas.height = height;
  const ctx = pictureCanvas.getContext("2d");
  ctx.putImageData(new ImageData(frame.rgba, width, height), 0, 0);
  // The clicked ray where the eye sees it: its first stretch is the eye's line of sight (a point
  // here), the rest bends inside the liquid. Only over the picture of the same eye.
  const c = frame.header.camera;
  if (path && c && dot(sub(path.observer, c.eye), sub(path.observer, c.eye)) < 1e-18) {
    const scaleUp = width / Math.max(1, pictureCanvas.getBoundingClientRect().width);
    drawPath(ctx, pictureProjection(), { labels: false, size: scaleUp });
  }
}

/** The picture's projection (its camera's, as the engine's): a 3D point to the frame's pixels,
 * null behind the eye. */
function pictureProjection() {
  const c = frame.header.camera, w = frame.header.width, h = frame.header.height;
  return {
    p: (q) => {
      const v = sub(q, c.eye), z = dot(v, c.forward);
      if (z <= 1e-12) return null;
      const sx = dot(v, c.right) / z / (c.tan_half_fov * (w / h)), sy = dot(v, c.up) / z / c.tan_half_fov;
      return [(sx + 1) * w / 2, (1 - sy) * h / 2];
    },
  };
}

/** Canvas sized to its box (in CSS pixels times the screen's density). */
function fit(canvas) {
  const r = canvas.getBoundingClientRect(), d = window.devicePixelRatio || 1;
  const w = Math.max(1, Math.round(r.width * d)), h = Math.max(1, Math.round(r.height * d));
  if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
  const ctx = canvas.getContext("2d");
  ctx.setTransform(d, 0, 0, d, 0, 0);
  return { ctx, w: r.width, h: r.height };
}

/** The 3D view's projection: orthographic, z up, azimuth/elevation/zoom of state.view. */
function cloudProjection(w, h) {
  const [az, el, zoom] = state.view;
  const a = az * Math.PI / 180, e = el * Math.PI / 180;
  const right = [-Math.sin(a), Math.cos(a), 0];
  const up = [-Math.sin(e) * Math.cos(a), -Math.sin(e) * Math.sin(a), Math.cos(e)];
  const toward = [Math.cos(e) * Math.cos(a), Math.cos(e) * Math.sin(a), Math.sin(e)];
  const box = sceneBox();
  const centre = box.centre;
  // The legend keeps the panel's bottom-left corner: the scene is drawn in the larger room beside
  // it, to its right or above it, so that it covers no point.
  const legend = $("legend").getBoundingClientRect(), cloud = cloudCanvas.getBoundingClientRect();
  let [x0, x1, y1] = [0, w, h];
  if (legend.width > 0 && legend.height > 0) {
    const aside = Math.min(w, legend.right - cloud.left + 6), above = Math.max(0, legend.top - cloud.top - 6);
    if (Math.min(w - aside, h) >= Math.min(w, above)) x0 = aside; else y1 = above;
  }
  const k = zoom * Math.min(x1 - x0, y1) / box.size;
  const cx = (x0 + x1) / 2, cy = y1 / 2;
  return {
    toward,
    p(q) { const d = sub(q, centre); return [cx + k * dot(d, right), cy - k * dot(d, up)]; },
  };
}

/** What the page draws of each scene file (wireframe, outlines, box), asked once per scene. */
const sketches = {};
/** The key of the state's scene file among the sketches: a gallery name, or the file's text. */
const sceneKey = (s) => (s.file ? "file:" + s.file : s.scene);
function sceneQuery(s) {
  const p = new URLSearchParams();
  if (s.file) p.set("scene-file", s.file); else p.set("scene", s.scene);
  return p.toString();
}
function fetchSketch(name) {
  if (sketches[name]) return;
  // A drag makes a new scene file at each step: only the latest few are kept.
  const names = Object.keys(sketches);
  if (names.length >= 24) delete sketches[names[0]];
  sketches[name] = "pending";
  engineFetch("sketch", "/api/sketch", sceneQuery(state)).then((r) => (r.ok ? r.json() : null)).then((sc) => {
    if (!sc) { delete sketches[name]; return; }
    const pt = (a, i) => [a[i], a[i + 1], a[i + 2]];
    const wire = [];
    for (let i = 0; i + 5 < sc.wireframe.length; i += 6) wire.push([pt(sc.wireframe, i), pt(sc.wireframe, i + 3)]);
    const outlines = sc.outlines.map((l) => Array.from({ length: l.length / 3 }, (_, i) => pt(l, 3 * i)));
    sketches[name] = { wire, outlines, bounds: sc.bounds, liquids: sc.liquids || [], container: sc.container || null };
    if (sceneKey(state) === name) { drawMaps(); drawCloud(); syncControls(); }
  });
}

/** The middle and size of what the views show: the glass and straw, or a gallery scene's box. */
function sceneBox() {
  const lines = sceneLines();
  const b = lines ? lines.bounds : null;
  if (!b) return { centre: [0, 0, 0.125], size: 0.36 };
  return { centre: [(b[0] + b[3]) / 2, (b[1] + b[4]) / 2, (b[2] + b[5]) / 2], size: 1.3 * Math.max(b[3] - b[0], b[4] - b[1], b[5] - b[2]) };
}

/** A gallery scene's wireframe (pairs of points), outlines (polylines) and box, once its sketch has come. */
function sceneLines() {
  if (!state.scene && !state.file) return null;
  const key = sceneKey(state);
  const sc = sketches[key];
  if (sc === undefined) fetchSketch(key);
  // While a scene's sketch is on its way (a drag's next step), the last one stands in.
  if (sc && sc !== "pending") lastLines = sc;
  return lastLines;
}
let lastLines = null;

let layer = null, layerPixels = null;
/** A CSS colour "#rrggbb" and an alpha 0..255 as one little-endian RGBA pixel. */
function rgba32(hex, alpha) {
  const v = parseInt(hex.slice(1), 16);
  return ((alpha << 24) | ((v & 0xff) << 16) | (v & 0xff00) | (v >> 16)) >>> 0;
}

function drawCloud() {
  const { ctx, w, h } = fit(cloudCanvas);
  ctx.clearRect(0, 0, w, h);
  const pr = cloudProjection(w, h);
  const line = (pts, style, width, dash) => {
    ctx.beginPath();
    pts.forEach((q, i) => { const [x, y] = pr.p(q); if (i) ctx.lineTo(x, y); else ctx.moveTo(x, y); });
    ctx.strokeStyle = style; ctx.lineWidth = width || 1; ctx.setLineDash(dash || []); ctx.stroke(); ctx.setLineDash([]);
  };
  const circle = (cx, cy, r, z) => Array.from({ length: 73 }, (_, i) => [cx + r * Math.cos(i * Math.PI / 36), cy + r * Math.sin(i * Math.PI / 36), z]);
  const lines = sceneLines();
  if (lines) {
    // A gallery scene: its container's and liquids' wireframe, its objects' true outlines.
    for (const seg of lines.wire) line(seg, "rgba(74,127,193,0.6)", 1);
    for (const l of lines.outlines) line(l, "#888", 1, [2, 3]);
  } else {
    // The water's wireframe, the glass's rim, the straw's true outline.
    for (const z of [0, state.he]) line(circle(0, 0, GLASS_R, z), "#4a7fc1", 1);
    line(circle(0, 0, GLASS_R, GLASS_H), "#b8c2d3", 1, [3, 3]);
    for (let i = 0; i < 30; i++) {
      const a = i * Math.PI / 15;
      line([[GLASS_R * Math.cos(a), GLASS_R * Math.sin(a), 0], [GLASS_R * Math.cos(a), GLASS_R * Math.sin(a), state.he]], "rgba(74,127,193,0.35)", 1);
    }
    const [sx, sy] = state.straw;
    for (let z = 0; z <= STRAW_H + 1e-9; z += 0.05) line(circle(sx, sy, STRAW_R, z), "#888", 1, [2, 3]);
    for (const a of [0, Math.PI / 2, Math.PI, 1.5 * Math.PI]) line([[sx + STRAW_R * Math.cos(a), sy + STRAW_R * Math.sin(a), 0], [sx + STRAW_R * Math.cos(a), sy + STRAW_R * Math.sin(a), STRAW_H]], "#888", 1, [2, 3]);
  }
  drawAxes(ctx, pr);
  // The points: written as pixels into an offscreen layer (tens of thousands of fillRect calls
  // would cost more than the frame itself), then laid over the outlines.
  const d = window.devicePixelRatio || 1;
  const W = cloudCanvas.width, H = cloudCanvas.height;
  if (!layer || layer.width !== W || layer.height !== H) { layer = new OffscreenCanvas(W, H); layerPixels = new ImageData(W, H); }
  const px = new Uint32Array(layerPixels.data.buffer);
  px.fill(0);
  const drawSet = (xyz, color, kind, alpha) => {
    // A kind of light path has one colour everywhere (the engine's): each point's kind indexes
    // the frame's list of kinds.
    const palette = (state.color === "path" && kind ? frame.header.paths.map((p) => p.rgb) : SECTION_RGB).map((c) => rgba32(c, alpha));
    const r = Math.max(1, Math.round(1.2 * d));
    for (let i = 0; i < color.length; i++) {
      const [x, y] = pr.p([xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]]);
      const cx = Math.round(x * d), cy = Math.round(y * d);
      if (cx < r || cy < r || cx >= W - r || cy >= H - r) continue;
      const c = palette[kind ? kind[i] : color[i] - 1];
      for (let a = -r; a < r; a++) px.fill(c, (cy + a) * W + cx - r, (cy + a) * W + cx + r);
    }
  };
  if (frame && state.models.includes("course")) drawSet(frame.xyz, frame.color, state.color === "path" ? frame.kind : null, 255);
  if (models.eye && state.models.includes("eye")) drawSet(models.eye.xyz, models.eye.color, null, 110);
  if (models.stereo && state.models.includes("stereo")) drawSet(models.stereo.xyz, models.stereo.color, null, 110);
  layer.getContext("2d").putImageData(layerPixels, 0, 0);
  ctx.setTransform(1, 0, 0, 1, 0, 0);
  ctx.drawImage(layer, 0, 0);
  ctx.setTransform(d, 0, 0, d, 0, 0);
  // The observer, and the clicked ray's path.
  const [ox, oy] = pr.p(state.observer);
  ctx.fillStyle = "#000"; ctx.beginPath(); ctx.arc(ox, oy, 5, 0, 2 * Math.PI); ctx.fill();
  if (path) drawPath(ctx, pr);
}

/** Colours of the axes in the 3D view (none of the straw's or the light paths' colours). */
const AXIS_RGB = { x: [190, 30, 60], y: [20, 130, 70], z: [40, 60, 190] };
/** Length of each axis drawn, metres. */
const AXIS_LENGTH = 0.05;

/** The scene's axes from the origin (the middle of the container's outer base), 5 cm each, each
 * named at its tip: a turned view still says which way is up and which is x. */
function drawAxes(ctx, pr) {
  const [x0, y0] = pr.p([0, 0, 0]);
  for (const [name, tip] of [["x", [AXIS_LENGTH, 0, 0]], ["y", [0, AXIS_LENGTH, 0]], ["z", [0, 0, AXIS_LENGTH]]]) {
    const [x1, y1] = pr.p(tip);
    const c = `rgb(${AXIS_RGB[name].join(",")})`;
    ctx.beginPath(); ctx.moveTo(x0, y0); ctx.lineTo(x1, y1);
    ctx.strokeStyle = c; ctx.lineWidth = 2; ctx.setLineDash([]); ctx.stroke();
    ctx.fillStyle = c; ctx.font = "bold 12px sans-serif"; ctx.fillText(name, x1 + 3, y1 - 3);
  }
}

/** The clicked ray: the broken path (solid), the course's line of sight to its image point
 * (dashed), events marked (circle: refraction, square: total reflection), the models' points. */
/** The clicked ray through the projection `pr` (a 3D point to the canvas, or null where it
 * cannot be drawn): its broken path, each event marked (a disk for a refraction, a square for a
 * total reflection), and with `labels` the image points of the three models, named without
 * overlapping. `size` scales lines and marks (a canvas in the screen's pixels). */
function drawPath(ctx, pr, { labels = true, size = 1 } = {}) {
  const pts = [path.observer, ...path.events.map((e) => e.point)];
  if (path.outcome === "straw") pts.push(path.straw_point);
  else if (path.leaves) pts.push(add(path.leaves.from, scale(path.leaves.direction, 0.15)));
  const polyline = (points) => {
    ctx.beginPath();
    let open = false;
    for (const q of points) {
      const at = pr.p(q);
      if (!at) { open = false; continue; }
      if (open) ctx.lineTo(...at); else ctx.moveTo(...at);
      open = true;
    }
    ctx.stroke();
  };
  // A light halo under the line, so that it reads on a dark or busy picture too.
  ctx.lineCap = "round";
  ctx.lineWidth = 5 * size; ctx.strokeStyle = "rgba(255,255,255,0.7)"; polyline(pts);
  ctx.lineWidth = 2.5 * size; ctx.strokeStyle = "#111"; polyline(pts);
  if (path.image_point && labels) {
    ctx.setLineDash([6 * size, 4 * size]); ctx.lineWidth = 1.5 * size; ctx.strokeStyle = "#555";
    polyline([path.observer, path.image_point]); ctx.setLineDash([]);
    const placed = [];
    marker(ctx, pr.p(path.image_point), t("mark.image"), "#111", placed);
    if (path.eye_point) marker(ctx, pr.p(path.eye_point), t("mark.eye"), "#0a7", placed);
    if (path.stereo_point) marker(ctx, pr.p(path.stereo_point), t("mark.stereo"), "#a50", placed);
  }
  // Total reflections' squares first, refractions' disks over them: where two events fall on one
  // spot of the picture, both still show.
  const ordered = [...path.events].sort((a, b) => (a.event === "refraction") - (b.event === "refraction"));
  for (const e of ordered) {
    const at = pr.p(e.point);
    if (!at) continue;
    const [x, y] = at, r = 4.5 * size;
    ctx.fillStyle = e.event === "refraction" ? "#1f77b4" : "#d62728";
    ctx.strokeStyle = "#fff"; ctx.lineWidth = size;
    ctx.beginPath();
    if (e.event === "refraction") ctx.arc(x, y, r, 0, 2 * Math.PI); else ctx.rect(x - r, y - r, 2 * r, 2 * r);
    ctx.fill(); ctx.stroke();
  }
}

/** A cross at `at` and its label beside it, moved down past the labels already `placed` (boxes
 * [x0, y0, x1, y1]) so that none covers another. */
function marker(ctx, at, label, colour, placed) {
  if (!at) return;
  const [x, y] = at;
  ctx.strokeStyle = colour; ctx.lineWidth = 2;
  ctx.beginPath(); ctx.moveTo(x - 6, y - 6); ctx.lineTo(x + 6, y + 6); ctx.moveTo(x - 6, y + 6); ctx.lineTo(x + 6, y - 6); ctx.stroke();
  ctx.font = "12px system-ui, sans-serif";
  const w = ctx.measureText(label).width;
  let ly = y - 6;
  const hits = (b) => b[0] < x + 8 + w && x + 8 < b[2] && b[1] < ly + 3 && ly - 12 < b[3];
  while (placed.some(hits)) ly += 14;
  placed.push([x + 8, ly - 12, x + 8 + w, ly + 3]);
  ctx.fillStyle = "rgba(255,255,255,0.8)"; ctx.fillRect(x + 7, ly - 11, w + 2, 14);
  ctx.fillStyle = colour; ctx.fillText(label, x + 8, ly);
}

function drawLegend() {
  const ul = $("legend");
  ul.textContent = "";
  const item = (colour, text, count) => {
    const li = document.createElement("li");
    li.innerHTML = `<span class="swatch" style="background:${colour}"></span><span></span><span class="count"></span>`;
    li.children[1].textContent = text;
    li.children[2].textContent = count;
    ul.appendChild(li);
  };
  if (!frame) return;
  if (state.color === "path") frame.header.paths.forEach((p) => item(p.rgb, pathWords(p.key, p.words), p.count));
  else frame.header.points_per_color.forEach((c, i) => { if ((i < 5 && !state.scene && !state.file) || c > 0) item(SECTION_RGB[i], `${i + 1} ${colourName(i + 1)}`, c); });
  const modelCount = (m) => (!m || m.pending ? "…" : m.all ? m.color.length : t("legend.more", { n: m.color.length }));
  if (state.models.includes("eye")) item("rgba(0,0,0,.3)", t("legend.eye"), modelCount(models.eye));
  if (state.models.includes("stereo")) item("rgba(0,0,0,.3)", t("legend.stereo"), modelCount(models.stereo));
}

// ---- the map: side (plane through the axis and the eye) and top ----
function mapScale(w, h, extent) { return Math.min(w, h) / (2.2 * extent); }
function mapGeometry() {
  const o = state.observer;
  const extent = Math.max(0.07, 1.1 * Math.max(Math.hypot(o[0], o[1]), Math.abs(o[2] - 0.1), 0.15));
  return { extent };
}

// ---- liquids' tints ----
/** Each liquid layer's colour on the maps, bottom first (water blue, then amber, green, purple). */
const LIQUID_RGB = [[74, 127, 193], [214, 160, 40], [60, 160, 90], [140, 90, 180]];
/** The tint of layer `k` of index `n`: the more the liquid bends light, the deeper its colour. */
function liquidTint(k, n) {
  const [r, g, b] = LIQUID_RGB[k % LIQUID_RGB.length];
  const alpha = 0.15 + 0.25 * Math.min(1, Math.max(0, (n - 1) / 0.6));
  return `rgba(${r},${g},${b},${alpha.toFixed(3)})`;
}
/** A scene's liquid layers as `[bottom, top, index, name]`, bottom first, from its sketch. */
function liquidLayers(lines) {
  const floor = lines.container ? lines.container.floor : 0;
  return lines.liquids.map((l, k) => [k ? lines.liquids[k - 1].top : floor, l.top, l.index, l.name]);
}
/**
 * The liquids on the side map, each layer tinted across the container's inside as seen along the
 * eye's azimuth `u` (a glass's inner diameter, a tank's width in that direction), its name and
 * index beside it; `P(s, z)` is the map's pixel.
 */
function drawLiquidsSide(ctx, lines, u, P) {
  const c = lines.container;
  if (!c) return;
  const half = c.shape === "glass" ? c.radius : Math.abs(u[0]) * c.half_x + Math.abs(u[1]) * c.half_y;
  liquidLayers(lines).forEach(([z0, z1, n, name], k) => {
    const [x0, y0] = P(-half, z1), [x1, y1] = P(half, z0);
    ctx.fillStyle = liquidTint(k, n); ctx.fillRect(x0, y0, x1 - x0, y1 - y0);
    if (y1 - y0 >= 12) {
      ctx.fillStyle = "#3b4454"; ctx.font = "11px system-ui";
      ctx.fillText(`${name} · n ${n}`, x1 + 4, Math.min(y1 - 2, y0 + 12));
    }
  });
}
/** The top liquid on the map from above: the container's inside, tinted; `P(x, y)` its pixel. */
function drawLiquidsTop(ctx, lines, P, k) {
  const c = lines.container, layers = liquidLayers(lines);
  if (!c || !layers.length) return;
  const top = layers.length - 1;
  ctx.fillStyle = liquidTint(top, layers[top][2]);
  ctx.beginPath();
  if (c.shape === "glass") ctx.arc(...P(0, 0), c.radius * k, 0, 2 * Math.PI);
  else ctx.rect(...P(-c.half_x, c.half_y), 2 * c.half_x * k, 2 * c.half_y * k);
  ctx.fill();
}

/** A gallery scene's wireframe and outlines on a map, through `at` (a point to the map's pixels). */
function drawLines(ctx, lines, at) {
  ctx.strokeStyle = "rgba(74,127,193,0.6)"; ctx.lineWidth = 1;
  ctx.beginPath();
  for (const [a, b] of lines.wire) { ctx.moveTo(...at(a)); ctx.lineTo(...at(b)); }
  ctx.stroke();
  ctx.strokeStyle = "#777"; ctx.setLineDash([2, 3]);
  ctx.beginPath();
  for (const l of lines.outlines) l.forEach((q, i) => (i ? ctx.lineTo(...at(q)) : ctx.moveTo(...at(q))));
  ctx.stroke(); ctx.setLineDash([]);
}

function drawMaps() {
  const g = mapGeometry();
  const o = state.observer, [sx, sy] = state.straw;
  const lines = sceneLines();
  // Side: horizontal axis along the eye's azimuth.
  {
    const { ctx, w, h } = fit(sideCanvas);
    ctx.clearRect(0, 0, w, h);
    const k = mapScale(w, h, g.extent);
    const az = Math.atan2(o[1], o[0]);
    const u = [Math.cos(az), Math.sin(az)];
    const P = (s, z) => [w / 2 + k * s, h / 2 - k * (z - 0.1)];
    ctx.fillStyle = "#5b667a"; ctx.font = "12px system-ui"; ctx.fillText(t("map.side"), 6, 14);
    sideCanvas.handles = [];
    if (lines) {
      // A gallery scene, seen along the eye's azimuth: `s` across, z up.
      drawLiquidsSide(ctx, lines, u, P);
      drawLines(ctx, lines, (q) => P(q[0] * u[0] + q[1] * u[1], q[2]));
      const form = viewForm(), c = lines.container;
      if (form && c) {
        const half = c.shape === "glass" ? c.radius : Math.abs(u[0]) * c.half_x + Math.abs(u[1]) * c.half_y;
        sideCanvas.handles = handlesOf(form, (z) => P(half, z), true);
        drawHandles(ctx, sideCanvas.handles);
      }
    } else {
      const [wx0, wy0] = P(-GLASS_R, state.he), [wx1, wy1] = P(GLASS_R, 0);
      ctx.fillStyle = liquidTint(0, state.n); ctx.fillRect(wx0, wy0, wx1 - wx0, wy1 - wy0);
      ctx.strokeStyle = "#4a7fc1"; ctx.strokeRect(...P(-GLASS_R, GLASS_H), 2 * GLASS_R * k, GLASS_H * k);
      const s = sx * u[0] + sy * u[1];
      for (let i = 0; i < 5; i++) {
        const [x0, y0] = P(s - STRAW_R, 0.05 * (i + 1));
        ctx.fillStyle = SECTION_RGB[i]; ctx.fillRect(x0, y0, 2 * STRAW_R * k, 0.05 * k);
      }
    }
    ctx.strokeStyle = "#999"; ctx.beginPath(); ctx.moveTo(0, P(0, 0)[1]); ctx.lineTo(w, P(0, 0)[1]); ctx.stroke();
    const [ex, ey] = P(Math.hypot(o[0], o[1]), o[2]);
    ctx.fillStyle = "#000"; ctx.beginPath(); ctx.arc(ex, ey, 6, 0, 2 * Math.PI); ctx.fill();
    if (path) drawPath(ctx, { p: (q) => P(q[0] * u[0] + q[1] * u[1], q[2]) }, { labels: false, size: 0.8 });
    sideCanvas.mapInverse = (x, y) => [(x - w / 2) / k, 0.1 - (y - h / 2) / k];
    sideCanvas.eyeAt = [ex, ey];
  }
  // Top.
  {
    const { ctx, w, h } = fit(topCanvas);
    ctx.clearRect(0, 0, w, h);
    const k = mapScale(w, h, g.extent);
    const P = (x, y) => [w / 2 + k * x, h / 2 - k * y]; // x right, y up: as the report's top views
    ctx.fillStyle = "#5b667a"; ctx.font = "12px system-ui"; ctx.fillText(t("map.top"), 6, 14);
    topCanvas.handles = [];
    if (lines) {
      drawLiquidsTop(ctx, lines, P, k);
      drawLines(ctx, lines, (q) => P(q[0], q[1]));
      const form = viewForm();
      if (form) { topCanvas.handles = handlesOf(form, P, false); drawHandles(ctx, topCanvas.handles); }
    }
    else {
      ctx.fillStyle = state.he > 0 ? liquidTint(0, state.n) : "transparent"; ctx.strokeStyle = "#4a7fc1";
      ctx.beginPath(); ctx.arc(...P(0, 0), GLASS_R * k, 0, 2 * Math.PI); ctx.fill(); ctx.stroke();
      ctx.fillStyle = SECTION_RGB[4]; ctx.beginPath(); ctx.arc(...P(sx, sy), Math.max(3, STRAW_R * k), 0, 2 * Math.PI); ctx.fill();
    }
    const [ex, ey] = P(o[0], o[1]);
    ctx.strokeStyle = "rgba(0,0,0,.35)"; ctx.beginPath(); ctx.moveTo(ex, ey); ctx.lineTo(...P(0, 0)); ctx.stroke();
    ctx.fillStyle = "#000"; ctx.beginPath(); ctx.arc(ex, ey, 6, 0, 2 * Math.PI); ctx.fill();
    if (path) drawPath(ctx, { p: (q) => P(q[0], q[1]) }, { labels: false, size: 0.8 });
    topCanvas.mapInverse = (x, y) => [(x - w / 2) / k, (h / 2 - y) / k];
    topCanvas.eyeAt = [ex, ey];
    topCanvas.strawAt = lines ? null : P(sx, sy);
  }
}

/** The objects' handles on a map: a small ring where a drag takes each. */
function drawHandles(ctx, handles) {
  ctx.lineWidth = 1.5;
  for (const h of handles) {
    ctx.strokeStyle = "#1d2330"; ctx.fillStyle = "rgba(255,255,255,.7)";
    ctx.beginPath(); ctx.arc(h.at[0], h.at[1], 5, 0, 2 * Math.PI); ctx.fill(); ctx.stroke();
  }
  ctx.lineWidth = 1;
}

// ---- input ----
/** Pointer input on `el` (mouse, pen, fingers): `move(dx, dy, event)` while dragging,
 * `click(event)` for a click or a tap, `pinch(ratio, event)` while two fingers spread (ratio > 1)
 * or close. A finger's drag is the page's only once it goes sideways: the canvases let the
 * browser scroll the page with a vertical swipe (touch-action: pan-y). With two fingers,
 * `twoFingers` says whether their middle's movement drags too. */
function onDrag(el, { start, move, click, pinch, twoFingers }) {
  const pointers = new Map(); // pointerId → [x, y]
  let last = null, moved = 0, engaged = false, spread = null, multi = false;
  const middle = () => {
    const [a, b] = [...pointers.values()];
    return { at: [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2], spread: Math.hypot(a[0] - b[0], a[1] - b[1]) };
  };
  el.addEventListener("pointerdown", (e) => {
    if (e.pointerType === "mouse" && e.button !== 0) return;
    pointers.set(e.pointerId, [e.clientX, e.clientY]);
    try { el.setPointerCapture(e.pointerId); } catch (_) { /* already gone */ }
    if (pointers.size === 1) {
      last = [e.clientX, e.clientY]; moved = 0; multi = false;
      // A mouse or a pen drags at once; a finger once it has gone sideways.
      engaged = e.pointerType !== "touch";
      if (start) start(e);
    } else if (pointers.size === 2) {
      const m = middle();
      multi = true; engaged = true; last = m.at; spread = m.spread;
    }
  });
  el.addEventListener("pointermove", (e) => {
    if (!pointers.has(e.pointerId)) return;
    pointers.set(e.pointerId, [e.clientX, e.clientY]);
    if (pointers.size >= 2) {
      const m = middle();
      if (pinch && spread > 0 && m.spread > 0) pinch(m.spread / spread, e);
      if (twoFingers && move) move(m.at[0] - last[0], m.at[1] - last[1], e);
      last = m.at; spread = m.spread;
      return;
    }
    if (!last) return;
    const dx = e.clientX - last[0], dy = e.clientY - last[1];
    if (!engaged) {
      // A finger: wait until its way is clear (its move so far is dx, dy); a vertical swipe is
      // the browser's, which scrolls the page.
      moved = Math.hypot(dx, dy);
      if (moved < 8) return;
      if (Math.abs(dy) > Math.abs(dx)) { pointers.delete(e.pointerId); last = null; return; }
      engaged = true;
    }
    last = [e.clientX, e.clientY]; moved += Math.abs(dx) + Math.abs(dy);
    if (moved > 3) move(dx, dy, e);
  });
  const end = (e) => {
    if (!pointers.has(e.pointerId)) return;
    pointers.delete(e.pointerId);
    if (pointers.size === 0) {
      if (e.type === "pointerup" && last && !multi && (!engaged || moved <= 3) && click) click(e);
      last = null;
    } else if (pointers.size === 1) {
      // From two fingers back to one: it drags on from where it is, never clicks.
      last = [...pointers.values()][0];
    }
  };
  el.addEventListener("pointerup", end);
  el.addEventListener("pointercancel", end);
}

/** Point `p` moved out of what the eye may not enter (the glass; a scene file's box), the
 * shortest way and 1 mm clear: a drag slides the eye round the glass instead of into it. */
function outside(p) {
  const clear = 1e-3;
  const round = (q) => q.map((x) => Math.round(x * 1e5) / 1e5);
  if (!state.scene && !state.file) {
    const r = Math.hypot(p[0], p[1]);
    if (r > GLASS_R || p[2] < 0 || p[2] > GLASS_H) return round(p);
    const k = r > 0 ? (GLASS_R + clear) / r : 0;
    const ways = [
      [GLASS_R + clear - r, r > 0 ? [p[0] * k, p[1] * k, p[2]] : [GLASS_R + clear, 0, p[2]]],
      [p[2] + clear, [p[0], p[1], -clear]],
      [GLASS_H + clear - p[2], [p[0], p[1], GLASS_H + clear]],
    ];
    return round(ways.sort((a, b) => a[0] - b[0])[0][1]);
  }
  const lines = sceneLines();
  if (!lines) return round(p);
  const b = lines.bounds;
  if ([0, 1, 2].some((i) => p[i] < b[i] || p[i] > b[i + 3])) return round(p);
  let best = null;
  for (let i = 0; i < 3; i++) {
    for (const [edge, side] of [[b[i], -1], [b[i + 3], 1]]) {
      const q = p.slice();
      q[i] = edge + side * clear;
      const d = Math.abs(q[i] - p[i]);
      if (!best || d < best[0]) best = [d, q];
    }
  }
  return round(best[1]);
}

/** Moves the eye round the orbit centre by `daz`, `del` degrees and distance factor `f`. */
function orbitBy(daz, del, f) {
  const o = orbitOf(state.observer);
  const el = Math.max(-89, Math.min(89, o.el + del));
  const dist = Math.max(0.045, Math.min(3, o.dist * f));
  state.observer = outside(fromOrbit(o.az + daz, el, dist));
  changed();
}

/** Two fingers spreading by `ratio` bring the eye nearer (closing: farther). */
const pinchEye = (ratio) => orbitBy(0, 0, 1 / ratio);
onDrag(pictureCanvas, {
  move: (dx, dy) => orbitBy(-0.4 * dx, 0.4 * dy, 1),
  pinch: pinchEye,
  twoFingers: true,
  click: (e) => {
    if (!frame) return;
    const r = pictureCanvas.getBoundingClientRect();
    // The picture keeps its aspect inside the canvas box (object-fit: contain).
    const { width, height } = frame.header;
    const k = Math.min(r.width / width, r.height / height);
    const col = (e.clientX - r.left - (r.width - k * width) / 2) / k, row = (e.clientY - r.top - (r.height - k * height) / 2) / k;
    if (col < 0 || row < 0 || col > width || row > height) return;
    pick(`px:${Math.round(row * 100) / 100},${Math.round(col * 100) / 100},${width}x${height}`);
  },
});
for (const el of [pictureCanvas, sideCanvas, topCanvas]) {
  el.addEventListener("wheel", (e) => { e.preventDefault(); orbitBy(0, 0, Math.exp(0.0015 * e.deltaY)); }, { passive: false });
}

/** The 3D view's zoom times `f`, within its bounds. */
function zoomCloud(f) {
  state.view[2] = Math.max(0.1, Math.min(40, state.view[2] * f));
  history.replaceState(null, "", stateHash(state)); drawCloud();
}
onDrag(cloudCanvas, {
  pinch: zoomCloud,
  twoFingers: true,
  move: (dx, dy) => {
    state.view[0] -= 0.5 * dx; state.view[1] = Math.max(-89, Math.min(89, state.view[1] + 0.5 * dy));
    history.replaceState(null, "", stateHash(state)); drawCloud();
  },
  click: (e) => {
    if (!frame) return;
    const r = cloudCanvas.getBoundingClientRect();
    const x = e.clientX - r.left, y = e.clientY - r.top;
    const pr = cloudProjection(r.width, r.height);
    let best = -1, bestD = 8 * 8;
    for (let i = 0; i < frame.color.length; i++) {
      const [px, py] = pr.p([frame.xyz[3 * i], frame.xyz[3 * i + 1], frame.xyz[3 * i + 2]]);
      const d = (px - x) ** 2 + (py - y) ** 2;
      if (d < bestD) { bestD = d; best = i; }
    }
    if (best >= 0) pick(`point:${best}`);
  },
});
cloudCanvas.addEventListener("wheel", (e) => { e.preventDefault(); zoomCloud(Math.exp(-0.0015 * e.deltaY)); }, { passive: false });

let dragging = null;
onDrag(topCanvas, {
  pinch: pinchEye,
  start: (e) => {
    const r = topCanvas.getBoundingClientRect(), x = e.clientX - r.left, y = e.clientY - r.top;
    const near = (p) => p && Math.hypot(p[0] - x, p[1] - y) < 14;
    const h = near(topCanvas.eyeAt) ? null : handleAt(topCanvas.handles, x, y, 14);
    dragging = h || (near(topCanvas.strawAt) && !near(topCanvas.eyeAt) ? "straw" : "eye");
    if (h) dragGesture = {};
  },
  move: (dx, dy, e) => {
    const r = topCanvas.getBoundingClientRect();
    const [x, y] = topCanvas.mapInverse(e.clientX - r.left, e.clientY - r.top);
    if (dragging && dragging.kind) { dragHandle(dragging, [x, y]); return; }
    if (dragging === "straw") {
      // Kept inside the glass, so that a drag never stops at the rule's edge.
      const lim = GLASS_R - STRAW_R - 1e-4, d = Math.hypot(x, y), f = d > lim ? lim / d : 1;
      state.straw = [x * f, y * f].map((v) => Math.round(v * 1e5) / 1e5);
    } else {
      state.observer = outside([x, y, state.observer[2]]);
    }
    changed();
  },
});
let draggingSide = null;
onDrag(sideCanvas, {
  pinch: pinchEye,
  start: (e) => {
    const r = sideCanvas.getBoundingClientRect(), x = e.clientX - r.left, y = e.clientY - r.top;
    const eye = sideCanvas.eyeAt && Math.hypot(sideCanvas.eyeAt[0] - x, sideCanvas.eyeAt[1] - y) < 14;
    draggingSide = eye ? null : handleAt(sideCanvas.handles, x, y, 14);
    if (draggingSide) dragGesture = {};
  },
  move: (dx, dy, e) => {
    const r = sideCanvas.getBoundingClientRect();
    const [s, z] = sideCanvas.mapInverse(e.clientX - r.left, e.clientY - r.top);
    if (draggingSide) { dragHandle(draggingSide, [s, z]); return; }
    const o = state.observer, az = Math.atan2(o[1], o[0]);
    const d = Math.max(0.001, s);
    state.observer = outside([d * Math.cos(az), d * Math.sin(az), z]);
    changed();
  },
});

// ---- the light's path ----
async function pick(what) {
  state.pick = what;
  history.replaceState(null, "", stateHash(state));
  let extra;
  if (what.startsWith("point:")) extra = { point: what.slice(6) };
  else {
    const [row, col, size] = what.slice(3).split(",");
    extra = { row, col, size: size || pictureSize().slice(0, 2).join("x") };
  }
  const r = await ask("ray", "/api/ray", viewQuery(state, extra));
  if (!r) return;
  if (!r.ok) { showError(await refusalOf(r)); return; }
  path = await r.json();
  showReadout();
  document.body.dataset.picked = what;
  drawPicture(); drawCloud(); drawMaps();
}
function restorePick() { if (state.pick) pick(state.pick); }
window.bentstraw.pickPoint = (k) => pick(`point:${k}`);
/** Where point `k` of the cloud is drawn, in the window's coordinates. */
window.bentstraw.screenOfPoint = (k) => {
  const r = cloudCanvas.getBoundingClientRect();
  const [x, y] = cloudProjection(r.width, r.height).p([frame.xyz[3 * k], frame.xyz[3 * k + 1], frame.xyz[3 * k + 2]]);
  return [r.left + x, r.top + y];
};

// ---- the engine's words in the page's language, from the keys its answers give ----
/** A colour code's name (1 red … 5 blue; 6 coin, 7 card, 8 arrow). */
const colourName = (code) => t("colour." + code);
/** A light path's words from its key ("wall", "top+2"…), else the engine's own words. */
function pathWords(key, words) {
  const m = /^(direct|top|wall|bottom)(?:\+(\d+))?$/.exec(key || "");
  if (!m) return words;
  const k = Number(m[2] || 0);
  return t("path." + m[1]) + (k === 0 ? "" : k === 1 ? t("path.reflection.1") : t("path.reflection.k", { k }));
}
/** A text of the engine from a known set (`prefix.text`), else the text as it came. */
function known(prefix, text) { return (prefix + "." + text) in I18N.en ? t(prefix + "." + text) : text; }

const m = (x) => (x == null ? "—" : localNumber(Number(x).toFixed(4)) + " m");
const v3 = (p) => (p ? `(${p.map((x) => localNumber(x.toFixed(4))).join(LANG === "fr" ? " ; " : ", ")})` : "—");
const focus = (f) => {
  const kind = known("focus", f.kind);
  return f.distance == null ? kind : (kind ? kind + " " : "") + localNumber(Number(f.distance).toFixed(4)) + " m";
};
const escapeHtml = (s) => String(s).replace(/[&<>"]/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;" })[c]);

/** The readout's hint, before anything is clicked. */
function showHint() {
  $("readout").innerHTML = '<p class="hint" data-i18n="readout.hint"></p>';
  applyI18n($("readout"));
}

function showReadout() {
  const el = $("readout");
  const rows = [];
  const row = (a, b) => rows.push(`<tr><td>${escapeHtml(a)}</td><td>${b}</td></tr>`);
  if (path.outcome === "straw") row(t("ro.colour"), `<span class="swatch-inline" style="color:${SECTION_RGB[path.color - 1]}">■</span> ${path.color} ${escapeHtml(colourName(path.color))}`);
  else row(t("ro.outcome"), escapeHtml(path.outcome === "escaped" ? t("ro.escaped") : t("ro.dropped")));
  row(t("ro.path"), escapeHtml(pathWords(path.path_key, path.path)));
  path.events.forEach((e, i) => {
    const face = (("face." + e.face) in I18N.en) ? t("face." + e.face) : t("face.other", { face: e.face });
    row(t("ro.event", { i: i + 1 }), escapeHtml(t("ro.event.text", { event: known("event", e.event), face, angle: localNumber(e.incidence_deg.toFixed(2)), out: localNumber(e.outgoing_deg.toFixed(2)), n1: localNumber(e.n1), n2: localNumber(e.n2) })));
  });
  if (path.outcome === "straw") {
    row(t("ro.length"), m(path.path_length));
    row(t("ro.straw-point"), v3(path.straw_point));
    row(t("ro.image-point"), v3(path.image_point));
    row("s_h, s_v", `${focus(path.s_h)}${LANG === "fr" ? " ; " : ", "}${focus(path.s_v)}`);
    row(t("ro.eye-point"), v3(path.eye_point));
    row(t("ro.gap-eye"), m(path.gap_eye));
    row(t("ro.stereo-point"), v3(path.stereo_point));
    row(t("ro.gap-stereo"), m(path.gap_stereo));
  }
  el.innerHTML = `<table id="path-table">${rows.join("")}</table>`;
}

// ---- controls ----
function syncControls() {
  fileOption();
  $("scene").value = state.file ? "file" : state.scene;
  // A scene file's liquids and straws are its own: the water's sliders are the glass's.
  const fromFile = Boolean(state.scene || state.file);
  $("he").disabled = $("n").disabled = fromFile;
  // A scene file's sliders show its own bottom liquid (its surface, its index), or none.
  const lines = fromFile ? sceneLines() : null;
  const liquid = lines && lines.liquids.length ? lines.liquids[0] : null;
  const [he, n] = fromFile ? (liquid ? [liquid.top, liquid.index] : [null, null]) : [state.he, state.n];
  if (he !== null) { $("he").value = he; $("n").value = n; }
  $("he-out").textContent = he === null ? "—" : localNumber(num(he)) + " m";
  $("n-out").textContent = n === null ? "—" : localNumber(num(n));
  $("events").value = state.events; $("events-out").textContent = String(state.events);
  $("mode").value = state.mode; $("backdrop").value = state.backdrop; $("color-by").value = state.color;
  for (const k of ["course", "eye", "stereo"]) $("show-" + k).checked = state.models.includes(k);
}

$("he").addEventListener("input", (e) => { state.he = Number(e.target.value); changed(); });
$("n").addEventListener("input", (e) => { state.n = Number(e.target.value); changed(); });
$("events").addEventListener("input", (e) => { state.events = Number(e.target.value); changed(); });
$("mode").addEventListener("change", (e) => { state.mode = e.target.value; changed({ keepPath: true }); });
$("backdrop").addEventListener("change", (e) => { state.backdrop = e.target.value; changed({ keepPath: true }); });
$("color-by").addEventListener("change", (e) => { state.color = e.target.value; history.replaceState(null, "", stateHash(state)); drawCloud(); drawLegend(); });
for (const k of ["course", "eye", "stereo"]) {
  $("show-" + k).addEventListener("change", (e) => {
    state.models = ["course", "eye", "stereo"].filter((x) => (x === k ? e.target.checked : state.models.includes(x)));
    history.replaceState(null, "", stateHash(state));
    drawCloud(); drawLegend(); requestModels();
  });
}
PRESETS.forEach((p, i) => { const o = document.createElement("option"); o.value = String(i); o.dataset.i18n = "preset." + i; o.textContent = t("preset." + i); $("preset").appendChild(o); });
$("preset").addEventListener("change", (e) => {
  const p = PRESETS[Number(e.target.value)];
  if (!p) return;
  Object.assign(state, { scene: "", file: "", n: 1.333, events: 10, color: "section" }, p.v);
  state.observer = p.v.observer.slice(); state.straw = p.v.straw.slice();
  changed();
});

/** The scene chooser's entry for the page's own scene file, while it shows one. */
function fileOption() {
  let o = $("scene").querySelector('option[value="file"]');
  if (state.file && !o) {
    o = document.createElement("option");
    o.value = "file"; o.dataset.i18n = "scene.file"; o.textContent = t("scene.file");
    $("scene").appendChild(o);
  }
  if (!state.file && o) o.remove();
}

// The gallery's scenes, from the engine: choosing one moves the eye to the view it is meant for.
let gallery = [];
engineFetch("scenes", "/api/scenes", "").then((r) => r.json()).then((list) => {
  gallery = list;
  for (const g of list) {
    const o = document.createElement("option");
    o.value = g.name; o.textContent = g.title; o.title = g.shows;
    $("scene").appendChild(o);
  }
  syncControls();
  document.body.dataset.scenes = String(list.length);
});
$("scene").addEventListener("change", (e) => {
  if (e.target.value === "file") return;
  state.scene = e.target.value;
  state.file = "";
  const g = gallery.find((x) => x.name === state.scene);
  state.observer = g ? g.observer.slice() : [0.1, 0, 0.1];
  $("preset").value = "";
  frame = null;
  changed();
});

$("copy-link").addEventListener("click", async () => {
  const link = window.bentstraw.link();
  document.body.dataset.link = link;
  try { await navigator.clipboard.writeText(link); $("status").textContent = t("status.copied", { link }); } catch (_) { prompt(t("prompt.copy"), link); }
});
/** Saves the file `simulate` or `render` would write for this view, computed by the engine. */
async function download(format, model) {
  const [w, h] = pictureSize();
  const r = await engineFetch("export", "/api/export", viewQuery(state, { format, size: `${w}x${h}`, model: model || "course" }));
  if (!r.ok) { showError(await refusalOf(r)); return; }
  const name = (r.headers.get("Content-Disposition") || "").match(/filename="([^"]+)"/);
  const a = document.createElement("a");
  a.href = URL.createObjectURL(await r.blob());
  a.download = name ? name[1] : "view";
  document.body.appendChild(a); a.click(); a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 10000);
}
$("export-png").addEventListener("click", () => download("png"));
$("export-csv").addEventListener("click", () => download("csv"));
$("export-ply").addEventListener("click", () => download("ply"));
function showCommands() {
  if (!frame) return;
  const c = $("commands");
  c.innerHTML = "<b data-i18n=\"commands.heading\"></b><code id=\"cmd-simulate\"></code><code id=\"cmd-render\"></code>";
  applyI18n(c);
  $("cmd-simulate").textContent = frame.header.simulate;
  $("cmd-render").textContent = frame.header.render;
}
$("show-commands").addEventListener("click", () => { const c = $("commands"); c.hidden = !c.hidden; showCommands(); });

// ---- the page's language (i18n.js): English or French ----
/** Writes again every text the page has drawn or written in the former language. */
function relabel() {
  $("lang").value = LANG;
  applyI18n();
  if (path) showReadout(); else if (!state.pick) showHint();
  if (typeof errorShown !== "string") showError(errorShown);
  if (sceneErrorShown !== null && typeof sceneErrorShown !== "string") showSceneErrors(sceneErrorShown);
  formSignature = ""; showObjects();
  if (!$("commands").hidden) showCommands();
  showStatus();
  syncControls();
  drawMaps(); drawCloud(); drawLegend();
  fullscreenLabel();
}
$("lang").value = LANG;
$("lang").addEventListener("change", (e) => {
  if (!setLang(e.target.value, true)) return;
  relabel();
  history.replaceState(null, "", stateHash(state));
});

// ---- full screen (for a projector): the picture's panel alone ----
const eyePanel = $("eye-panel");
function fullscreenLabel() {
  $("fullscreen").textContent = t(document.fullscreenElement ? "fullscreen.leave" : "fullscreen");
}
if (document.fullscreenEnabled) {
  $("fullscreen").hidden = false;
  $("fullscreen").addEventListener("click", () => {
    if (document.fullscreenElement) document.exitFullscreen().catch(() => {});
    else eyePanel.requestFullscreen().catch(() => {});
  });
  // The picture is asked for again at the new size (by the window's resize).
  document.addEventListener("fullscreenchange", () => { fullscreenLabel(); window.dispatchEvent(new Event("resize")); });
}

window.addEventListener("resize", () => { drawMaps(); drawCloud(); clearTimeout(fullTimer); fullPending = true; fullTimer = setTimeout(() => { fullPending = false; sendFrame(false); }, 200); });
window.addEventListener("hashchange", async () => {
  if (location.hash === stateHash(state)) return; // the page's own change of the address
  await readParams(location.hash, state); syncControls(); drawMaps(); requestFrame(false);
});

// ---- a scene file's text: checked by the engine, then shown ----
/** The eye for the scene file `toml` (its own [observer], else the current eye) once the engine
 * has checked the whole view by the same rules as `simulate --scene scene.toml --observer …`;
 * rejects with the engine's message (the command line's) if a rule is broken. */
async function checkScene(toml, worker) {
  const sketch = await engineFetch(worker, "/api/sketch", new URLSearchParams({ "scene-file": toml }).toString());
  const sc = JSON.parse(await answerText(sketch));
  const observer = sc.observer || state.observer;
  await answerText(await engineFetch(worker, "/api/scene-file", viewQuery({ ...state, file: toml, scene: "", observer })));
  return observer;
}
/** Makes the checked scene file `toml` the view's scene (the caller asks for the frame). */
async function useScene(toml, observer) {
  await packFile(toml);
  Object.assign(state, { file: toml, scene: "", observer: observer.slice() });
  $("preset").value = "";
}
function refused() { document.body.dataset.refused = String(Number(document.body.dataset.refused || 0) + 1); }

// ---- the scene file's text box: always the view's scene; typing sends it (after a pause) ----
const sceneText = $("scene-text"), sceneErrorsEl = $("scene-errors");
/** A typed text is sent this long after the last key. */
const EDIT_AFTER_MS = 400;
/** The scenes the view has shown, for undo and redo: { text, snap } (the text in the box, the
 * state that shows it), at most HISTORY_MAX of them. */
const HISTORY_MAX = 50;
const sceneHistory = { entries: [], at: -1 };
let editTimer = null;    // a typed text waiting to be sent
let editSeq = 0;         // the latest text sent
let syncSeq = 0;         // the latest view whose text was asked for
let sceneErrorShown = null;

/** What of the state makes the scene and its eye (what undo brings back). */
function sceneSnapshot() {
  return { scene: state.scene, file: state.file, observer: state.observer.slice(), straw: state.straw.slice(), he: state.he, n: state.n };
}

/** Under the box: the engine's message, a line per item (text, as it comes), or one of the
 * page's own ({ key, params }); null clears it. */
function showSceneErrors(error) {
  sceneErrorShown = error;
  const text = errorText(error);
  sceneErrorsEl.replaceChildren(...text.split("\n").filter((l) => l.trim()).map((l) => {
    const li = document.createElement("li");
    li.textContent = l;
    return li;
  }));
  sceneErrorsEl.hidden = !text;
  if (text) sceneErrorsEl.scrollIntoView({ block: "nearest" });
  sceneText.classList.toggle("refused", Boolean(text));
  markObjects(error);
  sceneText.setAttribute("aria-invalid", text ? "true" : "false");
}

/** After a full frame: the box shows the view's scene (the page's own text when it shows one,
 * else the engine's scene file for the view), unless the user is typing or a refused text is
 * being corrected; the scene enters the history. */
async function syncSceneText() {
  const seq = ++syncSeq;
  const snap = sceneSnapshot();
  let text = state.file;
  if (!text) {
    try {
      const r = await engineFetch("hook", "/api/scene-file", viewQuery(state));
      if (!r || !r.ok || seq !== syncSeq) return;
      text = await r.text();
    } catch (_) { return; } // the frame's own request shows what went wrong
    if (seq !== syncSeq) return;
  }
  remember(text, snap);
  loadForm(text);
  if (editTimer !== null || (document.activeElement === sceneText && sceneErrorShown !== null)) return;
  if (sceneText.value !== text) sceneText.value = text;
  showSceneErrors(null);
  document.body.dataset.sceneText = String(seq);
}

function remember(text, snap) {
  const h = sceneHistory;
  // The same text (a page's own file seen from another eye): the entry keeps the latest eye.
  if (h.at >= 0 && h.entries[h.at].text === text) { h.entries[h.at].snap = snap; return; }
  // A drag of an object is one step of the history, however many texts it went through.
  const gesture = text === dragText ? dragGesture : null;
  h.entries.splice(h.at + 1);
  if (gesture && h.at >= 0 && h.entries[h.at].gesture === gesture) { Object.assign(h.entries[h.at], { text, snap }); historyButtons(); return; }
  h.entries.push({ text, snap, gesture });
  if (h.entries.length > HISTORY_MAX) h.entries.shift();
  h.at = h.entries.length - 1;
  historyButtons();
}
function historyButtons() {
  // The scene file's panel and the objects' panel each have the pair.
  for (const id of ["scene-undo", "objects-undo"]) $(id).disabled = sceneHistory.at <= 0;
  for (const id of ["scene-redo", "objects-redo"]) $(id).disabled = sceneHistory.at >= sceneHistory.entries.length - 1;
}

/** Undo (-1) or redo (+1): the scene, its eye and its text as they were. */
async function stepHistory(d) {
  const h = sceneHistory, k = h.at + d;
  if (k < 0 || k >= h.entries.length) return;
  h.at = k;
  historyButtons();
  clearTimeout(editTimer); editTimer = null;
  editSeq++; syncSeq++; // answers still on their way belong to the scene left
  const { text, snap } = h.entries[k];
  if (snap.file) await packFile(snap.file);
  const sameScene = snap.scene === state.scene && snap.file === state.file;
  Object.assign(state, snap, { observer: snap.observer.slice(), straw: snap.straw.slice() });
  $("preset").value = "";
  sceneText.value = text;
  showSceneErrors(null);
  if (!sameScene) frame = null;
  changed();
}
for (const id of ["scene-undo", "objects-undo"]) $(id).addEventListener("click", () => stepHistory(-1));
for (const id of ["scene-redo", "objects-redo"]) $(id).addEventListener("click", () => stepHistory(1));
// Ctrl+Z / Ctrl+Shift+Z (or Ctrl+Y) for the scene, except where a text box has its own undo.
document.addEventListener("keydown", (e) => {
  if (!(e.ctrlKey || e.metaKey) || e.altKey) return;
  const key = e.key.toLowerCase();
  if (key !== "z" && key !== "y") return;
  const el = e.target;
  if (el && (el.tagName === "TEXTAREA" || el.isContentEditable || (el.tagName === "INPUT" && !/^(range|checkbox|button|file)$/.test(el.type)))) return;
  e.preventDefault();
  stepHistory(key === "y" || e.shiftKey ? 1 : -1);
});

/** Sends a text of the box as the view's scene: the view follows it, or, if a rule is broken,
 * the view stays and the box keeps the text, the engine's message under it. */
async function applySceneText(text) {
  const seq = ++editSeq;
  syncSeq++;
  const h = sceneHistory;
  if (h.at >= 0 && h.entries[h.at].text === text) { showSceneErrors(null); return; } // the view's own
  if (new Blob([text]).size > MAX_FILE_BYTES) { showSceneErrors({ key: "error.file-size" }); refused(); return; }
  let observer;
  try {
    observer = await checkScene(text, "hook");
  } catch (e) {
    if (seq !== editSeq) return;
    showSceneErrors(e.shown || e.message);
    refused();
    return;
  }
  if (seq !== editSeq) return;
  showSceneErrors(null);
  await useScene(text, observer);
  changed();
}
sceneText.addEventListener("input", () => {
  clearTimeout(editTimer);
  editTimer = setTimeout(() => { editTimer = null; applySceneText(sceneText.value); }, EDIT_AFTER_MS);
});

// Open…: a scene file from this computer, at most 1 MB, into the box and the view.
$("scene-open").addEventListener("click", () => $("scene-input").click());
$("scene-input").addEventListener("change", (e) => {
  const file = e.target.files[0];
  e.target.value = ""; // the same file can be opened again
  if (!file) return;
  if (file.size > MAX_FILE_BYTES) { showSceneErrors({ key: "edit.too-large", params: { name: file.name } }); return; }
  const reader = new FileReader();
  reader.onload = () => {
    $("scene-edit").open = true;
    clearTimeout(editTimer); editTimer = null;
    sceneText.value = reader.result;
    applySceneText(reader.result);
  };
  reader.onerror = () => showSceneErrors({ key: "edit.unreadable", params: { name: file.name, message: String(reader.error && reader.error.message) } });
  reader.readAsText(file);
});
// Save: the box's text as scene.toml.
$("scene-save").addEventListener("click", () => {
  const a = document.createElement("a");
  a.href = URL.createObjectURL(new Blob([sceneText.value], { type: "application/toml" }));
  a.download = "scene.toml";
  document.body.appendChild(a); a.click(); a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 10000);
});

// ---- the scene's objects: a control for each key of its file, and drags on the maps ----
// The controls edit the scene's form (its file's keys and values, as the engine reads them); the
// engine writes the form back as the file's text, which then goes the way a typed text goes:
// checked by the same rules, the view following it, refused key by key. One rule, one place.

/** Each kind of object's keys as the file names them, with their unit ("" a pure number, "text",
 * "m3" a point, or the words a value may be). */
const FORM_FIELDS = {
  glass: [["radius", "m"], ["height", "m"], ["wall", "m"], ["bottom", "m"], ["index", ""]],
  tank: [["half_x", "m"], ["half_y", "m"], ["height", "m"]],
  liquid: [["name", "text"], ["index", ""], ["top", "m"]],
  straw: [["x", "m"], ["y", "m"], ["tilt", "°"], ["azimuth", "°"], ["radius", "m"], ["length", "m"]],
  coin: [["x", "m"], ["y", "m"], ["radius", "m"], ["thickness", "m"]],
  card: [["center", "m3"], ["facing", "°"], ["width", "m"], ["height", "m"], ["picture", ["arrow", "none"]]],
};
/** The step of a control by unit: a millimetre, a tenth of a degree, a thousandth of an index. */
const STEP = { m: "0.001", "m3": "0.001", "°": "0.1", "": "0.001" };
const objectsEl = $("objects"), objectsErrorsEl = $("objects-errors");
/** The form of the view's scene: { text, key, form } (the text it was read from, the scene's key). */
let formOf = null;
let formSignature = "";

/** The form of the scene file `text` (the view's), read by the engine, then shown. */
async function loadForm(text) {
  if (formOf && formOf.text === text) return;
  const key = sceneKey(state);
  let form;
  try {
    const r = await engineFetch("hook", "/api/sketch", new URLSearchParams({ "scene-file": text }).toString());
    if (!r || !r.ok) return;
    form = (await r.json()).form;
  } catch (_) { return; }
  formOf = { text, key, form };
  showObjects();
  drawMaps();
}
/** The view's form, if it is the current scene's. */
const viewForm = () => (formOf && formOf.key === sceneKey(state) ? formOf.form : null);

/** The inside of the form's container: a glass's inner radius, or a tank's half widths. */
function inside(form) {
  const c = form.container || {};
  return c.shape === "tank" ? { tank: true, hx: c.half_x, hy: c.half_y, height: c.height, floor: 0 }
    : { tank: false, r: c.radius - (c.wall || 0), height: c.height, floor: c.bottom || 0 };
}
/** `[x, y]` kept inside the container, `margin` clear of its side (an object's radius). */
function keepInside(form, [x, y], margin) {
  const c = inside(form), clear = margin + 1e-4;
  const r5 = (v) => Math.round(v * 1e5) / 1e5;
  if (c.tank) {
    const lx = Math.max(0, c.hx - clear), ly = Math.max(0, c.hy - clear);
    return [r5(Math.max(-lx, Math.min(lx, x))), r5(Math.max(-ly, Math.min(ly, y)))];
  }
  const lim = Math.max(0, c.r - clear), d = Math.hypot(x, y), f = d > lim ? lim / d : 1;
  return [r5(x * f), r5(y * f)];
}
/** A place on the floor for a new straw or coin of radius `r`: the middle, else the first spot
 * on rings further out that is inside the container and 1 mm clear of the straws and coins. */
function freeSpot(form, r) {
  const c = inside(form), reach = c.tank ? Math.min(c.hx, c.hy) : c.r;
  const taken = [...(form.straw || []).map((o) => [o.x, o.y, o.radius || STRAW_R]), ...(form.coin || []).map((o) => [o.x, o.y, o.radius || COIN_R])];
  for (const f of [0, 0.25, 0.5, 0.7]) {
    for (let k = 0; k < (f ? 12 : 1); k++) {
      const a = (k * Math.PI) / 6, x = f * reach * Math.cos(a), y = f * reach * Math.sin(a);
      const inner = c.tank ? Math.abs(x) + r < c.hx && Math.abs(y) + r < c.hy : Math.hypot(x, y) + r < c.r;
      if (inner && taken.every(([u, v, q]) => Math.hypot(x - u, y - v) > q + r + 1e-3)) return [Math.round(x * 1e4) / 1e4, Math.round(y * 1e4) / 1e4];
    }
  }
  return [0, 0];
}
/** A new object of `kind` for the form: the keys a user would change first, the rest left to
 * the file's defaults. */
function newObject(kind, form) {
  const c = inside(form), r3 = (v) => Math.round(v * 1000) / 1000;
  if (kind === "liquid") {
    const layers = form.liquid || [];
    const below = layers.length ? layers[layers.length - 1].top : c.floor;
    const [name, index] = [["water", 1.333], ["oil", 1.47], ["syrup", 1.49]][Math.min(layers.length, 2)];
    return { name, index, top: r3(below + (c.height - below) / 2) };
  }
  if (kind === "straw" || kind === "coin") { const [x, y] = freeSpot(form, kind === "straw" ? STRAW_R : COIN_R); return { x, y }; }
  // A card behind the container, facing the eye.
  const az = Math.atan2(state.observer[1], state.observer[0]);
  const d = (c.tank ? Math.max(c.hx, c.hy) : c.r) + 0.06;
  return { center: [r3(-d * Math.cos(az)), r3(-d * Math.sin(az)), r3(c.height / 2)], facing: r3(az * 180 / Math.PI), width: 0.08, height: 0.06, picture: "arrow" };
}
/** A glass made a tank (and back), its size kept. */
function reshape(container, shape) {
  if (shape === container.shape) return container;
  if (shape === "tank") return { shape, half_x: container.radius, half_y: container.radius, height: container.height };
  return { shape, radius: Math.min(container.half_x, container.half_y), height: container.height, wall: 0, bottom: 0, index: 1.5 };
}

/** One control: its label (the key's words, the file's key in its tooltip), its value. */
function field(key, name, unit, value) {
  const label = document.createElement("label");
  const words = document.createElement("span");
  // A field's words: its own key ("obj.shape"), or the key's name among the fields' words.
  words.dataset.i18n = name.includes(".") ? name : "field." + name;
  words.textContent = t(words.dataset.i18n);
  label.title = key;
  label.append(words);
  const input = (i, v) => {
    const el = document.createElement("input");
    if (unit === "text") { el.type = "text"; el.value = v ?? ""; }
    else { el.type = "number"; el.step = STEP[unit]; el.value = v ?? ""; el.inputMode = "decimal"; }
    el.dataset.key = key; el.dataset.unit = unit;
    if (i !== null) el.dataset.part = String(i);
    return el;
  };
  if (Array.isArray(unit)) {
    const sel = document.createElement("select");
    sel.dataset.key = key;
    for (const w of unit) {
      const o = document.createElement("option");
      o.value = w; o.dataset.i18n = name + "." + w; o.textContent = t(name + "." + w);
      sel.append(o);
    }
    sel.value = value;
    label.append(sel);
  } else if (unit === "m3") {
    const row = document.createElement("span");
    (value || [0, 0, 0]).forEach((v, i) => row.append(input(i, v)));
    const u = document.createElement("span"); u.className = "unit"; u.textContent = " m";
    row.append(u);
    label.append(row);
  } else {
    const row = document.createElement("span");
    row.append(input(null, value));
    if (unit && unit !== "text") { const u = document.createElement("span"); u.className = "unit"; u.textContent = " " + unit; row.append(u); }
    label.append(row);
  }
  return label;
}
/** A button of the form: its words' key, what it does. */
function formButton(words, title, className, action) {
  const b = document.createElement("button");
  b.type = "button"; b.className = className;
  b.dataset.i18n = words; b.textContent = t(words);
  b.dataset.i18nTitle = title; b.title = t(title);
  b.addEventListener("click", action);
  return b;
}
/** The form's objects as controls: rebuilt when objects come or go, else only their values. */
function showObjects() {
  const form = viewForm();
  if (!form) return;
  const c = form.container || {};
  const signature = [c.shape, ...["liquid", "straw", "coin", "card"].map((k) => (form[k] || []).length)].join(",");
  if (signature === formSignature) { fillObjects(form); return; }
  formSignature = signature;
  const boxes = [];
  const box = (legend, params, fields, table, k) => {
    const fs = document.createElement("fieldset");
    const lg = document.createElement("legend");
    lg.textContent = t(legend, params); // written again with the others when the language changes
    fs.append(lg);
    const prefix = table === "container" ? "container" : `${table}[${k + 1}]`;
    const values = table === "container" ? c : form[table][k];
    if (table === "container") {
      fs.append(field("container.shape", "obj.shape", ["glass", "tank"], c.shape));
    }
    for (const [name, unit] of fields) fs.append(field(`${prefix}.${name}`, name, unit, values[name]));
    if (table !== "container") {
      fs.append(formButton("obj.remove", "obj.remove.title", "remove", () => editForm((f) => { f[table].splice(k, 1); })));
    }
    boxes.push(fs);
  };
  box("obj.container", null, FORM_FIELDS[c.shape === "tank" ? "tank" : "glass"], "container");
  for (const table of ["liquid", "straw", "coin", "card"]) {
    (form[table] || []).forEach((_, k) => box("obj." + table, { i: k + 1 }, FORM_FIELDS[table], table, k));
  }
  const add = document.createElement("div");
  add.className = "add";
  for (const table of ["liquid", "straw", "coin", "card"]) {
    add.append(formButton("obj.add." + table, "obj.add.title", "", () => editForm((f) => { (f[table] = f[table] || []).push(newObject(table, f)); })));
  }
  objectsEl.replaceChildren(...boxes, add);
  fillObjects(form);
}
/** The form's values into its controls, except the one being typed in. */
function fillObjects(form) {
  for (const el of objectsEl.querySelectorAll("[data-key]")) {
    if (el === document.activeElement) continue;
    const v = formValue(form, el.dataset.key);
    const part = el.dataset.part;
    el.value = part !== undefined ? (v ? v[Number(part)] : "") : (v ?? "");
    el.removeAttribute("aria-invalid");
  }
}
/** The value at a rule's key (`straw[2].tilt`, `container.radius`) of a form. */
function formValue(form, key) {
  const m = /^(\w+)(?:\[(\d+)\])?\.(\w+)$/.exec(key);
  if (!m) return undefined;
  const table = m[2] ? (form[m[1]] || [])[Number(m[2]) - 1] : form[m[1]];
  return table ? table[m[3]] : undefined;
}
/** The form's value at `key` set to `v`. */
function setFormValue(form, key, v) {
  const m = /^(\w+)(?:\[(\d+)\])?\.(\w+)$/.exec(key);
  const table = m[2] ? form[m[1]][Number(m[2]) - 1] : (form[m[1]] = form[m[1]] || {});
  table[m[3]] = v;
}

/** The text of the scene file `form` holds, its [observer] the current eye (its target kept). */
async function formText(form) {
  const f = structuredClone(form);
  const target = f.observer && f.observer.target;
  f.observer = target ? { position: state.observer.slice(), target } : { position: state.observer.slice() };
  return answerText(await engineFetch("hook", "/api/scene-text", "form=" + encodeURIComponent(JSON.stringify(f))));
}
/** A control's change: the form changed by `change(form)`, written as the file's text, into the
 * box and the view (or refused by its rules, the view staying). */
async function editForm(change) {
  const form = viewForm();
  if (!form) return;
  const f = structuredClone(form);
  change(f);
  let text;
  try { text = await formText(f); } catch (e) { showSceneErrors(e.shown || e.message); return; }
  clearTimeout(editTimer); editTimer = null;
  sceneText.value = text;
  await applySceneText(text);
}
objectsEl.addEventListener("submit", (e) => e.preventDefault());
objectsEl.addEventListener("change", (e) => {
  const el = e.target, key = el.dataset.key;
  if (!key) return;
  let value;
  if (el.tagName === "SELECT" || el.type === "text") value = el.value;
  else {
    value = el.valueAsNumber;
    if (!Number.isFinite(value)) {
      el.setAttribute("aria-invalid", "true");
      showSceneErrors({ key: "obj.not-a-number", params: { key } });
      return;
    }
  }
  editForm((f) => {
    if (key === "container.shape") { f.container = reshape(f.container, value); return; }
    if (el.dataset.part !== undefined) {
      const p = (formValue(f, key) || [0, 0, 0]).slice();
      p[Number(el.dataset.part)] = value;
      value = p;
    }
    setFormValue(f, key, value);
  });
});
/** Marks the controls whose keys a refusal names, and lists its rules under them. */
function markObjects(error) {
  for (const el of objectsEl.querySelectorAll("[aria-invalid]")) el.removeAttribute("aria-invalid");
  const keys = error && error.refusal ? error.refusal.rules.map((r) => r.key) : error && error.params && error.params.key ? [error.params.key] : [];
  for (const key of keys) for (const el of objectsEl.querySelectorAll(`[data-key="${CSS.escape(key)}"]`)) el.setAttribute("aria-invalid", "true");
  const text = errorText(error);
  objectsErrorsEl.replaceChildren(...text.split("\n").filter((l) => l.trim()).map((l) => { const li = document.createElement("li"); li.textContent = l; return li; }));
  objectsErrorsEl.hidden = !text;
}

// Drags on the maps: a straw, a coin or a card from above, a liquid's surface from the side.
// Each step is the form changed and sent as a text; a step the rules refuse is left out, so the
// object stops where it may still be (no banner: the banner is for typed values).
let dragSending = false, dragNext = null;
/** The object drag under way or last made (a token), and the latest text it made. */
let dragGesture = null, dragText = null;
async function dragForm(change) {
  const form = viewForm();
  if (!form) return;
  const f = structuredClone(form);
  change(f);
  dragNext = f;
  if (dragSending) return;
  dragSending = true;
  while (dragNext) {
    const next = dragNext;
    dragNext = null;
    try {
      const text = await formText(next);
      const observer = await checkScene(text, "hook");
      await useScene(text, observer);
      formOf = { text, key: sceneKey(state), form: next };
      dragText = text;
      showObjects();
      clearTimeout(editTimer); editTimer = null;
      sceneText.value = text;
      showSceneErrors(null);
      changed();
    } catch (_) { /* refused: the object stays at its last allowed place */ }
  }
  dragSending = false;
}
/** The objects a drag can take on a map: `{ kind, k, at }` (their pixels). */
function handlesOf(form, P, side) {
  const hs = [];
  if (side) {
    // A surface's ring beside the container's side, off the layer's tint.
    (form.liquid || []).forEach((l, k) => { const [x, y] = P(l.top); hs.push({ kind: "liquid", k, at: [x + 8, y] }); });
    return hs;
  }
  for (const kind of ["straw", "coin"]) (form[kind] || []).forEach((o, k) => hs.push({ kind, k, at: P(o.x, o.y) }));
  (form.card || []).forEach((o, k) => hs.push({ kind: "card", k, at: P(o.center[0], o.center[1]) }));
  return hs;
}
/** The handle within a fingertip of `(x, y)`, nearest first; null if none. */
function handleAt(handles, x, y, reach) {
  let best = null, bestD = reach;
  for (const h of handles || []) {
    const d = Math.hypot(h.at[0] - x, h.at[1] - y);
    if (d < bestD) { bestD = d; best = h; }
  }
  return best;
}
/** Moves the handle `h` to the map's point `q` (`[x, y]` from above, `[s, z]` from the side). */
function dragHandle(h, q) {
  dragForm((f) => {
    if (h.kind === "liquid") {
      const c = inside(f), layers = f.liquid;
      const lo = (h.k ? layers[h.k - 1].top : c.floor) + 1e-3;
      const hi = h.k + 1 < layers.length ? layers[h.k + 1].top - 1e-3 : c.height;
      layers[h.k].top = Math.round(Math.max(lo, Math.min(hi, q[1])) * 1e5) / 1e5;
    } else if (h.kind === "card") {
      const o = f.card[h.k];
      o.center = [Math.round(q[0] * 1e5) / 1e5, Math.round(q[1] * 1e5) / 1e5, o.center[2]];
    } else {
      const o = f[h.kind][h.k];
      [o.x, o.y] = keepInside(f, q, o.radius || 0);
    }
  });
}

// ---- the hook for tests and scripts: window.bentstraw (see docs/explorer.md) ----
/** Resolves when the full-quality frame of the current state is painted. */
function settled() {
  return new Promise((resolve) => {
    const check = () => (window.bentstraw.busy() ? setTimeout(check, 20) : resolve());
    check();
  });
}
/** The engine's answer as text, or a rejection with its message (the command line's; `shown`:
 * what the page shows of it, its broken rules in the page's language). */
async function answerText(r) {
  if (r.ok) return r.text();
  const why = await refusalOf(r);
  const e = new Error(typeof why === "string" ? why : why.message);
  e.shown = why;
  throw e;
}
Object.assign(window.bentstraw, {
  /** The current image points, as the CSV text `bentstraw simulate` writes. */
  async points() { await settled(); return answerText(await engineFetch("hook", "/api/export", viewQuery(state, { format: "csv" }))); },
  /** The arguments of the `bentstraw simulate` command giving those points (a page's own scene file is scene.toml). */
  async command() { await settled(); return frame.header.simulate_args.slice(); },
  /** The current scene as the text of a scene file, its [observer] the current eye. */
  async scene() { return answerText(await engineFetch("hook", "/api/scene-file", viewQuery(state))); },
  /** Shows the scene file `toml` (from its own [observer], if it has one); rejects with the
   * command line's message if a rule is broken, and the page shows it. */
  async setScene(toml) {
    let observer;
    try {
      observer = await checkScene(toml, "hook");
    } catch (e) {
      showError(e.shown || e.message);
      refused();
      throw e;
    }
    await useScene(toml, observer);
    frame = null;
    changed();
    await settled();
  },
  /** One request to the engine, for measuring it: its status, the time the engine took (around
   * the same call: in the worker, or the server's own, sent as Server-Timing), the time seen by
   * the page, the answer's size. */
  async request(path, query) {
    const t = performance.now();
    const r = await engineFetch("measure", path, query);
    const body = await r.arrayBuffer();
    const ms = performance.now() - t;
    const timing = /engine;dur=([0-9.]+)/.exec(r.headers.get("Server-Timing") || "");
    const server = timing ? Number(timing[1]) : null;
    return { status: r.status, engineMs: wasm ? r.engineMs : server, ms, bytes: body.byteLength };
  },
  /** The address that restores this view, its scene included. */
  link() { return location.origin + location.pathname + stateHash(state); },
  engine: ENGINE,
});

// ---- start: the address's state, else the command line's ----
(async () => {
  await readParams(document.body.dataset.initial || "", state);
  if (location.hash.length > 1) await readParams(location.hash, state);
  if (state.file) history.replaceState(null, "", stateHash(state));
  syncControls();
  drawMaps();
  sendFrame(false);
})();
