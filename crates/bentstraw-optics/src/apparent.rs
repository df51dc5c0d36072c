//! Where the straw really appears: the apparent position of a straw point for one eye with a small
//! pupil (the eye model) and for two eyes (the stereo model), beside the course's convention of
//! the image point (`O + L·u0`: along the first direction, as far as the light travelled).
//!
//! # Re-aiming
//! Every model needs the rays from one straw point `Q` that reach other eye positions along the
//! same light path (the same sequence of water faces, refracted or totally reflected alike). A
//! [`LightPath`] records that sequence for the traced ray from the observer; [`World::reaim`] finds,
//! by Newton's method on the initial direction, the ray from another eye position that follows the
//! same sequence and whose last straight segment passes through `Q`, then checks with the tracer
//! that this ray really reaches `Q` (within [`REACH_TOLERANCE`]) without meeting anything else.
//!
//! # Eye model
//! Displacing the eye from `E` to `E + δ·e` (`e ⟂ u0`) and re-aiming at `Q` gives a direction `u'`.
//! The displaced line of sight `E + δe + s'·u'`, projected onto the plane spanned by `u0` and `e`,
//! crosses the central line of sight `E + s·u0` at `s(δ) = −δ (u'·u0)/(u'·e)`. The focus for the
//! pupil direction `e` is the limit `δ → 0`: its inverse, the vergence `−e·(∂u/∂x)·e`, is the
//! normal curvature of the wavefront along `e`.
//!
//! That limit comes in closed form from the one traced ray, by ray differentials (the generalised
//! Coddington equations in matrix form, see `pencil`): four neighbouring rays are carried along
//! it to first order, the ray from an eye moved along `e_h` or `e_v` and the ray turned along
//! `e_h` or `e_v`, through every straight segment and every refraction or total reflection (the
//! face's curvature included: none for planes, `1/R` across an upright cylinder's axis). At the
//! straw point they cross the plane perpendicular to the last segment at `A·δx + B·δu` (eye moved
//! by `δx`, line of sight turned by `δu`); the rays through `Q` have `δu = −B⁻¹A·δx`, so the
//! vergence matrix is `W = B⁻¹A` in the basis `(e_h, e_v)`, and `1/s_h = W_hh`, `1/s_v = W_vv`
//! (its diagonal: `W` is symmetric but not diagonal in general, the wavefront's principal
//! directions being tilted). No finite difference, no iteration: exact up to rounding (the
//! re-aiming method, kept as the tests' oracle, agrees within 1e-10 m).
//!
//! Whether the pencil is cut (by the straw's silhouette, the rim of a face, the critical angle,
//! another object): the rays from the pupil's edges `E ± 2δe` (δ = [`PUPIL_STEP`]), aimed by the
//! first-order prediction `δu = −W·δx`, are traced side by side in one single-precision packet;
//! each must follow the same sequence of events and meet an object within [`PENCIL_REACH`] of `Q`
//! (the prediction misses by `O(δ²)`, far less), else the focus along that `e` is unresolved.
//! - horizontal focus `s_h`: `e_h = (u0 × ẑ)/|u0 × ẑ|` (`x̂` when `u0` is vertical, as the camera's
//!   right), the horizontal perpendicular to `u0`;
//! - vertical focus `s_v`: `e_v = e_h × u0`, the perpendicular to `u0` in the vertical plane
//!   containing it.
//!
//! Why the crossing in projection rather than the closest approach of the two skew lines: it is the
//! classical (Coddington) definition of the sagittal and tangential foci, and its inverse is a
//! normal curvature of the wavefront, so that `1/s_h + 1/s_v` is the same for any two perpendicular
//! pupil directions (Euler's theorem); the closest approach of skew lines has no such meaning.
//!
//! The apparent point is placed at `E + ((s_h + s_v)/2)·u0`, the mean of the two foci (halfway
//! between the two line images); [`ApparentPoint::least_confusion_distance`] gives the other
//! classical choice, the circle of least confusion at `2/(1/s_h + 1/s_v)`. When a focus is not in
//! front of the eye (collimated or converging light) or the pencil is cut, the point is undefined:
//! `position` is `None`, never a made-up number.
//!
//! # Stereo model
//! Two eyes [`EYE_SEPARATION`] apart on a horizontal baseline centred on the observer,
//! perpendicular to the horizontal projection of the direction from the observer to
//! [`SCENE_CENTRE`] (the left eye on the left when facing the scene; `x̂` is the baseline when the
//! observer stands straight above or below the centre). Each straw point `Q` of the observer's image
//! is seen by each eye along the same light path: both eyes then see the same image of `Q` (a point
//! may have several images, one per light path; the brain fuses corresponding ones). Each eye's ray
//! is found by Newton's method from the first-order prediction `δu = −W·δx` of the eye model
//! (`δx` the eye's offset across `u0`), its Jacobian exact from two ray differentials carried with
//! each trace (quadratic convergence: three or four traces; the last step, once the miss is below
//! a nanometre, is taken untraced). Where Newton's method does not converge from the prediction,
//! the solution is followed from the observer to the eye in steps halved where it is lost (the
//! continuation, which the tests use in its older form as the oracle). A ray stopped by an object
//! before the path's last face is followed through it (the world's faces alone), so that Newton's
//! method still converges and the eye is known at once not to see `Q`, rather than the path taken
//! as lost and searched for. The right eye's first guess adds the left eye's second-order part to
//! its own prediction (the eyes straddle the observer): right to third order. A ray found through
//! `Q` that meets something else first means the eye does not see `Q`. The apparent position is the
//! midpoint of the closest approach of the two lines of sight. Points that one eye does not see
//! along that path are skipped and counted.
//!
//! [`SCENE_CENTRE`]: crate::scene::SCENE_CENTRE
//!
//! # Where the code is
//! One concept per file: `eye` (the eye model: foci, apparent points), `stereo` (the stereo model:
//! two eyes, triangulation), `reaim` (re-aiming at a straw point by Newton's method, and the
//! oracles the tests check both models with), `pencil` (ray differentials), `sweep` (one point's
//! apparent position as the eye moves round the glass or up and down). This module keeps what
//! they share: the light path, the pupil's axes, both models' images of the same points.
//!
//! # Example
//! ```
//! use bentstraw_optics::apparent::{eye_model_points, stereo_points, Focus};
//! use bentstraw_optics::sampling::sample_image;
//! use bentstraw_optics::scene::{REFERENCES, WATER_INDEX};
//! use bentstraw_optics::world::World;
//!
//! let r = REFERENCES[0];
//! let world = World::assignment(&r.scene(WATER_INDEX));
//! let cloud = sample_image(&world, r.observer, 200, &|_| {});
//! let eye = eye_model_points(&world, r.observer, &cloud.points);
//! assert_eq!(eye.len(), cloud.points.len());
//! for p in &eye {
//!     // Both foci in front of the eye: the apparent point is defined, between them.
//!     if let (Focus::InFront(h), Focus::InFront(v)) = (p.s_h, p.s_v) {
//!         let s = p.position.unwrap().distance(r.observer);
//!         assert!(s >= h.min(v) - 1e-12 && s <= h.max(v) + 1e-12);
//!     }
//! }
//! let stereo = stereo_points(&world, r.observer, &cloud.points);
//! assert_eq!(stereo.points.len() + stereo.skipped, cloud.points.len());
//! ```

mod eye;
mod pencil;
mod reaim;
mod stereo;
mod sweep;

pub use eye::{
    eye_model_points, eye_model_points_until, ApparentPoint, Focus, INFINITY_VERGENCE, PUPIL_STEP,
};
pub use reaim::REACH_TOLERANCE;
pub use stereo::{
    stereo_point_each, stereo_point_each_until, stereo_points, stereo_points_until, StereoEyes,
    StereoImage, StereoPoint, EYE_SEPARATION,
};
pub use sweep::{
    default_sweep_point, sweep_apparent, sweep_apparent_until, sweep_seats, Sight, Sweep,
    SweepKind, SweepRow, SweepSight, DEFAULT_SWEEP_ROWS, MAX_SWEEP_ROWS, MIN_SWEEP_ROWS,
    SWEEP_POINT_TOLERANCE,
};

use crate::geometry::Ray;
use crate::image::ImagePoint;
use crate::world::{Outcome, World};
use crate::Vec3;

// Here, not in `eye`: re-aiming's untraced last step asks the same question of its ray.
/// How close to the straw point the rays predicted (to first order) from the edges of the
/// pupil must land for the pencil to count as uncut (m): far above the prediction's error
/// (`O(δ²)`, well under a nanometre), far below what another face or object would give.
pub const PENCIL_REACH: f64 = 1e-6;

/// The light path of one ray from an eye to the straw: the straw point reached and the sequence of
/// water events (faces, refraction or total reflection) on the way.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightPath {
    /// The straw point reached.
    pub straw_point: Vec3,
    /// Number of water events.
    pub events: u32,
    /// Unit direction of the last straight segment, into the straw.
    pub final_direction: Vec3,
    /// Hash of the sequence of events (FNV-1a over one code per event).
    sequence: u64,
}

/// FNV-1a offset basis: the hash of an empty sequence of events.
const EMPTY_SEQUENCE: u64 = 0xcbf2_9ce4_8422_2325;

/// The hash of a sequence of events extended by one event: its face's code and its kind.
#[inline]
fn extend_sequence(hash: u64, face: u64, totally_reflected: bool) -> u64 {
    let code = 1 + 2 * face + u64::from(totally_reflected);
    (hash ^ code).wrapping_mul(0x0000_0100_0000_01b3)
}

/// One event of a ray as the models see it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathEvent {
    /// A code for the face it happened on (the same face, the same code).
    pub face: u64,
    /// Where.
    pub point: Vec3,
    /// The direction after it.
    pub outgoing: Vec3,
    /// Whether it was a total reflection.
    pub totally_reflected: bool,
}

/// The light path of a ray, as the models follow it.
impl World {
    /// Traces `ray` from an eye by the course's law, telling `on_event` every event as the
    /// models see it; the object point reached and the number of events on the way, if it
    /// reaches one.
    #[inline]
    pub fn follow_events(
        &self,
        ray: Ray,
        mut on_event: impl FnMut(PathEvent),
    ) -> Option<(Vec3, u32)> {
        let outcome = self.trace_with(ray, |e| {
            on_event(PathEvent {
                face: e.boundary as u64,
                point: e.point,
                outgoing: e.outgoing,
                totally_reflected: e.totally_reflected,
            })
        });
        match outcome {
            Outcome::Object { point, events, .. } => Some((point, events)),
            _ => None,
        }
    }

    /// The light path of the ray from `eye` along unit `u0`, if it reaches the straw.
    pub fn light_path(&self, eye: Vec3, u0: Vec3) -> Option<LightPath> {
        let mut sequence = EMPTY_SEQUENCE;
        let mut last = u0;
        let outcome = self.follow_events(
            Ray {
                origin: eye,
                direction: u0,
            },
            |e| {
                sequence = extend_sequence(sequence, e.face, e.totally_reflected);
                last = e.outgoing;
            },
        );
        outcome.map(|(point, events)| LightPath {
            straw_point: point,
            events,
            final_direction: last,
            sequence,
        })
    }
}

/// The horizontal and vertical pupil directions `(e_h, e_v)` for a line of sight `u0`.
pub fn pupil_axes(u0: Vec3) -> (Vec3, Vec3) {
    let c = u0.cross(Vec3::Z);
    let e_h = if c.length() < 1e-9 {
        Vec3::X
    } else {
        c.normalize()
    };
    (e_h, e_h.cross(u0).normalize())
}

/// A unit vector perpendicular to unit `d`.
fn any_perpendicular(d: Vec3) -> Vec3 {
    let helper = if d.x.abs() < 0.6 { Vec3::X } else { Vec3::Y };
    d.cross(helper).normalize()
}

/// Both models' images of the same course image points.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ApparentImages {
    /// The eye model's points, one per input point, in the input's order.
    pub eye: Vec<ApparentPoint>,
    /// The stereo model's points (those seen by both eyes), in the input's order.
    pub stereo: StereoImage,
}

/// The eye model's and the stereo model's points for `points` (image points seen from
/// `observer`, e.g. [`crate::sampling::sample_image`]'s), in parallel, deterministic.
pub fn apparent_images(world: &World, observer: Vec3, points: &[ImagePoint]) -> ApparentImages {
    ApparentImages {
        eye: eye_model_points(world, observer, points),
        stereo: stereo_points(world, observer, points),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::sample_image;
    use crate::scene::{Scene, REFERENCES, WATER_INDEX};
    use std::sync::atomic::AtomicBool;

    pub(super) const N: f64 = WATER_INDEX;

    /// The ray from `eye` along `u0` must reach the straw; its image point.
    pub(super) fn image(scene: &Scene, eye: Vec3, u0: Vec3) -> ImagePoint {
        World::assignment(scene)
            .image_point(eye, u0.normalize())
            .expect("the ray reaches the straw")
    }

    /// Without refraction (n = 1) every model puts every point on the straw's surface.
    #[test]
    fn without_refraction_every_model_gives_the_straw_surface() {
        for r in REFERENCES {
            let scene = r.scene(1.0);
            let cloud = sample_image(&World::assignment(&scene), r.observer, 300, &|_| {});
            assert!(cloud.points.len() >= 300);
            let eye = eye_model_points(&World::assignment(&scene), r.observer, &cloud.points);
            let undefined = eye.iter().filter(|ap| ap.position.is_none()).count();
            // Only pencils cut by an edge (silhouettes, rims) may lack a focus.
            assert!(undefined * 50 <= eye.len(), "{undefined} of {}", eye.len());
            for ap in eye {
                let q = ap.image.straw_point;
                assert!(ap.image.position.distance(q) < 1e-9, "course");
                let Some(p) = ap.position else {
                    assert!(ap.s_h == Focus::Unresolved || ap.s_v == Focus::Unresolved);
                    continue;
                };
                assert!(
                    p.distance(q) < 1e-9,
                    "eye model {}: {:?} vs {q:?}",
                    r.number,
                    ap
                );
                assert!(World::assignment(&scene).distance_to_objects(p) < 1e-9);
                assert!((ap.astigmatism().unwrap()).abs() < 1e-9);
            }
            let stereo = stereo_points(&World::assignment(&scene), r.observer, &cloud.points);
            assert!(
                stereo.points.len() > cloud.points.len() / 2,
                "{}",
                stereo.skipped
            );
            assert_eq!(stereo.points.len() + stereo.skipped, cloud.points.len());
            for st in &stereo.points {
                let p = st.position.expect("lines of sight converge");
                assert!(
                    p.distance(st.image.straw_point) < 1e-9,
                    "stereo {}: {st:?}",
                    r.number
                );
                assert!(st.miss_distance < 1e-9 && st.disparity.abs() < 1e-9);
            }
        }
    }

    /// Same inputs, same outputs in the same order.
    #[test]
    fn batch_results_are_deterministic_and_in_input_order() {
        let r = REFERENCES[2];
        let (scene, eye) = (r.scene(N), r.observer);
        let cloud = sample_image(&World::assignment(&scene), eye, 500, &|_| {});
        let a = eye_model_points(&World::assignment(&scene), eye, &cloud.points);
        let b = eye_model_points(&World::assignment(&scene), eye, &cloud.points);
        assert_eq!(a, b);
        for (ap, im) in a.iter().zip(&cloud.points) {
            assert_eq!(ap.image, *im);
        }
        let both = apparent_images(&World::assignment(&scene), eye, &cloud.points);
        assert_eq!(both.eye, a);
        assert_eq!(
            both.stereo,
            stereo_points(&World::assignment(&scene), eye, &cloud.points)
        );
        let mut order = both
            .stereo
            .points
            .iter()
            .map(|st| cloud.points.iter().position(|im| *im == st.image).unwrap());
        let mut last = order.next().unwrap();
        for k in order {
            assert!(k > last);
            last = k;
        }
    }

    /// The stoppable models give the point-by-point answers when not stopped, and nothing once
    /// the flag is set.
    #[test]
    fn stopped_models_give_nothing_and_unstopped_ones_every_point() {
        let r = REFERENCES[1];
        let world = World::assignment(&r.scene(N));
        let eye = r.observer;
        let cloud = sample_image(&world, eye, 300, &|_| {});
        let go = AtomicBool::new(false);
        let eye_points = eye_model_points_until(&world, eye, &cloud.points, &go).unwrap();
        let one_by_one: Vec<ApparentPoint> = cloud
            .points
            .iter()
            .map(|p| world.apparent_point(eye, p))
            .collect();
        assert_eq!(eye_points, one_by_one);
        let eyes = StereoEyes::around(eye);
        let stereo = stereo_point_each_until(&world, eye, &cloud.points, &go).unwrap();
        let stereo_one_by_one: Vec<Option<StereoPoint>> = cloud
            .points
            .iter()
            .map(|p| world.stereo_point(&eyes, eye, p))
            .collect();
        assert_eq!(stereo, stereo_one_by_one);
        assert_eq!(
            stereo_points_until(&world, eye, &cloud.points, &go),
            Some(stereo_points(&world, eye, &cloud.points))
        );
        let stop = AtomicBool::new(true);
        assert!(eye_model_points_until(&world, eye, &cloud.points, &stop).is_none());
        assert!(stereo_points_until(&world, eye, &cloud.points, &stop).is_none());
    }

    /// Worlds to compare the models in: the four references, a denser liquid (more total
    /// reflections), and gallery scenes with thick cylindrical walls (inside and outside), a
    /// tank's flat walls, two liquid layers, a leaning straw.
    pub(super) fn comparison_worlds() -> Vec<(String, World, Vec3)> {
        let mut out: Vec<(String, World, Vec3)> = REFERENCES
            .iter()
            .map(|r| {
                (
                    format!("reference {}", r.number),
                    World::assignment(&r.scene(N)),
                    r.observer,
                )
            })
            .collect();
        let r = REFERENCES[2];
        out.push((
            "reference 3, n = 1.9".into(),
            World::assignment(&r.scene(1.9)),
            r.observer,
        ));
        for (name, text) in [
            (
                "real-glass",
                include_str!("../../../scenes/real-glass.toml"),
            ),
            (
                "tank-pencil",
                include_str!("../../../scenes/tank-pencil.toml"),
            ),
            (
                "oil-on-water",
                include_str!("../../../scenes/oil-on-water.toml"),
            ),
            (
                "leaning-straw",
                include_str!("../../../scenes/leaning-straw.toml"),
            ),
        ] {
            let d = crate::scene_file::SceneDescription::from_toml(text).unwrap();
            let observer = d.observer.unwrap().position;
            out.push((name.into(), World::new(&d, 10).unwrap(), observer));
        }
        out
    }
}
