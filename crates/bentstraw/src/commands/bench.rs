//! `bentstraw bench`.

use crate::cli::BenchArgs;
use crate::error::{fail, CliResult};

/// Runs `bench`.
pub fn run(_args: &BenchArgs) -> CliResult {
    fail("bench is not implemented yet")
}
