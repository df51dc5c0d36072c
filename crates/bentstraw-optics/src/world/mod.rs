//! A scene as data: any container, liquid layers and objects a scene file describes (a glass with
//! thick walls, a tank, oil on water, leaning straws, coins, cards), traced by the same laws as
//! the assignment's glass.
//!
//! The scene is a list of [`Boundary`]s, each between two media (each medium known by an id, its
//! index in a table), and a list of opaque [`Object`]s. A ray carries the id of the medium it
//! travels in; at the nearest boundary ahead it refracts or is totally reflected by Snell's law
//! between the indices on its two sides; an object stops it and gives its colour. In a scene
//! file, a face between media of the same index is no interface (light crosses it unbent, and it
//! is no event): a glass of index 1 traces exactly like walls of no thickness.
//!
//! The assignment's glass is a world too ([`World::assignment`]): one rule for what a ray meets
//! first ([`World::nearest`]) and one course loop serve it and every scene file, for one ray in
//! double precision and for eight in single precision ([`crate::lanes`]).

pub mod boundary;
pub(crate) mod fresnel;
mod nearest;
pub mod object;
mod trace;

use crate::geometry::Ray;
use crate::image::ImagePoint;
use crate::lanes::{Mask, Real};
use crate::profile;
use crate::scene::{Scene, SECTION_NAMES, SECTION_RGB};
use crate::scene_file::{Container, SceneDescription, SceneFileError};
use crate::Vec3;

pub use boundary::{Boundary, MediumId, Region, Shape};
use boundary::{Clip, Edge};
pub use object::{in_arrow, Object, Part, CARD_COLOR, COIN_COLOR, PICTURE_COLOR};
pub use trace::{FresnelStep, FRESNEL_SEGMENTS_PER_PIXEL, FRESNEL_SEGMENTS_PER_RAY};

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

/// The scene ready for tracing: media, boundaries, objects, and the volumes that hold them.
#[derive(Clone, Debug, PartialEq)]
pub struct World {
    /// Refractive index of each medium, by id.
    indices: Vec<f64>,
    /// The media that absorb light (tinted liquids), each with its absorption coefficients
    /// (per metre, red, green, blue).
    tinted: Vec<(MediumId, [f64; 3])>,
    /// Every boundary where light can refract or be totally reflected: the container's and
    /// liquids' faces first, then the transparent solids' faces.
    boundaries: Vec<Boundary>,
    /// How many of the boundaries are the container's and liquids' plain faces (the rest are
    /// solids' and a glass of revolution's curved wall).
    plain: usize,
    /// Those first `plain` boundaries as the lean loop reads them.
    plain_faces: Vec<boundary::PlainFace>,
    /// The lenses inside the container, as the faces they pierce see them.
    lens_holes: Vec<boundary::LensHole>,
    /// Every opaque object.
    objects: Vec<Object>,
    /// What solids make of horizontal faces (each face names its range of them).
    clips: Vec<Clip>,
    /// The transparent solids, each with the range of its faces (all after the plain ones).
    bodies: Vec<Body>,
    /// The edges of the prisms' polygons the clips name.
    edges: Vec<Edge>,
    /// How many whole surfaces the boundaries lie on: codes `0..surfaces` name them, and
    /// `surfaces + j` names object `j` (what a ray has just left).
    surfaces: u32,
    /// Corners of a box holding every boundary and object.
    lo: Vec3,
    hi: Vec3,
    /// A sphere holding the box (rays from afar are first brought to it).
    centre: Vec3,
    radius: f64,
    /// Radius of a circle around the `z` axis holding everything (a ray whose line passes
    /// clearly outside it meets nothing).
    reach: f64,
    /// The same for the container's and liquids' faces and the opaque objects alone (the
    /// solids may stand farther out).
    plain_reach: f64,
    /// Whether any boundary is a vertical plane (rays then need the reciprocals of `dx`, `dy`).
    verticals: bool,
    /// The radius and height of a glass whose walls have no thickness (pictures may draw its
    /// outline: nothing else shows where it is).
    thin_glass: Option<(f64, f64)>,
    /// Most events (refractions and total reflections) a ray may undergo.
    max_events: u32,
    /// The same scene at the middle of each band of white light
    /// ([`crate::spectrum::white_bands`]), when some index depends on the wavelength; empty
    /// otherwise (every band sees this world).
    white_light: Vec<World>,
    /// The unit direction towards the sun, for a scene seen outdoors.
    sun: Option<Vec3>,
}

/// Which faces between media of the same index are kept as events.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum SameIndex {
    /// None: light crosses them unbent and uncounted (scene files: a glass of index 1 is no glass).
    Dropped,
    /// A liquid's faces (the assignment's water at index 1 still has its faces, each an event).
    LiquidFacesKept,
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
pub struct Event {
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
pub enum Outcome {
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
        /// Which part of it.
        part: Part,
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

impl Outcome {
    /// The colour code reached, 0 for none.
    pub fn color(&self) -> u8 {
        match self {
            Outcome::Object { color, .. } => *color,
            _ => 0,
        }
    }

    /// The image point `P = O + L·u0` this outcome makes for the ray from `observer` along unit
    /// `u0`, if it reached an object.
    pub fn image_point(&self, observer: Vec3, u0: Vec3) -> Option<ImagePoint> {
        match *self {
            Outcome::Object {
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

/// A boundary of `shape` with `outer` and `inner` media, its surface and escape side not yet known.
fn piece(shape: Shape, outer: MediumId, inner: MediumId) -> Boundary {
    Boundary {
        shape,
        outer,
        inner,
        surface: 0,
        escape: 0,
        optics: boundary::Optics::default(),
        codes: boundary::Codes::default(),
        holes: [0, 0],
        solid: false,
        body: 0,
    }
}

/// A piece of a container of revolution's wall: `piece`, of the container's body.
fn wall_piece(shape: Shape, outer: MediumId, inner: MediumId) -> Boundary {
    Boundary {
        body: CONTAINER,
        ..piece(shape, outer, inner)
    }
}

/// A face of a transparent solid: `piece` marked as one.
fn solid_piece(shape: Shape, outer: MediumId, inner: MediumId) -> Boundary {
    Boundary {
        solid: true,
        body: inner,
        ..piece(shape, outer, inner)
    }
}

/// A transparent solid as the tracers skip it: the ball holding it, and the range of its faces
/// in the world's list (a line that misses the ball meets none of them).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Body {
    /// The ball's centre.
    pub centre: Vec3,
    /// Its radius², a hair over the solid's reach.
    pub r2: f64,
    /// The range of the solid's faces in the world's boundaries.
    pub faces: [usize; 2],
}

/// The plane `z` over `region`, `below` under it and `above` over it.
fn horizontal(z: f64, region: Region, below: MediumId, above: MediumId) -> Boundary {
    piece(Shape::Horizontal { z, region }, above, below)
}

/// The pieces of a wall between `z_min` and `z_max` with `outside` beyond it and the cavity
/// within: one per layer of the cavity it touches, made by `shape(lo, hi)`.
fn wall_pieces(
    cavity: &[(f64, MediumId)],
    z_min: f64,
    z_max: f64,
    outside: MediumId,
    shape: impl Fn(f64, f64) -> Shape,
) -> Vec<Boundary> {
    layers_between(cavity, z_min, z_max)
        .map(|(lo, hi, medium)| piece(shape(lo, hi), outside, medium))
        .collect()
}

/// The layers of the cavity (`(upper height, medium)`, lowest first) that the heights from
/// `z_min` to `z_max` span: each part's lowest and highest height and its medium.
fn layers_between(
    cavity: &[(f64, MediumId)],
    z_min: f64,
    z_max: f64,
) -> impl Iterator<Item = (f64, f64, MediumId)> + '_ {
    let belows = std::iter::once(f64::NEG_INFINITY).chain(cavity.iter().map(|(top, _)| *top));
    belows
        .zip(cavity)
        .map(move |(below, &(top, medium))| (below.max(z_min), top.min(z_max), medium))
        .filter(|(lo, hi, _)| lo < hi)
}

impl World {
    /// Most events (refractions and total reflections) a ray may undergo.
    pub fn max_events(&self) -> u32 {
        self.max_events
    }

    /// The world `scene` describes, with event limit `max_events`, once the scene is checked by
    /// every rule of a scene file (its fields are public: a description built in code is
    /// checked here as a file's is when read). A face between media of the same index is no
    /// interface (light crosses it unbent, and it is no event): a glass of index 1 traces
    /// exactly like walls of no thickness.
    pub fn new(scene: &SceneDescription, max_events: u32) -> Result<World, Box<SceneFileError>> {
        scene.validate()?;
        let mut world = World::build(scene, max_events, SameIndex::Dropped);
        if scene.disperses() {
            // Each band's own world: media of one index at one wavelength may part at another,
            // and their faces with them.
            world.white_light = crate::spectrum::white_bands()
                .iter()
                .map(|band| {
                    let at = scene.clone().at_wavelength(band.nm);
                    World::build(&at, max_events, SameIndex::Dropped)
                })
                .collect();
        }
        Ok(world)
    }

    /// The scene at the middle of each band of white light, violet first, when some index
    /// depends on the wavelength; empty when none does (white light then sees this world in
    /// every band).
    pub fn white_light(&self) -> &[World] {
        &self.white_light
    }

    /// The world band `band` of white light sees ([`World::white_light`]'s, violet first): this
    /// one where nothing disperses.
    pub fn in_band(&self, band: usize) -> &World {
        self.white_light.get(band).unwrap_or(self)
    }

    /// The world `point`'s ray was traced in: its band's of white light, or this one.
    pub fn of_point(&self, point: &ImagePoint) -> &World {
        point.band.map_or(self, |k| self.in_band(k as usize))
    }

    /// The unit direction towards the sun, when the scene is seen outdoors (against a dark sky
    /// with the sun in it).
    pub fn sun(&self) -> Option<Vec3> {
        self.sun
    }

    /// The assignment's scene as a world: the glass of radius 0.04 m with walls and bottom of no
    /// thickness, its water, its upright straw, traced exactly as the assignment says. Every
    /// water face is an event, even where the water's index is 1, so that the event limit counts
    /// the same faces whatever the index.
    pub fn assignment(scene: &Scene) -> World {
        World::build(
            &SceneDescription::assignment(scene),
            scene.max_events(),
            SameIndex::LiquidFacesKept,
        )
    }

    fn build(scene: &SceneDescription, max_events: u32, same_index: SameIndex) -> World {
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

        // The walls first (they win ties with the horizontal faces at their edges, as the
        // assignment's glass always had it), then the horizontal faces: each liquid's surface,
        // the floor above a thick bottom, the outer base, a glass's rings at its base and rim.
        let mut boundaries = Vec::new();
        // A container of revolution's curved faces, its inner pieces, its base's face, and the
        // ball holding it (with each solid's, by its medium's number).
        let mut curved = Vec::new();
        let mut cavity_disks: Option<Vec<crate::profile::Piece>> = None;
        let mut base_region: Option<Region> = None;
        let mut balls: Vec<(MediumId, Vec3, f64)> = Vec::new();
        let (surface, lo, hi, rings) = match &scene.container {
            Container::Glass(g) => {
                indices[CONTAINER as usize] = g.index;
                let inner = g.radius - g.wall;
                let upright = |radius: f64| {
                    move |z_min: f64, z_max: f64| Shape::Upright {
                        cx: 0.0,
                        cy: 0.0,
                        radius,
                        z_min,
                        z_max,
                    }
                };
                let mut rings = Vec::new();
                if g.wall > 0.0 {
                    boundaries.push(piece(upright(g.radius)(0.0, g.height), AIR, CONTAINER));
                    boundaries.extend(wall_pieces(
                        &cavity,
                        floor,
                        g.height,
                        CONTAINER,
                        upright(inner),
                    ));
                    let ring = Region::Annulus {
                        inner2: inner * inner,
                        outer2: g.radius * g.radius,
                    };
                    rings.push(horizontal(0.0, ring, AIR, CONTAINER));
                    rings.push(horizontal(g.height, ring, CONTAINER, AIR));
                } else {
                    boundaries.extend(wall_pieces(&cavity, 0.0, g.height, AIR, upright(g.radius)));
                }
                let surface = Region::Disk {
                    cx: 0.0,
                    cy: 0.0,
                    radius: inner,
                };
                let lo = Vec3::new(-g.radius, -g.radius, 0.0);
                let hi = Vec3::new(g.radius, g.radius, g.height);
                (surface, lo, hi, rings)
            }
            Container::Tank(t) => {
                for (axis, at, half) in [
                    (0, t.half_x, t.half_y),
                    (0, -t.half_x, t.half_y),
                    (1, t.half_y, t.half_x),
                    (1, -t.half_y, t.half_x),
                ] {
                    boundaries.extend(wall_pieces(&cavity, 0.0, t.height, AIR, |z_min, z_max| {
                        Shape::Vertical {
                            axis,
                            at,
                            half,
                            z_min,
                            z_max,
                        }
                    }));
                }
                let surface = Region::Rectangle {
                    half_x: t.half_x,
                    half_y: t.half_y,
                };
                let lo = Vec3::new(-t.half_x, -t.half_y, 0.0);
                let hi = Vec3::new(t.half_x, t.half_y, height);
                (surface, lo, hi, vec![])
            }
            Container::Revolution(v) => {
                indices[CONTAINER as usize] = v.index;
                let (outer, inner) = (v.outer_pieces(), v.inner_pieces());
                // The cavity's horizontal faces are disks of its radius at their height.
                let inner_radius = |z: f64| profile::radius_at(&inner, z).unwrap_or(0.0);
                let disk = |radius: f64| Region::Disk {
                    cx: 0.0,
                    cy: 0.0,
                    radius,
                };
                cavity_disks = Some(inner.clone());
                // Where two pieces of a profile meet, each reaches a hair past the knot, so that
                // no ray slips between them by rounding (their surfaces agree there).
                let hair = 1e-12;
                for (pieces, is_inner) in [(&outer, false), (&inner, true)] {
                    for p in pieces {
                        let (q_min, q_max) = (p.z0 - hair, p.z1 + hair);
                        let shape = |lo: f64, hi: f64| Shape::Revolution {
                            zc: p.zc,
                            c: p.c,
                            z_min: if lo == p.z0 { q_min } else { lo },
                            z_max: if hi == p.z1 { q_max } else { hi },
                            q_min,
                            q_max,
                        };
                        if is_inner {
                            for (lo, hi, medium) in layers_between(&cavity, p.z0, p.z1) {
                                curved.push(wall_piece(shape(lo, hi), CONTAINER, medium));
                            }
                        } else {
                            curved.push(wall_piece(shape(p.z0, p.z1), AIR, CONTAINER));
                        }
                    }
                }
                let base = v.outer[0][0];
                let (rim_in, rim_out) = (inner_radius(height), v.outer[v.outer.len() - 1][0]);
                let mut rings = Vec::new();
                if rim_in < rim_out {
                    let ring = Region::Annulus {
                        inner2: rim_in * rim_in,
                        outer2: rim_out * rim_out,
                    };
                    rings.push(horizontal(height, ring, CONTAINER, AIR));
                }
                if floor == 0.0 {
                    // A bottom of no thickness: the cavity's disk and the wall's foot.
                    let foot = inner_radius(0.0);
                    let ring = Region::Annulus {
                        inner2: foot * foot,
                        outer2: base * base,
                    };
                    rings.push(horizontal(0.0, ring, AIR, CONTAINER));
                    base_region = Some(disk(foot));
                } else {
                    base_region = Some(disk(base));
                }
                let reach = v.reach();
                let lo = Vec3::new(-reach, -reach, 0.0);
                let hi = Vec3::new(reach, reach, height);
                balls.push((
                    CONTAINER,
                    Vec3::new(0.0, 0.0, height / 2.0),
                    libm::hypot(reach, height / 2.0),
                ));
                (disk(inner_radius(floor)), lo, hi, rings)
            }
        };
        // The cavity's horizontal face at height `z`: a container of revolution's is the disk
        // of its radius there, a glass's or a tank's always the same.
        let surface_at = |z: f64| match &cavity_disks {
            Some(inner) => Region::Disk {
                cx: 0.0,
                cy: 0.0,
                radius: profile::radius_at(inner, z).unwrap_or(0.0),
            },
            None => surface,
        };
        for (k, liquid) in scene.liquids.iter().enumerate() {
            let below = 2 + k as MediumId;
            boundaries.push(horizontal(
                liquid.top,
                surface_at(liquid.top),
                below,
                medium_above(liquid.top),
            ));
        }
        if floor > 0.0 && surface_at(floor).reach() > 0.0 {
            boundaries.push(horizontal(
                floor,
                surface_at(floor),
                CONTAINER,
                medium_above(floor),
            ));
        }
        boundaries.push(horizontal(
            0.0,
            base_region.unwrap_or(surface),
            AIR,
            medium_above(0.0),
        ));
        boundaries.extend(rings);
        // A container of revolution's curved wall after the plain faces, as one body.
        boundaries.extend(curved);
        // Each sphere is a medium of its own, within whatever fills its place without it: inside
        // the container, the layers its height spans (one face piece per layer, its outer
        // medium that layer's); outside it, air. Its poles lie at infinite heights, so that no
        // rounding of a hit's height loses them.
        for sphere in &scene.spheres {
            let inner = indices.len() as MediumId;
            indices.push(sphere.index);
            balls.push((inner, sphere.center, sphere.radius));
            let (c, r) = (sphere.center, sphere.radius);
            let zone = |z_min: f64, z_max: f64| Shape::Sphere {
                centre: c,
                radius: r,
                z_min: if z_min <= c.z - r {
                    f64::NEG_INFINITY
                } else {
                    z_min
                },
                z_max: if z_max >= c.z + r {
                    f64::INFINITY
                } else {
                    z_max
                },
            };
            if !sphere.inside(&scene.container) {
                boundaries.push(solid_piece(zone(c.z - r, c.z + r), AIR, inner));
                continue;
            }
            for (lo, hi, medium) in layers_between(&cavity, c.z - r, c.z + r) {
                boundaries.push(solid_piece(zone(lo, hi), medium, inner));
            }
        }
        // Each prism likewise: its sides cut by the layers they cross, its top and bottom the
        // planes within its polygon (clipped below), between it and what lies above or below.
        let mut edges = Vec::new();
        let mut prism_edges = Vec::new();
        for prism in &scene.prisms {
            let inner = indices.len() as MediumId;
            indices.push(prism.index);
            let (lo, hi) = prism.bounds();
            balls.push((inner, 0.5 * (lo + hi), 0.5 * (hi - lo).length()));
            let corners = prism.counterclockwise();
            let start = edges.len() as u16;
            for k in 0..corners.len() {
                let (a, b) = (corners[k], corners[(k + 1) % corners.len()]);
                edges.push(Edge {
                    ax: a[0],
                    ay: a[1],
                    ex: b[0] - a[0],
                    ey: b[1] - a[1],
                });
            }
            let range = [start, edges.len() as u16];
            prism_edges.push(range);
            let inside = prism.inside(&scene.container);
            let around = |z: f64| if inside { medium_above(z) } else { AIR };
            // Just below the bottom: the floor's material when it stands on a thick bottom.
            let below = if inside && prism.bottom <= floor && floor > 0.0 {
                CONTAINER
            } else if inside && prism.bottom > 0.0 {
                cavity_medium(&cavity, prism.bottom - f64::EPSILON * prism.bottom.abs())
            } else {
                AIR
            };
            let layers: Vec<(f64, f64, MediumId)> = if inside {
                layers_between(&cavity, prism.bottom, prism.top).collect()
            } else {
                vec![(prism.bottom, prism.top, AIR)]
            };
            for k in 0..corners.len() {
                let (a, b) = (corners[k], corners[(k + 1) % corners.len()]);
                let length = libm::hypot(b[0] - a[0], b[1] - a[1]);
                let (ux, uy) = ((b[0] - a[0]) / length, (b[1] - a[1]) / length);
                for &(z_min, z_max, medium) in &layers {
                    let face = Shape::Face {
                        ax: a[0],
                        ay: a[1],
                        ux,
                        uy,
                        length,
                        z_min,
                        z_max,
                    };
                    boundaries.push(solid_piece(face, medium, inner));
                }
            }
            // Top and bottom: the disk round the polygon, clipped to it.
            let (cx, cy) = corners.iter().fold((0.0, 0.0), |(x, y), q| {
                (
                    x + q[0] / corners.len() as f64,
                    y + q[1] / corners.len() as f64,
                )
            });
            let radius = corners
                .iter()
                .map(|q| libm::hypot(q[0] - cx, q[1] - cy))
                .fold(0.0, f64::max)
                * (1.0 + 1e-9);
            let disk = Region::Disk { cx, cy, radius };
            let mut top = horizontal(prism.top, disk, inner, around(prism.top));
            let mut bottom = horizontal(prism.bottom, disk, below, inner);
            for face in [&mut top, &mut bottom] {
                face.solid = true;
                face.body = inner;
                // Marked with the prism's edges; its clip is made with the others below.
                face.holes = range;
            }
            boundaries.push(top);
            boundaries.push(bottom);
        }
        // Each lens: its two faces (caps of spheres, or flat disks) and its rim between them,
        // within the layer it lies in (or air).
        // A lens inside the container may cross liquids' surfaces: each face is then one
        // boundary per layer it may reach, between that layer's heights, and the surfaces it
        // pierces have a hole of its shape.
        let mut clips = Vec::new();
        let mut lens_holes = Vec::new();
        for lens in &scene.lenses {
            let inner = indices.len() as MediumId;
            indices.push(lens.index);
            let reach = lens.reach();
            balls.push((inner, lens.center, reach));
            let (a, c) = (lens.unit_axis(), lens.center);
            let mut layers: Vec<(f64, f64, MediumId)> = if lens.inside(&scene.container) {
                layers_between(&cavity, c.z - reach, c.z + reach).collect()
            } else {
                vec![(c.z - reach, c.z + reach, AIR)]
            };
            // A lens in one medium has its whole faces: no height cuts them.
            if let [(lo, hi, _)] = &mut layers[..] {
                (*lo, *hi) = (f64::NEG_INFINITY, f64::INFINITY);
            }
            if lens.inside(&scene.container) {
                lens_holes.push((
                    c.z - reach,
                    c.z + reach,
                    boundary::LensHole {
                        centre: c,
                        axis: a,
                        rim2: lens.diameter * lens.diameter / 4.0,
                        w1: -lens.thickness / 2.0,
                        r1: lens.radius1,
                        w2: lens.thickness / 2.0,
                        r2: lens.radius2,
                    },
                ));
            }
            // Each face, one piece per layer, between that layer's heights: the piece chooses its
            // crossing among those within its heights (a piece dropped between equal indices
            // hides no other piece's crossing).
            let rim = lens.diameter / 2.0;
            for &(z_min, z_max, outer) in &layers {
                // Face 1 faces −axis, face 2 +axis; a face of radius R has its centre of curvature
                // R along the axis from its vertex, and its cap lies towards the vertex from there.
                for (radius, vertex, outward) in [
                    (lens.radius1, c - lens.thickness / 2.0 * a, -a),
                    (lens.radius2, c + lens.thickness / 2.0 * a, a),
                ] {
                    let shape = if radius == 0.0 {
                        Shape::Disk {
                            centre: vertex,
                            normal: outward,
                            r2: rim * rim,
                            z_min,
                            z_max,
                        }
                    } else {
                        let toward = -radius.signum() * a;
                        // Outwards is away from the centre where the cap's normal there, `toward`,
                        // is the face's outward side.
                        let sign = if toward.dot(outward) > 0.0 { 1.0 } else { -1.0 };
                        Shape::Cap {
                            centre: vertex + radius * a,
                            radius: sign * radius.abs(),
                            toward,
                            rho2: rim * rim,
                            z_min,
                            z_max,
                        }
                    };
                    boundaries.push(solid_piece(shape, outer, inner));
                }
                let (w1, w2) = lens.faces_at(rim);
                if w2 > w1 {
                    let tube = Shape::Tube {
                        centre: c,
                        axis: a,
                        r2: rim * rim,
                        w_min: w1,
                        w_max: w2,
                        z_min,
                        z_max,
                    };
                    boundaries.push(solid_piece(tube, outer, inner));
                }
            }
        }
        // Where faces between media of the same index are dropped, such media are one medium:
        // light cannot tell them apart, and a ray that crossed a dropped face must still know on
        // which side of the next face it is. Each medium takes the id of the first medium of its
        // index (air's, 0, for index 1). The assignment's water keeps its own id: its faces stay.
        // A tinted liquid is a medium of its own whatever its index (light must know when it is
        // inside to be absorbed), and its faces stay: each crossing is an event, unbent where
        // the indices are equal.
        let liquids = 2 + scene.liquids.len() as MediumId;
        let is_liquid = |m: MediumId| (2..liquids).contains(&m);
        let absorption = |m: MediumId| {
            is_liquid(m)
                .then(|| scene.liquids[m as usize - 2].absorption())
                .flatten()
        };
        if same_index == SameIndex::Dropped {
            let one_medium = |m: MediumId| {
                let (n, a) = (indices[m as usize], absorption(m));
                (0..indices.len())
                    .position(|k| indices[k] == n && absorption(k as MediumId) == a)
                    .unwrap_or(m as usize) as MediumId
            };
            for b in &mut boundaries {
                b.outer = one_medium(b.outer);
                b.inner = one_medium(b.inner);
            }
        }
        // Faces with the same medium on both sides are none; faces between media of the same
        // index are kept only as the rule says.
        boundaries.retain(|b| {
            b.outer != b.inner
                && (indices[b.outer as usize] != indices[b.inner as usize]
                    || absorption(b.outer) != absorption(b.inner)
                    || (same_index == SameIndex::LiquidFacesKept
                        && (is_liquid(b.outer) || is_liquid(b.inner))))
        });

        // The faces a solid inside the container pierces (a liquid's surface, the top of a
        // layer, the floor under a prism standing on it) have a hole where it passes: its
        // cross-section there. A prism's own top and bottom are clipped to its polygon.
        for b in &mut boundaries {
            let Shape::Horizontal { z, .. } = b.shape else {
                continue;
            };
            let start = clips.len() as u16;
            if b.solid {
                clips.push(Clip::InsidePolygon(b.holes));
                b.holes = [start, start + 1];
                continue;
            }
            for sphere in scene.spheres.iter().filter(|s| s.inside(&scene.container)) {
                let (c, r) = (sphere.center, sphere.radius);
                if (z - c.z).abs() < r {
                    clips.push(Clip::OutsideDisk {
                        cx: c.x,
                        cy: c.y,
                        r2: r * r - (z - c.z) * (z - c.z),
                    });
                }
            }
            for (prism, range) in scene.prisms.iter().zip(&prism_edges) {
                if prism.inside(&scene.container) && (prism.bottom..=prism.top).contains(&z) {
                    clips.push(Clip::OutsidePolygon(*range));
                }
            }
            for (k, &(lo, hi, _)) in lens_holes.iter().enumerate() {
                if lo < z && z < hi {
                    clips.push(Clip::OutsideLens(k as u16));
                }
            }
            b.holes = [start, clips.len() as u16];
        }

        let mut objects = Vec::new();
        objects.extend(scene.straws.iter().map(|s| Object::straw(s, floor)));
        objects.extend(scene.coins.iter().map(|c| Object::coin(c, floor)));
        objects.extend(scene.cards.iter().map(Object::card));
        let (lo, hi) = objects
            .iter()
            .map(Object::bounds)
            .chain(scene.spheres.iter().map(|s| s.bounds()))
            .chain(scene.prisms.iter().map(|p| p.bounds()))
            .chain(scene.lenses.iter().map(|l| l.bounds()))
            .fold((lo, hi), |(lo, hi), (a, b)| (lo.min(a), hi.max(b)));
        let centre = 0.5 * (lo + hi);
        // Rays from afar start on a sphere round the box: its radius is the box's half diagonal
        // rounded up to whole 5 cm (a hair more first, so rounding never puts a face outside it),
        // so that the last digits of the box do not enter every distance. For the assignment's
        // glass it is 0.15 m.
        let half_diagonal = 0.5 * (hi - lo).length() * (1.0 + 1e-9) + 1e-12;
        let radius = (half_diagonal * 20.0).ceil() / 20.0;
        let reach = boundaries
            .iter()
            .map(Boundary::reach)
            .chain(objects.iter().map(Object::reach))
            .fold(0.0, f64::max);
        let plain_reach = boundaries
            .iter()
            .filter(|b| !b.solid)
            .map(Boundary::reach)
            .chain(objects.iter().map(Object::reach))
            .fold(0.0, f64::max);

        // Whole surfaces: every plane and cylinder a boundary lies on, numbered once.
        let mut keys: Vec<(u8, [f64; 3])> = Vec::new();
        for (index, b) in boundaries.iter_mut().enumerate() {
            let key = b.surface_key();
            b.surface = match keys.iter().position(|k| *k == key) {
                Some(i) => i as u32,
                None => {
                    keys.push(key);
                    keys.len() as u32 - 1
                }
            };
            b.escape = b.escape_side(lo, hi, reach);
            b.optics = boundary::Optics::new(indices[b.outer as usize], indices[b.inner as usize]);
            b.codes = boundary::Codes {
                index: index as f32,
                surface: b.surface as f32,
                inner: b.inner as f32,
                outer: b.outer as f32,
            };
        }
        // A cap lying in the plane of a horizontal boundary is part of that surface.
        for o in &mut objects {
            if let Object::Straw { solid, .. } | Object::Coin(solid) = o {
                if solid.upright() {
                    let top = solid.base.z + solid.length;
                    for (k, z) in [solid.base.z, top].into_iter().enumerate() {
                        solid.cap_surfaces[k] = keys
                            .iter()
                            .position(|key| *key == (0, [z, 0.0, 0.0]))
                            .map(|i| i as u32);
                    }
                }
            }
        }
        let verticals = boundaries
            .iter()
            .any(|b| matches!(b.shape, Shape::Vertical { .. }));
        let plain = boundaries
            .iter()
            .take_while(|b| !b.solid && b.shape.is_plain())
            .count();
        debug_assert!(boundaries[plain..]
            .iter()
            .all(|b| b.solid || !b.shape.is_plain()));
        // Each solid's faces lie together: one body per run of them.
        let mut bodies: Vec<Body> = Vec::new();
        for (k, b) in boundaries.iter().enumerate().skip(plain) {
            match bodies.last_mut() {
                Some(last) if boundaries[last.faces[0]].body == b.body => last.faces[1] = k + 1,
                _ => {
                    let (_, centre, radius) = balls
                        .iter()
                        .find(|(m, _, _)| *m == b.body)
                        .copied()
                        .expect("every solid's ball is known");
                    let r = radius * (1.0 + 1e-9) + 1e-12;
                    bodies.push(Body {
                        centre,
                        r2: r * r,
                        faces: [k, k + 1],
                    });
                }
            }
        }
        let plain_faces = boundaries[..plain]
            .iter()
            .map(|b| boundary::PlainFace {
                shape: b.shape.plain().expect("the first faces are plain"),
                codes: b.codes,
                holes: b.holes,
            })
            .collect();
        // (A tinted liquid merged into an earlier one of its index and tint is met by no ray.)
        let tinted = (2..liquids)
            .filter_map(|m| absorption(m).map(|a| (m, a)))
            .collect();
        World {
            indices,
            tinted,
            boundaries,
            plain,
            plain_faces,
            lens_holes: lens_holes.into_iter().map(|(_, _, hole)| hole).collect(),
            objects,
            clips,
            bodies,
            edges,
            surfaces: keys.len() as u32,
            lo,
            hi,
            centre,
            radius,
            reach,
            plain_reach,
            verticals,
            thin_glass: match &scene.container {
                Container::Glass(g) if g.wall == 0.0 => Some((g.radius, g.height)),
                _ => None,
            },
            max_events,
            white_light: Vec::new(),
            sun: scene.sun.map(|s| s.direction.normalize()),
        }
    }

    /// The same world without its objects, only the faces between media: a light path followed
    /// through whatever stands in its way (the same arithmetic, event for event, as in `self`).
    pub(crate) fn faces_only(&self) -> World {
        World {
            indices: self.indices.clone(),
            tinted: self.tinted.clone(),
            boundaries: self.boundaries.clone(),
            plain_faces: self.plain_faces.clone(),
            lens_holes: self.lens_holes.clone(),
            objects: Vec::new(),
            clips: self.clips.clone(),
            bodies: self.bodies.clone(),
            edges: self.edges.clone(),
            white_light: self.white_light.iter().map(World::faces_only).collect(),
            ..*self
        }
    }

    /// Whether some medium absorbs light (a tinted liquid): pictures then follow how much.
    pub fn absorbs(&self) -> bool {
        !self.tinted.is_empty()
    }

    /// Adds to `density` (per channel) the light absorbed along a piece of length `t` in
    /// `medium`, in the lanes of `mask`: a ray keeps `exp(−density)` of each channel.
    #[inline(always)]
    pub(crate) fn absorb_lanes<R: Real>(
        &self,
        medium: R,
        t: R,
        mask: R::Mask,
        density: &mut [R; 3],
    ) {
        for &(m, alpha) in &self.tinted {
            let here = mask.and(medium.eq(R::splat(m as f64)));
            if here.any() {
                for c in 0..3 {
                    density[c] = R::select(here, density[c] + t * R::splat(alpha[c]), density[c]);
                }
            }
        }
    }

    /// Whether the world has only plain faces (the container's and liquids' planes, upright
    /// sides and tank walls): no transparent solid, no curved wall of revolution.
    pub(crate) fn plain_only(&self) -> bool {
        self.bodies.is_empty() && self.clips.is_empty()
    }

    /// The refractive index of medium `m`.
    #[inline]
    pub fn index(&self, m: MediumId) -> f64 {
        self.indices[m as usize]
    }

    /// The boundaries, each between two media (walls cut where the medium inside them changes).
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

    /// The radius and height of the glass, if its walls have no thickness: light does not see
    /// them, so a picture may draw the glass's outline to show where it stands.
    pub fn thin_glass(&self) -> Option<(f64, f64)> {
        self.thin_glass
    }

    /// The centre and radius of a sphere holding everything (a ray from afar is first brought
    /// to it: no boundary or object lies before it).
    pub fn bounding_sphere(&self) -> (Vec3, f64) {
        (self.centre, self.radius)
    }

    /// Whether any interface bends light (media of different indices meet somewhere).
    pub fn refracts(&self) -> bool {
        self.boundaries
            .iter()
            .any(|b| self.index(b.outer) != self.index(b.inner))
    }

    /// The code of what a ray has just left, for the tracers: boundary `index`'s surface.
    #[inline(always)]
    pub fn surface_code(&self, index: usize) -> u32 {
        self.boundaries[index].surface
    }

    /// The code of object `index` as what a ray has just left.
    #[inline(always)]
    pub fn object_code(&self, index: usize) -> u32 {
        self.surfaces + index as u32
    }
}

impl World {
    /// How many colour codes the world's objects can show, counted from code 1: 5 for straws
    /// alone (their bands), 6 with a coin, 8 with a card and its picture.
    pub fn color_codes(&self) -> usize {
        self.objects
            .iter()
            .map(|o| match o {
                Object::Straw { .. } => 5,
                Object::Coin(_) => COIN_COLOR as usize,
                Object::Card { .. } => COLOR_COUNT,
            })
            .max()
            .unwrap_or(0)
    }

    /// Distance from `p` to the nearest object's surface (m).
    pub fn distance_to_objects(&self, p: Vec3) -> f64 {
        self.objects
            .iter()
            .map(|o| o.distance(p))
            .fold(f64::INFINITY, f64::min)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::REFERENCES;

    /// The assignment's glass as a world: the water's side, surface and bottom, in that order
    /// (the order of the assignment's ties), the side and the bottom faces of the scene's hull
    /// (light leaving through them escapes), the surface not; one surface each; the straw's
    /// bottom cap on the bottom's plane.
    #[test]
    fn the_assignments_glass_is_three_faces_and_a_straw() {
        let world = World::assignment(&REFERENCES[1].scene(1.333));
        let b = world.boundaries();
        assert_eq!(b.len(), 3);
        assert!(
            matches!(b[0].shape, Shape::Upright { z_min, z_max, .. } if z_min == 0.0 && z_max == 0.15)
        );
        assert!(matches!(b[1].shape, Shape::Horizontal { z, .. } if z == 0.15));
        assert!(matches!(b[2].shape, Shape::Horizontal { z, .. } if z == 0.0));
        assert_eq!(
            b.iter()
                .map(|b| (b.outer, b.inner, b.escape))
                .collect::<Vec<_>>(),
            [(AIR, 2, 1), (AIR, 2, 0), (2, AIR, -1)]
        );
        assert_eq!(b.iter().map(|b| b.surface).collect::<Vec<_>>(), [0, 1, 2]);
        let Object::Straw { solid, .. } = world.objects()[0] else {
            panic!("a straw")
        };
        assert_eq!(solid.cap_surfaces, [Some(2), None]);
        // With index 1 the water keeps its faces; without water there are none.
        assert_eq!(
            World::assignment(&REFERENCES[1].scene(1.0))
                .boundaries()
                .len(),
            3
        );
        let dry = Scene::new(0.0, 0.0, 0.0, 1.333, 10).unwrap();
        assert!(World::assignment(&dry).boundaries().is_empty());
    }

    /// A ray that meets a sphere first enters through a solid: its path says so, in its own
    /// words and colour; one that misses it enters the water as before.
    #[cfg(feature = "scene-file")]
    #[test]
    fn a_path_through_a_sphere_enters_through_a_solid() {
        use crate::geometry::Ray;
        use crate::light_path_type::Entry;
        let d = SceneDescription::from_toml(
            "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.15\n\n\
             [[liquid]]\nname = \"water\"\nindex = 1.333\ntop = 0.1\n\n\
             [[straw]]\nx = 0.0\ny = 0.0\n\n\
             [[sphere]]\ncenter = [0.1, 0.0, 0.05]\nradius = 0.02\nindex = 1.5\n",
        )
        .unwrap();
        let world = World::new(&d, 10).unwrap();
        let eye = Vec3::new(0.3, 0.0, 0.05);
        let (outcome, kind) = world.trace_path_type(Ray::new(eye, Vec3::new(-1.0, 0.0, 0.0)));
        assert!(matches!(outcome, Outcome::Object { .. }), "{outcome:?}");
        assert_eq!(kind.entry, Entry::Solid);
        assert_eq!(kind.key(), "solid");
        assert_eq!(kind.to_string(), "through a transparent solid");
        let (_, past) = world.trace_path_type(Ray::new(eye, Vec3::new(-0.3, 0.035, 0.0)));
        assert_eq!(past.entry, Entry::Wall);
        assert_ne!(kind.rgb(), past.rgb());
    }
}
