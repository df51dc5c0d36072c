// The eye's picture panel: the frame's picture with the clicked ray over it, and the eye's moves
// (a drag orbits the glass, a wheel or a pinch goes nearer or farther, a click asks for a ray).
import { state, GLASS_R, GLASS_H } from "./state.js";
import { sub, dot, orbitOf, fromOrbit } from "./geometry.js";
import { pictureCanvas, sideCanvas, topCanvas } from "./dom.js";
import { drawPath } from "./draw.js";
import { drawLightPath } from "./lightpath.js";
import { drawOutline } from "./outline.js";
import { onDrag } from "./pointer.js";
import { frame, path, changed, pick } from "./frames.js";
import { sceneLines } from "./sketch.js";

/** How many points of the objects' real outline the picture shows (0 when it is off). */
export let outlinePoints = 0;
document.addEventListener("bentstraw-outline", () => drawPicture());

/** Where the clicked ray's drawing is on the picture (arrows, event boxes), null without one. */
export let pathMarks = null;

/** The frame's picture, and over it the clicked ray when it is this eye's. */
export function drawPicture() {
  if (!frame) return;
  const { width, height } = frame.header;
  pictureCanvas.width = width; pictureCanvas.height = height;
  const ctx = pictureCanvas.getContext("2d");
  ctx.putImageData(new ImageData(frame.rgba, width, height), 0, 0);
  // Lines and marks drawn over it keep their size on screen: the frame's pixels per CSS pixel.
  const scaleUp = width / Math.max(1, pictureCanvas.getBoundingClientRect().width);
  const c = frame.header.camera, pr = c ? pictureProjection() : null;
  outlinePoints = pr ? drawOutline(ctx, pr, scaleUp) : 0;
  // The clicked ray where the eye sees it: its first stretch is the eye's line of sight (a point
  // here), the rest bends inside the liquid. Only over the picture of the same eye.
  if (path && c && dot(sub(path.observer, c.eye), sub(path.observer, c.eye)) < 1e-18) {
    drawPath(ctx, pr, { labels: false, size: scaleUp });
    pathMarks = drawLightPath(ctx, pr, width, scaleUp);
  } else pathMarks = null;
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


/** Point `p` moved out of what the eye may not enter (the glass; a scene file's box), the
 * shortest way and 1 mm clear: a drag slides the eye round the glass instead of into it. */
export function outside(p) {
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
export function pinchEye(ratio) { orbitBy(0, 0, 1 / ratio); }
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

