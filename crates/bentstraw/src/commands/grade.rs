//! `bentstraw grade CLASS --out DIR`: every student's solution files checked as `check` checks
//! one, with a progress line; the gradebook, the class's page, and each student's feedback page
//! and Gradescope results written as one set (nothing replaced unless all are written).

use std::path::PathBuf;

use rayon::prelude::*;

use bentstraw_io::files::{self, Output, OutputSet};
use bentstraw_io::grade::{
    assignment, class_page, grade_case, grades_csv, gradescope_results, student_page, students,
    CaseGrade, CaseVerdict, Graded,
};
use bentstraw_io::words::Lang;

use crate::cli::GradeArgs;
use crate::error::CliResult;
use crate::progress;

/// Runs `grade`.
pub fn run(args: &GradeArgs) -> CliResult {
    let cases = assignment(args.assignment.as_deref())?;
    let class = students(&args.class)?;
    let made = files::make_folder(&args.out)?;
    let result = write(args, &class, &cases);
    if result.is_err() {
        files::remove_made_folders(&made);
    }
    result
}

fn write(
    args: &GradeArgs,
    class: &[bentstraw_io::grade::Student],
    cases: &[bentstraw_io::grade::Case],
) -> CliResult {
    let folders: Vec<String> = class.iter().map(|s| s.folder_name()).collect();
    let mut made = Vec::new();
    for f in &folders {
        made.extend(files::make_folder(&args.out.join(f))?);
    }
    let result = (|| -> CliResult {
        let lang = Lang::from(args.lang);
        let grades = args.out.join("grades.csv");
        let overview = args.out.join("index.html");
        let results: Vec<PathBuf> = folders
            .iter()
            .map(|f| args.out.join(f).join("results.json"))
            .collect();
        let pages: Vec<PathBuf> = folders
            .iter()
            .map(|f| args.out.join(f).join("index.html"))
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
        let rows: Vec<Vec<CaseGrade>> = progress::with_progress(
            Some((class.len() * cases.len()) as u64),
            "grading {bar:30} {pos}/{len} cases  [{elapsed}, about {eta} left]",
            |bar| {
                // Students in parallel as well: reading a file is serial work.
                class
                    .par_iter()
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
        for (k, student_rows) in rows.iter().enumerate() {
            files::write_bytes(&results[k], gradescope_results(student_rows).as_bytes())?;
            let page = student_page(lang, &class[k].name, student_rows);
            files::write_bytes(&pages[k], page.as_bytes())?;
        }
        let graded: Vec<Graded> = class
            .iter()
            .zip(&rows)
            .zip(&folders)
            .map(|((s, r), f)| Graded {
                name: &s.name,
                folder: f,
                rows: r,
            })
            .collect();
        files::write_bytes(&overview, class_page(lang, &graded).as_bytes())?;
        set.commit()?;
        let count = |v: CaseVerdict| all.iter().filter(|r| r.verdict == v).count();
        progress::tell(&format!(
            "bentstraw grade: {} student{}, {} cases: {} pass, {} fail, {} missing, {} unreadable\n  wrote {} and {}\n",
            class.len(),
            if class.len() == 1 { "" } else { "s" },
            all.len(),
            count(CaseVerdict::Pass),
            count(CaseVerdict::Fail),
            count(CaseVerdict::Missing),
            count(CaseVerdict::Unreadable),
            files::shown(&grades),
            files::shown(&overview),
        ));
        Ok(())
    })();
    if result.is_err() {
        files::remove_made_folders(&made);
    }
    result
}
