//! The fast double-precision tracer: the same physics and the same arithmetic as
//! [`Scene::trace`](crate::scene::Scene::trace) and
//! [`Scene::trace_fresnel`](crate::scene::Scene::trace_fresnel), with the work that cannot change
//! the answer skipped.
//!
//! What it saves, per intersection search:
//! - a ray whose line passes clearly outside the glass's circle (every face lies within it) meets
//!   nothing: one cross product, no square root, no division;
//! - a ray whose line passes clearly outside the straw's circle meets none of the straw's three
//!   faces (its caps lie inside that circle);
//! - a plane `z = h` is crossed at a positive distance only if `h − z0` and `dz` have the same sign:
//!   the division is done only then; the two faces on `z = 0` share one division;
//! - `dx² + dy²` is shared by the two cylinders; the refractive ratios are computed once.
//!
//! Every distance that is computed is computed by the same floating-point operations, in the same
//! order, as in [`crate::geometry`], so colours are identical and lengths equal to the last bit;
//! the skips use a relative margin (1e-9) far above rounding, so they never drop a real hit.

use crate::geometry::{nearest_side_root, Ray, MIN_DISTANCE};
use crate::image::ImagePoint;
use crate::scene::{Scene, GLASS_RADIUS, SECTION_COUNT, STRAW_HEIGHT, STRAW_RADIUS};
use crate::trace::{follow_fresnel, follow_ray, Face, Intersection, NearestFace, Outcome};
use crate::Vec3;

/// Relative margin of the "line clearly misses the circle" tests, far above rounding (1e-16).
const MISS_MARGIN: f64 = 1e-9;

/// A scene made ready for tracing many rays: what every ray would recompute, computed once.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tracer {
    /// The scene traced.
    pub scene: Scene,
    /// `Rv²`.
    glass_r2: f64,
    /// `Rp²`.
    straw_r2: f64,
    /// `2·Rv²`.
    glass_2r2: f64,
    /// `2·Rp²`.
    straw_2r2: f64,
}

/// Whether the ray's line passes farther than `radius·(1 + 1e-9)` from a vertical axis, given the
/// quadratic of that axis's cylinder (`c = |p|² − radius²`, `two_r2 = 2·radius²`).
///
/// `disc/a = radius² − distance²`; the margin is relative to `|p|² + radius² = c + 2·radius²`, which
/// bounds the terms of `disc`, so rounding (1e-16 of them) can never fake a miss.
#[inline(always)]
fn clearly_misses(a: f64, c: f64, disc: f64, two_r2: f64) -> bool {
    disc < -MISS_MARGIN * a * (c + two_r2)
}

/// Whether a ray on or outside a vertical cylinder (`c >= 0`) moves away from its axis
/// (`half_b >= 0`): then both roots are `<= 0` (their product `c/a >= 0`, their sum `−2·half_b/a
/// <= 0`), and `CylinderSide::intersect` would find nothing, whatever the rounding, because its
/// `q = −(half_b + sq) <= 0` gives `q/a <= 0` and `c/q <= 0` by the signs alone.
#[inline(always)]
fn moving_away(half_b: f64, c: f64) -> bool {
    c >= 0.0 && half_b >= 0.0
}

/// Distance `t > MIN_DISTANCE` to the plane `z = h` (as `Disk::intersect`), skipping the division
/// when the plane is behind the ray or parallel to it.
#[inline(always)]
fn plane_distance(h: f64, oz: f64, dz: f64) -> Option<f64> {
    let num = h - oz;
    // t = num/dz > 0 needs both of the same strict sign (dz == 0: parallel; num == 0: t = 0).
    if (num > 0.0 && dz > 0.0) || (num < 0.0 && dz < 0.0) {
        let t = num / dz;
        (t > MIN_DISTANCE).then_some(t)
    } else {
        None
    }
}

/// Whether the ray at distance `t` lies within `r2 = radius²` of the vertical axis `(cx, cy)`.
#[inline(always)]
fn within(o: Vec3, d: Vec3, t: f64, cx: f64, cy: f64, r2: f64) -> bool {
    let x = o.x + t * d.x - cx;
    let y = o.y + t * d.y - cy;
    x * x + y * y <= r2
}

impl NearestFace for Tracer {
    #[inline]
    fn nearest_face(&self, ray: &Ray) -> Option<Intersection> {
        self.nearest_intersection(ray)
    }
}

impl Tracer {
    /// Prepares `scene` for tracing.
    pub fn new(scene: &Scene) -> Tracer {
        let glass_r2 = GLASS_RADIUS * GLASS_RADIUS;
        let straw_r2 = STRAW_RADIUS * STRAW_RADIUS;
        Tracer {
            scene: *scene,
            glass_r2,
            straw_r2,
            glass_2r2: 2.0 * glass_r2,
            straw_2r2: 2.0 * straw_r2,
        }
    }

    /// The nearest face `ray` meets at a distance `> MIN_DISTANCE`; the straw wins ties.
    ///
    /// The same answer, to the last bit, as [`Scene::nearest_intersection`].
    #[inline]
    pub fn nearest_intersection(&self, ray: &Ray) -> Option<Intersection> {
        let (o, d) = (ray.origin, ray.direction);
        let s = &self.scene;
        let a = d.x * d.x + d.y * d.y;

        // The glass's circle (the water's side wall), centred on the axis.
        let half_b = o.x * d.x + o.y * d.y;
        let c = o.x * o.x + o.y * o.y - self.glass_r2;
        let disc = half_b * half_b - a * c;
        if clearly_misses(a, c, disc, self.glass_2r2) {
            return None; // every face lies inside the glass's circle
        }
        // The plane z = 0 holds both the water's bottom and the straw's bottom cap.
        let t_bottom = plane_distance(0.0, o.z, d.z);

        let mut water = f64::INFINITY;
        let mut water_face = Face::WaterSide;
        if s.has_water() {
            if moving_away(half_b, c) {
                // No root ahead: the wall is behind the ray.
            } else if let Some(t) =
                nearest_side_root(a, half_b, c, disc, o.z, d.z, 0.0, s.water_height)
            {
                water = t;
            }
            if let Some(t) = plane_distance(s.water_height, o.z, d.z) {
                if t < water && within(o, d, t, 0.0, 0.0, self.glass_r2) {
                    water = t;
                    water_face = Face::WaterTop;
                }
            }
            if let Some(t) = t_bottom {
                if t < water && within(o, d, t, 0.0, 0.0, self.glass_r2) {
                    water = t;
                    water_face = Face::WaterBottom;
                }
            }
        }

        let mut straw = f64::INFINITY;
        let mut straw_face = Face::StrawSide;
        let px = o.x - s.straw_x;
        let py = o.y - s.straw_y;
        let half_b = px * d.x + py * d.y;
        let c = px * px + py * py - self.straw_r2;
        let disc = half_b * half_b - a * c;
        if !clearly_misses(a, c, disc, self.straw_2r2) {
            if moving_away(half_b, c) {
                // No root ahead: the straw's side is behind the ray.
            } else if let Some(t) =
                nearest_side_root(a, half_b, c, disc, o.z, d.z, 0.0, STRAW_HEIGHT)
            {
                straw = t;
            }
            if let Some(t) = plane_distance(STRAW_HEIGHT, o.z, d.z) {
                if t < straw && within(o, d, t, s.straw_x, s.straw_y, self.straw_r2) {
                    straw = t;
                    straw_face = Face::StrawTop;
                }
            }
            if let Some(t) = t_bottom {
                if t < straw && within(o, d, t, s.straw_x, s.straw_y, self.straw_r2) {
                    straw = t;
                    straw_face = Face::StrawBottom;
                }
            }
        }

        Intersection::nearer((water, water_face), (straw, straw_face))
    }

    /// Traces `ray`, which starts in air, by the course's law: the same outcome as [`Scene::trace`]
    /// (the same loop, [`follow_ray`], over this tracer's faster [`Self::nearest_intersection`]).
    #[inline]
    pub fn trace(&self, ray: Ray) -> Outcome {
        follow_ray(self, &self.scene, ray, |_| {})
    }

    /// Colour code (0 for none) of the section `ray` reaches by the course's law.
    #[inline]
    pub fn color(&self, ray: Ray) -> u8 {
        self.trace(ray).color()
    }

    /// The image point seen from `observer` along unit `u0`: the same as [`Scene::image_point`].
    #[inline]
    pub fn image_point(&self, observer: Vec3, u0: Vec3) -> Option<ImagePoint> {
        let outcome = self.trace(Ray {
            origin: observer,
            direction: u0,
        });
        ImagePoint::from_outcome(observer, u0, outcome)
    }

    /// Fresnel tracing: the same weights as [`Scene::trace_fresnel`] (the same loop,
    /// [`follow_fresnel`], over this tracer's faster [`Self::nearest_intersection`]).
    pub fn trace_fresnel(&self, ray: Ray, prune_below: f64) -> [f64; SECTION_COUNT] {
        follow_fresnel::<false>(self, &self.scene, ray, prune_below, |_| {})
    }

    /// Fresnel tracing for pictures: [`Self::trace_fresnel`], but branches that provably escape
    /// are not followed (see [`follow_fresnel`]).
    pub fn trace_fresnel_escaping(&self, ray: Ray, prune_below: f64) -> [f64; SECTION_COUNT] {
        follow_fresnel::<true>(self, &self.scene, ray, prune_below, |_| {})
    }
}
