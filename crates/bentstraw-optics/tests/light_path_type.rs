//! The kind of light path: entry face and total reflections, on rays whose path is known.

use bentstraw_optics::geometry::Ray;
use bentstraw_optics::light_path_type::{Entry, LightPathType};
use bentstraw_optics::scene::Scene;
use bentstraw_optics::world::World;
use bentstraw_optics::Vec3;

fn kind(scene: &Scene, from: Vec3, to: Vec3) -> (u8, LightPathType) {
    let (outcome, kind) = World::assignment(scene).trace_path_type(Ray::new(from, to - from));
    (outcome.color(), kind)
}

#[test]
fn entry_faces_of_rays_with_known_paths() {
    let scene = Scene::with_defaults(0.0, 0.0, 0.15).unwrap();
    // Straight down the axis from above the straw: its top cap, in air.
    let (c, k) = kind(&scene, Vec3::new(0.0, 0.0, 0.4), Vec3::new(0.0, 0.0, 0.0));
    assert_eq!((c, k), (5, LightPathType::DIRECT));
    // Horizontally at mid-water height, aimed at the axis: through the wall.
    let (c, k) = kind(&scene, Vec3::new(0.3, 0.0, 0.07), Vec3::new(0.0, 0.0, 0.07));
    assert_eq!((c, k.entry, k.total_reflections), (2, Entry::Wall, 0));
    // From above the glass, down through the water's surface beside the straw: through the top
    // (refraction bends it towards the vertical, so it meets the straw above where it was aimed).
    let (c, k) = kind(&scene, Vec3::new(0.02, 0.0, 0.3), Vec3::new(0.0, 0.0, 0.01));
    assert_eq!((c, k.entry, k.total_reflections), (2, Entry::Top, 0));
    // From below the glass, up towards the straw's bottom: through the bottom? No: the straw's
    // bottom cap lies on z = 0 itself, so aim beside it and let refraction carry the ray in.
    let (c, k) = kind(&scene, Vec3::new(0.0, 0.0, -0.2), Vec3::new(0.0, 0.0, 0.0));
    assert_eq!((c, k), (1, LightPathType::DIRECT));
    let (_, k) = kind(
        &scene,
        Vec3::new(0.03, 0.0, -0.2),
        Vec3::new(0.01, 0.0, 0.0),
    );
    assert_eq!(k.entry, Entry::Bottom);
}

#[test]
fn total_reflections_are_counted() {
    // Seen from below at a steep angle through the bottom, a ray reaching the wall from inside at
    // more than the critical angle (48.6°) is totally reflected there.
    let scene = Scene::with_defaults(0.02, 0.01, 0.2).unwrap();
    let observer = Vec3::new(0.1, 0.0, -0.1);
    let world = World::assignment(&scene);
    let mut seen = 0;
    for i in 0..400 {
        for j in 0..400 {
            let target = Vec3::new(
                -0.04 + 0.08 * i as f64 / 399.0,
                -0.04 + 0.08 * j as f64 / 399.0,
                0.0,
            );
            let ray = Ray::new(observer, target - observer);
            let mut events = Vec::new();
            let outcome = world.trace_with(ray, |e| events.push(*e));
            let (o2, k) = world.trace_path_type(ray);
            assert_eq!(outcome, o2);
            let tir = events.iter().filter(|e| e.totally_reflected).count() as u32;
            assert_eq!(k.total_reflections, tir);
            if outcome.color() > 0 && tir > 0 {
                seen += 1;
                assert_eq!(k.entry, Entry::Bottom);
                assert!(k.key().starts_with("bottom+"), "{}", k.key());
                assert!(k.to_string().contains("total reflection"), "{k}");
            }
        }
    }
    assert!(
        seen > 0,
        "some rays through the bottom reach the straw after a total reflection"
    );
}

#[test]
fn words_and_keys() {
    let k = LightPathType {
        entry: Entry::Wall,
        total_reflections: 2,
    };
    assert_eq!(k.key(), "wall+2");
    assert_eq!(k.to_string(), "through the side wall, 2 total reflections");
    assert_eq!(LightPathType::DIRECT.key(), "direct");
}

#[test]
fn each_kind_of_path_has_one_colour_of_its_own_in_every_figure() {
    let mut kinds = vec![LightPathType::DIRECT];
    for entry in [Entry::Top, Entry::Wall, Entry::Bottom] {
        for total_reflections in 0..=3 {
            kinds.push(LightPathType {
                entry,
                total_reflections,
            });
        }
    }
    // Different kinds, different colours, far enough apart to tell (at least 40 of 255 in
    // some channel).
    for (i, a) in kinds.iter().enumerate() {
        for b in &kinds[..i] {
            let (ca, cb) = (a.rgb(), b.rgb());
            let gap = (0..3).map(|c| ca[c].abs_diff(cb[c])).max().unwrap();
            assert!(gap >= 20, "{a} {ca:?} and {b} {cb:?}");
        }
    }
    // Fixed, not ranked by share: the same kind is the same colour whatever else is seen.
    let wall = LightPathType {
        entry: Entry::Wall,
        total_reflections: 0,
    };
    assert_eq!(wall.hex(), "#ff7f0e");
    assert_eq!(LightPathType::DIRECT.hex(), "#464646");
    let twice = LightPathType {
        entry: Entry::Wall,
        total_reflections: 2,
    };
    // A further reflection darkens the reflected hue.
    assert!(twice
        .rgb()
        .iter()
        .zip(
            LightPathType {
                total_reflections: 1,
                ..twice
            }
            .rgb()
        )
        .all(|(a, b)| *a <= b));
}
