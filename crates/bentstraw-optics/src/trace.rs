//! Following one ray through the water to the straw, told in the assignment's words:
//! the faces of the water and the straw, the events at the water's faces, the outcome. The tracing
//! itself is the one loop every scene is traced by ([`crate::world::World`]'s), run on the
//! assignment's glass built as a world ([`Tracer`]).
//!
//! Also the Fresnel tracer, which splits a ray at each water face into a reflected and a
//! refracted branch.

use std::borrow::Cow;

use crate::geometry::Ray;
use crate::scene::{section_at, Scene, GLASS_RADIUS, SECTION_COUNT};
use crate::tracer::Tracer;
use crate::Vec3;

/// A face of the scene a ray can meet.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Face {
    /// The water's side wall (the glass's wall, optically invisible, holds it).
    WaterSide,
    /// The water's free surface `z = he`.
    WaterTop,
    /// The water's bottom face `z = 0`.
    WaterBottom,
    /// The straw's side.
    StrawSide,
    /// The straw's top cap.
    StrawTop,
    /// The straw's bottom cap.
    StrawBottom,
}

impl Face {
    /// Whether this face belongs to the opaque straw.
    #[inline]
    pub fn is_straw(self) -> bool {
        matches!(self, Face::StrawSide | Face::StrawTop | Face::StrawBottom)
    }
}

/// The nearest face a ray meets and the distance to it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Intersection {
    /// Distance along the ray (m).
    pub distance: f64,
    /// The face met.
    pub face: Face,
}

/// What happened at one water face.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Event {
    /// Where it happened.
    pub point: Vec3,
    /// Which water face.
    pub face: Face,
    /// Unit normal of the face, pointing out of the water.
    pub normal: Vec3,
    /// Direction before the event.
    pub incoming: Vec3,
    /// Direction after the event.
    pub outgoing: Vec3,
    /// Index on the incoming side.
    pub n1: f64,
    /// Index on the other side.
    pub n2: f64,
    /// Whether the ray was totally reflected (otherwise refracted).
    pub totally_reflected: bool,
}

/// How a traced ray ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Outcome {
    /// The ray reached the straw.
    Straw {
        /// Colour code of the section hit, 1..=5.
        color: u8,
        /// The point of the straw hit.
        point: Vec3,
        /// Length of the broken path from the start to the straw (m).
        path_length: f64,
        /// Events undergone on the way.
        events: u32,
        /// The straw face hit.
        face: Face,
    },
    /// The ray left the scene without reaching the straw.
    Escaped {
        /// Events undergone before leaving.
        events: u32,
    },
    /// The ray would have needed more than `max_events` events.
    Dropped,
}

impl Outcome {
    /// Colour code of the straw section reached, or 0 if none.
    #[inline]
    pub fn color(&self) -> u8 {
        match self {
            Outcome::Straw { color, .. } => *color,
            _ => 0,
        }
    }
}

/// Most straight ray segments a Fresnel trace follows for one ray from the eye, all its branches
/// together (a picture's pixel with several samples shares [`FRESNEL_SEGMENTS_PER_PIXEL`]).
///
/// Without a bound the work has none: light trapped by total reflection (water of index 10, an
/// event limit of 1000) bounces a thousand times in every branch. Past the bound, what is still
/// travelling is dropped, exactly like light that would need an event past the limit; ordinary
/// scenes use a few dozen segments per ray.
pub const FRESNEL_SEGMENTS_PER_RAY: u32 = 2048;

/// Most ray segments followed for one pixel of a picture, all its samples together.
pub const FRESNEL_SEGMENTS_PER_PIXEL: u32 = 8192;

/// One step of Fresnel tracing, as reported by [`Scene::trace_fresnel_with`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FresnelStep {
    /// A branch of weight `weight` split at a water face into `reflected + refracted`.
    Split {
        /// Where.
        point: Vec3,
        /// Unit normal of the face, out of the water.
        normal: Vec3,
        /// Unit direction before the split.
        incoming: Vec3,
        /// Index on the incoming side.
        n1: f64,
        /// Index on the other side.
        n2: f64,
        /// Weight arriving.
        weight: f64,
        /// Weight of the reflected branch, `R · weight`.
        reflected: f64,
        /// Weight of the refracted branch, `(1 − R) · weight`.
        refracted: f64,
    },
    /// A branch was totally reflected, keeping its weight.
    TotalReflection {
        /// Where.
        point: Vec3,
        /// Its weight.
        weight: f64,
    },
    /// A branch ended on the straw.
    Straw {
        /// Colour code of the section, 1..=5.
        color: u8,
        /// The straw point reached.
        point: Vec3,
        /// The straw face reached.
        face: Face,
        /// Its weight.
        weight: f64,
        /// Events on its way.
        events: u32,
    },
    /// A branch left the scene along `ray` (its last straight piece).
    Escaped {
        /// The last straight piece of the branch, from its last event (or the start).
        ray: Ray,
        /// Its weight.
        weight: f64,
        /// Events on its way.
        events: u32,
    },
    /// A branch would have needed more than `max_events` events.
    Dropped {
        /// Its weight.
        weight: f64,
    },
    /// A branch lighter than the pruning threshold was abandoned.
    Pruned {
        /// Its weight.
        weight: f64,
    },
}

impl Scene {
    /// The nearest face `ray` meets ahead, `left` being the water face it has just left (if it
    /// starts on one); the opaque straw wins ties. The one rule is
    /// [`Tracer::nearest_intersection`].
    #[inline]
    pub fn nearest_intersection(&self, ray: &Ray, left: Option<Face>) -> Option<Intersection> {
        Tracer::new(self).nearest_intersection(ray, left)
    }

    /// Outward (out of the water) unit normal of water face `face` at point `p`.
    #[inline]
    pub fn water_normal(&self, face: Face, p: Vec3) -> Vec3 {
        match face {
            Face::WaterTop => Vec3::Z,
            Face::WaterBottom => Vec3::NEG_Z,
            _ => Vec3::new(p.x / GLASS_RADIUS, p.y / GLASS_RADIUS, 0.0).normalize(),
        }
    }

    /// Colour code of the straw at point `p` of face `face`.
    #[inline]
    pub fn straw_color(&self, face: Face, p: Vec3) -> u8 {
        match face {
            Face::StrawBottom => 1,
            Face::StrawTop => SECTION_COUNT as u8,
            _ => section_at(p.z),
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
        Tracer::new(self).trace_with(ray, on_event)
    }

    /// Fresnel tracing: the weight of `ray` that ends on each section (index 0 = code 1).
    ///
    /// At each water face the ray splits into a reflected branch of weight `R` (unpolarised Fresnel
    /// reflectance, 1 under total reflection) and a refracted branch of weight `1 − R`; each branch
    /// keeps its own event count and is dropped past `max_events`. Branches lighter than
    /// `prune_below` are abandoned (their weight is lost, never misattributed).
    #[inline]
    pub fn trace_fresnel(&self, ray: Ray, prune_below: f64) -> [f64; SECTION_COUNT] {
        self.trace_fresnel_with(ray, prune_below, |_| {})
    }

    /// [`Scene::trace_fresnel`], also reporting every split and how every branch ends to `on_step`
    /// (escaping branches with their last ray, so a picture can show what lies beyond).
    pub fn trace_fresnel_with(
        &self,
        ray: Ray,
        prune_below: f64,
        on_step: impl FnMut(FresnelStep),
    ) -> [f64; SECTION_COUNT] {
        self.trace_fresnel_bounded(ray, prune_below, FRESNEL_SEGMENTS_PER_RAY, on_step)
    }

    /// [`Scene::trace_fresnel_with`] following at most `max_segments` straight ray segments
    /// (all branches together; see [`FRESNEL_SEGMENTS_PER_RAY`]): what still travels after them is
    /// reported as dropped.
    pub fn trace_fresnel_bounded(
        &self,
        ray: Ray,
        prune_below: f64,
        max_segments: u32,
        on_step: impl FnMut(FresnelStep),
    ) -> [f64; SECTION_COUNT] {
        Tracer::new(self).fresnel_bounded::<false>(ray, prune_below, max_segments, on_step)
    }
}

/// The assignment's scene, prepared for tracing or not: what the course's loop and the Fresnel
/// loop ([`follow_ray`], [`follow_fresnel`]) trace.
pub trait NearestFace {
    /// The scene made ready for tracing (a [`Tracer`] is; a [`Scene`] makes one).
    fn prepared(&self) -> Cow<'_, Tracer>;

    /// The nearest face `ray` meets ahead, `left` being the water face it has just left (if it
    /// starts on one, after an event there); the opaque straw wins ties.
    fn nearest_face(&self, ray: &Ray, left: Option<Face>) -> Option<Intersection> {
        self.prepared().nearest_intersection(ray, left)
    }
}

impl NearestFace for Scene {
    #[inline]
    fn prepared(&self) -> Cow<'_, Tracer> {
        Cow::Owned(Tracer::new(self))
    }
}

/// The course's tracing loop in the assignment's words: from air, face after face,
/// refraction or total reflection at each water face, until the straw, escape, or one event more
/// than the scene's `max_events`; `on_event` is told every event, in order. It is the one loop
/// every scene is traced by ([`crate::world::World`]'s), told in the water's and straw's faces.
#[inline]
pub fn follow_ray(faces: &impl NearestFace, ray: Ray, on_event: impl FnMut(&Event)) -> Outcome {
    faces.prepared().trace_with(ray, on_event)
}

/// The Fresnel tracing loop in the assignment's words; see
/// [`Scene::trace_fresnel_with`]. With `SKIP_ESCAPING`, branches that provably escape are not
/// followed (for pictures, where they add nothing): a branch that leaves the water through its side
/// wall or bottom, or is reflected off their outside, moves away from the axis or downwards for good
/// and can meet no face again; only the order of the sums changes (weights agree to ~1e-16), and
/// `on_step` is then not told of those branches. At most `max_segments` straight segments are
/// followed; the branches still travelling then are reported as dropped.
#[inline]
pub fn follow_fresnel<const SKIP_ESCAPING: bool>(
    faces: &impl NearestFace,
    ray: Ray,
    prune_below: f64,
    max_segments: u32,
    on_step: impl FnMut(FresnelStep),
) -> [f64; SECTION_COUNT] {
    faces
        .prepared()
        .fresnel_bounded::<SKIP_ESCAPING>(ray, prune_below, max_segments, on_step)
}
