//! Scenes as data ([`World`]): every shape and interface, closed forms (Snell through flat layers,
//! slabs and thick bottoms), invariants (Snell at every event, energy in the Fresnel splits, index 1
//! everywhere puts every image point on its object), the gallery's classic effects (the reversing
//! arrow), and the assignment's scene written as data against the independent double-double tracer.

mod support;

use std::path::PathBuf;

use bentstraw_optics::geometry::Ray;
use bentstraw_optics::sampling::sample_image;
use bentstraw_optics::scene::Scene;
use bentstraw_optics::scene_file::SceneDescription;
use bentstraw_optics::world::{Event, Outcome, World, COIN_COLOR, PICTURE_COLOR};
use bentstraw_optics::Vec3;
use proptest::prelude::*;
use support::reference::{RefOutcome, Reference};

fn scene(toml: &str) -> SceneDescription {
    SceneDescription::from_toml(toml).unwrap_or_else(|e| panic!("{e}\n{toml}"))
}

fn gallery(name: &str) -> SceneDescription {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes")
        .join(name);
    scene(&std::fs::read_to_string(path).expect("a gallery file"))
}

const GALLERY: [&str; 31] = [
    "spec.toml",
    "leaning-straw.toml",
    "real-glass.toml",
    "oil-on-water.toml",
    "tank-pencil.toml",
    "coin-in-glass.toml",
    "reversing-arrow.toml",
    "vanishing-glass.toml",
    "two-straws.toml",
    "oil-on-water-above.toml",
    "appearing-coin.toml",
    "apparent-depth.toml",
    "mirror-surface.toml",
    "near-and-far-arrow.toml",
    "pencil-at-a-slant.toml",
    "leaning-straw-above.toml",
    "dense-liquid.toml",
    "marble-in-water.toml",
    "fish-bowl.toml",
    "water-drop-magnifier.toml",
    "vanishing-ball.toml",
    "ball-lens.toml",
    "half-dipped-ball.toml",
    "prism.toml",
    "glass-block-pencil.toml",
    "magnifying-glass.toml",
    "diverging-lens.toml",
    "lens-in-water.toml",
    "tapered-tumbler.toml",
    "wine-glass.toml",
    "cocktail-glass.toml",
];

fn ray_to(from: Vec3, to: Vec3) -> Ray {
    Ray::new(from, to - from)
}

fn trace_events(world: &World, ray: Ray) -> (Outcome, Vec<Event>) {
    let mut events = Vec::new();
    let outcome = world.trace_with(ray, |e| events.push(*e));
    (outcome, events)
}

/// The sine of the angle between unit `d` and the line of unit `n`.
fn sine(d: Vec3, n: Vec3) -> f64 {
    d.cross(n).length()
}

#[test]
fn flat_layers_shift_a_ray_as_snell_says() {
    // A tank with water under oil and a wide coin on its floor; a ray from above meets the oil at
    // incidence θ0 and goes on at θk in layer k, n0 sin θ0 = nk sin θk.
    let world = World::new(
        &scene(
            r#"
            [container]
            shape = "tank"
            half_x = 0.1
            half_y = 0.05
            height = 0.2
            [[liquid]]
            name = "water"
            index = 1.333
            top = 0.1
            [[liquid]]
            name = "oil"
            index = 1.47
            top = 0.15
            [[coin]]
            x = 0.0
            y = 0.0
            radius = 0.045
            thickness = 0.002
            "#,
        ),
        10,
    )
    .expect("a valid scene");
    for theta0 in [0.0f64, 0.1, 0.3, 0.6, 0.7] {
        let entry = Vec3::new(0.04, 0.0, 0.15);
        let o = entry + 0.1 * Vec3::new(theta0.sin(), 0.0, theta0.cos());
        let (outcome, events) = trace_events(&world, ray_to(o, entry));
        let (s_oil, s_water) = (theta0.sin() / 1.47, theta0.sin() / 1.333);
        let tan = |s: f64| s / (1.0 - s * s).sqrt();
        let (d_oil, d_water) = (0.05, 0.1 - 0.002);
        let want_x = 0.04 - d_oil * tan(s_oil) - d_water * tan(s_water);
        let cos = |s: f64| (1.0 - s * s).sqrt();
        let want_l = 0.1 + d_oil / cos(s_oil) + d_water / cos(s_water);
        let Outcome::Object {
            color,
            point,
            path_length,
            events: n,
            ..
        } = outcome
        else {
            panic!("θ0 = {theta0}: {outcome:?}");
        };
        assert_eq!(
            (color, n, events.len()),
            (COIN_COLOR, 2, 2),
            "θ0 = {theta0}"
        );
        assert!(
            (point.x - want_x).abs() < 1e-14,
            "θ0 = {theta0}: x {}",
            point.x
        );
        assert!((point.z - 0.002).abs() < 1e-15);
        assert!((path_length - want_l).abs() < 1e-14, "θ0 = {theta0}");
        assert_eq!((events[0].n1, events[0].n2), (1.0, 1.47));
        assert_eq!((events[1].n1, events[1].n2), (1.47, 1.333));
    }
}

#[test]
fn a_thick_bottom_shifts_light_from_below_and_the_coin_on_it_wins_the_tie() {
    // Light from below crosses the 8 mm bottom of index 1.5 and meets the coin lying on the
    // floor exactly where the floor's face is: the opaque coin wins the tie.
    let world = World::new(
        &scene(
            r#"
            [container]
            shape = "glass"
            radius = 0.04
            height = 0.12
            bottom = 0.008
            [[liquid]]
            name = "water"
            index = 1.333
            top = 0.1
            [[coin]]
            x = 0.0
            y = 0.0
            radius = 0.03
            "#,
        ),
        10,
    )
    .expect("a valid scene");
    for theta0 in [0.0f64, 0.2, 0.5, 1.0] {
        let entry = Vec3::new(-0.01, 0.0, 0.0);
        let o = entry - 0.1 * Vec3::new(-theta0.sin(), 0.0, theta0.cos());
        let (outcome, events) = trace_events(&world, ray_to(o, entry));
        let s = theta0.sin() / 1.5;
        let want_x = -0.01 - 0.008 * s / (1.0 - s * s).sqrt();
        let want_l = 0.1 + 0.008 / (1.0 - s * s).sqrt();
        let Outcome::Object {
            color,
            point,
            path_length,
            ..
        } = outcome
        else {
            panic!("θ0 = {theta0}: {outcome:?}");
        };
        assert_eq!((color, events.len()), (COIN_COLOR, 1), "θ0 = {theta0}");
        assert!((point.x - want_x).abs() < 1e-15, "θ0 = {theta0}");
        assert!((point.z - 0.008).abs() < 1e-15, "θ0 = {theta0}");
        assert!((path_length - want_l).abs() < 1e-14);
        assert_eq!((events[0].n1, events[0].n2), (1.0, 1.5));
    }
}

#[test]
fn light_runs_down_a_thick_wall_by_total_reflection() {
    // A ray entering the rim of the 2.5 mm wall almost straight down meets the wall's faces
    // at grazing incidence, beyond the critical angles towards air (41.8°) and water (62.7°).
    let world = World::new(&gallery("real-glass.toml"), 1000).expect("a valid scene");
    // 10° from the vertical in air, 6.6° in the glass: a reflection every 2 cm of height.
    let entry = Vec3::new(0.03875, 0.0, 0.12);
    let tilt = 10f64.to_radians();
    let from = entry + 0.02 * Vec3::new(-tilt.sin(), 0.0, tilt.cos());
    let (_, events) = trace_events(&world, ray_to(from, entry));
    assert_eq!((events[0].n1, events[0].n2), (1.0, 1.5));
    let inside: Vec<_> = events[1..]
        .iter()
        .take_while(|e| e.n1 == 1.5 && e.totally_reflected)
        .collect();
    assert!(
        inside.len() >= 3,
        "guided down the wall: {:?}",
        &events[..4.min(events.len())]
    );
    for e in &inside {
        assert!(e.point.z < 0.12 && e.point.z > 0.0);
        let r = (e.point.x * e.point.x + e.point.y * e.point.y).sqrt();
        assert!((0.0375 - 1e-12..=0.04 + 1e-12).contains(&r), "r = {r}");
    }
}

#[test]
fn snell_holds_at_every_event_in_every_gallery_scene() {
    for name in GALLERY {
        let d = gallery(name);
        let world = World::new(&d, 10).expect("a valid scene");
        let observer = d.observer.unwrap().position;
        let (lo, hi) = world.bounds();
        let mut checked = 0;
        for k in 0..4000u32 {
            // Aim at points spread through the scene's box (a deterministic low-discrepancy walk).
            let f = |m: f64| (k as f64 * m).fract();
            let aim = lo + Vec3::new(f(0.618034), f(0.7548777), f(0.5698403)) * (hi - lo);
            let (_, events) = trace_events(&world, ray_to(observer, aim));
            for e in events {
                assert!((e.outgoing.length() - 1.0).abs() < 1e-12);
                let (si, so) = (sine(e.incoming, e.normal), sine(e.outgoing, e.normal));
                if e.totally_reflected {
                    assert!(e.n1 * si > e.n2 * (1.0 - 1e-12), "{name}: {e:?}");
                    assert!((si - so).abs() < 1e-12);
                    assert!(e.incoming.dot(e.normal) * e.outgoing.dot(e.normal) < 0.0);
                } else {
                    assert!((e.n1 * si - e.n2 * so).abs() < 1e-12, "{name}: {e:?}");
                    assert!(e.incoming.dot(e.normal) * e.outgoing.dot(e.normal) > 0.0);
                }
                checked += 1;
            }
        }
        assert!(checked > 500, "{name}: {checked} events checked");
    }
}

/// The description with every index set to 1.
fn without_refraction(mut d: SceneDescription) -> SceneDescription {
    use bentstraw_optics::scene_file::Container;
    match &mut d.container {
        Container::Glass(g) => g.index = 1.0,
        Container::Revolution(v) => v.index = 1.0,
        Container::Tank(_) => {}
    }
    for l in &mut d.liquids {
        l.index = 1.0;
        // (A tinted liquid keeps its faces whatever its index: light must know where it is
        // absorbed.)
        l.tint = None;
    }
    for s in &mut d.spheres {
        s.index = 1.0;
    }
    for p in &mut d.prisms {
        p.index = 1.0;
    }
    for l in &mut d.lenses {
        l.index = 1.0;
    }
    d
}

#[test]
fn with_index_one_everywhere_every_image_point_lies_on_its_object() {
    for name in GALLERY {
        let d = without_refraction(gallery(name));
        let world = World::new(&d, 10).expect("a valid scene");
        assert!(
            world.boundaries().is_empty(),
            "{name}: no interface is left"
        );
        let observer = d.observer.unwrap().position;
        let cloud = sample_image(&world, observer, 5000, &|_| {});
        assert!(cloud.points.len() >= 5000, "{name}: {}", cloud.points.len());
        for p in &cloud.points {
            assert_eq!(p.events, 0);
            let miss = (p.position - p.straw_point).length();
            assert!(miss < 1e-9, "{name}: {p:?} is {miss:e} m off its object");
        }
    }
}

#[test]
fn a_glass_of_index_one_traces_like_walls_of_no_thickness() {
    let thick = World::new(
        &scene(
            r#"
            [container]
            shape = "glass"
            radius = 0.04
            height = 0.2
            wall = 0.004
            index = 1.0
            [[liquid]]
            name = "water"
            index = 1.333
            top = 0.15
            [[straw]]
            x = 0.015
            y = 0.01
            "#,
        ),
        10,
    )
    .expect("a valid scene");
    let thin = World::new(
        &scene(
            r#"
            [container]
            shape = "glass"
            radius = 0.036
            height = 0.2
            [[liquid]]
            name = "water"
            index = 1.333
            top = 0.15
            [[straw]]
            x = 0.015
            y = 0.01
            "#,
        ),
        10,
    )
    .expect("a valid scene");
    for observer in [
        Vec3::new(0.1, 0.0, 0.1),
        Vec3::new(0.0, 0.1, 0.1),
        Vec3::new(0.1, 0.0, 0.3),
        Vec3::new(0.1, 0.0, -0.1),
        Vec3::new(0.05, 0.07, 0.16),
    ] {
        let cloud = sample_image(&thick, observer, 5000, &|_| {});
        assert!(cloud.points.len() >= 5000);
        for p in &cloud.points {
            let q = thin
                .image_point(observer, p.direction)
                .expect("the same ray reaches the straw");
            assert_eq!((p.color, p.events), (q.color, q.events));
            assert!((p.path_length - q.path_length).abs() < 1e-12);
        }
    }
}

/// Every image point `a` sees from each observer, seen the same in `b`: same colour, events and
/// path length (to rounding).
fn assert_same_images(a: &World, b: &World, observers: &[Vec3]) {
    for &observer in observers {
        let cloud = sample_image(a, observer, 3000, &|_| {});
        assert!(cloud.points.len() >= 3000);
        for p in &cloud.points {
            let q = b
                .image_point(observer, p.direction)
                .unwrap_or_else(|| panic!("from {observer}, {p:?} reaches nothing"));
            assert_eq!((p.color, p.events), (q.color, q.events), "from {observer}");
            assert!((p.path_length - q.path_length).abs() < 1e-12);
        }
    }
}

const AROUND: [Vec3; 4] = [
    Vec3::new(0.1, 0.0, 0.1),
    Vec3::new(0.02, 0.01, 0.35),
    Vec3::new(0.1, 0.0, -0.1),
    Vec3::new(0.05, 0.07, 0.16),
];

#[test]
fn two_layers_of_the_same_index_trace_like_one() {
    let two = r#"
        [container]
        shape = "glass"
        radius = 0.04
        height = 0.2
        [[liquid]]
        name = "water"
        index = 1.333
        top = 0.06
        [[liquid]]
        name = "more water"
        index = 1.333
        top = 0.15
        [[straw]]
        x = -0.015
        y = 0.0
        tilt = 8
        "#;
    let one = two.replace("top = 0.06", "top = 0.15").replace(
        "[[liquid]]
        name = \"more water\"
        index = 1.333
        top = 0.15",
        "",
    );
    assert_eq!(scene(&one).liquids.len(), 1);
    let (two, one) = (
        World::new(&scene(two), 10).expect("a valid scene"),
        World::new(&scene(&one), 10).expect("a valid scene"),
    );
    assert_same_images(&two, &one, &AROUND);
    assert_same_images(&one, &two, &AROUND);
}

#[test]
fn a_glass_of_its_liquids_index_vanishes() {
    // A thick glass of index 1.47 filled to the rim with oil of index 1.47, a card behind it:
    // optically one cylinder of oil. Before the two were one medium, a ray that
    // crossed the face between glass and oil kept the glass's identity and met the oil's surface
    // from the wrong side.
    let vanishing = r#"
        [container]
        shape = "glass"
        radius = 0.04
        height = 0.12
        wall = 0.004
        bottom = 0.01
        index = 1.47
        [[liquid]]
        name = "oil"
        index = 1.47
        top = 0.12
        [[card]]
        center = [-0.12, 0.0, 0.06]
        facing = 0
        width = 0.1
        height = 0.1
        "#;
    // The same without its walls and bottom: a cylinder of oil of the glass's outer size.
    let cylinder = vanishing.replace(
        "wall = 0.004\n        bottom = 0.01\n        index = 1.47\n",
        "",
    );
    assert_ne!(cylinder, vanishing);
    let (a, b) = (
        World::new(&scene(vanishing), 10).expect("a valid scene"),
        World::new(&scene(&cylinder), 10).expect("a valid scene"),
    );
    let eyes = [
        Vec3::new(0.2, 0.0, 0.06),
        Vec3::new(0.15, 0.05, 0.2),
        Vec3::new(0.1, 0.02, -0.1),
    ];
    assert_same_images(&a, &b, &eyes);
    assert_same_images(&b, &a, &eyes);
}

/// The assignment's glass with the straw at `(x, y)`, water to `he` of index `n`.
fn spec_as_data(x: f64, y: f64, he: f64, n: f64) -> SceneDescription {
    scene(&format!(
        r#"
        [container]
        shape = "glass"
        radius = 0.04
        height = 0.2
        [[liquid]]
        name = "water"
        index = {n:?}
        top = {he:?}
        [[straw]]
        x = {x:?}
        y = {y:?}
        "#
    ))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// The assignment's scene written as data traces as the independent double-double tracer
    /// does: same colour and events, the same path length, for every ray whose decisions are
    /// clear (1e-9 m from any face's edge or tie).
    #[test]
    fn the_assignment_as_data_agrees_with_the_independent_tracer(
        r in 0.0f64..0.035, phi in 0.0f64..std::f64::consts::TAU, he in 0.01f64..0.2, n in 1.01f64..2.0,
        dist in 0.06f64..3.0, azimuth in 0.0f64..std::f64::consts::TAU, oz in -0.5f64..0.6, seed in 0u64..1000,
    ) {
        let (x, y) = (r * phi.cos(), r * phi.sin());
        let world = World::new(&spec_as_data(x, y, he, n), 10).expect("a valid scene");
        let reference = Reference::new(&Scene::new(x, y, he, n, 10).unwrap());
        let observer = Vec3::new(dist * azimuth.cos(), dist * azimuth.sin(), oz);
        prop_assume!(observer.x.hypot(observer.y) > 0.045 || !(0.0..=0.25).contains(&oz));
        let (mut clear, mut all) = (0, 0);
        for k in 0..300u64 {
            let f = |m: f64| ((k + seed) as f64 * m).fract();
            let aim = Vec3::new(0.08 * f(0.618034) - 0.04, 0.08 * f(0.7548777) - 0.04, 0.26 * f(0.5698403));
            let ray = ray_to(observer, aim);
            let (want, margin) = reference.trace(ray);
            all += 1;
            if margin < 1e-9 {
                continue;
            }
            clear += 1;
            match (world.trace(ray), want) {
                (
                    Outcome::Object { color, path_length, events, .. },
                    RefOutcome::Straw { color: c, length, events: e, .. },
                ) => {
                    prop_assert_eq!((color, events), (c, e));
                    prop_assert!((path_length - length).abs() < 1e-9 + 1e-14 * length,
                        "L {} against {}", path_length, length);
                }
                (Outcome::Escaped { events, .. }, RefOutcome::Escaped { events: e }) => {
                    prop_assert_eq!(events, e)
                }
                (Outcome::Dropped, RefOutcome::Dropped) => {}
                (got, want) => prop_assert!(false, "world {:?}, reference {:?}, ray {:?}", got, want, ray),
            }
        }
        prop_assert!(clear * 100 >= all * 95, "{} of {} rays well posed", clear, all);
    }
}

#[test]
fn the_reversing_arrow_points_the_other_way_through_the_water() {
    // The card faces +x; its right (where the arrow's head is) is +y. Seen through the full glass
    // of water (a cylindrical lens, the card beyond its focus) the head appears on the other side
    // of the tail; through a glass of index 1 it does not.
    for (n, reversed) in [(1.333, true), (1.0, false)] {
        let mut d = gallery("reversing-arrow.toml");
        d.liquids[0].index = n;
        let world = World::new(&d, 10).expect("a valid scene");
        let observer = d.observer.unwrap().position;
        let cloud = sample_image(&world, observer, 20000, &|_| {});
        let card_y = d.cards[0].center.y;
        let (mut head, mut tail) = (Vec::new(), Vec::new());
        for p in cloud.points.iter().filter(|p| p.color == PICTURE_COLOR) {
            // Through the water only (in and out of its side), not past the glass's sides.
            if n > 1.0 && p.events != 2 {
                continue;
            }
            let u = p.straw_point.y - card_y;
            if u > 0.2 * 0.12 {
                head.push(p.direction.y);
            } else if u < -0.2 * 0.12 {
                tail.push(p.direction.y);
            }
        }
        assert!(
            head.len() > 50 && tail.len() > 50,
            "n = {n}: {} {}",
            head.len(),
            tail.len()
        );
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
        // The observer looks along −x: a larger y is to its right.
        let head_right_of_tail = mean(&head) > mean(&tail);
        assert_eq!(head_right_of_tail, !reversed, "n = {n}");
    }
}

#[test]
fn a_leaning_straw_rests_on_the_rim_of_its_bottom_cap() {
    let d = gallery("leaning-straw.toml");
    let straw = d.straws[0];
    let world = World::new(&d, 10).expect("a valid scene");
    let (lo, _) = world.objects()[0].bounds();
    let foot = straw.foot(0.0);
    assert!(
        foot.z.abs() < 1e-15,
        "the cap's rim touches the floor: {foot}"
    );
    assert!(lo.z <= 0.0, "its box holds its foot");
    // Straight up from below, just inside the foot: through the bottom of the water, onto the
    // bottom cap, a hair above the floor.
    let inward = (Vec3::new(straw.x, straw.y, 0.0) - Vec3::new(foot.x, foot.y, 0.0)).normalize();
    let start = Vec3::new(foot.x, foot.y, -0.1) + 1e-4 * inward;
    let outcome = world.trace(Ray::new(start, Vec3::Z));
    let Outcome::Object { color, point, .. } = outcome else {
        panic!("{outcome:?}")
    };
    assert_eq!(color, 1);
    let rise = 1e-4 * straw.tilt_deg.to_radians().tan();
    assert!((point.z - rise).abs() < 1e-12, "{point} against {rise}");
}

#[test]
fn rays_that_miss_graze_or_pass_above_meet_nothing() {
    let world = World::new(&gallery("real-glass.toml"), 10).expect("a valid scene");
    // Tangent to the outer wall: no refraction, no event.
    let tangent = world.trace(Ray::new(Vec3::new(0.04 + 1e-12, -1.0, 0.05), Vec3::Y));
    assert!(
        matches!(tangent, Outcome::Escaped { events: 0, .. }),
        "{tangent:?}"
    );
    let above = world.trace(Ray::new(Vec3::new(-1.0, 0.0, 0.5), Vec3::X));
    assert!(matches!(above, Outcome::Escaped { events: 0, .. }));
    // A ray from 100 km away is brought to the scene first: it still finds the straw.
    let far = Vec3::new(1e5, 0.0, 0.1);
    let hit = world.trace(ray_to(far, Vec3::new(0.012, 0.0, 0.1)));
    assert!(hit.color() > 0, "{hit:?}");
}

#[test]
fn fresnel_weights_and_escaping_light_add_up_to_one() {
    for name in ["real-glass.toml", "oil-on-water.toml", "tank-pencil.toml"] {
        let d = gallery(name);
        let world = World::new(&d, 1000).expect("a valid scene");
        let observer = d.observer.unwrap().position;
        let (lo, hi) = world.bounds();
        let mut all_lost = 0.0;
        for k in 0..300u32 {
            let f = |m: f64| (k as f64 * m).fract();
            let aim = lo + Vec3::new(f(0.618034), f(0.7548777), f(0.5698403)) * (hi - lo);
            let (mut escaped, mut lost) = (0.0, 0.0);
            let weights = world.trace_fresnel(ray_to(observer, aim), 1e-6, |ray, w| match ray {
                Some(_) => escaped += w,
                None => lost += w,
            });
            let total: f64 = weights.iter().sum::<f64>() + escaped + lost;
            assert!((total - 1.0).abs() < 1e-12, "{name}: {total}");
            all_lost += lost;
        }
        // Little is abandoned (branches under 1e-6, light trapped in a thick wall bouncing on
        // until the segment bound): a few per cent at most.
        assert!(
            all_lost / 300.0 < 0.05,
            "{name}: {} lost on average",
            all_lost / 300.0
        );
    }
}

/// Light leaving through a face of the scene's hull never comes back: following those branches
/// (as the explorer's ray diagram does) or skipping them (as pictures do) puts the same weight on
/// every colour, for rays aimed all over every gallery scene and from observers all around it.
#[test]
fn branches_leaving_through_the_hull_never_return() {
    use bentstraw_optics::world::FresnelStep;
    let mut skipped = 0usize;
    for name in GALLERY {
        let d = gallery(name);
        let world = World::new(&d, 10).expect("a valid scene");
        let (lo, hi) = world.bounds();
        let centre = (lo + hi) * 0.5;
        let reach = (hi - lo).length();
        for k in 0..400u32 {
            let f = |m: f64| (k as f64 * m).fract();
            let aim = lo + Vec3::new(f(0.618034), f(0.7548777), f(0.5698403)) * (hi - lo);
            // Half from the file's observer, half from all around (above, below, beside).
            let observer = if k % 2 == 0 {
                d.observer.unwrap().position
            } else {
                let (az, el) = (
                    f(0.3819660) * std::f64::consts::TAU,
                    f(0.1415926) * 3.0 - 1.5,
                );
                centre + Vec3::new(el.cos() * az.cos(), el.cos() * az.sin(), el.sin()) * reach
            };
            let ray = ray_to(observer, aim);
            let mut escaping = 0usize;
            let all = world.fresnel_steps::<false>(ray, 1e-9, 100_000, |step| {
                escaping += usize::from(matches!(step, FresnelStep::Escaped { .. }))
            });
            let kept = world.fresnel_steps::<true>(ray, 1e-9, 100_000, |_| {});
            for (a, b) in all.iter().zip(&kept) {
                assert!(
                    (a - b).abs() <= 1e-12,
                    "{name}: {all:?} vs {kept:?}, ray {ray:?}"
                );
            }
            skipped += escaping;
        }
    }
    assert!(skipped > 1000, "{skipped} escaping branches");
}

#[test]
fn the_eye_model_finds_the_apparent_depth_of_a_coin_under_flat_water() {
    use bentstraw_optics::apparent::Focus;
    // A coin's top 0.118 m under the flat surface of a tank's water; the eye 0.18 m above the
    // surface. Straight down both foci are at the textbook apparent depth d/n; obliquely, at θ in
    // air and θ' in water, the sagittal focus (across the plane of incidence: the horizontal pupil
    // direction) is at d/(n cos θ') and the tangential one at d cos²θ/(n cos³θ') past the surface.
    let n = 1.333;
    let world = World::new(
        &scene(&format!(
            r#"
            [container]
            shape = "tank"
            half_x = 0.1
            half_y = 0.05
            height = 0.2
            [[liquid]]
            name = "water"
            index = {n}
            top = 0.12
            [[coin]]
            x = 0.0
            y = 0.0
            radius = 0.045
            thickness = 0.002
            "#
        )),
        10,
    )
    .expect("a valid scene");
    let d = 0.12 - 0.002;
    for theta in [0.0f64, 0.2, 0.4] {
        let surface = Vec3::new(0.0, 0.0, 0.12);
        let (above, u0) = (
            0.18 / theta.cos(),
            Vec3::new(theta.sin(), 0.0, -theta.cos()),
        );
        let eye = surface - above * u0;
        let image = world.image_point(eye, u0).expect("the coin is seen");
        let p = world.apparent_point(eye, &image);
        let cos_t = (1.0 - (theta.sin() / n).powi(2)).sqrt();
        let sagittal = above + d / (n * cos_t);
        let tangential = above + d * theta.cos().powi(2) / (n * cos_t.powi(3));
        let (Focus::InFront(s_h), Focus::InFront(s_v)) = (p.s_h, p.s_v) else {
            panic!("θ = {theta}: {p:?}");
        };
        assert!(
            (s_h - sagittal).abs() < 1e-7,
            "θ = {theta}: s_h {s_h} against {sagittal}"
        );
        assert!(
            (s_v - tangential).abs() < 1e-7,
            "θ = {theta}: s_v {s_v} against {tangential}"
        );
    }
    // The same through the round glass of the gallery's coin, looking straight down.
    let d = gallery("coin-in-glass.toml");
    let world = World::new(&d, 10).expect("a valid scene");
    let top = d.liquids[0].top;
    let coin_top = d.container.floor() + d.coins[0].thickness;
    let eye = Vec3::new(d.coins[0].x, d.coins[0].y, top + 0.2);
    let image = world.image_point(eye, -Vec3::Z).expect("the coin is seen");
    let want = 0.2 + (top - coin_top) / d.liquids[0].index;
    let p = world.apparent_point(eye, &image);
    let s = p.position.expect("both foci in front").distance(eye);
    assert!((s - want).abs() < 1e-7, "{s} against {want}");
}

#[test]
fn check_judges_a_worlds_points_and_finds_what_is_missing() {
    use bentstraw_optics::check::{check_solution, ClaimedPoint, DEFAULT_TOLERANCE};
    use bentstraw_optics::light_path_type::Entry;
    let d = gallery("leaning-straw.toml");
    let world = World::new(&d, 10).expect("a valid scene");
    let observer = d.observer.unwrap().position;
    let cloud = sample_image(&world, observer, 4000, &|_| {});
    let claimed =
        |keep: &dyn Fn(&bentstraw_optics::image::ImagePoint) -> bool| -> Vec<ClaimedPoint> {
            cloud
                .points
                .iter()
                .filter(|p| keep(p))
                .map(|p| ClaimedPoint {
                    position: p.position,
                    color: p.color,
                })
                .collect()
        };
    let all = check_solution(
        &world,
        observer,
        &claimed(&|_| true),
        DEFAULT_TOLERANCE,
        0.98,
    );
    assert!(all.passes(), "{:?}", all.tally);
    // Without the points seen through the water's surface, that part of the image is missing,
    // and named by its light path.
    let through_top = |p: &bentstraw_optics::image::ImagePoint| {
        world
            .trace_path_type(Ray::new(observer, p.direction))
            .1
            .entry
            == Entry::Top
    };
    let some = check_solution(
        &world,
        observer,
        &claimed(&|p| !through_top(p)),
        DEFAULT_TOLERANCE,
        0.98,
    );
    assert!(!some.passes());
    assert_eq!(
        some.tally.correct, some.tally.points,
        "the points kept are right"
    );
    assert!(!some.coverage.missing.is_empty());
    assert!(some
        .coverage
        .missing
        .iter()
        .all(|m| m.path.entry == Entry::Top));
    // A point moved 1 mm along its ray has the wrong length.
    let mut moved = claimed(&|_| true);
    let u = (moved[0].position - observer).normalize();
    moved[0].position += 1e-3 * u;
    let r = check_solution(&world, observer, &moved, DEFAULT_TOLERANCE, 0.98);
    assert_eq!(r.tally.wrong_length, 1);
}

mod random_scenes {
    use super::*;
    use bentstraw_optics::profile;
    use bentstraw_optics::scene_file::{
        Card, Coin, Container, Glass, Lens, Liquid, Observer, Picture, Prism, Revolution, Sphere,
        Straw, Tank,
    };

    /// Where the random scene's sphere lies, if it has one.
    #[derive(Clone, Copy, Debug)]
    enum Place {
        None,
        /// In the first liquid layer (in the air inside the container if there is none).
        FirstLayer,
        /// In the air above the liquids, inside the container (it may stand out above the rim).
        AboveTheLiquids,
        /// Outside the container, in air (partly below its base, at times).
        Outside,
    }

    /// A sphere at `place` in a scene with `container`, `liquids` and `straw`, its size, height
    /// and bearing chosen by `size`, `height` (0..1) and `bearing` (-1..1), of `index`. Placed so
    /// that the format's rules accept it: inside, beside the straw's foot on the side away from
    /// its lean (clear of the straw's capsule however it leans), small enough to fit in the
    /// container and in its layer, above the coin's thickness; outside, beyond the container's
    /// widest reach, on the side away from the straw's lean, never near the observers or the
    /// card.
    #[allow(clippy::too_many_arguments)]
    fn sphere(
        place: Place,
        container: &Container,
        liquids: &[Liquid],
        straw: &Straw,
        size: f64,
        height: f64,
        bearing: f64,
        index: f64,
    ) -> Option<Sphere> {
        let floor = container.floor();
        let (inner, reach) = match container {
            Container::Glass(g) => (g.radius - g.wall, g.radius),
            Container::Tank(t) => (t.half_y, t.half_x.hypot(t.half_y)),
            Container::Revolution(v) => (narrowest(v), v.reach()),
        };
        let lean = straw.azimuth_deg.to_radians();
        let away = -Vec3::new(lean.cos(), lean.sin(), 0.0);
        let inside = |low: f64, high: f64| {
            let foot = Vec3::new(straw.x, straw.y, 0.0);
            // |centre| + radius ≤ |foot| + gap + 2·radius ≤ inner.
            let mut radius =
                ((0.05 + 0.25 * size) * inner).min((inner - foot.length() - 0.005) / 2.0);
            let z = if high.is_finite() {
                radius = radius.min(0.45 * (high - low));
                low + radius + (high - low - 2.0 * radius) * (0.05 + 0.9 * height)
            } else {
                low + radius + 1e-3 + 0.03 * height
            };
            let centre = foot + (radius + straw.radius + 0.001) * away;
            Sphere {
                center: Vec3::new(centre.x, centre.y, z),
                radius,
                index,
            }
        };
        // Above the coin lying on the floor.
        let bottom = floor + 0.0025;
        let top = liquids.last().map_or(bottom, |l| l.top.max(bottom));
        match place {
            Place::None => None,
            Place::FirstLayer => Some(match liquids.first() {
                Some(l) => inside(bottom, l.top),
                None => inside(bottom, f64::INFINITY),
            }),
            Place::AboveTheLiquids => Some(inside(top, f64::INFINITY)),
            Place::Outside => {
                let radius = 0.005 + 0.035 * size;
                let bearing = lean + std::f64::consts::PI + 2.0 * bearing;
                let rho = reach + radius + 0.003;
                Some(Sphere {
                    center: Vec3::new(
                        rho * bearing.cos(),
                        rho * bearing.sin(),
                        -0.05 + 0.3 * height,
                    ),
                    radius,
                    index,
                })
            }
        }
    }

    /// The least radius of a container of revolution's inner profile: what the random objects
    /// inside it are sized by (its points' least radius; the wall between them stays between
    /// its points').
    fn narrowest(v: &Revolution) -> f64 {
        v.inner.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min)
    }

    /// A prism (`place` 1: inside the container, 2: outside it; else none), a triangle or a
    /// square box by `triangle`, its size, height and turn chosen by `size`, `height` and `turn`
    /// (0..1), of `index`. Inside, it stands on the floor near the wall, a quarter turn from the
    /// straw's lean on the side of +x (away from the coin; clear of the leaning straw, whose
    /// foot is within 0.4 of the inner radius of the axis, and of a sphere beside its foot);
    /// outside, it stands on the table beyond the container's widest reach in the direction of
    /// the straw's lean (the outside sphere lies at least 65° from it), below the rim's height.
    /// Dropped if it would come near the sphere.
    #[allow(clippy::too_many_arguments)]
    fn prism(
        place: u8,
        triangle: bool,
        container: &Container,
        straw: &Straw,
        sphere: Option<&Sphere>,
        (size, height, turn): (f64, f64, f64),
        index: f64,
    ) -> Option<Prism> {
        let (inner, reach, rim) = match container {
            Container::Glass(g) => (g.radius - g.wall, g.radius, g.height),
            Container::Tank(t) => (t.half_y, t.half_x.hypot(t.half_y), t.height),
            Container::Revolution(v) => (narrowest(v), v.reach(), container.height()),
        };
        let lean = straw.azimuth_deg.to_radians();
        let (centre, r, bottom, top) = match place {
            1 => {
                let r = (0.04 + 0.03 * size) * inner;
                let b = lean + std::f64::consts::FRAC_PI_2;
                let b = if b.cos() >= 0.0 {
                    b
                } else {
                    b + std::f64::consts::PI
                };
                let floor = container.floor();
                let c = 0.8 * inner * Vec3::new(b.cos(), b.sin(), 0.0);
                (c, r, floor, floor + 0.01 + (rim - floor) * height)
            }
            2 => {
                let r = 0.006 + 0.02 * size;
                let c = (reach + r + 0.003) * Vec3::new(lean.cos(), lean.sin(), 0.0);
                (c, r, 0.0, 0.01 + 0.09 * height)
            }
            _ => return None,
        };
        if let Some(s) = sphere {
            let (a, b) = (s.center, centre);
            let below = (s.center.z - s.radius > top) || (s.center.z + s.radius < bottom);
            if !below && (a.x - b.x).hypot(a.y - b.y) < s.radius + r + 0.002 {
                return None;
            }
        }
        let k = if triangle { 3 } else { 4 };
        let turn = turn * std::f64::consts::TAU;
        let corners = (0..k)
            .map(|j| {
                let a = turn + std::f64::consts::TAU * j as f64 / k as f64;
                [centre.x + r * a.cos(), centre.y + r * a.sin()]
            })
            .collect();
        Some(Prism {
            corners,
            bottom,
            top,
            index,
        })
    }

    /// A lens, if `on`: biconvex or biconcave by `convex`, outside the container on the line from
    /// the observer at `eye` to the middle of the container (0, 0, 0.08), its axis towards the
    /// container, its size and distance chosen by `size` and `far` (0..1), of `index`. Dropped if
    /// its holding sphere would come near the straw, the sphere or the prism.
    #[allow(clippy::too_many_arguments)]
    fn lens(
        on: bool,
        convex: bool,
        container: &Container,
        straw: &Straw,
        sphere: Option<&Sphere>,
        prism: Option<&Prism>,
        eye: Vec3,
        (size, far): (f64, f64),
        index: f64,
    ) -> Option<Lens> {
        if !on {
            return None;
        }
        let reach = container.reach();
        let target = Vec3::new(0.0, 0.0, 0.08);
        let diameter = 0.015 + 0.025 * size;
        let (radius1, radius2, thickness) = if convex {
            let r = 0.04 + 0.04 * far;
            let sag = r - (r * r - diameter * diameter / 4.0).sqrt();
            (r, -r, 2.0 * sag + 0.002)
        } else {
            let r = -(0.03 + 0.04 * size);
            (r, -r, 0.0015)
        };
        let mut l = Lens {
            center: target,
            axis: target - eye,
            radius1,
            radius2,
            thickness,
            diameter,
            index,
        };
        let held = l.reach();
        let flat = (eye - target).truncate().length();
        let rho = reach + held + 0.004 + 0.1 * far;
        l.center = target + (rho / flat) * (eye - target);
        // The straw's axis, from its foot up.
        let (tilt, az) = (straw.tilt_deg.to_radians(), straw.azimuth_deg.to_radians());
        let foot = Vec3::new(straw.x, straw.y, container.floor());
        let up = Vec3::new(tilt.sin() * az.cos(), tilt.sin() * az.sin(), tilt.cos());
        let along = (l.center - foot).dot(up).clamp(0.0, straw.length);
        if (foot + along * up - l.center).length() < held + straw.radius + 0.003 {
            return None;
        }
        if let Some(s) = sphere {
            if (s.center - l.center).length() < s.radius + held + 0.002 {
                return None;
            }
        }
        if let Some(p) = prism {
            let near = p
                .corners
                .iter()
                .any(|c| (Vec3::new(c[0], c[1], l.center.z) - l.center).length() < held + 0.03);
            if near && l.center.z - held < p.top + 0.002 {
                return None;
            }
        }
        Some(l)
    }

    /// A random scene of every kind the format allows (glass or tank, thick or thin, up to three
    /// layers, leaning straws, a coin, a card, a sphere in a liquid, in the air inside the
    /// container or outside it), kept when the format's rules accept it.
    fn scene() -> impl Strategy<Value = SceneDescription> {
        any_scene().prop_filter("the format's rules", |d| d.validate().is_ok())
    }

    /// [`scene`]'s scenes before the format's rules are asked.
    fn any_scene() -> impl Strategy<Value = SceneDescription> {
        (
            (
                0u8..3,
                0.03f64..0.06,
                0.12f64..0.22,
                0.0f64..0.004,
                0.0f64..0.01,
            ),
            (
                1.0f64..1.8,
                prop::collection::vec((1.0f64..2.0, 0.1f64..1.0), 0..4),
            ),
            (0.0f64..1.0, 0.0f64..6.3, 0.0f64..35.0, 0.0f64..360.0),
            (any::<bool>(), any::<bool>(), 0.0f64..6.3),
            (
                prop_oneof![
                    Just(Place::None),
                    Just(Place::FirstLayer),
                    Just(Place::AboveTheLiquids),
                    Just(Place::Outside),
                ],
                (0.0f64..1.0, 0.0f64..1.0, -1.0f64..1.0),
                1.0f64..2.0,
            ),
            (
                prop_oneof![Just(0u8), Just(1u8), Just(2u8)],
                any::<bool>(),
                (0.0f64..1.0, 0.0f64..1.0, 0.0f64..1.0),
                1.0f64..2.0,
            ),
            (
                any::<bool>(),
                any::<bool>(),
                (0.0f64..1.0, 0.0f64..1.0),
                1.0f64..2.0,
            ),
        )
            .prop_map(
                |(
                    (kind, r, h, wall, bottom),
                    (glass_n, layers),
                    (sr, sa, tilt, az),
                    (coin, card, oa),
                    (place, (size, height, bearing), sphere_n),
                    (prism_place, triangle, prism_shape, prism_n),
                    (lens_on, convex, lens_shape, lens_n),
                )| {
                    let tank = kind == 0;
                    let container = match kind {
                        0 => Container::Tank(Tank {
                            half_x: r * 1.6,
                            half_y: r,
                            height: h,
                        }),
                        1 => Container::Glass(Glass {
                            radius: r,
                            height: h,
                            wall,
                            bottom,
                            index: glass_n,
                        }),
                        // A tumbler that widens, bulges a little at mid-height, and narrows to
                        // its rim: three quadrics of revolution a side, walls at least 1 mm.
                        _ => {
                            let w = wall + 0.001;
                            let outer = vec![[0.8 * r, 0.0], [1.05 * r, 0.5 * h], [r, h]];
                            let inner =
                                vec![[0.8 * r - w, bottom], [1.05 * r - w, 0.5 * h], [r - w, h]];
                            Container::Revolution(Revolution {
                                outer,
                                inner,
                                index: glass_n,
                            })
                        }
                    };
                    let floor = container.floor();
                    // Tops rising from the floor to the rim.
                    let mut top = floor;
                    let room = h - floor;
                    let total: f64 = layers.iter().map(|l| l.1).sum::<f64>().max(1e-9);
                    let liquids: Vec<Liquid> = layers
                        .iter()
                        .enumerate()
                        .map(|(k, &(n, share))| {
                            top += 0.95 * room * share / total;
                            Liquid {
                                name: format!("liquid {k}"),
                                index: n,
                                top,
                                tint: None,
                            }
                        })
                        .collect();
                    let inner = match &container {
                        Container::Revolution(v) => narrowest(v),
                        _ if tank => r,
                        _ => r - wall,
                    };
                    let straw = Straw {
                        x: 0.4 * inner * sr * sa.cos(),
                        y: 0.4 * inner * sr * sa.sin(),
                        tilt_deg: tilt,
                        azimuth_deg: az,
                        radius: 0.004,
                        length: 0.2,
                    };
                    let coins = if coin {
                        vec![Coin {
                            x: -0.6 * inner,
                            y: 0.0,
                            radius: 0.2 * inner,
                            thickness: 0.002,
                        }]
                    } else {
                        vec![]
                    };
                    let cards = if card {
                        vec![Card {
                            center: Vec3::new(-0.3, 0.0, 0.1),
                            facing_deg: 0.0,
                            width: 0.12,
                            height: 0.06,
                            picture: Picture::Arrow,
                        }]
                    } else {
                        vec![]
                    };
                    let spheres: Vec<Sphere> = sphere(
                        place, &container, &liquids, &straw, size, height, bearing, sphere_n,
                    )
                    .into_iter()
                    .collect();
                    let prisms: Vec<Prism> = prism(
                        prism_place,
                        triangle,
                        &container,
                        &straw,
                        spheres.first(),
                        prism_shape,
                        prism_n,
                    )
                    .into_iter()
                    .collect();
                    let d = 0.4;
                    let eye = Vec3::new(d * oa.cos(), d * oa.sin(), 0.15);
                    let lenses = lens(
                        lens_on,
                        convex,
                        &container,
                        &straw,
                        spheres.first(),
                        prisms.first(),
                        eye,
                        lens_shape,
                        lens_n,
                    )
                    .into_iter()
                    .collect();
                    SceneDescription {
                        container,
                        liquids,
                        straws: vec![straw],
                        coins,
                        cards,
                        spheres,
                        prisms,
                        lenses,
                        observer: Some(Observer {
                            position: eye,
                            target: Vec3::new(0.0, 0.0, 0.08),
                        }),
                        sun: None,
                        lesson: None,
                        dispersion: vec![],
                    }
                },
            )
    }

    /// The solids cost the random scenes nothing: a scene drawn with a sphere, a prism or a lens
    /// is refused only where it would be without it (leaning straws through the wall are the
    /// usual reason), so proptest's rejections stay as they were; and valid scenes hold spheres
    /// in each place (in a liquid, in the air inside the container, in the air outside it) and
    /// each kind of container.
    #[test]
    fn the_random_spheres_break_no_rule_and_lie_everywhere() {
        use proptest::strategy::ValueTree;
        use proptest::test_runner::{Config, TestRng, TestRunner};
        let mut runner = TestRunner::new_with_rng(
            Config::default(),
            TestRng::deterministic_rng(Default::default()),
        );
        let strategy = any_scene();
        let (n, mut valid, mut places) = (2000, 0, [0; 4]);
        let (mut prisms, mut lenses, mut kinds) = ([0; 2], 0, [0; 3]);
        for _ in 0..n {
            let d = strategy.new_tree(&mut runner).expect("a scene").current();
            let bare = SceneDescription {
                spheres: vec![],
                prisms: vec![],
                lenses: vec![],
                ..d.clone()
            };
            let ok = d.validate().is_ok();
            assert_eq!(
                ok,
                bare.validate().is_ok(),
                "{:?} {:?} {:?}: {:?}",
                d.spheres,
                d.prisms,
                d.lenses,
                d.validate()
            );
            if !ok {
                continue;
            }
            valid += 1;
            let place = d.spheres.first().map_or(0, |s| {
                if !s.inside(&d.container) {
                    3
                } else if index_around(&d, s.center) == 1.0 {
                    2
                } else {
                    1
                }
            });
            places[place] += 1;
            for p in &d.prisms {
                prisms[usize::from(!p.inside(&d.container))] += 1;
            }
            lenses += d.lenses.len();
            kinds[match d.container {
                Container::Tank(_) => 0,
                Container::Glass(_) => 1,
                Container::Revolution(_) => 2,
            }] += 1;
        }
        eprintln!(
            "{valid} of {n} valid; no sphere, in a liquid, in air inside, outside: {places:?}; \
             prisms inside, outside: {prisms:?}; lenses: {lenses}; tanks, glasses, of \
             revolution: {kinds:?}"
        );
        assert!(kinds.iter().all(|&k| k * 5 >= valid), "{kinds:?}");
        assert!(prisms.iter().all(|&k| k * 10 >= valid), "{prisms:?}");
        assert!(lenses * 10 >= valid, "{lenses} lenses");
        assert!(valid * 10 >= n * 4, "{valid} of {n} valid");
        assert!(places.iter().all(|&k| k * 10 >= valid), "{places:?}");
    }

    /// The refractive index at `p`, read off the description's geometry alone (nothing of the
    /// library's media or boundaries): a solid's inside it (a sphere, a prism, a lens), else the
    /// container's material, the layer whose span holds `p`'s height inside the cavity, air
    /// elsewhere.
    fn index_at(d: &SceneDescription, p: Vec3) -> f64 {
        if let Some(s) = d
            .spheres
            .iter()
            .find(|s| (p - s.center).length() < s.radius)
        {
            return s.index;
        }
        if let Some(s) = d.prisms.iter().find(|s| in_prism(s, p)) {
            return s.index;
        }
        if let Some(s) = d.lenses.iter().find(|s| in_lens(s, p)) {
            return s.index;
        }
        index_around(d, p)
    }

    /// Whether `p` is inside the prism: between its bottom and top, and on the same side of
    /// every edge of its convex polygon (listed in either order).
    fn in_prism(s: &Prism, p: Vec3) -> bool {
        if p.z <= s.bottom || p.z >= s.top {
            return false;
        }
        let k = s.corners.len();
        let sides: Vec<f64> = (0..k)
            .map(|j| {
                let (a, b) = (s.corners[j], s.corners[(j + 1) % k]);
                (b[0] - a[0]) * (p.y - a[1]) - (b[1] - a[1]) * (p.x - a[0])
            })
            .collect();
        sides.iter().all(|&c| c > 0.0) || sides.iter().all(|&c| c < 0.0)
    }

    /// Whether `p` is inside the lens: within its diameter of its axis, its axial coordinate `w`
    /// (from the centre) between face 1 (−t/2 + sag(R1, ρ)) and face 2 (t/2 + sag(R2, ρ)).
    fn in_lens(s: &Lens, p: Vec3) -> bool {
        let sag = |r: f64, rho: f64| {
            if r == 0.0 {
                0.0
            } else {
                r - r.signum() * (r * r - rho * rho).sqrt()
            }
        };
        let a = s.axis / s.axis.length();
        let v = p - s.center;
        let w = v.dot(a);
        let rho = (v - w * a).length();
        rho < s.diameter / 2.0
            && w > -s.thickness / 2.0 + sag(s.radius1, rho)
            && w < s.thickness / 2.0 + sag(s.radius2, rho)
    }

    /// The refractive index at `p` were there no spheres.
    fn index_around(d: &SceneDescription, p: Vec3) -> f64 {
        let cavity = |z: f64| {
            d.liquids
                .iter()
                .find(|l| z < l.top)
                .map_or(1.0, |l| l.index)
        };
        match &d.container {
            Container::Glass(g) => {
                let r = p.x.hypot(p.y);
                if p.z < 0.0 || p.z > g.height || r > g.radius {
                    1.0
                } else if r > g.radius - g.wall || p.z < g.bottom {
                    g.index
                } else {
                    cavity(p.z)
                }
            }
            Container::Tank(t) => {
                if p.z < 0.0 || p.z > t.height || p.x.abs() > t.half_x || p.y.abs() > t.half_y {
                    1.0
                } else {
                    cavity(p.z)
                }
            }
            Container::Revolution(v) => {
                let r = p.x.hypot(p.y);
                let radius =
                    |points: &[[f64; 2]]| profile::radius_at(&profile::pieces(points), p.z);
                match (radius(&v.outer), radius(&v.inner)) {
                    (Some(outer), _) if r > outer => 1.0,
                    (None, _) => 1.0,
                    (Some(_), Some(inner)) if r < inner => cavity(p.z),
                    // Above the rim's ring only air; within the wall, or below the floor, glass.
                    _ => v.index,
                }
            }
        }
    }

    /// Points to aim at: `n` spread evenly over the box `lo..hi` (the world's), and 60 more over
    /// the box around each solid (sphere, prism, lens), so that small solids are met too.
    fn aims(d: &SceneDescription, lo: Vec3, hi: Vec3, n: u32) -> Vec<Vec3> {
        let spread = |k: u32| {
            let f = |m: f64| (k as f64 * m).fract();
            Vec3::new(f(0.618034), f(0.7548777), f(0.5698403))
        };
        let mut aims: Vec<Vec3> = (0..n).map(|k| lo + spread(k) * (hi - lo)).collect();
        for s in &d.spheres {
            aims.extend((0..60).map(|k| s.center + 2.0 * s.radius * (spread(k) - 0.5)));
        }
        for s in &d.prisms {
            let (x0, x1, y0, y1) = s.corners.iter().fold(
                (f64::MAX, f64::MIN, f64::MAX, f64::MIN),
                |(x0, x1, y0, y1), c| (x0.min(c[0]), x1.max(c[0]), y0.min(c[1]), y1.max(c[1])),
            );
            let (a, b) = (Vec3::new(x0, y0, s.bottom), Vec3::new(x1, y1, s.top));
            // Not spread(0), the box's corner: a ray through a prism's corner is left out.
            aims.extend((1..61).map(|k| a + spread(k) * (b - a)));
        }
        for s in &d.lenses {
            let r = s.reach();
            aims.extend((0..60).map(|k| s.center + 2.0 * r * (spread(k) - 0.5)));
        }
        aims
    }

    /// A random scene in which media share an index: the glass's index is a liquid's (the
    /// "vanishing glass"), or 1; a layer has the index of the one below, or 1; the sphere has
    /// the index of what is around it (a vanishing ball).
    fn equal_index_scene() -> impl Strategy<Value = SceneDescription> {
        (scene(), 0usize..5).prop_map(|(mut d, how)| {
            let first = d.liquids.first().map_or(1.0, |l| l.index);
            match (how, &mut d.container) {
                (0, Container::Glass(g)) => g.index = first,
                (1, Container::Glass(g)) => g.index = 1.0,
                (0, Container::Revolution(v)) => v.index = first,
                (1, Container::Revolution(v)) => v.index = 1.0,
                _ => {}
            }
            let k = d.liquids.len();
            if how == 2 && k >= 2 {
                d.liquids[k - 1].index = d.liquids[k - 2].index;
            }
            if how == 3 && k >= 1 {
                d.liquids[k - 1].index = 1.0;
            }
            if how == 4 {
                if let Some(c) = d.spheres.first().map(|s| s.center) {
                    d.spheres[0].index = index_around(&d, c);
                }
            }
            d
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(60))]

        /// Where media share an index they are one medium: at every event, from beside, above
        /// and below, the indices on the two sides are those of the description's geometry just
        /// before and just beyond the event point (never a stale medium's after a face between
        /// equal indices was crossed), and no event lies between equal indices.
        #[test]
        fn equal_indices_are_one_medium(d in equal_index_scene()) {
            let world = World::new(&d, 10).expect("a valid scene");
            let (lo, hi) = world.bounds();
            let mut checked = 0;
            for observer in [
                d.observer.unwrap().position,
                Vec3::new(0.01, 0.02, 0.45),
                Vec3::new(0.06, -0.01, -0.25),
            ] {
                for aim in aims(&d, lo, hi, 300) {
                    let (_, events) = trace_events(&world, ray_to(observer, aim));
                    for e in events {
                        prop_assert!(e.n1 != e.n2, "an event between equal indices: {:?}", e);
                        // A sphere of the index around it is no sphere: nothing happens on it.
                        for s in &d.spheres {
                            if s.index == index_around(&d, s.center) {
                                let off = ((e.point - s.center).length() - s.radius).abs();
                                prop_assert!(off > 1e-9, "an event on a vanished sphere: {:?}", e);
                            }
                        }
                        if e.incoming.dot(e.normal).abs() < 1e-6 {
                            continue;
                        }
                        let at = |s: f64| index_at(&d, e.point + s * e.incoming);
                        // Near an edge of two regions (a rim, a corner) the sides are not told
                        // by one step: such events are left out.
                        let t1 = if e.normal.z.abs() < 0.9 { Vec3::Z } else { Vec3::X };
                        let t1 = e.normal.cross(t1).normalize();
                        let t2 = e.normal.cross(t1);
                        let near_edge = [-1e-7, 1e-7].iter().any(|&s| {
                            [t1, -t1, t2, -t2].iter().any(|&t| {
                                index_at(&d, e.point + s * e.incoming + 1e-6 * t) != at(s)
                            })
                        });
                        if near_edge {
                            continue;
                        }
                        prop_assert_eq!((e.n1, e.n2), (at(-1e-7), at(1e-7)), "{:?}", e);
                        checked += 1;
                    }
                }
            }
            prop_assert!(checked > 0 || !world.refracts() || world.boundaries().is_empty());
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(40))]

        /// In any valid scene: Snell or total reflection at every event, Fresnel weights that add
        /// up to 1, and with every index 1 every image point on its object.
        #[test]
        fn any_valid_scene_obeys_the_laws(d in scene()) {
            let world = World::new(&d, 10).expect("a valid scene");
            let observer = d.observer.unwrap().position;
            let (lo, hi) = world.bounds();
            for aim in aims(&d, lo, hi, 200) {
                let ray = ray_to(observer, aim);
                let (_, events) = trace_events(&world, ray);
                for e in events {
                    let (si, so) = (sine(e.incoming, e.normal), sine(e.outgoing, e.normal));
                    if e.totally_reflected {
                        prop_assert!(e.n1 * si > e.n2 * (1.0 - 1e-12));
                    } else {
                        prop_assert!((e.n1 * si - e.n2 * so).abs() < 1e-12, "{:?}", e);
                    }
                }
                let mut rest = 0.0;
                let w = world.trace_fresnel(ray, 1e-6, |_, x| rest += x);
                prop_assert!((w.iter().sum::<f64>() + rest - 1.0).abs() < 1e-12);
            }
            let flat = World::new(&without_refraction(d.clone()), 10).expect("a valid scene");
            let cloud = sample_image(&flat, observer, 1500, &|_| {});
            for p in &cloud.points {
                prop_assert!((p.position - p.straw_point).length() < 1e-9);
            }
        }
    }
}

/// A description changed in code past its rules (its fields are public) makes no world: it is
/// refused as the same file would be.
#[test]
fn a_description_changed_past_its_rules_makes_no_world() {
    let mut d = gallery("leaning-straw.toml");
    assert!(World::new(&d, 10).is_ok());
    d.straws[0].x = 1.0; // outside the glass
    let e = World::new(&d, 10).expect_err("refused");
    assert!(e.to_string().contains("straw[1]"), "{e}");
    d.straws[0].x = f64::NAN;
    assert!(World::new(&d, 10).is_err());
}
