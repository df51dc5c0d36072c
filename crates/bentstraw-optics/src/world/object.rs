//! The opaque objects a ray can end on: straws (upright or leaning), coins and cards.
//!
//! Light stops at an object, which gives the ray its colour code: 1 (red, bottom) to 5 (blue, top)
//! for a straw's five bands, [`COIN_COLOR`] for a coin, [`CARD_COLOR`] for a card and
//! [`PICTURE_COLOR`] for the picture on a card's front. Only the crossing by which light enters an
//! object counts (it is opaque), and a ray that starts inside one, by rounding, meets it at once.

use crate::geometry::{plane_ahead, plane_distance_of, Ray, SideQuadratic};
use crate::lanes::{Mask, Real, V3};
use crate::scene_file::{Card, Coin, Picture, Straw};
use crate::world::boundary::Reciprocals;
use crate::Vec3;

/// Colour code of a coin.
pub const COIN_COLOR: u8 = 6;
/// Colour code of a card.
pub const CARD_COLOR: u8 = 7;
/// Colour code of the picture (the arrow) on a card's front.
pub const PICTURE_COLOR: u8 = 8;

/// Which part of an object a ray met.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Part {
    /// The side of a straw or coin, or a card's face.
    Side,
    /// The bottom cap of a straw or coin.
    Bottom,
    /// The top cap of a straw or coin.
    Top,
}

impl Part {
    /// The part of code 0 (side), 1 (bottom) or 2 (top).
    #[inline]
    pub fn from_code(code: f64) -> Part {
        match code as u8 {
            1 => Part::Bottom,
            2 => Part::Top,
            _ => Part::Side,
        }
    }
}

/// A cylinder along any axis with its two caps, in its own frame: `e1`, `e2` across the axis,
/// `axis` along it from the bottom cap's centre `base`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolidCylinder {
    /// Centre of the bottom cap.
    pub base: Vec3,
    /// Unit vector along the axis, bottom to top.
    pub axis: Vec3,
    /// Unit vector across the axis.
    pub e1: Vec3,
    /// Unit vector across the axis, `axis × e1`.
    pub e2: Vec3,
    /// Radius.
    pub radius: f64,
    /// Length along the axis.
    pub length: f64,
    /// The surfaces of the scene whose planes hold the bottom and top caps (a coin's bottom lies
    /// on the floor), if any: a ray leaving such a surface does not meet the cap on it.
    pub cap_surfaces: [Option<u32>; 2],
    /// Whether the axis is the scene's `z` (its frame is then the scene's own axes).
    upright: bool,
    /// The bottom cap's centre in the frame `(e1, e2, axis)`.
    base_in_frame: [f64; 3],
}

impl SolidCylinder {
    /// The cylinder from `base` along unit `axis`.
    pub fn new(base: Vec3, axis: Vec3, radius: f64, length: f64) -> SolidCylinder {
        // Upright cylinders keep x and y as their frame, so their arithmetic is the plain one.
        let e1 = if axis == Vec3::Z {
            Vec3::X
        } else {
            Vec3::Z.cross(axis).cross(axis).normalize()
        };
        let e2 = axis.cross(e1);
        let upright = axis == Vec3::Z;
        SolidCylinder {
            base,
            axis,
            e1,
            e2,
            radius,
            length,
            cap_surfaces: [None; 2],
            upright,
            base_in_frame: if upright {
                base.to_array()
            } else {
                [base.dot(e1), base.dot(e2), base.dot(axis)]
            },
        }
    }

    /// Whether its axis is the scene's `z`: its frame is then the scene's own axes.
    #[inline(always)]
    pub fn upright(&self) -> bool {
        self.upright
    }

    /// `v` in the frame `(e1, e2, axis)`: the components themselves when upright (the products
    /// with the unit axes would give the same numbers).
    #[inline(always)]
    fn frame<R: Real>(&self, v: V3<R>) -> V3<R> {
        if self.upright() {
            v
        } else {
            // Written out: a closure would not inherit the vector instructions of the tracer
            // that inlines this, and would call out for each product.
            V3::new(
                v.dot(V3::splat(self.e1)),
                v.dot(V3::splat(self.e2)),
                v.dot(V3::splat(self.axis)),
            )
        }
    }

    /// Where the rays from `o` along `d` enter the solid, by which part, and how far along its
    /// axis: the side's entering root (0 for a ray inside it by rounding), or a cap nearer than
    /// that; the side wins a tie. `left` is the code of the surface each ray has just left:
    /// a cap on that surface is not met.
    #[inline(always)]
    pub(crate) fn entry<R: Real>(
        &self,
        o: V3<R>,
        d: V3<R>,
        inv: &Reciprocals<R>,
        alive: R::Mask,
        left: R,
    ) -> Option<(R, R, R)> {
        let (o, d) = (self.frame(o), self.frame(d));
        let [c1, c2, c3] = self.base_in_frame;
        let r2 = R::splat(self.radius * self.radius);
        let (cx, cy, z0) = (R::splat(c1), R::splat(c2), R::splat(c3));
        let side = SideQuadratic::new(o.x - cx, o.y - cy, d.x, d.y, r2);
        // Nothing of it (its caps lie inside its circle) where the line clearly passes beside.
        let near = alive.and_not(side.clearly_misses(r2));
        if !near.any() {
            return None;
        }
        let (inv_a, inv_dz) = if self.upright() {
            (inv.a, inv.d.z)
        } else {
            let one = R::splat(1.0);
            (one / side.a, one / d.z)
        };
        let z1 = R::splat(c3 + self.length);
        let mut t = side.roots(inv_a).entering(&side, o.z, d.z, z0, z1);
        let mut part = R::splat(0.0);
        // The caps, top then bottom: a point of the cap's plane within the radius. (A loop, not
        // a closure called twice: a closure may be compiled apart, without the instruction set
        // of the packet kernel that calls it.)
        for (h, code, surface) in [
            (z1, 2.0, self.cap_surfaces[1]),
            (z0, 1.0, self.cap_surfaces[0]),
        ] {
            let (num, ahead) = plane_ahead(h, o.z, d.z);
            let mut ahead = ahead.and(near);
            if let Some(s) = surface {
                ahead = ahead.and_not(left.eq(R::splat(s as f64)));
            }
            if !ahead.any() {
                continue;
            }
            let tc = plane_distance_of(num, d.z, inv_dz);
            let (x, y) = (o.x + tc * d.x - cx, o.y + tc * d.y - cy);
            let m = ahead.and((x * x + y * y).le(r2)).and(tc.lt(t));
            t = R::select(m, tc, t);
            part = R::select(m, R::splat(code), part);
        }
        let t = R::select(near, t, R::splat(f64::INFINITY));
        Some((t, part, o.z + t * d.z))
    }

    /// Distance from `p` to the cylinder's surface (side or caps), inside or out.
    pub fn distance(&self, p: Vec3) -> f64 {
        let d = p - self.base;
        let along = d.dot(self.axis);
        let dr = (d - along * self.axis).length() - self.radius; // > 0 outside the side
        let dz = (-along).max(along - self.length); // > 0 beyond a cap
        if dr <= 0.0 && dz <= 0.0 {
            (-dr).min(-dz)
        } else {
            libm::hypot(dr.max(0.0), dz.max(0.0))
        }
    }

    /// Outward unit normal at the point `p` of `part`.
    pub fn normal(&self, part: Part, p: Vec3) -> Vec3 {
        match part {
            Part::Top => self.axis,
            Part::Bottom => -self.axis,
            Part::Side => {
                let r = p - self.base;
                (r - r.dot(self.axis) * self.axis).normalize_or_zero()
            }
        }
    }
}

/// An opaque object of the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Object {
    /// A five-colour straw; `edges` are the heights along its axis where bands 2..=5 begin.
    Straw {
        /// Its solid.
        solid: SolidCylinder,
        /// Lower edges of its bands 2..=5 along the axis.
        edges: [f64; 4],
    },
    /// A coin lying on the floor.
    Coin(SolidCylinder),
    /// A card: an upright rectangle.
    Card {
        /// Its centre.
        centre: Vec3,
        /// Unit horizontal normal of its front.
        front: Vec3,
        /// Unit horizontal vector to its right as seen from its front.
        right: Vec3,
        /// Width.
        width: f64,
        /// Height.
        height: f64,
        /// Whether its front shows the arrow.
        arrow: bool,
    },
}

impl Object {
    /// A straw resting on a floor at height `floor`.
    pub fn straw(s: &Straw, floor: f64) -> Object {
        let solid = SolidCylinder::new(s.bottom_centre(floor), s.axis(), s.radius, s.length);
        // The bands' edges along the axis from the bottom cap, each `k·length/5` rounded once
        // (0.15 m, not 3 × 0.05 = 0.15000000000000002).
        let edges = [1.0, 2.0, 3.0, 4.0].map(|k| k * s.length / 5.0);
        Object::Straw { solid, edges }
    }

    /// A coin lying on a floor at height `floor`.
    pub fn coin(c: &Coin, floor: f64) -> Object {
        Object::Coin(SolidCylinder::new(
            Vec3::new(c.x, c.y, floor),
            Vec3::Z,
            c.radius,
            c.thickness,
        ))
    }

    /// A card.
    pub fn card(c: &Card) -> Object {
        let f = c.facing_deg.to_radians();
        let front = Vec3::new(libm::cos(f), libm::sin(f), 0.0);
        Object::Card {
            centre: c.center,
            front,
            right: Vec3::Z.cross(front),
            width: c.width,
            height: c.height,
            arrow: c.picture == Picture::Arrow,
        }
    }

    /// Where the rays from `o` along `d` first meet the object: the distance (infinite where
    /// they do not), the part (0 side, 1 bottom, 2 top), and what tells the colour code there
    /// ([`Object::color_lanes`]): a straw's height along its axis, else the code itself.
    /// `left` is the code of the surface each ray has just left (see [`SolidCylinder::entry`]).
    #[inline(always)]
    pub(crate) fn entry<R: Real>(
        &self,
        o: V3<R>,
        d: V3<R>,
        inv: &Reciprocals<R>,
        alive: R::Mask,
        left: R,
    ) -> Option<(R, R, R)> {
        match self {
            // One solid's entry for both (inlined once: a smaller packet kernel).
            Object::Straw { solid, .. } | Object::Coin(solid) => {
                let (t, part, along) = solid.entry(o, d, inv, alive, left)?;
                let tag = if let Object::Straw { .. } = self {
                    along - R::splat(solid.base_in_frame[2])
                } else {
                    R::splat(COIN_COLOR as f64)
                };
                Some((t, part, tag))
            }
            Object::Card {
                centre,
                front,
                right,
                width,
                height,
                arrow,
            } => {
                let p = o - V3::splat(*centre);
                let (f, r) = (V3::splat(*front), V3::splat(*right));
                let dn = d.dot(f);
                let (num, ahead) = plane_ahead(R::splat(0.0), p.dot(f), dn);
                let ahead = ahead.and(alive);
                if !ahead.any() {
                    return None;
                }
                let t = num / dn;
                let q = p.along(t, d);
                let (u, v) = (q.dot(r), q.z);
                let (w, h) = (R::splat(*width), R::splat(*height));
                let half = R::splat(0.5);
                let on = ahead.and(u.abs().le(half * w)).and(v.abs().le(half * h));
                let t = R::select(on, t, R::splat(f64::INFINITY));
                let mut color = R::splat(CARD_COLOR as f64);
                if *arrow {
                    let seen_from_front = dn.lt(R::splat(0.0));
                    let drawn = seen_from_front.and(in_arrow_lanes(u, v, w, h));
                    color = R::select(drawn, R::splat(PICTURE_COLOR as f64), color);
                }
                Some((t, R::splat(0.0), color))
            }
        }
    }

    /// The colour codes where rays met the object on `part` with `tag` ([`Object::entry`]'s):
    /// a straw's band (one plus the band edges at or below the point; its caps are its end
    /// bands), else the tag itself.
    #[inline(always)]
    pub(crate) fn color_lanes<R: Real>(&self, part: R, tag: R) -> R {
        match self {
            Object::Straw { edges, .. } => {
                let mut band = R::splat(1.0);
                for &e in edges {
                    band = R::select(tag.ge(R::splat(e)), band + R::splat(1.0), band);
                }
                R::select(
                    part.eq(R::splat(0.0)),
                    band,
                    R::select(part.eq(R::splat(1.0)), R::splat(1.0), R::splat(5.0)),
                )
            }
            _ => tag,
        }
    }

    /// Where `ray` first meets the object: the distance, the part, and the colour code there.
    pub fn hit(&self, ray: &Ray) -> Option<(f64, Part, u8)> {
        let (o, d) = (V3::from(ray.origin), V3::from(ray.direction));
        let (t, part, tag) = self.entry(o, d, &Reciprocals::new(d), true, -1.0)?;
        let color = self.color_lanes(part, tag);
        t.is_finite()
            .then(|| (t, Part::from_code(part), color as u8))
    }

    /// Distance from `p` to the object's surface (m).
    pub fn distance(&self, p: Vec3) -> f64 {
        match self {
            Object::Straw { solid, .. } | Object::Coin(solid) => solid.distance(p),
            Object::Card {
                centre,
                front,
                right,
                width,
                height,
                ..
            } => {
                let q = p - *centre;
                let du = (q.dot(*right).abs() - width / 2.0).max(0.0);
                let dv = (q.z.abs() - height / 2.0).max(0.0);
                libm::hypot(q.dot(*front), libm::hypot(du, dv))
            }
        }
    }

    /// Outward unit normal at the point `p` of `part` (a card's: towards the side the ray came
    /// from is the caller's business; this is its front's).
    pub fn normal(&self, part: Part, p: Vec3) -> Vec3 {
        match self {
            Object::Straw { solid, .. } | Object::Coin(solid) => solid.normal(part, p),
            Object::Card { front, .. } => *front,
        }
    }

    /// The largest distance of a point of the object from the `z` axis (at most a hair more).
    pub(crate) fn reach(&self) -> f64 {
        let from_axis = |p: Vec3| libm::hypot(p.x, p.y);
        match self {
            Object::Straw { solid, .. } | Object::Coin(solid) => {
                let top = solid.base + solid.length * solid.axis;
                from_axis(solid.base).max(from_axis(top)) + solid.radius
            }
            Object::Card {
                centre,
                right,
                width,
                ..
            } => {
                let a = *centre + 0.5 * width * *right;
                let b = *centre - 0.5 * width * *right;
                from_axis(a).max(from_axis(b))
            }
        }
    }

    /// The corners of a box holding the object.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        match self {
            Object::Straw { solid, .. } | Object::Coin(solid) => {
                let top = solid.base + solid.length * solid.axis;
                // Upright: exactly its circle's extent across and nothing along; else a box of
                // the radius all round.
                let r = if solid.upright() {
                    Vec3::new(solid.radius, solid.radius, 0.0)
                } else {
                    Vec3::splat(solid.radius)
                };
                (solid.base.min(top) - r, solid.base.max(top) + r)
            }
            Object::Card {
                centre,
                right,
                width,
                height,
                ..
            } => {
                let a = *centre + 0.5 * width * *right;
                let b = *centre - 0.5 * width * *right;
                let h = Vec3::new(0.0, 0.0, 0.5 * height);
                (a.min(b) - h, a.max(b) + h)
            }
        }
    }
}

/// Whether the point `(u, v)` of a card (`u` to its right seen from its front, `v` up, from its
/// centre) lies on the arrow drawn on it: a shaft `|v| <= 0.1·h` for `−0.35·w <= u <= 0.1·w`, and
/// a head `0.1·w <= u <= 0.4·w`, `|v| <= 0.3·h·(0.4·w − u)/(0.3·w)`, pointing to the right.
pub fn in_arrow(u: f64, v: f64, w: f64, h: f64) -> bool {
    in_arrow_lanes(u, v, w, h)
}

/// [`in_arrow`], lane by lane.
#[inline(always)]
fn in_arrow_lanes<R: Real>(u: R, v: R, w: R, h: R) -> R::Mask {
    let k = |x: f64| R::splat(x);
    let between = |x: R, lo: R, hi: R| x.ge(lo).and(x.le(hi));
    let shaft = v
        .abs()
        .le(k(0.1) * h)
        .and(between(u, k(-0.35) * w, k(0.1) * w));
    let head = between(u, k(0.1) * w, k(0.4) * w)
        .and(v.abs().le(k(0.3) * h * (k(0.4) * w - u) / (k(0.3) * w)));
    shaft.or(head)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_leaning_straw_is_entered_by_its_side_and_caps_with_their_colours() {
        let s = Straw {
            x: 0.0,
            y: 0.0,
            tilt_deg: 30.0,
            azimuth_deg: 0.0,
            radius: 0.005,
            length: 0.25,
        };
        let straw = Object::straw(&s, 0.0);
        // Along its axis from above its top: the top cap, blue, at the axis's end.
        let top = s.bottom_centre(0.0) + s.length * s.axis();
        let from = top + 0.1 * s.axis();
        let (t, part, color) = straw.hit(&Ray::new(from, -s.axis())).unwrap();
        assert_eq!((part, color), (Part::Top, 5));
        assert!((t - 0.1).abs() < 1e-15);
        // Across its side at a third of its length: band 2 (orange), at the radius.
        let mid = s.bottom_centre(0.0) + 0.3 * s.length * s.axis();
        let across = Vec3::new(0.0, 1.0, 0.0);
        let (t, part, color) = straw.hit(&Ray::new(mid - 0.1 * across, across)).unwrap();
        assert_eq!((part, color), (Part::Side, 2));
        assert!((t - (0.1 - 0.005)).abs() < 1e-15);
        // Beside it: nothing; a ray starting inside it (by rounding) meets it at once.
        assert!(straw
            .hit(&Ray::new(
                mid - 0.1 * across + Vec3::new(0.0, 0.0, 0.2),
                across
            ))
            .is_none());
        assert_eq!(straw.hit(&Ray::new(mid, across)).unwrap().0, 0.0);
        // Its distance: zero on its surface, the radius less on its axis.
        assert!(straw.distance(mid + 0.005 * across).abs() < 1e-15);
        assert!((straw.distance(mid) - 0.005).abs() < 1e-15);
    }

    #[test]
    fn a_card_shows_its_arrow_on_its_front_only() {
        let card = Object::card(&Card {
            center: Vec3::new(-0.1, 0.0, 0.1),
            facing_deg: 0.0,
            width: 0.12,
            height: 0.06,
            picture: Picture::Arrow,
        });
        // The head's tip region (u = 0.3·w, on the +y side seen from the front), from the front.
        let at = Vec3::new(-0.1, 0.3 * 0.12, 0.1);
        let front = card.hit(&Ray::new(at + Vec3::X, Vec3::NEG_X)).unwrap();
        assert_eq!(front.2, PICTURE_COLOR);
        assert!((front.0 - 1.0).abs() < 1e-15);
        // The same point from behind: the plain card.
        assert_eq!(
            card.hit(&Ray::new(at - Vec3::X, Vec3::X)).unwrap().2,
            CARD_COLOR
        );
        // Off the arrow, off the card.
        assert_eq!(
            card.hit(&Ray::new(
                Vec3::new(-0.1, -0.05, 0.125) + Vec3::X,
                Vec3::NEG_X
            ))
            .unwrap()
            .2,
            CARD_COLOR
        );
        assert!(card
            .hit(&Ray::new(Vec3::new(-0.1, 0.07, 0.1) + Vec3::X, Vec3::NEG_X))
            .is_none());
        // The arrow's rule at its corners.
        let (w, h) = (1.0, 1.0);
        assert!(in_arrow(-0.35, 0.1, w, h) && !in_arrow(-0.36, 0.0, w, h));
        assert!(in_arrow(0.1, 0.3, w, h) && !in_arrow(0.1, 0.31, w, h));
        assert!(in_arrow(0.4, 0.0, w, h) && !in_arrow(0.41, 0.0, w, h));
        assert!(in_arrow(0.25, 0.15, w, h) && !in_arrow(0.25, 0.16, w, h));
    }
}
