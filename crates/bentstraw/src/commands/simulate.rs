//! `bentstraw simulate`.

use crate::cli::SimulateArgs;
use crate::error::{fail, CliResult};

/// Runs `simulate`.
pub fn run(_args: &SimulateArgs) -> CliResult {
    fail("simulate is not implemented yet")
}
