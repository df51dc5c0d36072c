// The clicked ray's geometry drawn over the eye's picture, so that it can be read there: the
// light's way from the object to the eye (arrows along the bent path), where the object really
// is, and at each event a small drawing in its plane of incidence — the surface, its normal, the
// two rays and their angles with the normal, each with its value and its medium's index.
// Snell–Descartes' law is what the drawing shows: n₁ sin θ₁ = n₂ sin θ₂ (docs/physics.md).
import { t, localNumber } from "./i18n.js";
import { sub, add, scale, dot } from "./geometry.js";
import { path } from "./frames.js";

/** The colours of the drawing: the light's arrows, the normal, the two angles. */
const ARROW = "#f39c12", NORMAL = "#1f77b4", ANGLE_1 = "#c0392b", ANGLE_2 = "#1e8449";
/** The side of an event's drawing, in CSS pixels. */
const BOX = 150;

const norm = (v) => { const l = Math.hypot(...v); return l > 0 ? scale(v, 1 / l) : v; };

/** A filled arrowhead at `tip`, pointing along the unit 2D vector `[ux, uy]`, `len` long. */
function arrowhead(ctx, tip, [ux, uy], len, colour) {
  const [x, y] = tip, w = 0.55 * len;
  ctx.beginPath();
  ctx.moveTo(x, y);
  ctx.lineTo(x - len * ux - w * uy, y - len * uy + w * ux);
  ctx.lineTo(x - len * ux + w * uy, y - len * uy - w * ux);
  ctx.closePath();
  ctx.fillStyle = colour; ctx.fill();
  ctx.strokeStyle = "#111"; ctx.lineWidth = len / 8; ctx.stroke();
}

/** A label with a light background, its left end at `[x, y]` (text's middle height). */
function label(ctx, text, [x, y], colour, px) {
  ctx.font = `600 ${px}px system-ui, sans-serif`;
  const w = ctx.measureText(text).width;
  ctx.fillStyle = "rgba(255,255,255,0.85)"; ctx.fillRect(x - px * 0.15, y - px * 0.65, w + px * 0.3, px * 1.25);
  ctx.fillStyle = colour; ctx.textBaseline = "middle"; ctx.fillText(text, x, y); ctx.textBaseline = "alphabetic";
  return w;
}

/**
 * Over the picture, through its projection `pr` (a 3D point to the picture's pixels, null behind
 * the eye), the clicked ray's light path: arrows in the light's direction on each stretch that
 * shows (the eye's own line of sight is a point here), the object's real point, and each event's
 * drawing in a row along the top, tied to where the event is seen. `size` is the picture's pixels
 * per CSS pixel. Returns where it drew, for tests and scripts: the arrows' tips and the events'
 * boxes `[x, y, w, h]`, in the picture's pixels.
 */
export function drawLightPath(ctx, pr, width, size) {
  const marks = { arrows: [], boxes: [], texts: [], real: null };
  const pts = [path.observer, ...path.events.map((e) => e.point)];
  if (path.outcome === "straw") pts.push(path.straw_point);
  else if (path.leaves) pts.push(add(path.leaves.from, scale(path.leaves.direction, 0.15)));
  // The light runs from the object to the eye: against the order the ray was traced in.
  for (let i = pts.length - 1; i > 0; i--) {
    const a = pr.p(pts[i]), b = pr.p(pts[i - 1]);
    if (!a || !b) continue;
    const d = Math.hypot(b[0] - a[0], b[1] - a[1]);
    if (d < 30 * size) continue;
    const u = [(b[0] - a[0]) / d, (b[1] - a[1]) / d], tip = [(a[0] + b[0]) / 2 + 6 * size * u[0], (a[1] + b[1]) / 2 + 6 * size * u[1]];
    arrowhead(ctx, tip, u, 13 * size, ARROW);
    marks.arrows.push(tip);
  }
  if (path.outcome === "straw") {
    const at = pr.p(path.straw_point);
    if (at) {
      ctx.beginPath(); ctx.arc(at[0], at[1], 6 * size, 0, 2 * Math.PI);
      ctx.fillStyle = ARROW; ctx.fill(); ctx.strokeStyle = "#111"; ctx.lineWidth = 1.5 * size; ctx.stroke();
      label(ctx, t("mark.real"), [at[0] + 10 * size, at[1] + 10 * size], "#111", 12 * size);
      marks.real = at;
    }
  }
  // Each event's number beside its mark on the path, as in its drawing and the readout.
  path.events.forEach((e, i) => {
    const at = pr.p(e.point);
    if (at) label(ctx, String(i + 1), [at[0] - 16 * size, at[1] - 9 * size * (i % 2 ? -1 : 1)], "#111", 11 * size);
  });
  const box = BOX * size, gap = 8 * size, perRow = Math.max(1, Math.floor((width - gap) / (box + gap)));
  path.events.slice(0, 2 * perRow).forEach((e, i) => {
    const x = gap + (i % perRow) * (box + gap), y = gap + Math.floor(i / perRow) * (box + gap);
    eventDrawing(ctx, e, i + 1, [x, y], box, size, pr, marks);
    marks.boxes.push([x, y, box, box]);
  });
  return marks;
}

/**
 * Event `k`'s drawing in the square at `[x, y]` of side `box`: its plane of incidence, the normal
 * upright, the side the eye is on above. The ray was traced from the eye; the light runs the other
 * way, so its arrows point towards the eye's side. A thin line ties the drawing to where the event
 * is in the picture.
 */
function eventDrawing(ctx, e, k, [x, y], box, size, pr, marks) {
  const n = e.normal, din = e.incoming, dout = e.outgoing;
  // The plane of incidence: the normal and the ray's part along the surface.
  let tang = sub(din, scale(n, dot(din, n)));
  if (Math.hypot(...tang) < 1e-9) tang = Math.abs(n[0]) < 0.9 ? sub([1, 0, 0], scale(n, n[0])) : sub([0, 1, 0], scale(n, n[1]));
  tang = norm(tang);
  // Left and right as in the picture, where the projection says which way the surface runs.
  const here = pr.p(e.point), along = pr.p(add(e.point, scale(tang, 1e-3)));
  const flip = here && along && along[0] < here[0] ? -1 : 1;
  const cx = x + box / 2, cy = y + box * 0.55, R = box * 0.4;
  const P = (v) => [cx + flip * R * dot(v, tang), cy - R * dot(v, n)];

  if (here) {
    ctx.setLineDash([4 * size, 3 * size]); ctx.strokeStyle = "rgba(20,20,20,0.7)"; ctx.lineWidth = 1.2 * size;
    ctx.beginPath(); ctx.moveTo(cx, y + box); ctx.lineTo(...here); ctx.stroke(); ctx.setLineDash([]);
  }
  ctx.fillStyle = "rgba(255,255,255,0.93)"; ctx.fillRect(x, y, box, box);
  // Each half tinted by its index, as the liquids on the maps: the denser, the deeper.
  const tint = (nIndex) => `rgba(74,127,193,${(0.05 + 0.3 * Math.min(1, Math.max(0, (nIndex - 1) / 0.6))).toFixed(3)})`;
  ctx.fillStyle = tint(e.n1); ctx.fillRect(x, y, box, cy - y);
  ctx.fillStyle = tint(e.n2); ctx.fillRect(x, cy, box, y + box - cy);
  ctx.strokeStyle = "#333"; ctx.lineWidth = size; ctx.strokeRect(x, y, box, box);
  ctx.strokeStyle = "#555"; ctx.lineWidth = 1.5 * size;
  ctx.beginPath(); ctx.moveTo(x, cy); ctx.lineTo(x + box, cy); ctx.stroke();
  ctx.setLineDash([5 * size, 3 * size]); ctx.strokeStyle = NORMAL; ctx.lineWidth = 1.3 * size;
  ctx.beginPath(); ctx.moveTo(cx, y + 4 * size); ctx.lineTo(cx, y + box - 4 * size); ctx.stroke(); ctx.setLineDash([]);

  // The eye's side: the light leaves along −incoming. The other ray: where the light came from.
  const eyeSide = scale(din, -1), reflected = e.event !== "refraction";
  ctx.lineWidth = 2.2 * size; ctx.strokeStyle = "#111";
  for (const v of [eyeSide, dout]) { ctx.beginPath(); ctx.moveTo(cx, cy); ctx.lineTo(...P(v)); ctx.stroke(); }
  // Arrows: into the point along the arriving ray, out of it along the leaving one.
  const arrive = P(dout), leave = P(eyeSide), c = [cx, cy];
  const unit = (a, b) => { const d = Math.hypot(b[0] - a[0], b[1] - a[1]) || 1; return [(b[0] - a[0]) / d, (b[1] - a[1]) / d]; };
  const mid = (a, b, f) => [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])];
  for (const [tip, u] of [[mid(arrive, c, 0.6), unit(arrive, c)], [mid(c, leave, 0.75), unit(c, leave)]]) {
    arrowhead(ctx, tip, u, 10 * size, ARROW);
    marks.arrows.push(tip);
  }

  // The angles with the normal: on the eye's side from the normal's upper half; the other ray's
  // from the lower half (refracted) or the upper half again (reflected).
  const arc = (v, up, deg, colour) => {
    const r = 0.36 * R, a0 = up ? -Math.PI / 2 : Math.PI / 2;
    const q = P(v), a1 = Math.atan2(q[1] - cy, q[0] - cx);
    let da = a1 - a0; while (da > Math.PI) da -= 2 * Math.PI; while (da < -Math.PI) da += 2 * Math.PI;
    ctx.strokeStyle = colour; ctx.lineWidth = 2 * size;
    ctx.beginPath(); ctx.arc(cx, cy, r, Math.min(a0, a0 + da), Math.max(a0, a0 + da)); ctx.stroke();
    // The value inside the angle, beyond its arc, on the line halving it.
    const am = a0 + da / 2, text = `${localNumber(deg.toFixed(1))}°`;
    ctx.font = `600 ${11 * size}px system-ui, sans-serif`;
    const w = ctx.measureText(text).width, d = r + 0.5 * w + 7 * size;
    label(ctx, text, [cx + d * Math.cos(am) - w / 2, cy + d * Math.sin(am)], colour, 11 * size);
    marks.texts.push(text);
  };
  arc(eyeSide, true, e.incidence_deg, ANGLE_1);
  arc(dout, reflected, e.outgoing_deg, ANGLE_2);
  // Each medium's index in its half's right-hand corner.
  const right = (text) => { ctx.font = `600 ${11 * size}px system-ui, sans-serif`; return x + box - 5 * size - ctx.measureText(text).width; };
  const n1 = `n ${localNumber(e.n1)}`, n2 = `n ${localNumber(e.n2)}`;
  label(ctx, n1, [right(n1), y + 12 * size], "#333", 11 * size);
  label(ctx, n2, [right(n2), y + box - 10 * size], "#333", 11 * size);
  marks.texts.push(n1, n2);

  // The event's number, as in the readout.
  ctx.beginPath(); ctx.arc(x + 13 * size, y + 13 * size, 9 * size, 0, 2 * Math.PI);
  ctx.fillStyle = e.event === "refraction" ? "#1f77b4" : "#d62728"; ctx.fill();
  ctx.fillStyle = "#fff"; ctx.font = `700 ${11 * size}px system-ui, sans-serif`; ctx.textAlign = "center"; ctx.textBaseline = "middle";
  ctx.fillText(String(k), x + 13 * size, y + 13.5 * size);
  ctx.textAlign = "start"; ctx.textBaseline = "alphabetic";
}
