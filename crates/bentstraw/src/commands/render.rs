//! `bentstraw render`.

use crate::cli::RenderArgs;
use crate::error::{fail, CliResult};

/// Runs `render`.
pub fn run(_args: &RenderArgs) -> CliResult {
    fail("render is not implemented yet")
}
