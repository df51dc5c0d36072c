//! The physics of bentstraw: a five-colour straw standing in a glass of water, seen through refraction.
//!
//! Data flows one way: a [`scene::Scene`] and an observer give rays ([`geometry::Ray`]), the tracer
//! ([`trace`]) follows them through the water's faces ([`interface`]) to the straw, and each ray that
//! arrives becomes an [`image::ImagePoint`]; [`sampling`] chooses the rays so that the straw's image is
//! covered evenly. The observer's own picture comes from [`camera`] and [`picture`] (one ray
//! per pixel, for data) and [`shading`] (an RGB picture for people). The crate does no I/O and
//! prints nothing.
//!
//! A scene can also be read from a scene file's text ([`scene_file`]): the TOML format, checked
//! rule by rule into a plain description. Every scene (the assignment's glass, thick glass, a tank,
//! liquid layers, leaning straws, coins, cards) is traced as a [`world::World`]: media known by id,
//! the boundaries between them, opaque objects; [`tracer::Tracer`] is the assignment's glass built
//! as one, once. Which surface a ray meets first, how it bends there and how a Fresnel split
//! weighs its branches are written once over the number type ([`lanes`]): `f64` for one ray in
//! double precision, eight `f32` lanes for [`packet`], which traces pictures eight rays at a time
//! (same pixels but for rare ones on colour boundaries). Sampling, the eye and stereo models, checking and
//! ray diagrams are written once over small traits that the assignment's glass and a world both
//! implement.
//!
//! The conventions (see `docs/physics.md` in the repository): SI units (metres),
//! origin at the centre of the glass's base, `z` up.

pub mod apparent;
pub mod camera;
pub mod check;
pub mod frame;
pub mod geometry;
pub mod image;
pub mod interface;
pub mod lanes;
pub mod light_path_type;
pub mod packet;
pub mod picture;
pub mod ray_diagram;
pub mod sampling;
pub mod scene;
pub mod scene_file;
pub mod shading;
pub mod trace;
pub mod tracer;
pub mod world;

pub use glam::DVec3 as Vec3;
