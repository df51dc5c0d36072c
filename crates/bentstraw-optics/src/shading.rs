//! The observer's picture for people: anti-aliased, the straw in its section colours, a light
//! backdrop seen through (and reflected by) the water, the glass outlined; and the point cloud seen
//! through the same camera, for comparison.
//!
//! Everything is computed in linear light and encoded as sRGB bytes at the end; the section
//! colours of SPEC §1 are display (sRGB) values, so a pixel wholly on one section, facing the light,
//! shows exactly that colour.
//!
//! The surroundings (chosen here; SPEC §6 is silent on them):
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

use rayon::prelude::*;

use crate::camera::Camera;
use crate::geometry::Ray;
use crate::image::ImagePoint;
use crate::packet::{BranchEnd, FresnelWave, PacketTracer};
use crate::scene::{Scene, GLASS_HEIGHT, GLASS_RADIUS, SECTION_RGB};
#[cfg(test)]
use crate::trace::{
    follow_fresnel, follow_ray, FresnelStep, NearestFace, Outcome, FRESNEL_SEGMENTS_PER_RAY,
};
use crate::trace::{Face, FRESNEL_SEGMENTS_PER_PIXEL};
#[cfg(test)]
use crate::tracer::Tracer;
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
    /// SPEC §3: one ray, refracted or totally reflected at each water face.
    Course,
    /// SPEC §6: reflected and refracted branches weighted by the Fresnel reflectance; branches
    /// lighter than `prune_below` are abandoned.
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
    /// Whether to draw the glass's outline.
    pub outline: bool,
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
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// Linear light to an sRGB display value (0..1), clamped.
#[inline]
pub fn linear_to_srgb(c: f64) -> f64 {
    let c = c.clamp(0.0, 1.0);
    if c <= 0.0031308 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// Entries of the tables that replace `powf` in the picture's inner loops (a picture needs a few
/// conversions per ray; `powf` was most of a picture's time). Linear interpolation between entries
/// is within 2e-5 of the exact curve, a hundredth of one 8-bit level.
const CURVE_STEPS: usize = 4096;

/// `f` sampled at `CURVE_STEPS + 1` evenly spaced points of `[0, 1]`.
fn curve_table(f: fn(f64) -> f64) -> Vec<f64> {
    (0..=CURVE_STEPS)
        .map(|k| f(k as f64 / CURVE_STEPS as f64))
        .collect()
}

/// `table`'s curve at `c` (clamped to `[0, 1]`), interpolated linearly.
#[inline]
fn lookup(table: &[f64], c: f64) -> f64 {
    let x = c.clamp(0.0, 1.0) * CURVE_STEPS as f64;
    let k = (x as usize).min(CURVE_STEPS - 1);
    let t = x - k as f64;
    table[k] + t * (table[k + 1] - table[k])
}

static TO_LINEAR: std::sync::OnceLock<Vec<f64>> = std::sync::OnceLock::new();
static TO_SRGB: std::sync::OnceLock<Vec<f64>> = std::sync::OnceLock::new();

/// [`srgb_to_linear`] by table, for the inner loops.
#[inline]
fn srgb_to_linear_fast(c: f64) -> f64 {
    lookup(TO_LINEAR.get_or_init(|| curve_table(srgb_to_linear)), c)
}

/// [`linear_to_srgb`] by table, for the inner loops.
#[inline]
fn linear_to_srgb_fast(c: f64) -> f64 {
    lookup(TO_SRGB.get_or_init(|| curve_table(linear_to_srgb)), c)
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
}

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

    /// Linear colour at plane coordinates `(a, b)` (squares of [`CHECKER_SIDE`]); the contrast
    /// shrinks by `fade` (far squares would only alias).
    #[inline]
    fn at(&self, a: f64, b: f64, fade: f64) -> [f64; 3] {
        let parity = (floor(a / CHECKER_SIDE) + floor(b / CHECKER_SIDE)) & 1;
        let square = if parity == 0 { self.light } else { self.dark };
        mix(self.average, square, fade)
    }
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

    /// Linear RGB of what `ray` (in air, leaving the scene) meets.
    // Inline: a call would store the ray the packet tracer just made and load it back at once,
    // in wider pieces than it was stored (a stall on every one of millions of calls).
    #[inline(always)]
    pub fn radiance(&self, ray: &Ray) -> [f64; 3] {
        let (o, d) = (ray.origin, ray.direction);
        if self.backdrop == Backdrop::Plain {
            // A gentle vertical gradient: flat enough to be "plain", enough for the water to show.
            let [down, up] = self.plain;
            return [down + (up - down) * (0.5 + 0.5 * d.z); 3];
        }
        // The nearer of the floor and the wall is found first; only its colour is worked out.
        let mut best = f64::INFINITY;
        let mut on_floor = false;
        // A ray leaving the water's bottom starts on z = 0 to rounding (a hair below it in single
        // precision): it still meets the floor there.
        if self.floor && d.z < 0.0 && o.z >= -FLOOR_TOLERANCE {
            let t = (-o.z / d.z).max(0.0);
            // The floor ends at the wall.
            if (o + t * d).dot(self.toward_eye) >= -WALL_DISTANCE {
                best = t;
                on_floor = true;
            }
        }
        let s = d.dot(self.toward_eye);
        if s < 0.0 {
            let t = (-WALL_DISTANCE - o.dot(self.toward_eye)) / s;
            if t >= 0.0 && t < best {
                let z = o.z + t * d.z;
                let bottom = if self.floor { 0.0 } else { -WALL_TOP };
                if z >= bottom && z <= WALL_TOP {
                    let u = (o + t * d).dot(self.along_wall);
                    // Fading as 1 / (1 + (u / 0.6)²), written with one division.
                    let fade = FADE2 / (FADE2 + u * u);
                    return self.wall_squares.at(u, z, fade);
                }
            }
        }
        if on_floor {
            let p = o + best * d;
            let fade = FADE2 / (FADE2 + p.x * p.x + p.y * p.y);
            return self.floor_squares.at(p.x, p.y, fade);
        }
        mix(self.sky[0], self.sky[1], d.z.max(0.0))
    }
}

/// Unit direction of the light that shades the straw (from the observer's side, above, left).
fn light_direction(s: &Surroundings) -> Vec3 {
    (s.toward_eye + 0.8 * Vec3::Z + 0.5 * s.toward_eye.cross(Vec3::Z)).normalize()
}

/// Linear colour of the straw's section `color` at `point` of `face`, gently shaded.
fn straw_radiance(scene: &Scene, light: Vec3, color: u8, face: Face, point: Vec3) -> [f64; 3] {
    let normal = match face {
        Face::StrawTop => Vec3::Z,
        Face::StrawBottom => Vec3::NEG_Z,
        _ => Vec3::new(point.x - scene.straw_x, point.y - scene.straw_y, 0.0).normalize_or_zero(),
    };
    let shade = 0.62 + 0.38 * normal.dot(light).max(0.0);
    linear(SECTION_RGB[color as usize - 1]).map(|c| c * shade)
}

/// The straw's face at a point `p` on it (from the packet tracer, which reports points only):
/// the caps within a micrometre of their planes, else the side.
fn straw_face_at(p: Vec3) -> Face {
    if p.z >= crate::scene::STRAW_HEIGHT - 1e-6 {
        Face::StrawTop
    } else if p.z <= 1e-6 {
        Face::StrawBottom
    } else {
        Face::StrawSide
    }
}

/// Linear colour seen along one ray, traced in double precision by `tracer`: the reference the
/// packet-traced pictures are checked against.
#[cfg(test)]
fn sample(
    tracer: &impl NearestFace,
    scene: &Scene,
    surroundings: &Surroundings,
    light: Vec3,
    mode: ShadingMode,
    ray: Ray,
) -> [f64; 3] {
    match mode {
        ShadingMode::Course => {
            let mut last = ray;
            let outcome = follow_ray(tracer, scene, ray, |e| {
                last = Ray {
                    origin: e.point,
                    direction: e.outgoing,
                }
            });
            match outcome {
                Outcome::Straw {
                    color, point, face, ..
                } => straw_radiance(scene, light, color, face, point),
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
            follow_fresnel::<false>(
                tracer,
                scene,
                ray,
                prune_below,
                FRESNEL_SEGMENTS_PER_RAY,
                |step| match step {
                    FresnelStep::Straw {
                        color,
                        point,
                        face,
                        weight,
                        ..
                    } => add(straw_radiance(scene, light, color, face, point), weight),
                    FresnelStep::Escaped { ray, weight, .. } => {
                        add(surroundings.radiance(&ray), weight)
                    }
                    // Dropped and pruned weight is light not followed: it adds nothing (dark).
                    _ => {}
                },
            );
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
/// a `samples × samples` grid over the pixel, jittered inside its cell (deterministically). Smooth
/// pixels keep their centre: the picture is then the same as a full supersampling to within a
/// few grey levels, several times faster.
pub fn shaded_picture(scene: &Scene, camera: &Camera, options: &ShadingOptions) -> RgbPicture {
    let mut picture = RgbPicture::default();
    shaded_picture_into(
        scene,
        camera,
        options,
        &mut ShadingBuffers::default(),
        &mut picture,
    );
    picture
}

/// Work space of [`shaded_picture_into`], kept from one picture to the next.
#[derive(Clone, Debug, Default)]
pub struct ShadingBuffers {
    centre: Vec<[f64; 3]>,
    display: Vec<[f64; 3]>,
    /// The glass outline's coverage per pixel.
    mask: Vec<f64>,
    /// Rows done of the picture being drawn, out of twice its height (centres, then edges).
    rows_done: Arc<AtomicU64>,
    /// Set by another thread to abandon the picture being drawn.
    stop: Arc<AtomicBool>,
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
}

/// [`shaded_picture`] into `picture`, reusing its pixels and `buffers` (an interactive view
/// redraws with no allocation once the size stops changing).
pub fn shaded_picture_into(
    scene: &Scene,
    camera: &Camera,
    options: &ShadingOptions,
    buffers: &mut ShadingBuffers,
    picture: &mut RgbPicture,
) {
    let (w, h) = (camera.width as usize, camera.height as usize);
    let surroundings = Surroundings::new(options.backdrop, camera.eye);
    let light = light_direction(&surroundings);
    let n = options.samples.max(1) as usize;
    let rows_done = &*buffers.rows_done;
    rows_done.store(0, Ordering::Relaxed);
    let stop = &*buffers.stop;
    let stopped = || stop.load(Ordering::Relaxed);
    let centre = &mut buffers.centre;
    centre.resize(w * h, [0.0; 3]);
    // Pixel centres: the single-precision packet tracer, eight rays at a time (most of a
    // picture's rays); the samples at edges below stay in double precision.
    let packets = PacketTracer::new(scene);
    let (split, prune) = match options.mode {
        ShadingMode::Course => (false, 0.0),
        ShadingMode::Fresnel { prune_below } => (true, prune_below),
    };
    // The linear colour and weight a branch's end adds to its pixel.
    let shade_end = |end: BranchEnd| -> Option<([f64; 3], f64)> {
        let v = |a: [f32; 3]| Vec3::new(a[0] as f64, a[1] as f64, a[2] as f64);
        match end {
            BranchEnd::Straw {
                code,
                point,
                weight,
            } => {
                let p = v(point);
                Some((
                    straw_radiance(scene, light, code, straw_face_at(p), p),
                    weight as f64,
                ))
            }
            BranchEnd::Escaped {
                origin,
                direction,
                weight,
            } => {
                let ray = Ray {
                    origin: v(origin),
                    direction: v(direction),
                };
                Some((surroundings.radiance(&ray), weight as f64))
            }
            // Light not followed: dark in course mode (as `sample` shows it), nothing added in
            // Fresnel mode.
            BranchEnd::Dropped { weight } if !split => Some(([0.05; 3], weight as f64)),
            BranchEnd::Dropped { .. } => None,
        }
    };
    centre
        .par_chunks_mut(w)
        .enumerate()
        .for_each_init(FresnelWave::default, |wave, (i, row)| {
            if stopped() {
                return;
            }
            row.fill([0.0; 3]);
            let mut on_end = |j: usize, end: BranchEnd| {
                if let Some((colour, weight)) = shade_end(end) {
                    let px = &mut row[j];
                    for k in 0..3 {
                        px[k] += weight * colour[k];
                    }
                }
            };
            packets.branch_ends_row(camera, i as u32, split, prune, wave, &mut on_end);
            for px in row.iter_mut() {
                *px = px.map(linear_to_srgb_fast);
            }
            rows_done.fetch_add(1, Ordering::Relaxed);
        });
    let centre = &buffers.centre;
    let display = &mut buffers.display;
    display.clear();
    display.extend_from_slice(centre);
    if n > 1 {
        let edge = |i: usize, j: usize| {
            let c = centre[i * w + j];
            let (i0, i1) = (i.saturating_sub(1), (i + 1).min(h - 1));
            let (j0, j1) = (j.saturating_sub(1), (j + 1).min(w - 1));
            (i0..=i1).any(|a| {
                (j0..=j1).any(|b| {
                    let d = centre[a * w + b];
                    (0..3).any(|k| (d[k] - c[k]).abs() > SMOOTH_CONTRAST)
                })
            })
        };
        // The edges' samples, a row at a time, through the packet tracer as the centres.
        let eye = camera.eye;
        let per_pixel = n * n;
        // A pixel's samples share the pixel's bound on Fresnel work, but each may follow at least
        // 64 segments (ordinary rays need a few dozen).
        let max_segments = (FRESNEL_SEGMENTS_PER_PIXEL / per_pixel as u32).max(64);
        display.par_chunks_mut(w).enumerate().for_each_init(
            || (FresnelWave::default(), Vec::new(), Vec::new(), Vec::new()),
            |(wave, edges, dirs, acc), (i, row)| {
                if stopped() {
                    return;
                }
                edges.clear();
                dirs.clear();
                for j in 0..w {
                    if !edge(i, j) {
                        continue;
                    }
                    edges.push(j);
                    for a in 0..n {
                        for b in 0..n {
                            let key = (((i * w + j) as u64) << 16) ^ (((a * n + b) as u64) << 1);
                            let r = i as f64 + (a as f64 + jitter(key)) / n as f64;
                            let c = j as f64 + (b as f64 + jitter(key | 1)) / n as f64;
                            dirs.push(camera.direction_at(r, c).normalize());
                        }
                    }
                }
                if edges.is_empty() {
                    rows_done.fetch_add(1, Ordering::Relaxed);
                    return;
                }
                acc.clear();
                acc.resize(edges.len(), [0.0f64; 3]);
                packets.branch_ends(
                    eye,
                    dirs,
                    split,
                    prune,
                    max_segments,
                    wave,
                    &mut |k, end| {
                        if let Some((colour, weight)) = shade_end(end) {
                            let px = &mut acc[k / per_pixel];
                            for c in 0..3 {
                                px[c] += weight * colour[c];
                            }
                        }
                    },
                );
                let inv = 1.0 / per_pixel as f64;
                for (&j, sum) in edges.iter().zip(acc.iter()) {
                    row[j] = sum.map(|c| linear_to_srgb_fast(c * inv));
                }
                rows_done.fetch_add(1, Ordering::Relaxed);
            },
        );
    }
    rows_done.store(2 * h as u64, Ordering::Relaxed);
    if options.outline {
        draw_glass_outline(display, &mut buffers.mask, camera);
    }
    encode_into(camera, display, picture);
}

/// The image points seen through `camera` (its eye should be their observer): each a disc of
/// `radius` pixels in its section colour, nearer points over farther ones, on a plain light
/// background with the glass outlined, for side-by-side comparison with [`shaded_picture`].
pub fn cloud_picture(camera: &Camera, points: &[ImagePoint], radius: f64) -> RgbPicture {
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
        let colour = SECTION_RGB[p.color as usize - 1];
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
    draw_glass_outline(&mut display, &mut Vec::new(), camera);
    encode(camera, &display)
}

fn encode(camera: &Camera, display: &[[f64; 3]]) -> RgbPicture {
    let mut picture = RgbPicture::default();
    encode_into(camera, display, &mut picture);
    picture
}

fn encode_into(camera: &Camera, display: &[[f64; 3]], picture: &mut RgbPicture) {
    picture.width = camera.width;
    picture.height = camera.height;
    picture.pixels.resize(display.len() * 3, 0);
    // `x + 0.5` truncated is `x.round()` for x ≥ 0, without a call into libm per channel.
    picture
        .pixels
        .par_chunks_mut(3 * 4096)
        .zip(display.par_chunks(4096))
        .for_each(|(out, px)| {
            for (o, c) in out.iter_mut().zip(px.iter().flatten()) {
                *o = (c.clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
            }
        });
}

/// Draws the glass's outline over `display` (sRGB values): rim and base circles (the part on the
/// observer's side stronger, the far side fainter; a circle seen from its open side wholly strong)
/// and the two vertical silhouette lines.
fn draw_glass_outline(display: &mut [[f64; 3]], mask: &mut Vec<f64>, camera: &Camera) {
    const STRONG: f64 = 0.75;
    const FAINT: f64 = 0.3;
    const STEPS: usize = 720;
    let (w, h) = (camera.width as usize, camera.height as usize);
    let width = (camera.height as f64 / 400.0).clamp(1.0, 4.0);
    mask.clear();
    mask.resize(w * h, 0.0);
    let eye = camera.eye;
    let eye_r = (eye.x * eye.x + eye.y * eye.y).sqrt();
    let circle = |a: f64, z: f64| Vec3::new(GLASS_RADIUS * a.cos(), GLASS_RADIUS * a.sin(), z);
    for (z, seen_inside) in [(GLASS_HEIGHT, eye.z > GLASS_HEIGHT), (0.0, eye.z < 0.0)] {
        for k in 0..STEPS {
            let a0 = k as f64 * std::f64::consts::TAU / STEPS as f64;
            let a1 = (k + 1) as f64 * std::f64::consts::TAU / STEPS as f64;
            let mid = 0.5 * (a0 + a1);
            let near_side = eye.x * mid.cos() + eye.y * mid.sin() > GLASS_RADIUS;
            let alpha = if seen_inside || near_side {
                STRONG
            } else {
                FAINT
            };
            stroke(mask, camera, circle(a0, z), circle(a1, z), width, alpha);
        }
    }
    if eye_r > GLASS_RADIUS {
        let towards = eye.y.atan2(eye.x);
        let half = (GLASS_RADIUS / eye_r).acos();
        for a in [towards - half, towards + half] {
            stroke(
                mask,
                camera,
                circle(a, 0.0),
                circle(a, GLASS_HEIGHT),
                width,
                STRONG,
            );
        }
    }
    let ink = [0.16, 0.18, 0.24];
    for (px, &m) in display.iter_mut().zip(mask.iter()) {
        if m > 0.0 {
            *px = mix(*px, ink, m);
        }
    }
}

/// Marks in `mask` (the strongest wins) an anti-aliased line of `width` pixels from the picture
/// of `p` to that of `q`, at opacity `alpha`; long 3D segments are cut so that their pictures
/// stay straight enough, and pieces behind the eye are skipped.
fn stroke(mask: &mut [f64], camera: &Camera, p: Vec3, q: Vec3, width: f64, alpha: f64) {
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

    fn options(mode: ShadingMode, samples: u32) -> ShadingOptions {
        ShadingOptions {
            mode,
            backdrop: Backdrop::Checker,
            samples,
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
            let scene = r.scene(WATER_INDEX);
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
        let scene = r.scene(WATER_INDEX);
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

    /// The picture's rays go through the prepared tracer; every sample must be what the scene's
    /// own (plain) tracer sees along the same ray.
    #[test]
    fn prepared_tracer_shades_as_the_scene_tracer() {
        for r in REFERENCES {
            let scene = r.scene(WATER_INDEX);
            let tracer = Tracer::new(&scene);
            let cam = Camera::new(r.observer, SCENE_CENTRE, 64, 48, 1.6);
            let s = Surroundings::new(Backdrop::Checker, cam.eye);
            let light = light_direction(&s);
            for mode in [
                ShadingMode::Course,
                ShadingMode::Fresnel { prune_below: 1e-4 },
            ] {
                for i in 0..cam.height {
                    for j in 0..cam.width {
                        let ray = cam.pixel_ray(i, j);
                        let fast = sample(&tracer, &scene, &s, light, mode, ray);
                        let plain = sample(&scene, &scene, &s, light, mode, ray);
                        assert_eq!(fast, plain, "pixel ({i}, {j}) of reference {}", r.number);
                    }
                }
            }
        }
    }

    /// Pixel centres come from the single-precision packet tracer: they must be what the
    /// double-precision tracer sees there, but for a few pixels on the picture's boundaries.
    #[test]
    fn packet_centres_shade_as_the_double_precision_tracer() {
        for r in REFERENCES {
            let scene = r.scene(WATER_INDEX);
            let tracer = Tracer::new(&scene);
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
                        let exact = sample(&tracer, &scene, &s, light, mode, cam.pixel_ray(i, j))
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

    /// A buffer reused across sizes holds nothing of the previous picture.
    #[test]
    fn reused_buffers_give_the_fresh_picture() {
        let r = REFERENCES[2];
        let scene = r.scene(WATER_INDEX);
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
        let scene = r.scene(WATER_INDEX);
        let cam = Camera::new(r.observer, SCENE_CENTRE, 80, 60, 1.6);
        let p = scene
            .image_point(r.observer, cam.pixel_ray(20, 45).direction)
            .unwrap();
        let pic = cloud_picture(&cam, &[p], 1.0);
        assert!(has_section_hue(pic.pixel(20, 45), p.color));
        assert_eq!(pic.pixel(5, 5), [247, 247, 247]);
    }
}
