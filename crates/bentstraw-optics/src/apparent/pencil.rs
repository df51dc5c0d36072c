//! Thin pencils of rays around one traced ray (ray differentials): how a neighbouring ray's point
//! and direction differ from the traced one's, to first order, carried along its straight
//! segments and through its refractions and total reflections in closed form.
//!
//! This is the matrix form of the generalised Coddington equations: a pencil from a point (or
//! from a displaced eye) is a pair of position and direction differentials for each of its two
//! transverse parameters, and the wavefront's curvature matrix is their quotient, so that a
//! point source (infinite curvature) and a focus between two faces need no special case.
//!
//! Along a straight segment of length `t` a differential `(δx, δd)` becomes `(δx + t·δd, δd)`.
//! At a face met at `p` with unit normal `n` (the tracer's), the neighbouring ray meets it
//! `δt = −(δx·n)/(d·n)` further, at `p + δp` with `δp = δx + δt·d` in the face's tangent plane,
//! where the normal has turned by `δn` (zero on a plane; `(δp_x, δp_y, 0)/R` on an upright
//! cylinder of radius `R`, whose outward normal is `(p − c)/R`: the face's curvature `1/R` across
//! its axis, none along it). Snell's law as `d' = η·d + γ·n`, `γ = b − η·a`, `a = d·n`,
//! `b = d'·n = ±√(1 − η²(1 − a²))`, differentiated: `δa = δd·n + d·δn`, `δb = η²·a·δa/b`,
//! `δd' = η·δd + (δb − η·δa)·n + γ·δn`. A total reflection is the same with `η = 1`, `b = −a`
//! (`d' = d − 2a·n`). (Igehy, "Tracing ray differentials", SIGGRAPH 1999.)

use crate::world::{Event, World};
use crate::Vec3;

/// How a ray's point and direction change, to first order, with one parameter of a family of
/// rays around it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Differential {
    /// Change of the ray's point (m per unit of the parameter).
    pub position: Vec3,
    /// Change of the ray's unit direction (per unit of the parameter).
    pub direction: Vec3,
}

impl Differential {
    /// A displacement of the ray's start along `v`, its direction unchanged.
    pub fn moved(v: Vec3) -> Differential {
        Differential {
            position: v,
            direction: Vec3::ZERO,
        }
    }

    /// A turn of the ray's direction by `v` (perpendicular to it), its start unchanged.
    pub fn turned(v: Vec3) -> Differential {
        Differential {
            position: Vec3::ZERO,
            direction: v,
        }
    }
}

/// `K` families of rays around one ray, followed with it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Pencil<const K: usize> {
    /// The point of the ray the differentials are at.
    origin: Vec3,
    /// The ray's unit direction there.
    direction: Vec3,
    /// The differentials at `origin`.
    differentials: [Differential; K],
}

impl<const K: usize> Pencil<K> {
    /// The ray from `origin` along unit `direction` with its `differentials` there.
    pub fn new(origin: Vec3, direction: Vec3, differentials: [Differential; K]) -> Self {
        Pencil {
            origin,
            direction,
            differentials,
        }
    }

    /// The ray's unit direction now.
    pub fn direction(&self) -> Vec3 {
        self.direction
    }

    /// The ray's point now (its start, or its last event).
    pub fn origin(&self) -> Vec3 {
        self.origin
    }

    /// Carries the pencil to `e`, the ray's next event in `world`, and through it (module docs).
    #[inline]
    pub fn cross(&mut self, world: &World, e: &Event) {
        let (d, n, out) = (self.direction, e.normal, e.outgoing);
        let t = (e.point - self.origin).dot(d);
        // Curved faces (a glass's walls, a sphere) turn the normal along the step: `dn`.
        let boundary = &world.boundaries()[e.boundary];
        let a = d.dot(n);
        let (eta, b) = if e.totally_reflected {
            (1.0, -a)
        } else {
            (e.n1 / e.n2, out.dot(n))
        };
        let gamma = b - eta * a;
        let (along_a, along_b) = (1.0 / a, eta * eta * a / b);
        for k in &mut self.differentials {
            let x = k.position + t * k.direction;
            let dp = x - (x.dot(n) * along_a) * d;
            let dn = boundary.normal_change(e.point, dp);
            let da = k.direction.dot(n) + d.dot(dn);
            let db = along_b * da;
            k.direction = eta * k.direction + (db - eta * da) * n + gamma * dn;
            k.position = dp;
        }
        self.origin = e.point;
        self.direction = out;
    }

    /// Each differential's displacement across the ray in the plane through `q` (a point on the
    /// ray's line ahead) perpendicular to the ray: where the neighbouring rays cross that plane.
    #[inline]
    pub fn across_at(&self, q: Vec3) -> [Vec3; K] {
        let d = self.direction;
        let t = (q - self.origin).dot(d);
        self.differentials.map(|k| {
            let x = k.position + t * k.direction;
            x - x.dot(d) * d
        })
    }

    /// The differentials at the ray's point now.
    pub fn differentials(&self) -> &[Differential; K] {
        &self.differentials
    }
}
