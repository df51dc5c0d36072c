//! Re-aiming: the ray from another eye position that reaches the same straw point along the same
//! light path, by Newton's method on its initial direction (the physics in [`super`],
//! "Re-aiming"): the stereo model's search, and the oracles the tests check both models with.

use std::cell::OnceCell;

use super::pencil::{Differential, Pencil};
use super::{any_perpendicular, extend_sequence, LightPath, EMPTY_SEQUENCE, PENCIL_REACH};
use crate::geometry::Ray;
use crate::world::{Outcome, World};
use crate::Vec3;

/// How close to the straw point a re-aimed ray must land to count as reaching it (m).
pub const REACH_TOLERANCE: f64 = 1e-10;
/// Steps of the eye position when following a point from the observer to one stereo eye.
#[cfg(test)]
const CONTINUATION_STEPS: u32 = 8;
/// Newton stops once the last segment passes this close to the straw point (m).
const NEWTON_TOLERANCE: f64 = 1e-15;
/// Newton's method has found the ray when its last segment passes this close to the point (m).
const CONVERGED: f64 = 1e-12;
/// Miss (m) at which Newton's method stops on the continuation's intermediate eyes: they only
/// keep the solution on its branch (10 nm gives the same stereo points, to 1e-14 m, as 1e-13 m on
/// the reference views, in a third less time; 1 µm starts to lose points).
const ON_THE_WAY: f64 = 1e-8;
/// Most Newton iterations per re-aiming.
const NEWTON_ITERATIONS: usize = 40;
/// Most iterations of Newton's method with the exact Jacobian: from a first-order prediction it
/// converges in a handful; more only wanders where there is no solution along the path.
const EXACT_NEWTON_ITERATIONS: usize = 8;
/// Miss (m) below which Newton's method with the exact Jacobian takes its last step untraced: the
/// next miss would be ~1e-18 m at centimetre scales.
const LAST_STEP_MISS: f64 = 1e-9;
/// Miss (m) that the next step of Newton's method with the exact Jacobian must be expected to
/// leave, from the last step's quadratic convergence, to be taken untraced: the miss it iterates
/// down to ([`NEWTON_TOLERANCE`]), so that the untraced step gives the same ray as a traced one.
const UNTRACED_MISS: f64 = NEWTON_TOLERANCE;
/// Most halvings of a step of Newton's method with the exact Jacobian at the end eye.
const EXACT_NEWTON_HALVINGS: usize = 4;
/// Most halvings of a step of Newton's method on the continuation's intermediate eyes: a step
/// that must be cut further is outside the method's reach from the prediction, where a shorter
/// move of the eye gives a better prediction than a shorter step.
const ON_THE_WAY_HALVINGS: usize = 2;
/// Most failed attempts in a row when following a stereo point from the observer to one eye (each
/// halves the eye's move). Three in a row mostly mean that the path's faces end just ahead (the
/// ray would leave a ball's rim, or start to reflect totally): halving further only creeps toward
/// that edge until [`MOST_TRACES`]. On the marble in water that creeping was a third of the stereo
/// model's traces, for no point; the bound skips no point on the reference views, and at most 4
/// in 1000 of the points that two eyes see in the gallery (the near and far arrow), where a fourth
/// bound costs the cocktail glass a fifth more time.
const MOST_MISSES: usize = 3;
/// Smallest step (fraction of the way from the observer to a stereo eye) at which the stereo
/// model still follows a solution that Newton's method lost; below it the point is skipped.
const SMALLEST_STEP: f64 = 1.0 / 256.0;
/// Most traces when following a stereo point from the observer to one eye: a solution that needs
/// more is skipped rather than searched for in ever smaller steps. On the reference views every
/// eye that sees its point takes at most 23 (2 to 4 for 99 in 100); one that does not, where the
/// path changes its faces on the way, took up to 110 before this bound (which also loses fewer of
/// the continuation oracle's points than a bound of eight Newton attempts did: 14 against 28 of
/// 48 000).
const MOST_TRACES: usize = 24;
/// Step of the forward differences of the Newton Jacobian (gnomonic units, ≈ radians).
const JACOBIAN_STEP: f64 = 1e-7;

/// A 2×2 Jacobian, row-major: `j[row][column]`.
type Jacobian = [[f64; 2]; 2];

/// The size of a miss `r` (m). Not `hypot`: the misses are far from overflow, and `hypot` was a
/// tenth of the time.
#[inline]
fn norm(r: [f64; 2]) -> f64 {
    (r[0] * r[0] + r[1] * r[1]).sqrt()
}

/// Newton's step `−J⁻¹·r` for the miss `r` with Jacobian `j`, if it is finite.
#[inline]
fn newton_step(j: &Jacobian, r: [f64; 2]) -> Option<[f64; 2]> {
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    let step = [
        -(j[1][1] * r[0] - j[0][1] * r[1]) / det,
        -(j[0][0] * r[1] - j[1][0] * r[0]) / det,
    ];
    (step[0].is_finite() && step[1].is_finite()).then_some(step)
}

/// A world's faces without its objects: made once for a batch, or when first needed.
// Kept unboxed: it lives beside one aim on the stack, and boxing would allocate per aim.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug)]
enum FacesOnly<'a> {
    Made(&'a World),
    Later(OnceCell<World>),
}

/// What one differentiated trace along a light path gives.
enum Traced {
    /// It follows the path: the miss of the straw point, its Jacobian, and how far from the
    /// straw point it meets an object after the path's events (infinite if none).
    Path([f64; 2], Jacobian, f64),
    /// An object stops it before the path's last event.
    Hidden,
    /// It leaves the path: another face, another kind of event, or out of the scene.
    Lost,
}

/// Re-aiming rays from any eye position at one straw point along one light path.
///
/// Directions are `forward + a·right + b·up` (normalised); the residual is the part of `Q − P`
/// perpendicular to the last segment (from `P`, direction `d`), on two fixed axes across the
/// central last segment.
#[derive(Clone, Debug)]
pub(super) struct Aim<'a> {
    world: &'a World,
    /// The world's faces without its objects ([`World::faces_only`]), made when first needed.
    faces: FacesOnly<'a>,
    pub(super) path: LightPath,
    forward: Vec3,
    right: Vec3,
    up: Vec3,
    across: [Vec3; 2],
}

impl<'a> Aim<'a> {
    pub(super) fn new(
        world: &'a World,
        path: LightPath,
        forward: Vec3,
        right: Vec3,
        up: Vec3,
    ) -> Self {
        let a = any_perpendicular(path.final_direction);
        let b = path.final_direction.cross(a);
        Aim {
            world,
            faces: FacesOnly::Later(OnceCell::new()),
            path,
            forward,
            right,
            up,
            across: [a, b],
        }
    }

    /// The same aim with the world's faces alone already made (`faces`, from
    /// [`World::faces_only`]): shared by every point of a batch.
    pub(super) fn with_faces(mut self, faces: &'a World) -> Self {
        self.faces = FacesOnly::Made(faces);
        self
    }

    /// The world's faces without its objects.
    fn faces(&self) -> &World {
        match &self.faces {
            FacesOnly::Made(faces) => faces,
            FacesOnly::Later(cell) => cell.get_or_init(|| self.world.faces_only()),
        }
    }

    /// The unit direction with parameters `x`.
    #[inline]
    pub(super) fn direction(&self, x: [f64; 2]) -> Vec3 {
        (self.forward + x[0] * self.right + x[1] * self.up).normalize()
    }

    /// Follows the ray from `eye` through the path's events: the last segment `(P, d)` before the
    /// straw point and the tracer's outcome; `None` if the events differ from the path's.
    #[allow(clippy::type_complexity)]
    fn follow(&self, eye: Vec3, direction: Vec3) -> Option<(Vec3, Vec3, Option<(Vec3, u32)>)> {
        let wanted = self.path.events;
        let mut count = 0u32;
        let mut sequence = EMPTY_SEQUENCE;
        let (mut origin, mut last) = (eye, direction);
        let outcome = self.world.follow_events(
            Ray {
                origin: eye,
                direction,
            },
            |e| {
                if count < wanted {
                    sequence = extend_sequence(sequence, e.face, e.totally_reflected);
                    origin = e.point;
                    last = e.outgoing;
                }
                count += 1;
            },
        );
        (count >= wanted && sequence == self.path.sequence).then_some((origin, last, outcome))
    }

    /// The miss of the straw point by the ray from `eye` with parameters `x` (m, two components).
    fn residual(&self, eye: Vec3, x: [f64; 2]) -> Option<[f64; 2]> {
        let (origin, d, _) = self.follow(eye, self.direction(x))?;
        let v = self.path.straw_point - origin;
        let along = v.dot(d);
        if along <= 0.0 {
            return None; // the straw point would be behind the last segment
        }
        let miss = v - along * d;
        Some([miss.dot(self.across[0]), miss.dot(self.across[1])])
    }

    fn jacobian(&self, eye: Vec3, x: [f64; 2], r: [f64; 2]) -> Option<Jacobian> {
        let h = JACOBIAN_STEP;
        let ra = self.residual(eye, [x[0] + h, x[1]])?;
        let rb = self.residual(eye, [x[0], x[1] + h])?;
        Some([
            [(ra[0] - r[0]) / h, (rb[0] - r[0]) / h],
            [(ra[1] - r[1]) / h, (rb[1] - r[1]) / h],
        ])
    }

    /// Whether the ray from `eye` with parameters `x` reaches the straw point along the path.
    fn reaches(&self, eye: Vec3, x: [f64; 2]) -> bool {
        self.reaches_within(eye, x, REACH_TOLERANCE)
    }

    /// Whether the ray from `eye` with parameters `x` follows the path's events and then meets an
    /// object within `tolerance` (m) of the straw point.
    fn reaches_within(&self, eye: Vec3, x: [f64; 2], tolerance: f64) -> bool {
        match self.follow(eye, self.direction(x)) {
            Some((_, _, Some((point, n)))) => {
                n == self.path.events && point.distance(self.path.straw_point) <= tolerance
            }
            _ => false,
        }
    }

    /// The miss of the straw point by the ray from `eye` with parameters `x` (as
    /// [`Aim::residual`]), its exact Jacobian from the ray's differentials, and how far from the
    /// straw point the ray meets an object after the path's events (infinite if it meets one
    /// before them, or none); one trace, two when an object is in the way: the path is then
    /// followed through it, so that Newton's method finds the ray along the path even where it
    /// is hidden (and the eye is known not to see the point, rather than the path lost).
    ///
    /// An eye on the way (`seeing` false) need not see the point: its ray follows the world's
    /// faces alone up to the path's last event (one trace, and a shorter one), and is taken to
    /// reach the point (a gap of zero).
    ///
    /// `traces` counts the traces; `None` once it has reached [`MOST_TRACES`].
    fn residual_with_jacobian(
        &self,
        eye: Vec3,
        x: [f64; 2],
        seeing: bool,
        traces: &mut usize,
    ) -> Option<([f64; 2], Jacobian, f64)> {
        let mut within_budget = || {
            *traces += 1;
            *traces <= MOST_TRACES
        };
        if !within_budget() {
            return None;
        }
        if !seeing {
            return match self.differentiate(self.faces(), eye, x, self.path.events) {
                Traced::Path(r, j, _) => Some((r, j, 0.0)),
                _ => None,
            };
        }
        match self.differentiate(self.world, eye, x, self.world.max_events()) {
            Traced::Path(r, j, gap) => Some((r, j, gap)),
            Traced::Hidden if within_budget() => {
                // Only the path's events are wanted: the faces beyond them do not matter.
                match self.differentiate(self.faces(), eye, x, self.path.events) {
                    Traced::Path(r, j, _) => Some((r, j, f64::INFINITY)),
                    _ => None,
                }
            }
            Traced::Hidden | Traced::Lost => None,
        }
    }

    /// Traces the ray from `eye` with parameters `x` in `world` (the scene or its faces alone),
    /// at most `max_events` events, with the differentials of its direction's two parameters.
    fn differentiate(&self, world: &World, eye: Vec3, x: [f64; 2], max_events: u32) -> Traced {
        let w = self.forward + x[0] * self.right + x[1] * self.up;
        let inverse = 1.0 / w.length();
        let u = w * inverse;
        // The turn of the unit direction per unit of each parameter.
        let turn = |e: Vec3| Differential::turned((e - e.dot(u) * u) * inverse);
        let mut pencil = Pencil::new(eye, u, [turn(self.right), turn(self.up)]);
        let wanted = self.path.events;
        let (mut count, mut sequence) = (0u32, EMPTY_SEQUENCE);
        let outcome = world.trace_limited(
            Ray {
                origin: eye,
                direction: u,
            },
            max_events,
            |e| {
                if count < wanted {
                    sequence = extend_sequence(sequence, e.boundary as u64, e.totally_reflected);
                    pencil.cross(world, e);
                }
                count += 1;
            },
        );
        if count < wanted {
            return match outcome {
                // Stopped by an object before the path's last face: in the way.
                Outcome::Object { .. } => Traced::Hidden,
                _ => Traced::Lost,
            };
        }
        if sequence != self.path.sequence {
            return Traced::Lost;
        }
        let q = self.path.straw_point;
        let d = pencil.direction();
        let v = q - pencil.origin();
        let along = v.dot(d);
        if along <= 0.0 {
            return Traced::Lost; // the straw point would be behind the last segment
        }
        let miss = v - along * d;
        let r = [miss.dot(self.across[0]), miss.dot(self.across[1])];
        // miss = v − (v·d)d with v = Q − P: δmiss = −(δP + t·δd)⊥ − (v·δd)·d.
        let across = pencil.across_at(q);
        let turned = pencil.differentials();
        let column = |k: usize| -across[k] - v.dot(turned[k].direction) * d;
        let (c0, c1) = (column(0), column(1));
        let j = [
            [c0.dot(self.across[0]), c1.dot(self.across[0])],
            [c0.dot(self.across[1]), c1.dot(self.across[1])],
        ];
        // How far from the straw point the ray meets an object after the path's events.
        let gap = match outcome {
            Outcome::Object { point, events, .. } if events == wanted => point.distance(q),
            _ => f64::INFINITY,
        };
        Traced::Path(r, j, gap)
    }

    /// The parameters of the ray from `to` that reaches the straw point along the path, from the
    /// solution at `from` (`x = 0`) and its first-order change `slope` per unit of the way from
    /// `from` to `to`: Newton's method from `first` (a prediction of the solution at `to`)
    /// straight away, else following the solution as the eye moves in steps halved where
    /// Newton's method loses it (the path must keep its events on the way, hidden or not; only
    /// the end eye must see the point), in at most [`MOST_TRACES`] traces.
    pub(super) fn predict_and_follow(
        &self,
        from: Vec3,
        to: Vec3,
        slope: [f64; 2],
        first: [f64; 2],
    ) -> Option<[f64; 2]> {
        let (mut t, mut h) = (0.0_f64, 1.0_f64);
        let (mut x, mut slope) = ([0.0; 2], slope);
        let (mut traces, mut misses) = (0, 0);
        while traces < MOST_TRACES {
            let next = (t + h).min(1.0);
            let dt = next - t;
            let guess = if t == 0.0 && next >= 1.0 {
                first
            } else {
                [x[0] + slope[0] * dt, x[1] + slope[1] * dt]
            };
            let end = next >= 1.0;
            let tolerance = if end { NEWTON_TOLERANCE } else { ON_THE_WAY };
            match self.newton(
                from + (to - from) * next,
                guess,
                tolerance,
                end,
                &mut traces,
            ) {
                // Found, but something else is met first: the end eye does not see the point
                // (smaller steps would find the same ray).
                Some((_, false)) if end => return None,
                Some((xn, _)) if end => return Some(xn),
                Some((xn, _)) => {
                    misses = 0;
                    slope = [(xn[0] - x[0]) / dt, (xn[1] - x[1]) / dt];
                    x = xn;
                    t = next;
                    h *= 2.0;
                }
                None => loop {
                    misses += 1;
                    if misses >= MOST_MISSES {
                        return None; // the path's faces end on the way
                    }
                    h *= 0.5;
                    if h < SMALLEST_STEP {
                        return None; // the path changes its events on the way, or is hidden
                    }
                    // A step doubled past the end and then halved may end there again: the same
                    // Newton's method from the same guess would fail again.
                    if (t + h).min(1.0) != next {
                        break;
                    }
                },
            }
        }
        None
    }

    /// Newton's method from `x0` with the exact Jacobian (quadratic convergence): the ray from
    /// `eye` along the path whose last segment passes within `tolerance` of the straw point
    /// (succeeding within [`CONVERGED`]), and whether it reaches the point (checked by the same
    /// traces: nothing else is met first) if the eye must see it (`seeing`; else it is taken to).
    fn newton(
        &self,
        eye: Vec3,
        x0: [f64; 2],
        tolerance: f64,
        seeing: bool,
        traces: &mut usize,
    ) -> Option<([f64; 2], bool)> {
        let mut x = x0;
        let (mut r, mut j, mut gap) = self.residual_with_jacobian(eye, x, seeing, traces)?;
        let halvings = if seeing {
            EXACT_NEWTON_HALVINGS
        } else {
            ON_THE_WAY_HALVINGS
        };
        // The miss before the last full step (infinite if there was none).
        let mut before = f64::INFINITY;
        for _ in 0..EXACT_NEWTON_ITERATIONS {
            let size = norm(r);
            if size <= tolerance {
                break;
            }
            let Some(step) = newton_step(&j, r) else {
                break;
            };
            // Quadratic convergence: the next miss is about c·size², with c = size/before² as
            // the last full step showed.
            let next = size * (size / before) * (size / before);
            let converging =
                size <= LAST_STEP_MISS || (before.is_finite() && next <= UNTRACED_MISS);
            if converging && gap <= PENCIL_REACH {
                // This step leaves a miss below rounding and the ray already meets the point
                // (within PENCIL_REACH: the same object, nothing in the way), so the step is taken
                // without another trace. A ray that meets nothing there grazes the straw: the
                // step is traced, to see whether the converged ray meets it.
                return Some(([x[0] + step[0], x[1] + step[1]], true));
            }
            // Damped: halve the step until the miss shrinks and the path is kept.
            let mut lambda = 1.0;
            let mut accepted = false;
            for _ in 0..halvings {
                let xn = [x[0] + lambda * step[0], x[1] + lambda * step[1]];
                if let Some((rn, jn, gap_n)) = self.residual_with_jacobian(eye, xn, seeing, traces)
                {
                    if norm(rn) < size {
                        (x, r, j, gap) = (xn, rn, jn, gap_n);
                        accepted = true;
                        break;
                    }
                }
                lambda *= 0.5;
            }
            if !accepted {
                break; // at rounding, or lost
            }
            before = if lambda == 1.0 { size } else { f64::INFINITY };
        }
        (norm(r) <= CONVERGED.max(tolerance)).then_some((x, gap <= REACH_TOLERANCE))
    }

    /// [`Aim::converge`], then a check with the tracer that the ray really reaches the straw point.
    pub(super) fn solve(
        &self,
        eye: Vec3,
        x0: [f64; 2],
        jacobian: &mut Option<Jacobian>,
    ) -> Option<[f64; 2]> {
        let x = self.converge(eye, x0, jacobian, NEWTON_TOLERANCE)?;
        self.reaches(eye, x).then_some(x)
    }

    /// Newton's method from `x0` for the ray from `eye` along the path whose last segment passes
    /// through the straw point (iterating down to a miss of `tolerance`, succeeding within
    /// [`CONVERGED`]); `jacobian` is reused if given (a chord step) and holds the last one computed
    /// on return. Does not check that nothing is in the way.
    fn converge(
        &self,
        eye: Vec3,
        x0: [f64; 2],
        jacobian: &mut Option<Jacobian>,
        tolerance: f64,
    ) -> Option<[f64; 2]> {
        let mut x = x0;
        let mut r = self.residual(eye, x)?;
        let (mut j, mut fresh) = match *jacobian {
            Some(j) => (j, false),
            None => (self.jacobian(eye, x, r)?, true),
        };
        for _ in 0..NEWTON_ITERATIONS {
            let size = norm(r);
            if size <= tolerance {
                break;
            }
            let mut accepted = None;
            if let Some(step) = newton_step(&j, r) {
                // Damped: halve the step until the miss shrinks and the path is kept.
                let mut lambda = 1.0;
                for _ in 0..16 {
                    let xn = [x[0] + lambda * step[0], x[1] + lambda * step[1]];
                    if let Some(rn) = self.residual(eye, xn) {
                        if norm(rn) < size {
                            accepted = Some((xn, rn));
                            break;
                        }
                    }
                    lambda *= 0.5;
                }
            }
            match accepted {
                Some((xn, rn)) => {
                    x = xn;
                    r = rn;
                    // Slow progress: the Jacobian is stale, refresh it.
                    fresh = norm(rn) > 0.1 * size;
                    if fresh {
                        j = self.jacobian(eye, x, r)?;
                    }
                }
                None if fresh => break, // no progress even with a fresh Jacobian: at rounding
                None => {
                    j = self.jacobian(eye, x, r)?;
                    fresh = true;
                }
            }
        }
        *jacobian = Some(j);
        (norm(r) <= CONVERGED.max(tolerance)).then_some(x)
    }

    /// Vergence (1/m) of the light from the straw point at the eye `eye` for pupil direction `e`
    /// (`self.right` or `self.up`), by re-aiming from `eye ± δe` and `eye ± 2δe` (see [`super`]).
    #[cfg(test)]
    pub(super) fn vergence(
        &self,
        eye: Vec3,
        e: Vec3,
        step: f64,
        jacobian: &mut Option<Jacobian>,
    ) -> Option<f64> {
        let mut inverse = [0.0; 4];
        let mut first = [0.0; 2];
        for (k, factor) in [1.0, -1.0, 2.0, -2.0].into_iter().enumerate() {
            let delta = factor * step;
            // The solution is nearly linear in δ: predict it from the first one.
            let guess = [factor * first[0], factor * first[1]];
            let x = self.solve(eye + delta * e, guess, jacobian)?;
            if k == 0 {
                first = x;
            }
            let u = self.direction(x);
            inverse[k] = -u.dot(e) / (delta * u.dot(self.forward));
        }
        let v1 = 0.5 * (inverse[0] + inverse[1]);
        let v2 = 0.5 * (inverse[2] + inverse[3]);
        Some((4.0 * v1 - v2) / 3.0)
    }

    /// The direction from `to` that reaches the straw point along the path, following the
    /// solution from `from` (where `x = 0` solves) as the eye moves along the segment, in steps of
    /// at most `1/CONTINUATION_STEPS` of it, halved where Newton's method loses the solution.
    /// Only the end eye must see the point: on the way, the path just has to keep its events.
    #[cfg(test)]
    pub(super) fn continue_to(&self, from: Vec3, to: Vec3) -> Option<Vec3> {
        self.continue_with(from, to, CONTINUATION_STEPS, ON_THE_WAY)
    }

    /// [`Aim::continue_to`] in at least `steps` steps, Newton's method stopping at a miss of
    /// `on_the_way` on the intermediate eyes.
    #[cfg(test)]
    fn continue_with(&self, from: Vec3, to: Vec3, steps: u32, on_the_way: f64) -> Option<Vec3> {
        let mut jacobian = None;
        let longest = 1.0 / steps as f64;
        let (mut t, mut h) = (0.0, longest);
        let (mut x, mut slope) = ([0.0; 2], [0.0; 2]);
        while t < 1.0 {
            let next = (t + h).min(1.0);
            let dt = next - t;
            let eye = from + (to - from) * next;
            // Linear prediction along the last slope.
            let guess = [x[0] + slope[0] * dt, x[1] + slope[1] * dt];
            // On the way only the prediction needs the solution; the end eye gets it in full.
            let tolerance = if next < 1.0 {
                on_the_way
            } else {
                NEWTON_TOLERANCE
            };
            match self.converge(eye, guess, &mut jacobian, tolerance) {
                Some(xn) => {
                    slope = [(xn[0] - x[0]) / dt, (xn[1] - x[1]) / dt];
                    x = xn;
                    t = next;
                    h = (2.0 * h).min(longest);
                }
                None => {
                    h *= 0.5;
                    jacobian = None;
                    if h < longest / 256.0 {
                        return None; // the path changes its events on the way
                    }
                }
            }
        }
        self.reaches(to, x).then(|| self.direction(x))
    }
}

/// Re-aiming, for any world.
impl World {
    /// The unit direction from `eye` whose ray reaches `path`'s straw point along the same
    /// sequence of events (within [`REACH_TOLERANCE`], checked by tracing), searched from `guess`;
    /// `None` if there is none near (the point is hidden, or seen along another path).
    pub fn reaim(&self, eye: Vec3, path: &LightPath, guess: Vec3) -> Option<Vec3> {
        let forward = guess.normalize();
        let right = any_perpendicular(forward);
        let aim = Aim::new(self, *path, forward, right, forward.cross(right));
        let x = aim.solve(eye, [0.0; 2], &mut None)?;
        Some(aim.direction(x))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::apparent::{pupil_axes, StereoEyes};
    use crate::sampling::sample_image;
    use crate::scene::{Scene, REFERENCES, SCENE_CENTRE, STRAW_RADIUS, WATER_INDEX};
    use proptest::prelude::*;
    use proptest::test_runner::{Config, TestRunner};

    /// The stereo continuation's loose tolerance on the intermediate eyes follows the same
    /// solution as one held to 1e-13 m all the way (the same points seen, the same directions);
    /// a continuation eight times finer finds the same directions, and loses none of its points
    /// (it keeps a few, at most 2 %, that the coarse one loses: seen from above, where many paths
    /// are totally reflected).
    #[test]
    fn stereo_continuation_follows_the_solution_of_a_fine_one() {
        for r in REFERENCES {
            let scene = r.scene(WATER_INDEX);
            let eyes = StereoEyes::around(r.observer);
            let cloud = sample_image(&World::assignment(&scene), r.observer, 1500, &|_| {});
            let (mut followed, mut lost) = (0, 0);
            for image in &cloud.points {
                let path = World::assignment(&scene)
                    .light_path(r.observer, image.direction)
                    .unwrap();
                let (e_h, e_v) = pupil_axes(image.direction);
                let world = World::assignment(&scene);
                let aim = Aim::new(&world, path, image.direction, e_h, e_v);
                for eye in [eyes.left, eyes.right] {
                    let coarse = aim.continue_to(r.observer, eye);
                    let tight = aim.continue_with(r.observer, eye, CONTINUATION_STEPS, 1e-13);
                    match (coarse, tight) {
                        (Some(a), Some(b)) => {
                            followed += 1;
                            assert!((a - b).length() < 1e-12, "reference {}", r.number);
                        }
                        (None, None) => {}
                        _ => panic!("reference {}: {coarse:?} vs {tight:?}", r.number),
                    }
                    let finer = aim.continue_with(r.observer, eye, 8 * CONTINUATION_STEPS, 1e-13);
                    match (coarse, finer) {
                        (Some(a), Some(b)) => assert!((a - b).length() < 1e-12),
                        (None, Some(_)) => lost += 1,
                        (None, None) => {}
                        (Some(_), None) => panic!("reference {}: only the coarse one", r.number),
                    }
                }
            }
            assert!(
                followed > 1000,
                "reference {}: {followed} followed",
                r.number
            );
            assert!(
                lost * 50 <= 2 * cloud.points.len(),
                "reference {}: {lost} of {} lost that a finer continuation keeps",
                r.number,
                2 * cloud.points.len()
            );
        }
    }

    /// For random rays that reach the straw, the ray re-aimed from a displaced eye reaches the
    /// same straw point (checked by an independent trace), and re-aiming almost always succeeds.
    #[test]
    fn reaimed_rays_reach_the_same_straw_point() {
        let mut runner = TestRunner::new(Config {
            cases: 400,
            ..Config::default()
        });
        let hits = std::cell::Cell::new(0usize);
        let reached = std::cell::Cell::new(0usize);
        let strategy = (
            (0.0..0.035f64, 0.0..std::f64::consts::TAU, 0.02..0.2f64),
            (0.08..0.5f64, 0.0..std::f64::consts::TAU, -1.2..1.2f64),
            (0.0..0.25f64, 0.0..std::f64::consts::TAU),
            (1e-6..1e-4f64, 0.0..std::f64::consts::TAU),
        );
        runner
            .run(
                &strategy,
                |((rp, ap, he), (dist, az, el), (zt, at), (delta, turn))| {
                    let scene = Scene::with_defaults(rp * ap.cos(), rp * ap.sin(), he).unwrap();
                    let eye = SCENE_CENTRE
                        + dist * Vec3::new(el.cos() * az.cos(), el.cos() * az.sin(), el.sin());
                    if scene.validate_observer(eye).is_err() {
                        return Ok(());
                    }
                    let target = Vec3::new(
                        scene.straw_x() + STRAW_RADIUS * at.cos(),
                        scene.straw_y() + STRAW_RADIUS * at.sin(),
                        zt,
                    );
                    let u0 = (target - eye).normalize();
                    let Some(path) = World::assignment(&scene).light_path(eye, u0) else {
                        return Ok(());
                    };
                    hits.set(hits.get() + 1);
                    let (e_h, e_v) = pupil_axes(u0);
                    let moved = eye + delta * (turn.cos() * e_h + turn.sin() * e_v);
                    if let Some(u) = World::assignment(&scene).reaim(moved, &path, u0) {
                        let out = World::assignment(&scene).trace(Ray {
                            origin: moved,
                            direction: u,
                        });
                        let Outcome::Object { point, .. } = out else {
                            return Err(TestCaseError::fail(format!("{out:?}")));
                        };
                        prop_assert!(point.distance(path.straw_point) <= 1e-10);
                        reached.set(reached.get() + 1);
                    }
                    Ok(())
                },
            )
            .unwrap();
        assert!(hits.get() >= 40, "{}", hits.get());
        assert!(
            reached.get() as f64 >= 0.9 * hits.get() as f64,
            "{}/{}",
            reached.get(),
            hits.get()
        );
    }
}
