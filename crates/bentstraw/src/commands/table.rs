//! `bentstraw table`: the report (the four reference simulations, or a scene file seen from four
//! observers) planned by the library ([`ReportPlan`]), its files reserved as one set, written with
//! a progress bar, then put in place together (and the PDF beside them).

use std::path::{Path, PathBuf};

use bentstraw_io::files::{self, Output, OutputSet};
use bentstraw_io::report::Report;
use bentstraw_io::report_pdf;
use bentstraw_io::report_plan::{self, checked_points, failed_checks, unwritten, ReportPlan};
use bentstraw_io::scene_input::SceneFile;
use bentstraw_io::words::Lang;
use indicatif::ProgressBar;

use crate::cli::TableArgs;
use crate::error::{fail, CliResult};
use crate::progress;

/// Runs `table`.
pub fn run(args: &TableArgs) -> CliResult {
    checked_points(args.points)?;
    let out = &args.out;
    if out.exists() && !out.is_dir() {
        return fail(format!(
            "--out {}: it exists and is not a folder",
            files::shown(out)
        ));
    }
    // A scene is read and checked before anything is made: bad input writes nothing.
    let lang = Lang::from(args.lang);
    let plan = match &args.scene {
        Some(file) => {
            let SceneFile { name, text } = SceneFile::read(file)?;
            ReportPlan::scene(
                name,
                &text,
                args.observer,
                args.wavelength,
                args.points,
                lang,
            )?
        }
        None if args.observer.is_some() => {
            return fail("--observer is for --scene: the reference simulations have their own")
        }
        None => ReportPlan::references(args.points, lang)?,
    };
    for hint in plan.hints() {
        eprintln!("hint: {hint}");
    }
    let made = files::make_folder(out)?;
    let result = write(&plan, out, args.pdf.as_deref());
    if result.is_err() {
        // A failed run leaves no folder it made (the set removed its temporaries).
        files::remove_made_folders(&made);
    }
    result
}

/// The progress bar as the report's work tells it.
struct Bar<'a>(&'a ProgressBar);

impl report_plan::Progress for Bar<'_> {
    fn stage(&self, stage: &str) {
        self.0.set_message(stage.to_string());
    }

    fn step(&self) {
        self.0.inc(1);
    }
}

/// Writes the report of `plan` into the existing folder `out` (and its PDF into `pdf`): every
/// file is replaced, or none; then tells what was done, and fails if a check failed.
fn write(plan: &ReportPlan, out: &Path, pdf: Option<&Path>) -> CliResult {
    let outputs = reserve(out, &plan.files(), pdf)?;
    let report = progress::with_progress(
        Some(plan.steps()),
        "{msg:22} {bar:30} {pos}/{len}  [{elapsed}, about {eta} left]",
        |bar| plan.write(out, &Bar(bar)),
    )?;
    finish(report, out, pdf, outputs)
}

/// Reserves the report's files `names` in the folder `out` (every file it will hold) and the PDF
/// `pdf`, wherever it goes, as one set: all are replaced together, or none.
fn reserve(out: &Path, names: &[String], pdf: Option<&Path>) -> CliResult<OutputSet> {
    let paths: Vec<PathBuf> = names.iter().map(|name| out.join(name)).collect();
    let mut outputs: Vec<Output> = paths
        .iter()
        .map(|path| Output {
            flag: "--out",
            path,
            extensions: &[],
        })
        .collect();
    outputs.extend(pdf.map(|path| Output {
        flag: "--pdf",
        path,
        extensions: &["pdf"],
    }));
    Ok(OutputSet::reserve_folder(out, &outputs)?)
}

/// Writes the PDF of `report` into `pdf` (from the figures just written into `out`) and puts the
/// set of outputs in place, unless a file could not be written; then tells what was done, and
/// fails if a check failed.
fn finish(report: Report, out: &Path, pdf: Option<&Path>, outputs: OutputSet) -> CliResult {
    // Any file that could not be written: nothing is replaced, the previous table stays whole.
    if let Some(message) = unwritten(&report, out) {
        return fail(message);
    }
    if let Some(pdf) = pdf {
        let read = |file: &str| files::read_written(&out.join(file));
        let bytes = progress::with_progress(None, "{spinner} {msg}", |bar| {
            bar.set_message(format!("PDF {}", files::shown(pdf)));
            report_pdf::report_pdf(&report, &read)
        })?;
        files::write_bytes(pdf, &bytes)?;
    }
    outputs.commit()?;
    progress::tell(&report_plan::summary(&report, out));
    // A failed check is reported after the files are in place, so that the report shows it.
    match failed_checks(&report) {
        Some(message) => fail(message),
        None => Ok(()),
    }
}
