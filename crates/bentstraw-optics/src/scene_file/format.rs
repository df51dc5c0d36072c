//! The scene-file format itself: TOML read into a [`SceneDescription`] (every key named as a
//! path when it breaks a rule) and written back.

use serde::{Deserialize, Serialize};

use super::*;
use crate::dispersion;
use crate::text::clip_text;

/// Longest user text (a name, a shape) quoted whole in a message, in characters.
const QUOTED_MAX: usize = 40;

// The file's form: what TOML may say, every optional key an `Option`, nothing else accepted.

/// A scene file's keys and values as its text holds them, before any rule is checked: what a
/// page edits key by key and turns back into the file's text ([`SceneForm::to_toml`]).
#[derive(Deserialize, Serialize)]
#[serde(transparent)]
pub struct SceneForm(FileScene);

impl SceneForm {
    /// The form as a scene file's TOML text (every key it holds, in the file's order); reading
    /// it checks the rules.
    pub fn to_toml(&self) -> String {
        // Tables of numbers and strings always have a TOML form.
        toml::to_string(&self.0).expect("a scene form is plain TOML data")
    }
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct FileScene {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    container: Option<FileContainer>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    liquid: Vec<FileLiquid>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    straw: Vec<FileStraw>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    coin: Vec<FileCoin>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    card: Vec<FileCard>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    sphere: Vec<FileSphere>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    prism: Vec<FilePrism>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    lens: Vec<FileLens>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    observer: Option<FileObserver>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    sun: Option<FileSun>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    lesson: Option<FileLesson>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct FileSun {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    direction: Option<[f64; 3]>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct FileLesson {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    en: Option<FileLessonText>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    fr: Option<FileLessonText>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct FileLessonText {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    title: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    text: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    questions: Option<Vec<String>>,
}

#[derive(Deserialize, Serialize, Default)]
#[serde(deny_unknown_fields)]
struct FileContainer {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    shape: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    radius: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    half_x: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    half_y: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    height: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    wall: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    bottom: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    index: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    cauchy: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    sellmeier: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    material: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    outer: Option<Vec<[f64; 2]>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    inner: Option<Vec<[f64; 2]>>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct FileLiquid {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    name: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    index: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    cauchy: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    sellmeier: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    material: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    top: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    tint: Option<String>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct FileStraw {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    x: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    y: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    tilt: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    azimuth: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    radius: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    length: Option<f64>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct FileCoin {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    x: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    y: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    radius: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    thickness: Option<f64>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct FileCard {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    center: Option<[f64; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    facing: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    width: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    height: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    picture: Option<String>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct FileSphere {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    center: Option<[f64; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    radius: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    index: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    cauchy: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    sellmeier: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    material: Option<String>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct FilePrism {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    corners: Option<Vec<[f64; 2]>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    bottom: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    top: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    index: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    cauchy: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    sellmeier: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    material: Option<String>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct FileLens {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    center: Option<[f64; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    axis: Option<[f64; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    radius1: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    radius2: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    thickness: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    diameter: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    index: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    cauchy: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    sellmeier: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    material: Option<String>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct FileObserver {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    position: Option<[f64; 3]>,
    #[serde(default)]
    target: Option<[f64; 3]>,
}

/// `path` (serde's, counting from 0) as the messages write it, counting entries from 1.
fn toml_path(path: &serde_path_to_error::Path) -> String {
    use serde_path_to_error::Segment;
    let mut out = String::new();
    for segment in path.iter() {
        match segment {
            Segment::Seq { index } => out.push_str(&format!("[{}]", index + 1)),
            Segment::Map { key } => {
                if !out.is_empty() {
                    out.push('.');
                }
                out.push_str(&clip_text(key, QUOTED_MAX));
            }
            Segment::Enum { variant } => {
                if !out.is_empty() {
                    out.push('.');
                }
                out.push_str(variant);
            }
            Segment::Unknown => {}
        }
    }
    out
}

/// TOML's error as one line: where (line, column), which key, and what is wrong.
fn syntax_error(text: &str, key: String, e: &toml::de::Error) -> Box<SceneFileError> {
    let line = e.span().map(|span| {
        let before = &text.as_bytes()[..span.start.min(text.len())];
        before.iter().filter(|&&b| b == b'\n').count() + 1
    });
    // TOML's messages can span lines (an expectation below the error): one line, clipped.
    let what: String = e
        .message()
        .split('\n')
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join("; ");
    let what = clip_text(&what, 200);
    // serde names a missing field from the table that lacks it: say the key's whole path.
    let mut e = match what
        .strip_prefix("missing field `")
        .and_then(|rest| rest.strip_suffix('`'))
    {
        Some(field) => {
            let full = if key.is_empty() {
                field.to_string()
            } else {
                format!("{key}.{field}")
            };
            Box::new(SceneFileError::new(&full, None, Rule::Required, vec![]))
        }
        None => Box::new(SceneFileError::new(
            &key,
            None,
            Rule::Syntax,
            vec![("what", words(what))],
        )),
    };
    if let Some(l) = line {
        e.message = format!("line {l}: {}", e.message);
    }
    e.line = line;
    e
}

/// The keys that give a medium's index: one number for every wavelength, or a law.
struct IndexKeys<'a> {
    index: Option<f64>,
    cauchy: &'a Option<Vec<f64>>,
    sellmeier: &'a Option<Vec<f64>>,
    material: &'a Option<String>,
}

/// The index keys of a file's table that has them (the container, a liquid, a solid).
macro_rules! index_keys {
    ($table:expr) => {
        IndexKeys {
            index: $table.index,
            cauchy: &$table.cauchy,
            sellmeier: &$table.sellmeier,
            material: &$table.material,
        }
    };
}

/// A stand-in index, valid, for a medium whose keys broke a rule (the rule is reported).
const STAND_IN_INDEX: f64 = 1.5;

/// The index at the d line of `medium` from its keys (`key` names each in messages), its law,
/// if it has one, added to `laws`: at most one of the four keys may be given; `default` when
/// none is (else it is required). A law must give a physical index everywhere in the visible.
fn refractive(
    k: IndexKeys<'_>,
    key: &dyn Fn(&str) -> String,
    default: Option<f64>,
    (medium, laws): (Medium, &mut Vec<Dispersive>),
    broken: &mut Vec<SceneFileError>,
) -> f64 {
    let (index, law) = index_and_law(k, key, default, broken);
    laws.extend(law.map(|law| Dispersive { medium, law }));
    index
}

/// [`refractive`]'s index and law.
fn index_and_law(
    k: IndexKeys<'_>,
    key: &dyn Fn(&str) -> String,
    default: Option<f64>,
    broken: &mut Vec<SceneFileError>,
) -> (f64, Option<Dispersion>) {
    let given: Vec<&str> = [
        ("index", k.index.is_some()),
        ("cauchy", k.cauchy.is_some()),
        ("sellmeier", k.sellmeier.is_some()),
        ("material", k.material.is_some()),
    ]
    .into_iter()
    .filter_map(|(name, is)| is.then_some(name))
    .collect();
    if given.len() > 1 {
        broken.push(*refuse_key(
            &key(given[1]),
            Rule::IndexChoice,
            vec![("keys", words(given.join(", ")))],
        ));
        return (STAND_IN_INDEX, None);
    }
    let count = |c: &Vec<f64>| bound(c.len() as f64);
    let (name, law) = if let Some(c) = k.cauchy {
        if !(2..=3).contains(&c.len()) {
            broken.push(*refuse_key(
                &key("cauchy"),
                Rule::CauchyCount,
                vec![("count", count(c))],
            ));
            return (STAND_IN_INDEX, None);
        }
        ("cauchy", Dispersion::Cauchy(c.clone()))
    } else if let Some(c) = k.sellmeier {
        if c.is_empty() || c.len() % 2 != 0 || c.len() > 2 * dispersion::MAX_SELLMEIER_TERMS {
            broken.push(*refuse_key(
                &key("sellmeier"),
                Rule::SellmeierCount,
                vec![
                    ("max", bound(dispersion::MAX_SELLMEIER_TERMS as f64)),
                    ("count", count(c)),
                ],
            ));
            return (STAND_IN_INDEX, None);
        }
        ("sellmeier", Dispersion::Sellmeier(c.clone()))
    } else if let Some(name) = k.material {
        let Some(m) = dispersion::material(name) else {
            let names: Vec<&str> = dispersion::MATERIALS.iter().map(|m| m.name).collect();
            let near = crate::text::nearest_names(name, names.iter().copied());
            let mut params = vec![
                ("material", words(clip_text(name, QUOTED_MAX))),
                ("materials", words(names.join(", "))),
            ];
            let rule = if near.is_empty() {
                Rule::MaterialUnknown
            } else {
                params.push(("nearest", words(crate::text::quoted_names(&near))));
                Rule::MaterialNear
            };
            broken.push(*refuse_key(&key("material"), rule, params));
            return (STAND_IN_INDEX, None);
        };
        ("material", Dispersion::Material(m))
    } else {
        let index = k.index.or(default).unwrap_or_else(|| {
            broken.push(*refuse_key(&key("index"), Rule::Required, vec![]));
            0.0
        });
        return (index, None);
    };
    if let Some((nm, n)) = law.formula().unphysical_in_visible() {
        broken.push(*refuse_key(
            &key(name),
            Rule::DispersionRange,
            vec![("index", rule::number(n)), ("wavelength", rule::number(nm))],
        ));
        return (STAND_IN_INDEX, None);
    }
    (law.index_at(dispersion::D_LINE_NM), Some(law))
}

/// The keys a medium's index is written with, as the file holds them: `index`, `cauchy`,
/// `sellmeier`, `material`.
type WrittenIndex = (
    Option<f64>,
    Option<Vec<f64>>,
    Option<Vec<f64>>,
    Option<String>,
);

/// The keys a medium's index is written with: its law's, or its one index.
fn index_keys(law: Option<&Dispersion>, index: f64) -> WrittenIndex {
    match law {
        None => (Some(index), None, None, None),
        Some(Dispersion::Cauchy(c)) => (None, Some(c.clone()), None, None),
        Some(Dispersion::Sellmeier(c)) => (None, None, Some(c.clone()), None),
        Some(Dispersion::Material(m)) => (None, None, None, Some(m.name.to_string())),
    }
}

impl SceneDescription {
    /// Reads a scene file's text: TOML of the scene-file format, defaults applied, every rule
    /// checked ([`SceneDescription::validate`]).
    pub fn from_toml(text: &str) -> Result<SceneDescription, Box<SceneFileError>> {
        let de =
            toml::Deserializer::parse(text).map_err(|e| syntax_error(text, String::new(), &e))?;
        let file: FileScene = serde_path_to_error::deserialize(de).map_err(|e| {
            let key = toml_path(e.path());
            syntax_error(text, key, e.inner())
        })?;
        let description = SceneDescription::from_file(file)?;
        description.validate()?;
        Ok(description)
    }

    /// The file's form with its defaults filled in; the keys of the other shape are refused here,
    /// as the description has no place for them. Every key missing or misplaced is reported at
    /// once.
    fn from_file(file: FileScene) -> Result<SceneDescription, Box<SceneFileError>> {
        let mut broken = Vec::new();
        // A required key: its value, or a refusal kept and a stand-in to go on with.
        let need = |key: String| refuse_key(&key, Rule::Required, vec![]);
        let get = |key: String, value: Option<f64>, broken: &mut Vec<SceneFileError>| {
            value.unwrap_or_else(|| {
                broken.push(*need(key));
                0.0
            })
        };
        let Some(c) = &file.container else {
            return Err(refuse_key("container", Rule::ContainerMissing, vec![]));
        };
        let given = |key: &str, value: Option<f64>, rule: Rule, broken: &mut Vec<_>| {
            if let Some(v) = value {
                broken.push(*refuse(&format!("container.{key}"), v, rule, vec![]));
            }
        };
        let shape_of = |key: &str, value: Option<f64>, rule: Rule, broken: &mut Vec<_>| {
            value.unwrap_or_else(|| {
                broken.push(*refuse_key(&format!("container.{key}"), rule, vec![]));
                0.0
            })
        };
        let mut laws: Vec<Dispersive> = Vec::new();
        let container_key = |k: &str| format!("container.{k}");
        let revolution = c.shape.as_deref() == Some("revolution");
        let height = if revolution {
            0.0
        } else {
            get("container.height".into(), c.height, &mut broken)
        };
        if !revolution {
            for (key, value) in [("outer", &c.outer), ("inner", &c.inner)] {
                if value.is_some() {
                    broken.push(*refuse_key(
                        &format!("container.{key}"),
                        Rule::ProfilesOnly,
                        vec![],
                    ));
                }
            }
        }
        let container = match c.shape.as_deref() {
            Some("revolution") => {
                for (key, value) in [
                    ("radius", c.radius),
                    ("half_x", c.half_x),
                    ("half_y", c.half_y),
                    ("height", c.height),
                    ("wall", c.wall),
                    ("bottom", c.bottom),
                ] {
                    given(key, value, Rule::RevolutionKeys, &mut broken);
                }
                let mut profile = |key: &str, value: &Option<Vec<[f64; 2]>>| {
                    value.clone().unwrap_or_else(|| {
                        broken.push(*refuse_key(
                            &format!("container.{key}"),
                            Rule::RevolutionNeeds,
                            vec![],
                        ));
                        Vec::new()
                    })
                };
                let (outer, inner) = (profile("outer", &c.outer), profile("inner", &c.inner));
                let index = refractive(
                    index_keys!(c),
                    &container_key,
                    Some(DEFAULT_CONTAINER_INDEX),
                    (Medium::Container, &mut laws),
                    &mut broken,
                );
                Some(Container::Revolution(Revolution {
                    outer,
                    inner,
                    index,
                }))
            }
            Some("glass") => {
                let not_glass = Rule::GlassNoHalfWidths;
                given("half_x", c.half_x, not_glass, &mut broken);
                given("half_y", c.half_y, not_glass, &mut broken);
                let radius = shape_of("radius", c.radius, Rule::GlassNeeds, &mut broken);
                let index = refractive(
                    index_keys!(c),
                    &container_key,
                    Some(DEFAULT_CONTAINER_INDEX),
                    (Medium::Container, &mut laws),
                    &mut broken,
                );
                Some(Container::Glass(Glass {
                    radius,
                    height,
                    wall: c.wall.unwrap_or(0.0),
                    bottom: c.bottom.unwrap_or(0.0),
                    index,
                }))
            }
            Some("tank") => {
                given("radius", c.radius, Rule::TankNoRadius, &mut broken);
                given("wall", c.wall, Rule::TankThin, &mut broken);
                given("bottom", c.bottom, Rule::TankThin, &mut broken);
                given("index", c.index, Rule::TankIndex, &mut broken);
                for (key, is) in [
                    ("cauchy", c.cauchy.is_some()),
                    ("sellmeier", c.sellmeier.is_some()),
                    ("material", c.material.is_some()),
                ] {
                    if is {
                        broken.push(*refuse_key(&container_key(key), Rule::TankIndex, vec![]));
                    }
                }
                Some(Container::Tank(Tank {
                    half_x: shape_of("half_x", c.half_x, Rule::TankNeeds, &mut broken),
                    half_y: shape_of("half_y", c.half_y, Rule::TankNeeds, &mut broken),
                    height,
                }))
            }
            Some(other) => {
                broken.push(*refuse_key(
                    "container.shape",
                    Rule::ShapeUnknown,
                    vec![("shape", words(clip_text(other, QUOTED_MAX)))],
                ));
                None
            }
            None => {
                broken.push(*refuse_key("container.shape", Rule::ShapeMissing, vec![]));
                None
            }
        };
        let liquids: Vec<Liquid> = file
            .liquid
            .into_iter()
            .enumerate()
            .map(|(i, l)| {
                let key = |k: &str| format!("liquid[{}].{k}", i + 1);
                if l.name.is_none() {
                    broken.push(*need(key("name")));
                }
                let tint = l.tint.as_deref().and_then(|text| {
                    let colour = tint_colour(text);
                    if colour.is_none() {
                        broken.push(*refuse_key(
                            &key("tint"),
                            Rule::TintFormat,
                            vec![("tint", words(clip_text(text, QUOTED_MAX)))],
                        ));
                    }
                    colour
                });
                let index = refractive(
                    index_keys!(l),
                    &key,
                    None,
                    (Medium::Liquid(i), &mut laws),
                    &mut broken,
                );
                Liquid {
                    name: l.name.unwrap_or_default(),
                    index,
                    top: get(key("top"), l.top, &mut broken),
                    tint,
                }
            })
            .collect();
        let straws: Vec<Straw> = file
            .straw
            .iter()
            .enumerate()
            .map(|(i, s)| {
                let key = |k: &str| format!("straw[{}].{k}", i + 1);
                Straw {
                    x: get(key("x"), s.x, &mut broken),
                    y: get(key("y"), s.y, &mut broken),
                    tilt_deg: s.tilt.unwrap_or(0.0),
                    azimuth_deg: s.azimuth.unwrap_or(0.0),
                    radius: s.radius.unwrap_or(STRAW_RADIUS),
                    length: s.length.unwrap_or(STRAW_HEIGHT),
                }
            })
            .collect();
        let coins: Vec<Coin> = file
            .coin
            .iter()
            .enumerate()
            .map(|(i, c)| {
                let key = |k: &str| format!("coin[{}].{k}", i + 1);
                Coin {
                    x: get(key("x"), c.x, &mut broken),
                    y: get(key("y"), c.y, &mut broken),
                    radius: c.radius.unwrap_or(DEFAULT_COIN_RADIUS),
                    thickness: c.thickness.unwrap_or(DEFAULT_COIN_THICKNESS),
                }
            })
            .collect();
        let cards: Vec<Card> = file
            .card
            .iter()
            .enumerate()
            .map(|(i, c)| {
                let key = |k: &str| format!("card[{}].{k}", i + 1);
                let picture = match c.picture.as_deref().unwrap_or("arrow") {
                    "arrow" => Picture::Arrow,
                    "none" => Picture::None,
                    other => {
                        broken.push(*refuse_key(
                            &key("picture"),
                            Rule::PictureUnknown,
                            vec![("picture", words(clip_text(other, QUOTED_MAX)))],
                        ));
                        Picture::None
                    }
                };
                if c.center.is_none() {
                    broken.push(*need(key("center")));
                }
                Card {
                    center: Vec3::from_array(c.center.unwrap_or_default()),
                    facing_deg: c.facing.unwrap_or(0.0),
                    width: get(key("width"), c.width, &mut broken),
                    height: get(key("height"), c.height, &mut broken),
                    picture,
                }
            })
            .collect();
        let spheres: Vec<Sphere> = file
            .sphere
            .iter()
            .enumerate()
            .map(|(i, b)| {
                let key = |k: &str| format!("sphere[{}].{k}", i + 1);
                if b.center.is_none() {
                    broken.push(*need(key("center")));
                }
                let index = refractive(
                    index_keys!(b),
                    &key,
                    None,
                    (Medium::Sphere(i), &mut laws),
                    &mut broken,
                );
                Sphere {
                    center: Vec3::from_array(b.center.unwrap_or_default()),
                    radius: get(key("radius"), b.radius, &mut broken),
                    index,
                }
            })
            .collect();
        let prisms: Vec<Prism> = file
            .prism
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let key = |k: &str| format!("prism[{}].{k}", i + 1);
                if p.corners.is_none() {
                    broken.push(*need(key("corners")));
                }
                let index = refractive(
                    index_keys!(p),
                    &key,
                    None,
                    (Medium::Prism(i), &mut laws),
                    &mut broken,
                );
                Prism {
                    corners: p.corners.clone().unwrap_or_default(),
                    bottom: get(key("bottom"), p.bottom, &mut broken),
                    top: get(key("top"), p.top, &mut broken),
                    index,
                }
            })
            .collect();
        let lenses: Vec<Lens> = file
            .lens
            .iter()
            .enumerate()
            .map(|(i, l)| {
                let key = |k: &str| format!("lens[{}].{k}", i + 1);
                for (name, given) in [("center", l.center.is_some()), ("axis", l.axis.is_some())] {
                    if !given {
                        broken.push(*need(key(name)));
                    }
                }
                let index = refractive(
                    index_keys!(l),
                    &key,
                    None,
                    (Medium::Lens(i), &mut laws),
                    &mut broken,
                );
                Lens {
                    center: Vec3::from_array(l.center.unwrap_or_default()),
                    axis: Vec3::from_array(l.axis.unwrap_or([0.0, 0.0, 1.0])),
                    radius1: get(key("radius1"), l.radius1, &mut broken),
                    radius2: get(key("radius2"), l.radius2, &mut broken),
                    thickness: get(key("thickness"), l.thickness, &mut broken),
                    diameter: get(key("diameter"), l.diameter, &mut broken),
                    index,
                }
            })
            .collect();
        let observer = file.observer.as_ref().map(|o| {
            if o.position.is_none() {
                broken.push(*need("observer.position".into()));
            }
            (o.position.unwrap_or_default(), o.target)
        });
        let sun = file.sun.as_ref().map(|s| {
            if s.direction.is_none() {
                broken.push(*need("sun.direction".into()));
            }
            Sun {
                direction: Vec3::from_array(s.direction.unwrap_or_default()),
            }
        });
        let lesson = file.lesson.as_ref().map(|l| {
            let mut text = |lang: &str, t: &Option<FileLessonText>| {
                t.as_ref().map(|t| {
                    if t.title.is_none() {
                        broken.push(*need(format!("lesson.{lang}.title")));
                    }
                    LessonText {
                        title: t.title.clone().unwrap_or_default(),
                        text: t.text.clone().unwrap_or_default(),
                        questions: t.questions.clone().unwrap_or_default(),
                    }
                })
            };
            Lesson {
                en: text("en", &l.en),
                fr: text("fr", &l.fr),
            }
        });
        if let Some(e) = SceneFileError::all(broken) {
            return Err(e);
        }
        let Some(container) = container else {
            return Err(refuse_key("container.shape", Rule::ShapeMissing, vec![]));
        };
        // Without a target, the eye looks at the middle of the container.
        let middle = Vec3::new(0.0, 0.0, container.height() / 2.0);
        Ok(SceneDescription {
            container,
            liquids,
            straws,
            coins,
            cards,
            spheres,
            prisms,
            lenses,
            observer: observer.map(|(position, target)| Observer {
                position: Vec3::from_array(position),
                target: target.map_or(middle, Vec3::from_array),
            }),
            sun,
            lesson,
            dispersion: laws,
        })
    }

    /// The description as a scene file's TOML, every value written out (defaults too), so that
    /// reading it back gives the same description.
    pub fn to_toml(&self) -> String {
        self.form().to_toml()
    }

    /// The description's form, every value written out (defaults too).
    pub fn form(&self) -> SceneForm {
        let keys = |medium: Medium, index: f64| index_keys(self.law(medium), index);
        let container = match &self.container {
            Container::Glass(g) => {
                let (index, cauchy, sellmeier, material) = keys(Medium::Container, g.index);
                FileContainer {
                    shape: Some("glass".into()),
                    radius: Some(g.radius),
                    height: Some(g.height),
                    wall: Some(g.wall),
                    bottom: Some(g.bottom),
                    index,
                    cauchy,
                    sellmeier,
                    material,
                    ..FileContainer::default()
                }
            }
            Container::Revolution(v) => {
                let (index, cauchy, sellmeier, material) = keys(Medium::Container, v.index);
                FileContainer {
                    shape: Some("revolution".into()),
                    outer: Some(v.outer.clone()),
                    inner: Some(v.inner.clone()),
                    index,
                    cauchy,
                    sellmeier,
                    material,
                    ..FileContainer::default()
                }
            }
            Container::Tank(t) => FileContainer {
                shape: Some("tank".into()),
                half_x: Some(t.half_x),
                half_y: Some(t.half_y),
                height: Some(t.height),
                ..FileContainer::default()
            },
        };
        let file = FileScene {
            container: Some(container),
            liquid: self
                .liquids
                .iter()
                .enumerate()
                .map(|(i, l)| {
                    let (index, cauchy, sellmeier, material) = keys(Medium::Liquid(i), l.index);
                    FileLiquid {
                        name: Some(l.name.clone()),
                        index,
                        cauchy,
                        sellmeier,
                        material,
                        top: Some(l.top),
                        tint: l.tint.map(|[r, g, b]| format!("#{r:02x}{g:02x}{b:02x}")),
                    }
                })
                .collect(),
            straw: self
                .straws
                .iter()
                .map(|s| FileStraw {
                    x: Some(s.x),
                    y: Some(s.y),
                    tilt: Some(s.tilt_deg),
                    azimuth: Some(s.azimuth_deg),
                    radius: Some(s.radius),
                    length: Some(s.length),
                })
                .collect(),
            coin: self
                .coins
                .iter()
                .map(|c| FileCoin {
                    x: Some(c.x),
                    y: Some(c.y),
                    radius: Some(c.radius),
                    thickness: Some(c.thickness),
                })
                .collect(),
            card: self
                .cards
                .iter()
                .map(|c| FileCard {
                    center: Some(c.center.to_array()),
                    facing: Some(c.facing_deg),
                    width: Some(c.width),
                    height: Some(c.height),
                    picture: Some(c.picture.word().to_string()),
                })
                .collect(),
            sphere: self
                .spheres
                .iter()
                .enumerate()
                .map(|(i, b)| {
                    let (index, cauchy, sellmeier, material) = keys(Medium::Sphere(i), b.index);
                    FileSphere {
                        center: Some(b.center.to_array()),
                        radius: Some(b.radius),
                        index,
                        cauchy,
                        sellmeier,
                        material,
                    }
                })
                .collect(),
            prism: self
                .prisms
                .iter()
                .enumerate()
                .map(|(i, p)| {
                    let (index, cauchy, sellmeier, material) = keys(Medium::Prism(i), p.index);
                    FilePrism {
                        corners: Some(p.corners.clone()),
                        bottom: Some(p.bottom),
                        top: Some(p.top),
                        index,
                        cauchy,
                        sellmeier,
                        material,
                    }
                })
                .collect(),
            lens: self
                .lenses
                .iter()
                .enumerate()
                .map(|(i, l)| {
                    let (index, cauchy, sellmeier, material) = keys(Medium::Lens(i), l.index);
                    FileLens {
                        center: Some(l.center.to_array()),
                        axis: Some(l.axis.to_array()),
                        radius1: Some(l.radius1),
                        radius2: Some(l.radius2),
                        thickness: Some(l.thickness),
                        diameter: Some(l.diameter),
                        index,
                        cauchy,
                        sellmeier,
                        material,
                    }
                })
                .collect(),
            observer: self.observer.map(|o| FileObserver {
                position: Some(o.position.to_array()),
                target: Some(o.target.to_array()),
            }),
            sun: self.sun.map(|s| FileSun {
                direction: Some(s.direction.to_array()),
            }),
            lesson: self.lesson.as_ref().map(|l| {
                let text = |t: &Option<LessonText>| {
                    t.as_ref().map(|t| FileLessonText {
                        title: Some(t.title.clone()),
                        text: Some(t.text.clone()),
                        questions: Some(t.questions.clone()),
                    })
                };
                FileLesson {
                    en: text(&l.en),
                    fr: text(&l.fr),
                }
            }),
        };
        SceneForm(file)
    }
}

/// The colour `"#RRGGBB"` (hexadecimal, either case) names.
fn tint_colour(text: &str) -> Option<[u8; 3]> {
    let hex = text
        .strip_prefix('#')
        .filter(|h| h.len() == 6 && h.bytes().all(|b| b.is_ascii_hexdigit()))?;
    let pair = |k: usize| u8::from_str_radix(&hex[2 * k..2 * k + 2], 16).ok();
    Some([pair(0)?, pair(1)?, pair(2)?])
}
