//! `bentstraw grade` on a class whose every case's fault is known: bentstraw's own points (a
//! pass, Moodle's folder name and an upper-case file name included), another view's points (a
//! fail with a partial score), a binary file and a link (unreadable), files not handed in
//! (missing). The verdicts are `check`'s on the same files.

use std::fs;
use std::path::Path;

use serde_json::Value;

use crate::bentstraw;
use crate::check_cli::reference_flags;

/// bentstraw's own points of reference `k`, written to `path` (a .csv).
fn simulate(dir: &Path, k: usize, path: &Path) {
    let mut args = vec!["simulate".to_string(), "--points".into(), "3000".into()];
    args.extend(reference_flags(k));
    args.extend(["--output".into(), path.display().to_string()]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let o = bentstraw(dir, &args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// `check`'s exit code for `file` as reference `k`'s solution.
fn check_code(dir: &Path, file: &Path, k: usize) -> i32 {
    let mut args = vec!["check".to_string(), file.display().to_string()];
    args.extend(reference_flags(k));
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    bentstraw(dir, &args).status.code().unwrap()
}

#[test]
fn a_class_gets_check_verdicts_partial_scores_and_gradescope_results() {
    let dir = tempfile::tempdir().unwrap();
    let class = dir.path().join("class");
    let (ada, marie, bob, carl) = (
        class.join("ada"),
        class.join("Marie Curie_123456_assignsubmission_file_"),
        class.join("bob"),
        class.join("carl"),
    );
    for d in [&ada, &marie, &bob, &carl] {
        fs::create_dir_all(d).unwrap();
    }
    simulate(dir.path(), 1, &ada.join("sim1.csv"));
    simulate(dir.path(), 2, &dir.path().join("two.csv"));
    fs::copy(dir.path().join("two.csv"), marie.join("SIM2.TXT")).unwrap();
    fs::copy(dir.path().join("two.csv"), bob.join("sim1.csv")).unwrap();
    fs::write(carl.join("sim1.dat"), [0u8, 159, 146, 150, 0, 1]).unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(ada.join("sim1.csv"), carl.join("sim2.csv")).unwrap();
    fs::write(class.join("notes.txt"), "not a student").unwrap();

    let out = dir.path().join("grades");
    let o = bentstraw(dir.path(), &["grade", "class", "--out", "grades"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = fs::read_to_string(out.join("grades.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "student,case,verdict,score,max_score,points,correct,coverage,note"
    );
    let rows: Vec<Vec<String>> = lines
        .map(|l| {
            // The note, last, may be quoted: the first eight fields have no comma.
            l.splitn(9, ',').map(str::to_string).collect()
        })
        .collect();
    assert_eq!(rows.len(), 4 * 4, "{csv}");
    let row = |student: &str, case: &str| {
        rows.iter()
            .find(|r| r[0] == student && r[1] == case)
            .unwrap_or_else(|| panic!("no row {student} {case} in {csv}"))
            .clone()
    };
    // A pass scores the case's 25 points; the verdict is check's.
    let a = row("ada", "sim1");
    assert_eq!(
        (a[2].as_str(), a[3].as_str(), a[4].as_str()),
        ("pass", "25", "25")
    );
    assert_eq!(check_code(dir.path(), &ada.join("sim1.csv"), 1), 0);
    let m = row("Marie Curie", "sim2");
    assert_eq!(m[2], "pass", "{m:?}");
    // Another view's points: a fail, scored by the share of right points and the coverage.
    let b = row("bob", "sim1");
    assert_eq!(b[2], "fail", "{b:?}");
    assert_eq!(check_code(dir.path(), &bob.join("sim1.csv"), 1), 1);
    let (points, correct, coverage): (f64, f64, f64) = (
        b[5].parse().unwrap(),
        b[6].parse().unwrap(),
        b[7].parse().unwrap(),
    );
    let expected = 25.0 * correct / points * (coverage / 0.98).min(1.0);
    let score: f64 = b[3].parse().unwrap();
    assert!((score - expected).abs() <= 0.006, "{score} vs {expected}");
    assert!(score < 25.0);
    // Unreadable files say why, naming the file as handed in (not where the class lies).
    let c = row("carl", "sim1");
    assert_eq!((c[2].as_str(), c[3].as_str()), ("unreadable", "0"), "{c:?}");
    assert!(
        c[8].contains("sim1.dat") && !c[8].contains("class/carl"),
        "{c:?}"
    );
    #[cfg(unix)]
    {
        let l = row("carl", "sim2");
        assert_eq!(l[2], "unreadable", "{l:?}");
        assert!(l[8].contains("link"), "{l:?}");
    }
    let miss = row("ada", "sim4");
    assert_eq!((miss[2].as_str(), miss[3].as_str()), ("missing", "0"));

    // Gradescope's results: the total and a test per case.
    let v: Value =
        serde_json::from_slice(&fs::read(out.join("bob").join("results.json")).unwrap()).unwrap();
    let tests = v["tests"].as_array().unwrap();
    assert_eq!(tests.len(), 4);
    let names: Vec<&str> = tests.iter().map(|t| t["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["sim1", "sim2", "sim3", "sim4"]);
    let total: f64 = tests.iter().map(|t| t["score"].as_f64().unwrap()).sum();
    assert!((v["score"].as_f64().unwrap() - total).abs() < 1e-9);
    assert_eq!(tests[0]["max_score"].as_f64(), Some(25.0));
    assert!(tests[0]["output"].as_str().unwrap().starts_with("fail: "));
    assert!(out
        .join("Marie Curie_123456_assignsubmission_file_")
        .join("results.json")
        .is_file());

    // The feedback pages: each student's, and the class's linking them.
    let bob_page = fs::read_to_string(out.join("bob").join("index.html")).unwrap();
    assert!(bob_page.contains("<html lang=\"en\">") && bob_page.contains("missing: "));
    assert!(bob_page.contains(&format!("{} / 25", b[3])), "{bob_page}");
    let overview = fs::read_to_string(out.join("index.html")).unwrap();
    assert!(overview.contains("href=\"Marie%20Curie_123456_assignsubmission_file_/index.html\""));
    assert!(overview.contains("Common mistakes"));
    // Each read case's check figure is in the student's page; a missing one has none.
    assert_eq!(
        bob_page
            .matches("<img src=\"data:image/png;base64,")
            .count(),
        1
    );
    let carl_page = fs::read_to_string(out.join("carl").join("index.html")).unwrap();
    assert!(!carl_page.contains("<img"));

    // The same class handed in as one zip (with Moodle's folder and a zip bomb): the same rows.
    let zipped = dir.path().join("class.zip");
    let mut zip = zip::ZipWriter::new(fs::File::create(&zipped).unwrap());
    let deflated = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated);
    for (folder, name) in [
        (&ada, "sim1.csv"),
        (&marie, "SIM2.TXT"),
        (&bob, "sim1.csv"),
        (&carl, "sim1.dat"),
    ] {
        let inside = format!(
            "class/{}/{name}",
            folder.file_name().unwrap().to_str().unwrap()
        );
        zip.start_file(inside, deflated).unwrap();
        std::io::Write::write_all(&mut zip, &fs::read(folder.join(name)).unwrap()).unwrap();
    }
    #[cfg(unix)]
    zip.add_symlink("class/carl/sim2.csv", "../ada/sim1.csv", deflated)
        .unwrap();
    zip.start_file("class/dan/sim3.csv", deflated).unwrap();
    std::io::Write::write_all(&mut zip, &vec![b' '; 30 << 20]).unwrap();
    zip.finish().unwrap();
    let o = bentstraw(dir.path(), &["grade", "class.zip", "--out", "zipped"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let from_zip = fs::read_to_string(dir.path().join("zipped").join("grades.csv")).unwrap();
    let (dan, others): (Vec<&str>, Vec<&str>) =
        from_zip.lines().partition(|l| l.starts_with("dan,"));
    assert_eq!(others.join("\n") + "\n", csv);
    assert!(
        dan[2].starts_with("dan,sim3,unreadable,0,") && dan[2].contains("zip bomb"),
        "{dan:?}"
    );

    // In French, the same verdicts in the explorer's words.
    let o = bentstraw(
        dir.path(),
        &["grade", "class", "--out", "fr", "--lang", "fr"],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let fr = fs::read_to_string(dir.path().join("fr").join("bob").join("index.html")).unwrap();
    assert!(
        fr.contains("<html lang=\"fr\">") && fr.contains("échoué"),
        "{fr}"
    );
    assert!(fr.contains("manquent : "), "{fr}");
    assert_eq!(
        fs::read_to_string(dir.path().join("fr").join("grades.csv")).unwrap(),
        csv
    );
}

#[test]
fn a_class_folder_that_is_not_one_is_refused_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(dir.path().join("file"), "x").unwrap();
    for (class, why) in [("absent", "class folder"), ("file", "as a zip")] {
        let o = bentstraw(dir.path(), &["grade", class, "--out", "grades"]);
        assert_eq!(o.status.code(), Some(2));
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(why), "{err}");
        assert!(!dir.path().join("grades").exists());
    }
    fs::create_dir(dir.path().join("empty")).unwrap();
    let o = bentstraw(dir.path(), &["grade", "empty", "--out", "grades"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("no sub-folder"));
    assert!(!dir.path().join("grades").exists());
}

#[test]
fn an_assignment_file_grades_its_own_scenes_files_and_points() {
    let dir = tempfile::tempdir().unwrap();
    let student = dir.path().join("class").join("dana");
    fs::create_dir_all(&student).unwrap();
    let o = bentstraw(
        dir.path(),
        &[
            "simulate",
            "--scene",
            "leaning-straw",
            "--points",
            "3000",
            "--output",
            "class/dana/My_Leaning.csv",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    fs::write(
        dir.path().join("lab.toml"),
        "[[case]]\nname = \"leaning\"\nfile = \"*leaning*.csv\"\nscene = \"leaning-straw\"\npoints = 10\n\n\
         [[case]]\nname = \"classic\"\nobserver = [0.1, 0.0, 0.1]\nstraw = [0.02, 0.01]\nwater_height = 0.15\n",
    )
    .unwrap();
    let o = bentstraw(
        dir.path(),
        &["grade", "class", "--out", "out", "--assignment", "lab.toml"],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = fs::read_to_string(dir.path().join("out").join("grades.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().skip(1).collect();
    assert_eq!(rows.len(), 2, "{csv}");
    assert!(rows[0].starts_with("dana,leaning,pass,10,10,"), "{csv}");
    assert!(
        rows[1].starts_with("dana,classic,missing,0,25,")
            && rows[1].contains("classic.csv, classic.txt or classic.dat"),
        "{csv}"
    );

    // A broken assignment: every mistake told, exit 2, nothing written.
    fs::write(
        dir.path().join("bad.toml"),
        "[[case]]\nname = \"x\"\npoints = 0\nscene = \"nowhere\"\n",
    )
    .unwrap();
    let o = bentstraw(
        dir.path(),
        &[
            "grade",
            "class",
            "--out",
            "out2",
            "--assignment",
            "bad.toml",
        ],
    );
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("points 0") && err.contains("scene \"nowhere\""),
        "{err}"
    );
    assert!(!dir.path().join("out2").exists());
}
