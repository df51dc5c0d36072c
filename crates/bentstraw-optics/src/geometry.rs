//! Rays and the two shapes the scene is made of: upright cylinders (their side) and horizontal disks.

use crate::lanes::{Mask, Real};
use crate::Vec3;

/// A half-line `origin + t·direction`, `t > 0`, with a unit `direction`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Where the ray starts.
    pub origin: Vec3,
    /// Unit direction of travel.
    pub direction: Vec3,
}

impl Ray {
    /// A ray from `origin` along `direction` (normalised here).
    pub fn new(origin: Vec3, direction: Vec3) -> Self {
        Ray {
            origin,
            direction: direction.normalize(),
        }
    }

    /// The point at distance `t` along the ray.
    #[inline]
    pub fn at(&self, t: f64) -> Vec3 {
        self.origin + t * self.direction
    }
}

/// The side of an upright (axis along `z`) circular cylinder between two heights; no caps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CylinderSide {
    /// `x` of the axis.
    pub cx: f64,
    /// `y` of the axis.
    pub cy: f64,
    /// Radius.
    pub radius: f64,
    /// Lowest height of the side.
    pub z_min: f64,
    /// Highest height of the side.
    pub z_max: f64,
}

impl CylinderSide {
    /// The quadratic of `ray`'s line meeting this side (see [`SideQuadratic`]).
    #[inline]
    fn quadratic(&self, ray: &Ray) -> SideQuadratic<f64> {
        SideQuadratic::new(
            ray.origin.x - self.cx,
            ray.origin.y - self.cy,
            ray.direction.x,
            ray.direction.y,
            self.radius * self.radius,
        )
    }

    /// Nearest distance `t > 0` at which `ray`, which does not start on this side, meets it.
    ///
    /// A ray that only grazes the cylinder (tangent) meets it at one point and counts as a hit there.
    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<f64> {
        let q = self.quadratic(ray);
        finite(
            q.roots(1.0 / q.a)
                .nearest(ray.origin.z, ray.direction.z, self.z_min, self.z_max),
        )
    }

    /// Distance at which `ray`, which starts on this side (it has just been refracted or reflected
    /// there), meets it again: the root at its start is excluded by construction, not by a minimum
    /// distance, so a genuine hit a hair away is never lost.
    #[inline]
    pub fn intersect_leaving(&self, ray: &Ray) -> Option<f64> {
        let q = self.quadratic(ray);
        finite(
            q.roots(1.0 / q.a)
                .other(ray.origin.z, ray.direction.z, self.z_min, self.z_max),
        )
    }

    /// Distance at which `ray` enters the solid cylinder through this side (an opaque object
    /// shows only the side by which light reaches it): its entering root `t > 0`, or `0` if the
    /// ray starts inside the solid (by rounding, on its surface).
    #[inline]
    pub fn entry(&self, ray: &Ray) -> Option<f64> {
        let q = self.quadratic(ray);
        finite(q.roots(1.0 / q.a).entering(
            &q,
            ray.origin.z,
            ray.direction.z,
            self.z_min,
            self.z_max,
        ))
    }

    /// Outward unit normal at a point `p` of the side.
    #[inline]
    pub fn normal(&self, p: Vec3) -> Vec3 {
        Vec3::new(p.x - self.cx, p.y - self.cy, 0.0).normalize()
    }
}

/// A ray's line `p + t·d` (horizontal parts relative to an upright axis) meeting a cylinder of
/// radius² `r2` around it: `a t² + 2 half_b t + c = 0`, for one ray or eight ([`Real`]).
///
/// The discriminant is computed as `disc = a·r² − (px·dy − py·dx)²` (Lagrange's identity), not
/// `half_b² − a·c`: for a distant origin both terms of the latter are huge and nearly equal, and
/// their difference loses every digit (an observer 1 km away put wall hits 1e-9 m off the wall).
/// The roots come in the cancellation-free form `q = −(half_b + sign(half_b)·√disc)`, `t = q/a`
/// and `c/q`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SideQuadratic<R = f64> {
    /// `dx² + dy²`: zero for a vertical ray, parallel to the side.
    pub a: R,
    /// `px·dx + py·dy`: negative when the ray moves towards the axis.
    pub half_b: R,
    /// `px² + py² − r²`: negative when the ray starts inside the cylinder.
    pub c: R,
    /// `a·r² − (px·dy − py·dx)²`: negative when the line misses the cylinder.
    pub disc: R,
}

/// The roots of a [`SideQuadratic`] in the lanes where the line meets the cylinder (`real`):
/// the smaller, the larger, and `q/a` (the one not near zero when `c` is).
#[derive(Clone, Copy, Debug)]
pub(crate) struct SideRoots<R: Real> {
    pub near: R,
    pub far: R,
    pub q_over_a: R,
    pub real: R::Mask,
}

impl<R: Real> SideQuadratic<R> {
    /// The quadratic of the line from `(px, py)` along `(dx, dy)` for radius² `r2`.
    #[inline(always)]
    pub fn new(px: R, py: R, dx: R, dy: R, r2: R) -> SideQuadratic<R> {
        let a = dx * dx + dy * dy;
        let cross = px * dy - py * dx;
        SideQuadratic {
            a,
            half_b: px * dx + py * dy,
            c: px * px + py * py - r2,
            disc: a * r2 - cross * cross,
        }
    }

    /// Whether the line passes farther than `r·(1 + 1e-9)` from the axis (`r2 = r²`): `disc/a =
    /// r² − distance²` without cancellation, and the margin, relative to `a·r²`, is far above its
    /// rounding, so rounding never fakes a miss.
    #[inline(always)]
    pub fn clearly_misses(&self, r2: R) -> R::Mask {
        self.disc.lt(-(R::splat(MISS_MARGIN) * self.a * r2))
    }

    /// Whether a ray on or outside the cylinder (`c >= 0`) moves away from its axis (`half_b >=
    /// 0`): then both roots are `<= 0` (their product `c/a >= 0`, their sum `−2·half_b/a <= 0`),
    /// so it meets the side nowhere ahead, whatever the rounding.
    #[inline(always)]
    pub fn moving_away(&self) -> R::Mask {
        let zero = R::splat(0.0);
        self.c.ge(zero).and(self.half_b.ge(zero))
    }

    /// The lanes where the line meets the cylinder (not vertical, `disc >= 0`).
    #[inline(always)]
    pub fn real(&self) -> R::Mask {
        let zero = R::splat(0.0);
        self.a.gt(zero).and(self.disc.ge(zero))
    }

    /// Both roots, smaller first, and `q/a`, where the line meets the cylinder (not vertical,
    /// `disc >= 0`); `inv_a = 1/a` (see [`Real::quotient`]). A ray tangent at its start (`q = 0`)
    /// has all three 0.
    #[inline(always)]
    pub fn roots(&self, inv_a: R) -> SideRoots<R> {
        let zero = R::splat(0.0);
        let real = self.real();
        let sq = self.disc.sqrt();
        let q = R::select(self.half_b.ge(zero), -(self.half_b + sq), -self.half_b + sq);
        let tangent = q.eq(zero);
        let r1 = R::quotient(q, self.a, inv_a);
        let r2 = self.c / q;
        SideRoots {
            near: R::select(tangent, zero, r1.min(r2)),
            far: R::select(tangent, zero, r1.max(r2)),
            q_over_a: R::select(tangent, zero, r1),
            real,
        }
    }
}

impl<R: Real> SideRoots<R> {
    /// The nearest root `t > 0` whose height `oz + t·dz` lies in `[z_min, z_max]` (infinite where
    /// none).
    #[inline(always)]
    pub fn nearest(&self, oz: R, dz: R, z_min: R, z_max: R) -> R {
        let zero = R::splat(0.0);
        let ok0 =
            self.real
                .and(self.near.gt(zero))
                .and(in_range(oz + self.near * dz, z_min, z_max));
        // Where every ray meets the near root there is nothing more to look at.
        if !self.real.and_not(ok0).any() {
            return R::select(ok0, self.near, R::splat(f64::INFINITY));
        }
        let ok1 = self
            .far
            .gt(zero)
            .and(in_range(oz + self.far * dz, z_min, z_max));
        let t = R::select(
            ok0,
            self.near,
            R::select(ok1, self.far, R::splat(f64::INFINITY)),
        );
        R::select(self.real, t, R::splat(f64::INFINITY))
    }

    /// For a ray starting on the cylinder (`c ≈ 0`): the root away from its start, `q/a` (the
    /// other, `c/q`, is the start itself), if it lies ahead and within the heights.
    #[inline(always)]
    pub fn other(&self, oz: R, dz: R, z_min: R, z_max: R) -> R {
        let t = self.q_over_a;
        let ok = self
            .real
            .and(t.gt(R::splat(0.0)))
            .and(in_range(oz + t * dz, z_min, z_max));
        R::select(ok, t, R::splat(f64::INFINITY))
    }

    /// The entering root of the solid cylinder between the heights: the smaller root if it lies
    /// ahead (`t > 0`) and within the heights; `0` where the ray starts inside the solid (`c < 0`
    /// with its start between the heights: only rounding puts a ray there, on the surface).
    #[inline(always)]
    pub fn entering(&self, q: &SideQuadratic<R>, oz: R, dz: R, z_min: R, z_max: R) -> R {
        let zero = R::splat(0.0);
        let inside = q.c.lt(zero).and(in_range(oz, z_min, z_max));
        let ok = self
            .real
            .and(self.near.gt(zero))
            .and(in_range(oz + self.near * dz, z_min, z_max));
        R::select(
            inside,
            zero,
            R::select(ok, self.near, R::splat(f64::INFINITY)),
        )
    }
}

/// Relative margin of the "line clearly misses the circle" tests, far above rounding (1e-16).
const MISS_MARGIN: f64 = 1e-9;

/// Whether `z_min <= z <= z_max`, lane by lane.
#[inline(always)]
pub(crate) fn in_range<R: Real>(z: R, z_min: R, z_max: R) -> R::Mask {
    z.ge(z_min).and(z.le(z_max))
}

/// The finite lanes of `t` as an `Option` for one ray.
#[inline(always)]
fn finite(t: f64) -> Option<f64> {
    t.is_finite().then_some(t)
}

/// A horizontal disk of centre `(cx, cy, z)`, boundary included.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Disk {
    /// `x` of the centre.
    pub cx: f64,
    /// `y` of the centre.
    pub cy: f64,
    /// Height of the disk's plane.
    pub z: f64,
    /// Radius.
    pub radius: f64,
}

impl Disk {
    /// Distance `t > 0` at which `ray` crosses the disk, if it does (a ray starting on the disk's
    /// plane, having just left it, does not cross it again).
    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<f64> {
        let t = plane_distance(self.z, ray.origin.z, ray.direction.z)?;
        let x = ray.origin.x + t * ray.direction.x - self.cx;
        let y = ray.origin.y + t * ray.direction.y - self.cy;
        (x * x + y * y <= self.radius * self.radius).then_some(t)
    }
}

/// The lanes where the plane `z = h` lies ahead of height `oz` along vertical component `dz`
/// (`h − oz` and `dz` of the same strict sign), and `h − oz`; [`plane_distance_of`] then gives
/// the distance, so that no division is done when no lane needs one.
#[inline(always)]
pub(crate) fn plane_ahead<R: Real>(h: R, oz: R, dz: R) -> (R, R::Mask) {
    let zero = R::splat(0.0);
    let num = h - oz;
    let ahead = (num.gt(zero).and(dz.gt(zero))).or(num.lt(zero).and(dz.lt(zero)));
    (num, ahead)
}

/// The distance `num / dz` to a plane [`plane_ahead`] found ahead; `inv_dz = 1/dz` (see
/// [`Real::quotient`]).
#[inline(always)]
pub(crate) fn plane_distance_of<R: Real>(num: R, dz: R, inv_dz: R) -> R {
    R::quotient(num, dz, inv_dz)
}

/// [`plane_ahead`] for one ray: the distance if the plane lies ahead (the division is done only
/// then).
#[inline(always)]
pub(crate) fn plane_distance(h: f64, oz: f64, dz: f64) -> Option<f64> {
    let num = h - oz;
    if (num > 0.0 && dz > 0.0) || (num < 0.0 && dz < 0.0) {
        Some(num / dz)
    } else {
        None
    }
}

/// Centre of the sphere that encloses every face of the scene.
pub const BOUNDING_CENTRE: Vec3 = Vec3::new(0.0, 0.0, 0.125);
/// Radius of that sphere (m): every point of the glass and straw lies within 0.1313 m of its centre.
pub const BOUNDING_RADIUS: f64 = 0.15;

/// The ray moved forward to where it enters the scene's bounding sphere, and the distance moved;
/// unchanged (distance 0) if it starts inside; `None` if it misses the sphere (it meets nothing).
///
/// No face lies between a distant origin and the sphere, so the trace is unchanged, but every
/// intersection is then computed from a point near the scene: the rounding of an origin kilometres
/// away (1e-13 m per km) enters once, in the distance moved, instead of in every quadratic.
#[inline]
pub fn enter_bounding_sphere(ray: Ray) -> Option<(Ray, f64)> {
    enter_sphere(ray, BOUNDING_CENTRE, BOUNDING_RADIUS)
}

/// The ray moved forward to where it enters the sphere of `centre` and `radius` (see
/// [`enter_bounding_sphere`], the assignment's scene's sphere), and the distance moved.
#[inline(always)]
pub fn enter_sphere(ray: Ray, centre: Vec3, radius: f64) -> Option<(Ray, f64)> {
    let p = ray.origin - centre;
    let c = p.length_squared() - radius * radius;
    if c <= 0.0 {
        return Some((ray, 0.0));
    }
    let d = ray.direction;
    let half_b = p.dot(d);
    if half_b >= 0.0 {
        return None; // outside and moving away
    }
    // disc = R² − |p × d|² (for unit d), free of the cancellation of half_b² − c.
    let disc = radius * radius - p.cross(d).length_squared();
    if disc < 0.0 {
        return None;
    }
    let q = -half_b + disc.sqrt();
    let t = c / q; // the near root
    Some((
        Ray {
            origin: ray.origin + t * d,
            direction: d,
        },
        t,
    ))
}
