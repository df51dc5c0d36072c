//! Where the rays go: enough points, few wasted rays, an even cover of the straw's image, no holes.

use std::collections::HashSet;

use bentstraw_optics::sampling::{sample_image, DirectionMap, ImageCloud};
use bentstraw_optics::scene::REFERENCES;
use bentstraw_optics::world::World;
use bentstraw_optics::Vec3;

/// The final-grid cell `(i, j)` a point's direction falls in.
fn cell_of(frame: &DirectionMap, d: Vec3, h: f64) -> (i64, i64) {
    let (a, b) = frame.coordinates(d);
    (
        ((a - frame.a_min) / h).floor() as i64,
        ((b - frame.b_min) / h).floor() as i64,
    )
}

fn cloud(i: usize, n: f64, points: usize) -> (bentstraw_optics::scene::Scene, Vec3, ImageCloud) {
    let r = REFERENCES[i];
    let scene = r.scene(n);
    let c = sample_image(&World::assignment(&scene), r.observer, points, &|_| {});
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
        let frame = DirectionMap::of_box(observer, World::assignment(&scene).bounds());
        let h = c.spacing;
        // No clumps: one point per cell of a uniform grid of equal solid angles.
        let cells: HashSet<_> = c
            .points
            .iter()
            .map(|p| cell_of(&frame, p.direction, h))
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
        let nx = (frame.width / h).ceil() as i64;
        let ny = (frame.height / h).ceil() as i64;
        for j in 0..ny {
            for ii in 0..nx {
                let a = frame.a_min + (ii as f64 + 0.5) * h;
                let b = frame.b_min + (j as f64 + 0.5) * h;
                if a > frame.a_min + frame.width || b > frame.b_min + frame.height {
                    continue;
                }
                if World::assignment(&scene)
                    .image_point(observer, frame.direction(a, b))
                    .is_some()
                {
                    total += 1;
                    if !cells.contains(&(ii, j)) {
                        missed += 1;
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
fn the_map_has_equal_areas_and_inverts() {
    let frame = DirectionMap::looking(Vec3::new(-1.0, 0.3, -0.2));
    for (a, b) in [(0.0, 0.0), (0.4, -0.3), (-2.5, 0.9), (3.0, -0.99)] {
        let d = frame.direction(a, b);
        assert!((d.length() - 1.0).abs() < 1e-14);
        let (a2, b2) = frame.coordinates(d);
        assert!(
            (a - a2).abs() < 1e-12 && (b - b2).abs() < 1e-12,
            "({a}, {b}) -> ({a2}, {b2})"
        );
        // The solid angle of a small cell da × db is |∂d/∂a × ∂d/∂b| da db: it must be 1.
        let e = 1e-6;
        let da = (frame.direction(a + e, b) - frame.direction(a - e, b)) / (2.0 * e);
        let db = (frame.direction(a, b + e) - frame.direction(a, b - e)) / (2.0 * e);
        assert!((da.cross(db).length() - 1.0).abs() < 1e-6, "({a}, {b})");
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
        let c = sample_image(&World::assignment(&scene), observer, 3000, &|_| {});
        assert!(c.points.len() >= 3000, "{observer}: {}", c.points.len());
    }
}

/// A sampling whose stop flag is set gives up (no points that are not the view's), set before it
/// starts or while it runs; left alone, the same call gives `sample_image`'s points exactly.
#[test]
fn a_stopped_sampling_gives_up() {
    use bentstraw_optics::sampling::sample_image_until;
    use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
    let r = REFERENCES[1];
    let world = World::assignment(&r.scene(1.333));
    let stop = AtomicBool::new(true);
    assert!(sample_image_until(&world, r.observer, 20_000, false, &|_| {}, &stop).is_none());
    // Set by the progress of its first level: the levels after it are not traced.
    let stop = AtomicBool::new(false);
    let told = AtomicU64::new(0);
    let stopped = sample_image_until(
        &world,
        r.observer,
        200_000,
        false,
        &|rays| {
            told.store(rays, Ordering::Relaxed);
            stop.store(true, Ordering::Relaxed);
        },
        &stop,
    );
    assert!(stopped.is_none());
    let whole = sample_image(&world, r.observer, 200_000, &|_| {});
    assert!(told.load(Ordering::Relaxed) < whole.rays_traced / 4);
    let never = AtomicBool::new(false);
    let same = sample_image_until(&world, r.observer, 200_000, false, &|_| {}, &never).unwrap();
    assert_eq!(same.points, whole.points);
    assert_eq!(same.rays_traced, whole.rays_traced);
}
