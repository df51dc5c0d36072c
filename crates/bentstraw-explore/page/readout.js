// The readout panel: the clicked ray's path in words and numbers, the status line, the command
// lines of the view.
import { I18N, LANG, t, localNumber, applyI18n } from "./i18n.js";
import { SECTION_RGB } from "./state.js";
import { $ } from "./dom.js";
import { wasm, ENGINE_THREADS } from "./engine.js";
import { frame, path } from "./frames.js";
import { syncSweep } from "./sweep.js";

// The engine's words in the page's language, from the keys its answers give.
/** A colour code's name (1 red … 5 blue; 6 coin, 7 card, 8 arrow). */
export const colourName = (code) => t("colour." + code);
/** A light path's words from its key ("wall", "top+2"…), else the engine's own words. */
export function pathWords(key, words) {
  const m = /^(direct|top|wall|bottom)(?:\+(\d+))?$/.exec(key || "");
  if (!m) return words;
  const k = Number(m[2] || 0);
  return t("path." + m[1]) + (k === 0 ? "" : k === 1 ? t("path.reflection.1") : t("path.reflection.k", { k }));
}
/** A text of the engine from a known set (`prefix.text`), else the text as it came. */
function known(prefix, text) { return (prefix + "." + text) in I18N.en ? t(prefix + "." + text) : text; }

const m = (x) => (x == null ? "—" : localNumber(Number(x).toFixed(4)) + " m");
const v3 = (p) => (p ? `(${p.map((x) => localNumber(x.toFixed(4))).join(LANG === "fr" ? " ; " : ", ")})` : "—");
const focus = (f) => {
  const kind = known("focus", f.kind);
  return f.distance == null ? kind : (kind ? kind + " " : "") + localNumber(Number(f.distance).toFixed(4)) + " m";
};
const escapeHtml = (s) => String(s).replace(/[&<>"]/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;" })[c]);

/** The readout's hint, before anything is clicked. */
export function showHint() {
  $("readout").innerHTML = '<p class="hint" data-i18n="readout.hint"></p>';
  applyI18n($("readout"));
  syncSweep();
}

/** The clicked ray's table: what it hit, its events, its image points and their gaps. */
export function showReadout() {
  const el = $("readout");
  const rows = [];
  const row = (a, b) => rows.push(`<tr><td>${escapeHtml(a)}</td><td>${b}</td></tr>`);
  if (path.outcome === "straw") row(t("ro.colour"), `<span class="swatch-inline" style="color:${SECTION_RGB[path.color - 1]}">■</span> ${path.color} ${escapeHtml(colourName(path.color))}`);
  else row(t("ro.outcome"), escapeHtml(path.outcome === "escaped" ? t("ro.escaped") : t("ro.dropped")));
  row(t("ro.path"), escapeHtml(pathWords(path.path_key, path.path)));
  path.events.forEach((e, i) => {
    const face = (("face." + e.face) in I18N.en) ? t("face." + e.face) : t("face.other", { face: e.face });
    row(t("ro.event", { i: i + 1 }), escapeHtml(t("ro.event.text", { event: known("event", e.event), face, angle: localNumber(e.incidence_deg.toFixed(2)), out: localNumber(e.outgoing_deg.toFixed(2)), n1: localNumber(e.n1), n2: localNumber(e.n2) })));
  });
  if (path.outcome === "straw") {
    row(t("ro.length"), m(path.path_length));
    row(t("ro.straw-point"), v3(path.straw_point));
    row(t("ro.image-point"), v3(path.image_point));
    row("s_h, s_v", `${focus(path.s_h)}${LANG === "fr" ? " ; " : ", "}${focus(path.s_v)}`);
    row(t("ro.eye-point"), v3(path.eye_point));
    row(t("ro.gap-eye"), m(path.gap_eye));
    row(t("ro.stereo-point"), v3(path.stereo_point));
    row(t("ro.gap-stereo"), m(path.gap_stereo));
  }
  el.innerHTML = `<table id="path-table">${rows.join("")}</table>`;
  syncSweep();
}

/** The status line: the frame's size, its points and the time it took. */
export function showStatus() {
  if (!frame) return;
  const h = frame.header;
  const where = !wasm ? t("status.server", { ms: h.ms.toFixed(0) })
    : ENGINE_THREADS.why ? t("status.wasm-one", { ms: frame.engineMs.toFixed(0), why: t(ENGINE_THREADS.why) })
      : t("status.wasm", { ms: frame.engineMs.toFixed(0), threads: ENGINE_THREADS.threads });
  $("status").textContent = t("status.frame", { w: h.width, h: h.height, n: h.n, rays: h.rays_traced, fov: localNumber(h.fov_deg.toFixed(1)), where });
  // Sizes that look like centimetres written as metres: said, as the command line says them.
  const hints = h.hints || [];
  $("notice").textContent = hints.map((x) => t("hint.centimetres", { key: x.key, value: localNumber(x.value), metres: localNumber(x.metres) })).join("\n");
  $("notice").hidden = hints.length === 0;
}

/** The command lines giving this view, when they are shown. */
export function showCommands() {
  if (!frame) return;
  const c = $("commands");
  c.innerHTML = "<b data-i18n=\"commands.heading\"></b><code id=\"cmd-simulate\"></code><code id=\"cmd-render\"></code>";
  applyI18n(c);
  $("cmd-simulate").textContent = frame.header.simulate;
  $("cmd-render").textContent = frame.header.render;
}
$("show-commands").addEventListener("click", () => { const c = $("commands"); c.hidden = !c.hidden; showCommands(); });

