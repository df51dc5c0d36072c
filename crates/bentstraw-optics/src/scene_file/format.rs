//! The scene-file format itself: TOML read into a [`SceneDescription`] (every key named as a
//! path when it breaks a rule) and written back.

use serde::{Deserialize, Serialize};

use super::*;
use crate::scene::clip_text;

/// Longest user text (a name, a shape) quoted whole in a message, in characters.
const QUOTED_MAX: usize = 40;

// The file's form: what TOML may say, every optional key an `Option`, nothing else accepted.

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct FileScene {
    container: FileContainer,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    liquid: Vec<FileLiquid>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    straw: Vec<FileStraw>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    coin: Vec<FileCoin>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    card: Vec<FileCard>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    observer: Option<FileObserver>,
}

#[derive(Deserialize, Serialize, Default)]
#[serde(deny_unknown_fields)]
struct FileContainer {
    shape: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    radius: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    half_x: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    half_y: Option<f64>,
    height: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    wall: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    bottom: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    index: Option<f64>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct FileLiquid {
    name: String,
    index: f64,
    top: f64,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct FileStraw {
    x: f64,
    y: f64,
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
    x: f64,
    y: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    radius: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    thickness: Option<f64>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct FileCard {
    center: [f64; 3],
    #[serde(default, skip_serializing_if = "Option::is_none")]
    facing: Option<f64>,
    width: f64,
    height: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    picture: Option<String>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct FileObserver {
    position: [f64; 3],
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
fn syntax_error(text: &str, key: String, e: &toml::de::Error) -> SceneFileError {
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
    let (key, what) = match what
        .strip_prefix("missing field `")
        .and_then(|rest| rest.strip_suffix('`'))
    {
        Some(field) => {
            let full = if key.is_empty() {
                field.to_string()
            } else {
                format!("{key}.{field}")
            };
            (full, " is missing: it is required".to_string())
        }
        None if key.is_empty() => (key, what),
        None => (key, format!(": {what}")),
    };
    let place = match line {
        Some(l) => format!("line {l}: "),
        None => String::new(),
    };
    let message = format!("{place}{key}{what}");
    SceneFileError { key, line, message }
}

impl SceneDescription {
    /// Reads a scene file's text: TOML of the scene-file format, defaults applied, every rule
    /// checked ([`SceneDescription::validate`]).
    pub fn from_toml(text: &str) -> Result<SceneDescription, SceneFileError> {
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
    /// as the description has no place for them.
    fn from_file(file: FileScene) -> Result<SceneDescription, SceneFileError> {
        let c = &file.container;
        let given = |key: &str, value: Option<f64>, rule: &str| match value {
            Some(v) => Err(refuse(&format!("container.{key}"), v, rule)),
            None => Ok(()),
        };
        let need = |key: &str, value: Option<f64>, shape: &str| {
            value.ok_or_else(|| {
                refuse_key(
                    &format!("container.{key}"),
                    &format!("is missing: a {shape} needs it"),
                )
            })
        };
        let container = match c.shape.as_str() {
            "glass" => {
                let not_glass = "a glass has no half widths (they are a tank's): give its radius";
                given("half_x", c.half_x, not_glass)?;
                given("half_y", c.half_y, not_glass)?;
                Container::Glass(Glass {
                    radius: need("radius", c.radius, "glass")?,
                    height: c.height,
                    wall: c.wall.unwrap_or(0.0),
                    bottom: c.bottom.unwrap_or(0.0),
                    index: c.index.unwrap_or(DEFAULT_CONTAINER_INDEX),
                })
            }
            "tank" => {
                given(
                    "radius",
                    c.radius,
                    "a tank has no radius (a glass has): give its half widths half_x and half_y",
                )?;
                let thin =
                    "a tank's walls and bottom have zero thickness (only a glass's may be thick)";
                given("wall", c.wall, thin)?;
                given("bottom", c.bottom, thin)?;
                given(
                    "index",
                    c.index,
                    "a tank's walls have zero thickness, so it has no index of its own",
                )?;
                Container::Tank(Tank {
                    half_x: need("half_x", c.half_x, "tank")?,
                    half_y: need("half_y", c.half_y, "tank")?,
                    height: c.height,
                })
            }
            other => {
                return Err(refuse_key(
                    "container.shape",
                    &format!(
                        "\"{}\" is not a shape: it must be \"glass\" or \"tank\"",
                        clip_text(other, QUOTED_MAX)
                    ),
                ))
            }
        };
        let cards = file
            .card
            .iter()
            .enumerate()
            .map(|(i, c)| {
                let picture = match c.picture.as_deref().unwrap_or("arrow") {
                    "arrow" => Picture::Arrow,
                    "none" => Picture::None,
                    other => {
                        return Err(refuse_key(
                            &format!("card[{}].picture", i + 1),
                            &format!(
                                "\"{}\" is not a picture: it must be \"arrow\" or \"none\"",
                                clip_text(other, QUOTED_MAX)
                            ),
                        ))
                    }
                };
                Ok(Card {
                    center: Vec3::from_array(c.center),
                    facing_deg: c.facing.unwrap_or(0.0),
                    width: c.width,
                    height: c.height,
                    picture,
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        // Without a target, the eye looks at the middle of the container.
        let middle = Vec3::new(0.0, 0.0, container.height() / 2.0);
        Ok(SceneDescription {
            container,
            liquids: file
                .liquid
                .into_iter()
                .map(|l| Liquid {
                    name: l.name,
                    index: l.index,
                    top: l.top,
                })
                .collect(),
            straws: file
                .straw
                .iter()
                .map(|s| Straw {
                    x: s.x,
                    y: s.y,
                    tilt_deg: s.tilt.unwrap_or(0.0),
                    azimuth_deg: s.azimuth.unwrap_or(0.0),
                    radius: s.radius.unwrap_or(STRAW_RADIUS),
                    length: s.length.unwrap_or(STRAW_HEIGHT),
                })
                .collect(),
            coins: file
                .coin
                .iter()
                .map(|c| Coin {
                    x: c.x,
                    y: c.y,
                    radius: c.radius.unwrap_or(DEFAULT_COIN_RADIUS),
                    thickness: c.thickness.unwrap_or(DEFAULT_COIN_THICKNESS),
                })
                .collect(),
            cards,
            observer: file.observer.map(|o| Observer {
                position: Vec3::from_array(o.position),
                target: o.target.map_or(middle, Vec3::from_array),
            }),
        })
    }

    /// The description as a scene file's TOML, every value written out (defaults too), so that
    /// reading it back gives the same description.
    pub fn to_toml(&self) -> String {
        let container = match &self.container {
            Container::Glass(g) => FileContainer {
                shape: "glass".into(),
                radius: Some(g.radius),
                height: g.height,
                wall: Some(g.wall),
                bottom: Some(g.bottom),
                index: Some(g.index),
                ..FileContainer::default()
            },
            Container::Tank(t) => FileContainer {
                shape: "tank".into(),
                half_x: Some(t.half_x),
                half_y: Some(t.half_y),
                height: t.height,
                ..FileContainer::default()
            },
        };
        let file = FileScene {
            container,
            liquid: self
                .liquids
                .iter()
                .map(|l| FileLiquid {
                    name: l.name.clone(),
                    index: l.index,
                    top: l.top,
                })
                .collect(),
            straw: self
                .straws
                .iter()
                .map(|s| FileStraw {
                    x: s.x,
                    y: s.y,
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
                    x: c.x,
                    y: c.y,
                    radius: Some(c.radius),
                    thickness: Some(c.thickness),
                })
                .collect(),
            card: self
                .cards
                .iter()
                .map(|c| FileCard {
                    center: c.center.to_array(),
                    facing: Some(c.facing_deg),
                    width: c.width,
                    height: c.height,
                    picture: Some(c.picture.word().to_string()),
                })
                .collect(),
            observer: self.observer.map(|o| FileObserver {
                position: o.position.to_array(),
                target: Some(o.target.to_array()),
            }),
        };
        // Tables of numbers and strings always have a TOML form.
        toml::to_string(&file).expect("a scene description is plain TOML data")
    }
}
