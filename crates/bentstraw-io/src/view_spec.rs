//! The view as asked for, as one value ([`ViewSpec`]): the scene (a scene file's name and text,
//! or none, and the values that override it or make the assignment's glass), the camera, the
//! picture and the number of image points. It is read from the page's query and written back to
//! it (names as the command line's flags, messages as clap's), and written as the command line's
//! arguments of `simulate` and `render`. Resolving it (the scene loaded, the camera aimed) and
//! the explorer's own limits are the explorer's.

use std::collections::HashMap;

use bentstraw_optics::scene::WATER_INDEX;
use bentstraw_optics::setup::{SceneValues, Setup};
use bentstraw_optics::text::{clip_text, refuse_choice};
use bentstraw_optics::view::{
    PictureSpec, CLASSIC_OBSERVER, CLASSIC_STRAW, CLASSIC_WATER_HEIGHT, DEFAULT_POINTS,
    DEFAULT_PRUNE, DEFAULT_SAMPLES, DEFAULT_SIZE,
};

use crate::camera::CameraSpec;
use crate::error::Result;
use crate::gallery::GALLERY;
use crate::parse::{parse_size, parse_vec2, parse_vec3};
pub use crate::scene_input::SceneFile;

/// The name a scene file the page holds (its text in the query's `scene-file`) goes by in
/// messages and commands.
pub const PAGE_SCENE_FILE: &str = "scene.toml";

/// Most parameters in one query.
const MAX_PARAMS: usize = 40;

/// A scene file as the page's query names it (its reading from a path is `scene_input`'s).
impl SceneFile {
    /// The scene file a query names: a scene of the gallery (`scene=NAME`) or a file's whole text
    /// (`scene-file=TEXT`, named [`PAGE_SCENE_FILE`]); `None` for the assignment's glass given by
    /// its numbers.
    pub fn from_query(q: &HashMap<String, String>) -> std::result::Result<Option<Self>, String> {
        let gallery = get(q, "scene").filter(|s| !s.is_empty());
        match (gallery, get(q, "scene-file")) {
            (Some(_), Some(_)) => Err(
                "give either 'scene' (a scene of the gallery) or 'scene-file' (a scene file's text), not both"
                    .into(),
            ),
            (None, Some(text)) => Ok(Some(SceneFile {
                name: PAGE_SCENE_FILE.to_string(),
                text: text.to_string(),
            })),
            // Named as the command line finds it from any folder (the gallery is built in).
            (Some(name), None) => SceneFile::gallery(name).map(Some).ok_or_else(|| {
                let names: Vec<&str> = GALLERY.iter().map(|(stem, _)| *stem).collect();
                refuse_choice("scene", name, &names)
            }),
            (None, None) => Ok(None),
        }
    }

    /// Whether this is the gallery's scene of its name, which the page's query names by it.
    fn in_gallery(&self) -> bool {
        GALLERY
            .iter()
            .any(|(stem, text)| *stem == self.name && *text == self.text)
    }
}

/// How `simulate` judges an image point's position (`--image-model`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ImageModel {
    /// The course's convention: straight ahead along the first ray, as far as the light went.
    #[default]
    Course,
    /// A small pupil: the astigmatic foci of the bundle reaching the eye.
    Eye,
    /// Two eyes: triangulated lines of sight.
    Stereo,
}

impl ImageModel {
    /// The models' names as `--image-model` takes them.
    pub const NAMES: [&'static str; 3] = ["course", "eye", "stereo"];

    /// The model's name.
    pub fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }
}

/// The command lines a view gives: `simulate` (its image points, placed by a model) and `render`
/// (its picture).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verb {
    /// `bentstraw simulate`, with this image model.
    Simulate(ImageModel),
    /// `bentstraw render`.
    Render,
}

/// Everything that defines a view as asked for, each value parsed but not yet checked by the
/// scene's and the camera's rules (see [`ViewSpec::load`] and `camera::scene_camera`).
#[derive(Clone, Debug, PartialEq)]
pub struct ViewSpec {
    /// The scene file, or none for the assignment's glass given by its values.
    pub scene: Option<SceneFile>,
    /// The scene's values: the glass's, or those that override the file's.
    pub values: SceneValues,
    /// The camera as asked for.
    pub camera: CameraSpec,
    /// The picture as asked for.
    pub picture: PictureSpec,
    /// Image points asked for (0: none).
    pub points: usize,
}

impl Default for ViewSpec {
    /// The first view of the explorer and the page: the classic broken straw, the picture and the
    /// points as the engine draws them by default.
    fn default() -> Self {
        ViewSpec {
            scene: None,
            values: SceneValues {
                observer: Some(CLASSIC_OBSERVER),
                straw: Some(CLASSIC_STRAW),
                water_height: Some(CLASSIC_WATER_HEIGHT),
                ..SceneValues::default()
            },
            camera: CameraSpec::default(),
            picture: PictureSpec::default(),
            points: DEFAULT_POINTS,
        }
    }
}

impl ViewSpec {
    /// The view described by the query `q` (names as the command line's flags), or clap's message
    /// for the first value that cannot be read. The values' rules are checked where the view is
    /// resolved (the scene loaded, the camera aimed, the shading checked).
    ///
    /// With a scene file, a straw, water height and index given are read (a malformed one is
    /// refused) but not kept: the page shows its file as the file has it.
    pub fn from_query(q: &HashMap<String, String>) -> std::result::Result<ViewSpec, String> {
        let observer_text = required(q, "observer")?;
        let scene = SceneFile::from_query(q)?;
        // A scene file needs no straw or water: it has them.
        let (straw_text, he_text) = match scene {
            Some(_) => (get(q, "straw"), get(q, "water-height")),
            None => (
                Some(required(q, "straw")?),
                Some(required(q, "water-height")?),
            ),
        };
        let observer = flag(parse_vec3(observer_text), "observer", observer_text)?;
        let straw = straw_text
            .map(|t| flag(parse_vec2(t), "straw", t))
            .transpose()?;
        let water_height = he_text.map(|t| number(t, "water-height")).transpose()?;
        let n_water = get(q, "n-water")
            .map(|t| number(t, "n-water"))
            .transpose()?;
        let max_events = match get(q, "max-events") {
            Some(t) => number(t, "max-events")?,
            None => SceneValues::default().max_events,
        };
        let wavelength = get(q, "wavelength")
            .map(|t| number(t, "wavelength"))
            .transpose()?;
        let values = match scene {
            Some(_) => SceneValues {
                observer: Some(observer),
                max_events,
                wavelength,
                ..SceneValues::default()
            },
            None => SceneValues {
                observer: Some(observer),
                straw,
                water_height,
                n_water,
                max_events,
                wavelength,
            },
        };
        let camera = CameraSpec {
            target: get(q, "target")
                .map(|t| flag(parse_vec3(t), "target", t))
                .transpose()?,
            fov: get(q, "fov").map(|t| number(t, "fov")).transpose()?,
            size: get(q, "size")
                .map(|t| flag(parse_size(t), "size", t))
                .transpose()?,
        };
        let mut picture = PictureSpec::default();
        if let Some(mode) = get(q, "mode") {
            picture = picture.with_mode("--mode", mode)?;
        }
        if let Some(backdrop) = get(q, "backdrop") {
            picture = picture.with_backdrop("--backdrop", backdrop)?;
        }
        if let Some(light) = get(q, "light") {
            picture = picture.with_light("--light", light)?;
        }
        if let Some(samples) = get(q, "samples") {
            picture.samples = number(samples, "samples")?;
        }
        if let Some(sampling) = get(q, "sampling") {
            picture = picture.with_sampling("--sampling", sampling)?;
        }
        if let Some(prune) = get(q, "prune") {
            picture.prune = number(prune, "prune")?;
        }
        let points = match get(q, "points") {
            Some(t) => number(t, "points")?,
            None => DEFAULT_POINTS,
        };
        Ok(ViewSpec {
            scene,
            values,
            camera,
            picture,
            points,
        })
    }

    /// The page's query for this view, as [`ViewSpec::from_query`] reads it back: the scene (a
    /// gallery scene by name, any other file by its text), the values given (the straw, water
    /// height and index only for the glass: a file has its own), the event limit, the points, the
    /// mode and the backdrop always, the samples and the pruning weight when not the defaults,
    /// and the camera's values given.
    pub fn to_query(&self) -> String {
        let mut p: Vec<(&str, String)> = Vec::new();
        match &self.scene {
            Some(file) if file.in_gallery() => p.push(("scene", query_value(&file.name))),
            Some(file) => p.push(("scene-file", query_value(&file.text))),
            None => {}
        }
        let v = &self.values;
        if let Some(o) = v.observer {
            p.push(("observer", list(&o)));
        }
        if self.scene.is_none() {
            if let Some(s) = v.straw {
                p.push(("straw", list(&s)));
            }
            if let Some(h) = v.water_height {
                p.push(("water-height", h.to_string()));
            }
            if let Some(n) = v.n_water {
                p.push(("n-water", n.to_string()));
            }
        }
        p.push(("max-events", v.max_events.to_string()));
        if let Some(nm) = v.wavelength {
            p.push(("wavelength", nm.to_string()));
        }
        p.push(("points", self.points.to_string()));
        p.push(("mode", self.picture.mode().to_string()));
        p.push(("backdrop", self.picture.backdrop().to_string()));
        if self.picture.white {
            p.push(("light", self.picture.light().to_string()));
        }
        if self.picture.samples != DEFAULT_SAMPLES {
            p.push(("samples", self.picture.samples.to_string()));
        }
        if !self.picture.adaptive {
            p.push(("sampling", self.picture.sampling().to_string()));
        }
        if self.picture.prune != DEFAULT_PRUNE {
            p.push(("prune", self.picture.prune.to_string()));
        }
        let c = &self.camera;
        if let Some(t) = c.target {
            p.push(("target", list(&t)));
        }
        if let Some(f) = c.fov {
            p.push(("fov", f.to_string()));
        }
        if let Some((w, h)) = c.size {
            p.push(("size", format!("{w}x{h}")));
        }
        p.iter()
            .map(|(name, value)| format!("{name}={value}"))
            .collect::<Vec<_>>()
            .join("&")
    }

    /// The command line's arguments (after the program's name, before `--output`) of `verb` for
    /// this view: the verb, the scene's flags, then `simulate`'s points (at least one), image
    /// model (unless the course's) and light (when white), or `render`'s camera (its size always) and picture.
    pub fn args(&self, verb: Verb) -> Vec<String> {
        let mut s = vec![match verb {
            Verb::Simulate(_) => "simulate".to_string(),
            Verb::Render => "render".to_string(),
        }];
        s.extend(self.scene_args());
        match verb {
            Verb::Simulate(model) => {
                s.extend(["--points".into(), self.points.max(1).to_string()]);
                if model != ImageModel::Course {
                    s.extend(["--image-model".into(), model.name().to_string()]);
                }
                if self.picture.white {
                    s.extend(["--light".into(), self.picture.light().to_string()]);
                }
            }
            Verb::Render => {
                let c = &self.camera;
                if let Some(t) = c.target {
                    s.extend(["--target".into(), list(&t)]);
                }
                if let Some(f) = c.fov {
                    s.extend(["--fov".into(), f.to_string()]);
                }
                let (w, h) = c.size.unwrap_or(DEFAULT_SIZE);
                s.extend(["--size".into(), format!("{w}x{h}")]);
                s.extend(self.picture.args());
            }
        }
        s
    }

    /// The scene's flags: the file and the values given, the index when it is not water's for
    /// the glass (where it changes nothing) and the event limit when it is not the default.
    fn scene_args(&self) -> Vec<String> {
        let v = &self.values;
        let mut s: Vec<String> = Vec::new();
        if let Some(file) = &self.scene {
            s.extend(["--scene".into(), file.name.clone()]);
        }
        if let Some(o) = v.observer {
            s.extend(["--observer".into(), list(&o)]);
        }
        if let Some(straw) = v.straw {
            s.extend(["--straw".into(), list(&straw)]);
        }
        if let Some(h) = v.water_height {
            s.extend(["--water-height".into(), h.to_string()]);
        }
        match v.n_water {
            // Water's index is the glass's default, but it changes a file's liquid.
            Some(n) if self.scene.is_some() || n != WATER_INDEX => {
                s.extend(["--n-water".into(), n.to_string()]);
            }
            _ => {}
        }
        if v.max_events != SceneValues::default().max_events {
            s.extend(["--max-events".into(), v.max_events.to_string()]);
        }
        if let Some(nm) = v.wavelength {
            s.extend(["--wavelength".into(), nm.to_string()]);
        }
        s
    }

    /// The scene of this view, checked: the assignment's glass from the values, or the scene
    /// file's text with the values overriding it (every refusal as `--scene FILE` gives it).
    pub fn load(&self) -> Result<Setup> {
        Ok(match &self.scene {
            None => Setup::from_values(&self.values)?,
            Some(file) => Setup::from_text(&file.name, &file.text, &self.values)?,
        })
    }
}

/// Numbers as the command line's lists take them: `X,Y,Z`.
fn list(v: &[f64]) -> String {
    v.iter().map(f64::to_string).collect::<Vec<_>>().join(",")
}

/// A request's query string as name → value (percent-decoded; `+` is a space).
pub fn parse_query(query: &str) -> std::result::Result<HashMap<String, String>, String> {
    let mut out = HashMap::new();
    for (k, part) in query.split('&').filter(|p| !p.is_empty()).enumerate() {
        if k >= MAX_PARAMS {
            return Err(format!("too many parameters: at most {MAX_PARAMS}"));
        }
        let (name, value) = part.split_once('=').unwrap_or((part, ""));
        let name = percent_decode(name)?;
        let value = percent_decode(value)?;
        out.insert(name, value);
    }
    Ok(out)
}

/// `%XX` and `+` decoded; an error for a broken escape or bytes that are not UTF-8.
fn percent_decode(s: &str) -> std::result::Result<String, String> {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'+' => out.push(b' '),
            b'%' => {
                let hex = bytes
                    .get(i + 1..i + 3)
                    .and_then(|h| std::str::from_utf8(h).ok())
                    .and_then(|h| u8::from_str_radix(h, 16).ok())
                    .ok_or_else(|| format!("'{}' has a broken %-escape", clip_text(s, 40)))?;
                out.push(hex);
                i += 2;
            }
            b => out.push(b),
        }
        i += 1;
    }
    String::from_utf8(out).map_err(|_| "a parameter is not UTF-8 text".to_string())
}

/// `text` written as one value of a query (`%XX` for everything but letters, digits and `-._~`),
/// as [`parse_query`] reads it back.
pub fn query_value(text: &str) -> String {
    let mut out = String::with_capacity(text.len() * 3 / 2);
    for b in text.bytes() {
        if b.is_ascii_alphanumeric() || b"-._~".contains(&b) {
            out.push(b as char);
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out
}

/// The query's value of `name`, if given.
fn get<'a>(q: &'a HashMap<String, String>, name: &str) -> Option<&'a str> {
    q.get(name).map(String::as_str)
}

/// The query's value of `name`, or clap's message for a missing one.
pub fn required<'a>(
    q: &'a HashMap<String, String>,
    name: &str,
) -> std::result::Result<&'a str, String> {
    get(q, name).ok_or_else(|| format!("missing required parameter '{name}'"))
}

/// A number parsed as clap parses the flag `--name`'s, or its message.
pub fn number<T: std::str::FromStr>(text: &str, name: &str) -> std::result::Result<T, String> {
    text.trim().parse().map_err(|_| {
        format!(
            "invalid value '{}' for '--{name}': not a {}",
            clip_text(text, 40),
            if std::any::type_name::<T>() == "f64" {
                "number"
            } else {
                "whole number in range"
            }
        )
    })
}

/// A value parsed by the flag `--name`'s own parser, its refusal said as clap says it.
fn flag<T>(
    r: std::result::Result<T, String>,
    name: &str,
    text: &str,
) -> std::result::Result<T, String> {
    r.map_err(|e| {
        format!(
            "invalid value '{}' for '--{name}': {e}",
            clip_text(text, 40)
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn from(query: &str) -> std::result::Result<ViewSpec, String> {
        ViewSpec::from_query(&parse_query(query).unwrap())
    }

    /// What the page's query says is what [`ViewSpec::to_query`] writes: every kind of view reads
    /// back as itself.
    #[test]
    fn a_view_reads_back_from_its_query() {
        let glass = ViewSpec {
            values: SceneValues {
                observer: Some([0.1, 0.0, 0.1]),
                straw: Some([0.02, -0.01]),
                water_height: Some(0.15),
                n_water: Some(1.4),
                max_events: 7,
                wavelength: Some(486.13),
            },
            points: 1500,
            ..ViewSpec::default()
        };
        let gallery = ViewSpec {
            scene: SceneFile::gallery("reversing-arrow"),
            values: SceneValues {
                observer: Some([0.3, 0.0, 0.1]),
                ..SceneValues::default()
            },
            ..ViewSpec::default()
        };
        let page_file = ViewSpec {
            scene: Some(SceneFile {
                name: PAGE_SCENE_FILE.into(),
                text: GALLERY[3].1.replace("0.10", "0.12") + "\n# a, b & c = 100%\n",
            }),
            ..gallery.clone()
        };
        let picture = ViewSpec {
            picture: PictureSpec {
                fresnel: true,
                checker: false,
                prune: 1e-3,
                samples: 5,
                adaptive: false,
                white: true,
            },
            points: 0,
            ..ViewSpec::default()
        };
        let course = ViewSpec {
            picture: PictureSpec::default()
                .with_mode("--mode", "course")
                .unwrap(),
            ..ViewSpec::default()
        };
        let camera = ViewSpec {
            camera: CameraSpec {
                target: Some([0.0, 0.01, -0.125]),
                fov: Some(40.5),
                size: Some((40, 30)),
            },
            ..ViewSpec::default()
        };
        for view in [
            ViewSpec::default(),
            glass,
            gallery,
            page_file,
            picture,
            course,
            camera,
        ] {
            let query = view.to_query();
            assert_eq!(from(&query).as_ref(), Ok(&view), "{query}");
        }
    }

    /// The query names a gallery scene by name and any other file by its text, and carries the
    /// glass's values only for the glass.
    #[test]
    fn the_query_names_the_scene_as_the_page_does() {
        let view = from("observer=0.1,0,0.1&straw=0.02,0.01&water-height=0.15").unwrap();
        assert_eq!(
            view.to_query(),
            "observer=0.1,0,0.1&straw=0.02,0.01&water-height=0.15&max-events=10&points=20000&mode=fresnel&backdrop=checker"
        );
        let arrow = from("scene=reversing-arrow&observer=0.3,0,0.1&straw=0,0&n-water=1.4").unwrap();
        assert_eq!(arrow.values.straw, None);
        assert_eq!(arrow.values.n_water, None);
        assert!(arrow
            .to_query()
            .starts_with("scene=reversing-arrow&observer=0.3,0,0.1&max-events="));
        let file = ViewSpec {
            scene: Some(SceneFile {
                name: "mine.toml".into(),
                text: "# The textbook".into(),
            }),
            ..arrow
        };
        assert!(file
            .to_query()
            .starts_with("scene-file=%23%20The%20textbook&observer="));
    }

    /// A value that cannot be read gets clap's message, naming the flag.
    #[test]
    fn unreadable_values_get_claps_messages() {
        let msg = |s: &str| from(s).unwrap_err();
        const REF2: &str = "observer=0.1,0,0.1&straw=0.02,0.01&water-height=0.15";
        assert_eq!(
            msg("straw=0,0&water-height=0.1"),
            "missing required parameter 'observer'"
        );
        assert_eq!(
            msg("observer=0.1,0,0.1&straw=0,0"),
            "missing required parameter 'water-height'"
        );
        assert!(msg("observer=0.1,0&straw=0,0&water-height=0.1")
            .starts_with("invalid value '0.1,0' for '--observer': "));
        assert_eq!(
            msg(&format!("{REF2}&points=many")),
            "invalid value 'many' for '--points': not a whole number in range"
        );
        assert_eq!(
            msg(&format!("{REF2}&fov=wide")),
            "invalid value 'wide' for '--fov': not a number"
        );
        assert!(msg(&format!("{REF2}&mode=wave")).contains("possible values"));
        assert!(msg("scene=teapot&observer=1,0,0").contains("leaning-straw"));
        assert!(msg("scene=tank-pencil&scene-file=x&observer=1,0,0").contains("not both"));
        // With a scene file the glass's values are not needed, but a given one must be readable.
        assert!(msg("scene=tank-pencil&observer=1,0,0&straw=x").contains("'--straw'"));
    }

    /// The command lines of a view: the verb, the scene's flags, then each verb's own.
    #[test]
    fn a_views_command_lines() {
        let view = from("observer=0.1,0,0.1&straw=0.02,0.01&water-height=0.15&n-water=1.333&max-events=5&points=0&size=40x30&fov=30&samples=4").unwrap();
        assert_eq!(
            view.args(Verb::Simulate(ImageModel::Eye)).join(" "),
            "simulate --observer 0.1,0,0.1 --straw 0.02,0.01 --water-height 0.15 --max-events 5 --points 1 --image-model eye"
        );
        assert_eq!(
            view.args(Verb::Render).join(" "),
            "render --observer 0.1,0,0.1 --straw 0.02,0.01 --water-height 0.15 --max-events 5 --fov 30 --size 40x30 --mode fresnel --backdrop checker --samples 4"
        );
        let arrow = from("scene=reversing-arrow&observer=0.3,0,0.1").unwrap();
        assert_eq!(
            arrow.args(Verb::Render).join(" "),
            "render --scene reversing-arrow --observer 0.3,0,0.1 --size 800x600 --mode fresnel --backdrop checker"
        );
    }
}
