//! The rules a valid simulation obeys, and the geometry helpers of the scene.

use bentstraw_optics::scene::{section_at, Scene, SceneError, REFERENCES};
use bentstraw_optics::world::World;
use bentstraw_optics::Vec3;

#[test]
fn the_reference_simulations_are_valid() {
    for r in REFERENCES {
        let scene = Scene::with_defaults(r.straw.0, r.straw.1, r.water_height).unwrap();
        scene.validate_observer(r.observer).unwrap();
    }
}

#[test]
fn invalid_scenes_are_rejected_with_a_message_naming_the_value() {
    let cases: Vec<(Result<Scene, SceneError>, &str)> = vec![
        (Scene::new(f64::NAN, 0.0, 0.1, 1.333, 10), "NaN"),
        (Scene::new(0.0, f64::INFINITY, 0.1, 1.333, 10), "inf"),
        (Scene::new(0.0, 0.0, -0.01, 1.333, 10), "-0.01"),
        (Scene::new(0.0, 0.0, 0.2000001, 1.333, 10), "0.2000001"),
        (Scene::new(0.03, 0.02, 0.1, 1.333, 10), "(0.03, 0.02)"),
        (Scene::new(0.0, 0.0, 0.1, 0.99, 10), "0.99"),
        (Scene::new(0.0, 0.0, 0.1, f64::NAN, 10), "NaN"),
        (Scene::new(0.0, 0.0, 0.1, 1.333, 0), "0"),
        (Scene::new(0.0, 0.0, 0.1, 1.333, 1001), "1001"),
    ];
    for (result, value) in cases {
        let e = result.expect_err(value);
        assert!(e.to_string().contains(value), "'{e}' does not name {value}");
    }
    // The limits themselves are allowed.
    Scene::new(0.035, 0.0, 0.0, 1.0, 1).unwrap();
    Scene::new(0.0, -0.035, 0.2, 1.333, 1000).unwrap();
}

#[test]
fn observers_in_or_on_the_glass_or_in_the_straw_are_rejected() {
    let scene = Scene::with_defaults(0.02, 0.01, 0.15).unwrap();
    for bad in [
        Vec3::new(0.0, 0.0, 0.1),
        Vec3::new(0.04, 0.0, 0.0),   // on the wall, at the bottom
        Vec3::new(0.0, 0.04, 0.2),   // on the rim
        Vec3::new(0.02, 0.01, 0.22), // in the straw above the glass
        Vec3::new(0.02, 0.01, 0.25), // on its top cap
        Vec3::new(f64::NAN, 0.0, 1.0),
    ] {
        assert!(scene.validate_observer(bad).is_err(), "{bad}");
    }
    for good in [
        Vec3::new(0.0, 0.0, 0.3),    // above
        Vec3::new(0.0, 0.0, -0.01),  // below
        Vec3::new(0.041, 0.0, 0.1),  // just outside the wall
        Vec3::new(0.0, 0.0, 0.21),   // above the glass, beside the straw
        Vec3::new(0.02, 0.01, 0.26), // above the straw
    ] {
        assert!(scene.validate_observer(good).is_ok(), "{good}");
    }
}

#[test]
fn sections_are_five_equal_bands_from_the_bottom() {
    assert_eq!(section_at(0.0), 1);
    assert_eq!(section_at(0.0499999), 1);
    assert_eq!(section_at(0.05), 2);
    assert_eq!(section_at(0.1), 3);
    assert_eq!(section_at(0.15), 4);
    assert_eq!(section_at(0.2), 5);
    assert_eq!(
        section_at(0.25),
        5,
        "the top edge belongs to the top section"
    );
}

#[test]
fn distance_to_the_straw_surface() {
    let scene = Scene::with_defaults(0.0, 0.0, 0.1).unwrap();
    assert!(
        (World::assignment(&scene).distance_to_objects(Vec3::new(0.005, 0.0, 0.1))).abs() < 1e-15
    );
    assert!(
        (World::assignment(&scene).distance_to_objects(Vec3::new(0.015, 0.0, 0.1)) - 0.01).abs()
            < 1e-15
    );
    assert!(
        (World::assignment(&scene).distance_to_objects(Vec3::new(0.0, 0.0, 0.3)) - 0.05).abs()
            < 1e-15
    );
    assert!(
        (World::assignment(&scene).distance_to_objects(Vec3::new(0.0, 0.0, 0.1)) - 0.005).abs()
            < 1e-15
    );
    assert!(
        (World::assignment(&scene).distance_to_objects(Vec3::new(0.008, 0.0, -0.004)) - 0.005)
            .abs()
            < 1e-15
    );
}

/// Messages quote numbers so that they show why a rule fails, and never at absurd length.
#[test]
fn messages_quote_numbers_short_and_exact() {
    use bentstraw_optics::text::{clip_text, number_text};
    assert_eq!(number_text(-1e-320), "-1e-320");
    assert_eq!(number_text(0.15), "0.15");
    // Just past the rule: the digits show that the sum exceeds 0.04.
    let e = Scene::with_defaults(0.0350000001, 0.0, 0.1)
        .unwrap_err()
        .to_string();
    assert!(e.contains("(it is 0.04000000009"), "{e}");
    let e = Scene::with_defaults(0.0, 0.0, -1e-320)
        .unwrap_err()
        .to_string();
    assert!(e.len() < 120 && e.contains("-1e-320"), "{e}");
    let long = "9".repeat(5000);
    let clipped = clip_text(&long, 40);
    assert_eq!(clipped.chars().count(), 40);
    assert!(clipped.ends_with('…'));
}
