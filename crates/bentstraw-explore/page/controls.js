// The view controls: the header's choosers and sliders and the cloud's toolbar (bound from the
// state's table, FIELDS), the presets and the gallery, the links, exports and full screen.
import { t } from "./i18n.js";
import { state, FIELDS, PRESETS, initialOf, viewQuery, stateHash } from "./state.js";
import { $ } from "./dom.js";
import { engineFetch, refusalOf } from "./engine.js";
import { showError } from "./errors.js";
import { changed, requestModels, pictureSize, forgetFrame } from "./frames.js";
import { drawCloud, drawLegend } from "./cloud.js";
import { sceneLines } from "./sketch.js";
import { inLanguage } from "./lesson.js";

/** The controls showing the state as it is. */
export function syncControls() {
  fileOption();
  $("scene").value = state.file ? "file" : state.scene;
  const fromFile = Boolean(state.scene || state.file);
  const lines = fromFile ? sceneLines() : null;
  const liquid = lines && lines.liquids.length ? lines.liquids[0] : null;
  for (const f of FIELDS) {
    const c = f.control;
    if (!c) continue;
    const el = $(c.id);
    let v = state[f.prop];
    if (f.glass) {
      // A scene file's liquids and straws are its own: the water's sliders are the glass's, and
      // show the file's own bottom liquid (its surface, its index), or none.
      el.disabled = fromFile;
      if (fromFile) v = liquid ? liquid[c.liquid] : null;
    }
    if (v !== null) el.value = v;
    if (c.out) $(c.id + "-out").textContent = v === null ? "—" : c.out(v);
  }
  for (const k of ["course", "eye", "stereo"]) $("show-" + k).checked = state.models.includes(k);
}

for (const f of FIELDS) {
  const c = f.control;
  if (!c) continue;
  $(c.id).addEventListener(c.event, (e) => {
    state[f.prop] = f.parse(e.target.value);
    if (c.redoes === "cloud") { history.replaceState(null, "", stateHash(state)); drawCloud(); drawLegend(); }
    else changed(c.redoes === "keep-path" ? { keepPath: true } : undefined);
  });
}
for (const k of ["course", "eye", "stereo"]) {
  $("show-" + k).addEventListener("change", (e) => {
    state.models = ["course", "eye", "stereo"].filter((x) => (x === k ? e.target.checked : state.models.includes(x)));
    history.replaceState(null, "", stateHash(state));
    drawCloud(); drawLegend(); requestModels();
  });
}
PRESETS.forEach((p, i) => { const o = document.createElement("option"); o.value = String(i); o.dataset.i18n = "preset." + i; o.textContent = t("preset." + i); $("preset").appendChild(o); });
$("preset").addEventListener("change", (e) => {
  const p = PRESETS[Number(e.target.value)];
  if (!p) return;
  // A scene of the gallery or of one's own is kept: the view moves its eye only.
  if (state.scene || state.file) {
    state.observer = p.v.observer.slice();
    changed();
    return;
  }
  Object.assign(state, { scene: "", file: "", n: initialOf("n"), events: initialOf("events"), color: initialOf("color") }, p.v);
  state.observer = p.v.observer.slice(); state.straw = p.v.straw.slice();
  changed();
});

/** The scene chooser's entry for the page's own scene file, while it shows one. */
function fileOption() {
  let o = $("scene").querySelector('option[value="file"]');
  if (state.file && !o) {
    o = document.createElement("option");
    o.value = "file"; o.dataset.i18n = "scene.file"; o.textContent = t("scene.file");
    $("scene").appendChild(o);
  }
  if (!state.file && o) o.remove();
}

// The gallery's scenes, from the engine: choosing one moves the eye to the view it is meant for.
let gallery = [];
/** The gallery's scenes (name, title, what each shows, its eye), once the engine has said them. */
export const galleryReady = engineFetch("scenes", "/api/scenes", "").then((r) => r.json()).then((list) => {
  gallery = list;
  for (const g of list) {
    const o = document.createElement("option");
    o.value = g.name;
    $("scene").appendChild(o);
  }
  relabelGallery();
  syncControls();
  document.body.dataset.scenes = String(list.length);
  return list;
});
/** The gallery's entries named in the page's language (their lessons' titles). */
export function relabelGallery() {
  for (const g of gallery) {
    const o = $("scene").querySelector(`option[value="${g.name}"]`);
    const l = inLanguage(g.lesson);
    if (o) { o.textContent = l ? l.title : g.title; o.title = l ? l.text : g.shows; }
  }
}
$("scene").addEventListener("change", (e) => {
  if (e.target.value === "file") return;
  state.scene = e.target.value;
  state.file = "";
  const g = gallery.find((x) => x.name === state.scene);
  state.observer = g ? g.observer.slice() : [0.1, 0, 0.1];
  $("preset").value = "";
  forgetFrame();
  changed();
});

// On a narrow screen the header's settings fold behind "Menu".
$("menu").addEventListener("click", () => {
  const open = document.querySelector("header").classList.toggle("open");
  $("menu").setAttribute("aria-expanded", String(open));
});

$("copy-link").addEventListener("click", async () => {
  const link = window.bentstraw.link();
  document.body.dataset.link = link;
  showQr(link);
  try { await navigator.clipboard.writeText(link); $("status").textContent = t("status.copied", { link }); } catch (_) { prompt(t("prompt.copy"), link); }
});
/** The link's QR code over the picture, for a class to scan from a projector (the engine draws
 * it; a link too long for one is said so). */
async function showQr(link) {
  const r = await engineFetch("qr", "/api/qr", "text=" + encodeURIComponent(link));
  const img = $("qr");
  if (img.src.startsWith("blob:")) URL.revokeObjectURL(img.src);
  img.hidden = !r.ok;
  if (r.ok) { img.src = URL.createObjectURL(await r.blob()); $("qr-note").textContent = ""; }
  else $("qr-note").textContent = t("qr.too-long", { n: link.length });
  $("qr-panel").hidden = false;
  document.body.dataset.qr = r.ok ? "shown" : "too-long";
}
$("qr-close").addEventListener("click", () => { $("qr-panel").hidden = true; });
/** Saves the file `simulate` or `render` would write for this view, computed by the engine. */
async function download(format, model) {
  const [w, h] = pictureSize();
  const r = await engineFetch("export", "/api/export", viewQuery(state, { format, size: `${w}x${h}`, model: model || "course" }));
  if (!r.ok) { showError(await refusalOf(r)); return; }
  const name = (r.headers.get("Content-Disposition") || "").match(/filename="([^"]+)"/);
  const a = document.createElement("a");
  a.href = URL.createObjectURL(await r.blob());
  a.download = name ? name[1] : "view";
  document.body.appendChild(a); a.click(); a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 10000);
}
$("export-png").addEventListener("click", () => download("png"));
$("export-csv").addEventListener("click", () => download("csv"));
$("export-ply").addEventListener("click", () => download("ply"));

// Full screen (for a projector): the picture's panel alone.
const eyePanel = $("eye-panel");
export function fullscreenLabel() {
  $("fullscreen").textContent = t(document.fullscreenElement ? "fullscreen.leave" : "fullscreen");
}
if (document.fullscreenEnabled) {
  $("fullscreen").hidden = false;
  $("fullscreen").addEventListener("click", () => {
    if (document.fullscreenElement) document.exitFullscreen().catch(() => {});
    else eyePanel.requestFullscreen().catch(() => {});
  });
  // The picture is asked for again at the new size (by the window's resize).
  document.addEventListener("fullscreenchange", () => { fullscreenLabel(); window.dispatchEvent(new Event("resize")); });
}

