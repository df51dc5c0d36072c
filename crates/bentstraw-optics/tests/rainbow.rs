//! The rainbow: Descartes' construction traced through a water drop by the pictures' own tracer
//! gives, at every wavelength, the bows of the closed form: for light leaving after `k`
//! reflections inside a sphere of index `n`, the stationary ray enters at `i` with
//! `cos² i = (n² − 1) / ((k + 1)² − 1)`, is refracted to `r = asin(sin i / n)`, and is turned by
//! `D = 2(i − r) + k(180° − 2r)`: 42.3° from the antisolar point in red and 40.6° in violet for
//! the first bow, 50° to 54° for the second, Alexander's dark band between. The same rays are
//! traced again by the double-double tracer of the tests (nothing shared but the drop's
//! numbers), every branch leaving the drop compared.

#[path = "support/spheres.rs"]
mod spheres;

use bentstraw_optics::geometry::Ray;
use bentstraw_optics::rainbow::{bow_angle, deviation_curves, drop_world};
use bentstraw_optics::scene::DEFAULT_MAX_EVENTS;
use bentstraw_optics::scene_file::SceneDescription;
use bentstraw_optics::spectrum::white_bands;
use bentstraw_optics::Vec3;
use spheres::{Ball, Balls};

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
    let drop = drop_world(&d, 0, 656.3).unwrap();
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
            let got = bow_angle(&drop.world, drop.centre, drop.radius, b, k).unwrap();
            assert!(
                (got - want).abs() < 1e-7,
                "k = {k}, b = {b}: {got} against {want}"
            );
        }
    }
}

/// The gallery's drop, seen level with the sun 42° high behind the eye, in white light: a white
/// glint high on the drop (the sun reflected by its front), and near its bottom the first bow's
/// glint, red above violet, then the second bow's, violet above red; in one colour neither glint
/// has both ends of the spectrum.
#[test]
fn the_drop_glints_with_both_bows_their_colours_reversed() {
    use bentstraw_optics::camera::Camera;
    use bentstraw_optics::setup::{SceneValues, Setup};
    use bentstraw_optics::shading::{shaded_picture, Backdrop, ShadingMode, ShadingOptions};
    let text = include_str!("../../bentstraw-io/scenes/rainbow.toml");
    let s = Setup::from_text("rainbow", text, &SceneValues::default()).unwrap();
    let (w, h) = (1024, 768);
    let target = s.target.unwrap();
    let fov = s.framing_fov(s.observer, target, w as f64 / h as f64);
    let camera = Camera::new(s.observer, target, w, h, fov);
    let picture = |white| {
        let options = ShadingOptions {
            mode: ShadingMode::Fresnel { prune_below: 1e-4 },
            backdrop: Backdrop::Checker,
            samples: 3,
            adaptive: true,
            outline: true,
            white,
        };
        let p = shaded_picture(&s.world, &camera, &options);
        // Bright pixels: (row, [r, g, b]).
        let bright: Vec<(usize, [u8; 3])> = p
            .pixels
            .chunks_exact(3)
            .enumerate()
            .filter(|(_, c)| *c.iter().max().unwrap() > 90)
            .map(|(k, c)| (k / w as usize, [c[0], c[1], c[2]]))
            .collect();
        bright
    };
    let red =
        |c: &[u8; 3]| c[0] as u32 > 2 * c[1].max(c[2]) as u32 && c[0] > c[2].saturating_add(100);
    let violet = |c: &[u8; 3]| c[2] > c[0].saturating_add(60) && c[2] > c[1].saturating_add(60);
    // The mean row of the pixels of `kind` among `glint`.
    let row = |glint: &[(usize, [u8; 3])], kind: &dyn Fn(&[u8; 3]) -> bool| {
        let rows: Vec<usize> = glint
            .iter()
            .filter(|(_, c)| kind(c))
            .map(|(r, _)| *r)
            .collect();
        assert!(!rows.is_empty(), "no such pixel in {glint:?}");
        rows.iter().sum::<usize>() as f64 / rows.len() as f64
    };
    let white = picture(true);
    // The sun's reflection, white, in the drop's upper half.
    assert!(white
        .iter()
        .any(|(r, c)| *r < h as usize / 2 && c.iter().all(|&v| v > 200)));
    // The glints near the bottom, parted where no pixel is bright.
    let low: Vec<_> = white
        .iter()
        .copied()
        .filter(|(r, _)| *r > h as usize / 2)
        .collect();
    let gap = low
        .windows(2)
        .find(|p| p[1].0 > p[0].0 + 10)
        .map(|p| p[1].0)
        .expect("two glints");
    let (first, second): (Vec<_>, Vec<_>) = low.iter().partition(|(r, _)| *r < gap);
    assert!(
        row(&first, &red) < row(&first, &violet),
        "first bow: red above violet"
    );
    assert!(
        row(&second, &violet) < row(&second, &red),
        "second bow: violet above red"
    );
    // In one colour (the d line, yellow) no pixel is red or violet.
    let one = picture(false);
    assert!(!one.is_empty());
    assert!(!one.iter().any(|(_, c)| red(c) || violet(c)), "{one:?}");
}

/// The drop in the double-double tracer: at each band's wavelength, for impact parameters across
/// the drop, the light leaving after one and two reflections leaves at the library's angle from
/// the antisolar point (within 1e-9°, where the ray is far from grazing), and the bows found on
/// the reference's own angles are the library's: the same angle (1e-9°), near the same impact
/// parameter (the angle is flat there, so `b` is known to about the square root of the
/// precision).
#[test]
fn the_drop_agrees_with_the_double_double_tracer() {
    let d = SceneDescription::from_toml(DROP).unwrap();
    for band in white_bands() {
        let drop = drop_world(&d, 0, band.nm).unwrap();
        let reference = Balls::new(
            &[Ball {
                centre: drop.centre,
                radius: drop.radius,
                index: drop.index,
            }],
            &[],
            DEFAULT_MAX_EVENTS,
        );
        // The library's rays: parallel to x, `b` radii from the line through the centre.
        let angle = |b: f64, k: u32| -> Option<(f64, f64)> {
            let ray = Ray {
                origin: drop.centre - 2.0 * drop.radius * Vec3::X + b * drop.radius * Vec3::Y,
                direction: Vec3::X,
            };
            let (escapes, margin) = reference.escapes(ray, 0.0);
            let (_, leaving, _) = escapes.into_iter().find(|e| e.0 == k + 2)?;
            Some(((-leaving.x).clamp(-1.0, 1.0).acos().to_degrees(), margin))
        };
        for k in [1, 2] {
            let mut compared = 0;
            for j in 1..60 {
                let b = j as f64 / 60.0;
                let (want, margin) = angle(b, k).expect("the reference follows the branch");
                let got = bow_angle(&drop.world, drop.centre, drop.radius, b, k).unwrap();
                if margin > 1e-9 {
                    compared += 1;
                    assert!(
                        (got - want).abs() < 1e-9,
                        "{} nm, k = {k}, b = {b}: {got} against {want}",
                        band.nm
                    );
                }
            }
            assert!(
                compared > 50,
                "{} nm, k = {k}: {compared} rays well posed",
                band.nm
            );
            // The reference's own bow, by golden section on its angles.
            let sign = if k == 1 { 1.0 } else { -1.0 };
            let f = |b: f64| sign * angle(b, k).unwrap().0;
            let (mut lo, mut hi) = (0.5, 0.99);
            let g = (5f64.sqrt() - 1.0) / 2.0;
            while hi - lo > 1e-12 {
                let (x1, x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
                if f(x1) < f(x2) {
                    lo = x1;
                } else {
                    hi = x2;
                }
            }
            let b = 0.5 * (lo + hi);
            let bow = deviation_curves(&d, 0, k, &[band.nm]).unwrap()[0].bow;
            assert!(
                (bow[1] - sign * f(b)).abs() < 1e-9,
                "{} nm, k = {k}: bow at {}° against {}°",
                band.nm,
                bow[1],
                sign * f(b)
            );
            assert!(
                (bow[0] - b).abs() < 1e-5,
                "{} nm, k = {k}: b {} against {b}",
                band.nm,
                bow[0]
            );
        }
    }
}
