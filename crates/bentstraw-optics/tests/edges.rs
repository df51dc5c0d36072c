//! Exact at the edges: rays that graze the straw where it meets the water's surface or touches the
//! wall, and observers from a metre to a hundred kilometres away, checked against an independent
//! double-double tracer (`support/reference.rs`).

mod support;

use bentstraw_optics::camera::Camera;
use bentstraw_optics::geometry::Ray;
use bentstraw_optics::sampling::sample_image;
use bentstraw_optics::scene::{Scene, GLASS_RADIUS, SECTION_EDGES, STRAW_RADIUS};
use bentstraw_optics::world::{Outcome, World};
use bentstraw_optics::Vec3;
use proptest::prelude::*;
use support::reference::{RefOutcome, Reference};

/// Below this margin (m) a decision is within rounding of going the other way.
const WELL_POSED: f64 = 1e-9;

/// The ray of a 1x1 picture aimed at `target`: exactly the line from the eye through it.
fn single_ray(observer: Vec3, target: Vec3) -> Ray {
    Camera::new(observer, target, 1, 1, 1f64.to_radians()).pixel_ray(0, 0)
}

/// The library's outcome agrees with the reference: same colour and events, same path length.
fn assert_agrees(scene: &Scene, ray: Ray, what: &str) {
    let (want, margin) = Reference::new(scene).trace(ray);
    let got = World::assignment(scene).trace(ray);
    if margin < WELL_POSED {
        return;
    }
    match (got, want) {
        (
            Outcome::Object {
                color,
                path_length,
                events,
                point,
                ..
            },
            RefOutcome::Straw {
                color: c,
                length,
                events: e,
                point: p,
            },
        ) => {
            assert_eq!((color, events), (c, e), "{what}: ray {ray:?}");
            let tol = 1e-9 + 1e-14 * length;
            assert!(
                (path_length - length).abs() <= tol,
                "{what}: L {path_length} vs {length}"
            );
            assert!((point - p).length() <= tol, "{what}: point {point} vs {p}");
        }
        (Outcome::Escaped { events, .. }, RefOutcome::Escaped { events: e }) => {
            assert_eq!(events, e, "{what}: ray {ray:?}")
        }
        (Outcome::Dropped, RefOutcome::Dropped) => {}
        (g, w) => panic!("{what}: library {g:?}, reference {w:?} (margin {margin:e}), ray {ray:?}"),
    }
}

#[test]
fn a_ray_refracted_at_the_surface_beside_the_straw_meets_its_near_side() {
    // The ray meets the water's surface 3e-10 m from the straw's side; the straw is the next
    // face, 3e-10 m on. A global minimum distance of 1 nm used to skip it and hit the far side
    // of the straw, lower down, in orange, 2 cm further.
    let scene = Scene::with_defaults(0.0, 0.0, 0.1002).unwrap();
    let ray = single_ray(
        Vec3::new(0.3, 0.0, 0.4),
        Vec3::new(0.0050000003, 0.0, 0.1002),
    );
    let Outcome::Object {
        color, path_length, ..
    } = World::assignment(&scene).trace(ray)
    else {
        panic!("reaches the straw")
    };
    assert_eq!(color, 3);
    assert!((path_length - 0.420601).abs() < 1e-6, "{path_length}");
    assert_agrees(&scene, ray, "surface beside the straw");
}

#[test]
fn a_straw_touching_the_wall_is_seen_where_it_touches() {
    let scene = Scene::with_defaults(
        0.03391518224816677,
        0.008646410415521237,
        0.14883313670332213,
    )
    .unwrap();
    let observer = Vec3::new(
        0.223463296594721,
        -0.045221596102236264,
        -0.08468021955131574,
    );
    let target = Vec3::new(
        0.030591983598984157,
        0.012320394019147321,
        0.05369871435365617,
    );
    let ray = single_ray(observer, target);
    assert_eq!(World::assignment(&scene).trace(ray).color(), 1);
    assert_agrees(&scene, ray, "straw touching the wall");
    // And every image point of that scene is where the reference puts it.
    let cloud = sample_image(&World::assignment(&scene), observer, 4000, &|_| {});
    assert!(cloud.points.len() >= 4000);
    for p in &cloud.points {
        assert_agrees(
            &scene,
            Ray {
                origin: observer,
                direction: p.direction,
            },
            "touching wall",
        );
    }
}

/// Observers at `distance` in every direction from the glass's centre, outside the glass.
fn observer_at(distance: f64, azimuth: f64, elevation: f64) -> Vec3 {
    let (se, ce) = elevation.sin_cos();
    let (sa, ca) = azimuth.sin_cos();
    Vec3::new(distance * ce * ca, distance * ce * sa, 0.1 + distance * se)
}

/// A scene of the kinds where precision is hardest: straws touching the wall, water heights on
/// the straw's section edges.
fn hard_scene() -> impl Strategy<Value = Scene> {
    (
        0.0f64..1.0,
        0.0f64..std::f64::consts::TAU,
        0usize..7,
        0.0f64..0.2,
        prop_oneof![Just(1.333), 1.0f64..2.0],
    )
        .prop_map(|(r, phi, kind, he, n)| {
            let reach = GLASS_RADIUS - STRAW_RADIUS;
            // Half the scenes have the straw against the wall (as close as the rule allows).
            let rr = if r < 0.5 { reach } else { reach * r };
            let (mut xp, mut yp) = (rr * phi.cos(), rr * phi.sin());
            while (xp * xp + yp * yp).sqrt() + STRAW_RADIUS > GLASS_RADIUS {
                xp *= 1.0 - 1e-16;
                yp *= 1.0 - 1e-16;
            }
            let he = if kind < SECTION_EDGES.len() {
                SECTION_EDGES[kind]
            } else {
                he
            };
            Scene::new(xp, yp, he, n, 10).unwrap()
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// From 1 m to 100 km away, every image point re-traces exactly under the reference: same
    /// colour, path length within 1e-6 m (in fact 1e-9 m plus 1e-14 of the length).
    #[test]
    fn image_points_of_distant_observers_retrace_exactly(
        scene in hard_scene(), log_d in 0.0f64..5.0, az in 0.0f64..std::f64::consts::TAU,
        el in -1.4f64..1.4,
    ) {
        let observer = observer_at(10f64.powf(log_d), az, el);
        prop_assume!(scene.validate_observer(observer).is_ok());
        let cloud = sample_image(&World::assignment(&scene), observer, 1500, &|_| {});
        let reference = Reference::new(&scene);
        let mut checked = 0;
        for p in &cloud.points {
            let ray = Ray { origin: observer, direction: p.direction };
            let (want, margin) = reference.trace(ray);
            if margin < WELL_POSED {
                continue;
            }
            checked += 1;
            let RefOutcome::Straw { color, length, .. } = want else {
                return Err(TestCaseError::fail(format!("reference: {want:?} for point {p:?}")));
            };
            prop_assert_eq!(p.color, color, "{:?}", p);
            prop_assert!((p.path_length - length).abs() <= 1e-9 + 1e-14 * length,
                "L {} vs {}", p.path_length, length);
        }
        // Not vacuous: most points are checked. Where the straw touches the wall, the points seen
        // along the contact line lie within 1e-10 m of the wall, where the order of the two
        // surfaces is within rounding; the sampler refines that edge, so up to a few per cent of a
        // cloud can be there (6% for one observer 2 km away, kept in the regressions file).
        prop_assert!(checked as f64 >= 0.9 * cloud.points.len() as f64,
            "only {checked} of {} points are well posed", cloud.points.len());
    }

    /// With water of index 1 the image points lie on the straw's surface, within 1e-9 m, from
    /// every distance up to 100 km.
    #[test]
    fn with_index_one_distant_image_points_lie_on_the_straw(
        scene in hard_scene(), log_d in 0.0f64..5.0, az in 0.0f64..std::f64::consts::TAU,
        el in -1.4f64..1.4,
    ) {
        let scene = scene.with_n_water(1.0).unwrap();
        let observer = observer_at(10f64.powf(log_d), az, el);
        prop_assume!(scene.validate_observer(observer).is_ok());
        let cloud = sample_image(&World::assignment(&scene), observer, 1000, &|_| {});
        prop_assert!(cloud.points.len() >= 1000);
        for p in &cloud.points {
            let miss = World::assignment(&scene).distance_to_objects(p.position);
            prop_assert!(miss <= 1e-9, "{miss:e} m off the straw, observer {observer}");
        }
    }
}

#[test]
fn observers_very_far_away_still_see_the_straw() {
    let scene = Scene::with_defaults(0.02, 0.01, 0.15)
        .unwrap()
        .with_n_water(1.0)
        .unwrap();
    for d in [1e3, 1e4, 1e5, 1e6, 1e8, 1e10] {
        let observer = Vec3::new(d, 0.0, 0.1);
        let cloud = sample_image(&World::assignment(&scene), observer, 1000, &|_| {});
        assert!(
            cloud.points.len() >= 1000,
            "{d}: {} points",
            cloud.points.len()
        );
        // The position P = O + L·u0 itself is only as exact as a number of that size (ulp).
        let ulp = d * f64::EPSILON;
        for p in &cloud.points {
            let miss = World::assignment(&scene).distance_to_objects(p.position);
            assert!(miss <= 1e-9 + 4.0 * ulp, "{d}: {miss:e}");
        }
    }
}
