//! The tracers give what an independent tracer gives.
//!
//! The reference is `support/reference.rs`: the course's law and the Fresnel split in the plainest
//! way, in double-double arithmetic, sharing no code with the library. Every expected value is
//! computed by it, over many rays (all pixels of the four benchmark views, random rays from random
//! observers of random scenes, and awkward rays: vertical, horizontal, along the axes, grazing).
//! Where the reference reports that a ray passes within rounding of a decision (an edge, a tie,
//! the critical angle), either answer is right and the ray is not compared.

mod support;

use bentstraw_optics::camera::Camera;
use bentstraw_optics::geometry::Ray;
use bentstraw_optics::picture::{course_picture_exact, fresnel_picture_exact};
use bentstraw_optics::scene::{
    Scene, GLASS_HEIGHT, GLASS_RADIUS, REFERENCES, STRAW_HEIGHT, STRAW_RADIUS,
};
use bentstraw_optics::world::{Outcome, World, FRESNEL_SEGMENTS_PER_RAY};
use bentstraw_optics::Vec3;
use support::reference::{RefOutcome, Reference};

/// Margin (m) above which a ray's answer is not a matter of rounding.
const WELL_POSED: f64 = 1e-9;

/// The reference's course-mode answer for `ray` and its margin.
fn reference_trace(s: &Scene, ray: Ray) -> (RefOutcome, f64) {
    Reference::new(s).trace(ray)
}

/// Compares one ray's outcome by the library's tracers against the reference; whether it was
/// well posed enough to compare.
fn check_ray(s: &Scene, tracer: &World, ray: Ray) -> bool {
    let (expected, margin) = reference_trace(s, ray);
    if margin < WELL_POSED {
        return false;
    }
    match (tracer.trace(ray), expected) {
        (
            Outcome::Object {
                color,
                point,
                path_length,
                events,
                ..
            },
            RefOutcome::Straw {
                color: c,
                length,
                point: p,
                events: e,
            },
        ) => {
            assert_eq!((color, events), (c, e), "ray {ray:?}, scene {s:?}");
            assert!(
                (path_length - length).abs() <= 1e-12,
                "length {path_length} vs {length}, ray {ray:?}"
            );
            assert!(
                (point - p).length() <= 1e-12,
                "point {point} vs {p}, ray {ray:?}"
            );
        }
        (Outcome::Escaped { events, .. }, RefOutcome::Escaped { events: e }) => {
            assert_eq!(events, e, "escaped, ray {ray:?}, scene {s:?}")
        }
        (Outcome::Dropped, RefOutcome::Dropped) => {}
        (got, want) => panic!("library {got:?}, reference {want:?}, ray {ray:?}, scene {s:?}"),
    }
    assert_eq!(tracer.trace(ray).color(), expected.color());
    // Fresnel, in full and in the picture variant (escaping branches not followed): the
    // reference's weights to 1e-12.
    let (want, fresnel_margin) = Reference::new(s).fresnel(ray, 1e-4);
    if fresnel_margin >= WELL_POSED {
        for got in [
            tracer.fresnel_steps::<false>(ray, 1e-4, FRESNEL_SEGMENTS_PER_RAY, |_| {}),
            tracer.fresnel_steps::<true>(ray, 1e-4, FRESNEL_SEGMENTS_PER_RAY, |_| {}),
        ] {
            for (g, w) in got.iter().zip(want) {
                assert!(
                    (g - w).abs() <= 1e-12,
                    "fresnel {ray:?}: {got:?} vs {want:?}"
                );
            }
        }
    }
    let u0 = ray.direction;
    let ip = tracer.image_point(ray.origin, u0);
    assert_eq!(ip.map_or(0, |p| p.color), expected.color());
    if let (Some(p), RefOutcome::Straw { length, .. }) = (ip, expected) {
        let want = ray.origin + length * u0;
        assert!((p.position - want).length() <= 1e-12, "image point {ray:?}");
    }
    true
}

/// Small deterministic generator (xorshift64*), so the test needs no extra crate.
struct Rng(u64);

impl Rng {
    fn next_f64(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }
}

/// The four benchmark views (zoomed on where the straw enters the water) at `w × h`.
fn bench_views(w: u32, h: u32) -> Vec<(Scene, Camera)> {
    REFERENCES
        .iter()
        .map(|r| {
            let scene = r.scene(1.333);
            let target = r.zoom_target();
            (
                scene,
                Camera::new(r.observer, target, w, h, 50f64.to_radians()),
            )
        })
        .collect()
}

#[test]
fn fast_tracer_matches_reference_on_benchmark_views() {
    for (scene, camera) in bench_views(160, 120) {
        let tracer = World::assignment(&scene);
        let mut hits = 0;
        for i in 0..camera.height {
            for j in 0..camera.width {
                let ray = camera.pixel_ray(i, j);
                check_ray(&scene, &tracer, ray);
                hits += usize::from(reference_trace(&scene, ray).0.color() > 0);
            }
        }
        // The views are zoomed on the straw: a good share of pixels must see it.
        assert!(hits > 1000, "only {hits} straw pixels");
    }
}

#[test]
fn fast_tracer_matches_reference_on_random_rays() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let mut compared = 0;
    for _ in 0..300 {
        // A random valid scene; sometimes no water, sometimes a full glass, sometimes n = 1.
        let r = rng.range(0.0, GLASS_RADIUS - STRAW_RADIUS);
        let phi = rng.range(0.0, std::f64::consts::TAU);
        let he = match rng.next_f64() {
            x if x < 0.1 => 0.0,
            x if x < 0.2 => GLASS_HEIGHT,
            _ => rng.range(0.0, GLASS_HEIGHT),
        };
        let n = if rng.next_f64() < 0.1 {
            1.0
        } else {
            rng.range(1.0, 2.0)
        };
        let events = 1 + (rng.next_f64() * 12.0) as u32;
        let scene = Scene::new(r * phi.cos(), r * phi.sin(), he, n, events).unwrap();
        let tracer = World::assignment(&scene);
        let mut shot = 0;
        while shot < 200 {
            let observer = Vec3::new(
                rng.range(-0.3, 0.3),
                rng.range(-0.3, 0.3),
                rng.range(-0.2, 0.45),
            );
            if scene.validate_observer(observer).is_err() {
                continue;
            }
            // Aim at a random point of the glass/straw box, so that most rays do something.
            let aim = Vec3::new(
                rng.range(-GLASS_RADIUS, GLASS_RADIUS),
                rng.range(-GLASS_RADIUS, GLASS_RADIUS),
                rng.range(0.0, STRAW_HEIGHT),
            );
            compared += usize::from(check_ray(
                &scene,
                &tracer,
                Ray::new(observer, aim - observer),
            ));
            shot += 1;
        }
    }
    // Only rays within rounding of an edge, a tie or the critical angle are passed over.
    assert!(compared >= 300 * 200 * 99 / 100, "compared {compared}");
}

#[test]
fn fast_tracer_matches_reference_on_awkward_rays() {
    let mut rng = Rng(42);
    for (xp, yp, he) in [
        (0.0, 0.0, 0.1),
        (0.035, 0.0, 0.2),
        (0.02, 0.01, 0.0),
        (-0.01, 0.02, 0.05),
    ] {
        let scene = Scene::with_defaults(xp, yp, he).unwrap();
        let tracer = World::assignment(&scene);
        for _ in 0..400 {
            let (x, y) = (rng.range(-0.05, 0.05), rng.range(-0.05, 0.05));
            // Straight down from above the straw, straight up from below the glass.
            check_ray(&scene, &tracer, Ray::new(Vec3::new(x, y, 0.3), Vec3::NEG_Z));
            check_ray(&scene, &tracer, Ray::new(Vec3::new(x, y, -0.1), Vec3::Z));
            // Horizontal rays (dz = 0) at random heights, along x and along y.
            let z = rng.range(-0.01, 0.26);
            check_ray(&scene, &tracer, Ray::new(Vec3::new(-0.2, y, z), Vec3::X));
            check_ray(&scene, &tracer, Ray::new(Vec3::new(x, 0.2, z), Vec3::NEG_Y));
            // Exactly through the straw's axis and exactly grazing the straw and the glass.
            check_ray(&scene, &tracer, Ray::new(Vec3::new(-0.2, yp, z), Vec3::X));
            check_ray(
                &scene,
                &tracer,
                Ray::new(Vec3::new(-0.2, yp + STRAW_RADIUS, z), Vec3::X),
            );
            check_ray(
                &scene,
                &tracer,
                Ray::new(Vec3::new(-0.2, GLASS_RADIUS, z), Vec3::X),
            );
        }
        // Along the water surface and the glass's bottom plane.
        for z in [0.0, he, STRAW_HEIGHT, GLASS_HEIGHT] {
            check_ray(&scene, &tracer, Ray::new(Vec3::new(-0.2, yp, z), Vec3::X));
        }
    }
}

#[test]
fn pictures_match_reference_per_pixel() {
    for (scene, camera) in bench_views(96, 72) {
        let codes = course_picture_exact(&World::assignment(&scene), &camera);
        let weights = fresnel_picture_exact(&World::assignment(&scene), &camera, 1e-4);
        for i in 0..camera.height {
            for j in 0..camera.width {
                let k = (i * camera.width + j) as usize;
                let ray = camera.pixel_ray(i, j);
                let (course, margin) = reference_trace(&scene, ray);
                if margin >= WELL_POSED {
                    assert_eq!(codes[k], course.color(), "pixel ({i}, {j})");
                }
                let (want, margin) = Reference::new(&scene).fresnel(ray, 1e-4);
                if margin < WELL_POSED {
                    continue;
                }
                for (g, w) in weights[k].iter().zip(want) {
                    assert!(
                        (g - w).abs() <= 1e-12,
                        "fresnel pixel ({i}, {j}): {g} vs {w}"
                    );
                }
            }
        }
    }
}

#[test]
fn sampled_image_points_are_the_reference_image_points() {
    use bentstraw_optics::sampling::sample_image;
    for r in REFERENCES {
        let scene = r.scene(1.333);
        let cloud = sample_image(&World::assignment(&scene), r.observer, 3000, &|_| {});
        assert!(cloud.points.len() >= 3000, "simulation {}", r.number);
        for p in &cloud.points {
            // Each point is what the reference finds along the point's own direction.
            let ray = Ray {
                origin: r.observer,
                direction: p.direction,
            };
            let (want, margin) = reference_trace(&scene, ray);
            if margin < WELL_POSED {
                continue;
            }
            let RefOutcome::Straw {
                color,
                length,
                point,
                events,
            } = want
            else {
                panic!("simulation {}: reference {want:?}", r.number)
            };
            assert_eq!(p.color, color, "simulation {}", r.number);
            let position = r.observer + length * p.direction;
            assert!((p.position - position).length() <= 1e-12);
            assert!((p.straw_point - point).length() <= 1e-12);
            assert_eq!(p.events, events);
        }
    }
}
