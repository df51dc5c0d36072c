//! `bentstraw check FILE`: judges a solution's image points one by one and tells what part of the
//! true image it misses; a summary for people, or one JSON object for graders' scripts.
//!
//! Exit codes: 0 when every point is correct and the coverage complete, 1 otherwise, 2 for bad input
//! (a malformed file, a scene outside the rules) — so a script can grade a folder of submissions.

use std::fmt::Write as _;
use std::time::Instant;

use bentstraw_optics::check::{check_solution, ClaimedPoint};
use bentstraw_optics::check::{DEFAULT_MIN_COVERAGE, DEFAULT_TOLERANCE};
use bentstraw_optics::image::ImagePoint;

use crate::cli::CheckArgs;
use crate::error::{CliError, CliResult};
use bentstraw_optics::setup::Setup;
use bentstraw_optics::text::{clip_text, number_text};
use bentstraw_outputs::files::check_writable;
use bentstraw_outputs::report::Check;
use bentstraw_outputs::solution::{
    colour_names, json_report, read_solution_of, region_words, summary, CheckOptions,
};

/// Runs `check`; `Ok(true)` for a pass, `Ok(false)` for a fail.
pub fn run(args: &CheckArgs) -> CliResult<bool> {
    let loaded = crate::cli::load_scene(&args.scene.source())?;
    let (checked, observer) = (&loaded, loaded.observer);
    let options = CheckOptions {
        tolerance: args.tolerance,
        min_coverage: args.min_coverage,
        worst: args.worst,
    };
    options.validate()?;
    if let Some(p) = &args.plot {
        bentstraw_outputs::plot::FigureFormat::of(p)
            .map_err(|e| CliError(format!("--plot {}", e)))?;
        check_writable(p)?;
    }
    let started = Instant::now();
    let solution = read_solution_of(&args.file, colour_names(checked).len())?;
    let report = check_solution(
        &checked.world,
        observer,
        &solution.points,
        args.tolerance,
        args.min_coverage,
    );
    let seconds = started.elapsed().as_secs_f64();
    if let Some(p) = &args.plot {
        let title = format!(
            "bentstraw check: {}: {}",
            clip_text(&args.file.display().to_string(), 60),
            if report.passes() { "pass" } else { "fail" }
        );
        bentstraw_outputs::check_plot::write_check_figure(
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

/// `bentstraw check` of a simulation's own image points (of the scene `loaded`, seen from its
/// observer) with the default tolerance and minimum coverage, for the report: its verdict in one
/// line.
pub fn own_points_check(loaded: &Setup, points: &[ImagePoint]) -> Check {
    let claimed: Vec<ClaimedPoint> = points
        .iter()
        .map(|p| ClaimedPoint {
            position: p.position,
            color: p.color,
        })
        .collect();
    let r = check_solution(
        &loaded.world,
        loaded.observer,
        &claimed,
        DEFAULT_TOLERANCE,
        DEFAULT_MIN_COVERAGE,
    );
    let colours = colour_names(loaded).len();
    let passed = r.passes();
    let verdict = if passed { "pass" } else { "fail" };
    let coverage: Vec<String> = r
        .coverage
        .per_colour
        .iter()
        .take(colours)
        .map(|c| format!("{:.1} %", 100.0 * c.share()))
        .collect();
    let mut text = format!(
        "{verdict}: {} of {} points correct (path lengths within {} m), coverage per colour 1–{colours}: {}",
        r.tally.correct,
        r.tally.points,
        number_text(DEFAULT_TOLERANCE),
        coverage.join(", ")
    );
    if let Some(m) = r.coverage.missing.first() {
        let _ = write!(text, "; largest missing region: {}", region_words(m));
    }
    Check {
        passed,
        text,
        short: format!("check: {verdict}"),
    }
}
