//! An independent tracer for the tests of transparent balls: balls of their own index in air, and
//! opaque cards (no picture: one colour, both sides), written straight from the textbook in
//! double-double arithmetic (`twofloat`, about 32 significant digits). A line meets a ball where
//! `|o + s·d − c|² = r²`, solved by the plain quadratic formula (double-double can afford its
//! cancellation); a ray leaving a ball outwards never meets it again (it is convex), one inside it
//! leaves by the far root; a card is a plane cut to a rectangle. At each ball's face: Snell–
//! Descartes or total reflection, and in Fresnel mode the unpolarised reflectance from Fresnel's
//! amplitude coefficients. Nothing is shared with the library but the numbers of the scene; a ball
//! of index 1 is no ball (the library's rule: a face between equal indices is none).
//!
//! Upright prisms in air too ([`Balls::with_prisms`]): a convex polyhedron of planes (one upright
//! through each side of the polygon, the bottom and the top), met where a line's span inside
//! every half-space begins (from outside) or ends (from inside), its face's normal the plane's.
//!
//! Along with each result it reports a `margin` (metres): how close the ray came to a decision
//! that could go the other way (grazing a ball, a card's edge, two hits nearly tied, the critical
//! angle, a branch's weight at the pruning threshold). Where the margin is far above double
//! precision's rounding (1e-9 m), the library must agree to its last digits.
#![allow(dead_code)]

use bentstraw_optics::geometry::Ray;
use bentstraw_optics::Vec3;
use twofloat::TwoFloat as T;

/// Where a ray crosses a prism's face, and which face: none, or the distance and the face.
type FaceCrossing = Option<(T, usize)>;
/// Scale turning dimensionless closeness (the critical angle, a weight) into metres.
const SCALE: f64 = 0.1;

/// A card's colour code (no picture on it).
pub const CARD_CODE: u8 = 7;

fn t(x: f64) -> T {
    T::from(x)
}

/// A vector in double-double.
#[derive(Clone, Copy, Debug)]
struct V {
    x: T,
    y: T,
    z: T,
}

impl V {
    fn of(v: Vec3) -> V {
        V {
            x: t(v.x),
            y: t(v.y),
            z: t(v.z),
        }
    }
    fn f64(self) -> Vec3 {
        Vec3::new(self.x.into(), self.y.into(), self.z.into())
    }
    fn add(self, o: V) -> V {
        V {
            x: self.x + o.x,
            y: self.y + o.y,
            z: self.z + o.z,
        }
    }
    fn sub(self, o: V) -> V {
        V {
            x: self.x - o.x,
            y: self.y - o.y,
            z: self.z - o.z,
        }
    }
    fn scale(self, k: T) -> V {
        V {
            x: self.x * k,
            y: self.y * k,
            z: self.z * k,
        }
    }
    fn dot(self, o: V) -> T {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    fn cross(self, o: V) -> V {
        V {
            x: self.y * o.z - self.z * o.y,
            y: self.z * o.x - self.x * o.z,
            z: self.x * o.y - self.y * o.x,
        }
    }
    fn unit(self) -> V {
        self.scale(t(1.0) / self.dot(self).sqrt())
    }
    fn at(self, d: V, s: T) -> V {
        self.add(d.scale(s))
    }
}

/// A transparent ball.
#[derive(Clone, Copy, Debug)]
pub struct Ball {
    /// Its centre (m).
    pub centre: Vec3,
    /// Its radius (m).
    pub radius: f64,
    /// Its refractive index (at least 1).
    pub index: f64,
}

/// A transparent upright prism: its section's corners seen from above (a convex polygon, listed
/// in either order), its bottom and top heights, its index. Its faces are planes: one through each
/// side of the polygon, upright, and the bottom and top.
#[derive(Clone, Debug)]
pub struct Prism {
    pub corners: Vec<[f64; 2]>,
    pub bottom: f64,
    pub top: f64,
    pub index: f64,
}

/// An opaque upright card: its centre, the direction (degrees from `x`, about `z`) its front faces,
/// its width and height.
#[derive(Clone, Copy, Debug)]
pub struct Card {
    /// Its centre (m).
    pub centre: Vec3,
    /// The direction its front faces, degrees.
    pub facing_deg: f64,
    /// Width (m).
    pub width: f64,
    /// Height (m).
    pub height: f64,
}

/// The reference's verdict on one ray (course mode).
#[derive(Clone, Debug, PartialEq)]
pub enum BallOutcome {
    /// Reached card `card` at `point`.
    Card {
        /// Which card.
        card: usize,
        /// The point reached.
        point: Vec3,
        /// Length of the broken path from the ray's origin (m).
        length: f64,
        /// The events' points, in order.
        events: Vec<Vec3>,
    },
    /// Left for good along `direction`, from the last event's point (the last of `events`).
    Escaped {
        /// The events' points, in order.
        events: Vec<Vec3>,
        /// The unit direction it leaves along.
        direction: Vec3,
    },
    /// Would need one event more than allowed.
    Dropped,
}

/// Where the weight of a ray ends in Fresnel mode.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Shares {
    /// On each card.
    pub cards: [f64; 4],
    /// Leaving the scene.
    pub escaped: f64,
    /// Past the event limit.
    pub dropped: f64,
    /// In branches lighter than the pruning threshold.
    pub pruned: f64,
}

/// The scene: balls in air and cards, and the event limit.
pub struct Balls {
    balls: Vec<(V, T, T)>,
    /// Each prism's planes (outward unit normal `m`, offset `h`: inside where `m·x < h`) and
    /// index; prism `j` is solid `balls.len() + j`.
    prisms: Vec<(Vec<(V, T)>, T)>,
    cards: Vec<(V, V, V, T, T)>,
    max_events: u32,
}

/// What a ray meets first.
enum Met {
    /// Ball `k`'s face, at distance `s`.
    Ball(usize, T),
    /// Card `k`, at distance `s`.
    Card(usize, T),
}

impl Balls {
    /// The reference for balls and cards (at most four) with event limit `max_events`.
    pub fn new(balls: &[Ball], cards: &[Card], max_events: u32) -> Balls {
        assert!(cards.len() <= 4);
        Balls {
            balls: balls
                .iter()
                .map(|b| (V::of(b.centre), t(b.radius), t(b.index)))
                .collect(),
            prisms: Vec::new(),
            cards: cards
                .iter()
                .map(|c| {
                    let f = c.facing_deg.to_radians();
                    let front = V::of(Vec3::new(f.cos(), f.sin(), 0.0));
                    let right = V::of(Vec3::Z).cross(front);
                    (V::of(c.centre), front, right, t(c.width), t(c.height))
                })
                .collect(),
            max_events,
        }
    }

    /// The same with `prisms` besides (solids `balls.len()`, … after the balls).
    pub fn with_prisms(mut self, prisms: &[Prism]) -> Balls {
        for p in prisms {
            let c = &p.corners;
            let k = c.len();
            let area: f64 = (0..k)
                .map(|j| c[j][0] * c[(j + 1) % k][1] - c[(j + 1) % k][0] * c[j][1])
                .sum();
            let mut planes = Vec::new();
            for j in 0..k {
                let (a, b) = (c[j], c[(j + 1) % k]);
                let (ax, ay) = (t(a[0]), t(a[1]));
                let (dx, dy) = (t(b[0]) - ax, t(b[1]) - ay);
                // Outwards: to the right of a counterclockwise side.
                let m = V {
                    x: dy,
                    y: -dx,
                    z: t(0.0),
                };
                let m = if area > 0.0 { m } else { m.scale(t(-1.0)) }.unit();
                planes.push((m, m.x * ax + m.y * ay));
            }
            let up = V::of(Vec3::Z);
            planes.push((up, t(p.top)));
            planes.push((up.scale(t(-1.0)), t(-p.bottom)));
            self.prisms.push((planes, t(p.index)));
        }
        self
    }

    /// Whether it holds prisms.
    pub fn has_prisms(&self) -> bool {
        !self.prisms.is_empty()
    }

    /// The nearest thing ahead of `o` along unit `d`, in ball `inside` (or air), having just left
    /// the face of ball `left`; lowers `margin` to the closeness of every decision taken.
    fn nearest(
        &self,
        o: V,
        d: V,
        inside: Option<usize>,
        left: Option<usize>,
        margin: &mut f64,
    ) -> Option<Met> {
        // (distance, what, closeness to an edge)
        let mut cands: Vec<(T, Met, f64)> = Vec::new();
        // (distance to the line's closest approach, how near it comes to grazing)
        let mut grazing: Vec<(T, f64)> = Vec::new();
        for (k, &(c, r, n)) in self.balls.iter().enumerate() {
            if n == 1.0 {
                continue; // a ball of air's index is no ball
            }
            let p = o.sub(c);
            let a = d.dot(d);
            let hb = p.dot(d);
            let cc = p.dot(p) - r * r;
            let disc = hb * hb - a * cc;
            if inside == Some(k) {
                // Inside: out by the far root, the near one is behind (or at the start).
                let s = (-hb + disc.sqrt()) / a;
                cands.push((s, Met::Ball(k, s), f64::INFINITY));
                continue;
            }
            if left == Some(k) {
                continue; // left outwards: a convex ball is not met again
            }
            // The line's distance from the centre, against the radius.
            let gap: f64 = ((p.cross(d).dot(p.cross(d)) / a).sqrt() - r).abs().into();
            grazing.push((-hb / a, gap));
            if disc < 0.0 {
                continue;
            }
            let s = (-hb - disc.sqrt()) / a;
            if s > 0.0 {
                cands.push((s, Met::Ball(k, s), f64::INFINITY));
            }
        }
        let nb = self.balls.len();
        for (j, (planes, n)) in self.prisms.iter().enumerate() {
            let k = nb + j;
            if *n == 1.0 {
                continue; // a prism of air's index is no prism
            }
            if left == Some(k) && inside != Some(k) {
                continue; // left outwards: a convex prism is not met again
            }
            // The line's span inside each half-space: entering where it crosses a face
            // inwards, leaving where outwards.
            let (mut enter, mut exit): (FaceCrossing, FaceCrossing) = (None, None);
            let mut missed = false;
            for (f, &(m, h)) in planes.iter().enumerate() {
                let dn = m.dot(d);
                let num = h - m.dot(o);
                if dn == 0.0 {
                    missed |= num < 0.0;
                    continue;
                }
                let s = num / dn;
                if dn < 0.0 {
                    if enter.is_none_or(|(e, _)| s > e) {
                        enter = Some((s, f));
                    }
                } else if exit.is_none_or(|(x, _)| s < x) {
                    exit = Some((s, f));
                }
            }
            // How deep inside the other faces a point of the line is (negative outside).
            let depth = |s: T, face: usize| -> T {
                let q = o.at(d, s);
                planes
                    .iter()
                    .enumerate()
                    .filter(|&(f, _)| f != face)
                    .map(|(_, &(m, h))| h - m.dot(q))
                    .fold(None, |a: Option<T>, x| {
                        Some(a.map_or(x, |a| if x < a { x } else { a }))
                    })
                    .unwrap()
            };
            if inside == Some(k) {
                let (s, f) = exit.expect("a bounded prism");
                let edge: f64 = depth(s, f).abs().into();
                cands.push((s, Met::Ball(k, s), edge));
                continue;
            }
            let (Some((se, fe)), Some((sx, fx))) = (enter, exit) else {
                continue;
            };
            if missed {
                continue;
            }
            let at_entry = depth(se, fe);
            if se < sx && se > 0.0 && at_entry >= 0.0 {
                cands.push((se, Met::Ball(k, se), at_entry.into()));
            } else {
                // Missed: by about how far its crossings lie outside the other faces.
                let gap: f64 = at_entry.abs().min(depth(sx, fx).abs()).into();
                grazing.push((se, gap));
            }
        }
        for (k, &(c, front, right, w, h)) in self.cards.iter().enumerate() {
            let dn = d.dot(front);
            if dn == 0.0 {
                continue;
            }
            let s = c.sub(o).dot(front) / dn;
            if s <= 0.0 {
                continue;
            }
            let q = o.at(d, s).sub(c);
            let (u, v) = (q.dot(right).abs(), q.z.abs());
            let (hw, hh) = (w * t(0.5), h * t(0.5));
            let on = u <= hw && v <= hh;
            // Distance to the rectangle's outline, within it or outside it.
            let edge: f64 = if on {
                f64::from(hw - u).min(f64::from(hh - v))
            } else {
                let du: f64 = (u - hw).into();
                let dv: f64 = (v - hh).into();
                du.max(0.0).hypot(dv.max(0.0))
            };
            if on {
                cands.push((s, Met::Card(k, s), edge));
            } else {
                cands.push((s, Met::Card(usize::MAX, s), edge));
            }
        }
        let accepted = |m: &Met| !matches!(m, Met::Card(usize::MAX, _));
        let mut best: Option<usize> = None;
        for (i, (s, m, _)) in cands.iter().enumerate() {
            if accepted(m) && best.is_none_or(|b| *s < cands[b].0) {
                best = Some(i);
            }
        }
        let limit = best.map(|b| cands[b].0);
        for (i, &(s, ref m, edge)) in cands.iter().enumerate() {
            if limit.is_none_or(|l| s <= l) {
                *margin = margin.min(edge);
            }
            if let Some(l) = limit {
                if accepted(m) && Some(i) != best {
                    *margin = margin.min(f64::from((s - l).abs()));
                }
            }
        }
        for (closest, gap) in grazing {
            // A nearly tangent hit lies up to a half-chord before the closest point.
            if closest > 0.0 && limit.is_none_or(|l| closest <= l + t(1e-4)) {
                *margin = margin.min(gap);
            }
        }
        let b = best?;
        Some(match cands.swap_remove(b).1 {
            Met::Ball(k, s) => Met::Ball(k, s),
            Met::Card(k, s) => Met::Card(k, s),
        })
    }

    /// Snell–Descartes or total reflection of unit `d` at unit `normal` from `n1` into `n2`: the
    /// new direction, whether it was refracted, and the reflectance `R`; lowers `margin` by the
    /// closeness to the critical angle.
    fn scatter(d: V, normal: V, n1: T, n2: T, margin: &mut f64) -> (V, bool, T) {
        let mut cos_i = -d.dot(normal);
        let m = if cos_i < 0.0 {
            cos_i = -cos_i;
            normal.scale(t(-1.0))
        } else {
            normal
        };
        let eta = n1 / n2;
        let sin2_t = eta * eta * (t(1.0) - cos_i * cos_i);
        if n1 > n2 {
            *margin = margin.min(SCALE * f64::from((sin2_t - t(1.0)).abs()));
        }
        if sin2_t > 1.0 {
            return (d.add(m.scale(t(2.0) * cos_i)), false, t(1.0));
        }
        let cos_t = (t(1.0) - sin2_t).sqrt();
        let rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
        let rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
        let r = t(0.5) * (rs * rs + rp * rp);
        (
            d.scale(eta).add(m.scale(eta * cos_i - cos_t)).unit(),
            true,
            r,
        )
    }

    /// The unit normal of ball `k` at `p`, outwards, and the indices on the ray's side and the
    /// other, for a ray `inside` it or not.
    fn face(&self, k: usize, p: V, inside: bool) -> (V, T, T) {
        let (normal, n) = if k < self.balls.len() {
            let (c, r, n) = self.balls[k];
            (p.sub(c).scale(t(1.0) / r), n)
        } else {
            // A prism: the face whose plane `p` lies on.
            let (planes, n) = &self.prisms[k - self.balls.len()];
            let off = |&(m, h): &(V, T)| (h - m.dot(p)).abs();
            let f = planes
                .iter()
                .min_by(|a, b| off(a).partial_cmp(&off(b)).unwrap())
                .unwrap();
            (f.0, *n)
        };
        if inside {
            (normal, n, t(1.0))
        } else {
            (normal, t(1.0), n)
        }
    }

    /// Traces `ray` (from air, outside every ball) by the course's law.
    pub fn trace(&self, ray: Ray) -> (BallOutcome, f64) {
        let mut margin = f64::INFINITY;
        let mut o = V::of(ray.origin);
        let mut d = V::of(ray.direction).unit();
        let (mut inside, mut left) = (None, None);
        let mut length = t(0.0);
        let mut events = Vec::new();
        loop {
            match self.nearest(o, d, inside, left, &mut margin) {
                None => {
                    let direction = d.f64();
                    return (BallOutcome::Escaped { events, direction }, margin);
                }
                Some(Met::Card(card, s)) => {
                    let point = o.at(d, s).f64();
                    let length = (length + s).into();
                    return (
                        BallOutcome::Card {
                            card,
                            point,
                            length,
                            events,
                        },
                        margin,
                    );
                }
                Some(Met::Ball(k, s)) => {
                    if events.len() == self.max_events as usize {
                        return (BallOutcome::Dropped, margin);
                    }
                    let p = o.at(d, s);
                    length += s;
                    events.push(p.f64());
                    let (normal, n1, n2) = self.face(k, p, inside == Some(k));
                    let (nd, refracted, _) = Self::scatter(d, normal, n1, n2, &mut margin);
                    if refracted {
                        inside = if inside == Some(k) { None } else { Some(k) };
                    }
                    (o, d, left) = (p, nd, Some(k));
                }
            }
        }
    }

    /// Fresnel mode: where the weight of `ray` ends (branches lighter than `prune` abandoned),
    /// and the smallest margin over all branches.
    pub fn fresnel(&self, ray: Ray, prune: f64) -> (Shares, f64) {
        let mut shares = Shares::default();
        let mut margin = f64::INFINITY;
        let start = Branch {
            o: V::of(ray.origin),
            d: V::of(ray.direction).unit(),
            inside: None,
            left: None,
            events: 0,
            weight: t(1.0),
        };
        self.branch(start, prune, &mut shares, &mut margin);
        (shares, margin)
    }

    fn branch(&self, b: Branch, prune: f64, shares: &mut Shares, margin: &mut f64) {
        let Some(met) = self.nearest(b.o, b.d, b.inside, b.left, margin) else {
            shares.escaped += f64::from(b.weight);
            return;
        };
        let (k, s) = match met {
            Met::Card(card, _) => {
                shares.cards[card] += f64::from(b.weight);
                return;
            }
            Met::Ball(k, s) => (k, s),
        };
        if b.events == self.max_events {
            shares.dropped += f64::from(b.weight);
            return;
        }
        let p = b.o.at(b.d, s);
        let was_inside = b.inside == Some(k);
        let (normal, n1, n2) = self.face(k, p, was_inside);
        let (nd, refracted, r) = Self::scatter(b.d, normal, n1, n2, margin);
        let mirrored = b.d.sub(normal.scale(t(2.0) * b.d.dot(normal)));
        let next = |d: V, inside: Option<usize>, weight: T| Branch {
            o: p,
            d,
            inside,
            left: Some(k),
            events: b.events + 1,
            weight,
        };
        if !refracted {
            self.branch(next(mirrored, b.inside, b.weight), prune, shares, margin);
            return;
        }
        let beyond = if was_inside { None } else { Some(k) };
        for (d, inside, w) in [
            (mirrored, b.inside, b.weight * r),
            (nd, beyond, b.weight * (t(1.0) - r)),
        ] {
            if prune > 0.0 {
                *margin = margin.min(SCALE * (f64::from(w) - prune).abs());
            }
            if f64::from(w) >= prune && w > 0.0 {
                self.branch(next(d, inside, w), prune, shares, margin);
            } else {
                shares.pruned += f64::from(w);
            }
        }
    }
}

/// One branch of a Fresnel trace.
struct Branch {
    o: V,
    d: V,
    inside: Option<usize>,
    left: Option<usize>,
    events: u32,
    weight: T,
}
