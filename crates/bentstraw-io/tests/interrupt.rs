//! An interruption that comes between an output set's writing and its commit: the commit must
//! not report success (nothing was put in place). Its own test program, since an interruption
//! stops every set of the process.

use bentstraw_io::files::{self, Output, OutputSet};

#[test]
fn an_interruption_before_the_commit_makes_it_fail_and_replaces_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let (view, points) = (dir.path().join("view.png"), dir.path().join("view.csv"));
    std::fs::write(&points, "previous").unwrap();
    let set = OutputSet::reserve(&[
        Output {
            flag: "--output",
            path: &view,
            extensions: &["png"],
        },
        Output {
            flag: "--points",
            path: &points,
            extensions: &["csv"],
        },
    ])
    .unwrap();
    files::write_bytes(&view, b"new picture").unwrap();
    files::write_bytes(&points, b"new points").unwrap();
    // The interruption's handler wins the race: it removes the temporaries first.
    assert!(files::remove_all_temporaries());
    assert!(files::interrupted());
    let e = set.commit().unwrap_err().to_string();
    assert!(e.contains("interrupted"), "{e}");
    assert!(!view.exists());
    assert_eq!(std::fs::read_to_string(&points).unwrap(), "previous");
    // Nor can another set begin.
    let later = dir.path().join("later.csv");
    assert!(OutputSet::reserve(&[Output {
        flag: "--output",
        path: &later,
        extensions: &["csv"],
    }])
    .is_err());
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        1,
        "temporaries left"
    );
}
