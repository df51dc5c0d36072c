// The Objects panel, the scene editor: a control for each key of the scene's file, buttons that
// add and remove objects, and the drags of objects on the maps. The controls edit the scene's
// form (its file's keys and values, as the engine reads them); the engine writes the form back
// as the file's text, which then goes the way a typed text goes: checked by the same rules, the
// view following it, refused key by key. One rule, one place.
import { t, localNumber, readNumber } from "./i18n.js";
import { state, STRAW_R, STRAW_H, COIN_R, sceneKey } from "./state.js";
import { $ } from "./dom.js";
import { profileAt, widest } from "./geometry.js";
import { engineFetch, answerText } from "./engine.js";
import { errorText, ruleWords } from "./errors.js";
import { changed } from "./frames.js";
import { drawMaps } from "./maps.js";
import { showSceneErrors, applySceneText, checkScene, useScene, cancelTyping, sceneText } from "./scenetext.js";

/** Each kind of object's keys as the file names them, with their unit ("" a pure number, "text",
 * "tint" a colour "#rrggbb" or nothing,
 * "m3" a point, "v3" a direction's three numbers, "xy" a list of pairs written "x, y; x, y; …",
 * a prism's corners or a profile's points r, z, or the words a value may be), and the key of
 * their words where the name's own are another's. */
const FORM_FIELDS = {
  glass: [["radius", "m"], ["height", "m"], ["wall", "m"], ["bottom", "m"], ["index", ""]],
  tank: [["half_x", "m"], ["half_y", "m"], ["height", "m"]],
  revolution: [["outer", "xy"], ["inner", "xy"], ["index", ""]],
  liquid: [["name", "text"], ["index", ""], ["top", "m"], ["tint", "tint"]],
  straw: [["x", "m"], ["y", "m"], ["tilt", "°"], ["azimuth", "°"], ["radius", "m"], ["length", "m"]],
  coin: [["x", "m"], ["y", "m"], ["radius", "m"], ["thickness", "m"]],
  card: [["center", "m3"], ["facing", "°"], ["width", "m"], ["height", "m"], ["picture", ["arrow", "none"]]],
  sphere: [["center", "m3"], ["radius", "m"], ["index", ""]],
  prism: [["corners", "xy"], ["bottom", "m", "field.prism-bottom"], ["top", "m", "field.prism-top"], ["index", ""]],
  lens: [["center", "m3"], ["axis", "v3"], ["radius1", "m"], ["radius2", "m"], ["thickness", "m", "field.lens-thickness"], ["diameter", "m"], ["index", ""]],
};
/** The tables of objects, in the panel's order (after the container). */
const TABLES = ["liquid", "straw", "coin", "card", "sphere", "prism", "lens"];
/** The step of a control by unit: a millimetre, a tenth of a degree, a thousandth of an index, a
 * hundredth of a direction. */
const STEP = { m: "0.001", "m3": "0.001", "v3": "0.01", "°": "0.1", "": "0.001" };
const objectsEl = $("objects"), objectsErrorsEl = $("objects-errors");
/** The form of the view's scene: { text, key, form } (the text it was read from, the scene's key). */
let formOf = null;
let formSignature = "";

/** The controls built again, in the page's new language. */
export function relabelObjects() { formSignature = ""; showObjects(); }

/** The form of the scene file `text` (the view's), read by the engine, then shown. */
export async function loadForm(text) {
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
export const viewForm = () => (formOf && formOf.key === sceneKey(state) ? formOf.form : null);

/** The inside of the form's container: a glass's inner radius, a tank's half widths, or a glass
 * of revolution's least inner radius over the heights `lo` to `hi` an object spans (all of them
 * if none are given); and its rim's and its floor's heights. */
function inside(form, lo = -Infinity, hi = Infinity) {
  const c = form.container || {};
  if (c.shape === "tank") return { tank: true, hx: c.half_x, hy: c.half_y, height: c.height, floor: 0 };
  if (c.shape === "revolution") return { tank: false, r: innerLeast(c.inner, lo, hi), height: c.outer[c.outer.length - 1][1], floor: c.inner[0][1] };
  return { tank: false, r: c.radius - (c.wall || 0), height: c.height, floor: c.bottom || 0 };
}
/** The least radius of the inner profile `inner` over the heights `lo` to `hi`, straight between
 * its points (see profileAt): free above the rim, none below the floor. */
function innerLeast(inner, lo, hi) {
  const floor = inner[0][1], rim = inner[inner.length - 1][1];
  if (lo > rim) return Infinity;
  if (hi < floor) return 0;
  const a = Math.max(lo, floor), b = Math.min(hi, rim);
  return Math.min(profileAt(inner, a), profileAt(inner, b), ...inner.filter(([, z]) => z > a && z < b).map(([r]) => r));
}
/** The container's radius seen from above: a glass's, or a glass of revolution's widest. */
const outerRadius = (k) => (k.shape === "revolution" ? widest(k.outer) : k.radius);
/** The radius of the upright cylinder about the axis that holds the container (a tank's through
 * its corners). */
const holdingRadius = (k) => (k.shape === "tank" ? Math.hypot(k.half_x, k.half_y) : outerRadius(k));
/** How far from the axis a ball of radius `r` centred at the height `z` may stand inside a glass
 * of revolution `k`: the least, over its horizontal circles at 33 heights across it, of the inner
 * profile's radius less the circle's (a marble in a bowl touches the wall above its lowest
 * point); free above the rim, -Infinity where it reaches below the floor. */
function ballRoom(k, z, r) {
  const floor = k.inner[0][1], rim = k.inner[k.inner.length - 1][1];
  let room = Infinity;
  for (let i = 0; i <= 32; i++) {
    const s = -1 + i / 16, h = z + s * r;
    if (h > rim) continue;
    // (A ball resting on the floor may reach a hair below it by rounding.)
    if (h < floor - 1e-5) return -Infinity;
    room = Math.min(room, profileAt(k.inner, Math.max(h, floor)) - r * Math.sqrt(Math.max(0, 1 - s * s)));
  }
  return room;
}
/** The inside of the form's container for a ball of radius `r` centred at the height `z`: in a
 * glass of revolution, the radius its centre may reach plus its own (so that it is held where
 * its distance from the axis plus `r` is within it). */
function ballInside(form, z, r) {
  const k = form.container || {};
  return k.shape === "revolution" ? { ...inside(form), r: ballRoom(k, z, r) + r } : inside(form);
}
/** A length rounded to 10 µm (no float noise in the file). */
const r5 = (v) => Math.round(v * 1e5) / 1e5;
/** `[x, y]` kept inside the container `c` (as inside() gives it), `margin` clear of its side (an
 * object's radius). */
function keepInside(form, [x, y], margin, c = inside(form)) {
  const clear = margin + 1e-4;
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
/** How far `(x, y)` lies outside the container's outer outline seen from above (0 on or within it). */
function outsideBy(form, x, y) {
  const k = form.container || {};
  if (k.shape === "tank") return Math.hypot(Math.max(0, Math.abs(x) - k.half_x), Math.max(0, Math.abs(y) - k.half_y));
  return Math.max(0, Math.hypot(x, y) - outerRadius(k));
}
/** `[x, y]` pushed out of the container's outer outline seen from above until `margin` clear
 * of it (a sphere beside the container slides round it). */
function keepOutside(form, [x, y], margin) {
  const k = form.container || {};
  if (k.shape !== "tank") {
    const d = Math.hypot(x, y), lim = outerRadius(k) + margin;
    if (d >= lim) return [r5(x), r5(y)];
    return d > 1e-9 ? [r5((x * lim) / d), r5((y * lim) / d)] : [r5(lim), 0];
  }
  const sx = x < 0 ? -1 : 1, sy = y < 0 ? -1 : 1, dx = Math.abs(x) - k.half_x, dy = Math.abs(y) - k.half_y;
  if (dx > 0 && dy > 0) {
    const d = Math.hypot(dx, dy);
    if (d < margin) { x = sx * (k.half_x + (dx * margin) / d); y = sy * (k.half_y + (dy * margin) / d); }
  } else if (dx <= 0 && dy <= 0) {
    // Within the outline: out through the nearest face.
    if (dx >= dy) x = sx * (k.half_x + margin); else y = sy * (k.half_y + margin);
  } else if (dx > 0) {
    if (dx < margin) x = sx * (k.half_x + margin);
  } else if (dy < margin) y = sy * (k.half_y + margin);
  return [r5(x), r5(y)];
}
/** How far out from the axis a new solid is sized by and looked for a place: a glass's inner
 * radius, a tank's narrower half width, a glass of revolution's widest inside (whether it fits
 * there is asked at its own heights). */
function reachOf(form) {
  const c = inside(form), k = form.container || {};
  return c.tank ? Math.min(c.hx, c.hy) : k.shape === "revolution" ? widest(k.inner) : c.r;
}
/** Whether a sphere of radius `r` centred at `[x, y, z]` lies within the walls' inner face,
 * `margin` clear of it across (seen from above for a glass or a tank, whose walls are upright). */
function sphereHeld(form, [x, y, z], r, margin = 0) {
  const c = ballInside(form, z, r), m = r + margin;
  return c.tank ? Math.abs(x) + m <= c.hx && Math.abs(y) + m <= c.hy : Math.hypot(x, y) + m <= c.r;
}
/** The lowest height of a sphere of radius `r` above `floor`: resting on it, to the rule's bit. */
function restingOn(floor, r) {
  let z = Math.ceil((floor + r) * 1e5) / 1e5;
  if (z - r < floor) z += 1e-5;
  return z;
}
/** Where a sphere of radius `r` at `(x, y)` comes to rest inside the container, `margin` clear of
 * its walls: on the floor, or in a glass of revolution as low as it fits (on a wall that
 * narrows, by steps of 0.1 mm); null where it fits nowhere below the rim. */
function restingIn(form, [x, y], r, margin) {
  const c = inside(form);
  let z = restingOn(c.floor, r);
  if ((form.container || {}).shape !== "revolution") return z;
  for (; z + r <= c.height; z = r5(z + 1e-4)) if (sphereHeld(form, [x, y, z], r, margin)) return z;
  return null;
}
/** Distance from `p` to the segment `a`–`b` (3D). */
function segmentDistance(p, a, b) {
  const d = [0, 1, 2].map((i) => b[i] - a[i]), w = [0, 1, 2].map((i) => p[i] - a[i]);
  const dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  const s = dd > 0 ? Math.max(0, Math.min(1, (w[0] * d[0] + w[1] * d[1] + w[2] * d[2]) / dd)) : 0;
  return Math.hypot(w[0] - s * d[0], w[1] - s * d[1], w[2] - s * d[2]);
}
/** A lens's axial coordinates of its two faces at `rho` from its axis (from its centre), as the
 * rules take them: each face's sag from its vertex. */
function lensFaces(o, rho) {
  const sag = (r) => (r === 0 ? 0 : r - Math.sign(r) * Math.sqrt(Math.max(0, r * r - rho * rho)));
  return [-o.thickness / 2 + sag(o.radius1), o.thickness / 2 + sag(o.radius2)];
}
/** The radius of the sphere about a lens's centre that holds it (the rules' measure of a lens). */
function lensReach(o) {
  const [f1, f2] = lensFaces(o, o.diameter / 2);
  return Math.hypot(o.diameter / 2, Math.max(o.thickness / 2, Math.abs(f1), Math.abs(f2)));
}
/** Distance in the plane from `p` to the segment `a`–`b`. */
function segmentDistance2(p, a, b) {
  const dx = b[0] - a[0], dy = b[1] - a[1], dd = dx * dx + dy * dy;
  const s = dd > 0 ? Math.max(0, Math.min(1, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / dd)) : 0;
  return Math.hypot(p[0] - a[0] - s * dx, p[1] - a[1] - s * dy);
}
/** Whether the convex polygon `poly` (either order round it) holds the point `p` (its edges too). */
function polygonHolds(poly, p) {
  let sign = 0;
  for (let i = 0; i < poly.length; i++) {
    const a = poly[i], b = poly[(i + 1) % poly.length];
    const c = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
    if (c !== 0) { if (sign && Math.sign(c) !== sign) return false; sign = Math.sign(c); }
  }
  return true;
}
/** Distance in the plane from `p` to the convex polygon `poly` (0 within it). */
function polygonDistance(poly, p) {
  if (polygonHolds(poly, p)) return 0;
  let d = Infinity;
  for (let i = 0; i < poly.length; i++) d = Math.min(d, segmentDistance2(p, poly[i], poly[(i + 1) % poly.length]));
  return d;
}
/** Whether the segments `a`–`b` and `c`–`d` cross. */
function segmentsCross(a, b, c, d) {
  const o = (p, q, r) => Math.sign((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]));
  return o(a, b, c) * o(a, b, d) < 0 && o(c, d, a) * o(c, d, b) < 0;
}
/** Distance in the plane between two convex polygons (0 where they meet). */
function polygonsGap(A, B) {
  for (let i = 0; i < A.length; i++) {
    for (let j = 0; j < B.length; j++) if (segmentsCross(A[i], A[(i + 1) % A.length], B[j], B[(j + 1) % B.length])) return 0;
  }
  return Math.min(...A.map((p) => polygonDistance(B, p)), ...B.map((p) => polygonDistance(A, p)));
}
/** The least of the convex function `f` on [0, 1] (a distance along a segment to a convex body). */
function leastOn(f) {
  let lo = 0, hi = 1;
  for (let i = 0; i < 60; i++) {
    const m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
    if (f(m1) <= f(m2)) hi = m2; else lo = m1;
  }
  return Math.min(f(0), f(1), f((lo + hi) / 2));
}
/** Distance from the point `p` (3D) to a prism's solid `{ poly, bottom, top }` (0 within it). */
function prismDistance(P, p) {
  return Math.hypot(polygonDistance(P.poly, p), Math.max(0, P.bottom - p[2], p[2] - P.top));
}
/** The transparent solids of the form as the rules measure them: a sphere or a lens as a ball
 * `{ kind, k, c, r }` (a lens as the sphere about its centre that holds it), a prism as its solid
 * `{ kind, k, poly, bottom, top }`. */
function solidsOf(form) {
  return [
    ...(form.sphere || []).map((o, k) => ({ kind: "sphere", k, c: o.center, r: o.radius })),
    ...(form.lens || []).map((o, k) => ({ kind: "lens", k, c: o.center, r: lensReach(o) })),
    ...(form.prism || []).map((o, k) => ({ kind: "prism", k, poly: o.corners, bottom: o.bottom, top: o.top })),
  ];
}
/** How far apart two solids are (at most 0 where they meet). */
function solidsGap(A, B) {
  if (A.poly && B.poly) {
    const up = Math.max(A.bottom - B.top, B.bottom - A.top), across = polygonsGap(A.poly, B.poly);
    return up > 0 && across > 0 ? Math.hypot(up, across) : Math.max(up, across);
  }
  if (A.poly || B.poly) { const [P, b] = A.poly ? [A, B] : [B, A]; return prismDistance(P, b.c) - b.r; }
  return Math.hypot(A.c[0] - B.c[0], A.c[1] - B.c[1], A.c[2] - B.c[2]) - A.r - B.r;
}
/** Whether the solid `S` (as `solidsOf` gives them) stands `gap` clear of the form's straws,
 * coins, cards, other solids (all but `S` itself, by its kind and number) and eye, as the rules
 * measure them. */
function solidClear(form, S, gap) {
  const floor = inside(form).floor, rad = (deg) => (deg * Math.PI) / 180;
  // Distance from a point to the solid, and from a segment (convex: its least along it).
  const from = (p) => (S.poly ? prismDistance(S, p) : Math.hypot(p[0] - S.c[0], p[1] - S.c[1], p[2] - S.c[2]) - S.r);
  for (const s of form.straw || []) {
    const t = rad(s.tilt || 0), a = rad(s.azimuth || 0), R = s.radius || STRAW_R, L = s.length || STRAW_H;
    const foot = [s.x, s.y, floor + R * Math.sin(t)];
    const top = [foot[0] + L * Math.sin(t) * Math.cos(a), foot[1] + L * Math.sin(t) * Math.sin(a), foot[2] + L * Math.cos(t)];
    const d = S.poly ? leastOn((u) => from([0, 1, 2].map((i) => foot[i] + u * (top[i] - foot[i])))) : segmentDistance(S.c, foot, top) - S.r;
    if (d < R + gap) return false;
  }
  for (const c of form.coin || []) {
    const cr = c.radius || COIN_R, ct = floor + (c.thickness || 0);
    if (S.poly) {
      const up = Math.max(0, S.bottom - ct, floor - S.top), across = Math.max(0, polygonDistance(S.poly, [c.x, c.y]) - cr);
      if (Math.hypot(across, up) < gap) return false;
    } else {
      const across = Math.max(0, Math.hypot(S.c[0] - c.x, S.c[1] - c.y) - cr);
      const up = Math.max(0, floor - S.c[2], S.c[2] - ct);
      if (Math.hypot(across, up) < S.r + gap) return false;
    }
  }
  for (const o of form.card || []) {
    const f = rad(o.facing || 0), h = o.width / 2, u = [-Math.sin(f), Math.cos(f)];
    const a = [o.center[0] - h * u[0], o.center[1] - h * u[1], 0], b = [o.center[0] + h * u[0], o.center[1] + h * u[1], 0];
    const lo = o.center[2] - o.height / 2, hi = o.center[2] + o.height / 2;
    if (S.poly) {
      const across = leastOn((v) => polygonDistance(S.poly, [a[0] + v * (b[0] - a[0]), a[1] + v * (b[1] - a[1])]));
      if (Math.hypot(across, Math.max(0, lo - S.top, S.bottom - hi)) < gap) return false;
    } else {
      const across = segmentDistance([S.c[0], S.c[1], 0], a, b);
      if (Math.hypot(across, Math.max(0, lo - S.c[2], S.c[2] - hi)) < S.r + gap) return false;
    }
  }
  if (solidsOf(form).some((T) => !(T.kind === S.kind && T.k === S.k) && solidsGap(S, T) < gap)) return false;
  return from(state.observer) > gap;
}
/** Whether a sphere of radius `r` at `p` stands `gap` clear of the form's objects and eye, as the
 * rules measure them (sphere `skip` itself left out). */
const sphereClear = (form, p, r, gap, skip) => solidClear(form, { kind: "sphere", k: skip, c: p, r }, gap);
/** A new sphere: a glass marble (radius 1 cm, index 1.5, smaller in a small container or
 * shallow water) resting on the floor (in a glass of revolution, as low as it fits), in the first
 * place on rings out from the middle 1 mm clear of every object; failing that, on the table
 * beside the container, away from the eye. */
function newSphere(form) {
  const c = inside(form), k0 = form.container || {}, reach = reachOf(form), mm = (v) => Math.floor(v * 1000) / 1000;
  let r = Math.max(0.001, Math.min(0.01, mm(0.3 * reach)));
  const water = (form.liquid || [])[0];
  if (water && water.top - c.floor < 2 * r + 0.002) r = Math.max(0.002, Math.min(r, mm((water.top - c.floor - 0.002) / 2)));
  const r4 = (v) => Math.round(v * 1e4) / 1e4;
  for (const f of [0, 0.25, 0.45, 0.65]) {
    for (let k = 0; k < (f ? 12 : 1); k++) {
      const a = (k * Math.PI) / 6, xy = [r4(f * reach * Math.cos(a)), r4(f * reach * Math.sin(a))], z = restingIn(form, xy, r, 1e-4);
      const p = [...xy, z];
      if (z !== null && sphereHeld(form, p, r, 1e-4) && sphereClear(form, p, r, 1e-3, -1)) return { center: p, radius: r, index: 1.5 };
    }
  }
  const out = holdingRadius(k0) + r + 0.01;
  const az = Math.atan2(state.observer[1], state.observer[0]);
  let p = null;
  for (let k = 0; k < 12; k++) {
    const a = az + Math.PI / 2 + (k * Math.PI) / 6;
    p = [r4(out * Math.cos(a)), r4(out * Math.sin(a)), restingOn(0, r)];
    if (sphereClear(form, p, r, 1e-3, -1)) break;
  }
  return { center: p, radius: r, index: 1.5 };
}
/** Whether the polygon `poly` seen from above lies within the walls' inner face (`margin` clear)
 * at the heights `lo` to `hi` (a prism's bottom and top). */
function polygonHeld(form, poly, margin, lo, hi) {
  const c = inside(form, lo, hi);
  return poly.every(([x, y]) => (c.tank ? Math.abs(x) + margin <= c.hx && Math.abs(y) + margin <= c.hy : Math.hypot(x, y) + margin <= c.r));
}
/** How far the polygon `poly` seen from above lies from the container's outer outline (at most 0
 * where it overlaps it). */
function polygonOutsideBy(form, poly) {
  const k = form.container || {};
  if (k.shape === "tank") return polygonsGap(poly, [[-k.half_x, -k.half_y], [k.half_x, -k.half_y], [k.half_x, k.half_y], [-k.half_x, k.half_y]]);
  return polygonDistance(poly, [0, 0]) - outerRadius(k);
}
/** The middle of a prism seen from above (its corners' mean): where its ring drags it. */
const polygonMiddle = (poly) => [0, 1].map((i) => poly.reduce((a, q) => a + q[i], 0) / poly.length);
/** The corners of a 60° prism of side `a` about `(x, y)`, one face towards the eye (rounded to
 * 10 µm). */
function triangle([x, y], a) {
  const az = Math.atan2(state.observer[1], state.observer[0]), R = a / Math.sqrt(3);
  return [0, 1, 2].map((i) => { const t = az + Math.PI + (2 * Math.PI * i) / 3; return [r5(x + R * Math.cos(t)), r5(y + R * Math.sin(t))]; });
}
/** A new prism: a 60° glass prism (2 cm a side and 3 cm high, smaller in a small container)
 * standing on the floor in the first place on rings out from the middle 1 mm clear of every
 * object; failing that, on the table beside the container, away from the eye. */
function newPrism(form) {
  const c = inside(form), reach = reachOf(form), mm = (v) => Math.floor(v * 1000) / 1000;
  const a = Math.max(0.002, Math.min(0.02, mm(0.6 * reach))), h = Math.max(0.002, Math.min(0.03, mm((c.height - c.floor) * 0.6)));
  for (const f of [0, 0.25, 0.45, 0.65]) {
    for (let k = 0; k < (f ? 12 : 1); k++) {
      const t = (k * Math.PI) / 6, poly = triangle([f * reach * Math.cos(t), f * reach * Math.sin(t)], a);
      const P = { kind: "prism", k: -1, poly, bottom: c.floor, top: r5(c.floor + h) };
      if (polygonHeld(form, poly, 1e-4, P.bottom, P.top) && solidClear(form, P, 1e-3)) return { corners: poly, bottom: P.bottom, top: P.top, index: 1.5 };
    }
  }
  const k0 = form.container || {}, out = holdingRadius(k0) + a + 0.01;
  const az = Math.atan2(state.observer[1], state.observer[0]);
  let poly = null;
  for (let k = 0; k < 12; k++) {
    const t = az + Math.PI / 2 + (k * Math.PI) / 6;
    poly = triangle([out * Math.cos(t), out * Math.sin(t)], a);
    if (solidClear(form, { kind: "prism", k: -1, poly, bottom: 0, top: h }, 1e-3)) break;
  }
  return { corners: poly, bottom: 0, top: h, index: 1.5 };
}
/** A new lens: a biconvex glass lens 3 cm across (radii 4 cm, 7 mm thick, index 1.5), its axis
 * level and towards the container, held between the eye and the container at half its height;
 * failing that, in the middle of the first liquid layer it fits in (or above them), else beside
 * the container, 1 mm clear of every object. */
function newLens(form) {
  const c = inside(form), k0 = form.container || {}, r4 = (v) => Math.round(v * 1e4) / 1e4;
  const az = Math.atan2(state.observer[1], state.observer[0]);
  const lens = { axis: [r4(-Math.cos(az)), r4(-Math.sin(az)), 0], radius1: 0.04, radius2: -0.04, thickness: 0.007, diameter: 0.03, index: 1.5 };
  const r = lensReach(lens), fits = (p) => solidClear(form, { kind: "lens", k: -1, c: p, r }, 1e-3);
  const out = holdingRadius(k0) + r + 0.005;
  const z = r4(Math.max(r + 0.001, c.height / 2));
  let p = [r4(out * Math.cos(az)), r4(out * Math.sin(az)), z];
  if (fits(p)) return { center: p, ...lens };
  const reach = reachOf(form), tops = (form.liquid || []).map((l) => l.top);
  for (const [lo, hi] of tops.map((t, i) => [i ? tops[i - 1] : c.floor, t]).concat([[tops.length ? tops[tops.length - 1] : c.floor, Infinity]])) {
    const zl = hi === Infinity ? lo + r + 0.002 : (lo + hi) / 2;
    if (zl - r < lo + 1e-4 || zl + r > hi - 1e-4) continue;
    for (const f of [0, 0.25, 0.45, 0.65]) {
      for (let k = 0; k < (f ? 12 : 1); k++) {
        const t = (k * Math.PI) / 6;
        p = [r4(f * reach * Math.cos(t)), r4(f * reach * Math.sin(t)), r4(zl)];
        if (sphereHeld(form, p, r, 1e-4) && fits(p)) return { center: p, ...lens };
      }
    }
  }
  for (let k = 0; k < 12; k++) {
    const t = az + Math.PI / 2 + (k * Math.PI) / 6;
    p = [r4(out * Math.cos(t)), r4(out * Math.sin(t)), z];
    if (fits(p)) break;
  }
  return { center: p, ...lens };
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
  if (kind === "sphere") return newSphere(form);
  if (kind === "prism") return newPrism(form);
  if (kind === "lens") return newLens(form);
  // A card behind the container, facing the eye.
  const az = Math.atan2(state.observer[1], state.observer[0]);
  const k0 = form.container || {}, d = (c.tank ? Math.max(c.hx, c.hy) : k0.shape === "revolution" ? outerRadius(k0) : c.r) + 0.06;
  return { center: [r3(-d * Math.cos(az)), r3(-d * Math.sin(az)), r3(c.height / 2)], facing: r3(az * 180 / Math.PI), width: 0.08, height: 0.06, picture: "arrow" };
}
/** A container made another shape, its size kept: each goes through a glass (a tank's narrower
 * half width its radius; a glass of revolution's widest its radius, its rim's thickness its wall,
 * its floor its bottom). A glass of revolution made from a glass has its straight profiles, a
 * wall and a bottom at least 2 mm thick (the rules want a wall below the rim). */
function reshape(container, shape) {
  if (shape === container.shape) return container;
  const g = asGlass(container);
  if (shape === "glass") return g;
  if (shape === "tank") return { shape, half_x: g.radius, half_y: g.radius, height: g.height };
  const r = r5(g.radius - (g.wall > 0 ? g.wall : 0.002)), floor = Math.max(g.bottom, 0.002);
  return { shape, outer: [[g.radius, 0], [g.radius, g.height]], inner: [[r, floor], [r, g.height]], index: g.index };
}
/** The glass a container is nearest to (see reshape). */
function asGlass(c) {
  if (c.shape === "glass") return c;
  if (c.shape === "tank") return { shape: "glass", radius: Math.min(c.half_x, c.half_y), height: c.height, wall: 0, bottom: 0, index: 1.5 };
  const rim = c.outer[c.outer.length - 1], inner = c.inner[c.inner.length - 1];
  return { shape: "glass", radius: widest(c.outer), height: rim[1], wall: r5(Math.max(0, rim[0] - inner[0])), bottom: c.inner[0][1], index: c.index };
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
    if (unit === "text" || unit === "tint") { el.type = "text"; el.value = v ?? ""; }
    else if (unit === "xy") { el.type = "text"; el.value = cornersText(v); el.spellcheck = false; }
    else {
      // Text, read as the page's language writes numbers (a decimal comma in French); the arrow
      // keys step it as a number control would.
      el.type = "text"; el.inputMode = "decimal"; el.value = shownNumber(v); el.spellcheck = false;
      el.addEventListener("keydown", (e) => {
        if (e.key !== "ArrowUp" && e.key !== "ArrowDown") return;
        const x = readNumber(el.value);
        if (!Number.isFinite(x)) return;
        e.preventDefault();
        const step = Number(STEP[unit]);
        el.value = shownNumber(Math.round((x + (e.key === "ArrowUp" ? step : -step)) / step) * step);
        el.dispatchEvent(new Event("change", { bubbles: true }));
      });
      if (unit === "v3") el.style.width = "5em";
    }
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
  } else if (unit === "m3" || unit === "v3") {
    const row = document.createElement("span");
    (value || [0, 0, 0]).forEach((v, i) => row.append(input(i, v)));
    if (unit === "m3") { const u = document.createElement("span"); u.className = "unit"; u.textContent = " m"; row.append(u); }
    label.append(row);
  } else if (unit === "tint") {
    // The colour written as text (empty: a clear liquid), with a swatch that picks it.
    const row = document.createElement("span"), text = input(null, value);
    text.placeholder = "#rrggbb"; text.spellcheck = false; text.style.width = "6em";
    const swatch = document.createElement("input");
    swatch.type = "color"; swatch.className = "tint-swatch"; swatch.value = value || "#ffffff";
    swatch.setAttribute("aria-label", t("field.tint"));
    swatch.addEventListener("change", () => { text.value = swatch.value; text.dispatchEvent(new Event("change", { bubbles: true })); });
    row.append(text, swatch);
    label.append(row);
  } else {
    const row = document.createElement("span");
    row.append(input(null, value));
    if (unit && unit !== "text") { const u = document.createElement("span"); u.className = "unit"; u.textContent = " " + (unit === "xy" ? "m" : unit); row.append(u); }
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
export function showObjects() {
  const form = viewForm();
  if (!form) return;
  const c = form.container || {};
  const signature = [c.shape, ...TABLES.map((k) => (form[k] || []).length)].join(",");
  if (signature === formSignature) { fillObjects(form); return; }
  formSignature = signature;
  const boxes = [];
  const box = (legend, params, fields, table, k) => {
    const fs = document.createElement("fieldset");
    const lg = document.createElement("legend");
    lg.textContent = t(legend, params); // written again with the others when the language changes
    fs.append(lg);
    const prefix = table === "container" ? "container" : `${table}[${k + 1}]`;
    fs.dataset.object = prefix; // a rule about the whole object (`sphere[1]`) marks its box
    const values = table === "container" ? c : form[table][k];
    if (table === "container") {
      fs.append(field("container.shape", "obj.shape", ["glass", "tank", "revolution"], c.shape));
    }
    for (const [name, unit, words] of fields) fs.append(field(`${prefix}.${name}`, words || name, unit, values[name]));
    if (table !== "container") {
      fs.append(formButton("obj.remove", "obj.remove.title", "remove", () => editForm((f) => { f[table].splice(k, 1); })));
    }
    boxes.push(fs);
  };
  box("obj.container", null, FORM_FIELDS[c.shape] || FORM_FIELDS.glass, "container");
  for (const table of TABLES) {
    (form[table] || []).forEach((_, k) => box("obj." + table, { i: k + 1 }, FORM_FIELDS[table], table, k));
  }
  const add = document.createElement("div");
  add.className = "add";
  for (const table of TABLES) {
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
    const unit = el.dataset.unit;
    el.value = part !== undefined ? shownNumber(v ? v[Number(part)] : "") : unit === "xy" ? cornersText(v) : unit === "text" || unit === "tint" || el.tagName === "SELECT" ? (v ?? "") : shownNumber(v);
    if (unit === "tint" && el.nextElementSibling) el.nextElementSibling.value = /^#[0-9a-f]{6}$/i.test(v ?? "") ? v.toLowerCase() : "#ffffff";
    el.removeAttribute("aria-invalid");
  }
}
/** A number as its control shows it, in the page's language (a decimal comma in French); text
 * as it is. */
function shownNumber(v) {
  if (typeof v !== "number") return v ?? "";
  // Rounded to a nanometre's digits: no float noise in the fields.
  return localNumber(String(Math.round(v * 1e9) / 1e9));
}
/** A prism's corners (or a profile's points r, z) as its control writes them: "x, y; x, y; …"
 * (metres). */
function cornersText(corners) {
  return Array.isArray(corners) ? corners.map((q) => q.join(", ")).join("; ") : "";
}
/** The pairs a control's text "x, y; x, y; …" gives, or null if it is not such a list. */
function cornersOf(text) {
  const corners = text.split(";").filter((p) => p.trim()).map((p) => p.split(",").map((v) => (v.trim() ? Number(v) : NaN)));
  return corners.length && corners.every((q) => q.length === 2 && q.every(Number.isFinite)) ? corners : null;
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
  cancelTyping();
  sceneText.value = text;
  await applySceneText(text);
}
objectsEl.addEventListener("submit", (e) => e.preventDefault());
objectsEl.addEventListener("change", (e) => {
  const el = e.target, key = el.dataset.key;
  if (!key) return;
  let value;
  if (el.dataset.unit === "xy") {
    value = cornersOf(el.value);
    if (!value) {
      el.setAttribute("aria-invalid", "true");
      // (The container's pairs are its profiles' points, r and z; a prism's its corners.)
      showSceneErrors({ key: key.startsWith("container.") ? "obj.not-profile" : "obj.not-corners", params: { key } });
      return;
    }
  } else if (el.tagName === "SELECT" || el.dataset.unit === "text") value = el.value;
  // (An empty tint is none: the key is left out of the file.)
  else if (el.dataset.unit === "tint") value = el.value.trim() || undefined;
  else {
    value = readNumber(el.value);
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
export function markObjects(error) {
  for (const el of objectsEl.querySelectorAll("[aria-invalid]")) el.removeAttribute("aria-invalid");
  for (const el of objectsEl.querySelectorAll(".field-rule")) el.remove();
  for (const el of objectsEl.querySelectorAll("[aria-describedby^='rule-']")) el.removeAttribute("aria-describedby");
  // A rule about one point of a list (`container.inner[2]`) marks the list's control.
  const control = (key) => (key || "").replace(/^(\w+(?:\[\d+\])?\.\w+)\[\d+\]$/, "$1");
  const rules = error && error.refusal ? error.refusal.rules : [];
  const keys = (rules.length ? rules.map((r) => r.key) : error && error.params && error.params.key ? [error.params.key] : []).map(control);
  for (const key of keys) {
    for (const el of objectsEl.querySelectorAll(`[data-key="${CSS.escape(key)}"], [data-object="${CSS.escape(key)}"]`)) el.setAttribute("aria-invalid", "true");
  }
  // Under each control a rule names, the rule's own words: what the value must be (its range).
  rules.forEach((r, i) => {
    const el = keys[i] && objectsEl.querySelector(`[data-key="${CSS.escape(keys[i])}"]`);
    const label = el && el.closest("label");
    if (!label || label.querySelector(".field-rule")) return;
    const note = document.createElement("small");
    note.className = "field-rule"; note.id = "rule-" + keys[i].replace(/[^\w]/g, "-");
    note.textContent = ruleWords(r);
    label.appendChild(note);
    el.setAttribute("aria-describedby", note.id);
  });
  const text = errorText(error);
  objectsErrorsEl.replaceChildren(...text.split("\n").filter((l) => l.trim()).map((l) => { const li = document.createElement("li"); li.textContent = l; return li; }));
  objectsErrorsEl.hidden = !text;
}

// Drags on the maps: a straw, a coin, a card or a solid (a sphere, a prism, a lens) from above, a
// liquid's surface, a solid's height or a glass of revolution's profile points from the side.
// Each step is the form changed and sent as a text; a step the rules refuse is left out, so the
// object stops where it may still be (no banner: the banner is for typed values). The body's
// data-drag is "1" while steps are being sent (tests wait on it), data-drag-steps and
// data-drag-refused count the steps taken and left out.
let dragSending = false, dragNext = null;
/** The object drag under way or last made (a token), and the latest text it made. */
export let dragGesture = null, dragText = null;
/** A drag of an object begins: its steps make one step of the history. */
export function startGesture() { dragGesture = {}; }
async function dragForm(change) {
  const form = viewForm();
  if (!form) return;
  const f = structuredClone(form);
  change(f);
  dragNext = f;
  if (dragSending) return;
  dragSending = true;
  const body = document.body.dataset, count = (k) => { body[k] = String(Number(body[k] || 0) + 1); };
  body.drag = "1";
  while (dragNext) {
    const next = dragNext;
    dragNext = null;
    // A step that moves nothing (an object held at a wall) asks for nothing.
    if (JSON.stringify(next) === JSON.stringify(viewForm())) continue;
    try {
      const text = await formText(next);
      const observer = await checkScene(text, "hook");
      await useScene(text, observer);
      formOf = { text, key: sceneKey(state), form: next };
      dragText = text;
      showObjects();
      cancelTyping();
      sceneText.value = text;
      showSceneErrors(null);
      changed();
      count("dragSteps");
    } catch (_) { count("dragRefused"); /* refused: the object stays at its last allowed place */ }
  }
  dragSending = false;
  body.drag = "0";
}
/** A sphere's handle: at its centre's pixel `at`, its ring within the sphere's disc of `px`
 * pixels where that is small, so that the disc shows round it. */
const sphereHandle = (k, at, px, kind = "sphere") => ({ kind, k, at, ring: px >= 10 ? 5 : Math.max(2.5, px / 2) });
/** The objects a drag can take on a map: `{ kind, k, at }` (their pixels). From above `P(x, y)`
 * is the map's pixel; from the side `P(s, z)`, with `side` `{ u, half }`: the horizontal unit
 * vector `s` runs along and the container's half width along it. */
export function handlesOf(form, P, side) {
  const hs = [];
  if (side) {
    // A glass of revolution's points, a small ring each (smaller where its neighbours are a few
    // pixels away): the outer profile's left of the axis, the inner's right of it, so that a
    // wall's two points a pixel or two apart are not one over the other.
    const c = form.container || {};
    if (c.shape === "revolution") {
      for (const [which, sign] of [["outer", -1], ["inner", 1]]) {
        const at = c[which].map(([r, z]) => P(sign * r, z)), gap = (i, j) => (at[j] ? Math.hypot(at[i][0] - at[j][0], at[i][1] - at[j][1]) : Infinity);
        at.forEach((p, k) => hs.push({ kind: "profile", which, k, at: p, ring: Math.max(1.5, Math.min(2.5, gap(k, k - 1) / 2, gap(k, k + 1) / 2)) }));
      }
    }
    // A surface's ring beside the container's side, off the layer's tint; a sphere's and a
    // lens's at its centre, a prism's at its middle.
    (form.liquid || []).forEach((l, k) => { const [x, y] = P(side.half, l.top); hs.push({ kind: "liquid", k, at: [x + 8, y] }); });
    const along = (q) => q[0] * side.u[0] + q[1] * side.u[1];
    (form.sphere || []).forEach((o, k) => {
      const s = along(o.center), at = P(s, o.center[2]);
      hs.push(sphereHandle(k, at, Math.abs(P(s + o.radius, o.center[2])[0] - at[0])));
    });
    (form.prism || []).forEach((o, k) => {
      const ss = o.corners.map(along), at = P(along(polygonMiddle(o.corners)), (o.bottom + o.top) / 2);
      hs.push(sphereHandle(k, at, Math.abs(P(Math.max(...ss), 0)[0] - P(Math.min(...ss), 0)[0]) / 2, "prism"));
    });
    (form.lens || []).forEach((o, k) => {
      const s = along(o.center), at = P(s, o.center[2]);
      hs.push(sphereHandle(k, at, Math.abs(P(s + o.diameter / 2, o.center[2])[0] - at[0]), "lens"));
    });
    return spreadHandles(hs);
  }
  for (const kind of ["straw", "coin"]) (form[kind] || []).forEach((o, k) => hs.push({ kind, k, at: P(o.x, o.y) }));
  // A straw's lean: a handle where its top end is seen from above (LEAN_PX beyond its foot along
  // its azimuth, so that an upright straw's two handles stay apart); a drag sets its tilt from
  // the handle's distance and its azimuth from its direction.
  const perMetre = Math.hypot(P(1e-3, 0)[0] - P(0, 0)[0], P(1e-3, 0)[1] - P(0, 0)[1]) / 1e-3;
  (form.straw || []).forEach((o, k) => {
    const a = ((o.azimuth || 0) * Math.PI) / 180, reach = LEAN_PX / perMetre + (o.length || STRAW_H) * Math.sin(((o.tilt || 0) * Math.PI) / 180);
    const foot = P(o.x, o.y);
    hs.push({ kind: "lean", k, from: foot, at: P(o.x + reach * Math.cos(a), o.y + reach * Math.sin(a)), ring: 4, dead: LEAN_PX / perMetre });
  });
  (form.card || []).forEach((o, k) => hs.push({ kind: "card", k, at: P(o.center[0], o.center[1]) }));
  (form.sphere || []).forEach((o, k) => {
    const at = P(o.center[0], o.center[1]);
    hs.push(sphereHandle(k, at, Math.abs(P(o.center[0] + o.radius, o.center[1])[0] - at[0])));
  });
  (form.prism || []).forEach((o, k) => {
    const m = polygonMiddle(o.corners), at = P(m[0], m[1]);
    const px = Math.min(...o.corners.map((q) => Math.hypot(...[0, 1].map((i) => P(q[0], q[1])[i] - at[i]))));
    hs.push(sphereHandle(k, at, px, "prism"));
    // Each corner's small ring: a drag moves that corner alone.
    o.corners.forEach((q, j) => hs.push({ kind: "corner", k, j, at: P(q[0], q[1]), ring: 3 }));
  });
  (form.lens || []).forEach((o, k) => {
    const at = P(o.center[0], o.center[1]);
    hs.push(sphereHandle(k, at, Math.abs(P(o.center[0] + o.diameter / 2, o.center[1])[0] - at[0]), "lens"));
    // Its axis's handle, AXIS_PX pixels from its centre along the axis's horizontal part (to the
    // right where the axis is upright): a drag turns that part towards the pointer.
    const [ax, ay] = o.axis || [0, 0, 1], flat = Math.hypot(ax, ay) < 1e-9;
    const e = P(o.center[0] + (flat ? 1 : ax) * 1e-3, o.center[1] + (flat ? 0 : ay) * 1e-3), dx = e[0] - at[0], dy = e[1] - at[1], d = Math.hypot(dx, dy) || 1;
    hs.push({ kind: "axis", k, from: at, at: [at[0] + (AXIS_PX * dx) / d, at[1] + (AXIS_PX * dy) / d], ring: 3.5 });
  });
  return spreadHandles(hs);
}
/** Least distance between the handles of two objects on a map (pixels): a fingertip's width. */
const SPREAD_PX = 44;
/**
 * Objects' handles a fingertip apart: where two objects' handles come closer than SPREAD_PX
 * (two straws a few millimetres apart, a coin under a lens), each object's handles are moved
 * apart together, as a callout: `home` is where the handle belongs (drawn with a thin line to
 * it) and `shift` the pixels a drag takes off the pointer, so the object still follows the
 * finger. How far they move depends on where the objects stand alone, so that leaning a straw or
 * turning a lens's axis never moves the handles under the finger. A prism's corners and a
 * glass's profile points stay on the outline they shape.
 */
function spreadHandles(hs) {
  const owner = { lean: "straw", axis: "lens" }, groups = new Map();
  for (const h of hs) {
    if (h.kind === "corner" || h.kind === "profile") continue;
    const key = (owner[h.kind] || h.kind) + ":" + h.k;
    if (!groups.has(key)) groups.set(key, { anchor: null, members: [], d: [0, 0] });
    const g = groups.get(key);
    g.members.push(h);
    if (!owner[h.kind]) g.anchor = h;
  }
  const list = [...groups.values()].filter((g) => g.anchor), at = (g) => [g.anchor.at[0] + g.d[0], g.anchor.at[1] + g.d[1]];
  for (let pass = 0; pass < 16; pass++) {
    let moved = false;
    for (let a = 0; a < list.length; a++) for (let b = a + 1; b < list.length; b++) {
      const [pa, pb] = [at(list[a]), at(list[b])], d = Math.hypot(pb[0] - pa[0], pb[1] - pa[1]);
      // (Handles on one spot part along a direction of their own.)
      const near = { d, u: d > 1e-6 ? [(pb[0] - pa[0]) / d, (pb[1] - pa[1]) / d] : [Math.cos(a + 2 * b), Math.sin(a + 2 * b)] };
      // (Half a pixel to spare: handles exactly a fingertip apart stay so once drawn.)
      if (near.d >= SPREAD_PX + 0.5) continue;
      const push = (SPREAD_PX - near.d) / 2 + 0.25;
      list[a].d = [list[a].d[0] - push * near.u[0], list[a].d[1] - push * near.u[1]];
      list[b].d = [list[b].d[0] + push * near.u[0], list[b].d[1] + push * near.u[1]];
      moved = true;
    }
    if (!moved) break;
  }
  for (const g of list) {
    if (!g.d[0] && !g.d[1]) continue;
    for (const h of g.members) {
      h.home = h.from ? null : h.at; h.shift = g.d;
      h.at = [h.at[0] + g.d[0], h.at[1] + g.d[1]];
      if (h.from) h.from = [h.from[0] + g.d[0], h.from[1] + g.d[1]];
    }
  }
  return hs;
}
/** How far from a lens's centre its axis's handle stands on the map from above (pixels). */
const AXIS_PX = 22;
/** How far beyond an upright straw's foot its lean's handle stands on the map from above (pixels). */
const LEAN_PX = 44;
/** The handle within a fingertip of `(x, y)`, nearest first; null if none. */
export function handleAt(handles, x, y, reach) {
  let best = null, bestD = reach;
  for (const h of handles || []) {
    const d = Math.hypot(h.at[0] - x, h.at[1] - y);
    if (d < bestD) { bestD = d; best = h; }
  }
  return best;
}
/** How deep `(x, y)` lies within the container's outer outline seen from above (<= 0 outside). */
function depthIn(form, x, y) {
  const k = form.container || {};
  return k.shape === "tank" ? Math.min(k.half_x - Math.abs(x), k.half_y - Math.abs(y)) : outerRadius(k) - Math.hypot(x, y);
}
/** The bounds `[lo, hi]` of the layer holding the height `z` inside the form's container: the
 * floor or a surface below it, the next surface above it (Infinity above them all). */
function layerAround(f, z) {
  let lo = inside(f).floor;
  for (const l of f.liquid || []) { if (z <= l.top) return [lo, l.top]; lo = l.top; }
  return [lo, Infinity];
}
/** Sphere or lens `k` of the form `f` (a ball of radius `r`: a lens as the sphere about its
 * centre that holds it) moved towards the map's point `q`. From above (`[x, y]`): kept inside
 * the container if it is in it, else round it (free where it floats above the rim or below the
 * foot). From the side (`[s, z]`, its height only): down to the floor inside (a lens within its
 * liquid layer, or above them; in a glass of revolution, down to where the wall narrows round
 * it), or stopped over the rim (or under the foot) where it overhangs the walls. On its way it
 * stops short of the straws, coins, cards, other solids and the eye, so that it never jumps over
 * one within a step; the rules (the engine) have the last word. */
function moveBall(f, kind, k, q, side) {
  const o = f[kind][k], [x, y, z] = o.center, r = kind === "lens" ? lensReach(o) : o.radius;
  const { floor, height } = inside(f), k0 = f.container || {}, turned = k0.shape === "revolution";
  let at; // the place at the fraction `t` of the way, or null where it must stop
  if (!side) {
    const free = z - r > height || z + r < 0;
    const held = sphereHeld(f, [x, y, z], r) && z - r >= floor, room = ballInside(f, z, r);
    at = (t) => {
      const p = [x + t * (q[0] - x), y + t * (q[1] - y)];
      if (free) return [r5(p[0]), r5(p[1]), z];
      if (held) return [...keepInside(f, p, r, room), z];
      // Round the container, not through it: the pointer deep inside its outline stops it.
      return depthIn(f, p[0], p[1]) > r ? null : [...keepOutside(f, p, r + 1e-4), z];
    };
  } else {
    let nz = r5(q[1]);
    // In a glass of revolution: its centre within the inner profile, or above the rim within its
    // mouth (its fit at each height is judged on the way).
    const within = turned ? z >= floor && Math.hypot(x, y) < profileAt(k0.inner, Math.min(z, height)) : sphereHeld(f, [x, y, z], r);
    if (within) {
      if (z < floor) nz = Math.min(nz, r5(-r - 1e-4));
      else if (kind === "lens") {
        // A lens stays in its layer, a hair clear of its surfaces, as the rules ask.
        const [lo, hi] = layerAround(f, z);
        nz = Math.max(nz, restingOn(lo, r));
        if (hi !== Infinity) { let top = Math.floor((hi - r) * 1e5) / 1e5; if (top + r > hi) top -= 1e-5; nz = Math.min(nz, top); }
      } else nz = Math.max(nz, restingOn(floor, r));
    } else {
      const d = outsideBy(f, x, y);
      if (d < r + 1e-4) {
        const h = Math.sqrt(Math.max(0, r * r - d * d)) + 1e-4;
        nz = z >= height / 2 ? Math.max(nz, Math.ceil((height + h) * 1e5) / 1e5) : Math.min(nz, Math.floor(-h * 1e5) / 1e5);
      }
    }
    // Fitting where it starts, it stops where it would no longer fit: on a wall that narrows.
    const fits = within && turned && sphereHeld(f, [x, y, z], r);
    at = (t) => {
      const p = [x, y, t === 1 ? nz : r5(z + t * (nz - z))];
      return fits && !sphereHeld(f, p, r) ? null : p;
    };
  }
  // Steps of 0.2 mm (at most 600) from where it is; the objects are judged only if the ball
  // stands clear of them where it starts (a card wholly inside a sphere, say, is the engine's to
  // judge), 10 µm clear unless it starts closer (touching one, it may still move away).
  const ball = (c) => ({ kind, k, c, r });
  const end = at(1), way = end ? Math.hypot(end[0] - x, end[1] - y, end[2] - z) : Math.hypot(q[0] - x, q[1] - y);
  const gap = solidClear(f, ball(o.center), 1e-5) ? 1e-5 : 0, judged = gap > 0 || solidClear(f, ball(o.center), 0);
  const n = Math.min(600, Math.max(1, Math.ceil(way / 2e-4)));
  let last = o.center;
  for (let i = 1; i <= n; i++) {
    const p = at(i / n);
    if (!p || (judged && !solidClear(f, ball(p), gap))) break;
    last = p;
  }
  o.center = last;
}
/** Prism `k` of the form `f` moved towards the map's point `q` by its middle. From above
 * (`[x, y]`): kept inside the container if it stands in it (sliding along its walls), else round
 * it (free where it stands above the rim or below the foot). From the side (`[s, z]`, its height
 * only): down to the floor inside (in a glass of revolution, down to where the wall narrows
 * round it), or stopped over the rim (or under the foot) where it overhangs the walls. On its way
 * it stops short of the straws, coins, cards, other solids and the eye; the rules (the engine)
 * have the last word. */
function movePrism(f, k, q, side) {
  const o = f.prism[k], poly = o.corners, { height, floor } = inside(f);
  const [cx, cy] = polygonMiddle(poly), h = o.top - o.bottom;
  // Within the walls at its own heights (a glass of revolution is narrower at some).
  const heldAt = (p, margin, bottom = o.bottom) => polygonHeld(f, p, margin, bottom, bottom + h);
  const moved = (dx, dy) => poly.map(([x, y]) => [r5(x + dx), r5(y + dy)]);
  let at; // the prism `{ poly, bottom, top }` at the fraction `t` of the way, or null where it must stop
  if (!side) {
    const free = o.bottom > height || o.top < 0;
    const held = heldAt(poly, 0) && o.bottom >= floor;
    const c = inside(f), k0 = f.container || {};
    at = (t) => {
      let dx = r5(t * (q[0] - cx)), dy = r5(t * (q[1] - cy));
      if (free) return { poly: moved(dx, dy), bottom: o.bottom, top: o.top };
      if (held) {
        if (c.tank) {
          // Each way on its own: it slides along a wall it meets.
          const lim = (lo, hi, d, half) => Math.max(-half + 1e-4 - lo, Math.min(half - 1e-4 - hi, d));
          dx = r5(lim(Math.min(...poly.map((p) => p[0])), Math.max(...poly.map((p) => p[0])), dx, c.hx));
          dy = r5(lim(Math.min(...poly.map((p) => p[1])), Math.max(...poly.map((p) => p[1])), dy, c.hy));
        } else if (!heldAt(moved(dx, dy), 1e-4)) {
          // Its middle drawn in towards the axis until it fits: it slides round the wall.
          const fits = (m) => heldAt(moved(r5(m * (cx + dx) - cx), r5(m * (cy + dy) - cy)), 1e-4);
          if (!fits(0)) return null;
          let lo = 0, hi = 1;
          for (let i = 0; i < 30; i++) { const m = (lo + hi) / 2; if (fits(m)) lo = m; else hi = m; }
          [dx, dy] = [r5(lo * (cx + dx) - cx), r5(lo * (cy + dy) - cy)];
          if (!fits(lo)) return null;
        }
        return { poly: moved(dx, dy), bottom: o.bottom, top: o.top };
      }
      // Round the container, not through it: its middle over the container's outline stops it;
      // round a glass it is pushed out along its middle's direction until clear of it.
      if (depthIn(f, cx + dx, cy + dy) > 0) return null;
      let p = moved(dx, dy);
      for (let i = 0; i < 8 && polygonOutsideBy(f, p) < 1e-4 && k0.shape !== "tank"; i++) {
        const m = [cx + dx, cy + dy], d = Math.hypot(...m), push = 1e-4 - polygonOutsideBy(f, p) + 1e-5;
        dx = r5(dx + (push * m[0]) / d); dy = r5(dy + (push * m[1]) / d);
        p = moved(dx, dy);
      }
      return polygonOutsideBy(f, p) < 1e-4 ? null : { poly: p, bottom: o.bottom, top: o.top };
    };
  } else {
    let nb = r5(q[1] - h / 2);
    const held = heldAt(poly, 0) && o.bottom >= floor;
    if (held) nb = Math.max(nb, floor);
    else if (polygonOutsideBy(f, poly) < 1e-4) {
      nb = o.bottom >= height / 2 ? Math.max(nb, Math.ceil((height + 1e-4) * 1e5) / 1e5) : Math.min(nb, Math.floor((-h - 1e-4) * 1e5) / 1e5);
    }
    // Held where it starts, it stops where it would no longer fit (a wall that narrows).
    at = (t) => {
      const b = t === 1 ? nb : r5(o.bottom + t * (nb - o.bottom));
      return held && !heldAt(poly, 0, b) ? null : { poly, bottom: b, top: r5(b + h) };
    };
  }
  // Steps of 0.2 mm (at most 600) from where it is, judged as a sphere's are.
  const solid = (p) => ({ kind: "prism", k, poly: p.poly, bottom: p.bottom, top: p.top });
  const start = { poly, bottom: o.bottom, top: o.top }, end = at(1);
  const shift = (p) => Math.max(Math.hypot(p.poly[0][0] - poly[0][0], p.poly[0][1] - poly[0][1]), Math.abs(p.bottom - o.bottom));
  const way = end ? shift(end) : Math.hypot(q[0] - cx, q[1] - cy);
  const gap = solidClear(f, solid(start), 1e-5) ? 1e-5 : 0, judged = gap > 0 || solidClear(f, solid(start), 0);
  const n = Math.min(600, Math.max(1, Math.ceil(way / 2e-4)));
  let last = start;
  for (let i = 1; i <= n; i++) {
    const p = at(i / n);
    if (!p || (judged && !solidClear(f, solid(p), gap))) break;
    last = p;
  }
  Object.assign(o, { corners: last.poly, bottom: last.bottom, top: last.top });
}
/** Moves the handle `h` to the map's point `q` (`[x, y]` from above, `[s, z]` from the side). */
export function dragHandle(h, q, side) {
  dragForm((f) => {
    if (h.kind === "sphere" || h.kind === "lens") { moveBall(f, h.kind, h.k, q, side); return; }
    if (h.kind === "prism") { movePrism(f, h.k, q, side); return; }
    if (h.kind === "corner") {
      // The corner goes to the pointer; a polygon the rules refuse (not convex, or cutting
      // something) is a step left out.
      const o = (f.prism || [])[h.k], p = o && o.corners[h.j];
      if (!p) return; // (the prism changed under the drag: an undo)
      o.corners[h.j] = [r5(q[0]), r5(q[1])];
      return;
    }
    if (h.kind === "lean") {
      const o = (f.straw || [])[h.k];
      if (!o) return; // (the straw changed under the drag: an undo)
      const d = Math.hypot(q[0] - o.x, q[1] - o.y) - h.dead, s = Math.max(0, Math.min(Math.sin((80 * Math.PI) / 180), d / (o.length || STRAW_H)));
      const tilt = Math.round((Math.asin(s) * 1800) / Math.PI) / 10;
      o.tilt = tilt < 0.1 ? 0 : tilt;
      o.azimuth = Math.round((Math.atan2(q[1] - o.y, q[0] - o.x) * 1800) / Math.PI) / 10 + 0;
      return;
    }
    if (h.kind === "axis") {
      // The axis's horizontal part turned towards the pointer, its slope kept (an upright axis
      // laid flat).
      const o = (f.lens || [])[h.k];
      if (!o) return;
      const a = o.axis || [0, 0, 1], n = Math.hypot(...a) || 1, [ax, ay, az] = a.map((v) => v / n);
      let hz = Math.hypot(ax, ay), vz = az;
      if (hz < 1e-9) { hz = 1; vz = 0; }
      const phi = Math.atan2(q[1] - o.center[1], q[0] - o.center[0]), r4 = (v) => Math.round(v * 1e4) / 1e4 + 0;
      o.axis = [r4(Math.cos(phi) * hz), r4(Math.sin(phi) * hz), r4(vz)];
      return;
    }
    if (h.kind === "profile") {
      // The point goes to the pointer's distance from the axis (either side of it) and height;
      // the base stays on z = 0 and the two rims at one height, as the rules ask: a rim's point
      // takes both rims up or down.
      const c = f.container, p = (c[h.which] || [])[h.k], z = r5(q[1]);
      if (!p) return; // (the container changed under the drag: an undo)
      p[0] = r5(Math.abs(q[0]));
      if (h.k === c[h.which].length - 1) for (const l of [c.outer, c.inner]) l[l.length - 1][1] = z;
      else if (h.which === "inner" || h.k > 0) p[1] = z;
      return;
    }
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

