//! The observer's pinhole camera and the per-pixel pictures against the point cloud.

use bentstraw_optics::camera::{framing_fov, framing_target, Camera, FRAMING_MARGIN};
use bentstraw_optics::picture::{course_picture, fresnel_picture};
use bentstraw_optics::sampling::sample_image;
use bentstraw_optics::scene::{
    Scene, GLASS_RADIUS, REFERENCES, SCENE_CENTRE, SECTION_COUNT, STRAW_HEIGHT, WATER_INDEX,
};
use bentstraw_optics::world::World;
use bentstraw_optics::Vec3;

/// The pixel direction of docs/physics.md, written out with plain arrays (no glam), normalised.
fn spec_direction(
    eye: [f64; 3],
    target: [f64; 3],
    w: u32,
    h: u32,
    fov: f64,
    i: u32,
    j: u32,
) -> [f64; 3] {
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let unit = |a: [f64; 3]| {
        let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
        [a[0] / n, a[1] / n, a[2] / n]
    };
    let norm = |a: [f64; 3]| (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    let f = unit(sub(target, eye));
    let fz = cross(f, [0.0, 0.0, 1.0]);
    let r = if norm(fz) < 1e-9 {
        [1.0, 0.0, 0.0]
    } else {
        unit(fz)
    };
    let u = cross(r, f);
    let (wf, hf) = (w as f64, h as f64);
    let t = (fov / 2.0).tan();
    let a = (2.0 * (j as f64 + 0.5) / wf - 1.0) * t * (wf / hf);
    let b = (1.0 - 2.0 * (i as f64 + 0.5) / hf) * t;
    unit([
        f[0] + a * r[0] + b * u[0],
        f[1] + a * r[1] + b * u[1],
        f[2] + a * r[2] + b * u[2],
    ])
}

fn close(a: Vec3, b: [f64; 3], tol: f64) -> bool {
    (a - Vec3::from_array(b)).length() < tol
}

#[test]
fn centre_pixel_of_an_odd_picture_looks_forward() {
    for r in REFERENCES {
        let cam = Camera::new(r.observer, SCENE_CENTRE, 101, 51, 0.7);
        let d = cam.pixel_ray(25, 50).direction;
        let forward = (SCENE_CENTRE - r.observer).normalize();
        assert!((d - forward).length() < 1e-12, "{d} vs {forward}");
    }
}

#[test]
fn corner_and_edge_pixels_follow_the_spec_formula() {
    let cases = [
        (
            [0.1, 0.0, 0.1],
            [0.0, 0.0, 0.125],
            800,
            600,
            60f64.to_radians(),
        ),
        (
            [0.0, 0.1, 0.1],
            [0.01, -0.02, 0.05],
            31,
            17,
            100f64.to_radians(),
        ),
        (
            [0.1, 0.0, -0.1],
            [0.0, 0.0, 0.125],
            5,
            9,
            20f64.to_radians(),
        ),
        // Looking straight down: the right vector falls back to x̂.
        ([0.0, 0.0, 0.6], [0.0, 0.0, 0.1], 40, 30, 45f64.to_radians()),
    ];
    for (eye, target, w, h, fov) in cases {
        let cam = Camera::new(Vec3::from_array(eye), Vec3::from_array(target), w, h, fov);
        for (i, j) in [
            (0, 0),
            (0, w - 1),
            (h - 1, 0),
            (h - 1, w - 1),
            (h / 2, 0),
            (0, w / 3),
        ] {
            let got = cam.pixel_ray(i, j).direction;
            let want = spec_direction(eye, target, w, h, fov, i, j);
            assert!(
                close(got, want, 1e-12),
                "pixel ({i},{j}) of {eye:?}: {got} vs {want:?}"
            );
        }
    }
}

#[test]
fn projecting_a_pixel_direction_gives_back_the_pixel() {
    let cam = Camera::new(Vec3::new(0.1, 0.03, 0.3), SCENE_CENTRE, 64, 48, 0.9);
    for (i, j) in [(0, 0), (10, 50), (47, 63), (24, 32)] {
        let p = cam.eye + 0.37 * cam.pixel_ray(i, j).direction;
        let (row, col) = cam.project(p).unwrap();
        assert!((row - (i as f64 + 0.5)).abs() < 1e-9 && (col - (j as f64 + 0.5)).abs() < 1e-9);
    }
    // Behind the eye: no picture.
    assert!(cam.project(cam.eye - cam.forward).is_none());
}

/// Mean (row, col) of the pixels showing colour `code`.
fn centroid(codes: &[u8], w: usize, code: u8) -> Option<(f64, f64)> {
    let (mut n, mut sr, mut sc) = (0.0, 0.0, 0.0);
    for (k, &c) in codes.iter().enumerate() {
        if c == code {
            n += 1.0;
            sr += (k / w) as f64;
            sc += (k % w) as f64;
        }
    }
    (n > 0.0).then(|| (sr / n, sc / n))
}

#[test]
fn straw_to_the_observers_right_appears_in_the_right_half_and_upright() {
    // The observer on +x looks towards −x: its right is +y.
    let eye = Vec3::new(0.12, 0.0, 0.1);
    let (w, h) = (80usize, 60usize);
    let cam = Camera::new(eye, SCENE_CENTRE, w as u32, h as u32, 100f64.to_radians());
    for (yp, right) in [(0.03, true), (-0.03, false)] {
        for n in [1.0, WATER_INDEX] {
            let scene = Scene::new(0.0, yp, 0.15, n, 10).unwrap();
            let codes = course_picture(&World::assignment(&scene), &cam);
            let cols: Vec<usize> = codes
                .iter()
                .enumerate()
                .filter(|(_, &c)| c != 0)
                .map(|(k, _)| k % w)
                .collect();
            assert!(cols.len() > 20, "the straw is seen");
            assert!(
                cols.iter().all(|&c| (c >= w / 2) == right),
                "straw at y = {yp}, n = {n}: columns {:?}",
                (cols.iter().min(), cols.iter().max())
            );
            // Top (blue) above bottom (red): smaller rows.
            let blue = centroid(&codes, w, 5).unwrap();
            let red = centroid(&codes, w, 1).unwrap();
            assert!(blue.0 < red.0, "blue {blue:?} above red {red:?}");
        }
    }
}

#[test]
fn course_pixels_have_the_colour_of_the_image_point_along_their_ray() {
    let (w, h) = (96u32, 72u32);
    for r in REFERENCES {
        let scene = r.scene(WATER_INDEX);
        let fov = framing_fov(r.observer, SCENE_CENTRE, w as f64 / h as f64);
        let cam = Camera::new(r.observer, SCENE_CENTRE, w, h, fov);
        let codes = course_picture(&World::assignment(&scene), &cam);
        assert_eq!(codes.len(), (w * h) as usize);
        let mut straw = 0;
        for i in 0..h {
            for j in 0..w {
                let u0 = cam.pixel_ray(i, j).direction;
                let ip = World::assignment(&scene).image_point(r.observer, u0);
                assert_eq!(codes[(i * w + j) as usize], ip.map_or(0, |p| p.color));
                if let Some(p) = ip {
                    straw += 1;
                    // The image point lies straight ahead: it projects into its own pixel.
                    let (row, col) = cam.project(p.position).unwrap();
                    assert!((row - (i as f64 + 0.5)).abs() < 1e-6);
                    assert!((col - (j as f64 + 0.5)).abs() < 1e-6);
                }
            }
        }
        assert!(
            straw > 50,
            "reference {}: straw seen in {straw} pixels",
            r.number
        );
    }
}

#[test]
fn the_sampled_point_cloud_falls_on_pixels_of_its_own_colour() {
    // The cloud's rays are chosen by the sampler, not by the camera: an independent check that
    // cloud and picture show the same thing where the cloud's points land.
    let (w, h) = (400u32, 300u32);
    for r in REFERENCES {
        let scene = r.scene(WATER_INDEX);
        let fov = framing_fov(r.observer, SCENE_CENTRE, w as f64 / h as f64);
        let cam = Camera::new(r.observer, SCENE_CENTRE, w, h, fov);
        let codes = course_picture(&World::assignment(&scene), &cam);
        let cloud = sample_image(&World::assignment(&scene), r.observer, 3000, &|_| {});
        let (mut inside, mut agree, mut stray) = (0usize, 0usize, 0usize);
        for p in &cloud.points {
            if let Some((row, col)) = cam.project(p.position) {
                if row >= 0.0 && col >= 0.0 && row < h as f64 && col < w as f64 {
                    inside += 1;
                    let (i, j) = (row as i64, col as i64);
                    let code = |i: i64, j: i64| {
                        let (i, j) = (i.clamp(0, h as i64 - 1), j.clamp(0, w as i64 - 1));
                        codes[(i * w as i64 + j) as usize]
                    };
                    if code(i, j) == p.color {
                        agree += 1;
                    } else {
                        // A point that disagrees with its pixel's centre sits at an edge of
                        // its colour: a neighbouring pixel shows it, except in slivers of the
                        // image thinner than a pixel, which the sampler's finer grid can see.
                        let near =
                            (-1..=1).any(|di| (-1..=1).any(|dj| code(i + di, j + dj) == p.color));
                        if !near {
                            stray += 1;
                        }
                    }
                }
            }
        }
        assert!(
            stray * 1000 <= inside,
            "reference {}: {stray} of {inside} points far from any pixel of their colour",
            r.number
        );
        assert!(
            inside > 1000,
            "reference {}: {inside} points in the picture",
            r.number
        );
        let share = agree as f64 / inside as f64;
        assert!(
            share > 0.9,
            "reference {}: {share} of points agree",
            r.number
        );
    }
}

#[test]
fn framing_fov_just_holds_the_glass_and_straw() {
    for r in REFERENCES {
        for aspect in [4.0 / 3.0, 1.0, 0.5] {
            let fov = framing_fov(r.observer, SCENE_CENTRE, aspect);
            assert!(fov > 0.0 && fov < std::f64::consts::PI);
            let h = 300u32;
            let w = (h as f64 * aspect).round() as u32;
            let cam = Camera::new(r.observer, SCENE_CENTRE, w, h, fov);
            // Largest excursion from the centre, as a fraction of the half-picture, over dense
            // points of the enclosing cylinder (circles and side lines).
            let mut worst: f64 = 0.0;
            for k in 0..2000 {
                let a = k as f64 * std::f64::consts::TAU / 2000.0;
                for s in 0..=10 {
                    let z = STRAW_HEIGHT * s as f64 / 10.0;
                    let p = Vec3::new(GLASS_RADIUS * a.cos(), GLASS_RADIUS * a.sin(), z);
                    let (row, col) = cam.project(p).unwrap();
                    let y = (row - h as f64 / 2.0).abs() / (h as f64 / 2.0);
                    let x = (col - w as f64 / 2.0).abs() / (w as f64 / 2.0);
                    worst = worst.max(x).max(y);
                }
            }
            let want = 1.0 / (1.0 + FRAMING_MARGIN);
            assert!(
                (worst - want).abs() < 2e-3,
                "reference {}: {worst} vs {want}",
                r.number
            );
        }
    }
    // Farther away, a narrower view.
    let near = framing_fov(Vec3::new(0.3, 0.0, 0.125), SCENE_CENTRE, 1.0);
    let far = framing_fov(Vec3::new(3.0, 0.0, 0.125), SCENE_CENTRE, 1.0);
    assert!(far < near / 5.0);
}

#[test]
fn fresnel_picture_equals_course_picture_without_refraction() {
    // n_water = 1: no reflection at any face, so each pixel's whole weight lands where the course
    // ray lands.
    let (w, h) = (64u32, 48u32);
    for r in REFERENCES {
        let scene = r.scene(1.0);
        let cam = Camera::new(r.observer, SCENE_CENTRE, w, h, 90f64.to_radians());
        let codes = course_picture(&World::assignment(&scene), &cam);
        let weights = fresnel_picture(&World::assignment(&scene), &cam, 0.0);
        for (code, wk) in codes.iter().zip(&weights) {
            for k in 0..SECTION_COUNT {
                let want = if *code as usize == k + 1 { 1.0 } else { 0.0 };
                assert!((wk[k] - want).abs() < 1e-12, "{wk:?} vs code {code}");
            }
        }
    }
}

/// Extent of the enclosing cylinder's picture as `(row_min, row_max, col_min, col_max)`.
fn picture_extent(cam: &Camera) -> (f64, f64, f64, f64) {
    let mut e = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for k in 0..2000 {
        let a = k as f64 * std::f64::consts::TAU / 2000.0;
        for s in 0..=10 {
            let z = STRAW_HEIGHT * s as f64 / 10.0;
            let p = Vec3::new(GLASS_RADIUS * a.cos(), GLASS_RADIUS * a.sin(), z);
            let (row, col) = cam.project(p).unwrap();
            e = (e.0.min(row), e.1.max(row), e.2.min(col), e.3.max(col));
        }
    }
    e
}

#[test]
fn framing_target_centres_the_glass_and_narrows_the_view() {
    for r in REFERENCES {
        let target = framing_target(r.observer);
        let (w, h) = (400u32, 300u32);
        let fov = framing_fov(r.observer, target, w as f64 / h as f64);
        let cam = Camera::new(r.observer, target, w, h, fov);
        let (r0, r1, c0, c1) = picture_extent(&cam);
        // Centred: equal room on both sides, in both directions.
        assert!(
            (r0 - (h as f64 - r1)).abs() < 1.0,
            "reference {}: rows {r0}..{r1}, target {target}",
            r.number
        );
        assert!((c0 - (w as f64 - c1)).abs() < 1.0, "cols {c0}..{c1}");
        // Never wider than aiming at the box's centre.
        assert!(fov <= framing_fov(r.observer, SCENE_CENTRE, w as f64 / h as f64) + 1e-12);
    }
}
