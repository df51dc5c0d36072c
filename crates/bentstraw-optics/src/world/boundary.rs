//! The boundaries between media: where light refracts or is totally reflected.
//!
//! A boundary is a piece of one simple surface (a horizontal plane, an upright cylinder's side, a
//! vertical plane, a sphere) with one medium on each side. Where the medium inside a container's wall
//! changes with the height (liquid layers, air above them), the wall is cut into one boundary per
//! layer, so that every boundary knows both its media.

use crate::geometry::{in_range, plane_ahead, plane_distance_of, SideQuadratic, SideRoots};
use crate::lanes::{Constant, Mask, Real, V3};
use crate::Vec3;

/// Which medium: an index into the world's table (0 is air, 1 the container, 2 + k the k-th liquid).
pub type MediumId = u16;

/// The part of a horizontal plane a boundary covers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Region {
    /// A disk around `(cx, cy)`.
    Disk {
        /// `x` of the centre.
        cx: f64,
        /// `y` of the centre.
        cy: f64,
        /// Radius.
        radius: f64,
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
    /// Whether the points `(x, y)` of the plane lie in the region (its edge included).
    #[inline(always)]
    pub fn contains<R: Real>(&self, x: R, y: R) -> R::Mask {
        match *self {
            Region::Disk { cx, cy, radius } => {
                let (u, v) = (x - R::splat(cx), y - R::splat(cy));
                (u * u + v * v).le(R::splat(radius * radius))
            }
            Region::Annulus { inner2, outer2 } => {
                let q = x * x + y * y;
                q.ge(R::splat(inner2)).and(q.le(R::splat(outer2)))
            }
            Region::Rectangle { half_x, half_y } => x
                .abs()
                .le(R::splat(half_x))
                .and(y.abs().le(R::splat(half_y))),
        }
    }

    /// The largest distance of a point of the region from the `z` axis.
    pub(crate) fn reach(&self) -> f64 {
        match *self {
            Region::Disk { cx, cy, radius } => libm::hypot(cx, cy) + radius,
            Region::Annulus { outer2, .. } => outer2.sqrt(),
            Region::Rectangle { half_x, half_y } => libm::hypot(half_x, half_y),
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
    /// A vertical rectangle: from `(ax, ay)` along the horizontal unit `(ux, uy)` for `length`,
    /// between two heights (a prism's side); its outer side is to the right of `u` seen from
    /// above (away from a counterclockwise polygon's inside).
    Face {
        /// `x` of its first edge.
        ax: f64,
        /// `y` of its first edge.
        ay: f64,
        /// `x` of the unit vector along it.
        ux: f64,
        /// `y` of the unit vector along it.
        uy: f64,
        /// Its width.
        length: f64,
        /// Lowest height.
        z_min: f64,
        /// Highest height.
        z_max: f64,
    },
    /// A lens's curved face: the cap of the sphere of `centre` and radius `|radius|` on the side
    /// `toward` points to (unit), within `√rho2` of the line through the centre along it. Its
    /// outer side is away from the centre when `radius > 0`, towards it when `radius < 0`.
    Cap {
        /// The sphere's centre.
        centre: Vec3,
        /// Its radius, signed by the side the outer medium is on.
        radius: f64,
        /// Unit vector from the centre towards the cap's vertex (along the lens's axis).
        toward: Vec3,
        /// The square of the cap's rim's distance from the axis.
        rho2: f64,
        /// Lowest height (−∞ unless a liquid's surface cuts the lens).
        z_min: f64,
        /// Highest height (+∞ unless a liquid's surface cuts the lens).
        z_max: f64,
    },
    /// A lens's flat face: the disk of radius² `r2` about `centre` in the plane of unit
    /// `normal`, which points to its outer side.
    Disk {
        /// Its centre.
        centre: Vec3,
        /// Its unit normal, to its outer side.
        normal: Vec3,
        /// Its radius².
        r2: f64,
        /// Lowest height (−∞ unless a liquid's surface cuts the lens).
        z_min: f64,
        /// Highest height (+∞ unless a liquid's surface cuts the lens).
        z_max: f64,
    },
    /// A lens's rim: the side of the cylinder of radius² `r2` about the line through `centre`
    /// along unit `axis`, between axial coordinates `w_min` and `w_max` from the centre; its
    /// outer side is away from the axis.
    Tube {
        /// A point of its axis (the lens's centre).
        centre: Vec3,
        /// Unit vector along its axis.
        axis: Vec3,
        /// Its radius².
        r2: f64,
        /// Lowest axial coordinate.
        w_min: f64,
        /// Highest axial coordinate.
        w_max: f64,
        /// Lowest height (−∞ unless a liquid's surface cuts the lens).
        z_min: f64,
        /// Highest height (+∞ unless a liquid's surface cuts the lens).
        z_max: f64,
    },
    /// A piece of a container of revolution's wall (see [`crate::profile`]): the surface
    /// `x² + y² = c0 + c1·u + c2·u²`, `u = z − zc`, between two heights; its outer side is away
    /// from the axis.
    Revolution {
        /// The height the quadratic is written about.
        zc: f64,
        /// Its coefficients.
        c: [f64; 3],
        /// Lowest height of this boundary.
        z_min: f64,
        /// Highest height of this boundary.
        z_max: f64,
        /// Lowest height of the whole piece of the wall on this quadric (a liquid's surface
        /// cuts a piece in boundaries): a ray leaving from there leaves this quadric.
        q_min: f64,
        /// Highest height of the whole piece.
        q_max: f64,
    },
    /// A sphere (the part of it between two heights); its outer side is away from its centre.
    Sphere {
        /// Its centre.
        centre: Vec3,
        /// Its radius.
        radius: f64,
        /// Lowest height (−∞ for the whole sphere: no rounding then loses its poles).
        z_min: f64,
        /// Highest height (+∞ for the whole sphere).
        z_max: f64,
    },
}

/// The container's and liquids' three plain shapes alone (a plane over a region, an upright
/// cylinder's side, a tank's wall), as the lean loop over their faces reads them: a compact copy
/// of their [`Shape`], so that the scenes without solids trace with the code and the data they
/// always had.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum PlainShape {
    Horizontal {
        z: f64,
        region: Region,
    },
    Upright {
        cx: f64,
        cy: f64,
        radius: f64,
        z_min: f64,
        z_max: f64,
    },
    Vertical {
        axis: usize,
        at: f64,
        half: f64,
        z_min: f64,
        z_max: f64,
    },
}

/// A face of the container or a liquid as the lean loop reads it: its shape, the numbers its
/// lanes are compared with, and what solids take from it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PlainFace {
    pub shape: PlainShape,
    pub codes: Codes,
    pub holes: [u16; 2],
}

impl PlainShape {
    /// [`Boundary::crossing`] for this shape.
    #[inline(always)]
    pub(crate) fn crossing<R: Real>(
        &self,
        o: V3<R>,
        d: V3<R>,
        inv: &Reciprocals<R>,
        leaving: R::Mask,
        alive: R::Mask,
        around: &Around<R>,
    ) -> R {
        let inf = R::splat(f64::INFINITY);
        if let PlainShape::Horizontal { z, region } = *self {
            let (num, ahead) = plane_ahead(R::splat(z), o.z, d.z);
            let ahead = ahead.and_not(leaving).and(alive);
            if !ahead.any() {
                return inf;
            }
            let t = plane_distance_of(num, d.z, inv.d.z);
            let inside = region.contains(o.x + t * d.x, o.y + t * d.y);
            R::select(ahead.and(inside), t, inf)
        } else if let PlainShape::Upright {
            cx,
            cy,
            radius,
            z_min,
            z_max,
        } = *self
        {
            // The circle the whole scene lies within is often this one: its quadratic is done.
            let q = if cx == 0.0 && cy == 0.0 && radius * radius == around.r2 {
                around.quadratic
            } else {
                SideQuadratic::new(
                    o.x - R::splat(cx),
                    o.y - R::splat(cy),
                    d.x,
                    d.y,
                    R::splat(radius * radius),
                )
            };
            // A ray outside the cylinder moving away from it meets it nowhere ahead.
            if !alive.and(q.real()).and_not(q.moving_away()).any() {
                return inf;
            }
            let roots = q.roots(inv.a);
            let (zl, zh) = (R::splat(z_min), R::splat(z_max));
            let leaving = leaving.and(alive);
            if !leaving.any() {
                roots.nearest(o.z, d.z, zl, zh)
            } else if !alive.and_not(leaving).any() {
                roots.other(o.z, d.z, zl, zh)
            } else {
                R::select(
                    leaving,
                    roots.other(o.z, d.z, zl, zh),
                    roots.nearest(o.z, d.z, zl, zh),
                )
            }
        } else if let PlainShape::Vertical {
            axis,
            at,
            half,
            z_min,
            z_max,
        } = *self
        {
            let (num, ahead) = plane_ahead(R::splat(at), o.get(axis), d.get(axis));
            let ahead = ahead.and_not(leaving).and(alive);
            if !ahead.any() {
                return inf;
            }
            let t = plane_distance_of(num, d.get(axis), inv.d.get(axis));
            let across = o.get(1 - axis) + t * d.get(1 - axis);
            let ok = ahead.and(across.abs().le(R::splat(half))).and(in_range(
                o.z + t * d.z,
                R::splat(z_min),
                R::splat(z_max),
            ));
            R::select(ok, t, inf)
        } else {
            inf
        }
    }

    /// [`Boundary::normal_at`] for this shape.
    #[inline(always)]
    pub(crate) fn normal_at<R: Real>(&self, p: V3<R>) -> V3<R> {
        let zero = R::splat(0.0);
        match *self {
            PlainShape::Horizontal { .. } => V3::new(zero, zero, R::splat(1.0)),
            PlainShape::Upright { cx, cy, radius, .. } => {
                let (r, inv) = (R::splat(radius), R::splat(1.0 / radius));
                let x = R::quotient(p.x - R::splat(cx), r, inv);
                let y = R::quotient(p.y - R::splat(cy), r, inv);
                V3::new(x, y, zero).renormalize()
            }
            PlainShape::Vertical { axis, at, .. } => {
                let s = R::splat(at.signum());
                if axis == 0 {
                    V3::new(s, zero, zero)
                } else {
                    V3::new(zero, s, zero)
                }
            }
        }
    }
}

impl Shape {
    /// Its plain form, for the container's and liquids' shapes.
    #[inline(always)]
    pub(crate) fn plain(&self) -> Option<PlainShape> {
        match *self {
            Shape::Horizontal { z, region } => Some(PlainShape::Horizontal { z, region }),
            Shape::Upright {
                cx,
                cy,
                radius,
                z_min,
                z_max,
            } => Some(PlainShape::Upright {
                cx,
                cy,
                radius,
                z_min,
                z_max,
            }),
            Shape::Vertical {
                axis,
                at,
                half,
                z_min,
                z_max,
            } => Some(PlainShape::Vertical {
                axis,
                at,
                half,
                z_min,
                z_max,
            }),
            _ => None,
        }
    }

    /// Whether it is one of the container's and liquids' plain shapes (a plane, an upright
    /// cylinder's side, a tank's wall), which the lean loop reads.
    pub(crate) fn is_plain(&self) -> bool {
        self.plain().is_some()
    }
}

/// A boundary between two media.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Boundary {
    /// The surface it lies on.
    pub shape: Shape,
    /// The medium on its outer side (above, away from the axis, away from the origin).
    pub outer: MediumId,
    /// The medium on its inner side.
    pub inner: MediumId,
    /// Which whole surface it is part of: a ray that leaves a surface at a point of it does not
    /// meet that surface again there, whichever boundary of it the point belongs to.
    pub surface: u32,
    /// The side a ray leaving it escapes to for good (+1 the outer side, −1 the inner side, 0
    /// none): the side beyond which nothing of the scene lies (the scene's convex hull ends here).
    pub escape: i8,
    /// The indices on its outer and inner sides, and their ratios `n_outer/n_inner` (light going
    /// in) and `n_inner/n_outer` (going out), worked out once.
    pub(crate) optics: Optics,
    /// Its numbers that the tracers compare lanes with, worked out once.
    pub(crate) codes: Codes,
    /// What solids take from a horizontal face, or the polygon a prism's own top or bottom
    /// is: the range of [`Clip`]s in the world's list, empty for most faces.
    pub(crate) holes: [u16; 2],
    /// Whether it is a transparent solid's face (light entering there enters the solid).
    pub solid: bool,
    /// Which solid it is a face of (its own medium's number as built), for a solid's face.
    pub(crate) body: u16,
}

/// What a transparent solid makes of a horizontal face: where a solid pierces it, its
/// cross-section is no part of it (a ball half in the water has no water surface inside it); a
/// prism's top and bottom are the plane within its polygon only.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Clip {
    /// No part of the face lies in this disk.
    OutsideDisk {
        /// `x` of the disk's centre.
        cx: f64,
        /// `y` of the disk's centre.
        cy: f64,
        /// Its radius².
        r2: f64,
    },
    /// No part of the face lies in the convex polygon of these edges (a range of the world's
    /// [`Edge`]s).
    OutsidePolygon([u16; 2]),
    /// The face lies in the convex polygon of these edges only.
    InsidePolygon([u16; 2]),
    /// No part of the face lies inside this lens (the world's [`LensHole`] of this number).
    OutsideLens(u16),
}

/// A lens as a face it pierces (a liquid's surface) sees it: the solid between its two faces
/// within its rim, to test points against.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LensHole {
    /// Its centre.
    pub centre: Vec3,
    /// Its unit axis.
    pub axis: Vec3,
    /// Its rim's radius².
    pub rim2: f64,
    /// Its faces' vertices' axial coordinates from the centre, and their signed radii (0 flat).
    pub w1: f64,
    pub r1: f64,
    pub w2: f64,
    pub r2: f64,
}

impl LensHole {
    /// The lanes whose point `(x, y, z)` lies inside the lens: within its rim, beyond face 1
    /// and before face 2 along its axis (each face at its vertex plus its sag there).
    #[inline(always)]
    pub fn holds<R: Real>(&self, x: R, y: R, z: R) -> R::Mask {
        let v = V3::new(x, y, z) - V3::splat(self.centre);
        let w = v.dot(V3::splat(self.axis));
        let rho2 = v.dot(v) - w * w;
        rho2.lt(R::splat(self.rim2))
            .and(w.gt(R::splat(self.w1) + sag(self.r1, rho2)))
            .and(w.lt(R::splat(self.w2) + sag(self.r2, rho2)))
    }
}

/// How far along the axis a lens's face of signed radius `r` (0 flat) lies from its vertex at
/// the squared distance `rho2` from the axis. A function, not a closure: it must be inlined into
/// the packets' code compiled for their instruction set.
#[inline(always)]
fn sag<R: Real>(r: f64, rho2: R) -> R {
    if r == 0.0 {
        R::splat(0.0)
    } else {
        let under = (R::splat(r * r) - rho2).max(R::splat(0.0));
        R::splat(r) - R::splat(r.signum()) * under.sqrt()
    }
}

/// An edge of a counterclockwise convex polygon seen from above: from `(ax, ay)` along `(ex,
/// ey)`; the polygon lies to its left.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Edge {
    pub ax: f64,
    pub ay: f64,
    pub ex: f64,
    pub ey: f64,
}

/// A boundary's whole numbers as the tracers' lanes hold them: its place in the world's list, its
/// surface, and the media on its two sides. Stored as `f32` (exact for whole numbers, in either
/// precision) so that the packets load them as they are instead of converting an integer at every
/// step.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Codes {
    pub index: f32,
    pub surface: f32,
    pub inner: f32,
    pub outer: f32,
}

/// A boundary's indices and their ratios.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Optics {
    pub n_outer: Constant,
    pub n_inner: Constant,
    pub eta_in: Constant,
    pub eta_out: Constant,
}

impl Optics {
    /// Between media of indices `n_outer` and `n_inner`.
    pub fn new(n_outer: f64, n_inner: f64) -> Optics {
        Optics {
            n_outer: Constant::new(n_outer),
            n_inner: Constant::new(n_inner),
            eta_in: Constant::new(n_outer / n_inner),
            eta_out: Constant::new(n_inner / n_outer),
        }
    }
}

/// The lanes whose point `p + t·d` (relative to a cap's sphere's centre) lies on the cap: ahead,
/// on the side `h` points to, within the rim (a hair wide, so that no ray slips between the cap
/// and the rim by rounding). A function, not a closure: it must be inlined into the packets'
/// code compiled for their instruction set.
#[inline(always)]
fn on_cap<R: Real>(p: V3<R>, d: V3<R>, h: V3<R>, rho2: f64, t: R, heights: (R, R)) -> R::Mask {
    let x = p.along(t, d);
    let w = x.dot(h);
    t.gt(R::splat(0.0))
        .and(w.ge(R::splat(0.0)))
        .and((x.dot(x) - w * w).le(R::splat(rho2 * (1.0 + 1e-12))))
        .and(in_range(x.z, heights.0, heights.1))
}

/// The lanes whose point at `t` lies on a lens's rim: ahead, between its axial coordinates
/// (`pw + t·dw`) and between its heights (`oz + t·dz`). A function, not a closure (see
/// [`on_cap`]).
#[inline(always)]
fn on_tube<R: Real>(t: R, along: (R, R), w: (R, R), z: (R, R), heights: (R, R)) -> R::Mask {
    t.gt(R::splat(0.0))
        .and(in_range(along.0 + t * along.1, w.0, w.1))
        .and(in_range(z.0 + t * z.1, heights.0, heights.1))
}

/// The circle around the `z` axis that holds the whole scene: its radius² and the quadratic of
/// the rays' lines meeting it, worked out once per search.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Around<R> {
    /// Radius² (m²).
    pub r2: f64,
    /// The rays' quadratic for it.
    pub quadratic: SideQuadratic<R>,
}

/// `1/d` of a ray's components and of `a = dx² + dy²`, computed once per ray for the packets'
/// quotients (see [`Real::quotient`]; one ray divides instead, and never reads them).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Reciprocals<R> {
    /// `1/dx`, `1/dy`, `1/dz`.
    pub d: V3<R>,
    /// `1/(dx² + dy²)`.
    pub a: R,
}

impl<R: Real> Reciprocals<R> {
    /// The reciprocals of direction `d`'s components.
    #[inline(always)]
    pub fn new(d: V3<R>) -> Reciprocals<R> {
        let one = R::splat(1.0);
        Reciprocals {
            d: V3::new(one / d.x, one / d.y, one / d.z),
            a: one / (d.x * d.x + d.y * d.y),
        }
    }
}

impl Boundary {
    /// The distance `t > 0` at which each ray from `o` along `d` first meets the boundary
    /// (infinite where it does not). In the lanes of `leaving` the ray starts on this boundary's
    /// surface, having just met it: its crossing at the start is excluded exactly (a plane is not
    /// met again; a cylinder only at its other root), never by a minimum distance.
    #[inline(always)]
    pub(crate) fn crossing<R: Real>(
        &self,
        o: V3<R>,
        d: V3<R>,
        inv: &Reciprocals<R>,
        leaving: R::Mask,
        alive: R::Mask,
        around: &Around<R>,
    ) -> R {
        let inf = R::splat(f64::INFINITY);
        match self.shape {
            Shape::Horizontal { .. } | Shape::Upright { .. } | Shape::Vertical { .. } => {
                self.plain_crossing(o, d, inv, leaving, alive, around)
            }
            Shape::Face {
                ax,
                ay,
                ux,
                uy,
                length,
                z_min,
                z_max,
            } => {
                // The plane n·p = n·a, n = (uy, −ux) its outer normal.
                let (nx, ny) = (R::splat(uy), R::splat(-ux));
                let den = nx * d.x + ny * d.y;
                let (num, ahead) =
                    plane_ahead(R::splat(uy * ax - ux * ay), nx * o.x + ny * o.y, den);
                let ahead = ahead.and_not(leaving).and(alive);
                if !ahead.any() {
                    return inf;
                }
                let t = R::quotient(num, den, R::splat(1.0) / den);
                let along = R::splat(ux) * (o.x + t * d.x - R::splat(ax))
                    + R::splat(uy) * (o.y + t * d.y - R::splat(ay));
                let ok = ahead
                    .and(in_range(along, R::splat(0.0), R::splat(length)))
                    .and(in_range(o.z + t * d.z, R::splat(z_min), R::splat(z_max)));
                R::select(ok, t, inf)
            }
            Shape::Cap {
                centre,
                radius,
                toward,
                rho2,
                z_min,
                z_max,
            } => {
                let p = o - V3::splat(centre);
                let q = SideQuadratic::sphere(p, d, R::splat(radius * radius));
                if !alive.and(q.real()).and_not(q.moving_away()).any() {
                    return inf;
                }
                let roots = q.roots(R::splat(1.0) / q.a);
                let h = V3::splat(toward);
                // Its heights as the centre's offsets (its points are taken from the centre).
                let zs = (R::splat(z_min - centre.z), R::splat(z_max - centre.z));
                let leaving = leaving.and(alive);
                let near = R::select(on_cap(p, d, h, rho2, roots.near, zs), roots.near, inf);
                let near = R::select(
                    near.lt(inf),
                    near,
                    R::select(on_cap(p, d, h, rho2, roots.far, zs), roots.far, inf),
                );
                let other = R::select(
                    on_cap(p, d, h, rho2, roots.q_over_a, zs),
                    roots.q_over_a,
                    inf,
                );
                R::select(roots.real.and(alive), R::select(leaving, other, near), inf)
            }
            Shape::Disk {
                centre,
                normal,
                r2,
                z_min,
                z_max,
            } => {
                let n = V3::splat(normal);
                let den = n.dot(d);
                let (num, ahead) = plane_ahead(R::splat(normal.dot(centre)), n.dot(o), den);
                let ahead = ahead.and_not(leaving).and(alive);
                if !ahead.any() {
                    return inf;
                }
                let t = R::quotient(num, den, R::splat(1.0) / den);
                let x = o.along(t, d) - V3::splat(centre);
                let ok = ahead
                    .and(x.dot(x).le(R::splat(r2 * (1.0 + 1e-12))))
                    .and(in_range(
                        x.z,
                        R::splat(z_min - centre.z),
                        R::splat(z_max - centre.z),
                    ));
                R::select(ok, t, inf)
            }
            Shape::Tube {
                centre,
                axis,
                r2,
                w_min,
                w_max,
                z_min,
                z_max,
            } => {
                let a = V3::splat(axis);
                let p = o - V3::splat(centre);
                let (pw, dw) = (p.dot(a), d.dot(a));
                let (pp, dp) = (p - a.scale(pw), d - a.scale(dw));
                let cross = V3::new(
                    pp.y * dp.z - pp.z * dp.y,
                    pp.z * dp.x - pp.x * dp.z,
                    pp.x * dp.y - pp.y * dp.x,
                );
                let a2 = dp.dot(dp);
                let r2 = R::splat(r2);
                let q = SideQuadratic {
                    a: a2,
                    half_b: pp.dot(dp),
                    c: pp.dot(pp) - r2,
                    disc: a2 * r2 - cross.dot(cross),
                };
                if !alive.and(q.real()).and_not(q.moving_away()).any() {
                    return inf;
                }
                let roots = q.roots(R::splat(1.0) / a2);
                let (w, zs) = (
                    (R::splat(w_min), R::splat(w_max)),
                    (R::splat(z_min), R::splat(z_max)),
                );
                let leaving = leaving.and(alive);
                let (along, z) = ((pw, dw), (o.z, d.z));
                let near = R::select(on_tube(roots.near, along, w, z, zs), roots.near, inf);
                let near = R::select(
                    near.lt(inf),
                    near,
                    R::select(on_tube(roots.far, along, w, z, zs), roots.far, inf),
                );
                let other = R::select(
                    on_tube(roots.q_over_a, along, w, z, zs),
                    roots.q_over_a,
                    inf,
                );
                R::select(roots.real.and(alive), R::select(leaving, other, near), inf)
            }
            Shape::Revolution {
                zc,
                c,
                z_min,
                z_max,
                q_min,
                q_max,
            } => {
                let u = o.z - R::splat(zc);
                let (c1, c2) = (R::splat(c[1]), R::splat(c[2]));
                let a_h = d.x * d.x + d.y * d.y;
                let h = o.x * d.x + o.y * d.y;
                let p2 = o.x * o.x + o.y * o.y;
                let f = R::splat(c[0]) + u * (c1 + u * c2);
                let g = R::splat(0.5) * c1 + c2 * u;
                let cross = o.x * d.y - o.y * d.x;
                // a·t² + 2·half_b·t + c: the line's squared distance from the axis less the
                // profile's squared radius at its height.
                let a = a_h - c2 * d.z * d.z;
                let half_b = h - d.z * g;
                let cc = p2 - f;
                // half_b² − a·c, rearranged as for a cylinder (Lagrange's identity takes out
                // the huge equal terms): `(c1/2)² − c0·c2` is the profile's own discriminant.
                let disc = a_h * f - cross * cross - R::splat(2.0) * h * d.z * g
                    + d.z * d.z * (R::splat(0.25 * c[1] * c[1] - c[0] * c[2]) + c2 * p2);
                let zero = R::splat(0.0);
                let live = alive.and(disc.ge(zero));
                if !live.any() {
                    return inf;
                }
                let sq = R::select(live, disc, zero).sqrt();
                let q = R::select(half_b.ge(zero), -(half_b + sq), -half_b + sq);
                let real = live.and_not(q.eq(zero));
                // `a` may be 0 or negative (a ray as steep as a cone's side): q/a is then
                // infinite or the far root, which the heights sort out.
                let r1 = q / a;
                let r2 = cc / q;
                let roots = SideRoots {
                    near: r1.min(r2),
                    far: r1.max(r2),
                    q_over_a: r1,
                    real,
                };
                let (zl, zh) = (R::splat(z_min), R::splat(z_max));
                // Leaving this quadric (a ray starting on its piece of the wall): the other root.
                let leaving =
                    leaving
                        .and(alive)
                        .and(in_range(o.z, R::splat(q_min), R::splat(q_max)));
                let t = R::select(
                    leaving,
                    roots.other(o.z, d.z, zl, zh),
                    roots.nearest(o.z, d.z, zl, zh),
                );
                // One Newton step on the line's x² + y² − r²(z) from the root found: for a
                // strongly curved piece seen from afar the quadratic's terms cancel to a few
                // digits, which the step gives back (a step larger than 10 nm, near grazing
                // where the slope vanishes, is not taken).
                let found = t.lt(inf);
                let ts = R::select(found, t, zero);
                let (x, y) = (o.x + ts * d.x, o.y + ts * d.y);
                let u = o.z + ts * d.z - R::splat(zc);
                let off = x * x + y * y - (R::splat(c[0]) + u * (c1 + u * c2));
                let two = R::splat(2.0);
                let slope = two * (x * d.x + y * d.y) - (c1 + two * c2 * u) * d.z;
                let steep = slope.abs().gt(R::splat(1e-12));
                let step = off / R::select(steep, slope, R::splat(1.0));
                let take = found.and(steep).and(step.abs().lt(R::splat(1e-8)));
                R::select(take, t - step, t)
            }
            Shape::Sphere {
                centre,
                radius,
                z_min,
                z_max,
            } => {
                let q = SideQuadratic::sphere(o - V3::splat(centre), d, R::splat(radius * radius));
                // A ray outside the sphere moving away from it meets it nowhere ahead.
                if !alive.and(q.real()).and_not(q.moving_away()).any() {
                    return inf;
                }
                // `a = |d|²`, 1 to rounding: divided by, not multiplied by its reciprocal.
                let roots = q.roots(R::splat(1.0) / q.a);
                let (zl, zh) = (R::splat(z_min), R::splat(z_max));
                let leaving = leaving.and(alive);
                R::select(
                    leaving,
                    roots.other(o.z, d.z, zl, zh),
                    roots.nearest(o.z, d.z, zl, zh),
                )
            }
        }
    }

    /// [`Boundary::crossing`] for the container's and liquids' faces alone (a plane, an
    /// upright cylinder's side, a tank's wall; a solid's face gives infinity here).
    #[inline(always)]
    pub(crate) fn plain_crossing<R: Real>(
        &self,
        o: V3<R>,
        d: V3<R>,
        inv: &Reciprocals<R>,
        leaving: R::Mask,
        alive: R::Mask,
        around: &Around<R>,
    ) -> R {
        match self.shape.plain() {
            Some(shape) => shape.crossing(o, d, inv, leaving, alive, around),
            None => R::splat(f64::INFINITY),
        }
    }

    /// Unit normal at the points `p` of the boundary, pointing to its outer side: for an upright
    /// side `((p − c)/r).normalize()`, the form the assignment's glass always used.
    #[inline(always)]
    pub(crate) fn normal_at<R: Real>(&self, p: V3<R>) -> V3<R> {
        let zero = R::splat(0.0);
        match self.shape {
            Shape::Horizontal { .. } | Shape::Upright { .. } | Shape::Vertical { .. } => {
                self.plain_normal_at(p)
            }
            Shape::Face { ux, uy, .. } => V3::new(R::splat(uy), R::splat(-ux), zero),
            Shape::Disk { normal, .. } => V3::splat(normal),
            Shape::Revolution { zc, c, .. } => {
                // The gradient of x² + y² − r²(z), halved.
                let g = R::splat(0.5 * c[1]) + R::splat(c[2]) * (p.z - R::splat(zc));
                V3::new(p.x, p.y, -g).normalize()
            }
            Shape::Tube { centre, axis, .. } => {
                let a = V3::splat(axis);
                let q = p - V3::splat(centre);
                (q - a.scale(q.dot(a))).normalize()
            }
            // A cap's radius is signed by its outer side: the same rule.
            Shape::Sphere { centre, radius, .. } | Shape::Cap { centre, radius, .. } => {
                let (r, inv) = (R::splat(radius), R::splat(1.0 / radius));
                let q = p - V3::splat(centre);
                V3::new(
                    R::quotient(q.x, r, inv),
                    R::quotient(q.y, r, inv),
                    R::quotient(q.z, r, inv),
                )
                .renormalize()
            }
        }
    }

    /// [`Boundary::normal_at`] for the container's and liquids' faces alone (a solid's face
    /// gives the zero vector here).
    #[inline(always)]
    pub(crate) fn plain_normal_at<R: Real>(&self, p: V3<R>) -> V3<R> {
        match self.shape.plain() {
            Some(shape) => shape.normal_at(p),
            None => V3::splat(Vec3::ZERO),
        }
    }

    /// Unit normal at the point `p` of the boundary, pointing to its outer side.
    #[inline]
    pub fn normal(&self, p: Vec3) -> Vec3 {
        self.normal_at(V3::<f64>::from(p)).into()
    }

    /// The largest distance of a point of the boundary from the `z` axis.
    pub(crate) fn reach(&self) -> f64 {
        match self.shape {
            Shape::Horizontal { region, .. } => region.reach(),
            Shape::Upright { cx, cy, radius, .. } => libm::hypot(cx, cy) + radius,
            Shape::Vertical { at, half, .. } => libm::hypot(at, half),
            Shape::Sphere { centre, radius, .. } => libm::hypot(centre.x, centre.y) + radius,
            Shape::Revolution {
                zc,
                c,
                z_min,
                z_max,
                ..
            } => {
                let piece = crate::profile::Piece {
                    zc,
                    c,
                    z0: z_min,
                    z1: z_max,
                };
                piece.r2_range(z_min, z_max).1.max(0.0).sqrt()
            }
            Shape::Face {
                ax,
                ay,
                ux,
                uy,
                length,
                ..
            } => libm::hypot(ax, ay).max(libm::hypot(ax + length * ux, ay + length * uy)),
            Shape::Cap { centre, radius, .. } => libm::hypot(centre.x, centre.y) + radius.abs(),
            Shape::Disk { centre, r2, .. } => libm::hypot(centre.x, centre.y) + r2.sqrt(),
            Shape::Tube {
                centre,
                r2,
                w_min,
                w_max,
                ..
            } => libm::hypot(centre.x, centre.y) + r2.sqrt() + w_min.abs().max(w_max.abs()),
        }
    }

    /// The curvature of the boundary's surface at its point `p`, as the change of the unit
    /// normal along a small step `dp` in the surface there: `dn = K·dp` for a sphere of radius
    /// `1/K`, only the horizontal part of `dp` over `R` for an upright cylinder, nothing for a
    /// plane.
    pub fn normal_change(&self, p: Vec3, dp: Vec3) -> Vec3 {
        // Multiplied by the curvature `1/R`, as the models have always rounded it.
        match self.shape {
            Shape::Revolution { zc, c, .. } => {
                // N = (x, y, −r²'(z)/2) and its change (dx, dy, −c2·dz), projected across the
                // unit normal and divided by |N|.
                let big = Vec3::new(p.x, p.y, -(0.5 * c[1] + c[2] * (p.z - zc)));
                let (len, n) = (big.length(), big.normalize());
                let change = Vec3::new(dp.x, dp.y, -c[2] * dp.z);
                (change - change.dot(n) * n) / len
            }
            Shape::Upright { radius, .. } => (1.0 / radius) * Vec3::new(dp.x, dp.y, 0.0),
            // A cap's signed radius turns the normal the way its outer side faces.
            Shape::Sphere { radius, .. } | Shape::Cap { radius, .. } => (1.0 / radius) * dp,
            Shape::Tube { axis, r2, .. } => (1.0 / r2.sqrt()) * (dp - dp.dot(axis) * axis),
            Shape::Disk { .. } => Vec3::ZERO,
            Shape::Horizontal { .. } | Shape::Vertical { .. } | Shape::Face { .. } => {
                0.0 * Vec3::new(dp.x, dp.y, 0.0)
            }
        }
    }

    /// What names the whole surface the boundary lies on: its kind and its numbers.
    pub(crate) fn surface_key(&self) -> (u8, [f64; 3]) {
        match self.shape {
            Shape::Horizontal { z, .. } => (0, [z, 0.0, 0.0]),
            Shape::Upright { cx, cy, radius, .. } => (1, [cx, cy, radius]),
            Shape::Vertical { axis, at, .. } => (2, [axis as f64, at, 0.0]),
            // Spheres do not touch one another: a centre names one.
            Shape::Sphere { centre, .. } => (3, centre.to_array()),
            // A lens's parts by their centres (lenses do not touch one another).
            Shape::Cap { centre, .. } => (5, centre.to_array()),
            Shape::Disk { centre, .. } => (6, centre.to_array()),
            Shape::Tube { centre, .. } => (7, centre.to_array()),
            // A container of revolution's piece by its quadric (each piece is its own).
            Shape::Revolution { zc, c, .. } => (8, [zc, c[0], c[1]]),
            // A plane by its outer normal and its offset.
            Shape::Face { ax, ay, ux, uy, .. } => (4, [uy, -ux, uy * ax - ux * ay]),
        }
    }

    /// The side a ray leaving this boundary escapes to (see [`Boundary::escape`]), in a world
    /// whose everything lies in the box `lo..hi` and within `reach` of the `z` axis: the air
    /// below the lowest plane or above the highest, outside the widest cylinder around the axis,
    /// beyond a wall of the box.
    pub(crate) fn escape_side(&self, lo: Vec3, hi: Vec3, reach: f64) -> i8 {
        let (outer_air, inner_air) = (self.outer == super::AIR, self.inner == super::AIR);
        match self.shape {
            Shape::Horizontal { z, .. } if z == lo.z && inner_air => -1,
            Shape::Horizontal { z, .. } if z == hi.z && outer_air => 1,
            Shape::Upright { cx, cy, radius, .. }
                if cx == 0.0
                    && cy == 0.0
                    && radius >= reach * (1.0 - 8.0 * f64::EPSILON)
                    && outer_air =>
            {
                1
            }
            Shape::Vertical { axis, at, .. }
                if outer_air && ((at > 0.0 && hi[axis] <= at) || (at < 0.0 && lo[axis] >= at)) =>
            {
                1
            }
            _ => 0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Ray;

    fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
        Ray::new(Vec3::from_array(o), Vec3::from_array(d))
    }

    fn boundary(shape: Shape) -> Boundary {
        Boundary {
            shape,
            outer: 0,
            inner: 2,
            surface: 0,
            escape: 0,
            optics: Optics::new(1.0, 1.333),
            codes: Codes {
                index: 0.0,
                surface: 0.0,
                inner: 2.0,
                outer: 0.0,
            },
            holes: [0, 0],
            solid: false,
            body: 0,
        }
    }

    /// The first crossing of one ray.
    fn cross(b: &Boundary, r: &Ray, leaving: bool) -> f64 {
        let (o, d) = (V3::from(r.origin), V3::from(r.direction));
        let around = Around {
            r2: 1.0,
            quadratic: SideQuadratic::new(o.x, o.y, d.x, d.y, 1.0),
        };
        b.crossing(o, d, &Reciprocals::new(d), leaving, true, &around)
    }

    #[test]
    fn a_horizontal_region_is_crossed_inside_and_missed_outside() {
        let disk = boundary(Shape::Horizontal {
            z: 0.1,
            region: Region::Disk {
                cx: 0.0,
                cy: 0.0,
                radius: 0.04,
            },
        });
        let down = ray([0.01, 0.0, 0.3], [0.0, 0.0, -1.0]);
        assert_eq!(cross(&disk, &down, false), 0.3 - 0.1);
        // Leaving it: not met again.
        assert!(cross(&disk, &down, true).is_infinite());
        // Outside the disk, parallel to it, or going away: missed.
        assert!(cross(&disk, &ray([0.05, 0.0, 0.3], [0.0, 0.0, -1.0]), false).is_infinite());
        assert!(cross(&disk, &ray([0.0, 0.0, 0.1], [1.0, 0.0, 0.0]), false).is_infinite());
        assert!(cross(&disk, &ray([0.0, 0.0, 0.3], [0.0, 0.0, 1.0]), false).is_infinite());
        // A ring holds what lies between its radii only; a rectangle its half widths.
        let ring = boundary(Shape::Horizontal {
            z: 0.0,
            region: Region::Annulus {
                inner2: 0.0375 * 0.0375,
                outer2: 0.04 * 0.04,
            },
        });
        assert_eq!(
            cross(&ring, &ray([0.039, 0.0, 1.0], [0.0, 0.0, -1.0]), false),
            1.0
        );
        assert!(cross(&ring, &ray([0.03, 0.0, 1.0], [0.0, 0.0, -1.0]), false).is_infinite());
        let rect = boundary(Shape::Horizontal {
            z: 0.0,
            region: Region::Rectangle {
                half_x: 0.1,
                half_y: 0.05,
            },
        });
        assert_eq!(
            cross(&rect, &ray([0.09, -0.05, 1.0], [0.0, 0.0, -1.0]), false),
            1.0
        );
        assert!(cross(&rect, &ray([0.09, 0.06, 1.0], [0.0, 0.0, -1.0]), false).is_infinite());
    }

    #[test]
    fn an_upright_side_is_met_at_its_near_crossing_and_only_at_the_far_one_when_leaving() {
        let side = boundary(Shape::Upright {
            cx: 0.0,
            cy: 0.0,
            radius: 0.04,
            z_min: 0.0,
            z_max: 0.2,
        });
        let through = ray([-1.0, 0.0, 0.1], [1.0, 0.0, 0.0]);
        let a = cross(&side, &through, false);
        assert!((a - 0.96).abs() < 1e-15, "{a}");
        // From the near crossing, leaving the side inwards: only the far one.
        let inside = ray([-0.04, 0.0, 0.1], [1.0, 0.0, 0.0]);
        let c = cross(&side, &inside, true);
        assert!((c - 0.08).abs() < 1e-15, "{c}");
        // Above its top: no crossing; starting inside: the far one.
        assert!(cross(&side, &ray([-1.0, 0.0, 0.3], [1.0, 0.0, 0.0]), false).is_infinite());
        let e = cross(&side, &ray([0.0, 0.0, 0.1], [1.0, 0.0, 0.0]), false);
        assert!((e - 0.04).abs() < 1e-15);
        // A line passing beside it, or a ray moving away from it outside: missed; the normal
        // points away from the axis.
        assert!(cross(&side, &ray([-1.0, 0.05, 0.1], [1.0, 0.0, 0.0]), false).is_infinite());
        assert!(cross(&side, &ray([0.05, 0.0, 0.1], [1.0, 0.1, 0.0]), false).is_infinite());
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
        assert!((cross(&wall, &r, false) - 0.55).abs() < 1e-15);
        assert!(cross(&wall, &r, true).is_infinite());
        // Beyond its ends, above its top: missed.
        assert!(cross(&wall, &ray([0.11, 0.5, 0.1], [0.0, -1.0, 0.0]), false).is_infinite());
        assert!(cross(&wall, &ray([0.0, 0.5, 0.25], [0.0, -1.0, 0.0]), false).is_infinite());
    }
}
