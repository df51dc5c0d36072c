//! Where the rays go: enough points, few wasted rays, an even cover of the straw's image, no holes.

use std::collections::HashSet;

use bentstraw_optics::sampling::{frames_for, sample_image, ImageCloud};
use bentstraw_optics::scene::REFERENCES;
use bentstraw_optics::Vec3;

/// The final-grid cell `(frame, i, j)` a point's direction falls in.
fn cell_of(frames: &[bentstraw_optics::sampling::Frame], d: Vec3, h: f64) -> (usize, i64, i64) {
    // The frame the direction belongs to is the one it projects into (largest forward component
    // among the frames whose rectangle contains it).
    for (k, f) in frames.iter().enumerate() {
        let w = d.dot(f.forward);
        if w <= 0.0 {
            continue;
        }
        let (a, b) = (d.dot(f.right) / w, d.dot(f.up) / w);
        if frames.len() > 1 && (a.abs() > 1.0 || b.abs() > 1.0) {
            continue; // cube faces: each direction lies in exactly one face
        }
        if a < f.a_min || b < f.b_min || a > f.a_min + f.width || b > f.b_min + f.height {
            continue;
        }
        return (
            k,
            ((a - f.a_min) / h).floor() as i64,
            ((b - f.b_min) / h).floor() as i64,
        );
    }
    panic!("direction {d} is in no frame");
}

fn cloud(i: usize, n: f64, points: usize) -> (bentstraw_optics::scene::Scene, Vec3, ImageCloud) {
    let r = REFERENCES[i];
    let scene = r.scene(n);
    let c = sample_image(&scene, r.observer, points, &|_| {});
    (scene, r.observer, c)
}

#[test]
fn enough_points_and_at_least_a_quarter_of_rays_reach_the_straw() {
    for i in 0..4 {
        for n in [1.333, 1.0, 1.05] {
            let (_, _, c) = cloud(i, n, 20_000);
            assert!(
                c.points.len() >= 20_000,
                "reference {}: {} points",
                i + 1,
                c.points.len()
            );
            assert!(
                c.points.len() <= 30_000,
                "reference {}: {} points, far too many",
                i + 1,
                c.points.len()
            );
            assert!(
                c.hit_ratio() >= 0.25,
                "reference {} n={n}: hit ratio {}",
                i + 1,
                c.hit_ratio()
            );
            assert!(
                c.counts_per_color().iter().all(|&k| k > 0),
                "every section is seen"
            );
        }
    }
}

#[test]
fn same_inputs_give_identical_points_in_the_same_order() {
    let (_, _, a) = cloud(0, 1.333, 5000);
    let (_, _, b) = cloud(0, 1.333, 5000);
    assert_eq!(a.rays_traced, b.rays_traced);
    assert_eq!(a.points, b.points);
    // Also with a different number of threads.
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let (_, _, c) = pool.install(|| cloud(0, 1.333, 5000));
    assert_eq!(a.points, c.points);
}

#[test]
fn points_cover_the_straw_image_evenly_without_holes() {
    for i in 0..4 {
        let (scene, observer, c) = cloud(i, 1.333, 20_000);
        let frames = frames_for(observer);
        let h = c.spacing;
        // No clumps: one point per cell of a uniform grid.
        let cells: HashSet<_> = c
            .points
            .iter()
            .map(|p| cell_of(&frames, p.direction, h))
            .collect();
        assert_eq!(
            cells.len(),
            c.points.len(),
            "reference {}: two points share a cell",
            i + 1
        );
        // No holes: every cell of the same grid over the whole view whose centre ray reaches the
        // straw, found by brute force, is among the points.
        let mut missed = 0;
        let mut total = 0;
        for (k, f) in frames.iter().enumerate() {
            let nx = (f.width / h).ceil() as i64;
            let ny = (f.height / h).ceil() as i64;
            for j in 0..ny {
                for ii in 0..nx {
                    let a = f.a_min + (ii as f64 + 0.5) * h;
                    let b = f.b_min + (j as f64 + 0.5) * h;
                    if a > f.a_min + f.width || b > f.b_min + f.height {
                        continue;
                    }
                    if scene.image_point(observer, f.direction(a, b)).is_some() {
                        total += 1;
                        if !cells.contains(&(k, ii, j)) {
                            missed += 1;
                        }
                    }
                }
            }
        }
        assert!(total >= c.points.len());
        let missed_fraction = missed as f64 / total as f64;
        assert!(
            missed_fraction < 0.002,
            "reference {}: {missed} of {total} straw cells missed",
            i + 1
        );
    }
}

#[test]
fn a_far_observer_and_a_close_one_still_see_the_straw() {
    let scene = REFERENCES[0].scene(1.333);
    for observer in [
        Vec3::new(5.0, 3.0, 1.0),
        Vec3::new(0.041, 0.0, 0.1),
        Vec3::new(0.0, 0.0, -0.05),
    ] {
        assert!(scene.validate_observer(observer).is_ok());
        let c = sample_image(&scene, observer, 3000, &|_| {});
        assert!(c.points.len() >= 3000, "{observer}: {}", c.points.len());
    }
}
