//! Choosing the rays: aim at what the observer can see of the glass and straw, and spend the rays
//! where they reach the straw, so that the image points cover the straw's image evenly.
//!
//! Directions are laid out on the image plane of a pinhole camera at the observer (gnomonic
//! coordinates `(a, b)`: direction `f + a·r + b·u`), one frame framing the glass and straw, or the six
//! faces of a cube around the observer when it stands so close that no single frame can hold them.
//! A coarse grid over the frame is traced; the cells that reach the straw, grown by one cell, are
//! split in four and traced again, level after level; the last level is a uniform grid whose spacing
//! is chosen to give the requested number of points. The points are thus the hits of a uniform grid
//! on the image plane (even, no clumps), restricted to a band around where the straw is seen (few
//! wasted rays). Deterministic: the same inputs give the same points in the same order, whatever the
//! number of threads.

use rayon::prelude::*;

use crate::geometry::Ray;
use crate::image::ImagePoint;
use crate::scene::{Scene, GLASS_RADIUS, STRAW_HEIGHT};
use crate::tracer::Tracer;
use crate::Vec3;

/// The image plane of one viewing frame, and the rectangle of it that is sampled.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// Unit forward direction (the centre of the image plane).
    pub forward: Vec3,
    /// Unit right direction.
    pub right: Vec3,
    /// Unit up direction.
    pub up: Vec3,
    /// Smallest `a` (along `right`).
    pub a_min: f64,
    /// Smallest `b` (along `up`).
    pub b_min: f64,
    /// Width of the sampled rectangle in `a`.
    pub width: f64,
    /// Height of the sampled rectangle in `b`.
    pub height: f64,
}

impl Frame {
    /// The unit direction through the image-plane point `(a, b)`.
    #[inline]
    pub fn direction(&self, a: f64, b: f64) -> Vec3 {
        (self.forward + a * self.right + b * self.up).normalize()
    }

    /// A frame looking along `forward`, with right/up as in the camera of SPEC §6.
    pub fn looking(forward: Vec3) -> Frame {
        let f = forward.normalize();
        let c = f.cross(Vec3::Z);
        let right = if c.length() < 1e-9 {
            Vec3::X
        } else {
            c.normalize()
        };
        let up = right.cross(f);
        Frame {
            forward: f,
            right,
            up,
            a_min: -1.0,
            b_min: -1.0,
            width: 2.0,
            height: 2.0,
        }
    }
}

/// The frames that together see everything of the glass and straw from `observer`.
pub fn frames_for(observer: Vec3) -> Vec<Frame> {
    let r = GLASS_RADIUS;
    let corners = [
        Vec3::new(-r, -r, 0.0),
        Vec3::new(r, -r, 0.0),
        Vec3::new(-r, r, 0.0),
        Vec3::new(r, r, 0.0),
        Vec3::new(-r, -r, STRAW_HEIGHT),
        Vec3::new(r, -r, STRAW_HEIGHT),
        Vec3::new(-r, r, STRAW_HEIGHT),
        Vec3::new(r, r, STRAW_HEIGHT),
    ];
    let centre = Vec3::new(0.0, 0.0, STRAW_HEIGHT / 2.0);
    let mut frame = Frame::looking(centre - observer);
    let (mut a0, mut a1, mut b0, mut b1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    let mut fits = true;
    for c in corners {
        let v = c - observer;
        let w = v.dot(frame.forward);
        // Past about 70° off-axis the plane stretches too much: use the cube instead.
        if w <= 0.35 * v.length() {
            fits = false;
            break;
        }
        let (a, b) = (v.dot(frame.right) / w, v.dot(frame.up) / w);
        a0 = a0.min(a);
        a1 = a1.max(a);
        b0 = b0.min(b);
        b1 = b1.max(b);
    }
    if fits {
        let pad = 0.02 * (a1 - a0).max(b1 - b0);
        frame.a_min = a0 - pad;
        frame.b_min = b0 - pad;
        frame.width = a1 - a0 + 2.0 * pad;
        frame.height = b1 - b0 + 2.0 * pad;
        return vec![frame];
    }
    // Too close for one frame: the six faces of a cube around the observer, each cropped to the
    // part where the glass or straw can appear (found by projecting points spread over the box).
    let mut faces: Vec<(Frame, [f64; 4])> = [
        Vec3::X,
        Vec3::NEG_X,
        Vec3::Y,
        Vec3::NEG_Y,
        Vec3::Z,
        Vec3::NEG_Z,
    ]
    .into_iter()
    .map(|f| {
        // Make the six faces' right/up well defined even when forward is ±z.
        let up_hint = if f.z.abs() > 0.5 { Vec3::Y } else { Vec3::Z };
        let right = f.cross(up_hint).normalize();
        let up = right.cross(f);
        let frame = Frame {
            forward: f,
            right,
            up,
            a_min: -1.0,
            b_min: -1.0,
            width: 2.0,
            height: 2.0,
        };
        (frame, [f64::MAX, f64::MIN, f64::MAX, f64::MIN])
    })
    .collect();
    const N: usize = 48;
    let lo = Vec3::new(-r, -r, 0.0);
    let size = Vec3::new(2.0 * r, 2.0 * r, STRAW_HEIGHT);
    for axis in 0..3 {
        for side in [0.0, 1.0] {
            for p in 0..=N {
                for q in 0..=N {
                    let (s, t) = (p as f64 / N as f64, q as f64 / N as f64);
                    let mut unit = [0.0; 3];
                    unit[axis] = side;
                    unit[(axis + 1) % 3] = s;
                    unit[(axis + 2) % 3] = t;
                    let v = lo + Vec3::from_array(unit) * size - observer;
                    // The cube face this point projects onto: its largest component.
                    let (k, w) = faces
                        .iter()
                        .enumerate()
                        .map(|(k, (f, _))| (k, v.dot(f.forward)))
                        .fold((0, f64::MIN), |best, x| if x.1 > best.1 { x } else { best });
                    let (f, bounds) = &mut faces[k];
                    let (a, b) = (v.dot(f.right) / w, v.dot(f.up) / w);
                    bounds[0] = bounds[0].min(a);
                    bounds[1] = bounds[1].max(a);
                    bounds[2] = bounds[2].min(b);
                    bounds[3] = bounds[3].max(b);
                }
            }
        }
    }
    faces
        .into_iter()
        .filter(|(_, b)| b[0] <= b[1])
        .map(|(mut f, b)| {
            let pad = 0.05;
            let (a0, a1) = ((b[0] - pad).max(-1.0), (b[1] + pad).min(1.0));
            let (b0, b1) = ((b[2] - pad).max(-1.0), (b[3] + pad).min(1.0));
            f.a_min = a0;
            f.b_min = b0;
            f.width = a1 - a0;
            f.height = b1 - b0;
            f
        })
        .collect()
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

    /// Points of each colour, codes 1..=5 at indices 0..=4.
    pub fn counts_per_color(&self) -> [usize; 5] {
        let mut c = [0; 5];
        for p in &self.points {
            c[p.color as usize - 1] += 1;
        }
        c
    }
}

/// A grid cell `(frame, i, j)` at some level.
type Cell = (u32, u32, u32);

/// Cells along the longer side of the coarse grid, per frame.
const COARSE_CELLS: f64 = 128.0;
/// Levels of refinement allowed when the coarse grid sees no straw at all.
const BLIND_LEVELS: u32 = 2;

/// Traces rays from `observer` and returns at least `min_points` image points of the straw (fewer
/// only if the straw is all but invisible from there). `progress` is told the rays traced so far.
pub fn sample_image(
    scene: &Scene,
    observer: Vec3,
    min_points: usize,
    progress: &(dyn Fn(u64) + Sync),
) -> ImageCloud {
    let tracer = Tracer::new(scene);
    let frames = frames_for(observer);
    let longest = frames
        .iter()
        .map(|f| f.width.max(f.height))
        .fold(0.0, f64::max);
    let mut spacing = longest / COARSE_CELLS;
    let mut rays = 0u64;

    // Level 0: every cell of every frame.
    let mut cells: Vec<Cell> = Vec::new();
    for (k, f) in frames.iter().enumerate() {
        let (nx, ny) = grid_size(f, spacing);
        for j in 0..ny {
            for i in 0..nx {
                cells.push((k as u32, i, j));
            }
        }
    }
    // Whether the ray through each cell's centre reaches the straw (no image point is built).
    let trace_cells = |cells: &[Cell], spacing: f64| -> Vec<bool> {
        cells
            .par_iter()
            .with_min_len(256)
            .map(|&(k, i, j)| {
                let f = &frames[k as usize];
                let a = f.a_min + (i as f64 + 0.5) * spacing;
                let b = f.b_min + (j as f64 + 0.5) * spacing;
                tracer.color(Ray {
                    origin: observer,
                    direction: f.direction(a, b),
                }) > 0
            })
            .collect()
    };

    let mut blind = 0;
    loop {
        let results = trace_cells(&cells, spacing);
        rays += cells.len() as u64;
        progress(rays);
        let hits: Vec<Cell> = cells
            .iter()
            .zip(&results)
            .filter(|(_, &r)| r)
            .map(|(c, _)| *c)
            .collect();
        if hits.is_empty() {
            if blind == BLIND_LEVELS {
                return ImageCloud {
                    points: Vec::new(),
                    rays_traced: rays,
                    spacing,
                };
            }
            blind += 1;
            cells = split(&cells);
            spacing /= 2.0;
            continue;
        }
        // Spacing that would give about 10% more than the points asked for.
        let target = spacing * (hits.len() as f64 / (1.1 * min_points as f64)).sqrt();
        let active = dilate(&hits, &frames, spacing);
        if spacing / 2.0 > target {
            cells = split(&active);
            spacing /= 2.0;
            continue;
        }
        // Final level: a uniform grid of spacing `h`, traced where the last level saw the straw.
        let mut h = target.min(spacing);
        loop {
            let points = final_level(&tracer, observer, &frames, &active, spacing, h, &mut rays);
            progress(rays);
            if points.len() >= min_points || h < 1e-7 * longest {
                return ImageCloud {
                    points,
                    rays_traced: rays,
                    spacing: h,
                };
            }
            h /= (min_points as f64 / points.len().max(1) as f64).sqrt() * 1.02;
        }
    }
}

/// Cells of a frame's grid at `spacing`: `(nx, ny)`.
fn grid_size(f: &Frame, spacing: f64) -> (u32, u32) {
    (
        (f.width / spacing).ceil().max(1.0) as u32,
        (f.height / spacing).ceil().max(1.0) as u32,
    )
}

/// The four children of every cell.
fn split(cells: &[Cell]) -> Vec<Cell> {
    let mut out = Vec::with_capacity(4 * cells.len());
    for &(k, i, j) in cells {
        for (di, dj) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            out.push((k, 2 * i + di, 2 * j + dj));
        }
    }
    out
}

/// The cells that are hits or touch one (8-neighbourhood), sorted.
///
/// Marks a bitmap of each frame's grid (cheaper than hashing: one bit per cell, and reading the
/// bits in order gives the cells already sorted as `(frame, i, j)`).
fn dilate(hits: &[Cell], frames: &[Frame], spacing: f64) -> Vec<Cell> {
    let mut cells = Vec::with_capacity(hits.len() * 2);
    for (k, frame) in frames.iter().enumerate() {
        let k = k as u32;
        let (nx, ny) = grid_size(frame, spacing);
        let (nx, ny) = (nx as usize, ny as usize);
        let mut bits = vec![0u64; (nx * ny).div_ceil(64)];
        let mut any = false;
        for &(_, i, j) in hits.iter().filter(|c| c.0 == k) {
            any = true;
            let (i, j) = (i as usize, j as usize);
            for ii in i.saturating_sub(1)..=(i + 1).min(nx - 1) {
                for jj in j.saturating_sub(1)..=(j + 1).min(ny - 1) {
                    let n = ii * ny + jj;
                    bits[n / 64] |= 1 << (n % 64);
                }
            }
        }
        if !any {
            continue;
        }
        for (w, &word) in bits.iter().enumerate() {
            let mut word = word;
            while word != 0 {
                let n = w * 64 + word.trailing_zeros() as usize;
                word &= word - 1;
                cells.push((k, (n / ny) as u32, (n % ny) as u32));
            }
        }
    }
    cells
}

/// Traces the points of the uniform grid of spacing `h` whose centres lie in `active` cells (of
/// size `spacing`), and returns the image points, in cell order.
fn final_level(
    tracer: &Tracer,
    observer: Vec3,
    frames: &[Frame],
    active: &[Cell],
    spacing: f64,
    h: f64,
    rays: &mut u64,
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
            for &(k, i, j) in chunk {
                let f = &frames[k as usize];
                let (i0, i1) = range(i);
                let (j0, j1) = range(j);
                for jj in j0..j1 {
                    let b = f.b_min + (jj as f64 + 0.5) * h;
                    if b > f.b_min + f.height {
                        continue;
                    }
                    for ii in i0..i1 {
                        let a = f.a_min + (ii as f64 + 0.5) * h;
                        if a > f.a_min + f.width {
                            continue;
                        }
                        n += 1;
                        if let Some(p) = tracer.image_point(observer, f.direction(a, b)) {
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
