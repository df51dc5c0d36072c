// The view's state: everything the address holds, its defaults, and its codec (the engine's
// query, the address's fragment, reading either back). One table, FIELDS, names each value once:
// its key in the state, its name in queries, its default, how it is written and read; the view
// controls (controls.js) are bound from the same entries.
import { LANG, t, localNumber } from "./i18n.js";

// The view's defaults as the engine holds them (the page's HTML carries them), so that the page
// and the command line start from the same values.
const ENGINE = JSON.parse(document.getElementById("bentstraw-defaults").textContent);

// The scene's fixed sizes (the glass and the straw), for drawing outlines only.
export const GLASS_R = ENGINE.glass.radius, GLASS_H = ENGINE.glass.height;
export const STRAW_R = ENGINE.straw.radius, STRAW_H = ENGINE.straw.height;
// What the assignment's glass teaches, in English and French (a gallery scene's come with its sketch).
export const ASSIGNMENT_LESSON = ENGINE.lesson;
// A new coin's radius when the file gives none (a one-euro coin, the engine's default).
export const COIN_R = ENGINE.coin.radius;
// Colour codes 1..5 a straw's sections; in the gallery's scenes also 6 a coin, 7 a card, 8 its arrow.
export const SECTION_RGB = ["#ff0000", "#edb120", "#ff00ff", "#00cc00", "#0000ff", "#c79938", "#edebe0", "#1f1f24"];

// Their names are the texts "preset.0", "preset.1"… (i18n.js).
// The first four are the reference simulations, as the engine holds them.
export const PRESETS = [
  ...ENGINE.references.map((r) => ({ v: { observer: r.observer, straw: r.straw, he: r.waterHeight } })),
  { v: { observer: [0.3, 0, 0.16], straw: [0, 0.025], he: 0.12 } },
  { v: { observer: [0.3, 0, 0.07], straw: [0, 0], he: 0.15 } },
  { v: { observer: [0.3, 0, 0.07], straw: [0, 0.034], he: 0.15 } },
  { v: { observer: [0.03, 0, 0.45], straw: [0.02, 0.01], he: 0.15 } },
  { v: { observer: [0.06, 0, -0.25], straw: [0.02, 0.01], he: 0.15 } },
  { v: { observer: [0.1, 0, 0.3], straw: [0.02, 0.01], he: 0.2, color: "path" } },
];

/** Shortest text of a number rounded to 0.1 µm (no float noise in addresses and commands). */
export function num(x) { return String(Math.round(x * 1e7) / 1e7); }

const list = (v) => v.split(",").map(Number);
const text = { parse: (v) => v, format: (v) => v };
const number = { parse: Number, format: String };
const metres = { parse: Number, format: num };
const point = { parse: list, format: (v) => v.map(num).join(",") };

/**
 * The state's values other than its scene, in the order of the state, of queries and of the
 * address. Each entry: `prop`, its property in the state; `query`, its name in queries and
 * addresses (the command line's flag where there is one); `initial`, its default; `parse` (a
 * query's text to a value, undefined to leave the state as it is) and `format` (the value to a
 * query's text); `engine`, whether the engine's query has it (else only the address); `glass`,
 * whether only the assignment's glass takes it (a scene file has its own straws and liquids).
 * `control`, where a view control shows it: the element's `id`, the `event` it changes on, what
 * a change `redoes` ("frame": a new view; "keep-path": a new view, the clicked ray kept;
 * "cloud": the cloud redrawn), and `out` (the text of the output beside a slider, `ID-out`, if
 * any); for the glass's water, `liquid` names what its slider shows of a scene file's bottom
 * liquid instead. `optional`: written into the address only when it is not its default (and
 * back to its default when an address leaves it out).
 */
export const FIELDS = [
  // The first view shows the effect: the straw seen from the side, broken at the water's surface.
  { prop: "observer", query: "observer", initial: ENGINE.classic.observer, ...point, engine: true },
  { prop: "straw", query: "straw", initial: ENGINE.classic.straw, ...point, engine: true, glass: true },
  { prop: "he", query: "water-height", initial: ENGINE.classic.waterHeight, ...metres, engine: true, glass: true,
    control: { id: "he", event: "input", redoes: "frame", out: (v) => localNumber(num(v)) + " m", liquid: "top" } },
  { prop: "n", query: "n-water", initial: ENGINE.nWater, ...metres, engine: true, glass: true,
    control: { id: "n", event: "input", redoes: "frame", out: (v) => localNumber(num(v)), liquid: "index" } },
  // The colour of the light, where an index depends on it (a scene file's laws); sent only when
  // it is not the d line, as the command line writes it only when given.
  { prop: "wavelength", query: "wavelength", initial: ENGINE.wavelength.d, ...metres, engine: true, optional: true,
    control: { id: "wavelength", event: "input", redoes: "frame", out: (v) => localNumber(Math.round(num(v))) + " nm" } },
  { prop: "events", query: "max-events", initial: ENGINE.maxEvents, ...number, engine: true,
    control: { id: "events", event: "input", redoes: "frame", out: String } },
  { prop: "points", query: "points", initial: ENGINE.points, ...number, engine: true },
  { prop: "mode", query: "mode", initial: ENGINE.mode, ...text, engine: true,
    control: { id: "mode", event: "change", redoes: "keep-path" } },
  // White light costs a picture per band where some index depends on the wavelength.
  { prop: "light", query: "light", initial: ENGINE.light, ...text, engine: true, optional: true,
    control: { id: "light", event: "change", redoes: "keep-path" } },
  { prop: "backdrop", query: "backdrop", initial: ENGINE.backdrop, ...text, engine: true,
    control: { id: "backdrop", event: "change", redoes: "keep-path" } },
  { prop: "color", query: "color", initial: "section", ...text,
    control: { id: "color-by", event: "change", redoes: "cloud" } },
  // Shown by a checkbox each (show-course, show-eye, show-stereo).
  { prop: "models", query: "models", initial: ["course"], parse: (v) => v.split(",").filter(Boolean), format: (v) => v.join(",") },
  { prop: "view", query: "view", initial: [-35, 22, 1],
    parse: (v) => { const l = list(v); return l.length === 3 && l.every(Number.isFinite) ? l : undefined; },
    format: (v) => v.map((x) => Math.round(x * 100) / 100).join(",") },
  // "Predict, then look" (predict.js): a teacher's link opens the page with the picture hidden.
  { prop: "predict", query: "predict", initial: false, parse: (v) => v === "1", format: (v) => (v ? "1" : "0"), optional: true },
];

/** The default of the state's value `prop`. */
export const initialOf = (prop) => FIELDS.find((f) => f.prop === prop).initial;

/** A fresh copy of a default (the state's lists are changed in place by drags). */
const copy = (v) => (Array.isArray(v) ? v.slice() : v);

export const state = {
  scene: "", // "" the assignment's glass, else a scene of the gallery (scenes/NAME.toml)
  file: "", // the text of the page's own scene file (scene.toml), when it shows one
  ...Object.fromEntries(FIELDS.map((f) => [f.prop, copy(f.initial)])),
  pick: "",
};

// A scene file in the address: deflate (raw), then base64url.
export const MAX_FILE_BYTES = 1 << 20; // a scene file is at most 1 MB, as on the command line
const fileCode = { text: "", code: "" }; // the last file packed, and its code
async function streamBytes(bytes, stream) {
  const out = new Response(new Blob([bytes]).stream().pipeThrough(stream));
  return new Uint8Array(await out.arrayBuffer());
}
export async function packFile(text) {
  if (fileCode.text === text) return fileCode.code;
  const z = await streamBytes(new TextEncoder().encode(text), new CompressionStream("deflate-raw"));
  let bin = "";
  for (const b of z) bin += String.fromCharCode(b);
  fileCode.text = text;
  fileCode.code = btoa(bin).replace(/\+/g, "-").replace(/\//g, "_").replace(/=+$/, "");
  return fileCode.code;
}
async function unpackFile(code) {
  const bin = atob(code.replace(/-/g, "+").replace(/_/g, "/"));
  if (bin.length > MAX_FILE_BYTES) throw new Error(t("error.packed-size"));
  const z = Uint8Array.from(bin, (c) => c.charCodeAt(0));
  // Fed to the unpacker a kilobyte at a time, each piece's output read before the next goes in,
  // and stopped past 1 MB: deflate makes at most about a megabyte of a kilobyte, so a link cannot
  // make the page hold more than that whatever it unpacks to.
  const unpacker = new DecompressionStream("deflate-raw");
  const writer = unpacker.writable.getWriter();
  const reader = unpacker.readable.getReader();
  const feeding = (async () => {
    for (let k = 0; k < z.length; k += 1024) await writer.write(z.subarray(k, k + 1024));
    await writer.close();
  })();
  feeding.catch(() => {}); // a cancelled unpacking refuses the pieces still to come
  const parts = [];
  let size = 0;
  for (;;) {
    const { done, value } = await reader.read();
    if (done) break;
    size += value.length;
    if (size > MAX_FILE_BYTES) { reader.cancel(); throw new Error(t("error.file-size")); }
    parts.push(value);
  }
  await feeding;
  return new TextDecoder("utf-8", { fatal: true }).decode(await new Blob(parts).arrayBuffer());
}

/** The engine's query for the state (names as the command line's flags). */
export function viewQuery(s, extra) {
  const p = new URLSearchParams();
  if (s.file) p.set("scene-file", s.file);
  else if (s.scene) p.set("scene", s.scene);
  for (const f of FIELDS) {
    if (f.engine && !(f.glass && (s.scene || s.file)) && !(f.optional && s[f.prop] === f.initial)) p.set(f.query, f.format(s[f.prop]));
  }
  for (const [k, v] of Object.entries(extra || {})) p.set(k, String(v));
  return p.toString();
}

/** A checksum of `text`: FNV-1a's 32 bits, as 8 hexadecimal digits. It finds a link damaged on its
 * way (characters lost, the address cut by a chat or a learning platform), not a forgery. */
export function checksum(text) {
  let h = 2166136261;
  for (let i = 0; i < text.length; i++) h = Math.imul(h ^ text.charCodeAt(i), 16777619);
  return (h >>> 0).toString(16).padStart(8, "0");
}

/** The address's fragment for the state: a scene file travels compressed (`file`), and the whole
 * is checked by the sum that comes first (`sum`), so that a link cut anywhere is known to be. */
export function stateHash(s) {
  const p = new URLSearchParams(viewQuery(s));
  if (s.file) { p.delete("scene-file"); p.set("file", fileCode.text === s.file ? fileCode.code : ""); }
  for (const f of FIELDS) if (!f.engine && !(f.optional && s[f.prop] === f.initial)) p.set(f.query, f.format(s[f.prop]));
  if (s.pick) p.set("pick", s.pick);
  p.set("lang", LANG);
  const rest = p.toString();
  return `#sum=${checksum(rest)}&${rest}`;
}

/** Whether an address's text is damaged: it begins with a sum (as every link the page makes) that
 * the rest does not match. Addresses written by hand (`#scene=prism`) have none, and are read. */
export function damaged(text) {
  const body = text.replace(/^[#?]/, "");
  if (!body.startsWith("sum=")) return false;
  const m = /^sum=([0-9a-f]{8})(&|$)/.exec(body);
  return !m || checksum(body.slice(m[0].length)) !== m[1];
}

/** Reads a query or fragment into the state; values are kept as text-parsed numbers, checked by
 * the engine. A compressed scene file (`file`) is unpacked before the state changes. Resolves to
 * what the state does not hold: `{ lang }` (the language the address asks for, or null),
 * `fileError` (why its scene file could not be unpacked, or null), `damaged` (its sum does not
 * match: the state is left as it was) and `eyeGiven` (whether it names an observer). */
export async function readParams(text, s) {
  const p = new URLSearchParams(text.replace(/^[#?]/, ""));
  if (damaged(text)) return { lang: p.get("lang"), fileError: null, damaged: true, eyeGiven: false };
  let file = p.get("scene-file") || "";
  if (p.get("file")) {
    try { file = await unpackFile(p.get("file")); } catch (e) { return { lang: p.get("lang"), fileError: e, damaged: false, eyeGiven: false }; }
  }
  s.scene = p.get("scene") || "";
  s.file = file;
  if (s.file) { s.scene = ""; await packFile(s.file); }
  for (const f of FIELDS) {
    if (!p.has(f.query)) { if (f.optional) s[f.prop] = copy(f.initial); continue; }
    const v = f.parse(p.get(f.query));
    if (v !== undefined) s[f.prop] = v;
  }
  s.pick = p.get("pick") || "";
  return { lang: p.get("lang"), fileError: null, damaged: false, eyeGiven: p.has("observer") };
}

/** The key of the state's scene file among the sketches: a gallery name, or the file's text. */
export const sceneKey = (s) => (s.file ? "file:" + s.file : s.scene);
/** The query naming the state's scene alone. */
export function sceneQuery(s) {
  const p = new URLSearchParams();
  if (s.file) p.set("scene-file", s.file); else p.set("scene", s.scene);
  return p.toString();
}
