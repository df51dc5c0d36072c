//! The course's tracing loop (refraction or total reflection at each water face, the event
//! limit), and the facts it must reproduce, such as a straw on the axis looking `n` times wider.

use bentstraw_optics::geometry::Ray;
use bentstraw_optics::scene::{Scene, GLASS_RADIUS, REFERENCES, STRAW_HEIGHT, STRAW_RADIUS};
use bentstraw_optics::world::{Event, Hit, Outcome, Part, Shape, World};
use bentstraw_optics::Vec3;
use proptest::prelude::*;

fn events_of(scene: &Scene, ray: Ray) -> (Outcome, Vec<Event>) {
    let mut events = Vec::new();
    let outcome = World::assignment(scene).trace_with(ray, |e| events.push(*e));
    (outcome, events)
}

/// The water's face an event of the assignment's glass happens on, in the assignment's words.
fn water_face(scene: &Scene, e: &Event) -> &'static str {
    match World::assignment(scene).boundaries()[e.boundary].shape {
        Shape::Upright { .. } => "side",
        Shape::Horizontal { z: 0.0, .. } => "bottom",
        _ => "top",
    }
}

#[test]
fn the_straw_wins_the_tie_on_the_glass_bottom() {
    // From below, straight up into the straw's footprint: the bottom cap (red) and the water's bottom
    // face are at the same distance; the opaque straw wins.
    let scene = Scene::with_defaults(0.02, 0.01, 0.15).unwrap();
    let ray = Ray::new(Vec3::new(0.02, 0.01, -0.1), Vec3::Z);
    match World::assignment(&scene).trace(ray) {
        Outcome::Object {
            color,
            part,
            path_length,
            events,
            ..
        } => {
            assert_eq!((color, part, events), (1, Part::Bottom, 0));
            assert!((path_length - 0.1).abs() < 1e-15);
        }
        other => panic!("{other:?}"),
    }
    // Just outside the footprint, the ray enters the water instead and climbs to the surface.
    let ray = Ray::new(Vec3::new(0.02 + STRAW_RADIUS + 1e-6, 0.01, -0.1), Vec3::Z);
    let (outcome, events) = events_of(&scene, ray);
    assert_eq!(water_face(&scene, &events[0]), "bottom");
    assert_eq!(water_face(&scene, &events[1]), "top");
    assert!(matches!(outcome, Outcome::Escaped { events: 2, .. }));
}

#[test]
fn colour_codes_follow_the_sections_from_the_bottom() {
    let scene = Scene::with_defaults(0.0, 0.0, 0.0).unwrap(); // no water: straight lines
    for (z, code) in [
        (0.001, 1),
        (0.049, 1),
        (0.051, 2),
        (0.12, 3),
        (0.17, 4),
        (0.2, 5),
        (0.249, 5),
    ] {
        let ray = Ray::new(Vec3::new(1.0, 0.0, z), Vec3::NEG_X);
        assert_eq!(
            World::assignment(&scene).trace(ray).color(),
            code,
            "z = {z}"
        );
    }
    let top = Ray::new(Vec3::new(0.001, 0.0, 1.0), Vec3::NEG_Z);
    assert_eq!(
        World::assignment(&scene).trace(top).color(),
        5,
        "top cap is blue"
    );
}

#[test]
fn a_straw_on_the_axis_looks_n_times_wider_for_any_distance() {
    // Horizontal rays at impact parameter b meet the straw iff b <= n·Rp.
    for n in [1.0, 1.1, 1.333, 1.5] {
        let scene = Scene::new(0.0, 0.0, 0.2, n, 10).unwrap();
        let threshold = n * STRAW_RADIUS;
        for distance in [0.05, 0.1, 1.0, 100.0] {
            for k in 0..=2000 {
                let b = 0.012 * k as f64 / 2000.0;
                if (b - threshold).abs() < 1e-9 {
                    continue; // at the threshold itself rounding decides
                }
                let ray = Ray::new(Vec3::new(distance, b, 0.1), Vec3::NEG_X);
                let hit = matches!(World::assignment(&scene).trace(ray), Outcome::Object { .. });
                assert_eq!(hit, b <= threshold, "n = {n}, D = {distance}, b = {b}");
            }
            // Right at both sides of the threshold.
            for (b, expect) in [(threshold - 1e-8, true), (threshold + 1e-8, false)] {
                let ray = Ray::new(Vec3::new(distance, b, 0.1), Vec3::NEG_X);
                assert_eq!(
                    matches!(World::assignment(&scene).trace(ray), Outcome::Object { .. }),
                    expect
                );
            }
        }
    }
}

#[test]
fn with_n_water_1_every_image_point_lies_on_the_straw_surface() {
    for r in REFERENCES {
        let scene = r.scene(1.0);
        let cloud = bentstraw_optics::sampling::sample_image(
            &World::assignment(&scene),
            r.observer,
            5000,
            &|_| {},
        );
        assert!(cloud.points.len() >= 5000);
        for p in &cloud.points {
            let d = World::assignment(&scene).distance_to_objects(p.position);
            assert!(
                d < 1e-12,
                "reference {}: {} is {d} m off",
                r.number,
                p.position
            );
            assert!((p.position - p.straw_point).length() < 1e-12);
        }
    }
}

#[test]
fn with_water_the_image_is_displaced_from_the_straw() {
    // The check above must be able to fail: with n = 1.333 the points under water are off the straw.
    let r = REFERENCES[1];
    let scene = r.scene(1.333);
    let cloud = bentstraw_optics::sampling::sample_image(
        &World::assignment(&scene),
        r.observer,
        2000,
        &|_| {},
    );
    let off = cloud
        .points
        .iter()
        .filter(|p| World::assignment(&scene).distance_to_objects(p.position) > 1e-3)
        .count();
    assert!(
        off > cloud.points.len() / 4,
        "{off} of {}",
        cloud.points.len()
    );
}

/// A deterministic stream of pseudo-random numbers in [0, 1) (SplitMix64).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Finds a ray that reaches the straw after exactly `k` events (with a generous limit).
///
/// In a shallow layer of water, a ray entering through the side wall at a moderate slope is totally
/// reflected again and again between the surface and the bottom: a light guide, many events.
fn ray_with_events(scene: &Scene, k: u32) -> Ray {
    let mut rng = Rng(k as u64 + 7);
    for _ in 0..5_000_000 {
        let phi = rng.next() * std::f64::consts::TAU;
        let origin = Vec3::new(
            0.06 * phi.cos(),
            0.06 * phi.sin(),
            0.12 * (rng.next() - 0.5),
        );
        let target = Vec3::new(
            (rng.next() - 0.5) * 2.0 * GLASS_RADIUS,
            (rng.next() - 0.5) * 2.0 * GLASS_RADIUS,
            rng.next() * scene.water_height(),
        );
        let ray = Ray::new(origin, target - origin);
        if let Outcome::Object { events, .. } = World::assignment(scene).trace(ray) {
            if events == k {
                return ray;
            }
        }
    }
    panic!("no ray with {k} events found");
}

#[test]
fn the_event_limit_keeps_a_ray_with_exactly_that_many_events_and_drops_one_more() {
    let (xp, yp, he) = (0.02, 0.01, 0.004);
    let generous = Scene::new(xp, yp, he, 1.333, 100).unwrap();
    let limit_10 = Scene::new(xp, yp, he, 1.333, 10).unwrap();
    let ten = ray_with_events(&generous, 10);
    let (generous_world, limit_10) = (World::assignment(&generous), World::assignment(&limit_10));
    match limit_10.trace(ten) {
        Outcome::Object { events, .. } => assert_eq!(events, 10),
        other => panic!("a 10-event ray must count: {other:?}"),
    }
    let eleven = ray_with_events(&generous, 11);
    assert!(matches!(
        generous_world.trace(eleven),
        Outcome::Object { events: 11, .. }
    ));
    assert_eq!(limit_10.trace(eleven), Outcome::Dropped);
    // The default limit is 10.
    assert_eq!(
        World::assignment(&Scene::with_defaults(xp, yp, he).unwrap()).trace(eleven),
        Outcome::Dropped
    );
    // The events are the light guide's: one refraction in, then total reflections.
    let (_, events) = events_of(&generous, eleven);
    assert_eq!(events.len(), 11);
    assert!(!events[0].totally_reflected);
    assert!(events.iter().filter(|e| e.totally_reflected).count() >= 9);
}

fn valid_observer() -> impl Strategy<Value = Vec3> {
    // Anywhere in a shell around the glass, above, beside or below it.
    (0.05f64..0.6, 0.0f64..std::f64::consts::TAU, -0.3f64..0.5)
        .prop_map(|(r, phi, z)| Vec3::new(r * phi.cos(), r * phi.sin(), z))
}

fn aim_point() -> impl Strategy<Value = Vec3> {
    (-1.0f64..1.0, -1.0f64..1.0, 0.0f64..1.0)
        .prop_map(|(x, y, z)| Vec3::new(x * GLASS_RADIUS, y * GLASS_RADIUS, z * STRAW_HEIGHT))
}

fn scene_strategy() -> impl Strategy<Value = Scene> {
    (
        0.0f64..0.035,
        0.0f64..std::f64::consts::TAU,
        0.0f64..0.2,
        1.0f64..1.8,
    )
        .prop_map(|(r, phi, he, n)| Scene::new(r * phi.cos(), r * phi.sin(), he, n, 10).unwrap())
}

fn sin_angle(d: Vec3, n: Vec3) -> f64 {
    d.cross(n).length()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// Every event obeys its law, every segment joins the last event to the next, and the path length
    /// is the sum of the segments.
    #[test]
    fn every_event_obeys_snell_or_total_reflection(
        scene in scene_strategy(), observer in valid_observer(), aim in aim_point(),
    ) {
        prop_assume!(scene.validate_observer(observer).is_ok());
        let ray = Ray::new(observer, aim - observer);
        let (outcome, events) = events_of(&scene, ray);
        let mut last = observer;
        let mut length = 0.0;
        let mut in_water = false;
        for e in &events {
            length += (e.point - last).length();
            // The segment to this event follows the previous direction.
            prop_assert!(((e.point - last).normalize() - e.incoming).length() < 1e-9);
            // The event lies on its face.
            match water_face(&scene, e) {
                "top" => prop_assert!((e.point.z - scene.water_height()).abs() < 1e-12),
                "bottom" => prop_assert!(e.point.z.abs() < 1e-12),
                _ => prop_assert!((e.point.truncate().length() - GLASS_RADIUS).abs() < 1e-12),
            }
            let (n1, n2) = if in_water { (scene.n_water(), 1.0) } else { (1.0, scene.n_water()) };
            prop_assert_eq!((e.n1, e.n2), (n1, n2));
            let sin_i = sin_angle(e.incoming, e.normal);
            let tir = n1 / n2 * sin_i > 1.0;
            prop_assert_eq!(e.totally_reflected, tir);
            if tir {
                prop_assert!((sin_angle(e.outgoing, e.normal) - sin_i).abs() < 1e-12);
                prop_assert!(e.outgoing.dot(e.normal).signum() == -e.incoming.dot(e.normal).signum());
            } else {
                prop_assert!((n1 * sin_i - n2 * sin_angle(e.outgoing, e.normal)).abs() < 1e-12);
                prop_assert!(e.outgoing.dot(e.normal).signum() == e.incoming.dot(e.normal).signum());
                in_water = !in_water;
            }
            prop_assert!((e.outgoing.length() - 1.0).abs() < 1e-12);
            last = e.point;
        }
        if let Outcome::Object { point, path_length, events: n, color, .. } = outcome {
            prop_assert_eq!(n as usize, events.len());
            length += (point - last).length();
            prop_assert!((path_length - length).abs() < 1e-12);
            prop_assert!(World::assignment(&scene).distance_to_objects(point) < 1e-12);
            prop_assert!((1..=5).contains(&color));
            // The image point is at the path length along the first direction.
            let image = World::assignment(&scene).image_point(observer, ray.direction).unwrap();
            prop_assert!(((image.position - observer).length() - path_length).abs() < 1e-12);
            prop_assert!(((image.position - observer).normalize() - ray.direction).length() < 1e-12);
        }
    }

    /// Light from the straw point, sent back along the last segment, retraces the path to the eye.
    #[test]
    fn a_ray_traced_back_from_the_straw_returns_to_the_observer(
        scene in scene_strategy(), observer in valid_observer(), aim in aim_point(),
    ) {
        prop_assume!(scene.validate_observer(observer).is_ok());
        let ray = Ray::new(observer, aim - observer);
        let (outcome, events) = events_of(&scene, ray);
        let Outcome::Object { point, object, .. } = outcome else { return Ok(()) };
        let world = World::assignment(&scene);
        let last_dir = events.last().map_or(ray.direction, |e| e.outgoing);
        // Start on the straw, in the water when the light came through it (the tracer's rays start
        // in air; here we follow the laws by hand, using only the scene's intersection, told which
        // face each piece starts on, and the interface laws).
        let mut back = Ray::new(point, -last_dir);
        let mut left = Some(world.object_code(object));
        let mut in_water = events.iter().filter(|e| !e.totally_reflected).count() % 2 == 1;
        for _ in 0..events.len() {
            let hit = world.nearest(&back, left).expect("the path back meets the water");
            let Hit::Boundary { t, index } = hit else {
                return Err(TestCaseError::fail("the path back meets the straw"));
            };
            left = Some(world.surface_code(index));
            let p = back.at(t);
            let normal = world.boundaries()[index].normal(p);
            let (n1, n2) = if in_water { (scene.n_water(), 1.0) } else { (1.0, scene.n_water()) };
            let d = match bentstraw_optics::interface::refract(back.direction, normal, n1, n2) {
                Some(t) => { in_water = !in_water; t.normalize() }
                None => bentstraw_optics::interface::reflect(back.direction, normal),
            };
            back = Ray { origin: p, direction: d };
        }
        prop_assert!(!in_water);
        // The final segment points at the observer.
        let to_eye = observer - back.origin;
        let miss = to_eye.cross(back.direction).length();
        prop_assert!(miss < 1e-9, "misses the eye by {miss}");
        prop_assert!(to_eye.dot(back.direction) > 0.0);
    }
}
