//! `bentstraw`: the command line over the `bentstraw-optics` library.
//!
//! This crate parses arguments, writes files and draws pictures; all physics lives in the library.

mod cli;
mod commands;
mod error;
mod files;
mod html;
mod pictures;
mod plot;

use clap::Parser;

fn main() {
    let cli = cli::Cli::parse();
    if let Err(e) = commands::run(cli) {
        eprintln!("error: {e}");
        std::process::exit(2);
    }
}
