//! The report's words in each language: one table, each entry a [`Text`] in English and in
//! French, picked by a [`Lang`]. The French uses the explorer's words (its page's `i18n.js`):
//! "points images", the sections' colour names, the light paths' names.
//!
//! A text with `{}` is a template: [`Lang::fill`] puts its values in, in order. Numbers keep
//! their decimal point in both languages.

use bentstraw_optics::light_path_type::LightPathType;
use bentstraw_optics::scene::{SECTION_NAMES, SECTION_NAMES_FR};
use bentstraw_optics::world::COLOR_NAMES;

/// A language of the report.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Lang {
    /// English, the default.
    #[default]
    En,
    /// French.
    Fr,
}

/// One text of the report, in each language.
#[derive(Clone, Copy, Debug)]
pub struct Text {
    /// In English.
    pub en: &'static str,
    /// In French.
    pub fr: &'static str,
}

impl Lang {
    /// The language of the code `code` (`en` or `fr`), or a refusal naming the choices.
    pub fn from_code(code: &str) -> Result<Lang, String> {
        match code {
            "en" => Ok(Lang::En),
            "fr" => Ok(Lang::Fr),
            other => Err(format!(
                "language {other:?} is not known: choose \"en\" (English) or \"fr\" (French)"
            )),
        }
    }

    /// The language's code, as `<html lang>` takes it.
    pub fn code(self) -> &'static str {
        match self {
            Lang::En => "en",
            Lang::Fr => "fr",
        }
    }

    /// `text` in this language.
    pub fn of(self, text: Text) -> &'static str {
        match self {
            Lang::En => text.en,
            Lang::Fr => text.fr,
        }
    }

    /// The template `text` in this language, each `{}` replaced by the next of `values`.
    pub fn fill(self, text: Text, values: &[&dyn std::fmt::Display]) -> String {
        let mut out = String::new();
        let mut values = values.iter();
        let mut parts = self.of(text).split("{}");
        if let Some(first) = parts.next() {
            out.push_str(first);
        }
        for part in parts {
            if let Some(v) = values.next() {
                out.push_str(&v.to_string());
            }
            out.push_str(part);
        }
        out
    }

    /// The colour name of straw section `k` (0 = red at the bottom).
    pub fn section_name(self, k: usize) -> &'static str {
        match self {
            Lang::En => SECTION_NAMES[k],
            Lang::Fr => SECTION_NAMES_FR[k],
        }
    }

    /// The name of colour code `k + 1`: the straw's five sections, then a coin, a card and the
    /// arrow on it (the explorer's words).
    pub fn colour_name(self, k: usize) -> &'static str {
        match (self, k) {
            (_, 0..=4) => self.section_name(k),
            (Lang::En, _) => COLOR_NAMES.get(k).copied().unwrap_or("?"),
            (Lang::Fr, _) => ["pièce", "carte", "flèche"]
                .get(k - 5)
                .copied()
                .unwrap_or("?"),
        }
    }

    /// A light path's name in words.
    pub fn light_path(self, kind: &LightPathType) -> String {
        match self {
            Lang::En => kind.to_string(),
            Lang::Fr => kind.french(),
        }
    }
}

/// A [`Text`] from its English and French.
const fn t(en: &'static str, fr: &'static str) -> Text {
    Text { en, fr }
}

// The page's frame.
/// The overview's heading and link.
pub const OVERVIEW: Text = t("Overview", "Vue d'ensemble");
/// A simulation's link in the navigation.
pub const NAV_SIMULATION: Text = t("Simulation {}", "Simulation {}");
/// The conventions' heading and link.
pub const CONVENTIONS: Text = t("Conventions", "Conventions");
/// The note at the top of the printed page.
pub const PRINTED_FROM: Text = t(
    "Printed from index.html: the rotatable 3D views and the data files named in the captions \
     are in the same folder.",
    "Imprimé depuis index.html : les vues 3D orientables et les fichiers de données cités dans \
     les légendes sont dans le même dossier.",
);
/// A reference's heading.
pub const REFERENCE_SIMULATION: Text = t("Reference simulation {}", "Simulation de référence {}");
/// The note naming the sections left off the paper.
pub const NOT_PRINTED: Text = t(
    "Not printed (in the report on screen, index.html): {}.",
    "Non imprimé (dans le rapport à l'écran, index.html) : {}.",
);
/// The footer: the section names, the version and the time fill it.
pub const FOOTER: Text = t(
    "<footer id=\"conventions\">\n<h2>Conventions</h2>\n\
     <p>Lengths in metres; origin at the centre of the glass's base, z up. Glass radius 0.04 m and \
     height 0.20 m; straw radius 0.005 m and height 0.25 m, five sections of 0.05 m: \
     {}.</p>\n\
     <p>A ray leaves the observer O with direction u0, is refracted or totally reflected at each \
     water face (at most the event limit), and stops on the opaque straw, of whose section it \
     takes the colour. Its image point is P = O + L·u0, with L the length of its broken path: \
     where the observer believes the straw point is. With n_water = 1 every image point lies on \
     the straw, which the checks measure.</p>\n\
     <p>Written by bentstraw {} in {} (wall clock). The simulations run side by side, \
     so each one's times are wall-clock times shared with the others.</p>\n</footer>\n</body>\n</html>\n",
    "<footer id=\"conventions\">\n<h2>Conventions</h2>\n\
     <p>Longueurs en mètres ; origine au centre du fond du verre, z vers le haut. Verre de rayon \
     0.04 m et de hauteur 0.20 m ; paille de rayon 0.005 m et de hauteur 0.25 m, cinq tronçons de \
     0.05 m : {}.</p>\n\
     <p>Un rayon quitte l'observateur O dans la direction u0, est réfracté ou totalement réfléchi \
     à chaque face de l'eau (au plus le nombre maximal d'événements), et s'arrête sur la paille \
     opaque, dont il prend la couleur du tronçon. Son point image est P = O + L·u0, où L est la \
     longueur de son chemin brisé : là où l'observateur croit voir le point de la paille. Avec \
     n_water = 1 chaque point image est sur la paille, ce que mesurent les vérifications.</p>\n\
     <p>Écrit par bentstraw {} en {} (temps réel). Les simulations tournent en parallèle : les \
     durées de chacune sont des temps réels partagés avec les autres.</p>\n</footer>\n</body>\n</html>\n",
);
/// The overview's column headings, before the sections' colours.
pub const OVERVIEW_HEAD: [Text; 5] = [
    t("simulation", "simulation"),
    t("n_water", "n_water"),
    t("rays", "rayons"),
    t("points", "points"),
    t("hit ratio", "taux d'atteinte"),
];
/// The overview's column headings after the sections' colours.
pub const OVERVIEW_TAIL: [Text; 2] = [t("time", "durée"), t("check", "vérification")];
/// A simulation's numbers.
pub const FACTS: [Text; 3] = [
    t("rays traced", "rayons tracés"),
    t("image points", "points images"),
    t("hit ratio", "taux d'atteinte"),
];
/// Before what `bentstraw check` says of a simulation's points.
pub const CHECKED_AS_SOLUTION: Text = t(
    "Checked as a solution (<code>bentstraw check</code>): ",
    "Vérifié comme une solution (<code>bentstraw check</code>) : ",
);
/// Before a simulation's timings.
pub const TIME: Text = t("Time: ", "Durée : ");
/// A picture that could not be written.
pub const NOT_WRITTEN_FIGURE: Text = t(
    "{} could not be written: {}",
    "{} n'a pas pu être écrit : {}",
);
/// A companion file that could not be written.
pub const NOT_WRITTEN_LINK: Text = t("{} not written ({})", "{} non écrit ({})");

// The report's text.
/// The page's title.
pub const TITLE: Text = t(
    "bentstraw: why a straw in a glass of water looks broken",
    "bentstraw : pourquoi une paille dans un verre d'eau paraît brisée",
);
/// Under the title; the number of points fills it.
pub const SUBTITLE: Text = t(
    "A short lab report. Rays are traced from the observer's eye through the water \
     (Snell–Descartes refraction and total reflection) to a five-colour straw, and each \
     ray that reaches it gives an image point: where the observer believes that piece of \
     straw is. Four reference simulations, each also with water of index 1 (the image must \
     then lie on the straw) and 1.05; at least {} image points each.",
    "Un court compte rendu de TP. Des rayons sont tracés depuis l'œil de l'observateur à travers \
     l'eau (réfraction de Snell–Descartes et réflexion totale) jusqu'à une paille de cinq \
     couleurs, et chaque rayon qui l'atteint donne un point image : là où l'observateur croit \
     voir ce morceau de paille. Quatre simulations de référence, chacune aussi avec une eau \
     d'indice 1 (l'image doit alors être sur la paille) et 1.05 ; au moins {} points images \
     chacune.",
);
/// What the classic figure shows.
pub const CLOUD_CAPTION: Text = t(
    "The image points in their section colours, the water as a wireframe \
     and the observer (black dot): a front view from the observer's side, \
     a side view with the observer to the right, and the view from above.",
    "Les points images aux couleurs de leur tronçon, l'eau en fil de fer et l'observateur (point \
     noir) : une vue de face du côté de l'observateur, une vue de côté avec l'observateur à \
     droite, et la vue de dessus.",
);
/// The link to a simulation's rotatable view.
pub const ROTATABLE_VIEW: Text = t("rotatable 3D view", "vue 3D orientable");
/// The link to a simulation's points.
pub const POINTS_FILE: Text = t("points (CSV, gzip)", "points (CSV, gzip)");
/// The timings' names.
pub const TRACING: Text = t("tracing", "tracé");
/// The timings' names.
pub const WRITING_FILES: Text = t("writing files", "écriture des fichiers");
/// The timings' names.
pub const OBSERVERS_PICTURE: Text = t("observer's picture", "image de l'observateur");
/// The timings' names.
pub const RAY_DIAGRAM: Text = t("ray diagram", "schéma des rayons");
/// The timings' names.
pub const EYE_AND_STEREO: Text = t("eye and stereo models", "modèles de l'œil et stéréo");
/// A simulation's image points.
pub const IMAGE_POINTS_SECTION: Text = t(
    "Virtual image points (course convention, P = O + L·u0)",
    "Points images virtuels (convention du cours, P = O + L·u0)",
);
/// The observer's pictures.
pub const OBSERVER_SECTION: Text = t(
    "What the observer sees (Fresnel picture)",
    "Ce que voit l'observateur (image de Fresnel)",
);
/// The observer's picture.
pub const OBSERVER_CAPTION: Text = t(
    "What the observer sees: a pinhole camera at the observer, Fresnel reflection and \
     refraction at every water face, a checkerboard wall and floor behind the glass.",
    "Ce que voit l'observateur : un sténopé à la place de l'observateur, réflexion et \
     réfraction de Fresnel à chaque face de l'eau, un mur et un sol en damier derrière le verre.",
);
/// The image points through the observer's camera.
pub const SPLAT_CAPTION: Text = t(
    "The course's image points seen through the same camera: each lies on the ray that \
     shows it, so the two pictures agree on where each colour appears.",
    "Les points images du cours vus par la même caméra : chacun est sur le rayon qui le montre, \
     si bien que les deux images s'accordent sur l'endroit où apparaît chaque couleur.",
);
/// A simulation's ray diagram's title; the heading and the scene fill it.
pub const RAY_DIAGRAM_TITLE: Text = t("{} ray diagram: {}", "{}, schéma des rayons : {}");
/// A simulation's ray diagram.
pub const RAYS_CAPTION: Text = t(
    "About forty of the rays, each drawn as its broken path from the eye (black dot) through \
     the water's faces to the straw, coloured by the kind of light path; rings mark \
     refractions, crosses total reflections, and the dashed line runs from the eye straight \
     to the ray's image point. Side view in the vertical plane through the glass's axis and \
     the observer (the observer to the right), and top view.",
    "Une quarantaine de rayons, chacun tracé comme son chemin brisé depuis l'œil (point noir) à \
     travers les faces de l'eau jusqu'à la paille, colorié selon le chemin de la lumière ; les \
     cercles marquent les réfractions, les croix les réflexions totales, et le tireté va en \
     ligne droite de l'œil au point image du rayon. Vue de côté dans le plan vertical passant \
     par l'axe du verre et l'observateur (l'observateur à droite), et vue de dessus.",
);
/// The ray diagram's section.
pub const RAYS_SECTION: Text = t(
    "Which light path makes which piece (ray diagram)",
    "Quel chemin de la lumière fait quel morceau (schéma des rayons)",
);
/// Under the ray diagram; the shares fill it.
pub const RAYS_NOTE: Text = t(
    "Image points by light path: {}. Pieces of the image far from the straw, even \
     outside the glass, come from light totally reflected inside the water: the eye, \
     looking along the first straight piece of the ray, places the straw as far away as \
     the light really travelled.",
    "Points images par chemin de la lumière : {}. Les morceaux de l'image loin de la paille, \
     même hors du verre, viennent de lumière totalement réfléchie dans l'eau : l'œil, qui \
     regarde le long du premier morceau droit du rayon, place la paille aussi loin que la \
     lumière a réellement voyagé.",
);
/// The realistic view.
pub const VIEW_CAPTION: Text = t(
    "What an eye 30 cm from the glass sees (bentstraw render --observer 0.3,0,0.22 --straw \
     -0.02,0.02 --water-height 0.15): below the water's surface the straw is shifted sideways and \
     looks wider; above it, it is seen straight.",
    "Ce que voit un œil à 30 cm du verre (bentstraw render --observer 0.3,0,0.22 --straw \
     -0.02,0.02 --water-height 0.15) : sous la surface de l'eau la paille est décalée de côté et \
     paraît plus large ; au-dessus, on la voit droite.",
);
/// The method's ray diagram.
pub const INTRO_RAYS_CAPTION: Text = t(
    "The same view as a ray diagram: each ray's broken path from the eye to the straw, and \
     the dashed straight line along which the eye looks. The eye places each piece of straw \
     on that line, as far away as the light travelled.",
    "La même vue en schéma des rayons : le chemin brisé de chaque rayon de l'œil à la paille, \
     et la droite en tireté le long de laquelle l'œil regarde. L'œil place chaque morceau de \
     paille sur cette droite, aussi loin que la lumière a voyagé.",
);
/// A ray diagram's title; the scene fills it.
pub const RAY_DIAGRAM_OF: Text = t("Ray diagram: {}", "Schéma des rayons : {}");
/// The opening section.
pub const BROKEN_STRAW: Text = t("The broken straw", "La paille brisée");
/// The method's section.
pub const METHOD: Text = t("Method", "Méthode");
/// The method.
pub const METHOD_NOTES: [Text; 2] = [
    t(
        "A ray leaves the observer's eye O with direction u0 and goes straight until it \
         meets a face of the water (its side, its surface, its bottom) or the straw. At a \
         water face it is refracted by Snell–Descartes, n1 sin θ1 = n2 sin θ2, or totally \
         reflected when no refracted ray exists (from water to air beyond 48.6°); at most \
         ten such events. A ray that meets the opaque straw stops there and takes the \
         colour of that section. Its image point is P = O + L·u0, with L the length of its \
         broken path: where the eye, looking along u0, believes the light came from. \
         Rays are spread evenly over the directions in which the straw can be seen.",
        "Un rayon quitte l'œil O de l'observateur dans la direction u0 et va tout droit jusqu'à \
         rencontrer une face de l'eau (sa paroi, sa surface libre, son fond) ou la paille. À une \
         face de l'eau il est réfracté selon Snell–Descartes, n1 sin θ1 = n2 sin θ2, ou \
         totalement réfléchi quand aucun rayon réfracté n'existe (de l'eau vers l'air au-delà de \
         48.6°) ; au plus dix tels événements. Un rayon qui rencontre la paille opaque s'y arrête \
         et prend la couleur de ce tronçon. Son point image est P = O + L·u0, où L est la \
         longueur de son chemin brisé : là d'où l'œil, regardant le long de u0, croit que vient \
         la lumière. Les rayons sont répartis uniformément sur les directions où l'on peut voir \
         la paille.",
    ),
    t(
        "Every image point is checked: with water of index 1 the points must lie on the \
         straw; and every simulation's points are re-traced one by one by bentstraw check, \
         the tool a student uses on their own program's output.",
        "Chaque point image est vérifié : avec une eau d'indice 1 les points doivent être sur la \
         paille ; et les points de chaque simulation sont retracés un à un par bentstraw check, \
         l'outil qu'un étudiant utilise sur les résultats de son propre programme.",
    ),
];
/// A reference in the validation: its number fills it.
pub const VALIDATION_SERIES: Text = t("simulation {}", "simulation {}");
/// The validation figure.
pub const VALIDATION_CAPTION: Text = t(
    "For the image points seen through the water, the largest (solid) and median (dashed) \
     distance from the straw's surface, as the water's index goes from 1 to 1.333, log scale.",
    "Pour les points images vus à travers l'eau, la plus grande distance (trait plein) et la \
     distance médiane (tireté) à la surface de la paille, quand l'indice de l'eau va de 1 à \
     1.333, en échelle logarithmique.",
);
/// The validation table's columns: a series' label fills each.
pub const LARGEST_M: Text = t("{}: largest (m)", "{} : plus grande (m)");
/// The validation table's columns: a series' label fills each.
pub const MEDIAN_M: Text = t("{}: median (m)", "{} : médiane (m)");
/// The validation's section.
pub const VALIDATION: Text = t("Validation", "Validation");
/// Under the validation; the number of points fills it.
pub const VALIDATION_NOTE: Text = t(
    "With index 1 the water bends nothing, and every image point lies on the straw to \
     rounding (about 1e-16 m); as soon as the index grows, the points seen through the \
     water leave the straw, by millimetres at first and by centimetres at 1.333. The \
     points seen straight through air are left out: they lie on the straw whatever the \
     water. {} image points per simulation and index.",
    "Avec l'indice 1 l'eau ne dévie rien, et chaque point image est sur la paille à l'arrondi \
     près (environ 1e-16 m) ; dès que l'indice croît, les points vus à travers l'eau quittent la \
     paille, de quelques millimètres d'abord et de quelques centimètres à 1.333. Les points vus \
     directement dans l'air sont laissés de côté : ils sont sur la paille quelle que soit l'eau. \
     {} points images par simulation et par indice.",
);
/// The limits' section.
pub const LIMITS: Text = t("Limits", "Limites");
/// The limits.
pub const LIMITS_NOTE: Text = t(
    "The image point P = O + L·u0 is the course's convention, not what an eye measures: \
     the eye and stereo models above say where one eye with a small pupil, and two \
     eyes, see each point. The glass has walls of no thickness and the index of air; \
     the straw is opaque and its surface does not reflect; light is traced for one \
     colour (no dispersion). The pictures' Fresnel mode follows at most 2048 ray \
     segments per ray from the eye.",
    "Le point image P = O + L·u0 est la convention du cours, pas ce que mesure un œil : les \
     modèles de l'œil et stéréo ci-dessus disent où un œil à petite pupille, et deux yeux, \
     voient chaque point. Le verre a des parois sans épaisseur et l'indice de l'air ; la paille \
     est opaque et sa surface ne réfléchit pas ; la lumière est tracée pour une seule couleur \
     (pas de dispersion). Le mode Fresnel des images suit au plus 2048 segments par rayon issu \
     de l'œil.",
);
/// The models' comparison's title; the heading fills it.
pub const WHERE_IT_APPEARS: Text = t("{}: where the straw appears", "{} : où la paille apparaît");
/// The models' comparison.
pub const MODELS_CAPTION: Text = t(
    "The same straw points placed by the three models, seen from the same side and scale.",
    "Les mêmes points de la paille placés par les trois modèles, vus du même côté et à la même \
     échelle.",
);
/// The gap plot.
pub const GAP_CAPTION: Text = t(
    "Distance between the course's image point and the eye model's (and the stereo model's) \
     point of the same straw point, against the height of that straw point.",
    "Distance entre le point image du cours et le point du modèle de l'œil (et du modèle \
     stéréo) d'un même point de la paille, en fonction de la hauteur de ce point de la paille.",
);
/// The gap plot's title; the heading fills it.
pub const GAP_TITLE: Text = t(
    "{}: distance from the course's image point to the eye's and the stereo point",
    "{} : distance du point image du cours au point de l'œil et au point stéréo",
);
/// The models' section.
pub const MODELS_SECTION: Text = t(
    "Where the straw really appears: course, eye and stereo models",
    "Où la paille apparaît vraiment : cours, modèle de l'œil et modèle stéréo",
);
/// The eye model's numbers: placed, of, unplaced, median, largest.
pub const EYE_NOTE: Text = t(
    "Eye model: {} of {} points placed at (s_h + s_v)/2 along their ray; {} without a \
     position (a focus unresolved, at infinity or behind the eye). Gap to the course's point: \
     median {} mm, largest {} mm.",
    "Modèle de l'œil : {} points sur {} placés en (s_h + s_v)/2 le long de leur rayon ; {} sans \
     position (un foyer indéterminé, à l'infini ou derrière l'œil). Écart au point du cours : \
     médiane {} mm, plus grand {} mm.",
);
/// The stereo model's numbers.
pub const STEREO_NOTE: Text = t(
    "Stereo model: {} points seen by both eyes and triangulated, {} seen by one eye only.",
    "Modèle stéréo : {} points vus des deux yeux et triangulés, {} vus d'un seul œil.",
);
/// How to get each model's points; the flags fill it.
pub const MODELS_FILE_NOTE: Text = t(
    "Each model's points, as a file: bentstraw simulate {} --image-model eye (or \
     stereo) --output points.csv.",
    "Les points de chaque modèle, en fichier : bentstraw simulate {} --image-model eye (ou \
     stereo) --output points.csv.",
);
/// A reference's heading.
pub const SIMULATION: Text = t("Simulation {}", "Simulation {}");
/// An index check's heading.
pub const SIMULATION_CHECK: Text = t(
    "Simulation {}, check n_water = {}",
    "Simulation {}, vérification n_water = {}",
);
/// The inputs' labels.
pub const INPUTS: [Text; 5] = [
    t("observer", "observateur"),
    t("straw axis", "axe de la paille"),
    t("water height", "hauteur d'eau"),
    t("water index", "indice de l'eau"),
    t("event limit", "événements au plus"),
];
/// The `n_water = 1` check with no points.
pub const NO_POINTS_TO_CHECK: Text = t(
    "n_water = 1: no image points to check",
    "n_water = 1 : aucun point image à vérifier",
);
/// The `n_water = 1` check: points, distance, limit, verdict.
pub const ON_STRAW_CHECK: Text = t(
    "n_water = 1: the {} image points lie on the straw, at most {} m from its surface \
     (limit {} m): {}",
    "n_water = 1 : les {} points images sont sur la paille, à au plus {} m de sa surface \
     (limite {} m) : {}",
);
/// The check in a few words: distance, verdict.
pub const ON_STRAW_SHORT: Text = t("on the straw, max {} m: {}", "sur la paille, max {} m : {}");
/// A passed check.
pub const PASS: Text = t("pass", "réussi");
/// A failed check.
pub const FAIL: Text = t("FAIL", "ÉCHEC");
/// No image point.
pub const NOT_SEEN: Text = t(
    "No image point: the straw is not seen from here.",
    "Aucun point image : la paille n'est pas visible d'ici.",
);
/// How far the image lies from the straw: distance, index.
pub const DISTANCE_NOTE: Text = t(
    "The image points lie up to {} mm from the straw's surface (n_water = {}; with \
     n_water = 1 they would lie on it).",
    "Les points images sont jusqu'à {} mm de la surface de la paille (n_water = {} ; avec \
     n_water = 1 ils seraient dessus).",
);

// The gallery.
/// A gallery scene's section; its name fills it.
pub const GALLERY: Text = t("Gallery: {}", "Galerie : {}");
/// A lesson's question to the class; its number and its words fill it.
pub const LESSON_QUESTION: Text = t("Question {}: {}", "Question {} : {}");
/// A gallery scene's picture; its stem fills it.
pub const GALLERY_PICTURE: Text = t(
    "What the eye sees (bentstraw render --scene scenes/{}.toml): Fresnel reflection \
     and refraction at every surface, the checkerboard behind.",
    "Ce que voit l'œil (bentstraw render --scene scenes/{}.toml) : réflexion et réfraction de \
     Fresnel à chaque surface, le damier derrière.",
);
/// A gallery scene's points' title; its name fills it.
pub const GALLERY_POINTS_TITLE: Text = t(
    "{}: the image points (course model)",
    "{} : les points images (modèle du cours)",
);
/// A gallery scene's points: stem, number.
pub const GALLERY_POINTS: Text = t(
    "Where each piece appears (bentstraw simulate --scene scenes/{}.toml --plot \
     points.png): {} image points P = O + L·u0, the container and liquids as a \
     wireframe, the objects' true outlines dashed.",
    "Où apparaît chaque morceau (bentstraw simulate --scene scenes/{}.toml --plot \
     points.png) : {} points images P = O + L·u0, le récipient et les liquides en fil de fer, \
     les vrais contours des objets en tireté.",
);
/// A gallery scene's ray diagram.
pub const GALLERY_RAYS: Text = t(
    "Which light path makes which piece (bentstraw simulate --rays): broken paths from the \
     eye, refractions (o) and total reflections (x), the dashed line of sight to each image \
     point.",
    "Quel chemin de la lumière fait quel morceau (bentstraw simulate --rays) : chemins brisés \
     depuis l'œil, réfractions (o) et réflexions totales (x), la ligne de visée en tireté \
     vers chaque point image.",
);

// The report of one scene file (`table --scene`).
/// The scene report's title; the scene's name fills it.
pub const SCENE_TITLE: Text = t("bentstraw: {}", "bentstraw : {}");
/// Under the scene report's title: the file's own comment, the number of points.
pub const SCENE_SUBTITLE: Text = t(
    "{} Rays are traced from the eye through every surface between media (Snell–Descartes \
     refraction and total reflection) to the objects, and each ray that reaches one gives an \
     image point: where the eye believes that piece is. The scene is seen from the file's \
     observer and from three more around it; at least {} image points each.",
    "{} Des rayons sont tracés depuis l'œil à travers chaque surface entre deux milieux \
     (réfraction de Snell–Descartes et réflexion totale) jusqu'aux objets, et chaque rayon qui \
     en atteint un donne un point image : là où l'œil croit voir ce morceau. La scène est vue \
     depuis l'observateur du fichier et depuis trois autres autour de lui ; au moins {} points \
     images chacun.",
);
/// The scene report's opening section.
pub const THE_SCENE: Text = t("The scene", "La scène");
/// The scene's picture; the file's name fills it.
pub const SCENE_PICTURE: Text = t(
    "What the file's observer sees (bentstraw render --scene {}): Fresnel reflection and \
     refraction at every surface, the checkerboard behind.",
    "Ce que voit l'observateur du fichier (bentstraw render --scene {}) : réflexion et \
     réfraction de Fresnel à chaque surface, le damier derrière.",
);
/// How the report's observers are chosen; the turns taken fill it.
pub const OBSERVERS_NOTE: Text = t(
    "Observer 1 is the file's. Observers 2 to 4 are the same eye turned about the vertical line \
     through the point it looks at ({}), at the same height and distance: a quarter turn or less \
     keeps it on the side the scene is meant to be seen from (a card's front, the straw's lean), \
     so each still looks at the same objects, from another side.",
    "L'observateur 1 est celui du fichier. Les observateurs 2 à 4 sont le même œil tourné autour \
     de la verticale passant par le point qu'il regarde ({}), à la même hauteur et à la même \
     distance : un quart de tour ou moins le garde du côté d'où la scène est faite pour être vue \
     (le devant d'une carte, l'inclinaison de la paille), si bien que chacun regarde encore les \
     mêmes objets, d'un autre côté.",
);
/// A turn that could not be taken: the angle and why.
pub const TURN_REFUSED: Text = t(
    "The turn by {}° was not taken: {}.",
    "La rotation de {}° n'a pas été prise : {}.",
);
/// An observer's heading; its number fills it.
pub const OBSERVER_N: Text = t("Observer {}", "Observateur {}");
/// The file's observer's group heading; its number fills it.
pub const OBSERVER_OF_FILE: Text = t(
    "Observer {}: the file's",
    "Observateur {} : celui du fichier",
);
/// A turned observer's group heading: its number and the angle.
pub const OBSERVER_TURNED: Text = t(
    "Observer {}: turned {}° about the vertical through the target",
    "Observateur {} : tourné de {}° autour de la verticale passant par la cible",
);
/// An input row: the scene file.
pub const SCENE_FILE: Text = t("scene file", "fichier de scène");
/// An input row: a liquid's name.
pub const LIQUID_ROW: Text = t("liquid: {}", "liquide : {}");
/// An input row: a liquid's top and index.
pub const LIQUID_VALUE: Text = t("top {} m, index {}", "surface à {} m, indice {}");
/// An input row: the objects.
pub const OBJECTS: Text = t("objects", "objets");
/// An input row: the straws, coins and cards.
pub const OBJECTS_VALUE: Text = t(
    "{} straw(s), {} coin(s), {} card(s)",
    "{} paille(s), {} pièce(s), {} carte(s)",
);
/// The transparent solids a scene holds, after its objects; the counts fill it.
pub const SOLIDS_VALUE: Text = t(
    ", {} sphere(s), {} prism(s), {} lens(es)",
    ", {} sphère(s), {} prisme(s), {} lentille(s)",
);
/// How far the image lies from the objects; the distance fills it.
pub const SCENE_DISTANCE_NOTE: Text = t(
    "The image points lie up to {} mm from the surface of the objects they show.",
    "Les points images sont jusqu'à {} mm de la surface des objets qu'ils montrent.",
);
/// A series of the scene's validation: the observer's number fills it.
pub const OBSERVER_SERIES: Text = t("observer {}", "observateur {}");
/// The scene's validation figure: the liquid's name and its index.
pub const SCENE_VALIDATION_CAPTION: Text = t(
    "For the image points whose light crossed a surface, the largest (solid) and median (dashed) \
     distance from the objects' surface, as the index of the bottom liquid ({}) goes from 1 to \
     its own {}, log scale.",
    "Pour les points images dont la lumière a traversé une surface, la plus grande distance \
     (trait plein) et la distance médiane (tireté) à la surface des objets, quand l'indice du \
     liquide du fond ({}) va de 1 à son propre indice {}, en échelle logarithmique.",
);
/// Under the scene's validation; the number of points fills it.
pub const SCENE_VALIDATION_NOTE: Text = t(
    "With index 1 the bottom liquid bends nothing: the image points lie on the objects to \
     rounding, unless something else bends the light on its way (a glass with thick walls, \
     another liquid); as the index grows, the image leaves the objects. The points seen straight \
     through air are left out: they lie on the objects whatever the liquid. {} image points per \
     observer and index.",
    "Avec l'indice 1 le liquide du fond ne dévie rien : les points images sont sur les objets à \
     l'arrondi près, sauf si autre chose dévie la lumière en chemin (un verre aux parois \
     épaisses, un autre liquide) ; quand l'indice croît, l'image quitte les objets. Les points \
     vus directement dans l'air sont laissés de côté : ils sont sur les objets quel que soit le \
     liquide. {} points images par observateur et par indice.",
);
/// The scene's validation when it cannot be made: the reason fills it.
pub const NO_VALIDATION: Text = t(
    "No validation figure: {}.",
    "Pas de figure de validation : {}.",
);
/// Why: the scene has no liquid.
pub const NO_LIQUID: Text = t(
    "the scene has no liquid, so there is no index to vary (with nothing but air in the \
     container, only the glass itself bends the light)",
    "la scène n'a pas de liquide, donc pas d'indice à faire varier (avec seulement de l'air dans \
     le récipient, seul le verre lui-même dévie la lumière)",
);
/// Why: the liquid's index is already 1.
pub const INDEX_ONE: Text = t(
    "the bottom liquid's index is 1, so there is nothing to vary",
    "l'indice du liquide du fond vaut 1, il n'y a donc rien à faire varier",
);
/// The scene report's limits.
pub const SCENE_LIMITS_NOTE: Text = t(
    "The image point P = O + L·u0 is the course's convention, not what an eye measures: the eye \
     and stereo models above say where one eye with a small pupil, and two eyes, see each point. \
     The objects are opaque and their surfaces do not reflect; light is traced for one colour (no \
     dispersion). The pictures' Fresnel mode follows at most 2048 ray segments per ray from the \
     eye.",
    "Le point image P = O + L·u0 est la convention du cours, pas ce que mesure un œil : les \
     modèles de l'œil et stéréo ci-dessus disent où un œil à petite pupille, et deux yeux, voient \
     chaque point. Les objets sont opaques et leur surface ne réfléchit pas ; la lumière est \
     tracée pour une seule couleur (pas de dispersion). Le mode Fresnel des images suit au plus \
     2048 segments par rayon issu de l'œil.",
);
/// The validation figure's x axis for a scene's liquid.
pub const LIQUID_INDEX_AXIS: Text = t(
    "index of the bottom liquid n →",
    "indice du liquide du fond n →",
);
/// The scene report's footer: the colour names, the version and the time fill it.
pub const SCENE_FOOTER: Text = t(
    "<footer id=\"conventions\">\n<h2>Conventions</h2>\n\
     <p>Lengths in metres; z up from the container's outer base. Colour codes: {}.</p>\n\
     <p>A ray leaves the observer O with direction u0, is refracted or totally reflected at each \
     surface between two media (at most the event limit), and stops on the first opaque object \
     it meets, of which it takes the colour. Its image point is P = O + L·u0, with L the length \
     of its broken path: where the observer believes that piece is.</p>\n\
     <p>Written by bentstraw {} in {} (wall clock). The observers' simulations run side by side, \
     so each one's times are wall-clock times shared with the others.</p>\n</footer>\n</body>\n</html>\n",
    "<footer id=\"conventions\">\n<h2>Conventions</h2>\n\
     <p>Longueurs en mètres ; z vers le haut depuis le fond extérieur du récipient. Codes de \
     couleur : {}.</p>\n\
     <p>Un rayon quitte l'observateur O dans la direction u0, est réfracté ou totalement réfléchi \
     à chaque surface entre deux milieux (au plus le nombre maximal d'événements), et s'arrête \
     sur le premier objet opaque qu'il rencontre, dont il prend la couleur. Son point image est \
     P = O + L·u0, où L est la longueur de son chemin brisé : là où l'observateur croit voir ce \
     morceau.</p>\n\
     <p>Écrit par bentstraw {} en {} (temps réel). Les simulations des observateurs tournent en \
     parallèle : les durées de chacune sont des temps réels partagés avec les autres.</p>\n</footer>\n</body>\n</html>\n",
);

// The figures.
/// The validation figure's title.
pub const VALIDATION_FIGURE_TITLE: Text = t(
    "Image points seen through the water: distance from the straw",
    "Points images vus à travers l'eau : distance à la paille",
);
/// The validation figure's x axis.
pub const INDEX_AXIS: Text = t("index of the water n →", "indice de l'eau n →");
/// The validation figure's y axis.
pub const DISTANCE_LOG_AXIS: Text = t("distance (m), log scale →", "distance (m), échelle log →");
/// The validation figure's key to its lines.
pub const SOLID_DASHED: Text = t(
    "solid: largest distance; dashed: median",
    "trait plein : plus grande distance ; tireté : médiane",
);
/// The gap plot's x axis.
pub const HEIGHT_AXIS: Text = t(
    "height z of the straw point (m) →",
    "hauteur z du point de la paille (m) →",
);
/// The gap plot's y axis.
pub const GAP_AXIS: Text = t(
    "gap to the course's point (mm) →",
    "écart au point du cours (mm) →",
);
/// The rainbow section's heading (scenes with a sun and a drop).
pub const RAINBOW: Text = t(
    "The rainbow: Descartes' construction",
    "L'arc-en-ciel : la construction de Descartes",
);
/// The rainbow figure's horizontal axis.
pub const RAINBOW_X_AXIS: Text = t(
    "impact parameter b (distance from the centre / radius) →",
    "paramètre d'impact b (distance au centre / rayon) →",
);
/// The rainbow figure's vertical axis.
pub const RAINBOW_Y_AXIS: Text = t(
    "angle from the antisolar point →",
    "angle depuis le point antisolaire →",
);
/// The first bow's angles: violet's and red's.
pub const RAINBOW_FIRST_LABEL: Text = t(
    "first bow: {}° (violet) to {}° (red)",
    "premier arc : {}° (violet) à {}° (rouge)",
);
/// The second bow's angles: violet's and red's.
pub const RAINBOW_SECOND_LABEL: Text = t(
    "second bow: {}° (violet) to {}° (red)",
    "second arc : {}° (violet) à {}° (rouge)",
);
/// The rainbow figure's caption.
pub const RAINBOW_CAPTION: Text = t(
    "Sunlight leaving the drop after one reflection inside it (lower curves) and after two (upper curves), traced at each band of white light in its colour, against where it entered. Where a curve turns, rays of many impact parameters leave together: the dots are the bows.",
    "La lumière du soleil qui ressort de la goutte après une réflexion à l'intérieur (courbes du bas) et après deux (courbes du haut), tracée pour chaque bande de la lumière blanche dans sa couleur, selon l'endroit où elle est entrée. Là où une courbe tourne, des rayons de nombreux paramètres d'impact ressortent ensemble : les points sont les arcs.",
);
/// How the rainbow figure is made, under it.
pub const RAINBOW_NOTE: Text = t(
    "Each ray is traced through the scene's first sphere, alone in air, by the same tracer as the pictures, splitting at each face by Fresnel's law; the bow is where the angle is largest (one reflection) or smallest (two), found to a billionth of the radius. Descartes' closed form gives the same angles: the stationary ray enters at i with cos² i = (n² − 1)/((k + 1)² − 1) for k reflections. The sky is bright inside the first bow and outside the second, dark between them: Alexander's band.",
    "Chaque rayon est tracé à travers la première sphère de la scène, seule dans l'air, par le même traceur que les images, partagé à chaque face selon la loi de Fresnel ; l'arc est là où l'angle est le plus grand (une réflexion) ou le plus petit (deux), trouvé au milliardième du rayon près. La formule de Descartes donne les mêmes angles : le rayon stationnaire entre sous l'incidence i avec cos² i = (n² − 1)/((k + 1)² − 1) pour k réflexions. Le ciel est clair à l'intérieur du premier arc et à l'extérieur du second, sombre entre les deux : la bande d'Alexandre.",
);
/// The rainbow table's header: wavelength, index, the two bows' angles.
pub const RAINBOW_HEAD: [Text; 4] = [
    t("wavelength (nm)", "longueur d'onde (nm)"),
    t("index", "indice"),
    t("first bow", "premier arc"),
    t("second bow", "second arc"),
];
/// The sweep section's heading: apparent depth against the viewing angle.
pub const SWEEP: Text = t(
    "Apparent depth from every seat",
    "La profondeur apparente depuis chaque place",
);
/// The round-the-glass sweep's caption: the object point's coordinates fill it.
pub const SWEEP_AROUND_CAPTION: Text = t(
    "The point ({}, {}, {}) m as the eye moves round the glass at the observer's height and \
     distance: the height of the course's point, of the eye model's two focal lines and of the \
     stereo point at each seat; gaps where the point is hidden.",
    "Le point ({}, {}, {}) m quand l'œil tourne autour du verre, à la hauteur et à la distance \
     de l'observateur : la hauteur du point du cours, des deux focales du modèle de l'œil et du \
     point stéréo depuis chaque place ; des trous là où le point est caché.",
);
/// The up-and-down sweep's caption: the object point's coordinates fill it.
pub const SWEEP_UPDOWN_CAPTION: Text = t(
    "The same point as the eye moves up and down at the same distance, from straight below to \
     straight above.",
    "Le même point quand l'œil monte et descend à la même distance, de juste en dessous à juste \
     au-dessus.",
);
/// The sweep section's note: what the figures show and why.
pub const SWEEP_NOTE: Text = t(
    "Each seat sees the point along its own light path: the steeper the light leaves the water, \
     the less the refraction lifts the point, and the farther apart the two focal lines lie. \
     That is why the straw looks broken differently from every seat of a classroom. The eye \
     follows one image of the point from the observer's seat as long as it lasts; where it is \
     lost the point is looked for afresh (the path's kind is in the CSV). Heights in the \
     figures; every position in the CSV files.",
    "Chaque place voit le point par son propre chemin de lumière : plus la lumière sort de \
     l'eau à la verticale, moins la réfraction relève le point, et plus les deux focales sont \
     proches. C'est pourquoi la paille paraît brisée autrement depuis chaque place d'une classe. \
     L'œil suit une image du point depuis la place de l'observateur tant qu'elle dure ; là où \
     elle se perd, le point est cherché à nouveau (le genre du chemin est dans le CSV). Les \
     hauteurs dans les figures ; toutes les positions dans les fichiers CSV.",
);
/// The round-the-glass sweep's x axis.
pub const SWEEP_AROUND_AXIS: Text = t(
    "turn of the eye from the observer's seat (°) →",
    "rotation de l'œil depuis la place de l'observateur (°) →",
);
/// The up-and-down sweep's x axis.
pub const SWEEP_UPDOWN_AXIS: Text = t("elevation of the eye (°) →", "élévation de l'œil (°) →");
/// The sweep's y axis.
pub const SWEEP_HEIGHT_AXIS: Text = t(
    "height z of the apparent point (cm) →",
    "hauteur z du point apparent (cm) →",
);
/// The sweep's models, in the order of its figure and CSV.
pub const SWEEP_MODELS: [Text; 4] = [
    t("course's point (O + L·u0)", "point du cours (O + L·u0)"),
    t("eye: horizontal focal line", "œil : focale horizontale"),
    t("eye: vertical focal line", "œil : focale verticale"),
    t("stereo point (two eyes)", "point stéréo (deux yeux)"),
];
/// The sweeps' figures' titles after the section's heading: round the glass, up and down.
pub const SWEEP_KINDS: [Text; 2] = [
    t("round the glass", "autour du verre"),
    t("up and down", "de haut en bas"),
];
/// The sweep's dashed line: the object point's own height.
pub const SWEEP_TRUE: Text = t("the point itself", "le point lui-même");
/// The sweep's mark of the observer's seat.
pub const SWEEP_SEAT: Text = t("the observer's seat", "la place de l'observateur");
/// The sweep section's note when the observer sees no object to follow.
pub const SWEEP_NONE: Text = t(
    "The file's observer sees no object: there is no point to follow.",
    "L'observateur du fichier ne voit aucun objet : il n'y a pas de point à suivre.",
);
/// The link to a sweep's CSV.
pub const SWEEP_CSV: Text = t("numbers (CSV)", "nombres (CSV)");
/// The gap plot's series.
pub const EYE_MODEL: Text = t("eye model", "modèle de l'œil");
/// The gap plot's series.
pub const STEREO_MODEL: Text = t("stereo model", "modèle stéréo");
/// A gap series with no points; its name fills it.
pub const NO_POINTS: Text = t("{}: no points", "{} : aucun point");
/// A gap series: its name and number of points.
pub const N_POINTS: Text = t("{} ({} points)", "{} ({} points)");
/// The ray diagram's side view's captions.
pub const DIAGRAM_SIDE: [Text; 2] = [
    t("side view", "vue de côté"),
    t("(observer to the right)", "(l'observateur à droite)"),
];
/// The ray diagram's side view's horizontal axis.
pub const TOWARDS_OBSERVER: Text = t("towards observer (m) →", "vers l'observateur (m) →");
/// The ray diagram's top view's captions.
pub const DIAGRAM_TOP: [Text; 2] = [
    t("top view", "vue de dessus"),
    t("(from above)", "(d'en haut)"),
];
/// The ray diagram's key to its marks.
pub const DIAGRAM_KEY: [Text; 2] = [
    t(
        "o refraction    x total reflection",
        "o réfraction    x réflexion totale",
    ),
    t("dashed: the line of sight", "tireté : la ligne de visée"),
];

// Grading a class.
/// The class page's title.
pub const GRADE_CLASS_TITLE: Text = t("The class at a glance", "La classe d'un coup d'œil");
/// A student's feedback page's title.
pub const GRADE_STUDENT_TITLE: Text = t("{}: feedback", "{} : retour");
/// The class page's line on the class.
pub const GRADE_CLASS_LINE: Text = t(
    "{} students, {} cases each; mean score {} of {}.",
    "{} élèves, {} cas chacun ; note moyenne {} sur {}.",
);
/// Heading of the distribution of scores.
pub const GRADE_SCORES: Text = t("Scores", "Notes");
/// Heading of the pass rates.
pub const GRADE_PASS_RATES: Text = t("Each case", "Chaque cas");
/// Heading of the common mistakes.
pub const GRADE_MISTAKES: Text = t("Common mistakes", "Erreurs fréquentes");
/// A common mistake: how many students miss a part of the image.
pub const GRADE_MISTAKE: Text = t(
    "{} students miss the {} points seen {}",
    "{} élèves n'ont pas les points {} vus {}",
);
/// No common mistake.
pub const GRADE_NO_MISTAKE: Text = t(
    "No part of the image is missed by two students or more.",
    "Aucune partie de l'image ne manque à deux élèves ou plus.",
);
/// Column heads of the case table.
pub const GRADE_CASE_HEADS: [Text; 5] = [
    t("case", "cas"),
    t("verdict", "verdict"),
    t("score", "note"),
    t("points right", "points justes"),
    t("coverage", "couverture"),
];
/// The verdicts, in the order of `CaseVerdict`.
pub const GRADE_VERDICTS: [Text; 4] = [
    t("pass", "réussi"),
    t("fail", "échoué"),
    t("missing", "manquant"),
    t("unreadable", "illisible"),
];
/// A missing region of the image.
pub const GRADE_MISSING_REGION: Text = t(
    "missing: {} ({} % of its image), seen {}, {}",
    "manquent : {} ({} % de son image), vu {}, {}",
);
/// Where a missing region lies along its section, in the order of `Place`.
pub const GRADE_PLACES: [Text; 4] = [
    t(
        "over its whole visible height",
        "sur toute sa hauteur visible",
    ),
    t("at the top end", "en haut"),
    t("at the bottom end", "en bas"),
    t("in the middle", "au milieu"),
];
/// The total of a student.
pub const GRADE_TOTAL: Text = t("Total: {} of {}", "Total : {} sur {}");
/// The caption of a case's check figure on a student's page.
pub const GRADE_FIGURE: Text = t(
    "{}: the true image pale, your points over it in full colour; wrong points marked by kind, \
     the parts you miss outlined and numbered.",
    "{} : l'image vraie en pâle, vos points par-dessus en couleurs vives ; les points faux marqués \
     selon leur faute, les parties manquantes entourées et numérotées (le texte de la figure est \
     en anglais).",
);
/// The note under a student's table: how a fail is scored.
pub const GRADE_HOW: Text = t(
    "A pass scores the case's points; a fail scores them times the share of right points times \
     the coverage over the coverage asked for (at most 1); a missing or unreadable file scores 0. \
     Why the points are where they are: bentstraw's docs/physics.md.",
    "Un cas réussi rapporte ses points ; un cas échoué, ses points fois la part de points justes \
     fois la couverture rapportée à celle demandée (au plus 1) ; un fichier manquant ou illisible, \
     0. Pourquoi les points sont où ils sont : docs/physics.md de bentstraw.",
);
/// A case passed.
pub const GRADE_NOTE_PASS: Text = t(
    "{}: every point right, the image covered",
    "{} : tous les points justes, l'image couverte",
);
/// Points wrong.
pub const GRADE_NOTE_WRONG: Text = t("{} of {} points wrong", "{} points faux sur {}");
/// Coverage short.
pub const GRADE_NOTE_COVERAGE: Text = t(
    "{} % of a colour's image covered (at least {} % asked)",
    "{} % de l'image d'une couleur couverte (au moins {} % demandés)",
);
/// No file handed in.
pub const GRADE_NOTE_MISSING: Text = t(
    "no file {} in the student's folder",
    "aucun fichier {} dans le dossier de l'élève",
);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_template_takes_its_values_in_order() {
        assert_eq!(
            Lang::En.fill(SIMULATION_CHECK, &[&1, &1.05]),
            "Simulation 1, check n_water = 1.05"
        );
        assert_eq!(
            Lang::Fr.fill(SIMULATION_CHECK, &[&1, &1.05]),
            "Simulation 1, vérification n_water = 1.05"
        );
        assert_eq!(Lang::Fr.section_name(3), "vert");
        assert_eq!(Lang::Fr.code(), "fr");
    }
}
