//! `--scene FILE.toml`: a scene file (or a gallery scene by name) read ([`SceneFile::read`], the
//! one reading of scene files), which a [`ViewSpec`](crate::ViewSpec) holds and makes into the
//! one scene value ([`Setup`]) with the flags that override it (`ViewSpec::load`).

use std::path::Path;

use bentstraw_optics::scene_file::SceneDescription;
use bentstraw_optics::setup::{self, SceneValues, Setup, MAX_SCENE_FILE_BYTES};
use bentstraw_optics::text;

use crate::error::{Error, Result};
use crate::files::{read_input, shown, Unread};
use crate::gallery::{named_scenes, GALLERY};

/// A scene file as a view names it: its name (as messages and commands show it) and its text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneFile {
    /// The name: a built-in scene's, the page's own (`view_spec::PAGE_SCENE_FILE`), or a path as
    /// shown.
    pub name: String,
    /// The whole text of the file.
    pub text: String,
}

impl SceneFile {
    /// The gallery's scene `name`, if there is one of that name.
    pub fn gallery(name: &str) -> Option<SceneFile> {
        GALLERY
            .iter()
            .find(|(stem, _)| *stem == name)
            .map(|(stem, text)| SceneFile {
                name: stem.to_string(),
                text: text.to_string(),
            })
    }

    /// The scene file `--scene PATH` names, read (not yet checked): a built-in scene by its name
    /// ([`built_in`]), else the file (at most [`MAX_SCENE_FILE_BYTES`], UTF-8), named as messages
    /// show its path.
    pub fn read(path: &Path) -> Result<SceneFile> {
        if let Some((stem, text)) = built_in(path) {
            return Ok(SceneFile {
                name: stem.to_string(),
                text: text.to_string(),
            });
        }
        let near = path.to_str().filter(|name| {
            !path.exists()
                && path.components().count() == 1
                && text::did_you_mean(name, named_scenes().map(|(stem, _)| stem)).is_some()
        });
        if let Some(name) = near {
            return Err(Error::Refused(format!(
                "there is no scene file {name}, and {}",
                gallery_miss(name)
            )));
        }
        Ok(SceneFile {
            name: shown(path),
            text: read_scene_text(path)?,
        })
    }
}

/// Why `name` is no gallery scene: the names it may be a slip for, and the gallery's names.
pub fn gallery_miss(name: &str) -> String {
    let stems: Vec<&str> = named_scenes().map(|(stem, _)| stem).collect();
    let hint = text::did_you_mean(
        name.strip_suffix(".toml").unwrap_or(name),
        stems.iter().copied(),
    )
    .map_or(String::new(), |h| h + " ");
    format!(
        "no gallery scene is called '{}': {hint}the gallery has {}",
        text::clip_text(name, 60),
        stems.join(", ")
    )
}

/// The gallery's scene `name` (its file's text), seen from its own `[observer]`, with the event
/// limit `max_events`.
pub fn gallery_setup(name: &str, text: &str, max_events: u32) -> Result<Setup> {
    let values = SceneValues {
        max_events,
        ..SceneValues::default()
    };
    Ok(Setup::from_text(name, text, &values)?)
}

/// The built-in scene `path` names (the assignment's `spec` or a gallery scene), when no such file
/// exists: `leaning-straw` or `leaning-straw.toml` from any folder (a file of that name, where
/// there is one, wins).
pub fn built_in(path: &Path) -> Option<(&'static str, &'static str)> {
    if path.exists() || path.components().count() != 1 {
        return None;
    }
    let name = path.to_str()?;
    let stem = name.strip_suffix(".toml").unwrap_or(name);
    named_scenes().find(|(s, _)| *s == stem)
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
    Ok(setup::parse_scene_text(name, text)?)
}
