//! The one rule for what a ray meets first, and what light does there: written once over
//! [`Real`], so that the same rule traces one ray in double precision and eight rays in single
//! precision.

use crate::geometry::{Ray, SideQuadratic};
use crate::interface::{reflectance_lanes, scatter_lanes};
use crate::lanes::{Constant, Mask, Real, V3};

use super::boundary::{Around, Clip, Reciprocals};
use super::{Hit, Part, World};

/// What the rays of a [`Real`] meet first.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Nearest<R: Real> {
    /// The distance (infinite where nothing is met).
    pub t: R,
    /// What is met: boundary `k` as `k`, object `j` as `boundaries + j`.
    pub code: R,
    /// The object's part (0 side, 1 bottom, 2 top).
    pub part: R,
    /// What tells the object's colour code there ([`Nearest::color`]).
    pub tag: R,
}

impl<R: Real> Nearest<R> {
    /// The colour codes where the lanes of `on_object` met objects of `world`.
    #[inline(always)]
    pub fn color(&self, world: &World, on_object: R::Mask) -> R {
        let first = world.boundaries.len();
        let object = self.code - R::splat(first as f64);
        let mut color = R::splat(0.0);
        for (j, m) in object.values(on_object, world.objects.len()) {
            color = R::select(m, world.objects[j].color_lanes(self.part, self.tag), color);
        }
        color
    }
}

/// What light does at the boundaries the rays of a [`Real`] have met.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Bend<R: Real> {
    /// Unit normal of the boundary, towards its outer side.
    pub normal: V3<R>,
    /// Index of the medium each ray comes through, and of the one beyond, and their ratio.
    pub n1: R,
    pub n2: R,
    pub eta: R,
    /// The medium beyond (the ray's if it is totally reflected).
    pub beyond: R,
    /// The refracted unit direction (meaningless where `total`) and the mirrored one.
    pub refracted: V3<R>,
    pub reflected: V3<R>,
    /// Total internal reflection.
    pub total: R::Mask,
    /// Cosine of incidence.
    pub cos_i: R,
    /// The code of the surface met (what the ray leaves from).
    pub surface: R,
    /// Whether the refracted ray, or the mirrored one, leaves the scene for good there.
    pub refracted_escapes: R::Mask,
    pub reflected_escapes: R::Mask,
}

impl<R: Real> Bend<R> {
    /// The unpolarised Fresnel reflectance (1 under total reflection).
    #[inline(always)]
    pub fn reflectance(&self) -> R {
        reflectance_lanes(self.n1, self.n2, self.eta, self.cos_i)
    }

    /// The direction the course's law picks: mirrored under total reflection, else refracted.
    #[inline(always)]
    pub fn outgoing(&self) -> V3<R> {
        V3::select(self.total, self.reflected, self.refracted)
    }
}

impl World {
    /// What the rays from `o` along unit `d` (the lanes of `alive`) meet first: the nearest
    /// boundary, or an object, which wins a tie; `None` if no live ray can meet anything. `left`
    /// is the code of what each ray has just left ([`World::surface_code`],
    /// [`World::object_code`], or −1): that surface's crossing at the ray's start is excluded
    /// exactly, and an object (convex) not met at all.
    #[inline(always)]
    pub(crate) fn nearest_lanes<R: Real>(
        &self,
        o: V3<R>,
        d: V3<R>,
        alive: R::Mask,
        left: R,
    ) -> Option<Nearest<R>> {
        self.nearest_lanes_in::<R, true>(o, d, alive, left)
    }

    /// [`World::nearest_lanes`], compiled for a world with transparent solids or a curved wall
    /// (`SOLIDS`) or for one of plain faces alone ([`World::plain_only`]): the packet tracers
    /// choose once per row, so that the plain scenes' loop carries none of the solids' code.
    #[inline(always)]
    pub(crate) fn nearest_lanes_in<R: Real, const SOLIDS: bool>(
        &self,
        o: V3<R>,
        d: V3<R>,
        alive: R::Mask,
        left: R,
    ) -> Option<Nearest<R>> {
        let inf = R::splat(f64::INFINITY);
        // Everything lies within the reach around the z axis: a line clearly outside meets nothing.
        let reach2 = self.reach * self.reach;
        let r2 = R::splat(reach2);
        let around = Around {
            r2: reach2,
            quadratic: SideQuadratic::new(o.x, o.y, d.x, d.y, r2),
        };
        let alive = alive.and_not(around.quadratic.clearly_misses(r2));
        if !alive.any() {
            return None;
        }
        let mut inv = Reciprocals::new(d);
        if !self.verticals {
            // Not needed: no division by dx or dy (the compiler drops the unused ones).
            inv.d.x = R::splat(0.0);
            inv.d.y = R::splat(0.0);
        }
        let mut t = inf;
        let mut code = R::splat(-1.0);
        // The nearest so far, without a closure: everything here must be inlined into the
        // packets' code compiled for their instruction set.
        macro_rules! take {
            ($tb:expr, $b:expr) => {{
                let tb = $tb;
                let m = tb.lt(t);
                t = R::select(m, tb, t);
                code = R::select(m, R::splat($b.codes.index as f64), code);
            }};
        }
        // The lanes the objects may be met in: within the circle holding the container and its
        // objects.
        let objects_alive;
        if !SOLIDS || self.plain_only() {
            // No solid and no curved wall: the container's and liquids' faces alone, with the
            // lean intersection of their three shapes, in one loop (the scenes of old trace as
            // they always did, at their speed).
            for f in &self.plain_faces {
                let leaving = left.eq(R::splat(f.codes.surface as f64));
                take!(f.shape.crossing(o, d, &inv, leaving, alive, &around), f);
            }
            objects_alive = alive;
        } else {
            // The container, its liquids and the objects may lie within a narrower circle than
            // the solids beside them: lines clearly outside it skip their faces.
            let pr2 = R::splat(self.plain_reach * self.plain_reach);
            let quadratic = SideQuadratic::new(o.x, o.y, d.x, d.y, pr2);
            let plain_alive = alive.and_not(quadratic.clearly_misses(pr2));
            let plain_around = Around {
                r2: self.plain_reach * self.plain_reach,
                quadratic,
            };
            // The container's and liquids' plain faces first, clipped where a solid pierces
            // them; then each solid's faces (and a glass of revolution's wall), unless every
            // line misses the ball holding them (or starts outside it moving away): a lens's
            // three faces cost one quadratic then.
            if plain_alive.any() {
                for f in &self.plain_faces {
                    let leaving = left.eq(R::splat(f.codes.surface as f64));
                    let tb = f
                        .shape
                        .crossing(o, d, &inv, leaving, plain_alive, &plain_around);
                    take!(self.clipped(f.holes, o, d, tb), f);
                }
            }
            for body in &self.bodies {
                let faces = &self.boundaries[body.faces[0]..body.faces[1]];
                if faces.len() > 1 {
                    let q = SideQuadratic::sphere(o - V3::splat(body.centre), d, R::splat(body.r2));
                    if !alive.and(q.real()).and_not(q.moving_away()).any() {
                        continue;
                    }
                }
                for b in faces {
                    let leaving = left.eq(R::splat(b.codes.surface as f64));
                    let tb = b.crossing(o, d, &inv, leaving, alive, &around);
                    take!(self.clipped(b.holes, o, d, tb), b);
                }
            }
            objects_alive = plain_alive;
        }
        let mut part = R::splat(0.0);
        let mut tag = R::splat(0.0);
        let first_object = self.boundaries.len();
        for (j, object) in self.objects.iter().enumerate() {
            let own = R::splat(self.object_code(j) as f64);
            let live = objects_alive.and_not(left.eq(own));
            if !live.any() {
                continue;
            }
            if let Some((to, po, co)) = object.entry(o, d, &inv, live, left) {
                // The opaque object wins a tie (a straw's bottom cap on the water's bottom).
                let m = live.and(to.le(t)).and(to.lt(inf));
                t = R::select(m, to, t);
                code = R::select(m, R::splat((first_object + j) as f64), code);
                part = R::select(m, po, part);
                tag = R::select(m, co, tag);
            }
        }
        Some(Nearest { t, code, part, tag })
    }

    /// `tb` (the distances at which the rays from `o` along `d` meet a face), infinite where
    /// what solids make of the face (its `holes` in the clips) leaves the point out: a hole where one pierces it, outside
    /// a prism's polygon for its own top and bottom.
    #[inline(always)]
    fn clipped<R: Real>(&self, holes: [u16; 2], o: V3<R>, d: V3<R>, mut tb: R) -> R {
        let inf = R::splat(f64::INFINITY);
        for clip in &self.clips[holes[0] as usize..holes[1] as usize] {
            let (x, y) = (o.x + tb * d.x, o.y + tb * d.y);
            tb = match *clip {
                Clip::OutsideDisk { cx, cy, r2 } => {
                    let (u, v) = (x - R::splat(cx), y - R::splat(cy));
                    R::select((u * u + v * v).lt(R::splat(r2)), inf, tb)
                }
                Clip::OutsidePolygon(range) => {
                    R::select(self.outside_polygon(x, y, range), tb, inf)
                }
                Clip::InsidePolygon(range) => R::select(self.outside_polygon(x, y, range), inf, tb),
                Clip::OutsideLens(k) => {
                    let z = o.z + tb * d.z;
                    R::select(self.lens_holes[k as usize].holds(x, y, z), inf, tb)
                }
            };
        }
        tb
    }

    /// The lanes whose point `(x, y)` lies outside the convex polygon of the world's edges in
    /// `range` (to the right of one of them).
    #[inline(always)]
    fn outside_polygon<R: Real>(&self, x: R, y: R, range: [u16; 2]) -> R::Mask {
        let mut outside = R::splat(1.0).lt(R::splat(0.0));
        for e in &self.edges[range[0] as usize..range[1] as usize] {
            let side =
                R::splat(e.ex) * (y - R::splat(e.ay)) - R::splat(e.ey) * (x - R::splat(e.ax));
            outside = outside.or(side.lt(R::splat(0.0)));
        }
        outside
    }

    /// What light does where the rays of `live`, travelling along `d` in medium `medium`, meet
    /// the boundaries `code` at the points `q`: the boundary's normal and the indices on its two
    /// sides, then Snell's law (refraction or total reflection) and the mirror.
    #[inline(always)]
    pub(crate) fn bend_lanes<R: Real>(
        &self,
        code: R,
        live: R::Mask,
        q: V3<R>,
        d: V3<R>,
        medium: R,
    ) -> Bend<R> {
        self.bend_lanes_in::<R, true>(code, live, q, d, medium)
    }

    /// [`World::bend_lanes`] for a world with solids or without (see
    /// [`World::nearest_lanes_in`]).
    #[inline(always)]
    pub(crate) fn bend_lanes_in<R: Real, const SOLIDS: bool>(
        &self,
        code: R,
        live: R::Mask,
        q: V3<R>,
        d: V3<R>,
        medium: R,
    ) -> Bend<R> {
        let zero = R::splat(0.0);
        let none = R::Mask::splat(false);
        let mut normal = V3::new(zero, zero, zero);
        let (mut n1, mut n2, mut eta) = (zero, zero, zero);
        let mut beyond = medium;
        let mut surface = R::splat(-1.0);
        // Where the refracted and the mirrored light leave the scene for good.
        let (mut refracted_escapes, mut reflected_escapes) = (none, none);
        for (k, m) in code.values(live, self.boundaries.len()) {
            let b = &self.boundaries[k];
            // Most packets meet one boundary: then every lane takes its values, no select.
            let all = !live.and_not(m).any();
            let pick = |a: R, b: R| if all { a } else { R::select(m, a, b) };
            let pick_mask = |a: R::Mask, b: R::Mask| {
                if all {
                    a
                } else {
                    R::Mask::select_mask(m, a, b)
                }
            };
            // The container's and liquids' faces (first in the list) by their lean rule.
            let n = if !SOLIDS || k < self.plain {
                self.plain_faces[k].shape.normal_at(q)
            } else {
                b.normal_at(q)
            };
            normal = V3::new(
                pick(n.x, normal.x),
                pick(n.y, normal.y),
                pick(n.z, normal.z),
            );
            // The lanes coming from the inner side, and each side's indices and medium.
            let inside = medium.eq(R::splat(b.codes.inner as f64));
            let x = &b.optics;
            let side = |from_inner: Constant, from_outer: Constant| {
                R::select(inside, R::constant(from_inner), R::constant(from_outer))
            };
            n1 = pick(side(x.n_inner, x.n_outer), n1);
            n2 = pick(side(x.n_outer, x.n_inner), n2);
            eta = pick(side(x.eta_out, x.eta_in), eta);
            beyond = pick(
                R::select(
                    inside,
                    R::splat(b.codes.outer as f64),
                    R::splat(b.codes.inner as f64),
                ),
                beyond,
            );
            surface = pick(R::splat(b.codes.surface as f64), surface);
            // Refracted light changes side, mirrored light stays; it escapes where that side is
            // the boundary's escape side.
            let (to_outer, to_inner) = (inside, R::Mask::splat(true).and_not(inside));
            let (refr, refl) = match b.escape {
                1 => (to_outer, to_inner),
                -1 => (to_inner, to_outer),
                _ => (none, none),
            };
            refracted_escapes = pick_mask(refr, refracted_escapes);
            reflected_escapes = pick_mask(refl, reflected_escapes);
        }
        let s = scatter_lanes(d, normal, eta);
        Bend {
            normal,
            n1,
            n2,
            eta,
            beyond: R::select(s.total, medium, beyond),
            refracted: s.refracted.renormalize(),
            reflected: s.reflected,
            total: s.total,
            cos_i: s.cos_i,
            surface,
            refracted_escapes: refracted_escapes.and(live).and_not(s.total),
            reflected_escapes: reflected_escapes.and(live),
        }
    }

    /// The nearest thing `ray` meets ahead: a boundary or an object (which wins a tie). `left` is
    /// the code of what the ray starts on, having just met it ([`World::surface_code`] of a
    /// boundary, [`World::object_code`] of an object).
    #[inline]
    pub fn nearest(&self, ray: &Ray, left: Option<u32>) -> Option<Hit> {
        let (o, d) = (V3::from(ray.origin), V3::from(ray.direction));
        let left = left.map_or(-1.0, |c| c as f64);
        let n = self.nearest_lanes(o, d, true, left)?;
        if !n.t.is_finite() {
            return None;
        }
        let k = n.code as usize;
        Some(if k < self.boundaries.len() {
            Hit::Boundary { t: n.t, index: k }
        } else {
            Hit::Object {
                t: n.t,
                index: k - self.boundaries.len(),
                part: Part::from_code(n.part),
                color: n.color(self, true) as u8,
            }
        })
    }
}
