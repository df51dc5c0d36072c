//! `--scene FILE.toml`: a scene file read and checked, the flags that override it applied, and
//! the result turned into the scene to trace: the assignment's glass when the file is of its kind
//! (traced by the fast tracers, exactly as the same flags), else a world of any shapes and media.

use std::path::{Path, PathBuf};

use bentstraw_optics::scene::{Scene, SceneError, MAX_EVENTS_LIMIT, WATER_INDEX};
use bentstraw_optics::scene_file::{Observer, SceneDescription};
use bentstraw_optics::world::World;
use bentstraw_optics::Vec3;

use crate::error::{fail, Error, Result};
use crate::files::{read_input, shown, Unread};
use crate::gallery::GALLERY;

/// Largest scene file read (1 MB): a scene is a few dozen lines.
pub const MAX_SCENE_FILE_BYTES: u64 = 1 << 20;

/// A scene ready to trace and draw, with its observer: the assignment's glass from its numbers
/// (flags, or a file of its kind), or a scene file's world of any shapes and media.
#[derive(Clone, Debug)]
pub struct Loaded {
    /// The scene file's name as messages show it, if the scene came from a file.
    pub name: Option<String>,
    /// The assignment's numbers, when the scene is of its kind.
    pub assignment: Option<Scene>,
    /// The scene file's description (the flags' overrides applied), when not of the assignment's kind.
    pub description: Option<SceneDescription>,
    /// The scene ready for tracing.
    pub world: World,
    /// The validated observer.
    pub observer: Vec3,
    /// The scene file's `[observer].target`, if any.
    pub target: Option<Vec3>,
}

impl Loaded {
    /// The assignment's scene seen from `observer` (both already validated).
    pub fn assignment(scene: Scene, observer: Vec3) -> Loaded {
        Loaded {
            name: None,
            assignment: Some(scene),
            description: None,
            world: World::assignment(&scene),
            observer,
            target: None,
        }
    }

    /// The scene file's name, or empty when the scene came from flags.
    pub fn name(&self) -> &str {
        self.name.as_deref().unwrap_or("")
    }
}

/// The scene's inputs as the flags give them: a file, or the values, or a file and overrides.
#[derive(Clone, Debug, Default)]
pub struct SceneSource {
    /// `--scene`.
    pub file: Option<PathBuf>,
    /// `--observer`.
    pub observer: Option<[f64; 3]>,
    /// `--straw`.
    pub straw: Option<[f64; 2]>,
    /// `--water-height`.
    pub water_height: Option<f64>,
    /// `--n-water`.
    pub n_water: Option<f64>,
    /// `--max-events`.
    pub max_events: u32,
}

/// The scene and observer as plain values, checked by [`SceneValues::scene_and_observer`] (the
/// command line's flags and the explorer's queries both end here).
#[derive(Debug, Clone)]
pub struct SceneValues {
    /// Observer position X,Y,Z in metres.
    pub observer: [f64; 3],
    /// Straw axis XP,YP in metres.
    pub straw: [f64; 2],
    /// Water height in metres.
    pub water_height: f64,
    /// Refractive index of the water.
    pub n_water: f64,
    /// Most events (refractions and total reflections) a ray may undergo.
    pub max_events: u32,
}

impl SceneValues {
    /// The scene and observer, checked against the rules of valid inputs.
    pub fn scene_and_observer(&self) -> Result<(Scene, Vec3)> {
        let scene = Scene::new(
            self.straw[0],
            self.straw[1],
            self.water_height,
            self.n_water,
            self.max_events,
        )?;
        let observer = Vec3::from_array(self.observer);
        scene.validate_observer(observer)?;
        Ok((scene, observer))
    }
}

impl SceneSource {
    /// The validated scene and observer: from the flags alone as always, or from the scene file
    /// with the flags overriding it. Every value goes through the same rules as the flags'; a
    /// file of the assignment's kind gives exactly the scene the same flags give.
    pub fn load(&self) -> Result<Loaded> {
        let Some(path) = &self.file else {
            let (Some(observer), Some(straw), Some(water_height)) =
                (self.observer, self.straw, self.water_height)
            else {
                return fail(
                    "the scene needs --observer, --straw and --water-height, or a --scene file",
                );
            };
            let (scene, observer) = SceneValues {
                observer,
                straw,
                water_height,
                n_water: self.n_water.unwrap_or(WATER_INDEX),
                max_events: self.max_events,
            }
            .scene_and_observer()?;
            return Ok(Loaded::assignment(scene, observer));
        };
        if let Some((stem, text)) = built_in(path) {
            return self.load_text(stem, text);
        }
        self.load_description(shown(path), read_scene_file(path)?)
    }

    /// [`SceneSource::load`] for the scene file whose text is `text` and whose name, as messages
    /// show it, is `name` (the page's scene files; `self.file` is not read).
    pub fn load_text(&self, name: &str, text: &str) -> Result<Loaded> {
        self.load_description(name.to_string(), parse_scene_text(name, text)?)
    }

    /// The scene file `name` read as `description`, the flags applied and checked.
    fn load_description(&self, name: String, mut description: SceneDescription) -> Result<Loaded> {
        let overrides: Vec<&str> = [
            (self.straw.is_some(), "--straw"),
            (self.water_height.is_some(), "--water-height"),
            (self.n_water.is_some(), "--n-water"),
        ]
        .iter()
        .filter(|(given, _)| *given)
        .map(|(_, flag)| *flag)
        .collect();
        let (straws, liquids) = (description.straws.len(), description.liquids.len());
        if !overrides.is_empty() && (straws != 1 || liquids != 1) {
            return fail(format!(
                "{} can change a scene file's values only when it has one straw and one liquid: {name} has {straws} straw(s) and {liquids} liquid(s)",
                overrides.join(", ")
            ));
        }
        let observer = match (self.observer, description.observer) {
            (Some(o), _) => o,
            (None, Some(o)) => o.position.to_array(),
            (None, None) => {
                return fail(format!("{name} has no [observer]: give --observer X,Y,Z"))
            }
        };
        if let Some(spec) = description.spec_scene() {
            let (scene, observer) = SceneValues {
                observer,
                straw: self.straw.unwrap_or([spec.straw_x(), spec.straw_y()]),
                water_height: self.water_height.unwrap_or(spec.water_height()),
                n_water: self.n_water.unwrap_or(spec.n_water()),
                max_events: self.max_events,
            }
            .scene_and_observer()?;
            return Ok(Loaded {
                target: description.observer.map(|o| o.target),
                ..Loaded::assignment(scene, observer)
            });
        }
        // Any other scene: the overrides change the file's one straw and liquid, and the whole
        // scene, observer included, is checked again by the file's rules.
        if let Some([x, y]) = self.straw {
            description.straws[0].x = x;
            description.straws[0].y = y;
        }
        if let Some(h) = self.water_height {
            description.liquids[0].top = h;
        }
        if let Some(n) = self.n_water {
            description.liquids[0].index = n;
        }
        if self.max_events == 0 || self.max_events > MAX_EVENTS_LIMIT {
            return Err(SceneError::MaxEvents(self.max_events).into());
        }
        let target = description.observer.map(|o| o.target);
        let position = Vec3::from_array(observer);
        let mut checked = description.clone();
        checked.observer = Some(Observer {
            position,
            // Any point away from the eye: the target is the camera's business.
            target: target
                .filter(|t| *t != position)
                .unwrap_or(position + Vec3::Z),
        });
        let flagged = |error| Error::SceneFile {
            name: name.clone(),
            flagged: true,
            error,
        };
        // The world of the scene as the flags make it, checked by every rule of a file.
        let world = World::new(&checked, self.max_events).map_err(flagged)?;
        Ok(Loaded {
            name: Some(name),
            assignment: None,
            world,
            description: Some(description),
            observer: position,
            target,
        })
    }
}

/// The world of a scene file's text named `name`, seen from its own `[observer]`, with the event
/// limit `max_events` (for the built-in gallery).
pub fn file_world(name: &str, text: &str, max_events: u32) -> Result<Loaded> {
    let description = parse_scene_text(name, text)?;
    let Some(observer) = description.observer else {
        return fail(format!("{name} has no [observer]"));
    };
    Ok(Loaded {
        name: Some(name.to_string()),
        assignment: None,
        world: World::new(&description, max_events).map_err(|error| Error::SceneFile {
            name: name.to_string(),
            flagged: false,
            error,
        })?,
        description: Some(description),
        observer: observer.position,
        target: Some(observer.target),
    })
}

/// The gallery's scene `path` names, when no such file exists: `leaning-straw` or
/// `leaning-straw.toml` from any folder (a file of that name, where there is one, wins).
pub fn built_in(path: &Path) -> Option<(&'static str, &'static str)> {
    if path.exists() || path.components().count() != 1 {
        return None;
    }
    let name = path.to_str()?;
    let stem = name.strip_suffix(".toml").unwrap_or(name);
    GALLERY.iter().find(|(s, _)| *s == stem).copied()
}

/// Reads and checks the scene file at `path`; every refusal names the file.
pub fn read_scene_file(path: &Path) -> Result<SceneDescription> {
    parse_scene_text(&shown(path), &read_scene_text(path)?)
}

/// The text of the scene file at `path` (at most [`MAX_SCENE_FILE_BYTES`], UTF-8), not checked
/// further; every refusal names the file.
pub fn read_scene_text(path: &Path) -> Result<String> {
    let name = shown(path);
    let bytes = read_input(path, MAX_SCENE_FILE_BYTES).map_err(|unread| match unread {
        Unread::Io(source) => Error::Io {
            action: "read the scene file",
            path: path.to_path_buf(),
            source,
        },
        Unread::NotAFile(why) => {
            Error::Refused(format!("cannot read the scene file {name}: {why}"))
        }
        Unread::TooLarge(size) => Error::Refused(format!(
            "the scene file {name} is {size}: a scene file is at most {MAX_SCENE_FILE_BYTES} bytes (1 MB), not read"
        )),
    })?;
    String::from_utf8(bytes).map_err(|e| {
        Error::Refused(format!(
            "the scene file {name} is not UTF-8 text: byte {} is not valid UTF-8",
            e.utf8_error().valid_up_to() + 1
        ))
    })
}

/// The scene file named `name` whose text is `text`, read and checked by the scene file's rules
/// (at most [`MAX_SCENE_FILE_BYTES`]); every refusal names the file.
pub fn parse_scene_text(name: &str, text: &str) -> Result<SceneDescription> {
    if text.len() as u64 > MAX_SCENE_FILE_BYTES {
        return fail(format!(
            "the scene file {name} is {} bytes: a scene file is at most {MAX_SCENE_FILE_BYTES} bytes (1 MB), not read",
            text.len()
        ));
    }
    SceneDescription::from_toml(text).map_err(|error| Error::SceneFile {
        name: name.to_string(),
        flagged: false,
        error,
    })
}
