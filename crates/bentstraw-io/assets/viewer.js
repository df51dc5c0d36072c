// bentstraw 3D viewer: the straw's image points, the water's wireframe, the straw's true outline and the
// observer, in an orthographic view with one scale on every axis (z stays upright).
// Data comes from the JSON script element "bentstraw-data": coordinates as little-endian float32
// offsets from `origin` (base64), colour codes 1..8 as bytes (base64).
"use strict";

// ---- pure helpers (also used by the tests under node) ----

/** Bytes of a base64 string. */
function base64Bytes(text) {
  const bin = atob(text);
  const out = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) out[i] = bin.charCodeAt(i);
  return out;
}

/** The points of the data: xyz offsets from data.origin (Float32Array) and colour codes (Uint8Array). */
function decodePoints(data) {
  const raw = base64Bytes(data.xyz);
  const bigEndian = new Uint8Array(new Uint16Array([1]).buffer)[0] === 0;
  if (bigEndian) {
    for (let i = 0; i < raw.length; i += 4) {
      let t = raw[i]; raw[i] = raw[i + 3]; raw[i + 3] = t;
      t = raw[i + 1]; raw[i + 1] = raw[i + 2]; raw[i + 2] = t;
    }
  }
  const xyz = new Float32Array(raw.buffer, raw.byteOffset, raw.length / 4);
  const color = base64Bytes(data.color);
  if (xyz.length !== 3 * data.n || color.length !== data.n) {
    throw new Error("corrupt point data: " + xyz.length / 3 + " coordinates, " + color.length + " colours, " + data.n + " points announced");
  }
  return { xyz, color };
}

/** Screen axes of a view from azimuth `az` and elevation `el` (degrees): right, up, towards the viewer. */
function viewAxes(az, el) {
  const a = az * Math.PI / 180, e = el * Math.PI / 180;
  const ca = Math.cos(a), sa = Math.sin(a), ce = Math.cos(e), se = Math.sin(e);
  return {
    right: [-sa, ca, 0],
    up: [-se * ca, -se * sa, ce],
    toward: [ce * ca, ce * sa, se],
  };
}

/** A step of 1, 2 or 5 times a power of ten giving about `count` ticks over `span`. */
function tickStep(span, count) {
  const raw = Math.max(span / count, 1e-12);
  const p = Math.pow(10, Math.floor(Math.log10(raw)));
  const m = raw / p;
  return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p;
}

function tickLabel(v, step) {
  const d = Math.max(0, -Math.floor(Math.log10(step)));
  const s = v.toFixed(d);
  return /^-0(\.0*)?$/.test(s) ? s.slice(1) : s;
}

if (typeof module !== "undefined") {
  module.exports = { base64Bytes, decodePoints, viewAxes, tickStep, tickLabel };
}

// ---- the viewer ----

if (typeof document !== "undefined") {
  window.addEventListener("DOMContentLoaded", () => {
    const data = JSON.parse(document.getElementById("bentstraw-data").textContent);
    startViewer(data);
  });
}

function startViewer(data) {
  const canvas = document.getElementById("view");
  const ctx = canvas.getContext("2d");
  const off = document.createElement("canvas");
  const offCtx = off.getContext("2d");
  const { xyz, color } = decodePoints(data);
  const n = data.n;
  const O = data.origin;
  const bmin = data.box.min, bmax = data.box.max;
  // Half the box's diagonal: the view keeps its size whatever the rotation.
  const radius = 0.5 * Math.hypot(bmax[0] - bmin[0], bmax[1] - bmin[1], bmax[2] - bmin[2]);

  const state = { az: 0, el: 0, zoom: 1, panX: 0, panY: 0 };
  // Colour codes 1..5 a straw's sections; in a scene file's world 6 a coin, 7 a card, 8 its arrow.
  const show = { water: true, straw: true, axes: true, sections: new Array(9).fill(true) };
  let width = 0, height = 0, dpr = 1;
  let image = null, pixels = null, depth = null;
  let interacting = false, idleTimer = 0, frameQueued = false, benchNote = "";

  // Colours per section, shaded by depth in 16 steps (far points a little darker) for a sense of depth.
  const SHADES = 16;
  const lut = new Uint32Array(9 * SHADES);
  for (const s of data.sections) {
    for (let k = 0; k < SHADES; k++) {
      const f = 0.72 + 0.28 * k / (SHADES - 1);
      const r = Math.round(s.rgb[0] * f), g = Math.round(s.rgb[1] * f), b = Math.round(s.rgb[2] * f);
      lut[s.code * SHADES + k] = (255 << 24 | b << 16 | g << 8 | r) >>> 0;
    }
  }

  function setView(v) {
    state.az = v.az; state.el = v.el; state.zoom = 1; state.panX = 0; state.panY = 0;
    redraw();
  }

  function resize() {
    dpr = window.devicePixelRatio || 1;
    width = Math.max(1, Math.round(canvas.clientWidth * dpr));
    height = Math.max(1, Math.round(canvas.clientHeight * dpr));
    canvas.width = width; canvas.height = height;
    off.width = width; off.height = height;
    image = offCtx.createImageData(width, height);
    pixels = new Uint32Array(image.data.buffer);
    depth = new Float32Array(width * height);
    redraw();
  }

  function redraw() {
    if (!frameQueued) {
      frameQueued = true;
      requestAnimationFrame(() => { frameQueued = false; draw(); });
    }
  }

  function interact() {
    interacting = true;
    clearTimeout(idleTimer);
    idleTimer = setTimeout(() => { interacting = false; redraw(); }, 150);
    redraw();
  }

  function camera() {
    const ax = viewAxes(state.az, state.el);
    const scale = state.zoom * Math.min(width - panelRoom(), height) / (2.15 * radius);
    const cx = (width + panelRoom()) / 2 + state.panX * dpr, cy = height / 2 + state.panY * dpr;
    // Pixel of an absolute point, and its nearness to the viewer (m).
    const px = (p) => {
      const x = p[0] - O[0], y = p[1] - O[1], z = p[2] - O[2];
      return [cx + scale * (x * ax.right[0] + y * ax.right[1]),
              cy - scale * (x * ax.up[0] + y * ax.up[1] + z * ax.up[2]),
              x * ax.toward[0] + y * ax.toward[1] + z * ax.toward[2]];
    };
    return { ax, scale, cx, cy, px };
  }

  // Device pixels on the left taken by the panel, when the window is wide enough to keep them free.
  function panelRoom() {
    const r = document.getElementById("panel").getBoundingClientRect();
    const room = (r.right + 10) * dpr;
    return width - room > 0.6 * width ? room : 0;
  }

  function draw() {
    const started = performance.now();
    const cam = camera();
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.fillStyle = "#fff";
    ctx.fillRect(0, 0, width, height);
    if (show.axes) drawPanes(cam);
    if (show.water) drawWater(cam, false);
    if (show.straw) drawStraw(cam);
    drawPoints(cam);
    if (show.water) drawWater(cam, true);
    if (show.axes) drawAxisLabels(cam);
    drawObserver(cam);
    document.getElementById("status").textContent =
      "azimuth " + Math.round(normAngle(state.az)) + "°, elevation " + Math.round(state.el) +
      "°, zoom ×" + state.zoom.toFixed(2) + (interacting && n > MAX_MOVING ? " (thinned while moving)" : "") +
      " · drawn in " + Math.round(performance.now() - started) + " ms" + benchNote;
  }

  function normAngle(a) {
    a = ((a % 360) + 360) % 360;
    return a > 180 ? a - 360 : a;
  }

  const MAX_MOVING = 150000;

  function drawPoints(cam) {
    const { ax, scale, cx, cy } = cam;
    pixels.fill(0);
    depth.fill(-Infinity);
    const rx = ax.right[0], ry = ax.right[1];
    const ux = ax.up[0], uy = ax.up[1], uz = ax.up[2];
    const tx = ax.toward[0], ty = ax.toward[1], tz = ax.toward[2];
    const stride = interacting && n > MAX_MOVING ? Math.ceil(n / MAX_MOVING) : 1;
    const size = Math.max(2, Math.min(8, Math.round((stride > 1 ? 3 : 2.2) * dpr * Math.sqrt(state.zoom))));
    const half = size / 2;
    const dInv = (SHADES - 1) / (2 * radius);
    const W = width, H = height, sec = show.sections;
    for (let i = 0; i < n; i += stride) {
      const c = color[i];
      if (!sec[c]) continue;
      const x = xyz[3 * i], y = xyz[3 * i + 1], z = xyz[3 * i + 2];
      const sx = Math.round(cx + scale * (x * rx + y * ry) - half);
      const sy = Math.round(cy - scale * (x * ux + y * uy + z * uz) - half);
      if (sx >= W || sy >= H || sx + size <= 0 || sy + size <= 0) continue;
      const d = x * tx + y * ty + z * tz;
      let k = Math.round((d + radius) * dInv);
      k = k < 0 ? 0 : k >= SHADES ? SHADES - 1 : k;
      const rgba = lut[c * SHADES + k];
      const x0 = sx < 0 ? 0 : sx, x1 = sx + size > W ? W : sx + size;
      const y0 = sy < 0 ? 0 : sy, y1 = sy + size > H ? H : sy + size;
      for (let py = y0; py < y1; py++) {
        let o = py * W + x0;
        for (let px = x0; px < x1; px++, o++) {
          if (d > depth[o]) { depth[o] = d; pixels[o] = rgba; }
        }
      }
    }
    offCtx.putImageData(image, 0, 0);
    ctx.drawImage(off, 0, 0);
  }

  function line(a, b) {
    ctx.moveTo(a[0], a[1]);
    ctx.lineTo(b[0], b[1]);
  }

  function axisStep(a) { return tickStep(bmax[a] - bmin[a], 5); }

  function ticks(lo, hi, step) {
    const out = [];
    for (let k = Math.ceil(lo / step); k <= Math.floor(hi / step); k++) out.push(k * step);
    return out;
  }

  // The three far faces of the box, shaded, with grid lines at the ticks.
  function drawPanes(cam) {
    const t = cam.ax.toward;
    ctx.lineWidth = dpr;
    for (let a = 0; a < 3; a++) {
      if (Math.abs(t[a]) < 1e-6) continue;
      const at = t[a] > 0 ? bmin[a] : bmax[a];
      const b = (a + 1) % 3, c = (a + 2) % 3;
      const corner = (vb, vc) => { const p = [0, 0, 0]; p[a] = at; p[b] = vb; p[c] = vc; return cam.px(p); };
      const q = [corner(bmin[b], bmin[c]), corner(bmax[b], bmin[c]), corner(bmax[b], bmax[c]), corner(bmin[b], bmax[c])];
      ctx.beginPath();
      ctx.moveTo(q[0][0], q[0][1]);
      for (let i = 1; i < 4; i++) ctx.lineTo(q[i][0], q[i][1]);
      ctx.closePath();
      ctx.fillStyle = "#f4f4f6";
      ctx.fill();
      ctx.strokeStyle = "#aaaab2";
      ctx.stroke();
      if (Math.abs(t[a]) >= 0.3) {
        ctx.beginPath();
        for (const v of ticks(bmin[b], bmax[b], axisStep(b))) line(corner(v, bmin[c]), corner(v, bmax[c]));
        for (const v of ticks(bmin[c], bmax[c], axisStep(c))) line(corner(bmin[b], v), corner(bmax[b], v));
        ctx.strokeStyle = "#dadae0";
        ctx.stroke();
      }
    }
  }

  // The water's top and bottom circles and vertical lines, on the far or near side of the glass's axis;
  // or a scene file's wireframe (data.wire: segments), on the far or near side of its centre.
  function drawWater(cam, front) {
    if (data.wire) {
      const centreDepth = cam.px(data.sceneCentre)[2];
      ctx.beginPath();
      for (const [a, b] of data.wire) {
        const pa = cam.px(a), pb = cam.px(b);
        if ((0.5 * (pa[2] + pb[2]) > centreDepth) === front) line(pa, pb);
      }
      ctx.strokeStyle = front ? "rgba(40,120,200,0.75)" : "rgba(40,120,200,0.45)";
      ctx.lineWidth = dpr;
      ctx.stroke();
      return;
    }
    const he = data.water.height, R = data.water.radius;
    const axisDepth = cam.px([0, 0, he / 2])[2];
    ctx.beginPath();
    const seg = (a, b) => {
      const pa = cam.px(a), pb = cam.px(b);
      if ((0.5 * (pa[2] + pb[2]) > axisDepth) === front) line(pa, pb);
    };
    const N = 72;
    for (const z of he > 0 ? [0, he] : [0]) {
      for (let k = 0; k < N; k++) {
        const t0 = 2 * Math.PI * k / N, t1 = 2 * Math.PI * (k + 1) / N;
        seg([R * Math.cos(t0), R * Math.sin(t0), z], [R * Math.cos(t1), R * Math.sin(t1), z]);
      }
    }
    if (he > 0) {
      for (let k = 0; k < data.water.verticals; k++) {
        const t = 2 * Math.PI * k / data.water.verticals;
        seg([R * Math.cos(t), R * Math.sin(t), 0], [R * Math.cos(t), R * Math.sin(t), he]);
      }
    }
    ctx.strokeStyle = front ? "rgba(40,120,200,0.75)" : "rgba(40,120,200,0.45)";
    ctx.lineWidth = dpr;
    ctx.stroke();
  }

  // The straw's true outline, dashed: section boundaries and its two silhouette lines; or a scene
  // file's objects' outlines (data.outlines: polylines).
  function drawStraw(cam) {
    ctx.beginPath();
    if (data.outlines) {
      for (const poly of data.outlines) {
        for (let k = 1; k < poly.length; k++) line(cam.px(poly[k - 1]), cam.px(poly[k]));
      }
    } else {
      drawStrawOutline(cam);
    }
    ctx.setLineDash([5 * dpr, 4 * dpr]);
    ctx.strokeStyle = "#787878";
    ctx.lineWidth = dpr;
    ctx.stroke();
    ctx.setLineDash([]);
  }

  function drawStrawOutline(cam) {
    const s = data.straw;
    const N = 48;
    for (let j = 0; j <= 5; j++) {
      const z = j * s.sectionHeight;
      for (let k = 0; k < N; k++) {
        const t0 = 2 * Math.PI * k / N, t1 = 2 * Math.PI * (k + 1) / N;
        line(cam.px([s.x + s.radius * Math.cos(t0), s.y + s.radius * Math.sin(t0), z]),
             cam.px([s.x + s.radius * Math.cos(t1), s.y + s.radius * Math.sin(t1), z]));
      }
    }
    const r = cam.ax.right;
    for (const sign of [-1, 1]) {
      const x = s.x + sign * s.radius * r[0], y = s.y + sign * s.radius * r[1];
      line(cam.px([x, y, 0]), cam.px([x, y, s.height]));
    }
  }

  // Tick labels and names along three outer edges of the box (the same rule as the PNG figure).
  function drawAxisLabels(cam) {
    const { ax } = cam;
    const names = ["x (m)", "y (m)", "z (m)"];
    const centre = cam.px(O);
    ctx.lineWidth = dpr;
    for (let a = 0; a < 3; a++) {
      const ex = ax.right[a], ey = -ax.up[a];
      const onScreen = Math.hypot(ex, ey);
      if (onScreen < 0.3) continue;
      const across = Math.abs(ex) >= Math.abs(ey);
      const b = (a + 1) % 3, c = (a + 2) % 3;
      let best = null, bestScore = -Infinity;
      for (const [vb, vc] of [[bmin[b], bmin[c]], [bmax[b], bmin[c]], [bmin[b], bmax[c]], [bmax[b], bmax[c]]]) {
        const base = [0, 0, 0]; base[b] = vb; base[c] = vc; base[a] = 0.5 * (bmin[a] + bmax[a]);
        const p = cam.px(base);
        const out = across ? p[1] : a === 2 ? -p[0] : p[0];
        const score = out - 1e-3 * p[2] * cam.scale;
        if (score > bestScore + 1e-6) { bestScore = score; best = base; }
      }
      const mid = cam.px(best);
      let nx = -ey, ny = ex;
      const len = Math.hypot(nx, ny);
      nx /= len; ny /= len;
      if (nx * (mid[0] - centre[0]) + ny * (mid[1] - centre[1]) < 0) { nx = -nx; ny = -ny; }
      const lo = best.slice(), hi = best.slice();
      lo[a] = bmin[a]; hi[a] = bmax[a];
      ctx.beginPath();
      line(cam.px(lo), cam.px(hi));
      ctx.strokeStyle = "#78787f";
      ctx.stroke();
      const step = axisStep(a);
      const gap = step * cam.scale * onScreen;
      const every = Math.max(1, Math.ceil((across ? 44 : 17) * dpr / Math.max(gap, 1e-9)));
      ctx.font = (12 * dpr) + "px sans-serif";
      ctx.textAlign = "center";
      ctx.textBaseline = "middle";
      ctx.fillStyle = "#5a5a60";
      let widest = 0;
      const reach = (text, size) => Math.abs(nx) * ctx.measureText(text).width / 2 + Math.abs(ny) * size / 2;
      ctx.beginPath();
      for (const v of ticks(bmin[a], bmax[a], step)) {
        const p = best.slice(); p[a] = v;
        const q = cam.px(p);
        line(q, [q[0] + 5 * dpr * nx, q[1] + 5 * dpr * ny]);
        if (((Math.round(v / step) % every) + every) % every !== 0) continue;
        const text = tickLabel(v, step);
        const r = reach(text, 12 * dpr);
        widest = Math.max(widest, 2 * r);
        const d = 8 * dpr + r;
        ctx.fillText(text, q[0] + d * nx, q[1] + d * ny);
      }
      ctx.stroke();
      ctx.font = (14 * dpr) + "px sans-serif";
      ctx.fillStyle = "#1a1a1a";
      const d = 16 * dpr + widest + reach(names[a], 14 * dpr);
      ctx.fillText(names[a], mid[0] + d * nx, mid[1] + d * ny);
    }
  }

  function drawObserver(cam) {
    ctx.font = (13 * dpr) + "px sans-serif";
    ctx.textBaseline = "middle";
    if (data.observerInside) {
      const p = cam.px(data.observer);
      ctx.beginPath();
      ctx.arc(p[0], p[1], 5 * dpr, 0, 2 * Math.PI);
      // Seen from its own direction the marker sits on the image: a ring hides less.
      const d = [0, 1, 2].map((a) => data.observer[a] - data.sceneCentre[a]);
      const t = cam.ax.toward;
      if (d[0] * t[0] + d[1] * t[1] + d[2] * t[2] > 0.999 * Math.hypot(d[0], d[1], d[2])) {
        ctx.strokeStyle = "#000";
        ctx.lineWidth = 2 * dpr;
        ctx.stroke();
      } else {
        ctx.fillStyle = "#000";
        ctx.fill();
      }
      const w = ctx.measureText("observer").width;
      ctx.fillStyle = "rgba(255,255,255,0.75)";
      ctx.fillRect(p[0] + 7 * dpr, p[1] - 9 * dpr, w + 4 * dpr, 18 * dpr);
      ctx.fillStyle = "#000";
      ctx.textAlign = "left";
      ctx.fillText("observer", p[0] + 9 * dpr, p[1]);
      return;
    }
    // Far observer: an arrow in the room left for it in the box, pointing at it.
    const s = cam.px(data.arrow[0]), t = cam.px(data.arrow[1]);
    const dx = t[0] - s[0], dy = t[1] - s[1], len = Math.hypot(dx, dy);
    if (len < 18 * dpr) return;
    const ux = dx / len, uy = dy / len;
    ctx.beginPath();
    line(s, t);
    ctx.strokeStyle = "#000";
    ctx.lineWidth = 2 * dpr;
    ctx.stroke();
    ctx.beginPath();
    ctx.moveTo(t[0], t[1]);
    ctx.lineTo(t[0] - 11 * dpr * ux - 5 * dpr * uy, t[1] - 11 * dpr * uy + 5 * dpr * ux);
    ctx.lineTo(t[0] - 11 * dpr * ux + 5 * dpr * uy, t[1] - 11 * dpr * uy - 5 * dpr * ux);
    ctx.closePath();
    ctx.fillStyle = "#000";
    ctx.fill();
    ctx.textAlign = "center";
    ctx.fillText("observer (far)", 0.5 * (s[0] + t[0]) + 12 * dpr * Math.abs(uy), 0.5 * (s[1] + t[1]) - 12 * dpr * Math.abs(ux));
  }

  // ---- controls ----

  const pointers = new Map();
  let last = null;

  canvas.addEventListener("pointerdown", (e) => {
    canvas.setPointerCapture(e.pointerId);
    pointers.set(e.pointerId, [e.clientX, e.clientY]);
    last = gesture();
    canvas.classList.add("dragging");
  });
  const release = (e) => {
    pointers.delete(e.pointerId);
    last = pointers.size ? gesture() : null;
    if (!pointers.size) canvas.classList.remove("dragging");
  };
  canvas.addEventListener("pointerup", release);
  canvas.addEventListener("pointercancel", release);
  canvas.addEventListener("pointermove", (e) => {
    if (!pointers.has(e.pointerId)) return;
    pointers.set(e.pointerId, [e.clientX, e.clientY]);
    const g = gesture();
    if (last && g.count === last.count) {
      const dx = g.x - last.x, dy = g.y - last.y;
      if (g.count >= 2) {
        // Two fingers: pinch zooms about their middle, moving them pans.
        zoomAbout(g.spread / Math.max(last.spread, 1), g.x, g.y);
        state.panX += dx; state.panY += dy;
      } else if (e.shiftKey || e.ctrlKey || (e.buttons & 2) || (e.buttons & 4)) {
        state.panX += dx; state.panY += dy;
      } else {
        state.az -= dx * 0.5;
        state.el = Math.max(-90, Math.min(90, state.el + dy * 0.5));
      }
      interact();
    }
    last = g;
  });
  canvas.addEventListener("contextmenu", (e) => e.preventDefault());
  canvas.addEventListener("wheel", (e) => {
    e.preventDefault();
    const unit = e.deltaMode === 1 ? 33 : e.deltaMode === 2 ? 400 : 1;
    zoomAbout(Math.exp(-e.deltaY * unit * 0.0015), e.clientX, e.clientY);
    interact();
  }, { passive: false });
  canvas.addEventListener("dblclick", () => setView(data.views[0]));
  window.addEventListener("keydown", (e) => {
    if (e.target instanceof HTMLInputElement || e.ctrlKey || e.metaKey || e.altKey) return;
    const k = e.key;
    if (k === "ArrowLeft") state.az += 5;
    else if (k === "ArrowRight") state.az -= 5;
    else if (k === "ArrowUp") state.el = Math.min(90, state.el + 5);
    else if (k === "ArrowDown") state.el = Math.max(-90, state.el - 5);
    else if (k === "+" || k === "=") state.zoom = Math.min(60, state.zoom * 1.2);
    else if (k === "-" || k === "_") state.zoom = Math.max(0.2, state.zoom / 1.2);
    else if (k === "r" || k === "R") { setView(data.views[0]); return; }
    else return;
    e.preventDefault();
    interact();
  });

  function gesture() {
    const pts = [...pointers.values()];
    const x = pts.reduce((s, p) => s + p[0], 0) / pts.length;
    const y = pts.reduce((s, p) => s + p[1], 0) / pts.length;
    const spread = pts.length >= 2 ? Math.hypot(pts[0][0] - pts[1][0], pts[0][1] - pts[1][1]) : 0;
    return { count: pts.length, x, y, spread };
  }

  // Zoom by `factor` keeping the point under (clientX, clientY) in place.
  function zoomAbout(factor, clientX, clientY) {
    const z = Math.max(0.2, Math.min(60, state.zoom * factor));
    const f = z / state.zoom;
    const rect = canvas.getBoundingClientRect();
    const mx = clientX - rect.left - (rect.width + panelRoom() / dpr) / 2, my = clientY - rect.top - rect.height / 2;
    state.panX = mx - (mx - state.panX) * f;
    state.panY = my - (my - state.panY) * f;
    state.zoom = z;
  }

  // ---- panel ----

  const buttons = document.getElementById("buttons");
  for (const v of data.views) {
    const b = document.createElement("button");
    b.textContent = v.name;
    b.title = v.caption;
    b.addEventListener("click", () => setView(v));
    buttons.appendChild(b);
  }
  const reset = document.createElement("button");
  reset.textContent = "reset view";
  reset.title = "back to the opening view, zoom 1 (or double-click the picture)";
  reset.addEventListener("click", () => setView(data.views[0]));
  buttons.appendChild(reset);
  const save = document.createElement("button");
  save.textContent = "save PNG";
  save.title = "download the current view as a PNG picture";
  save.addEventListener("click", () => {
    draw();
    const a = document.createElement("a");
    a.download = (data.fileStem || "bentstraw-view") + ".png";
    a.href = canvas.toDataURL("image/png");
    a.click();
  });
  buttons.appendChild(save);

  for (const li of document.querySelectorAll("#legend li[data-code]")) {
    li.addEventListener("click", () => {
      const c = Number(li.dataset.code);
      show.sections[c] = !show.sections[c];
      li.classList.toggle("off", !show.sections[c]);
      redraw();
    });
  }
  for (const key of ["water", "straw", "axes"]) {
    const box = document.getElementById("show-" + key);
    box.addEventListener("change", () => { show[key] = box.checked; redraw(); });
  }

  window.addEventListener("resize", resize);
  state.az = data.views[0].az;
  state.el = data.views[0].el;
  // A view can be given in the address: #az=30&el=20&zoom=1.5 (degrees), or #view=2 for a preset.
  const asked = new URLSearchParams(location.hash.slice(1));
  const preset = data.views[Number(asked.get("view"))];
  if (preset) { state.az = preset.az; state.el = preset.el; }
  for (const key of ["az", "el", "zoom"]) {
    const v = Number(asked.get(key));
    if (asked.has(key) && Number.isFinite(v)) state[key] = v;
  }
  state.el = Math.max(-90, Math.min(90, state.el));
  state.zoom = Math.max(0.2, Math.min(60, state.zoom));
  resize();
  // The first frame at once, not at the next animation frame: the page is complete when it has loaded.
  draw();
  // #bench=N: draw N frames while turning, and report the mean time per frame (for checking speed).
  const frames = Number(asked.get("bench"));
  if (frames > 0) {
    const t0 = performance.now();
    for (let i = 0; i < frames; i++) { state.az += 1; draw(); }
    benchNote = " · bench: " + ((performance.now() - t0) / frames).toFixed(1) + " ms per frame";
    redraw();
  }
}
