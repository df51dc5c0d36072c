//! A scene as data: any container, liquid layers and objects a scene file describes (a glass with
//! thick walls, a tank, oil on water, leaning straws, coins, cards), traced by the same laws as
//! the assignment's glass.
//!
//! The scene is a list of [`Boundary`]s between media (each medium known by an id, its index in
//! a table) and a list of opaque [`Object`]s. A ray carries the medium it travels in; at the
//! nearest boundary ahead it refracts or is totally reflected by Snell's law between the indices on
//! its two sides; an object stops it and gives its colour. A boundary between media of the same
//! index is no interface (light crosses it unbent, and it is no event): a glass of index 1 traces
//! exactly like walls of no thickness.

pub mod boundary;
pub mod object;
pub mod picture;

use crate::geometry::{enter_sphere, Ray};
use crate::image::ImagePoint;
use crate::interface::{reflect, refract, refract_with_reflectance};
use crate::light_path_type::{Entry, LightPathType};
use crate::sampling::ImageTracer;
use crate::scene::{SECTION_NAMES, SECTION_RGB};
use crate::scene_file::{Container, SceneDescription};
use crate::trace::FRESNEL_SEGMENTS_PER_RAY;
use crate::Vec3;

pub use boundary::{Boundary, MediumId, Region, Shape, Side};
pub use object::{in_arrow, Object, Part, CARD_COLOR, COIN_COLOR, PICTURE_COLOR};

/// The medium id of air.
pub const AIR: MediumId = 0;
/// The medium id of the container's material.
pub const CONTAINER: MediumId = 1;
/// How many colour codes there are: 1..=5 a straw's bands, 6 a coin, 7 a card, 8 its picture.
pub const COLOR_COUNT: usize = 8;
/// Display colours of codes 1..=8 (index 0 is code 1), RGB in 0..1: the straw's five sections,
/// then a coin's brass, a card's off-white and its arrow's near black.
pub const COLOR_RGB: [[f64; 3]; COLOR_COUNT] = [
    SECTION_RGB[0],
    SECTION_RGB[1],
    SECTION_RGB[2],
    SECTION_RGB[3],
    SECTION_RGB[4],
    [0.78, 0.6, 0.22],
    [0.93, 0.92, 0.88],
    [0.12, 0.12, 0.14],
];
/// Names of colour codes 1..=8: the straw's five sections, then a coin, a card, its arrow.
pub const COLOR_NAMES: [&str; COLOR_COUNT] = [
    SECTION_NAMES[0],
    SECTION_NAMES[1],
    SECTION_NAMES[2],
    SECTION_NAMES[3],
    SECTION_NAMES[4],
    "coin",
    "card",
    "arrow",
];

/// The scene ready for tracing: media, boundaries, objects, and a sphere holding them all.
#[derive(Clone, Debug, PartialEq)]
pub struct World {
    /// Refractive index of each medium, by id.
    indices: Vec<f64>,
    /// The cavity's media by height: `(upper height, medium)`, lowest first, the last unbounded.
    cavity: Vec<(f64, MediumId)>,
    /// Every boundary between media of different index.
    boundaries: Vec<Boundary>,
    /// Every opaque object.
    objects: Vec<Object>,
    /// Corners of a box holding every boundary and object.
    lo: Vec3,
    hi: Vec3,
    /// A sphere holding the box (rays from afar are first brought to it).
    centre: Vec3,
    radius: f64,
    /// Most events (refractions and total reflections) a ray may undergo.
    pub max_events: u32,
}

/// What a ray meets first.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Hit {
    /// The boundary `index`, at distance `t`.
    Boundary {
        /// Distance along the ray.
        t: f64,
        /// Which boundary.
        index: usize,
    },
    /// The object `index`, at distance `t`, on `part`, where it has colour code `color`.
    Object {
        /// Distance along the ray.
        t: f64,
        /// Which object.
        index: usize,
        /// Which part of it.
        part: Part,
        /// Its colour code there.
        color: u8,
    },
}

/// One refraction or total reflection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorldEvent {
    /// Where.
    pub point: Vec3,
    /// Which boundary.
    pub boundary: usize,
    /// Unit normal of the boundary there, towards its outer side.
    pub normal: Vec3,
    /// Direction before.
    pub incoming: Vec3,
    /// Direction after.
    pub outgoing: Vec3,
    /// Index of the medium the ray came through.
    pub n1: f64,
    /// Index of the medium on the other side.
    pub n2: f64,
    /// Whether the ray was totally reflected (otherwise refracted).
    pub totally_reflected: bool,
}

/// How a ray traced by the course's law ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum WorldOutcome {
    /// It reached an object.
    Object {
        /// The colour code there.
        color: u8,
        /// The point reached.
        point: Vec3,
        /// Length of the broken path (m).
        path_length: f64,
        /// Events on the way.
        events: u32,
        /// Which object.
        object: usize,
        /// The object's unit normal there, facing the ray.
        normal: Vec3,
    },
    /// It left the scene.
    Escaped {
        /// Events before it left.
        events: u32,
        /// Its last straight piece.
        ray: Ray,
    },
    /// It would have needed more than the event limit.
    Dropped,
}

impl WorldOutcome {
    /// The colour code reached, 0 for none.
    pub fn color(&self) -> u8 {
        match self {
            WorldOutcome::Object { color, .. } => *color,
            _ => 0,
        }
    }

    /// The image point `P = O + L·u0` this outcome makes for the ray from `observer` along unit
    /// `u0`, if it reached an object.
    pub fn image_point(&self, observer: Vec3, u0: Vec3) -> Option<ImagePoint> {
        match *self {
            WorldOutcome::Object {
                color,
                point,
                path_length,
                events,
                ..
            } => Some(ImagePoint::reached(
                observer,
                u0,
                color,
                point,
                path_length,
                events,
            )),
            _ => None,
        }
    }
}

/// The medium of the cavity at height `z`: the first layer whose top lies above `z` (`cavity` is
/// `(upper height, medium)`, lowest first), else air.
fn cavity_medium(cavity: &[(f64, MediumId)], z: f64) -> MediumId {
    cavity
        .iter()
        .find(|(top, _)| z < *top)
        .map_or(AIR, |(_, m)| *m)
}

/// The boundary of the plane `z` over `region`, `below` under it and `above` over it.
fn horizontal(z: f64, region: Region, below: MediumId, above: MediumId) -> Boundary {
    Boundary {
        shape: Shape::Horizontal { z, region },
        outer: Side::Medium(above),
        inner: Side::Medium(below),
    }
}

impl World {
    /// The world a valid scene description describes, with event limit `max_events`.
    pub fn new(scene: &SceneDescription, max_events: u32) -> World {
        let mut indices = vec![1.0, 1.0];
        let floor = scene.container.floor();
        let height = scene.container.height();
        let mut cavity = Vec::with_capacity(scene.liquids.len() + 2);
        if floor > 0.0 {
            cavity.push((floor, CONTAINER));
        }
        for liquid in &scene.liquids {
            cavity.push((liquid.top, indices.len() as MediumId));
            indices.push(liquid.index);
        }
        cavity.push((f64::INFINITY, AIR));
        let medium_above = |z: f64| cavity_medium(&cavity, z);

        // The container's own faces (a glass's rings at its base and rim, its sides; a tank's
        // walls), the horizontal region its inside covers, and its box.
        let (rings, surface, walls, lo, hi) = match &scene.container {
            Container::Glass(g) => {
                indices[CONTAINER as usize] = g.index;
                let inner = g.radius - g.wall;
                let ring = Region::Annulus {
                    inner2: inner * inner,
                    outer2: g.radius * g.radius,
                };
                let upright = |radius: f64, z_min: f64| Shape::Upright {
                    cx: 0.0,
                    cy: 0.0,
                    radius,
                    z_min,
                    z_max: g.height,
                };
                let (rings, walls) = if g.wall > 0.0 {
                    (
                        vec![
                            horizontal(0.0, ring, AIR, CONTAINER),
                            horizontal(g.height, ring, CONTAINER, AIR),
                        ],
                        vec![
                            Boundary {
                                shape: upright(g.radius, 0.0),
                                outer: Side::Medium(AIR),
                                inner: Side::Medium(CONTAINER),
                            },
                            Boundary {
                                shape: upright(inner, floor),
                                outer: Side::Medium(CONTAINER),
                                inner: Side::Cavity,
                            },
                        ],
                    )
                } else {
                    (
                        vec![],
                        vec![Boundary {
                            shape: upright(g.radius, 0.0),
                            outer: Side::Medium(AIR),
                            inner: Side::Cavity,
                        }],
                    )
                };
                let surface = Region::Disk {
                    cx: 0.0,
                    cy: 0.0,
                    r2: inner * inner,
                };
                let lo = Vec3::new(-g.radius, -g.radius, 0.0);
                let hi = Vec3::new(g.radius, g.radius, g.height);
                (rings, surface, walls, lo, hi)
            }
            Container::Tank(t) => {
                let surface = Region::Rectangle {
                    half_x: t.half_x,
                    half_y: t.half_y,
                };
                let walls = [
                    (0, t.half_x, t.half_y),
                    (0, -t.half_x, t.half_y),
                    (1, t.half_y, t.half_x),
                    (1, -t.half_y, t.half_x),
                ]
                .map(|(axis, at, half)| Boundary {
                    shape: Shape::Vertical {
                        axis,
                        at,
                        half,
                        z_min: 0.0,
                        z_max: t.height,
                    },
                    outer: Side::Medium(AIR),
                    inner: Side::Cavity,
                })
                .to_vec();
                let lo = Vec3::new(-t.half_x, -t.half_y, 0.0);
                let hi = Vec3::new(t.half_x, t.half_y, height);
                (vec![], surface, walls, lo, hi)
            }
        };
        // The horizontal faces over the inside: the outer base, the floor above a thick bottom,
        // each liquid's surface; then the walls.
        let mut boundaries = rings;
        boundaries.push(horizontal(0.0, surface, AIR, medium_above(0.0)));
        if floor > 0.0 {
            boundaries.push(horizontal(floor, surface, CONTAINER, medium_above(floor)));
        }
        for (k, liquid) in scene.liquids.iter().enumerate() {
            let below = 2 + k as MediumId;
            boundaries.push(horizontal(
                liquid.top,
                surface,
                below,
                medium_above(liquid.top),
            ));
        }
        boundaries.extend(walls);

        let mut objects = Vec::new();
        objects.extend(scene.straws.iter().map(|s| Object::straw(s, floor)));
        objects.extend(scene.coins.iter().map(|c| Object::coin(c, floor)));
        objects.extend(scene.cards.iter().map(Object::card));
        let (lo, hi) = objects.iter().fold((lo, hi), |(lo, hi), o| {
            let (a, b) = o.bounds();
            (lo.min(a), hi.max(b))
        });
        let centre = 0.5 * (lo + hi);
        // A hair larger than the box's half diagonal, so rounding never puts a face outside it.
        let radius = 0.5 * (hi - lo).length() * (1.0 + 1e-9) + 1e-12;
        let mut world = World {
            indices,
            cavity,
            boundaries,
            objects,
            lo,
            hi,
            centre,
            radius,
            max_events,
        };
        // Boundaries with the same index on both sides everywhere are no interfaces at all.
        let all = std::mem::take(&mut world.boundaries);
        world.boundaries = all
            .into_iter()
            .filter(|b| !world.never_refracts(b))
            .collect();
        world
    }

    /// Whether `b` has the same index on both sides at every height.
    fn never_refracts(&self, b: &Boundary) -> bool {
        let n_outer = |z: f64| self.index(self.medium(b.outer, z));
        let n_inner = |z: f64| self.index(self.medium(b.inner, z));
        match b.shape {
            Shape::Horizontal { z, .. } => n_outer(z) == n_inner(z),
            Shape::Upright { z_min, z_max, .. } | Shape::Vertical { z_min, z_max, .. } => {
                // Sides change only at the cavity's band edges: test each band's middle and ends.
                let mut heights = vec![z_min, z_max];
                let mut below = f64::NEG_INFINITY;
                for &(top, _) in &self.cavity {
                    let (a, b) = (below.max(z_min), top.min(z_max));
                    if a <= b {
                        heights.push(0.5 * (a + b));
                    }
                    below = top;
                }
                heights.iter().all(|&z| n_outer(z) == n_inner(z))
            }
        }
    }

    /// The medium on side `side` at height `z`.
    #[inline]
    pub fn medium(&self, side: Side, z: f64) -> MediumId {
        match side {
            Side::Medium(m) => m,
            Side::Cavity => cavity_medium(&self.cavity, z),
        }
    }

    /// The refractive index of medium `m`.
    #[inline]
    pub fn index(&self, m: MediumId) -> f64 {
        self.indices[m as usize]
    }

    /// The boundaries (between media of different index somewhere).
    pub fn boundaries(&self) -> &[Boundary] {
        &self.boundaries
    }

    /// The opaque objects.
    pub fn objects(&self) -> &[Object] {
        &self.objects
    }

    /// The corners of a box holding every boundary and object.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        (self.lo, self.hi)
    }

    /// The indices on the two sides of boundary `b` at `p` for a ray along `d`: the one it comes
    /// through and the one it goes into.
    #[inline]
    fn sides(&self, b: &Boundary, p: Vec3, d: Vec3) -> (f64, f64) {
        let outer = self.index(self.medium(b.outer, p.z));
        let inner = self.index(self.medium(b.inner, p.z));
        if d.dot(b.normal(p)) > 0.0 {
            (inner, outer)
        } else {
            (outer, inner)
        }
    }

    /// The nearest thing `ray` meets ahead: a boundary where the indices differ, or an object
    /// (which wins a tie). `left` is the boundary the ray starts on, having just met it.
    #[inline]
    pub fn nearest(&self, ray: &Ray, left: Option<usize>) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        let mut best_t = f64::INFINITY;
        for (index, b) in self.boundaries.iter().enumerate() {
            for t in b.crossings(ray, left == Some(index)) {
                if t >= best_t {
                    break;
                }
                // A boundary between two fixed media refracts everywhere (those of one index were
                // left out); one beside the cavity only where the layer there differs.
                let refracts = match (b.outer, b.inner) {
                    (Side::Medium(_), Side::Medium(_)) => true,
                    _ => {
                        let (n1, n2) = self.sides(b, ray.at(t), ray.direction);
                        n1 != n2
                    }
                };
                if refracts {
                    best = Some(Hit::Boundary { t, index });
                    best_t = t;
                    break;
                }
            }
        }
        for (index, o) in self.objects.iter().enumerate() {
            if let Some((t, part, color)) = o.hit(ray) {
                if t <= best_t {
                    best = Some(Hit::Object {
                        t,
                        index,
                        part,
                        color,
                    });
                    best_t = t;
                }
            }
        }
        best
    }

    /// The point at distance `t` along `ray` on boundary `b`, put exactly on its plane when it
    /// is a plane (so that no other piece of the same plane is met again a hair away).
    #[inline]
    fn point_on(&self, b: &Boundary, ray: &Ray, t: f64) -> Vec3 {
        let mut p = ray.at(t);
        match b.shape {
            Shape::Horizontal { z, .. } => p.z = z,
            Shape::Vertical { axis, at, .. } => p[axis] = at,
            Shape::Upright { .. } => {}
        }
        p
    }

    /// Traces `ray`, which starts in air outside every object, by the course's law.
    pub fn trace(&self, ray: Ray) -> WorldOutcome {
        self.trace_with(ray, |_| {})
    }

    /// [`World::trace`], telling `on_event` every refraction and total reflection, in order.
    pub fn trace_with(&self, ray: Ray, on_event: impl FnMut(&WorldEvent)) -> WorldOutcome {
        self.trace_limited(ray, self.max_events, on_event)
    }

    /// [`World::trace_with`] with the event limit `max_events` instead of the world's.
    pub fn trace_limited(
        &self,
        ray: Ray,
        max_events: u32,
        mut on_event: impl FnMut(&WorldEvent),
    ) -> WorldOutcome {
        let Some((mut ray, mut length)) = enter_sphere(ray, self.centre, self.radius) else {
            return WorldOutcome::Escaped { events: 0, ray };
        };
        let mut events = 0u32;
        let mut left = None;
        loop {
            match self.nearest(&ray, left) {
                None => return WorldOutcome::Escaped { events, ray },
                Some(Hit::Object {
                    t,
                    index,
                    part,
                    color,
                }) => {
                    let point = ray.at(t);
                    let normal = self.objects[index].normal(part, point);
                    return WorldOutcome::Object {
                        color,
                        point,
                        path_length: length + t,
                        events,
                        object: index,
                        normal: if normal.dot(ray.direction) > 0.0 {
                            -normal
                        } else {
                            normal
                        },
                    };
                }
                Some(Hit::Boundary { t, index }) => {
                    if events == max_events {
                        return WorldOutcome::Dropped;
                    }
                    events += 1;
                    length += t;
                    let b = &self.boundaries[index];
                    let point = self.point_on(b, &ray, t);
                    let normal = b.normal(point);
                    let (n1, n2) = self.sides(b, point, ray.direction);
                    let (outgoing, totally_reflected) = match refract(ray.direction, normal, n1, n2)
                    {
                        Some(d) => (d.normalize(), false),
                        None => (reflect(ray.direction, normal), true),
                    };
                    on_event(&WorldEvent {
                        point,
                        boundary: index,
                        normal,
                        incoming: ray.direction,
                        outgoing,
                        n1,
                        n2,
                        totally_reflected,
                    });
                    ray = Ray {
                        origin: point,
                        direction: outgoing,
                    };
                    left = Some(index);
                }
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

    /// Fresnel tracing: the weight of `ray` that ends on each colour code (index 0 = code 1). At
    /// every interface a branch splits into a reflected part `R` (unpolarised Fresnel
    /// reflectance; all of it under total reflection) and a refracted part `1 − R`. `on_leave` is
    /// told every other end of a branch with its weight: `Some(last straight piece)` for light
    /// leaving the scene, `None` for light abandoned (lighter than `prune_below`, past the event
    /// limit, or past [`FRESNEL_SEGMENTS_PER_RAY`] straight segments in all), so that the weights
    /// told and returned add up to 1. No allocation.
    pub fn trace_fresnel(
        &self,
        ray: Ray,
        prune_below: f64,
        mut on_leave: impl FnMut(Option<Ray>, f64),
    ) -> [f64; COLOR_COUNT] {
        // Depth-first; a thick wall or layers can hold several waiting branches, so the stack is
        // deeper than the one glass of water needs. A branch that finds it full is abandoned.
        const STACK: usize = 32;
        #[derive(Clone, Copy)]
        struct Branch {
            ray: Ray,
            events: u32,
            weight: f64,
            left: Option<usize>,
        }
        let mut weights = [0.0; COLOR_COUNT];
        let Some((start, _)) = enter_sphere(ray, self.centre, self.radius) else {
            on_leave(Some(ray), 1.0);
            return weights;
        };
        let mut stack = [Branch {
            ray: start,
            events: 0,
            weight: 1.0,
            left: None,
        }; STACK];
        let mut top = 1;
        let mut segments = 0;
        while top > 0 {
            top -= 1;
            let mut b = stack[top];
            loop {
                if segments == FRESNEL_SEGMENTS_PER_RAY {
                    on_leave(None, b.weight);
                    for waiting in &stack[..top] {
                        on_leave(None, waiting.weight);
                    }
                    return weights;
                }
                segments += 1;
                match self.nearest(&b.ray, b.left) {
                    None => {
                        on_leave(Some(if b.events == 0 { ray } else { b.ray }), b.weight);
                        break;
                    }
                    Some(Hit::Object { color, .. }) => {
                        weights[color as usize - 1] += b.weight;
                        break;
                    }
                    Some(Hit::Boundary { t, index }) => {
                        if b.events == self.max_events {
                            on_leave(None, b.weight);
                            break;
                        }
                        b.events += 1;
                        let boundary = &self.boundaries[index];
                        let point = self.point_on(boundary, &b.ray, t);
                        let normal = boundary.normal(point);
                        let (n1, n2) = self.sides(boundary, point, b.ray.direction);
                        let reflected = Ray {
                            origin: point,
                            direction: reflect(b.ray.direction, normal),
                        };
                        b.left = Some(index);
                        match refract_with_reflectance(b.ray.direction, normal, n1, n2) {
                            None => b.ray = reflected,
                            Some((d, r)) => {
                                let later = Branch {
                                    ray: reflected,
                                    weight: b.weight * r,
                                    ..b
                                };
                                b.weight -= later.weight;
                                if later.weight >= prune_below && later.weight > 0.0 && top < STACK
                                {
                                    stack[top] = later;
                                    top += 1;
                                } else {
                                    on_leave(None, later.weight);
                                }
                                b.ray = Ray {
                                    origin: point,
                                    direction: d.normalize(),
                                };
                                if b.weight < prune_below || b.weight == 0.0 {
                                    on_leave(None, b.weight);
                                    break;
                                }
                            }
                        }
                    }
                }
            }
        }
        weights
    }
}

impl World {
    /// How a ray enters the liquid (or the container) at event `e`, its first: through a surface
    /// from above, through a wall, through a bottom from below.
    pub fn entry_of(&self, e: &WorldEvent) -> Entry {
        match self.boundaries[e.boundary].shape {
            Shape::Horizontal { .. } if e.incoming.z < 0.0 => Entry::Top,
            Shape::Horizontal { .. } => Entry::Bottom,
            _ => Entry::Wall,
        }
    }

    /// Traces `ray` by the course's law and tells the kind of its light path: how it enters (its
    /// first event) and how many total reflections it undergoes.
    pub fn trace_path_type(&self, ray: Ray) -> (WorldOutcome, LightPathType) {
        self.trace_path_type_limited(ray, self.max_events)
    }

    /// [`World::trace_path_type`] with the event limit `max_events`.
    pub fn trace_path_type_limited(
        &self,
        ray: Ray,
        max_events: u32,
    ) -> (WorldOutcome, LightPathType) {
        let mut kind = LightPathType::DIRECT;
        let outcome = self.trace_limited(ray, max_events, |e| {
            kind.record_entry(self.entry_of(e), e.totally_reflected)
        });
        (outcome, kind)
    }
}

impl World {
    /// Distance from `p` to the nearest object's surface (m).
    pub fn distance_to_objects(&self, p: Vec3) -> f64 {
        self.objects
            .iter()
            .map(|o| o.distance(p))
            .fold(f64::INFINITY, f64::min)
    }
}

impl ImageTracer for World {
    #[inline]
    fn reaches_object(&self, ray: Ray) -> bool {
        self.trace(ray).color() > 0
    }

    #[inline]
    fn image_point(&self, observer: Vec3, u0: Vec3) -> Option<ImagePoint> {
        World::image_point(self, observer, u0)
    }

    fn scene_box(&self) -> (Vec3, Vec3) {
        (self.lo, self.hi)
    }
}
