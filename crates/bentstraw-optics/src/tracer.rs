//! The assignment's scene made ready for tracing: its [`World`] (built once), traced by the one
//! rule every scene uses, and told in the assignment's words (the water's side, top and bottom,
//! the straw's side and caps).

use crate::geometry::Ray;
use crate::image::ImagePoint;
use crate::scene::{Scene, SECTION_COUNT};
use crate::trace::{
    Event, Face, FresnelStep, Intersection, NearestFace, Outcome, FRESNEL_SEGMENTS_PER_RAY,
};
use crate::world::{Hit, Part, Shape, World, WorldEvent, WorldFresnelStep, WorldOutcome};
use crate::Vec3;

/// The assignment's scene made ready for tracing many rays.
#[derive(Clone, Debug, PartialEq)]
pub struct Tracer {
    /// The scene traced.
    pub scene: Scene,
    /// The scene as a world: its boundaries (the water's faces) and its object (the straw).
    world: World,
}

impl NearestFace for Tracer {
    #[inline]
    fn prepared(&self) -> std::borrow::Cow<'_, Tracer> {
        std::borrow::Cow::Borrowed(self)
    }
}

/// The straw's face of part `part`.
fn straw_face(part: Part) -> Face {
    match part {
        Part::Side => Face::StrawSide,
        Part::Bottom => Face::StrawBottom,
        Part::Top => Face::StrawTop,
    }
}

impl Tracer {
    /// Prepares `scene` for tracing.
    pub fn new(scene: &Scene) -> Tracer {
        Tracer {
            scene: *scene,
            world: World::assignment(scene),
        }
    }

    /// The scene as a world.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// The water's face that boundary `index` of the world is.
    #[inline]
    pub fn face_of(&self, index: usize) -> Face {
        match self.world.boundaries()[index].shape {
            Shape::Upright { .. } => Face::WaterSide,
            Shape::Horizontal { z: 0.0, .. } => Face::WaterBottom,
            _ => Face::WaterTop,
        }
    }

    /// The world's code of the face a ray has just left (−1 for none).
    #[inline]
    fn left_code(&self, left: Option<Face>) -> Option<u32> {
        let face = left?;
        if face.is_straw() {
            return Some(self.world.object_code(0));
        }
        (0..self.world.boundaries().len())
            .find(|&k| self.face_of(k) == face)
            .map(|k| self.world.surface_code(k))
    }

    /// The nearest face `ray` meets ahead (`t > 0`); the opaque straw wins ties.
    ///
    /// `left` is the face the ray has just left (it starts on it, after an event there, or, for a
    /// ray sent back from the straw, on the straw): its root at the start is excluded exactly (a
    /// plane is not met again, a side only at its other root, the convex straw not at all), while
    /// every other face counts at any positive distance, so a face a hair away is never skipped.
    /// The straw is opaque: only the root by which a ray enters it counts.
    #[inline]
    pub fn nearest_intersection(&self, ray: &Ray, left: Option<Face>) -> Option<Intersection> {
        Some(match self.world.nearest(ray, self.left_code(left))? {
            Hit::Boundary { t, index } => Intersection {
                distance: t,
                face: self.face_of(index),
            },
            Hit::Object { t, part, .. } => Intersection {
                distance: t,
                face: straw_face(part),
            },
        })
    }

    /// The event `e` of the world in the assignment's words (the normal out of the water).
    #[inline]
    fn event(&self, e: &WorldEvent) -> Event {
        let face = self.face_of(e.boundary);
        Event {
            point: e.point,
            face,
            normal: self.scene.water_normal(face, e.point),
            incoming: e.incoming,
            outgoing: e.outgoing,
            n1: e.n1,
            n2: e.n2,
            totally_reflected: e.totally_reflected,
        }
    }

    /// Traces `ray`, which starts in air, by the course's law: refraction or total reflection at
    /// each water face.
    #[inline]
    pub fn trace(&self, ray: Ray) -> Outcome {
        self.trace_with(ray, |_| {})
    }

    /// Traces `ray`, which starts in air, calling `on_event` at every water event, in order.
    #[inline]
    pub fn trace_with(&self, ray: Ray, on_event: impl FnMut(&Event)) -> Outcome {
        self.trace_limited(ray, self.scene.max_events, on_event)
    }

    /// [`Tracer::trace_with`] with the event limit `max_events` instead of the scene's.
    #[inline]
    pub fn trace_limited(
        &self,
        ray: Ray,
        max_events: u32,
        mut on_event: impl FnMut(&Event),
    ) -> Outcome {
        let outcome = self
            .world
            .trace_limited(ray, max_events, |e| on_event(&self.event(e)));
        match outcome {
            WorldOutcome::Object {
                color,
                point,
                path_length,
                events,
                part,
                ..
            } => Outcome::Straw {
                color,
                point,
                path_length,
                events,
                face: straw_face(part),
            },
            WorldOutcome::Escaped { events, .. } => Outcome::Escaped { events },
            WorldOutcome::Dropped => Outcome::Dropped,
        }
    }

    /// Colour code (0 for none) of the section `ray` reaches by the course's law.
    #[inline]
    pub fn color(&self, ray: Ray) -> u8 {
        self.world.trace(ray).color()
    }

    /// The image point seen from `observer` along unit `u0`: the same as [`Scene::image_point`].
    #[inline]
    pub fn image_point(&self, observer: Vec3, u0: Vec3) -> Option<ImagePoint> {
        self.world.image_point(observer, u0)
    }

    /// Fresnel tracing (the ray splits at each water face into branches weighted by the Fresnel
    /// reflectance): the weight of `ray` that ends on each section.
    pub fn trace_fresnel(&self, ray: Ray, prune_below: f64) -> [f64; SECTION_COUNT] {
        self.fresnel_bounded::<false>(ray, prune_below, FRESNEL_SEGMENTS_PER_RAY, |_| {})
    }

    /// Fresnel tracing for pictures: [`Self::trace_fresnel`], but branches that provably escape
    /// (out of the water through its side or bottom, or mirrored off their outside) are not
    /// followed.
    pub fn trace_fresnel_escaping(&self, ray: Ray, prune_below: f64) -> [f64; SECTION_COUNT] {
        self.fresnel_bounded::<true>(ray, prune_below, FRESNEL_SEGMENTS_PER_RAY, |_| {})
    }

    /// Fresnel tracing, at most `max_segments` straight segments in all, every split and every
    /// branch's end told to `on_step` in the assignment's words (see
    /// [`World::fresnel_steps`]).
    pub fn fresnel_bounded<const SKIP_ESCAPING: bool>(
        &self,
        ray: Ray,
        prune_below: f64,
        max_segments: u32,
        mut on_step: impl FnMut(FresnelStep),
    ) -> [f64; SECTION_COUNT] {
        let w = self
            .world
            .fresnel_steps::<SKIP_ESCAPING>(ray, prune_below, max_segments, |step| {
                on_step(match step {
                    WorldFresnelStep::Split {
                        point,
                        boundary,
                        incoming,
                        n1,
                        n2,
                        weight,
                        reflected,
                        refracted,
                        ..
                    } => FresnelStep::Split {
                        point,
                        normal: self.scene.water_normal(self.face_of(boundary), point),
                        incoming,
                        n1,
                        n2,
                        weight,
                        reflected,
                        refracted,
                    },
                    WorldFresnelStep::TotalReflection { point, weight, .. } => {
                        FresnelStep::TotalReflection { point, weight }
                    }
                    WorldFresnelStep::Object {
                        color,
                        point,
                        part,
                        weight,
                        events,
                        ..
                    } => FresnelStep::Straw {
                        color,
                        point,
                        face: straw_face(part),
                        weight,
                        events,
                    },
                    WorldFresnelStep::Escaped {
                        ray,
                        weight,
                        events,
                    } => FresnelStep::Escaped {
                        ray,
                        weight,
                        events,
                    },
                    WorldFresnelStep::Dropped { weight } => FresnelStep::Dropped { weight },
                    WorldFresnelStep::Pruned { weight } => FresnelStep::Pruned { weight },
                })
            });
        std::array::from_fn(|k| w[k])
    }
}
