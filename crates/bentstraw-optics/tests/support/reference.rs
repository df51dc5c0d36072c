//! An independent tracer for the tests, written straight from the physics in double-double
//! arithmetic (`twofloat`, about 32 significant digits): the six faces tested one by one with the
//! textbook formulas (which double-double can afford: their cancellation costs it nothing that
//! matters), the nearest kept (the straw wins ties), refraction or total reflection at each water
//! face, at most `max_events` events. Nothing is shared with the library but the scene's numbers.
//!
//! Along with each result it reports a `margin` (metres): how close the ray came to a decision
//! that could go the other way — a face's edge, a grazing or nearly tied hit, the critical angle,
//! a colour boundary. Where the margin is far above double precision's rounding (say 1e-9 m), the
//! library must agree exactly; below it, either answer is right to rounding.
#![allow(dead_code)]

use bentstraw_optics::geometry::Ray;
use bentstraw_optics::scene::{
    Scene, GLASS_RADIUS, SECTION_COUNT, SECTION_EDGES, STRAW_HEIGHT, STRAW_RADIUS,
};
use bentstraw_optics::Vec3;
use twofloat::TwoFloat as T;

/// Scale turning dimensionless closeness (the critical angle) into metres.
const SCALE: f64 = 0.1;

#[derive(Clone, Copy, Debug)]
struct V {
    x: T,
    y: T,
    z: T,
}

fn t(x: f64) -> T {
    T::from(x)
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
    fn unit(self) -> V {
        self.scale(T::from(1.0) / self.dot(self).sqrt())
    }
    fn at(self, d: V, s: T) -> V {
        self.add(d.scale(s))
    }
}

/// Faces: 0 water side, 1 water top, 2 water bottom, 3 straw side, 4 straw top, 5 straw bottom.
const WATER_SIDE: usize = 0;
const WATER_TOP: usize = 1;
const WATER_BOTTOM: usize = 2;

/// The reference's verdict on one ray (course mode).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RefOutcome {
    /// Reached the straw.
    Straw {
        /// Colour code.
        color: u8,
        /// Length of the broken path (m).
        length: f64,
        /// The straw point.
        point: Vec3,
        /// Events on the way.
        events: u32,
    },
    /// Left the scene after so many events.
    Escaped { events: u32 },
    /// Would need one event more than allowed.
    Dropped,
}

impl RefOutcome {
    /// Colour code, 0 for none.
    pub fn color(&self) -> u8 {
        match self {
            RefOutcome::Straw { color, .. } => *color,
            _ => 0,
        }
    }
}

/// The scene in double-double.
pub struct Reference {
    xp: T,
    yp: T,
    he: T,
    n: T,
    has_water: bool,
    max_events: u32,
}

/// A hit found: distance, face, and the closeness of the decisions that made it.
struct Hit {
    s: T,
    face: usize,
}

impl Reference {
    /// The reference for `scene`.
    pub fn new(scene: &Scene) -> Reference {
        Reference {
            xp: t(scene.straw_x()),
            yp: t(scene.straw_y()),
            he: t(scene.water_height()),
            n: t(scene.n_water()),
            has_water: scene.water_height() > 0.0,
            max_events: scene.max_events(),
        }
    }

    /// The nearest face ahead of `o + s·d` (`s > 0`), `left` the face it starts on; lowers
    /// `margin` to the closeness of every decision taken.
    fn nearest(&self, o: V, d: V, left: Option<usize>, margin: &mut f64) -> Option<Hit> {
        // (distance, face, accepted, closeness to the face's edge)
        let mut cands: Vec<(T, usize, bool, f64)> = Vec::new();
        let mut grazing: Vec<(T, f64)> = Vec::new();
        let mut side = |cx: T, cy: T, r: f64, zmax: T, face: usize, straw: bool| {
            let (px, py) = (o.x - cx, o.y - cy);
            let a = d.x * d.x + d.y * d.y;
            if a == 0.0 {
                return;
            }
            let hb = px * d.x + py * d.y;
            let c = px * px + py * py - t(r) * t(r);
            let disc = hb * hb - a * c;
            // How near the line comes to touching the cylinder, where that happens ahead.
            let closest = -hb / a;
            let line_gap: f64 = ((px * px + py * py - hb * hb / a).sqrt() - t(r))
                .abs()
                .into();
            grazing.push((closest, line_gap));
            if disc < 0.0 {
                return;
            }
            let sq = disc.sqrt();
            let roots = [(-hb - sq) / a, (-hb + sq) / a];
            let chosen: Vec<T> = if straw {
                vec![roots[0]] // opaque: only where light enters it
            } else if left == Some(face) {
                // Starting on it: the other root from the one at the start.
                if roots[0].abs() < roots[1].abs() {
                    vec![roots[1]]
                } else {
                    vec![roots[0]]
                }
            } else {
                roots.to_vec()
            };
            for s in chosen {
                if s > 0.0 {
                    let z = o.z + s * d.z;
                    let edge: f64 = z.abs().min((z - zmax).abs()).into();
                    cands.push((s, face, z >= 0.0 && z <= zmax, edge));
                }
            }
        };
        if self.has_water {
            side(t(0.0), t(0.0), GLASS_RADIUS, self.he, WATER_SIDE, false);
        }
        side(self.xp, self.yp, STRAW_RADIUS, t(STRAW_HEIGHT), 3, true);
        let mut disk = |cx: T, cy: T, z: T, r: f64, face: usize| {
            if d.z == 0.0 {
                return;
            }
            let s = (z - o.z) / d.z;
            if s > 0.0 {
                let (x, y) = (o.x + s * d.x - cx, o.y + s * d.y - cy);
                let rho = (x * x + y * y).sqrt();
                let edge: f64 = (rho - t(r)).abs().into();
                cands.push((s, face, rho <= t(r), edge));
            }
        };
        if self.has_water && left != Some(WATER_TOP) {
            disk(t(0.0), t(0.0), self.he, GLASS_RADIUS, WATER_TOP);
        }
        if left != Some(WATER_BOTTOM) {
            if self.has_water {
                disk(t(0.0), t(0.0), t(0.0), GLASS_RADIUS, WATER_BOTTOM);
            }
            disk(self.xp, self.yp, t(0.0), STRAW_RADIUS, 5);
        }
        disk(self.xp, self.yp, t(STRAW_HEIGHT), STRAW_RADIUS, 4);

        // Nearest accepted; the straw wins ties.
        let mut best: Option<(T, usize)> = None;
        for &(s, face, ok, _) in &cands {
            if !ok {
                continue;
            }
            best = match best {
                None => Some((s, face)),
                Some((bs, bf)) => {
                    if s < bs || (s == bs && face >= 3 && bf < 3) {
                        Some((s, face))
                    } else {
                        Some((bs, bf))
                    }
                }
            };
        }
        let limit = best.map(|b| b.0);
        for &(s, face, ok, edge) in &cands {
            let before = limit.is_none_or(|l| s <= l);
            if before {
                *margin = margin.min(edge);
            }
            if let Some((bs, bf)) = best {
                let same_plane = matches!((face, bf), (2, 5) | (5, 2));
                if ok && face != bf && !same_plane {
                    *margin = margin.min(f64::from((s - bs).abs()));
                }
            }
        }
        for (closest, gap) in grazing {
            // A nearly tangent hit lies up to a half-chord sqrt(2·R·gap) before the closest point.
            if closest > 0.0 && limit.is_none_or(|l| closest <= l + t(1e-4)) {
                *margin = margin.min(gap);
            }
        }
        best.map(|(s, face)| Hit { s, face })
    }

    /// Colour code of straw face `face` at `p`, lowering `margin` to the distance from a
    /// section boundary.
    fn color(&self, face: usize, p: V, margin: &mut f64) -> u8 {
        match face {
            5 => 1,
            4 => SECTION_COUNT as u8,
            _ => {
                let mut code = 1;
                for e in SECTION_EDGES {
                    *margin = margin.min(f64::from((p.z - t(e)).abs()));
                    if p.z >= t(e) {
                        code += 1;
                    }
                }
                code
            }
        }
    }

    /// Unit normal out of the water at `p` of water face `face`.
    fn normal(&self, face: usize, p: V) -> V {
        match face {
            WATER_TOP => V::of(Vec3::Z),
            WATER_BOTTOM => V::of(Vec3::NEG_Z),
            _ => V {
                x: p.x,
                y: p.y,
                z: t(0.0),
            }
            .unit(),
        }
    }

    /// Snell–Descartes or total reflection of `d` at unit `normal` from `n1` into `n2`: the new
    /// direction and whether it was refracted; lowers `margin` by the closeness to the critical
    /// angle.
    fn scatter(d: V, normal: V, n1: T, n2: T, margin: &mut f64) -> (V, bool) {
        let mut cos_i = -(d.dot(normal));
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
            (d.add(m.scale(t(2.0) * cos_i)), false)
        } else {
            let cos_t = (t(1.0) - sin2_t).sqrt();
            (d.scale(eta).add(m.scale(eta * cos_i - cos_t)).unit(), true)
        }
    }

    /// Traces the ray from `origin` along `direction` (normalised here) by the course's law.
    pub fn trace(&self, ray: Ray) -> (RefOutcome, f64) {
        let mut margin = f64::INFINITY;
        let mut o = V::of(ray.origin);
        let mut d = V::of(ray.direction).unit();
        let (mut in_water, mut events, mut length, mut left) = (false, 0u32, t(0.0), None);
        loop {
            let Some(hit) = self.nearest(o, d, left, &mut margin) else {
                return (RefOutcome::Escaped { events }, margin);
            };
            let p = o.at(d, hit.s);
            length += hit.s;
            if hit.face >= 3 {
                let color = self.color(hit.face, p, &mut margin);
                return (
                    RefOutcome::Straw {
                        color,
                        length: length.into(),
                        point: p.f64(),
                        events,
                    },
                    margin,
                );
            }
            if events == self.max_events {
                return (RefOutcome::Dropped, margin);
            }
            events += 1;
            let (n1, n2) = if in_water {
                (self.n, t(1.0))
            } else {
                (t(1.0), self.n)
            };
            let (nd, refracted) = Self::scatter(d, self.normal(hit.face, p), n1, n2, &mut margin);
            if refracted {
                in_water = !in_water;
            }
            (o, d, left) = (p, nd, Some(hit.face));
        }
    }

    /// Fresnel weights per section (unpolarised reflectance, branches lighter than `prune`
    /// abandoned), and the smallest margin over all branches.
    pub fn fresnel(&self, ray: Ray, prune: f64) -> ([f64; SECTION_COUNT], f64) {
        let mut out = [0.0; SECTION_COUNT];
        let mut margin = f64::INFINITY;
        let d = V::of(ray.direction).unit();
        self.branch(
            V::of(ray.origin),
            d,
            false,
            0,
            1.0,
            prune,
            None,
            &mut out,
            &mut margin,
        );
        (out, margin)
    }

    #[allow(clippy::too_many_arguments)]
    fn branch(
        &self,
        o: V,
        d: V,
        in_water: bool,
        events: u32,
        weight: f64,
        prune: f64,
        left: Option<usize>,
        out: &mut [f64; SECTION_COUNT],
        margin: &mut f64,
    ) {
        let Some(hit) = self.nearest(o, d, left, margin) else {
            return;
        };
        let p = o.at(d, hit.s);
        if hit.face >= 3 {
            out[self.color(hit.face, p, margin) as usize - 1] += weight;
            return;
        }
        if events == self.max_events {
            return;
        }
        let normal = self.normal(hit.face, p);
        let (n1, n2) = if in_water {
            (self.n, t(1.0))
        } else {
            (t(1.0), self.n)
        };
        let (nd, refracted) = Self::scatter(d, normal, n1, n2, margin);
        let mirrored = {
            let c = d.dot(normal);
            d.add(normal.scale(t(-2.0) * c))
        };
        let next = Some(hit.face);
        if !refracted {
            self.branch(
                p,
                mirrored,
                in_water,
                events + 1,
                weight,
                prune,
                next,
                out,
                margin,
            );
            return;
        }
        let cos_i = d.dot(normal).abs();
        let cos_t = nd.dot(normal).abs();
        let rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
        let rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
        let r: f64 = (t(0.5) * (rs * rs + rp * rp)).into();
        let (wr, wt) = (weight * r, weight * (1.0 - r));
        if wr >= prune && wr > 0.0 {
            self.branch(
                p,
                mirrored,
                in_water,
                events + 1,
                wr,
                prune,
                next,
                out,
                margin,
            );
        }
        if wt >= prune && wt > 0.0 {
            self.branch(p, nd, !in_water, events + 1, wt, prune, next, out, margin);
        }
    }
}
