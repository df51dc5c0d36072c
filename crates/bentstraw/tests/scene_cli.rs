//! `--scene FILE.toml` from the outside: the assignment's scene from a file gives the same files
//! as the same flags; every gallery scene is simulated and rendered; a bad file, or one a command
//! cannot take yet, is refused in one line, exit code 2, with no file written and the previous
//! ones kept.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn gallery(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes")
        .join(name)
        .display()
        .to_string()
}

fn run(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_bentstraw"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("bentstraw runs")
}

fn files_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

fn succeeded(out: &Output) {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Runs `args` in a folder holding only `old.csv` and the given scene files; checks it is refused
/// in one line naming each of `names`, with exit code 2, and leaves the folder as it was.
fn assert_refused(scene_files: &[(&str, &str)], args: &[&str], names: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("old.csv"), "previous\n").unwrap();
    for (name, text) in scene_files {
        std::fs::write(dir.path().join(name), text).unwrap();
    }
    let before = files_in(dir.path());
    let out = run(dir.path(), args);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "one line: {stderr}");
    for name in names {
        assert!(
            stderr.contains(name),
            "{args:?} should name {name}: {stderr}"
        );
    }
    assert_eq!(files_in(dir.path()), before, "no file written: {stderr}");
    assert_eq!(
        std::fs::read_to_string(dir.path().join("old.csv")).unwrap(),
        "previous\n"
    );
    stderr
}

#[test]
fn the_spec_file_gives_the_same_points_as_the_same_flags() {
    let dir = tempfile::tempdir().unwrap();
    let spec = gallery("spec.toml");
    succeeded(&run(
        dir.path(),
        &["simulate", "--scene", &spec, "--output", "file.csv"],
    ));
    succeeded(&run(
        dir.path(),
        &[
            "simulate",
            "--observer",
            "0.1,0,0.1",
            "--straw",
            "0.02,0.01",
            "--water-height",
            "0.15",
            "--output",
            "flags.csv",
        ],
    ));
    // By its name from any folder, as the gallery's scenes are.
    succeeded(&run(
        dir.path(),
        &["simulate", "--scene", "spec", "--output", "name.csv"],
    ));
    let file = std::fs::read(dir.path().join("file.csv")).unwrap();
    let flags = std::fs::read(dir.path().join("flags.csv")).unwrap();
    let name = std::fs::read(dir.path().join("name.csv")).unwrap();
    assert!(file.len() > 1000);
    assert!(
        file == flags,
        "the file's scene is the flags' scene, byte for byte"
    );
    assert!(
        name == file,
        "spec by its name is the file scenes/spec.toml"
    );
}

#[test]
fn the_flags_override_the_file_and_its_observer() {
    let dir = tempfile::tempdir().unwrap();
    let spec = gallery("spec.toml");
    let changes = [
        "--observer",
        "0,0.1,0.3",
        "--straw",
        "0,0",
        "--water-height",
        "0.2",
        "--n-water",
        "1.5",
        "--points",
        "3000",
    ];
    let mut with_file = vec!["simulate", "--scene", &spec, "--output", "file.csv"];
    with_file.extend(changes);
    succeeded(&run(dir.path(), &with_file));
    let mut flags = vec!["simulate", "--output", "flags.csv"];
    flags.extend(changes);
    succeeded(&run(dir.path(), &flags));
    let file = std::fs::read(dir.path().join("file.csv")).unwrap();
    assert!(file == std::fs::read(dir.path().join("flags.csv")).unwrap());
    // And they did change something: the file's own scene gives other points.
    succeeded(&run(
        dir.path(),
        &[
            "simulate", "--scene", &spec, "--points", "3000", "--output", "own.csv",
        ],
    ));
    assert!(file != std::fs::read(dir.path().join("own.csv")).unwrap());
}

#[test]
fn render_takes_the_files_target_unless_target_is_given() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(gallery("spec.toml"))
        .unwrap()
        .replace("target = [0.0, 0.0, 0.125]", "target = [0.0, 0.0, 0.05]");
    assert!(text.contains("0.05]"));
    std::fs::write(dir.path().join("low.toml"), text).unwrap();
    let common = [
        "render", "--mode", "course", "--size", "32x24", "--fov", "60",
    ];
    let raw = |name: &str, extra: &[&str]| {
        let mut args = common.to_vec();
        args.extend(extra);
        args.extend(["--output", "v.png", "--raw", name]);
        succeeded(&run(dir.path(), &args));
        std::fs::read(dir.path().join(name)).unwrap()
    };
    let scene = [
        "--observer",
        "0.1,0,0.1",
        "--straw",
        "0.02,0.01",
        "--water-height",
        "0.15",
    ];
    let from_file = raw("file.csv", &["--scene", "low.toml"]);
    let mut low = scene.to_vec();
    low.extend(["--target", "0,0,0.05"]);
    assert!(from_file == raw("low.csv", &low));
    assert!(from_file != raw("centre.csv", &scene));
    let overridden = raw(
        "over.csv",
        &["--scene", "low.toml", "--target", "0,0,0.125"],
    );
    assert!(overridden == raw("centre2.csv", &scene));
}

#[test]
fn check_and_bench_take_a_scene_file() {
    let dir = tempfile::tempdir().unwrap();
    let spec = gallery("spec.toml");
    succeeded(&run(
        dir.path(),
        &[
            "simulate", "--scene", &spec, "--points", "2000", "--output", "p.csv",
        ],
    ));
    let out = run(dir.path(), &["check", "p.csv", "--scene", &spec, "--json"]);
    succeeded(&out);
    assert!(String::from_utf8_lossy(&out.stdout).contains("\"verdict\":\"pass\""));
    // Checked against another scene, the same points fail.
    let out = run(
        dir.path(),
        &["check", "p.csv", "--scene", &spec, "--water-height", "0.1"],
    );
    assert_eq!(out.status.code(), Some(1));
    let out = run(
        dir.path(),
        &[
            "bench",
            "--scene",
            &spec,
            "--mode",
            "course",
            "--size",
            "20x10",
            "--repeat",
            "1",
            "--threads",
            "1",
        ],
    );
    succeeded(&out);
    let text = String::from_utf8(out.stdout).unwrap();
    assert_eq!(text.lines().count(), 3, "one case: {text}");
}

#[test]
fn a_bad_scene_file_is_refused_in_one_line_naming_the_file_the_key_and_the_value() {
    let bad = "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.2\n[[straw]]\nx = 0\ny = 0\ntilt = 95\n";
    for command in [
        vec![
            "simulate",
            "--scene",
            "bad.toml",
            "--observer",
            "0.1,0,0.1",
            "--output",
            "old.csv",
        ],
        vec![
            "render",
            "--scene",
            "bad.toml",
            "--observer",
            "0.1,0,0.1",
            "--output",
            "v.png",
        ],
        vec![
            "check",
            "old.csv",
            "--scene",
            "bad.toml",
            "--observer",
            "0.1,0,0.1",
        ],
        vec!["bench", "--scene", "bad.toml", "--observer", "0.1,0,0.1"],
    ] {
        assert_refused(
            &[("bad.toml", bad)],
            &command,
            &["bad.toml", "straw[1].tilt", "95"],
        );
    }
    let syntax = "[container]\nshape = \"glass\"\nradius = 0.04,\nheight = 0.2\n";
    assert_refused(
        &[("bad.toml", syntax)],
        &["simulate", "--scene", "bad.toml", "--output", "old.csv"],
        &["bad.toml", "line 3"],
    );
}

#[test]
fn an_unreadable_or_huge_scene_file_is_refused() {
    assert_refused(
        &[],
        &["simulate", "--scene", "none.toml", "--output", "old.csv"],
        &["cannot read", "none.toml"],
    );
    let huge = format!("{}\n", "#".repeat(1 << 20));
    assert_refused(
        &[("huge.toml", &huge)],
        &["simulate", "--scene", "huge.toml", "--output", "old.csv"],
        &["huge.toml", "1 MB"],
    );
}

/// `check` judges a solution in any scene file: a scene's own points pass, a solution with wrong
/// colours fails and says so, colour codes past the scene's are refused with their line.
#[test]
fn check_judges_solutions_in_any_scene_file() {
    let dir = tempfile::tempdir().unwrap();
    let file = gallery("reversing-arrow.toml");
    succeeded(&run(
        dir.path(),
        &[
            "simulate", "--scene", &file, "--points", "3000", "--output", "mine.csv",
        ],
    ));
    let out = run(
        dir.path(),
        &[
            "check",
            "mine.csv",
            "--scene",
            &file,
            "--json",
            "--plot",
            "check.svg",
        ],
    );
    succeeded(&out);
    let json = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(json.contains("\"verdict\":\"pass\""), "{json}");
    assert!(json.contains("\"scene_file\""), "{json}");
    assert!(dir.path().join("check.svg").is_file());
    // The arrow's points claimed as the card: every one a wrong colour.
    let text = std::fs::read_to_string(dir.path().join("mine.csv")).unwrap();
    let wrong: String = text
        .lines()
        .map(|l| {
            l.strip_suffix(",8")
                .map_or(l.to_string(), |p| format!("{p},7"))
        })
        .collect::<Vec<_>>()
        .join("\n");
    std::fs::write(dir.path().join("wrong.csv"), wrong).unwrap();
    let out = run(dir.path(), &["check", "wrong.csv", "--scene", &file]);
    assert_eq!(out.status.code(), Some(1));
    let summary = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        summary.contains("FAIL") && summary.contains("8 arrow"),
        "{summary}"
    );
    // A colour code past the scene's eight is refused with its line.
    std::fs::write(dir.path().join("nine.csv"), "x,y,z,color\n0.1,0,0.1,9\n").unwrap();
    let out = run(dir.path(), &["check", "nine.csv", "--scene", &file]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("line 2") && err.contains("1 to 8"), "{err}");
}

/// Every gallery scene gives its image points and its picture; the points are the objects'
/// (codes 1..=8), the files complete, and the same inputs give the same bytes.
#[test]
fn every_gallery_scene_is_simulated_and_rendered() {
    let dir = tempfile::tempdir().unwrap();
    for name in [
        "leaning-straw",
        "real-glass",
        "oil-on-water",
        "tank-pencil",
        "coin-in-glass",
        "reversing-arrow",
        "vanishing-glass",
        "two-straws",
        "oil-on-water-above",
        "appearing-coin",
        "apparent-depth",
        "mirror-surface",
        "near-and-far-arrow",
        "pencil-at-a-slant",
        "leaning-straw-above",
        "dense-liquid",
        "marble-in-water",
        "fish-bowl",
        "water-drop-magnifier",
        "vanishing-ball",
        "ball-lens",
        "half-dipped-ball",
        "prism",
        "glass-block-pencil",
        "magnifying-glass",
        "diverging-lens",
        "lens-in-water",
        "tapered-tumbler",
        "wine-glass",
        "cocktail-glass",
    ] {
        let file = gallery(&format!("{name}.toml"));
        for (ext, check) in [("csv", true), ("ply", false), ("json", false)] {
            let out = format!("{name}.{ext}");
            succeeded(&run(
                dir.path(),
                &[
                    "simulate", "--scene", &file, "--points", "3000", "--output", &out,
                ],
            ));
            let bytes = std::fs::read(dir.path().join(&out)).unwrap();
            assert!(bytes.len() > 3000 * 20, "{out}: {} bytes", bytes.len());
            if check {
                let text = String::from_utf8(bytes).unwrap();
                let mut lines = text.lines();
                assert_eq!(lines.next(), Some("x,y,z,color"));
                let rows: Vec<&str> = lines.collect();
                assert!(rows.len() >= 3000, "{out}: {} rows", rows.len());
                for row in &rows {
                    let cells: Vec<f64> = row.split(',').map(|c| c.parse().unwrap()).collect();
                    assert_eq!(cells.len(), 4);
                    assert!((1.0..=8.0).contains(&cells[3]), "{out}: {row}");
                    // Every point lies within a metre of the scene.
                    assert!(cells[..3].iter().all(|c| c.abs() < 1.0), "{out}: {row}");
                }
            }
        }
        let again = run(
            dir.path(),
            &[
                "simulate",
                "--scene",
                &file,
                "--points",
                "3000",
                "--output",
                "again.csv",
            ],
        );
        succeeded(&again);
        assert_eq!(
            std::fs::read(dir.path().join("again.csv")).unwrap(),
            std::fs::read(dir.path().join(format!("{name}.csv"))).unwrap(),
            "{name}: deterministic"
        );
        for mode in ["course", "fresnel"] {
            let png = format!("{name}-{mode}.png");
            let raw = format!("{name}-{mode}.raw.csv");
            succeeded(&run(
                dir.path(),
                &[
                    "render", "--scene", &file, "--mode", mode, "--size", "160x120", "--output",
                    &png, "--raw", &raw,
                ],
            ));
            let picture = std::fs::read(dir.path().join(&png)).unwrap();
            assert!(picture.starts_with(b"\x89PNG"), "{png}");
            let text = std::fs::read_to_string(dir.path().join(&raw)).unwrap();
            assert_eq!(text.lines().count(), 1 + 160 * 120, "{raw}");
            if mode == "course" {
                // The picture shows some object of the scene.
                assert!(
                    text.lines().skip(1).any(|l| !l.ends_with(",0")),
                    "{name}: an object in view"
                );
            } else {
                // Weights are fractions of one ray's light.
                for line in text.lines().skip(1) {
                    let w: f64 = line
                        .split(',')
                        .skip(2)
                        .map(|c| c.parse::<f64>().unwrap())
                        .sum();
                    assert!((0.0..=1.0 + 1e-12).contains(&w), "{raw}: {line}");
                }
            }
        }
    }
}

#[test]
fn flags_override_a_scene_files_straw_and_liquid_by_the_files_rules() {
    let dir = tempfile::tempdir().unwrap();
    let file = gallery("leaning-straw.toml");
    // A higher water level, a denser liquid: accepted and traced.
    succeeded(&run(
        dir.path(),
        &[
            "simulate",
            "--scene",
            &file,
            "--water-height",
            "0.1",
            "--n-water",
            "1.5",
            "--points",
            "1000",
            "--output",
            "a.csv",
        ],
    ));
    // A water level above the rim breaks the file's rule, named by its key.
    assert_refused(
        &[],
        &[
            "simulate",
            "--scene",
            &file,
            "--water-height",
            "0.3",
            "--output",
            "new.csv",
        ],
        &["leaning-straw.toml", "liquid[1].top", "0.3"],
    );
    // So does an eye inside the glass.
    assert_refused(
        &[],
        &[
            "render",
            "--scene",
            &file,
            "--observer",
            "0,0,0.1",
            "--output",
            "new.png",
        ],
        &["observer.position", "inside or on the container"],
    );
    assert_refused(
        &[],
        &[
            "simulate",
            "--scene",
            &file,
            "--max-events",
            "0",
            "--output",
            "new.csv",
        ],
        &["event limit 0"],
    );
}

/// A scene of four hundred leaning straws in a wide tank is traced like any other (every ray
/// tests every object: bounded by the format's thousand entries of a kind).
#[test]
fn a_scene_of_many_straws_is_traced() {
    let mut text =
        String::from("[container]\nshape = \"tank\"\nhalf_x = 10.0\nhalf_y = 10.0\nheight = 0.2\n");
    // As many objects as a file may hold.
    for i in 0..100 {
        text.push_str(&format!(
            "[[straw]]\nx = {}\ny = {}\ntilt = {}\n",
            -9.0 + (i % 10) as f64 * 1.5,
            -9.0 + (i / 10) as f64 * 1.5,
            1.0 + i as f64 * 0.4
        ));
    }
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("many.toml"), &text).unwrap();
    succeeded(&run(
        dir.path(),
        &[
            "simulate",
            "--scene",
            "many.toml",
            "--observer",
            "30,0,1",
            "--points",
            "2000",
            "--output",
            "many.csv",
        ],
    ));
    let rows = std::fs::read_to_string(dir.path().join("many.csv")).unwrap();
    assert!(rows.lines().count() > 2000);
}

#[test]
fn overrides_need_one_straw_and_one_liquid_and_a_file_without_observer_needs_the_flag() {
    assert_refused(
        &[],
        &[
            "simulate",
            "--scene",
            &gallery("oil-on-water.toml"),
            "--n-water",
            "1.4",
            "--output",
            "old.csv",
        ],
        &["--n-water", "one straw and one liquid", "2 liquid(s)"],
    );
    let no_view =
        "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.2\n[[straw]]\nx = 0\ny = 0\n";
    assert_refused(
        &[("plain.toml", no_view)],
        &["simulate", "--scene", "plain.toml", "--output", "old.csv"],
        &["plain.toml", "[observer]", "--observer"],
    );
    // The flags' own rules still hold for an override.
    assert_refused(
        &[],
        &[
            "simulate",
            "--scene",
            &gallery("spec.toml"),
            "--water-height",
            "0.3",
            "--output",
            "old.csv",
        ],
        &["water height 0.3"],
    );
}

/// `explore --scene` starts the page on the file's scene and observer, the flags overriding it;
/// a file the page cannot show as it is, with those flags, is refused before anything listens.
#[test]
fn explore_starts_on_a_scene_file() {
    use std::io::{BufRead, BufReader, Read, Write};
    // The page `explore --scene FILE EXTRA…` serves.
    let page_on = |file: &str, extra: &[&str]| -> String {
        let mut child = Command::new(env!("CARGO_BIN_EXE_bentstraw"))
            .args(["explore", "--no-open", "--port", "0", "--scene", file])
            .args(extra)
            .stdout(std::process::Stdio::piped())
            .spawn()
            .expect("bentstraw runs");
        let mut line = String::new();
        BufReader::new(child.stdout.take().unwrap())
            .read_line(&mut line)
            .unwrap();
        let url = line
            .split_whitespace()
            .find(|w| w.starts_with("http://"))
            .unwrap();
        let host = url.trim_start_matches("http://").trim_end_matches('/');
        let mut stream = std::net::TcpStream::connect(host).unwrap();
        write!(
            stream,
            "GET / HTTP/1.1\r\nHost: {host}\r\nConnection: close\r\n\r\n"
        )
        .unwrap();
        let mut body = String::new();
        stream.read_to_string(&mut body).unwrap();
        child.kill().unwrap();
        child.wait().unwrap();
        body
    };
    // The file's observer, straw and water (spec.toml: the second reference view).
    let spec = gallery("spec.toml");
    let from_file = page_on(&spec, &[]);
    assert!(from_file.contains("observer=0.1,0,0.1&amp;straw=0.02,0.01&amp;water-height=0.15"));
    let overridden = page_on(&spec, &["--water-height", "0.1"]);
    assert!(overridden.contains("straw=0.02,0.01&amp;water-height=0.1&amp;"));
    // A scene of the gallery starts the page on it, from its own observer.
    let tank = page_on(&gallery("tank-pencil.toml"), &[]);
    assert!(
        tank.contains("scene=tank-pencil&amp;observer="),
        "{}",
        &tank[..tank.len().min(2000)]
    );
    // Any other scene file travels with the view, its text in the page's starting address.
    let dir = tempfile::tempdir().unwrap();
    let mine = dir.path().join("mine.toml");
    std::fs::write(
        &mine,
        std::fs::read_to_string(gallery("tank-pencil.toml"))
            .unwrap()
            .replace("half_x = 0.10", "half_x = 0.12"),
    )
    .unwrap();
    let page = page_on(&mine.display().to_string(), &[]);
    assert!(
        page.contains("scene-file=%23%20The%20textbook"),
        "{}",
        &page[..page.len().min(2000)]
    );
    assert!(page.contains("half_x%20%3D%200.12"));
    // Its values are the file's: the flags that change the assignment's scene are refused here.
    let out = run(
        dir.path(),
        &[
            "explore",
            "--no-open",
            "--port",
            "0",
            "--scene",
            "mine.toml",
            "--n-water",
            "1.4",
        ],
    );
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(
        err.contains("mine.toml") && err.contains("--n-water"),
        "{err}"
    );
    assert!(out.stdout.is_empty());
}

/// The eye and stereo models and the gap plot work on any scene file: the columns of the
/// models, a point for most image points, and the figure written.
#[test]
fn the_models_work_in_every_kind_of_scene() {
    let dir = tempfile::tempdir().unwrap();
    let file = gallery("coin-in-glass.toml");
    for (model, first) in [("eye", "x,y,z,color,s_h,s_v"), ("stereo", "x,y,z,color")] {
        let out = format!("{model}.csv");
        succeeded(&run(
            dir.path(),
            &[
                "simulate",
                "--scene",
                &file,
                "--points",
                "2000",
                "--image-model",
                model,
                "--output",
                &out,
            ],
        ));
        let text = std::fs::read_to_string(dir.path().join(&out)).unwrap();
        assert!(text.starts_with(first), "{model}: {}", &text[..80]);
        let placed = text.lines().skip(1).filter(|l| !l.starts_with(',')).count();
        assert!(placed > 1000, "{model}: {placed} points placed");
    }
    succeeded(&run(
        dir.path(),
        &[
            "simulate",
            "--scene",
            &file,
            "--points",
            "2000",
            "--output",
            "p.json",
            "--gap-plot",
            "gap.svg",
        ],
    ));
    let svg = std::fs::read_to_string(dir.path().join("gap.svg")).unwrap();
    assert!(svg.contains("<svg"));
    let json = std::fs::read_to_string(dir.path().join("p.json")).unwrap();
    assert!(
        json.contains("\"scene_file\"") && json.contains("\"coin\""),
        "{}",
        &json[..400]
    );
}

/// `bench --scene` times a scene file of any kind: a line per case, then the averages.
#[test]
fn bench_times_any_scene_file() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["real-glass.toml", "reversing-arrow.toml"] {
        for extra in [&[][..], &["--frame"][..]] {
            let mut args = vec![
                "bench",
                "--scene",
                &gallery(name),
                "--size",
                "40x30",
                "--repeat",
                "1",
                "--threads",
                "1",
            ]
            .into_iter()
            .map(String::from)
            .collect::<Vec<_>>();
            args.extend(extra.iter().map(|s| s.to_string()));
            let refs: Vec<&str> = args.iter().map(String::as_str).collect();
            let out = run(dir.path(), &refs);
            succeeded(&out);
            let text = String::from_utf8(out.stdout).unwrap();
            // A header, course and fresnel, the averages.
            assert_eq!(text.lines().count(), 4, "{name} {extra:?}: {text}");
            assert!(text.contains("Mrays/s"));
        }
    }
}

/// The gallery is built in: `--scene leaning-straw` (or `leaning-straw.toml`) works from any
/// folder and gives the file's points; a file of that name in the folder wins.
#[test]
fn a_gallery_scene_is_named_from_any_folder() {
    let dir = tempfile::tempdir().unwrap();
    let points = |scene: &str, out: &str| {
        let o = run(
            dir.path(),
            &[
                "simulate", "--scene", scene, "--points", "300", "--output", out,
            ],
        );
        succeeded(&o);
        std::fs::read(dir.path().join(out)).unwrap()
    };
    let from_file = points(&gallery("leaning-straw.toml"), "file.csv");
    assert_eq!(points("leaning-straw", "name.csv"), from_file);
    assert_eq!(points("leaning-straw.toml", "toml.csv"), from_file);
    // A file of that name, where there is one, is the one read.
    let own = std::fs::read_to_string(gallery("leaning-straw.toml"))
        .unwrap()
        .replace("tilt = 15.0", "tilt = 10.0");
    std::fs::write(dir.path().join("leaning-straw.toml"), own).unwrap();
    assert_ne!(points("leaning-straw.toml", "own.csv"), from_file);
    // An unknown name is still a missing file.
    let o = run(
        dir.path(),
        &[
            "simulate", "--scene", "teapot", "--points", "10", "--output", "t.csv",
        ],
    );
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("cannot read the scene file teapot"));
    // A slip in a gallery name gets the names it may stand for, and nothing is written.
    let o = run(
        dir.path(),
        &[
            "simulate",
            "--scene",
            "leanin-straw",
            "--output",
            "slip.csv",
        ],
    );
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("there is no scene file leanin-straw")
            && err.contains("did you mean 'leaning-straw'")
            && err.contains("the gallery has spec, "),
        "{err}"
    );
    assert!(!dir.path().join("slip.csv").exists());
}

/// A file whose sizes read like centimetres is traced as written, with a hint on standard
/// error naming the key and what to write; several broken rules are refused together.
#[test]
fn centimetres_get_a_hint_and_broken_rules_come_together() {
    let dir = tempfile::tempdir().unwrap();
    let big = "[container]\nshape = \"glass\"\nradius = 4\nheight = 20\n\n[[straw]]\nx = 0\ny = 0\n\n[observer]\nposition = [30, 0, 10]\n";
    std::fs::write(dir.path().join("big.toml"), big).unwrap();
    let out = run(
        dir.path(),
        &[
            "simulate", "--scene", "big.toml", "--points", "200", "--output", "big.csv",
        ],
    );
    succeeded(&out);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("hint: big.toml: container.radius = 4: lengths are in metres"),
        "{err}"
    );
    assert!(err.contains("write 0.04"), "{err}");
    let broken = "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.2\n\n[[liquid]]\nname = \"water\"\nindex = 0.5\ntop = 0.1\n\n[[straw]]\nx = 0\ny = 0\ntilt = 95\n";
    std::fs::write(dir.path().join("broken.toml"), broken).unwrap();
    let out = run(
        dir.path(),
        &[
            "simulate",
            "--scene",
            "broken.toml",
            "--observer",
            "0.3,0,0.1",
            "--output",
            "b.csv",
        ],
    );
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("2 rules are broken:"), "{err}");
    assert!(
        err.contains("liquid[1].index = 0.5") && err.contains("straw[1].tilt = 95"),
        "{err}"
    );
    assert!(!dir.path().join("b.csv").exists());
}

/// A prism of flint glass and water by its measured law, in a glass of crown glass.
const DISPERSIVE: &str = "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.2\nwall = 0.003\nbottom = 0.005\nmaterial = \"bk7\"\n\n[[liquid]]\nname = \"water\"\nmaterial = \"water\"\ntop = 0.12\n\n[[straw]]\nx = 0.01\ny = 0.01\n\n[[prism]]\ncorners = [[0.06, -0.03], [0.1, -0.03], [0.08, 0.0046]]\nbottom = 0\ntop = 0.09\nmaterial = \"f2\"\n\n[observer]\nposition = [0.3, -0.04, 0.15]\n";

/// `--wavelength` traces a dispersive scene at that wavelength: the files are those of the same
/// scene with every index written as its law's value there (the same bytes), they change with
/// the wavelength, and `render`, `check` and `table` take it too.
#[test]
fn a_wavelength_traces_the_scene_with_its_indices_there() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("d.toml"), DISPERSIVE).unwrap();
    let simulate = |scene: &str, extra: &[&str], out: &str| {
        let mut args = vec![
            "simulate", "--scene", scene, "--points", "2000", "--output", out,
        ];
        args.extend_from_slice(extra);
        succeeded(&run(dir.path(), &args));
        std::fs::read(dir.path().join(out)).unwrap()
    };
    // The indices at 450 nm, from the laws' sources (written with enough digits to be exact is
    // not needed: the engine's own values are compared below, these only pick the file).
    let d = bentstraw_optics::scene_file::SceneDescription::from_toml(DISPERSIVE).unwrap();
    let at = |nm: f64| {
        let mut text = DISPERSIVE.to_string();
        for l in &d.dispersion {
            let bentstraw_optics::dispersion::Dispersion::Material(m) = &l.law else {
                unreachable!()
            };
            let n = l.law.index_at(nm);
            text = text.replacen(
                &format!("material = \"{}\"", m.name),
                &format!("index = {n:?}"),
                1,
            );
        }
        text
    };
    std::fs::write(dir.path().join("p450.toml"), at(450.0)).unwrap();
    let blue = simulate("d.toml", &["--wavelength", "450"], "blue.csv");
    assert_eq!(blue, simulate("p450.toml", &[], "plain.csv"));
    let red = simulate("d.toml", &["--wavelength", "700"], "red.csv");
    assert_ne!(blue, red);
    // Without a wavelength, the d line.
    assert_eq!(
        simulate("d.toml", &[], "d.csv"),
        simulate("d.toml", &["--wavelength", "587.56"], "d2.csv")
    );
    for args in [
        vec![
            "render",
            "--scene",
            "d.toml",
            "--wavelength",
            "450",
            "--size",
            "64x48",
            "--output",
            "v.png",
        ],
        vec![
            "check",
            "blue.csv",
            "--scene",
            "d.toml",
            "--wavelength",
            "450",
        ],
        vec![
            "table",
            "--scene",
            "d.toml",
            "--wavelength",
            "450",
            "--points",
            "300",
            "--out",
            "t",
        ],
    ] {
        succeeded(&run(dir.path(), &args));
    }
    let check = run(
        dir.path(),
        &[
            "check",
            "blue.csv",
            "--scene",
            "d.toml",
            "--wavelength",
            "700",
        ],
    );
    assert!(
        !check.status.success(),
        "the blue points are not the red image"
    );
}

/// A wavelength outside the visible, a material not in the table and laws that break their rules
/// are refused in one line each, naming the key, the value and the rule.
#[test]
fn bad_wavelengths_and_laws_are_refused_with_their_rules() {
    let args = |extra: &'static str| {
        let mut a = vec!["simulate", "--scene", "d.toml", "--output", "old.csv"];
        if !extra.is_empty() {
            a.extend(["--wavelength", extra]);
        }
        a
    };
    for nm in ["300", "800", "nan"] {
        assert_refused(
            &[("d.toml", DISPERSIVE)],
            &args(nm),
            &[
                "wavelength",
                "nm is not allowed: visible light is from 380 to 780 nm",
            ],
        );
    }
    for (from, to, names) in [
        (
            "material = \"f2\"",
            "material = \"f3\"",
            vec!["prism[1].material", "did you mean 'f2'", "sf10"],
        ),
        (
            "material = \"f2\"",
            "material = \"unobtainium\"",
            vec!["\"unobtainium\" is not a named material"],
        ),
        (
            "material = \"f2\"",
            "cauchy = [1.6]",
            vec!["prism[1].cauchy", "not 1 numbers"],
        ),
        (
            "material = \"f2\"",
            "sellmeier = [1.0, 0.25]",
            vec!["prism[1].sellmeier", "at 500 nm"],
        ),
        (
            "material = \"f2\"",
            "index = 1.6\nmaterial = \"f2\"",
            vec!["give one of index, cauchy, sellmeier or material, not index, material"],
        ),
    ] {
        let text = DISPERSIVE.replace(from, to);
        assert_refused(&[("d.toml", &text)], &args(""), &names);
    }
}

/// `simulate --light white`: each point carries its band's wavelength, about an eighth of the
/// points in each band; every point of each band is correct by the checker against the scene at
/// that wavelength (its ray traced again there), and the violet points are not against the red
/// end; the figures are drawn. (An eighth of the points covers a band's image too thinly for
/// the checker's test of completeness.)
#[test]
fn white_light_points_are_each_at_their_bands_wavelength() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("d.toml"), DISPERSIVE).unwrap();
    let out = run(
        dir.path(),
        &[
            "simulate", "--scene", "d.toml", "--points", "4000", "--light", "white", "--output",
            "w.csv", "--html", "w.html", "--plot", "w.png",
        ],
    );
    succeeded(&out);
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("light           white: 8 bands"),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(dir.path().join("w.csv")).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("x,y,z,color,wavelength"));
    let mut bands: std::collections::BTreeMap<String, Vec<String>> = Default::default();
    for line in lines {
        let (point, nm) = line.rsplit_once(',').unwrap();
        bands
            .entry(nm.to_string())
            .or_default()
            .push(point.to_string());
    }
    let names: Vec<&str> = bands.keys().map(String::as_str).collect();
    assert_eq!(
        names,
        ["405.0", "455.0", "505.0", "555.0", "605.0", "655.0", "705.0", "755.0"]
    );
    let total: usize = bands.values().map(Vec::len).sum();
    for (nm, points) in &bands {
        assert!(
            points.len() * 8 > total * 3 / 4,
            "{nm} nm: {}",
            points.len()
        );
        let file = format!("{nm}.csv");
        let csv = format!("x,y,z,color\n{}\n", points.join("\n"));
        std::fs::write(dir.path().join(&file), csv).unwrap();
        let nm = nm.trim_end_matches(".0");
        let args = ["check", &file, "--scene", "d.toml", "--wavelength", nm];
        let report = String::from_utf8_lossy(&run(dir.path(), &args).stdout).to_string();
        assert!(report.contains("every point correct"), "{nm} nm: {report}");
    }
    let violet = [
        "check",
        "405.0.csv",
        "--scene",
        "d.toml",
        "--wavelength",
        "755",
    ];
    let report = String::from_utf8_lossy(&run(dir.path(), &violet).stdout).to_string();
    assert!(!report.contains("every point correct"), "{report}");
    for figure in ["w.html", "w.png"] {
        assert!(dir.path().join(figure).is_file(), "{figure}");
    }
    let page = std::fs::read_to_string(dir.path().join("w.html")).unwrap();
    assert!(page.contains("405 nm") && page.contains("white light"));
}
