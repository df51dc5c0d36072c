//! The command line's one error type: a message for the user, and exit code 2.

use std::fmt;

use bentstraw_optics::scene::SceneError;

/// An error to show the user, one line, naming the value and the rule.
#[derive(Debug)]
pub struct CliError(pub String);

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for CliError {}

impl From<SceneError> for CliError {
    fn from(e: SceneError) -> Self {
        CliError(e.to_string())
    }
}

/// A `CliError` from anything printable.
pub fn fail<T>(msg: impl Into<String>) -> Result<T, CliError> {
    Err(CliError(msg.into()))
}

/// Shorthand result type.
pub type CliResult<T = ()> = Result<T, CliError>;

impl From<bentstraw_io::Error> for CliError {
    fn from(e: bentstraw_io::Error) -> Self {
        CliError(e.to_string())
    }
}
