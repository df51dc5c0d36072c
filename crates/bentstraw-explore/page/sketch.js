// What the page draws of a scene file (its wireframe, its objects' outlines, its box and
// liquids), asked of the engine once per scene and kept for the panels.
import { state, sceneKey, sceneQuery } from "./state.js";
import { engineFetch } from "./engine.js";
import { drawCloud } from "./cloud.js";
import { drawMaps } from "./maps.js";
import { syncControls } from "./controls.js";
import { showLesson } from "./lesson.js";
import { drawPicture } from "./picture.js";

/** What the page draws of each scene file (wireframe, outlines, box), asked once per scene. */
const sketches = {};
function fetchSketch(name) {
  if (sketches[name]) return;
  // A drag makes a new scene file at each step: only the latest few are kept.
  const names = Object.keys(sketches);
  if (names.length >= 24) delete sketches[names[0]];
  sketches[name] = "pending";
  engineFetch("sketch", "/api/sketch", sceneQuery(state)).then((r) => (r.ok ? r.json() : null)).then((sc) => {
    if (!sc) { delete sketches[name]; return; }
    const pt = (a, i) => [a[i], a[i + 1], a[i + 2]];
    const wire = [];
    for (let i = 0; i + 5 < sc.wireframe.length; i += 6) wire.push([pt(sc.wireframe, i), pt(sc.wireframe, i + 3)]);
    const outlines = sc.outlines.map((l) => Array.from({ length: l.length / 3 }, (_, i) => pt(l, 3 * i)));
    sketches[name] = { wire, outlines, bounds: sc.bounds, liquids: sc.liquids || [], container: sc.container || null, lesson: sc.lesson || null };
    if (sceneKey(state) === name) { drawMaps(); drawCloud(); syncControls(); showLesson(); drawPicture(); }
  });
}

/** The current scene's own sketch once it has come (never another scene's standing in), else null. */
export function currentSketch() {
  const sc = sketches[sceneKey(state)];
  return sc && sc !== "pending" ? sc : null;
}

/** The middle and size of what the views show: the glass and straw, or a gallery scene's box. */
export function sceneBox() {
  const lines = sceneLines();
  const b = lines ? lines.bounds : null;
  if (!b) return { centre: [0, 0, 0.125], size: 0.36 };
  return { centre: [(b[0] + b[3]) / 2, (b[1] + b[4]) / 2, (b[2] + b[5]) / 2], size: 1.3 * Math.max(b[3] - b[0], b[4] - b[1], b[5] - b[2]) };
}

/** A gallery scene's wireframe (pairs of points), outlines (polylines) and box, once its sketch has come. */
export function sceneLines() {
  if (!state.scene && !state.file) return null;
  const key = sceneKey(state);
  const sc = sketches[key];
  if (sc === undefined) fetchSketch(key);
  // While a scene's sketch is on its way (a drag's next step), the last one stands in.
  if (sc && sc !== "pending") lastLines = sc;
  return lastLines;
}
let lastLines = null;
