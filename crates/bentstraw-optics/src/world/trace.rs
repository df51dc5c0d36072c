//! The tracing loops: the course's law (one ray or eight at a time, over [`Real`]) and the
//! Fresnel split (one ray, depth first).

use crate::geometry::{enter_sphere, Ray};
use crate::image::ImagePoint;
use crate::lanes::{Mask, Real, V3};
use crate::light_path_type::{Entry, LightPathType};
use crate::Vec3;

use super::fresnel::{followed, split, SegmentBudget};
use super::nearest::{Bend, Nearest};
use super::{Event, Outcome, Part, Shape, World, AIR, COLOR_COUNT};

/// Most straight ray segments a Fresnel trace follows for one ray from the eye, all its branches
/// together (a picture's pixel with several samples shares [`FRESNEL_SEGMENTS_PER_PIXEL`]).
///
/// Without a bound the work has none: light trapped by total reflection (water of index 5, an
/// event limit of 1000) bounces a thousand times in every branch. Past the bound, what is still
/// travelling is dropped, exactly like light that would need an event past the limit; ordinary
/// scenes use a few dozen segments per ray.
pub const FRESNEL_SEGMENTS_PER_RAY: u32 = 2048;

/// Most ray segments followed for one pixel of a picture, all its samples together.
pub const FRESNEL_SEGMENTS_PER_PIXEL: u32 = 8192;

/// How the rays of a [`Real`] traced by the course's law end.
#[derive(Clone, Copy, Debug)]
pub(crate) struct CourseEnds<R: Real> {
    /// The lanes that reached an object.
    pub reached: R::Mask,
    /// The lanes that would have needed one event more than allowed.
    pub dropped: R::Mask,
    /// Where each reached lane met its object, which (its index), its colour code and part
    /// there, and the length of its broken path.
    pub point: V3<R>,
    pub object: R,
    pub color: R,
    pub part: R,
    pub length: R,
    /// Events each lane underwent.
    pub events: R,
    /// The light each lane lost on its way in tinted media, per channel (it keeps
    /// `exp(−density)`); zero in a world where nothing absorbs.
    pub density: [R; 3],
    /// Each lane's last straight piece (for those that left the scene: what they see beyond).
    pub origin: V3<R>,
    pub direction: V3<R>,
}

/// One event of a lane, as the course's loop tells it.
pub(crate) struct LaneEvent<'a, R: Real> {
    /// The boundary met (its index).
    pub boundary: R,
    /// Where.
    pub point: V3<R>,
    /// The direction before, and after.
    pub incoming: V3<R>,
    pub outgoing: V3<R>,
    /// What light does there.
    pub bend: &'a Bend<R>,
}

impl World {
    /// The course's tracing loop, for one ray (`f64`) or eight (`F8`): from air, the nearest
    /// boundary or object, refraction or total reflection at each boundary, until an object, the
    /// open air (no boundary or object ahead, or beyond a face of the scene's hull), or one event
    /// more than `max_events`. The rays start at `o` along unit `d` having travelled `length`;
    /// `on_event` is told every event, in order.
    #[inline(always)]
    pub(crate) fn follow_course<R: Real>(
        &self,
        o: V3<R>,
        d: V3<R>,
        alive: R::Mask,
        length: R,
        max_events: u32,
        on_event: impl FnMut(&LaneEvent<R>),
    ) -> CourseEnds<R> {
        self.follow_course_in::<R, true>(o, d, alive, length, max_events, on_event)
    }

    /// [`World::follow_course`] for a world with solids or without (see
    /// [`World::nearest_lanes_in`]).
    #[inline(always)]
    pub(crate) fn follow_course_in<R: Real, const SOLIDS: bool>(
        &self,
        mut o: V3<R>,
        mut d: V3<R>,
        mut alive: R::Mask,
        mut length: R,
        max_events: u32,
        mut on_event: impl FnMut(&LaneEvent<R>),
    ) -> CourseEnds<R> {
        let (zero, one) = (R::splat(0.0), R::splat(1.0));
        let inf = R::splat(f64::INFINITY);
        let first_object = R::splat(self.boundaries.len() as f64);
        let mut ends = CourseEnds {
            reached: R::Mask::splat(false),
            dropped: R::Mask::splat(false),
            point: o,
            object: zero,
            color: zero,
            part: zero,
            length,
            events: zero,
            density: [zero; 3],
            origin: o,
            direction: d,
        };
        let absorbs = self.absorbs();
        let mut medium = R::splat(AIR as f64);
        let mut left = R::splat(-1.0);
        let mut events = zero;
        let (mut t_end, mut code_end, mut tag_end) = (zero, first_object, zero);
        // One pass per event, the last (`event == max_events`) only to see what the rays meet.
        let mut event = 0u32;
        loop {
            if !alive.any() {
                break;
            }
            let Some(hit) = self.nearest_lanes_in::<R, SOLIDS>(o, d, alive, left) else {
                break;
            };
            let met = alive.and(hit.t.lt(inf));
            let on_object = met.and(hit.code.ge(first_object));
            if absorbs {
                self.absorb_lanes(medium, hit.t, met, &mut ends.density);
            }
            if on_object.any() {
                // What it met; where, and the colour there, once the loop is done (a lane that
                // has stopped keeps its ray and its length).
                ends.reached = ends.reached.or(on_object);
                t_end = R::select(on_object, hit.t, t_end);
                code_end = R::select(on_object, hit.code, code_end);
                ends.part = R::select(on_object, hit.part, ends.part);
                tag_end = R::select(on_object, hit.tag, tag_end);
            }
            // Lanes that met nothing have left the scene along (o, d).
            alive = met.and_not(on_object);
            if !alive.any() {
                break;
            }
            if event == max_events {
                ends.dropped = alive;
                break;
            }
            let q = o.along(hit.t, d);
            length = R::select(alive, length + hit.t, length);
            let bend = self.bend_lanes_in::<R, SOLIDS>(hit.code, alive, q, d, medium);
            let out = bend.outgoing();
            on_event(&LaneEvent {
                boundary: hit.code,
                point: q,
                incoming: d,
                outgoing: out,
                bend: &bend,
            });
            events = R::select(alive, events + one, events);
            medium = R::select(alive, bend.beyond, medium);
            left = R::select(alive, bend.surface, left);
            o = V3::select(alive, q, o);
            d = V3::select(alive, out, d);
            // Out through a face of the scene's hull: nothing lies ahead any more.
            let gone =
                R::Mask::select_mask(bend.total, bend.reflected_escapes, bend.refracted_escapes);
            alive = alive.and_not(gone);
            event += 1;
        }
        if ends.reached.any() {
            let hit = Nearest {
                t: t_end,
                code: code_end,
                part: ends.part,
                tag: tag_end,
            };
            ends.point = o.along(t_end, d);
            ends.length = length + t_end;
            ends.object = code_end - first_object;
            ends.color = hit.color(self, ends.reached);
        }
        ends.events = events;
        ends.origin = o;
        ends.direction = d;
        ends
    }

    /// Traces `ray`, which starts in air outside every object, by the course's law.
    pub fn trace(&self, ray: Ray) -> Outcome {
        self.trace_with(ray, |_| {})
    }

    /// [`World::trace`], telling `on_event` every refraction and total reflection, in order.
    pub fn trace_with(&self, ray: Ray, on_event: impl FnMut(&Event)) -> Outcome {
        self.trace_limited(ray, self.max_events, on_event)
    }

    /// [`World::trace_with`] with the event limit `max_events` instead of the world's.
    pub fn trace_limited(
        &self,
        ray: Ray,
        max_events: u32,
        mut on_event: impl FnMut(&Event),
    ) -> Outcome {
        // A distant ray is first brought to the scene (nothing lies before its sphere).
        let Some((start, length)) = enter_sphere(ray, self.centre, self.radius) else {
            return Outcome::Escaped { events: 0, ray };
        };
        let ends = self.follow_course::<f64>(
            start.origin.into(),
            start.direction.into(),
            true,
            length,
            max_events,
            |e| {
                on_event(&Event {
                    point: e.point.into(),
                    boundary: e.boundary as usize,
                    normal: e.bend.normal.into(),
                    incoming: e.incoming.into(),
                    outgoing: e.outgoing.into(),
                    n1: e.bend.n1,
                    n2: e.bend.n2,
                    totally_reflected: e.bend.total,
                })
            },
        );
        if ends.reached {
            Outcome::Object {
                color: ends.color as u8,
                point: ends.point.into(),
                path_length: ends.length,
                events: ends.events as u32,
                object: ends.object as usize,
                part: Part::from_code(ends.part),
            }
        } else if ends.dropped {
            Outcome::Dropped
        } else {
            Outcome::Escaped {
                events: ends.events as u32,
                ray: Ray {
                    origin: ends.origin.into(),
                    direction: ends.direction.into(),
                },
            }
        }
    }

    /// The image point seen from `observer` along unit `u0` by the course's convention,
    /// `P = O + L·u0`, if the ray reaches an object.
    pub fn image_point(&self, observer: Vec3, u0: Vec3) -> Option<ImagePoint> {
        self.trace(Ray {
            origin: observer,
            direction: u0,
        })
        .image_point(observer, u0)
    }

    /// How a ray enters the liquid (or the container, or a solid) at event `e`, its first:
    /// through a surface from above, through a wall, through a bottom from below, through a
    /// solid's face.
    pub fn entry_of(&self, e: &Event) -> Entry {
        let b = &self.boundaries[e.boundary];
        if b.solid {
            return Entry::Solid;
        }
        match b.shape {
            Shape::Horizontal { .. } if e.incoming.z < 0.0 => Entry::Top,
            Shape::Horizontal { .. } => Entry::Bottom,
            _ => Entry::Wall,
        }
    }

    /// The kind of face boundary `index` is, in a teacher's words: a wall (a glass's or a tank's
    /// side), the top surface (air above it: a liquid's free surface, a glass's rim), the bottom
    /// (air below it), or the surface between two layers (or a liquid and the glass's floor).
    pub fn face_name(&self, index: usize) -> &'static str {
        let b = &self.boundaries[index];
        if b.solid {
            return "a transparent solid's face";
        }
        match b.shape {
            Shape::Horizontal { .. } if b.outer == AIR => "top surface",
            Shape::Horizontal { .. } if b.inner == AIR => "bottom",
            Shape::Horizontal { .. } => "surface between layers",
            _ => "wall",
        }
    }

    /// Traces `ray` by the course's law and tells the kind of its light path: how it enters (its
    /// first event) and how many total reflections it undergoes.
    pub fn trace_path_type(&self, ray: Ray) -> (Outcome, LightPathType) {
        self.trace_path_type_limited(ray, self.max_events)
    }

    /// [`World::trace_path_type`] with the event limit `max_events`.
    pub fn trace_path_type_limited(&self, ray: Ray, max_events: u32) -> (Outcome, LightPathType) {
        let mut kind = LightPathType::DIRECT;
        let outcome = self.trace_limited(ray, max_events, |e| {
            kind.record_entry(self.entry_of(e), e.totally_reflected)
        });
        (outcome, kind)
    }
}

/// One step of Fresnel tracing ([`World::fresnel_steps`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FresnelStep {
    /// A branch of weight `weight` split at boundary `boundary` into `reflected + refracted`.
    Split {
        /// Where.
        point: Vec3,
        /// Which boundary.
        boundary: usize,
        /// Its unit normal there, towards its outer side.
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
    /// A branch was totally reflected at boundary `boundary`, keeping its weight.
    TotalReflection {
        /// Where.
        point: Vec3,
        /// Which boundary.
        boundary: usize,
        /// Its weight.
        weight: f64,
    },
    /// A branch ended on an object.
    Object {
        /// The colour code there.
        color: u8,
        /// The point reached.
        point: Vec3,
        /// Which object.
        object: usize,
        /// Which part of it.
        part: Part,
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
    /// A branch would have needed more than the event limit.
    Dropped {
        /// Its weight.
        weight: f64,
    },
    /// A branch lighter than the pruning threshold (or finding no room to wait) was abandoned.
    Pruned {
        /// Its weight.
        weight: f64,
    },
}

impl World {
    /// Fresnel tracing (one ray, double precision): the weight of `ray` that ends on each colour
    /// code (index 0 = code 1). At every interface a branch splits into a reflected part `R`
    /// (unpolarised Fresnel reflectance; all of it under total reflection) and a refracted part
    /// `1 − R`; each branch keeps its own event count and is dropped past the event limit;
    /// branches lighter than `prune_below` are abandoned; at most `max_segments` straight
    /// segments are followed in all, and what still travels then is dropped. `on_step` is told
    /// every split and how every branch ends, so the weights told add up to 1. With
    /// `SKIP_ESCAPING`, branches that leave the scene for good (out through a face of its hull)
    /// are not followed nor told: only the order of the sums changes. No allocation.
    pub fn fresnel_steps<const SKIP_ESCAPING: bool>(
        &self,
        ray: Ray,
        prune_below: f64,
        max_segments: u32,
        mut on_step: impl FnMut(FresnelStep),
    ) -> [f64; COLOR_COUNT] {
        // Depth-first. At each split the branch going into (or staying in) the optically thinner
        // medium is followed first: in the glass of water it leaves the water and ends at once,
        // so the stack holds at most one waiting branch there. Thick walls and layers can hold
        // several; a branch that finds no room is abandoned.
        const STACK: usize = 32;
        #[derive(Clone, Copy)]
        struct Branch {
            ray: Ray,
            medium: f64,
            events: u32,
            weight: f64,
            left: f64,
        }
        let mut weights = [0.0; COLOR_COUNT];
        let Some((start, _)) = enter_sphere(ray, self.centre, self.radius) else {
            on_step(FresnelStep::Escaped {
                ray,
                weight: 1.0,
                events: 0,
            });
            return weights;
        };
        let first_object = self.boundaries.len();
        let mut stack = [Branch {
            ray: start,
            medium: AIR as f64,
            events: 0,
            weight: 1.0,
            left: -1.0,
        }; STACK];
        let mut top = 1usize;
        let mut budget = SegmentBudget::new(max_segments);
        while top > 0 {
            top -= 1;
            let mut b = stack[top];
            loop {
                let (o, d) = (V3::from(b.ray.origin), V3::from(b.ray.direction));
                let hit = self
                    .nearest_lanes(o, d, true, b.left)
                    .filter(|h| h.t.is_finite());
                let Some(hit) = hit else {
                    on_step(FresnelStep::Escaped {
                        // A branch that met nothing is the ray as it started, from the eye.
                        ray: if b.events == 0 { ray } else { b.ray },
                        weight: b.weight,
                        events: b.events,
                    });
                    break;
                };
                let point: Vec3 = o.along(hit.t, d).into();
                let k = hit.code as usize;
                if k >= first_object {
                    let color = hit.color(self, true) as u8;
                    weights[color as usize - 1] += b.weight;
                    on_step(FresnelStep::Object {
                        color,
                        point,
                        object: k - first_object,
                        part: Part::from_code(hit.part),
                        weight: b.weight,
                        events: b.events,
                    });
                    break;
                }
                if b.events == self.max_events {
                    on_step(FresnelStep::Dropped { weight: b.weight });
                    break;
                }
                b.events += 1;
                let bend = self.bend_lanes(hit.code, true, point.into(), d, b.medium);
                let reflected = Ray {
                    origin: point,
                    direction: bend.reflected.into(),
                };
                if bend.total {
                    on_step(FresnelStep::TotalReflection {
                        point,
                        boundary: k,
                        weight: b.weight,
                    });
                    if !budget.spend() {
                        // Out of work: dropped, like light past the event limit.
                        on_step(FresnelStep::Dropped { weight: b.weight });
                        break;
                    }
                    b.ray = reflected;
                    b.left = bend.surface;
                    continue;
                }
                let (mut wr, mut wt) = split(b.weight, bend.reflectance(), false);
                on_step(FresnelStep::Split {
                    point,
                    boundary: k,
                    normal: bend.normal.into(),
                    incoming: b.ray.direction,
                    n1: bend.n1,
                    n2: bend.n2,
                    weight: b.weight,
                    reflected: wr,
                    refracted: wt,
                });
                if SKIP_ESCAPING {
                    if bend.refracted_escapes {
                        wt = 0.0;
                    }
                    if bend.reflected_escapes {
                        wr = 0.0;
                    }
                }
                let refl = Branch {
                    ray: reflected,
                    medium: b.medium,
                    events: b.events,
                    weight: wr,
                    left: bend.surface,
                };
                let refr = Branch {
                    ray: Ray {
                        origin: point,
                        direction: bend.refracted.into(),
                    },
                    medium: bend.beyond,
                    events: b.events,
                    weight: wt,
                    left: bend.surface,
                };
                // The thinner side's branch now, the other later (lower medium id on a tie).
                let refracted_first =
                    bend.n2 < bend.n1 || (bend.n2 == bend.n1 && bend.beyond < b.medium);
                let (now, later) = if refracted_first {
                    (refr, refl)
                } else {
                    (refl, refr)
                };
                // A branch not followed is told as pruned (a weightless one adds nothing);
                // one followed takes a segment of the ray's budget, or is dropped.
                let mut follow = |branch: &Branch, on_step: &mut dyn FnMut(FresnelStep)| {
                    if !followed(branch.weight, prune_below) {
                        if branch.weight > 0.0 {
                            on_step(FresnelStep::Pruned {
                                weight: branch.weight,
                            });
                        }
                        false
                    } else if !budget.spend() {
                        on_step(FresnelStep::Dropped {
                            weight: branch.weight,
                        });
                        false
                    } else {
                        true
                    }
                };
                if follow(&later, &mut on_step) {
                    if top < STACK {
                        stack[top] = later;
                        top += 1;
                    } else {
                        // No room to wait: abandoned.
                        on_step(FresnelStep::Pruned {
                            weight: later.weight,
                        });
                    }
                }
                if !follow(&now, &mut on_step) {
                    break;
                }
                b = now;
            }
        }
        weights
    }

    /// Fresnel tracing (see [`World::fresnel_steps`]), following at most
    /// [`FRESNEL_SEGMENTS_PER_RAY`] segments: the weight of `ray` that ends on each colour code.
    /// `on_leave` is told every other end of a branch with its weight: `Some(last straight
    /// piece)` for light leaving the scene, `None` for light abandoned, so that the weights told
    /// and returned add up to 1.
    pub fn trace_fresnel(
        &self,
        ray: Ray,
        prune_below: f64,
        mut on_leave: impl FnMut(Option<Ray>, f64),
    ) -> [f64; COLOR_COUNT] {
        self.fresnel_steps::<false>(
            ray,
            prune_below,
            FRESNEL_SEGMENTS_PER_RAY,
            |step| match step {
                FresnelStep::Escaped { ray, weight, .. } => on_leave(Some(ray), weight),
                FresnelStep::Dropped { weight } | FresnelStep::Pruned { weight } => {
                    on_leave(None, weight)
                }
                _ => {}
            },
        )
    }
}
