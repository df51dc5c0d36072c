//! Following one ray through the water to the straw (SPEC §3): nearest face, refraction or total
//! reflection at each water face, at most `max_events` events, the opaque straw stops the ray.
//!
//! Also the Fresnel tracer of SPEC §6, which splits a ray at each water face into a reflected and a
//! refracted branch.

use crate::geometry::{enter_bounding_sphere, Ray};
use crate::interface::{reflect, refract, refract_with_reflectance};
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

impl Intersection {
    /// The nearer of the nearest water face and the nearest straw face (each a distance, infinite
    /// if none, and a face); the opaque straw wins ties (SPEC §3), e.g. its bottom cap on `z = 0`.
    #[inline]
    pub fn nearer(water: (f64, Face), straw: (f64, Face)) -> Option<Intersection> {
        let (distance, face) = if straw.0 <= water.0 { straw } else { water };
        distance
            .is_finite()
            .then_some(Intersection { distance, face })
    }
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
    /// starts on one); the straw wins ties (SPEC §3). The one rule is [`Tracer::nearest_intersection`].
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

    /// Traces `ray`, which starts in air, by the course's law (SPEC §3).
    #[inline]
    pub fn trace(&self, ray: Ray) -> Outcome {
        self.trace_with(ray, |_| {})
    }

    /// Traces `ray`, which starts in air, calling `on_event` at every water event, in order.
    #[inline]
    pub fn trace_with(&self, ray: Ray, on_event: impl FnMut(&Event)) -> Outcome {
        follow_ray(&Tracer::new(self), self, ray, on_event)
    }

    /// Fresnel tracing (SPEC §6): the weight of `ray` that ends on each section (index 0 = code 1).
    ///
    /// At each water face the ray splits into a reflected branch of weight `R` (unpolarised Fresnel
    /// reflectance, 1 under total reflection) and a refracted branch of weight `1 − R`; each branch
    /// keeps its own event count and is dropped past `max_events`. Branches lighter than
    /// `prune_below` are abandoned (their weight is lost, never misattributed). No allocation.
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
        follow_fresnel::<false>(
            &Tracer::new(self),
            self,
            ray,
            prune_below,
            max_segments,
            on_step,
        )
    }
}

/// A way of finding the nearest face a ray meets (the tracer, [`crate::tracer::Tracer`]).
pub trait NearestFace {
    /// The nearest face `ray` meets ahead, `left` being the water face it has just left (if it
    /// starts on one, after an event there); the straw wins ties (SPEC §3).
    fn nearest_face(&self, ray: &Ray, left: Option<Face>) -> Option<Intersection>;
}

impl NearestFace for Scene {
    #[inline]
    fn nearest_face(&self, ray: &Ray, left: Option<Face>) -> Option<Intersection> {
        self.nearest_intersection(ray, left)
    }
}

/// The course's tracing loop (SPEC §3), written once for every [`NearestFace`]: from air, face after
/// face, refraction or total reflection at each water face, until the straw, escape, or one event
/// more than `scene.max_events`; `on_event` is told every event, in order.
#[inline]
pub fn follow_ray(
    faces: &impl NearestFace,
    scene: &Scene,
    ray: Ray,
    mut on_event: impl FnMut(&Event),
) -> Outcome {
    // A distant ray is first brought to the scene (no face lies before its bounding sphere).
    let Some((mut ray, mut length)) = enter_bounding_sphere(ray) else {
        return Outcome::Escaped { events: 0 };
    };
    let mut in_water = false;
    let mut events = 0u32;
    let mut left = None;
    loop {
        let Some(hit) = faces.nearest_face(&ray, left) else {
            return Outcome::Escaped { events };
        };
        let point = ray.at(hit.distance);
        length += hit.distance;
        if hit.face.is_straw() {
            return Outcome::Straw {
                color: scene.straw_color(hit.face, point),
                point,
                path_length: length,
                events,
                face: hit.face,
            };
        }
        if events == scene.max_events {
            return Outcome::Dropped;
        }
        events += 1;
        let normal = scene.water_normal(hit.face, point);
        let (n1, n2) = if in_water {
            (scene.n_water, 1.0)
        } else {
            (1.0, scene.n_water)
        };
        let (outgoing, totally_reflected) = match refract(ray.direction, normal, n1, n2) {
            Some(t) => (t.normalize(), false),
            None => (reflect(ray.direction, normal), true),
        };
        on_event(&Event {
            point,
            face: hit.face,
            normal,
            incoming: ray.direction,
            outgoing,
            n1,
            n2,
            totally_reflected,
        });
        if !totally_reflected {
            in_water = !in_water;
        }
        ray = Ray {
            origin: point,
            direction: outgoing,
        };
        left = Some(hit.face);
    }
}

/// The Fresnel tracing loop of SPEC §6, written once for every [`NearestFace`]; see
/// [`Scene::trace_fresnel_with`]. With `SKIP_ESCAPING`, branches that provably escape are not
/// followed (for pictures, where they add nothing): a branch that leaves the water through its side
/// wall or bottom, or is reflected off their outside, moves away from the axis or downwards for good
/// and can meet no face again; only the order of the sums changes (weights agree to ~1e-16), and
/// `on_step` is then not told of those branches. At most `max_segments` straight segments are
/// followed; the branches still travelling then are reported as dropped.
#[inline]
pub fn follow_fresnel<const SKIP_ESCAPING: bool>(
    faces: &impl NearestFace,
    scene: &Scene,
    ray: Ray,
    prune_below: f64,
    max_segments: u32,
    mut on_step: impl FnMut(FresnelStep),
) -> [f64; SECTION_COUNT] {
    // Depth-first. At each split the branch on the air side is followed first: the water is
    // convex, so a branch in air that leaves a water face never meets the water again and ends at
    // once; the stack thus holds at most one waiting branch, whatever the event limit (a few slots
    // spare; a branch that found no slot would be reported as pruned).
    const STACK: usize = 4;
    #[derive(Clone, Copy)]
    struct Branch {
        ray: Ray,
        in_water: bool,
        events: u32,
        weight: f64,
        /// The water face the branch starts on (it has just left it).
        left: Option<Face>,
    }
    let mut weights = [0.0; SECTION_COUNT];
    // A distant ray is first brought to the scene; one that misses it escapes as it is.
    let Some((start, _)) = enter_bounding_sphere(ray) else {
        on_step(FresnelStep::Escaped {
            ray,
            weight: 1.0,
            events: 0,
        });
        return weights;
    };
    let mut stack = [Branch {
        ray: start,
        in_water: false,
        events: 0,
        weight: 1.0,
        left: None,
    }; STACK];
    let mut top = 1usize;
    let mut segments = 0u32;
    while top > 0 {
        top -= 1;
        let mut b = stack[top];
        loop {
            if segments == max_segments {
                // Out of work: this branch and every waiting one are dropped.
                on_step(FresnelStep::Dropped { weight: b.weight });
                for waiting in &stack[..top] {
                    on_step(FresnelStep::Dropped {
                        weight: waiting.weight,
                    });
                }
                return weights;
            }
            segments += 1;
            let Some(hit) = faces.nearest_face(&b.ray, b.left) else {
                on_step(FresnelStep::Escaped {
                    // A branch that met nothing is the ray as it started, from the eye.
                    ray: if b.events == 0 { ray } else { b.ray },
                    weight: b.weight,
                    events: b.events,
                });
                break;
            };
            let point = b.ray.at(hit.distance);
            if hit.face.is_straw() {
                let color = scene.straw_color(hit.face, point);
                weights[color as usize - 1] += b.weight;
                on_step(FresnelStep::Straw {
                    color,
                    point,
                    face: hit.face,
                    weight: b.weight,
                    events: b.events,
                });
                break;
            }
            if b.events == scene.max_events {
                on_step(FresnelStep::Dropped { weight: b.weight });
                break;
            }
            b.events += 1;
            let normal = scene.water_normal(hit.face, point);
            let (n1, n2) = if b.in_water {
                (scene.n_water, 1.0)
            } else {
                (1.0, scene.n_water)
            };
            let reflected = reflect(b.ray.direction, normal);
            match refract_with_reflectance(b.ray.direction, normal, n1, n2) {
                None => {
                    on_step(FresnelStep::TotalReflection {
                        point,
                        weight: b.weight,
                    });
                    b.ray = Ray {
                        origin: point,
                        direction: reflected,
                    };
                    b.left = Some(hit.face);
                }
                Some((t, r)) => {
                    let mut wr = b.weight * r;
                    let mut wt = b.weight * (1.0 - r);
                    on_step(FresnelStep::Split {
                        point,
                        normal,
                        incoming: b.ray.direction,
                        n1,
                        n2,
                        weight: b.weight,
                        reflected: wr,
                        refracted: wt,
                    });
                    if SKIP_ESCAPING && hit.face != Face::WaterTop {
                        // The branch that ends up in air here escapes (see above).
                        if b.in_water {
                            wt = 0.0;
                        } else {
                            wr = 0.0;
                        }
                    }
                    let refl = Branch {
                        ray: Ray {
                            origin: point,
                            direction: reflected,
                        },
                        in_water: b.in_water,
                        events: b.events,
                        weight: wr,
                        left: Some(hit.face),
                    };
                    let refr = Branch {
                        ray: Ray {
                            origin: point,
                            direction: t.normalize(),
                        },
                        in_water: !b.in_water,
                        events: b.events,
                        weight: wt,
                        left: Some(hit.face),
                    };
                    // The air-side branch now (it ends at once), the water-side one later.
                    let (now, later) = if b.in_water {
                        (refr, refl)
                    } else {
                        (refl, refr)
                    };
                    if later.weight >= prune_below && later.weight > 0.0 && top < STACK {
                        stack[top] = later;
                        top += 1;
                    } else if !(SKIP_ESCAPING && later.weight == 0.0) {
                        on_step(FresnelStep::Pruned {
                            weight: later.weight,
                        });
                    }
                    if now.weight < prune_below || now.weight == 0.0 {
                        if !(SKIP_ESCAPING && now.weight == 0.0) {
                            on_step(FresnelStep::Pruned { weight: now.weight });
                        }
                        break;
                    }
                    b = now;
                }
            }
        }
    }
    weights
}
