//! The rainbow: Descartes' construction traced through a water drop by the pictures' own tracer
//! gives, at every wavelength, the bows of the closed form: for light leaving after `k`
//! reflections inside a sphere of index `n`, the stationary ray enters at `i` with
//! `cos² i = (n² − 1) / ((k + 1)² − 1)`, is refracted to `r = asin(sin i / n)`, and is turned by
//! `D = 2(i − r) + k(180° − 2r)`: 42.3° from the antisolar point in red and 40.6° in violet for
//! the first bow, 50° to 54° for the second, Alexander's dark band between.

use bentstraw_optics::rainbow::{bow_angle, deviation_curves, drop_world};
use bentstraw_optics::scene_file::SceneDescription;

const DROP: &str = r#"
[container]
shape = "glass"
radius = 0.01
height = 0.01

[[sphere]]
center = [0.3, 0.0, 0.5]
radius = 0.02
material = "water"
"#;

/// Descartes' closed form: the bow's angle from the antisolar point (degrees) and its impact
/// parameter, for `k` reflections inside a sphere of index `n`.
fn descartes(n: f64, k: u32) -> (f64, f64) {
    let k = k as f64;
    let cos2 = (n * n - 1.0) / ((k + 1.0) * (k + 1.0) - 1.0);
    let i = cos2.sqrt().acos();
    let r = (i.sin() / n).asin();
    let turned = (2.0 * (i - r) + k * (std::f64::consts::PI - 2.0 * r)).to_degrees();
    // The angle between the sunlight and the light leaving, folded to 0°–180°, from the
    // antisolar point.
    let between = turned.rem_euclid(360.0);
    let between = between.min(360.0 - between);
    (180.0 - between, i.sin())
}

#[test]
fn each_wavelength_bows_where_descartes_says() {
    let d = SceneDescription::from_toml(DROP).unwrap();
    let nms = [404.7, 450.0, 486.1, 546.1, 587.56, 656.3, 700.0, 750.0];
    for k in [1, 2] {
        let curves = deviation_curves(&d, 0, k, &nms).unwrap();
        for c in &curves {
            let (angle, b) = descartes(c.index, k);
            eprintln!("{} nm, k = {k}: n = {:.5}, traced {:.4}° at b = {:.5}, closed form {angle:.4}° at {b:.5}", c.nm, c.index, c.bow[1], c.bow[0]);
            assert!(
                (c.bow[1] - angle).abs() < 1e-6,
                "{} nm: {} against {angle}",
                c.nm,
                c.bow[1]
            );
            assert!(
                (c.bow[0] - b).abs() < 1e-4,
                "{} nm: b {} against {b}",
                c.nm,
                c.bow[0]
            );
            // Every traced ray lies on the bow's side: inside the first bow, outside the others.
            for p in &c.points {
                if k == 1 {
                    assert!(p[1] <= c.bow[1] + 1e-9);
                } else {
                    assert!(p[1] >= c.bow[1] - 1e-9);
                }
            }
        }
        // Red outside violet in the first bow, inside it in the second.
        // The violet mercury line (404.7 nm) and the red hydrogen C line (656.3 nm).
        let (violet, red) = (curves[0].bow[1], curves[5].bow[1]);
        if k == 1 {
            assert!(
                (red - 42.3).abs() < 0.1 && (violet - 40.6).abs() < 0.15,
                "{red} {violet}"
            );
        } else {
            assert!(
                red > 50.0 && red < 51.0 && violet > 53.0 && violet < 54.0,
                "{red} {violet}"
            );
        }
    }
}

/// At each impact parameter, the traced angle is the closed form's for that ray: in at `i` with
/// `sin i = b`, out turned by `2(i − r) + k(180° − 2r)`.
#[test]
fn every_ray_turns_as_snell_and_reflection_say() {
    let d = SceneDescription::from_toml(DROP).unwrap();
    let (world, centre, radius) = drop_world(&d, 0, 656.3).unwrap();
    let n = d
        .law(bentstraw_optics::scene_file::Medium::Sphere(0))
        .unwrap()
        .index_at(656.3);
    for k in [1, 2, 3] {
        for j in 1..50 {
            let b = j as f64 / 50.0;
            let (i, r) = (b.asin(), (b / n).asin());
            let turned = (2.0 * (i - r) + k as f64 * (std::f64::consts::PI - 2.0 * r)).to_degrees();
            let between = turned.rem_euclid(360.0);
            let want = 180.0 - between.min(360.0 - between);
            let got = bow_angle(&world, centre, radius, b, k).unwrap();
            assert!(
                (got - want).abs() < 1e-7,
                "k = {k}, b = {b}: {got} against {want}"
            );
        }
    }
}
