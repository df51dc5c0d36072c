//! The command line's tests, one test binary: each links the whole program's dependencies, so one
//! binary instead of seven saves six links on every `cargo test`. Each file of `tests/` is a
//! module here (`autotests = false` in Cargo.toml: a new file must be added below, which
//! `every_test_file_is_a_module` checks).
//!
//! The report job (`bentstraw table`, many seconds) runs once, in `the_report_job`, and the
//! modules check its output. What needs a tool from outside Rust (Chromium's print, poppler's
//! reading of a PDF) is checked by ignored tests (`#[ignore = "needs …"]`), each running its own
//! report: `cargo test -- --ignored` runs them, as CI does; there a missing tool fails them.

mod bench_cli;
mod check_cli;
mod cli;
mod explore_server;
mod figures_cli;
mod golden;
mod grade_cli;
mod outputs_cli;
mod render_cli;
mod report_cli;
mod scene_cli;

/// The rule for tests needing node, Chromium or poppler, shared with the unit tests.
#[allow(dead_code)]
#[path = "../../bentstraw-io/src/test_support.rs"]
mod test_support;

use std::path::Path;
use std::process::{Command, Output};

/// `bentstraw ARGS…` run in `dir`.
fn bentstraw(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_bentstraw"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("the binary runs")
}

/// `bentstraw ARGS…` run in `dir`, which must succeed.
fn bentstraw_ok(dir: &Path, args: &[&str]) {
    let out = bentstraw(dir, args);
    assert!(
        out.status.success(),
        "{} failed: {}",
        args.join(" "),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The report job in French, on few points, with its PDF: `fr/` and `rapport.pdf` in `dir`.
const FRENCH_REPORT: [&str; 9] = [
    "table",
    "--lang",
    "fr",
    "--points",
    "1000",
    "--out",
    "fr",
    "--pdf",
    "rapport.pdf",
];

/// The headings the French report's PDF holds.
const FRENCH_PDF_HEADINGS: [&str; 4] = [
    "Vue d'ensemble",
    "Simulation de référence 1",
    "Validation",
    "Limites",
];

/// `table --scene` on the leaning straw's file, with its PDF: `lean/` and `lean.pdf` in `dir`.
fn scene_report(dir: &Path) {
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../scenes/leaning-straw.toml"
    );
    bentstraw_ok(
        dir,
        &[
            "table", "--scene", scene, "--out", "lean", "--pdf", "lean.pdf",
        ],
    );
}

/// The headings the scene report's PDF holds.
const SCENE_PDF_HEADINGS: [&str; 3] = ["Observer 1: the file's", "Observer 4", "Validation"];

/// The report job on its defaults (as `cargo run --release` runs it; `cli` checks that no
/// arguments means `table --out out`), into folders it must make; run once, checked by each
/// module that has something to say about the report.
#[test]
fn the_report_job() {
    let dir = tempfile::tempdir().unwrap();
    let out = bentstraw(dir.path(), &["table", "--out", "made/here"]);
    let folder = dir.path().join("made/here");
    cli::table_writes_every_simulation_and_the_report(&out, &folder);
    figures_cli::the_reports_figures_come_as_svg_too_and_are_legible(&folder);
    report_cli::the_report_is_lean_and_prints(&folder);
}

/// The report job on its defaults, its page printed by headless Chromium on few A4 pages.
#[test]
#[ignore = "needs Chromium (headless) to print the page and poppler's pdftotext to read it"]
fn the_report_job_prints_on_few_pages() {
    // The tools first: without them the test fails before its report's many seconds.
    test_support::require_tool("chromium");
    let dir = tempfile::tempdir().unwrap();
    bentstraw_ok(dir.path(), &["table", "--out", "made/here"]);
    report_cli::the_report_prints_on_few_pages(&dir.path().join("made/here"));
}

/// The report job in French, on few points (its words, not its numbers, are checked).
#[test]
fn the_report_job_in_french() {
    let dir = tempfile::tempdir().unwrap();
    bentstraw_ok(dir.path(), &FRENCH_REPORT);
    report_cli::the_french_report_is_in_french(&dir.path().join("fr"));
    report_cli::the_pdf_is_the_report(&dir.path().join("rapport.pdf"));
}

/// The French report's PDF, read back by poppler: A4, few pages, its headings and figures.
#[test]
#[ignore = "needs poppler's pdfinfo and pdftotext to read the PDF"]
fn the_french_reports_pdf_is_a4_on_few_pages() {
    let dir = tempfile::tempdir().unwrap();
    bentstraw_ok(dir.path(), &FRENCH_REPORT);
    report_cli::the_pdf_is_the_report_on_few_pages(
        &dir.path().join("rapport.pdf"),
        &FRENCH_PDF_HEADINGS,
    );
}

/// `table --scene` on the leaning straw's file, into a folder it must make.
#[test]
fn the_scene_report_job() {
    let dir = tempfile::tempdir().unwrap();
    scene_report(dir.path());
    report_cli::the_scene_report_has_its_observers_and_validation(&dir.path().join("lean"));
    report_cli::the_pdf_is_the_report(&dir.path().join("lean.pdf"));
}

/// The scene report printed by headless Chromium, and its PDF read back by poppler.
#[test]
#[ignore = "needs Chromium (headless) to print the page and poppler's pdfinfo and pdftotext"]
fn the_scene_report_prints_and_its_pdf_is_a4() {
    // The tools first: without them the test fails before its report's many seconds.
    test_support::require_tool("chromium");
    let dir = tempfile::tempdir().unwrap();
    scene_report(dir.path());
    report_cli::the_scene_report_prints_on_few_pages(&dir.path().join("lean"));
    report_cli::the_pdf_is_the_report_on_few_pages(
        &dir.path().join("lean.pdf"),
        &SCENE_PDF_HEADINGS,
    );
}

/// `table --scene reversing-arrow --lang fr`: a gallery scene by its name, in French, on few points.
#[test]
fn the_scene_report_in_french_by_gallery_name() {
    let dir = tempfile::tempdir().unwrap();
    bentstraw_ok(
        dir.path(),
        &[
            "table",
            "--scene",
            "reversing-arrow",
            "--lang",
            "fr",
            "--points",
            "1000",
            "--out",
            "fleche",
        ],
    );
    report_cli::the_french_scene_report_is_in_french(&dir.path().join("fleche"));
}

/// Every `.rs` file of `tests/` is compiled: as this file or a module of it.
#[test]
fn every_test_file_is_a_module() {
    let tests = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let main = std::fs::read_to_string(tests.join("main.rs")).unwrap();
    for entry in std::fs::read_dir(&tests).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        if let Some(stem) = name.strip_suffix(".rs") {
            assert!(
                stem == "main" || main.contains(&format!("\nmod {stem};\n")),
                "tests/{name} is not compiled: add `mod {stem};` to tests/main.rs"
            );
        }
    }
}
