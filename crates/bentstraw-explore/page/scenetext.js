// The scene file's text box: the view's scene as the text of its file, typed, opened or saved,
// checked by the engine before the view follows it; the history of the scenes shown (undo, redo).
import { state, MAX_FILE_BYTES, packFile, viewQuery, num } from "./state.js";
import { $ } from "./dom.js";
import { engineFetch, answerText } from "./engine.js";
import { errorText } from "./errors.js";
import { changed, forgetFrame } from "./frames.js";
import { loadForm, markObjects, dragText, dragGesture } from "./editor.js";

/** The eye for the scene file `toml` (its own [observer], else the current eye) once the engine
 * has checked the whole view by the same rules as `simulate --scene scene.toml --observer …`;
 * rejects with the engine's message (the command line's) if a rule is broken. */
export async function checkScene(toml, worker) {
  const sketch = await engineFetch(worker, "/api/sketch", new URLSearchParams({ "scene-file": toml }).toString());
  const sc = JSON.parse(await answerText(sketch));
  const observer = sc.observer || state.observer;
  await answerText(await engineFetch(worker, "/api/scene-file", viewQuery({ ...state, file: toml, scene: "", observer })));
  return observer;
}
/** Makes the checked scene file `toml` the view's scene (the caller asks for the frame). */
export async function useScene(toml, observer) {
  await packFile(toml);
  Object.assign(state, { file: toml, scene: "", observer: observer.slice() });
  $("preset").value = "";
}
/** Counts a refused view or text (tests wait on the count). */
export function refused() { document.body.dataset.refused = String(Number(document.body.dataset.refused || 0) + 1); }

// The text box is always the view's scene; typing sends it (after a pause).
export const sceneText = $("scene-text");
const sceneErrorsEl = $("scene-errors");
/** A typed text is sent this long after the last key. */
const EDIT_AFTER_MS = 400;
/** The scenes the view has shown, for undo and redo: { text, snap } (the text in the box, the
 * state that shows it), at most HISTORY_MAX of them. */
const HISTORY_MAX = 50;
const sceneHistory = { entries: [], at: -1 };
let editTimer = null;    // a typed text waiting to be sent
let editSeq = 0;         // the latest text sent
let syncSeq = 0;         // the latest view whose text was asked for
export let sceneErrorShown = null;

/** Forgets a typed text still waiting to be sent: a newer text replaces it. */
export function cancelTyping() { clearTimeout(editTimer); editTimer = null; }

/** What of the state makes the scene and its eye (what undo brings back). */
function sceneSnapshot() {
  return { scene: state.scene, file: state.file, observer: state.observer.slice(), straw: state.straw.slice(), he: state.he, n: state.n };
}

/** Under the box: the engine's message, a line per item (text, as it comes), or one of the
 * page's own ({ key, params }); null clears it. */
export function showSceneErrors(error) {
  sceneErrorShown = error;
  const text = errorText(error);
  sceneErrorsEl.replaceChildren(...text.split("\n").filter((l) => l.trim()).map((l) => {
    const li = document.createElement("li");
    li.textContent = l;
    return li;
  }));
  sceneErrorsEl.hidden = !text;
  if (text) sceneErrorsEl.scrollIntoView({ block: "nearest" });
  sceneText.classList.toggle("refused", Boolean(text));
  markObjects(error);
  sceneText.setAttribute("aria-invalid", text ? "true" : "false");
}

/** After a full frame: the box shows the view's scene (the page's own text when it shows one,
 * else the engine's scene file for the view), unless the user is typing or a refused text is
 * being corrected; the scene enters the history. */
export async function syncSceneText() {
  const seq = ++syncSeq;
  const snap = sceneSnapshot();
  let text = state.file;
  if (!text) {
    try {
      const r = await engineFetch("hook", "/api/scene-file", viewQuery(state));
      if (!r || !r.ok || seq !== syncSeq) return;
      text = await r.text();
    } catch (_) { return; } // the frame's own request shows what went wrong
    if (seq !== syncSeq) return;
  }
  remember(text, snap);
  loadForm(text);
  if (editTimer !== null || (document.activeElement === sceneText && sceneErrorShown !== null)) return;
  if (sceneText.value !== text) sceneText.value = text;
  showSceneErrors(null);
  document.body.dataset.sceneText = String(seq);
}

function remember(text, snap) {
  const h = sceneHistory;
  // The same text (a page's own file seen from another eye): the entry keeps the latest eye.
  if (h.at >= 0 && h.entries[h.at].text === text) { h.entries[h.at].snap = snap; return; }
  // A drag of an object is one step of the history, however many texts it went through.
  const gesture = text === dragText ? dragGesture : null;
  h.entries.splice(h.at + 1);
  if (gesture && h.at >= 0 && h.entries[h.at].gesture === gesture) { Object.assign(h.entries[h.at], { text, snap }); historyButtons(); return; }
  h.entries.push({ text, snap, gesture });
  if (h.entries.length > HISTORY_MAX) h.entries.shift();
  h.at = h.entries.length - 1;
  historyButtons();
}
function historyButtons() {
  // The scene file's panel and the objects' panel each have the pair.
  for (const id of ["scene-undo", "objects-undo"]) $(id).disabled = sceneHistory.at <= 0;
  for (const id of ["scene-redo", "objects-redo"]) $(id).disabled = sceneHistory.at >= sceneHistory.entries.length - 1;
}

/** Undo (-1) or redo (+1): the scene, its eye and its text as they were. */
async function stepHistory(d) {
  const h = sceneHistory, k = h.at + d;
  if (k < 0 || k >= h.entries.length) return;
  h.at = k;
  historyButtons();
  clearTimeout(editTimer); editTimer = null;
  editSeq++; syncSeq++; // answers still on their way belong to the scene left
  const { text, snap } = h.entries[k];
  if (snap.file) await packFile(snap.file);
  const sameScene = snap.scene === state.scene && snap.file === state.file;
  Object.assign(state, snap, { observer: snap.observer.slice(), straw: snap.straw.slice() });
  $("preset").value = "";
  sceneText.value = text;
  showSceneErrors(null);
  if (!sameScene) forgetFrame();
  changed();
}
for (const id of ["scene-undo", "objects-undo"]) $(id).addEventListener("click", () => stepHistory(-1));
for (const id of ["scene-redo", "objects-redo"]) $(id).addEventListener("click", () => stepHistory(1));
// Ctrl+Z / Ctrl+Shift+Z (or Ctrl+Y) for the scene, except where a text box has its own undo.
document.addEventListener("keydown", (e) => {
  if (!(e.ctrlKey || e.metaKey) || e.altKey) return;
  const key = e.key.toLowerCase();
  if (key !== "z" && key !== "y") return;
  const el = e.target;
  if (el && (el.tagName === "TEXTAREA" || el.isContentEditable || (el.tagName === "INPUT" && !/^(range|checkbox|button|file)$/.test(el.type)))) return;
  e.preventDefault();
  stepHistory(key === "y" || e.shiftKey ? 1 : -1);
});

/** Sends a text of the box as the view's scene: the view follows it, or, if a rule is broken,
 * the view stays and the box keeps the text, the engine's message under it. */
export async function applySceneText(text) {
  const seq = ++editSeq;
  syncSeq++;
  const h = sceneHistory;
  if (h.at >= 0 && h.entries[h.at].text === text) { showSceneErrors(null); return; } // the view's own
  if (new Blob([text]).size > MAX_FILE_BYTES) { showSceneErrors({ key: "error.file-size" }); refused(); return; }
  let observer;
  try {
    observer = await checkScene(text, "hook");
  } catch (e) {
    if (seq !== editSeq) return;
    showSceneErrors(e.shown || e.message);
    refused();
    return;
  }
  if (seq !== editSeq) return;
  showSceneErrors(null);
  await useScene(text, observer);
  changed();
}
sceneText.addEventListener("input", () => {
  clearTimeout(editTimer);
  editTimer = setTimeout(() => { editTimer = null; applySceneText(sceneText.value); }, EDIT_AFTER_MS);
});

// Open…: a scene file from this computer, at most 1 MB, into the box and the view.
$("scene-open").addEventListener("click", () => $("scene-input").click());
$("scene-input").addEventListener("change", (e) => {
  const file = e.target.files[0];
  e.target.value = ""; // the same file can be opened again
  if (!file) return;
  if (file.size > MAX_FILE_BYTES) { showSceneErrors({ key: "edit.too-large", params: { name: file.name } }); return; }
  const reader = new FileReader();
  reader.onload = () => {
    $("scene-edit").open = true;
    clearTimeout(editTimer); editTimer = null;
    sceneText.value = reader.result;
    applySceneText(reader.result);
  };
  reader.onerror = () => showSceneErrors({ key: "edit.unreadable", params: { name: file.name, message: String(reader.error && reader.error.message) } });
  reader.readAsText(file);
});
/** A scene file's `text` with its observer at `eye`: the position of its `[observer]` table
 * written again where it differs (the rest of the text, comments included, as it is), the table
 * added when there is none. */
export function withEye(text, eye) {
  const written = `[${eye.map(num).join(", ")}]`;
  const header = /^[ \t]*\[observer\][ \t]*(#.*)?$/m.exec(text);
  if (!header) return text.replace(/\s*$/, "") + `\n\n[observer]\nposition = ${written}\n`;
  const start = header.index + header[0].length;
  const next = /^[ \t]*\[/m.exec(text.slice(start));
  const end = next ? start + next.index : text.length;
  const section = text.slice(start, end);
  const position = /^([ \t]*position[ \t]*=[ \t]*)\[([^\]]*)\]/m.exec(section);
  if (!position) return text.slice(0, start) + `\nposition = ${written}` + text.slice(start);
  const old = position[2].split(",").map(Number);
  if (old.length === 3 && old.every((v, i) => Math.abs(v - eye[i]) < 1e-9)) return text;
  const at = start + position.index;
  return text.slice(0, at) + position[1] + written + text.slice(at + position[0].length);
}

// Save: the box's text as scene.toml, its observer the view's eye (a page's own file keeps the
// eye it was opened with in the box, however far the eye was dragged since).
$("scene-save").addEventListener("click", () => {
  const a = document.createElement("a");
  a.href = URL.createObjectURL(new Blob([withEye(sceneText.value, state.observer)], { type: "application/toml" }));
  a.download = "scene.toml";
  document.body.appendChild(a); a.click(); a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 10000);
});

