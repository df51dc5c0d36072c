// Where the objects really are, drawn over the eye's picture when asked: each straw's outline
// (its rings at the ends and between its sections, and four lines along it), each coin's and
// card's, projected straight to the eye as if there were no water. Against the picture, it shows
// how far refraction moves what is seen (docs/physics.md).
import { state, STRAW_R, STRAW_H } from "./state.js";
import { $ } from "./dom.js";
import { currentSketch } from "./sketch.js";
import { tracePolyline } from "./draw.js";

/** Whether the outline is shown (the "Where it really is" button). */
export let outlineShown = false;

/** The assignment's straw as polylines: rings at its ends and at its sections' edges (every 5
 * cm), and four lines along it. */
function glassStraw() {
  const [x, y] = state.straw, lines = [];
  for (let k = 0; k <= 5; k++) {
    const z = (STRAW_H * k) / 5;
    lines.push(Array.from({ length: 25 }, (_, i) => [x + STRAW_R * Math.cos((i * Math.PI) / 12), y + STRAW_R * Math.sin((i * Math.PI) / 12), z]));
  }
  for (const [dx, dy] of [[1, 0], [-1, 0], [0, 1], [0, -1]]) lines.push([[x + STRAW_R * dx, y + STRAW_R * dy, 0], [x + STRAW_R * dx, y + STRAW_R * dy, STRAW_H]]);
  return lines;
}

/** The objects' outlines as polylines of 3D points: the assignment's straw, or a scene file's
 * objects from its sketch (none until it has come). */
function outlines() {
  if (!state.scene && !state.file) return glassStraw();
  const sc = currentSketch();
  return sc ? sc.outlines : [];
}

/** Draws the outlines through the picture's projection `pr`, dashed white over a dark halo, so
 * that they read on any picture; `size` the picture's pixels per CSS pixel. Returns how many
 * points it drew. */
export function drawOutline(ctx, pr, size) {
  if (!outlineShown) return 0;
  let n = 0;
  const stroke = (width, colour, dash) => {
    ctx.lineWidth = width * size; ctx.strokeStyle = colour; ctx.setLineDash(dash.map((d) => d * size));
    ctx.beginPath();
    n = 0;
    for (const line of outlines()) n += tracePolyline(ctx, pr, line);
    ctx.stroke();
  };
  stroke(3, "rgba(20,20,20,0.55)", []);
  stroke(1.5, "#ffffff", [5, 3]);
  ctx.setLineDash([]);
  return n;
}

$("outline").addEventListener("click", () => {
  outlineShown = !outlineShown;
  $("outline").setAttribute("aria-pressed", String(outlineShown));
  document.dispatchEvent(new Event("bentstraw-outline"));
});
