//! The command line from the outside: outputs, their exactness, the report, and every rejection.
//!
//! The points written are checked against the library in-process (same inputs, same points, bit
//! for bit) and re-traced one by one along their own direction, as an independent reviewer would.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use bentstraw_optics::sampling::sample_image;
use bentstraw_optics::scene::{Scene, REFERENCES, SECTION_RGB};
use bentstraw_optics::world::World;
use bentstraw_optics::Vec3;

/// Runs the binary in `dir` with `args`.
fn bentstraw(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_bentstraw"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("the binary runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The scene arguments of reference simulation `k` (1..=4).
fn reference_args(k: usize) -> Vec<String> {
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

fn simulate(dir: &Path, k: usize, points: usize, extra: &[&str]) -> Output {
    let mut args: Vec<String> = vec!["simulate".into()];
    args.extend(reference_args(k));
    args.extend(["--points".into(), points.to_string()]);
    args.extend(extra.iter().map(|s| s.to_string()));
    let refs: Vec<&str> = args.iter().map(String::as_str).collect();
    bentstraw(dir, &refs)
}

/// Parses a points CSV (gzip-compressed if its name ends in `.gz`): exact header, then
/// `(x, y, z, color)` rows.
fn read_csv(path: &Path) -> Vec<(Vec3, u8)> {
    let text = if path.extension().is_some_and(|e| e == "gz") {
        let mut text = String::new();
        std::io::Read::read_to_string(
            &mut flate2::read::GzDecoder::new(fs::File::open(path).unwrap()),
            &mut text,
        )
        .unwrap();
        text
    } else {
        fs::read_to_string(path).unwrap()
    };
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("x,y,z,color"), "{}", path.display());
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            assert_eq!(f.len(), 4, "row {l}");
            let v: Vec<f64> = f[..3].iter().map(|s| s.parse().unwrap()).collect();
            // Shortest form: the same significant digits as Rust's shortest round-trip `{}`
            // (which may write the same number without an exponent).
            for (s, x) in f[..3].iter().zip(&v) {
                assert_eq!(
                    significant(s),
                    significant(&format!("{x}")),
                    "{s}: not the shortest exact form"
                );
            }
            (Vec3::new(v[0], v[1], v[2]), f[3].parse().unwrap())
        })
        .collect()
}

/// The significant digits of a decimal number: no sign, point, exponent or padding zeros.
fn significant(s: &str) -> String {
    let mantissa = s.split(['e', 'E']).next().unwrap();
    let digits: String = mantissa.chars().filter(char::is_ascii_digit).collect();
    digits
        .trim_start_matches('0')
        .trim_end_matches('0')
        .to_string()
}

/// Every point re-traced along `(P − O)/|P − O|` gives its colour and a path of length `|P − O|`.
fn assert_retraces(scene: &Scene, observer: Vec3, points: &[(Vec3, u8)]) {
    let mut worst = 0.0f64;
    let world = World::assignment(scene);
    for &(p, color) in points {
        let d = p - observer;
        let u0 = d / d.length();
        let again = world
            .image_point(observer, u0)
            .unwrap_or_else(|| panic!("point {p} re-traced misses the straw"));
        assert_eq!(again.color, color, "point {p}: colour");
        worst = worst.max((again.path_length - d.length()).abs());
    }
    assert!(worst <= 1e-9, "path lengths differ by up to {worst} m");
}

#[test]
fn csv_points_are_the_librarys_bit_for_bit_and_retrace_on_every_reference() {
    let dir = tempfile::tempdir().unwrap();
    for k in 1..=4 {
        let n = 2000;
        let name = format!("sim{k}.csv");
        let out = simulate(dir.path(), k, n, &["--output", &name]);
        assert!(out.status.success(), "{}", stderr(&out));
        let points = read_csv(&dir.path().join(&name));
        assert!(points.len() >= n, "{} points < {n}", points.len());

        let r = &REFERENCES[k - 1];
        let scene = r.scene(1.333);
        let expected = sample_image(&World::assignment(&scene), r.observer, n, &|_| {});
        assert_eq!(points.len(), expected.points.len());
        for ((p, c), e) in points.iter().zip(&expected.points) {
            assert_eq!(
                p.to_array().map(f64::to_bits),
                e.position.to_array().map(f64::to_bits)
            );
            assert_eq!(*c, e.color);
        }
        assert_retraces(&scene, r.observer, &points);
        // Every colour the straw shows here is a valid code.
        assert!(points.iter().all(|(_, c)| (1..=5).contains(c)));
    }
}

#[test]
fn same_inputs_give_byte_identical_files() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["a.csv", "b.csv", "a.json", "b.json", "a.ply", "b.ply"] {
        let out = simulate(dir.path(), 2, 1500, &["--output", name]);
        assert!(out.status.success(), "{}", stderr(&out));
    }
    for ext in ["csv", "json", "ply"] {
        let a = fs::read(dir.path().join(format!("a.{ext}"))).unwrap();
        let b = fs::read(dir.path().join(format!("b.{ext}"))).unwrap();
        assert!(a == b, "{ext} differs between two identical runs");
    }
}

#[test]
fn json_holds_inputs_stats_and_the_same_points() {
    let dir = tempfile::tempdir().unwrap();
    let n = 1500;
    for name in ["p.json", "p.csv"] {
        let out = simulate(dir.path(), 3, n, &["--output", name, "--n-water", "1.5"]);
        assert!(out.status.success(), "{}", stderr(&out));
    }
    let v: serde_json::Value =
        serde_json::from_slice(&fs::read(dir.path().join("p.json")).unwrap()).unwrap();
    assert_eq!(v["schema"], "bentstraw-image-points/1");
    assert_eq!(v["units"], "m");
    assert_eq!(v["image_model"], "course");
    assert_eq!(v["inputs"]["observer"], serde_json::json!([0.1, 0.0, 0.3]));
    assert_eq!(v["inputs"]["straw"], serde_json::json!([0.02, 0.01]));
    assert_eq!(v["inputs"]["water_height"], 0.2);
    assert_eq!(v["inputs"]["n_water"], 1.5);
    assert_eq!(v["inputs"]["max_events"], 10);
    assert_eq!(v["inputs"]["min_points"], n);
    assert_eq!(
        v["point_fields"],
        serde_json::json!(["x", "y", "z", "color"])
    );
    let pts = v["points"].as_array().unwrap();
    assert!(pts.len() >= n);
    assert_eq!(v["stats"]["points"], pts.len());
    let rays = v["stats"]["rays_traced"].as_u64().unwrap();
    assert!(rays >= pts.len() as u64);
    let ratio = v["stats"]["hit_ratio"].as_f64().unwrap();
    assert!((ratio - pts.len() as f64 / rays as f64).abs() < 1e-12);
    let names = ["red", "orange", "magenta", "green", "blue"];
    for (k, name) in names.iter().enumerate() {
        let counted = pts.iter().filter(|p| p[3] == k as u64 + 1).count();
        assert_eq!(v["stats"]["points_per_color"][name], counted, "{name}");
        assert_eq!(v["colors"][k]["name"], *name);
    }
    let csv = read_csv(&dir.path().join("p.csv"));
    assert_eq!(csv.len(), pts.len());
    for (j, (p, c)) in pts.iter().zip(&csv) {
        for (a, b) in (0..3).map(|i| j[i].as_f64().unwrap()).zip(p.to_array()) {
            assert_eq!(a.to_bits(), b.to_bits());
        }
        assert_eq!(j[3].as_u64().unwrap(), *c as u64);
    }
}

#[test]
fn ply_has_coloured_double_vertices() {
    let dir = tempfile::tempdir().unwrap();
    let n = 1500;
    for name in ["p.ply", "p.csv"] {
        let out = simulate(dir.path(), 4, n, &["--output", name]);
        assert!(out.status.success(), "{}", stderr(&out));
    }
    let bytes = fs::read(dir.path().join("p.ply")).unwrap();
    let end = b"end_header\n";
    let at = bytes.windows(end.len()).position(|w| w == end).unwrap() + end.len();
    let header = std::str::from_utf8(&bytes[..at]).unwrap();
    let lines: Vec<&str> = header
        .lines()
        .filter(|l| !l.starts_with("comment"))
        .collect();
    let csv = read_csv(&dir.path().join("p.csv"));
    let count = format!("element vertex {}", csv.len());
    assert_eq!(
        lines,
        [
            "ply",
            "format binary_little_endian 1.0",
            count.as_str(),
            "property double x",
            "property double y",
            "property double z",
            "property uchar red",
            "property uchar green",
            "property uchar blue",
            "property uchar color",
            "end_header"
        ]
    );
    assert!(csv.len() >= n);
    let body = &bytes[at..];
    assert_eq!(body.len(), 28 * csv.len());
    for (rec, (p, c)) in body.chunks(28).zip(&csv) {
        let f = |i: usize| f64::from_le_bytes(rec[8 * i..8 * i + 8].try_into().unwrap());
        assert_eq!(
            [f(0), f(1), f(2)].map(f64::to_bits),
            p.to_array().map(f64::to_bits)
        );
        let rgb = SECTION_RGB[*c as usize - 1].map(|v| (v * 255.0).round() as u8);
        assert_eq!(&rec[24..27], &rgb);
        assert_eq!(rec[27], *c);
    }
}

#[test]
fn summary_names_every_colour_and_the_hit_ratio() {
    let dir = tempfile::tempdir().unwrap();
    let out = simulate(dir.path(), 1, 1000, &["--output", "s.csv"]);
    assert!(out.status.success());
    let err = stderr(&out);
    let csv = read_csv(&dir.path().join("s.csv"));
    for (k, name) in ["red", "orange", "magenta", "green", "blue"]
        .iter()
        .enumerate()
    {
        let n = csv.iter().filter(|(_, c)| *c as usize == k + 1).count();
        let line = err.lines().find(|l| l.contains(name)).expect(name);
        assert!(line.trim_end().ends_with(&format!(" {n}")), "{line}");
    }
    assert!(err.contains("rays traced") && err.contains("hit ratio") && err.contains("time"));
    assert!(err.lines().count() <= 24, "more than one screen:\n{err}");
}

#[test]
fn boundary_inputs_are_accepted() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [&[&str]; 5] = [
        &[
            "--observer",
            "0,0.1,0.1",
            "--straw",
            "0,0",
            "--water-height",
            "0",
        ],
        &[
            "--observer",
            "0,0.1,0.1",
            "--straw",
            "0,0",
            "--water-height",
            "0.2",
        ],
        &[
            "--observer",
            "0.1,0,-0.1",
            "--straw",
            "0,0",
            "--water-height",
            "0.1",
            "--max-events",
            "1",
        ],
        &[
            "--observer",
            "0.1,0,0.1",
            "--straw",
            "0,0",
            "--water-height",
            "0.1",
            "--max-events",
            "1000",
        ],
        &[
            "--observer",
            "0,0,0.3",
            "--straw",
            "0,-0.03",
            "--water-height",
            "0.1",
            "--n-water",
            "1",
        ],
    ];
    for case in cases {
        let mut args = vec!["simulate", "--points", "50", "--output", "ok.csv"];
        args.extend_from_slice(case);
        let out = bentstraw(dir.path(), &args);
        assert!(out.status.success(), "{case:?}: {}", stderr(&out));
        assert!(read_csv(&dir.path().join("ok.csv")).len() >= 50, "{case:?}");
    }
}

#[test]
fn figures_are_written_without_leftovers() {
    let dir = tempfile::tempdir().unwrap();
    let out = simulate(
        dir.path(),
        1,
        1000,
        &["--output", "f.csv", "--plot", "f.png", "--html", "f.html"],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let (png, page) = (dir.path().join("f.png"), dir.path().join("f.html"));
    assert!(fs::read(&png).unwrap().starts_with(b"\x89PNG\r\n\x1a\n"));
    let html = fs::read_to_string(&page).unwrap();
    assert!(html.to_lowercase().contains("<html"));
    assert!(read_csv(&dir.path().join("f.csv")).len() >= 1000);
    // The three files and nothing else: no temporary left behind.
    let mut names: Vec<String> = fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["f.csv", "f.html", "f.png"]);
}

/// The report job's run (`table --out made/here` on the default 20 000 points, run once by the
/// test `the_report_job` in `main.rs`): every simulation and the report, in the folders it made.
pub fn table_writes_every_simulation_and_the_report(out: &Output, folder: &Path) {
    let err = stderr(out);
    let stems: Vec<String> = (1..=4)
        .flat_map(|k| ["", "_n1", "_n1.05"].map(|s| format!("sim{k}{s}")))
        .collect();
    for stem in &stems {
        let points = read_csv(&folder.join(format!("{stem}.csv.gz")));
        assert!(points.len() >= 20000, "{stem}: {} points", points.len());
    }
    // The n_water = 1 points lie on the straw; the others keep their colours when re-traced.
    for r in &REFERENCES {
        let on = read_csv(&folder.join(format!("sim{}_n1.csv.gz", r.number)));
        let scene = r.scene(1.0);
        let far = on
            .iter()
            .map(|(p, _)| World::assignment(&scene).distance_to_objects(*p))
            .fold(0.0, f64::max);
        assert!(far < 1e-9, "sim{}_n1: {far} m off the straw", r.number);
        let bent = read_csv(&folder.join(format!("sim{}_n1.05.csv.gz", r.number)));
        assert_retraces(&r.scene(1.05), r.observer, &bent);
    }
    let index = fs::read_to_string(folder.join("index.html")).unwrap();
    assert!(index.starts_with("<!DOCTYPE html>"));
    for stem in &stems {
        assert!(
            index.contains(&format!("id=\"{stem}\"")),
            "{stem} not in the report"
        );
        assert!(
            index.contains(&format!("src=\"{stem}.svg\"")),
            "{stem}.svg not in the report"
        );
        assert!(
            index.contains(&format!("href=\"{stem}.csv.gz\"")),
            "{stem}.csv.gz not in the report"
        );
    }
    assert_eq!(
        index.matches("class=\"check pass\"").count(),
        4,
        "four n_water = 1 checks"
    );
    assert!(!index.contains("https://") && !index.contains("http://"));
    // Every figure written, the run succeeds, and the folder holds the table's files only.
    assert!(out.status.success(), "{err}");
    for stem in &stems {
        assert!(folder.join(format!("{stem}.svg")).is_file(), "{stem}.svg");
        // The rotatable view: of the reference simulations, not of their index checks.
        let view = folder.join(format!("{stem}.html"));
        assert_eq!(view.is_file(), !stem.contains("_n"), "{}", view.display());
    }
    assert!(fs::read(folder.join("sim1_observer.png"))
        .unwrap()
        .starts_with(b"\x89PNG"));
    let files = fs::read_dir(folder).unwrap().count();
    // 12 × (gzipped CSV, SVG figure), 4 × (3D view, 2 pictures, models, gap plot, ray diagram),
    // the opening view and its ray diagram, the validation figure, the report, and each gallery
    // scene's picture, points and ray diagram.
    for f in [
        "classic_view.png",
        "classic_rays.svg",
        "validation.svg",
        "sim3_rays.svg",
        "gallery_reversing-arrow_observer.png",
        "gallery_tank-pencil_points.svg",
        "gallery_oil-on-water_rays.svg",
    ] {
        assert!(folder.join(f).is_file(), "{f}");
        assert!(index.contains(f), "{f} not in the report");
    }
    assert_eq!(
        files,
        12 * 2 + 4 * 6 + 2 + 1 + 1 + bentstraw_io::gallery::GALLERY.len() * 3,
        "unexpected files in the table's folder"
    );
    assert!(!err.contains("could not be written"), "{err}");
}

// ---- Rejections ------------------------------------------------------------------------------

/// Runs `simulate` with `scene` arguments and every output in a fresh folder, and checks the
/// refusal: exit code 2, one stderr line starting `error:` and containing each of `names`, and
/// the folder still empty.
fn assert_rejected(args: &[&str], names: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let out = bentstraw(dir.path(), args);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert_eq!(
        err.trim_end().lines().count(),
        1,
        "{args:?}: not one line:\n{err}"
    );
    assert!(err.starts_with("error: "), "{err}");
    for n in names {
        assert!(
            err.contains(n),
            "{args:?}: message does not name '{n}': {err}"
        );
    }
    let left: Vec<PathBuf> = fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    assert!(left.is_empty(), "{args:?} left {left:?}");
}

/// `simulate` with the given scene arguments, all three outputs, 100 points unless `more` says.
fn simulate_args<'a>(
    observer: &'a str,
    straw: &'a str,
    he: &'a str,
    more: &[&'a str],
) -> Vec<&'a str> {
    let mut a = vec![
        "simulate",
        "--observer",
        observer,
        "--straw",
        straw,
        "--water-height",
        he,
        "--output",
        "out.csv",
        "--plot",
        "out.png",
        "--html",
        "out.html",
    ];
    if !more.contains(&"--points") {
        a.extend(["--points", "100"]);
    }
    a.extend_from_slice(more);
    a
}

#[test]
fn non_finite_numbers_are_rejected() {
    for (o, s, h, name) in [
        ("NaN,0.1,0.1", "0.02,0.01", "0.15", "NaN"),
        ("0,inf,0.1", "0.02,0.01", "0.15", "inf"),
        ("0,0.1,-inf", "0.02,0.01", "0.15", "-inf"),
        ("0,0.1,0.1", "nan,0.01", "0.15", "NaN"),
        ("0,0.1,0.1", "0.02,infinity", "0.15", "inf"),
        ("0,0.1,0.1", "0.02,0.01", "nan", "NaN"),
    ] {
        assert_rejected(&simulate_args(o, s, h, &[]), &[name, "finite"]);
    }
    assert_rejected(
        &simulate_args("0,0.1,0.1", "0.02,0.01", "0.15", &["--n-water", "nan"]),
        &["NaN"],
    );
    assert_rejected(
        &simulate_args("0,0.1,0.1", "0.02,0.01", "0.15", &["--n-water", "inf"]),
        &["inf"],
    );
}

#[test]
fn water_height_outside_the_glass_is_rejected() {
    assert_rejected(
        &simulate_args("0,0.1,0.1", "0.02,0.01", "-0.01", &[]),
        &["-0.01", "0 <= he <= 0.2"],
    );
    assert_rejected(
        &simulate_args("0,0.1,0.1", "0.02,0.01", "0.2000001", &[]),
        &["0.2000001", "0 <= he <= 0.2"],
    );
}

#[test]
fn straw_outside_the_glass_is_rejected() {
    assert_rejected(
        &simulate_args("0,0.1,0.1", "0.036,0", "0.15", &[]),
        &["0.036", "fit"],
    );
    assert_rejected(
        &simulate_args("0,0.1,0.1", "0.03,-0.03", "0.15", &[]),
        &["0.03", "-0.03"],
    );
    assert_rejected(&simulate_args("0,0.1,0.1", "1,1", "0.15", &[]), &["(1, 1)"]);
    // Just outside: the message gives the digits that show it does not fit.
    assert_rejected(
        &simulate_args("0,0.1,0.1", "0.0350000001,0", "0.15", &[]),
        &["0.0350000001", "0.04000000"],
    );
}

#[test]
fn observer_in_or_on_the_glass_is_rejected() {
    for o in [
        "0,0,0.1",
        "0,0,0",
        "0,0,0.2",
        "0.04,0,0.1",
        "0,-0.04,0.2",
        "0.01,0.01,0.05",
    ] {
        // The numbers as the user wrote them.
        let shown = format!("({})", o.split(',').collect::<Vec<_>>().join(", "));
        assert_rejected(
            &simulate_args(o, "0.02,0.01", "0.15", &[]),
            &[&shown, "glass"],
        );
    }
}

#[test]
fn observer_in_the_straw_above_the_glass_is_rejected() {
    assert_rejected(
        &simulate_args("0.02,0.01,0.22", "0.02,0.01", "0.15", &[]),
        &["(0.02, 0.01, 0.22)", "straw"],
    );
    assert_rejected(
        &simulate_args("0.024,0.01,0.25", "0.02,0.01", "0.15", &[]),
        &["(0.024, 0.01, 0.25)", "straw"],
    );
}

#[test]
fn water_index_outside_one_to_five_is_rejected() {
    assert_rejected(
        &simulate_args("0,0.1,0.1", "0.02,0.01", "0.15", &["--n-water", "0.99"]),
        &["0.99", "between 1 and 5"],
    );
    assert_rejected(
        &simulate_args("0,0.1,0.1", "0.02,0.01", "0.15", &["--n-water", "5.5"]),
        &["5.5", "between 1 and 5"],
    );
    assert_rejected(
        &simulate_args("0,0.1,0.1", "0.02,0.01", "0.15", &["--n-water", "-1.333"]),
        &["-1.333"],
    );
}

#[test]
fn event_limits_out_of_range_are_rejected() {
    for m in ["0", "1001", "-1", "ten"] {
        assert_rejected(
            &simulate_args("0,0.1,0.1", "0.02,0.01", "0.15", &["--max-events", m]),
            &[m],
        );
    }
}

#[test]
fn malformed_numbers_are_rejected() {
    let cases: [(&str, &[&str]); 5] = [
        ("1,2", &["'1,2'", "--observer", "expected 3"]),
        ("a,b,c", &["'a,b,c'", "--observer", "'a'"]),
        ("1,2,3,4", &["'1,2,3,4'", "expected 3"]),
        ("0.1;0;0.1", &["'0.1;0;0.1'"]),
        ("", &["--observer"]),
    ];
    for (o, names) in cases {
        assert_rejected(&simulate_args(o, "0.02,0.01", "0.15", &[]), names);
    }
    assert_rejected(
        &simulate_args("0,0.1,0.1", "0.02", "0.15", &[]),
        &["'0.02'", "--straw", "expected 2"],
    );
    assert_rejected(
        &simulate_args("0,0.1,0.1", "0.02,0.01", "0.15m", &[]),
        &["'0.15m'", "--water-height"],
    );
    assert_rejected(
        &simulate_args("0,0.1,0.1", "0.02,0.01", "0.15", &["--points", "many"]),
        &["'many'", "--points"],
    );
    assert_rejected(
        &simulate_args("0,0.1,0.1", "0.02,0.01", "0.15", &["--points", "0"]),
        &["--points 0"],
    );
    assert_rejected(
        &simulate_args("0,0.1,0.1", "0.02,0.01", "0.15", &["--points", "-5"]),
        &["'-5'"],
    );
}

#[test]
fn missing_arguments_are_rejected() {
    assert_rejected(
        &[
            "simulate",
            "--observer",
            "0,0.1,0.1",
            "--straw",
            "0.02,0.01",
            "--water-height",
            "0.15",
        ],
        &["--output", "bentstraw simulate --help"],
    );
    assert_rejected(
        &["simulate", "--output", "out.csv"],
        &["--observer", "--straw", "--water-height"],
    );
    assert_rejected(
        &["simulate", "--observr", "0,0.1,0.1"],
        &["'--observr'", "'--observer'"],
    );
    assert_rejected(
        &simulate_args("0,0.1,0.1", "0.02,0.01", "0.15", &["--image-model", "foo"]),
        &["'foo'", "--image-model", "course, eye, stereo"],
    );
}

#[test]
fn unknown_output_extensions_are_rejected() {
    let scene = |out: &'static str, plot: &'static str, page: &'static str| {
        vec![
            "simulate",
            "--observer",
            "0,0.1,0.1",
            "--straw",
            "0.02,0.01",
            "--water-height",
            "0.15",
            "--points",
            "100",
            "--output",
            out,
            "--plot",
            plot,
            "--html",
            page,
        ]
    };
    assert_rejected(
        &scene("out.txt", "out.png", "out.html"),
        &["out.txt", ".csv, .json or .ply"],
    );
    assert_rejected(
        &scene("out", "out.png", "out.html"),
        &["out", "no extension"],
    );
    assert_rejected(
        &scene("out.csv", "out.jpg", "out.html"),
        &["--plot out.jpg", ".png"],
    );
    assert_rejected(
        &scene("out.csv", "out.png", "out.svg"),
        &["--html out.svg", ".html"],
    );
}

#[test]
fn eye_and_stereo_models_write_their_columns_and_points_near_the_course_ones() {
    let dir = tempfile::tempdir().unwrap();
    let out = simulate(dir.path(), 2, 500, &["--output", "course.csv"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let course = read_csv(&dir.path().join("course.csv"));
    for (model, header) in [
        ("eye", "x,y,z,color,s_h,s_v,s_h_kind,s_v_kind,gap"),
        (
            "stereo",
            "x,y,z,color,disparity,vertical_disparity,miss_distance,gap",
        ),
    ] {
        let file = format!("{model}.csv");
        let out = simulate(
            dir.path(),
            2,
            500,
            &["--image-model", model, "--output", &file],
        );
        assert!(out.status.success(), "{}", stderr(&out));
        assert!(stderr(&out).contains(&format!("{model} model")));
        let text = fs::read_to_string(dir.path().join(&file)).unwrap();
        let mut lines = text.lines();
        assert_eq!(lines.next(), Some(header));
        let mut placed = 0;
        for line in lines {
            let f: Vec<&str> = line.split(',').collect();
            assert_eq!(f.len(), header.split(',').count(), "{line}");
            let color: u8 = f[3].parse().unwrap();
            assert!((1..=5).contains(&color));
            if f[0].is_empty() {
                continue; // no position: the row says why
            }
            placed += 1;
            let p = Vec3::new(
                f[0].parse().unwrap(),
                f[1].parse().unwrap(),
                f[2].parse().unwrap(),
            );
            let gap: f64 = f[f.len() - 1].parse().unwrap();
            // The apparent point is within centimetres of some course point of its colour.
            let nearest = course
                .iter()
                .filter(|(_, c)| *c == color)
                .map(|(q, _)| q.distance(p))
                .fold(f64::MAX, f64::min);
            assert!(
                nearest < 0.02,
                "{model}: {p} is {nearest} m from the course cloud"
            );
            assert!((0.0..0.05).contains(&gap), "{model}: gap {gap}");
            if model == "eye" {
                let (sh, sv): (f64, f64) = (f[4].parse().unwrap(), f[5].parse().unwrap());
                assert!(sh > 0.0 && sv > 0.0 && f[6] == "in_front" && f[7] == "in_front");
                let observer = REFERENCES[1].observer;
                assert!(((p - observer).length() - 0.5 * (sh + sv)).abs() < 1e-9);
            }
        }
        assert!(
            placed as f64 > 0.8 * course.len() as f64,
            "{model}: {placed} placed"
        );
    }
}

#[test]
fn missing_folders_and_unwritable_paths_are_rejected() {
    let s = |out: &'static str, plot: &'static str, page: &'static str| {
        vec![
            "simulate",
            "--observer",
            "0,0.1,0.1",
            "--straw",
            "0.02,0.01",
            "--water-height",
            "0.15",
            "--points",
            "100",
            "--output",
            out,
            "--plot",
            plot,
            "--html",
            page,
        ]
    };
    assert_rejected(
        &s("nowhere/out.csv", "out.png", "out.html"),
        &["nowhere/out.csv", "does not exist"],
    );
    assert_rejected(
        &s("out.csv", "nowhere/out.png", "out.html"),
        &["nowhere/out.png", "does not exist"],
    );
    assert_rejected(
        &s("out.csv", "out.png", "nowhere/out.html"),
        &["nowhere/out.html", "does not exist"],
    );
    #[cfg(target_os = "linux")]
    assert_rejected(
        &s("/proc/bentstraw-test.csv", "out.png", "out.html"),
        &["/proc/bentstraw-test.csv"],
    );

    // An output that is a folder is refused, and the folder is left as it was.
    let dir = tempfile::tempdir().unwrap();
    fs::create_dir(dir.path().join("taken.csv")).unwrap();
    let out = bentstraw(dir.path(), &s("taken.csv", "out.png", "out.html"));
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("taken.csv"), "{}", stderr(&out));
    let left: Vec<_> = fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(left.len(), 1);
    assert_eq!(
        fs::read_dir(dir.path().join("taken.csv")).unwrap().count(),
        0
    );
}

#[test]
fn table_refuses_bad_arguments_without_output() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(dir.path().join("file"), b"x").unwrap();
    let out = bentstraw(dir.path(), &["table", "--out", "file"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("file") && stderr(&out).trim_end().lines().count() == 1);
    let out = bentstraw(dir.path(), &["table", "--out", "new", "--points", "0"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("--points 0"));
    assert!(!dir.path().join("new").exists());
    // A PDF must be named .pdf: refused before any work, no folder made.
    let out = bentstraw(
        dir.path(),
        &["table", "--out", "new", "--pdf", "report.txt"],
    );
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("--pdf report.txt") && stderr(&out).contains(".pdf"),
        "{}",
        stderr(&out)
    );
    assert!(!dir.path().join("new").exists());
    assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 1);
}

/// A missing or broken scene file, or one of the gallery's names misspelt: one clear line naming
/// it, exit code 2, nothing written, a previous report left as it was.
#[test]
fn table_refuses_a_bad_scene_and_keeps_the_previous_report() {
    let dir = tempfile::tempdir().unwrap();
    fs::create_dir(dir.path().join("out")).unwrap();
    fs::write(dir.path().join("out/index.html"), b"the previous report").unwrap();
    fs::write(
        dir.path().join("broken.toml"),
        "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.2\n\n[[liquid]]\n\
         name = \"water\"\nindex = 0.5\ntop = 0.1\n\n[observer]\nposition = [0, -0.3, 0.1]\n",
    )
    .unwrap();
    for (scene, named) in [
        ("missing.toml", "missing.toml"),
        ("broken.toml", "liquid[1].index"),
        ("leaning-stra", "leaning-stra"),
    ] {
        for out_dir in ["out", "new"] {
            let out = bentstraw(
                dir.path(),
                &[
                    "table", "--scene", scene, "--out", out_dir, "--points", "100",
                ],
            );
            assert_eq!(out.status.code(), Some(2), "{scene}: {}", stderr(&out));
            assert!(stderr(&out).contains(named), "{scene}: {}", stderr(&out));
            assert!(
                !dir.path().join("new").exists(),
                "{scene}: a folder was made"
            );
            assert_eq!(
                fs::read(dir.path().join("out/index.html")).unwrap(),
                b"the previous report"
            );
            assert_eq!(fs::read_dir(dir.path().join("out")).unwrap().count(), 1);
        }
    }
    // --observer belongs to --scene.
    let out = bentstraw(dir.path(), &["table", "--observer", "0,-0.3,0.1"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("--scene"), "{}", stderr(&out));
}

#[test]
fn help_and_version_still_print_in_full() {
    let dir = tempfile::tempdir().unwrap();
    let out = bentstraw(dir.path(), &["simulate", "--help"]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("--observer") && text.contains("Example:"),
        "{text}"
    );
    let out = bentstraw(dir.path(), &["--version"]);
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).starts_with("bentstraw "));
}

/// No arguments is `table --out out` (whose run on the defaults `the_report_job` checks): seen
/// without running the job, as the refusal of an `out` that is a file, before any work.
#[test]
fn no_arguments_runs_the_table_into_out() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(dir.path().join("out"), b"x").unwrap();
    let out = bentstraw(dir.path(), &[]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        stderr(&out).trim_end(),
        "error: --out out: it exists and is not a folder"
    );
    assert_eq!(fs::read(dir.path().join("out")).unwrap(), b"x");
    assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 1);
}
