//! `bentstraw grade CLASS --out DIR`: every student's solution files checked as `check` checks
//! one, with a progress line; the gradebook, the class's page, and each student's feedback page
//! and Gradescope results written as one set (nothing replaced unless all are written).

use bentstraw_io::files;
use bentstraw_io::grade::{assignment, grade_class, CaseVerdict};
use bentstraw_io::words::Lang;

use crate::cli::GradeArgs;
use crate::error::CliResult;
use crate::progress;

/// Runs `grade`.
pub fn run(args: &GradeArgs) -> CliResult {
    let cases = assignment(args.assignment.as_deref())?;
    let graded = progress::with_progress(
        None,
        "grading {bar:30} {pos}/{len} cases  [{elapsed}, about {eta} left]",
        |bar| {
            let step = |done: usize, total: usize| {
                bar.set_length(total as u64);
                bar.set_position(done as u64);
            };
            grade_class(&args.class, &cases, &args.out, Lang::from(args.lang), &step)
        },
    )?;
    let all: Vec<_> = graded.rows.iter().flatten().collect();
    let count = |v: CaseVerdict| all.iter().filter(|r| r.verdict == v).count();
    let n = graded.students.len();
    progress::tell(&format!(
        "bentstraw grade: {n} student{}, {} cases: {} pass, {} fail, {} missing, {} unreadable\n  wrote {} and {}\n",
        if n == 1 { "" } else { "s" },
        all.len(),
        count(CaseVerdict::Pass),
        count(CaseVerdict::Fail),
        count(CaseVerdict::Missing),
        count(CaseVerdict::Unreadable),
        files::shown(&graded.grades),
        files::shown(&graded.overview),
    ));
    Ok(())
}
