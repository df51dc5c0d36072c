//! Checking someone else's image points: is each one right, and what part of the image is missing?
//!
//! A solution is a list of claimed image points, each a position and a colour code, seen from a known
//! observer in a known scene. By the course's convention (`P = O + L·u0`) a point fixes its ray: the
//! direction `u0 = (P − O)/|P − O|` and the path length `L = |P − O|`. Each point is judged by tracing
//! that ray exactly: it must reach the straw, with the same colour, within the event limit, after a
//! broken path whose length matches `|P − O|` within a tolerance.
//!
//! What is missing is found by comparing the solution with the true image, densely sampled by
//! [`sample_image`] on the equal-area map of the observer's directions
//! ([`DirectionMap`]): equal areas of that map are equal solid angles, so counting the true image's samples
//! that a solution reaches measures the solid angle it covers. A true sample counts as reached when a
//! solution point of its colour, whose ray really reaches that colour, lies within [`REACH_CELLS`]
//! of the solution's own spacing there: the distance from that point to its nearest neighbour of the
//! same colour, but at least the even spacing `sqrt(Ω / N)` (for a true image of solid angle `Ω` and
//! a solution of `N` points) and at most that of a good image of [`GOOD_IMAGE_POINTS`] points (a
//! sparser solution is judged as if it had that many). So a solution that samples some directions
//! more sparsely than others is judged at its own density there, and only holes larger than that
//! count as missing. The true samples left unreached, grouped by colour, by kind of light path and
//! by adjacency on the sampling grid, are the missing regions.

use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, Ordering};

use crate::parallel::*;

mod nearest;
use nearest::nearest_spacing;

use crate::geometry::Ray;
use crate::image::ImagePoint;
use crate::light_path_type::LightPathType;
use crate::sampling::{sample_image, DirectionMap, ImageCloud};
use crate::scene::MAX_EVENTS_LIMIT;
use crate::world::{Outcome, World, COLOR_COUNT};
use crate::Vec3;

/// How a ray traced to judge a point ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Reach {
    /// It reaches an object, of colour code `color`, after a broken path of length `path_length`.
    Object {
        /// The colour code reached.
        color: u8,
        /// The length of its broken path (m).
        path_length: f64,
        /// Its events on the way.
        events: u32,
    },
    /// It leaves the scene.
    Escaped,
    /// It would need more events than allowed.
    Dropped,
}

/// How `ray` ends, traced through `world` with its event limit (or `max_events`), and the kind
/// of its light path.
fn reach(world: &World, ray: Ray, max_events: Option<u32>) -> (Reach, LightPathType) {
    let (outcome, path) =
        world.trace_path_type_limited(ray, max_events.unwrap_or(world.max_events()));
    let reach = match outcome {
        Outcome::Object {
            color,
            path_length,
            events,
            ..
        } => Reach::Object {
            color,
            path_length,
            events,
        },
        Outcome::Escaped { .. } => Reach::Escaped,
        Outcome::Dropped => Reach::Dropped,
    };
    (reach, path)
}

/// Default tolerance on a point's path length (m).
pub const DEFAULT_TOLERANCE: f64 = 1e-6;
/// Default share of each colour's image a complete solution must cover.
pub const DEFAULT_MIN_COVERAGE: f64 = 0.98;
/// How far a solution point reaches on the direction map, in its own point spacings.
pub const REACH_CELLS: f64 = 2.0;
/// True-image samples per solution point: the true image is sampled more densely than the solution.
pub const TRUE_SAMPLES_PER_POINT: usize = 4;
/// Fewest true-image samples drawn for the comparison, however small the solution.
pub const MIN_TRUE_SAMPLES: usize = 20_000;
/// Most true-image samples drawn, however large the solution (time and memory stay bounded).
pub const MAX_TRUE_SAMPLES: usize = 400_000;
/// Points a good image has at least (the specification's rule): a sparser solution is judged as if
/// it had this many, so that ten points cannot cover an image by being far apart.
pub const GOOD_IMAGE_POINTS: usize = 1000;
/// A missing region smaller than this share of its colour's image is not listed (counted all the same).
pub const MIN_REGION_SHARE: f64 = 0.002;

/// One image point as a solution claims it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClaimedPoint {
    /// The claimed image point `P` (m).
    pub position: Vec3,
    /// The claimed colour code, 1..=5.
    pub color: u8,
}

/// What tracing a claimed point's ray shows about it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Verdict {
    /// The ray reaches the claimed colour within the event limit, and the lengths agree.
    Correct {
        /// `|P − O| − L` (m).
        length_error: f64,
    },
    /// The ray reaches the straw, but another colour.
    WrongColour {
        /// The colour code the ray really meets.
        actual: u8,
    },
    /// The right colour, but `|P − O|` is not the path length.
    WrongLength {
        /// `|P − O| − L` (m): positive when the point is too far away.
        length_error: f64,
    },
    /// The ray never reaches the straw: it escapes, is still going after the largest event limit
    /// allowed, or has no direction (the point is the observer itself).
    NoStraw,
    /// The ray reaches the straw only after more events than the limit allows.
    TooManyEvents {
        /// Events it really needs.
        events: u32,
        /// The colour code it then meets.
        actual: u8,
    },
}

/// The kinds of verdict, in the order the summary lists them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum VerdictKind {
    /// See [`Verdict::Correct`].
    Correct,
    /// See [`Verdict::WrongColour`].
    WrongColour,
    /// See [`Verdict::WrongLength`].
    WrongLength,
    /// See [`Verdict::NoStraw`].
    NoStraw,
    /// See [`Verdict::TooManyEvents`].
    TooManyEvents,
}

impl VerdictKind {
    /// Every kind, in the summary's order.
    pub const ALL: [VerdictKind; 5] = [
        VerdictKind::Correct,
        VerdictKind::WrongColour,
        VerdictKind::WrongLength,
        VerdictKind::NoStraw,
        VerdictKind::TooManyEvents,
    ];

    /// A short stable key for data files: `correct`, `wrong_colour`, …
    pub fn key(self) -> &'static str {
        match self {
            VerdictKind::Correct => "correct",
            VerdictKind::WrongColour => "wrong_colour",
            VerdictKind::WrongLength => "wrong_length",
            VerdictKind::NoStraw => "no_straw",
            VerdictKind::TooManyEvents => "too_many_events",
        }
    }

    /// In words, for people.
    pub fn words(self) -> &'static str {
        match self {
            VerdictKind::Correct => "correct",
            VerdictKind::WrongColour => "wrong colour",
            VerdictKind::WrongLength => "wrong length",
            VerdictKind::NoStraw => "no straw in that direction",
            VerdictKind::TooManyEvents => "needs more events than allowed",
        }
    }
}

impl Verdict {
    /// The kind of this verdict.
    pub fn kind(&self) -> VerdictKind {
        match self {
            Verdict::Correct { .. } => VerdictKind::Correct,
            Verdict::WrongColour { .. } => VerdictKind::WrongColour,
            Verdict::WrongLength { .. } => VerdictKind::WrongLength,
            Verdict::NoStraw => VerdictKind::NoStraw,
            Verdict::TooManyEvents { .. } => VerdictKind::TooManyEvents,
        }
    }

    /// Whether the point's ray really reaches its claimed colour (so it shows that part of the
    /// image, whatever its length): correct or wrong length only.
    pub fn reaches_claimed_colour(&self) -> bool {
        matches!(self, Verdict::Correct { .. } | Verdict::WrongLength { .. })
    }
}

/// One claimed point, judged.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Judgement {
    /// The verdict.
    pub verdict: Verdict,
    /// The kind of light path the point's ray really takes (up to the straw, the escape or the limit).
    pub path: LightPathType,
}

/// Judges `point` seen from `observer` in `world` (with its event limit) and a path-length
/// `tolerance` (m).
pub fn judge_point(
    world: &World,
    observer: Vec3,
    point: &ClaimedPoint,
    tolerance: f64,
) -> Judgement {
    let offset = point.position - observer;
    let distance = offset.length();
    if distance == 0.0 || !distance.is_finite() {
        // No direction: a point at the eye shows nothing.
        return Judgement {
            verdict: Verdict::NoStraw,
            path: LightPathType::DIRECT,
        };
    }
    let ray = Ray {
        origin: observer,
        direction: offset / distance,
    };
    let (outcome, path) = reach(world, ray, None);
    let verdict = match outcome {
        Reach::Object {
            color, path_length, ..
        } => {
            let length_error = distance - path_length;
            if color != point.color {
                Verdict::WrongColour { actual: color }
            } else if length_error.abs() > tolerance {
                Verdict::WrongLength { length_error }
            } else {
                Verdict::Correct { length_error }
            }
        }
        Reach::Escaped => Verdict::NoStraw,
        Reach::Dropped => {
            // Tell "would reach the straw later" from "never reaches it": trace again with the
            // largest event limit allowed.
            let (outcome, path) = reach(world, ray, Some(MAX_EVENTS_LIMIT));
            return Judgement {
                verdict: match outcome {
                    Reach::Object { color, events, .. } => Verdict::TooManyEvents {
                        events,
                        actual: color,
                    },
                    _ => Verdict::NoStraw,
                },
                path,
            };
        }
    };
    Judgement { verdict, path }
}

/// Judges every point (in parallel; the result is in the points' order).
pub fn judge_points(
    world: &World,
    observer: Vec3,
    points: &[ClaimedPoint],
    tolerance: f64,
) -> Vec<Judgement> {
    points
        .par_iter()
        .with_min_len(256)
        .map(|p| judge_point(world, observer, p, tolerance))
        .collect()
}

/// Counts of one colour's points (by claimed colour) per verdict kind.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tally {
    /// Points in all.
    pub points: usize,
    /// Correct points.
    pub correct: usize,
    /// Wrong colour.
    pub wrong_colour: usize,
    /// Wrong length.
    pub wrong_length: usize,
    /// No straw in that direction.
    pub no_straw: usize,
    /// More events needed than allowed.
    pub too_many_events: usize,
}

impl Tally {
    /// Counts `verdicts`.
    pub fn of<'a>(verdicts: impl IntoIterator<Item = &'a Verdict>) -> Tally {
        let mut t = Tally::default();
        for v in verdicts {
            t.add(v.kind());
        }
        t
    }

    /// Counts one more point of `kind`.
    pub fn add(&mut self, kind: VerdictKind) {
        self.points += 1;
        *self.count_mut(kind) += 1;
    }

    /// The count of `kind`.
    pub fn count(&self, kind: VerdictKind) -> usize {
        match kind {
            VerdictKind::Correct => self.correct,
            VerdictKind::WrongColour => self.wrong_colour,
            VerdictKind::WrongLength => self.wrong_length,
            VerdictKind::NoStraw => self.no_straw,
            VerdictKind::TooManyEvents => self.too_many_events,
        }
    }

    fn count_mut(&mut self, kind: VerdictKind) -> &mut usize {
        match kind {
            VerdictKind::Correct => &mut self.correct,
            VerdictKind::WrongColour => &mut self.wrong_colour,
            VerdictKind::WrongLength => &mut self.wrong_length,
            VerdictKind::NoStraw => &mut self.no_straw,
            VerdictKind::TooManyEvents => &mut self.too_many_events,
        }
    }

    /// Share of the points that are correct (1 when there are none).
    pub fn share_correct(&self) -> f64 {
        if self.points == 0 {
            1.0
        } else {
            self.correct as f64 / self.points as f64
        }
    }
}

/// Tallies per claimed colour code 1..=5 (indices 0..=4).
pub fn tally_per_colour(points: &[ClaimedPoint], judged: &[Judgement]) -> [Tally; COLOR_COUNT] {
    let mut t = [Tally::default(); COLOR_COUNT];
    for (p, j) in points.iter().zip(judged) {
        if (1..=COLOR_COUNT as u8).contains(&p.color) {
            t[p.color as usize - 1].add(j.verdict.kind());
        }
    }
    t
}

/// The indices of the wrong points, worst first: no straw, wrong colour and too many events before
/// wrong lengths, larger length errors first, then in the file's order; at most `count`.
pub fn worst_points(judged: &[Judgement], count: usize) -> Vec<usize> {
    let rank = |v: &Verdict| match v {
        Verdict::NoStraw => (0, 0.0),
        Verdict::WrongColour { .. } => (1, 0.0),
        Verdict::TooManyEvents { .. } => (2, 0.0),
        Verdict::WrongLength { length_error } => (3, -length_error.abs()),
        Verdict::Correct { .. } => (4, 0.0),
    };
    let mut wrong: Vec<usize> = (0..judged.len())
        .filter(|&i| judged[i].verdict.kind() != VerdictKind::Correct)
        .collect();
    wrong.sort_by(|&a, &b| {
        let (ra, ea) = rank(&judged[a].verdict);
        let (rb, eb) = rank(&judged[b].verdict);
        ra.cmp(&rb).then(ea.total_cmp(&eb)).then(a.cmp(&b))
    });
    wrong.truncate(count);
    wrong
}

/// How many true-image samples to draw for a solution of `solution_points` points.
pub fn true_sample_count(solution_points: usize) -> usize {
    solution_points
        .saturating_mul(TRUE_SAMPLES_PER_POINT)
        .clamp(MIN_TRUE_SAMPLES, MAX_TRUE_SAMPLES)
}

/// The true image seen from `observer`, sampled densely enough to judge a solution of
/// `solution_points` points.
pub fn true_image(world: &World, observer: Vec3, solution_points: usize) -> ImageCloud {
    sample_image(world, observer, true_sample_count(solution_points), &|_| {})
}

/// Where on its section a missing region lies, along the straw.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Place {
    /// The region spans all the heights at which the colour is seen.
    Whole,
    /// The region reaches the top of the heights at which the colour is seen, not the bottom.
    TopEnd,
    /// The region reaches the bottom of those heights, not the top.
    BottomEnd,
    /// The region lies between.
    Middle,
}

impl Place {
    /// In words.
    pub fn words(self) -> &'static str {
        match self {
            Place::Whole => "over its whole visible height",
            Place::TopEnd => "at the top end",
            Place::BottomEnd => "at the bottom end",
            Place::Middle => "in the middle",
        }
    }
}

/// A connected part of the true image that the solution does not reach.
#[derive(Clone, Debug, PartialEq)]
pub struct MissingRegion {
    /// Colour code, 1..=5.
    pub color: u8,
    /// The light path that makes this part of the image.
    pub path: LightPathType,
    /// Indices of the true image's points in the region.
    pub samples: Vec<usize>,
    /// Its solid angle as the eye sees it (sr).
    pub solid_angle: f64,
    /// Its share of the colour's image (by solid angle), 0..=1.
    pub share_of_colour: f64,
    /// Lowest and highest straw heights the region's rays reach (m).
    pub straw_z: (f64, f64),
    /// Where along the visible part of its colour the region lies.
    pub place: Place,
}

/// How much of one colour's true image a solution covers.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ColourCoverage {
    /// Samples of the true image of this colour.
    pub true_samples: usize,
    /// Of them, those the solution reaches.
    pub reached: usize,
    /// The colour's true image's solid angle (sr).
    pub solid_angle: f64,
    /// Lowest and highest straw heights at which this colour is seen (m; zero when unseen).
    pub straw_z: (f64, f64),
}

impl ColourCoverage {
    /// Share of the colour's image reached, 0..=1 (1 when the colour is not seen at all: nothing
    /// to miss).
    pub fn share(&self) -> f64 {
        if self.true_samples == 0 {
            1.0
        } else {
            self.reached as f64 / self.true_samples as f64
        }
    }
}

/// How a solution covers the true image.
#[derive(Clone, Debug, PartialEq)]
pub struct Coverage {
    /// The equal-area map the comparison is made on.
    pub frame: DirectionMap,
    /// Per colour code 1..=5 (indices 0..=4).
    pub per_colour: [ColourCoverage; COLOR_COUNT],
    /// For each true-image point, whether the solution reaches it.
    pub reached: Vec<bool>,
    /// The missing regions at least [`MIN_REGION_SHARE`] of their colour, largest first.
    pub missing: Vec<MissingRegion>,
    /// The reach of one solution point on the map where the solution is evenly dense
    /// (`REACH_CELLS` cell widths; ≈ radians); points where it is sparser reach farther.
    pub reach: f64,
    /// Solid angle of one true-image sample (sr).
    pub sample_solid_angle: f64,
}

impl Coverage {
    /// Whether every colour's coverage is at least `min_coverage`.
    pub fn complete(&self, min_coverage: f64) -> bool {
        self.per_colour.iter().all(|c| c.share() >= min_coverage)
    }
}

/// Compares the solution with the true image `truth` (from [`true_image`]): `covering` holds the
/// directions (unit) and colours of the solution's points that really reach their colour,
/// `solution_points` the number of points the solution has in all (its density).
pub fn coverage(
    world: &World,
    observer: Vec3,
    truth: &ImageCloud,
    covering: &[(Vec3, u8)],
    solution_points: usize,
) -> Coverage {
    let frame = DirectionMap::of_box(observer, world.bounds());
    let h = truth.spacing;
    let sample_solid_angle = h * h;
    let total_solid_angle = truth.points.len() as f64 * sample_solid_angle;
    // The solution's spacing where it is evenly dense, and that of a good image (the sparsest
    // spacing any point is allowed).
    let cell = (total_solid_angle / solution_points.max(GOOD_IMAGE_POINTS) as f64).sqrt();
    let sparsest = (total_solid_angle / GOOD_IMAGE_POINTS as f64).sqrt();
    let on_map: Vec<(f64, f64, u8)> = covering
        .iter()
        .map(|&(d, c)| {
            let (a, b) = frame.coordinates(d);
            (a, b, c)
        })
        .collect();
    // Each point reaches REACH_CELLS of its own local spacing (the distance to its nearest
    // neighbour of the same colour), between the even spacing and a good image's: a solution that
    // samples some directions more sparsely than others (a grid on a plane, in angles) is judged
    // at its density there; never less than two true samples' spacing (a solution denser than the
    // true sampling is judged at the true sampling's resolution).
    let spacing = if truth.points.is_empty() {
        // Nothing to cover (the straw is not seen): no spacing to measure.
        vec![0.0; on_map.len()]
    } else {
        nearest_spacing(&on_map, cell, sparsest)
    };
    let reaches: Vec<f64> = spacing
        .iter()
        .map(|&s| (REACH_CELLS * s.clamp(cell, sparsest)).max(2.0 * h))
        .collect();
    let reach = (REACH_CELLS * cell).max(2.0 * h);

    // Mark the true samples within each point's reach: the true image is one uniform grid of
    // spacing h (centres at `min + (index + 0.5)·h`), so the samples near a point are found by
    // their grid indices.
    let index_of = |a: f64, b: f64| -> (i64, i64) {
        (
            ((a - frame.a_min) / h - 0.5).round() as i64,
            ((b - frame.b_min) / h - 0.5).round() as i64,
        )
    };
    let grid = Bins::new(
        &truth
            .points
            .iter()
            .map(|p| {
                let (a, b) = frame.coordinates(p.direction);
                index_of(a, b)
            })
            .collect::<Vec<_>>(),
    );
    let marks: Vec<AtomicBool> = (0..truth.points.len())
        .map(|_| AtomicBool::new(false))
        .collect();
    on_map
        .par_iter()
        .zip(&reaches)
        .with_min_len(256)
        .for_each(|(&(a, b, c), &r)| {
            let lo = |x: f64| ((x - r) / h - 0.5).ceil() as i64;
            let hi = |x: f64| ((x + r) / h - 0.5).floor() as i64;
            let (x, y) = (a - frame.a_min, b - frame.b_min);
            for i in lo(x)..=hi(x) {
                for j in lo(y)..=hi(y) {
                    let (da, db) = ((i as f64 + 0.5) * h - x, (j as f64 + 0.5) * h - y);
                    if da * da + db * db > r * r {
                        continue;
                    }
                    for &k in grid.get(i, j) {
                        if truth.points[k as usize].color == c {
                            marks[k as usize].store(true, Ordering::Relaxed);
                        }
                    }
                }
            }
        });
    let reached: Vec<bool> = marks.into_iter().map(AtomicBool::into_inner).collect();

    let mut per_colour = [ColourCoverage::default(); COLOR_COUNT];
    for (p, &r) in truth.points.iter().zip(&reached) {
        let c = &mut per_colour[p.color as usize - 1];
        let z = p.straw_point.z;
        if c.true_samples == 0 {
            c.straw_z = (z, z);
        } else {
            c.straw_z = (c.straw_z.0.min(z), c.straw_z.1.max(z));
        }
        c.true_samples += 1;
        c.reached += r as usize;
    }
    for c in &mut per_colour {
        c.solid_angle = c.true_samples as f64 * sample_solid_angle;
    }

    let missing = missing_regions(world, observer, truth, &reached, &frame, &per_colour);
    Coverage {
        frame,
        per_colour,
        reached,
        missing,
        reach,
        sample_solid_angle,
    }
}

/// Most cells of a dense [`Bins`] table (beyond that, a hash map).
const DENSE_CELLS: i64 = 1 << 24;

/// Item indices filed by integer cell `(i, j)`: a dense table over the cells' bounding box (fast
/// look-ups), or a hash map when that box would be too large.
enum Bins {
    /// Cell `(i, j)` holds `items[start[c]..start[c + 1]]`, `c = (i − i0)·nj + (j − j0)`.
    Dense {
        i0: i64,
        j0: i64,
        ni: i64,
        nj: i64,
        start: Vec<u32>,
        items: Vec<u32>,
    },
    /// For scattered cells.
    Sparse(HashMap<(i64, i64), Vec<u32>>),
}

impl Bins {
    /// Files item `k` in cell `keys[k]`, for every `k`.
    fn new(keys: &[(i64, i64)]) -> Bins {
        let (mut i0, mut i1, mut j0, mut j1) = (i64::MAX, i64::MIN, i64::MAX, i64::MIN);
        for &(i, j) in keys {
            (i0, i1, j0, j1) = (i0.min(i), i1.max(i), j0.min(j), j1.max(j));
        }
        let (ni, nj) = (i1.saturating_sub(i0) + 1, j1.saturating_sub(j0) + 1);
        if keys.is_empty() || ni.checked_mul(nj).is_none_or(|n| n > DENSE_CELLS) {
            let mut map: HashMap<(i64, i64), Vec<u32>> = HashMap::new();
            for (k, &key) in keys.iter().enumerate() {
                map.entry(key).or_default().push(k as u32);
            }
            return Bins::Sparse(map);
        }
        let cell = |(i, j): (i64, i64)| ((i - i0) * nj + (j - j0)) as usize;
        let mut start = vec![0u32; (ni * nj) as usize + 1];
        for &key in keys {
            start[cell(key) + 1] += 1;
        }
        for c in 1..start.len() {
            start[c] += start[c - 1];
        }
        let mut fill = start.clone();
        let mut items = vec![0u32; keys.len()];
        for (k, &key) in keys.iter().enumerate() {
            let c = cell(key);
            items[fill[c] as usize] = k as u32;
            fill[c] += 1;
        }
        Bins::Dense {
            i0,
            j0,
            ni,
            nj,
            start,
            items,
        }
    }

    /// The items in cell `(i, j)`.
    fn get(&self, i: i64, j: i64) -> &[u32] {
        match self {
            Bins::Dense {
                i0,
                j0,
                ni,
                nj,
                start,
                items,
            } => {
                let (di, dj) = (i - i0, j - j0);
                if di < 0 || dj < 0 || di >= *ni || dj >= *nj {
                    return &[];
                }
                let c = (di * nj + dj) as usize;
                &items[start[c] as usize..start[c + 1] as usize]
            }
            Bins::Sparse(map) => map.get(&(i, j)).map(Vec::as_slice).unwrap_or(&[]),
        }
    }
}

/// Groups the unreached true samples into regions: same colour, same kind of light path, and
/// neighbours on the true sampling grid (8-neighbourhood).
fn missing_regions(
    world: &World,
    observer: Vec3,
    truth: &ImageCloud,
    reached: &[bool],
    frame: &DirectionMap,
    per_colour: &[ColourCoverage; COLOR_COUNT],
) -> Vec<MissingRegion> {
    let h = truth.spacing;
    let unreached: Vec<usize> = (0..truth.points.len()).filter(|&i| !reached[i]).collect();
    let paths: Vec<LightPathType> = unreached
        .par_iter()
        .map(|&i| {
            let ray = Ray {
                origin: observer,
                direction: truth.points[i].direction,
            };
            reach(world, ray, None).1
        })
        .collect();
    // Grid cell of each unreached sample: the true image's directions are the centres
    // `min + (index + 0.5)·h` of one uniform grid (the same frame as the sampler's).
    let cell_of = |p: &ImagePoint| -> (i64, i64) {
        let (a, b) = frame.coordinates(p.direction);
        (
            ((a - frame.a_min) / h - 0.5).round() as i64,
            ((b - frame.b_min) / h - 0.5).round() as i64,
        )
    };
    let mut at: HashMap<(u8, LightPathType, i64, i64), usize> = HashMap::new();
    for (k, &i) in unreached.iter().enumerate() {
        let p = &truth.points[i];
        let (x, y) = cell_of(p);
        at.insert((p.color, paths[k], x, y), k);
    }
    let mut seen = vec![false; unreached.len()];
    let mut regions = Vec::new();
    for start in 0..unreached.len() {
        if seen[start] {
            continue;
        }
        seen[start] = true;
        let p0 = &truth.points[unreached[start]];
        let (color, path) = (p0.color, paths[start]);
        let mut stack = vec![start];
        let mut members = Vec::new();
        while let Some(k) = stack.pop() {
            members.push(unreached[k]);
            let (x, y) = cell_of(&truth.points[unreached[k]]);
            for dx in -1..=1 {
                for dy in -1..=1 {
                    if let Some(&n) = at.get(&(color, path, x + dx, y + dy)) {
                        if !seen[n] {
                            seen[n] = true;
                            stack.push(n);
                        }
                    }
                }
            }
        }
        let colour = &per_colour[color as usize - 1];
        let share = members.len() as f64 / colour.true_samples.max(1) as f64;
        if share < MIN_REGION_SHARE {
            continue;
        }
        members.sort_unstable();
        let (mut z0, mut z1) = (f64::INFINITY, f64::NEG_INFINITY);
        for &i in &members {
            let z = truth.points[i].straw_point.z;
            z0 = z0.min(z);
            z1 = z1.max(z);
        }
        regions.push(MissingRegion {
            color,
            path,
            solid_angle: members.len() as f64 * h * h,
            share_of_colour: share,
            straw_z: (z0, z1),
            place: place((z0, z1), colour.straw_z),
            samples: members,
        });
    }
    regions.sort_by(|a, b| {
        b.samples
            .len()
            .cmp(&a.samples.len())
            .then(a.color.cmp(&b.color))
            .then(a.samples[0].cmp(&b.samples[0]))
    });
    regions
}

/// Where the straw heights `region` lie within the heights `seen` at which their colour is seen.
fn place(region: (f64, f64), seen: (f64, f64)) -> Place {
    // Within 5 % of the seen span (at least 0.5 mm) counts as reaching an end.
    let tol = (0.05 * (seen.1 - seen.0)).max(5e-4);
    match (region.0 <= seen.0 + tol, region.1 >= seen.1 - tol) {
        (true, true) => Place::Whole,
        (false, true) => Place::TopEnd,
        (true, false) => Place::BottomEnd,
        (false, false) => Place::Middle,
    }
}

/// A likely reason why most of a solution's points are wrong, found by trying it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Hint {
    /// The points are correct once multiplied by `factor` (coordinates in mm or cm, not metres).
    Units {
        /// The factor that makes them right (1e-3 for millimetres, 1e-2 for centimetres).
        factor: f64,
        /// Share of the points tried that it makes correct.
        share: f64,
    },
    /// `|P − O|` matches the optical path length `Σ n·l` (the course's convention is the
    /// geometric length `Σ l`).
    OpticalPath {
        /// Share of the points tried that match it.
        share: f64,
    },
    /// The points lie on the straw itself: the points hit, not the image points `O + L·u0`.
    OnStraw {
        /// Share of the points that lie on it.
        share: f64,
    },
}

impl std::fmt::Display for Hint {
    /// In words, for the student.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Hint::Units { factor, share } => write!(
                f,
                "multiplied by {factor}, {:.0} % of the points tried would be correct: are the coordinates in {} rather than metres?",
                100.0 * share,
                if *factor == 1e-3 { "millimetres" } else { "centimetres" }
            ),
            Hint::OpticalPath { share } => write!(
                f,
                "for {:.0} % of the points tried, the distance from the eye equals the optical path length (index × length summed over the path); the course's convention uses the geometric length L",
                100.0 * share
            ),
            Hint::OnStraw { share } => write!(
                f,
                "{:.0} % of the points lie on the straw itself: they look like the points the rays hit, not the image points P = O + L·u0",
                100.0 * share
            ),
        }
    }
}

/// Points tried when looking for a hint.
const HINT_SAMPLE: usize = 400;
/// Share of the points tried a hint must explain to be given.
const HINT_SHARE: f64 = 0.5;

/// The optical path length `Σ n·l` of the ray from `observer` along unit `u0` through `world`, if
/// it reaches an object: each straight piece in the index of the medium it crosses, the one each
/// event leaves (`n1`), and after the last event the one it enters (or stays in, when totally
/// reflected).
pub fn optical_path_length(world: &World, observer: Vec3, u0: Vec3) -> Option<f64> {
    let (mut at, mut optical, mut n) = (observer, 0.0, 1.0);
    let outcome = world.trace_with(
        Ray {
            origin: observer,
            direction: u0,
        },
        |e| {
            optical += e.n1 * (e.point - at).length();
            at = e.point;
            n = if e.totally_reflected { e.n1 } else { e.n2 };
        },
    );
    match outcome {
        Outcome::Object { point, .. } => Some(optical + n * (point - at).length()),
        _ => None,
    }
}

/// Likely reasons why most points are wrong (none when at least half are correct): tried on an
/// even subset of the points.
pub fn hints(
    world: &World,
    observer: Vec3,
    points: &[ClaimedPoint],
    judged: &[Judgement],
    tolerance: f64,
) -> Vec<Hint> {
    let correct = judged
        .iter()
        .filter(|j| j.verdict.kind() == VerdictKind::Correct)
        .count();
    if points.is_empty() || correct as f64 >= HINT_SHARE * points.len() as f64 {
        return Vec::new();
    }
    let step = points.len().div_ceil(HINT_SAMPLE).max(1);
    let tried: Vec<&ClaimedPoint> = points.iter().step_by(step).collect();
    let share = |n: usize| n as f64 / tried.len() as f64;
    let mut out = Vec::new();
    for factor in [1e-3, 1e-2] {
        let n = tried
            .iter()
            .filter(|p| {
                let scaled = ClaimedPoint {
                    position: p.position * factor,
                    color: p.color,
                };
                judge_point(world, observer, &scaled, tolerance)
                    .verdict
                    .kind()
                    == VerdictKind::Correct
            })
            .count();
        if share(n) >= HINT_SHARE {
            out.push(Hint::Units {
                factor,
                share: share(n),
            });
        }
    }
    let optical = tried
        .iter()
        .filter(|p| {
            let d = p.position - observer;
            let len = d.length();
            len > 0.0
                && optical_path_length(world, observer, d / len)
                    .is_some_and(|l| (l - len).abs() <= tolerance)
        })
        .count();
    if world.refracts() && share(optical) >= HINT_SHARE {
        out.push(Hint::OpticalPath {
            share: share(optical),
        });
    }
    let on_straw = points
        .iter()
        .filter(|p| world.distance_to_objects(p.position) <= tolerance)
        .count() as f64
        / points.len() as f64;
    if world.refracts() && on_straw >= HINT_SHARE {
        out.push(Hint::OnStraw { share: on_straw });
    }
    out
}

/// Everything a check finds about one solution.
#[derive(Clone, Debug)]
pub struct CheckReport {
    /// Each point's judgement, in the solution's order.
    pub judged: Vec<Judgement>,
    /// Counts over all points.
    pub tally: Tally,
    /// Counts per claimed colour code 1..=8 (a straw's five, then a coin, a card, a picture).
    pub per_colour: [Tally; COLOR_COUNT],
    /// The true image the solution is compared with.
    pub truth: ImageCloud,
    /// How the solution covers it.
    pub coverage: Coverage,
    /// Whether every colour's coverage is at least the minimum asked for.
    pub complete: bool,
    /// Likely reasons, when most points are wrong.
    pub hints: Vec<Hint>,
}

impl CheckReport {
    /// A pass: every point correct, and the coverage complete.
    pub fn passes(&self) -> bool {
        self.tally.correct == self.tally.points && self.complete
    }
}

/// Judges every point of a solution and compares its coverage with the true image.
pub fn check_solution(
    world: &World,
    observer: Vec3,
    points: &[ClaimedPoint],
    tolerance: f64,
    min_coverage: f64,
) -> CheckReport {
    let judged = judge_points(world, observer, points, tolerance);
    let tally = Tally::of(judged.iter().map(|j| &j.verdict));
    let per_colour = tally_per_colour(points, &judged);
    let covering: Vec<(Vec3, u8)> = points
        .iter()
        .zip(&judged)
        .filter(|(_, j)| j.verdict.reaches_claimed_colour())
        .map(|(p, _)| ((p.position - observer).normalize(), p.color))
        .collect();
    let truth = true_image(world, observer, points.len());
    let coverage = coverage(world, observer, &truth, &covering, points.len());
    let complete = coverage.complete(min_coverage);
    let hints = hints(world, observer, points, &judged, tolerance);
    CheckReport {
        hints,
        judged,
        tally,
        per_colour,
        truth,
        coverage,
        complete,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Scene, REFERENCES};

    fn own_points(k: usize, n: usize) -> (World, Vec3, Vec<ImagePoint>) {
        let r = &REFERENCES[k];
        let scene = World::assignment(&r.scene(1.333));
        let cloud = sample_image(&scene, r.observer, n, &|_| {});
        (scene, r.observer, cloud.points)
    }

    fn claimed(points: &[ImagePoint]) -> Vec<ClaimedPoint> {
        points
            .iter()
            .map(|p| ClaimedPoint {
                position: p.position,
                color: p.color,
            })
            .collect()
    }

    #[test]
    fn own_points_pass_in_every_reference() {
        for k in 0..4 {
            let (scene, o, pts) = own_points(k, 5000);
            let r = check_solution(&scene, o, &claimed(&pts), DEFAULT_TOLERANCE, 0.98);
            assert_eq!(r.tally.correct, pts.len(), "reference {}", k + 1);
            assert!(
                r.complete,
                "reference {}: {:?}",
                k + 1,
                r.coverage.per_colour
            );
            assert!(r.passes());
        }
    }

    #[test]
    fn each_fault_gets_its_verdict() {
        let (scene, o, pts) = own_points(1, 2000);
        let tracer = scene.clone();
        let p = pts[10];
        // Moved 10 µm along its ray: wrong length by +10 µm.
        let moved = ClaimedPoint {
            position: p.position + 1e-5 * p.direction,
            color: p.color,
        };
        match judge_point(&tracer, o, &moved, DEFAULT_TOLERANCE).verdict {
            Verdict::WrongLength { length_error } => assert!((length_error - 1e-5).abs() < 1e-9),
            v => panic!("{v:?}"),
        }
        // Within the tolerance: correct.
        let near = ClaimedPoint {
            position: p.position + 5e-7 * p.direction,
            color: p.color,
        };
        assert_eq!(
            judge_point(&tracer, o, &near, DEFAULT_TOLERANCE)
                .verdict
                .kind(),
            VerdictKind::Correct
        );
        // Another colour: the true one is named.
        let recoloured = ClaimedPoint {
            position: p.position,
            color: p.color % 5 + 1,
        };
        assert_eq!(
            judge_point(&tracer, o, &recoloured, DEFAULT_TOLERANCE).verdict,
            Verdict::WrongColour { actual: p.color }
        );
        // Straight away from the glass: nothing there.
        let away = ClaimedPoint {
            position: o + Vec3::new(1.0, 0.0, 0.0),
            color: 1,
        };
        assert_eq!(
            judge_point(&tracer, o, &away, DEFAULT_TOLERANCE).verdict,
            Verdict::NoStraw
        );
        // The observer itself: no direction, no straw.
        let at_eye = ClaimedPoint {
            position: o,
            color: 1,
        };
        assert_eq!(
            judge_point(&tracer, o, &at_eye, DEFAULT_TOLERANCE).verdict,
            Verdict::NoStraw
        );
    }

    #[test]
    fn a_point_needing_more_events_is_told_apart_from_no_straw() {
        // Points of reference 2 that need 2 or more events, judged with a limit of 1.
        let (_, o, pts) = own_points(1, 3000);
        let r = &REFERENCES[1];
        let strict =
            World::assignment(&Scene::new(r.straw.0, r.straw.1, r.water_height, 1.333, 1).unwrap());
        let tracer = strict.clone();
        let deep: Vec<&ImagePoint> = pts.iter().filter(|p| p.events >= 2).collect();
        assert!(!deep.is_empty());
        for p in deep {
            let c = ClaimedPoint {
                position: p.position,
                color: p.color,
            };
            assert_eq!(
                judge_point(&tracer, o, &c, DEFAULT_TOLERANCE).verdict,
                Verdict::TooManyEvents {
                    events: p.events,
                    actual: p.color
                }
            );
        }
    }

    #[test]
    fn a_removed_colour_is_missing_whole_and_the_others_complete() {
        let (scene, o, pts) = own_points(1, 5000);
        let kept: Vec<ImagePoint> = pts.iter().copied().filter(|p| p.color != 2).collect();
        let r = check_solution(&scene, o, &claimed(&kept), DEFAULT_TOLERANCE, 0.98);
        assert_eq!(r.tally.correct, kept.len());
        assert_eq!(r.coverage.per_colour[1].share(), 0.0);
        for k in [0, 2, 3, 4] {
            assert!(r.coverage.per_colour[k].share() >= 0.98, "{k}");
        }
        assert!(!r.complete && !r.passes());
        assert!(r.coverage.missing.iter().all(|m| m.color == 2));
        let total: f64 = r.coverage.missing.iter().map(|m| m.share_of_colour).sum();
        assert!(total > 0.99, "{total}");
        assert_eq!(r.coverage.missing[0].place, Place::Whole);
    }

    #[test]
    fn points_after_total_reflection_removed_are_missing_as_total_reflection() {
        let (scene, o, pts) = own_points(1, 8000);
        let tir = |p: &ImagePoint| {
            let ray = Ray {
                origin: o,
                direction: p.direction,
            };
            scene.trace_path_type(ray).1.total_reflections > 0
        };
        let removed = pts.iter().filter(|p| tir(p)).count();
        assert!(removed > 20, "reference 2 shows total reflections");
        let kept: Vec<ImagePoint> = pts.iter().copied().filter(|p| !tir(p)).collect();
        let r = check_solution(&scene, o, &claimed(&kept), DEFAULT_TOLERANCE, 0.98);
        assert_eq!(r.tally.correct, kept.len());
        assert!(!r.coverage.missing.is_empty());
        let big = &r.coverage.missing[0];
        assert!(big.path.total_reflections > 0, "{:?}", big.path);
        // Every listed region is a total-reflection one.
        assert!(r
            .coverage
            .missing
            .iter()
            .all(|m| m.path.total_reflections > 0));
    }

    #[test]
    fn hints_name_millimetres_optical_paths_and_straw_points() {
        let (scene, o, pts) = own_points(1, 1000);
        let r = check_solution(&scene, o, &claimed(&pts), DEFAULT_TOLERANCE, 0.98);
        assert!(r.hints.is_empty());
        let tracer = scene.clone();
        // In millimetres.
        let mm: Vec<ClaimedPoint> = pts
            .iter()
            .map(|p| ClaimedPoint {
                position: 1e3 * p.position,
                color: p.color,
            })
            .collect();
        let r = check_solution(&scene, o, &mm, DEFAULT_TOLERANCE, 0.98);
        assert!(
            matches!(r.hints[..], [Hint::Units { factor, share }] if factor == 1e-3 && share > 0.99)
        );
        // At the optical path length: n·l summed, larger than l for every ray through water.
        let optical: Vec<ClaimedPoint> = pts
            .iter()
            .map(|p| {
                let l = optical_path_length(&scene, o, p.direction).unwrap();
                assert!(l >= p.path_length - 1e-12);
                ClaimedPoint {
                    position: o + l * p.direction,
                    color: p.color,
                }
            })
            .collect();
        let judged = judge_points(&scene, o, &optical, DEFAULT_TOLERANCE);
        let h = hints(&scene, o, &optical, &judged, DEFAULT_TOLERANCE);
        assert!(
            matches!(h[..], [Hint::OpticalPath { share }] if share > 0.9),
            "{h:?}"
        );
        // The straw points themselves.
        let on: Vec<ClaimedPoint> = pts
            .iter()
            .map(|p| ClaimedPoint {
                position: p.straw_point,
                color: p.color,
            })
            .collect();
        let judged: Vec<Judgement> = on
            .iter()
            .map(|p| judge_point(&tracer, o, p, DEFAULT_TOLERANCE))
            .collect();
        let h = hints(&scene, o, &on, &judged, DEFAULT_TOLERANCE);
        assert!(
            h.iter()
                .any(|h| matches!(h, Hint::OnStraw { share } if *share > 0.99)),
            "{h:?}"
        );
    }

    #[test]
    fn optical_path_of_a_ray_in_air_is_its_length() {
        // Straight down onto the straw's top cap from above: no water on the way.
        let scene = World::assignment(&Scene::with_defaults(0.0, 0.0, 0.15).unwrap());
        let o = Vec3::new(0.0, 0.0, 0.4);
        let l = optical_path_length(&scene, o, Vec3::new(0.0, 0.0, -1.0)).unwrap();
        assert!((l - 0.15).abs() < 1e-15, "{l}");
        // Horizontally at mid-height onto the straw on the axis: 0.1 − 0.04 in air, 0.035 in water.
        let o = Vec3::new(0.1, 0.0, 0.07);
        let l = optical_path_length(&scene, o, Vec3::new(-1.0, 0.0, 0.0)).unwrap();
        assert!((l - (0.06 + 1.333 * 0.035)).abs() < 1e-12, "{l}");
    }

    #[test]
    fn a_few_correct_points_do_not_cover_the_image() {
        // Every 100th point: all correct, but judged at the density of a good image, far from complete.
        let (scene, o, pts) = own_points(1, 5000);
        let few: Vec<ImagePoint> = pts.iter().copied().step_by(100).collect();
        let r = check_solution(&scene, o, &claimed(&few), DEFAULT_TOLERANCE, 0.98);
        assert_eq!(r.tally.correct, few.len());
        assert!(!r.complete, "{:?}", r.coverage.per_colour);
        // Every 4th (over 1000 points): complete again.
        let quarter: Vec<ImagePoint> = pts.iter().copied().step_by(4).collect();
        assert!(quarter.len() > GOOD_IMAGE_POINTS);
        let r = check_solution(&scene, o, &claimed(&quarter), DEFAULT_TOLERANCE, 0.98);
        assert!(r.passes(), "{:?}", r.coverage.per_colour);
    }

    #[test]
    fn a_solution_sparser_in_some_directions_is_judged_at_its_density_there() {
        // Half of the image sampled five times more sparsely in each direction (every fifth grid
        // point both ways): no hole larger than the solution's own spacing there.
        let r = &REFERENCES[1];
        let scene = World::assignment(&r.scene(1.333));
        let cloud = sample_image(&scene, r.observer, 10_000, &|_| {});
        let frame = DirectionMap::of_box(r.observer, scene.bounds());
        let h = cloud.spacing;
        let index = |p: &ImagePoint| {
            let (a, b) = frame.coordinates(p.direction);
            (
                ((a - frame.a_min) / h - 0.5).round() as i64,
                ((b - frame.b_min) / h - 0.5).round() as i64,
            )
        };
        let mut bs: Vec<i64> = cloud.points.iter().map(|p| index(p).1).collect();
        bs.sort_unstable();
        let middle = bs[bs.len() / 2];
        let kept: Vec<ImagePoint> = cloud
            .points
            .iter()
            .copied()
            .filter(|p| {
                let (i, j) = index(p);
                j < middle || (i % 5 == 0 && j % 5 == 0)
            })
            .collect();
        assert!(kept.len() < cloud.points.len() * 6 / 10);
        let rep = check_solution(&scene, r.observer, &claimed(&kept), DEFAULT_TOLERANCE, 0.98);
        assert!(rep.passes(), "{:?}", rep.coverage.per_colour);
    }

    #[test]
    fn bins_dense_and_sparse_file_the_same_items() {
        let keys = [(0, 0), (2, -1), (0, 0), (5, 3)];
        let far = [(0, 0), (1 << 40, -1), (0, 0), (5, 3)];
        let dense = Bins::new(&keys);
        assert!(matches!(dense, Bins::Dense { .. }));
        assert!(matches!(Bins::new(&far), Bins::Sparse(_)));
        for bins in [dense, Bins::new(&far)] {
            assert_eq!(bins.get(0, 0), &[0, 2]);
            assert_eq!(bins.get(5, 3), &[3]);
            assert!(bins.get(1, 1).is_empty() && bins.get(-9, 0).is_empty());
        }
        assert_eq!(Bins::new(&keys).get(2, -1), &[1]);
        assert!(Bins::new(&[]).get(0, 0).is_empty());
    }

    #[test]
    fn place_names_the_end() {
        let seen = (0.05, 0.10);
        assert_eq!(place((0.05, 0.10), seen), Place::Whole);
        assert_eq!(place((0.08, 0.10), seen), Place::TopEnd);
        assert_eq!(place((0.05, 0.06), seen), Place::BottomEnd);
        assert_eq!(place((0.06, 0.08), seen), Place::Middle);
    }

    #[test]
    fn worst_points_come_in_order_of_severity() {
        let j = |verdict| Judgement {
            verdict,
            path: LightPathType::DIRECT,
        };
        let judged = [
            j(Verdict::Correct { length_error: 0.0 }),
            j(Verdict::WrongLength { length_error: 1e-5 }),
            j(Verdict::WrongLength {
                length_error: -3e-5,
            }),
            j(Verdict::WrongColour { actual: 2 }),
            j(Verdict::NoStraw),
        ];
        assert_eq!(worst_points(&judged, 10), vec![4, 3, 2, 1]);
        assert_eq!(worst_points(&judged, 2), vec![4, 3]);
    }
}
