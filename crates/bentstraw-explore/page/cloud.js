// The 3D point cloud: where the straw appears, with the scene's outlines, the axes, the models'
// points and the clicked ray; its legend; turning, zooming and clicking a point.
import { t } from "./i18n.js";
import { state, SECTION_RGB, GLASS_R, GLASS_H, STRAW_R, STRAW_H, stateHash } from "./state.js";
import { sub, dot } from "./geometry.js";
import { $, cloudCanvas } from "./dom.js";
import { fit, drawPath } from "./draw.js";
import { onDrag } from "./pointer.js";
import { frame, models, path, pick } from "./frames.js";
import { sceneBox, sceneLines } from "./sketch.js";
import { colourName, pathWords } from "./readout.js";

/** The 3D view's projection: orthographic, z up, azimuth/elevation/zoom of state.view. */
export function cloudProjection(w, h) {
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

let layer = null, layerPixels = null;
/** A CSS colour "#rrggbb" and an alpha 0..255 as one little-endian RGBA pixel. */
function rgba32(hex, alpha) {
  const v = parseInt(hex.slice(1), 16);
  return ((alpha << 24) | ((v & 0xff) << 16) | (v & 0xff00) | (v >> 16)) >>> 0;
}

export function drawCloud() {
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
  // Each point in its section's colour, or (`index` given) in the colour of entry `index[i]` of
  // `list`: its kind of light path (one colour everywhere, the engine's) or in white light its
  // band of the spectrum (its wavelength's colour).
  const drawSet = (xyz, color, index, list, alpha) => {
    const palette = (index ? list.map((p) => p.rgb) : SECTION_RGB).map((c) => rgba32(c, alpha));
    const r = Math.max(1, Math.round(1.2 * d));
    for (let i = 0; i < color.length; i++) {
      const [x, y] = pr.p([xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]]);
      const cx = Math.round(x * d), cy = Math.round(y * d);
      if (cx < r || cy < r || cx >= W - r || cy >= H - r) continue;
      const c = palette[index ? index[i] : color[i] - 1];
      for (let a = -r; a < r; a++) px.fill(c, (cy + a) * W + cx - r, (cy + a) * W + cx + r);
    }
  };
  if (frame && state.models.includes("course")) {
    if (state.color === "path") drawSet(frame.xyz, frame.color, frame.kind, frame.header.paths, 255);
    else drawSet(frame.xyz, frame.color, frame.band, frame.header.bands, 255);
  }
  if (models.eye && state.models.includes("eye")) drawSet(models.eye.xyz, models.eye.color, null, null, 110);
  if (models.stereo && state.models.includes("stereo")) drawSet(models.stereo.xyz, models.stereo.color, null, null, 110);
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
/** The cloud's legend: a line per colour (a section, a light path, or in white light a band of
 * the spectrum) with its count, and the models'. */
export function drawLegend() {
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
  else if (frame.header.bands) frame.header.bands.forEach((b) => item(b.rgb, `${b.nm} nm`, b.count));
  else frame.header.points_per_color.forEach((c, i) => { if ((i < 5 && !state.scene && !state.file) || c > 0) item(SECTION_RGB[i], `${i + 1} ${colourName(i + 1)}`, c); });
  const modelCount = (m) => (!m || m.pending ? "…" : m.all ? m.color.length : t("legend.more", { n: m.color.length }));
  if (state.models.includes("eye")) item("rgba(0,0,0,.3)", t("legend.eye"), modelCount(models.eye));
  if (state.models.includes("stereo")) item("rgba(0,0,0,.3)", t("legend.stereo"), modelCount(models.stereo));
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

/** Where point `k` of the cloud is drawn, in the window's coordinates. */
export function screenOfPoint(k) {
  const r = cloudCanvas.getBoundingClientRect();
  const [x, y] = cloudProjection(r.width, r.height).p([frame.xyz[3 * k], frame.xyz[3 * k + 1], frame.xyz[3 * k + 2]]);
  return [r.left + x, r.top + y];
}

