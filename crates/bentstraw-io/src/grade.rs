//! Grading a class: every student's solution files judged as `check` judges one (the same
//! reading and the same verdict), a score per case, the gradebook, Gradescope's results and the
//! feedback pages. A student whose file is missing or cannot be read gets that case's verdict with the
//! reason; the rest of the class is graded.

use std::path::{Path, PathBuf};

use bentstraw_optics::check::{
    check_solution, CheckReport, Place, DEFAULT_MIN_COVERAGE, DEFAULT_TOLERANCE,
};
use bentstraw_optics::light_path_type::LightPathType;
use bentstraw_optics::scene::{DEFAULT_MAX_EVENTS, REFERENCES};
use bentstraw_optics::setup::{SceneValues, Setup};
use bentstraw_optics::text::clip_text;
use rayon::prelude::*;
use serde::Deserialize;

use crate::check_plot::check_figure_bytes;
pub use crate::class::{students, HandIn, Student};
use crate::error::{Error, Result};
use crate::escape::escape_html;
use crate::files::{self, read_input, Output, OutputSet, Unread};
use crate::html::base64;
use crate::plot::FigureFormat;
use crate::solution::{read_solution_of, solution_from_bytes, CheckOptions, Solution};
use crate::view_spec::{SceneFile, ViewSpec};
use crate::words::{self, Lang};

/// Points of each case of the default assignment (four cases: 100 in all).
pub const REFERENCE_CASE_POINTS: f64 = 25.0;
/// The extensions a solution file of the default assignment may have.
pub const SOLUTION_EXTENSIONS: [&str; 3] = ["csv", "txt", "dat"];

/// One case of an assignment: a solution file each student hands in, for one scene and observer.
#[derive(Clone, Debug)]
pub struct Case {
    /// The case's name (a column of the gradebook), e.g. `sim1`.
    pub name: String,
    /// The names the case's file may have: patterns where `*` stands for any characters and `?`
    /// for one, matched whatever the letters' case.
    pub files: Vec<String>,
    /// The scene and observer the solution is computed for.
    pub setup: Setup,
    /// Points a pass scores.
    pub points: f64,
    /// Largest allowed difference between a point's distance and its ray's path length (m).
    pub tolerance: f64,
    /// Share of each colour's true image the points must cover.
    pub min_coverage: f64,
}

/// The names a case's file may have when the assignment does not say: `NAME` with one of the
/// solution extensions.
fn default_files(name: &str) -> Vec<String> {
    SOLUTION_EXTENSIONS
        .iter()
        .map(|e| format!("{name}.{e}"))
        .collect()
}

/// The cases to grade: the assignment file's (see [`read_assignment`]), else the four reference
/// simulations ([`reference_assignment`]).
pub fn assignment(file: Option<&Path>) -> Result<Vec<Case>> {
    match file {
        Some(path) => read_assignment(path),
        None => reference_assignment(),
    }
}

/// The four reference simulations, as the course sets them: files `sim1` … `sim4` (.csv, .txt or
/// .dat), 25 points each, `check`'s tolerance and coverage.
pub fn reference_assignment() -> Result<Vec<Case>> {
    REFERENCES
        .iter()
        .map(|r| {
            let values = SceneValues {
                observer: Some(r.observer.to_array()),
                straw: Some([r.straw.0, r.straw.1]),
                water_height: Some(r.water_height),
                n_water: None,
                max_events: DEFAULT_MAX_EVENTS,
                wavelength: None,
            };
            Ok(Case {
                name: format!("sim{}", r.number),
                files: default_files(&format!("sim{}", r.number)),
                setup: Setup::from_values(&values)?,
                points: REFERENCE_CASE_POINTS,
                tolerance: DEFAULT_TOLERANCE,
                min_coverage: DEFAULT_MIN_COVERAGE,
            })
        })
        .collect()
}

/// Most cases in an assignment file.
pub const MAX_CASES: usize = 100;
/// Largest assignment file read (bytes).
pub const MAX_ASSIGNMENT_BYTES: u64 = 1 << 20;

/// One `[[case]]` of an assignment file, as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CaseEntry {
    name: String,
    file: Option<String>,
    points: Option<f64>,
    scene: Option<String>,
    observer: Option<[f64; 3]>,
    straw: Option<[f64; 2]>,
    water_height: Option<f64>,
    n_water: Option<f64>,
    max_events: Option<u32>,
    tolerance: Option<f64>,
    min_coverage: Option<f64>,
}

/// An assignment file, as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct AssignmentEntries {
    case: Vec<CaseEntry>,
}

/// Reads the assignment file at `path` (see [`parse_assignment`]); its scene files are found
/// beside it.
pub fn read_assignment(path: &Path) -> Result<Vec<Case>> {
    let name = clip_text(&path.display().to_string(), 80);
    let bytes = read_input(path, MAX_ASSIGNMENT_BYTES).map_err(|unread| {
        Error::Refused(match unread {
            Unread::Io(e) => format!("cannot read the assignment {name}: {e}"),
            Unread::NotAFile(why) => format!("cannot read the assignment {name}: {why}"),
            Unread::TooLarge(size) => {
                format!("the assignment {name} is {size}: at most {MAX_ASSIGNMENT_BYTES} bytes")
            }
        })
    })?;
    let text = String::from_utf8(bytes)
        .map_err(|_| Error::Refused(format!("the assignment {name} is not UTF-8 text")))?;
    let folder = path.parent().unwrap_or(Path::new("."));
    parse_assignment(&name, &text, folder)
}

/// The cases of the assignment file `text` (named `name` in messages): a `[[case]]` table each,
/// with `name`, and optionally `file` (its names: a pattern or a list of them; `NAME.csv`,
/// `NAME.txt` or `NAME.dat` by default), `points` (25), the scene as `scene` (a gallery scene's
/// name or a scene file beside the assignment, in `folder`) and the values `observer`, `straw`,
/// `water_height`, `n_water` and `max_events` as the command line takes them, `tolerance` and
/// `min_coverage` (`check`'s). Every broken rule is told, together.
pub fn parse_assignment(name: &str, text: &str, folder: &Path) -> Result<Vec<Case>> {
    let entries: AssignmentEntries = toml::from_str(text).map_err(|e| {
        let line = e
            .span()
            .map(|s| {
                let line = text.get(..s.start).map_or(0, |t| t.matches('\n').count()) + 1;
                format!(" (line {line})")
            })
            .unwrap_or_default();
        Error::Refused(format!("{name}{line}: {}", e.message().trim()))
    })?;
    let mut broken = Vec::new();
    if entries.case.is_empty() {
        broken.push(format!("{name}: no [[case]]: list at least one"));
    }
    if entries.case.len() > MAX_CASES {
        broken.push(format!(
            "{name}: {} cases: at most {MAX_CASES}",
            entries.case.len()
        ));
    }
    let mut cases = Vec::new();
    for (k, c) in entries.case.iter().enumerate().take(MAX_CASES) {
        let at = format!("{name}: case {} ({})", k + 1, clip_text(&c.name, 40));
        let before = broken.len();
        let plain = |s: &str| {
            !s.is_empty()
                && s.len() <= 64
                && s.chars()
                    .all(|ch| ch.is_alphanumeric() || "-_.".contains(ch))
        };
        if !plain(&c.name) {
            broken.push(format!(
                "{at}: name {:?} is not allowed: 1 to 64 letters, digits, '-', '_' or '.'",
                clip_text(&c.name, 40)
            ));
        }
        if entries.case[..k].iter().any(|o| o.name == c.name) {
            broken.push(format!(
                "{at}: another case has this name: give each its own"
            ));
        }
        let files = match &c.file {
            Some(f) if f.is_empty() || f.contains(['/', '\\']) || f.len() > 255 => {
                broken.push(format!(
                    "{at}: file {:?} is not allowed: a file name (with * or ?), no folder",
                    clip_text(f, 40)
                ));
                Vec::new()
            }
            Some(f) => vec![f.clone()],
            None => default_files(&c.name),
        };
        let points = c.points.unwrap_or(REFERENCE_CASE_POINTS);
        if !(points.is_finite() && points > 0.0) {
            broken.push(format!(
                "{at}: points {points} is not allowed: it must be > 0"
            ));
        }
        let tolerance = c.tolerance.unwrap_or(DEFAULT_TOLERANCE);
        let min_coverage = c.min_coverage.unwrap_or(DEFAULT_MIN_COVERAGE);
        let options = CheckOptions {
            tolerance,
            min_coverage,
            worst: 0,
        };
        if let Err(e) = options.validate() {
            broken.extend(e.to_string().lines().map(|l| format!("{at}: {l}")));
        }
        let scene = match &c.scene {
            None => None,
            Some(s) => match SceneFile::gallery(s) {
                Some(file) => Some(file),
                None => match SceneFile::read(&folder.join(s)) {
                    Ok(file) => Some(file),
                    Err(e) => {
                        broken.push(format!("{at}: scene {s:?}: {e}"));
                        continue;
                    }
                },
            },
        };
        let view = ViewSpec {
            scene,
            values: SceneValues {
                observer: c.observer,
                straw: c.straw,
                water_height: c.water_height,
                n_water: c.n_water,
                max_events: c.max_events.unwrap_or(DEFAULT_MAX_EVENTS),
                wavelength: None,
            },
            ..ViewSpec::default()
        };
        match view.load() {
            Ok(setup) if broken.len() == before => cases.push(Case {
                name: c.name.clone(),
                files,
                setup,
                points,
                tolerance,
                min_coverage,
            }),
            Ok(_) => {}
            Err(e) => broken.extend(e.to_string().lines().map(|l| format!("{at}: {l}"))),
        }
    }
    if broken.is_empty() {
        Ok(cases)
    } else {
        Err(Error::Refused(broken.join("\n")))
    }
}

/// The verdict on one student's case.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CaseVerdict {
    /// Every point correct and the coverage complete.
    Pass,
    /// Read, but some points are wrong or the coverage is incomplete.
    Fail,
    /// No file for the case.
    Missing,
    /// A file that cannot be read as image points.
    Unreadable,
}

impl CaseVerdict {
    /// The verdict's word in the gradebook.
    pub fn key(self) -> &'static str {
        match self {
            CaseVerdict::Pass => "pass",
            CaseVerdict::Fail => "fail",
            CaseVerdict::Missing => "missing",
            CaseVerdict::Unreadable => "unreadable",
        }
    }
}

/// One row of the gradebook: a student's case.
#[derive(Clone, Debug)]
pub struct CaseGrade {
    /// The student's name.
    pub student: String,
    /// The case's name.
    pub case: String,
    /// The names the case's file may have (as [`Case::files`]).
    pub files: Vec<String>,
    /// The verdict.
    pub verdict: CaseVerdict,
    /// The score (see [`partial_score`]).
    pub score: f64,
    /// The case's points.
    pub max_score: f64,
    /// Points in the file.
    pub points: usize,
    /// Of them, those correct.
    pub correct: usize,
    /// The smallest share of a colour's true image the points cover (0 when not read).
    pub coverage: f64,
    /// The case's file name as handed in, if found.
    pub file: Option<String>,
    /// Why the file could not be read (the reader's words), if it could not.
    pub unread: Option<String>,
    /// The coverage asked for.
    pub min_coverage: f64,
    /// The parts of the true image the points miss, largest first.
    pub missing: Vec<Missed>,
}

/// A part of the true image a solution misses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Missed {
    /// Colour code, 1..=8.
    pub color: u8,
    /// The light path that makes this part of the image.
    pub path: LightPathType,
    /// Its share of the colour's image, 0..=1.
    pub share: f64,
    /// Where along the colour's visible height it lies.
    pub place: Place,
}

impl Missed {
    /// The missing part in words.
    pub fn words(&self, lang: Lang) -> String {
        lang.fill(
            words::GRADE_MISSING_REGION,
            &[
                &lang.colour_name(self.color as usize - 1),
                &format!("{:.1}", 100.0 * self.share),
                &lang.light_path(&self.path),
                &lang.of(words::GRADE_PLACES[self.place as usize]),
            ],
        )
    }
}

impl CaseGrade {
    /// The row of a case worth `max_score` whose file `file` was read and judged as `report`
    /// says, with the coverage `min_coverage` asked for: a pass scores `max_score`, a fail its
    /// [`partial_score`].
    pub fn judged(
        student: &str,
        case: &str,
        (max_score, min_coverage): (f64, f64),
        file: &str,
        report: &CheckReport,
    ) -> CaseGrade {
        let coverage = report
            .coverage
            .per_colour
            .iter()
            .map(|c| c.share())
            .fold(1.0_f64, f64::min);
        let (points, correct) = (report.tally.points, report.tally.correct);
        let passes = report.passes();
        CaseGrade {
            student: student.to_string(),
            case: case.to_string(),
            files: Vec::new(),
            verdict: if passes {
                CaseVerdict::Pass
            } else {
                CaseVerdict::Fail
            },
            score: if passes {
                max_score
            } else {
                partial_score(max_score, points, correct, coverage, min_coverage)
            },
            max_score,
            points,
            correct,
            coverage,
            file: Some(file.to_string()),
            unread: None,
            min_coverage,
            missing: report
                .coverage
                .missing
                .iter()
                .map(|m| Missed {
                    color: m.color,
                    path: m.path,
                    share: m.share_of_colour,
                    place: m.place,
                })
                .collect(),
        }
    }

    /// Why, in one line: what is wrong, or why the file was not read.
    pub fn note(&self, lang: Lang) -> String {
        let file = self.file.as_deref().unwrap_or("");
        match self.verdict {
            CaseVerdict::Pass => lang.fill(words::GRADE_NOTE_PASS, &[&file]),
            CaseVerdict::Missing => {
                let or = match lang {
                    Lang::En => " or ",
                    Lang::Fr => " ou ",
                };
                let names = match self.files.split_last() {
                    Some((last, [])) => last.clone(),
                    Some((last, rest)) => format!("{}{or}{last}", rest.join(", ")),
                    None => String::new(),
                };
                lang.fill(words::GRADE_NOTE_MISSING, &[&names])
            }
            CaseVerdict::Unreadable => self.unread.clone().unwrap_or_default(),
            CaseVerdict::Fail => {
                let mut why = Vec::new();
                if self.correct < self.points {
                    why.push(lang.fill(
                        words::GRADE_NOTE_WRONG,
                        &[&(self.points - self.correct), &self.points],
                    ));
                }
                if self.coverage < self.min_coverage {
                    why.push(lang.fill(
                        words::GRADE_NOTE_COVERAGE,
                        &[
                            &format!("{:.1}", 100.0 * self.coverage),
                            &format!("{:.1}", 100.0 * self.min_coverage),
                        ],
                    ));
                }
                match lang {
                    Lang::En => format!("{file}: {}", why.join("; ")),
                    Lang::Fr => format!("{file} : {}", why.join(" ; ")),
                }
            }
        }
    }
}

/// The score of a failed case worth `max_score`: its share of correct points times its coverage
/// over the coverage asked for (at most 1), so that half the points right over the whole image,
/// or every point right over half the image asked for, score half.
pub fn partial_score(
    max_score: f64,
    points: usize,
    correct: usize,
    coverage: f64,
    min: f64,
) -> f64 {
    if points == 0 {
        return 0.0;
    }
    let right = correct as f64 / points as f64;
    let covered = if min > 0.0 {
        (coverage / min).min(1.0)
    } else {
        1.0
    };
    let score = max_score * right * covered;
    (score * 100.0).round() / 100.0
}

/// Whether the file name `name` matches `pattern` (`*` any characters, `?` one), whatever the
/// letters' case.
pub fn name_matches(pattern: &str, name: &str) -> bool {
    let p: Vec<char> = pattern.to_lowercase().chars().collect();
    let n: Vec<char> = name.to_lowercase().chars().collect();
    // Greedy with one backtrack point per star: linear in practice, quadratic at worst.
    let (mut i, mut j) = (0, 0);
    let mut star: Option<(usize, usize)> = None;
    while j < n.len() {
        if i < p.len() && (p[i] == '?' || p[i] == n[j]) {
            i += 1;
            j += 1;
        } else if i < p.len() && p[i] == '*' {
            star = Some((i, j));
            i += 1;
        } else if let Some((si, sj)) = star {
            i = si + 1;
            j = sj + 1;
            star = Some((si, sj + 1));
        } else {
            return false;
        }
    }
    p[i..].iter().all(|&c| c == '*')
}

/// The file `student` handed in for `case`: the first of its names that a file has (the first
/// in name order if a pattern matches several).
pub fn case_file(student: &Student, case: &Case) -> Option<HandIn> {
    let files = student.hand_ins();
    case.files.iter().find_map(|pattern| {
        files
            .iter()
            .filter(|f| name_matches(pattern, &f.name))
            .min_by(|a, b| a.name.cmp(&b.name))
            .cloned()
    })
}

/// Judges `solution` as `check` does.
fn judge(setup: &Setup, solution: &Solution, tolerance: f64, min_coverage: f64) -> CheckReport {
    check_solution(
        &setup.world,
        setup.observer,
        &solution.points,
        tolerance,
        min_coverage,
    )
}

/// Reads the solution at `path` and judges it as `check` does: the file, and the judgement.
pub fn check_file(
    setup: &Setup,
    path: &Path,
    tolerance: f64,
    min_coverage: f64,
) -> Result<(Solution, CheckReport)> {
    let solution = read_solution_of(path, setup.colour_names().len())?;
    let report = judge(setup, &solution, tolerance, min_coverage);
    Ok((solution, report))
}

/// Grades `student`'s file for `case`.
pub fn grade_case(student: &Student, case: &Case) -> CaseGrade {
    judge_case(student, case).0
}

/// Grades `student`'s file for `case`: the row, and the solution with its judgement when the
/// file was read.
fn judge_case(student: &Student, case: &Case) -> (CaseGrade, Option<(Solution, CheckReport)>) {
    let row = |verdict, file: Option<String>, unread: Option<String>| CaseGrade {
        student: student.name.clone(),
        case: case.name.clone(),
        files: case.files.clone(),
        verdict,
        score: 0.0,
        max_score: case.points,
        points: 0,
        correct: 0,
        coverage: 0.0,
        file,
        unread,
        min_coverage: case.min_coverage,
        missing: Vec::new(),
    };
    let Some(file) = case_file(student, case) else {
        return (row(CaseVerdict::Missing, None, None), None);
    };
    let unreadable = |why: String| {
        let row = row(CaseVerdict::Unreadable, Some(file.name.clone()), Some(why));
        (row, None)
    };
    // The file named as the student named it, not by where the class was unpacked.
    let name = clip_text(&file.name, 80);
    let bytes = match student.read(&file) {
        Ok(bytes) => bytes,
        Err(why) => return unreadable(why),
    };
    let solution = match solution_from_bytes(&name, &bytes, case.setup.colour_names().len()) {
        Ok(solution) => solution,
        Err(e) => return unreadable(e.to_string()),
    };
    drop(bytes);
    let report = judge(&case.setup, &solution, case.tolerance, case.min_coverage);
    let graded = CaseGrade {
        files: case.files.clone(),
        ..CaseGrade::judged(
            &student.name,
            &case.name,
            (case.points, case.min_coverage),
            &file.name,
            &report,
        )
    };
    (graded, Some((solution, report)))
}

/// A field of the gradebook's CSV, quoted when it holds a comma, a quote or a line break.
fn csv_field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

/// The gradebook: one row per student and case.
pub fn grades_csv(rows: &[CaseGrade]) -> String {
    let mut out =
        String::from("student,case,verdict,score,max_score,points,correct,coverage,note\n");
    for r in rows {
        out.push_str(&format!(
            "{},{},{},{},{},{},{},{:.4},{}\n",
            csv_field(&r.student),
            csv_field(&r.case),
            r.verdict.key(),
            r.score,
            r.max_score,
            r.points,
            r.correct,
            r.coverage,
            csv_field(&r.note(Lang::En))
        ));
    }
    out
}

/// The rows as JSON, for scripts and notebooks: the gradebook's columns (the note in `lang`), and
/// the parts of the image each solution misses, in words.
pub fn rows_json(rows: &[CaseGrade], lang: Lang) -> serde_json::Value {
    rows.iter()
        .map(|r| {
            serde_json::json!({
                "student": r.student,
                "case": r.case,
                "verdict": r.verdict.key(),
                "score": r.score,
                "max_score": r.max_score,
                "points": r.points,
                "correct": r.correct,
                "coverage": r.coverage,
                "note": r.note(lang),
                "missing": r.missing.iter().map(|m| m.words(lang)).collect::<Vec<_>>(),
            })
        })
        .collect()
}

/// One student's results in Gradescope's autograder format (`results.json`): the total score and
/// one test per case.
pub fn gradescope_results(rows: &[CaseGrade]) -> String {
    let tests: Vec<serde_json::Value> = rows
        .iter()
        .map(|r| {
            let mut output = format!("{}: {}", r.verdict.key(), r.note(Lang::En));
            for m in &r.missing {
                output.push('\n');
                output.push_str(&m.words(Lang::En));
            }
            serde_json::json!({
                "name": r.case,
                "score": r.score,
                "max_score": r.max_score,
                "output": output,
            })
        })
        .collect();
    let score: f64 = rows.iter().map(|r| r.score).sum();
    let v = serde_json::json!({
        "score": (score * 100.0).round() / 100.0,
        "tests": tests,
    });
    format!("{v:#}\n")
}

/// The style of the grading pages: plain, printable, readable on a phone.
const PAGE_STYLE: &str = "body{font-family:system-ui,sans-serif;max-width:52rem;margin:1rem auto;\
padding:0 1rem;line-height:1.4}table{border-collapse:collapse;width:100%}th,td{border-bottom:1px \
solid #ccc;padding:.3rem;text-align:left;vertical-align:top}.pass{color:#1a7f37}.fail{color:#b35900}\
.missing,.unreadable{color:#b00020}.bar{display:inline-block;height:.8rem;background:#4a78c2;max-width:80%}\
tr:not(.why)>td:first-child{white-space:nowrap}tr.why td{padding-top:0;font-size:.95rem}tr:has(+tr.why) td\
{border-bottom:none}ul{margin:.2rem 0}figure{margin:1rem 0}figure img{max-width:100%;height:auto}";

/// A page's frame around `body`.
fn page(lang: Lang, title: &str, body: &str) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"{}\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>{}</title>\n<style>{PAGE_STYLE}</style>\n</head>\n<body>\n<h1>{}</h1>\n{body}</body>\n</html>\n",
        lang.code(),
        escape_html(title),
        escape_html(title)
    )
}

/// A score as the pages write it: at most two decimals.
fn score_text(score: f64) -> String {
    let text = format!("{score:.2}");
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// The feedback page of one student (`rows`: their cases, in the assignment's order; `figures`:
/// each case's check figure as PNG, for the cases read).
pub fn student_page(
    lang: Lang,
    student: &str,
    rows: &[CaseGrade],
    figures: &[Option<Vec<u8>>],
) -> String {
    let mut body = String::from("<table>\n<tr>");
    for head in words::GRADE_CASE_HEADS {
        body.push_str(&format!("<th>{}</th>", lang.of(head)));
    }
    body.push_str("</tr>\n");
    for (k, r) in rows.iter().enumerate() {
        let figure = figures.get(k).and_then(Option::as_ref);
        let verdict = lang.of(words::GRADE_VERDICTS[r.verdict as usize]);
        let mut note = escape_html(&r.note(lang));
        if !r.missing.is_empty() {
            note.push_str("<ul>");
            for m in &r.missing {
                note.push_str(&format!("<li>{}</li>", escape_html(&m.words(lang))));
            }
            note.push_str("</ul>");
        }
        let read = matches!(r.verdict, CaseVerdict::Pass | CaseVerdict::Fail);
        body.push_str(&format!(
            "<tr><td>{}</td><td class=\"{}\">{verdict}</td><td>{} / {}</td><td>{}</td><td>{}</td></tr>\n\
             <tr class=\"why\"><td colspan=\"5\">{note}</td></tr>\n",
            // A read case's name leads to its figure, below the table.
            match figure {
                Some(_) => format!(
                    "<a href=\"#figure-{}\">{}</a>",
                    escape_html(&percent_path(&r.case)),
                    escape_html(&r.case)
                ),
                None => escape_html(&r.case),
            },
            r.verdict.key(),
            score_text(r.score),
            score_text(r.max_score),
            if read { format!("{} / {}", r.correct, r.points) } else { "–".into() },
            if read { format!("{:.1} %", 100.0 * r.coverage) } else { "–".into() },
        ));
    }
    body.push_str("</table>\n");
    let total: f64 = rows.iter().map(|r| r.score).sum();
    let most: f64 = rows.iter().map(|r| r.max_score).sum();
    body.push_str(&format!(
        "<p><strong>{}</strong></p>\n<p>{}</p>\n",
        lang.fill(words::GRADE_TOTAL, &[&score_text(total), &score_text(most)]),
        lang.of(words::GRADE_HOW)
    ));
    // Each read case's check figure, in the page itself: one file a student can keep.
    for (r, figure) in rows.iter().zip(figures) {
        if let Some(png) = figure {
            let caption = lang.fill(words::GRADE_FIGURE, &[&r.case]);
            body.push_str(&format!(
                "<figure id=\"figure-{}\"><img src=\"data:image/png;base64,{}\" alt=\"{}\">\
                 <figcaption>{}</figcaption></figure>\n",
                escape_html(&percent_path(&r.case)),
                base64(png),
                escape_html(&caption),
                escape_html(&caption),
            ));
        }
    }
    page(
        lang,
        &lang.fill(words::GRADE_STUDENT_TITLE, &[&student]),
        &body,
    )
}

/// One student on the class page: the name, the folder of their page, their cases.
pub struct Graded<'a> {
    /// The student's name.
    pub name: &'a str,
    /// The folder (in the output) holding their page.
    pub folder: &'a str,
    /// Their cases, in the assignment's order.
    pub rows: &'a [CaseGrade],
}

/// The class at a glance: the distribution of the scores, each case's verdicts, and the parts of
/// the image most students miss.
pub fn class_page(lang: Lang, class: &[Graded]) -> String {
    let most: f64 = class
        .first()
        .map(|g| g.rows.iter().map(|r| r.max_score).sum())
        .unwrap_or(0.0);
    let totals: Vec<f64> = class
        .iter()
        .map(|g| g.rows.iter().map(|r| r.score).sum())
        .collect();
    let mean = totals.iter().sum::<f64>() / totals.len().max(1) as f64;
    let cases = class.first().map_or(0, |g| g.rows.len());
    let mut body = format!(
        "<p>{}</p>\n",
        lang.fill(
            words::GRADE_CLASS_LINE,
            &[&class.len(), &cases, &score_text(mean), &score_text(most)]
        )
    );
    // Scores in ten bins of a tenth of the most (the top bin holds full marks).
    body.push_str(&format!(
        "<h2>{}</h2>\n<table>\n",
        lang.of(words::GRADE_SCORES)
    ));
    let mut bins = [0usize; 10];
    for t in &totals {
        let k = if most > 0.0 {
            (10.0 * t / most).floor() as usize
        } else {
            0
        };
        bins[k.min(9)] += 1;
    }
    let tallest = bins.iter().copied().max().unwrap_or(0).max(1);
    for (k, n) in bins.iter().enumerate() {
        let (lo, hi) = (most * k as f64 / 10.0, most * (k + 1) as f64 / 10.0);
        body.push_str(&format!(
            "<tr><td>{}–{}</td><td><span class=\"bar\" style=\"width:{:.1}%\"></span> {n}</td></tr>\n",
            score_text(lo),
            score_text(hi),
            100.0 * *n as f64 / tallest as f64
        ));
    }
    body.push_str("</table>\n");
    // Each case's verdicts.
    body.push_str(&format!(
        "<h2>{}</h2>\n<table>\n<tr>",
        lang.of(words::GRADE_PASS_RATES)
    ));
    for head in std::iter::once(words::GRADE_CASE_HEADS[0]).chain(words::GRADE_VERDICTS) {
        body.push_str(&format!("<th>{}</th>", lang.of(head)));
    }
    body.push_str("</tr>\n");
    for k in 0..cases {
        let name = &class[0].rows[k].case;
        let count = |v: CaseVerdict| class.iter().filter(|g| g.rows[k].verdict == v).count();
        body.push_str(&format!(
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
            escape_html(name),
            count(CaseVerdict::Pass),
            count(CaseVerdict::Fail),
            count(CaseVerdict::Missing),
            count(CaseVerdict::Unreadable)
        ));
    }
    body.push_str("</table>\n");
    // The parts of the image missed, counted once per student.
    let mut missed: Vec<((u8, LightPathType), usize)> = Vec::new();
    for g in class {
        let mut own: Vec<(u8, LightPathType)> = g
            .rows
            .iter()
            .flat_map(|r| r.missing.iter().map(|m| (m.color, m.path)))
            .collect();
        own.sort();
        own.dedup();
        for key in own {
            match missed.iter_mut().find(|(k, _)| *k == key) {
                Some((_, n)) => *n += 1,
                None => missed.push((key, 1)),
            }
        }
    }
    missed.retain(|(_, n)| *n >= 2);
    missed.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    body.push_str(&format!("<h2>{}</h2>\n", lang.of(words::GRADE_MISTAKES)));
    if missed.is_empty() {
        body.push_str(&format!("<p>{}</p>\n", lang.of(words::GRADE_NO_MISTAKE)));
    } else {
        body.push_str("<ul>\n");
        for ((color, path), n) in missed.iter().take(12) {
            body.push_str(&format!(
                "<li>{}</li>\n",
                escape_html(&lang.fill(
                    words::GRADE_MISTAKE,
                    &[
                        n,
                        &lang.colour_name(*color as usize - 1),
                        &lang.light_path(path)
                    ]
                ))
            ));
        }
        body.push_str("</ul>\n");
    }
    // Each student's total, linking their page.
    body.push_str("<table>\n");
    for (g, t) in class.iter().zip(&totals) {
        body.push_str(&format!(
            "<tr><td><a href=\"{}/index.html\">{}</a></td><td>{} / {}</td></tr>\n",
            escape_html(&percent_path(g.folder)),
            escape_html(g.name),
            score_text(*t),
            score_text(most)
        ));
    }
    body.push_str("</table>\n");
    page(lang, lang.of(words::GRADE_CLASS_TITLE), &body)
}

/// A folder name as a relative link: every byte outside the unreserved set percent-encoded.
fn percent_path(name: &str) -> String {
    name.bytes()
        .map(|b| match b {
            b'A'..=b'Z' | b'a'..=b'z' | b'0'..=b'9' | b'-' | b'_' | b'.' | b'~' => {
                (b as char).to_string()
            }
            _ => format!("%{b:02X}"),
        })
        .collect()
}

/// What [`grade_class`] graded and wrote.
pub struct ClassGrades {
    /// The students, in the class's order.
    pub students: Vec<Student>,
    /// Each student's cases, in the assignment's order.
    pub rows: Vec<Vec<CaseGrade>>,
    /// The gradebook written.
    pub grades: PathBuf,
    /// The class's page written.
    pub overview: PathBuf,
}

/// Grades the class `class` (a folder or a zip: see [`students`]) on `cases` and writes into
/// `out`, as one set (nothing is replaced unless all is written): the gradebook `grades.csv`,
/// the class's page `index.html`, and in a folder per student their Gradescope `results.json`
/// and their feedback page `index.html` with each read case's check figure, in `lang`. Students
/// are graded in parallel; `graded(done, total)` is called after each case (for a progress line).
pub fn grade_class(
    class: &Path,
    cases: &[Case],
    out: &Path,
    lang: Lang,
    graded: &(dyn Fn(usize, usize) + Sync),
) -> Result<ClassGrades> {
    let students = students(class)?;
    let made = files::make_folder(out)?;
    let result = write_class(students, cases, out, lang, graded);
    if result.is_err() {
        files::remove_made_folders(&made);
    }
    result
}

/// [`grade_class`] once the students are known and `out` is made.
fn write_class(
    students: Vec<Student>,
    cases: &[Case],
    out: &Path,
    lang: Lang,
    graded: &(dyn Fn(usize, usize) + Sync),
) -> Result<ClassGrades> {
    let mut made = Vec::new();
    let result = (|| {
        for s in &students {
            made.extend(files::make_folder(&out.join(&s.folder))?);
        }
        let grades = out.join("grades.csv");
        let overview = out.join("index.html");
        let results: Vec<PathBuf> = students
            .iter()
            .map(|s| out.join(&s.folder).join("results.json"))
            .collect();
        let pages: Vec<PathBuf> = students
            .iter()
            .map(|s| out.join(&s.folder).join("index.html"))
            .collect();
        let mut outputs = vec![
            Output {
                flag: "--out",
                path: &grades,
                extensions: &["csv"],
            },
            Output {
                flag: "--out",
                path: &overview,
                extensions: &["html"],
            },
        ];
        outputs.extend(results.iter().chain(&pages).map(|path| Output {
            flag: "--out",
            path,
            extensions: &[],
        }));
        let set = OutputSet::reserve(&outputs)?;
        let total = students.len() * cases.len();
        let done = std::sync::atomic::AtomicUsize::new(0);
        // Each student's files are written as soon as they are graded: the figures are not all
        // held at once.
        let rows = students
            .par_iter()
            .enumerate()
            .map(|(k, student)| {
                let mut rows = Vec::with_capacity(cases.len());
                let mut figures = Vec::with_capacity(cases.len());
                for case in cases {
                    let (row, judged) = judge_case(student, case);
                    let figure = match judged {
                        Some((solution, report)) => Some(check_figure_bytes(
                            &pages[k],
                            FigureFormat::Png,
                            &case.setup,
                            case.setup.observer,
                            &solution.points,
                            &report,
                            &format!(
                                "{}: {}: {}",
                                clip_text(&student.name, 40),
                                case.name,
                                row.verdict.key()
                            ),
                        )?),
                        None => None,
                    };
                    rows.push(row);
                    figures.push(figure);
                    graded(
                        done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1,
                        total,
                    );
                }
                files::write_bytes(&results[k], gradescope_results(&rows).as_bytes())?;
                let page = student_page(lang, &student.name, &rows, &figures);
                files::write_bytes(&pages[k], page.as_bytes())?;
                Ok(rows)
            })
            .collect::<Result<Vec<Vec<CaseGrade>>>>()?;
        let all: Vec<CaseGrade> = rows.iter().flatten().cloned().collect();
        files::write_bytes(&grades, grades_csv(&all).as_bytes())?;
        let class: Vec<Graded> = students
            .iter()
            .zip(&rows)
            .map(|(s, r)| Graded {
                name: &s.name,
                folder: &s.folder,
                rows: r,
            })
            .collect();
        files::write_bytes(&overview, class_page(lang, &class).as_bytes())?;
        set.commit()?;
        Ok((rows, grades, overview))
    })();
    match result {
        Ok((rows, grades, overview)) => Ok(ClassGrades {
            students,
            rows,
            grades,
            overview,
        }),
        Err(e) => {
            files::remove_made_folders(&made);
            Err(e)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_partial_score_weighs_right_points_by_coverage() {
        assert_eq!(partial_score(25.0, 100, 50, 0.98, 0.98), 12.5);
        assert_eq!(partial_score(25.0, 100, 100, 0.49, 0.98), 12.5);
        assert_eq!(partial_score(25.0, 0, 0, 0.0, 0.98), 0.0);
        // Coverage beyond the bar does not add.
        assert_eq!(partial_score(20.0, 10, 9, 1.0, 0.5), 18.0);
    }

    #[test]
    fn file_name_patterns_match_whatever_the_case() {
        assert!(name_matches("sim1.csv", "SIM1.CSV"));
        assert!(name_matches("sim1.*", "sim1.txt"));
        assert!(name_matches("*prism*.csv", "my_prism_v2.csv"));
        assert!(name_matches("sim?.dat", "sim4.dat"));
        assert!(!name_matches("sim1.*", "sim12.txt"));
        assert!(!name_matches("*.csv", "a.csv.txt"));
        assert!(name_matches("**", ""));
    }

    #[test]
    fn an_assignment_file_gives_its_cases_with_the_defaults() {
        let text = r#"
[[case]]
name = "straight"
observer = [0.1, 0.0, 0.1]
straw = [0.02, 0.01]
water_height = 0.15

[[case]]
name = "leaning"
file = "*lean*.csv"
scene = "leaning-straw"
points = 10
tolerance = 2e-6
min_coverage = 0.9
"#;
        let cases = parse_assignment("lab.toml", text, Path::new(".")).unwrap();
        assert_eq!(cases.len(), 2);
        assert_eq!(
            cases[0].files,
            ["straight.csv", "straight.txt", "straight.dat"]
        );
        assert_eq!(cases[0].points, REFERENCE_CASE_POINTS);
        assert_eq!(cases[0].tolerance, DEFAULT_TOLERANCE);
        assert_eq!(cases[0].setup.observer.to_array(), [0.1, 0.0, 0.1]);
        assert_eq!(cases[1].files, ["*lean*.csv"]);
        assert_eq!((cases[1].points, cases[1].min_coverage), (10.0, 0.9));
        // The gallery scene's own observer.
        let gallery = crate::view_spec::SceneFile::gallery("leaning-straw").unwrap();
        let own = ViewSpec {
            scene: Some(gallery),
            values: SceneValues::default(),
            ..ViewSpec::default()
        }
        .load()
        .unwrap();
        assert_eq!(cases[1].setup.observer, own.observer);
    }

    #[test]
    fn an_assignment_file_is_refused_with_every_broken_rule_at_once() {
        let text = r#"
[[case]]
name = "a b"
points = -1
min_coverage = 2
observer = [0.1, 0.0, 0.1]
straw = [0.02, 0.01]
water_height = 0.15

[[case]]
name = "twice"
file = "../x.csv"
scene = "no-such-scene"

[[case]]
name = "twice"
observer = [0.1, 0.0, 0.1]
straw = [0.02, 0.01]
water_height = 0.15
"#;
        let e = parse_assignment("lab.toml", text, Path::new("/nonexistent"))
            .unwrap_err()
            .to_string();
        for part in [
            "case 1 (a b): name",
            "points -1",
            "--min-coverage 2",
            "case 2 (twice): file \"../x.csv\"",
            "case 2 (twice): scene \"no-such-scene\"",
            "case 3 (twice): another case has this name",
        ] {
            assert!(e.contains(part), "{part:?} not in {e}");
        }
        // Unknown keys and malformed TOML name the line.
        let e = parse_assignment(
            "lab.toml",
            "[[case]]\nname = \"x\"\ncolour = 3\n",
            Path::new("."),
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("lab.toml (line 3)") && e.contains("colour"),
            "{e}"
        );
        let e = parse_assignment("lab.toml", "case = []\n", Path::new("."))
            .unwrap_err()
            .to_string();
        assert!(e.contains("no [[case]]"), "{e}");
    }

    #[test]
    fn csv_fields_with_commas_and_quotes_are_quoted() {
        assert_eq!(csv_field("a, \"b\""), "\"a, \"\"b\"\"\"");
        assert_eq!(csv_field("plain"), "plain");
    }
}
