//! The fast tracers give what a plain, obviously-correct tracer gives.
//!
//! The reference below is SPEC §3 written out the simplest way: test all six faces with the
//! geometry's own intersection routines, keep the nearest (straw wins ties), refract or reflect
//! totally, repeat. Nothing here was produced by the code under test: every expected value is
//! computed by the reference, over many rays (all pixels of the four benchmark views, random rays
//! from random observers of random scenes, and awkward rays: vertical, horizontal, along the axes).

use bentstraw_optics::camera::Camera;
use bentstraw_optics::geometry::{CylinderSide, Disk, Ray};
use bentstraw_optics::interface::{fresnel_reflectance, reflect, refract};
use bentstraw_optics::picture::{course_picture_exact, fresnel_picture_exact};
use bentstraw_optics::scene::{
    section_at, Scene, GLASS_HEIGHT, GLASS_RADIUS, REFERENCES, SECTION_COUNT, STRAW_HEIGHT,
    STRAW_RADIUS,
};
use bentstraw_optics::trace::Outcome;
use bentstraw_optics::tracer::Tracer;
use bentstraw_optics::Vec3;

/// The reference's result: colour code (0 = none), path length, straw point, events.
#[derive(Debug, Clone, Copy, PartialEq)]
struct RefHit {
    color: u8,
    length: f64,
    point: Vec3,
    events: u32,
}

/// The six faces of the scene, in the order: water side, top, bottom, straw side, top, bottom.
fn faces(s: &Scene) -> ([CylinderSide; 2], [Disk; 4]) {
    let (xp, yp, he) = (s.straw_x, s.straw_y, s.water_height);
    let cyl = |cx, cy, radius, z_max| CylinderSide {
        cx,
        cy,
        radius,
        z_min: 0.0,
        z_max,
    };
    let disk = |cx, cy, z, radius| Disk { cx, cy, z, radius };
    (
        [
            cyl(0.0, 0.0, GLASS_RADIUS, he),
            cyl(xp, yp, STRAW_RADIUS, STRAW_HEIGHT),
        ],
        [
            disk(0.0, 0.0, he, GLASS_RADIUS),
            disk(0.0, 0.0, 0.0, GLASS_RADIUS),
            disk(xp, yp, STRAW_HEIGHT, STRAW_RADIUS),
            disk(xp, yp, 0.0, STRAW_RADIUS),
        ],
    )
}

/// Which face a hit is on: 0..=2 water (side, top, bottom), 3..=5 straw (side, top, bottom).
fn nearest(s: &Scene, ray: &Ray) -> Option<(f64, usize)> {
    let (cyl, disks) = faces(s);
    let candidates = [
        (cyl[0].intersect(ray), 0),
        (disks[0].intersect(ray), 1),
        (disks[1].intersect(ray), 2),
        (cyl[1].intersect(ray), 3),
        (disks[2].intersect(ray), 4),
        (disks[3].intersect(ray), 5),
    ];
    let best = |range: std::ops::Range<usize>| {
        let mut best: Option<(f64, usize)> = None;
        for &(t, k) in &candidates[range] {
            if let Some(t) = t {
                if !matches!(best, Some((bt, _)) if bt <= t) {
                    best = Some((t, k));
                }
            }
        }
        best
    };
    let water = if s.water_height > 0.0 {
        best(0..3)
    } else {
        None
    };
    let straw = best(3..6);
    match (straw, water) {
        (Some(st), Some(w)) => Some(if st.0 <= w.0 { st } else { w }),
        (Some(st), None) => Some(st),
        (None, w) => w,
    }
}

fn normal_out_of_water(face: usize, p: Vec3) -> Vec3 {
    match face {
        1 => Vec3::Z,
        2 => Vec3::NEG_Z,
        _ => Vec3::new(p.x / GLASS_RADIUS, p.y / GLASS_RADIUS, 0.0).normalize(),
    }
}

fn straw_code(face: usize, p: Vec3) -> u8 {
    match face {
        4 => 5,
        5 => 1,
        _ => section_at(p.z),
    }
}

/// SPEC §3, plainly.
fn reference_trace(s: &Scene, ray: Ray) -> RefHit {
    let (mut ray, mut in_water, mut events, mut length) = (ray, false, 0u32, 0.0);
    let none = |events| RefHit {
        color: 0,
        length: 0.0,
        point: Vec3::ZERO,
        events,
    };
    loop {
        let Some((t, face)) = nearest(s, &ray) else {
            return none(events);
        };
        let p = ray.at(t);
        length += t;
        if face >= 3 {
            return RefHit {
                color: straw_code(face, p),
                length,
                point: p,
                events,
            };
        }
        if events == s.max_events {
            return none(u32::MAX);
        }
        events += 1;
        let n = normal_out_of_water(face, p);
        let (n1, n2) = if in_water {
            (s.n_water, 1.0)
        } else {
            (1.0, s.n_water)
        };
        let d = match refract(ray.direction, n, n1, n2) {
            Some(t) => {
                in_water = !in_water;
                t.normalize()
            }
            None => reflect(ray.direction, n),
        };
        ray = Ray {
            origin: p,
            direction: d,
        };
    }
}

/// SPEC §6 fresnel mode, plainly (recursive), with the same pruning rule as the library.
fn reference_fresnel(
    s: &Scene,
    ray: Ray,
    in_water: bool,
    events: u32,
    weight: f64,
    prune: f64,
    out: &mut [f64; SECTION_COUNT],
) {
    let Some((t, face)) = nearest(s, &ray) else {
        return;
    };
    let p = ray.at(t);
    if face >= 3 {
        out[straw_code(face, p) as usize - 1] += weight;
        return;
    }
    if events == s.max_events {
        return;
    }
    let n = normal_out_of_water(face, p);
    let (n1, n2) = if in_water {
        (s.n_water, 1.0)
    } else {
        (1.0, s.n_water)
    };
    let reflected = Ray {
        origin: p,
        direction: reflect(ray.direction, n),
    };
    match refract(ray.direction, n, n1, n2) {
        None => reference_fresnel(s, reflected, in_water, events + 1, weight, prune, out),
        Some(d) => {
            let r = fresnel_reflectance(n1, n2, ray.direction.dot(n));
            for (w, next, water) in [
                (weight * r, reflected, in_water),
                (
                    weight * (1.0 - r),
                    Ray {
                        origin: p,
                        direction: d.normalize(),
                    },
                    !in_water,
                ),
            ] {
                if w >= prune && w > 0.0 {
                    reference_fresnel(s, next, water, events + 1, w, prune, out);
                }
            }
        }
    }
}

/// Compares one ray's outcome by the library's tracers against the reference.
fn check_ray(s: &Scene, tracer: &Tracer, ray: Ray) {
    let expected = reference_trace(s, ray);
    for (name, got) in [
        ("Tracer::trace", tracer.trace(ray)),
        ("Scene::trace", s.trace(ray)),
    ] {
        match got {
            Outcome::Straw {
                color,
                point,
                path_length,
                events,
                ..
            } => {
                assert_eq!(
                    color, expected.color,
                    "{name} colour, ray {ray:?}, scene {s:?}"
                );
                assert!(
                    (path_length - expected.length).abs() <= 1e-12,
                    "{name} length {path_length} vs {}, ray {ray:?}",
                    expected.length
                );
                assert!(
                    (point - expected.point).length() <= 1e-12,
                    "{name} point {point} vs {}, ray {ray:?}",
                    expected.point
                );
                assert_eq!(events, expected.events, "{name} events, ray {ray:?}");
            }
            Outcome::Escaped { events } => {
                assert_eq!(
                    expected.color, 0,
                    "{name} escaped, ray {ray:?}, scene {s:?}"
                );
                assert_eq!(events, expected.events, "{name} events, ray {ray:?}");
            }
            Outcome::Dropped => {
                assert_eq!(expected.color, 0, "{name} dropped, ray {ray:?}");
                assert_eq!(expected.events, u32::MAX, "{name} dropped, ray {ray:?}");
            }
        }
    }
    assert_eq!(tracer.color(ray), expected.color);
    // Fresnel: the prepared tracer gives the scene's weights to the bit; the picture variant
    // (escaping branches not followed) gives the plain recursive reference's to 1e-12.
    assert_eq!(
        tracer.trace_fresnel(ray, 1e-4),
        s.trace_fresnel(ray, 1e-4),
        "fresnel {ray:?}"
    );
    let mut want = [0.0; SECTION_COUNT];
    reference_fresnel(s, ray, false, 0, 1.0, 1e-4, &mut want);
    for got in [
        s.trace_fresnel(ray, 1e-4),
        tracer.trace_fresnel_escaping(ray, 1e-4),
    ] {
        for (g, w) in got.iter().zip(want) {
            assert!(
                (g - w).abs() <= 1e-12,
                "fresnel {ray:?}: {got:?} vs {want:?}"
            );
        }
    }
    let u0 = ray.direction;
    let ip = tracer.image_point(ray.origin, u0);
    assert_eq!(ip.map_or(0, |p| p.color), expected.color);
    if let Some(p) = ip {
        let want = ray.origin + expected.length * u0;
        assert!((p.position - want).length() <= 1e-12, "image point {ray:?}");
    }
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
            let target = if r.number == 4 {
                Vec3::new(0.0, 0.0, 0.05)
            } else {
                Vec3::new(r.straw.0, r.straw.1, r.water_height)
            };
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
        let tracer = Tracer::new(&scene);
        let mut hits = 0;
        for i in 0..camera.height {
            for j in 0..camera.width {
                let ray = camera.pixel_ray(i, j);
                check_ray(&scene, &tracer, ray);
                hits += usize::from(reference_trace(&scene, ray).color > 0);
            }
        }
        // The views are zoomed on the straw: a good share of pixels must see it.
        assert!(hits > 1000, "only {hits} straw pixels");
    }
}

#[test]
fn fast_tracer_matches_reference_on_random_rays() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
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
        let tracer = Tracer::new(&scene);
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
            check_ray(&scene, &tracer, Ray::new(observer, aim - observer));
            shot += 1;
        }
    }
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
        let tracer = Tracer::new(&scene);
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
        let codes = course_picture_exact(&scene, &camera);
        let weights = fresnel_picture_exact(&scene, &camera, 1e-4);
        for i in 0..camera.height {
            for j in 0..camera.width {
                let k = (i * camera.width + j) as usize;
                let ray = camera.pixel_ray(i, j);
                assert_eq!(
                    codes[k],
                    reference_trace(&scene, ray).color,
                    "pixel ({i}, {j})"
                );
                let mut want = [0.0; SECTION_COUNT];
                reference_fresnel(&scene, ray, false, 0, 1.0, 1e-4, &mut want);
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
        let cloud = sample_image(&scene, r.observer, 3000, &|_| {});
        assert!(cloud.points.len() >= 3000, "simulation {}", r.number);
        for p in &cloud.points {
            // Each point is what the plain reference tracer finds along the point's own direction.
            let want = reference_trace(
                &scene,
                Ray {
                    origin: r.observer,
                    direction: p.direction,
                },
            );
            assert_eq!(p.color, want.color, "simulation {}", r.number);
            let position = r.observer + want.length * p.direction;
            assert!((p.position - position).length() <= 1e-12);
            assert!((p.straw_point - want.point).length() <= 1e-12);
            assert_eq!(p.events, want.events);
        }
    }
}
