//! Containers of revolution: a straight profile traces exactly as the glass it describes, a
//! cone's wall is met where its closed form says with its closed-form normal, and the curvature
//! the eye model follows is the change of the wall's normal.

use bentstraw_optics::apparent::eye_model_points;
use bentstraw_optics::geometry::Ray;
use bentstraw_optics::sampling::sample_image;
use bentstraw_optics::scene_file::SceneDescription;
use bentstraw_optics::world::{Event, Outcome, Shape, World};
use bentstraw_optics::Vec3;

fn scene(toml: &str) -> SceneDescription {
    SceneDescription::from_toml(toml).unwrap_or_else(|e| panic!("{e}\n{toml}"))
}

fn trace_events(world: &World, ray: Ray) -> (Outcome, Vec<Event>) {
    let mut events = Vec::new();
    let outcome = world.trace_with(ray, |e| events.push(*e));
    (outcome, events)
}

/// What fills a thick glass: two liquids and a leaning straw, seen from `observer`.
const CONTENTS: &str = "[[liquid]]\nname = \"water\"\nindex = 1.333\ntop = 0.07\n\n\
                        [[liquid]]\nname = \"oil\"\nindex = 1.47\ntop = 0.095\n\n\
                        [[straw]]\nx = -0.012\ny = 0.004\ntilt = 12\nazimuth = 20\nlength = 0.15\n\n\
                        [[coin]]\nx = 0.02\ny = -0.01\n";

/// A glass of revolution whose profiles are two upright lines is the glass they describe: from
/// beside, above, below and far, every image point, every eye-model position, within 1e-9 m.
#[test]
fn a_straight_profile_traces_as_the_glass_it_describes() {
    let glass = World::new(
        &scene(&format!(
            "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.12\nwall = 0.0025\n\
             bottom = 0.008\nindex = 1.5\n\n{CONTENTS}"
        )),
        10,
    )
    .expect("a valid glass");
    let turned = World::new(
        &scene(&format!(
            "[container]\nshape = \"revolution\"\nouter = [[0.04, 0], [0.04, 0.12]]\n\
             inner = [[0.0375, 0.008], [0.0375, 0.12]]\nindex = 1.5\n\n{CONTENTS}"
        )),
        10,
    )
    .expect("a valid glass of revolution");
    let mut compared = 0;
    for eye in [
        Vec3::new(0.3, -0.05, 0.06),
        Vec3::new(0.05, 0.2, 0.25),
        Vec3::new(-0.1, 0.15, -0.12),
        Vec3::new(40.0, 3.0, 5.0),
    ] {
        let a = sample_image(&glass, eye, 3000, &|_| {});
        let b = sample_image(&turned, eye, 3000, &|_| {});
        assert_eq!(a.points.len(), b.points.len(), "from {eye}");
        for (p, q) in a.points.iter().zip(&b.points) {
            assert_eq!(p.color, q.color);
            assert_eq!(p.events, q.events);
            assert!(
                (p.position - q.position).length() < 1e-9,
                "from {eye}: {} and {}",
                p.position,
                q.position
            );
        }
        let some: Vec<_> = a.points.iter().step_by(40).copied().collect();
        let twins: Vec<_> = b.points.iter().step_by(40).copied().collect();
        for (p, q) in eye_model_points(&glass, eye, &some)
            .iter()
            .zip(eye_model_points(&turned, eye, &twins))
        {
            match (p.position, q.position) {
                (Some(x), Some(y)) => assert!((x - y).length() < 1e-9, "from {eye}: {x}, {y}"),
                (x, y) => assert_eq!(x.is_some(), y.is_some()),
            }
        }
        compared += a.points.len();
    }
    assert!(compared > 8000, "{compared} points compared");
}

/// A tumbler's outer wall is the cone `r = r0 + k·z`: a horizontal ray towards the axis meets it
/// at `r(z)`, where its outer normal is `(x/r, y/r, −k)/√(1 + k²)`, and bends there by Snell's
/// law about that normal (the refracted ray tilts up, towards the inward normal).
#[test]
fn a_cone_wall_is_met_at_its_radius_with_its_closed_form_normal() {
    let (r0, k) = (0.03, 0.1);
    let world = World::new(
        &scene(
            "[container]\nshape = \"revolution\"\nouter = [[0.03, 0], [0.042, 0.12]]\n\
             inner = [[0.0275, 0.008], [0.0395, 0.12]]\nindex = 1.5\n",
        ),
        10,
    )
    .expect("a valid tumbler");
    for (z, bearing) in [(0.01, 0.3), (0.05, 2.0), (0.1, -2.5), (0.119, 4.0)] {
        let u = Vec3::new(f64::cos(bearing), f64::sin(bearing), 0.0);
        let r = r0 + k * z;
        let ray = Ray::new(0.5 * u + Vec3::new(0.0, 0.0, z), -u);
        let (_, events) = trace_events(&world, ray);
        let e = events.first().expect("the wall is met");
        let expected = r * u + Vec3::new(0.0, 0.0, z);
        assert!(
            (e.point - expected).length() < 1e-15,
            "at z = {z}: {}",
            e.point
        );
        let normal = (u - Vec3::new(0.0, 0.0, k)) / (1.0 + k * k).sqrt();
        assert!((e.normal - normal).length() < 1e-14, "{}", e.normal);
        // Snell's law about the tilted normal: sin θ₂ = sin θ₁ / 1.5, in the plane of incidence.
        let sin_in = e.incoming.cross(normal).length();
        let sin_out = e.outgoing.cross(normal).length();
        assert!((sin_in - 1.5 * sin_out).abs() < 1e-14);
        // Towards the inward normal, which tilts up where the cone widens upwards.
        assert!(e.outgoing.z > 0.0, "bent up into the wall: {}", e.outgoing);
    }
}

/// The curvature the eye model follows on a wall of revolution is the change of the wall's unit
/// normal: for small steps in the wall at points of a tumbler's cone and a wine glass's bowl
/// and stem, `normal(p + dp) − normal(p)` is `normal_change(p, dp)` to second order.
#[test]
fn a_walls_normal_change_is_the_derivative_of_its_normal() {
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/wine-glass.toml"),
    )
    .expect("the gallery's wine glass");
    let mut checked = 0;
    for text in [
        text,
        "[container]\nshape = \"revolution\"\nouter = [[0.03, 0], [0.042, 0.12]]\n\
         inner = [[0.0275, 0.008], [0.0395, 0.12]]\nindex = 1.5\n"
            .to_string(),
    ] {
        let world = World::new(&scene(&text), 10).expect("a valid scene");
        for b in world.boundaries() {
            let Shape::Revolution {
                zc,
                c,
                z_min,
                z_max,
                ..
            } = b.shape
            else {
                continue;
            };
            for (j, s) in [0.2, 0.5, 0.8].into_iter().enumerate() {
                let z = z_min + s * (z_max - z_min);
                let u = z - zc;
                let r = (c[0] + u * (c[1] + u * c[2])).sqrt();
                let phi = 0.7 + 2.0 * j as f64;
                let at = |z: f64, phi: f64| {
                    let u = z - zc;
                    let r = (c[0] + u * (c[1] + u * c[2])).sqrt();
                    Vec3::new(r * phi.cos(), r * phi.sin(), z)
                };
                let p = at(z, phi);
                assert!((p.x.hypot(p.y) - r).abs() < 1e-15);
                let h = 1e-6 * (z_max - z_min);
                for q in [at(z + h, phi), at(z, phi + h / r.max(1e-3))] {
                    let dp = q - p;
                    let change = b.normal_change(p, dp);
                    let diff = b.normal(q) - b.normal(p);
                    let size = dp.length() / r.max(1e-3);
                    assert!(
                        (change - diff).length() < 1e-4 * size + 1e-13,
                        "at {p}: {change} against {diff}"
                    );
                    checked += 1;
                }
            }
        }
    }
    assert!(checked >= 60, "{checked} steps checked");
}
