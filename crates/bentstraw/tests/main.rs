//! The command line's tests, one test binary: each links the whole program's dependencies, so one
//! binary instead of seven saves six links on every `cargo test`. Each file of `tests/` is a
//! module here (`autotests = false` in Cargo.toml: a new file must be added below, which
//! `every_test_file_is_a_module` checks).
//!
//! The report job (`bentstraw table`, many seconds) runs once, in `the_report_job`, and the
//! modules check its output.

mod bench_cli;
mod check_cli;
mod cli;
mod explore_server;
mod figures_cli;
mod outputs_cli;
mod render_cli;
mod report_cli;
mod scene_cli;

/// The rule for tests needing node, Chromium or poppler, shared with the unit tests.
#[allow(dead_code)]
#[path = "../../bentstraw-outputs/src/test_support.rs"]
mod test_support;

use std::process::Command;

/// The report job on its defaults (as `cargo run --release` runs it; `cli` checks that no
/// arguments means `table --out out`), into folders it must make; run once, checked by each
/// module that has something to say about the report.
#[test]
fn the_report_job() {
    let dir = tempfile::tempdir().unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_bentstraw"))
        .current_dir(dir.path())
        .args(["table", "--out", "made/here"])
        .output()
        .expect("the binary runs");
    let folder = dir.path().join("made/here");
    cli::table_writes_every_simulation_and_the_report(&out, &folder);
    figures_cli::the_reports_figures_come_as_svg_too_and_are_legible(&folder);
    report_cli::the_report_is_lean_and_prints_on_few_pages(&folder);
}

/// The report job in French, on few points (its words, not its numbers, are checked).
#[test]
fn the_report_job_in_french() {
    let dir = tempfile::tempdir().unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_bentstraw"))
        .current_dir(dir.path())
        .args(["table", "--lang", "fr", "--points", "1000", "--out", "fr"])
        .args(["--pdf", "rapport.pdf"])
        .output()
        .expect("the binary runs");
    assert!(
        out.status.success(),
        "table --lang fr failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    report_cli::the_french_report_is_in_french(&dir.path().join("fr"));
    report_cli::the_pdf_is_the_report_on_few_pages(
        &dir.path().join("rapport.pdf"),
        &[
            "Vue d'ensemble",
            "Simulation de référence 1",
            "Validation",
            "Limites",
        ],
    );
}

/// `table --scene` on the leaning straw's file, into a folder it must make.
#[test]
fn the_scene_report_job() {
    let dir = tempfile::tempdir().unwrap();
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../scenes/leaning-straw.toml"
    );
    let out = Command::new(env!("CARGO_BIN_EXE_bentstraw"))
        .current_dir(dir.path())
        .args([
            "table", "--scene", scene, "--out", "lean", "--pdf", "lean.pdf",
        ])
        .output()
        .expect("the binary runs");
    assert!(
        out.status.success(),
        "table --scene failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    report_cli::the_scene_report_has_its_observers_and_validation(&dir.path().join("lean"));
    report_cli::the_pdf_is_the_report_on_few_pages(
        &dir.path().join("lean.pdf"),
        &["Observer 1: the file's", "Observer 4", "Validation"],
    );
}

/// `table --scene reversing-arrow --lang fr`: a gallery scene by its name, in French, on few points.
#[test]
fn the_scene_report_in_french_by_gallery_name() {
    let dir = tempfile::tempdir().unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_bentstraw"))
        .current_dir(dir.path())
        .args(["table", "--scene", "reversing-arrow", "--lang", "fr"])
        .args(["--points", "1000", "--out", "fleche"])
        .output()
        .expect("the binary runs");
    assert!(
        out.status.success(),
        "table --scene reversing-arrow --lang fr failed: {}",
        String::from_utf8_lossy(&out.stderr)
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
