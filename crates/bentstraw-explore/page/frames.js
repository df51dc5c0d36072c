// The frames: asking the engine for the view (quick frames while the input moves, then the full
// one), the models' points and the clicked ray, and painting what comes. Holds the last frame,
// the models and the path, and the members of window.bentstraw that report on them.
import { state, viewQuery, stateHash } from "./state.js";
import { ask, cancel, refusalOf } from "./engine.js";
import { $, pictureCanvas } from "./dom.js";
import { showError, linkRefusal, refuseLink } from "./errors.js";
import { drawPicture } from "./picture.js";
import { drawCloud, drawLegend } from "./cloud.js";
import { drawMaps } from "./maps.js";
import { syncControls } from "./controls.js";
import { showHint, showReadout, showStatus, showCommands } from "./readout.js";
import { syncSceneText } from "./scenetext.js";
import { showLesson } from "./lesson.js";
import { QuickScale } from "./quickscale.js";

// Quick frames (while the input moves) take one sample per pixel and this many times fewer image
// points (the full frame, when the input stops, has them all and samples the edges); they are as
// fine as the engine draws them in time (quickscale.js): at full resolution on a laptop's cores,
// coarser on a slow phone.
const QUICK_POINTS = 6;
const quickScale = new QuickScale();
// The full frame is asked for this long after the last quick one: soon, in the page's own engine
// (a full frame superseded by new input is stopped at once); later from the server, whose two
// threads every open page shares.
const FULL_AFTER_MS = document.body.dataset.engine === "wasm" ? 80 : 150;

export let frame = null; // the last good frame: picture, points, header
export let models = { eye: null, stereo: null };
export let path = null; // the clicked ray's path (JSON from the server)
let inputSince = null; // time of the oldest input the painted frame does not show yet
let inFlight = null; // { quick, since }
let dirty = false;
let fullTimer = null;
const latencies = []; // input-to-paint times of painted frames (ms), for the benchmark
let fullPending = false;
/** What window.bentstraw says of the frames (main.js adds the rest). */
export const hook = {
  state, latencies, frames: 0,
  get frame() { return frame; }, get path() { return path; }, get models() { return models; },
  /** The frame being computed now: "quick", "full", or null. */
  get computing() { return inFlight ? (inFlight.quick ? "quick" : "full") : null; },
  /** The scale the next quick frame will be drawn at (1: the box's full resolution). */
  get quickScale() { return quickScale.next(); },
  /** Whether a frame is being computed or the full-quality frame is still to come. */
  busy: () => inFlight !== null || fullPending || dirty || (frame !== null && frame.quick),
};

/** Picture size for the eye panel (full quality) in the screen's pixels: its box times the
 * screen's density, at most 2 (a phone's 3 would cost over twice the time for little to see)
 * and at most 1600x1200; the third number is the density used. */
export function pictureSize() {
  const r = pictureCanvas.getBoundingClientRect();
  let d = Math.min(2, Math.max(1, window.devicePixelRatio || 1));
  // Within the cap, with the box's shape, while the density is above 1.
  d = Math.max(1, Math.min(d, 1600 / Math.max(1, r.width), 1200 / Math.max(1, r.height)));
  const w = Math.max(40, Math.min(1600, Math.round(r.width * d))), h = Math.max(30, Math.min(1200, Math.round(r.height * d)));
  return [w, h, d];
}

/** Called on every change of the state by the user. */
export function changed(options) {
  // The user moves on from a refused link: the view they make is drawn.
  if (linkRefusal) refuseLink(null);
  if (inputSince === null) inputSince = performance.now();
  document.body.dataset.ready = "0";
  history.replaceState(null, "", stateHash(state));
  syncControls();
  drawMaps();
  if (!(options && options.keepPath)) {
    path = null; state.pick = "";
    showHint();
  }
  // The models' points belong to the previous view: they come back with the full frame. Their
  // requests are given up, so that the next full frame, in the same worker, does not wait for them.
  models = { eye: null, stereo: null };
  cancel("model-eye"); cancel("model-stereo");
  requestFrame(true);
}

export function requestFrame(quick) {
  clearTimeout(fullTimer);
  fullPending = false;
  if (inFlight && inFlight.quick && quick) { dirty = true; return; }
  sendFrame(quick);
}

export async function sendFrame(quick) {
  // A refused link: nothing in its place.
  if (linkRefusal) return;
  const [w, h, d] = pictureSize();
  // Quick frames are measured in the box's CSS pixels, whatever the screen's density.
  const scale = quick ? quickScale.next() : null;
  const size = quick ? [Math.max(40, Math.round(w / (scale * d))), Math.max(30, Math.round(h / (scale * d)))] : [w, h];
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
  // In the page's engine, full frames have a worker apart from the quick ones' (shared with the
  // models, which start from its points): one superseded by a drag is stopped without holding up
  // the quick frames.
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
  // The engine's own time: the page's worker's, or the server's.
  if (quick) quickScale.timed(scale, frame.engineMs || frame.header.ms);
  showError("");
  // The first picture is here: the engine's download is over.
  $("loading").hidden = true;
  const t = performance.now();
  paintAll();
  const paintMs = performance.now() - t;
  requestAnimationFrame(() => {
    // Where the time went: waiting to be sent, the request (server included), the body, painting.
    if (since !== null) latencies.push({ ms: performance.now() - since, quick, scale, mode: state.mode, server: frame.header.ms, paint: paintMs, wait: sent - since, request: answered - sent, body: received - answered });
    hook.frames += 1;
    document.body.dataset.frames = String(hook.frames);
  });
  if (dirty) { sendFrame(true); return; }
  if (quick) { fullPending = true; fullTimer = setTimeout(() => { fullPending = false; sendFrame(false); }, FULL_AFTER_MS); }
  else {
    document.body.dataset.ready = "1";
    hook.fullPaintedAt = performance.now();
    requestModels();
    if (state.pick && !path) restorePick();
    syncSceneText();
  }
}

/** The server's binary frame: header, RGBA picture, points (and in white light their bands). */
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
  const kind = new Uint8Array(buffer, at, n); at += n;
  // In white light, each point's band of the spectrum (an index into the header's bands).
  const band = header.bands ? new Uint8Array(buffer, at, n) : null;
  return { header, rgba, xyz, color, kind, band, quick };
}

/** Asks for the eye and stereo models switched on and not yet shown for this view, both at once
 * (each on its own channel): first every 4th point, painted at once, then all of them. In the
 * page's engine they are computed by the worker of the full frames, which holds the frame's points:
 * the models start from them instead of tracing them again. */
export function requestModels() {
  for (const m of ["eye", "stereo"]) {
    // A model switched off gives up its work: on the site it would hold up the next full frame.
    if (!state.models.includes(m)) { if (models[m]) cancel("model-" + m); models[m] = null; continue; }
    if (models[m] && models[m].query === viewQuery(state)) continue; // shown, or on its way
    requestModel(m);
  }
}

async function requestModel(m) {
  const query = viewQuery(state);
  models[m] = { xyz: new Float32Array(0), color: new Uint8Array(0), query, pending: true, all: false };
  const steps = state.points >= 4000 ? [4, 1] : [1];
  for (const every of steps) {
    const r = await ask("model-" + m, "/api/model", viewQuery(state, { model: m, every }), "frame-full");
    if (!r || !r.ok || !models[m] || models[m].query !== query) return; // superseded or refused
    // Counted for the tests: the answers that started from the frame's points.
    if (r.headers.get("X-Points") === "reused") document.body.dataset.modelsReused = String(Number(document.body.dataset.modelsReused || 0) + 1);
    const b = await r.arrayBuffer();
    if (!models[m] || models[m].query !== query) return;
    const n = new DataView(b).getUint32(0, true);
    models[m] = { xyz: new Float32Array(b.slice(4, 4 + 12 * n)), color: new Uint8Array(b, 4 + 12 * n, n), query, pending: false, all: every === 1 };
    drawCloud(); drawLegend();
    document.body.dataset.models = state.models.join(",");
  }
}

function paintAll() {
  drawPicture();
  drawCloud();
  drawLegend();
  showStatus();
  showLesson();
  if (!$("commands").hidden) showCommands();
}


/** Asks for the path of the ray through a pixel (`px:row,col,WxH`) or to a point of the cloud
 * (`point:k`), then shows it. */
export async function pick(what) {
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
  // The ray's words in view: its panel opens (the lesson, the objects and the file fold away).
  $("path-details").open = true;
  document.body.dataset.picked = what;
  drawPicture(); drawCloud(); drawMaps();
}
export function restorePick() { if (state.pick) pick(state.pick); }

/** Resolves when the full-quality frame of the current state is painted. */
export function settled() {
  return new Promise((resolve) => {
    const check = () => (hook.busy() ? setTimeout(check, 20) : resolve());
    check();
  });
}

/** Drops the last frame: the next one is of another scene, nothing of this one stays. */
export function forgetFrame() { frame = null; }

/** A new size of the picture's box: its full frame is asked for again, a moment later. */
export function resized() {
  clearTimeout(fullTimer);
  fullPending = true;
  fullTimer = setTimeout(() => { fullPending = false; sendFrame(false); }, 200);
}
