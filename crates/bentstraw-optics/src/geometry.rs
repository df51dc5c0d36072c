//! Rays and the two shapes the scene is made of: upright cylinders (their side) and horizontal disks.

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
    fn quadratic(&self, ray: &Ray) -> SideQuadratic {
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
        self.quadratic(ray)
            .nearest_root(ray.origin.z, ray.direction.z, self.z_min, self.z_max)
    }

    /// Distance at which `ray`, which starts on this side (it has just been refracted or reflected
    /// there), meets it again: the root at its start is excluded by construction, not by a minimum
    /// distance, so a genuine hit a hair away is never lost.
    #[inline]
    pub fn intersect_leaving(&self, ray: &Ray) -> Option<f64> {
        self.quadratic(ray)
            .other_root(ray.origin.z, ray.direction.z, self.z_min, self.z_max)
    }

    /// Distance at which `ray` enters the solid cylinder through this side (an opaque object
    /// shows only the side by which light reaches it): its entering root `t > 0`, or `0` if the
    /// ray starts inside the solid (by rounding, on its surface).
    #[inline]
    pub fn entry(&self, ray: &Ray) -> Option<f64> {
        self.quadratic(ray)
            .entering_root(ray.origin.z, ray.direction.z, self.z_min, self.z_max)
    }

    /// Outward unit normal at a point `p` of the side.
    #[inline]
    pub fn normal(&self, p: Vec3) -> Vec3 {
        Vec3::new(p.x - self.cx, p.y - self.cy, 0.0).normalize()
    }
}

/// A ray's line `p + t·d` (horizontal parts relative to an upright axis) meeting a cylinder of
/// radius² `r2` around it: `a t² + 2 half_b t + c = 0`.
///
/// The discriminant is computed as `disc = a·r² − (px·dy − py·dx)²` (Lagrange's identity), not
/// `half_b² − a·c`: for a distant origin both terms of the latter are huge and nearly equal, and
/// their difference loses every digit (an observer 1 km away put wall hits 1e-9 m off the wall).
/// The roots come in the cancellation-free form `q = −(half_b + sign(half_b)·√disc)`, `t = q/a`
/// and `c/q`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SideQuadratic {
    /// `dx² + dy²`: zero for a vertical ray, parallel to the side.
    pub a: f64,
    /// `px·dx + py·dy`: negative when the ray moves towards the axis.
    pub half_b: f64,
    /// `px² + py² − r²`: negative when the ray starts inside the cylinder.
    pub c: f64,
    /// `a·r² − (px·dy − py·dx)²`: negative when the line misses the cylinder.
    pub disc: f64,
}

impl SideQuadratic {
    /// The quadratic of the line from `(px, py)` along `(dx, dy)` for radius² `r2`.
    #[inline(always)]
    pub fn new(px: f64, py: f64, dx: f64, dy: f64, r2: f64) -> SideQuadratic {
        let a = dx * dx + dy * dy;
        let cross = px * dy - py * dx;
        SideQuadratic {
            a,
            half_b: px * dx + py * dy,
            c: px * px + py * py - r2,
            disc: a * r2 - cross * cross,
        }
    }

    /// Both roots, smaller first, and `q/a` (the one not near zero when `c` is); `None` if the
    /// line misses or is vertical.
    #[inline(always)]
    pub(crate) fn roots(&self) -> Option<(f64, f64, f64)> {
        if self.a == 0.0 || self.disc < 0.0 {
            return None;
        }
        let sq = self.disc.sqrt();
        let q = if self.half_b >= 0.0 {
            -(self.half_b + sq)
        } else {
            -self.half_b + sq
        };
        if q == 0.0 {
            return Some((0.0, 0.0, 0.0)); // tangent at the start
        }
        let (r1, r2) = (q / self.a, self.c / q);
        Some((r1.min(r2), r1.max(r2), r1))
    }

    /// The nearest root `t > 0` whose height `oz + t·dz` lies in `[z_min, z_max]`.
    #[inline(always)]
    pub fn nearest_root(&self, oz: f64, dz: f64, z_min: f64, z_max: f64) -> Option<f64> {
        let (t0, t1, _) = self.roots()?;
        [t0, t1]
            .into_iter()
            .find(|&t| t > 0.0 && in_range(oz + t * dz, z_min, z_max))
    }

    /// For a ray starting on the cylinder (`c ≈ 0`): the root away from its start, `q/a` (the
    /// other, `c/q`, is the start itself), if it lies ahead and within the heights.
    #[inline(always)]
    pub fn other_root(&self, oz: f64, dz: f64, z_min: f64, z_max: f64) -> Option<f64> {
        let (_, _, t) = self.roots()?;
        (t > 0.0 && in_range(oz + t * dz, z_min, z_max)).then_some(t)
    }

    /// The entering root of the solid cylinder between the heights: the smaller root if it lies
    /// ahead (`t > 0`) and within the heights; `0` if the ray starts inside the solid (`c < 0` with
    /// its start between the heights: only rounding puts a ray there, on the surface).
    #[inline(always)]
    pub fn entering_root(&self, oz: f64, dz: f64, z_min: f64, z_max: f64) -> Option<f64> {
        if self.c < 0.0 && in_range(oz, z_min, z_max) {
            return Some(0.0);
        }
        let (t0, _, _) = self.roots()?;
        (t0 > 0.0 && in_range(oz + t0 * dz, z_min, z_max)).then_some(t0)
    }
}

/// Whether `z_min <= z <= z_max`.
#[inline(always)]
fn in_range(z: f64, z_min: f64, z_max: f64) -> bool {
    z >= z_min && z <= z_max
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

/// Distance `t > 0` to the plane `z = h` from height `oz` along vertical component `dz`; the
/// division is done only when the plane lies ahead (`h − oz` and `dz` of the same strict sign).
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
