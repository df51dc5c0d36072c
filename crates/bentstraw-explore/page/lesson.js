// The scene's lesson, shown in its own panel: its title, what it shows and why, and the questions
// a teacher would ask, in the page's language (a scene file holds them in English and French;
// one written in only one language shows that one).
import { LANG } from "./i18n.js";
import { state, ASSIGNMENT_LESSON } from "./state.js";
import { $ } from "./dom.js";
import { currentSketch, sceneLines } from "./sketch.js";

/** A lesson (`{en, fr}`) in the page's language, else the other; null without one. */
export function inLanguage(lesson) {
  if (!lesson) return null;
  return (LANG === "fr" ? lesson.fr || lesson.en : lesson.en || lesson.fr) || null;
}

/** The current scene's lesson: the assignment's, or the scene file's once its sketch has come. */
function currentLesson() {
  if (!state.scene && !state.file) return ASSIGNMENT_LESSON;
  sceneLines(); // asks for the sketch if it has not come
  const sc = currentSketch();
  return sc ? sc.lesson : null;
}

let shown = null;
/** The lesson panel showing the current scene's lesson (hidden when it has none); opened again
 * when the scene changes, so that a new scene starts with what it teaches, unless the objects or
 * the scene file are open. */
export function showLesson() {
  const l = inLanguage(currentLesson());
  const panel = $("lesson");
  panel.hidden = !l;
  if (!l) { shown = null; return; }
  const key = JSON.stringify(l);
  if (key === shown) return;
  const first = shown === null || panel.dataset.scene !== (state.file ? "file" : state.scene);
  shown = key;
  panel.dataset.scene = state.file ? "file" : state.scene;
  $("lesson-title").textContent = l.title;
  $("lesson-text").textContent = l.text;
  $("lesson-questions").replaceChildren(...l.questions.map((q) => {
    const li = document.createElement("li");
    li.textContent = q;
    return li;
  }));
  // (Not over the objects or the scene file while someone works in them.)
  if (first && !$("scene-objects").open && !$("scene-edit").open) panel.open = true;
}
