//! `bentstraw check` on solutions whose faults are known: bentstraw's own points (a pass), and
//! copies of them with points moved along their ray, colours changed, a colour removed, the points
//! made by total reflection removed; the same files in other formats; malformed files.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use bentstraw_optics::geometry::Ray;
use bentstraw_optics::image::ImagePoint;
use bentstraw_optics::sampling::sample_image;
use bentstraw_optics::scene::{Scene, REFERENCES};
use bentstraw_optics::world::World;
use serde_json::Value;

fn bentstraw(dir: &Path, args: &[String]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_bentstraw"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("the binary runs")
}

/// The scene flags of reference simulation `k` (1..=4).
pub(crate) fn reference_flags(k: usize) -> Vec<String> {
    let r = &REFERENCES[k - 1];
    let o = r.observer;
    vec![
        "--observer".into(),
        format!("{},{},{}", o.x, o.y, o.z),
        "--straw".into(),
        format!("{},{}", r.straw.0, r.straw.1),
        "--water-height".into(),
        format!("{}", r.water_height),
    ]
}

/// Runs `check FILE` for reference `k` with `extra` flags.
fn check(dir: &Path, file: &Path, k: usize, extra: &[&str]) -> Output {
    let mut args = vec!["check".to_string(), file.display().to_string()];
    args.extend(reference_flags(k));
    args.extend(extra.iter().map(|s| s.to_string()));
    bentstraw(dir, &args)
}

/// `check --json`: the exit code and the object.
fn check_json(dir: &Path, file: &Path, k: usize, extra: &[&str]) -> (i32, Value) {
    let mut flags = vec!["--json"];
    flags.extend(extra);
    let o = check(dir, file, k, &flags);
    let v: Value = serde_json::from_slice(&o.stdout).unwrap_or_else(|e| {
        panic!(
            "{e}: stdout {:?} stderr {:?}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        )
    });
    (o.status.code().unwrap(), v)
}

/// Reference `k`'s scene and its own image points (the library's sampler).
fn own_points(k: usize, n: usize) -> (Scene, Vec<ImagePoint>) {
    let r = &REFERENCES[k - 1];
    let scene = r.scene(1.333);
    (
        scene,
        sample_image(&World::assignment(&scene), r.observer, n, &|_| {}).points,
    )
}

/// Writes points as `x<sep>y<sep>z<sep>color` lines with full precision, with an optional header.
fn write(
    dir: &Path,
    name: &str,
    points: &[(f64, f64, f64, u8)],
    sep: &str,
    header: bool,
) -> PathBuf {
    let mut s = String::new();
    if header {
        s.push_str(&["x", "y", "z", "color"].join(sep));
        s.push('\n');
    }
    for (x, y, z, c) in points {
        s.push_str(&format!("{x:?}{sep}{y:?}{sep}{z:?}{sep}{c}\n"));
    }
    let path = dir.join(name);
    fs::write(&path, s).unwrap();
    path
}

fn rows(points: &[ImagePoint]) -> Vec<(f64, f64, f64, u8)> {
    points
        .iter()
        .map(|p| (p.position.x, p.position.y, p.position.z, p.color))
        .collect()
}

fn counts(v: &Value) -> [u64; 6] {
    [
        "points",
        "correct",
        "wrong_colour",
        "wrong_length",
        "no_straw",
        "too_many_events",
    ]
    .map(|k| v[k].as_u64().unwrap_or_else(|| panic!("{k} in {v}")))
}

#[test]
fn bentstraws_own_output_passes_in_the_four_references() {
    let dir = tempfile::tempdir().unwrap();
    for k in 1..=4 {
        let csv = dir.path().join(format!("sim{k}.csv"));
        let mut args = vec!["simulate".to_string()];
        args.extend(reference_flags(k));
        args.extend(["--points".into(), "5000".into(), "--output".into()]);
        args.push(csv.display().to_string());
        assert!(bentstraw(dir.path(), &args).status.success());
        let (code, v) = check_json(dir.path(), &csv, k, &[]);
        let n = v["points"].as_u64().unwrap();
        assert!(n >= 5000);
        assert_eq!(counts(&v), [n, n, 0, 0, 0, 0], "reference {k}: {v}");
        assert_eq!(v["verdict"], "pass", "reference {k}: {v}");
        assert_eq!(v["complete"], true);
        for c in 1..=5 {
            assert!(v["coverage"][c.to_string()].as_f64().unwrap() >= 0.98);
        }
        assert_eq!(code, 0);
        // The summary for people says so too.
        let o = check(dir.path(), &csv, k, &[]);
        let text = String::from_utf8_lossy(&o.stdout);
        assert!(text.contains("PASS"), "{text}");
        assert_eq!(o.status.code(), Some(0));
    }
}

#[test]
fn points_moved_ten_micrometres_along_their_ray_have_the_wrong_length() {
    let dir = tempfile::tempdir().unwrap();
    let (_, pts) = own_points(2, 5000);
    // 1 % of the points, every 100th, 10 µm farther along their own ray.
    let moved: Vec<ImagePoint> = pts
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let mut p = *p;
            if i % 100 == 0 {
                p.position += 1e-5 * p.direction;
            }
            p
        })
        .collect();
    let n_moved = pts.len().div_ceil(100) as u64;
    let file = write(dir.path(), "moved.csv", &rows(&moved), ",", true);
    let (code, v) = check_json(dir.path(), &file, 2, &[]);
    let n = pts.len() as u64;
    assert_eq!(counts(&v), [n, n - n_moved, 0, n_moved, 0, 0], "{v}");
    assert_eq!(v["verdict"], "fail");
    assert_eq!(v["complete"], true, "moving points keeps the coverage");
    assert_eq!(code, 1);
    // The worst points name their line (header = line 1, point i on line i + 2) and the error.
    let worst = &v["worst"][0];
    assert_eq!(worst["kind"], "wrong_length");
    assert_eq!((worst["line"].as_u64().unwrap() - 2) % 100, 0);
    assert!((worst["length_error_m"].as_f64().unwrap() - 1e-5).abs() < 1e-9);
    // A looser tolerance forgives them.
    let (code, v) = check_json(dir.path(), &file, 2, &["--tolerance", "2e-5"]);
    assert_eq!((code, v["verdict"].as_str()), (0, Some("pass")));
}

#[test]
fn changed_colours_are_named_with_the_colour_really_seen() {
    let dir = tempfile::tempdir().unwrap();
    let (_, pts) = own_points(1, 5000);
    let mut r = rows(&pts);
    let changed = [3usize, 500, 1234, 4000];
    for &i in &changed {
        r[i].3 = r[i].3 % 5 + 1;
    }
    let file = write(dir.path(), "colours.csv", &r, ",", true);
    let (code, v) = check_json(dir.path(), &file, 1, &[]);
    let n = pts.len() as u64;
    assert_eq!(counts(&v), [n, n - 4, 4, 0, 0, 0], "{v}");
    assert_eq!(code, 1);
    let mut lines: Vec<u64> = v["worst"]
        .as_array()
        .unwrap()
        .iter()
        .map(|w| {
            assert_eq!(w["kind"], "wrong_colour");
            w["line"].as_u64().unwrap()
        })
        .collect();
    lines.sort();
    assert_eq!(lines, changed.map(|i| i as u64 + 2));
    for w in v["worst"].as_array().unwrap() {
        let i = w["line"].as_u64().unwrap() as usize - 2;
        assert_eq!(w["actual_color"].as_u64(), Some(pts[i].color as u64));
    }
}

#[test]
fn a_colour_removed_is_missing_whole() {
    let dir = tempfile::tempdir().unwrap();
    let (_, pts) = own_points(2, 5000);
    let kept: Vec<ImagePoint> = pts.iter().copied().filter(|p| p.color != 3).collect();
    let file = write(dir.path(), "no_magenta.csv", &rows(&kept), ",", true);
    let (code, v) = check_json(dir.path(), &file, 2, &[]);
    let n = kept.len() as u64;
    assert_eq!(counts(&v), [n, n, 0, 0, 0, 0]);
    assert_eq!(v["coverage"]["3"].as_f64(), Some(0.0));
    for c in ["1", "2", "4", "5"] {
        assert!(v["coverage"][c].as_f64().unwrap() >= 0.98, "{c}: {v}");
    }
    assert_eq!(v["complete"], false);
    assert_eq!((code, v["verdict"].as_str()), (1, Some("fail")));
    let missing = v["missing"].as_array().unwrap();
    assert!(!missing.is_empty());
    assert!(missing.iter().all(|m| m["color"] == 3), "{missing:?}");
    assert_eq!(missing[0]["place"], "whole");
    assert!(missing[0]["words"]
        .as_str()
        .unwrap()
        .starts_with("magenta (3)"));
}

#[test]
fn points_past_the_first_total_reflection_removed_are_missing_as_total_reflection() {
    let dir = tempfile::tempdir().unwrap();
    let (scene, pts) = own_points(2, 8000);
    let o = REFERENCES[1].observer;
    let reflected = |p: &ImagePoint| {
        let ray = Ray {
            origin: o,
            direction: p.direction,
        };
        World::assignment(&scene)
            .trace_path_type(ray)
            .1
            .total_reflections
            > 0
    };
    let kept: Vec<ImagePoint> = pts.iter().copied().filter(|p| !reflected(p)).collect();
    assert!(
        kept.len() + 50 < pts.len(),
        "total reflections make part of the image"
    );
    let file = write(dir.path(), "no_tir.csv", &rows(&kept), ",", true);
    let (code, v) = check_json(dir.path(), &file, 2, &[]);
    let n = kept.len() as u64;
    assert_eq!(counts(&v), [n, n, 0, 0, 0, 0]);
    assert_eq!(code, 1);
    assert_eq!(v["complete"], false, "{v}");
    let missing = v["missing"].as_array().unwrap();
    assert!(!missing.is_empty());
    for m in missing {
        let path = m["path"].as_str().unwrap();
        assert!(path.contains('+'), "{path}: not a total reflection");
        assert!(m["words"].as_str().unwrap().contains("total reflection"));
    }
    // The summary for people lists them in words.
    let text = String::from_utf8_lossy(&check(dir.path(), &file, 2, &[]).stdout).into_owned();
    assert!(text.contains("missing from the image"), "{text}");
    assert!(text.contains("1 total reflection"), "{text}");
}

#[test]
fn the_same_points_headerless_space_or_semicolon_separated_get_the_same_verdicts() {
    let dir = tempfile::tempdir().unwrap();
    let (_, pts) = own_points(3, 3000);
    let mut r = rows(&pts);
    r[7].3 = r[7].3 % 5 + 1;
    r[9].2 += 0.01;
    let mut results = Vec::new();
    for (name, sep, header) in [
        ("a.csv", ",", true),
        ("b.csv", ",", false),
        ("c.txt", " ", false),
        ("d.txt", "\t", true),
        ("e.csv", ";", true),
        ("f.csv", ";", false),
    ] {
        let file = write(dir.path(), name, &r, sep, header);
        let (code, mut v) = check_json(dir.path(), &file, 3, &[]);
        for k in ["file", "seconds"] {
            v.as_object_mut().unwrap().remove(k);
        }
        // Line numbers move by one without the header.
        for w in v["worst"].as_array_mut().unwrap() {
            let l = w["line"].as_u64().unwrap();
            w["line"] = (l - header as u64).into();
        }
        results.push((code, v));
    }
    assert_eq!(results[0].0, 1);
    assert!(results[0].1["wrong_colour"].as_u64().unwrap() >= 1);
    for r in &results[1..] {
        assert_eq!(r, &results[0]);
    }
}

#[test]
fn too_many_events_is_told_apart_from_no_straw() {
    let dir = tempfile::tempdir().unwrap();
    let (_, pts) = own_points(2, 3000);
    let deep = pts.iter().filter(|p| p.events > 1).count() as u64;
    assert!(deep > 0);
    let mut r = rows(&pts);
    // One point straight away from the glass.
    r.push((1.0, 0.0, 0.1, 2));
    let file = write(dir.path(), "pts.csv", &r, ",", true);
    let (code, v) = check_json(dir.path(), &file, 2, &["--max-events", "1"]);
    assert_eq!(v["too_many_events"].as_u64(), Some(deep), "{v}");
    assert_eq!(v["no_straw"].as_u64(), Some(1));
    assert_eq!(code, 1);
}

#[test]
fn malformed_files_are_refused_with_the_line_number_and_no_figure() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("fig.png");
    for (text, want) in [
        (
            "x,y,z,color\n0.1,0,0.1,1\n0.1,0,0.1\n",
            "line 3: 3 value(s)",
        ),
        (
            "0.1 0 0.1 1\n0.1 0 zero 1\n",
            "line 2: 'zero' is not a number",
        ),
        ("0.1 0 0.1 7\n", "line 1: colour 7 is not a colour code"),
        (
            "NaN,NaN,NaN,NaN\nNaN,NaN,NaN,NaN\n",
            "line 1: x = NaN is not a finite number",
        ),
        ("", "no points"),
    ] {
        let file = dir.path().join("bad.csv");
        fs::write(&file, text).unwrap();
        let o = check(dir.path(), &file, 2, &["--plot", png.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{text:?}: {err}");
        assert!(err.contains(want), "{text:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
        assert!(o.stdout.is_empty());
        assert!(!png.exists());
    }
    // A scene outside the rules, a bad tolerance, a missing file: exit 2 too.
    let file = write(dir.path(), "ok.csv", &[(0.1, 0.0, 0.1, 1)], ",", false);
    for extra in [
        &["--tolerance", "0"][..],
        &["--min-coverage", "1.5"][..],
        &["--n-water", "0.5"][..],
        &["--plot", "fig.jpg"][..],
    ] {
        let o = check(dir.path(), &file, 2, extra);
        assert_eq!(o.status.code(), Some(2), "{extra:?}");
    }
    let o = check(dir.path(), &dir.path().join("absent.csv"), 2, &[]);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn the_figure_is_written_as_png_svg_or_pdf() {
    let dir = tempfile::tempdir().unwrap();
    let (_, pts) = own_points(2, 3000);
    let kept: Vec<ImagePoint> = pts.iter().copied().filter(|p| p.color != 2).collect();
    let mut r = rows(&kept);
    r[5].3 = r[5].3 % 5 + 1;
    let file = write(dir.path(), "s.csv", &r, ",", true);
    for name in ["fig.png", "fig.svg", "fig.pdf"] {
        let o = check(dir.path(), &file, 2, &["--plot", name]);
        assert_eq!(o.status.code(), Some(1));
        let bytes = fs::read(dir.path().join(name)).unwrap();
        if name.ends_with(".png") {
            assert!(bytes.starts_with(b"\x89PNG"));
        } else if name.ends_with(".pdf") {
            assert!(bytes.starts_with(b"%PDF"));
        } else {
            let s = String::from_utf8(bytes).unwrap();
            let doc = roxmltree::Document::parse(&s).expect("well-formed SVG");
            let width: f64 = doc
                .root_element()
                .attribute("width")
                .unwrap()
                .parse()
                .unwrap();
            let texts: Vec<(String, f64)> = doc
                .descendants()
                .filter(|n| n.has_tag_name("text"))
                .map(|n| {
                    let size = n.attribute("font-size").unwrap().parse().unwrap();
                    (n.text().unwrap_or("").trim().to_string(), size)
                })
                .collect();
            // 7 pt when printed 8.5 cm wide, for every text.
            for (t, size) in &texts {
                assert!(*size >= width * 7.0 / 72.0 * 2.54 / 8.5, "'{t}': {size} px");
            }
            for want in ["front view", "wrong colour: 1", "missing (numbered)"] {
                assert!(texts.iter().any(|t| t.0.contains(want)), "no '{want}'");
            }
        }
    }
}

#[test]
fn points_in_millimetres_get_a_hint() {
    let dir = tempfile::tempdir().unwrap();
    let (_, pts) = own_points(1, 2000);
    let mm: Vec<(f64, f64, f64, u8)> = rows(&pts)
        .into_iter()
        .map(|(x, y, z, c)| (1e3 * x, 1e3 * y, 1e3 * z, c))
        .collect();
    let file = write(dir.path(), "mm.csv", &mm, ",", true);
    let (code, v) = check_json(dir.path(), &file, 1, &[]);
    assert_eq!(code, 1);
    assert_eq!(v["correct"].as_u64(), Some(0));
    let hints = v["hints"].as_array().unwrap();
    assert!(hints[0].as_str().unwrap().contains("millimetres"), "{v}");
    let text = String::from_utf8_lossy(&check(dir.path(), &file, 1, &[]).stdout).into_owned();
    assert!(
        text.contains("hint") && text.contains("millimetres"),
        "{text}"
    );
}

#[test]
fn a_file_saved_with_five_digits_gets_a_hint_about_precision() {
    // MATLAB's csvwrite keeps five significant digits: rounding alone moves points by micrometres.
    let dir = tempfile::tempdir().unwrap();
    let (_, pts) = own_points(2, 3000);
    let text: String = rows(&pts)
        .iter()
        .map(|(x, y, z, c)| format!("{x:.4e},{y:.4e},{z:.4e},{c}\n"))
        .collect();
    let file = dir.path().join("short.csv");
    fs::write(&file, text).unwrap();
    let (code, v) = check_json(dir.path(), &file, 2, &[]);
    assert_eq!(code, 1);
    assert!(v["wrong_length"].as_u64().unwrap() > 0, "{v}");
    assert_eq!(v["digits"].as_u64(), Some(5));
    let hints = v["hints"].as_array().unwrap();
    assert!(
        hints
            .iter()
            .any(|h| h.as_str().unwrap().contains("at most 5 significant digits")),
        "{hints:?}"
    );
    // With a tolerance to match, no length is wrong (a colour may still flip at a section edge).
    let (_, v) = check_json(dir.path(), &file, 2, &["--tolerance", "3e-5"]);
    assert_eq!(v["wrong_length"].as_u64(), Some(0), "{v}");
}

#[test]
fn devices_pipes_and_huge_files_are_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let refused = |o: &Output, words: &str| {
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains(words), "{err}");
        assert!(o.stdout.is_empty());
    };
    // A device that never ends: refused before a byte is read.
    refused(
        &check(d, Path::new("/dev/zero"), 2, &[]),
        "not a regular file",
    );
    // A named pipe no one writes to: opening it would wait forever.
    let made = Command::new("mkfifo").arg(d.join("pipe.csv")).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo is needed");
    refused(&check(d, &d.join("pipe.csv"), 2, &[]), "not a regular file");
    let scene_pipe = bentstraw(
        d,
        &["simulate", "--scene", "pipe.csv", "--output", "x.csv"].map(String::from),
    );
    refused(&scene_pipe, "not a regular file");
    // A 2 GiB file (sparse: it costs no disk): refused by its size, not read.
    let big = fs::File::create(d.join("big.csv")).unwrap();
    big.set_len(2 << 30).unwrap();
    refused(&check(d, &d.join("big.csv"), 2, &[]), "2147483648 bytes");
}
