//! `--scene FILE.toml`: a scene file read and checked, the flags that override it applied, and
//! the result turned into the scene the tracer knows (or refused, when this version cannot
//! trace it).

use std::io::Read as _;
use std::path::{Path, PathBuf};

use bentstraw_optics::scene::{Scene, WATER_INDEX};
use bentstraw_optics::scene_file::SceneDescription;
use bentstraw_optics::Vec3;

use crate::cli::{OptionalSceneFlags, SceneArgs, SceneFlags};
use crate::error::{fail, CliError, CliResult};
use crate::files::shown;

/// Largest scene file read (1 MB): a scene is a few dozen lines.
pub const MAX_SCENE_FILE_BYTES: u64 = 1 << 20;

/// Most reasons an unsupported scene's refusal names.
const MAX_REASONS: usize = 5;

/// The scene and observer of one run, with the target a scene file suggests.
#[derive(Clone, Copy, Debug)]
pub struct Resolved {
    /// The validated scene.
    pub scene: Scene,
    /// The validated observer.
    pub observer: Vec3,
    /// The scene file's `[observer].target`, if it came from a file.
    pub target: Option<Vec3>,
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

impl SceneFlags {
    /// The flags as a scene source.
    pub fn source(&self) -> SceneSource {
        SceneSource {
            file: self.scene.clone(),
            observer: self.observer,
            straw: self.straw,
            water_height: self.water_height,
            n_water: self.n_water,
            max_events: self.max_events,
        }
    }

    /// The validated scene and observer (and a scene file's target).
    pub fn resolve(&self) -> CliResult<Resolved> {
        self.source().resolve()
    }

    /// The validated scene and observer.
    pub fn scene_and_observer(&self) -> CliResult<(Scene, Vec3)> {
        let r = self.resolve()?;
        Ok((r.scene, r.observer))
    }
}

impl OptionalSceneFlags {
    /// The flags as a scene source.
    pub fn source(&self) -> SceneSource {
        SceneSource {
            file: self.scene.clone(),
            observer: self.observer,
            straw: self.straw,
            water_height: self.water_height,
            n_water: self.n_water,
            max_events: self.max_events,
        }
    }
}

impl SceneSource {
    /// The validated scene and observer: from the flags alone as always, or from the scene file
    /// with the flags overriding it. Every value goes through the same rules as the flags'.
    pub fn resolve(&self) -> CliResult<Resolved> {
        let Some(path) = &self.file else {
            let (Some(observer), Some(straw), Some(water_height)) =
                (self.observer, self.straw, self.water_height)
            else {
                return fail(
                    "the scene needs --observer, --straw and --water-height, or a --scene file",
                );
            };
            let (scene, observer) = SceneArgs {
                observer,
                straw,
                water_height,
                n_water: self.n_water.unwrap_or(WATER_INDEX),
                max_events: self.max_events,
            }
            .scene_and_observer()?;
            return Ok(Resolved {
                scene,
                observer,
                target: None,
            });
        };
        let name = shown(path);
        let description = read_scene_file(path)?;
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
        let Some(spec) = description.spec_scene() else {
            // The first few reasons: a file of a thousand different straws must not flood the
            // terminal.
            let reasons = description.unsupported();
            let mut said = reasons[..reasons.len().min(MAX_REASONS)].join(", ");
            if reasons.len() > MAX_REASONS {
                said.push_str(&format!(" and {} more", reasons.len() - MAX_REASONS));
            }
            return fail(format!(
                "{name} is a valid scene, but this version traces only scenes of the assignment's kind \
                 (a glass of radius 0.04 m and height 0.2 m with walls of no thickness, at most one liquid, \
                 one upright straw of radius 0.005 m and length 0.25 m, nothing else): it has {said}"
            ));
        };
        let observer = match (self.observer, description.observer) {
            (Some(o), _) => o,
            (None, Some(o)) => o.position.to_array(),
            (None, None) => {
                return fail(format!("{name} has no [observer]: give --observer X,Y,Z"))
            }
        };
        let (scene, observer) = SceneArgs {
            observer,
            straw: self.straw.unwrap_or([spec.straw_x, spec.straw_y]),
            water_height: self.water_height.unwrap_or(spec.water_height),
            n_water: self.n_water.unwrap_or(spec.n_water),
            max_events: self.max_events,
        }
        .scene_and_observer()?;
        Ok(Resolved {
            scene,
            observer,
            target: description.observer.map(|o| o.target),
        })
    }
}

/// Reads and checks the scene file at `path`; every refusal names the file.
pub fn read_scene_file(path: &Path) -> CliResult<SceneDescription> {
    let name = shown(path);
    let cannot = |e: std::io::Error| CliError(format!("cannot read the scene file {name}: {e}"));
    let meta = std::fs::metadata(path).map_err(cannot)?;
    if meta.is_dir() {
        return fail(format!("cannot read the scene file {name}: it is a folder"));
    }
    let too_large = |bytes: u64| {
        CliError(format!(
            "the scene file {name} is {bytes} bytes: a scene file is at most {MAX_SCENE_FILE_BYTES} bytes (1 MB), not read"
        ))
    };
    if meta.len() > MAX_SCENE_FILE_BYTES {
        return Err(too_large(meta.len()));
    }
    // Read at most one byte past the limit, in case it grew (or is a device that never ends).
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(MAX_SCENE_FILE_BYTES + 1).read_to_end(&mut bytes))
        .map_err(cannot)?;
    if bytes.len() as u64 > MAX_SCENE_FILE_BYTES {
        return Err(too_large(bytes.len() as u64));
    }
    let text = String::from_utf8(bytes).map_err(|e| {
        CliError(format!(
            "the scene file {name} is not UTF-8 text: byte {} is not valid UTF-8",
            e.utf8_error().valid_up_to() + 1
        ))
    })?;
    SceneDescription::from_toml(&text).map_err(|e| CliError(format!("{name}: {e}")))
}
