//! `bentstraw grade CLASS --out DIR`: every student's solution files checked as `check` checks
//! one, with a progress line; the gradebook and each student's Gradescope results written as one
//! set (nothing replaced unless all are written).

use std::path::{Path, PathBuf};

use bentstraw_io::files::{self, Output, OutputSet};
use bentstraw_io::grade::{
    grade_case, grades_csv, gradescope_results, reference_assignment, students, CaseGrade,
    CaseVerdict,
};

use crate::cli::GradeArgs;
use crate::error::CliResult;
use crate::progress;

/// Runs `grade`.
pub fn run(args: &GradeArgs) -> CliResult {
    let cases = reference_assignment()?;
    let class = students(&args.class)?;
    let made = files::make_folder(&args.out)?;
    let result = write(args, &class, &cases);
    if result.is_err() {
        files::remove_made_folders(&made);
    }
    result
}

/// The folder of a student's outputs: their folder's own name (unique in the class).
fn output_folder(out: &Path, student: &bentstraw_io::grade::Student) -> PathBuf {
    out.join(student.folder.file_name().unwrap_or_default())
}

fn write(
    args: &GradeArgs,
    class: &[bentstraw_io::grade::Student],
    cases: &[bentstraw_io::grade::Case],
) -> CliResult {
    let mut made = Vec::new();
    for s in class {
        made.extend(files::make_folder(&output_folder(&args.out, s))?);
    }
    let result = (|| -> CliResult {
        let grades = args.out.join("grades.csv");
        let results: Vec<PathBuf> = class
            .iter()
            .map(|s| output_folder(&args.out, s).join("results.json"))
            .collect();
        let mut outputs = vec![Output {
            flag: "--out",
            path: &grades,
            extensions: &["csv"],
        }];
        outputs.extend(results.iter().map(|path| Output {
            flag: "--out",
            path,
            extensions: &["json"],
        }));
        let set = OutputSet::reserve(&outputs)?;
        let rows: Vec<Vec<CaseGrade>> = progress::with_progress(
            Some((class.len() * cases.len()) as u64),
            "grading {bar:30} {pos}/{len} cases  [{elapsed}, about {eta} left]",
            |bar| {
                class
                    .iter()
                    .map(|s| {
                        cases
                            .iter()
                            .map(|c| {
                                let row = grade_case(s, c);
                                bar.inc(1);
                                row
                            })
                            .collect()
                    })
                    .collect()
            },
        );
        let all: Vec<CaseGrade> = rows.iter().flatten().cloned().collect();
        files::write_bytes(&grades, grades_csv(&all).as_bytes())?;
        for (path, student_rows) in results.iter().zip(&rows) {
            files::write_bytes(path, gradescope_results(student_rows).as_bytes())?;
        }
        set.commit()?;
        let count = |v: CaseVerdict| all.iter().filter(|r| r.verdict == v).count();
        progress::tell(&format!(
            "bentstraw grade: {} students, {} cases: {} pass, {} fail, {} missing, {} unreadable\n  wrote {}",
            class.len(),
            all.len(),
            count(CaseVerdict::Pass),
            count(CaseVerdict::Fail),
            count(CaseVerdict::Missing),
            count(CaseVerdict::Unreadable),
            files::shown(&grades),
        ));
        Ok(())
    })();
    if result.is_err() {
        files::remove_made_folders(&made);
    }
    result
}
