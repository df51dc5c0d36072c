// Apparent depth as the eye moves: the clicked ray's object point followed as the eye goes round
// the glass or up and down at the same distance (the engine's /api/sweep); a small plot of the
// height of each model's point against the eye's angle, the current eye marked, and its CSV.
import { t, localNumber, applyI18n } from "./i18n.js";
import { state, viewQuery } from "./state.js";
import { $ } from "./dom.js";
import { ask, engineFetch, refusalOf } from "./engine.js";
import { showError } from "./errors.js";
import { path } from "./frames.js";

/** The sweep shown when a point is clicked: none until one is chosen. */
export const SWEEP_DEFAULT = "off";
/** Seats of a sweep (the engine's default: every 6° round the glass, every 3° up and down). */
const SWEEP_ROWS = 61;
/** The models, in the engine's order: their field, their words, their colour (the report's). */
const MODELS = [
  { field: "course", key: "sweep.course", colour: "#14288c" },
  { field: "focus_h", key: "sweep.focus-h", colour: "#d25000" },
  { field: "focus_v", key: "sweep.focus-v", colour: "#960096" },
  { field: "stereo", key: "sweep.stereo", colour: "#00823c" },
];
const SVG = "http://www.w3.org/2000/svg";

let kind = SWEEP_DEFAULT;
/** The last answer: its query and its JSON. */
let shown = null;

const m4 = (x) => localNumber(Number(x).toFixed(4));

/** The engine's query for the clicked ray's point and the chosen sweep. */
function sweepQuery(format) {
  return viewQuery(state, {
    point: path.straw_point.join(","),
    direction: path.direction.join(","),
    sweep: kind,
    rows: SWEEP_ROWS,
    format,
  });
}

/** Shows the sweep's controls when a ray that reached an object is shown, and its plot when a
 * sweep is chosen (asked again only when the point, the view or the sweep changed). */
export async function syncSweep() {
  const box = $("sweep");
  if (!path || path.outcome !== "straw") {
    box.hidden = true;
    delete document.body.dataset.sweep;
    return;
  }
  box.hidden = false;
  $("sweep-kind").value = kind;
  const on = kind !== SWEEP_DEFAULT;
  // An SVG element has no `hidden` property: its attribute, which the style sheet hides.
  $("sweep-plot").toggleAttribute("hidden", !on);
  $("sweep-csv").hidden = !on;
  $("sweep-legend").hidden = !on;
  $("sweep-note").hidden = !on;
  if (!on) { delete document.body.dataset.sweep; return; }
  const query = sweepQuery("json");
  if (shown && shown.query === query) { draw(shown.answer); return; }
  document.body.dataset.sweep = "busy";
  const r = await ask("sweep", "/api/sweep", query);
  if (!r) return;
  if (!r.ok) { showError(await refusalOf(r)); return; }
  const answer = await r.json();
  if (query !== sweepQuery("json")) return; // the point or the sweep changed meanwhile
  shown = { query, answer };
  draw(answer);
}

/** An SVG element `name` with attributes `attrs`, appended to `parent`. */
function el(parent, name, attrs, text) {
  const e = document.createElementNS(SVG, name);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (text !== undefined) e.textContent = text;
  parent.appendChild(e);
  return e;
}

/** A step of 1, 2 or 5 times a power of ten giving about `count` intervals over `span`. */
function niceStep(span, count) {
  const raw = span / count, p = 10 ** Math.floor(Math.log10(raw));
  return [1, 2, 5, 10].map((k) => k * p).find((s) => s >= raw);
}

/** Draws the answer: axes with units, a line per model (broken where the point is not seen or
 * its light path changes), the point's own height dashed, the current eye marked. */
function draw(answer) {
  const svg = $("sweep-plot");
  svg.replaceChildren();
  const W = 400, H = 200, L = 46, R = 10, T = 10, B = 40;
  svg.setAttribute("viewBox", `0 0 ${W} ${H}`);
  const [x0, x1] = answer.range;
  const z0 = answer.point[2];
  // The heights the report's figures show too: a focus far away would squash everything else.
  const near = (p) => p && p[2] >= answer.shown[0] && p[2] <= answer.shown[1];
  let lo = z0, hi = z0;
  for (const row of answer.rows) for (const md of MODELS) if (near(row[md.field])) { lo = Math.min(lo, row[md.field][2]); hi = Math.max(hi, row[md.field][2]); }
  const pad = Math.max((hi - lo) * 0.08, 0.002);
  const y0 = (lo - pad) * 100, y1 = (hi + pad) * 100; // centimetres
  const X = (a) => L + ((a - x0) / (x1 - x0)) * (W - L - R);
  const Y = (cm) => T + ((y1 - cm) / (y1 - y0)) * (H - T - B);
  // Grid, ticks and their numbers.
  const xStep = x1 - x0 > 200 ? 90 : 45;
  for (let a = x0; a <= x1 + 1e-9; a += xStep) {
    el(svg, "line", { x1: X(a), x2: X(a), y1: T, y2: H - B, class: "grid" });
    el(svg, "text", { x: X(a), y: H - B + 13, "text-anchor": "middle", class: "tick" }, localNumber(String(a)));
  }
  const yStep = niceStep(y1 - y0, 5);
  for (let v = Math.ceil(y0 / yStep) * yStep; v <= y1 + 1e-9; v += yStep) {
    el(svg, "line", { x1: L, x2: W - R, y1: Y(v), y2: Y(v), class: "grid" });
    const decimals = yStep >= 1 ? 0 : yStep >= 0.1 ? 1 : 2;
    el(svg, "text", { x: L - 4, y: Y(v) + 3.5, "text-anchor": "end", class: "tick" }, localNumber(v.toFixed(decimals)));
  }
  el(svg, "rect", { x: L, y: T, width: W - L - R, height: H - T - B, class: "frame" });
  el(svg, "text", { x: (L + W - R) / 2, y: H - 6, "text-anchor": "middle", class: "axis" }, t(answer.sweep === "around" ? "sweep.axis.around" : "sweep.axis.updown"));
  el(svg, "text", { x: 11, y: (T + H - B) / 2, "text-anchor": "middle", class: "axis", transform: `rotate(-90 11 ${(T + H - B) / 2})` }, t("sweep.axis.height"));
  // The point's own height: where it would seem without refraction.
  el(svg, "line", { x1: L, x2: W - R, y1: Y(z0 * 100), y2: Y(z0 * 100), class: "true-height" });
  // The current eye.
  const here = answer.rows.find((r) => r.current);
  if (here) el(svg, "line", { x1: X(here.angle), x2: X(here.angle), y1: T, y2: H - B, class: "seat" });
  for (const md of MODELS) {
    let run = [], last = null;
    const flush = () => { if (run.length > 1) el(svg, "polyline", { points: run.join(" "), fill: "none", stroke: md.colour, "stroke-width": 1.6 }); run = []; };
    for (const row of answer.rows) {
      const p = row[md.field];
      if (!near(p) || row.path !== last) flush();
      last = near(p) ? row.path : null;
      if (near(p)) {
        run.push(`${X(row.angle).toFixed(2)},${Y(p[2] * 100).toFixed(2)}`);
        el(svg, "circle", { cx: X(row.angle), cy: Y(p[2] * 100), r: 1.4, fill: md.colour });
      }
    }
    flush();
    if (here && near(here[md.field])) el(svg, "circle", { cx: X(here.angle), cy: Y(here[md.field][2] * 100), r: 3.6, fill: "none", stroke: md.colour, "stroke-width": 1.5, class: "here" });
  }
  // The legend and the numbers at the current eye.
  const legend = $("sweep-legend");
  legend.replaceChildren();
  const item = (swatchClass, colour, text) => {
    const li = document.createElement("li");
    const s = document.createElement("span");
    s.className = swatchClass;
    if (colour) s.style.background = colour;
    li.append(s, " " + text);
    legend.appendChild(li);
  };
  for (const md of MODELS) {
    const v = here && here[md.field];
    item("swatch-line", md.colour, v ? t("sweep.here", { model: t(md.key), z: m4(v[2]) }) : t(md.key));
  }
  item("swatch-dash", null, t("sweep.true", { z: m4(z0) }));
  const seen = answer.rows.filter((r) => r.sight === "seen").length;
  $("sweep-note").textContent = t("sweep.note", { seen, n: answer.rows.length });
  svg.dataset.rows = String(answer.rows.length);
  document.body.dataset.sweep = `${answer.sweep}:${answer.rows.length}`;
}

/** Saves the sweep as CSV, computed by the engine. */
async function downloadCsv(e) {
  e.preventDefault();
  if (!path) return;
  const r = await engineFetch("sweep-csv", "/api/sweep", sweepQuery("csv"));
  if (!r.ok) { showError(await refusalOf(r)); return; }
  const a = document.createElement("a");
  a.href = URL.createObjectURL(await r.blob());
  a.download = `sweep-${kind}.csv`;
  document.body.appendChild(a); a.click(); a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 10000);
}

$("sweep-kind").addEventListener("change", async (e) => {
  kind = e.target.value;
  await syncSweep();
  // The readout's panel scrolls on its own: the plot brought into it.
  if (kind !== SWEEP_DEFAULT) $("sweep").scrollIntoView({ block: "nearest" });
});
$("sweep-csv").addEventListener("click", downloadCsv);
applyI18n($("sweep"));
