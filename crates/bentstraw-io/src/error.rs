//! The I/O library's one error type: every refusal and failure as one line for the user.

use std::fmt;
use std::io;
use std::path::{Path, PathBuf};

use bentstraw_optics::scene::SceneError;
use bentstraw_optics::scene_file::SceneFileError;
use bentstraw_optics::setup::SetupError;
use bentstraw_optics::text::clip_text;

/// Longest path quoted in a message, in characters.
const SHOWN_PATH_MAX: usize = 100;

/// A path for a message, clipped (a hostile 5 kB path must not flood the terminal).
pub fn shown(path: &Path) -> String {
    clip_text(&path.display().to_string(), SHOWN_PATH_MAX)
}

/// Why an output could not be made or an input not be read, with the message the user sees.
#[derive(Debug)]
pub enum Error {
    /// A rule broken (a value out of range, an output that may not be replaced…): its message.
    Refused(String),
    /// A file operation failed: `cannot {action} {path}: {source}`.
    Io {
        /// What was being done, e.g. `write` or `read the scene file`.
        action: &'static str,
        /// The file or folder.
        path: PathBuf,
        /// The system's reason.
        source: io::Error,
    },
    /// A picture or figure could not be drawn or encoded (PNG, SVG, PDF): its message.
    Encode(String),
    /// The scene's values break the physics library's rules.
    Scene(SceneError),
    /// The scene file `name` breaks the rules of scene files (`flagged`: once the flags that
    /// override it were applied): `{name}: {error}`, every broken rule as data in `error`.
    SceneFile {
        /// The file's name as messages show it.
        name: String,
        /// Whether the rules were broken by the flags' values rather than the file's own.
        flagged: bool,
        /// Every broken rule.
        error: Box<SceneFileError>,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Refused(message) | Error::Encode(message) => f.write_str(message),
            Error::Io {
                action,
                path,
                source,
            } => write!(f, "cannot {action} {}: {source}", shown(path)),
            Error::Scene(e) => write!(f, "{e}"),
            Error::SceneFile {
                name,
                flagged: false,
                error,
            } => write!(f, "{name}: {error}"),
            Error::SceneFile {
                name,
                flagged: true,
                error,
            } => write!(f, "{name} with the flags given: {error}"),
        }
    }
}

impl std::error::Error for Error {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Error::Io { source, .. } => Some(source),
            _ => None,
        }
    }
}

impl From<SceneError> for Error {
    fn from(e: SceneError) -> Self {
        Error::Scene(e)
    }
}

impl From<SetupError> for Error {
    fn from(e: SetupError) -> Self {
        match e {
            SetupError::Scene(e) => Error::Scene(e),
            SetupError::SceneFile {
                name,
                flagged,
                error,
            } => Error::SceneFile {
                name,
                flagged,
                error,
            },
            SetupError::Refused(message) => Error::Refused(message),
        }
    }
}

/// An [`Error::Refused`] from anything printable.
pub fn fail<T>(msg: impl Into<String>) -> Result<T> {
    Err(Error::Refused(msg.into()))
}

/// The library's result type.
pub type Result<T = (), E = Error> = std::result::Result<T, E>;
