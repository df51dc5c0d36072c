//! The observer's picture for people: anti-aliased, the straw in its section colours, a light
//! backdrop seen through (and reflected by) the water, the glass outlined; and the point cloud seen
//! through the same camera, for comparison.
//!
//! Everything is computed in linear light and encoded as sRGB bytes at the end; the section
//! colours are display (sRGB) values, so a pixel wholly on one section, facing the light,
//! shows exactly that colour.
//!
//! The surroundings (chosen here; the assignment says nothing of them):
//! - a vertical wall behind the glass, opposite the observer: the plane at [`WALL_DISTANCE`] behind
//!   the glass's axis, facing the observer horizontally, up to `z =` [`WALL_TOP`];
//! - a floor (the table the glass stands on) at `z = 0`, only when the observer is above it: an
//!   observer below `z = 0` (reference 4) looks through a glass table, so the floor is left out and
//!   the wall reaches down to `−`[`WALL_TOP`];
//! - a pale sky everywhere else.
//!
//! Rays that leave the scene (in course mode the one ray, in Fresnel mode every escaping branch with
//! its weight) take the colour of the surroundings where their last straight piece meets them, so the
//! checkerboard seen through the water is distorted as in reality, and the water's faces show
//! faintly by what they reflect. The glass (index 1, invisible) is drawn as an outline: its rim and
//! base circles and its two silhouette lines, straight projections, the far side fainter.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Arc;

use crate::parallel::*;

use crate::camera::Camera;
use crate::geometry::Ray;
use crate::image::ImagePoint;
use crate::packet::{BranchEnd, FresnelWave, PacketTracer};
#[cfg(test)]
use crate::world::{FresnelStep, Outcome, FRESNEL_SEGMENTS_PER_RAY};
use crate::world::{Object, Part, World, COLOR_RGB, FRESNEL_SEGMENTS_PER_PIXEL};
use crate::Vec3;

/// Distance of the backdrop wall behind the glass's axis (m).
pub const WALL_DISTANCE: f64 = 0.15;
/// Height of the backdrop wall's top edge (m).
pub const WALL_TOP: f64 = 0.45;
/// How far below the floor (m) a ray may start and still meet it: rays out of the water's bottom
/// start on `z = 0` only to rounding.
pub const FLOOR_TOLERANCE: f64 = 1e-6;
/// Side of one checkerboard square (m), half the glass's radius.
pub const CHECKER_SIDE: f64 = 0.02;

/// What lies behind the glass.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Backdrop {
    /// A plain light background, slightly lighter upwards (so that the water's faces still show).
    Plain,
    /// A checkerboard wall and floor.
    Checker,
}

/// How rays are followed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ShadingMode {
    /// The course's law: one ray, refracted or totally reflected at each water face.
    Course,
    /// Fresnel splitting: reflected and refracted branches weighted by the Fresnel reflectance;
    /// branches lighter than `prune_below` are abandoned.
    Fresnel {
        /// Pruning threshold on a branch's weight.
        prune_below: f64,
    },
}

/// Everything that decides how the picture looks, beside the scene and camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadingOptions {
    /// Course or Fresnel tracing.
    pub mode: ShadingMode,
    /// What lies behind the glass.
    pub backdrop: Backdrop,
    /// Samples per pixel side (`samples²` rays per pixel); 1 traces the pixel centre only.
    pub samples: u32,
    /// Adaptive sampling (true): every pixel's centre first, then `samples²` rays only where a
    /// pixel's centre and a neighbour's differ (an edge); or (false) `samples²` rays at every
    /// pixel.
    pub adaptive: bool,
    /// Whether to draw the glass's outline.
    pub outline: bool,
    /// White light (every band of the spectrum, each traced at its own wavelength) rather than
    /// light of the one wavelength the scene is traced at.
    pub white: bool,
}

/// An RGB picture, 8-bit sRGB, row-major, 3 bytes per pixel, row 0 at the top.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct RgbPicture {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width × height × 3` bytes.
    pub pixels: Vec<u8>,
}

impl RgbPicture {
    /// The colour of pixel row `i`, column `j`.
    pub fn pixel(&self, i: u32, j: u32) -> [u8; 3] {
        let k = 3 * (i as usize * self.width as usize + j as usize);
        [self.pixels[k], self.pixels[k + 1], self.pixels[k + 2]]
    }
}

/// sRGB display value (0..1) to linear light.
#[inline]
pub fn srgb_to_linear(c: f64) -> f64 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        libm::pow((c + 0.055) / 1.055, 2.4)
    }
}

/// Linear light to an sRGB display value (0..1), clamped.
#[inline]
pub fn linear_to_srgb(c: f64) -> f64 {
    let c = c.clamp(0.0, 1.0);
    if c <= 0.0031308 {
        12.92 * c
    } else {
        1.055 * libm::pow(c, 1.0 / 2.4) - 0.055
    }
}

/// Entries of the tables that replace `powf` in the picture's inner loops (a picture needs a few
/// conversions per ray; `powf` was most of a picture's time). Linear interpolation between entries
/// is within 2e-5 of the exact curve, a hundredth of one 8-bit level.
const CURVE_STEPS: usize = 4096;

/// `f` sampled at `CURVE_STEPS + 1` evenly spaced points of `[0, 1]`.
fn curve_table(f: fn(f64) -> f64) -> CurveTable {
    Box::new(std::array::from_fn(|k| f(k as f64 / CURVE_STEPS as f64)))
}

/// `table`'s curve at `c` (clamped to `[0, 1]`), interpolated linearly.
#[inline]
fn lookup(table: &[f64; CURVE_STEPS + 1], c: f64) -> f64 {
    let x = c.clamp(0.0, 1.0) * CURVE_STEPS as f64;
    // Through `i32`: one instruction on x86-64, where `as usize` takes a branch and several (the
    // same entry: `x` is in `[0, CURVE_STEPS]`, or NaN, which both make 0).
    let k = (x as i32).min(CURVE_STEPS as i32 - 1) as usize;
    let t = x - k as f64;
    table[k] + t * (table[k + 1] - table[k])
}

type CurveTable = Box<[f64; CURVE_STEPS + 1]>;
static TO_LINEAR: std::sync::OnceLock<CurveTable> = std::sync::OnceLock::new();
static TO_SRGB: std::sync::OnceLock<CurveTable> = std::sync::OnceLock::new();

/// [`srgb_to_linear`] by table, for the inner loops.
#[inline]
fn srgb_to_linear_fast(c: f64) -> f64 {
    lookup(TO_LINEAR.get_or_init(|| curve_table(srgb_to_linear)), c)
}

/// [`linear_to_srgb`] by table, for the inner loops.
#[inline]
fn linear_to_srgb_fast(c: f64) -> f64 {
    lookup(to_srgb_table(), c)
}

/// The table of [`linear_to_srgb_fast`], for a loop that converts many colours to look up once
/// (each look-up is an atomic load).
#[inline]
fn to_srgb_table() -> &'static [f64; CURVE_STEPS + 1] {
    TO_SRGB.get_or_init(|| curve_table(linear_to_srgb))
}

fn linear(rgb: [f64; 3]) -> [f64; 3] {
    rgb.map(srgb_to_linear_fast)
}

fn mix(a: [f64; 3], b: [f64; 3], t: f64) -> [f64; 3] {
    [
        a[0] + (b[0] - a[0]) * t,
        a[1] + (b[1] - a[1]) * t,
        a[2] + (b[2] - a[2]) * t,
    ]
}

/// Square of the distance (m) over which the checkerboards' contrast halves.
const FADE2: f64 = 0.6 * 0.6;

/// `x.floor()` as an integer, inline (`f64::floor` is a call into libm on the baseline target);
/// `x` is a plane coordinate in squares, far inside `i64`.
#[inline]
fn floor(x: f64) -> i64 {
    let t = x as i64;
    t - i64::from(x < t as f64)
}

/// The wall, floor and sky around the scene, placed for one observer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surroundings {
    backdrop: Backdrop,
    /// Horizontal unit vector from the glass's axis towards the observer; the wall faces it.
    toward_eye: Vec3,
    /// Horizontal unit vector along the wall.
    along_wall: Vec3,
    /// Whether there is a floor (the observer is above `z = 0`).
    floor: bool,
    /// The floor's and the wall's squares.
    floor_squares: Checker,
    wall_squares: Checker,
    /// Linear colours of the sky at the horizon and straight up; of the plain backdrop looking
    /// straight down and straight up.
    sky: [[f64; 3]; 2],
    plain: [f64; 2],
    /// The unit direction towards the sun, outdoors: then only the dark sky and the sun.
    sun: Option<Vec3>,
    /// The cosine of the sun's angular radius.
    sun_cos: f64,
}

/// The sun's angular radius (degrees): its disc is 0.533° across.
pub const SUN_ANGULAR_RADIUS_DEG: f64 = 0.2665;
/// The sun's radiance against a white surface's 1, in every channel. Far less than the true
/// ratio (some 10⁵) but enough that light a water drop sends back after one or two partial
/// reflections inside it (a few per cent of the sun's, then a few thousandths) shows against the
/// dark sky, the first bow's colours about full and the second bow's dimmer.
pub const SUN_RADIANCE: f64 = 60.0;
/// The dark sky around the sun, in linear light, at the horizon and straight up (a dusk sky's
/// deep blue, lighter low down so that a drop shows by what it refracts).
const DARK_SKY: [[f64; 3]; 2] = [[0.018, 0.022, 0.036], [0.002, 0.003, 0.008]];

/// A checkerboard's two squares and their average, in linear light (worked out once per picture,
/// not per ray).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Checker {
    light: [f64; 3],
    dark: [f64; 3],
    average: [f64; 3],
}

impl Checker {
    /// The squares of display (sRGB) colours `light` and `dark`.
    fn new(light: [f64; 3], dark: [f64; 3]) -> Checker {
        let exact = |c: [f64; 3]| c.map(srgb_to_linear);
        Checker {
            light: exact(light),
            dark: exact(dark),
            average: exact(mix(light, dark, 0.5)),
        }
    }

    /// Linear colour at plane coordinates `(a, b)` (metres), averaged over the patch of
    /// half-widths `(ha, hb)` around it (zero: the square at the point); the contrast shrinks by
    /// `fade` (far squares would only alias).
    #[inline(always)]
    fn at(&self, a: f64, b: f64, ha: f64, hb: f64, fade: f64) -> [f64; 3] {
        // The light squares are where a·b's square wave (±1 per square along each axis) is +1;
        // over a patch, the product's mean is the product of the two waves' means.
        let k = 1.0 / CHECKER_SIDE;
        let wave = square_wave_mean(a * k, ha * k) * square_wave_mean(b * k, hb * k);
        let light = 0.5 + 0.5 * wave;
        let square = mix(self.dark, self.light, light);
        mix(self.average, square, fade)
    }
}

/// The mean over `[x − h, x + h]` of the square wave that is +1 where `floor(x)` is even and −1
/// where it is odd: the change of its integral (a triangle wave) over the interval, divided by
/// the interval's length; the wave's value at `x` for a vanishing interval.
#[inline(always)]
fn square_wave_mean(x: f64, h: f64) -> f64 {
    if h < 1e-6 {
        return if floor(x) & 1 == 0 { 1.0 } else { -1.0 };
    }
    // ∫₀ˣ wave = 1 − |x mod 2 − 1|.
    let integral = |x: f64| 1.0 - ((x - 2.0 * floor(0.5 * x) as f64) - 1.0).abs();
    (integral(x + h) - integral(x - h)) / (2.0 * h)
}

impl Surroundings {
    /// The surroundings of `backdrop` kind for an observer at `eye`.
    pub fn new(backdrop: Backdrop, eye: Vec3) -> Surroundings {
        let h = Vec3::new(eye.x, eye.y, 0.0);
        let toward_eye = if h.length() > 1e-9 {
            h.normalize()
        } else {
            Vec3::X
        };
        Surroundings {
            backdrop,
            toward_eye,
            along_wall: Vec3::Z.cross(toward_eye),
            floor: eye.z > 0.0,
            floor_squares: Checker::new([0.95, 0.92, 0.86], [0.70, 0.63, 0.55]),
            wall_squares: Checker::new([0.96, 0.96, 0.95], [0.66, 0.72, 0.84]),
            sky: [
                [0.86, 0.91, 0.97].map(srgb_to_linear),
                [0.97, 0.98, 1.0].map(srgb_to_linear),
            ],
            plain: [srgb_to_linear(0.80), srgb_to_linear(0.97)],
            sun: None,
            sun_cos: SUN_ANGULAR_RADIUS_DEG.to_radians().cos(),
        }
    }

    /// These surroundings outdoors under the sun in the unit direction `sun`, if any: a dark sky
    /// with the sun's disc in it, in place of the wall, the floor and the backdrop.
    pub fn under_sun(self, sun: Option<Vec3>) -> Surroundings {
        Surroundings {
            sun,
            floor: self.floor && sun.is_none(),
            ..self
        }
    }

    /// Whether the surroundings have a floor at `z = 0`.
    pub fn has_floor(&self) -> bool {
        self.floor
    }

    /// Horizontal unit normal of the wall, pointing towards the observer.
    pub fn wall_normal(&self) -> Vec3 {
        self.toward_eye
    }

    /// What a ray from `o` along `d` (in air, leaving the scene; `d` need not be a unit vector)
    /// meets, and how far along it in units of `d`: the nearer of the floor and the wall, else
    /// the sky (or the plain backdrop).
    #[inline(always)]
    fn meet(&self, o: Vec3, d: Vec3) -> (Region, f64) {
        if self.backdrop == Backdrop::Plain || self.sun.is_some() {
            return (Region::Sky, f64::INFINITY);
        }
        let mut best = (Region::Sky, f64::INFINITY);
        // A ray leaving the water's bottom starts on z = 0 to rounding (a hair below it in single
        // precision): it still meets the floor there.
        if self.floor && d.z < 0.0 && o.z >= -FLOOR_TOLERANCE {
            let t = (-o.z / d.z).max(0.0);
            // The floor ends at the wall.
            if (o + t * d).dot(self.toward_eye) >= -WALL_DISTANCE {
                best = (Region::Floor, t);
            }
        }
        let s = d.dot(self.toward_eye);
        if s < 0.0 {
            let t = (-WALL_DISTANCE - o.dot(self.toward_eye)) / s;
            if t >= 0.0 && t < best.1 {
                let z = o.z + t * d.z;
                let bottom = if self.floor { 0.0 } else { -WALL_TOP };
                if z >= bottom && z <= WALL_TOP {
                    best = (Region::Wall, t);
                }
            }
        }
        best
    }

    /// Linear RGB of what `ray` (in air, leaving the scene) meets.
    // Inline: a call would store the ray the packet tracer just made and load it back at once,
    // in wider pieces than it was stored (a stall on every one of millions of calls).
    #[inline(always)]
    pub fn radiance(&self, ray: &Ray) -> [f64; 3] {
        let (o, d) = (ray.origin, ray.direction);
        let (region, t) = self.meet(o, d);
        self.colour_at(region, o, d, t, 0.0, 0.0, d.z)
    }

    /// The surroundings seen by a whole pixel from the eye `o`: its centre's direction `d` (any
    /// length) and the changes `dc`, `dr` of that direction from one pixel column and row to the
    /// next. On the floor and the wall this is the checkerboard averaged over the patch the pixel
    /// covers (in closed form, instead of tracing many rays through the pixel).
    pub fn radiance_over_pixel(&self, o: Vec3, d: Vec3, dc: Vec3, dr: Vec3) -> [f64; 3] {
        let (region, t) = self.meet(o, d);
        // The plane's normal; the pixel's corners move along it by d's change, so their points
        // on the plane move by t·(change − d·(n·change)/(n·d)).
        let n = match region {
            Region::Floor => Vec3::Z,
            Region::Wall => self.toward_eye,
            Region::Sky | Region::Scene => {
                return self.colour_at(region, o, d, t, 0.0, 0.0, d.z / d.length())
            }
        };
        let on_plane = |change: Vec3| t * (change - d * (n.dot(change) / n.dot(d)));
        let (pc, pr) = (on_plane(dc), on_plane(dr));
        let (axis_a, axis_b) = match region {
            Region::Floor => (Vec3::X, Vec3::Y),
            _ => (self.along_wall, Vec3::Z),
        };
        let half = |axis: Vec3| 0.5 * (pc.dot(axis).abs() + pr.dot(axis).abs());
        self.colour_at(region, o, d, t, half(axis_a), half(axis_b), 0.0)
    }

    /// Linear RGB of `region` where the ray `o + t·d` meets it, its checkerboard averaged over a
    /// patch of half-widths `(ha, hb)` along the plane's two axes (zero: the colour at the point);
    /// the sky's colour depends only on `up`, the height of the ray's unit direction.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn colour_at(
        &self,
        region: Region,
        o: Vec3,
        d: Vec3,
        t: f64,
        ha: f64,
        hb: f64,
        up: f64,
    ) -> [f64; 3] {
        match region {
            Region::Floor => {
                let p = o + t * d;
                let fade = FADE2 / (FADE2 + p.x * p.x + p.y * p.y);
                self.floor_squares.at(p.x, p.y, ha, hb, fade)
            }
            Region::Wall => {
                let p = o + t * d;
                let u = p.dot(self.along_wall);
                // Fading as 1 / (1 + (u / 0.6)²), written with one division.
                let fade = FADE2 / (FADE2 + u * u);
                self.wall_squares.at(u, p.z, ha, hb, fade)
            }
            Region::Sky | Region::Scene => {
                if let Some(sun) = self.sun {
                    let cos = sun.dot(d) / d.length();
                    if cos >= self.sun_cos {
                        [SUN_RADIANCE; 3]
                    } else {
                        mix(DARK_SKY[0], DARK_SKY[1], up.abs().min(1.0))
                    }
                } else if self.backdrop == Backdrop::Plain {
                    // A gentle vertical gradient: flat enough to be "plain", enough for the water
                    // to show.
                    let [down, top] = self.plain;
                    [down + (top - down) * (0.5 + 0.5 * up); 3]
                } else {
                    mix(self.sky[0], self.sky[1], up.max(0.0))
                }
            }
        }
    }
}

/// What a pixel's centre ray met, as the picture's second pass needs to know it: the scene
/// (anything of the glass or straw), or else, straight from the eye, the floor, the wall or the
/// sky.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[repr(u8)]
enum Region {
    #[default]
    Scene = 0,
    Floor = 1,
    Wall = 2,
    Sky = 3,
}

/// Unit direction of the light that shades the straw (from the observer's side, above, left).
fn light_direction(s: &Surroundings) -> Vec3 {
    (s.toward_eye + 0.8 * Vec3::Z + 0.5 * s.toward_eye.cross(Vec3::Z)).normalize()
}

/// Linear colour of colour code `color` at `point` of part `part` of object `object` of
/// `world`, gently shaded by `light` (a card shows the side facing the eye `eye`).
fn object_radiance(
    world: &World,
    light: Vec3,
    eye: Vec3,
    color: u8,
    (object, part): (usize, Part),
    point: Vec3,
) -> [f64; 3] {
    let o = &world.objects()[object];
    let mut normal = o.normal(part, point);
    if matches!(o, Object::Card { .. }) && normal.dot(eye - point) < 0.0 {
        normal = -normal;
    }
    let shade = 0.62 + 0.38 * normal.dot(light).max(0.0);
    linear_colour(color).map(|c| c * shade)
}

/// Colour code `color`'s colour in linear light (converted once, not at every ray's end).
#[inline(always)]
fn linear_colour(color: u8) -> [f64; 3] {
    static LINEAR: std::sync::OnceLock<Vec<[f64; 3]>> = std::sync::OnceLock::new();
    LINEAR.get_or_init(|| COLOR_RGB.iter().map(|&c| linear(c)).collect())[color as usize - 1]
}

/// Linear colour seen along one ray of `world`, traced in double precision: the reference the
/// packet-traced pictures are checked against.
#[cfg(test)]
fn sample(
    world: &World,
    surroundings: &Surroundings,
    light: Vec3,
    mode: ShadingMode,
    ray: Ray,
) -> [f64; 3] {
    match mode {
        ShadingMode::Course => {
            let mut last = ray;
            let outcome = world.trace_with(ray, |e| {
                last = Ray {
                    origin: e.point,
                    direction: e.outgoing,
                }
            });
            match outcome {
                Outcome::Object {
                    color,
                    point,
                    object,
                    part,
                    ..
                } => object_radiance(world, light, ray.origin, color, (object, part), point),
                Outcome::Escaped { .. } => surroundings.radiance(&last),
                // Light that needs more events than allowed is not followed: shown dark.
                Outcome::Dropped => [0.05; 3],
            }
        }
        ShadingMode::Fresnel { prune_below } => {
            let mut acc = [0.0; 3];
            let mut add = |c: [f64; 3], w: f64| {
                for k in 0..3 {
                    acc[k] += w * c[k];
                }
            };
            world.fresnel_steps::<false>(ray, prune_below, FRESNEL_SEGMENTS_PER_RAY, |step| {
                match step {
                    FresnelStep::Object {
                        color,
                        point,
                        object,
                        part,
                        weight,
                        ..
                    } => add(
                        object_radiance(world, light, ray.origin, color, (object, part), point),
                        weight,
                    ),
                    FresnelStep::Escaped { ray, weight, .. } => {
                        add(surroundings.radiance(&ray), weight)
                    }
                    // Dropped and pruned weight is light not followed: it adds nothing (dark).
                    _ => {}
                }
            });
            acc
        }
    }
}

/// A deterministic pseudo-random number in `[0, 1)` from `key` (SplitMix64), for sample jitter.
#[inline]
fn jitter(key: u64) -> f64 {
    let mut z = key.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 53) as f64
}

/// Largest difference (sRGB, 0..1, any channel) between a pixel's centre and a neighbour's below
/// which the pixel is taken as smooth and not supersampled.
pub const SMOOTH_CONTRAST: f64 = 2.0 / 255.0;

/// The picture of `scene` through `camera` for people (see the module's documentation).
///
/// Every pixel centre is traced first. Where a pixel differs from a neighbour by more than
/// [`SMOOTH_CONTRAST`] (an edge), it is replaced by the average of `samples²` rays, one per cell of
/// a `samples × samples` grid over the pixel, jittered inside its cell (deterministically); but an
/// edge whose neighbourhood sees only the floor or only the wall, straight from the eye (most of a
/// picture's edges: the squares past the glass), gets the checkerboard's exact mean over the patch
/// the pixel covers instead, more accurate than the samples and cheaper. Smooth pixels keep their
/// centre: the picture is then the same as a full supersampling to within a few grey levels,
/// several times faster.
pub fn shaded_picture(world: &World, camera: &Camera, options: &ShadingOptions) -> RgbPicture {
    let mut picture = RgbPicture::default();
    shaded_picture_into(
        world,
        camera,
        options,
        &mut ShadingBuffers::default(),
        &mut picture,
    );
    picture
}

/// How the ends of a picture's branches are shaded.
struct EndShader<'a> {
    world: &'a World,
    surroundings: &'a Surroundings,
    light: Vec3,
    /// Whether rays split (Fresnel mode).
    split: bool,
    /// The eye, as the packet tracer reports it.
    eye: [f32; 3],
    /// The eye.
    eye64: Vec3,
}

impl EndShader<'_> {
    /// The linear colour and weight a branch's end adds to its pixel, and what it met if it is
    /// the ray from the eye that met nothing of the scene.
    // Inline: as a call, the end just made would be stored and at once read back.
    #[inline(always)]
    fn shade(&self, end: BranchEnd) -> Option<([f64; 3], f64, Region)> {
        let v = |a: [f32; 3]| Vec3::new(a[0] as f64, a[1] as f64, a[2] as f64);
        match end {
            BranchEnd::Object {
                code,
                object,
                part,
                point,
                weight,
                absorbed,
            } => {
                let p = v(point);
                let at = (object as usize, Part::from_code(part as f64));
                let colour = object_radiance(self.world, self.light, self.eye64, code, at, p);
                Some((filtered(colour, absorbed), weight as f64, Region::Scene))
            }
            BranchEnd::Escaped {
                origin,
                direction,
                weight,
                absorbed,
            } => {
                let (o, d) = (v(origin), v(direction));
                let (region, t) = self.surroundings.meet(o, d);
                let colour = self.surroundings.colour_at(region, o, d, t, 0.0, 0.0, d.z);
                // Compared number by number (an array's `==` is a loop over a slice).
                let [x, y, z] = self.eye;
                let direct = weight == 1.0 && origin[0] == x && origin[1] == y && origin[2] == z;
                let seen = if direct { region } else { Region::Scene };
                Some((filtered(colour, absorbed), weight as f64, seen))
            }
            // Light not followed: dark in course mode (as `sample` shows it), nothing added in
            // Fresnel mode.
            BranchEnd::Dropped { weight } if !self.split => {
                Some(([0.05; 3], weight as f64, Region::Scene))
            }
            BranchEnd::Dropped { .. } | BranchEnd::Pruned { .. } => None,
        }
    }
}

/// Linear `colour` after the light lost `absorbed` in tinted media (Beer–Lambert: it keeps
/// `exp(−absorbed)` of each channel).
#[inline(always)]
fn filtered(colour: [f64; 3], absorbed: [f32; 3]) -> [f64; 3] {
    if absorbed[0] == 0.0 && absorbed[1] == 0.0 && absorbed[2] == 0.0 {
        return colour;
    }
    let mut out = colour;
    for c in 0..3 {
        out[c] *= (-(absorbed[c] as f64)).exp();
    }
    out
}

/// The picture in white light of a world whose indices depend on the wavelength: each band's
/// picture (its own world), in linear light, weighted by the band's colour and added up. Light
/// that every band sees alike keeps its colour (the bands' colours add up to white); where the
/// bands part, colour fringes appear.
///
/// A middle band is drawn whole first, then the violet and the red band at every
/// [`PROBE_STEP`]-th pixel of every [`PROBE_STEP`]-th row. Where the three centres agree, and
/// within two pixels of such a place, no ray met light that the wavelength bends (dispersion
/// parts the spectrum's colours in order, its two ends most): the middle band's colour stands for
/// every band there. Elsewhere every band is drawn: at the middle band's edges the other bands
/// take one sample in [`OTHER_BANDS_EVERY`] (stratified: neighbouring bands take neighbouring
/// samples), each averaged over its own, and elsewhere their centres, sampled where their own
/// centres differ. At an edge sampled 3x3 times that is 24 rays for the eight bands instead of 72.
fn white_picture_into(
    world: &World,
    camera: &Camera,
    options: &ShadingOptions,
    buffers: &mut ShadingBuffers,
    picture: &mut RgbPicture,
) {
    const AROUND: usize = 2;
    let single = ShadingOptions {
        white: false,
        ..*options
    };
    let (w, h) = (camera.width as usize, camera.height as usize);
    let bands = crate::spectrum::white_bands();
    let worlds = world.white_light();
    let (middle, last) = (bands.len() / 2, bands.len() - 1);
    buffers.needed.clear();
    buffers.band_samples = None;
    // The middle band whole, then the violet and the red band at every other pixel's centre
    // (every other row), keeping the centres of each.
    let mut band_picture = RgbPicture::default();
    shaded_picture_into(&worlds[middle], camera, &single, buffers, picture);
    let middle_centres = std::mem::take(&mut buffers.centre);
    let middle_seen = std::mem::take(&mut buffers.seen);
    let probed =
        |p: usize| (p / w).is_multiple_of(PROBE_STEP) && (p % w).is_multiple_of(PROBE_STEP);
    buffers.needed.extend((0..w * h).map(probed));
    let centres_only = ShadingOptions {
        samples: 1,
        ..single
    };
    shaded_picture_into(
        &worlds[0],
        camera,
        &centres_only,
        buffers,
        &mut band_picture,
    );
    let violet_centres = std::mem::take(&mut buffers.centre);
    shaded_picture_into(
        &worlds[last],
        camera,
        &centres_only,
        buffers,
        &mut band_picture,
    );
    if buffers.stop.load(Ordering::Relaxed) {
        return;
    }
    // Half a level of the picture's bytes.
    const ALIKE: f32 = 0.5 / 255.0;
    let differs: Vec<bool> = (0..w * h)
        .map(|p| {
            let (m, v, r) = (middle_centres[p], violet_centres[p], buffers.centre[p]);
            probed(p) && (0..3).any(|c| (m[c] - v[c]).abs() > ALIKE || (m[c] - r[c]).abs() > ALIKE)
        })
        .collect();
    buffers.needed.clear();
    buffers.needed.extend((0..w * h).map(|p| {
        let (i, j) = (p / w, p % w);
        (i.saturating_sub(AROUND)..(i + AROUND + 1).min(h)).any(|a| {
            (j.saturating_sub(AROUND)..(j + AROUND + 1).min(w)).any(|b| differs[a * w + b])
        })
    }));
    // The other bands sample the middle band's edges, and are drawn over its centres: where no
    // band differs, they are every band's.
    let mut contrasts = Vec::new();
    contrasts_into(&middle_centres, w, |_| true, |_| true, &mut contrasts);
    buffers.edges.clear();
    buffers
        .edges
        .extend((0..w * h).map(|p| buffers.needed[p] && on_edge(&contrasts, w, p / w, p % w)));
    buffers.centre = middle_centres;
    buffers.seen = middle_seen;
    // The sRGB code of each byte, in linear light.
    let linear: Vec<f32> = (0..=255)
        .map(|c| srgb_to_linear(c as f64 / 255.0) as f32)
        .collect();
    let mut sum = vec![[0.0f32; 3]; w * h];
    // Adds a band's picture, weighted by `rgb` where the bands differ and by `alike` elsewhere.
    let mut add = |rgb: [f64; 3], alike: [f32; 3], p: &RgbPicture, needed: &[bool]| {
        let rgb = rgb.map(|c| c as f32);
        for ((px, bytes), &part) in sum.iter_mut().zip(p.pixels.chunks_exact(3)).zip(needed) {
            let weight = if part { rgb } else { alike };
            for c in 0..3 {
                px[c] += weight[c] * linear[bytes[c] as usize];
            }
        }
    };
    // Where no band differs the middle band's colour stands for all of them.
    add(bands[middle].rgb, [1.0; 3], picture, &buffers.needed);
    for (k, (band, band_world)) in bands.iter().zip(worlds).enumerate() {
        if k == middle || buffers.stop.load(Ordering::Relaxed) {
            continue;
        }
        buffers.band_samples = Some((k, OTHER_BANDS_EVERY));
        shaded_picture_into(band_world, camera, &single, buffers, &mut band_picture);
        add(band.rgb, [0.0; 3], &band_picture, &buffers.needed);
    }
    buffers.needed.clear();
    buffers.edges.clear();
    buffers.band_samples = None;
    picture.width = camera.width;
    picture.height = camera.height;
    picture.pixels.clear();
    picture.pixels.extend(sum.iter().flat_map(|px| {
        px.map(|c| (linear_to_srgb_fast(c.clamp(0.0, 1.0) as f64) * 255.0 + 0.5) as u8)
    }));
}

/// Whether some pixel around pixel `(i, j)` of a `w × h` picture, itself included, has
/// `found(k)` for its index `k`. Written as two plain loops: it runs for every pixel of a picture,
/// and an iterator of iterators cost more than the comparisons it makes.
#[inline(always)]
fn any_neighbour(w: usize, h: usize, i: usize, j: usize, found: impl Fn(usize) -> bool) -> bool {
    let (i0, i1) = (i.saturating_sub(1), (i + 1).min(h - 1));
    let (j0, j1) = (j.saturating_sub(1), (j + 1).min(w - 1));
    for a in i0..=i1 {
        for k in a * w + j0..=a * w + j1 {
            if found(k) {
                return true;
            }
        }
    }
    false
}

/// Whether two pixel centres' colours differ by more than [`SMOOTH_CONTRAST`] in some channel.
#[inline(always)]
fn differ(a: [f32; 3], b: [f32; 3]) -> bool {
    let contrast = SMOOTH_CONTRAST as f32;
    ((a[0] - b[0]).abs() > contrast)
        | ((a[1] - b[1]).abs() > contrast)
        | ((a[2] - b[2]).abs() > contrast)
}

/// A pixel's centre differs from its neighbour's to the right, below, below right and below left
/// (bits of [`contrasts_row`]'s bytes).
const RIGHT: u8 = 1;
const BELOW: u8 = 2;
const BELOW_RIGHT: u8 = 4;
const BELOW_LEFT: u8 = 8;

/// Which of its forward neighbours each pixel of row `row` (starting at pixel `first`) differs
/// from, both centres `traced`: the row's bits, with the row `below` when there is one. Each
/// pair of neighbours is compared once, not once from each side.
fn contrasts_row(
    row: &[[f32; 3]],
    below: Option<&[[f32; 3]]>,
    first: usize,
    traced: impl Fn(usize) -> bool,
    out: &mut [u8],
) {
    let w = row.len();
    let pair =
        |a: usize, b: usize, ca: [f32; 3], cb: [f32; 3]| differ(ca, cb) && traced(a) && traced(b);
    for j in 0..w {
        let p = first + j;
        let c = row[j];
        let mut bits = 0;
        if j + 1 < w && pair(p, p + 1, c, row[j + 1]) {
            bits |= RIGHT;
        }
        if let Some(below) = below {
            let q = p + w;
            if pair(p, q, c, below[j]) {
                bits |= BELOW;
            }
            if j + 1 < w && pair(p, q + 1, c, below[j + 1]) {
                bits |= BELOW_RIGHT;
            }
            if j > 0 && pair(p, q - 1, c, below[j - 1]) {
                bits |= BELOW_LEFT;
            }
        }
        out[j] = bits;
    }
}

/// [`contrasts_row`] of the rows `wanted` of a `w` pixels wide picture's `centre` colours, into
/// `out` (its other rows are left as they were).
fn contrasts_into(
    centre: &[[f32; 3]],
    w: usize,
    wanted: impl Fn(usize) -> bool + Sync,
    traced: impl Fn(usize) -> bool + Sync + Copy,
    out: &mut Vec<u8>,
) {
    let h = centre.len() / w;
    out.resize(w * h, 0);
    out.par_chunks_mut(w).enumerate().for_each(|(i, out)| {
        if wanted(i) {
            let row = &centre[i * w..(i + 1) * w];
            let below = (i + 1 < h).then(|| &centre[(i + 1) * w..(i + 2) * w]);
            contrasts_row(row, below, i * w, traced, out);
        }
    });
}

/// Whether pixel `(i, j)` is on an edge: its centre's colour and a neighbour's differ (see
/// [`differ`]), both traced, by the pictures' bits of [`contrasts_row`]. Edges are sampled.
#[inline(always)]
fn on_edge(contrasts: &[u8], w: usize, i: usize, j: usize) -> bool {
    let p = i * w + j;
    let own = contrasts[p] != 0;
    let left = j > 0 && contrasts[p - 1] & RIGHT != 0;
    let above = i > 0 && {
        let a = p - w;
        contrasts[a] & BELOW != 0
            || (j > 0 && contrasts[a - 1] & BELOW_RIGHT != 0)
            || (j + 1 < w && contrasts[a + 1] & BELOW_LEFT != 0)
    };
    own || left || above
}

/// Work space of [`shaded_picture_into`], kept from one picture to the next.
#[derive(Clone, Debug, Default)]
pub struct ShadingBuffers {
    /// Each pixel centre's sRGB colour.
    centre: Vec<[f32; 3]>,
    /// What each pixel centre's ray met.
    seen: Vec<Region>,
    /// The glass outline's coverage per pixel.
    mask: Vec<f32>,
    /// Which neighbours each pixel centre's colour differs from (see [`contrasts_row`]).
    contrasts: Vec<u8>,
    /// Rows done of the picture being drawn, out of twice its height (centres, then edges).
    rows_done: Arc<AtomicU64>,
    /// Set by another thread to abandon the picture being drawn.
    stop: Arc<AtomicBool>,
    /// The pixels to draw (all when empty); the others keep what the last picture drawn into
    /// these buffers had there (white light's bands where they do not differ).
    needed: Vec<bool>,
    /// Which of an edge pixel's samples to trace: `Some((k, m))` those whose index `s` (row by
    /// row in the pixel) has `(s + k) % m == 0` (white light's other bands), `None` all.
    band_samples: Option<(usize, usize)>,
    /// Pixels to sample as edges whatever their centres (white light's other bands take the
    /// middle band's edges, and do not trace these pixels' centres); empty: none.
    edges: Vec<bool>,
}

impl ShadingBuffers {
    /// A counter of the rows done of the picture being drawn, out of twice its height (the
    /// pixel centres, then the edges' samples): another thread may read it to show progress.
    pub fn progress(&self) -> Arc<AtomicU64> {
        Arc::clone(&self.rows_done)
    }

    /// A flag another thread may set to abandon the picture being drawn (a live view whose input
    /// has moved on): the rows not yet started are left as they were, so a picture drawn while it
    /// was set must be thrown away. Drawing does not clear it.
    pub fn stop_flag(&self) -> Arc<AtomicBool> {
        Arc::clone(&self.stop)
    }

    /// Empty buffers whose drawing is abandoned when `stop` is set (another picture's flag).
    pub fn with_stop_flag(stop: Arc<AtomicBool>) -> ShadingBuffers {
        ShadingBuffers {
            stop,
            ..ShadingBuffers::default()
        }
    }
}

/// White light's violet and red bands are compared with the middle one at one pixel in this many
/// along each row and column: dispersion shows over regions wider than that.
pub const PROBE_STEP: usize = 2;

/// At an edge pixel in white light, each band but the middle one traces one sample in this many.
pub const OTHER_BANDS_EVERY: usize = 4;

/// The colour of the glass's outline (sRGB).
const INK: [f64; 3] = [0.16, 0.18, 0.24];

/// [`shaded_picture`] into `picture`, reusing its pixels and `buffers` (an interactive view
/// redraws with no allocation once the size stops changing).
///
/// Two passes over the rows: the pixel centres, then each row's edges (supersampled), outline
/// and encoding at once.
pub fn shaded_picture_into(
    world: &World,
    camera: &Camera,
    options: &ShadingOptions,
    buffers: &mut ShadingBuffers,
    picture: &mut RgbPicture,
) {
    if options.white && !world.white_light().is_empty() {
        white_picture_into(world, camera, options, buffers, picture);
        return;
    }
    let (w, h) = (camera.width as usize, camera.height as usize);
    let surroundings = Surroundings::new(options.backdrop, camera.eye).under_sun(world.sun());
    let light = light_direction(&surroundings);
    let n = options.samples.max(1) as usize;
    let rows_done = &*buffers.rows_done;
    rows_done.store(0, Ordering::Relaxed);
    let stop = &*buffers.stop;
    let stopped = || stop.load(Ordering::Relaxed);
    let ShadingBuffers {
        centre,
        seen,
        mask,
        contrasts,
        needed,
        band_samples,
        edges,
        ..
    } = buffers;
    let needed = &*needed;
    // Which pixels of row `i` to draw: all (None), or those marked.
    let needed_row = |i: usize| (!needed.is_empty()).then(|| &needed[i * w..(i + 1) * w]);
    let skipped = |i: usize| needed_row(i).is_some_and(|r| !r.contains(&true));
    // The pixels given as edges, whose centres are not traced.
    let given = (!edges.is_empty()).then_some(&**edges);
    let traced_centre = |p: usize| given.is_none_or(|e| !e[p]);
    centre.resize(w * h, [0.0; 3]);
    seen.resize(w * h, Region::Scene);
    // Pixel centres: the single-precision packet tracer, eight rays at a time (most of a
    // picture's rays); the samples at edges below go through it too.
    let packets = PacketTracer::new(world);
    let (split, prune) = match options.mode {
        ShadingMode::Course => (false, 0.0),
        ShadingMode::Fresnel { prune_below } => (true, prune_below),
    };
    let eye = camera.eye;
    let shader = EndShader {
        world,
        surroundings: &surroundings,
        light,
        split,
        eye: [eye.x as f32, eye.y as f32, eye.z as f32],
        eye64: eye,
    };
    let draw_outline = || {
        // Outdoors, under the sun, the container is not drawn: it only holds the scene.
        let outlined = options.outline && world.sun().is_none();
        if let Some(glass) = world.thin_glass().filter(|_| outlined) {
            outline_mask(mask, camera, glass);
        } else {
            mask.clear();
        }
    };
    let centres = || {
        centre
            .par_chunks_mut(w)
            .zip(seen.par_chunks_mut(w))
            .enumerate()
            .for_each_init(
                || {
                    let wave = FresnelWave::pooled();
                    (wave, Vec::new(), Vec::new(), Vec::new(), Vec::new())
                },
                |(wave, sum, ends, columns, dirs), (i, (row, seen_row))| {
                    if stopped() || skipped(i) {
                        return;
                    }
                    sum.clear();
                    sum.resize(w, [0.0f64; 3]);
                    // The ends are kept and shaded after the row is traced: shading inside the
                    // tracer's loop would read each end back while it is still being written.
                    ends.clear();
                    let some = needed_row(i).filter(|r| {
                        r.contains(&false) || (0..w).any(|j| !traced_centre(i * w + j))
                    });
                    match some {
                        None => {
                            seen_row.fill(Region::Scene);
                            let mut on_end = |j: usize, end: BranchEnd| ends.push((j as u32, end));
                            packets.branch_ends_row(
                                camera,
                                i as u32,
                                split,
                                prune,
                                wave,
                                &mut on_end,
                            );
                        }
                        Some(r) => {
                            // Some pixels only: their centres' rays, as the edges' samples go.
                            columns.clear();
                            columns.extend((0..w).filter(|&j| r[j] && traced_centre(i * w + j)));
                            dirs.clear();
                            dirs.extend(columns.iter().map(|&j| {
                                camera
                                    .direction_at(i as f64 + 0.5, j as f64 + 0.5)
                                    .normalize()
                            }));
                            for &j in columns.iter() {
                                seen_row[j] = Region::Scene;
                            }
                            let mut on_end =
                                |k: usize, end: BranchEnd| ends.push((columns[k] as u32, end));
                            packets.branch_ends(
                                camera.eye,
                                dirs,
                                split,
                                prune,
                                FRESNEL_SEGMENTS_PER_PIXEL,
                                wave,
                                &mut on_end,
                            );
                        }
                    }
                    for &(j, end) in ends.iter() {
                        if let Some((colour, weight, region)) = shader.shade(end) {
                            let px = &mut sum[j as usize];
                            for k in 0..3 {
                                px[k] += weight * colour[k];
                            }
                            if region != Region::Scene {
                                seen_row[j as usize] = region;
                            }
                        }
                    }
                    let to_srgb = to_srgb_table();
                    for (j, (px, lin)) in row.iter_mut().zip(sum.iter()).enumerate() {
                        if some.is_none_or(|r| r[j] && traced_centre(i * w + j)) {
                            *px = lin.map(|c| lookup(to_srgb, c) as f32);
                        }
                    }
                    rows_done.fetch_add(1, Ordering::Relaxed);
                },
            )
    };
    join(centres, draw_outline);
    let (centre, seen, mask) = (&*centre, &*seen, &*mask);
    if options.adaptive && n > 1 {
        // A row's bits are read for its own edges and the next row's.
        let wanted = |i: usize| !stopped() && !(skipped(i) && (i + 1 == h || skipped(i + 1)));
        contrasts_into(centre, w, wanted, traced_centre, contrasts);
    }
    let contrasts = &*contrasts;
    // Given edges aside, a pixel is an edge where its centre and a neighbour's (one traced)
    // differ; every pixel is one without adaptive sampling.
    let edge = |i: usize, j: usize| {
        !options.adaptive || !traced_centre(i * w + j) || on_edge(contrasts, w, i, j)
    };
    // Whether the whole neighbourhood of a pixel met one plane (or the sky) straight from the
    // eye: the pixel then sees only that, and its average is worked out without samples.
    let uniform_backdrop = |i: usize, j: usize| {
        let g = seen[i * w + j];
        g != Region::Scene && !any_neighbour(w, h, i, j, |k| seen[k] != g)
    };
    // The samples of an edge pixel traced, and how many.
    let band_samples = *band_samples;
    let traced = |s: usize| band_samples.is_none_or(|(k, m)| (s + k).is_multiple_of(m));
    let per_pixel = (0..n * n).filter(|&s| traced(s)).count().max(1);
    // A pixel's samples share the pixel's bound on Fresnel work, but each may follow at least
    // 64 segments (ordinary rays need a few dozen).
    let max_segments = (FRESNEL_SEGMENTS_PER_PIXEL / (n * n) as u32).max(64);
    // One column's and one row's change of a pixel's direction (the camera is linear in both).
    let dc = camera.direction_at(0.0, 1.0) - camera.direction_at(0.0, 0.0);
    let dr = camera.direction_at(1.0, 0.0) - camera.direction_at(0.0, 0.0);
    picture.width = camera.width;
    picture.height = camera.height;
    picture.pixels.resize(w * h * 3, 0);
    picture
        .pixels
        .par_chunks_mut(3 * w)
        .enumerate()
        .for_each_init(
            || {
                (
                    FresnelWave::pooled(),
                    Vec::new(),
                    Vec::new(),
                    Vec::new(),
                    Vec::new(),
                    Vec::new(),
                )
            },
            |(wave, line, edges, dirs, acc, ends), (i, out)| {
                if stopped() || skipped(i) {
                    return;
                }
                line.clear();
                line.extend(centre[i * w..(i + 1) * w].iter().map(|c| c.map(f64::from)));
                let drawn = |j: usize| needed_row(i).is_none_or(|r| r[j]);
                if n > 1 {
                    edges.clear();
                    dirs.clear();
                    let to_srgb = to_srgb_table();
                    for (j, px) in line.iter_mut().enumerate() {
                        if !edge(i, j) || !drawn(j) {
                            continue;
                        }
                        // Most edges of a picture are the backdrop's squares seen past the glass.
                        if uniform_backdrop(i, j) {
                            let d = camera.direction_at(i as f64 + 0.5, j as f64 + 0.5);
                            *px = surroundings
                                .radiance_over_pixel(eye, d, dc, dr)
                                .map(|c| lookup(to_srgb, c));
                            continue;
                        }
                        edges.push(j);
                        for a in 0..n {
                            for b in (0..n).filter(|&b| traced(a * n + b)) {
                                let key =
                                    (((i * w + j) as u64) << 16) ^ (((a * n + b) as u64) << 1);
                                let r = i as f64 + (a as f64 + jitter(key)) / n as f64;
                                let c = j as f64 + (b as f64 + jitter(key | 1)) / n as f64;
                                dirs.push(camera.direction_at(r, c).normalize());
                            }
                        }
                    }
                    if !edges.is_empty() {
                        acc.clear();
                        acc.resize(edges.len(), [0.0f64; 3]);
                        ends.clear();
                        packets.branch_ends(
                            eye,
                            dirs,
                            split,
                            prune,
                            max_segments,
                            wave,
                            &mut |k, end| ends.push((k as u32, end)),
                        );
                        for &(k, end) in ends.iter() {
                            if let Some((colour, weight, _)) = shader.shade(end) {
                                let px = &mut acc[k as usize / per_pixel];
                                for c in 0..3 {
                                    px[c] += weight * colour[c];
                                }
                            }
                        }
                        let inv = 1.0 / per_pixel as f64;
                        for (&j, sum) in edges.iter().zip(acc.iter()) {
                            line[j] = sum.map(|c| lookup(to_srgb, c * inv));
                        }
                    }
                }
                let mask_row = if mask.is_empty() {
                    &[][..]
                } else {
                    &mask[i * w..(i + 1) * w]
                };
                for (j, (o, px)) in out.chunks_exact_mut(3).zip(line.iter()).enumerate() {
                    if !drawn(j) {
                        continue;
                    }
                    let px = match mask_row.get(j) {
                        Some(&m) if m > 0.0 => mix(*px, INK, m as f64),
                        _ => *px,
                    };
                    for k in 0..3 {
                        // `x + 0.5` truncated is `x.round()` for x ≥ 0, without a call into libm.
                        o[k] = (px[k].clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
                    }
                }
                rows_done.fetch_add(1, Ordering::Relaxed);
            },
        );
}

/// The image points seen through `camera` (its eye should be their observer): each a disc of
/// `radius` pixels in its section colour, nearer points over farther ones, on a plain light
/// background with the glass outlined, for side-by-side comparison with [`shaded_picture`].
pub fn cloud_picture(
    world: &World,
    camera: &Camera,
    points: &[ImagePoint],
    radius: f64,
) -> RgbPicture {
    let (w, h) = (camera.width as usize, camera.height as usize);
    let mut display = vec![[0.97f64; 3]; w * h];
    let mut order: Vec<&ImagePoint> = points.iter().collect();
    // Painter's order: the farthest first.
    order.sort_by(|a, b| {
        let da = (a.position - camera.eye).length();
        let db = (b.position - camera.eye).length();
        db.total_cmp(&da)
    });
    for p in order {
        let Some((row, col)) = camera.project(p.position) else {
            continue;
        };
        let colour = COLOR_RGB[p.color as usize - 1];
        let reach = radius + 1.0;
        let i0 = (row - reach).floor().max(0.0) as usize;
        let i1 = ((row + reach).ceil().max(0.0) as usize).min(h);
        let j0 = (col - reach).floor().max(0.0) as usize;
        let j1 = ((col + reach).ceil().max(0.0) as usize).min(w);
        for i in i0..i1 {
            for j in j0..j1 {
                let d = ((i as f64 + 0.5 - row).powi(2) + (j as f64 + 0.5 - col).powi(2)).sqrt();
                let cover = (radius + 0.5 - d).clamp(0.0, 1.0);
                if cover > 0.0 {
                    let px = &mut display[i * w + j];
                    *px = mix(*px, colour, cover);
                }
            }
        }
    }
    let mut mask = Vec::new();
    if let Some(glass) = world.thin_glass() {
        outline_mask(&mut mask, camera, glass);
    }
    for (px, &m) in display.iter_mut().zip(mask.iter()) {
        if m > 0.0 {
            *px = mix(*px, INK, m as f64);
        }
    }
    encode(camera, &display)
}

fn encode(camera: &Camera, display: &[[f64; 3]]) -> RgbPicture {
    RgbPicture {
        width: camera.width,
        height: camera.height,
        pixels: display
            .iter()
            .flatten()
            .map(|c| (c.clamp(0.0, 1.0) * 255.0 + 0.5) as u8)
            .collect(),
    }
}

/// The glass's outline as each pixel's coverage in `mask`: rim and base circles (the part on the
/// observer's side stronger, the far side fainter; a circle seen from its open side wholly strong)
/// and the two vertical silhouette lines.
fn outline_mask(mask: &mut Vec<f32>, camera: &Camera, (radius, height): (f64, f64)) {
    const STRONG: f64 = 0.75;
    const FAINT: f64 = 0.3;
    const STEPS: usize = 720;
    let (w, h) = (camera.width as usize, camera.height as usize);
    let width = (camera.height as f64 / 400.0).clamp(1.0, 4.0);
    mask.clear();
    mask.resize(w * h, 0.0);
    let eye = camera.eye;
    let eye_r = (eye.x * eye.x + eye.y * eye.y).sqrt();
    let circle = |a: f64, z: f64| Vec3::new(radius * libm::cos(a), radius * libm::sin(a), z);
    for (z, seen_inside) in [(height, eye.z > height), (0.0, eye.z < 0.0)] {
        for k in 0..STEPS {
            let a0 = k as f64 * std::f64::consts::TAU / STEPS as f64;
            let a1 = (k + 1) as f64 * std::f64::consts::TAU / STEPS as f64;
            let mid = 0.5 * (a0 + a1);
            let near_side = eye.x * libm::cos(mid) + eye.y * libm::sin(mid) > radius;
            let alpha = if seen_inside || near_side {
                STRONG
            } else {
                FAINT
            };
            stroke(mask, camera, circle(a0, z), circle(a1, z), width, alpha);
        }
    }
    if eye_r > radius {
        let towards = libm::atan2(eye.y, eye.x);
        let half = libm::acos(radius / eye_r);
        for a in [towards - half, towards + half] {
            stroke(
                mask,
                camera,
                circle(a, 0.0),
                circle(a, height),
                width,
                STRONG,
            );
        }
    }
}

/// Marks in `mask` (the strongest wins) an anti-aliased line of `width` pixels from the picture
/// of `p` to that of `q`, at opacity `alpha`; long 3D segments are cut so that their pictures
/// stay straight enough, and pieces behind the eye are skipped.
fn stroke(mask: &mut [f32], camera: &Camera, p: Vec3, q: Vec3, width: f64, alpha: f64) {
    let (w, h) = (camera.width as usize, camera.height as usize);
    let pieces = match (camera.project(p), camera.project(q)) {
        (Some((r0, c0)), Some((r1, c1))) => {
            (((r1 - r0).powi(2) + (c1 - c0).powi(2)).sqrt() / 4.0).clamp(1.0, 256.0) as usize
        }
        _ => 256,
    };
    for k in 0..pieces {
        let a = p + (q - p) * (k as f64 / pieces as f64);
        let b = p + (q - p) * ((k + 1) as f64 / pieces as f64);
        let (Some((ra, ca)), Some((rb, cb))) = (camera.project(a), camera.project(b)) else {
            continue;
        };
        let reach = width / 2.0 + 1.0;
        let i0 = (ra.min(rb) - reach).floor().max(0.0) as usize;
        let i1 = ((ra.max(rb) + reach).ceil().max(0.0) as usize).min(h);
        let j0 = (ca.min(cb) - reach).floor().max(0.0) as usize;
        let j1 = ((ca.max(cb) + reach).ceil().max(0.0) as usize).min(w);
        let (dr, dc) = (rb - ra, cb - ca);
        let len2 = dr * dr + dc * dc;
        for i in i0..i1 {
            for j in j0..j1 {
                let (pr, pc) = (i as f64 + 0.5 - ra, j as f64 + 0.5 - ca);
                let t = if len2 > 0.0 {
                    ((pr * dr + pc * dc) / len2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let d = ((pr - t * dr).powi(2) + (pc - t * dc).powi(2)).sqrt();
                let cover = (width / 2.0 + 0.5 - d).clamp(0.0, 1.0) * alpha;
                let m = &mut mask[i * w + j];
                let cover = cover as f32;
                if cover > *m {
                    *m = cover;
                }
            }
        }
    }
}

/// A splat radius (pixels) for [`cloud_picture`] that makes neighbouring points just touch: 0.6 of
/// the median distance between a projected point and its nearest neighbour, within 0.8..=4 pixels.
pub fn splat_radius(camera: &Camera, points: &[ImagePoint]) -> f64 {
    use std::collections::HashMap;
    const CELL: f64 = 4.0;
    const RINGS: i64 = 6;
    let projected: Vec<(f64, f64)> = points
        .iter()
        .filter_map(|p| camera.project(p.position))
        .collect();
    let key = |(r, c): (f64, f64)| ((r / CELL).floor() as i64, (c / CELL).floor() as i64);
    let mut grid: HashMap<(i64, i64), Vec<(f64, f64)>> = HashMap::new();
    for &p in &projected {
        grid.entry(key(p)).or_default().push(p);
    }
    // At most about 2000 points are measured: the median does not need more.
    let stride = (projected.len() / 2000).max(1);
    let mut nearest: Vec<f64> = Vec::new();
    for &p in projected.iter().step_by(stride) {
        let (ki, kj) = key(p);
        let mut best = f64::INFINITY;
        for ring in 0..=RINGS {
            for di in -ring..=ring {
                for dj in -ring..=ring {
                    if di.abs().max(dj.abs()) != ring {
                        continue;
                    }
                    for q in grid.get(&(ki + di, kj + dj)).into_iter().flatten() {
                        let d = ((q.0 - p.0).powi(2) + (q.1 - p.1).powi(2)).sqrt();
                        if d > 0.0 && d < best {
                            best = d;
                        }
                    }
                }
            }
            // Anything in a farther ring is at least `ring · CELL` away.
            if best <= ring as f64 * CELL {
                break;
            }
        }
        if best.is_finite() {
            nearest.push(best);
        }
    }
    if nearest.is_empty() {
        return 1.5;
    }
    nearest.sort_by(f64::total_cmp);
    (0.6 * nearest[nearest.len() / 2]).clamp(0.8, 4.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::picture::course_picture;
    use crate::scene::{REFERENCES, SCENE_CENTRE, WATER_INDEX};

    /// The edges found by comparing each pair of neighbours once are the pixels whose centre
    /// differs from one of its eight neighbours', both traced, or whose own centre is untraced:
    /// checked against that definition on small random pictures with colours near the contrast.
    #[test]
    fn edges_are_the_pixels_with_a_differing_neighbour() {
        for seed in 0..200u64 {
            let (w, h) = (1 + seed as usize % 7, 1 + (seed as usize / 7) % 6);
            let r = |k: u64| jitter(seed << 20 | k);
            let level = |k: u64| (r(k) * 4.0).floor() as f32 * SMOOTH_CONTRAST as f32 * 0.75;
            let centre: Vec<[f32; 3]> = (0..w * h)
                .map(|p| std::array::from_fn(|c| level((3 * p + c) as u64)))
                .collect();
            let untraced: Vec<bool> = (0..w * h).map(|p| r(1000 + p as u64) < 0.2).collect();
            let traced = |p: usize| !untraced[p];
            let mut contrasts = Vec::new();
            contrasts_into(&centre, w, |_| true, traced, &mut contrasts);
            for i in 0..h {
                for j in 0..w {
                    let p = i * w + j;
                    let mut expected = false;
                    for a in i.saturating_sub(1)..(i + 2).min(h) {
                        for b in j.saturating_sub(1)..(j + 2).min(w) {
                            let q = a * w + b;
                            let differs = (0..3).any(|c| {
                                (centre[p][c] - centre[q][c]).abs() > SMOOTH_CONTRAST as f32
                            });
                            expected |= differs && traced(q);
                        }
                    }
                    let found = !traced(p) || on_edge(&contrasts, w, i, j);
                    assert_eq!(
                        found,
                        !traced(p) || expected,
                        "seed {seed}, pixel ({i}, {j})"
                    );
                }
            }
        }
    }

    fn options(mode: ShadingMode, samples: u32) -> ShadingOptions {
        ShadingOptions {
            white: false,
            mode,
            backdrop: Backdrop::Checker,
            samples,
            adaptive: true,
            outline: false,
        }
    }

    /// Whether byte colour `c` is a (shaded) multiple of section `code`'s colour.
    fn has_section_hue(c: [u8; 3], code: u8) -> bool {
        let [r, g, b] = c;
        match code {
            1 => r > 100 && g == 0 && b == 0,
            2 => r > g && (b as u32) * 2 < g as u32 && r > 100,
            3 => r > 100 && g == 0 && r.abs_diff(b) <= 1,
            4 => r == 0 && g > 100 && b == 0,
            5 => r == 0 && g == 0 && b > 100,
            _ => false,
        }
    }

    #[test]
    fn straw_pixels_show_their_section_colour_and_others_do_not() {
        let (w, h) = (80, 60);
        for r in REFERENCES {
            let scene = World::assignment(&r.scene(WATER_INDEX));
            let cam = Camera::new(r.observer, SCENE_CENTRE, w, h, 1.6);
            let codes = course_picture(&scene, &cam);
            for mode in [
                ShadingMode::Course,
                ShadingMode::Fresnel { prune_below: 1e-4 },
            ] {
                let pic = shaded_picture(&scene, &cam, &options(mode, 1));
                assert_eq!(pic.pixels.len(), (w * h * 3) as usize);
                let mut straw = 0;
                for i in 0..h {
                    for j in 0..w {
                        let code = codes[(i * w + j) as usize];
                        let c = pic.pixel(i, j);
                        if code != 0 && mode == ShadingMode::Course {
                            straw += 1;
                            assert!(has_section_hue(c, code), "{c:?} for code {code}");
                        }
                        if code == 0 {
                            // The surroundings are light and greyish, never a pure section hue.
                            assert!((1..=5).all(|k| !has_section_hue(c, k)), "{c:?}");
                        }
                    }
                }
                assert!(mode != ShadingMode::Course || straw > 20);
            }
        }
    }

    #[test]
    fn antialiasing_averages_and_is_deterministic() {
        let r = REFERENCES[1];
        let scene = World::assignment(&r.scene(WATER_INDEX));
        let cam = Camera::new(r.observer, SCENE_CENTRE, 60, 45, 1.6);
        let opts = options(ShadingMode::Fresnel { prune_below: 1e-4 }, 3);
        let a = shaded_picture(&scene, &cam, &opts);
        let b = shaded_picture(&scene, &cam, &opts);
        assert_eq!(a, b);
        // Edges get in-between colours: more distinct colours than with one sample per pixel.
        let distinct = |p: &RgbPicture| {
            let mut v: Vec<[u8; 3]> = p.pixels.chunks(3).map(|c| [c[0], c[1], c[2]]).collect();
            v.sort();
            v.dedup();
            v.len()
        };
        let one = shaded_picture(&scene, &cam, &options(opts.mode, 1));
        assert!(distinct(&a) > distinct(&one));
    }

    #[test]
    fn checkerboard_wall_and_floor_are_where_they_were_put() {
        let s = Surroundings::new(Backdrop::Checker, Vec3::new(0.1, 0.0, 0.1));
        assert!(s.has_floor());
        assert!((s.wall_normal() - Vec3::X).length() < 1e-12);
        // Horizontal rays along −x meet the wall at x = −WALL_DISTANCE; squares alternate every
        // CHECKER_SIDE in height (light at z in [0.04, 0.06), dark in [0.06, 0.08)).
        let at = |z: f64| s.radiance(&Ray::new(Vec3::new(0.0, 0.001, z), Vec3::NEG_X));
        let (light, dark) = (at(0.05), at(0.07));
        assert!(light[0] > dark[0] + 0.1);
        assert_eq!(at(0.05), at(0.045));
        // Above the wall's top: sky, neither square.
        let sky = at(WALL_TOP + 0.01);
        assert!(sky != light && sky != dark);
        // Straight down from above: the floor, whose squares alternate in x.
        let down = |x: f64| s.radiance(&Ray::new(Vec3::new(x, 0.001, 0.3), Vec3::NEG_Z));
        assert!((down(0.05)[0] - down(0.07)[0]).abs() > 0.1);
        // A ray out of the water's bottom, a rounding error below z = 0, meets the floor too.
        let out = |z0: f64| {
            s.radiance(&Ray::new(
                Vec3::new(0.01, 0.001, z0),
                Vec3::new(0.3, 0.1, -1.0),
            ))
        };
        assert_eq!(out(-3e-8), out(0.0));
        // Seen from below z = 0 there is no floor (a glass table).
        assert!(!Surroundings::new(Backdrop::Checker, Vec3::new(0.1, 0.0, -0.1)).has_floor());
        // The plain backdrop has no squares.
        let p = Surroundings::new(Backdrop::Plain, Vec3::new(0.1, 0.0, 0.1));
        let flat = |z: f64| p.radiance(&Ray::new(Vec3::new(0.0, 0.001, z), Vec3::NEG_X));
        assert_eq!(flat(0.05), flat(0.07));
    }

    /// The straight line `ray` first meets the upright straw of axis `(xp, yp)` of the
    /// assignment (radius 0.005 m, from z = 0 to 0.25 m), solved here on its own: the side's
    /// quadratic and the caps' planes. The point and the part, if it does.
    fn straight_hit(ray: Ray, (xp, yp): (f64, f64)) -> Option<(Vec3, Part)> {
        use crate::scene::{STRAW_HEIGHT, STRAW_RADIUS};
        let (o, d) = (ray.origin - Vec3::new(xp, yp, 0.0), ray.direction);
        let mut best: Option<(f64, Part)> = None;
        let mut keep = |t: f64, part: Part| {
            if t > 0.0 && best.is_none_or(|(b, _)| t < b) {
                best = Some((t, part));
            }
        };
        let a = d.x * d.x + d.y * d.y;
        let b = o.x * d.x + o.y * d.y;
        let c = o.x * o.x + o.y * o.y - STRAW_RADIUS * STRAW_RADIUS;
        if a > 0.0 && b * b - a * c >= 0.0 {
            let t = (-b - (b * b - a * c).sqrt()) / a;
            let z = o.z + t * d.z;
            if (0.0..=STRAW_HEIGHT).contains(&z) {
                keep(t, Part::Side);
            }
        }
        for (z, part) in [(0.0, Part::Bottom), (STRAW_HEIGHT, Part::Top)] {
            let t = (z - o.z) / d.z;
            let (x, y) = (o.x + t * d.x, o.y + t * d.y);
            if x * x + y * y <= STRAW_RADIUS * STRAW_RADIUS {
                keep(t, part);
            }
        }
        best.map(|(t, part)| (ray.at(t), part))
    }

    /// With water of index 1 nothing bends: the course's shading of every ray is the straw's
    /// shade where the straight line first meets it (found by [`straight_hit`], not by the
    /// tracer), in its section's colour, or else the backdrop's along the line.
    #[test]
    fn without_refraction_a_ray_shows_what_its_straight_line_meets() {
        use crate::scene::section_at;
        for r in REFERENCES {
            let world = World::assignment(&r.scene(1.0));
            let aim = Vec3::new(r.straw.0, r.straw.1, 0.1);
            let cam = Camera::new(r.observer, aim, 64, 48, 0.8);
            let s = Surroundings::new(Backdrop::Plain, cam.eye);
            let light = light_direction(&s);
            let (mut straw, mut off) = (0, 0);
            for i in 0..cam.height {
                for j in 0..cam.width {
                    let ray = cam.pixel_ray(i, j);
                    let expected = match straight_hit(ray, r.straw) {
                        Some((point, part)) => {
                            straw += 1;
                            let color = match part {
                                Part::Bottom => 1,
                                Part::Top => 5,
                                Part::Side => section_at(point.z),
                            };
                            object_radiance(&world, light, cam.eye, color, (0, part), point)
                        }
                        None => s.radiance(&ray),
                    };
                    let got = sample(&world, &s, light, ShadingMode::Course, ray);
                    if (0..3).any(|k| (got[k] - expected[k]).abs() > 1e-9) {
                        off += 1;
                    }
                }
            }
            // A pixel whose line grazes the straw's silhouette may go either way by rounding.
            assert!(straw > 50, "reference {}: the straw is in view", r.number);
            assert!(off <= 3, "reference {}: {off} pixels differ", r.number);
        }
    }

    /// Pixel centres come from the single-precision packet tracer: they must be what the
    /// double-precision tracer sees there, but for a few pixels on the picture's boundaries.
    #[test]
    fn packet_centres_shade_as_the_double_precision_tracer() {
        for r in REFERENCES {
            let scene = World::assignment(&r.scene(WATER_INDEX));
            let cam = Camera::new(r.observer, SCENE_CENTRE, 160, 120, 1.6);
            let s = Surroundings::new(Backdrop::Checker, cam.eye);
            let light = light_direction(&s);
            for mode in [
                ShadingMode::Course,
                ShadingMode::Fresnel { prune_below: 1e-4 },
            ] {
                let mut opts = options(mode, 1);
                opts.outline = false;
                let pic = shaded_picture(&scene, &cam, &opts);
                let mut off = 0;
                for i in 0..cam.height {
                    for j in 0..cam.width {
                        let exact = sample(&scene, &s, light, mode, cam.pixel_ray(i, j))
                            .map(|c| (linear_to_srgb(c) * 255.0).round() as i32);
                        let got = pic.pixel(i, j).map(i32::from);
                        if (0..3).any(|k| (exact[k] - got[k]).abs() > 2) {
                            off += 1;
                        }
                    }
                }
                let share = off as f64 / (cam.width * cam.height) as f64;
                assert!(
                    share < 0.01,
                    "reference {} {mode:?}: {off} pixels off",
                    r.number
                );
            }
        }
    }

    /// A tinted layer of oil on water: every pixel centre is the double-precision tracer's colour
    /// with light absorbed by the Beer–Lambert law along the path's pieces inside the oil, found
    /// here from the events' points (a piece is in oil where the index beyond the event is oil's).
    #[cfg(feature = "scene-file")]
    #[test]
    fn a_tinted_liquid_absorbs_light_along_the_path_inside_it() {
        use crate::scene_file::SceneDescription;
        let oil = 1.47;
        let text = format!(
            "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.20\n\
             [[liquid]]\nname = \"water\"\nindex = 1.333\ntop = 0.10\n\
             [[liquid]]\nname = \"oil\"\nindex = {oil}\ntop = 0.15\ntint = \"#e0b020\"\n\
             [[straw]]\nx = 0.02\ny = 0.01\n"
        );
        let scene = SceneDescription::from_toml(&text).expect("oil on water");
        let alpha = scene.liquids[1].absorption().expect("a tint");
        let world = World::new(&scene, 10).expect("a valid scene");
        let cam = Camera::new(
            Vec3::new(0.3, 0.05, 0.2),
            Vec3::new(0.0, 0.0, 0.11),
            96,
            72,
            0.6,
        );
        let s = Surroundings::new(Backdrop::Checker, cam.eye);
        let light = light_direction(&s);
        let mut opts = options(ShadingMode::Course, 1);
        opts.outline = false;
        let pic = shaded_picture(&world, &cam, &opts);
        let (mut off, mut through_oil) = (0, 0);
        for i in 0..cam.height {
            for j in 0..cam.width {
                let ray = cam.pixel_ray(i, j);
                let mut in_oil = 0.0;
                let (mut from, mut n_here) = (ray.origin, 1.0);
                let outcome = world.trace_with(ray, |e| {
                    if n_here == oil {
                        in_oil += (e.point - from).length();
                    }
                    from = e.point;
                    if !e.totally_reflected {
                        n_here = e.n2;
                    }
                });
                if let Outcome::Object { point, .. } = outcome {
                    if n_here == oil {
                        in_oil += (point - from).length();
                    }
                }
                if in_oil > 0.01 {
                    through_oil += 1;
                }
                let clear = sample(&world, &s, light, ShadingMode::Course, ray);
                let exact = std::array::from_fn::<_, 3, _>(|c| {
                    let kept = clear[c] * (-alpha[c] * in_oil).exp();
                    (linear_to_srgb(kept) * 255.0).round() as i32
                });
                let got = pic.pixel(i, j).map(i32::from);
                if (0..3).any(|k| (exact[k] - got[k]).abs() > 2) {
                    off += 1;
                }
            }
        }
        assert!(
            through_oil > 500,
            "{through_oil} pixels see through the oil"
        );
        assert!(
            off * 100 < (cam.width * cam.height) as usize,
            "{off} pixels off"
        );
        // And the tint shows: the same scene with clear oil is another picture there.
        let clear = SceneDescription::from_toml(&text.replace("tint = \"#e0b020\"\n", ""))
            .expect("clear oil");
        let plain = shaded_picture(&World::new(&clear, 10).expect("valid"), &cam, &opts);
        let changed = (0..pic.pixels.len() / 3)
            .filter(|k| {
                let (a, b) = (
                    &pic.pixels[3 * k..3 * k + 3],
                    &plain.pixels[3 * k..3 * k + 3],
                );
                a.iter().zip(b).any(|(x, y)| x.abs_diff(*y) > 8)
            })
            .count();
        assert!(changed * 2 > through_oil, "{changed} pixels tinted");
    }

    /// A buffer reused across sizes holds nothing of the previous picture.
    #[test]
    fn reused_buffers_give_the_fresh_picture() {
        let r = REFERENCES[2];
        let scene = World::assignment(&r.scene(WATER_INDEX));
        let opts = options(ShadingMode::Fresnel { prune_below: 1e-4 }, 2);
        let mut buffers = ShadingBuffers::default();
        let mut pic = RgbPicture::default();
        for (w, h) in [(90, 70), (40, 30), (64, 48)] {
            let cam = Camera::new(r.observer, SCENE_CENTRE, w, h, 1.2);
            shaded_picture_into(&scene, &cam, &opts, &mut buffers, &mut pic);
            let fresh = shaded_picture(&scene, &cam, &opts);
            assert_eq!(pic, fresh, "{w}x{h}");
        }
    }

    /// The tables used in the inner loops follow the exact curves to far below one 8-bit level.
    #[test]
    fn curve_tables_match_the_exact_curves() {
        let mut worst: f64 = 0.0;
        for k in 0..=100_000 {
            let c = k as f64 / 100_000.0;
            worst = worst
                .max((srgb_to_linear_fast(c) - srgb_to_linear(c)).abs())
                .max((linear_to_srgb_fast(c) - linear_to_srgb(c)).abs());
        }
        assert!(worst < 2e-5, "worst {worst}");
        // Out of range: clamped as the exact encoder clamps.
        assert_eq!(linear_to_srgb_fast(1.7), linear_to_srgb(1.0));
        assert_eq!(linear_to_srgb_fast(-0.2), 0.0);
    }

    #[test]
    fn srgb_round_trip() {
        for k in 0..=255 {
            let c = k as f64 / 255.0;
            assert!((linear_to_srgb(srgb_to_linear(c)) - c).abs() < 1e-12);
        }
    }

    #[test]
    fn cloud_points_land_where_the_camera_sees_them() {
        let r = REFERENCES[1];
        let scene = World::assignment(&r.scene(WATER_INDEX));
        let cam = Camera::new(r.observer, SCENE_CENTRE, 80, 60, 1.6);
        let p = scene
            .image_point(r.observer, cam.pixel_ray(20, 45).direction)
            .unwrap();
        let pic = cloud_picture(&scene, &cam, &[p], 1.0);
        assert!(has_section_hue(pic.pixel(20, 45), p.color));
        assert_eq!(pic.pixel(5, 5), [247, 247, 247]);
    }

    /// The square wave's mean over an interval, in closed form, is the mean of many points of it.
    #[test]
    fn square_wave_mean_is_the_mean_of_its_points() {
        let wave = |x: f64| if floor(x) & 1 == 0 { 1.0 } else { -1.0 };
        for &(x, h) in &[
            (0.3, 0.1),
            (0.95, 0.1),
            (-1.2, 0.5),
            (3.7, 1.3),
            (10.0, 2.5),
            (-0.01, 0.02),
        ] {
            let n = 200_000;
            let mean = (0..n)
                .map(|k| wave(x - h + 2.0 * h * (k as f64 + 0.5) / n as f64))
                .sum::<f64>()
                / n as f64;
            let closed = square_wave_mean(x, h);
            assert!(
                (closed - mean).abs() < 1e-4,
                "x {x} h {h}: {closed} vs {mean}"
            );
        }
        assert_eq!(square_wave_mean(0.5, 0.0), 1.0);
        assert_eq!(square_wave_mean(1.5, 0.0), -1.0);
    }

    /// A pixel that sees only the floor or only the wall gets its checkerboard's mean over the
    /// pixel: close to the mean of a fine grid of rays through it, much closer than its centre.
    #[test]
    fn a_pixel_of_backdrop_is_the_mean_of_the_rays_through_it() {
        let (mut sum_filtered, mut sum_centre, mut sum_jittered) = (0.0, 0.0, 0.0);
        let mut compared = 0;
        for eye in [
            Vec3::new(0.3, 0.1, 0.15),
            Vec3::new(-0.5, 0.6, 0.4),
            Vec3::new(1.5, -0.2, 0.3),
        ] {
            let s = Surroundings::new(Backdrop::Checker, eye);
            let cam = Camera::new(eye, SCENE_CENTRE, 64, 48, 1.2);
            let dc = cam.direction_at(0.0, 1.0) - cam.direction_at(0.0, 0.0);
            let dr = cam.direction_at(1.0, 0.0) - cam.direction_at(0.0, 0.0);
            for i in 0..cam.height {
                for j in 0..cam.width {
                    let m = 24;
                    let mut regions = Vec::new();
                    let mut mean = [0.0; 3];
                    for a in 0..m {
                        for b in 0..m {
                            let r = i as f64 + (a as f64 + 0.5) / m as f64;
                            let c = j as f64 + (b as f64 + 0.5) / m as f64;
                            let ray = Ray::new(eye, cam.direction_at(r, c));
                            regions.push(s.meet(ray.origin, ray.direction).0);
                            let colour = s.radiance(&ray);
                            for k in 0..3 {
                                mean[k] += colour[k] / (m * m) as f64;
                            }
                        }
                    }
                    // Only pixels wholly on one plane.
                    if regions.iter().any(|&g| g != regions[0]) || regions[0] == Region::Sky {
                        continue;
                    }
                    compared += 1;
                    let d = cam.direction_at(i as f64 + 0.5, j as f64 + 0.5);
                    let filtered = s.radiance_over_pixel(eye, d, dc, dr);
                    let centre = s.radiance(&Ray::new(eye, d));
                    let err =
                        |x: [f64; 3]| (0..3).map(|k| (x[k] - mean[k]).abs()).fold(0.0, f64::max);
                    // As the edges were drawn before: nine rays, one jittered in each cell.
                    let mut jittered = [0.0; 3];
                    for a in 0..3 {
                        for b in 0..3 {
                            let key = (((i * 64 + j) as u64) << 16) ^ (((a * 3 + b) as u64) << 1);
                            let r = i as f64 + (a as f64 + jitter(key)) / 3.0;
                            let c = j as f64 + (b as f64 + jitter(key | 1)) / 3.0;
                            let colour = s.radiance(&Ray::new(eye, cam.direction_at(r, c)));
                            for k in 0..3 {
                                jittered[k] += colour[k] / 9.0;
                            }
                        }
                    }
                    sum_filtered += err(filtered);
                    sum_centre += err(centre);
                    sum_jittered += err(jittered);
                }
            }
        }
        let n = compared as f64;
        let (filtered, centre, jittered) = (sum_filtered / n, sum_centre / n, sum_jittered / n);
        assert!(compared > 3000, "{compared} pixels compared");
        assert!(
            filtered < 0.3 * centre && filtered < jittered,
            "mean error: {filtered} averaged over the pixel, {centre} at its centre, {jittered} with nine jittered rays"
        );
    }

    /// Anti-aliased pictures are close to a brute-force one: every pixel the mean of 6x6 rays
    /// traced in double precision.
    #[test]
    fn antialiased_pictures_are_close_to_brute_force_supersampling() {
        for r in [REFERENCES[1], REFERENCES[2]] {
            let scene = World::assignment(&r.scene(WATER_INDEX));
            let cam = Camera::new(r.observer, SCENE_CENTRE, 96, 72, 1.0);
            let s = Surroundings::new(Backdrop::Checker, cam.eye);
            let light = light_direction(&s);
            let mode = ShadingMode::Fresnel { prune_below: 1e-4 };
            let mut opts = options(mode, 3);
            opts.outline = false;
            let pic = shaded_picture(&scene, &cam, &opts);
            let (mut off, mut total_error) = (0, 0.0);
            for i in 0..cam.height {
                for j in 0..cam.width {
                    let m = 6;
                    let mut mean = [0.0; 3];
                    for a in 0..m {
                        for b in 0..m {
                            let row = i as f64 + (a as f64 + 0.5) / m as f64;
                            let col = j as f64 + (b as f64 + 0.5) / m as f64;
                            let ray = Ray::new(cam.eye, cam.direction_at(row, col));
                            let c = sample(&scene, &s, light, mode, ray);
                            for k in 0..3 {
                                mean[k] += c[k] / (m * m) as f64;
                            }
                        }
                    }
                    let exact = mean.map(|c| linear_to_srgb(c) * 255.0);
                    let got = pic.pixel(i, j);
                    let e = (0..3)
                        .map(|k| (exact[k] - got[k] as f64).abs())
                        .fold(0.0, f64::max);
                    total_error += e;
                    if e > 12.0 {
                        off += 1;
                    }
                }
            }
            let pixels = (cam.width * cam.height) as f64;
            let (share, mean_error) = (off as f64 / pixels, total_error / pixels);
            assert!(
                share < 0.04 && mean_error < 3.0,
                "reference {}: {share} of the pixels off by more than 12 levels, mean {mean_error}",
                r.number
            );
        }
    }
}
