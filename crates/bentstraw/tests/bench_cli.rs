//! `bentstraw bench`: what it prints, and how it refuses bad input (one line, exit code 2).

use std::process::{Command, Output};

fn bench(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_bentstraw"))
        .arg("bench")
        .args(args)
        .output()
        .expect("bentstraw runs")
}

fn assert_refused(args: &[&str], names: &str) {
    let out = bench(args);
    assert_eq!(out.status.code(), Some(2), "{args:?} should be refused");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.trim_end().lines().count(), 1, "one-line message: {err}");
    assert!(err.contains(names), "message names {names}: {err}");
    assert!(out.stdout.is_empty(), "nothing timed: {:?}", out.stdout);
}

#[test]
fn bench_refuses_bad_input() {
    assert_refused(&["--fov", "0"], "fov");
    assert_refused(&["--fov", "180"], "fov");
    assert_refused(&["--repeat", "0"], "repeat");
    // The same pixel limit as render, and bounded work whatever the repeats.
    assert_refused(&["--size", "6000x4200"], "at most 25000000 pixels");
    assert_refused(&["--repeat", "1001"], "at most 1000");
    assert_refused(
        &["--repeat", "1000", "--size", "2000x1000"],
        "at most 1000000000",
    );
    assert_refused(&["--threads", "0"], "threads");
    assert_refused(&["--straw", "0.02,0.01"], "--observer");
    assert_refused(
        &[
            "--observer",
            "0.1,0,0.1",
            "--straw",
            "0.02,0.01",
            "--water-height",
            "0.15",
            "--target",
            "0.1,0,0.1",
        ],
        "target",
    );
    assert_refused(
        &[
            "--observer",
            "0,0,0.1",
            "--straw",
            "0.02,0.01",
            "--water-height",
            "0.15",
        ],
        "observer",
    );
    assert_refused(
        &[
            "--observer",
            "0.1,0,0.1",
            "--straw",
            "0.02,0.01",
            "--water-height",
            "0.3",
        ],
        "water height",
    );
}

/// A successful run's standard output and its lines, one JSON object each.
fn json_lines(out: std::process::Output) -> (String, Vec<serde_json::Value>) {
    assert_eq!(out.status.code(), Some(0));
    let text = String::from_utf8(out.stdout).unwrap();
    let lines = text
        .lines()
        .map(|l| serde_json::from_str(l).expect("one JSON object a line"))
        .collect();
    (text, lines)
}

#[test]
fn bench_json_reports_every_case_and_the_averages() {
    let out = bench(&[
        "--json",
        "--size",
        "32x24",
        "--repeat",
        "3",
        "--threads",
        "2",
    ]);
    let (_, lines) = json_lines(out);
    // 4 views × 2 modes × (1 and 2 threads), then 2 modes × 2 thread counts of averages.
    assert_eq!(lines.len(), 4 * 2 * 2 + 4);
    for (k, v) in lines.iter().enumerate() {
        let seconds = v["seconds"].as_f64().unwrap();
        let rays = v["rays"].as_u64().unwrap();
        assert!(seconds > 0.0);
        let rate = v["rays_per_s"].as_f64().unwrap();
        assert!((rate * seconds / rays as f64 - 1.0).abs() < 1e-9);
        assert!(["course", "fresnel"].contains(&v["mode"].as_str().unwrap()));
        assert!([1, 2].contains(&v["threads"].as_u64().unwrap()));
        if k < 16 {
            assert_eq!(rays, 32 * 24);
            assert_eq!(
                (v["width"].as_u64(), v["height"].as_u64()),
                (Some(32), Some(24))
            );
            assert_eq!(v["simulation"].as_u64(), Some(k as u64 / 4 + 1));
        } else {
            assert_eq!(v["simulation"], "average");
            assert_eq!(rays, 4 * 32 * 24);
        }
    }
}

#[test]
fn bench_times_one_given_view() {
    let out = bench(&[
        "--observer",
        "0.1,0,0.1",
        "--straw",
        "0.02,0.01",
        "--water-height",
        "0.15",
        "--mode",
        "course",
        "--size",
        "20x10",
        "--repeat",
        "1",
        "--threads",
        "1",
    ]);
    assert_eq!(out.status.code(), Some(0));
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    // Header, one case (1 thread only), the averages.
    assert_eq!(lines.len(), 3, "{text}");
    assert!(
        lines[1].contains("course") && lines[1].contains("20x10"),
        "{text}"
    );
    assert!(lines[2].starts_with("average:"), "{text}");
}

/// `--frame` times the pictures as `render` draws them: slower than one ray per pixel (shading,
/// the backdrop and the edges' samples come on top), for both modes.
#[test]
fn frame_times_the_shaded_pictures() {
    let args = |frame: bool| {
        let mut a = vec![
            "--json",
            "--size",
            "96x72",
            "--repeat",
            "3",
            "--threads",
            "1",
            "--observer",
            "0.1,0,0.1",
            "--straw",
            "0.02,0.01",
            "--water-height",
            "0.15",
        ];
        if frame {
            a.push("--frame");
        }
        let out = bench(&a);
        assert_eq!(out.status.code(), Some(0));
        let text = String::from_utf8(out.stdout).unwrap();
        text.lines()
            .map(|l| serde_json::from_str::<serde_json::Value>(l).unwrap())
            .filter(|v| v["simulation"].is_null())
            .map(|v| {
                (
                    v["mode"].as_str().unwrap().to_string(),
                    v["seconds"].as_f64().unwrap(),
                )
            })
            .collect::<Vec<_>>()
    };
    let rays = args(false);
    let frames = args(true);
    assert_eq!(rays.len(), 2);
    assert_eq!(frames.len(), 2);
    for ((m1, t_rays), (m2, t_frame)) in rays.iter().zip(&frames) {
        assert_eq!(m1, m2);
        assert!(
            t_frame > t_rays,
            "{m1}: frame {t_frame} s vs rays {t_rays} s"
        );
    }
}

/// `--models` times the image points and both models on one view after its pictures: a line
/// per view with each cost per point, its ratio to the image points' cost agreeing with them.
#[test]
fn models_are_timed_per_point_beside_the_image_points() {
    let out = bench(&[
        "--json",
        "--models",
        "--mode",
        "course",
        "--size",
        "20x10",
        "--repeat",
        "1",
        "--threads",
        "1",
        "--observer",
        "0.1,0,0.1",
        "--straw",
        "0.02,0.01",
        "--water-height",
        "0.15",
    ]);
    let (text, lines) = json_lines(out);
    // The case, the average, then the models.
    assert_eq!(lines.len(), 3, "{text}");
    let m = &lines[2];
    assert_eq!(m["models"], true, "{text}");
    assert!(m["points"].as_u64().unwrap() >= 50_000);
    let image = m["image_ns_per_point"].as_f64().unwrap();
    for model in ["eye", "stereo"] {
        let cost = m[format!("{model}_ns_per_point")].as_f64().unwrap();
        let ratio = m[format!("{model}_ratio")].as_f64().unwrap();
        assert!(image > 0.0 && cost > 0.0);
        assert!((ratio * image / cost - 1.0).abs() < 1e-9, "{text}");
    }
}
