//! The double-precision tracer: the scene made ready for tracing many rays, and the one rule for
//! the nearest face a ray meets, which every double-precision trace uses ([`Scene::trace`] and
//! [`Scene::trace_fresnel`](crate::scene::Scene::trace_fresnel) prepare one and call it).
//!
//! Work that cannot change the answer is skipped, per intersection search:
//! - a ray whose line passes clearly outside the glass's circle (every face lies within it) meets
//!   nothing: one cross product, no square root, no division;
//! - a ray whose line passes clearly outside the straw's circle meets none of the straw's three
//!   faces (its caps lie inside that circle);
//! - a plane `z = h` is crossed at a positive distance only if `h − z0` and `dz` have the same sign:
//!   the division is done only then; the two faces on `z = 0` share one division.
//!
//! The quadratics and roots are [`crate::geometry`]'s own (the same operations), and the skips use
//! a relative margin (1e-9) far above rounding, so they never drop a real hit.

use crate::geometry::{plane_distance, Ray, SideQuadratic};
use crate::image::ImagePoint;
use crate::scene::{Scene, GLASS_RADIUS, SECTION_COUNT, STRAW_HEIGHT, STRAW_RADIUS};
use crate::trace::{
    follow_fresnel, follow_ray, Face, Intersection, NearestFace, Outcome, FRESNEL_SEGMENTS_PER_RAY,
};
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
}

/// Whether the ray's line passes farther than `r·(1 + 1e-9)` from a vertical axis, given its
/// quadratic for that axis's cylinder of radius² `r2`.
///
/// `disc/a = r² − distance²`, computed without cancellation (see [`SideQuadratic`]); the margin is
/// relative to `a·r²`, far above its rounding, so rounding can never fake a miss.
#[inline(always)]
fn clearly_misses(q: &SideQuadratic, r2: f64) -> bool {
    q.disc < -MISS_MARGIN * q.a * r2
}

/// Whether a ray on or outside a vertical cylinder (`c >= 0`) moves away from its axis
/// (`half_b >= 0`): then both roots are `<= 0` (their product `c/a >= 0`, their sum `−2·half_b/a
/// <= 0`), so it meets the side nowhere ahead, whatever the rounding (the roots' signs follow
/// from those of `c`, `half_b` and `q` alone).
#[inline(always)]
fn moving_away(q: &SideQuadratic) -> bool {
    q.c >= 0.0 && q.half_b >= 0.0
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
    fn nearest_face(&self, ray: &Ray, left: Option<Face>) -> Option<Intersection> {
        self.nearest_intersection(ray, left)
    }
}

impl Tracer {
    /// Prepares `scene` for tracing.
    pub fn new(scene: &Scene) -> Tracer {
        Tracer {
            scene: *scene,
            glass_r2: GLASS_RADIUS * GLASS_RADIUS,
            straw_r2: STRAW_RADIUS * STRAW_RADIUS,
        }
    }

    /// The nearest face `ray` meets ahead (`t > 0`); the straw wins ties (SPEC §3).
    ///
    /// `left` is the face the ray has just left (it starts on it, after an event there, or, for a
    /// ray sent back from the straw, on the straw): its root at the start is excluded exactly (a
    /// plane is not met again, a side only at its other root, the convex straw not at all), while
    /// every other face counts at any positive distance, so a face a hair away is never skipped.
    /// The straw is opaque: only the root by which a ray enters it counts.
    #[inline]
    pub fn nearest_intersection(&self, ray: &Ray, left: Option<Face>) -> Option<Intersection> {
        let (o, d) = (ray.origin, ray.direction);
        let s = &self.scene;

        // The glass's circle (the water's side wall), centred on the axis.
        let glass = SideQuadratic::new(o.x, o.y, d.x, d.y, self.glass_r2);
        if clearly_misses(&glass, self.glass_r2) {
            return None; // every face lies inside the glass's circle
        }
        // The plane z = 0 holds both the water's bottom and the straw's bottom cap: a ray that has
        // just left the water's bottom is on it and meets neither.
        let t_bottom = if left == Some(Face::WaterBottom) {
            None
        } else {
            plane_distance(0.0, o.z, d.z)
        };

        let mut water = f64::INFINITY;
        let mut water_face = Face::WaterSide;
        if s.has_water() {
            let side = if left == Some(Face::WaterSide) {
                glass.other_root(o.z, d.z, 0.0, s.water_height)
            } else if moving_away(&glass) {
                None // the wall is behind the ray
            } else {
                glass.nearest_root(o.z, d.z, 0.0, s.water_height)
            };
            if let Some(t) = side {
                water = t;
            }
            if left != Some(Face::WaterTop) {
                if let Some(t) = plane_distance(s.water_height, o.z, d.z) {
                    if t < water && within(o, d, t, 0.0, 0.0, self.glass_r2) {
                        water = t;
                        water_face = Face::WaterTop;
                    }
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
        let straw_side =
            SideQuadratic::new(o.x - s.straw_x, o.y - s.straw_y, d.x, d.y, self.straw_r2);
        // The straw is convex: a ray that starts on it (sent back from it) does not meet it again.
        let leaving_straw = left.is_some_and(Face::is_straw);
        if !leaving_straw && !clearly_misses(&straw_side, self.straw_r2) {
            if let Some(t) = straw_side.entering_root(o.z, d.z, 0.0, STRAW_HEIGHT) {
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
        follow_fresnel::<false>(
            self,
            &self.scene,
            ray,
            prune_below,
            FRESNEL_SEGMENTS_PER_RAY,
            |_| {},
        )
    }

    /// Fresnel tracing for pictures: [`Self::trace_fresnel`], but branches that provably escape
    /// are not followed (see [`follow_fresnel`]).
    pub fn trace_fresnel_escaping(&self, ray: Ray, prune_below: f64) -> [f64; SECTION_COUNT] {
        follow_fresnel::<true>(
            self,
            &self.scene,
            ray,
            prune_below,
            FRESNEL_SEGMENTS_PER_RAY,
            |_| {},
        )
    }
}
