// "Predict, then look": the picture (and the 3D view, which would give the answer away) hidden,
// the student clicks where they expect the scene's target to appear (a straw's bottom end, a
// coin's centre, an arrow's tip: the engine chooses it, /api/aim), in the hidden picture or on
// the side map; "Reveal" shows the picture with the guess and the true image marked, and how far
// apart they are: an angle in the picture, centimetres on the side map. A link with `predict=1`
// (state.js) opens the page in this mode.
import { t, touchKey, localNumber } from "./i18n.js";
import { state, viewQuery, stateHash } from "./state.js";
import { $, pictureCanvas, cloudCanvas, sideCanvas } from "./dom.js";
import { ask, refusalOf } from "./engine.js";
import { showError } from "./errors.js";
import { frame, path, changed, pick } from "./frames.js";
import { dot } from "./geometry.js";
import { drawMaps } from "./maps.js";

const bar = $("predict-bar"), text = $("predict-text"), cover = $("predict-cover");
const marks = $("predict-marks"), mapMarks = $("predict-map-marks"), cloudCover = $("predict-cloud-cover");
const toggle = $("predict"), revealButton = $("predict-reveal"), againButton = $("predict-again"), pathButton = $("predict-path");

/** The mode's state: `phase` "off", "guess" (the picture hidden) or "shown"; the guesses (a
 * direction from the eye in the picture, a point `[s, z]` of the side map, in metres); the
 * engine's answer for the view `key` (the target and its images), asked as soon as the view is
 * drawn, shown only on "Reveal". */
const P = { phase: "off", guessDir: null, guessMap: null, key: null, answer: null, asked: null };
// Arrow keys move the guess by this share of the picture (with Shift, five times as far).
const KEY_STEP = 0.01;
// Colours of the marks: the guess, the true image.
const GUESS_RGB = "#d62728", SEEN_RGB = "#111";

/** The picture's camera as a map between directions from the eye and the picture canvas's CSS
 * pixels (the picture keeps its aspect in its box: object-fit: contain). */
function pictureMap() {
  if (!frame || !frame.header.camera) return null;
  const c = frame.header.camera, { width, height } = frame.header;
  const r = pictureCanvas.getBoundingClientRect();
  const k = Math.min(r.width / width, r.height / height);
  const x0 = (r.width - k * width) / 2, y0 = (r.height - k * height) / 2, aspect = width / height;
  return {
    rect: r,
    /** A direction to [x, y] in the canvas's CSS pixels, null behind the eye. */
    at(d) {
      const z = dot(d, c.forward);
      if (z <= 1e-12) return null;
      const sx = dot(d, c.right) / z / (c.tan_half_fov * aspect), sy = dot(d, c.up) / z / c.tan_half_fov;
      return [x0 + k * (sx + 1) * width / 2, y0 + k * (1 - sy) * height / 2];
    },
    /** [x, y] in the canvas's CSS pixels to a unit direction, null off the picture. */
    direction(x, y) {
      const col = (x - x0) / k, row = (y - y0) / k;
      if (col < 0 || row < 0 || col > width || row > height) return null;
      const sx = (2 * col / width - 1) * c.tan_half_fov * aspect, sy = (1 - 2 * row / height) * c.tan_half_fov;
      const d = [0, 1, 2].map((i) => c.forward[i] + sx * c.right[i] + sy * c.up[i]);
      const n = Math.hypot(...d);
      return d.map((v) => v / n);
    },
    /** A direction to the frame's pixel [row, col]. */
    pixel(d) { const a = this.at(d); return a && [(a[1] - y0) / k, (a[0] - x0) / k]; },
  };
}

/** The side map's own map between its points [s, z] (metres: across along the eye's azimuth,
 * up) and its CSS pixels, from the inverse maps.js keeps on the canvas. */
function sideMap() {
  const inv = sideCanvas.mapInverse;
  if (!inv) return null;
  const a = inv(0, 0), b = inv(1, 0), k = 1 / (b[0] - a[0]);
  const o = state.observer, az = Math.atan2(o[1], o[0]), u = [Math.cos(az), Math.sin(az)];
  return {
    at: ([s, z]) => [(s - a[0]) * k, (a[1] - z) * k],
    inverse: inv,
    /** A 3D point to the map's [s, z]. */
    of: (p) => [p[0] * u[0] + p[1] * u[1], p[2]],
  };
}

/** Where an image appears on the side map, and by which model: two eyes (the stereo model),
 * else one eye focusing (the eye model), else the course's image point. */
function apparentOf(image) {
  const r = image.ray;
  if (r.stereo_point) return { point: r.stereo_point, model: "stereo" };
  if (r.eye_point) return { point: r.eye_point, model: "eye" };
  return { point: r.image_point, model: "course" };
}

const degrees = (a, b) => (Math.acos(Math.max(-1, Math.min(1, dot(a, b)))) * 180) / Math.PI;

/** The distances from the guesses to the nearest image: in the picture (degrees) and on the
 * side map (metres), with the image each is nearest. */
function results() {
  const a = P.answer;
  if (!a || !a.images.length) return null;
  const out = {};
  if (P.guessDir) {
    const each = a.images.map((im, i) => [degrees(P.guessDir, im.ray.direction), i]);
    const [deg, i] = each.sort((x, y) => x[0] - y[0])[0];
    out.picture = { degrees: deg, image: i };
  }
  const m = sideMap();
  if (P.guessMap && m) {
    const each = a.images.map((im, i) => {
      const [s, z] = m.of(apparentOf(im).point);
      return [Math.hypot(s - P.guessMap[0], z - P.guessMap[1]), i];
    });
    const [metres, i] = each.sort((x, y) => x[0] - y[0])[0];
    out.map = { metres, image: i, model: apparentOf(a.images[i]).model };
  }
  return out;
}

/** Puts `el` over `under` (both children of the same panel), at its place and size. */
function overlay(el, under) {
  el.style.left = under.offsetLeft + "px"; el.style.top = under.offsetTop + "px";
  el.style.width = under.offsetWidth + "px"; el.style.height = under.offsetHeight + "px";
}
/** A canvas of the screen's density over `under`, cleared: its context in CSS pixels. */
function fitOver(canvas, under) {
  overlay(canvas, under);
  const d = window.devicePixelRatio || 1, w = under.offsetWidth, h = under.offsetHeight;
  canvas.width = Math.max(1, Math.round(w * d)); canvas.height = Math.max(1, Math.round(h * d));
  const ctx = canvas.getContext("2d");
  ctx.setTransform(d, 0, 0, d, 0, 0);
  ctx.clearRect(0, 0, w, h);
  return ctx;
}

/** A mark of `size` px at `at` (a cross, or with `ring` a ring round a dot: the two still read
 * when they fall on one spot), `label` beside it (below it with `below`), over a light halo;
 * the label moves down past those `placed` before it (boxes [x0, y0, x1, y1]). */
function cross(ctx, at, colour, label, placed, { size = 9, below = false, ring = false } = {}) {
  if (!at) return;
  const [x, y] = at;
  const strokeX = ring
    ? () => { ctx.beginPath(); ctx.arc(x, y, size + 3, 0, 2 * Math.PI); ctx.moveTo(x + 1.5, y); ctx.arc(x, y, 1.5, 0, 2 * Math.PI); ctx.stroke(); }
    : () => { ctx.beginPath(); ctx.moveTo(x - size, y - size); ctx.lineTo(x + size, y + size); ctx.moveTo(x - size, y + size); ctx.lineTo(x + size, y - size); ctx.stroke(); };
  ctx.lineCap = "round";
  ctx.lineWidth = 6; ctx.strokeStyle = "rgba(255,255,255,0.85)"; strokeX();
  ctx.lineWidth = 3; ctx.strokeStyle = colour; strokeX();
  if (!label) return;
  ctx.font = "600 13px system-ui, sans-serif";
  const w = ctx.measureText(label).width, lx = x + size + 4;
  let ly = below ? y + size + 14 : y - size;
  const hits = (b) => b[0] < lx + w + 2 && lx - 2 < b[2] && b[1] < ly + 4 && ly - 12 < b[3];
  while (placed.some(hits)) ly += 17;
  placed.push([lx - 2, ly - 12, lx + w + 2, ly + 4]);
  ctx.fillStyle = "rgba(255,255,255,0.85)"; ctx.fillRect(lx - 2, ly - 12, w + 4, 16);
  ctx.fillStyle = colour; ctx.fillText(label, lx, ly);
}

/** The marks over the picture: the guess, and once shown each image of the target. */
function drawPictureMarks() {
  const ctx = fitOver(marks, pictureCanvas), m = pictureMap(), placed = [];
  if (!m) return;
  if (P.phase === "shown" && P.answer) {
    const r = results();
    P.answer.images.forEach((im, i) => {
      const nearest = r && r.picture && r.picture.image === i;
      cross(ctx, m.at(im.ray.direction), SEEN_RGB, t("mark.seen"), placed, { size: nearest || !r || !r.picture ? 10 : 7, below: true, ring: true });
    });
  }
  if (P.guessDir) cross(ctx, m.at(P.guessDir), GUESS_RGB, t("mark.guess"), placed);
}

/** The marks over the side map: the guess, and once shown the target's true place, each
 * image's apparent place and the line of sight to it. */
function drawMapMarks() {
  const ctx = fitOver(mapMarks, sideCanvas), m = sideMap(), placed = [];
  if (!m) return;
  if (P.phase === "shown" && P.answer && P.answer.target) {
    const eye = sideCanvas.eyeAt;
    for (const im of P.answer.images) {
      const at = m.at(m.of(apparentOf(im).point));
      if (eye) {
        ctx.setLineDash([5, 4]); ctx.lineWidth = 1.5; ctx.strokeStyle = "#555";
        ctx.beginPath(); ctx.moveTo(...eye); ctx.lineTo(...at); ctx.stroke(); ctx.setLineDash([]);
      }
      cross(ctx, at, SEEN_RGB, t("mark.seen"), placed, { size: 7, below: true, ring: true });
    }
    const real = m.at(m.of(P.answer.target.point));
    ctx.lineWidth = 2; ctx.strokeStyle = "#1f77b4";
    ctx.beginPath(); ctx.arc(real[0], real[1], 6, 0, 2 * Math.PI); ctx.stroke();
  }
  if (P.guessMap) cross(ctx, m.at(P.guessMap), GUESS_RGB, t("mark.guess"), placed, { size: 7 });
}

/** The target's words ("the bottom of the straw"…), once the engine has named it. */
const targetWords = () => t("predict.target." + (P.answer && P.answer.target ? P.answer.target.kind : "straw-bottom"));

/** The bar's text and buttons, and the covers, for the phase. */
function show() {
  const on = P.phase !== "off", hidden = P.phase === "guess";
  toggle.setAttribute("aria-pressed", String(on));
  bar.hidden = !on;
  cover.hidden = !hidden;
  cloudCover.hidden = !hidden;
  marks.hidden = !on;
  mapMarks.hidden = !on;
  pictureCanvas.style.visibility = hidden ? "hidden" : "";
  cloudCanvas.style.visibility = hidden ? "hidden" : "";
  $("legend").style.visibility = hidden ? "hidden" : "";
  document.body.dataset.predict = P.phase;
  if (!on) return;
  const noTarget = P.answer && !P.answer.target;
  revealButton.hidden = !hidden;
  revealButton.disabled = noTarget || !(P.guessDir || P.guessMap);
  againButton.hidden = hidden;
  pathButton.hidden = hidden || !(P.answer && P.answer.images.length);
  cover.setAttribute("aria-label", t(touchKey("predict.click"), { target: targetWords() }));
  $("predict-question").textContent = noTarget ? t("predict.no-target") : t("predict.question", { target: targetWords() });
  const lines = [];
  if (noTarget) lines.push(t("predict.no-target"));
  else if (hidden) lines.push(t(touchKey(P.guessDir || P.guessMap ? "predict.placed" : "predict.click"), { target: targetWords() }));
  else if (!P.answer) lines.push(t("predict.waiting"));
  else if (!P.answer.images.length) lines.push(t("predict.result.none", { target: targetWords() }));
  else {
    const r = results();
    if (r.picture) lines.push(t("predict.result.picture", { angle: localNumber(r.picture.degrees.toFixed(1)), target: targetWords() }));
    if (r.map) lines.push(t("predict.result.map." + r.map.model, { cm: localNumber((100 * r.map.metres).toFixed(1)), target: targetWords() }));
    if (P.answer.images.length > 1) lines.push(t("predict.result.many", { n: P.answer.images.length }));
  }
  text.replaceChildren(...lines.map((l) => Object.assign(document.createElement("span"), { textContent: l })));
  redraw();
}

/** Every mark again (a new frame, a new size, the page's language). */
export function redraw() {
  if (P.phase === "off") return;
  overlay(cover, pictureCanvas);
  overlay(cloudCover, cloudCanvas);
  drawPictureMarks();
  drawMapMarks();
}

/** Asks the engine where the target appears in the view drawn (kept hidden until "Reveal"). */
async function askAnswer() {
  if (!frame) return;
  const key = P.key, size = `${frame.header.width}x${frame.header.height}`;
  if (P.asked === key) return;
  P.asked = key;
  const r = await ask("aim", "/api/aim", viewQuery(state, { size }), "ray");
  if (!r || P.key !== key) return; // superseded: a newer view asks again
  if (!r.ok) { showError(await refusalOf(r)); P.asked = null; return; }
  P.answer = await r.json();
  document.body.dataset.predictAnswer = key;
  show();
}

/** A new frame: a new view starts a new guess; the answer is asked for once the view settles. */
function framed() {
  if (P.phase === "off" || !frame) return;
  const key = viewQuery(state);
  if (key !== P.key) {
    Object.assign(P, { key, answer: null, asked: null, guessDir: null, guessMap: null, phase: "guess" });
    show();
  } else redraw();
  if (document.body.dataset.ready === "1") askAnswer();
}
new MutationObserver(framed).observe(document.body, { attributes: true, attributeFilter: ["data-frames", "data-ready"] });
new ResizeObserver(redraw).observe(pictureCanvas);
new ResizeObserver(redraw).observe(sideCanvas);

/** Drops the clicked ray (a new frame of the same view), and its lines on the maps at once. */
function forgetPath() { changed({}); drawMaps(); }

/** Into the mode or out of it, as the state says (a link, the toggle). */
export function syncPredict() {
  const on = Boolean(state.predict);
  if (on === (P.phase !== "off")) return;
  Object.assign(P, { phase: on ? "guess" : "off", key: null, answer: null, asked: null, guessDir: null, guessMap: null });
  // A clicked ray on the picture or the maps would give the answer away.
  if (on && (path || state.pick)) forgetPath();
  show();
  framed();
}

/** The texts again, in the page's language. */
export function relabelPredict() { if (P.phase !== "off") show(); }

function setGuess(kind, value) {
  if (P.phase !== "guess") return;
  P[kind] = value;
  show();
}

toggle.addEventListener("click", () => {
  state.predict = !state.predict;
  history.replaceState(null, "", stateHash(state));
  syncPredict();
  if (state.predict) cover.focus({ preventScroll: true });
});
revealButton.addEventListener("click", () => reveal());
againButton.addEventListener("click", () => {
  Object.assign(P, { phase: "guess", guessDir: null, guessMap: null });
  // The light's path shown would give the answer away (the view is the same: a new frame of it).
  if (path || state.pick) forgetPath();
  show();
  cover.focus({ preventScroll: true });
});
pathButton.addEventListener("click", () => {
  const r = results(), m = pictureMap();
  if (!P.answer || !P.answer.images.length || !m) return;
  const im = P.answer.images[r && r.picture ? r.picture.image : r && r.map ? r.map.image : 0];
  const [row, col] = m.pixel(im.ray.direction);
  const { width, height } = frame.header;
  pick(`px:${Math.round(row * 100) / 100},${Math.round(col * 100) / 100},${width}x${height}`);
});

/** Shows the picture with the guesses and the images of the target marked. */
export async function reveal() {
  if (P.phase !== "guess" || !(P.guessDir || P.guessMap)) return;
  P.phase = "shown";
  show();
  if (!P.answer) await askAnswer();
  revealButton.blur();
  againButton.focus({ preventScroll: true });
}

// The guess in the hidden picture: a click or a tap; the arrow keys move it, Enter reveals.
cover.addEventListener("click", (e) => {
  const m = pictureMap();
  if (!m) return;
  const d = m.direction(e.clientX - m.rect.left, e.clientY - m.rect.top);
  if (d) setGuess("guessDir", d);
});
cover.addEventListener("keydown", (e) => {
  const steps = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, -1], ArrowDown: [0, 1] };
  if (e.key === "Enter" || e.key === " ") { e.preventDefault(); reveal(); return; }
  const s = steps[e.key], m = pictureMap();
  if (!s || !m) return;
  e.preventDefault();
  const w = m.rect.width, h = m.rect.height, k = (e.shiftKey ? 5 : 1) * KEY_STEP * Math.min(w, h);
  const at = (P.guessDir && m.at(P.guessDir)) || [w / 2, h / 2];
  const d = m.direction(Math.min(w, Math.max(0, at[0] + s[0] * k)), Math.min(h, Math.max(0, at[1] + s[1] * k)));
  if (d) setGuess("guessDir", d);
});
// The guess on the side map: a click or a tap that did not drag.
let downAt = null;
sideCanvas.addEventListener("pointerdown", (e) => { downAt = [e.clientX, e.clientY]; });
sideCanvas.addEventListener("click", (e) => {
  if (P.phase !== "guess" || !downAt || Math.hypot(e.clientX - downAt[0], e.clientY - downAt[1]) > 4) return;
  const r = sideCanvas.getBoundingClientRect(), m = sideMap();
  if (m) setGuess("guessMap", m.inverse(e.clientX - r.left, e.clientY - r.top));
});

/** What the tests and scripts read (window.bentstraw.predict): the phase, the answer, the
 * distances, and where an image lies on the screen (in the picture, on the side map). */
export const predictHook = {
  get phase() { return P.phase; },
  get answer() { return P.answer; },
  results,
  /** Where image `k` of the target appears in the picture, in the window's coordinates. */
  screenOfImage(k) {
    const m = pictureMap();
    const at = m && P.answer && P.answer.images[k] ? m.at(P.answer.images[k].ray.direction) : null;
    return at && [m.rect.left + at[0], m.rect.top + at[1]];
  },
  /** Where the guess in the picture is drawn, in the window's coordinates. */
  screenOfGuess() {
    const m = pictureMap(), at = m && P.guessDir ? m.at(P.guessDir) : null;
    return at && [m.rect.left + at[0], m.rect.top + at[1]];
  },
  /** Where image `k`'s apparent place is on the side map, in the window's coordinates. */
  screenOfApparent(k) {
    const m = sideMap(), r = sideCanvas.getBoundingClientRect();
    if (!m || !P.answer || !P.answer.images[k]) return null;
    const at = m.at(m.of(apparentOf(P.answer.images[k]).point));
    return [r.left + at[0], r.top + at[1]];
  },
  reveal,
};
