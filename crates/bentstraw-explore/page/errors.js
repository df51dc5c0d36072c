// Errors in the page's language: the banner under the header, and the text of the engine's
// refusals (its broken rules, a line each, as the command line writes them in English).
import { t, localNumber, tomlWords } from "./i18n.js";
import { $ } from "./dom.js";

/** One broken rule's words alone (its range or its limit), in the page's language. */
export function ruleWords(r) {
  const params = {};
  for (const [k, v] of Object.entries(r.params || {})) params[k] = typeof v === "string" ? localNumber(v) : v.text;
  if (r.code === "toml.syntax" && params.what) params.what = tomlWords(params.what);
  return t("rule." + r.code, params);
}

/** One broken rule's line in the page's language: `key = value: rule`, its numbers written as
 * the language writes them, words from the file as they are. */
function ruleLine(r) {
  const rule = ruleWords(r);
  let line = !r.key ? rule : r.value !== null ? t("refusal.value", { key: r.key, value: localNumber(r.value), rule }) : t("refusal.key", { key: r.key, rule });
  if (r.line) line = t("refusal.line", { line: r.line, rule: line });
  return line;
}

/** A refusal's text in the page's language, a line per broken rule (the English is the command
 * line's message, to the character). */
function refusalText(f) {
  const lines = f.rules.map(ruleLine);
  const rules = lines.length === 1 ? lines[0] : [t("refusal.many", { n: lines.length }), ...lines.map((l) => "  " + l)].join("\n");
  return f.file === null ? rules : t(f.flagged ? "refusal.flagged" : "refusal.file", { file: f.file, rules });
}

/** The text of something to show: the engine's message (text, as it comes), its broken rules
 * ({ refusal }), or one of the page's own ({ key, params }); the last two in the page's language. */
export function errorText(error) {
  if (error === null) return "";
  if (typeof error === "string") return error;
  return error.refusal ? refusalText(error.refusal) : t(error.key, error.params);
}

/** A link the page refused (damaged, cut, or its scene file unreadable): said until the page is
 * given another address or the user changes the view; no scene is drawn meanwhile. */
export let linkRefusal = null;
export function refuseLink(error) {
  linkRefusal = error;
  showError(error || "");
}

/** Shows an error (see errorText), translated again when the language changes. A refused link
 * stays said when nothing else is. */
export let errorShown = "";
export function showError(error) {
  if (!error && linkRefusal) error = linkRefusal;
  errorShown = error;
  const e = $("error");
  const text = errorText(error);
  e.textContent = text;
  e.hidden = !text;
}
