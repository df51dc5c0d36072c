//! `bentstraw check FILE`: judges a solution's image points one by one and tells what part of the
//! true image it misses; a summary for people, or one JSON object for graders' scripts.
//!
//! Exit codes: 0 when every point is correct and the coverage complete, 1 otherwise, 2 for bad input
//! (a malformed file, a scene outside the rules) — so a script can grade a folder of submissions.

use std::time::Instant;

use crate::cli::CheckArgs;
use crate::error::{CliError, CliResult};
use bentstraw_io::files::check_writable;
use bentstraw_io::grade::check_file;
use bentstraw_io::solution::{json_report, summary, CheckOptions};
use bentstraw_optics::text::clip_text;

/// Runs `check`; `Ok(true)` for a pass, `Ok(false)` for a fail.
pub fn run(args: &CheckArgs) -> CliResult<bool> {
    let loaded = crate::cli::load_scene(&args.scene.view()?)?;
    let (checked, observer) = (&loaded, loaded.observer);
    let options = CheckOptions {
        tolerance: args.tolerance,
        min_coverage: args.min_coverage,
        worst: args.worst,
    };
    options.validate()?;
    if let Some(p) = &args.plot {
        bentstraw_io::plot::FigureFormat::of(p).map_err(|e| CliError(format!("--plot {}", e)))?;
        check_writable(p)?;
    }
    let started = Instant::now();
    let (solution, report) = check_file(checked, &args.file, args.tolerance, args.min_coverage)?;
    let seconds = started.elapsed().as_secs_f64();
    if let Some(p) = &args.plot {
        let title = format!(
            "bentstraw check: {}: {}",
            clip_text(&args.file.display().to_string(), 60),
            if report.passes() { "pass" } else { "fail" }
        );
        bentstraw_io::check_plot::write_check_figure(
            p,
            checked,
            observer,
            &solution.points,
            &report,
            &title,
        )?;
    }
    let file = args.file.display().to_string();
    if args.json {
        let v = json_report(&file, checked, &solution, &report, &options, seconds);
        println!("{v}");
    } else {
        print!(
            "{}",
            summary(&file, checked, &solution, &report, &options, seconds)
        );
    }
    Ok(report.passes())
}
