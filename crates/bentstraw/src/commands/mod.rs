//! One module per command.

pub mod bench;
pub mod check;
pub mod grade;
pub mod render;
pub mod simulate;
pub mod table;

use crate::cli::{Cli, Command, TableArgs};
use crate::error::CliResult;

/// Runs the command the user asked for (`table` when none).
pub fn run(cli: Cli) -> CliResult {
    match cli.command {
        None => table::run(&TableArgs {
            out: "out".into(),
            points: 20000,
            lang: Default::default(),
            scene: None,
            observer: None,
            wavelength: None,
            pdf: None,
        }),
        Some(Command::Simulate(a)) => simulate::run(&a),
        Some(Command::Table(a)) => table::run(&a),
        Some(Command::Render(a)) => render::run(&a),
        Some(Command::Bench(a)) => bench::run(&a),
        Some(Command::Check(a)) => {
            // A fail is a result, not an error: exit code 1 (errors get 2).
            if !check::run(&a)? {
                use std::io::Write as _;
                let _ = std::io::stdout().flush();
                std::process::exit(1);
            }
            Ok(())
        }
        Some(Command::Grade(a)) => grade::run(&a),
        Some(Command::Explore(a)) => crate::explore::run(&a),
    }
}
