// The side and top maps: the glass or the scene's outlines and liquids, the eye, the straw, the
// transparent solids and the objects' handles, and their drags (the eye, the glass's straw, a scene's objects).
import { t, localNumber, liquidName } from "./i18n.js";
import { state, SECTION_RGB, GLASS_R, GLASS_H, STRAW_R, STRAW_H } from "./state.js";
import { sideCanvas, topCanvas } from "./dom.js";
import { fit, drawPath } from "./draw.js";
import { onDrag } from "./pointer.js";
import { path, changed } from "./frames.js";
import { sceneLines } from "./sketch.js";
import { profileAt } from "./geometry.js";
import { outside, pinchEye } from "./picture.js";
import { viewForm, handlesOf, handleAt, dragHandle, startGesture } from "./editor.js";

/** The scene's box [x0, y0, z0, x1, y1, z1]: the glass and its straw, or a scene file's. */
function sceneBounds(lines) {
  return lines ? lines.bounds : [-GLASS_R, -GLASS_R, 0, GLASS_R, GLASS_R, Math.max(GLASS_H, STRAW_H)];
}
/** How far a map shows, about its centre, along each of its axes: the container and its objects
 * with a margin, widened towards the eye while the container keeps two thirds of the map (a
 * far eye is drawn at the map's edge, pointing its way). */
function mapHalf(room, eye) { return Math.max(room, Math.min(1.1 * Math.abs(eye), 1.5 * room)); }
/** Pixels per metre of a map `w` by `h` showing half extents `hx`, `hy`. */
const mapScale = (w, h, hx, hy) => Math.max(1e-3, Math.min(w / (2 * hx), (h - 32) / (2 * hy)));
/**
 * The eye's place on a map: its pixel, or where the line from the map's centre to it leaves the
 * map (then `far`: it is farther than the map shows).
 */
function eyeOnMap([x, y], w, h) {
  const [cx, cy] = [w / 2, h / 2], m = 12;
  const f = Math.min(1, ...[[x - cx, cx - m], [y - cy, cy - 16 - m]].map(([d, room]) => (Math.abs(d) > room ? room / Math.abs(d) : 1)));
  return { at: [cx + f * (x - cx), cy + f * (y - cy)], far: f < 1 };
}
/** The eye on a map: a disc, or at the edge a ring with an arrow its way and its distance. */
function drawEye(ctx, eye, [x, y], distance) {
  const [ex, ey] = eye.at;
  ctx.fillStyle = "#000"; ctx.strokeStyle = "#000"; ctx.lineWidth = 2;
  ctx.beginPath(); ctx.arc(ex, ey, 6, 0, 2 * Math.PI);
  if (!eye.far) { ctx.fill(); ctx.lineWidth = 1; return; }
  ctx.fillStyle = "#fff"; ctx.fill(); ctx.stroke();
  const d = Math.hypot(x - ex, y - ey) || 1, u = [(x - ex) / d, (y - ey) / d];
  ctx.beginPath(); ctx.moveTo(ex + 9 * u[0], ey + 9 * u[1]); ctx.lineTo(ex + 4 * u[0] - 4 * u[1], ey + 4 * u[1] + 4 * u[0]); ctx.lineTo(ex + 4 * u[0] + 4 * u[1], ey + 4 * u[1] - 4 * u[0]); ctx.closePath();
  ctx.fillStyle = "#000"; ctx.fill();
  ctx.font = "11px system-ui"; ctx.fillStyle = "#1d2330";
  const text = `${localNumber(distance.toFixed(2))} m`, tw = ctx.measureText(text).width;
  ctx.fillText(text, Math.max(2, Math.min(ex - tw / 2, ctx.canvas.clientWidth - tw - 2)), ey + (u[1] > 0 ? -10 : 18));
  ctx.lineWidth = 1;
}

/** Each liquid layer's colour on the maps, bottom first (water blue, then amber, green, purple). */
const LIQUID_RGB = [[74, 127, 193], [214, 160, 40], [60, 160, 90], [140, 90, 180]];
/** The tint of layer `k` of index `n`: the more the liquid bends light, the deeper its colour;
 * a liquid with a colour of its own (`tint`, "#rrggbb") takes that hue, as in the picture. */
function liquidTint(k, n, tint) {
  const own = /^#[0-9a-f]{6}$/i.test(tint ?? "") ? [1, 3, 5].map((i) => parseInt(tint.slice(i, i + 2), 16)) : null;
  const [r, g, b] = own ?? LIQUID_RGB[k % LIQUID_RGB.length];
  const alpha = 0.15 + 0.25 * Math.min(1, Math.max(0, (n - 1) / 0.6));
  return `rgba(${r},${g},${b},${alpha.toFixed(3)})`;
}
/** A scene's liquid layers as `[bottom, top, index, name, tint]`, bottom first, from its sketch. */
function liquidLayers(lines) {
  const floor = lines.container ? lines.container.floor : 0;
  return lines.liquids.map((l, k) => [k ? lines.liquids[k - 1].top : floor, l.top, l.index, l.name, l.tint]);
}
/** The container's half width along the side map's horizontal `u`: a glass's inner radius, a
 * tank's half width in that direction, a glass of revolution's widest outer radius. */
const halfWidth = (c, u) => (c.shape === "tank" ? Math.abs(u[0]) * c.half_x + Math.abs(u[1]) * c.half_y : c.radius);
/**
 * The liquids on the side map, each layer tinted across the container's inside as seen along the
 * eye's azimuth `u` (a glass's inner diameter, a tank's width in that direction, a glass of
 * revolution's inner profile at each height, straight between its points), its name and index
 * beside it; `P(s, z)` is the map's pixel.
 */
function drawLiquidsSide(ctx, lines, u, P) {
  const c = lines.container;
  if (!c) return;
  const half = halfWidth(c, u);
  liquidLayers(lines).forEach(([z0, z1, n, name, tint], k) => {
    const [x0, y0] = P(-half, z1), [x1, y1] = P(half, z0);
    ctx.fillStyle = liquidTint(k, n, tint);
    if (c.shape === "revolution") {
      const at = (z) => [profileAt(c.inner, z) ?? 0, z];
      const right = [at(z0), ...c.inner.filter(([, z]) => z > z0 && z < z1), at(z1)];
      ctx.beginPath();
      right.forEach(([r, z], i) => (i ? ctx.lineTo(...P(r, z)) : ctx.moveTo(...P(r, z))));
      for (const [r, z] of right.reverse()) ctx.lineTo(...P(-r, z));
      ctx.fill();
    } else ctx.fillRect(x0, y0, x1 - x0, y1 - y0);
    if (y1 - y0 >= 12) {
      ctx.fillStyle = "#3b4454"; ctx.font = "11px system-ui";
      ctx.fillText(`${liquidName(name)} · n ${localNumber(n)}`, x1 + 4, Math.min(y1 - 2, y0 + 12));
    }
  });
}
/** The top liquid on the map from above: the container's inside, tinted; `P(x, y)` its pixel. */
function drawLiquidsTop(ctx, lines, P, k) {
  const c = lines.container, layers = liquidLayers(lines);
  if (!c || !layers.length) return;
  const top = layers.length - 1;
  ctx.fillStyle = liquidTint(top, layers[top][2], layers[top][4]);
  ctx.beginPath();
  // (A glass of revolution's inside at the top liquid's surface.)
  if (c.shape === "glass") ctx.arc(...P(0, 0), c.radius * k, 0, 2 * Math.PI);
  else if (c.shape === "revolution") ctx.arc(...P(0, 0), (profileAt(c.inner, layers[top][1]) ?? 0) * k, 0, 2 * Math.PI);
  else ctx.rect(...P(-c.half_x, c.half_y), 2 * c.half_x * k, 2 * c.half_y * k);
  ctx.fill();
}
/** A glass of revolution on the side map: its wall's section, both profiles mirrored about the
 * axis, straight between their points (the wireframe's meridians show the smooth wall). */
function drawProfilesSide(ctx, c, P) {
  const section = [...c.outer, ...[...c.inner].reverse()];
  ctx.beginPath();
  section.forEach(([r, z], i) => (i ? ctx.lineTo(...P(r, z)) : ctx.moveTo(...P(r, z))));
  for (const [r, z] of section.reverse()) ctx.lineTo(...P(-r, z));
  ctx.closePath();
  ctx.fillStyle = "rgba(74,127,193,0.18)"; ctx.strokeStyle = "#4a7fc1"; ctx.lineWidth = 1.25;
  ctx.fill(); ctx.stroke();
  ctx.lineWidth = 1;
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

/** Both maps: side (the plane through the glass's axis and the eye) and top. */
export function drawMaps() {
  const o = state.observer, [sx, sy] = state.straw;
  const lines = sceneLines();
  const b = sceneBounds(lines).slice();
  // The transparent solids too, wherever they stand (a lens between the eye and the glass).
  const form = lines ? viewForm() : null;
  for (const [c, r] of form ? [...(form.sphere || []).map((o) => [o.center, o.radius]), ...(form.lens || []).map((o) => [o.center, o.diameter / 2]), ...(form.prism || []).flatMap((o) => o.corners.map(([x, y]) => [[x, y, (o.bottom + o.top) / 2], (o.top - o.bottom) / 2]))] : []) {
    for (let i = 0; i < 3; i++) { b[i] = Math.min(b[i], c[i] - r); b[i + 3] = Math.max(b[i + 3], c[i] + r); }
  }
  const reach = 1.15 * Math.max(...[0, 1, 3, 4].map((i) => Math.abs(b[i])));
  const zc = (b[2] + b[5]) / 2, zHalf = 0.55 * (b[5] - b[2]) + 0.01;
  // Side: horizontal axis along the eye's azimuth.
  {
    const { ctx, w, h } = fit(sideCanvas);
    ctx.clearRect(0, 0, w, h);
    const az = Math.atan2(o[1], o[0]);
    const u = [Math.cos(az), Math.sin(az)];
    const k = mapScale(w, h, mapHalf(reach, Math.hypot(o[0], o[1])), mapHalf(zHalf, o[2] - zc));
    const P = (s, z) => [w / 2 + k * s, h / 2 - k * (z - zc)];
    ctx.fillStyle = "#5b667a"; ctx.font = "12px system-ui"; ctx.fillText(t("map.side"), 6, 14);
    sideCanvas.handles = [];
    if (lines) {
      // A gallery scene, seen along the eye's azimuth: `s` across, z up.
      drawLiquidsSide(ctx, lines, u, P);
      drawLines(ctx, lines, (q) => P(q[0] * u[0] + q[1] * u[1], q[2]));
      const form = viewForm(), c = lines.container;
      if (c && c.shape === "revolution") drawProfilesSide(ctx, c, P);
      if (form) drawSolids(ctx, form, (q) => P(q[0] * u[0] + q[1] * u[1], q[2]), k, [-u[1], u[0], 0]);
      if (form && c) {
        sideCanvas.handles = handlesOf(form, P, { u, half: halfWidth(c, u) });
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
    const eyePx = P(Math.hypot(o[0], o[1]), o[2]), eye = eyeOnMap(eyePx, w, h);
    if (path) drawPath(ctx, { p: (q) => P(q[0] * u[0] + q[1] * u[1], q[2]) }, { labels: false, size: 0.8 });
    drawEye(ctx, eye, eyePx, Math.hypot(o[0], o[1], o[2] - zc));
    sideCanvas.mapInverse = (x, y) => [(x - w / 2) / k, zc - (y - h / 2) / k];
    sideCanvas.eyeAt = eye.at; sideCanvas.eyeFar = eye.far; sideCanvas.centre = [0, zc];
  }
  // Top.
  {
    const { ctx, w, h } = fit(topCanvas);
    ctx.clearRect(0, 0, w, h);
    const k = mapScale(w, h, mapHalf(reach, o[0]), mapHalf(reach, o[1]));
    const P = (x, y) => [w / 2 + k * x, h / 2 - k * y]; // x right, y up: as the report's top views
    ctx.fillStyle = "#5b667a"; ctx.font = "12px system-ui"; ctx.fillText(t("map.top"), 6, 14);
    topCanvas.handles = [];
    if (lines) {
      drawLiquidsTop(ctx, lines, P, k);
      drawLines(ctx, lines, (q) => P(q[0], q[1]));
      // A glass of revolution's outline from above: its widest circle.
      const c = lines.container;
      if (c && c.shape === "revolution") { ctx.strokeStyle = "#4a7fc1"; ctx.beginPath(); ctx.arc(...P(0, 0), c.radius * k, 0, 2 * Math.PI); ctx.stroke(); }
      const form = viewForm();
      if (form) { drawSolids(ctx, form, (q) => P(q[0], q[1]), k, [0, 0, 1]); topCanvas.handles = handlesOf(form, P, null); drawHandles(ctx, topCanvas.handles); }
    }
    else {
      ctx.fillStyle = state.he > 0 ? liquidTint(0, state.n) : "transparent"; ctx.strokeStyle = "#4a7fc1";
      ctx.beginPath(); ctx.arc(...P(0, 0), GLASS_R * k, 0, 2 * Math.PI); ctx.fill(); ctx.stroke();
      ctx.fillStyle = SECTION_RGB[4]; ctx.beginPath(); ctx.arc(...P(sx, sy), Math.max(3, STRAW_R * k), 0, 2 * Math.PI); ctx.fill();
    }
    const eyePx = P(o[0], o[1]), eye = eyeOnMap(eyePx, w, h), [ex, ey] = eye.at;
    ctx.strokeStyle = "rgba(0,0,0,.35)"; ctx.beginPath(); ctx.moveTo(ex, ey); ctx.lineTo(...P(0, 0)); ctx.stroke();
    if (path) drawPath(ctx, { p: (q) => P(q[0], q[1]) }, { labels: false, size: 0.8 });
    drawEye(ctx, eye, eyePx, Math.hypot(o[0], o[1]));
    topCanvas.mapInverse = (x, y) => [(x - w / 2) / k, (h / 2 - y) / k];
    topCanvas.eyeAt = eye.at; topCanvas.eyeFar = eye.far;
    topCanvas.strawAt = lines ? null : P(sx, sy);
  }
}

/** The form's transparent solids on a map, tinted as glass (`at` a point's pixel, `k` pixels per
 * metre, `n` the unit vector the map looks along): a sphere's disc of its radius about its
 * centre; a prism's outline (from above its polygon, from the side the rectangle of its width
 * along the map and its height); a lens's profile (its section through its axis, across the
 * line of sight) and its rim's circle (from along its axis a circle, at a slant an ellipse). */
function drawSolids(ctx, form, at, k, n) {
  ctx.lineWidth = 1.5; ctx.strokeStyle = "#1b7f86"; ctx.fillStyle = "rgba(27,127,134,0.16)";
  for (const o of form.sphere || []) {
    ctx.beginPath(); ctx.arc(...at(o.center), Math.max(2, o.radius * k), 0, 2 * Math.PI); ctx.fill(); ctx.stroke();
  }
  const outline = (pts) => { ctx.beginPath(); pts.forEach((q, i) => (i ? ctx.lineTo(...q) : ctx.moveTo(...q))); ctx.closePath(); ctx.fill(); ctx.stroke(); };
  for (const o of form.prism || []) {
    if (n[2] === 1) { outline(o.corners.map(([x, y]) => at([x, y, 0]))); continue; }
    // From the side: the corners' extent along the map, from the bottom to the top.
    const xs = o.corners.map(([x, y]) => at([x, y, o.bottom])[0]);
    const [x0, x1] = [Math.min(...xs), Math.max(...xs)], y0 = at([0, 0, o.top])[1], y1 = at([0, 0, o.bottom])[1];
    outline([[x0, y0], [Math.max(x1, x0 + 2), y0], [Math.max(x1, x0 + 2), y1], [x0, y1]]);
  }
  for (const o of form.lens || []) drawLens(ctx, o, at, n, outline);
  ctx.lineWidth = 1;
}
/** A lens on a map (see drawSolids). */
function drawLens(ctx, o, at, n, outline) {
  const norm = (v) => { const l = Math.hypot(...v); return l > 0 ? v.map((c) => c / l) : null; };
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const a = norm(o.axis), half = o.diameter / 2;
  if (!a) return;
  const sag = (r, rho) => (r === 0 ? 0 : r - Math.sign(r) * Math.sqrt(Math.max(0, r * r - rho * rho)));
  const face1 = (rho) => -o.thickness / 2 + sag(o.radius1, rho), face2 = (rho) => o.thickness / 2 + sag(o.radius2, rho);
  const point = (w, v) => o.center.map((c, i) => c + w * a[i] + v[i]);
  // Its profile: the section through its axis that the map sees broadside (none along the axis).
  const e = norm(cross(n, a));
  if (e) {
    const N = 24, rhos = [...Array(2 * N + 1).keys()].map((i) => -half + (i * half) / N);
    outline([...rhos.map((r) => at(point(face1(Math.abs(r)), e.map((c) => c * r)))), ...rhos.reverse().map((r) => at(point(face2(Math.abs(r)), e.map((c) => c * r))))]);
  }
  // Its rim's two circles, where the faces meet it.
  const u = norm(Math.abs(a[2]) < 0.9 ? cross(a, [0, 0, 1]) : cross(a, [1, 0, 0])), v = cross(a, u);
  for (const w of [face1(half), face2(half)]) {
    ctx.beginPath();
    for (let i = 0; i <= 48; i++) {
      const t = (i * Math.PI) / 24, q = at(point(w, u.map((c, j) => half * (c * Math.cos(t) + v[j] * Math.sin(t)))));
      if (i) ctx.lineTo(...q); else ctx.moveTo(...q);
    }
    if (!e) ctx.fill();
    ctx.stroke();
  }
}

/** The objects' handles on a map: a small ring where a drag takes each (of radius `ring`, else 5 px;
 * the smallest drawn finer, so that a glass's many points do not hide it). */
function drawHandles(ctx, handles) {
  for (const h of handles) {
    ctx.lineWidth = h.ring < 3 ? 1 : 1.5;
    ctx.strokeStyle = "#1d2330"; ctx.fillStyle = "rgba(255,255,255,.7)";
    // (A handle moved a fingertip from another object's: a thin line from where it belongs.)
    if (h.home) {
      ctx.lineWidth = 1; ctx.setLineDash([3, 2]); ctx.beginPath(); ctx.moveTo(...h.home); ctx.lineTo(...h.at); ctx.stroke(); ctx.setLineDash([]);
      ctx.fillStyle = "#1d2330"; ctx.beginPath(); ctx.arc(h.home[0], h.home[1], 1.5, 0, 2 * Math.PI); ctx.fill();
      ctx.fillStyle = "rgba(255,255,255,.7)"; ctx.lineWidth = h.ring < 3 ? 1 : 1.5;
    }
    // (A lens's axis handle: a thin line from its centre.)
    if (h.from) { ctx.lineWidth = 1; ctx.beginPath(); ctx.moveTo(...h.from); ctx.lineTo(...h.at); ctx.stroke(); ctx.lineWidth = 1.5; }
    // (A prism's corner: a fine hollow ring, so that its outline shows through.)
    if (h.kind === "corner") ctx.lineWidth = 1;
    ctx.beginPath(); ctx.arc(h.at[0], h.at[1], h.ring || 5, 0, 2 * Math.PI);
    if (h.kind !== "corner") ctx.fill();
    ctx.stroke();
  }
  ctx.lineWidth = 1;
}

let dragging = null, eyeFarAtStart = false;
onDrag(topCanvas, {
  pinch: pinchEye,
  start: (e) => {
    const r = topCanvas.getBoundingClientRect(), x = e.clientX - r.left, y = e.clientY - r.top;
    const near = (p) => p && Math.hypot(p[0] - x, p[1] - y) < 14;
    const h = near(topCanvas.eyeAt) ? null : handleAt(topCanvas.handles, x, y, 14);
    dragging = h || (near(topCanvas.strawAt) && !near(topCanvas.eyeAt) ? "straw" : "eye");
    eyeFarAtStart = topCanvas.eyeFar;
    if (h) startGesture();
  },
  move: (dx, dy, e) => {
    const r = topCanvas.getBoundingClientRect();
    // (A handle drawn off its object, a fingertip from another's, moves it as if it were on it.)
    const shift = (dragging && dragging.shift) || [0, 0];
    const [x, y] = topCanvas.mapInverse(e.clientX - r.left - shift[0], e.clientY - r.top - shift[1]);
    if (dragging && dragging.kind) { dragHandle(dragging, [x, y]); return; }
    if (dragging === "straw") {
      // Kept inside the glass, so that a drag never stops at the rule's edge.
      const lim = GLASS_R - STRAW_R - 1e-4, d = Math.hypot(x, y), f = d > lim ? lim / d : 1;
      state.straw = [x * f, y * f].map((v) => Math.round(v * 1e5) / 1e5);
    } else if (eyeFarAtStart) {
      // An eye beyond the map turns round the axis towards the pointer, at its distance.
      const o = state.observer, d = Math.hypot(o[0], o[1]), a = Math.atan2(y, x);
      state.observer = outside([d * Math.cos(a), d * Math.sin(a), o[2]]);
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
    eyeFarAtStart = sideCanvas.eyeFar;
    if (draggingSide) startGesture();
  },
  move: (dx, dy, e) => {
    const r = sideCanvas.getBoundingClientRect();
    const shift = (draggingSide && draggingSide.shift) || [0, 0];
    const [s, z] = sideCanvas.mapInverse(e.clientX - r.left - shift[0], e.clientY - r.top - shift[1]);
    if (draggingSide) { dragHandle(draggingSide, [s, z], true); return; }
    const o = state.observer, az = Math.atan2(o[1], o[0]);
    let [d, zz] = [Math.max(0.001, s), z];
    if (eyeFarAtStart) {
      // An eye beyond the map turns up or down round the map's centre towards the pointer, at its distance.
      const [, zc] = sideCanvas.centre, r = Math.hypot(Math.hypot(o[0], o[1]), o[2] - zc), a = Math.atan2(z - zc, Math.max(1e-6, s));
      [d, zz] = [Math.max(0.001, r * Math.cos(a)), zc + r * Math.sin(a)];
    }
    state.observer = outside([d * Math.cos(az), d * Math.sin(az), zz]);
    changed();
  },
});

