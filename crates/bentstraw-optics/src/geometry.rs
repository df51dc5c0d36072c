//! Rays and the two shapes the scene is made of: upright cylinders (their side) and horizontal disks.

use crate::Vec3;

/// The smallest distance along a ray at which an intersection counts (metres).
///
/// A ray leaving a surface must not find that same surface again at distance zero; one nanometre is
/// far below any length that matters here (the scene is centimetres) and far above rounding (1e-17 m).
pub const MIN_DISTANCE: f64 = 1e-9;

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
    /// Nearest distance `t > MIN_DISTANCE` at which `ray` meets the side, if any.
    ///
    /// A ray that only grazes the cylinder (tangent) meets it at one point and counts as a hit there.
    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<f64> {
        let px = ray.origin.x - self.cx;
        let py = ray.origin.y - self.cy;
        let (dx, dy) = (ray.direction.x, ray.direction.y);
        let a = dx * dx + dy * dy;
        if a == 0.0 {
            return None; // a vertical ray runs parallel to the side
        }
        let half_b = px * dx + py * dy;
        let c = px * px + py * py - self.radius * self.radius;
        let disc = half_b * half_b - a * c;
        nearest_side_root(
            a,
            half_b,
            c,
            disc,
            ray.origin.z,
            ray.direction.z,
            self.z_min,
            self.z_max,
        )
    }

    /// Outward unit normal at a point `p` of the side.
    #[inline]
    pub fn normal(&self, p: Vec3) -> Vec3 {
        Vec3::new(p.x - self.cx, p.y - self.cy, 0.0).normalize()
    }
}

/// The nearest root `t > MIN_DISTANCE` of an upright cylinder's side, `a t² + 2 half_b t + c = 0`
/// with discriminant `disc = half_b² − a c`, whose height `oz + t·dz` lies in `[z_min, z_max]`.
///
/// The roots in a cancellation-free form: `q = −(half_b + sign(half_b)·√disc)`, `t = q/a` and `c/q`.
/// A vertical ray (`a = 0`) runs parallel to the side; `disc < 0` misses it.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn nearest_side_root(
    a: f64,
    half_b: f64,
    c: f64,
    disc: f64,
    oz: f64,
    dz: f64,
    z_min: f64,
    z_max: f64,
) -> Option<f64> {
    if a == 0.0 || disc < 0.0 {
        return None;
    }
    let sq = disc.sqrt();
    let q = if half_b >= 0.0 {
        -(half_b + sq)
    } else {
        -half_b + sq
    };
    let (mut t0, mut t1) = if q == 0.0 { (0.0, 0.0) } else { (q / a, c / q) };
    if t0 > t1 {
        std::mem::swap(&mut t0, &mut t1);
    }
    for t in [t0, t1] {
        if t > MIN_DISTANCE {
            let z = oz + t * dz;
            if z >= z_min && z <= z_max {
                return Some(t);
            }
        }
    }
    None
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
    /// Distance `t > MIN_DISTANCE` at which `ray` crosses the disk, if it does.
    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<f64> {
        if ray.direction.z == 0.0 {
            return None; // parallel to the plane
        }
        let t = (self.z - ray.origin.z) / ray.direction.z;
        if t <= MIN_DISTANCE {
            return None;
        }
        let x = ray.origin.x + t * ray.direction.x - self.cx;
        let y = ray.origin.y + t * ray.direction.y - self.cy;
        (x * x + y * y <= self.radius * self.radius).then_some(t)
    }
}
