//! Rays, and where a ray's line meets the surfaces scenes are made of: the side of an upright
//! cylinder and a sphere (quadratics), a horizontal plane, a sphere around everything.

use crate::lanes::{Mask, Real, V3};
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

    /// The quadratic of the line from `p` (relative to a sphere's centre) along `d` meeting the
    /// sphere of radius² `r2`: the same form in three dimensions, its discriminant `a·r² − |p ×
    /// d|²` by Lagrange's identity again.
    #[inline(always)]
    pub fn sphere(p: V3<R>, d: V3<R>, r2: R) -> SideQuadratic<R> {
        let a = d.dot(d);
        let cross = V3::new(
            p.y * d.z - p.z * d.y,
            p.z * d.x - p.x * d.z,
            p.x * d.y - p.y * d.x,
        );
        SideQuadratic {
            a,
            half_b: p.dot(d),
            c: p.dot(p) - r2,
            disc: a * r2 - cross.dot(cross),
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

/// The ray moved forward to where it enters the sphere of `centre` and `radius`, and the distance
/// moved; unchanged (distance 0) if it starts inside; `None` if it misses the sphere.
///
/// With a sphere holding every face of a scene, no face lies between a distant origin and the
/// sphere, so the trace is unchanged, but every intersection is then computed from a point near
/// the scene: the rounding of an origin kilometres away (1e-13 m per km) enters once, in the
/// distance moved, instead of in every quadratic.
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

#[cfg(test)]
mod tests {
    //! Where a ray's line meets the side of an upright cylinder: the quadratic every upright
    //! boundary and straw uses, through a small view of it for one ray.

    use super::*;

    /// The side of the upright cylinder of radius 1 around the `z` axis, from `z = -1` to `1`.
    struct UnitCylinder;

    fn unit_cylinder() -> UnitCylinder {
        UnitCylinder
    }

    fn finite(t: f64) -> Option<f64> {
        t.is_finite().then_some(t)
    }

    impl UnitCylinder {
        fn roots(&self, ray: &Ray) -> (SideQuadratic<f64>, SideRoots<f64>) {
            let (o, d) = (ray.origin, ray.direction);
            let q = SideQuadratic::new(o.x, o.y, d.x, d.y, 1.0);
            (q, q.roots(1.0 / q.a))
        }

        /// Nearest distance `t > 0` at which `ray`, not starting on the side, meets it.
        fn intersect(&self, ray: &Ray) -> Option<f64> {
            let (o, d) = (ray.origin, ray.direction);
            finite(self.roots(ray).1.nearest(o.z, d.z, -1.0, 1.0))
        }

        /// Where `ray`, starting on the side, meets it again.
        fn intersect_leaving(&self, ray: &Ray) -> Option<f64> {
            let (o, d) = (ray.origin, ray.direction);
            finite(self.roots(ray).1.other(o.z, d.z, -1.0, 1.0))
        }

        /// Where `ray` enters the solid cylinder through the side (0 if it starts inside).
        fn entry(&self, ray: &Ray) -> Option<f64> {
            let (o, d) = (ray.origin, ray.direction);
            let (q, r) = self.roots(ray);
            finite(r.entering(&q, o.z, d.z, -1.0, 1.0))
        }
    }

    #[test]
    fn cylinder_hit_from_outside_is_the_near_side() {
        let ray = Ray::new(Vec3::new(-5.0, 0.0, 0.0), Vec3::X);
        assert_eq!(unit_cylinder().intersect(&ray), Some(4.0));
    }

    #[test]
    fn cylinder_hit_off_centre_matches_pythagoras() {
        // Impact parameter b = 0.6: the near side is at x = -sqrt(1 - 0.36) = -0.8.
        let ray = Ray::new(Vec3::new(-5.0, 0.6, 0.0), Vec3::X);
        let t = unit_cylinder().intersect(&ray).unwrap();
        assert!((t - 4.2).abs() < 1e-14, "{t}");
    }

    #[test]
    fn cylinder_from_inside_finds_the_far_side() {
        let ray = Ray::new(Vec3::new(0.5, 0.0, 0.0), Vec3::X);
        assert!((unit_cylinder().intersect(&ray).unwrap() - 0.5).abs() < 1e-15);
        // Leaving from a point on the surface, the surface itself (t = 0) does not count.
        let ray = Ray::new(Vec3::new(-1.0, 0.0, 0.0), Vec3::X);
        assert!((unit_cylinder().intersect(&ray).unwrap() - 2.0).abs() < 1e-15);
    }

    #[test]
    fn cylinder_misses() {
        let c = unit_cylinder();
        // Passing beside it.
        assert_eq!(
            c.intersect(&Ray::new(Vec3::new(-5.0, 1.0 + 1e-9, 0.0), Vec3::X)),
            None
        );
        // Pointing away.
        assert_eq!(
            c.intersect(&Ray::new(Vec3::new(-5.0, 0.0, 0.0), Vec3::NEG_X)),
            None
        );
        // Vertical: parallel to the side.
        assert_eq!(
            c.intersect(&Ray::new(Vec3::new(0.5, 0.0, -5.0), Vec3::Z)),
            None
        );
        // Above the side's height range, and below it.
        assert_eq!(
            c.intersect(&Ray::new(Vec3::new(-5.0, 0.0, 1.0 + 1e-9), Vec3::X)),
            None
        );
        assert_eq!(
            c.intersect(&Ray::new(Vec3::new(-5.0, 0.0, -1.0 - 1e-9), Vec3::X)),
            None
        );
    }

    #[test]
    fn cylinder_tangent_ray_touches_once() {
        // Exactly tangent at (0, 1, 0): discriminant zero, one point of contact at t = 5.
        let ray = Ray::new(Vec3::new(-5.0, 1.0, 0.0), Vec3::X);
        assert_eq!(unit_cylinder().intersect(&ray), Some(5.0));
    }

    #[test]
    fn cylinder_slanted_ray_enters_through_the_side_within_its_height() {
        // A ray climbing at 45° meets the side at x = -1, i.e. after 4 units of x, so z = -4.5 + 4 = -0.5.
        let ray = Ray::new(Vec3::new(-5.0, 0.0, -4.5), Vec3::new(1.0, 0.0, 1.0));
        let t = unit_cylinder().intersect(&ray).unwrap();
        let p = ray.at(t);
        assert!(
            (p.x + 1.0).abs() < 1e-12 && (p.z + 0.5).abs() < 1e-12,
            "{p}"
        );
        // Climbing faster, it passes over the near side's top and the far side is too high as well.
        let ray = Ray::new(Vec3::new(-5.0, 0.0, -4.5), Vec3::new(1.0, 0.0, 2.0));
        assert_eq!(unit_cylinder().intersect(&ray), None);
    }

    #[test]
    fn a_distant_ray_meets_the_cylinder_exactly() {
        // From 100 km, impact parameter 0.6: the near side at x = -0.8, so t = 1e5 - 0.8. The
        // discriminant's textbook form half_b² - a·c subtracts two numbers of 1e10 and loses ~1e-6 of
        // it; the cancellation-free form keeps every digit.
        for dist in [1e3, 1e5, 1e7] {
            let ray = Ray::new(Vec3::new(-dist, 0.6, 0.0), Vec3::X);
            let t = unit_cylinder().intersect(&ray).unwrap();
            let want = dist - 0.8;
            assert!(
                (t - want).abs() <= 4.0 * f64::EPSILON * dist,
                "{dist}: {t} vs {want}"
            );
            assert!((ray.at(t).x + 0.8).abs() <= 4.0 * f64::EPSILON * dist);
        }
    }

    #[test]
    fn a_ray_leaving_the_side_meets_it_again_only_across_the_chord() {
        // Start on the surface (rounded: cos and sin are not exact), heading inwards at an angle: the
        // other side is a chord 2·|d·n| away; the start itself never counts, however it rounded.
        let c = unit_cylinder();
        for k in 0..200 {
            let th = 0.0314 * k as f64;
            let p = Vec3::new(th.cos(), th.sin(), 0.0);
            let inward = Vec3::new(-th.cos() + 0.3 * th.sin(), -th.sin() - 0.3 * th.cos(), 0.1);
            let ray = Ray::new(p, inward);
            let n = Vec3::new(p.x, p.y, 0.0);
            let horizontal = Vec3::new(ray.direction.x, ray.direction.y, 0.0);
            let want = 2.0 * horizontal.dot(-n) / horizontal.length_squared();
            let t = c.intersect_leaving(&ray).unwrap();
            assert!((t - want).abs() < 1e-14, "{t} vs {want}");
            // Heading outwards from the surface: no second meeting.
            assert_eq!(c.intersect_leaving(&Ray::new(p, -inward)), None);
        }
    }

    #[test]
    fn a_side_a_hair_away_is_met_a_hair_away() {
        // No minimum distance: 1e-12 m outside the side, moving in, the side is 1e-12 m ahead.
        let ray = Ray::new(Vec3::new(-1.0 - 1e-12, 0.0, 0.0), Vec3::X);
        let t = unit_cylinder().intersect(&ray).unwrap();
        assert!(t > 0.0 && t < 2e-12, "{t}");
        assert!((unit_cylinder().entry(&ray).unwrap() - t).abs() < 1e-20);
    }

    #[test]
    fn an_opaque_solid_is_entered_only_through_its_near_side() {
        let c = unit_cylinder();
        // From outside: the entering root, never the exit one.
        let ray = Ray::new(Vec3::new(-5.0, 0.6, 0.0), Vec3::X);
        assert!((c.entry(&ray).unwrap() - 4.2).abs() < 1e-14);
        // From inside the solid (only rounding puts a ray there): met at once.
        assert_eq!(
            c.entry(&Ray::new(Vec3::new(0.5, 0.0, 0.0), Vec3::X)),
            Some(0.0)
        );
        // From outside, moving away: nothing, even though the line crosses the cylinder behind.
        assert_eq!(
            c.entry(&Ray::new(Vec3::new(-5.0, 0.0, 0.0), Vec3::NEG_X)),
            None
        );
        // Entering above the side's top (through where a cap would be): not through the side.
        let ray = Ray::new(Vec3::new(-5.0, 0.0, 1.5), Vec3::new(1.0, 0.0, -0.1));
        assert_eq!(c.entry(&ray), None);
    }
}
