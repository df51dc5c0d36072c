//! The rainbow of a drop: Descartes' construction, traced.
//!
//! Sunlight meets a transparent sphere in parallel rays, at every impact parameter `b` (a ray's
//! distance from the parallel line through the centre, over the radius, from 0 to 1). A ray that
//! leaves after `k` partial reflections inside the sphere has been turned by an angle that
//! depends on `b`. Where that angle is stationary in `b`, rays of many impact parameters leave
//! together and the light piles up: that direction is the bow. Measured from the antisolar point
//! (the direction opposite the sun, the shadow of the observer's head), the first bow (`k = 1`)
//! is the largest angle any ray reaches and the second (`k = 2`) the smallest, so the sky is
//! bright inside the first bow, outside the second, and dark between (Alexander's band). Each
//! wavelength has its own index, so its own bow: red outside violet in the first bow, inside it
//! in the second.
//!
//! The rays here are traced by the same tracer as every picture, with Fresnel's splitting: the
//! branch that leaves after `k` reflections inside is the one with `k + 2` events (in, `k`
//! reflections, out). Traced from the eye, a ray's path is the sunlight's path reversed.

use crate::geometry::Ray;
use crate::scene::DEFAULT_MAX_EVENTS;
use crate::scene_file::{Container, Dispersive, Glass, Medium, SceneDescription, SceneFileError};
use crate::world::{FresnelStep, World};
use crate::Vec3;

/// Impact parameters sampled evenly for a curve (the bow itself is then found to 1e-12 in `b`).
pub const CURVE_SAMPLES: usize = 400;

/// The angle from the antisolar point of light that left a sphere after some reflections
/// inside it, against the impact parameter, at one wavelength.
#[derive(Clone, Debug, PartialEq)]
pub struct DeviationCurve {
    /// The wavelength (nm).
    pub nm: f64,
    /// The sphere's index there.
    pub index: f64,
    /// The reflections inside.
    pub reflections: u32,
    /// `(b, angle in degrees)` for evenly spaced impact parameters; a ray whose branch was
    /// abandoned (too faint) is left out.
    pub points: Vec<[f64; 2]>,
    /// The bow: the impact parameter and the angle (degrees) where the angle is stationary (the
    /// largest for one reflection, the smallest for more).
    pub bow: [f64; 2],
}

/// The angle from the antisolar point (degrees) of light of impact parameter `b` on the sphere of
/// `world` (centred at `centre`, of radius `radius`) that leaves after `reflections` reflections
/// inside it; `None` when that branch was not followed (too faint to matter).
pub fn bow_angle(
    world: &World,
    centre: Vec3,
    radius: f64,
    b: f64,
    reflections: u32,
) -> Option<f64> {
    let incoming = Vec3::X;
    // Start well outside the sphere, on a line parallel to x at distance b·radius.
    let ray = Ray {
        origin: centre - 2.0 * radius * incoming + b * radius * Vec3::Y,
        direction: incoming,
    };
    let mut angle = None;
    world.fresnel_steps::<false>(ray, 1e-12, 4096, |step| {
        if let FresnelStep::Escaped { ray, events, .. } = step {
            if events == reflections + 2 {
                // The light came from the sun along −(leaving direction) and leaves towards the
                // eye along −incoming: its angle from the antisolar point is between the eye's
                // line of sight and the leaving ray reversed.
                let cos = -incoming.dot(ray.direction.normalize());
                angle = Some(cos.clamp(-1.0, 1.0).acos().to_degrees());
            }
        }
    });
    angle
}

/// The drop of Descartes' construction: one sphere alone in air, at one wavelength.
pub struct Drop {
    /// The world holding only the sphere.
    pub world: World,
    /// Its centre (m).
    pub centre: Vec3,
    /// Its radius (m).
    pub radius: f64,
    /// Its index at the wavelength.
    pub index: f64,
}

/// Sphere `sphere` of `description` (its index, or its law at `nm`) alone in air.
pub fn drop_world(
    description: &SceneDescription,
    sphere: usize,
    nm: f64,
) -> Result<Drop, Box<SceneFileError>> {
    let mut s = description.spheres[sphere];
    let law = description.law(Medium::Sphere(sphere)).cloned();
    // Far above a glass too small to meet any ray.
    s.center = Vec3::new(0.0, 0.0, 1.0 + s.radius);
    let alone = SceneDescription {
        container: Container::Glass(Glass {
            radius: 1e-3,
            height: 1e-3,
            wall: 0.0,
            bottom: 0.0,
            index: 1.0,
        }),
        liquids: vec![],
        straws: vec![],
        coins: vec![],
        cards: vec![],
        spheres: vec![s],
        prisms: vec![],
        lenses: vec![],
        observer: None,
        sun: None,
        lesson: None,
        dispersion: law
            .map(|law| Dispersive {
                medium: Medium::Sphere(0),
                law,
            })
            .into_iter()
            .collect(),
    }
    .at_wavelength(nm);
    Ok(Drop {
        world: World::new(&alone, DEFAULT_MAX_EVENTS)?,
        centre: s.center,
        radius: s.radius,
        index: alone.spheres[0].index,
    })
}

/// Descartes' construction for sphere `sphere` of `description` at each wavelength of `nms`:
/// the curve of the light leaving after `reflections` reflections inside, and its bow.
pub fn deviation_curves(
    description: &SceneDescription,
    sphere: usize,
    reflections: u32,
    nms: &[f64],
) -> Result<Vec<DeviationCurve>, Box<SceneFileError>> {
    nms.iter()
        .map(|&nm| {
            let drop = drop_world(description, sphere, nm)?;
            let at = |b: f64| bow_angle(&drop.world, drop.centre, drop.radius, b, reflections);
            let points: Vec<[f64; 2]> = (0..CURVE_SAMPLES)
                .filter_map(|k| {
                    let b = (k as f64 + 0.5) / CURVE_SAMPLES as f64;
                    at(b).map(|a| [b, a])
                })
                .collect();
            // The first bow is a maximum of the angle, the others minima.
            let sign = if reflections == 1 { 1.0 } else { -1.0 };
            let best = points
                .iter()
                .copied()
                .max_by(|p, q| (sign * p[1]).total_cmp(&(sign * q[1])))
                .unwrap_or([0.5, 0.0]);
            let step = 1.0 / CURVE_SAMPLES as f64;
            let f = |b: f64| at(b).map_or(f64::NEG_INFINITY, |a| sign * a);
            let b = golden_section((best[0] - step).max(0.0), (best[0] + step).min(1.0), f);
            let bow = [b, sign * f(b)];
            Ok(DeviationCurve {
                nm,
                index: drop.index,
                reflections,
                points,
                bow,
            })
        })
        .collect()
}

/// The point of `[a, b]` where `f`, single-peaked there, is largest (to 1e-12).
fn golden_section(mut a: f64, mut b: f64, f: impl Fn(f64) -> f64) -> f64 {
    let g = (5f64.sqrt() - 1.0) / 2.0;
    let (mut c, mut d) = (b - g * (b - a), a + g * (b - a));
    let (mut fc, mut fd) = (f(c), f(d));
    while b - a > 1e-12 {
        if fc > fd {
            b = d;
            (d, fd) = (c, fc);
            c = b - g * (b - a);
            fc = f(c);
        } else {
            a = c;
            (c, fc) = (d, fd);
            d = a + g * (b - a);
            fd = f(d);
        }
    }
    0.5 * (a + b)
}
