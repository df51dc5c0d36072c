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
//! Lenses and glasses of revolution ([`Solids`]), where a solid need not be convex nor stand in
//! air: every face is a piece of a surface `F(x) = 0` with the medium on each side of it named,
//! and a ray meets the face where `F(o + s·d)`, a quadratic (or linear) in `s`, vanishes at a
//! point of the piece; it crosses from the side it comes from (by the sign of `∇F·d`) into the
//! other. A lens is two caps of spheres (or flat disks) within its rim's radius of its axis,
//! closed by the cylinder of that radius where its faces leave a gap there. A glass of
//! revolution is its two walls, pieces on which `x² + y² = c0 + c1·u + c2·u²` (`u = z − zc`)
//! between two heights, glass between them, air outside, and in the cavity the liquids by height
//! (air above the last); its horizontal faces are the base, the floor, each liquid's surface and
//! the rim's ring, holed where a ball or a lens stands through them. A ray leaving a surface is not met again at its start (the quadratic's
//! constant is then 0: its other root only). What fills each point of a path (a ball, a lens by
//! its rim and faces, the glass or the cavity by the walls' radii at its height) is also told
//! from the solids' own definitions, and checked against what the faces said.
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

/// `a / b` to double-double's precision: long division, each step's remainder taken exactly.
/// (`twofloat` 0.8's own quotient of two double-doubles is no closer than a double's, 5e-17: it
/// forms `1 − b·(1/b)` without a fused multiply-add. A crossing 6 km from the eye was then
/// 0.3 pm off, as far as the library's own rounding puts it.)
fn div(a: T, b: T) -> T {
    let q1 = a.hi() / b.hi();
    let r = a - b * q1;
    let q2 = r.hi() / b.hi();
    let r = r - b * q2;
    let q3 = r.hi() / b.hi();
    T::new_add(q1, q2) + q3
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
        self.scale(div(t(1.0), self.dot(self).sqrt()))
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
                let s = div(-hb + disc.sqrt(), a);
                cands.push((s, Met::Ball(k, s), f64::INFINITY));
                continue;
            }
            if left == Some(k) {
                continue; // left outwards: a convex ball is not met again
            }
            // The line's distance from the centre, against the radius.
            let gap: f64 = (div(p.cross(d).dot(p.cross(d)), a).sqrt() - r).abs().into();
            grazing.push((div(-hb, a), gap));
            if disc < 0.0 {
                continue;
            }
            let s = div(-hb - disc.sqrt(), a);
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
                let s = div(num, dn);
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
            let s = div(c.sub(o).dot(front), dn);
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
        let eta = div(n1, n2);
        let sin2_t = eta * eta * (t(1.0) - cos_i * cos_i);
        if n1 > n2 {
            *margin = margin.min(SCALE * f64::from((sin2_t - t(1.0)).abs()));
        }
        if sin2_t > 1.0 {
            return (d.add(m.scale(t(2.0) * cos_i)), false, t(1.0));
        }
        let cos_t = (t(1.0) - sin2_t).sqrt();
        let rs = div(n1 * cos_i - n2 * cos_t, n1 * cos_i + n2 * cos_t);
        let rp = div(n2 * cos_i - n1 * cos_t, n2 * cos_i + n1 * cos_t);
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
            (p.sub(c).scale(div(t(1.0), r)), n)
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
        let start = Branch::from_eye(ray);
        self.branch(start, prune, &mut shares, &mut margin, &mut |_, _, _| {});
        (shares, margin)
    }

    /// Fresnel mode: every branch of `ray` that leaves the scene, as its events, its unit
    /// direction and its weight (branches lighter than `prune` abandoned), and the smallest
    /// margin over all branches.
    pub fn escapes(&self, ray: Ray, prune: f64) -> (Vec<(u32, Vec3, f64)>, f64) {
        let (mut shares, mut margin, mut out) = (Shares::default(), f64::INFINITY, Vec::new());
        let mut record = |events: u32, d: V, w: T| out.push((events, d.unit().f64(), f64::from(w)));
        let start = Branch::from_eye(ray);
        self.branch(start, prune, &mut shares, &mut margin, &mut record);
        (out, margin)
    }

    fn branch(
        &self,
        b: Branch,
        prune: f64,
        shares: &mut Shares,
        margin: &mut f64,
        escaped: &mut dyn FnMut(u32, V, T),
    ) {
        let Some(met) = self.nearest(b.o, b.d, b.inside, b.left, margin) else {
            shares.escaped += f64::from(b.weight);
            escaped(b.events, b.d, b.weight);
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
            self.branch(
                next(mirrored, b.inside, b.weight),
                prune,
                shares,
                margin,
                escaped,
            );
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
                self.branch(next(d, inside, w), prune, shares, margin, escaped);
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

impl Branch {
    /// The whole of `ray`, from air: no event yet, all its weight.
    fn from_eye(ray: Ray) -> Branch {
        Branch {
            o: V::of(ray.origin),
            d: V::of(ray.direction).unit(),
            inside: None,
            left: None,
            events: 0,
            weight: t(1.0),
        }
    }
}

/// What the tests compare: a reference's answer for one ray by the course's law and in Fresnel
/// mode, each with its margin.
pub trait Tracer {
    /// The course's answer for `ray` and its margin.
    fn trace(&self, ray: Ray) -> (BallOutcome, f64);
    /// Where the weight of `ray` ends in Fresnel mode, and the margin.
    fn fresnel(&self, ray: Ray, prune: f64) -> (Shares, f64);
    /// Whether light that came in from the air may be totally reflected.
    fn reflects_totally(&self) -> bool;
    /// How far `p` lies from the nearest of the surfaces its faces lie on (m): a point where a
    /// ray crosses a face lies on its surface to the rounding of its coordinates.
    fn off_surface(&self, p: Vec3) -> f64;
}

impl Tracer for Balls {
    fn trace(&self, ray: Ray) -> (BallOutcome, f64) {
        Balls::trace(self, ray)
    }
    fn fresnel(&self, ray: Ray, prune: f64) -> (Shares, f64) {
        Balls::fresnel(self, ray, prune)
    }
    fn reflects_totally(&self) -> bool {
        self.has_prisms()
    }
    fn off_surface(&self, p: Vec3) -> f64 {
        let p = V::of(p);
        let balls = self.balls.iter().map(|&(c, r, _)| {
            let q = p.sub(c);
            f64::from((q.dot(q).sqrt() - r).abs())
        });
        let planes = self
            .prisms
            .iter()
            .flat_map(|(planes, _)| planes.iter())
            .map(|&(m, h)| f64::from((m.dot(p) - h).abs()));
        balls.chain(planes).fold(f64::INFINITY, f64::min)
    }
}

// Lenses and containers of revolution: faces, each with a medium on either side.

/// A lens, by the scene file's numbers: its centre, its axis (light along it meets face 1
/// first), face 1's vertex `thickness/2` before the centre along it and face 2's as far after;
/// each face's signed radius of curvature (positive when its centre of curvature lies on the
/// `+axis` side of its vertex; 0 for a flat face), its diameter, its index. It is the solid
/// between its faces within `diameter/2` of its axis.
#[derive(Clone, Copy, Debug)]
pub struct Lens {
    pub centre: Vec3,
    pub axis: Vec3,
    pub radius1: f64,
    pub radius2: f64,
    pub thickness: f64,
    pub diameter: f64,
    pub index: f64,
}

/// A glass of revolution about the `z` axis, standing on `z = 0`: its outer surface (from the
/// base to the rim) and its inner one (from the floor to the rim) as pieces on which the squared
/// radius is a quadratic of the height (the profiles' definition: the scene's numbers, as a
/// ball's radius is), its glass's index and its liquids `(top, index)`, lowest first (each fills
/// the cavity from the one below, or the floor, up to its top; air above the last).
#[derive(Clone, Debug)]
pub struct Turned {
    pub outer: Vec<bentstraw_optics::profile::Piece>,
    pub inner: Vec<bentstraw_optics::profile::Piece>,
    pub index: f64,
    pub liquids: Vec<(f64, f64)>,
}

/// What lies on one side of a face.
#[derive(Clone, Copy, Debug)]
enum Side {
    /// A medium of this index.
    Index(T),
    /// Whatever fills the container's cavity at the point's height.
    Cavity,
}

/// The surface a face lies on, `F(x) = 0`, and the part of it the face is.
#[derive(Clone, Copy, Debug)]
enum Surface {
    /// `F = |x − c|² − r²`; a lens's cap is the part within `rim` of the line through `c` along
    /// the unit `toward` (from `c` to the cap's vertex), on the side it points to.
    Sphere { c: V, r: T, cap: Option<(V, T)> },
    /// `F = m·x − h` (unit `m`), the ring of radii `lo` to `hi` about its point `centre`.
    Plane { m: V, h: T, centre: V, lo: T, hi: T },
    /// `F = ρ² − r²`, `ρ` the distance from the line through `c` along unit `a`, for axial
    /// coordinates `(x − c)·a` from `w0` to `w1`.
    Cylinder { c: V, a: V, r: T, w0: T, w1: T },
    /// `F = x² + y² − (c0 + c1·u + c2·u²)`, `u = z − zc`, for `z` from `z0` to `z1`; `sharp` says
    /// which of its ends is an edge of the wall (the others are knots, where the next piece goes
    /// on smoothly).
    Turned {
        zc: T,
        c: [T; 3],
        z0: T,
        z1: T,
        sharp: [bool; 2],
    },
}

impl Surface {
    /// `F(o + s·d) = a·s² + 2·b·s + c`: `(a, b, c)`.
    fn along(&self, o: V, d: V) -> (T, T, T) {
        match *self {
            Surface::Sphere { c, r, .. } => {
                let p = o.sub(c);
                (d.dot(d), p.dot(d), p.dot(p) - r * r)
            }
            Surface::Plane { m, h, .. } => (t(0.0), t(0.5) * m.dot(d), m.dot(o) - h),
            Surface::Cylinder { c, a, r, .. } => {
                let p = o.sub(c);
                let pp = p.sub(a.scale(p.dot(a)));
                let dp = d.sub(a.scale(d.dot(a)));
                (dp.dot(dp), pp.dot(dp), pp.dot(pp) - r * r)
            }
            Surface::Turned { zc, c, .. } => {
                let u = o.z - zc;
                (
                    d.x * d.x + d.y * d.y - c[2] * d.z * d.z,
                    o.x * d.x + o.y * d.y - d.z * (t(0.5) * c[1] + c[2] * u),
                    o.x * o.x + o.y * o.y - (c[0] + c[1] * u + c[2] * u * u),
                )
            }
        }
    }

    /// `∇F` at `x` (towards the side where `F > 0`).
    fn gradient(&self, x: V) -> V {
        match *self {
            Surface::Sphere { c, .. } => x.sub(c).scale(t(2.0)),
            Surface::Plane { m, .. } => m,
            Surface::Cylinder { c, a, .. } => {
                let p = x.sub(c);
                p.sub(a.scale(p.dot(a))).scale(t(2.0))
            }
            Surface::Turned { zc, c, .. } => V {
                x: t(2.0) * x.x,
                y: t(2.0) * x.y,
                z: -(c[1] + t(2.0) * c[2] * (x.z - zc)),
            },
        }
    }

    /// Whether `x` (a point of the surface) lies on the face, and how near it is to the face's
    /// edge (m, roughly).
    fn within(&self, x: V) -> (bool, f64) {
        let gap = |a: T, b: T| f64::from((a - b).abs());
        match *self {
            Surface::Sphere { cap: None, .. } => (true, f64::INFINITY),
            Surface::Sphere {
                c,
                cap: Some((toward, rim)),
                ..
            } => {
                let q = x.sub(c);
                let w = q.dot(toward);
                let rho = max0(q.dot(q) - w * w).sqrt();
                (w >= 0.0 && rho <= rim, gap(rho, rim).min(gap(w, t(0.0))))
            }
            Surface::Plane { centre, lo, hi, .. } => {
                let q = x.sub(centre);
                let rho = q.dot(q).sqrt();
                let inner = if lo > 0.0 {
                    gap(rho, lo)
                } else {
                    f64::INFINITY
                };
                (rho >= lo && rho <= hi, gap(rho, hi).min(inner))
            }
            Surface::Cylinder { c, a, w0, w1, .. } => {
                let w = x.sub(c).dot(a);
                (w >= w0 && w <= w1, gap(w, w0).min(gap(w, w1)))
            }
            Surface::Turned { z0, z1, sharp, .. } => {
                let mut edge = f64::INFINITY;
                if sharp[0] {
                    edge = edge.min(gap(x.z, z0));
                }
                if sharp[1] {
                    edge = edge.min(gap(x.z, z1));
                }
                (x.z >= z0 && x.z <= z1, edge)
            }
        }
    }
}

/// `x`, or 0 if it is negative.
fn max0(x: T) -> T {
    if x < 0.0 {
        t(0.0)
    } else {
        x
    }
}

/// How far along its axis a lens's face of signed radius `r` lies from its vertex at distance
/// `rho` from the axis (its sag; 0 for a flat face).
fn sag(r: T, rho: T) -> T {
    if r == 0.0 {
        t(0.0)
    } else {
        let root = max0(r * r - rho * rho).sqrt();
        if r > 0.0 {
            r - root
        } else {
            r + root
        }
    }
}

/// One face: its surface, what lies on the side `∇F` points to (`plus`) and on the other, which
/// sheet it lies on (faces of one plane share one: a ray leaving it meets none of them at its
/// start), and whether the solids standing through it cut holes in it (the container's
/// horizontal faces: a liquid's surface does not lie inside a lens half dipped in it).
#[derive(Clone, Copy, Debug)]
struct Face {
    surface: Surface,
    plus: Side,
    minus: Side,
    sheet: usize,
    holed: bool,
}

/// A lens in double-double: centre, unit axis, signed radii, half thickness, rim radius, index.
#[derive(Clone, Copy, Debug)]
struct LensT {
    c: V,
    a: V,
    r1: T,
    r2: T,
    half: T,
    rim: T,
    n: T,
}

impl LensT {
    /// Whether `p` is strictly inside it: within its rim and between its faces.
    fn holds(&self, p: V) -> bool {
        let q = p.sub(self.c);
        let w = q.dot(self.a);
        let rho = max0(q.dot(q) - w * w).sqrt();
        rho < self.rim && w > -self.half + sag(self.r1, rho) && w < self.half + sag(self.r2, rho)
    }

    /// How far `p` is from the nearest of the surfaces its faces and rim lie on (m; no farther
    /// than from its boundary).
    fn edge(&self, p: V) -> f64 {
        let q = p.sub(self.c);
        let w = q.dot(self.a);
        let rho = max0(q.dot(q) - w * w).sqrt();
        let face = |r: T, vertex: T| {
            if r == 0.0 {
                (w - vertex).abs()
            } else {
                let centre = self.c.add(self.a.scale(vertex + r));
                let x = p.sub(centre);
                (x.dot(x).sqrt() - r.abs()).abs()
            }
        };
        f64::from((rho - self.rim).abs())
            .min(f64::from(face(self.r1, -self.half)))
            .min(f64::from(face(self.r2, self.half)))
    }
}

/// The container's profiles in double-double: each piece `(zc, c, z0, z1)`, lowest first.
type Pieces = Vec<(T, [T; 3], T, T)>;

/// The container in double-double, for telling what fills a point.
struct TurnedT {
    outer: Pieces,
    inner: Pieces,
    floor: T,
    rim: T,
    n: T,
    liquids: Vec<(T, T)>,
}

/// The squared radius at height `z` of the surface made of `pieces` (`None` outside them).
fn r2_at(pieces: &Pieces, z: T) -> Option<T> {
    pieces
        .iter()
        .find(|&&(_, _, z0, z1)| z >= z0 && z <= z1)
        .map(|&(zc, c, _, _)| {
            let u = z - zc;
            c[0] + c[1] * u + c[2] * u * u
        })
}

impl TurnedT {
    /// The index of what fills the cavity at height `z`: the first liquid whose top lies above,
    /// else air.
    fn cavity(&self, z: T) -> T {
        self.liquids
            .iter()
            .find(|&&(top, _)| z < top)
            .map_or(t(1.0), |&(_, n)| n)
    }

    /// What fills `p` (the container's glass, its cavity's contents, or air), and whether it is
    /// the cavity.
    fn medium(&self, p: V) -> (T, bool) {
        let rho2 = p.x * p.x + p.y * p.y;
        if p.z < 0.0 || p.z > self.rim || r2_at(&self.outer, p.z).is_none_or(|r2| rho2 > r2) {
            return (t(1.0), false);
        }
        if p.z < self.floor || r2_at(&self.inner, p.z).is_none_or(|r2| rho2 > r2) {
            return (self.n, false);
        }
        (self.cavity(p.z), true)
    }
}

/// What a ray meets first in [`Solids`].
enum Hit {
    /// Face `k`, at distance `s`.
    Face(usize, T),
    /// Card `k`, at distance `s`.
    Card(usize, T),
}

/// Transparent solids (balls, lenses) in air or in a container of revolution's liquids, the
/// container itself, and cards: every face with the medium on either side of it, so that a
/// ray's index on each side of a face it meets is the face's to say (and, as a check of the
/// reference itself, agrees with what the ray came through and with what fills the points of its
/// path by the solids' own definitions).
pub struct Solids {
    faces: Vec<Face>,
    balls: Vec<(V, T, T)>,
    lenses: Vec<LensT>,
    container: Option<TurnedT>,
    cards: Vec<(V, V, V, T, T)>,
    max_events: u32,
}

impl Solids {
    /// The reference for a container of revolution (or none), balls, lenses and cards (at most
    /// four), with event limit `max_events`. A solid whose centre lies over the cavity's floor,
    /// within its walls, stands in its contents (whichever layers it spans, and the air above
    /// them), any other in air.
    pub fn new(
        container: Option<&Turned>,
        balls: &[Ball],
        lenses: &[Lens],
        cards: &[Card],
        max_events: u32,
    ) -> Solids {
        assert!(cards.len() <= 4);
        let mut faces: Vec<Face> = Vec::new();
        let mut sheets = 0;
        let mut sheet = || {
            sheets += 1;
            sheets - 1
        };
        let air = Side::Index(t(1.0));
        let turned = container.map(|v| {
            let dd = |ps: &[bentstraw_optics::profile::Piece]| -> Pieces {
                ps.iter()
                    .map(|p| (t(p.zc), p.c.map(t), t(p.z0), t(p.z1)))
                    .collect()
            };
            let (outer, inner) = (dd(&v.outer), dd(&v.inner));
            TurnedT {
                floor: inner[0].2,
                rim: outer[outer.len() - 1].3,
                outer,
                inner,
                n: t(v.index),
                liquids: v.liquids.iter().map(|&(top, n)| (t(top), t(n))).collect(),
            }
        });
        if let Some(v) = &turned {
            let glass = Side::Index(v.n);
            // The walls: the outer between air and glass, the inner between glass and the
            // cavity's contents.
            for (pieces, plus, minus) in [(&v.outer, air, glass), (&v.inner, glass, Side::Cavity)] {
                for (i, &(zc, c, z0, z1)) in pieces.iter().enumerate() {
                    let surface = Surface::Turned {
                        zc,
                        c,
                        z0,
                        z1,
                        sharp: [i == 0, i == pieces.len() - 1],
                    };
                    faces.push(Face {
                        surface,
                        plus,
                        minus,
                        sheet: sheet(),
                        holed: false,
                    });
                }
            }
            // Horizontal faces: below each the `minus` side, above it the `plus` side.
            let up = V::of(Vec3::Z);
            let mut level = |z: T, lo: T, hi: T, below: T, above: T, sheet: usize| {
                faces.push(Face {
                    surface: Surface::Plane {
                        m: up,
                        h: z,
                        centre: V {
                            x: t(0.0),
                            y: t(0.0),
                            z,
                        },
                        lo,
                        hi,
                    },
                    plus: Side::Index(above),
                    minus: Side::Index(below),
                    sheet,
                    holed: true,
                });
            };
            let radius = |pieces: &Pieces, z: T| max0(r2_at(pieces, z).unwrap()).sqrt();
            let first = v.cavity(v.floor);
            let zero = t(0.0);
            let base = sheet();
            if v.floor > 0.0 {
                level(zero, zero, radius(&v.outer, zero), t(1.0), v.n, base);
                let r = radius(&v.inner, v.floor);
                if r > 0.0 {
                    level(v.floor, zero, r, v.n, first, sheet());
                }
            } else {
                // A bottom of no thickness: the cavity over the disk within the inner wall,
                // the wall's foot around it.
                let r = radius(&v.inner, zero);
                level(zero, zero, r, t(1.0), first, base);
                level(zero, r, radius(&v.outer, zero), t(1.0), v.n, base);
            }
            let mut rim_sheet = None;
            for (i, &(top, n)) in v.liquids.iter().enumerate() {
                let above = v.liquids.get(i + 1).map_or(t(1.0), |&(_, m)| m);
                let s = sheet();
                if top == v.rim {
                    rim_sheet = Some(s);
                }
                level(top, zero, radius(&v.inner, top), n, above, s);
            }
            let (r_in, r_out) = (radius(&v.inner, v.rim), radius(&v.outer, v.rim));
            if r_in < r_out {
                let s = rim_sheet.unwrap_or_else(&mut sheet);
                level(v.rim, r_in, r_out, v.n, t(1.0), s);
            }
        }
        // Where a solid stands: in the cavity's contents (its centre above the floor, within
        // the inner wall's radius at its height or the rim's above it: it may stand out of the
        // glass, or through a liquid's surface), or in air.
        let around = |c: V| match &turned {
            Some(v) => {
                let z = if c.z > v.rim { v.rim } else { c.z };
                let within = r2_at(&v.inner, z).is_some_and(|r2| c.x * c.x + c.y * c.y < r2);
                if c.z >= v.floor && within {
                    Side::Cavity
                } else {
                    air
                }
            }
            None => air,
        };
        let balls: Vec<(V, T, T)> = balls
            .iter()
            .map(|b| (V::of(b.centre), t(b.radius), t(b.index)))
            .collect();
        for &(c, r, n) in &balls {
            faces.push(Face {
                surface: Surface::Sphere { c, r, cap: None },
                plus: around(c),
                minus: Side::Index(n),
                sheet: sheet(),
                holed: false,
            });
        }
        let lenses: Vec<LensT> = lenses
            .iter()
            .map(|l| LensT {
                c: V::of(l.centre),
                a: V::of(l.axis).unit(),
                r1: t(l.radius1),
                r2: t(l.radius2),
                half: t(l.thickness) * t(0.5),
                rim: t(l.diameter) * t(0.5),
                n: t(l.index),
            })
            .collect();
        for l in &lenses {
            let (out, glass) = (around(l.c), Side::Index(l.n));
            // Face 1 faces −axis, face 2 +axis. A curved face's centre of curvature lies its
            // radius along the axis from its vertex; the lens lies inside that sphere where the
            // centre is on the lens's side of the vertex (radius1 > 0, radius2 < 0).
            for (r, vertex, outwards, inside_sphere) in [
                (
                    l.r1,
                    l.c.sub(l.a.scale(l.half)),
                    l.a.scale(t(-1.0)),
                    l.r1 > 0.0,
                ),
                (l.r2, l.c.add(l.a.scale(l.half)), l.a, l.r2 < 0.0),
            ] {
                let face = if r == 0.0 {
                    Face {
                        surface: Surface::Plane {
                            m: outwards,
                            h: outwards.dot(vertex),
                            centre: vertex,
                            lo: t(0.0),
                            hi: l.rim,
                        },
                        plus: out,
                        minus: glass,
                        sheet: sheet(),
                        holed: false,
                    }
                } else {
                    let c = vertex.add(l.a.scale(r));
                    let toward = vertex.sub(c).unit();
                    let (plus, minus) = if inside_sphere {
                        (out, glass)
                    } else {
                        (glass, out)
                    };
                    Face {
                        surface: Surface::Sphere {
                            c,
                            r: r.abs(),
                            cap: Some((toward, l.rim)),
                        },
                        plus,
                        minus,
                        sheet: sheet(),
                        holed: false,
                    }
                };
                faces.push(face);
            }
            // The rim, where the faces leave a gap at its radius.
            let (w0, w1) = (-l.half + sag(l.r1, l.rim), l.half + sag(l.r2, l.rim));
            if w1 > w0 {
                faces.push(Face {
                    surface: Surface::Cylinder {
                        c: l.c,
                        a: l.a,
                        r: l.rim,
                        w0,
                        w1,
                    },
                    plus: out,
                    minus: glass,
                    sheet: sheet(),
                    holed: false,
                });
            }
        }
        // A face between equal indices is none.
        faces.retain(|f| match (f.plus, f.minus) {
            (Side::Index(a), Side::Index(b)) => a != b,
            _ => true,
        });
        Solids {
            faces,
            balls,
            lenses,
            container: turned,
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

    /// The index on `side` of a face at `x`, and how near `x` is to a change of it (m).
    fn index(&self, side: Side, x: V) -> (T, f64) {
        match side {
            Side::Index(n) => (n, f64::INFINITY),
            Side::Cavity => {
                let v = self.container.as_ref().expect("a container");
                let near = v
                    .liquids
                    .iter()
                    .map(|&(top, _)| f64::from((x.z - top).abs()))
                    .fold(f64::INFINITY, f64::min);
                (v.cavity(x.z), near)
            }
        }
    }

    /// Whether `p` lies inside a ball or a lens, and how near it is to one's surface (m).
    fn in_solid(&self, p: V) -> (bool, f64) {
        let mut near = f64::INFINITY;
        let mut inside = false;
        for &(c, r, _) in &self.balls {
            let q = p.sub(c);
            let gap = q.dot(q).sqrt() - r;
            inside |= gap < 0.0;
            near = near.min(f64::from(gap.abs()));
        }
        for l in &self.lenses {
            inside |= l.holds(p);
            near = near.min(l.edge(p));
        }
        (inside, near)
    }

    /// What fills `p`, by the solids' and the container's own definitions.
    fn medium_at(&self, p: V) -> T {
        for &(c, r, n) in &self.balls {
            let q = p.sub(c);
            if q.dot(q) < r * r {
                return n;
            }
        }
        if let Some(l) = self.lenses.iter().find(|l| l.holds(p)) {
            return l.n;
        }
        self.container.as_ref().map_or(t(1.0), |v| v.medium(p).0)
    }

    /// The nearest thing ahead of `o` along unit `d`, having just left the sheet `left`; lowers
    /// `margin` to the closeness of every decision taken.
    fn nearest(&self, o: V, d: V, left: Option<usize>, margin: &mut f64) -> Option<Hit> {
        // (distance, what if it counts, closeness to an edge)
        let mut cands: Vec<(T, Option<Hit>, f64)> = Vec::new();
        // (distance to where the line comes nearest to touching a surface, how near)
        let mut grazing: Vec<(T, f64)> = Vec::new();
        for (k, f) in self.faces.iter().enumerate() {
            let leaving = left == Some(f.sheet);
            let (a, b, mut c) = f.surface.along(o, d);
            if leaving {
                c = t(0.0); // it starts on this surface: its crossing there is `s = 0`
            }
            let mut roots = [None, None];
            if a == 0.0 {
                if b != 0.0 && !leaving {
                    roots[0] = Some(div(-c, t(2.0) * b));
                }
            } else {
                let disc = b * b - a * c;
                // Where `F` along the line turns, and how far that point is from the surface
                // (`|F|` over `|∇F|`): 0 for a tangent line.
                let turn = div(-b, a);
                if turn > 0.0 {
                    let g = f.surface.gradient(o.at(d, turn));
                    let g = g.dot(g).sqrt();
                    if g > 0.0 {
                        grazing.push((turn, f64::from(div(div(disc, a).abs(), g))));
                    }
                }
                if disc >= 0.0 {
                    let sq = disc.sqrt();
                    let q = if b >= 0.0 { -(b + sq) } else { sq - b };
                    if q != 0.0 {
                        roots[0] = Some(div(q, a));
                        if !leaving {
                            roots[1] = Some(div(c, q));
                        }
                    }
                }
            }
            for s in roots.into_iter().flatten() {
                if s <= 0.0 {
                    continue;
                }
                let x = o.at(d, s);
                let (mut on, mut edge) = f.surface.within(x);
                if f.holed {
                    let (inside, near) = self.in_solid(x);
                    on &= !inside;
                    edge = edge.min(near);
                }
                let (np, ep) = self.index(f.plus, x);
                let (nm, em) = self.index(f.minus, x);
                let counts = on && np != nm;
                cands.push((s, counts.then_some(Hit::Face(k, s)), edge.min(ep).min(em)));
            }
        }
        for (k, &(c, front, right, w, h)) in self.cards.iter().enumerate() {
            let dn = d.dot(front);
            if dn == 0.0 {
                continue;
            }
            let s = div(c.sub(o).dot(front), dn);
            if s <= 0.0 {
                continue;
            }
            let q = o.at(d, s).sub(c);
            let (u, v) = (q.dot(right).abs(), q.z.abs());
            let (hw, hh) = (w * t(0.5), h * t(0.5));
            let on = u <= hw && v <= hh;
            let edge: f64 = if on {
                f64::from(hw - u).min(f64::from(hh - v))
            } else {
                let du: f64 = (u - hw).into();
                let dv: f64 = (v - hh).into();
                du.max(0.0).hypot(dv.max(0.0))
            };
            cands.push((s, on.then_some(Hit::Card(k, s)), edge));
        }
        let mut best: Option<usize> = None;
        for (i, (s, m, _)) in cands.iter().enumerate() {
            if m.is_some() && best.is_none_or(|b| *s < cands[b].0) {
                best = Some(i);
            }
        }
        let limit = best.map(|b| cands[b].0);
        for (i, &(s, ref m, edge)) in cands.iter().enumerate() {
            if limit.is_none_or(|l| s <= l) {
                *margin = margin.min(edge);
            }
            if let Some(l) = limit {
                if m.is_some() && Some(i) != best {
                    *margin = margin.min(f64::from((s - l).abs()));
                }
            }
        }
        for (turn, gap) in grazing {
            // A nearly tangent hit lies up to a half-chord before the turning point.
            if limit.is_none_or(|l| turn <= l + t(1e-4)) {
                *margin = margin.min(gap);
            }
        }
        cands.swap_remove(best?).1
    }

    /// Face `k` at `p` for a ray along `d`: its unit normal and the indices on the ray's side and
    /// the other.
    fn face(&self, k: usize, p: V, d: V) -> (V, T, T) {
        let f = &self.faces[k];
        let normal = f.surface.gradient(p).unit();
        let (np, _) = self.index(f.plus, p);
        let (nm, _) = self.index(f.minus, p);
        if d.dot(normal) < 0.0 {
            (normal, np, nm)
        } else {
            (normal, nm, np)
        }
    }

    /// Checks the reference's own bookkeeping: the ray travels through `here` on its way from `o`
    /// to `o + s·d` (or on for good, `s` infinite), as what fills the points of its path says.
    fn check_path(&self, o: V, d: V, s: Option<T>, here: T, margin: f64) {
        let mid = o.at(d, s.map_or(t(1.0), |s| s * t(0.5)));
        let there = self.medium_at(mid);
        assert!(
            there == here || margin < 1e-9,
            "reference: at {:?} the ray thinks it is in {here:?}, the point is in {there:?}",
            mid.f64()
        );
    }

    /// The indices the ray goes from and to at face `k`, checked against where it is.
    fn crossing(&self, k: usize, p: V, d: V, here: T, margin: f64) -> (V, T, T) {
        let (normal, n1, n2) = self.face(k, p, d);
        assert!(
            n1 == here || margin < 1e-9,
            "reference: at {:?} face {k} says the ray comes from {n1:?}, it is in {here:?}",
            p.f64()
        );
        (normal, n1, n2)
    }
}

impl Tracer for Solids {
    /// Traces `ray` by the course's law.
    fn trace(&self, ray: Ray) -> (BallOutcome, f64) {
        let mut margin = f64::INFINITY;
        let mut o = V::of(ray.origin);
        let mut d = V::of(ray.direction).unit();
        let mut here = self.medium_at(o);
        let mut left = None;
        let mut length = t(0.0);
        let mut events = Vec::new();
        loop {
            match self.nearest(o, d, left, &mut margin) {
                None => {
                    self.check_path(o, d, None, here, margin);
                    let direction = d.f64();
                    return (BallOutcome::Escaped { events, direction }, margin);
                }
                Some(Hit::Card(card, s)) => {
                    self.check_path(o, d, Some(s), here, margin);
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
                Some(Hit::Face(k, s)) => {
                    if events.len() == self.max_events as usize {
                        return (BallOutcome::Dropped, margin);
                    }
                    self.check_path(o, d, Some(s), here, margin);
                    let p = o.at(d, s);
                    length += s;
                    events.push(p.f64());
                    let (normal, n1, n2) = self.crossing(k, p, d, here, margin);
                    let (nd, refracted, _) = Balls::scatter(d, normal, n1, n2, &mut margin);
                    if refracted {
                        here = n2;
                    }
                    (o, d, left) = (p, nd, Some(self.faces[k].sheet));
                }
            }
        }
    }

    /// Fresnel mode: where the weight of `ray` ends (branches lighter than `prune` abandoned),
    /// and the smallest margin over all branches.
    fn fresnel(&self, ray: Ray, prune: f64) -> (Shares, f64) {
        let mut shares = Shares::default();
        let mut margin = f64::INFINITY;
        let o = V::of(ray.origin);
        let start = Ray3 {
            o,
            d: V::of(ray.direction).unit(),
            here: self.medium_at(o),
            left: None,
            events: 0,
            weight: t(1.0),
        };
        self.branch(start, prune, &mut shares, &mut margin);
        (shares, margin)
    }

    fn reflects_totally(&self) -> bool {
        true
    }

    fn off_surface(&self, p: Vec3) -> f64 {
        let p = V::of(p);
        self.faces
            .iter()
            .map(|f| {
                // |F| over |∇F|: the distance to the surface, to first order.
                let (_, _, c) = f.surface.along(p, V::of(Vec3::X));
                let g = f.surface.gradient(p);
                f64::from(div(c.abs(), g.dot(g).sqrt()))
            })
            .fold(f64::INFINITY, f64::min)
    }
}

/// One branch of a Fresnel trace through [`Solids`]: where it starts, along what, in what, the
/// sheet it leaves, its events so far and its weight.
struct Ray3 {
    o: V,
    d: V,
    here: T,
    left: Option<usize>,
    events: u32,
    weight: T,
}

impl Solids {
    fn branch(&self, b: Ray3, prune: f64, shares: &mut Shares, margin: &mut f64) {
        let Some(met) = self.nearest(b.o, b.d, b.left, margin) else {
            shares.escaped += f64::from(b.weight);
            return;
        };
        let (k, s) = match met {
            Hit::Card(card, _) => {
                shares.cards[card] += f64::from(b.weight);
                return;
            }
            Hit::Face(k, s) => (k, s),
        };
        if b.events == self.max_events {
            shares.dropped += f64::from(b.weight);
            return;
        }
        let p = b.o.at(b.d, s);
        let (normal, n1, n2) = self.crossing(k, p, b.d, b.here, *margin);
        let (nd, refracted, r) = Balls::scatter(b.d, normal, n1, n2, margin);
        let mirrored = b.d.sub(normal.scale(t(2.0) * b.d.dot(normal)));
        let next = |d: V, here: T, weight: T| Ray3 {
            o: p,
            d,
            here,
            left: Some(self.faces[k].sheet),
            events: b.events + 1,
            weight,
        };
        if !refracted {
            self.branch(next(mirrored, n1, b.weight), prune, shares, margin);
            return;
        }
        for (d, here, w) in [
            (mirrored, n1, b.weight * r),
            (nd, n2, b.weight * (t(1.0) - r)),
        ] {
            if prune > 0.0 {
                *margin = margin.min(SCALE * (f64::from(w) - prune).abs());
            }
            if f64::from(w) >= prune && w > 0.0 {
                self.branch(next(d, here, w), prune, shares, margin);
            } else {
                shares.pruned += f64::from(w);
            }
        }
    }
}
