// bentstraw explore: the page's texts, in English and in French. Every text the page itself
// shows is here (the engine's own texts — its error messages, the gallery's titles, the command
// lines — come as the engine sends them). `t(key, params)` gives the text of `key` in the page's
// language, `{name}` replaced by `params.name`; elements with `data-i18n` (their text) and
// `data-i18n-title` (their tooltip) are filled by `applyI18n()`. Loaded before explorer.js.
"use strict";

const I18N = {
  en: {
    "page.title": "bentstraw explore — the straw in the glass, live",
    "lang.title": "Language of the page",
    "scene": "Scene",
    "scene.title": "The assignment's glass, or a classic demonstration from the gallery",
    "scene.assignment": "the assignment's glass",
    "scene.file": "your scene file (scene.toml)",
    "view": "View",
    "view.title": "Reference simulations and teaching views",
    "view.choose": "— choose a view —",
    "picture": "Picture",
    "picture.title": "How the picture is made: with the reflections Fresnel's laws give, or the course's one ray per pixel",
    "mode.fresnel": "Fresnel (reflections too)",
    "mode.course": "course (one ray)",
    "backdrop": "Backdrop",
    "backdrop.title": "What is seen behind the glass",
    "backdrop.checker": "checkerboard",
    "backdrop.none": "plain",
    "water": "Water",
    "water.title": "Water height he, 0 to 0.2 m",
    "n.title": "Refractive index of the water, 1 to 2.5",
    "events": "events",
    "events.title": "Most events (refractions and total reflections) per ray",
    "copy-link": "Copy link",
    "copy-link.title": "Copy an address that restores this view",
    "png.title": "Save the picture (the file bentstraw render writes)",
    "csv.title": "Save the image points (the file bentstraw simulate writes)",
    "ply.title": "Save the image points as a 3D cloud (PLY)",
    "commands": "Commands",
    "commands.title": "Show the command lines that reproduce this view",
    "commands.heading": "Reproduce this view on the command line",
    "fullscreen": "Full screen",
    "fullscreen.leave": "Leave full screen",
    "fullscreen.title": "Show the picture on the whole screen (for a projector)",
    "eye.heading": "What the eye sees",
    "eye.hint": "drag to move the eye round the glass · wheel: nearer/farther · click: the light's path",
    "eye.hint.touch": "drag sideways to move the eye round the glass · pinch: nearer/farther · tap: the light's path",
    "cloud.heading": "Where the straw appears",
    "cloud.hint": "drag to turn · wheel to zoom · click a point",
    "cloud.hint.touch": "drag sideways to turn · pinch to zoom · tap a point",
    "show.course": "course",
    "show.course.title": "The image points of the course's law",
    "show.eye": "eye model",
    "show.eye.title": "Where one eye with a small pupil sees each point",
    "show.stereo": "stereo model",
    "show.stereo.title": "Where two eyes see each point",
    "color-by": "colour by",
    "color.section": "section",
    "color.path": "light path",
    "map.heading": "Map",
    "map.hint": "drag the eye (●) or, from above, the straw · wheel: nearer/farther",
    "map.hint.touch": "drag the eye (●) or, from above, the straw, starting sideways · pinch: nearer/farther",
    "map.side": "side",
    "map.top": "from above (x →, y ↑)",
    "readout.heading": "The light's path",
    "readout.hint": "Click the picture or a point of the cloud.",
    "readout.hint.touch": "Tap the picture or a point of the cloud.",
    "ro.colour": "colour",
    "ro.outcome": "outcome",
    "ro.escaped": "the ray misses the straw",
    "ro.dropped": "dropped: it would need more events than allowed",
    "ro.path": "light path",
    "ro.event": "event {i}",
    "ro.event.text": "{event} {face}, incidence {angle}° → {out}°, n {n1} → {n2}",
    "ro.length": "path length L",
    "ro.straw-point": "straw point",
    "ro.image-point": "image point (course)",
    "ro.eye-point": "eye model point",
    "ro.gap-eye": "gap course–eye",
    "ro.stereo-point": "stereo model point",
    "ro.gap-stereo": "gap course–stereo",
    "event.refraction": "refraction",
    "event.total reflection": "total reflection",
    "face.top surface": "at the top surface",
    "face.bottom": "at the bottom",
    "face.surface between layers": "at the surface between layers",
    "face.wall": "at the wall",
    "face.other": "at the {face}",
    "focus.in_front": "",
    "focus.at_infinity": "at infinity",
    "focus.behind_eye": "behind the eye",
    "focus.unresolved": "unresolved",
    "path.direct": "direct (through air)",
    "path.top": "through the surface",
    "path.wall": "through the side wall",
    "path.bottom": "through the bottom",
    "path.reflection.1": ", 1 total reflection",
    "path.reflection.k": ", {k} total reflections",
    "colour.1": "red",
    "colour.2": "orange",
    "colour.3": "magenta",
    "colour.4": "green",
    "colour.5": "blue",
    "colour.6": "coin",
    "colour.7": "card",
    "colour.8": "arrow",
    "legend.eye": "eye model: faint, smaller",
    "legend.stereo": "stereo model: faint, smaller",
    "legend.more": "{n}, more coming",
    "mark.image": "image",
    "mark.eye": "eye",
    "mark.stereo": "stereo",
    "status.frame": "{w}x{h} picture, {n} image points from {rays} rays, field of view {fov}°, {where}",
    "status.wasm": "{ms} ms in this page (WebAssembly)",
    "status.server": "{ms} ms on the server",
    "status.copied": "link copied: {link}",
    "prompt.copy": "Copy this link:",
    "edit.heading": "Scene file",
    "edit.title": "The scene as the text of a scene file (scene.toml): edit it, open one, save it",
    "edit.hint": "Edit the scene's text: the view follows a moment after you stop typing.",
    "edit.text.title": "The scene file of this view (TOML); bentstraw simulate --scene reads the same text",
    "edit.undo": "Undo",
    "edit.undo.title": "Back to the previous scene (Ctrl+Z outside the text box)",
    "edit.redo": "Redo",
    "edit.redo.title": "Forward to the next scene (Ctrl+Shift+Z outside the text box)",
    "edit.open": "Open…",
    "edit.open.title": "Open a scene file (.toml, at most 1 MB) from this computer",
    "edit.save": "Save",
    "edit.save.title": "Save the text of the box as scene.toml",
    "edit.too-large": "{name} is larger than 1 MB: it was not opened",
    "edit.unreadable": "{name} cannot be read: {message}",
    "error.link-file": "this link's scene file cannot be read: {message}",
    "error.packed-size": "the packed file is larger than 1 MB",
    "error.file-size": "the scene file is larger than 1 MB",
    "error.no-answer": "the server does not answer: {message}",
    "error.engine-stopped": "the engine stopped",
    "error.engine-broken": "internal error while computing this view",
    "preset.0": "Reference 1: eye at (0, 0.1, 0.1)",
    "preset.1": "Reference 2: eye at (0.1, 0, 0.1)",
    "preset.2": "Reference 3: eye above, (0.1, 0, 0.3)",
    "preset.3": "Reference 4: eye below, (0.1, 0, -0.1)",
    "preset.4": "The broken straw, from the side at 0.3 m",
    "preset.5": "Straw on the axis: n times wider",
    "preset.6": "The straw vanishing near the wall",
    "preset.7": "From above",
    "preset.8": "From below",
    "preset.9": "Displaced pieces made by total reflection",
  },
  fr: {
    "page.title": "bentstraw explore — la paille dans le verre, en direct",
    "lang.title": "Langue de la page",
    "scene": "Scène",
    "scene.title": "Le verre de l'énoncé, ou une expérience classique de la galerie",
    "scene.assignment": "le verre de l'énoncé",
    "scene.file": "votre fichier de scène (scene.toml)",
    "view": "Vue",
    "view.title": "Simulations de référence et vues pour l'enseignement",
    "view.choose": "— choisir une vue —",
    "picture": "Image",
    "picture.title": "Comment l'image est calculée : avec les reflets que donnent les lois de Fresnel, ou un seul rayon par pixel comme dans le cours",
    "mode.fresnel": "Fresnel (avec les reflets)",
    "mode.course": "cours (un seul rayon)",
    "backdrop": "Fond",
    "backdrop.title": "Ce que l'on voit derrière le verre",
    "backdrop.checker": "damier",
    "backdrop.none": "uni",
    "water": "Eau",
    "water.title": "Hauteur d'eau he, de 0 à 0,2 m",
    "n.title": "Indice de réfraction de l'eau, de 1 à 2,5",
    "events": "événements",
    "events.title": "Nombre maximal d'événements (réfractions et réflexions totales) par rayon",
    "copy-link": "Copier le lien",
    "copy-link.title": "Copier une adresse qui rétablit cette vue",
    "png.title": "Enregistrer l'image (le fichier qu'écrit bentstraw render)",
    "csv.title": "Enregistrer les points images (le fichier qu'écrit bentstraw simulate)",
    "ply.title": "Enregistrer les points images en nuage 3D (PLY)",
    "commands": "Commandes",
    "commands.title": "Afficher les lignes de commande qui reproduisent cette vue",
    "commands.heading": "Reproduire cette vue en ligne de commande",
    "fullscreen": "Plein écran",
    "fullscreen.leave": "Quitter le plein écran",
    "fullscreen.title": "Afficher l'image sur tout l'écran (pour un vidéoprojecteur)",
    "eye.heading": "Ce que voit l'œil",
    "eye.hint": "faire glisser pour déplacer l'œil autour du verre · molette : plus près/plus loin · clic : le chemin de la lumière",
    "eye.hint.touch": "glisser latéralement pour déplacer l'œil autour du verre · pincer : plus près/plus loin · toucher : le chemin de la lumière",
    "cloud.heading": "Où la paille apparaît",
    "cloud.hint": "faire glisser pour tourner · molette pour zoomer · cliquer sur un point",
    "cloud.hint.touch": "glisser latéralement pour tourner · pincer pour zoomer · toucher un point",
    "show.course": "cours",
    "show.course.title": "Les points images selon la loi du cours",
    "show.eye": "modèle de l'œil",
    "show.eye.title": "Où un œil à petite pupille voit chaque point",
    "show.stereo": "modèle stéréo",
    "show.stereo.title": "Où deux yeux voient chaque point",
    "color-by": "couleur selon",
    "color.section": "le tronçon",
    "color.path": "le chemin de la lumière",
    "map.heading": "Schéma",
    "map.hint": "faire glisser l'œil (●) ou, vue de dessus, la paille · molette : plus près/plus loin",
    "map.hint.touch": "glisser l'œil (●) ou, vue de dessus, la paille, en partant latéralement · pincer : plus près/plus loin",
    "map.side": "de côté",
    "map.top": "vue de dessus (x →, y ↑)",
    "readout.heading": "Le chemin de la lumière",
    "readout.hint": "Cliquer sur l'image ou sur un point du nuage.",
    "readout.hint.touch": "Toucher l'image ou un point du nuage.",
    "ro.colour": "couleur",
    "ro.outcome": "résultat",
    "ro.escaped": "le rayon n'atteint pas la paille",
    "ro.dropped": "abandonné : il lui faudrait plus d'événements que permis",
    "ro.path": "chemin de la lumière",
    "ro.event": "événement {i}",
    "ro.event.text": "{event} {face}, angle d'incidence {angle}° → {out}°, n {n1} → {n2}",
    "ro.length": "longueur du chemin L",
    "ro.straw-point": "point de la paille",
    "ro.image-point": "point image (cours)",
    "ro.eye-point": "point du modèle de l'œil",
    "ro.gap-eye": "écart cours–œil",
    "ro.stereo-point": "point du modèle stéréo",
    "ro.gap-stereo": "écart cours–stéréo",
    "event.refraction": "réfraction",
    "event.total reflection": "réflexion totale",
    "face.top surface": "à la surface libre",
    "face.bottom": "au fond",
    "face.surface between layers": "à la surface entre deux liquides",
    "face.wall": "à la paroi",
    "face.other": "sur : {face}",
    "focus.in_front": "",
    "focus.at_infinity": "à l'infini",
    "focus.behind_eye": "derrière l'œil",
    "focus.unresolved": "indéterminé",
    "path.direct": "direct (dans l'air)",
    "path.top": "par la surface libre",
    "path.wall": "par la paroi latérale",
    "path.bottom": "par le fond",
    "path.reflection.1": ", 1 réflexion totale",
    "path.reflection.k": ", {k} réflexions totales",
    "colour.1": "rouge",
    "colour.2": "orange",
    "colour.3": "magenta",
    "colour.4": "vert",
    "colour.5": "bleu",
    "colour.6": "pièce",
    "colour.7": "carte",
    "colour.8": "flèche",
    "legend.eye": "modèle de l'œil : pâle, plus petit",
    "legend.stereo": "modèle stéréo : pâle, plus petit",
    "legend.more": "{n}, d'autres arrivent",
    "mark.image": "image",
    "mark.eye": "œil",
    "mark.stereo": "stéréo",
    "status.frame": "image {w}×{h}, {n} points images issus de {rays} rayons, champ de vision {fov}°, {where}",
    "status.wasm": "{ms} ms dans cette page (WebAssembly)",
    "status.server": "{ms} ms sur le serveur",
    "status.copied": "lien copié : {link}",
    "prompt.copy": "Copiez ce lien :",
    "edit.heading": "Fichier de scène",
    "edit.title": "La scène sous forme de fichier de scène (scene.toml) : modifiez-le, ouvrez-en un, enregistrez-le",
    "edit.hint": "Modifiez le texte de la scène : la vue suit un instant après la dernière frappe.",
    "edit.text.title": "Le fichier de scène de cette vue (TOML) ; bentstraw simulate --scene lit le même texte",
    "edit.undo": "Annuler",
    "edit.undo.title": "Revenir à la scène précédente (Ctrl+Z hors de la zone de texte)",
    "edit.redo": "Rétablir",
    "edit.redo.title": "Aller à la scène suivante (Ctrl+Maj+Z hors de la zone de texte)",
    "edit.open": "Ouvrir…",
    "edit.open.title": "Ouvrir un fichier de scène (.toml, 1 Mo au plus) de cet ordinateur",
    "edit.save": "Enregistrer",
    "edit.save.title": "Enregistrer le texte de la zone sous scene.toml",
    "edit.too-large": "{name} dépasse 1 Mo : il n'a pas été ouvert",
    "edit.unreadable": "{name} est illisible : {message}",
    "error.link-file": "le fichier de scène de ce lien est illisible : {message}",
    "error.packed-size": "le fichier compressé dépasse 1 Mo",
    "error.file-size": "le fichier de scène dépasse 1 Mo",
    "error.no-answer": "le serveur ne répond pas : {message}",
    "error.engine-stopped": "le moteur de calcul s'est arrêté",
    "error.engine-broken": "erreur interne pendant le calcul de cette vue",
    "preset.0": "Référence 1 : œil en (0 ; 0,1 ; 0,1)",
    "preset.1": "Référence 2 : œil en (0,1 ; 0 ; 0,1)",
    "preset.2": "Référence 3 : œil au-dessus, (0,1 ; 0 ; 0,3)",
    "preset.3": "Référence 4 : œil en dessous, (0,1 ; 0 ; −0,1)",
    "preset.4": "La paille brisée, vue de côté à 0,3 m",
    "preset.5": "Paille sur l'axe : n fois plus large",
    "preset.6": "La paille qui disparaît près de la paroi",
    "preset.7": "Vue de dessus",
    "preset.8": "Vue de dessous",
    "preset.9": "Morceaux déplacés par réflexion totale",
  },
};

/** The languages the page speaks. */
const LANGS = Object.keys(I18N);
const LANG_KEY = "bentstraw-lang";

/** The page's language: the address's `lang=`, else the one chosen before, else the browser's. */
function initialLang() {
  const asked = new URLSearchParams(location.hash.slice(1)).get("lang");
  if (LANGS.includes(asked)) return asked;
  try {
    const kept = localStorage.getItem(LANG_KEY);
    if (LANGS.includes(kept)) return kept;
  } catch (_) { /* no storage (a private window, a file): the browser's language */ }
  const wanted = navigator.languages && navigator.languages.length ? navigator.languages : [navigator.language || "en"];
  return String(wanted[0] || "en").toLowerCase().startsWith("fr") ? "fr" : "en";
}
let LANG = initialLang();

/** Whether the page is used with a finger (a phone, a tablet): its hints name touch gestures. */
const TOUCH = window.matchMedia("(pointer: coarse)").matches;

/** The text of `key` in the page's language, `{name}` replaced by `params.name`. */
function t(key, params) {
  let text = I18N[LANG][key];
  if (text === undefined) text = I18N.en[key];
  if (text === undefined) return key;
  if (params) text = text.replace(/\{(\w+)\}/g, (all, k) => (k in params ? String(params[k]) : all));
  return text;
}

/** `key`'s touch-screen variant (`key.touch`) on a touch screen, if there is one. */
const touchKey = (key) => (TOUCH && (key + ".touch") in I18N.en ? key + ".touch" : key);

/** A number's text in the page's language (a decimal comma in French). */
function localNumber(text) { return LANG === "fr" ? String(text).replace(/\./g, ",") : String(text); }

/** Fills the texts of the elements under `root` marked with `data-i18n` / `data-i18n-title`. */
function applyI18n(root) {
  const r = root || document;
  for (const el of r.querySelectorAll("[data-i18n]")) el.textContent = t(touchKey(el.dataset.i18n));
  for (const el of r.querySelectorAll("[data-i18n-title]")) el.title = t(el.dataset.i18nTitle);
  if (!root) {
    document.documentElement.lang = LANG;
    document.title = t("page.title");
  }
}

/** Switches the page to `lang` and remembers the choice. */
function setLang(lang, remember) {
  if (!LANGS.includes(lang)) return false;
  LANG = lang;
  if (remember) { try { localStorage.setItem(LANG_KEY, lang); } catch (_) { /* not remembered */ } }
  applyI18n();
  return true;
}

applyI18n();
