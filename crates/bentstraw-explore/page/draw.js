// Drawing shared by the panels: a canvas fitted to its box, and the clicked ray's path drawn
// through any of the panels' projections.
import { t } from "./i18n.js";
import { add, scale } from "./geometry.js";
import { path } from "./frames.js";

/** Canvas sized to its box (in CSS pixels times the screen's density). */
export function fit(canvas) {
  const r = canvas.getBoundingClientRect(), d = window.devicePixelRatio || 1;
  const w = Math.max(1, Math.round(r.width * d)), h = Math.max(1, Math.round(r.height * d));
  if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
  const ctx = canvas.getContext("2d");
  ctx.setTransform(d, 0, 0, d, 0, 0);
  return { ctx, w: r.width, h: r.height };
}


/** Adds the 3D polyline `points` to the current path through the projection `pr`, broken where a
 * point cannot be drawn; how many points it drew. */
export function tracePolyline(ctx, pr, points) {
  let open = false, n = 0;
  for (const q of points) {
    const at = pr.p(q);
    if (!at) { open = false; continue; }
    if (open) ctx.lineTo(...at); else ctx.moveTo(...at);
    open = true; n++;
  }
  return n;
}

/** The clicked ray through the projection `pr` (a 3D point to the canvas, or null where it
 * cannot be drawn): its broken path, each event marked (a disk for a refraction, a square for a
 * total reflection), and with `labels` the image points of the three models, named without
 * overlapping. `size` scales lines and marks (a canvas in the screen's pixels). */
export function drawPath(ctx, pr, { labels = true, size = 1 } = {}) {
  const pts = [path.observer, ...path.events.map((e) => e.point)];
  if (path.outcome === "straw") pts.push(path.straw_point);
  else if (path.leaves) pts.push(add(path.leaves.from, scale(path.leaves.direction, 0.15)));
  const polyline = (points) => { ctx.beginPath(); tracePolyline(ctx, pr, points); ctx.stroke(); };
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
