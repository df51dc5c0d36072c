//! Grading a class: every student's solution files judged as `check` judges one (the same
//! reading and the same verdict), a score per case, and the class's table and Gradescope's
//! results. A student whose file is missing or cannot be read gets that case's verdict with the
//! reason; the rest of the class is graded.

use std::path::{Path, PathBuf};

use bentstraw_optics::check::{
    check_solution, CheckReport, DEFAULT_MIN_COVERAGE, DEFAULT_TOLERANCE,
};
use bentstraw_optics::scene::{DEFAULT_MAX_EVENTS, REFERENCES};
use bentstraw_optics::setup::{SceneValues, Setup};

use bentstraw_optics::text::clip_text;

use crate::error::{Error, Result};
use crate::solution::{read_solution_of, region_words, Solution};

/// Points of each case of the default assignment (four cases: 100 in all).
pub const REFERENCE_CASE_POINTS: f64 = 25.0;
/// The extensions a solution file of the default assignment may have.
pub const SOLUTION_EXTENSIONS: [&str; 3] = ["csv", "txt", "dat"];
/// Most students in a class (sub-folders read): a folder with more is not a class.
pub const MAX_STUDENTS: usize = 5000;
/// The suffix Moodle gives each student's folder in "download all submissions".
const MOODLE_SUFFIX: &str = "_assignsubmission_file_";

/// One case of an assignment: a solution file each student hands in, for one scene and observer.
#[derive(Clone, Debug)]
pub struct Case {
    /// The case's name (a column of the gradebook), e.g. `sim1`.
    pub name: String,
    /// The file's name without its extension, matched whatever the letters' case.
    pub stem: String,
    /// The scene and observer the solution is computed for.
    pub setup: Setup,
    /// Points a pass scores.
    pub points: f64,
    /// Largest allowed difference between a point's distance and its ray's path length (m).
    pub tolerance: f64,
    /// Share of each colour's true image the points must cover.
    pub min_coverage: f64,
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
            };
            Ok(Case {
                name: format!("sim{}", r.number),
                stem: format!("sim{}", r.number),
                setup: Setup::from_values(&values)?,
                points: REFERENCE_CASE_POINTS,
                tolerance: DEFAULT_TOLERANCE,
                min_coverage: DEFAULT_MIN_COVERAGE,
            })
        })
        .collect()
}

/// A student: a name and the folder holding their files.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Student {
    /// The name shown in the gradebook: the folder's, or Moodle's name part of it.
    pub name: String,
    /// The student's folder.
    pub folder: PathBuf,
}

/// The name of a student's folder: Moodle's `Name_Id_assignsubmission_file_` gives `Name`.
pub fn student_name(folder_name: &str) -> String {
    match folder_name.strip_suffix(MOODLE_SUFFIX) {
        Some(rest) => match rest.rsplit_once('_') {
            Some((name, id)) if !name.is_empty() && id.chars().all(|c| c.is_ascii_digit()) => {
                name.to_string()
            }
            _ => rest.to_string(),
        },
        None => folder_name.to_string(),
    }
}

/// The students of the class folder `class`: one per sub-folder (links are not followed), in
/// the order of their names.
pub fn students(class: &Path) -> Result<Vec<Student>> {
    let entries = std::fs::read_dir(class).map_err(|e| {
        Error::Refused(format!(
            "cannot read the class folder {} ({e}): give a folder with one sub-folder per student",
            class.display()
        ))
    })?;
    let mut found = Vec::new();
    for entry in entries.flatten() {
        let Ok(kind) = entry.file_type() else {
            continue;
        };
        if !kind.is_dir() {
            continue; // files beside the students' folders, and links, are not students
        }
        let folder_name = entry.file_name().to_string_lossy().into_owned();
        if folder_name.starts_with('.') {
            continue;
        }
        found.push(Student {
            name: student_name(&folder_name),
            folder: entry.path(),
        });
        if found.len() > MAX_STUDENTS {
            return Err(Error::Refused(format!(
                "{} has more than {MAX_STUDENTS} sub-folders: not a class",
                class.display()
            )));
        }
    }
    if found.is_empty() {
        return Err(Error::Refused(format!(
            "{} has no sub-folder: give a folder with one sub-folder per student",
            class.display()
        )));
    }
    found.sort_by(|a, b| a.name.cmp(&b.name).then(a.folder.cmp(&b.folder)));
    Ok(found)
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
    /// Why, in one line: the file read, the reason it was not, or what is wrong.
    pub note: String,
    /// The parts of the true image the points miss, in words.
    pub missing_regions: Vec<String>,
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

/// The file in `folder` that holds `case`'s solution: `stem` with one of the solution
/// extensions, whatever the letters' case; the first in name order if several.
pub fn case_file(folder: &Path, case: &Case) -> Option<PathBuf> {
    let mut candidates: Vec<PathBuf> = std::fs::read_dir(folder)
        .ok()?
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            let (Some(stem), Some(ext)) = (p.file_stem(), p.extension()) else {
                return false;
            };
            stem.to_string_lossy().eq_ignore_ascii_case(&case.stem)
                && SOLUTION_EXTENSIONS
                    .iter()
                    .any(|e| ext.to_string_lossy().eq_ignore_ascii_case(e))
        })
        .collect();
    candidates.sort();
    candidates.into_iter().next()
}

/// Reads the solution at `path` and judges it as `check` does: the file, and the judgement.
pub fn check_file(
    setup: &Setup,
    path: &Path,
    tolerance: f64,
    min_coverage: f64,
) -> Result<(Solution, CheckReport)> {
    let solution = read_solution_of(path, setup.colour_names().len())?;
    let report = check_solution(
        &setup.world,
        setup.observer,
        &solution.points,
        tolerance,
        min_coverage,
    );
    Ok((solution, report))
}

/// Grades `student`'s file for `case`.
pub fn grade_case(student: &Student, case: &Case) -> CaseGrade {
    let row = |verdict, note: String| CaseGrade {
        student: student.name.clone(),
        case: case.name.clone(),
        verdict,
        score: 0.0,
        max_score: case.points,
        points: 0,
        correct: 0,
        coverage: 0.0,
        note,
        missing_regions: Vec::new(),
    };
    let Some(path) = case_file(&student.folder, case) else {
        return row(
            CaseVerdict::Missing,
            format!(
                "no file {}.csv, .txt or .dat in the student's folder",
                case.stem
            ),
        );
    };
    let file_name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    if std::fs::symlink_metadata(&path).is_ok_and(|m| m.file_type().is_symlink()) {
        return row(
            CaseVerdict::Unreadable,
            format!("{file_name} is a link: hand in the file itself"),
        );
    }
    match check_file(&case.setup, &path, case.tolerance, case.min_coverage) {
        // The file named as the student named it, not by where the class was unpacked.
        Err(e) => row(
            CaseVerdict::Unreadable,
            e.to_string()
                .replace(&clip_text(&path.display().to_string(), 80), &file_name),
        ),
        Ok((_, report)) => {
            let coverage = report
                .coverage
                .per_colour
                .iter()
                .map(|c| c.share())
                .fold(1.0_f64, f64::min);
            let (points, correct) = (report.tally.points, report.tally.correct);
            let missing_regions: Vec<String> =
                report.coverage.missing.iter().map(region_words).collect();
            let passes = report.passes();
            let note = if passes {
                format!("{file_name}: every point right, the image covered")
            } else {
                let mut why = Vec::new();
                if correct < points {
                    why.push(format!("{} of {points} points wrong", points - correct));
                }
                if !report.complete {
                    why.push(format!(
                        "{:.1} % of a colour's image covered (at least {:.1} % asked)",
                        100.0 * coverage,
                        100.0 * case.min_coverage
                    ));
                }
                format!("{file_name}: {}", why.join("; "))
            };
            CaseGrade {
                verdict: if passes {
                    CaseVerdict::Pass
                } else {
                    CaseVerdict::Fail
                },
                score: if passes {
                    case.points
                } else {
                    partial_score(case.points, points, correct, coverage, case.min_coverage)
                },
                points,
                correct,
                coverage,
                note,
                missing_regions,
                ..row(CaseVerdict::Fail, String::new())
            }
        }
    }
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
            csv_field(&r.note)
        ));
    }
    out
}

/// One student's results in Gradescope's autograder format (`results.json`): the total score and
/// one test per case.
pub fn gradescope_results(rows: &[CaseGrade]) -> String {
    let tests: Vec<serde_json::Value> = rows
        .iter()
        .map(|r| {
            let mut output = format!("{}: {}", r.verdict.key(), r.note);
            for region in &r.missing_regions {
                output.push_str(&format!("\nmissing: {region}"));
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moodle_folders_give_the_students_names() {
        assert_eq!(
            student_name("Marie Curie_123456_assignsubmission_file_"),
            "Marie Curie"
        );
        assert_eq!(student_name("ada"), "ada");
        // Not Moodle's id: kept whole.
        assert_eq!(student_name("x_y_assignsubmission_file_"), "x_y");
    }

    #[test]
    fn a_partial_score_weighs_right_points_by_coverage() {
        assert_eq!(partial_score(25.0, 100, 50, 0.98, 0.98), 12.5);
        assert_eq!(partial_score(25.0, 100, 100, 0.49, 0.98), 12.5);
        assert_eq!(partial_score(25.0, 0, 0, 0.0, 0.98), 0.0);
        // Coverage beyond the bar does not add.
        assert_eq!(partial_score(20.0, 10, 9, 1.0, 0.5), 18.0);
    }

    #[test]
    fn csv_fields_with_commas_and_quotes_are_quoted() {
        assert_eq!(csv_field("a, \"b\""), "\"a, \"\"b\"\"\"");
        assert_eq!(csv_field("plain"), "plain");
    }
}
