//! The report on paper and on disk: the folder of the main job stays small, and the page prints
//! on a few A4 pages (through headless Chromium's print, as a reader's browser prints it: those
//! checks are ignored tests of `main.rs`, run by `cargo test -- --ignored`).

use std::fs;
use std::path::Path;
use std::process::{Command, Stdio};

use crate::test_support::{require_tool, unavailable};

/// Most bytes the report's folder may hold.
const MAX_FOLDER_BYTES: u64 = 25 * 1024 * 1024;
/// Most A4 pages the report may print on.
const MAX_PAGES: usize = 16;

/// The bytes the files of `folder` hold.
fn folder_bytes(folder: &Path) -> u64 {
    fs::read_dir(folder)
        .unwrap()
        .map(|e| e.unwrap().metadata().unwrap().len())
        .sum()
}

/// The report job's folder (see `the_report_job`) holds at most 25 MB, and its page has a print
/// stylesheet.
pub fn the_report_is_lean_and_prints(folder: &Path) {
    let bytes = folder_bytes(folder);
    assert!(
        bytes <= MAX_FOLDER_BYTES,
        "the report's folder holds {bytes} bytes, more than {MAX_FOLDER_BYTES}"
    );
    has_a_print_stylesheet(folder);
}

/// The report job's page (see `the_report_job_prints_on_few_pages`) printed by Chromium fills at
/// most 16 A4 pages, its tables and headings included.
pub fn the_report_prints_on_few_pages(folder: &Path) {
    let text = printed_by_chromium(folder);
    // What is not printed is named, with where to find it; the reference simulations are.
    assert!(
        text.contains("Not printed"),
        "no note on what is not printed"
    );
    for k in 1..=4 {
        assert!(
            text.contains(&format!("Reference simulation {k}")),
            "simulation {k} not printed"
        );
    }
}

/// The page in `folder` has a print stylesheet.
fn has_a_print_stylesheet(folder: &Path) {
    let index = fs::read_to_string(folder.join("index.html")).unwrap();
    assert!(index.contains("@media print"), "no print stylesheet");
}

/// The text of the report in `folder` as headless Chromium prints it on A4, after checking that
/// it has a print stylesheet and prints on 1 to 16 pages. Without Chromium or poppler's pdftotext
/// the test fails.
pub fn printed_by_chromium(folder: &Path) -> String {
    has_a_print_stylesheet(folder);
    let (chromium, pdftotext) = (require_tool("chromium"), require_tool("pdftotext"));
    let dir = tempfile::tempdir().unwrap();
    let pdf = dir.path().join("report.pdf");
    let status = Command::new(chromium)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-background-networking",
            "--disable-component-update",
            "--no-first-run",
            "--no-pdf-header-footer",
        ])
        .arg(format!(
            "--user-data-dir={}",
            dir.path().join("profile").display()
        ))
        .arg(format!("--print-to-pdf={}", pdf.display()))
        .arg(format!("file://{}", folder.join("index.html").display()))
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .unwrap();
    if !status.success() || !pdf.is_file() {
        unavailable(
            "Chromium did not print the report",
            "apt-get install chromium",
        );
    }
    let text = pdf_text(&pdftotext, &pdf);
    // pdftotext separates pages with form feeds: one per page.
    let pages = text.matches('\u{c}').count();
    assert!(
        (1..=MAX_PAGES).contains(&pages),
        "the report prints on {pages} A4 pages, more than {MAX_PAGES}"
    );
    text
}

/// `table --pdf FILE` (run by `the_report_job_in_french` and `the_scene_report_job`): a PDF,
/// written beside the report's folder, of at most half the report's folder's bytes.
pub fn the_pdf_is_the_report(pdf: &Path) {
    let bytes = fs::read(pdf).unwrap_or_else(|e| panic!("no PDF {pdf:?}: {e}"));
    assert!(bytes.starts_with(b"%PDF-"));
    assert!(
        bytes.len() < MAX_FOLDER_BYTES as usize / 2,
        "{} bytes",
        bytes.len()
    );
}

/// `table --pdf FILE` (run by the ignored `the_french_reports_pdf_is_a4_on_few_pages` and
/// `the_scene_report_prints_and_its_pdf_is_a4`): [`the_pdf_is_the_report`], of at most 16 A4
/// pages whose text (read by poppler) holds `headings`, with its figures embedded.
pub fn the_pdf_is_the_report_on_few_pages(pdf: &Path, headings: &[&str]) {
    the_pdf_is_the_report(pdf);
    let (pdfinfo, pdftotext) = (require_tool("pdfinfo"), require_tool("pdftotext"));
    let info = Command::new(pdfinfo).arg(pdf).output().unwrap();
    assert!(info.status.success(), "pdfinfo could not read {pdf:?}");
    let info = String::from_utf8_lossy(&info.stdout);
    assert!(info.contains("(A4)"), "not A4: {info}");
    let text = pdf_text(&pdftotext, pdf);
    let pages = text.matches('\u{c}').count();
    assert!(
        (2..=MAX_PAGES).contains(&pages),
        "the PDF has {pages} pages, more than {MAX_PAGES}"
    );
    let flat = text.split_whitespace().collect::<Vec<_>>().join(" ");
    for heading in headings {
        assert!(flat.contains(heading), "no {heading:?} in the PDF's text");
    }
    // Each page is numbered, and the figures are there (their own text: axes, keys).
    assert!(flat.contains(&format!("{pages} / {pages}")));
    assert!(flat.contains("z (m)"), "no figure's text in the PDF");
}

/// The text of the PDF file `pdf`, pages separated by form feeds.
fn pdf_text(pdftotext: &Path, pdf: &Path) -> String {
    let text = Command::new(pdftotext).arg(pdf).arg("-").output().unwrap();
    assert!(text.status.success(), "pdftotext could not read {pdf:?}");
    String::from_utf8_lossy(&text.stdout).into_owned()
}

/// `table --scene scenes/leaning-straw.toml` (run by `the_scene_report_job`): the report of that
/// scene, its four observers each with the reference simulations' figures, the validation over
/// its water's index, a folder of a few MB that prints (on few pages, all four observers:
/// [`the_scene_report_prints_on_few_pages`]).
pub fn the_scene_report_has_its_observers_and_validation(folder: &Path) {
    let index = fs::read_to_string(folder.join("index.html")).unwrap();
    // What the scene teaches: its lesson's title, text and questions, in English.
    assert!(index.contains("The broken straw"), "no lesson");
    assert!(index.contains("Question 1: "), "no lesson question");
    let headings = headings(&index);
    for heading in [
        "The scene",
        "Observer 1: the file's",
        "Observer 2: turned +45° about the vertical through the target",
        "Observer 3: turned −45° about the vertical through the target",
        "Observer 4: turned +90° about the vertical through the target",
        "Apparent depth from every seat",
        "Validation",
        "Limits",
    ] {
        assert!(
            headings.iter().any(|h| h == heading),
            "no heading {heading:?} in {headings:?}"
        );
    }
    for k in 1..=4 {
        for suffix in [
            ".csv.gz",
            ".svg",
            ".html",
            "_observer.png",
            "_cloud.png",
            "_models.svg",
            "_gap.svg",
            "_rays.svg",
        ] {
            let file = format!("obs{k}{suffix}");
            assert!(folder.join(&file).is_file(), "no {file}");
            assert!(
                index.contains(&format!("\"{file}\"")),
                "{file} not in the report"
            );
        }
    }
    for file in ["scene_view.png", "validation.svg"] {
        assert!(folder.join(file).is_file(), "no {file}");
    }
    // Apparent depth against the viewing angle: a figure and a CSV file for each sweep, a row
    // per seat (61 on the grid, and the observer's own unless the grid holds it), the observer's
    // seat seeing the point.
    for kind in ["around", "updown"] {
        for extension in ["svg", "csv"] {
            let file = format!("sweep_{kind}.{extension}");
            assert!(folder.join(&file).is_file(), "no {file}");
            assert!(
                index.contains(&format!("\"{file}\"")),
                "{file} not in the report"
            );
        }
        let csv = fs::read_to_string(folder.join(format!("sweep_{kind}.csv"))).unwrap();
        let lines: Vec<&str> = csv.lines().collect();
        assert!(lines[0].starts_with("angle_deg,eye_x_m,eye_y_m,eye_z_m,current,sight,path,"));
        assert!((62..=63).contains(&lines.len()), "{} lines", lines.len());
        let own: Vec<&&str> = lines
            .iter()
            .filter(|l| l.split(',').nth(4) == Some("1"))
            .collect();
        assert_eq!(own.len(), 1);
        assert_eq!(own[0].split(',').nth(5), Some("seen"));
        let svg = fs::read_to_string(folder.join(format!("sweep_{kind}.svg"))).unwrap();
        assert!(svg.contains("height z of the apparent point (cm)"));
    }
    // Each observer's points checked as a solution, and its light paths counted.
    assert_eq!(index.matches("class=\"check pass solution\"").count(), 4);
    assert_eq!(index.matches("Image points by light path: ").count(), 4);
    // The turned observers keep the file's height and distance from the target's vertical.
    assert!(
        index.contains("(0, -0.3, 0.2) m"),
        "the file's observer is not shown"
    );
    let validation = fs::read_to_string(folder.join("validation.svg")).unwrap();
    assert!(validation.contains("index of the bottom liquid n"));
    let bytes = folder_bytes(folder);
    assert!(
        bytes <= MAX_FOLDER_BYTES / 2,
        "the scene report's folder holds {bytes} bytes"
    );
    has_a_print_stylesheet(folder);
}

/// The scene report's page (run by the ignored `the_scene_report_prints_and_its_pdf_is_a4`)
/// printed by Chromium: on at most 16 A4 pages, its fourth observer included.
pub fn the_scene_report_prints_on_few_pages(folder: &Path) {
    let text = printed_by_chromium(folder);
    assert!(text.contains("Observer 4"), "observer 4 is not printed");
}

/// `table --scene NAME --lang fr` (run by `the_scene_report_in_french_by_gallery_name`): the
/// gallery's scene found by its name from a folder without it, its report in French, the card
/// and its arrow counted in their own colour codes.
pub fn the_french_scene_report_is_in_french(folder: &Path) {
    let index = fs::read_to_string(folder.join("index.html")).unwrap();
    assert!(index.contains("<html lang=\"fr\">"));
    let headings = headings(&index);
    for french in [
        "La scène",
        "Méthode",
        "Vue d'ensemble",
        "Observateur 1 : celui du fichier",
        "Observateur 2 : tourné de +45° autour de la verticale passant par la cible",
        "La profondeur apparente depuis chaque place",
        "Validation",
        "Limites",
    ] {
        assert!(
            headings.iter().any(|h| h == french),
            "no heading {french:?} in {headings:?}"
        );
    }
    for english in ["The scene", "Observer", "Method", "Overview", "Limits"] {
        assert!(
            !headings.iter().any(|h| h.contains(english)),
            "a heading left in English: {english:?}"
        );
    }
    assert!(index.contains("carte") && index.contains("flèche"));
    assert!(index.contains("reversing-arrow"));
    // The scene's lesson, in French: its title and its questions to the class.
    assert!(
        index.contains("La flèche qui s&#39;inverse"),
        "no lesson title"
    );
    assert!(index.contains("Question 1 : "), "no lesson question");
}

/// The texts of the page's `<h1>` to `<h4>` headings, as read (entities decoded).
fn headings(html: &str) -> Vec<String> {
    let mut found = Vec::new();
    for level in 1..=4 {
        let open = format!("<h{level}");
        let close = format!("</h{level}>");
        for piece in html.split(&open).skip(1) {
            let text = piece.split_once('>').map(|(_, rest)| rest).unwrap_or("");
            if let Some((text, _)) = text.split_once(&close) {
                found.push(
                    text.replace("&#39;", "'")
                        .replace("&quot;", "\"")
                        .replace("&lt;", "<")
                        .replace("&gt;", ">")
                        .replace("&amp;", "&"),
                );
            }
        }
    }
    found
}

/// `table --lang fr`'s report (run by `the_report_job_in_french`): a French page, its headings in
/// French with none left in English, and its figures' axes in French.
pub fn the_french_report_is_in_french(folder: &Path) {
    let index = fs::read_to_string(folder.join("index.html")).unwrap();
    assert!(
        index.contains("<html lang=\"fr\">"),
        "the page is not marked French"
    );
    let headings = headings(&index);
    for french in [
        "Vue d'ensemble",
        "La paille brisée",
        "Méthode",
        "Simulation de référence 1",
        "Simulation 1, vérification n_water = 1",
        "Points images virtuels (convention du cours, P = O + L·u0)",
        "Ce que voit l'observateur (image de Fresnel)",
        "Quel chemin de la lumière fait quel morceau (schéma des rayons)",
        "Validation",
        "Limites",
        "Conventions",
    ] {
        assert!(
            headings.iter().any(|h| h == french),
            "no heading {french:?} in {headings:?}"
        );
    }
    for english in [
        "Overview",
        "The broken straw",
        "Method",
        "Reference simulation",
        ", check n_water",
        "Virtual image points",
        "What the observer sees",
        "Which light path",
        "Where the straw really appears",
        "Gallery:",
        "Limits",
    ] {
        assert!(
            !headings.iter().any(|h| h.contains(english)),
            "a heading left in English: {english:?}"
        );
    }
    for english in [
        "image points",
        "rays traced",
        "hit ratio",
        "Time: ",
        "Not printed",
    ] {
        assert!(
            !index.contains(english),
            "English left in the page: {english:?}"
        );
    }
    // The section colours and a light path, in the explorer's words.
    assert!(index.contains("vert") && index.contains("bleu"));
    assert!(index.contains("par la paroi latérale"));
    let validation = fs::read_to_string(folder.join("validation.svg")).unwrap();
    assert!(
        validation.contains("indice de l&apos;eau n") || validation.contains("indice de l'eau n"),
        "the validation figure's axis is not in French"
    );
    let rays = fs::read_to_string(folder.join("sim1_rays.svg")).unwrap();
    assert!(
        rays.contains("vue de dessus") && rays.contains("réflexion totale"),
        "the ray diagram's text is not in French"
    );
    let gap = fs::read_to_string(folder.join("sim1_gap.svg")).unwrap();
    assert!(
        gap.contains("hauteur z du point de la paille (m)"),
        "the gap plot's axis is not in French"
    );
}
