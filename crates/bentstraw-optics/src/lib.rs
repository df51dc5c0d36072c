//! The physics of bentstraw: what refraction does to what we see, for a five-colour straw in a
//! glass of water and any scene a scene file describes.
//!
//! Data flows one way: a scene becomes a [`world::World`] (media, the boundaries between them,
//! opaque objects), built once: from the assignment's numbers ([`scene::Scene`], through
//! [`world::World::assignment`]) or from a scene file's description ([`scene_file`], the TOML
//! format checked rule by rule). Rays ([`geometry::Ray`]) from an observer are traced through it
//! by the course's law (refraction or total reflection at each boundary, [`interface`]) or split
//! by the Fresnel reflectance; each ray that reaches an object becomes an
//! [`image::ImagePoint`], and [`sampling`] chooses the rays so that the image is covered evenly.
//! From the points come the apparent-position models ([`apparent`]), the check of someone else's
//! points ([`check`]) and ray diagrams ([`ray_diagram`]); the observer's own picture comes from
//! [`camera`] and [`picture`] (one ray per pixel, for data) and [`shading`] (an RGB picture for
//! people), and a live view's frame from [`frame`]. Every one of them takes a `World`: one door.
//!
//! Which surface a ray meets first, how it bends there and how a Fresnel split weighs its
//! branches are written once over the number type ([`lanes`]): `f64` for one ray in double
//! precision, eight `f32` lanes for [`packet`], which traces pictures eight rays at a time (same
//! pixels but for rare ones on colour boundaries). The crate does no I/O and prints nothing.
//!
//! The conventions (see `docs/physics.md` in the repository): SI units (metres),
//! origin at the centre of the glass's base, `z` up.

#![warn(missing_docs)]

pub mod apparent;
pub mod camera;
pub mod check;
pub mod dispersion;
pub mod frame;
pub mod geometry;
pub mod image;
pub mod interface;
pub mod lanes;
pub mod light_path_type;
pub mod packet;
pub mod parallel;
pub mod picture;
pub mod profile;
pub mod rainbow;
pub mod ray_diagram;
pub mod record;
pub mod rule;
pub mod sampling;
pub mod scene;
pub mod scene_file;
pub mod setup;
pub mod shading;
pub mod sketch;
pub mod spectrum;
pub mod text;
pub mod view;
pub mod world;

pub use glam::DVec3 as Vec3;
