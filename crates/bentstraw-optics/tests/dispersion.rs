//! Dispersion: a scene traced at one wavelength is, to the bit, the scene whose indices are its
//! laws' values there; those values are the laws as written (evaluated again here in
//! double-double arithmetic, from the coefficients alone); and a flint prism deviates each
//! wavelength by its closed form, `2·asin(n(λ)·sin(A/2)) − A` at minimum deviation, blue more
//! than red.

use bentstraw_optics::camera::Camera;
use bentstraw_optics::dispersion::{material, Dispersion, Formula, MATERIALS};
use bentstraw_optics::geometry::Ray;
use bentstraw_optics::sampling::sample_image;
use bentstraw_optics::scene_file::{Medium, SceneDescription};
use bentstraw_optics::setup::{SceneValues, Setup};
use bentstraw_optics::shading::{
    linear_to_srgb, shaded_picture, srgb_to_linear, Backdrop, RgbPicture, ShadingMode,
    ShadingOptions,
};
use bentstraw_optics::spectrum::{white_bands, WHITE_BANDS};
use bentstraw_optics::world::{Event, Outcome, World};
use bentstraw_optics::Vec3;
use twofloat::TwoFloat as T;

/// A glass of oil (Cauchy's law) in crown glass, a flint prism, a ball of Sellmeier's law and a
/// diamond lens beside it, a straw in the oil.
const DISPERSIVE: &str = r#"
[container]
shape = "glass"
radius = 0.04
height = 0.2
wall = 0.003
bottom = 0.005
material = "bk7"

[[liquid]]
name = "oil"
cauchy = [1.46, 0.0045, 0.00002]
top = 0.12

[[straw]]
x = 0.005
y = 0.01

[[prism]]
corners = [[0.06, -0.03], [0.1, -0.03], [0.08, 0.0046]]
bottom = 0.02
top = 0.09
material = "f2"

[[sphere]]
center = [0.08, 0.05, 0.05]
radius = 0.015
sellmeier = [1.5, 0.012, 0.3, 0.05, 1.0, 120.0]

[[lens]]
center = [0.0, -0.08, 0.06]
axis = [0, 1, 0]
radius1 = 0.06
radius2 = -0.06
thickness = 0.008
diameter = 0.03
material = "diamond"

[observer]
position = [0.3, -0.05, 0.15]
target = [0.03, 0.0, 0.07]
"#;

fn setup(text: &str, wavelength: Option<f64>) -> Setup {
    let values = SceneValues {
        wavelength,
        ..SceneValues::default()
    };
    Setup::from_text("dispersive.toml", text, &values).unwrap_or_else(|e| panic!("{e}"))
}

/// `text` (at most one law of each kind, one material of each name) with each law's line
/// replaced by the index it gives at `nm`, written in its shortest exact digits (which read back
/// to the same number).
fn with_indices_at(text: &str, nm: f64) -> String {
    let d = SceneDescription::from_toml(text).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    for law in &d.dispersion {
        let n = law.law.index_at(nm);
        let start = match &law.law {
            Dispersion::Cauchy(_) => "cauchy = ".to_string(),
            Dispersion::Sellmeier(_) => "sellmeier = ".to_string(),
            Dispersion::Material(m) => format!("material = \"{}\"", m.name),
        };
        let line = lines
            .iter_mut()
            .find(|l| l.starts_with(&start))
            .expect("its line");
        *line = format!("index = {n:?}");
    }
    lines.join("\n")
}

#[test]
fn a_scene_at_a_wavelength_is_the_scene_of_its_indices_there() {
    let d = SceneDescription::from_toml(DISPERSIVE).unwrap();
    let media: Vec<Medium> = d.dispersion.iter().map(|l| l.medium).collect();
    assert_eq!(
        media,
        [
            Medium::Container,
            Medium::Liquid(0),
            Medium::Sphere(0),
            Medium::Prism(0),
            Medium::Lens(0)
        ]
    );
    let mut clouds = Vec::new();
    for nm in [380.0, 450.0, 587.56, 656.27, 780.0] {
        let at = setup(DISPERSIVE, Some(nm));
        let plain = setup(&with_indices_at(DISPERSIVE, nm), None);
        assert!(!plain.description.disperses());
        // The same world, every index the same number.
        for m in &media {
            let (mut a, mut b) = (at.description.clone(), plain.description.clone());
            assert_eq!(
                a.index_mut(*m).map(|n| *n),
                b.index_mut(*m).map(|n| *n),
                "{m:?}"
            );
        }
        let eye = at.observer;
        let (p, q) = (
            sample_image(&at.world, eye, 3000, &|_| {}),
            sample_image(&plain.world, eye, 3000, &|_| {}),
        );
        assert!(p.points.len() >= 3000);
        assert!(p.points == q.points, "{nm} nm: the points differ");
        clouds.push(p.points);
    }
    // The wavelength matters: the points move from one colour to the next.
    assert!(clouds.windows(2).all(|w| w[0] != w[1]));
    // Without a wavelength, the d line.
    assert!(
        sample_image(
            &setup(DISPERSIVE, None).world,
            Vec3::new(0.3, -0.05, 0.15),
            500,
            &|_| {}
        )
        .points
            == sample_image(
                &setup(DISPERSIVE, Some(587.56)).world,
                Vec3::new(0.3, -0.05, 0.15),
                500,
                &|_| {}
            )
            .points
    );
    // The scene's text keeps its laws.
    let again = SceneDescription::from_toml(&d.to_toml()).unwrap();
    assert_eq!(again, d);
    assert!(d.to_toml().contains("material = \"f2\""));
}

/// A law evaluated in double-double from its coefficients, as its source writes it.
fn reference_index(formula: Formula<'_>, nm: f64) -> f64 {
    let um = T::from(nm) / T::from(1000.0);
    let l2 = um * um;
    let n = match formula {
        Formula::Cauchy(c) => {
            let mut n = T::from(c[0]);
            for (k, b) in c.iter().enumerate().skip(1) {
                let mut power = T::from(1.0);
                for _ in 0..k {
                    power *= l2;
                }
                n += T::from(*b) / power;
            }
            n
        }
        Formula::Sellmeier(c) => {
            let mut n2 = T::from(1.0);
            for bc in c.chunks(2) {
                n2 += T::from(bc[0]) * l2 / (l2 - T::from(bc[1]));
            }
            n2.sqrt()
        }
    };
    n.into()
}

#[test]
fn each_law_gives_its_formula_to_the_last_digits() {
    for m in MATERIALS {
        for nm in [380.0, 404.66, 486.13, 546.07, 587.56, 656.27, 706.52, 780.0] {
            let n = Dispersion::Material(m).index_at(nm);
            let want = reference_index(m.formula, nm);
            assert!(
                (n - want).abs() <= 4.0 * f64::EPSILON,
                "{} at {nm}: {n} vs {want}",
                m.name
            );
        }
    }
    for law in [
        Dispersion::Cauchy(vec![1.5, 0.004]),
        Dispersion::Cauchy(vec![1.46, 0.0045, 0.00002]),
        Dispersion::Sellmeier(vec![1.5, 0.012, 0.3, 0.05, 1.0, 120.0]),
    ] {
        for nm in [380.0, 500.0, 780.0] {
            let want = reference_index(law.formula(), nm);
            assert!((law.index_at(nm) - want).abs() <= 4.0 * f64::EPSILON);
        }
    }
}

fn trace_events(world: &World, ray: Ray) -> (Outcome, Vec<Event>) {
    let mut events = Vec::new();
    let outcome = world.trace_with(ray, |e| events.push(*e));
    (outcome, events)
}

/// Newton's prism: a 60° prism of flint glass (F2) in air, traced at the mercury, hydrogen and
/// helium lines. At each wavelength the ray entering at the closed form's angle of least
/// deviation leaves deviated by `2·asin(n(λ)·sin(A/2)) − A`, with `n(λ)` the law evaluated
/// independently; the deviation falls from violet to red, and the spread between the F and C
/// lines is the closed forms' difference.
#[test]
fn a_flint_prism_deviates_each_colour_by_its_closed_form() {
    let h = 0.1 * 3f64.sqrt() / 2.0;
    let text = format!(
        "[container]\nshape = \"glass\"\nradius = 0.01\nheight = 0.01\n\n\
         [[prism]]\ncorners = [[0.3, 0], [0.4, 0], [0.35, {h}]]\nbottom = 0.05\ntop = 0.15\n\
         material = \"f2\"\n\n[observer]\nposition = [0.1, 0.0, 0.1]\n"
    );
    let apex = std::f64::consts::PI / 3.0;
    let f2 = material("f2").unwrap().formula;
    let mut least = Vec::new();
    let mut closed_forms = Vec::new();
    for nm in [404.66, 486.13, 587.56, 656.27, 706.52] {
        let world = setup(&text, Some(nm)).world;
        let n = reference_index(f2, nm);
        let deviation = |i: f64| {
            let mid = Vec3::new(0.325, h / 2.0, 0.1);
            let theta = i - apex / 2.0;
            let d = Vec3::new(theta.cos(), theta.sin(), 0.0);
            let (outcome, events) = trace_events(&world, Ray::new(mid - 0.2 * d, d));
            assert_eq!(events.len(), 2, "in and out: {events:?}");
            let Outcome::Escaped { ray, .. } = outcome else {
                panic!("it leaves the scene")
            };
            d.y.atan2(d.x) - ray.direction.y.atan2(ray.direction.x)
        };
        let i_min = (n * (apex / 2.0).sin()).asin();
        let closed = 2.0 * i_min - apex;
        let traced = deviation(i_min);
        assert!(
            (traced - closed).abs() < 1e-12,
            "{nm} nm: {traced} vs {closed}"
        );
        for di in [-0.02, 0.02] {
            assert!(
                deviation(i_min + di) > traced + 1e-6,
                "{nm} nm: not the least"
            );
        }
        least.push((nm, traced.to_degrees()));
        closed_forms.push(closed.to_degrees());
    }
    // Violet is bent most, and the spread between the F and C lines is the closed forms'.
    assert!(least.windows(2).all(|w| w[0].1 > w[1].1), "{least:?}");
    let spread = least[1].1 - least[3].1;
    assert!(
        (spread - (closed_forms[1] - closed_forms[3])).abs() < 1e-9,
        "{spread}°"
    );
    // As the catalogue's dispersion says: dD = 2·sin(A/2)/cos(i)·(n_F − n_C), about 1.67°.
    assert!(spread > 1.6 && spread < 1.75, "F−C spread {spread}°");
}

#[test]
fn a_wavelength_outside_the_visible_is_refused_with_its_rule() {
    for nm in [379.9, 780.5, f64::NAN, -500.0] {
        let values = SceneValues {
            wavelength: Some(nm),
            ..SceneValues::default()
        };
        let e = Setup::from_text("d.toml", DISPERSIVE, &values).unwrap_err();
        assert!(
            e.to_string()
                .contains("nm is not allowed: visible light is from 380 to 780 nm"),
            "{e}"
        );
        let glass = SceneValues {
            observer: Some([0.1, 0.0, 0.1]),
            straw: Some([0.0, 0.0]),
            water_height: Some(0.1),
            ..values
        };
        assert!(Setup::from_values(&glass).is_err());
    }
}

/// A prism of `law` on the table beside a tiny empty glass (which has no face), seen from the
/// gallery prism's eye; the prism's corners are the gallery's.
fn prism_scene(law: &str) -> String {
    format!(
        "[container]\nshape = \"glass\"\nradius = 0.01\nheight = 0.01\n\n\
         [[prism]]\ncorners = [[0.06329, 0.07209], [0.054221, 0.033138], [0.092493, 0.044766]]\n\
         bottom = 0.0\ntop = 0.05\n{law}\n\n\
         [observer]\nposition = [0.42, 0.0396, 0.04]\ntarget = [0.07, 0.05, 0.025]\n"
    )
}

fn pictures(text: &str) -> (RgbPicture, RgbPicture) {
    let s = setup(text, None);
    let camera = Camera::new(s.observer, s.target.unwrap(), 200, 150, 0.35);
    let options = |white| ShadingOptions {
        mode: ShadingMode::Fresnel { prune_below: 1e-4 },
        backdrop: Backdrop::Checker,
        samples: 3,
        adaptive: true,
        outline: true,
        white,
    };
    (
        shaded_picture(&s.world, &camera, &options(false)),
        shaded_picture(&s.world, &camera, &options(true)),
    )
}

/// Pixels of a colour the checkerboard has not (its blue has green between red and blue, its
/// brown too, its white all three alike): green or magenta, green at least 6 levels above or
/// below both others.
fn spectral(p: &RgbPicture) -> usize {
    p.pixels
        .chunks_exact(3)
        .filter(|c| {
            let (r, g, b) = (c[0] as i32, c[1] as i32, c[2] as i32);
            g >= r.max(b) + 6 || g + 6 <= r.min(b)
        })
        .count()
}

/// White light where every band sees the same indices is the ordinary picture: to the byte
/// when no index depends on the wavelength, within 3 levels (of 255) through laws that give
/// one index at every wavelength, where every band is traced and their colours added up.
#[test]
fn white_light_where_nothing_disperses_is_the_ordinary_picture() {
    let (mono, white) = pictures(&prism_scene("index = 1.5"));
    assert_eq!(mono, white);
    let flat = prism_scene("cauchy = [1.5, 0.0]");
    let s = setup(&flat, None);
    assert_eq!(s.world.white_light().len(), WHITE_BANDS);
    let (mono, white) = pictures(&flat);
    let most = mono
        .pixels
        .iter()
        .zip(&white.pixels)
        .map(|(a, b)| a.abs_diff(*b))
        .max()
        .unwrap();
    assert!(most <= 3, "{most} levels apart");
}

/// Through a prism of dense flint glass the checkerboard's edges are spread into spectra: in
/// white light the prism shows greens and magentas that the checkerboard has not, and light of
/// one colour shows none; outside the prism the picture is the same.
#[test]
fn white_light_through_a_flint_prism_shows_the_spectrum() {
    let (mono, white) = pictures(&prism_scene("material = \"sf10\""));
    let (plain, colour) = (spectral(&mono), spectral(&white));
    assert!(
        plain < 20 && colour > 300,
        "spectral pixels: {plain} in one colour, {colour} in white"
    );
    // Outside the prism nothing changes: most of the picture is the same.
    let same = mono
        .pixels
        .chunks_exact(3)
        .zip(white.pixels.chunks_exact(3))
        .filter(|(a, b)| a == b)
        .count();
    assert!(same * 2 > mono.pixels.len() / 3, "{same} pixels unchanged");
}

/// The picture in white light drawn the long way: every band traced at every pixel and every
/// sample of every edge, in its own world, its colour weighted by the band's and added up in
/// linear light.
fn every_band_everywhere(world: &World, camera: &Camera, options: &ShadingOptions) -> RgbPicture {
    let one = ShadingOptions {
        white: false,
        ..*options
    };
    let mut sum = vec![0.0f64; 3 * camera.width as usize * camera.height as usize];
    for (band, band_world) in white_bands().iter().zip(world.white_light()) {
        let p = shaded_picture(band_world, camera, &one);
        for (k, (s, &byte)) in sum.iter_mut().zip(&p.pixels).enumerate() {
            *s += band.rgb[k % 3] * srgb_to_linear(byte as f64 / 255.0);
        }
    }
    RgbPicture {
        width: camera.width,
        height: camera.height,
        pixels: sum
            .iter()
            .map(|&c| (linear_to_srgb(c.clamp(0.0, 1.0)) * 255.0).round() as u8)
            .collect(),
    }
}

/// White light traces every band only where the bands' pictures differ, and samples the edges
/// there with fewer rays per band than one colour does: against the picture of every band
/// traced at every sample, the gallery's dispersive scenes differ only around what disperses
/// (the glass of liquid, the prism, the lens), by a few levels on average there, and by more
/// than 32 levels (of 255) at fewer than three pixels in a thousand: the noise of an edge sampled
/// by two or three rays per band.
#[test]
fn white_light_keeps_the_picture_of_every_band_traced_everywhere() {
    let scenes = [
        (
            "prism",
            include_str!("../../bentstraw-io/scenes/prism-spectrum.toml"),
        ),
        (
            "lens",
            include_str!("../../bentstraw-io/scenes/lens-colours.toml"),
        ),
        (
            "liquid",
            include_str!("../../bentstraw-io/scenes/dispersive-liquid.toml"),
        ),
    ];
    for (name, text) in scenes {
        let s = setup(text, None);
        let camera = Camera::new(s.observer, s.target.unwrap(), 320, 240, 0.6);
        let options = ShadingOptions {
            mode: ShadingMode::Fresnel { prune_below: 1e-4 },
            backdrop: Backdrop::Checker,
            samples: 3,
            adaptive: true,
            outline: true,
            white: true,
        };
        let fast = shaded_picture(&s.world, &camera, &options);
        let slow = every_band_everywhere(&s.world, &camera, &options);
        let diffs: Vec<u8> = fast
            .pixels
            .chunks_exact(3)
            .zip(slow.pixels.chunks_exact(3))
            .map(|(a, b)| (0..3).map(|c| a[c].abs_diff(b[c])).max().unwrap())
            .collect();
        let pixels = diffs.len();
        let differing = diffs.iter().filter(|&&d| d > 0).count();
        let mean = diffs.iter().map(|&d| d as f64).sum::<f64>() / differing.max(1) as f64;
        let far = diffs.iter().filter(|&&d| d > 32).count();
        eprintln!("{name}: {differing} of {pixels} pixels differ, by {mean:.1} levels on average, {far} by more than 32");
        assert!(differing * 5 < pixels, "{name}: {differing} pixels differ");
        assert!(mean < 10.0, "{name}: {mean:.1} levels on average");
        assert!(
            far * 1000 < 3 * pixels,
            "{name}: {far} pixels more than 32 levels apart"
        );
    }
}

/// White light's image points: every point is the one its ray gives in the scene whose indices
/// are its band's (re-traced there, to the bit), the bands take turns so that each has about an
/// eighth of the points, and where nothing disperses they are the points of one wavelength,
/// marked with their bands.
#[test]
fn white_light_points_are_each_bands_own() {
    use bentstraw_optics::sampling::sample_image_until;
    use std::sync::atomic::AtomicBool;
    let never = AtomicBool::new(false);
    let white = |world: &World, eye: Vec3, n: usize| {
        sample_image_until(world, eye, n, true, &|_| {}, &never).unwrap()
    };
    let per_band = |points: &[bentstraw_optics::image::ImagePoint]| {
        let mut counts = [0usize; WHITE_BANDS];
        for p in points {
            counts[p.band.expect("a band") as usize] += 1;
        }
        counts
    };
    let s = setup(DISPERSIVE, None);
    let cloud = white(&s.world, s.observer, 4000);
    assert!(cloud.white && cloud.points.len() >= 4000);
    let plain: Vec<Setup> = white_bands()
        .iter()
        .map(|b| setup(&with_indices_at(DISPERSIVE, b.nm), None))
        .collect();
    for p in &cloud.points {
        let k = p.band.unwrap() as usize;
        let again = plain[k].world.image_point(s.observer, p.direction);
        assert_eq!(
            again,
            Some(bentstraw_optics::image::ImagePoint { band: None, ..*p })
        );
    }
    let counts = per_band(&cloud.points);
    let n = cloud.points.len();
    assert!(
        counts
            .iter()
            .all(|&c| c * 8 > n * 3 / 4 && c * 8 < n * 5 / 4),
        "{counts:?}"
    );
    // The violet and the red rays of a direction reach different points.
    let (violet, red) = (&plain[0].world, &plain[WHITE_BANDS - 1].world);
    let parted = cloud
        .points
        .iter()
        .filter(|p| {
            violet
                .image_point(s.observer, p.direction)
                .map(|q| q.position)
                != red.image_point(s.observer, p.direction).map(|q| q.position)
        })
        .count();
    assert!(parted * 2 > n, "{parted} of {n}");

    // Nothing disperses: the same rays and points as in light of one wavelength.
    let plain = setup(&with_indices_at(DISPERSIVE, 587.56), None);
    let mono = sample_image(&plain.world, plain.observer, 4000, &|_| {});
    let cloud = white(&plain.world, plain.observer, 4000);
    assert_eq!(cloud.rays_traced, mono.rays_traced);
    assert_eq!(cloud.points.len(), mono.points.len());
    for (w, m) in cloud.points.iter().zip(&mono.points) {
        assert_eq!(bentstraw_optics::image::ImagePoint { band: None, ..*w }, *m);
    }
    let (counts, n) = (per_band(&cloud.points), cloud.points.len());
    assert!(
        counts
            .iter()
            .all(|&c| c * 8 > n * 3 / 4 && c * 8 < n * 5 / 4),
        "{counts:?}"
    );
}
