//! `bentstraw`: the command line over the `bentstraw-optics` library.
//!
//! This crate parses arguments, writes files and draws pictures; all physics lives in the library.

mod cli;
mod commands;
mod error;
mod explore;
mod progress;

use bentstraw_optics::text::clip_text;
use clap::error::{ContextKind, ContextValue, ErrorKind};
use clap::Parser;

fn main() {
    progress::remove_temporaries_on_interrupt();
    let cli = match cli::Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => match e.kind() {
            // Help and version are not errors: clap prints them as it always does.
            ErrorKind::DisplayHelp
            | ErrorKind::DisplayVersion
            | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => e.exit(),
            _ => {
                progress::tell(&format!("{}\n", one_line(&e)));
                std::process::exit(2);
            }
        },
    };
    if let Err(e) = commands::run(cli) {
        if bentstraw_io::files::interrupted() {
            // The interruption's handler says so and ends the program with its exit code.
            progress::wait_for_interruption();
        }
        progress::tell(&format!("error: {e}\n"));
        std::process::exit(2);
    }
}

/// A clap error as one line: its first line, with the missing arguments or clap's tip folded in,
/// and the user's values clipped.
fn one_line(e: &clap::Error) -> String {
    let mut line = first_line(e);
    for kind in [ContextKind::InvalidValue, ContextKind::InvalidArg] {
        if let Some(ContextValue::String(value)) = e.get(kind) {
            if value.chars().count() > bentstraw_io::parse::QUOTED_MAX {
                line = line.replace(
                    value.as_str(),
                    &clip_text(value, bentstraw_io::parse::QUOTED_MAX),
                );
            }
        }
    }
    line
}

/// A clap error's first line with the missing arguments or clap's tip folded in.
fn first_line(e: &clap::Error) -> String {
    if e.kind() == ErrorKind::MissingRequiredArgument {
        if let Some(ContextValue::Strings(args)) = e.get(ContextKind::InvalidArg) {
            return format!(
                "error: missing required argument(s): {} (see '{} --help')",
                args.join(", "),
                command_of(&e.render().to_string())
            );
        }
    }
    let text = e.render().to_string();
    let mut lines = text.lines().map(str::trim).filter(|l| !l.is_empty());
    let mut line = lines
        .next()
        .unwrap_or("error: invalid arguments")
        .to_string();
    // clap's suggestions ("tip: a similar argument exists: '--observer'") and lists of possible
    // values are worth keeping; the usage lines that follow them are not.
    for extra in lines {
        if extra.starts_with("tip:") {
            line.push_str(&format!(" ({extra})"));
        } else if extra.starts_with("[possible values:") {
            line.push_str(&format!(" {extra}"));
        }
    }
    line
}

/// The command named in a rendered clap error's usage line, e.g. `bentstraw simulate`.
fn command_of(rendered: &str) -> String {
    let usage = rendered
        .lines()
        .find_map(|l| l.trim().strip_prefix("Usage: "))
        .unwrap_or("bentstraw");
    usage
        .split_whitespace()
        .take_while(|w| !w.starts_with(['[', '<', '-']))
        .collect::<Vec<_>>()
        .join(" ")
}
