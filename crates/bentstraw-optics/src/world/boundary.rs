//! The boundaries between media: where light refracts or is totally reflected.
//!
//! A boundary is a piece of one simple surface (a horizontal plane, an upright cylinder's side, a
//! vertical plane) with a medium on each side. The medium inside a container's wall depends on the
//! height (the liquid layers), so a side may be "the cavity", whose media are looked up by height.

use crate::geometry::{plane_distance, Ray, SideQuadratic};
use crate::Vec3;

/// Which medium: an index into the world's table (0 is air, 1 the container, 2 + k the k-th liquid).
pub type MediumId = u16;

/// What lies on one side of a boundary.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Side {
    /// One medium.
    Medium(MediumId),
    /// The inside of the container, whose medium depends on the height (liquid layers, air above).
    Cavity,
}

/// The part of a horizontal plane a boundary covers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Region {
    /// A disk around `(cx, cy)`.
    Disk {
        /// `x` of the centre.
        cx: f64,
        /// `y` of the centre.
        cy: f64,
        /// Radius².
        r2: f64,
    },
    /// A ring around the `z` axis between two radii² (a glass's rim).
    Annulus {
        /// Inner radius².
        inner2: f64,
        /// Outer radius².
        outer2: f64,
    },
    /// A rectangle `|x| <= half_x`, `|y| <= half_y` (a tank's floor or a liquid's surface in it).
    Rectangle {
        /// Half width along `x`.
        half_x: f64,
        /// Half width along `y`.
        half_y: f64,
    },
}

impl Region {
    /// Whether the point `(x, y)` of the plane lies in the region (its edge included).
    #[inline]
    fn contains(&self, x: f64, y: f64) -> bool {
        match *self {
            Region::Disk { cx, cy, r2 } => (x - cx).powi(2) + (y - cy).powi(2) <= r2,
            Region::Annulus { inner2, outer2 } => {
                let q = x * x + y * y;
                q >= inner2 && q <= outer2
            }
            Region::Rectangle { half_x, half_y } => x.abs() <= half_x && y.abs() <= half_y,
        }
    }
}

/// The surface a boundary lies on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// The plane `z = z` over `region`; its outer side is above.
    Horizontal {
        /// Height.
        z: f64,
        /// The part covered.
        region: Region,
    },
    /// The side of an upright cylinder between two heights; its outer side is away from the axis.
    Upright {
        /// `x` of the axis.
        cx: f64,
        /// `y` of the axis.
        cy: f64,
        /// Radius.
        radius: f64,
        /// Lowest height.
        z_min: f64,
        /// Highest height.
        z_max: f64,
    },
    /// The vertical plane `x = at` (`axis` 0) or `y = at` (`axis` 1), where the other horizontal
    /// coordinate is within `±half`, between two heights; its outer side is away from the origin.
    Vertical {
        /// 0 for a plane `x = at`, 1 for `y = at`.
        axis: usize,
        /// Where the plane stands (not 0).
        at: f64,
        /// Half width along the plane.
        half: f64,
        /// Lowest height.
        z_min: f64,
        /// Highest height.
        z_max: f64,
    },
}

/// A boundary between two media.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Boundary {
    /// The surface it lies on.
    pub shape: Shape,
    /// What lies on its outer side (above, away from the axis, away from the origin).
    pub outer: Side,
    /// What lies on its inner side.
    pub inner: Side,
}

/// Whether `z_min <= z <= z_max`.
#[inline(always)]
fn within(z: f64, z_min: f64, z_max: f64) -> bool {
    z >= z_min && z <= z_max
}

impl Boundary {
    /// The distances `t > 0` at which `ray` meets the boundary, nearest first (at most two, the
    /// rest infinite). `leaving` says the ray starts on it, having just met it: its crossing at the
    /// start is excluded exactly (a plane is not met again; a cylinder only at its other root),
    /// never by a minimum distance.
    #[inline]
    pub fn crossings(&self, ray: &Ray, leaving: bool) -> [f64; 2] {
        let (o, d) = (ray.origin, ray.direction);
        let none = [f64::INFINITY; 2];
        match self.shape {
            Shape::Horizontal { z, region } => {
                if leaving {
                    return none;
                }
                match plane_distance(z, o.z, d.z) {
                    Some(t) if region.contains(o.x + t * d.x, o.y + t * d.y) => [t, f64::INFINITY],
                    _ => none,
                }
            }
            Shape::Upright {
                cx,
                cy,
                radius,
                z_min,
                z_max,
            } => {
                let q = SideQuadratic::new(o.x - cx, o.y - cy, d.x, d.y, radius * radius);
                let Some((t0, t1, other)) = q.roots() else {
                    return none;
                };
                let keep = |t: f64| {
                    if t > 0.0 && within(o.z + t * d.z, z_min, z_max) {
                        t
                    } else {
                        f64::INFINITY
                    }
                };
                if leaving {
                    [keep(other), f64::INFINITY]
                } else {
                    // Nearest first, whichever of the two is kept.
                    let (a, b) = (keep(t0), keep(t1));
                    [a.min(b), a.max(b)]
                }
            }
            Shape::Vertical {
                axis,
                at,
                half,
                z_min,
                z_max,
            } => {
                if leaving {
                    return none;
                }
                let (oa, da) = (o[axis], d[axis]);
                match plane_distance(at, oa, da) {
                    Some(t)
                        if (o[1 - axis] + t * d[1 - axis]).abs() <= half
                            && within(o.z + t * d.z, z_min, z_max) =>
                    {
                        [t, f64::INFINITY]
                    }
                    _ => none,
                }
            }
        }
    }

    /// Unit normal at the point `p` of the boundary, pointing to its outer side.
    #[inline]
    pub fn normal(&self, p: Vec3) -> Vec3 {
        match self.shape {
            Shape::Horizontal { .. } => Vec3::Z,
            Shape::Upright { cx, cy, .. } => Vec3::new(p.x - cx, p.y - cy, 0.0).normalize(),
            Shape::Vertical { axis, at, .. } => {
                let mut n = Vec3::ZERO;
                n[axis] = at.signum();
                n
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
        Ray::new(Vec3::from_array(o), Vec3::from_array(d))
    }

    fn boundary(shape: Shape) -> Boundary {
        Boundary {
            shape,
            outer: Side::Medium(0),
            inner: Side::Medium(2),
        }
    }

    #[test]
    fn a_horizontal_region_is_crossed_inside_and_missed_outside() {
        let disk = boundary(Shape::Horizontal {
            z: 0.1,
            region: Region::Disk {
                cx: 0.0,
                cy: 0.0,
                r2: 0.04 * 0.04,
            },
        });
        let down = ray([0.01, 0.0, 0.3], [0.0, 0.0, -1.0]);
        assert_eq!(disk.crossings(&down, false)[0], 0.3 - 0.1);
        // Leaving it: not met again.
        assert_eq!(disk.crossings(&down, true), [f64::INFINITY; 2]);
        // Outside the disk, parallel to it, or going away: missed.
        assert!(disk.crossings(&ray([0.05, 0.0, 0.3], [0.0, 0.0, -1.0]), false)[0].is_infinite());
        assert!(disk.crossings(&ray([0.0, 0.0, 0.1], [1.0, 0.0, 0.0]), false)[0].is_infinite());
        assert!(disk.crossings(&ray([0.0, 0.0, 0.3], [0.0, 0.0, 1.0]), false)[0].is_infinite());
        // A ring holds what lies between its radii only; a rectangle its half widths.
        let ring = boundary(Shape::Horizontal {
            z: 0.0,
            region: Region::Annulus {
                inner2: 0.0375 * 0.0375,
                outer2: 0.04 * 0.04,
            },
        });
        assert!(ring.crossings(&ray([0.039, 0.0, 1.0], [0.0, 0.0, -1.0]), false)[0] == 1.0);
        assert!(ring.crossings(&ray([0.03, 0.0, 1.0], [0.0, 0.0, -1.0]), false)[0].is_infinite());
        let rect = boundary(Shape::Horizontal {
            z: 0.0,
            region: Region::Rectangle {
                half_x: 0.1,
                half_y: 0.05,
            },
        });
        assert!(rect.crossings(&ray([0.09, -0.05, 1.0], [0.0, 0.0, -1.0]), false)[0] == 1.0);
        assert!(rect.crossings(&ray([0.09, 0.06, 1.0], [0.0, 0.0, -1.0]), false)[0].is_infinite());
    }

    #[test]
    fn an_upright_side_gives_both_crossings_in_order_and_only_the_far_one_when_leaving() {
        let side = boundary(Shape::Upright {
            cx: 0.0,
            cy: 0.0,
            radius: 0.04,
            z_min: 0.0,
            z_max: 0.2,
        });
        let through = ray([-1.0, 0.0, 0.1], [1.0, 0.0, 0.0]);
        let [a, b] = side.crossings(&through, false);
        assert!(
            (a - 0.96).abs() < 1e-15 && (b - 1.04).abs() < 1e-15,
            "{a} {b}"
        );
        // From the near crossing, leaving the side inwards: only the far one.
        let inside = ray([-0.04, 0.0, 0.1], [1.0, 0.0, 0.0]);
        let [c, d] = side.crossings(&inside, true);
        assert!((c - 0.08).abs() < 1e-15 && d.is_infinite(), "{c} {d}");
        // Above its top: no crossing; starting inside: the far one only, in order.
        assert!(side.crossings(&ray([-1.0, 0.0, 0.3], [1.0, 0.0, 0.0]), false)[0].is_infinite());
        let [e, f] = side.crossings(&ray([0.0, 0.0, 0.1], [1.0, 0.0, 0.0]), false);
        assert!((e - 0.04).abs() < 1e-15 && f.is_infinite());
        // A line passing beside it misses; the normal points away from the axis.
        assert!(side.crossings(&ray([-1.0, 0.05, 0.1], [1.0, 0.0, 0.0]), false)[0].is_infinite());
        assert_eq!(side.normal(Vec3::new(0.0, -0.04, 0.1)), Vec3::NEG_Y);
    }

    #[test]
    fn a_tank_wall_is_a_bounded_vertical_plane_facing_away_from_the_middle() {
        let wall = boundary(Shape::Vertical {
            axis: 1,
            at: -0.05,
            half: 0.1,
            z_min: 0.0,
            z_max: 0.2,
        });
        assert_eq!(wall.normal(Vec3::ZERO), Vec3::NEG_Y);
        let r = ray([0.02, 0.5, 0.1], [0.0, -1.0, 0.0]);
        assert!((wall.crossings(&r, false)[0] - 0.55).abs() < 1e-15);
        assert!(wall.crossings(&r, true)[0].is_infinite());
        // Beyond its ends, above its top: missed.
        assert!(wall.crossings(&ray([0.11, 0.5, 0.1], [0.0, -1.0, 0.0]), false)[0].is_infinite());
        assert!(wall.crossings(&ray([0.0, 0.5, 0.25], [0.0, -1.0, 0.0]), false)[0].is_infinite());
    }
}
