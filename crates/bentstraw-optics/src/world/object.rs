//! The opaque objects a ray can end on: straws (upright or leaning), coins and cards.
//!
//! Light stops at an object, which gives the ray its colour code: 1 (red, bottom) to 5 (blue, top)
//! for a straw's five bands, [`COIN_COLOR`] for a coin, [`CARD_COLOR`] for a card and
//! [`PICTURE_COLOR`] for the picture on a card's front. Only the crossing by which light enters an
//! object counts (it is opaque), and a ray that starts inside one, by rounding, meets it at once.

use crate::geometry::{plane_distance, Ray, SideQuadratic};
use crate::scene_file::{Card, Coin, Picture, Straw};
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
        SolidCylinder {
            base,
            axis,
            e1,
            e2: axis.cross(e1),
            radius,
            length,
        }
    }

    /// Where `ray` enters the solid, and by which part.
    #[inline]
    pub fn entry(&self, ray: &Ray) -> Option<(f64, Part, f64)> {
        let p = ray.origin - self.base;
        let d = ray.direction;
        let (px, py, pz) = (p.dot(self.e1), p.dot(self.e2), p.dot(self.axis));
        let (dx, dy, dz) = (d.dot(self.e1), d.dot(self.e2), d.dot(self.axis));
        let r2 = self.radius * self.radius;
        let side = SideQuadratic::new(px, py, dx, dy, r2);
        let mut best: Option<(f64, Part)> = side
            .entering_root(pz, dz, 0.0, self.length)
            .map(|t| (t, Part::Side));
        let on_cap = |t: f64| {
            let (x, y) = (px + t * dx, py + t * dy);
            x * x + y * y <= r2
        };
        for (h, part) in [(0.0, Part::Bottom), (self.length, Part::Top)] {
            if let Some(t) = plane_distance(h, pz, dz) {
                let nearer = match best {
                    Some((b, _)) => t < b,
                    None => true,
                };
                if nearer && on_cap(t) {
                    best = Some((t, part));
                }
            }
        }
        best.map(|(t, part)| (t, part, pz + t * dz))
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
            dr.max(0.0).hypot(dz.max(0.0))
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
        let band = s.length / 5.0;
        Object::Straw {
            solid,
            edges: [band, 2.0 * band, 3.0 * band, 4.0 * band],
        }
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
        let front = Vec3::new(f.cos(), f.sin(), 0.0);
        Object::Card {
            centre: c.center,
            front,
            right: Vec3::Z.cross(front),
            width: c.width,
            height: c.height,
            arrow: c.picture == Picture::Arrow,
        }
    }

    /// Where `ray` first meets the object: the distance, the part, and the colour code there.
    #[inline]
    pub fn hit(&self, ray: &Ray) -> Option<(f64, Part, u8)> {
        match self {
            Object::Straw { solid, edges } => {
                let (t, part, along) = solid.entry(ray)?;
                let color = match part {
                    Part::Bottom => 1,
                    Part::Top => 5,
                    Part::Side => 1 + edges.iter().filter(|&&e| along >= e).count() as u8,
                };
                Some((t, part, color))
            }
            Object::Coin(solid) => solid.entry(ray).map(|(t, part, _)| (t, part, COIN_COLOR)),
            Object::Card {
                centre,
                front,
                right,
                width,
                height,
                arrow,
            } => {
                let p = ray.origin - *centre;
                let t = plane_distance(0.0, p.dot(*front), ray.direction.dot(*front))?;
                let q = p + t * ray.direction;
                let (u, v) = (q.dot(*right), q.z);
                if u.abs() > width / 2.0 || v.abs() > height / 2.0 {
                    return None;
                }
                let seen_from_front = ray.direction.dot(*front) < 0.0;
                let color = if *arrow && seen_from_front && in_arrow(u, v, *width, *height) {
                    PICTURE_COLOR
                } else {
                    CARD_COLOR
                };
                Some((t, Part::Side, color))
            }
        }
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
                q.dot(*front).hypot(du.hypot(dv))
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

    /// The corners of a box holding the object.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        match self {
            Object::Straw { solid, .. } | Object::Coin(solid) => {
                let top = solid.base + solid.length * solid.axis;
                let r = Vec3::splat(solid.radius);
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
    let shaft = v.abs() <= 0.1 * h && (-0.35 * w..=0.1 * w).contains(&u);
    let head = (0.1 * w..=0.4 * w).contains(&u) && v.abs() <= 0.3 * h * (0.4 * w - u) / (0.3 * w);
    shaft || head
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
