//! `bentstraw table`.

use crate::cli::TableArgs;
use crate::error::{fail, CliResult};

/// Runs `table`.
pub fn run(_args: &TableArgs) -> CliResult {
    fail("table is not implemented yet")
}
