//! Choosing the rays: aim at what the observer can see of the glass and straw, and spend the rays
//! where they reach the straw, so that the image points cover the straw's image evenly.
//!
//! Directions from the observer are mapped onto a plane by Lambert's cylindrical equal-area
//! projection, its poles to the observer's left and right: `a` is the angle of a direction around the
//! horizontal right axis (up-down, measured from the direction of the scene's centre), `b` the sine of
//! its angle to that axis's normal plane (left-right). Equal areas of the `(a, b)` plane are equal solid
//! angles, so a uniform grid on it is a uniform sampling of the observer's field of view, however close
//! the observer stands and however wide the scene appears (up to the whole sphere).
//!
//! A coarse grid over the rectangle where the glass and straw appear is traced; the cells that reach
//! the straw, grown by one cell, are split in four and traced again, level after level; the last level
//! is a uniform grid whose spacing is chosen to give the requested number of points. The points are
//! thus the hits of one uniform grid of equal solid angles (even, no clumps), restricted to a band
//! around where the straw is seen (few wasted rays). Deterministic: the same inputs give the same
//! points in the same order, whatever the number of threads.

use std::f64::consts::PI;
use std::sync::atomic::{AtomicBool, Ordering};

use crate::parallel::*;

use crate::camera::view_basis;
use crate::geometry::Ray;
use crate::image::ImagePoint;
use crate::light_path_type::LightPathType;
use crate::spectrum::WHITE_BANDS;
use crate::world::World;
use crate::Vec3;

/// The equal-area map of the observer's directions, and the rectangle of it that is sampled.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionMap {
    /// Unit direction at the map's origin `(a, b) = (0, 0)`: towards the scene's centre.
    pub forward: Vec3,
    /// Unit horizontal right direction: the map's pole (`b = 1`).
    pub right: Vec3,
    /// Unit up direction, `right × forward`.
    pub up: Vec3,
    /// Smallest `a` (radians, around `right`, positive upwards).
    pub a_min: f64,
    /// Smallest `b` (sine of the angle towards `right`).
    pub b_min: f64,
    /// Extent of the sampled rectangle in `a`.
    pub width: f64,
    /// Extent of the sampled rectangle in `b`.
    pub height: f64,
}

impl DirectionMap {
    /// The unit direction at map point `(a, b)`.
    #[inline]
    pub fn direction(&self, a: f64, b: f64) -> Vec3 {
        let c = (1.0 - b * b).max(0.0).sqrt();
        let (sin_a, cos_a) = libm::sincos(a);
        c * (cos_a * self.forward + sin_a * self.up) + b * self.right
    }

    /// The map point `(a, b)` of a unit direction.
    #[inline]
    pub fn coordinates(&self, d: Vec3) -> (f64, f64) {
        (
            libm::atan2(d.dot(self.up), d.dot(self.forward)),
            d.dot(self.right).clamp(-1.0, 1.0),
        )
    }

    /// A whole-sphere map looking along `forward`, with right/up as in the observer's camera.
    pub fn looking(forward: Vec3) -> DirectionMap {
        let (f, right, up) = view_basis(forward);
        DirectionMap {
            forward: f,
            right,
            up,
            a_min: -PI,
            b_min: -1.0,
            width: 2.0 * PI,
            height: 2.0,
        }
    }
}

impl DirectionMap {
    /// The map of the directions from `observer`, cropped to where the box of corners `lo`, `hi`
    /// (holding everything that can be seen) can appear, looking at its centre.
    pub fn of_box(observer: Vec3, (lo, hi): (Vec3, Vec3)) -> DirectionMap {
        let mut frame = DirectionMap::looking(0.5 * (lo + hi) - observer);
        // Project points spread over the box; the box is convex, so its surface bounds what can be
        // seen.
        const N: usize = 48;
        let size = hi - lo;
        let (mut a0, mut a1, mut b0, mut b1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for axis in 0..3 {
            for side in [0.0, 1.0] {
                for p in 0..=N {
                    for q in 0..=N {
                        let mut unit = [0.0; 3];
                        unit[axis] = side;
                        unit[(axis + 1) % 3] = p as f64 / N as f64;
                        unit[(axis + 2) % 3] = q as f64 / N as f64;
                        let v = lo + Vec3::from_array(unit) * size - observer;
                        let (a, b) = frame.coordinates(v.normalize());
                        a0 = a0.min(a);
                        a1 = a1.max(a);
                        b0 = b0.min(b);
                        b1 = b1.max(b);
                    }
                }
            }
        }
        // A margin of a few coarse cells; all the way round if the scene wraps behind the observer.
        let pad = 0.02 * (a1 - a0).max(b1 - b0).max(f64::MIN_POSITIVE);
        if a1.max(-a0) > 0.9 * PI {
            (a0, a1) = (-PI, PI);
        }
        frame.a_min = (a0 - pad).max(-PI);
        frame.width = (a1 + pad).min(PI) - frame.a_min;
        frame.b_min = (b0 - pad).max(-1.0);
        frame.height = (b1 + pad).min(1.0) - frame.b_min;
        frame
    }
}

/// What a sampling run produced.
#[derive(Clone, Debug, Default)]
pub struct ImageCloud {
    /// The image points, in a deterministic order.
    pub points: Vec<ImagePoint>,
    /// Rays traced in all, coarse levels included.
    pub rays_traced: u64,
    /// Angular spacing of the final grid, on the image plane (dimensionless, ≈ radians near the centre).
    pub spacing: f64,
    /// Whether the rays carried white light (each point's `band` says which band), or light of
    /// the scene's one wavelength.
    pub white: bool,
}

impl ImageCloud {
    /// Fraction of the traced rays that reached the straw and became points.
    pub fn hit_ratio(&self) -> f64 {
        if self.rays_traced == 0 {
            0.0
        } else {
            self.points.len() as f64 / self.rays_traced as f64
        }
    }

    /// Points of each straw colour, codes 1..=5 at indices 0..=4 (other objects' not counted).
    pub fn counts_per_color(&self) -> [usize; 5] {
        let mut c = [0; 5];
        for p in &self.points {
            if let Some(n) = c.get_mut(p.color as usize - 1) {
                *n += 1;
            }
        }
        c
    }

    /// Points of each colour code 1..=8 at indices 0..=7 (straws' bands, coins, cards, pictures).
    pub fn counts_per_code(&self) -> [usize; crate::world::COLOR_COUNT] {
        let mut c = [0; crate::world::COLOR_COUNT];
        for p in &self.points {
            c[p.color as usize - 1] += 1;
        }
        c
    }
}

/// A grid cell `(i, j)` at some level: `i` along `a`, `j` along `b`.
type Cell = (u32, u32);

/// Cells along the longer side of the coarse grid.
const COARSE_CELLS: f64 = 128.0;
/// Levels of refinement allowed when the coarse grid sees no straw at all.
const BLIND_LEVELS: u32 = 2;

/// The kind of light path that makes each of `points` (image points seen from `observer`, or
/// anything `ray` gives a ray's first direction `u0` and band of white light of), in order, into
/// `paths`: the ray of each traced again in its band's world, its entry face and total
/// reflections noted. Once `stop` is set the rays left are not traced (their kinds are then
/// meaningless, and the caller throws them away).
pub fn light_path_types<P: Sync>(
    world: &World,
    observer: Vec3,
    points: &[P],
    ray: impl Fn(&P) -> (Vec3, Option<u8>) + Sync + Send,
    paths: &mut Vec<LightPathType>,
    stop: &AtomicBool,
) {
    points
        .par_iter()
        .map(|p| {
            if stop.load(Ordering::Relaxed) {
                return LightPathType::DIRECT;
            }
            let (direction, band) = ray(p);
            let world = band.map_or(world, |k| world.in_band(k as usize));
            world
                .trace_path_type(Ray {
                    origin: observer,
                    direction,
                })
                .1
        })
        .collect_into_vec(paths);
}

/// Traces rays from `world`'s `observer` and returns at least `min_points` image points of its
/// objects (fewer only if they are all but invisible from there). `progress` is told the rays
/// traced so far.
pub fn sample_image(
    world: &World,
    observer: Vec3,
    min_points: usize,
    progress: &(dyn Fn(u64) + Sync),
) -> ImageCloud {
    let never = AtomicBool::new(false);
    sample_image_until(world, observer, min_points, false, progress, &never)
        .expect("a stop flag never set does not stop the sampling")
}

/// [`sample_image`], in white light if `white`, abandoned (`None`) soon after `stop` is set:
/// every ray looks at the flag first, so a client that hangs up frees its worker within a ray's
/// time.
///
/// In white light each ray of the final grid carries one band of the spectrum, the bands taking
/// turns along the grid's rows and columns (so that every band covers the image evenly, with an
/// eighth of the points): the same rays, as many points, each traced in its band's world and
/// marked with its band. Where nothing disperses these are the points of one wavelength.
pub fn sample_image_until(
    world: &World,
    observer: Vec3,
    min_points: usize,
    white: bool,
    progress: &(dyn Fn(u64) + Sync),
    stop: &AtomicBool,
) -> Option<ImageCloud> {
    let stopped = || stop.load(Ordering::Relaxed);
    // The world each band's rays are traced in (the scene's alone in light of one wavelength).
    let bands: Vec<&World> = if white {
        (0..WHITE_BANDS).map(|k| world.in_band(k)).collect()
    } else {
        vec![world]
    };
    // Where the coarse levels look for the objects: in the spectrum's two ends, as the bands
    // between are bent between them (the dilation of the cells seen gives a margin); in one
    // world when the ends are one.
    let ends = [bands[0], bands[bands.len() - 1]];
    let ends = if std::ptr::eq(ends[0], ends[1]) {
        &ends[..1]
    } else {
        &ends[..]
    };
    let frame = DirectionMap::of_box(observer, world.bounds());
    let longest = frame.width.max(frame.height);
    let mut spacing = longest / COARSE_CELLS;
    let mut rays = 0u64;

    // Level 0: every cell.
    let (nx, ny) = grid_size(&frame, spacing);
    let mut cells: Vec<Cell> = (0..ny).flat_map(|j| (0..nx).map(move |i| (i, j))).collect();
    // Whether the ray through each cell's centre reaches an object (no image point is built),
    // and how many rays that took (one per end of the spectrum looked in, until one reaches).
    let trace_cells = |cells: &[Cell], spacing: f64| -> Vec<(bool, u8)> {
        cells
            .par_iter()
            .with_min_len(256)
            .map(|&(i, j)| {
                if stopped() {
                    return (false, 0);
                }
                let a = frame.a_min + (i as f64 + 0.5) * spacing;
                let b = frame.b_min + (j as f64 + 0.5) * spacing;
                let ray = Ray {
                    origin: observer,
                    direction: frame.direction(a, b),
                };
                let mut traced = 0;
                let hit = ends.iter().any(|w| {
                    traced += 1;
                    w.trace(ray).color() > 0
                });
                (hit, traced)
            })
            .collect()
    };

    let mut blind = 0;
    loop {
        let hit = trace_cells(&cells, spacing);
        if stopped() {
            return None;
        }
        rays += hit.iter().map(|&(_, traced)| traced as u64).sum::<u64>();
        progress(rays);
        let hits: Vec<Cell> = cells
            .iter()
            .zip(&hit)
            .filter(|(_, h)| h.0)
            .map(|(c, _)| *c)
            .collect();
        if hits.is_empty() {
            if blind == BLIND_LEVELS {
                return Some(ImageCloud {
                    points: Vec::new(),
                    rays_traced: rays,
                    spacing,
                    white,
                });
            }
            blind += 1;
            cells = split(&cells);
            spacing /= 2.0;
            continue;
        }
        // Spacing that would give about 10% more than the points asked for.
        let target = spacing * (hits.len() as f64 / (1.1 * min_points as f64)).sqrt();
        let active = dilate(&hits, &frame, spacing);
        if spacing / 2.0 > target {
            cells = split(&active);
            spacing /= 2.0;
            continue;
        }
        // Final level: a uniform grid of spacing `h`, traced where the last level saw the straw.
        let mut h = target.min(spacing);
        loop {
            let points = final_level(
                &bands, white, observer, &frame, &active, spacing, h, &mut rays, stop,
            );
            if stopped() {
                return None;
            }
            progress(rays);
            if points.len() >= min_points || h < 1e-7 * longest {
                return Some(ImageCloud {
                    points,
                    rays_traced: rays,
                    spacing: h,
                    white,
                });
            }
            h /= (min_points as f64 / points.len().max(1) as f64).sqrt() * 1.02;
        }
    }
}

/// Cells of the grid at `spacing`: `(nx, ny)`.
fn grid_size(f: &DirectionMap, spacing: f64) -> (u32, u32) {
    (
        (f.width / spacing).ceil().max(1.0) as u32,
        (f.height / spacing).ceil().max(1.0) as u32,
    )
}

/// The four children of every cell.
fn split(cells: &[Cell]) -> Vec<Cell> {
    let mut out = Vec::with_capacity(4 * cells.len());
    for &(i, j) in cells {
        for (di, dj) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            out.push((2 * i + di, 2 * j + dj));
        }
    }
    out
}

/// The cells that are hits or touch one (8-neighbourhood), sorted.
///
/// Marks a bitmap of the grid (cheaper than hashing: one bit per cell, and reading the bits in
/// order gives the cells already sorted as `(i, j)`).
fn dilate(hits: &[Cell], frame: &DirectionMap, spacing: f64) -> Vec<Cell> {
    let (nx, ny) = grid_size(frame, spacing);
    let (nx, ny) = (nx as usize, ny as usize);
    let mut bits = vec![0u64; (nx * ny).div_ceil(64)];
    for &(i, j) in hits {
        let (i, j) = (i as usize, j as usize);
        for ii in i.saturating_sub(1)..=(i + 1).min(nx - 1) {
            for jj in j.saturating_sub(1)..=(j + 1).min(ny - 1) {
                let n = ii * ny + jj;
                bits[n / 64] |= 1 << (n % 64);
            }
        }
    }
    let mut cells = Vec::with_capacity(hits.len() * 2);
    for (w, &word) in bits.iter().enumerate() {
        let mut word = word;
        while word != 0 {
            let n = w * 64 + word.trailing_zeros() as usize;
            word &= word - 1;
            cells.push(((n / ny) as u32, (n % ny) as u32));
        }
    }
    cells
}

/// Traces the points of the uniform grid of spacing `h` whose centres lie in `active` cells (of
/// size `spacing`), and returns the image points, in cell order (cut short once `stop` is set).
/// The ray of grid point `(i, j)` is traced in world `bands[(i + 3j) mod bands.len()]`, its
/// point marked with that band if the light is `white`.
#[allow(clippy::too_many_arguments)]
fn final_level(
    bands: &[&World],
    white: bool,
    observer: Vec3,
    frame: &DirectionMap,
    active: &[Cell],
    spacing: f64,
    h: f64,
    rays: &mut u64,
    stop: &AtomicBool,
) -> Vec<ImagePoint> {
    // Final-grid indices whose centres (index + 0.5)·h fall in [lo, hi) of a cell.
    let range = |cell_index: u32| -> (u64, u64) {
        let lo = cell_index as f64 * spacing;
        let hi = lo + spacing;
        let first = ((lo / h) - 0.5).ceil().max(0.0) as u64;
        let end = ((hi / h) - 0.5).ceil().max(0.0) as u64;
        (first, end)
    };
    // Chunks of cells per task: enough work per task, one vector per chunk, order kept.
    let per_cell: Vec<(u64, Vec<ImagePoint>)> = active
        .par_chunks(64)
        .map(|chunk| {
            let mut pts = Vec::new();
            let mut n = 0;
            for &(i, j) in chunk {
                if stop.load(Ordering::Relaxed) {
                    break;
                }
                let (i0, i1) = range(i);
                let (j0, j1) = range(j);
                for jj in j0..j1 {
                    let b = frame.b_min + (jj as f64 + 0.5) * h;
                    if b > frame.b_min + frame.height {
                        continue;
                    }
                    for ii in i0..i1 {
                        let a = frame.a_min + (ii as f64 + 0.5) * h;
                        if a > frame.a_min + frame.width {
                            continue;
                        }
                        n += 1;
                        // Neighbouring rays carry different bands: three apart along a column,
                        // one apart along a row.
                        let band = (ii + 3 * jj) as usize % bands.len();
                        let u0 = frame.direction(a, b);
                        if let Some(mut p) = bands[band].image_point(observer, u0) {
                            p.band = white.then_some(band as u8);
                            pts.push(p);
                        }
                    }
                }
            }
            (n, pts)
        })
        .collect();
    let mut points = Vec::with_capacity(per_cell.iter().map(|c| c.1.len()).sum());
    for (n, pts) in per_cell {
        *rays += n;
        points.extend(pts);
    }
    points
}
