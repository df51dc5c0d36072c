// The page's wiring: window.bentstraw (the hook tests and scripts use, see docs/explorer.md),
// the language switch, the window's resize and the address's changes, and the start.
import { LANG, setLang, applyI18n } from "./i18n.js";
import { state, viewQuery, stateHash, readParams } from "./state.js";
import { $ } from "./dom.js";
import { ENGINE, ENGINE_THREADS, threadsInUse, stops, wasm, engineFetch, answerText } from "./engine.js";
import { errorShown, showError, errorText, linkRefusal, refuseLink } from "./errors.js";
import { hook, frame, path, changed, requestFrame, sendFrame, settled, pick, forgetFrame, resized } from "./frames.js";
import { drawCloud, drawLegend, screenOfPoint } from "./cloud.js";
import { drawMaps } from "./maps.js";
import { pathMarks, outlinePoints } from "./picture.js";
import { showHint, showReadout, showStatus, showCommands } from "./readout.js";
import { syncControls, fullscreenLabel, galleryReady, relabelGallery } from "./controls.js";
import { sceneErrorShown, showSceneErrors, checkScene, useScene, refused } from "./scenetext.js";
import { relabelObjects } from "./editor.js";
import { showLesson } from "./lesson.js";
import { syncPredict, relabelPredict, predictHook } from "./predict.js";

/** Reads a query or fragment (the address's, the command line's) into the state. A damaged link,
 * or one whose scene file cannot be read, changes nothing: it is refused, said in an alert, and no
 * other scene is drawn in its place. A gallery scene named without an eye is seen from the eye
 * the scene is meant for. */
async function readAddress(text) {
  const { lang, fileError, damaged, eyeGiven } = await readParams(text, state);
  // The page's language (not the view's): a link opens in the language it was copied in.
  if (lang !== null && lang !== LANG && setLang(lang, false)) relabel();
  if (damaged) return refuseLink({ key: "error.link-damaged" });
  if (fileError) return refuseLink({ key: "error.link-file", params: { message: fileError.message } });
  refuseLink(null);
  if (state.scene && !eyeGiven) {
    const g = (await galleryReady).find((x) => x.name === state.scene);
    if (g) state.observer = g.observer.slice();
  }
}

/** Writes again every text the page has drawn or written in the former language. */
function relabel() {
  $("lang").value = LANG;
  applyI18n();
  if (path) showReadout(); else if (!state.pick) showHint();
  if (typeof errorShown !== "string") showError(errorShown);
  if (sceneErrorShown !== null && typeof sceneErrorShown !== "string") showSceneErrors(sceneErrorShown);
  relabelObjects();
  if (!$("commands").hidden) showCommands();
  showStatus();
  syncControls();
  drawMaps(); drawCloud(); drawLegend();
  fullscreenLabel();
  relabelPredict();
  showLesson();
  relabelGallery();
}
$("lang").value = LANG;
$("lang").addEventListener("change", (e) => {
  if (!setLang(e.target.value, true)) return;
  relabel();
  history.replaceState(null, "", stateHash(state));
});

window.addEventListener("resize", () => { drawMaps(); drawCloud(); resized(); });
window.addEventListener("hashchange", async () => {
  if (location.hash === stateHash(state)) return; // the page's own change of the address
  await readAddress(location.hash); syncControls(); drawMaps(); syncPredict(); requestFrame(false);
});

window.bentstraw = Object.assign(hook, {
  pickPoint: (k) => pick(`point:${k}`),
  /** Where point `k` of the cloud is drawn, in the window's coordinates. */
  screenOfPoint,
  /** The current image points, as the CSV text `bentstraw simulate` writes. */
  async points() { await settled(); return answerText(await engineFetch("hook", "/api/export", viewQuery(state, { format: "csv" }))); },
  /** The arguments of the `bentstraw simulate` command giving those points (a page's own scene file is scene.toml). */
  async command() { await settled(); return frame.header.simulate_args.slice(); },
  /** The current scene as the text of a scene file, its [observer] the current eye; rejects with
   * the page's message while it refuses its link. */
  async scene() {
    if (linkRefusal) throw new Error(errorText(linkRefusal));
    return answerText(await engineFetch("hook", "/api/scene-file", viewQuery(state)));
  },
  /** Shows the scene file `toml` (from its own [observer], if it has one); rejects with the
   * command line's message if a rule is broken, and the page shows it. */
  async setScene(toml) {
    let observer;
    try {
      observer = await checkScene(toml, "hook");
    } catch (e) {
      showError(e.shown || e.message);
      refused();
      throw e;
    }
    await useScene(toml, observer);
    forgetFrame();
    changed();
    await settled();
  },
  /** One request to the engine, for measuring it: its status, the time the engine took (around
   * the same call: in the worker, or the server's own, sent as Server-Timing), the time seen by
   * the page, the answer's size. */
  async request(path, query) {
    const t = performance.now();
    const r = await engineFetch("measure", path, query);
    const body = await r.arrayBuffer();
    const ms = performance.now() - t;
    const timing = /engine;dur=([0-9.]+)/.exec(r.headers.get("Server-Timing") || "");
    const server = timing ? Number(timing[1]) : null;
    return { status: r.status, engineMs: wasm ? r.engineMs : server, ms, bytes: body.byteLength };
  },
  /** The address that restores this view, its scene included. */
  link() { return location.origin + location.pathname + stateHash(state); },
  engine: ENGINE,
  /** The page's engine's threads: how many it meant to use and why not more ({ threads, why }),
   * and `inUse()`, the number its full frames' pool really has once it has started. */
  engineThreads: { get threads() { return ENGINE_THREADS.threads; }, get why() { return ENGINE_THREADS.why; }, inUse: () => threadsInUse },
  /** Requests stopped while they ran: { inPlace, restarts } (see engine.js). */
  engineStops: stops,
  /** "Predict, then look": its phase, the engine's answer, the distances (predict.js). */
  predict: predictHook,
});

/** Where the clicked ray's drawing is on the picture (its frame's pixels): the arrows' tips, each
 * event's box [x, y, w, h], the texts written, the object's real point; null without one. (A
 * getter: Object.assign would copy its value once.) */
Object.defineProperty(window.bentstraw, "pathMarks", { get: () => pathMarks });
/** How many points of the objects' real outline the picture shows (0 when it is off). */
Object.defineProperty(window.bentstraw, "outlinePoints", { get: () => outlinePoints });

// The start: the address's state, else the command line's.
(async () => {
  await readAddress(document.body.dataset.initial || "");
  if (location.hash.length > 1) await readAddress(location.hash);
  if (state.file && !linkRefusal) history.replaceState(null, "", stateHash(state));
  syncControls();
  drawMaps();
  syncPredict();
  // The page's own engine: the frames' workers and the one for the page's small requests (the
  // scene's text, sketches, checks) start at once, and the first picture is a quick one (its
  // engine's code is not yet optimised by the browser), the full one following. Frames, quick and
  // full, take every core (a drag's quick frames at full resolution where that is fast enough);
  // small requests: one thread (no pool to start).
  wasm?.start(["frame", "frame-full", "hook"], { oneThread: ["hook"] });
  sendFrame(wasm !== null);
})();
