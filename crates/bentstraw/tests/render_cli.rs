//! `bentstraw render` from the outside: its files, and its refusals (exit code 2, no file).

use std::path::Path;
use std::process::{Command, Output};

use bentstraw_optics::camera::Camera;
use bentstraw_optics::picture::{course_picture_exact, fresnel_picture_exact};
use bentstraw_optics::scene::{Scene, SCENE_CENTRE};
use bentstraw_optics::world::World;
use bentstraw_optics::Vec3;

const SCENE: [&str; 6] = [
    "--observer",
    "0.1,0,0.1",
    "--straw",
    "0.02,0.01",
    "--water-height",
    "0.15",
];

fn render(dir: &Path, extra: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_bentstraw"))
        .current_dir(dir)
        .arg("render")
        .args(extra)
        .output()
        .expect("bentstraw runs")
}

fn files_in(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect()
}

#[test]
fn writes_the_picture_and_one_course_ray_per_pixel() {
    let dir = tempfile::tempdir().unwrap();
    let mut args = SCENE.to_vec();
    args.extend([
        "--mode", "course", "--size", "40x30", "--fov", "100", "--output", "v.png", "--raw",
        "v.csv",
    ]);
    let out = render(dir.path(), &args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains(" s"),
        "the summary gives the time: {stderr}"
    );
    let png = image::open(dir.path().join("v.png")).unwrap().to_rgb8();
    assert_eq!(png.dimensions(), (40, 30));

    let csv = std::fs::read_to_string(dir.path().join("v.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("row,col,color"));
    let scene = Scene::with_defaults(0.02, 0.01, 0.15).unwrap();
    let cam = Camera::new(
        Vec3::new(0.1, 0.0, 0.1),
        SCENE_CENTRE,
        40,
        30,
        100f64.to_radians(),
    );
    let codes = course_picture_exact(&World::assignment(&scene), &cam);
    let rows: Vec<&str> = lines.collect();
    assert_eq!(rows.len(), 1200);
    for (k, line) in rows.iter().enumerate() {
        assert_eq!(*line, format!("{},{},{}", k / 40, k % 40, codes[k]));
    }
    assert!(codes.iter().any(|&c| c != 0));
}

#[test]
fn fresnel_raw_weights_read_back_exactly() {
    let dir = tempfile::tempdir().unwrap();
    let mut args = SCENE.to_vec();
    args.extend([
        "--size",
        "32x24",
        "--samples",
        "1",
        "--output",
        "f.png",
        "--raw",
        "f.csv",
    ]);
    let out = render(dir.path(), &args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(dir.path().join("f.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("row,col,w1,w2,w3,w4,w5"));
    // The default camera: target at the scene's centre, framing field of view.
    let scene = Scene::with_defaults(0.02, 0.01, 0.15).unwrap();
    let eye = Vec3::new(0.1, 0.0, 0.1);
    let fov = bentstraw_optics::camera::framing_fov(eye, SCENE_CENTRE, 32.0 / 24.0);
    let want = fresnel_picture_exact(
        &World::assignment(&scene),
        &Camera::new(eye, SCENE_CENTRE, 32, 24, fov),
        1e-4,
    );
    let mut n = 0;
    for (k, line) in lines.enumerate() {
        let f: Vec<&str> = line.split(',').collect();
        assert_eq!(f.len(), 7);
        assert_eq!(
            (
                f[0].parse::<usize>().unwrap(),
                f[1].parse::<usize>().unwrap()
            ),
            (k / 32, k % 32)
        );
        let w: Vec<f64> = f[2..].iter().map(|s| s.parse().unwrap()).collect();
        for (got, want) in w.iter().zip(want[k]) {
            // Bit for bit: the sums a reader forms are the renderer's sums.
            assert_eq!(got.to_bits(), want.to_bits(), "{got} vs {want}");
        }
        n += 1;
    }
    assert_eq!(n, 32 * 24);
}

#[test]
fn bad_input_is_refused_with_exit_code_2_and_no_file() {
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["--size", "0x10"], "between 1 and 16384"),
        (vec!["--size", "10x-3"], "between 1 and 16384"),
        (vec!["--size", "10000x5000"], "too large"),
        (vec!["--fov", "0"], "fov"),
        (vec!["--fov", "180"], "fov"),
        (vec!["--fov", "-5"], "fov"),
        (vec!["--fov", "NaN"], "fov"),
        (vec!["--target", "0.1,0,0.1"], "target"),
        (vec!["--target", "0,inf,0"], "target"),
        (vec!["--prune", "1"], "prune"),
        (vec!["--prune", "-0.1"], "prune"),
        (vec!["--samples", "0"], "samples"),
        (vec!["--samples", "17"], "samples"),
        (vec!["--n-water", "0.9"], "index"),
        (vec!["--n-water", "nan"], "index"),
        (vec!["--max-events", "0"], "event limit"),
        (vec!["--max-events", "1001"], "event limit"),
    ];
    let scene_cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec![
                "--observer",
                "0,0,0.1",
                "--straw",
                "0.02,0.01",
                "--water-height",
                "0.15",
            ],
            "glass",
        ),
        (
            vec![
                "--observer",
                "0.1,0,nan",
                "--straw",
                "0.02,0.01",
                "--water-height",
                "0.15",
            ],
            "finite",
        ),
        (
            vec![
                "--observer",
                "0.1,0,0.1",
                "--straw",
                "0.04,0",
                "--water-height",
                "0.15",
            ],
            "fit",
        ),
        (
            vec![
                "--observer",
                "0.1,0,0.1",
                "--straw",
                "0.02,0.01",
                "--water-height",
                "-0.01",
            ],
            "water height",
        ),
        (
            vec![
                "--observer",
                "0.1,0,0.1",
                "--straw",
                "0.02,0.01",
                "--water-height",
                "0.21",
            ],
            "water height",
        ),
        (
            vec![
                "--observer",
                "0.02,0.01,0.22",
                "--straw",
                "0.02,0.01",
                "--water-height",
                "0.1",
            ],
            "straw",
        ),
    ];
    let mut all: Vec<Vec<&str>> = Vec::new();
    let mut needles = Vec::new();
    for (extra, needle) in cases {
        let mut a = SCENE.to_vec();
        a.extend(extra);
        all.push(a);
        needles.push(needle);
    }
    for (a, needle) in scene_cases {
        all.push(a);
        needles.push(needle);
    }
    // An output folder that does not exist.
    let mut a = SCENE.to_vec();
    a.extend(["--output", "missing/v.png"]);
    all.push(a);
    needles.push("missing");
    for (args, needle) in all.iter().zip(needles) {
        let dir = tempfile::tempdir().unwrap();
        let mut args = args.clone();
        if !args.contains(&"--output") {
            args.extend(["--output", "v.png"]);
        }
        args.extend(["--raw", "v.csv", "--size"]);
        if let Some(p) = args.iter().position(|&s| s == "--size") {
            if p + 1 < args.len() - 1 {
                // A size was given by the case: drop the trailing flag added above.
                args.pop();
            } else {
                args.push("16x12");
            }
        }
        let out = render(dir.path(), &args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(
            stderr.to_lowercase().contains(&needle.to_lowercase()),
            "{args:?}: {stderr}"
        );
        assert!(
            files_in(dir.path()).is_empty(),
            "{args:?} left {:?}",
            files_in(dir.path())
        );
    }
}
